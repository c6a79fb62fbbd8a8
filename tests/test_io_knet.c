/* test_io_knet.c: the K-NET / KiK-net ASCII reader against the values in
 * tests/data/records/PROVENANCE.md (computed there by an independent parser;
 * each demeaned peak equals the file's own "Max. Acc. (gal)"), and its
 * refusals of truncated or malformed files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define REC_DIR "tests/data/records/"
#define G0_MPS2 9.80665      /* standard gravity (CGPM 1901), for the g columns */
#define HEADER_GAL_ABS 6e-4  /* the header's Max. Acc. has 3 decimals of gal */

AQ_TEST(io_knet_agency_files)
{
  static const struct {
    const char *file, *format, *channel, *location, *reference;
    size_t npts;
    double pga_g, demeaned_g, header_gal;
    int vertical;
    double tol_g; /* 0.6 x the last digit PROVENANCE prints of PGA and demeaned PGA */
  } f[] = {
      {"AOM0170806140843.NS", "knet", "NS", "", "2008-06-13T23:44:03.000Z", 11500, 0.03290,
       0.02096, 20.557, 0, 6e-6},
      {"AOM0170806140843.EW", "knet", "EW", "", "2008-06-13T23:44:03.000Z", 11500, 0.01955,
       0.01678, 16.452, 0, 6e-6},
      {"AOM0170806140843.UD", "knet", "UD", "", "2008-06-13T23:44:03.000Z", 11500, 0.01748,
       0.007059, 6.922, 1, 6e-6},
      {"NGNH351106302345.NS1", "kiknet", "NS1", "borehole", "2011-06-30T14:45:36.000Z", 12000,
       0.07547, 0.0002354, 0.231, 0, 6e-6},
      {"NGNH351106302345.EW2", "kiknet", "EW2", "surface", "2011-06-30T14:45:36.000Z", 12000,
       0.02770, 0.001315, 1.290, 0, 6e-6},
      {"AOM0081801241951.NS", "knet", "NS", "", "2018-01-24T10:51:21.000Z", 13800, 0.0394,
       0.0369, 36.185, 0, 6e-5},
  };
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
    char path[256];
    snprintf(path, sizeof path, REC_DIR "%s", f[i].file);
    aq_record r;
    aq_error e;
    aq_read_opts ro = {0};
    ro.accept_vertical = 1;
    if (!aq_check(aq_record_read(path, &ro, &r, &e) == AQ_OK, "%s: %s", f[i].file,
                  e.message))
      continue;
    aq_check(strcmp(r.format, f[i].format) == 0, "%s: format %s", f[i].file, r.format);
    aq_check(r.npts == f[i].npts, "%s: npts %zu", f[i].file, r.npts);
    aq_check(r.dt_s == 0.01, "%s: dt %.17g", f[i].file, r.dt_s);
    aq_check(strcmp(r.channel, f[i].channel) == 0 && strcmp(r.location, f[i].location) == 0,
             "%s: channel %s location %s", f[i].file, r.channel, r.location);
    aq_check(r.vertical == f[i].vertical, "%s: vertical %d", f[i].file, r.vertical);
    aq_check(strcmp(r.reference, f[i].reference) == 0, "%s: start %s", f[i].file,
             r.reference);
    aq_check(strcmp(r.units_stated, "counts") == 0, "%s: units %s", f[i].file,
             r.units_stated);
    double peak = 0, mean = 0;
    for (size_t k = 0; k < r.npts; k++) {
      peak = fmax(peak, fabs(r.acc_mps2[k]));
      mean += r.acc_mps2[k];
    }
    mean /= (double)r.npts;
    double dpeak = 0;
    for (size_t k = 0; k < r.npts; k++)
      dpeak = fmax(dpeak, fabs(r.acc_mps2[k] - mean));
    aq_check_abs(peak / G0_MPS2, f[i].pga_g, f[i].tol_g, "%s: PGA as stored (g)",
                 f[i].file);
    aq_check_abs(dpeak / G0_MPS2, f[i].demeaned_g,
                 f[i].demeaned_g < 0.001 ? 6e-8 : f[i].demeaned_g < 0.01 ? 6e-7 : f[i].tol_g,
                 "%s: demeaned PGA (g)", f[i].file);
    aq_check_abs(dpeak * 100.0, f[i].header_gal, HEADER_GAL_ABS,
                 "%s: demeaned peak = header Max. Acc. (gal)", f[i].file);
    if (f[i].vertical) {
      ro.accept_vertical = 0;
      aq_check(aq_record_check_horizontal(&r, &ro, &e) != AQ_OK && strstr(e.message, "UD"),
               "%s: the main job refuses it: %s", f[i].file, e.message);
    }
    aq_record_free(&r);
  }
}

