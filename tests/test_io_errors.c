/* test_io_errors.c: every reader error path provoked through the CLI
 * (`archquake info BAD`): exit status, one line on stderr naming the file,
 * the position (line or byte) and the field, and no table row for the bad
 * record; and a suite of good and bad records that still prints the good
 * rows and exits 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC_DIR "tests/data/records/"

static void put(const char *path, const void *data, size_t n)
{
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(data, 1, n, f) != n || fclose(f) != 0)
    fprintf(stderr, "test: cannot write %s\n", path);
}

static void put_text(const char *path, const char *text) { put(path, text, strlen(text)); }

/* Count the lines in s. */
static int nlines(const char *s)
{
  int k = 0;
  for (; *s; s++)
    k += *s == '\n';
  return k;
}

/* Run `info ARGS`; check the exit status, that stderr is exactly one line
 * starting "archquake: " and containing each of the NULL-terminated
 * needles, and that stdout holds the header row only. */
static void expect_fail(const char *args, int want_rc, const char *const *needles)
{
  char cmd[2048], out[8192], err[8192];
  snprintf(cmd, sizeof cmd, "info %s", args);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == want_rc, "%s: exit %d, want %d (stderr: %s)", args, rc, want_rc, err);
  aq_check(nlines(err) == 1 && strncmp(err, "archquake: ", 11) == 0,
           "%s: one diagnostic line: %s", args, err);
  for (int i = 0; needles[i]; i++)
    aq_check(strstr(err, needles[i]) != NULL, "%s: message has \"%s\": %s", args,
             needles[i], err);
  if (want_rc == 1)
    aq_check(nlines(out) == 1 && strncmp(out, "file\t", 5) == 0,
             "%s: header row only: %s", args, out);
}

#define NEED(...) ((const char *const[]){__VA_ARGS__, NULL})

AQ_TEST(io_errors_files)
{
  char d[512], p[700], q[700];
  aq_test_tmpdir(d, sizeof d);
  /* a directory, a missing file, an empty file */
  snprintf(p, sizeof p, "%s", d);
  expect_fail(p, 1, NEED(d, "expected a record file, got a directory"));
  snprintf(p, sizeof p, "%s/missing.AT2", d);
  expect_fail(p, 1, NEED("missing.AT2", "cannot open", "No such file"));
  snprintf(p, sizeof p, "%s/empty.csv", d);
  put(p, "", 0);
  expect_fail(p, 1, NEED("empty.csv", "empty file (0 bytes)"));
  /* binary garbage (a deterministic pseudo-random byte stream) */
  unsigned char g[3000];
  unsigned x = 2385u;
  for (size_t i = 0; i < sizeof g; i++) {
    x = x * 1103515245u + 12345u;
    g[i] = (unsigned char)(x >> 16);
  }
  snprintf(p, sizeof p, "%s/garbage.sac", d);
  put(p, g, sizeof g);
  expect_fail(p, 1, NEED("garbage.sac", "format", "neither SAC", "NVHDR"));
  /* text that is no record */
  snprintf(p, sizeof p, "%s/notes.txt", d);
  put_text(p, "some words\nand more words\n");
  expect_fail(p, 1, NEED("notes.txt", "expected rows of numbers"));
  (void)q;
}

AQ_TEST(io_errors_refused_formats)
{
  expect_fail(REC_DIR "CI.CLC..HNE.mseed", 1, NEED("CI.CLC..HNE.mseed", "sensitivity", "--response"));
  expect_fail(REC_DIR "RSN1616_DUZCE_362-E.VT2", 1, NEED("VT2", "velocity", "not acceleration"));
  expect_fail(REC_DIR "RSN4013_SANSIMEO_36258021.DT2", 1, NEED("DT2", "displacement", "not acceleration"));
  expect_fail(REC_DIR "CI.CLC.xml", 1, NEED("CI.CLC.xml", "XML", "not a record"));
  char d[512], p[700];
  aq_test_tmpdir(d, sizeof d);
  snprintf(p, sizeof p, "%s/x.v2", d);
  put_text(p, "Corrected acceleration  (Format v01.20 with 13 text lines) Src: 1\n"
              "Record of the test\n");
  expect_fail(p, 1, NEED("x.v2:3", "text header", "expected 13 text lines"));
  snprintf(p, sizeof p, "%s/x.smc", d);
  put_text(p, "2 CORRECTED ACCELEROGRAM\n1994-01-17 ARLETA\n");
  expect_fail(p, 1, NEED("x.smc:3", "text header", "expected 11 text lines"));
}

