/* test_io_geonet.c: the GeoNet V1A/V2A reader against the values stated in
 * tests/data/records/PROVENANCE.md for 20161113_110259_WTMC_20.V2A (the
 * header peaks of the file itself, gmprocess's asserted trace maxima, the
 * independently computed PGA in g, npts, dt, azimuths and start), the
 * detection by content, the vertical refusal of the main job, and the
 * refusals of damaged files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "raw_fixture.h"

#define WTMC "tests/data/records/20161113_110259_WTMC_20.V2A"
#define G0_MPS2 9.80665     /* standard gravity (CGPM 1901), for the g columns */
#define MMPS2_TO_MPS2 0.001 /* literal */
#define CMPS2_TO_MMPS2 10.0 /* literal */
#define PROV_PGA_REL 5e-4   /* PROVENANCE prints PGA to 4 significant digits */
#define PEAK_ABS_MMPS2 0.05 /* header peaks and F8.1 values: 0.1 mm/s^2 steps */

AQ_TEST(io_geonet_wtmc_v2a)
{
  aq_raw_file r;
  if (!aq_test_raw_load(aq_geonet_parse, WTMC, &r))
    return;
  static const struct {
    const char *channel;
    double header_peak_mmps2, gmprocess_cmps2, pga_g, azimuth_deg;
    int vertical;
    double last2[2]; /* the 2 values of the series' last line (file text) */
  } w[3] = {
      {"N28W", -9733.1, -973.31, 0.9925, 332, 0, {1.6, 0.8}},
      {"S62W", 7966.4, 796.64, 0.8123, 242, 0, {NAN, NAN}},
      {"Up", 18021.9, 1802.19, 1.838, NAN, 1, {NAN, NAN}},
  };
  aq_check(r.nchan == 3, "3 components, got %zu", r.nchan);
  aq_check(strcmp(r.format, "geonet") == 0, "format %s", r.format);
  aq_check(strstr(r.event, "2016 November 13") && strstr(r.event, "11:02:56"), "event %s",
           r.event);
  aq_check(strstr(r.processing, "V2A") && strstr(r.processing, "Band-pass"), "processing %s",
           r.processing);
  for (size_t i = 0; i < r.nchan && i < 3; i++) {
    const aq_raw_channel *c = &r.chan[i];
    aq_check(strcmp(c->channel, w[i].channel) == 0, "channel %zu: %s", i, c->channel);
    aq_check(c->npts == 8192, "%s npts %zu", w[i].channel, c->npts);
    aq_check(c->dt_s == 0.02, "%s dt %.17g", w[i].channel, c->dt_s);
    aq_check(strcmp(c->units, "mm/s2") == 0, "%s units %s", w[i].channel, c->units);
    aq_check(strcmp(c->network, "NZ") == 0 && strcmp(c->station, "WTMC") == 0,
             "%s network %s station %s", w[i].channel, c->network, c->station);
    aq_check(strcmp(c->reference, "2016-11-13T11:02:19.715Z") == 0, "%s start %s",
             w[i].channel, c->reference);
    aq_check(c->vertical == w[i].vertical, "%s vertical %d", w[i].channel, c->vertical);
    if (w[i].vertical)
      aq_check(isnan(c->azimuth_deg) && c->dip_deg == -90, "%s azimuth %g dip %g",
               w[i].channel, c->azimuth_deg, c->dip_deg);
    else
      aq_check(c->azimuth_deg == w[i].azimuth_deg && c->dip_deg == 0, "%s azimuth %g dip %g",
               w[i].channel, c->azimuth_deg, c->dip_deg);
    /* the signed extreme sample against the header peak and gmprocess */
    size_t kmax = 0;
    for (size_t k = 0; k < c->npts; k++)
      if (fabs(c->values[k]) > fabs(c->values[kmax]))
        kmax = k;
    double pk = c->values[kmax];
    aq_check_abs(pk, w[i].header_peak_mmps2, PEAK_ABS_MMPS2, "%s header peak", w[i].channel);
    aq_check_abs(pk, w[i].gmprocess_cmps2 * CMPS2_TO_MMPS2, PEAK_ABS_MMPS2,
                 "%s gmprocess maximum", w[i].channel);
    aq_check_rel(fabs(pk) * MMPS2_TO_MPS2 / G0_MPS2, w[i].pga_g, PROV_PGA_REL, "%s PGA (g)",
                 w[i].channel);
    if (i == 0) /* PROVENANCE: the peak is index 2494 (49.88 s) */
      aq_check(kmax == 2494, "N28W peak at index %zu", kmax);
    if (!isnan(w[i].last2[0])) { /* the short last line is read, nothing past it */
      aq_check_abs(c->values[8190], w[i].last2[0], PEAK_ABS_MMPS2, "last line value 1");
      aq_check_abs(c->values[8191], w[i].last2[1], PEAK_ABS_MMPS2, "last line value 2");
    }
  }
  aq_raw_file_free(&r);
}

