/* test_signal_errors.c: bad processing input gives one clear error naming
 * the record and the option; bad options on the command line exit 2. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "signal/signal.h"

/* Process a 10 s record at 100 Hz with one option changed; check the status
 * and that the formatted one-line message names the record, the field and
 * the words expected. */
static void expect_error(const aq_signal_opts *o, size_t n, double dt,
                         const char *field, const char *words)
{
  aq_record r;
  memset(&r, 0, sizeof r);
  r.path = "quake/short-7.at2";
  r.npts = n;
  r.dt_s = dt;
  r.acc_mps2 = calloc(n ? n : 1, sizeof(double));
  for (size_t i = 0; i < n; i++)
    r.acc_mps2[i] = 0.37 * sin(0.71 * (double)i);
  aq_processed p;
  aq_error e;
  aq_error_clear(&e);
  aq_status st = aq_signal_process(&r, o, NULL, &p, &e);
  char line[1200];
  aq_error_format(&e, line, sizeof line);
  aq_check(st == AQ_EVALUE && strstr(line, "quake/short-7.at2: ") == line &&
               strstr(line, field) && strstr(line, words) &&
               !strchr(line, '\n') && p.acc_mps2 == NULL && p.n == 0,
           "%s: status %d, message \"%s\"", field, (int)st, line);
  aq_processed_free(&p);
  free(r.acc_mps2);
}

AQ_TEST(signal_errors_bad_input)
{
  aq_signal_opts o;
  aq_signal_opts_default(&o);
  o.highpass_hz = 0.05; /* as --highpass 0.05 sets it: needs 20 s */
  o.highpass_auto = 0;
  expect_error(&o, 1000, 0.01, "--highpass", "at least 20 s");
  o.highpass_hz = 50; /* Nyquist of dt = 0.01 s */
  expect_error(&o, 1000, 0.01, "--highpass", "Nyquist frequency 50 Hz");
  o.highpass_hz = 73.1;
  expect_error(&o, 1000, 0.01, "--highpass", "got 73.1 Hz");
  aq_signal_opts_default(&o);
  o.highpass_hz = 0.5;
  o.taper_frac = -0.01;
  expect_error(&o, 1000, 0.01, "--taper", "[0, 0.5]");
  o.taper_frac = 0.51;
  expect_error(&o, 1000, 0.01, "--taper", "got 0.51");
  o.taper_frac = 0.05;
  o.order = 0;
  expect_error(&o, 1000, 0.01, "--order", "got 0");
  o.order = 4;
  o.lowpass_hz = 0.3;
  expect_error(&o, 1000, 0.01, "--lowpass", "above the high-pass corner");
  o.lowpass_hz = 50;
  expect_error(&o, 1000, 0.01, "--lowpass", "Nyquist");
  o.lowpass_hz = 0;
  expect_error(&o, 0, 0.01, "npts", "at least 1 sample");
  expect_error(&o, 1000, 0, "dt", "> 0 s");
  /* --no-filter: no filter, so no record length or Nyquist limits */
  aq_signal_opts_default(&o);
  o.filter = 0;
  o.detrend = AQ_DETREND_MEAN;
  o.highpass_hz = 400;
  aq_record r;
  memset(&r, 0, sizeof r);
  r.path = "x";
  r.npts = 3;
  r.dt_s = 0.01;
  double a[3] = {1.5, -0.25, 2.0};
  r.acc_mps2 = a;
  aq_processed p;
  aq_error e;
  aq_check(aq_signal_process(&r, &o, NULL, &p, &e) == AQ_OK && p.n == 3 &&
               fabs(p.acc_mps2[0] - (1.5 - 3.25 / 3)) < 1e-15,
           "--no-filter on 3 samples: mean removed only");
  aq_processed_free(&p);
  a[1] = NAN;
  aq_check(aq_signal_process(&r, &o, NULL, &p, &e) == AQ_EVALUE &&
               strstr(e.message, "sample 1"),
           "NaN sample refused: %s", e.message);
}

AQ_TEST(signal_errors_cli_options)
{
  char out[4096], err[4096];
  int st = aq_test_run("info --taper -0.1 --order 0 --detrend cubic "
                       "--highpass 0 --lowpass x --merge-tol -1 nofile.at2",
                       out, sizeof out, err, sizeof err);
  aq_check(st == 2, "bad options exit 2, got %d", st);
  static const char *const want[] = {"--taper", "--order", "--detrend",
                                     "--highpass", "--lowpass", "--merge-tol"};
  int lines = 0;
  for (const char *c = err; *c; c++)
    lines += *c == '\n';
  aq_check(lines == 6, "one line per bad option: %d lines\n%s", lines, err);
  for (size_t i = 0; i < 6; i++)
    aq_check(strstr(err, want[i]) != NULL, "names %s: %s", want[i], err);
  st = aq_test_run("info --highpass 0.5 --lowpass 0.2 nofile.at2", out,
                   sizeof out, err, sizeof err);
  aq_check(st == 2 && strstr(err, "--lowpass") && strstr(err, "above"),
           "lowpass below highpass: %d %s", st, err);
  st = aq_test_run("info --help", out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "--no-filter") && strstr(out, "cav_m_s"),
           "help lists the processing options and columns");
}

AQ_TEST(signal_errors_cli_per_record)
{
  char out[4096], err[4096];
  /* 0.01 s sampling: Nyquist 50 Hz; the other record still gets its row */
  int st = aq_test_run("info --highpass 60 tests/data/records/IELC180.AT2",
                       out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "archquake: tests/data/records/IELC180.AT2: "
                                  "--highpass: expected") &&
               strstr(err, "Nyquist"),
           "corner above Nyquist: exit %d, %s", st, err);
  st = aq_test_run("info --highpass 0.02 tests/data/records/IELC180.AT2 "
                   "tests/data/records/TCU052-N.AT2",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "IELC180.AT2: --highpass") &&
               strstr(err, "at least 50 s") && strstr(out, "TCU052-N.AT2") &&
               !strstr(out, "IELC180"),
           "short record refused, the other processed: exit %d, %s", st, err);
  /* the raw Ridgecrest vertical carries +1 g: as read it drifts away */
  st = aq_test_run("info --units '*CJ.T001230*=g' --no-filter --detrend none "
                   "tests/data/records/20190706031952.CJ.T001230.HNZ.sac",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(err, "HNZ.sac: warning: residual velocity") &&
               strchr(out, '\n') != strrchr(out, '\n'),
           "residuals warned, not failed: exit %d, %s", st, err);
  st = aq_test_run("info --units '*CJ.T001230*=g' "
                   "tests/data/records/20190706031952.CJ.T001230.HNZ.sac",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 0 && !strstr(err, "residual"), "processed: no warning: %s", err);
}
