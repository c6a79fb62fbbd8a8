/* test_io_csv_rows.c: the CSV reader's rows four at a time (csv_fields.c)
 * against strtod and against the one-row reading.  Files of fixed layouts
 * (so the kernel takes their rows): "%.3f" times whose width grows past 10
 * and 100 s, channels "%.7E", "%.6f", "%+.3e", "%.4f" with random signs and
 * now and then an exponent too large for the exact path, separators ',',
 * ';', tab, LF and CR LF ends, each header padded 0..31 bytes so the rows
 * start at every offset of a 32-byte block.  Expected values: strtod of the
 * tokens written (the C library, not the reader's parser).  Then every
 * byte of such files replaced in turn (a letter, '.', a digit, '-', 'e',
 * LF) and every cut: the AVX2 kernel and the one-row reading must give the
 * same status, message, line and values bit for bit, and a letter must be
 * refused at its line.  Each buffer is a heap block of exactly its size,
 * so a read past its end is caught by the address sanitizer. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/at2_fields.h"
#include "io/readers.h"
#include "kernels.h"

#define ROWS_MAX 160 /* rows of one file */
#define COLS_MAX 4   /* the time and up to three channels */
#define TOK 32       /* characters of one token */

typedef struct {
  unsigned long long s;
} rng;

static unsigned rnd(rng *r, unsigned n)
{
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (unsigned)((r->s >> 33) % n);
}

typedef struct {
  char *text;
  size_t len, cap;
  size_t rows, ncols;
  char tok[ROWS_MAX][COLS_MAX][TOK];
} gen;

static void put(gen *g, const char *s)
{
  size_t l = strlen(s);
  if (g->len + l + 1 > g->cap) {
    g->cap = 2 * (g->len + l + 1);
    g->text = realloc(g->text, g->cap);
  }
  memcpy(g->text + g->len, s, l + 1);
  g->len += l;
}

/* A file of fixed layouts: header padded by pad bytes, rows rows. */
static void generate(gen *g, rng *r, size_t pad, size_t rows)
{
  static const char seps[] = {',', ';', '\t'};
  static const char *const fmts[] = {"%.7E", "%.6f", "%+.3e", "%.4f"};
  static const double t0s[] = {0.0, 9.9, 99.85, 999.9};
  g->len = 0;
  g->ncols = 2 + rnd(r, COLS_MAX - 1);
  g->rows = rows;
  char sep[2] = {seps[rnd(r, 3)], 0};
  const char *end = rnd(r, 2) ? "\n" : "\r\n";
  int fmt[COLS_MAX];
  for (size_t i = 1; i < g->ncols; i++)
    fmt[i] = (int)rnd(r, 4);
  double t0 = t0s[rnd(r, 4)];
  put(g, "t");
  for (size_t i = 1; i < g->ncols; i++) {
    put(g, sep);
    put(g, "a");
    if (i == 1)
      for (size_t j = 0; j < pad; j++)
        put(g, "x");
  }
  put(g, end);
  for (size_t k = 0; k < rows; k++) {
    snprintf(g->tok[k][0], TOK, "%.3f", t0 + (double)k * 0.005);
    for (size_t i = 1; i < g->ncols; i++) {
      double v = (rnd(r, 2000001) - 1000000.0) / 1000000.0 * pow(10.0, (int)rnd(r, 7) - 5);
      if (rnd(r, 40) == 0)
        v *= 1e-25; /* 10^e not exact: strtod's */
      else if ((fmt[i] == 0 || fmt[i] == 2) && rnd(r, 8) == 0)
        /* exponents about the exact path's edges, e = exponent less the
         * digits after the point: +-22 and +-23 */
        v = (1 + rnd(r, 1000000) / 1e6) * pow(10.0, (int)rnd(r, 14) + (rnd(r, 2) ? 18 : -23));
      snprintf(g->tok[k][i], TOK, fmts[fmt[i]], v);
    }
    for (size_t i = 0; i < g->ncols; i++) {
      if (i)
        put(g, sep);
      put(g, g->tok[k][i]);
    }
    if (k + 1 < rows || rnd(r, 2))
      put(g, end);
  }
}

