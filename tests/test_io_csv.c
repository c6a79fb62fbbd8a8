/* test_io_csv.c: the CSV/text reader: the JMA strong-motion CSV against the
 * per-component PGA in tests/data/records/PROVENANCE.md, and layouts written
 * here as text whose expected samples are the same text through strtod. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "units.h"

#define REC_DIR "tests/data/records/"
#define PROV_PGA_ABS_G 0.5e-4 /* PROVENANCE.md prints 4 decimals of g */
/* dt and the first time come from decimal text: binary rounding only */
#define TIME_REL 1e-15 /* measured 0 */
#define TIME_ABS_S 1e-14 /* a few ulps of the times (measured 0) */
/* a sample is strtod of the text times the units factor: one rounding */
#define SAMPLE_REL 1e-15

static double max_abs_g(const aq_record *r)
{
  double m = 0;
  for (size_t k = 0; k < r->npts; k++)
    m = fmax(m, fabs(r->acc_mps2[k]));
  return m / AQ_G0_MPS2;
}

AQ_TEST(io_csv_jma_three_components)
{
  /* PROVENANCE: NS 0.3334 g, EW 0.2864 g, UD 0.2252 g; 30000 at 0.01 s, gal */
  static const double pga[3] = {0.3334, 0.2864, 0.2252};
  static const char *const comp[3] = {"NS", "EW", "UD"};
  for (size_t way = 0; way < 3; way++)
    for (size_t i = 0; i < 3; i++) {
      aq_read_opts ro = {0};
      char path[256];
      snprintf(path, sizeof path, REC_DIR "Q4149CF2.csv");
      if (way == 0) /* --column N */
        ro.column = i + 1;
      else if (way == 1) /* FILE#CHANNEL */
        snprintf(path, sizeof path, REC_DIR "Q4149CF2.csv#%s", comp[i]);
      else { /* --component GLOB=CH */
        snprintf(ro.components[0].glob, sizeof ro.components[0].glob, "*Q4149*");
        snprintf(ro.components[0].channel, sizeof ro.components[0].channel, "%s", comp[i]);
        ro.ncomponents = 1;
      }
      aq_record r;
      aq_error e;
      if (!aq_check(aq_record_read(path, &ro, &r, &e) == AQ_OK, "way %zu %s: %s", way,
                    comp[i], e.message))
        continue;
      aq_check(r.npts == 30000, "npts %zu", r.npts);
      aq_check(r.dt_s == 0.01, "dt from SAMPLING RATE= 100Hz: %.17g", r.dt_s);
      aq_check(strcmp(r.units_orig, "gal") == 0, "units %s", r.units_orig);
      aq_check(strcmp(r.channel, comp[i]) == 0, "channel %s", r.channel);
      aq_check(r.vertical == (i == 2), "%s vertical %d", comp[i], r.vertical);
      aq_check_abs(max_abs_g(&r), pga[i], PROV_PGA_ABS_G, "%s PGA (g)", comp[i]);
      /* "INITIAL TIME = 2016 04 14 21 26 20" is JST (UTC+9): the foreshock
         of 2016-04-14 21:26 JST = 12:26 UTC (PROVENANCE) */
      aq_check(strcmp(r.reference, "2016-04-14T12:26:20.000Z") == 0 && r.begin_s == 0,
               "%s start %s + %g s", comp[i], r.reference, r.begin_s);
      aq_record_free(&r);
    }
  /* no channel named: refused, naming the three, never the first silently */
  aq_record r;
  aq_error e;
  aq_check(aq_record_read(REC_DIR "Q4149CF2.csv", NULL, &r, &e) != AQ_OK &&
               strstr(e.message, "NS, EW, UD") && strstr(e.message, "#"),
           "three channels, none chosen: %s", e.message);
}

/* Parse text; check npts, dt, begin, units and that sample k equals
 * strtod(vals[k]) * factor. */
