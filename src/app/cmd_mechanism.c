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
#include "app.h"
#include "opt.h"
#include "opt_arch.h"

#define MIN_SET_TIE_REL 1e-9 /* relative: a lower lambda0 by less is the same mechanism */

static const char usage[] =
    "usage: archquake mechanism --arch FILE [--table] [--points N]\n"
    "The hinge sets of an arch: one TSV row per set: primary, reverse, and\n"
    "minimum, the admissible set of lowest lambda0 over every joint (the\n"
    "primary itself without [hinges]; with [hinges] a lower one is warned of\n"
    "on stderr: it governs unless its joints are restrained).  An arch whose\n"
    "minimum lambda0 is <= 0 cannot stand and is refused (exit 1), naming the set.\n"
    "  --arch FILE   the arch file (.cfg), or an installed arch by name\n"
    "  --table       add, after a blank line, the work path of each admissible\n"
    "                set at N points over [0, q_c] (the data of the paper's Figs 4-7)\n"
    "  --points N    rows per set in --table (2..100000, default 101)\n"
    "  --help        this text\n"
    "Columns: set joints faces lambda0 q_c_rad admissible act_sign q_sign mass_kg\n"
    "  impact_vel_ratio end table_n table_err thrust_ecc searched reason\n"
    "  q_c_rad is the rotation of body 1 about H1 at collapse (magnitude;\n"
    "  q = q_sign * s); act_sign is the sign of the ground acceleration along +x\n"
    "  that drives the set; end is why the path ends (peak: lambda = 0, toggle,\n"
    "  hinge: a hinge closes); table_err is the measured relative error of the\n"
    "  interpolation tables against the exact kinematics; thrust_ecc is the\n"
    "  largest eccentricity |r - R|/(t/2) of the line of thrust over the joints\n"
    "  at q = 0 (<= 1: the thrust stays inside, lambda0 is also a lower bound).\n"
    "Table columns: set s_rad q_rad lambda lambda_eq x_m y_m pe_j mgen_kgm2\n"
    "  min_normal_n (lambda by virtual work and by the 9x9 equilibrium; pe_j =\n"
    "  m_T g y; min_normal_n the smallest compressive hinge force; thrust_ecc\n"
    "  as above, in the deformed arch at lambda(q)).\n"
    "Exit status: 0 success, 1 the arch could not be built, 2 bad options.\n";

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
  printf("%s\t%s\t%s\t%.10g\t%.10g\t%d\t%+d\t%+d\t%.10g\t%.10g\t%s\t%zu\t%.3g\t%.6g\t%d\t%s\n",
         p->name, joints, faces, p->lambda0, p->s_c_rad, p->admissible, p->act_sign,
         p->q_sign, p->mass_kg, p->impact_vel_ratio,
         p->admissible ? end_name(aq_workpath_end(w)) : "-", aq_workpath_table_size(w),
         aq_workpath_table_error(w), aq_workpath_thrust0(w), searched,
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
  static const struct option longopts[] = {
      {"arch", required_argument, NULL, 'a'},
      {"table", no_argument, NULL, 't'},
      {"points", required_argument, NULL, 'p'},
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  const char *file = NULL;
  int table = 0, nerr = 0, c;
  long points = 101;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
    switch (c) {
    case 'a':
      file = aq_opt_arch(optarg, &nerr);
      break;
    case 't':
      table = 1;
      break;
    case 'p':
      aq_opt_long("--points", optarg, 2, 100000, &points, &nerr);
      break;
    case 'h':
      fputs(usage, stdout);
      return AQ_EXIT_OK;
    default:
      aq_opt_unknown("mechanism", argv, optind, optopt, &nerr);
    }
  }
  aq_opt_no_operands("mechanism", argc, argv, optind, &nerr);
  aq_opt_require("mechanism", "--arch FILE", file != NULL, &nerr);
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
        printf("%s\t%.10g\t%.10g\t%.10g\t%.10g\t%.10g\t%.10g\t%.10g\t%.10g\t%.6g\t%.6g\n",
               p->name, sv, p->q_sign * sv, pt.lambda, eq.lambda, pt.x_m, pt.y_m,
               p->mass_kg * p->g_mps2 * pt.y_m, pt.mgen_kgm2, nmin, thrust);
      }
    }
    free(ecc);
  }
  aq_arch_free(a);
  return rc;
}
