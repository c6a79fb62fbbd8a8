/* test_dyn_paper.c: the paper-as-printed model against the exact ones: its
 * qualitative findings (sections 2.5, 4.1, 4.2) and the size of its error. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/paper.h"
#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "units.h"

/* Fig. 7 / eq. (14): with the torque terms the printed W_min to collapse
 * exceeds the potential energy m_T g y(s_c) (docs/method.md sec. 5: it should
 * equal it). */
AQ_TEST(dyn_paper_wmin_exceeds_pe)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  aq_error e;
  aq_paper *pp = aq_paper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), &e);
  aq_check(pp != NULL, "paper fits");
  for (int k = 0; pp && k < 2; k++) {
    const aq_path *p = aq_arch_path(a, k);
    aq_path_point pc;
    p->eval_exact(p->ctx, p->s_c_rad, &pc);
    double pe = p->mass_kg * p->g_mps2 * pc.y_m;
    double w = aq_paper_wmin(pp, k, p->s_c_rad);
    aq_check(w > pe * 1.001 && w < 2 * pe,
             "set %d: W_min(q_c) = %.6g J vs m g y(q_c) = %.6g J (+%.2f %%)", k,
             w, pe, 100 * (w / pe - 1));
  }
  aq_paper_free(pp);
  aq_arch_free(a);
}

/* Section 4.2 with the printed method: COR = 1, 0.55 g for 0.5 s, 20 s at
 * 0.02 s.  Its own energy KE + W_min changes only at the motion switches
 * (the paper: 0.4 % lost per cycle); the exact models keep it to round-off
 * (test_dyn_arch.c). */
AQ_TEST(dyn_paper_energy_loss_per_cycle)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  enum { N = 1025 };
  static double t[N], d[N], acc[N];
  for (size_t i = 0; i < N; i++) {
    t[i] = 0.02 * (double)i;
    d[i] = 0.02;
    acc[i] = i < 25 ? p->act_sign * 0.55 * AQ_G0_MPS2 : 0;
  }
  aq_error e;
  aq_steps s;
  aq_steps_from_list(t, d, acc, N, &s, &e);
  aq_stepper *st = aq_stepper_alloc(p, aq_arch_path(a, 1), AQ_MODEL_PAPER, &e);
  aq_paper *pp = aq_paper_alloc(p, aq_arch_path(a, 1), &e);
  aq_result r;
  if (st && pp) {
    aq_stepper_set_cor(st, 1.0);
    aq_stepper_set_history(st, 1);
    aq_check(aq_stepper_run(st, &s, &r, &e) == AQ_OK, "run");
    const aq_history *h = &r.history;
    double e0 = NAN, e1 = NAN;
    for (size_t i = 24; i < h->n; i++) {
      if (h->set[i] < 0)
        break;
      double ep = h->kinetic_energy_j[i] +
                  aq_paper_wmin(pp, h->set[i], fabs(h->rotation_rad[i]));
      if (i == 24)
        e0 = ep;
      e1 = ep;
    }
    double cycles = 0.5 * (double)r.impacts;
    double loss = (e0 - e1) / e0 / cycles;
    /* Stated expectation: the loss is bounded by the paper's order of
     * magnitude (0.4 %); how much is lost depends entirely on the pivot
     * rule, which the paper does not print.  With the pivot interpolated
     * from the samples it is far below that (docs/dynamics.md); with the
     * pivot at the last sample it would be several percent here. */
    aq_check(cycles >= 5 && fabs(loss) < 1e-2,
             "paper model: %.1f cycles, energy loss %.4f %% per cycle", cycles,
             100 * loss);
    aq_result_free(&r);
  }
  aq_paper_free(pp);
  aq_stepper_free(st);
  aq_steps_free(&s);
  aq_arch_free(a);
}

/* Section 4.1 with the printed method: its half-cycle domain is shifted
 * from the exact one (the torque terms raise the barrier, eq. 23 changes
 * the time scale); measured at each default ratio against the work path. */
AQ_TEST(dyn_paper_domain_shift)
{
  static char o1[4096], o2[4096], er[4096];
  int rc1 = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 1.2,1.5,2,3,4",
                        o1, sizeof o1, er, sizeof er);
  int rc2 = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 1.2,1.5,2,3,4 "
                        "--model paper",
                        o2, sizeof o2, er, sizeof er);
  aq_check(rc1 == 0 && rc2 == 0, "domain runs %d %d: %s", rc1, rc2, er);
  char *l1 = strchr(o1, '\n'), *l2 = strchr(o2, '\n');
  int rows = 0;
  while (l1 && l2) {
    double r1, a1, t1, r2, a2, t2;
    if (sscanf(l1 + 1, "%lf %lf %lf", &r1, &a1, &t1) != 3 ||
        sscanf(l2 + 1, "%lf %lf %lf", &r2, &a2, &t2) != 3)
      break;
    rows++;
    double rel = t2 / t1 - 1;
    aq_check(fabs(rel) > 1e-3 && fabs(rel) < 0.6,
             "r = %g: paper %.6g s vs exact %.6g s (%+.2f %%)", r1, t2, t1,
             100 * rel);
    l1 = strchr(l1 + 1, '\n');
    l2 = strchr(l2 + 1, '\n');
  }
  aq_check(rows == 5, "5 rows, got %d", rows);
}
