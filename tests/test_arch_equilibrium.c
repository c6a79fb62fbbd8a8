/* test_arch_equilibrium.c: the 9x9 balance (eq. (3)) against virtual work,
 * the KCLC published point-load case, and the impact rule against Housner's
 * rocking block. */
#include <gsl/gsl_errno.h>
#include <math.h>

#include "arch/model.h"
#include "check.h"
#include "units.h"

#define LAMBDA_REL_TOL 1e-12 /* 9x9 vs virtual work: round-off of an LU solve (measured 2.8e-14) */

static const char *const arch_files[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                         "arches/thick.cfg", "arches/segmental.cfg",
                                         "arches/search.cfg"};

AQ_TEST(arch_equilibrium_vs_virtual_work)
{
  gsl_set_error_handler_off();
  for (size_t f = 0; f < sizeof arch_files / sizeof arch_files[0]; f++) {
    aq_arch *a = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(arch_files[f], &a, &e) == AQ_OK, "load %s", arch_files[f]))
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_workpath *w = aq_arch_workpath(a, set);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      static const double at[] = {0.0, 0.0731, 0.3517, 0.6389, 0.9123};
      for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        double s = at[i] * p->s_c_rad;
        aq_equil eq;
        aq_path_point pt;
        aq_check(aq_workpath_equilibrium(w, s, &eq, &e) == AQ_OK, "solves");
        p->eval_exact(p->ctx, s, &pt);
        /* virtual work from the body velocities, independently of x, y */
        double wx = 0, wy = 0;
        for (int b = 0; b < 3; b++) {
          wx += pt.body[b].mass_kg * pt.body[b].dx_m;
          wy += pt.body[b].mass_kg * pt.body[b].dy_m;
        }
        double lvw = -p->act_sign * wy / wx;
        aq_check_rel(eq.lambda, lvw, LAMBDA_REL_TOL, "%s set %d s = %g: 9x9 vs virtual work",
                     arch_files[f], set, s);
        aq_check_rel(pt.lambda, lvw, 1e-14, "path lambda");
        if (i == 0 && set == 0) {
          /* the shipped primaries are upper-bound mechanisms: the line of
           * thrust at lambda0 stays inside the arch (lower bound = upper) */
          aq_mech_state st;
          aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, p->g_mps2};
          double ecc[64];
          int tension = 1;
          aq_mech_eval(aq_workpath_mech(w), 0.0, &st);
          double emax = aq_mech_thrust(aq_workpath_mech(w), &st, &live, &eq, ecc, &tension);
          aq_check(emax <= 1.0 && !tension, "%s: thrust inside (max |e| = %.6g)", arch_files[f], emax);
          aq_check_rel(emax, aq_workpath_thrust0(w), 1e-15, "thrust0");
        }
        if (i == 0)
          for (int k = 0; k < 4; k++)
            aq_check(eq.normal[k] > 0, "%s set %d hinge %d compressive", arch_files[f], set, k);
        /* global balance: the hinge forces at the ends carry all loads */
        double mt = 0;
        for (int b = 0; b < 3; b++)
          mt += pt.body[b].mass_kg;
        double gg = p->g_mps2;
        aq_check_rel(eq.h[0] - eq.h[3], p->act_sign * eq.lambda * mt * gg, 5e-13, "sum Fx");
        aq_check_rel(eq.v[0] - eq.v[3], mt * gg, 5e-15, "sum Fy");
      }
    }
    aq_arch_free(a);
  }
}

/* KCLC (Stockdale et al. 2018) case (docs/method.md sec. 10): 27 voussoirs,
 * intrados radius 1.806 m, t/R_i = 0.1661, depth 0.25 m, 1530 kg/m^3,
 * vertical point load at joint 8, hinges 3i 8e 20i 27e, g = 9.81: collapse
 * load 2.751 kN (KCLC), 2.756 kN (virtual powers).  The embrace and the
 * face the load acts on are not stated: this test CHOSE them (a semicircle,
 * the load at the extrados of joint 8) because that choice reproduces
 * 2.751 kN, so the case is fitted and checks consistency only.  The cases
 * with every parameter stated are the minimum thickness of a semicircle
 * (arch_standing_minimum_thickness_of_a_semicircle, test_arch_standing.c,
 * and arch_search_minimum_thickness_semicircle, test_arch_search.c). */
