/* bench_orient.c: the cost of an azimuth scan against the runs it makes.
 * One ground motion (RSN6 ELC180 + ELC270) at 72 azimuths (--azimuth all)
 * against the same number of runs of one component (ELC180 at 72 scale
 * factors, its steps made once per factor), both against
 * arches/oppenheim.cfg at -j 1, measured alternately in one process
 * (medians of REPS suites each, after one untimed suite of each).  The scan
 * reads and processes two components once and projects the step list of
 * each run; the ratio of the medians is its overhead. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/opt_orient.h"
#include "app/suite.h"
#include "bench.h"

#define REPS 9
#define NRUNS 72

int main(void)
{
  gsl_set_error_handler_off();
  char *arch[1] = {"arches/oppenheim.cfg"};
  char *plain[1] = {"tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"};
  FILE *text = fopen("/dev/null", "w");
  if (!text)
    return 1;
  aq_orient_opts o;
  aq_opt_orient_init(&o);
  int nerr = 0;
  aq_opt_components("tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2,"
                    "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
                    &o, &nerr);
  aq_opt_azimuth("all", &o, &nerr);
  aq_opt_orient_check(&o, &nerr);
  if (nerr || o.nazimuth != NRUNS)
    return 1;
  static const double one[1] = {1.5};
  double scales[NRUNS];
  for (int i = 0; i < NRUNS; i++)
    scales[i] = 1.5 + 1e-4 * i;
  const aq_orient_motion *mo[1] = {&o.motions[0]};

  aq_suite_cfg c[2];
  for (int k = 0; k < 2; k++) {
    memset(&c[k], 0, sizeof c[k]);
    aq_signal_opts_default(&c[k].proc);
    c[k].arch_paths = arch;
    c[k].narches = 1;
    c[k].nrecords = 1;
    c[k].scale_to_pga_g = NAN;
    c[k].model = AQ_MODEL_WORKPATH;
    c[k].cor = NAN;
    c[k].text = text;
    c[k].threads = 1;
    c[k].command_line = "bench_orient";
  }
  c[0].records = &o.motions[0].label;
  c[0].motions = mo;
  c[0].azimuths_deg = o.azimuths_deg;
  c[0].nazimuth = o.nazimuth;
  c[0].scales = one;
  c[0].nscale = 1;
  c[1].records = plain;
  c[1].scales = scales;
  c[1].nscale = NRUNS;
  double wall[2][REPS];
  for (int rep = -1; rep < REPS; rep++)
    for (int k = 0; k < 2; k++) {
      aq_suite_stats st;
      double t0 = aq_bench_now_s();
      if (aq_suite_run(&c[k], &st) != 0 || st.runs != NRUNS) {
        fprintf(stderr, "bench_orient: suite failed\n");
        return 1;
      }
      if (rep >= 0)
        wall[k][rep] = aq_bench_now_s() - t0;
    }
  double m0 = aq_bench_median(wall[0], REPS), m1 = aq_bench_median(wall[1], REPS);
  printf("%d runs against arches/oppenheim.cfg, -j 1, medians of %d:\n", NRUNS, REPS);
  printf("  ELC180+ELC270 at 72 azimuths (scale 1.5)   %8.1f ms  (%.2f ms/run)\n",
         1e3 * m0, 1e3 * m0 / NRUNS);
  printf("  ELC180 at 72 scale factors (1.5..1.507)    %8.1f ms  (%.2f ms/run)\n",
         1e3 * m1, 1e3 * m1 / NRUNS);
  printf("  ratio scan / runs                          %8.2f\n", m0 / m1);
  aq_opt_orient_free(&o);
  fclose(text);
  return 0;
}