AQ_TEST(io_geonet_detect_and_decide)
{
  size_t n;
  char *buf = aq_test_read_file(WTMC, &n);
  if (!aq_check(buf != NULL, "read %s", WTMC))
    return;
  aq_check(aq_sniff_format((const unsigned char *)buf, n) == AQ_FMT_GEONET,
           "detected by content");
  /* the name does not matter: a .txt name still reads as GeoNet */
  aq_raw_file raw;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_raw_parse((const unsigned char *)buf, n, "renamed.txt", NULL, &raw, &e);
  aq_check(s == AQ_OK && raw.nchan == 3 && strcmp(raw.format, "geonet") == 0,
           "aq_raw_parse on renamed.txt: %s", e.message);
  if (s == AQ_OK) {
    aq_record rec;
    aq_read_opts ro = {0};
    if (aq_check(aq_record_decide(&raw, 0, "renamed.txt", &ro, &rec, &e) == AQ_OK, "%s",
                 e.message)) {
      double pk = 0;
      for (size_t k = 0; k < rec.npts; k++)
        pk = fmax(pk, fabs(rec.acc_mps2[k]));
      aq_check_rel(pk / G0_MPS2, 0.9925, PROV_PGA_REL, "N28W decided PGA (g)");
      aq_record_free(&rec);
    }
    if (aq_check(aq_record_decide(&raw, 2, "renamed.txt", &ro, &rec, &e) == AQ_OK, "%s",
                 e.message)) {
      aq_check(rec.vertical == 1, "Up decided vertical");
      aq_check(aq_record_check_horizontal(&rec, &ro, &e) == AQ_EUNSUPPORTED &&
                   strstr(e.message, "\"Up\"") && strstr(e.message, "--accept-vertical"),
               "Up refused: %s", e.message);
      aq_record_free(&rec);
    }
  }
  aq_raw_file_free(&raw);
  free(buf);
}

AQ_TEST(io_geonet_run_refuses_vertical)
{
  static char out[16384], err[4096];
  int st = aq_test_run("--arch arches/oppenheim.cfg " WTMC, out, sizeof out, err, sizeof err);
  /* the file given whole: its vertical left out with one note, exit 0 */
  aq_check(st == 0 && strstr(out, "WTMC_20.V2A#N28W\toppenheim") &&
               strstr(out, "WTMC_20.V2A#S62W\toppenheim") && !strstr(out, "#Up") &&
               strstr(err, "WTMC_20.V2A#Up: skipped") && aq_test_count_lines(err) == 1,
           "run: exit %d: %s %s", st, out, err);
  /* named: refused */
  st = aq_test_run("--arch arches/oppenheim.cfg " WTMC "#Up", out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "WTMC_20.V2A#Up: channel: expected a horizontal"),
           "Up named: exit %d: %s", st, err);
  st = aq_test_run("--arch arches/oppenheim.cfg --accept-vertical " WTMC "#Up", out,
                   sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "WTMC_20.V2A#Up\toppenheim"),
           "--accept-vertical runs Up: exit %d: %s", st, err);
}

/* The first component alone as V1A: "Uncorrected", npts in integer #31 (#34
 * made 0, #35/#36 left at 8192), one series (cut after the acceleration's
 * last line, 846). */
