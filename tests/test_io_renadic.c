/* test_io_renadic.c: the RENADIC (Chile) V1 reader against the numbers in
 * tests/data/records/PROVENANCE.md (copiapo1002271.v1) and the file's own
 * header MAX lines; its detection beside CSMIP; the vertical refusal; and
 * its refusals of damaged files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "raw_fixture.h"

#define RENADIC_FILE "tests/data/records/copiapo1002271.v1"
#define G10_TO_G 0.1      /* literal: units "G/10" */
#define G0_MPS2 9.80665   /* literal */
#define STORED_STEP_G 1e-4 /* values printed to 0.001 g/10 */

static aq_status parse_via_detect(const unsigned char *buf, size_t n, const char *name,
                                  const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  return aq_raw_parse(buf, n, name, NULL, raw, err);
}

AQ_TEST(io_renadic_three_channels)
{
  aq_raw_file r;
  /* through aq_raw_parse: detection from the content, then the reader */
  if (!aq_test_raw_load(parse_via_detect, RENADIC_FILE, &r))
    return;
  aq_check(strcmp(r.format, "renadic") == 0, "format %s", r.format);
  aq_check(r.nchan == 3, "nchan %zu", r.nchan);
  if (r.nchan != 3)
    goto out;
  aq_check(strcmp(r.event, "MAULE 2010") == 0, "event %s", r.event);
  static const char *const name[3] = {"EW", "NZ", "Z"};
  static const int vertical[3] = {-1, -1, 1};
  /* PROVENANCE: stored peaks -0.300, -0.160, -0.081 g/10 (0.03000, 0.01600,
   * 0.00810 g), at 43.18, 33.64, 38.05 s; Z demeaned 0.008083 g */
  static const double pga_g[3] = {0.03000, 0.01600, 0.00810};
  static const double t_peak_s[3] = {43.18, 33.64, 38.05};
  /* header: MAX = -0.030 G, AT 23.180 / -0.016 G AT 13.640 / -0.008 G AT
   * 18.050 SEC, counted from the trigger 20 s after the first sample */
  static const double header_max_g[3] = {0.030, 0.016, 0.008};
  static const double header_t_s[3] = {23.180, 13.640, 18.050};
  for (int i = 0; i < 3; i++) {
    const aq_raw_channel *c = &r.chan[i];
    aq_check(strcmp(c->channel, name[i]) == 0, "ch %d name %s", i + 1, c->channel);
    aq_check(c->npts == 7000, "ch %d npts %zu", i + 1, c->npts);
    aq_check_rel(c->dt_s, 0.01, 1e-9, "ch %d dt (time column 0.00..69.99)", i + 1);
    aq_check(strcmp(c->units, "g/10") == 0, "ch %d units %s", i + 1, c->units);
    aq_check(isnan(c->azimuth_deg) && isnan(c->dip_deg), "ch %d azimuth %g dip %g not stated",
             i + 1, c->azimuth_deg, c->dip_deg);
    aq_check(c->vertical == vertical[i], "ch %d vertical %d", i + 1, c->vertical);
    aq_check(strcmp(c->station, "672") == 0, "station %s", c->station);
    aq_check(strcmp(c->reference, "2010-02-27T02:45:26.000Z") == 0 && c->begin_s == 0,
             "ch %d start %s + %g s", i + 1, c->reference, c->begin_s);
    double pk_g = aq_test_peak_abs(c) * G10_TO_G;
    aq_check_abs(pk_g, pga_g[i], STORED_STEP_G / 20, "ch %d PGA (g)", i + 1);
    aq_check_abs(pk_g, header_max_g[i], 0.0005, "ch %d header MAX (g, 3 decimals)", i + 1);
    size_t k = (size_t)((header_t_s[i] + 20.0) / 0.01 + 0.5);
    aq_check(k < c->npts && fabs(c->values[k]) * G10_TO_G == pk_g &&
                 fabs(t_peak_s[i] - (header_t_s[i] + 20.0)) < 1e-9,
             "ch %d peak at header time + 20 s", i + 1);
  }
  aq_check_abs(aq_test_peak_demeaned(&r.chan[2]) * G10_TO_G, 0.008083, 5e-7,
               "Z demeaned PGA (g)");
out:
  aq_raw_file_free(&r);
}

/* RENADIC is told from CSMIP by content, both ways. */
AQ_TEST(io_renadic_detection)
{
  static const struct {
    const char *path;
    aq_format want;
  } f[] = {{RENADIC_FILE, AQ_FMT_RENADIC},
           {AGENCY_DIR "CE89146.V1", AQ_FMT_COSMOS}, /* CSMIP, read by the COSMOS reader */
           {AGENCY_DIR "ce36456p_CE36456.V2", AQ_FMT_COSMOS}};
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
    size_t n;
    char *buf = aq_test_read_file(f[i].path, &n);
    if (!aq_check(buf != NULL, "read %s", f[i].path))
      continue;
    aq_format got = aq_sniff_format((const unsigned char *)buf, n);
    aq_check(got == f[i].want, "%s: detected %d (%s), want %d", f[i].path, (int)got,
             aq_sniff_describe(got), (int)f[i].want);
    free(buf);
  }
}

