/* test_io_rows.c: the text readers' one-pass reading of plain values (CSV
 * rows, AT2 values) mixed with everything that is not plain: blank lines,
 * comments, quotes, tabs, CR and CRLF ends, no final line end, a value that
 * strtod reads as 0 (1e-400), more rows than the first row's length
 * foretells.  Expected samples: strtod of the same text (the C library, not
 * the reader's parser); expected line numbers: counted in the text here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

/* Parse text as name (the extension picks the reader). */
static aq_status parse(const char *text, const char *name, aq_raw_file *raw, aq_error *e)
{
  return aq_raw_parse((const unsigned char *)text, strlen(text), name, NULL, raw, e);
}

static void same_values(const aq_raw_channel *ch, const char *const *want, size_t n,
                        const char *what)
{
  if (!aq_check(ch->npts == n, "%s: npts %zu, expected %zu", what, ch->npts, n))
    return;
  size_t bad = 0;
  for (size_t k = 0; k < n; k++) {
    double w = strtod(want[k], NULL);
    if (memcmp(&w, &ch->values[k], sizeof w) != 0 && bad++ < 3)
      aq_check(0, "%s: value %zu = %.17g, strtod(\"%s\") = %.17g", what, k, ch->values[k],
               want[k], w);
  }
  aq_check(bad == 0, "%s: %zu of %zu values differ from strtod", what, bad, n);
}

AQ_TEST(io_csv_plain_and_other_rows)
{
  static const char text[] = "t,acc_g\n"
                             "0.00,1.5\n"
                             "0.01, -2.385E-3 \r\n"
                             "0.02,\t7\r\r\n"
                             "\n"
                             "# a comment line\n"
                             "0.03,\"4.25\"\n"
                             "0.04,8.5e-1 # note\n"
                             "  0.05,1e-400\r"
                             "0.06,-.5";
  static const char *const acc[] = {"1.5", "-2.385E-3", "7", "4.25", "8.5e-1", "1e-400", "-.5"};
  aq_raw_file raw;
  aq_error e;
  if (aq_check(parse(text, "rows.csv", &raw, &e) == AQ_OK, "%s", e.message)) {
    same_values(&raw.chan[0], acc, 7, "mixed rows");
    aq_check(fabs(raw.chan[0].dt_s - 0.01) < 1e-15, "dt %.17g", raw.chan[0].dt_s);
    aq_raw_file_free(&raw);
  }
  /* tab- and blank-separated */
  static const char tabs[] = "t\tacc_g\n0\t1.25\n0.01\t2.5\n0.02\t-3.75e-2\n";
  static const char *const tv[] = {"1.25", "2.5", "-3.75e-2"};
  if (aq_check(parse(tabs, "tabs.csv", &raw, &e) == AQ_OK, "%s", e.message)) {
    same_values(&raw.chan[0], tv, 3, "tab-separated");
    aq_raw_file_free(&raw);
  }
  static const char blanks[] = "0 1.0\n0.01   2.0\n 0.02\t 3.5E+1\n";
  static const char *const bv[] = {"1.0", "2.0", "3.5E+1"};
  if (aq_check(parse(blanks, "blanks.txt", &raw, &e) == AQ_OK, "%s", e.message)) {
    same_values(&raw.chan[0], bv, 3, "blank-separated");
    aq_raw_file_free(&raw);
  }
}

/* A first row longer than the rest: more rows than its length foretells. */
AQ_TEST(io_csv_more_rows_than_foretold)
{
  enum { N = 3000 };
  size_t cap = 64 + N * 24;
  char *text = malloc(cap), (*want)[24] = malloc(N * sizeof *want);
  const char **wp = malloc(N * sizeof *wp);
  if (!aq_check(text && want && wp, "memory")) {
    free(text), free(want), free(wp);
    return;
  }
  size_t p = (size_t)snprintf(text, cap, "time,acc_g\n0.000000000000,2.38541700000000\n");
  snprintf(want[0], sizeof want[0], "2.38541700000000");
  wp[0] = want[0];
  for (int k = 1; k < N; k++) {
    snprintf(want[k], sizeof want[k], "%d.%d", k % 7 - 3, k % 10);
    wp[k] = want[k];
    p += (size_t)snprintf(text + p, cap - p, "%d,%s\n", k, want[k]);
  }
  aq_raw_file raw;
  aq_error e;
  if (aq_check(parse(text, "long.csv", &raw, &e) == AQ_OK, "%s", e.message)) {
    same_values(&raw.chan[0], wp, N, "3000 short rows");
    aq_raw_file_free(&raw);
  }
  free(text), free(want), free(wp);
}

