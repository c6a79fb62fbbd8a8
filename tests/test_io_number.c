/* test_io_number.c: the text readers' decimal parser (io/number.h) against
 * the C library's strtod (glibc's, an independent implementation), bit for
 * bit and character for character, on about two million generated decimals
 * of many shapes: 1-25 digits, the point anywhere or absent, leading and
 * trailing zeros, exponents -330..310 (subnormals, underflow, overflow),
 * halfway cases between adjacent doubles, e/E and Fortran's D; plus the
 * tokens it must refuse or stop in, and a buffer that ends mid-number.
 * Each token sits at the very end of a heap block, so a read past the
 * buffer's end is caught by the address sanitizer. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <locale.h>
#include <unistd.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/number.h"

#define BLOCK 96 /* heap block holding one token at its end */

typedef struct {
  char *block;
  size_t compared, fast, bad;
} harness;

static uint64_t rng(uint64_t *x)
{
  *x ^= *x << 13;
  *x ^= *x >> 7;
  *x ^= *x << 17;
  return *x;
}

/* Parse tok (length len) placed at the end of the block, and strtod of its
 * copy with D/d turned into e; compare value bits and characters taken. */
static void compare(harness *h, const char *tok, unsigned flags)
{
  size_t len = strlen(tok);
  char want_txt[BLOCK];
  for (size_t i = 0; i <= len; i++)
    want_txt[i] = (tok[i] == 'd' || tok[i] == 'D') ? 'e' : tok[i];
  char *end;
  double want = strtod(want_txt, &end);
  size_t want_used = (size_t)(end - want_txt);
  char *at = h->block + BLOCK - len;
  memcpy(at, tok, len);
  double got = -12345.678;
  size_t used = aq_number_parse(at, len, flags, &got);
  h->compared++;
  if (used != want_used || (used && memcmp(&got, &want, sizeof got) != 0)) {
    if (h->bad++ < 8)
      aq_check(0, "\"%s\": %.17g taking %zu, strtod %.17g taking %zu", tok, got, used, want,
               want_used);
  }
}

/* A random decimal: sign, leading zeros, 1-25 digits with the point
 * anywhere or absent, trailing zeros, an exponent in -330..310. */
static void random_decimal(uint64_t *x, char *t, size_t cap, int with_d)
{
  uint64_t r = rng(x);
  size_t p = 0;
  if (r & 1)
    t[p++] = (r & 2) ? '-' : '+';
  int lead0 = (r >> 2) % 5 == 0 ? (int)((r >> 5) % 4) : 0;
  for (int k = 0; k < lead0; k++)
    t[p++] = '0';
  int nd = 1 + (int)((r >> 8) % 25), dot = (int)((r >> 13) % (uint64_t)(nd + 2)) - 1;
  int trail0 = (r >> 18) % 6 == 0 ? (int)((r >> 21) % 6) : 0;
  uint64_t y = rng(x);
  for (int k = 0; k < nd + trail0; k++) {
    if (k == dot)
      t[p++] = '.';
    if (k >= nd) {
      t[p++] = '0';
      continue;
    }
    if (k % 16 == 15)
      y = rng(x);
    t[p++] = (char)('0' + (y >> (4 * (k % 16))) % 10);
  }
  if ((r >> 24) % 4 != 0) {
    int ex = (int)((r >> 26) % 641) - 330;
    if ((r >> 36) % 3 != 0)
      ex = ex % 23; /* mostly the fast path's range */
    static const char letters[] = "eEdD";
    char c = letters[(r >> 40) % (with_d ? 4 : 2)];
    const char *sign = ex < 0 ? "-" : ((r >> 43) & 1) ? "+" : "";
    p += (size_t)snprintf(t + p, cap - p, "%c%s%0*d", c, sign, (int)((r >> 44) % 3) + 1,
                          ex < 0 ? -ex : ex);
  }
  t[p] = '\0';
}

AQ_TEST(io_number_random_decimals_equal_strtod)
{
  harness h = {malloc(BLOCK), 0, 0, 0};
  if (!aq_check(h.block != NULL, "memory"))
    return;
  uint64_t x = 0x2385417A9C3ULL;
  char t[80];
  enum { N = 1500000 };
  for (int i = 0; i < N; i++) {
    int with_d = i & 1;
    random_decimal(&x, t, sizeof t, with_d);
    compare(&h, t, with_d ? AQ_NUMBER_FORTRAN_D : 0);
  }
  aq_check(h.bad == 0, "%zu of %zu random decimals differ from strtod", h.bad, h.compared);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  number: %zu random decimals compared with strtod, %zu differ\n", h.compared,
           h.bad);
  free(h.block);
}