AQ_TEST(arch_kclc_point_load)
{
  gsl_set_error_handler_off();
  double ri = 1.806, t = 0.1661 * ri;
  aq_arch_params p = aq_arch_circular(ri + 0.5 * t, t, AQ_PI, 27, 1530.0, 0.25);
  aq_hinge_set hs = {{3, 8, 20, 27}, {'i', 'e', 'i', 'e'}};
  aq_arch_dynamics dyn = {0.0, AQ_IMPACT_COR, 9.81};
  aq_arch *a = NULL;
  aq_error e;
  if (!aq_check(aq_arch_build(&p, &hs, NULL, &dyn, "kclc", &a, &e) == AQ_OK, "builds"))
    return;
  const aq_workpath *w = aq_arch_workpath(a, 0);
  const aq_mech *m = aq_workpath_mech(w);
  const aq_path *path = aq_workpath_path(w);
  aq_vec2 load = aq_geom_joint_point(aq_arch_geom(a), 8, 'e');
  for (int b = 0; b < 2; b++) { /* joint 8 is H2: either body may carry it */
    aq_mech_state st;
    aq_equil eq;
    aq_mech_eval(m, 0.0, &st);
    aq_live live = {AQ_LIVE_POINT, 1, load, b, 9.81};
    aq_check(aq_mech_equilibrium(m, &st, &live, &eq, &e) == AQ_OK, "solves");
    aq_check_abs(eq.lambda / 1000.0, 2.751, 0.0005, "KCLC collapse load, kN (body %d)", b);
    for (int k = 0; k < 4; k++)
      aq_check(eq.normal[k] > 0, "hinge %d compressive", k + 1);
  }
  /* deformed: the point-load multiplier by virtual work, -g sum m dy / dP_y,
   * with the load point carried by body 2 (it sits on H2') */
  static const double at[] = {0.1, 0.5, 0.9};
  for (int i = 0; i < 3; i++) {
    double s = at[i] * path->s_c_rad, q = path->q_sign * s;
    aq_mech_state st;
    aq_equil eq;
    aq_check(aq_mech_eval(m, q, &st) == 0, "closes");
    aq_live live = {AQ_LIVE_POINT, 1, load, 1, 9.81};
    aq_check(aq_mech_equilibrium(m, &st, &live, &eq, &e) == AQ_OK, "solves");
    double wy = 0;
    for (int b = 0; b < 3; b++)
      wy += m->body[b].mass_kg * st.c[b][1].y;
    /* H2' = H1 + R(q)(H2 - H1): dH2'/dq = J (H2' - H1) */
    double dpy = st.h2.x - m->h[0].x;
    aq_check_rel(eq.lambda, -9.81 * wy / dpy, 5e-14 /* measured 1.3e-15 */, "deformed point load, s = %g", s);
  }
  aq_arch_free(a);
}

/* One rectangular block (width b, height h) rocking: the multi-body rule
 * -sum(m u_A.u_B + I w_A w_B)/M_B reduces to Housner's 1 - 1.5 sin^2(alpha),
 * tan(alpha) = b/h, whether the block is one part or cut into slices. */
AQ_TEST(arch_impact_rule_housner_block)
{
  static const double dims[][2] = {{0.4, 1.7}, {0.913, 2.385}, {1.0, 1.0}};
  for (size_t k = 0; k < 3; k++) {
    double b = dims[k][0], h = dims[k][1], rho = 2137.0;
    enum { NS = 7 };
    aq_mass parts[NS];
    aq_vec2 ua[NS], ub[NS];
    double wa[NS], wb[NS];
    aq_vec2 A = {0.5 * b, 0.0}, B = {-0.5 * b, 0.0}; /* the two corners */
    for (int i = 0; i < NS; i++) { /* horizontal slices */
      double hh = h / NS;
      parts[i].mass_kg = rho * b * hh;
      parts[i].c.x = 0.0;
      parts[i].c.y = hh * (i + 0.5);
      parts[i].inertia_kgm2 = parts[i].mass_kg * (b * b + hh * hh) / 12.0;
      /* A: rocking about the right corner, positive lifts the left side
       * (counter-clockwise); B: about the left corner, clockwise */
      ua[i].x = -(parts[i].c.y - A.y), ua[i].y = parts[i].c.x - A.x, wa[i] = 1.0;
      ub[i].x = (parts[i].c.y - B.y), ub[i].y = -(parts[i].c.x - B.x), wb[i] = -1.0;
    }
    double r = -aq_field_dot(parts, NS, ua, wa, ub, wb) / aq_field_dot(parts, NS, ub, wb, ub, wb);
    double alpha = atan(b / h), sa = sin(alpha);
    aq_check_rel(r, 1.0 - 1.5 * sa * sa, 2e-14, "Housner, block %g x %g", b, h);
  }
  /* the same set before and after: nothing changes (ratio -1 means the
   * velocity is unchanged in sign convention of the return) */
  aq_arch *a = NULL;
  aq_error e;
  if (!aq_check(aq_arch_load("arches/oppenheim.cfg", &a, &e) == AQ_OK, "load"))
    return;
  size_t n = aq_arch_geom(a)->p.voussoirs;
  aq_vec2 u[40];
  double w[40];
  const aq_workpath *wp = aq_arch_workpath(a, 0);
  aq_mech_field0(aq_workpath_mech(wp), aq_workpath_path(wp)->q_sign, u, w);
  aq_path_point z;
  aq_workpath_path(wp)->eval_exact(aq_workpath_path(wp)->ctx, 0.0, &z);
  aq_check_rel(aq_field_dot(aq_arch_geom(a)->vous, n, u, w, u, w), z.mgen_kgm2, 5e-15,
               "per-voussoir sum = M(0) (parallel axes)");
  /* impacts lose energy: KE ratio M_B r_B^2 / M_A < 1 both ways */
  const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
  aq_path_point z1;
  p1->eval_exact(p1->ctx, 0.0, &z1);
  double k01 = z.mgen_kgm2 * p0->impact_vel_ratio * p0->impact_vel_ratio / z1.mgen_kgm2;
  double k10 = z1.mgen_kgm2 * p1->impact_vel_ratio * p1->impact_vel_ratio / z.mgen_kgm2;
  aq_check(k01 > 0 && k01 < 1 && k10 > 0 && k10 < 1, "energy ratios %g %g in (0, 1)", k01, k10);
  aq_arch_free(a);
}
