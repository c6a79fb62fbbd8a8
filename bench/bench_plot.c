/* bench_plot.c: time to draw each figure in each format (median of REPS,
 * plinit to plend, the inputs already read) and the size of the file.
 * Capacity twice: 2 records x 2 polarities, and 6 records x 2 polarities
 * (the lines through every scanned scale, the strips, the fragility). */
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../src/arch/domain.h"
#include "../src/plot/plot.h"
#include "../src/report/h5.h"
#include "bench.h"

enum { REPS = 5 };

static long size_of(const char *path)
{
  struct stat st;
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

int main(void)
{
  char dir[] = "/tmp/aq-bench-plot-XXXXXX", cmd[1024], h5[256], out[256];
  if (!mkdtemp(dir))
    return 1;
  snprintf(h5, sizeof h5, "%s/h.h5", dir);
  snprintf(cmd, sizeof cmd,
           "./archquake tests/data/records/ARL360.at2 tests/data/records/IELC180.AT2 "
           "--arch arches/oppenheim.cfg --arch arches/thick.cfg --scale 5,10 --history "
           "--store-records "
           "-o %s >/dev/null",
           h5);
  if (system(cmd) != 0)
    return 1;
  aq_error err;
  aq_plot_run run;
  aq_arch *arch = NULL;
  aq_h5_suite S;
  if (aq_plot_run_read(h5, "00000_000_001", &run, &err) != AQ_OK ||
      aq_arch_load("arches/oppenheim.cfg", &arch, &err) != AQ_OK ||
      aq_h5_read_suite(h5, &S, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return 1;
  }
  static const double ratio[] = {1.02, 1.05, 1.1, 1.2, 1.35, 1.5, 1.75, 2, 2.5, 3, 4, 5};
  enum { NR = sizeof ratio / sizeof ratio[0] };
  double dur[NR], a;
  const aq_path *pp = aq_arch_path(arch, 0);
  aq_stepper *st = aq_stepper_alloc(pp, aq_arch_path(arch, 1), AQ_MODEL_WORKPATH, &err);
  double t0 = aq_bench_now_s();
  for (size_t i = 0; st && i < NR; i++)
    aq_domain_min_duration(st, pp, ratio[i], 1e-6, 100, &a, &dur[i], &err);
  double domain_s = aq_bench_now_s() - t0;
  aq_stepper_free(st);
  printf("plot: history of %zu samples (ground %zu), suite of %zu runs; "
         "domain computed in %.3f s (12 ratios, 1e-6 s), not in the times below\n",
         run.n, run.na, S.nruns, domain_s);
  printf("%-10s %-4s %12s %10s %14s\n", "figure", "fmt", "median_s", "bytes", "ratio_to_arch");
  enum { NFIG = 6 };
  static const char *const figs[NFIG] = {"history", "arch",      "domain",
                                         "suite",   "capacity4", "capacity12"};
  static const char *const cap_recs[2] = {
      "ARL360.at2 tests/data/records/IELC180.AT2",
      "ARL360.at2 tests/data/records/IELC180.AT2 tests/data/records/CHY028-N.AT2 "
      "tests/data/records/RSN1616_DUZCE_362-E.AT2 tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 "
      "tests/data/records/RSN4843_CHUETSU_65006NS.AT2"};
  aq_h5_capacity_table ct[2];
  char ch5[2][300];
  size_t npoint[2] = {0, 0};
  for (int c = 0; c < 2; c++) {
    int present = 0;
    snprintf(ch5[c], sizeof ch5[c], "%s/c%d.h5", dir, c);
    snprintf(cmd, sizeof cmd,
             "./archquake capacity tests/data/records/%s --arch arches/oppenheim.cfg -o %s "
             ">/dev/null", cap_recs[c], ch5[c]);
    if (system(cmd) != 0 || aq_h5_capacity_read(ch5[c], &ct[c], &present, &err) != AQ_OK)
      return 1;
    npoint[c] = ct[c].npoint;
  }
  printf("capacity4: %zu lines, %zu scanned points; capacity12: %zu lines, %zu points\n",
         ct[0].n, npoint[0], ct[1].n, npoint[1]);
  const aq_plot_capacity_opts co = {NULL, NULL, 0, 0};
  static const char *const fmts[] = {"png", "svg", "pdf"};
  for (size_t k = 0; k < 3; k++) {
    double med[NFIG];
    long bytes[NFIG];
    for (size_t f = 0; f < NFIG; f++) {
      double t[REPS];
      snprintf(out, sizeof out, "%s/%s.%s", dir, figs[f], fmts[k]);
      for (int r = 0; r < REPS; r++) {
        aq_status rc = f == 0   ? aq_plot_history(&run, out, NULL, &t[r], &err)
                       : f == 1 ? aq_plot_arch(arch, 0.15, out, NULL, &t[r], &err)
                       : f == 2 ? aq_plot_domain("oppenheim", pp->lambda0, ratio, dur, NR, 100,
                                                 out, NULL, &t[r], &err)
                       : f == 3 ? aq_plot_suite(S.runs, S.nruns, h5, out, NULL, &t[r], &err)
                                : aq_plot_capacity(&ct[f - 4], &co, ch5[f - 4], out, NULL,
                                                   &t[r], &err);
        if (rc != AQ_OK) {
          aq_error_print(&err, stderr);
          return 1;
        }
      }
      med[f] = aq_bench_median(t, REPS);
      bytes[f] = size_of(out);
      remove(out);
    }
    for (size_t f = 0; f < NFIG; f++)
      printf("%-10s %-4s %12.4f %10ld %14.2f\n", figs[f], fmts[k], med[f], bytes[f],
             med[f] / med[1]);
  }
  aq_plot_run_free(&run);
  aq_arch_free(arch);
  aq_h5_suite_free(&S);
  for (int c = 0; c < 2; c++) {
    aq_h5_capacity_table_free(&ct[c]);
    remove(ch5[c]);
  }
  remove(h5);
  rmdir(dir);
  return 0;
}