/* Doubles written back in decimal: shortest-ish (%.15g..%.17g), %.7E as
 * agencies write, and the exact midpoints between adjacent doubles (which
 * round to the even neighbour) together with decimals just above and
 * below them. */
AQ_TEST(io_number_doubles_and_halfway_cases_equal_strtod)
{
  harness h = {malloc(BLOCK), 0, 0, 0};
  if (!aq_check(h.block != NULL, "memory"))
    return;
  uint64_t x = 0x9E3779B97F4A7C15ULL;
  char t[BLOCK];
  static const char *const fmt[] = {"%.15g", "%.16g", "%.17g", "%.7E", "%.9e", "%.3f"};
  for (int i = 0; i < 250000; i++) {
    uint64_t bits = rng(&x) & 0x7FFFFFFFFFFFFFFFULL;
    double v;
    if (i % 3 == 0) /* magnitudes of accelerations: 1e-8 .. 1e3 */
      v = ldexp((double)(bits >> 11) / 9007199254740992.0, (int)(bits % 37) - 27);
    else
      memcpy(&v, &bits, sizeof v);
    if (!isfinite(v))
      continue;
    for (size_t f = 0; f < sizeof fmt / sizeof fmt[0]; f++) {
      snprintf(t, sizeof t, fmt[f], (rng(&x) & 1) ? -v : v);
      if (strlen(t) < AQ_NUMBER_TOKEN_MAX) /* longer ones are cut: number.h */
        compare(&h, t, 0);
    }
  }
  /* integers 2^53 + odd: exactly halfway between two doubles */
  for (int i = 0; i < 100000; i++) {
    uint64_t m = (1ULL << 53) + 2 * (rng(&x) % (1ULL << 52)) + 1;
    snprintf(t, sizeof t, "%llu", (unsigned long long)m);
    compare(&h, t, 0);
    snprintf(t, sizeof t, "%llue%d", (unsigned long long)m, (int)(rng(&x) % 40) - 20);
    compare(&h, t, 0);
    snprintf(t, sizeof t, "%llu1", (unsigned long long)m); /* just above, x10 */
    compare(&h, t, 0);
  }
  /* exact decimal midpoints m * 2^-k (m odd, 54 bits): k digits after the point */
  for (int i = 0; i < 20000; i++) {
    uint64_t m = (1ULL << 53) | (rng(&x) & ((1ULL << 53) - 1)) | 1;
    int k = 1 + (int)(rng(&x) % 60);
    /* m * 5^k / 10^k written exactly: multiply the decimal digits by 5, k times */
    char dig[160];
    int nd = snprintf(dig, sizeof dig, "%llu", (unsigned long long)m);
    for (int j = 0; j < k; j++) {
      int carry = 0;
      for (int q = nd - 1; q >= 0; q--) {
        int d = (dig[q] - '0') * 5 + carry;
        dig[q] = (char)('0' + d % 10);
        carry = d / 10;
      }
      if (carry) {
        memmove(dig + 1, dig, (size_t)nd + 1);
        dig[0] = (char)('0' + carry);
        nd++;
      }
    }
    if (nd > k && nd + 4 < AQ_NUMBER_TOKEN_MAX) {
      snprintf(t, sizeof t, "%.*s.%se0", nd - k, dig, dig + nd - k);
      compare(&h, t, 0);
    }
  }
  static const char *const hard[] = {
      "9007199254740993", "9007199254740992", "9007199254740994", "9007199254740995",
      "1e23", "8.589973e9", "1e22", "1e-22", "123456789012345678e-22", "4.9406564584124654e-324",
      "2.4703282292062327e-324", "2.4703282292062328e-324", "2.2250738585072011e-308",
      "2.2250738585072014e-308", "1.7976931348623157e308", "1.7976931348623158e308",
      "1.7976931348623159e308", "1e309", "1e-400", "-0", "-0.0e-999", "0e99999999999",
      "1e000000000000000000000005", "0.000000000000000000000000000000001",
      "7.2730250E-07", ".7273025E-06", "-.6403182E-02", "1.", "00000000000000000000001.5",
      "0.1", "0.2", "0.3", "3.0517578125e-05", "179769313486231570000000000000000000000e270"};
  for (size_t i = 0; i < sizeof hard / sizeof hard[0]; i++)
    compare(&h, hard[i], 0);
  aq_check(h.bad == 0, "%zu of %zu written doubles and halfway cases differ from strtod", h.bad,
           h.compared);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  number: %zu doubles and halfway cases compared with strtod, %zu differ\n",
           h.compared, h.bad);
  free(h.block);
}

/* What is not a number, or stops one: the characters taken as strtod
 * (C locale, decimals only) would take them. */