/* A copy of a record with its first occurrence of from replaced by to. */
static void edited_copy(const char *src, const char *dst, const char *from, const char *to)
{
  size_t n;
  char *t = aq_test_read_file(src, &n);
  char *at = t ? strstr(t, from) : NULL;
  if (!at) {
    aq_check(0, "cannot edit %s", src);
    free(t);
    return;
  }
  FILE *f = fopen(dst, "wb");
  fwrite(t, 1, (size_t)(at - t), f);
  fputs(to, f);
  fputs(at + strlen(from), f);
  fclose(f);
  free(t);
}

AQ_TEST(io_errors_at2)
{
  char d[512], p[700];
  aq_test_tmpdir(d, sizeof d);
  const char *src = REC_DIR "IELC180.AT2";
  /* NPTS larger than the data */
  snprintf(p, sizeof p, "%s/big.AT2", d);
  edited_copy(src, p, "NPTS=  4000", "NPTS=  4001");
  expect_fail(p, 1, NEED("big.AT2:", "NPTS", "expected 4001 values", "got 4000"));
  /* truncated in the middle of the data */
  size_t n;
  char *t = aq_test_read_file(src, &n);
  snprintf(p, sizeof p, "%s/cut.AT2", d);
  put(p, t, n / 2);
  free(t);
  expect_fail(p, 1, NEED("cut.AT2:", "NPTS", "expected 4000 values", "truncated"));
  /* NPTS absurdly large: refused before any allocation */
  snprintf(p, sizeof p, "%s/huge.AT2", d);
  edited_copy(src, p, "NPTS=  4000", "NPTS= 900000000000");
  expect_fail(p, 1, NEED("huge.AT2:4: NPTS", "expected at most"));
  /* bad NPTS and DT */
  snprintf(p, sizeof p, "%s/npts.AT2", d);
  edited_copy(src, p, "NPTS=  4000", "NPTS=  40a0");
  expect_fail(p, 1, NEED("npts.AT2:4: NPTS: expected", "40a0"));
  snprintf(p, sizeof p, "%s/dt.AT2", d);
  edited_copy(src, p, "DT= .01000", "DT= -.0100");
  expect_fail(p, 1, NEED("dt.AT2:4: DT: expected a sample interval > 0 s"));
  snprintf(p, sizeof p, "%s/dt0.AT2", d);
  edited_copy(src, p, "DT= .01000", "DT= .00000");
  expect_fail(p, 1, NEED("dt0.AT2:4: DT: expected a sample interval > 0 s"));
  snprintf(p, sizeof p, "%s/half.AT2", d);
  edited_copy(src, p, "NPTS=  4000", "NPTS=  3999.5");
  expect_fail(p, 1, NEED("half.AT2:4: NPTS: expected a positive integer", "3999.5"));
  snprintf(p, sizeof p, "%s/nodt.AT2", d);
  edited_copy(src, p, "DT= .01000 SEC", "");
  expect_fail(p, 1, NEED("nodt.AT2:4: DT: expected"));
  /* NaN, Inf and a non-number: line and value index */
  snprintf(p, sizeof p, "%s/nan.AT2", d);
  edited_copy(src, p, "  .5304162E-03", "  NaN");
  expect_fail(p, 1, NEED("nan.AT2:5: value 3: expected a finite number, got \"NaN\""));
  snprintf(p, sizeof p, "%s/inf.AT2", d);
  edited_copy(src, p, "   .1438734E-03", "   -Infinity");
  expect_fail(p, 1, NEED("inf.AT2:", "expected a finite number", "-Infinity"));
  snprintf(p, sizeof p, "%s/word.AT2", d);
  edited_copy(src, p, "  .7743260E-02", "  .77x3260E-02");
  expect_fail(p, 1, NEED("word.AT2:5: value 4: expected a number, got \".77x3260E-02\""));
  snprintf(p, sizeof p, "%s/over.AT2", d);
  edited_copy(src, p, "  .7743260E-02", "  .7743260E+999");
  expect_fail(p, 1, NEED("over.AT2:5: value 4: expected a finite number"));
  snprintf(p, sizeof p, "%s/huge-g.AT2", d);
  edited_copy(src, p, "  .7743260E-02", "  .7743260E+308");
  expect_fail(p, 1, NEED("huge-g.AT2", "value 4", "finite in m/s2", "overflows"));
  /* a rule reading an AT2 as counts: an AT2 has no sensitivity */
  char a[800];
  snprintf(a, sizeof a, "--units '*IELC180*=counts' %s", src);
  expect_fail(a, 1, NEED("IELC180.AT2", "counts", "sensitivity"));
}

