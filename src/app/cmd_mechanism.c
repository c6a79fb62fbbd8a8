/* cmd_mechanism.c: `archquake mechanism --arch FILE [--table] [--points N]`:
 * the hinge sets of an arch, their collapse multipliers and work paths. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/arch.h"
#include "../arch/model.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"

#define MIN_SET_TIE_REL 1e-9 /* relative: a lower lambda0 by less is the same mechanism */

static const char *end_name(aq_end e)
{
  switch (e) {
  case AQ_END_PEAK:
    return "peak";
  case AQ_END_TOGGLE:
    return "toggle";
  case AQ_END_HINGE:
    return "hinge";
  default:
    return "none";
  }
}

/* One TSV row for the set of w. */
static void print_set(const aq_workpath *w, int searched)
{
  const aq_path *p = aq_workpath_path(w);
  const aq_mech *m = aq_workpath_mech(w);
  char joints[64], faces[8];
  aq_hinge_set_format(&m->hs, joints, sizeof joints, faces, sizeof faces);
  printf("%s\t%s\t%s\t%s\t%s\t%d\t%+d\t%+d\t%s\t%s\t%s\t%zu\t%s\t%s\t%d\t%s\n", p->name, joints,
         faces, AQ_TEXT_NUM(p->lambda0), AQ_TEXT_NUM(p->s_c_rad), p->admissible, p->act_sign,
         p->q_sign, AQ_TEXT_NUM(p->mass_kg), AQ_TEXT_NUM(p->impact_vel_ratio),
         p->admissible ? end_name(aq_workpath_end(w)) : "-", aq_workpath_table_size(w),
         AQ_TEXT_NUM(aq_workpath_table_error(w)), AQ_TEXT_NUM(aq_workpath_thrust0(w)), searched,
         p->admissible ? "-" : aq_workpath_reason(w));
}

void aq_mechanism_warn_minimum(const char *path, const aq_arch *a)
{
  aq_hinge_set mhs;
  double ml0, l0 = aq_arch_path(a, 0)->lambda0;
  if (!aq_arch_minimum(a, &mhs, &ml0)) {
    fprintf(stderr, "archquake: %s: warning: the search found no admissible hinge set: "
                    "that the arch stands is not checked\n", path);
    return;
  }
  size_t lj;
  double ll;
  if (aq_arch_liftoff(a, &lj, &ll))
    fprintf(stderr, "archquake: %s: warning: a mechanism in which joint %zu lifts off has "
                    "lambda = %.6g, below every four-hinge set's (%.6g): archquake models "
                    "four-hinge mechanisms only, so it overestimates this arch\n",
            path, lj, ll, ml0);
  if (aq_arch_searched(a) || !(ml0 < l0 - MIN_SET_TIE_REL * fabs(l0)))
    return;
  char set[64], prim[64];
  aq_hinge_set_text(&mhs, set, sizeof set);
  aq_hinge_set_text(&aq_workpath_mech(aq_arch_workpath(a, 0))->hs, prim, sizeof prim);
  fprintf(stderr, "archquake: %s: warning: the admissible hinge set %s has lambda0 = "
                  "%.6g, below the primary %s's %.6g: that mechanism governs unless "
                  "its joints are restrained\n", path, set, ml0, prim, l0);
}

int aq_cmd_mechanism(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_MECHANISM);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_MECHANISM, argc, argv, &o, &nerr))
    return AQ_EXIT_OK; /* --help */
  const char *file = o.arch;
  long points = o.points;
  int table = o.table;
  aq_opt_no_operands("mechanism", argc, argv, optind, &nerr);
  if (nerr)
    return AQ_EXIT_USAGE;

  aq_arch *a = NULL;
  aq_error err;
  aq_error_clear(&err);
  if (aq_arch_load(file, &a, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return AQ_EXIT_FAIL;
  }
  printf("set\tjoints\tfaces\tlambda0\tq_c_rad\tadmissible\tact_sign\tq_sign\tmass_kg\t"
         "impact_vel_ratio\tend\ttable_n\ttable_err\tthrust_ecc\tsearched\treason\n");
  for (int s = 0; s < 2; s++)
    print_set(aq_arch_workpath(a, s), s == 0 && aq_arch_searched(a));
  /* the arch's own minimum-lambda0 set: it governs unless its joints are
   * restrained, whatever [hinges] names */
  aq_hinge_set mhs;
  double ml0;
  if (aq_arch_minimum(a, &mhs, &ml0)) {
    aq_workpath *mw = NULL;
    if (aq_workpath_build(aq_arch_geom(a), &mhs, aq_arch_path(a, 0)->g_mps2, "minimum",
                          &mw, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      aq_arch_free(a);
      return AQ_EXIT_FAIL;
    }
    print_set(mw, aq_arch_searched(a));
    aq_workpath_free(mw);
  }
  aq_mechanism_warn_minimum(file, a);
  int rc = AQ_EXIT_OK;
  if (table) {
    printf("\nset\ts_rad\tq_rad\tlambda\tlambda_eq\tx_m\ty_m\tpe_j\tmgen_kgm2\tmin_normal_n"
           "\tthrust_ecc\n");
    double *ecc = malloc((aq_arch_geom(a)->p.voussoirs + 1) * sizeof *ecc);
    if (!ecc) {
      fprintf(stderr, "archquake: mechanism: out of memory\n");
      aq_arch_free(a);
      return AQ_EXIT_FAIL;
    }
    for (int s = 0; s < 2 && rc == AQ_EXIT_OK; s++) {
      const aq_workpath *w = aq_arch_workpath(a, s);
      const aq_path *p = aq_arch_path(a, s);
      if (!p->admissible)
        continue;
      for (long i = 0; i < points; i++) {
        double sv = p->s_c_rad * (double)i / (double)(points - 1);
        aq_path_point pt;
        aq_equil eq;
        if (p->eval_exact(p->ctx, sv, &pt) != 0 ||
            aq_workpath_equilibrium(w, sv, &eq, &err) != AQ_OK) {
          aq_error_set(&err, AQ_ENUMERIC, file, -1, -1, p->name,
                       "expected a closed linkage at s = %.10g rad, got none", sv);
          aq_error_print(&err, stderr);
          rc = AQ_EXIT_FAIL;
          break;
        }
        double nmin = eq.normal[0];
        for (int k = 1; k < 4; k++)
          nmin = eq.normal[k] < nmin ? eq.normal[k] : nmin;
        aq_mech_state st;
        aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, p->g_mps2};
        double thrust = aq_mech_eval(aq_workpath_mech(w), p->q_sign * sv, &st) == 0
                            ? aq_mech_thrust(aq_workpath_mech(w), &st, &live, &eq, ecc, NULL)
                            : NAN;
        printf("%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", p->name, AQ_TEXT_NUM(sv),
               AQ_TEXT_NUM(p->q_sign * sv), AQ_TEXT_NUM(pt.lambda), AQ_TEXT_NUM(eq.lambda),
               AQ_TEXT_NUM(pt.x_m), AQ_TEXT_NUM(pt.y_m),
               AQ_TEXT_NUM(p->mass_kg * p->g_mps2 * pt.y_m), AQ_TEXT_NUM(pt.mgen_kgm2),
               AQ_TEXT_NUM(nmin), AQ_TEXT_NUM(thrust));
      }
    }
    free(ecc);
  }
  aq_arch_free(a);
  return rc;
}