/* Errors after plain rows name the line as counted here. */
AQ_TEST(io_csv_errors_after_plain_rows_name_their_line)
{
  static const struct {
    const char *text;
    long line;
    const char *says;
  } c[] = {
      {"t,a\n0,1\n0.01,2\n0.02,x\n", 4, "got \"x\""},
      {"t,a\r0,1\r0.01,2\r0.02,x\r", 4, "got \"x\""},
      {"t,a\r\n0,1\r\n\r\n0.01,2\r\n0.02,2,3\r\n", 5, "expected 2 fields"},
      {"t,a\n0,1\n0.01,2\n0.02,1e999\n", 4, "finite"},
      {"t,a\n0,1\n0.01,2\n0.02,3\n0.04,4\n0.05,5\n0.06,6\n", 5, "evenly spaced"},
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    aq_raw_file raw;
    aq_error e;
    aq_status st = parse(c[i].text, "bad.csv", &raw, &e);
    if (aq_check(st != AQ_OK, "case %zu refused", i)) {
      aq_check(e.line == c[i].line, "case %zu: line %ld, expected %ld (%s)", i, e.line,
               c[i].line, e.message);
      aq_check(strstr(e.message, c[i].says) != NULL, "case %zu: \"%s\" says \"%s\"", i,
               e.message, c[i].says);
    } else {
      aq_raw_file_free(&raw);
    }
  }
}

/* AT2: plain values mixed with glued ones, CR CR LF ends, an end marker. */
AQ_TEST(io_at2_plain_and_glued_values)
{
  static const char text[] = "PEER NGA STRONG MOTION DATABASE RECORD\n"
                             "TEST 2385, 1/1/2000, STATION, 090\n"
                             "ACCELERATION TIME SERIES IN UNITS OF G\n"
                             "NPTS=    9, DT=   .0100 SEC\n"
                             "  .1000000E-01  -.2385417E-02,  .3000000E-01\r\r\n"
                             "  .4000000E-01-.5000000E-01   .6E-01\r\n"
                             "\t7.25\n"
                             "  -.8000000E+00   9   End Data\n";
  static const char *const v[] = {".1000000E-01", "-.2385417E-02", ".3000000E-01",
                                  ".4000000E-01", "-.5000000E-01", ".6E-01",
                                  "7.25",         "-.8000000E+00", "9"};
  aq_raw_file raw;
  aq_error e;
  if (aq_check(parse(text, "mixed.AT2", &raw, &e) == AQ_OK, "%s", e.message)) {
    same_values(&raw.chan[0], v, 9, "AT2 mixed");
    aq_raw_file_free(&raw);
  }
  /* a bad value after plain lines: its line, counted here */
  static const char bad[] = "PEER NGA STRONG MOTION DATABASE RECORD\n"
                            "TEST 2385, 1/1/2000, STATION, 090\n"
                            "ACCELERATION TIME SERIES IN UNITS OF G\n"
                            "NPTS=    6, DT=   .0100 SEC\n"
                            "  .1000000E-01  -.2385417E-02\r\r\n"
                            "  .3000000E-01\r\n"
                            "  .4000000E-01  .5000000X-01  .6E-01\n";
  aq_status st = parse(bad, "bad.AT2", &raw, &e);
  if (aq_check(st != AQ_OK, "bad AT2 refused")) {
    aq_check(e.line == 7, "line %ld, expected 7 (%s)", e.line, e.message);
    aq_check(strstr(e.message, ".5000000X-01") != NULL, "names the token: %s", e.message);
  } else {
    aq_raw_file_free(&raw);
  }
}