AQ_TEST(io_number_refusals_and_stops)
{
  static const struct {
    const char *tok;
    unsigned flags;
    size_t used;
  } c[] = {{"", 0, 0},      {"-", 0, 0},       {"+", 0, 0},       {".", 0, 0},
           {"-.", 0, 0},    {"e5", 0, 0},      {".e5", 0, 0},     {"+-1", 0, 0},
           {"inf", 0, 0},   {"-nan", 0, 0},    {"infinity", 0, 0}, {" 1", 0, 0},
           {"0x10", 0, 1},  {"0x1p3", 0, 1},   {"1e", 0, 1},      {"1e+", 0, 1},
           {"1.5x", 0, 3},  {"1,5", 0, 1},     {"1d5", 0, 1},     {"1d5", AQ_NUMBER_FORTRAN_D, 3},
           {"1.5E-0x", 0, 6}, {"-.5e-1-2", 0, 6}, {"1.0D-02", 0, 3},
           {"-1.0D-02", AQ_NUMBER_FORTRAN_D, 8}, {"1..2", 0, 2}, {"2385.417.", 0, 8}};
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    size_t len = strlen(c[i].tok);
    char *b = malloc(len ? len : 1);
    if (!b)
      return;
    memcpy(b, c[i].tok, len);
    double v = 2.385;
    size_t used = aq_number_parse(b, len, c[i].flags, &v);
    aq_check(used == c[i].used, "\"%s\": takes %zu, expected %zu", c[i].tok, used, c[i].used);
    if (used == 0)
      aq_check(v == 2.385, "\"%s\": value untouched", c[i].tok);
    free(b);
  }
  /* more than 19 digits and longer than the strtod buffer: its first 63 characters */
  {
    char longnum[71];
    for (int i = 0; i < 70; i++)
      longnum[i] = (char)('1' + i % 9);
    longnum[70] = '\0';
    double v = 0;
    aq_check(aq_number_parse(longnum, 70, 0, &v) == AQ_NUMBER_TOKEN_MAX - 1,
             "70 digits: takes %d", AQ_NUMBER_TOKEN_MAX - 1);
  }
  /* the buffer ends mid-number: only what is inside counts */
  double v = 0;
  aq_check(aq_number_parse("123456e-3", 4, 0, &v) == 4 && v == 1234.0, "cut at 4: %g", v);
  aq_check(aq_number_parse("1.5e-3", 4, 0, &v) == 3 && v == 1.5, "cut in the exponent: %g", v);
  aq_check(aq_decimal_parse(" \t-2.5e1,", 9, &v) == 8 && v == -25.0, "blanks skipped: %g", v);
}

/* A locale whose decimal point is a comma must not change what is read
 * (the strtod path runs in the "C" numeric locale).  Skipped, and said so,
 * when the system has no such locale. */
AQ_TEST(io_number_ignores_the_locale)
{
  static const char *const names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8",
                                      "fr_FR.utf8",  "de_DE",      "nl_NL.UTF-8"};
  static const char *const toks[] = {"0.12345678901234567890123", "1.5e-400",
                                     "9007199254740993.5", "2.385417"};
  double want[4];
  for (int i = 0; i < 4; i++)
    want[i] = strtod(toks[i], NULL); /* the "C" locale: the runner's */
  const char *set = NULL;
  for (size_t i = 0; i < sizeof names / sizeof names[0] && !set; i++)
    set = setlocale(LC_NUMERIC, names[i]);
  char dir[512] = "", cmd[1200];
  if (!set && access("/usr/share/i18n/locales/de_DE", R_OK) == 0 &&
      aq_test_tmpdir(dir, sizeof dir)) {
    /* No comma locale installed: compile one (Debian's locales package
     * has the sources) into a temporary LOCPATH. */
    char abs[PATH_MAX];
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 '%s/de_DE.UTF-8' >/dev/null 2>&1", dir);
    if (system(cmd) == 0 && realpath(dir, abs) && setenv("LOCPATH", abs, 1) == 0)
      set = setlocale(LC_NUMERIC, "de_DE.UTF-8");
  }
  if (!set || strcmp(localeconv()->decimal_point, ",") != 0) {
    setlocale(LC_NUMERIC, "C");
    unsetenv("LOCPATH");
    printf("  number: no comma-decimal locale (install Debian's locales); locale check skipped\n");
    return;
  }
  for (int i = 0; i < 4; i++) {
    double v = 0;
    size_t used = aq_number_parse(toks[i], strlen(toks[i]), 0, &v);
    aq_check(used == strlen(toks[i]) && memcmp(&v, &want[i], sizeof v) == 0,
             "\"%s\" under %s: %.17g taking %zu", toks[i], set, v, used);
  }
  setlocale(LC_NUMERIC, "C");
  if (dir[0]) {
    unsetenv("LOCPATH");
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    aq_check(system(cmd) == 0, "removing %s", dir);
  }
}
