/* bench_arch.c: building an arch (geometry, both work paths with their
 * tables and the Taylor leg's pieces) at 20 and 60 voussoirs, with given hinges and with the mechanism
 * search, and the cost of one path evaluation (tables vs exact). */
#include <stdio.h>

#include "arch/model.h"
#include "bench.h"
#include "units.h"

#define REPS 21

static double build_ms(size_t nv, int search, size_t *table_n, double *table_err,
                       size_t *piece_n)
{
  double t[REPS];
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
  /* the oppenheim mechanism scaled to nv voussoirs */
  aq_hinge_set hs = {{0, 6 * nv / 20, 12 * nv / 20, 19 * nv / 20}, {'e', 'i', 'e', 'i'}};
  for (int r = 0; r < REPS; r++) {
    aq_arch *a = NULL;
    aq_error e;
    double t0 = aq_bench_now_s();
    if (aq_arch_build(&p, search ? NULL : &hs, NULL, NULL, "bench", &a, &e) != AQ_OK) {
      fprintf(stderr, "bench_arch: %s\n", e.message);
      return -1;
    }
    t[r] = aq_bench_now_s() - t0;
    if (r == 0) {
      table_n[0] = aq_workpath_table_size(aq_arch_workpath(a, 0));
      table_n[1] = aq_workpath_table_size(aq_arch_workpath(a, 1));
      table_err[0] = aq_workpath_table_error(aq_arch_workpath(a, 0));
      table_err[1] = aq_workpath_table_error(aq_arch_workpath(a, 1));
      piece_n[0] = aq_workpath_piece_count(aq_arch_workpath(a, 0));
      piece_n[1] = aq_workpath_piece_count(aq_arch_workpath(a, 1));
    }
    aq_arch_free(a);
  }
  return 1e3 * aq_bench_median(t, REPS);
}

static double search_ms(size_t nv)
{
  double t[REPS];
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
  aq_geom g;
  aq_error e;
  if (aq_geom_init(&g, &p, &e) != AQ_OK)
    return -1;
  for (int r = 0; r < REPS; r++) {
    aq_hinge_set hs;
    double t0 = aq_bench_now_s();
    aq_search_minimum(&g, AQ_G0_MPS2, &hs, NULL, NULL, &e);
    t[r] = aq_bench_now_s() - t0;
  }
  aq_geom_free(&g);
  return 1e3 * aq_bench_median(t, REPS);
}

int main(void)
{
  printf("voussoirs\thinges\tbuild_ms\tsearch_ms\tsets\ttable_n_primary\ttable_n_reverse\t"
         "table_err_primary\ttable_err_reverse\tpieces_primary\tpieces_reverse\n");
  static const size_t nvs[] = {20, 60};
  for (int k = 0; k < 2; k++) {
    for (int search = 0; search < 2; search++) {
      size_t tn[2] = {0, 0}, pn[2] = {0, 0}, nsets = 16 * (nvs[k] + 1) * nvs[k] * (nvs[k] - 1) * (nvs[k] - 2) / 24;
      double te[2] = {0, 0};
      double b = build_ms(nvs[k], search, tn, te, pn);
      double s = search ? search_ms(nvs[k]) : 0;
      printf("%zu\t%s\t%.3f\t%.3f\t%zu\t%zu\t%zu\t%.2g\t%.2g\t%zu\t%zu\n", nvs[k],
             search ? "search" : "given", b, s, nsets, tn[0], tn[1], te[0], te[1],
             pn[0], pn[1]);
    }
  }
  /* one evaluation: tables vs exact, oppenheim primary */
  aq_arch *a = NULL;
  aq_error e;
  if (aq_arch_load("arches/oppenheim.cfg", &a, &e) != AQ_OK) {
    fprintf(stderr, "bench_arch: %s\n", e.message);
    return 1;
  }
  const aq_path *p = aq_arch_path(a, 0);
  enum { NE = 200000 };
  double te[REPS], tx[REPS], sink = 0;
  for (int r = 0; r < REPS; r++) {
    aq_path_point pt;
    double t0 = aq_bench_now_s();
    for (int i = 0; i < NE; i++) {
      p->eval(p->ctx, p->s_c_rad * (i % 997) / 997.0, &pt);
      sink += pt.x_m;
    }
    te[r] = (aq_bench_now_s() - t0) / NE;
    t0 = aq_bench_now_s();
    for (int i = 0; i < NE / 10; i++) {
      p->eval_exact(p->ctx, p->s_c_rad * (i % 997) / 997.0, &pt);
      sink += pt.x_m;
    }
    tx[r] = (aq_bench_now_s() - t0) / (NE / 10);
  }
  double me = aq_bench_median(te, REPS), mx = aq_bench_median(tx, REPS);
  printf("\neval\tns_per_call\tratio_to_table\n");
  printf("table\t%.1f\t1.00\nexact\t%.1f\t%.2f\n", 1e9 * me, 1e9 * mx, mx / me);
  aq_arch_free(a);
  return sink == 12345.678 ? 1 : 0;
}