static void check_text(const char *what, const char *text, const aq_read_opts *ro,
                       const char *const *vals, size_t nv, double dt, double begin,
                       double factor, const char *units)
{
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  char msg[1400];
  aq_status s = aq_record_parse((const unsigned char *)text, strlen(text), what, ro, &r, &e);
  aq_error_format(&e, msg, sizeof msg);
  if (!aq_check(s == AQ_OK, "%s: %s", what, msg))
    return;
  aq_check(r.npts == nv, "%s: npts %zu, want %zu", what, r.npts, nv);
  aq_check_rel(r.dt_s, dt, TIME_REL, "%s: dt", what);
  aq_check_abs(r.begin_s, begin, TIME_ABS_S, "%s: begin", what);
  aq_check(strcmp(r.units_orig, units) == 0, "%s: units %s, want %s", what, r.units_orig,
           units);
  for (size_t k = 0; k < nv && k < r.npts; k++)
    aq_check_rel(r.acc_mps2[k], strtod(vals[k], NULL) * factor, SAMPLE_REL, "%s: sample %zu",
                 what, k);
  aq_record_free(&r);
}

AQ_TEST(io_csv_layouts)
{
  static const char *const v[5] = {"0.02385", "-0.0771905", "1.0937E-01", "-3.14159e-4",
                                   "0.2718281"};
  static const char *const vc[5] = {"0.02385", "-0.0771905", "1.0937E-01", "-3.14159e-4",
                                    "0.2718281"};
  aq_read_opts none = {0}, dt = {0}, gal = {0};
  dt.dt_s = 0.004;
  dt.units = AQ_UNITS_GAL;
  gal.units = AQ_UNITS_GAL;
  check_text("comma-g", "time,acc (g)\n0,0.02385\n0.02,-0.0771905\n0.04,1.0937E-01\n"
                        "0.06,-3.14159e-4\n0.08,0.2718281\n",
             &none, v, 5, 0.02, 0, AQ_G0_MPS2, "g");
  check_text("utf8-bom", "\xEF\xBB\xBFtime,acc (g)\n0,0.02385\n0.02,-0.0771905\n"
                        "0.04,1.0937E-01\n0.06,-3.14159e-4\n0.08,0.2718281\n",
             &none, v, 5, 0.02, 0, AQ_G0_MPS2, "g");
  check_text("t-acc_g-crlf-comments",
             "# exported\r\nt,acc_g\r\n# start\r\n12.5,0.02385\r\n12.505,-0.0771905\r\n\r\n"
             "12.51,1.0937E-01 # peak\r\n12.515,-3.14159e-4\r\n12.52,0.2718281\r\n",
             &none, v, 5, 0.005, 12.5, AQ_G0_MPS2, "g");
  check_text("tab-mps2", "time\ta [m/s2]\n0.0\t0.02385\n0.01\t-0.0771905\n0.02\t1.0937E-01\n"
                         "0.03\t-3.14159e-4\n0.04\t0.2718281\n",
             &none, v, 5, 0.01, 0, 1.0, "m/s2");
  check_text("blanks-cms2", "  t    acc(cm/s^2)\n  0.0   0.02385\n  0.01  -0.0771905\n"
                            "  0.02  1.0937E-01\n  0.03  -3.14159e-4\n  0.04  0.2718281\n",
             &none, v, 5, 0.01, 0, 0.01, "gal");
  check_text("blanks-split-units", "time   acc (g)\n0.0 0.02385\n0.01 -0.0771905\n"
                                   "0.02 1.0937E-01\n0.03 -3.14159e-4\n0.04 0.2718281\n",
             &none, v, 5, 0.01, 0, AQ_G0_MPS2, "g");
  check_text("semicolon-decimal-comma",
             "zeit;acc (g)\n0,00;0,02385\n0,01;-0,0771905\n0,02;1,0937E-01\n"
             "0,03;-3,14159e-4\n0,04;0,2718281\n",
             &none, vc, 5, 0.01, 0, AQ_G0_MPS2, "g");
  check_text("single-column-dt-override",
             "0.02385\n-0.0771905\n1.0937E-01\n-3.14159e-4\n0.2718281", &dt, v, 5, 0.004, 0,
             0.01, "gal");
  check_text("preamble-rate-unit",
             "STATION X\n SAMPLING RATE= 200Hz\n UNIT = gal(cm/s/s)\n NS\n0.02385\n"
             "-0.0771905\n1.0937E-01\n-3.14159e-4\n0.2718281\n",
             &none, v, 5, 0.005, 0, 0.01, "gal");
  /* a plain --units does not override units the header states */
  check_text("units-stated-win", "time,acc (g)\n0,0.02385\n0.02,-0.0771905\n0.04,1.0937E-01\n"
                               "0.06,-3.14159e-4\n0.08,0.2718281\n",
             &gal, v, 5, 0.02, 0, 9.80665, "g");
  /* a GLOB rule for this name */
  aq_read_opts rule = {0};
  snprintf(rule.rules[0].glob, sizeof rule.rules[0].glob, "*layout*");
  rule.rules[0].units = AQ_UNITS_MPS2;
  rule.nrules = 1;
  rule.units = AQ_UNITS_GAL;
  check_text("glob-layout", "time,acc (g)\n0,0.02385\n0.02,-0.0771905\n0.04,1.0937E-01\n"
                            "0.06,-3.14159e-4\n0.08,0.2718281\n",
             &rule, v, 5, 0.02, 0, 1.0, "m/s2");
}

