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

/* One TSV row for the set of w of arch a. */
static void print_set(const aq_arch *a, const aq_workpath *w, int searched)
{
  const aq_path *p = aq_workpath_path(w);
  const aq_mech *m = aq_workpath_mech(w);
  char joints[64], faces[8];
  aq_hinge_set_format(&m->hs, joints, sizeof joints, faces, sizeof faces);
  size_t mj;
  double mu = aq_workpath_friction(w, NULL, &mj);
  char mjs[32] = "-";
  if (mj != SIZE_MAX)
    snprintf(mjs, sizeof mjs, "%zu", mj);
  /* with a friction: the largest load of a line of thrust in this set's direction */
  double lf = aq_arch_lambda_friction(a, p->act_sign, aq_arch_friction(a));
  printf("%s\t%s\t%s\t%s\t%s\t%d\t%+d\t%+d\t%s\t%s\t%s\t%zu\t%s\t%s\t%d\t%s\t%s\t%s\t%s"
         "\t%s\n",
         p->name, joints, faces, AQ_TEXT_NUM(p->lambda0), AQ_TEXT_NUM(p->s_c_rad),
         p->admissible, p->act_sign, p->q_sign, AQ_TEXT_NUM(p->mass_kg),
         AQ_TEXT_NUM(p->impact_vel_ratio), p->admissible ? end_name(aq_workpath_end(w)) : "-",
         aq_workpath_table_size(w), AQ_TEXT_NUM(aq_workpath_table_error(w)),
         AQ_TEXT_NUM(aq_workpath_thrust0(w)), searched,
         p->admissible ? "-" : aq_workpath_reason(w), aq_hinge_control_names[aq_arch_control(a)],
         AQ_TEXT_NUM(mu), mjs, AQ_TEXT_NUM(lf));
}

/* The `minimum` rows: the arch's minimum-lambda0 set of each direction of
 * ground acceleration (act_sign -1, then +1), whatever [hinges] names:
 * with free control the arch's own two sets, else the search's minimum
 * and the other direction's by the search.  0, or -1 (printed) when a
 * path cannot be built. */
static int print_minima(const char *file, const aq_arch *a, aq_error *err)
{
  aq_hinge_set mhs;
  if (!aq_arch_minimum(a, &mhs, NULL))
    return 0;
  const aq_geom *g = aq_arch_geom(a);
  double g_mps2 = aq_arch_path(a, 0)->g_mps2;
  int mact = aq_search_act_sign(g, &mhs);
  for (int k = 0; k < 2; k++) {
    int act = k ? 1 : -1;
    aq_hinge_set hs = mhs;
    if (aq_arch_control(a) == AQ_CONTROL_FREE) {
      hs = *aq_arch_hinge_set(a, k);
    } else if (act != mact) {
      aq_error e2;
      aq_error_clear(&e2);
      if (aq_search_direction(g, g_mps2, act, &hs, NULL, NULL, &e2) != AQ_OK) {
        fprintf(stderr, "archquake: %s: warning: no minimum four-hinge set for act_sign %+d: "
                        "%s\n", file, act, e2.message);
        continue;
      }
    }
    aq_workpath *mw = NULL, *swap = NULL;
    if (aq_workpath_build(g, &hs, g_mps2, "minimum", &mw, err) != AQ_OK) {
      aq_error_print(err, stderr);
      return -1;
    }
    /* its impact_vel_ratio: entered from the set the arch rocks on before
     * it, as the arch's own rows are (the arch's other set where the
     * minimum is one of the arch's sets, else its face swap, the reverse
     * rule of a fixed set) */
    const aq_workpath *from = NULL;
    for (int s = 0; s < 2 && !from; s++) {
      const aq_hinge_set *own = aq_arch_hinge_set(a, s);
      if (!memcmp(own->joint, hs.joint, sizeof hs.joint) &&
          !memcmp(own->face, hs.face, sizeof hs.face))
        from = aq_arch_workpath(a, 1 - s);
    }
    if (!from) {
      aq_hinge_set sw = hs;
      for (int k = 0; k < 4; k++)
        sw.face[k] = hs.face[k] == 'e' ? 'i' : 'e';
      if (aq_workpath_build(g, &sw, g_mps2, "minimum", &swap, err) != AQ_OK) {
        aq_error_print(err, stderr);
        aq_workpath_free(mw);
        return -1;
      }
      from = swap;
    }
    aq_workpath_set_impact(mw, from);
    aq_workpath_free(swap);
    print_set(a, mw, aq_arch_searched(a));
    /* a fixed set of this direction above its minimum: free joints fail sooner */
    const aq_path *mp = aq_workpath_path(mw);
    for (int s = 0; s < 2 && aq_arch_control(a) == AQ_CONTROL_FIXED; s++) {
      const aq_path *p = aq_arch_path(a, s);
      if (!p->admissible || p->act_sign != act ||
          !(mp->lambda0 < p->lambda0 - MIN_SET_TIE_REL * fabs(p->lambda0)))
        continue;
      char set[64], fixed[64];
      aq_hinge_set_text(&hs, set, sizeof set);
      aq_hinge_set_text(aq_arch_hinge_set(a, s), fixed, sizeof fixed);
      fprintf(stderr, "archquake: %s: warning: the %s set %s (act_sign %+d) has lambda0 = "
                      "%.6g, above that direction's minimum %s's %.6g: the verdicts hold for "
                      "hinges fixed where [hinges] puts them; with joints free to open "
                      "(control = free) that direction fails at the lower load\n",
              file, p->name, fixed, act, p->lambda0, set, mp->lambda0);
    }
    aq_workpath_free(mw);
  }
  return 0;
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
  const aq_statics *st = aq_arch_statics(a);
  for (int act = -1; st && act <= 1; act += 2)
    if (!aq_statics_resolved(st, act)) {
      fprintf(stderr, "archquake: %s: warning: the table of the least friction over the load "
                      "(mu_demand) did not reach its 1e-6 in %d nodes (act_sign %+d): its "
                      "kinks, where the line of thrust of least friction changes the joint "
                      "faces it touches, need more; mu_demand is interpolated less closely "
                      "there\n",
              path, aq_statics_nodes(st, act), act);
      break;
    }
  if (aq_arch_liftoff(a, &lj, &ll))
    fprintf(stderr, "archquake: %s: warning: a mechanism in which joint %zu lifts off has "
                    "lambda = %.6g, below every four-hinge set's (%.6g): the four-hinge "
                    "models do not describe it and overestimate this arch; --model blocks "
                    "follows it\n",
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
  aq_arch_options ao = {.friction = o.friction};
  if (aq_arch_load_opts(file, &ao, &a, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return AQ_EXIT_FAIL;
  }
  printf("set\tjoints\tfaces\tlambda0\tq_c_rad\tadmissible\tact_sign\tq_sign\tmass_kg\t"
         "impact_vel_ratio\tend\ttable_n\ttable_err\tthrust_ecc\tsearched\treason\t"
         "control\tmu_required\tmu_joint\tlambda_friction\n");
  for (int s = 0; s < 2; s++)
    print_set(a, aq_arch_workpath(a, s),
              aq_arch_searched(a) && (s == 0 || aq_arch_control(a) == AQ_CONTROL_FREE));
  /* the arch's own minimum-lambda0 sets: they govern unless its joints are
   * restrained, whatever [hinges] names */
  if (print_minima(file, a, &err) != 0) {
    aq_arch_free(a);
    return AQ_EXIT_FAIL;
  }
  aq_mechanism_warn_minimum(file, a);
  aq_opt_spread_four_hinge(file, 1, aq_arch_spread(a));
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