/* 1-based line of byte pos (LF, CR LF or a run of CRs end a line). */
static long line_at(const char *s, size_t pos)
{
  long line = 1;
  for (size_t i = 0; i < pos;) {
    if (s[i] == '\r') {
      while (i < pos && s[i] == '\r')
        i++;
      if (i < pos && s[i] == '\n')
        i++;
      line++;
    } else if (s[i++] == '\n') {
      line++;
    }
  }
  return line;
}

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* s[0..n) read from a heap block of exactly n bytes, kernel avx2 (1) or
 * the one-row reading (0). */
static aq_status parse_with(int avx2, const char *s, size_t n, aq_raw_file *raw, aq_error *e)
{
  unsigned char *b = malloc(n ? n : 1);
  memcpy(b, s, n);
  aq_at2_fields_force_(avx2);
  aq_status st = aq_raw_parse(b, n, "rows.csv", NULL, raw, e);
  aq_at2_fields_force_(-1);
  free(b);
  return st;
}

/* The two readings of s[0..n) agree: status, message, line, values.
 * Returns 1 if they do; *st_out the status. */
static int agree(const char *s, size_t n, aq_status *st_out, aq_error *e1)
{
  aq_raw_file r1, r0;
  aq_error e0;
  aq_status s1 = parse_with(1, s, n, &r1, e1), s0 = parse_with(0, s, n, &r0, &e0);
  int ok = s1 == s0;
  if (ok && s1 != AQ_OK)
    ok = e1->line == e0.line && strcmp(e1->message, e0.message) == 0 &&
         strcmp(e1->field, e0.field) == 0;
  if (ok && s1 == AQ_OK) {
    ok = r1.nchan == r0.nchan;
    for (size_t j = 0; ok && j < r1.nchan; j++) {
      ok = r1.chan[j].npts == r0.chan[j].npts && same(r1.chan[j].dt_s, r0.chan[j].dt_s);
      for (size_t k = 0; ok && k < r1.chan[j].npts; k++)
        ok = same(r1.chan[j].values[k], r0.chan[j].values[k]);
    }
  }
  if (s1 == AQ_OK)
    aq_raw_file_free(&r1);
  if (s0 == AQ_OK)
    aq_raw_file_free(&r0);
  *st_out = s1;
  return ok;
}

/* Every alignment, both readings: the values strtod gives. */
AQ_TEST(io_csv_rows_fixed_layouts_equal_strtod)
{
  rng r = {424242};
  gen g = {0};
  size_t bad = 0, values = 0;
  for (int mode = 1; mode >= 0; mode--)
    for (size_t pad = 0; pad < 32; pad++)
      for (int f = 0; f < 4; f++) {
        generate(&g, &r, pad, 40 + rnd(&r, ROWS_MAX - 40));
        aq_raw_file raw;
        aq_error e;
        if (!aq_check(parse_with(mode, g.text, g.len, &raw, &e) == AQ_OK, "pad %zu: %s", pad,
                      e.message))
          continue;
        aq_check(raw.nchan == g.ncols - 1, "pad %zu: %zu channels", pad, raw.nchan);
        for (size_t j = 0; j < raw.nchan; j++) {
          aq_check(raw.chan[j].npts == g.rows, "pad %zu: %zu rows, want %zu", pad,
                   raw.chan[j].npts, g.rows);
          for (size_t k = 0; k < g.rows && k < raw.chan[j].npts; k++, values++)
            if (!same(raw.chan[j].values[k], strtod(g.tok[k][j + 1], NULL)) && bad++ < 5)
              aq_check(0, "mode %d pad %zu row %zu column %zu: %.17g, strtod(\"%s\") %.17g",
                       mode, pad, k, j + 2, raw.chan[j].values[k], g.tok[k][j + 1],
                       strtod(g.tok[k][j + 1], NULL));
        }
        aq_check(raw.chan[0].dt_s == 0.005, "pad %zu: dt %.17g", pad, raw.chan[0].dt_s);
        aq_raw_file_free(&raw);
      }
  aq_check(bad == 0, "%zu of %zu values differ from strtod", bad, values);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu values, %zu differ from strtod\n", values, bad);
  free(g.text);
}