/* Parse edited copies from memory; expect a one-line refusal naming the
 * field (and line). */
static void expect_refusal(const char *what, const char *text, size_t n, const char *need1,
                           const char *need2)
{
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  char msg[1400];
  aq_status s = aq_record_parse((const unsigned char *)text, n, what, NULL, &r, &e);
  aq_error_format(&e, msg, sizeof msg);
  aq_check(s != AQ_OK && !strchr(msg, '\n') && strstr(msg, what) && strstr(msg, need1) &&
               (!need2 || strstr(msg, need2)),
           "%s: %s", what, msg);
  if (s == AQ_OK)
    aq_record_free(&r);
}

AQ_TEST(io_knet_bad_input)
{
  size_t n = 0;
  char *src = aq_test_read_file(REC_DIR "AOM0170806140843.NS", &n);
  if (!aq_check(src && n > 2000, "read the file"))
    return;
  char *buf = malloc(n + 64);
  if (!buf) {
    free(src);
    return;
  }
  /* header cut after 11 lines */
  size_t cut = 0;
  for (int lines = 0; cut < n && lines < 11; cut++)
    lines += src[cut] == '\n';
  expect_refusal("head.NS", src, cut, "header truncated", "Duration Time(s)");
  /* data cut: the last 300 bytes gone */
  expect_refusal("data.NS", src, n - 300, "file truncated", "11500");
  /* scale factor with a zero denominator, and a word instead of it */
  static const char *const bad_scale[] = {"3920(gal)/0      ", "3920(cm)/6182761 ",
                                          "abc              "};
  char *sf = strstr(src, "3920(gal)/6182761");
  for (size_t k = 0; sf && k < 3; k++) {
    memcpy(buf, src, n);
    memcpy(buf + (sf - src), bad_scale[k], 17);
    expect_refusal("scale.NS", buf, n, "Scale Factor", ":14:");
  }
  /* a count that is not an integer */
  memcpy(buf, src, n);
  char *v = strstr(buf, "  -18473");
  if (v) {
    memcpy(v, "  -18.73", 8);
    expect_refusal("value.NS", buf, n, "expected an integer count", "-18.73");
  }
  /* Dir. unknown */
  memcpy(buf, src, n);
  char *d = strstr(buf, "N-S");
  if (d) {
    memcpy(d, "X-Y", 3);
    expect_refusal("dir.NS", buf, n, "Dir.", "X-Y");
  }
  free(buf);
  free(src);
}

/* The main job runs a K-NET horizontal and refuses its U-D channel. */
AQ_TEST(io_knet_cli)
{
  static char out[8192], err[4096];
  int st = aq_test_run("--arch arches/thick.cfg --scale 1 " REC_DIR "AOM0170806140843.NS " REC_DIR
                       "AOM0170806140843.UD",
                       out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(out, "AOM0170806140843.NS\tthick") &&
               strstr(err, "AOM0170806140843.UD: channel") && strstr(err, "\"UD\"") &&
               !strstr(err, ".NS:"),
           "exit %d: %s %s", st, out, err);
}