AQ_TEST(io_units_rules_last_match_wins)
{
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_G;
  const char *globs[3] = {"*.SAC", "records/*", "*/CI.*"};
  aq_units us[3] = {AQ_UNITS_COUNTS, AQ_UNITS_GAL, AQ_UNITS_NMPS2};
  for (int i = 0; i < 3; i++) {
    snprintf(ro.rules[i].glob, sizeof ro.rules[i].glob, "%s", globs[i]);
    ro.rules[i].units = us[i];
  }
  ro.nrules = 3;
  aq_check(aq_read_opts_units_for(&ro, "records/CI.CLC.SAC") == AQ_UNITS_NMPS2, "3 match");
  aq_check(aq_read_opts_units_for(&ro, "records/x.SAC") == AQ_UNITS_GAL, "2 match");
  aq_check(aq_read_opts_units_for(&ro, "other/x.SAC") == AQ_UNITS_COUNTS, "* spans /");
  aq_check(aq_read_opts_units_for(&ro, "x.AT2") == AQ_UNITS_G, "plain --units");
  aq_check(aq_read_opts_units_for(NULL, "x.AT2") == AQ_UNITS_FILE, "no options");
  aq_units u;
  aq_check(aq_units_parse("cm/s2", &u) && u == AQ_UNITS_GAL, "cm/s2 is gal");
  aq_check(aq_units_parse("M/S**2", &u) && u == AQ_UNITS_MPS2, "M/S**2");
  aq_check(!aq_units_parse("cm/s", &u), "cm/s is not acceleration");
  aq_check(aq_units_to_mps2(AQ_UNITS_G) == AQ_G0_MPS2 && aq_units_to_mps2(AQ_UNITS_GAL) == 0.01,
           "factors");
}

/* Every component of a multi-component file is a record of its own in the
 * main job and in info, named FILE#CHANNEL; --component or FILE#CHANNEL
 * chooses one.  PGA per PROVENANCE: NS 0.3334 g, EW 0.2864 g. */
AQ_TEST(io_csv_multicomponent_cli)
{
  static char out[16384], err[4096];
  int st = aq_test_run("info " REC_DIR "Q4149CF2.csv", out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "Q4149CF2.csv#NS\tcsv\t30000") &&
               strstr(out, "Q4149CF2.csv#EW\tcsv\t30000") &&
               strstr(out, "Q4149CF2.csv#UD\tcsv\t30000") && strstr(out, "\tUD\tyes"),
           "info: three records: exit %d: %s %s", st, out, err);
  st = aq_test_run("--arch arches/thick.cfg --scale 1 --accept-vertical " REC_DIR
                   "Q4149CF2.csv", out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "Q4149CF2.csv#NS\tthick\tworkpath\t1\t0.333") &&
               strstr(out, "Q4149CF2.csv#EW\tthick\tworkpath\t1\t0.286") &&
               strstr(out, "Q4149CF2.csv#UD\t"),
           "run: three rows: exit %d: %s %s", st, out, err);
  st = aq_test_run("--arch arches/thick.cfg --scale 1 --component '*Q4149*=EW' " REC_DIR
                   "Q4149CF2.csv", out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "Q4149CF2.csv#EW\tthick\tworkpath\t1\t0.286") &&
               !strstr(out, "#NS") && !strstr(out, "#UD"),
           "run --component EW: one row: exit %d: %s %s", st, out, err);
  st = aq_test_run("--arch arches/thick.cfg --scale 1 " REC_DIR "Q4149CF2.csv#NS", out,
                   sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "Q4149CF2.csv#NS\tthick") && !strstr(out, "#EW"),
           "run FILE#NS: one row: exit %d: %s %s", st, out, err);
  st = aq_test_run("info " REC_DIR "Q4149CF2.csv#XY", out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "NS, EW, UD") && strstr(err, "\"XY\""),
           "unknown channel named: exit %d: %s", st, err);
}