/* Each byte of the rows replaced in turn: both readings agree, and a
 * letter is refused at its line. */
AQ_TEST(io_csv_rows_bad_byte_each_position)
{
  static const char bytes[] = {'x', '.', '7', '-', 'e', '\n'};
  rng r = {1123};
  gen g = {0};
  size_t tried = 0, differ = 0, wrong = 0;
  for (int f = 0; f < 6; f++) {
    generate(&g, &r, (size_t)f * 5, 24);
    /* from the second row on (a first row that is not numbers would be
     * taken for a line of the preamble) */
    size_t first = 0;
    for (int l = 0; l < 2; l++)
      first += strcspn(g.text + first, "\n") + 1;
    char *t = malloc(g.len);
    for (size_t pos = first; pos < g.len; pos++)
      for (size_t b = 0; b < sizeof bytes; b++) {
        if (g.text[pos] == bytes[b])
          continue;
        memcpy(t, g.text, g.len);
        t[pos] = bytes[b];
        aq_status st;
        aq_error e;
        tried++;
        if (!agree(t, g.len, &st, &e) && differ++ < 5)
          aq_check(0, "file %d: '%c' at byte %zu: the readings differ", f, bytes[b], pos);
        if (bytes[b] == 'x' && (st == AQ_OK || e.line != line_at(t, pos)) && wrong++ < 5)
          aq_check(0, "file %d: 'x' at byte %zu: status %d line %ld, want line %ld", f, pos,
                   (int)st, st == AQ_OK ? -1 : e.line, line_at(t, pos));
      }
    free(t);
  }
  aq_check(differ == 0 && wrong == 0, "%zu of %zu changes read differently, %zu misreported",
           differ, tried, wrong);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu changed bytes, %zu read differently, %zu misreported\n", tried, differ, wrong);
  free(g.text);
}

/* Every cut of such files: both readings agree (and no read past the end). */
AQ_TEST(io_csv_rows_cut_anywhere)
{
  rng r = {77};
  gen g = {0};
  size_t cuts = 0, differ = 0;
  for (int f = 0; f < 6; f++) {
    generate(&g, &r, (size_t)f * 3, 30);
    for (size_t n = 0; n <= g.len; n++) {
      aq_status st;
      aq_error e;
      cuts++;
      if (!agree(g.text, n, &st, &e) && differ++ < 5)
        aq_check(0, "file %d cut at %zu: the readings differ", f, n);
    }
  }
  aq_check(differ == 0, "%zu of %zu cuts read differently", differ, cuts);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu cuts, %zu read differently\n", cuts, differ);
  free(g.text);
}

/* One row's time moved by 30 % of the step, at each row in turn: refused
 * at that row's line (its step is 1.3 dt, the first uneven one). */
static void io_csv_rows_uneven_step_each_row_(void)
{
  enum { N = 41 };
  size_t wrong = 0;
  for (int j = 1; j < N; j++) {
    char *text = malloc(N * 32 + 16);
    size_t p = (size_t)sprintf(text, "t,acc\n");
    for (int k = 0; k < N; k++)
      p += (size_t)sprintf(text + p, "%.3f,%.4f\n", 0.01 * k + (k == j ? 0.003 : 0.0),
                           0.001 * (k % 7));
    aq_raw_file raw;
    aq_error e;
    aq_status st = parse_with(aq_at2_fields_avx2(), text, p, &raw, &e);
    if (st == AQ_OK) {
      aq_raw_file_free(&raw);
      if (wrong++ < 5)
        aq_check(0, "row %d moved: accepted", j);
    } else if ((e.line != j + 2 || !strstr(e.message, "evenly spaced")) && wrong++ < 5) {
      aq_check(0, "row %d moved: line %ld, want %d (%s)", j, e.line, j + 2, e.message);
    }
    free(text);
  }
  aq_check(wrong == 0, "%zu of %d moved rows misreported", wrong, N - 1);
}
BOTH_KERNELS(io_csv_rows_uneven_step_each_row)