/* Offsets in a SAC file (little-endian, as in tests/data/records). */
static void put_i32(unsigned char *b, size_t off, int v)
{
  unsigned u = (unsigned)v;
  for (int i = 0; i < 4; i++)
    b[off + i] = (unsigned char)(u >> (8 * i));
}

AQ_TEST(io_errors_sac)
{
  char d[512], p[700], a[900];
  aq_test_tmpdir(d, sizeof d);
  size_t n;
  unsigned char *t = (unsigned char *)aq_test_read_file(REC_DIR "CI.CLC..HNE.D.2019.187.031923.SAC", &n);
  if (!aq_check(t && n == 156636, "source SAC"))
    return;
  unsigned char *c = malloc(n);
  /* truncated: NPTS larger than the data */
  snprintf(p, sizeof p, "%s/cut.SAC", d);
  put(p, t, n - 1000);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("cut.SAC: header NPTS (byte 316)", "file truncated"));
  /* header only, shorter than a header */
  snprintf(p, sizeof p, "%s/short.SAC", d);
  put(p, t, 700);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("short.SAC: header NPTS", "got 68"));
  /* trailing bytes */
  memcpy(c, t, n);
  put_i32(c, 4 * 79, 39000);
  snprintf(p, sizeof p, "%s/long.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("long.SAC: header NPTS", "trailing bytes"));
  /* no samples */
  memcpy(c, t, n);
  put_i32(c, 4 * 79, 0);
  snprintf(p, sizeof p, "%s/zero.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("zero.SAC: header NPTS (byte 316): expected a positive number of "
                         "samples, got 0"));
  /* a NaN sample: byte offset of sample 17 */
  memcpy(c, t, n);
  c[632 + 4 * 17 + 0] = 0x00, c[632 + 4 * 17 + 1] = 0x00;
  c[632 + 4 * 17 + 2] = 0xc0, c[632 + 4 * 17 + 3] = 0x7f;
  snprintf(p, sizeof p, "%s/nan.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("nan.SAC: sample (byte 700)", "sample 17", "NaN"));
  /* DELTA negative */
  memcpy(c, t, n);
  c[3] ^= 0x80; /* sign bit of the little-endian float at byte 0 */
  snprintf(p, sizeof p, "%s/delta.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("delta.SAC: header DELTA (byte 0): expected a sample interval > 0 s, got -0.01"));
  /* not evenly spaced, not a time series */
  memcpy(c, t, n);
  put_i32(c, 4 * 105, 0);
  snprintf(p, sizeof p, "%s/uneven.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("uneven.SAC: header LEVEN (byte 420): expected 1 (evenly sampled), got 0"));
  memcpy(c, t, n);
  put_i32(c, 4 * 85, 2); /* IRLIM: a spectrum */
  snprintf(p, sizeof p, "%s/spectrum.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("spectrum.SAC: header IFTYPE (byte 340): expected ITIME", "got 2"));
  /* counts without SCALE */
  memcpy(c, t, n);
  c[12] = 0x00, c[13] = 0xe4, c[14] = 0x40, c[15] = 0xc6; /* -12345.0f */
  snprintf(p, sizeof p, "%s/noscale.SAC", d);
  put(p, c, n);
  snprintf(a, sizeof a, "--units counts %s", p);
  expect_fail(a, 1, NEED("noscale.SAC", "SCALE", "found none"));
  /* units: undefined IDEP without --units; IVEL and IDISP */
  expect_fail(REC_DIR "CI.CLC..HNE.D.2019.187.031923.SAC", 1,
              NEED("IDEP", "undefined", "--units"));
  memcpy(c, t, n);
  put_i32(c, 4 * 86, 7);
  snprintf(p, sizeof p, "%s/vel.SAC", d);
  put(p, c, n);
  expect_fail(p, 1, NEED("vel.SAC", "IDEP", "IVEL", "velocity", "acceleration only"));
  /* not an acceleration whatever --units says */
  snprintf(a, sizeof a, "--units g --units '*=gal' %s", p);
  expect_fail(a, 1, NEED("vel.SAC", "header IDEP: IVEL", "expected ground acceleration"));
  put_i32(c, 4 * 86, 6);
  snprintf(p, sizeof p, "%s/disp.SAC", d);
  put(p, c, n);
  expect_fail(p, 1, NEED("disp.SAC", "IDEP", "IDISP", "displacement", "acceleration only"));
  snprintf(a, sizeof a, "--units m/s2 %s", p);
  expect_fail(a, 1, NEED("disp.SAC", "header IDEP: IDISP", "expected ground acceleration"));
  /* IACC with values in g: implausible as nm/s2 */
  expect_fail(REC_DIR "20190706031952.CJ.T001230.HNE.sac", 1,
              NEED("HNE.sac", "nm/s2", "implausible", "header IDEP: IACC", "what the file states",
                   "--units '"));
  {
    /* no other units offered for what the file states */
    char out[4096], err[4096];
    aq_test_run("info " REC_DIR "20190706031952.CJ.T001230.HNE.sac", out, sizeof out, err,
                sizeof err);
    aq_check(!strstr(err, "plausible in") && !strstr(err, "g (0.0"),
             "stated units second-guessed: %s", err);
  }
  free(c);
  free(t);
}

AQ_TEST(io_errors_csv)
{
  char d[512], p[700], a[900];
  aq_test_tmpdir(d, sizeof d);
  snprintf(p, sizeof p, "%s/nan.csv", d);
  put_text(p, "time,acc (g)\n0,0.1\n0.01,0.2\n0.02,nan\n0.03,0.1\n");
  expect_fail(p, 1, NEED("nan.csv:4: column 2 (acc (g)): expected a finite number, got \"nan\""));
  snprintf(p, sizeof p, "%s/huge.csv", d);
  put_text(p, "time,acc (g)\n0,0.1\n0.01,1.5e308\n");
  expect_fail(p, 1, NEED("huge.csv", "value 2", "finite in m/s2"));
  snprintf(p, sizeof p, "%s/word.csv", d);
  put_text(p, "time,acc (g)\r\n0,0.1\r\n0.01,0.2\r\n0.02,0.3\r\n0.03,abc\r\n");
  expect_fail(p, 1, NEED("word.csv:5: column 2 (acc (g)): expected a number, got \"abc\""));
  snprintf(p, sizeof p, "%s/empty-field.csv", d);
  put_text(p, "time,acc (g)\n0,0.1\n0.01,\n");
  expect_fail(p, 1, NEED("empty-field.csv:3: column 2 (acc (g)): expected a number, got \"\""));
  snprintf(p, sizeof p, "%s/ragged.csv", d);
  put_text(p, "time,acc (g)\n0,0.1\n0.01,0.2,0.3\n");
  expect_fail(p, 1, NEED("ragged.csv:3: expected 2 fields like line 2, got 3"));
  snprintf(p, sizeof p, "%s/uneven.csv", d);
  put_text(p, "time,acc (g)\n0,0.1\n0.01,0.2\n0.03,0.3\n0.04,0.1\n0.05,0.1\n");
  expect_fail(p, 1, NEED("uneven.csv:4: time: expected evenly spaced times", "within 1 %", "from 0.01 to 0.03"));
  /* times drifting slowly: every step within 1 % of the median, but sample
   * 500 is 1.3 % of a step off the even grid (t_i = 0.01 i + 4e-8 i^2) */
  snprintf(p, sizeof p, "%s/drift.csv", d);
  {
    FILE *f = fopen(p, "w");
    fputs("time,acc (g)\n", f);
    for (int i = 0; i < 1000; i++)
      fprintf(f, "%.10f,%.4f\n", 0.01 * i + 4e-8 * i * i, 0.01 * (i % 7));
    fclose(f);
  }
  expect_fail(p, 1, NEED("drift.csv:", "time: expected evenly spaced times", "for sample"));
  snprintf(p, sizeof p, "%s/backwards.csv", d);
  put_text(p, "time,acc (g)\n0.04,0.1\n0.03,0.2\n0.02,0.3\n");
  expect_fail(p, 1, NEED("backwards.csv:", "time: expected increasing times"));
  snprintf(p, sizeof p, "%s/nounits.csv", d);
  put_text(p, "time,acc\n0,0.1\n0.01,0.2\n");
  expect_fail(p, 1, NEED("nounits.csv", "units", "found none", "--units"));
  snprintf(p, sizeof p, "%s/vel.csv", d);
  put_text(p, "time,vel (cm/s)\n0,0.1\n0.01,0.2\n");
  expect_fail(p, 1, NEED("vel.csv", "vel (cm/s)", "velocity", "acceleration only"));
  snprintf(a, sizeof a, "--units g %s", p);
  expect_fail(a, 1, NEED("vel.csv", "vel (cm/s)", "expected ground acceleration"));
  snprintf(p, sizeof p, "%s/single.txt", d);
  put_text(p, "acc_g\n0.1\n0.2\n0.3\n");
  expect_fail(p, 1, NEED("single.txt:2: dt: no time column", "--dt"));
  snprintf(a, sizeof a, "--column 3 %s", REC_DIR "elcentro_chopra.csv");
  expect_fail(a, 1, NEED("elcentro_chopra.csv:2: --column: expected a column in 1..2, got 3"));
  snprintf(a, sizeof a, "--column 1 %s", REC_DIR "elcentro_chopra.csv");
  expect_fail(a, 1, NEED("--column: expected an acceleration column, got 1 (the time)"));
}

AQ_TEST(io_errors_bad_reader_options)
{
  char out[4096], err[4096];
  int rc = aq_test_run("info --units furlongs --units '*.SAC=' --units '=g' --column 0 "
                       "--dt 0 " REC_DIR "IELC180.AT2",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "bad reader options exit 2, got %d", rc);
  aq_check(nlines(err) == 5, "five lines, one per bad option: %s", err);
  aq_check(strstr(err, "\"furlongs\"") && strstr(err, "--units: expected GLOB=U") &&
               strstr(err, "--column") && strstr(err, "--dt"),
           "each named: %s", err);
  aq_check(out[0] == '\0', "no table: %s", out);
}

AQ_TEST(io_errors_suite_good_bad_good)
{
  char out[8192], err[8192];
  int rc = aq_test_run("info " REC_DIR "IELC180.AT2 " REC_DIR "CI.CLC..HNE.mseed " REC_DIR
                       "CI.CLC..HNE.D.2019.187.031923.SAC " REC_DIR "kocaeli.csv "
                       "--units '*.SAC=counts'",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "a bad record makes exit 1, got %d", rc);
  aq_check(nlines(out) == 4, "header and three good rows: %s", out);
  aq_check(strstr(out, "IELC180.AT2\tat2\t4000\t") && strstr(out, "kocaeli.csv\tcsv\t5440\t") &&
               strstr(out, "CI.CLC..HNE.D.2019.187.031923.SAC\tsac-le\t39001\t0.01\t") &&
               strstr(out, "\tcounts\t"),
           "good rows: %s", out);
  aq_check(nlines(err) == 1 && strstr(err, "CI.CLC..HNE.mseed") && strstr(err, "miniSEED"),
           "one line for the bad one: %s", err);
  /* the main job's record list reads with the documented --units rule */
  rc = aq_test_run("info records/*.AT2 records/*.csv records/*.SAC --units '*.SAC=counts'", out,
                   sizeof out, err, sizeof err);
  aq_check(rc == 0, "records/ all read: rc %d %s", rc, err);
  aq_check(nlines(out) == 6, "5 sample records: %s", out);
}