AQ_TEST(io_geonet_v1a)
{
  size_t n;
  char *buf = aq_test_read_file(WTMC, &n);
  if (!aq_check(buf != NULL, "read %s", WTMC))
    return;
  size_t cut = 0;
  for (int line = 0; cut < n && line < 846; cut++)
    line += buf[cut] == '\n';
  char *at = strstr(buf, "   65536     250     250    8192"); /* integers #31-#34 */
  if (aq_check(at != NULL && memcmp(buf, "Corrected", 9) == 0, "layout as expected")) {
    memcpy(at, "    8192     250     250       0", 32);
    size_t m = cut + 2;
    char *v1 = malloc(m + 1);
    memcpy(v1, "Un", 2);
    v1[2] = 'c';
    memcpy(v1 + 3, buf + 1, cut - 1);
    v1[m] = '\0';
    aq_raw_file r;
    char msg[1400];
    if (aq_check(aq_test_raw_parse_buf(aq_geonet_parse, v1, m, "x.V1A", &r, msg, sizeof msg) ==
                     AQ_OK,
                 "V1A: %s", msg)) {
      aq_check(r.nchan == 1 && r.chan[0].npts == 8192 && r.chan[0].dt_s == 0.02,
               "V1A one component of 8192 at 0.02 s");
      aq_check(strstr(r.processing, "V1A") != NULL, "processing %s", r.processing);
      aq_check_abs(aq_test_peak_abs(&r.chan[0]), 9733.1, PEAK_ABS_MMPS2, "V1A peak");
      aq_raw_file_free(&r);
    }
    free(v1);
  }
  free(buf);
}

AQ_TEST(io_geonet_bad_input)
{
  char msg[1400];
  /* truncated in the real header (byte 1330 is inside line 22) */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, 1330, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":22", "real header"),
           "truncated header: %s", msg);
  /* truncated in the text header */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, 300, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC, "expected 16 text lines"),
           "truncated text: %s", msg);
  /* truncated in the first acceleration series */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, 30000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               (aq_test_msg_names(msg, WTMC, "npts") ||
                aq_test_msg_names(msg, WTMC, "acceleration of component 1")),
           "truncated data: %s", msg);
  /* truncated in the last displacement series */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, 602000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC, "displacement of component 3"),
           "truncated displacement: %s", msg);
  /* dt (real #26, line 23): zero, and one that disagrees with text line 11 */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, (size_t)-1, "  0.0050  0.0200",
                               "  0.0050  0.0000", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":23", "real header #26 (dt)") &&
               strstr(msg, "expected a sample interval > 0 s, got 0"),
           "dt 0: %s", msg);
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, (size_t)-1, "  0.0050  0.0200",
                               "  0.0050  0.0050", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":23", "real header #26 (dt)") &&
               strstr(msg, "0.02 s"),
           "dt disagreeing with line 11: %s", msg);
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, (size_t)-1, "  0.0050  0.0200",
                               "  0.0050  0.02x0", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":23", "\"0.02x0\""),
           "dt not a number: %s", msg);
  /* a non-numeric value on data line 27 */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, (size_t)-1, "     0.2    -0.1",
                               "     0.2    -0.x", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":27", "\"-0.x\""),
           "bad value: %s", msg);
  /* the text line 10 npts disagreeing with integer #34 */
  aq_check(aq_test_raw_altered(aq_geonet_parse, WTMC, (size_t)-1, "Number of points  8192",
                               "Number of points  8191", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, WTMC ":10", "Number of points"),
           "npts disagreeing: %s", msg);
}

/* As a user sees it: archquake on a damaged copy says one line naming the
 * file, the line and the field, and exits 1. */
AQ_TEST(io_geonet_cli_damaged)
{
  size_t n;
  char *buf = aq_test_read_file(WTMC, &n);
  if (!aq_check(buf != NULL, "read %s", WTMC))
    return;
  char d[512], p[700], args[800];
  aq_test_tmpdir(d, sizeof d);
  snprintf(p, sizeof p, "%s/cut.V2A", d);
  FILE *f = fopen(p, "wb");
  if (aq_check(f != NULL, "write %s", p)) {
    fwrite(buf, 1, 1330, f); /* inside line 22, the real header */
    fclose(f);
    static char out[4096], err[4096];
    snprintf(args, sizeof args, "info %s", p);
    int st = aq_test_run(args, out, sizeof out, err, sizeof err);
    char *nl = strchr(err, '\n');
    aq_check(st == 1 && strstr(err, "cut.V2A:22: real header (10F8)") && nl && !nl[1],
             "info on a truncated file: exit %d: %s", st, err);
    snprintf(args, sizeof args, "--arch arches/oppenheim.cfg %s", p);
    st = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(st == 1 && strstr(err, "cut.V2A:22: real header (10F8)"),
             "run on a truncated file: exit %d: %s", st, err);
  }
  free(buf);
}