/* CWB text: '#' header lines state the units (#AmplitudeUnit: gal.) and
 * name the columns (#DataSequence: Time U(+); N(+); E(+)); three records,
 * U vertical.  PROVENANCE: 6000 at 0.02 s; PGA U 0.001220, N 0.002989,
 * E 0.002866 g (header AmplitudeMAX 1.196, -2.931, -2.811 gal). */
/* Start times written here: a zone behind UTC rolls the day forward, one
 * ahead rolls it back across a year, a time that does not parse is unknown
 * (""), never a guess. */
AQ_TEST(io_csv_start_times)
{
  static const struct {
    const char *head, *want;
  } c[] = {
      {"#StartTime(GMT-05): 2020/12/31-22:15:01.250\n", "2021-01-01T03:15:01.250Z"},
      {"#StartTime(GMT+08): 2021/01/01-03:00:00.000\n", "2020-12-31T19:00:00.000Z"},
      {"INITIAL TIME = 2011 03 11 14 46 18\n", "2011-03-11T05:46:18.000Z"},
      {"INITIAL TIME = 2011 13 11 14 46 18\n", ""},
      {"INITIAL TIME = 2011 03 11 14 46\n", ""},
      {"#StartTime(GMT+08): 2018/02/06 23:50:29\n", ""}};
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    char text[256];
    snprintf(text, sizeof text, "%sSAMPLING RATE= 100Hz\nUNIT = gal\nNS\n1.5\n-2.5\n0.5\n",
             c[i].head);
    aq_raw_file raw;
    aq_error e;
    if (!aq_check(aq_raw_parse((const unsigned char *)text, strlen(text), "t.csv", NULL, &raw,
                               &e) == AQ_OK,
                  "%zu: %s", i, e.message))
      continue;
    aq_check(raw.nchan == 1 && strcmp(raw.chan[0].reference, c[i].want) == 0,
             "%zu: start \"%s\", expected \"%s\"", i, raw.chan[0].reference, c[i].want);
    aq_raw_file_free(&raw);
  }
}

AQ_TEST(io_csv_cwb_three_components)
{
  static const char *const comp[3] = {"U", "N", "E"};
  static const double peak_gal[3] = {1.196, 2.931, 2.811};
  for (size_t i = 0; i < 3; i++) {
    char path[256];
    snprintf(path, sizeof path, REC_DIR "2-ECU.dat#%s", comp[i]);
    aq_record r;
    aq_error e;
    if (!aq_check(aq_record_read(path, NULL, &r, &e) == AQ_OK, "%s: %s", comp[i], e.message))
      continue;
    aq_check(r.npts == 6000 && r.dt_s == 0.02, "%s: npts %zu dt %.17g", comp[i], r.npts,
             r.dt_s);
    aq_check(strcmp(r.units_stated, "gal") == 0, "%s: units %s", comp[i], r.units_stated);
    aq_check(r.vertical == (i == 0), "%s: vertical %d", comp[i], r.vertical);
    double m = 0;
    for (size_t k = 0; k < r.npts; k++)
      m = fmax(m, fabs(r.acc_mps2[k]));
    aq_check_abs(m * 100.0, peak_gal[i], 1e-9, "%s: peak (gal, 3 decimals in the file)",
                 comp[i]);
    /* "#StartTime(GMT+08): 2018/02/06-23:50:29.000": 8 h ahead of UTC, 13 s
       before the origin at 15:50:42 UTC (PROVENANCE) */
    aq_check(strcmp(r.reference, "2018-02-06T15:50:29.000Z") == 0 && r.begin_s == 0,
             "%s: start %s + %g s", comp[i], r.reference, r.begin_s);
    aq_record_free(&r);
  }
}