/* Through aq_record_decide: g/10 to m/s^2, and Z refused as excitation. */
AQ_TEST(io_renadic_decide_vertical)
{
  aq_read_opts ro = {0};
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_read(RENADIC_FILE "#EW", &ro, &r, &e) == AQ_OK, "%s", e.message)) {
    double pk = 0;
    for (size_t k = 0; k < r.npts; k++)
      pk = fmax(pk, fabs(r.acc_mps2[k]));
    aq_check_rel(pk, 0.03000 * G0_MPS2, 1e-9, "EW PGA m/s2");
    aq_check(r.vertical == 0 && aq_record_check_horizontal(&r, &ro, &e) == AQ_OK,
             "EW runs");
    aq_record_free(&r);
  }
  if (aq_check(aq_record_read(RENADIC_FILE "#NZ", &ro, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check(r.vertical == 0, "NZ is not vertical");
    aq_record_free(&r);
  }
  if (aq_check(aq_record_read(RENADIC_FILE "#Z", &ro, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check(r.vertical == 1, "Z vertical %d", r.vertical);
    aq_check(aq_record_check_horizontal(&r, &ro, &e) == AQ_EUNSUPPORTED &&
                 strstr(e.message, "\"Z\"") && strstr(e.message, "--accept-vertical"),
             "Z refused: %s", e.message);
    ro.accept_vertical = 1;
    aq_check(aq_record_check_horizontal(&r, &ro, &e) == AQ_OK, "Z accepted");
    aq_record_free(&r);
  }
}

/* Byte offset of the first `text` in the file, or 0. */
static size_t offset_of(const char *text)
{
  size_t n;
  char *buf = aq_test_read_file(RENADIC_FILE, &n);
  char *at = buf ? strstr(buf, text) : NULL;
  size_t off = at ? (size_t)(at - buf) : 0;
  free(buf);
  return off;
}

static void expect_bad(size_t cut, const char *from, const char *to, const char *line,
                       const char *field, const char *found, const char *what)
{
  char msg[1400];
  aq_status s =
      aq_test_raw_altered(aq_renadic_parse, RENADIC_FILE, cut, from, to, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && aq_test_msg_names(msg, RENADIC_FILE, line) &&
               strstr(msg, field) && (!found || strstr(msg, found)),
           "%s: %s", what, msg);
}

AQ_TEST(io_renadic_bad_input)
{
  expect_bad(500, NULL, NULL, ":11:", "text header", "13 text lines", "cut in the text header");
  expect_bad(1200, NULL, NULL, ":20:", "integer header", "value 98", "cut in the integer header");
  size_t end1 = offset_of("/&  ----------  END OF DATA FOR CHANNEL 1");
  aq_check(end1 > 300, "end line of channel 1 found");
  /* 300 bytes before it: line 1423 is cut short */
  expect_bad(end1 - 300, NULL, NULL, ":1423:", "pairs of channel 1", "line of 60 characters",
             "cut in the data");
  /* at the start of channel 1's last data line */
  expect_bad(offset_of(" 69.950 "), NULL, NULL, ":1427:", "pairs of channel 1",
             "file ends after 13990", "data ends early");
  expect_bad((size_t)-1, " 10.010  0.029", " 10.015  0.029", ":228:", "time column",
             "10.015", "uneven time column");
  expect_bad((size_t)-1, "  1.010  0.026", "  1.010  0.0z6", ":48:", "pairs of channel 1",
             "\"0.0z6\"", "non-numeric value");
  expect_bad((size_t)-1, "/&  ----------  END OF DATA FOR CHANNEL 1",
             "    ----------  END OF DATA FOR CHANNEL 1", ":1428:", "end of data",
             "END OF DATA FOR CHANNEL 1", "missing END OF DATA marker");
  expect_bad((size_t)-1, "/&  ----------  END OF DATA FOR CHANNEL 1",
             "/&  ----------  MORE DATA FOR CHANNEL 1", ":1428:", "end of data",
             "MORE DATA", "end line without END OF DATA");
  size_t end3 = offset_of("/&  ----------  END OF DATA FOR CHANNEL 3");
  expect_bad(end3, NULL, NULL, ":", "end of data", "end of the file", "file ends before END");
  expect_bad((size_t)-1, "NO. OF POINTS =   7000", "NO. OF POINTS =   7x00", ":11:",
             "NO. OF POINTS", "7x00", "bad NO. OF POINTS");
}

/* The same through the command line: one line on stderr, exit non-zero. */
AQ_TEST(io_renadic_cli_refusal)
{
  size_t n;
  char *buf = aq_test_read_file(RENADIC_FILE, &n);
  if (!aq_check(buf != NULL, "read"))
    return;
  char path[] = "build/test-renadic-uneven.v1";
  char *at = strstr(buf, " 10.010  0.029");
  if (at)
    memcpy(at, " 10.015", 7);
  FILE *f = fopen(path, "wb");
  aq_check(f && fwrite(buf, 1, n, f) == n && fclose(f) == 0, "write %s", path);
  free(buf);
  char cmd[256], out[8192], err[8192];
  snprintf(cmd, sizeof cmd, "info %s", path);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc != 0 && strncmp(err, "archquake: ", 11) == 0 && strstr(err, path) &&
               strstr(err, ":228:") && strstr(err, "time column") &&
               strchr(err, '\n') == strrchr(err, '\n'),
           "exit %d, stderr: %s", rc, err);
  remove(path);
}
