/* test_arch_kinematics.c: the four-bar against finite differences, its
 * closure along the whole path, the hinge-opening rule against the deformed
 * corners, the tables against the exact path, and the potential energy
 * summed voussoir by voussoir. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch_fixture.h"
#include "check.h"
#include "units.h"

#define FD_STEP_RAD 1e-5      /* central differences */
#define FD_REL_TOL 5e-9       /* O(h^2) truncation + round-off/h, relative to scale */
#define CLOSURE_TOL_REL 1e-14 /* closure residual relative to the radius */
#define TABLE_TOL_REL 1e-10   /* tables against exact, relative to the scale */

static const char *const arch_files[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                         "arches/thick.cfg", "arches/segmental.cfg",
                                         "arches/search.cfg"};
enum { NFILES = sizeof arch_files / sizeof arch_files[0] };

AQ_TEST(arch_kinematics_derivatives_vs_fd)
{
  gsl_set_error_handler_off();
  for (size_t f = 0; f < NFILES; f++) {
    aq_arch *a = aq_test_arch_load(arch_files[f]);
    if (!a)
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_workpath *w = aq_arch_workpath(a, set);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      const aq_mech *m = aq_workpath_mech(w);
      for (int k = 1; k <= 4; k++) {
        double q = p->q_sign * p->s_c_rad * (0.2 * k - 0.0137);
        aq_mech_state s0, sp, sm;
        aq_check(aq_mech_eval(m, q, &s0) == 0 && aq_mech_eval(m, q + FD_STEP_RAD, &sp) == 0 &&
                     aq_mech_eval(m, q - FD_STEP_RAD, &sm) == 0,
                 "%s set %d closes at q = %g", arch_files[f], set, q);
        for (int b = 0; b < 3; b++)
          for (int d = 0; d < 3; d++) {
            double scale_phi = 1.0 + fabs(s0.phi[b][d + 1]);
            double fd = (sp.phi[b][d] - sm.phi[b][d]) / (2 * FD_STEP_RAD);
            aq_check_abs(s0.phi[b][d + 1], fd, FD_REL_TOL * scale_phi * 10,
                         "%s set %d body %d phi deriv %d", arch_files[f], set, b, d + 1);
            double sc = 1.0 + hypot(s0.c[b][d + 1].x, s0.c[b][d + 1].y);
            double fdx = (sp.c[b][d].x - sm.c[b][d].x) / (2 * FD_STEP_RAD);
            double fdy = (sp.c[b][d].y - sm.c[b][d].y) / (2 * FD_STEP_RAD);
            aq_check_abs(s0.c[b][d + 1].x, fdx, FD_REL_TOL * sc * 10,
                         "%s set %d body %d cx deriv %d", arch_files[f], set, b, d + 1);
            aq_check_abs(s0.c[b][d + 1].y, fdy, FD_REL_TOL * sc * 10,
                         "%s set %d body %d cy deriv %d", arch_files[f], set, b, d + 1);
          }
      }
      /* the path's own derivatives in s */
      double s = 0.537 * p->s_c_rad;
      aq_path_point c, up, dn;
      aq_check(p->eval_exact(p->ctx, s, &c) == 0 &&
                   p->eval_exact(p->ctx, s + FD_STEP_RAD, &up) == 0 &&
                   p->eval_exact(p->ctx, s - FD_STEP_RAD, &dn) == 0,
               "path evaluates");
      double h2 = 2 * FD_STEP_RAD;
      aq_check_rel(c.dx_m, (up.x_m - dn.x_m) / h2, FD_REL_TOL, "dx/ds");
      aq_check_rel(c.dy_m, (up.y_m - dn.y_m) / h2, FD_REL_TOL, "dy/ds");
      aq_check_rel(c.d2x_m, (up.dx_m - dn.dx_m) / h2, FD_REL_TOL * 10, "d2x/ds2");
      aq_check_rel(c.d2y_m, (up.dy_m - dn.dy_m) / h2, FD_REL_TOL * 10, "d2y/ds2");
      aq_check_rel(c.dmgen_kgm2, (up.mgen_kgm2 - dn.mgen_kgm2) / h2, FD_REL_TOL * 10, "dM/ds");
      for (int b = 0; b < 3; b++) {
        aq_check_rel(c.body[b].dphi, (up.body[b].phi_rad - dn.body[b].phi_rad) / h2,
                     FD_REL_TOL, "body %d dphi/ds", b);
        aq_check_abs(c.body[b].dx_m, (up.body[b].x_m - dn.body[b].x_m) / h2,
                     FD_REL_TOL * 10, "body %d dx/ds", b);
        aq_check_abs(c.body[b].dy_m, (up.body[b].y_m - dn.body[b].y_m) / h2,
                     FD_REL_TOL * 10, "body %d dy/ds", b);
      }
      /* M from its definition with the body data */
      double mg = 0;
      for (int b = 0; b < 3; b++)
        mg += c.body[b].mass_kg * (c.body[b].dx_m * c.body[b].dx_m + c.body[b].dy_m * c.body[b].dy_m) +
              c.body[b].inertia_kgm2 * c.body[b].dphi * c.body[b].dphi;
      aq_check_rel(c.mgen_kgm2, mg, 1e-15, "M(s) = sum m|dc/ds|^2 + I dphi^2");
      aq_check_rel(c.lambda, -p->act_sign * c.dy_m / c.dx_m, 1e-15, "lambda by virtual work");
    }
    aq_arch_free(a);
  }
}

AQ_TEST(arch_kinematics_closure_along_path)
{
  for (size_t f = 0; f < NFILES; f++) {
    aq_arch *a = aq_test_arch_load(arch_files[f]);
    if (!a)
      continue;
    double r = aq_arch_geom(a)->p.radius_m;
    for (int set = 0; set < 2; set++) {
      const aq_workpath *w = aq_arch_workpath(a, set);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      double worst = 0, prev_phi2 = 0;
      int jumps = 0;
      for (int i = 0; i <= 1000; i++) {
        aq_mech_state st;
        double q = p->q_sign * p->s_c_rad * i / 1000.0;
        if (!aq_check(aq_mech_eval(aq_workpath_mech(w), q, &st) == 0, "closes at %g", q))
          break;
        double res = aq_mech_closure_residual(aq_workpath_mech(w), &st);
        worst = res > worst ? res : worst;
        if (i > 0 && fabs(st.phi[1][0] - prev_phi2) > 10 * fabs(st.phi[1][1]) * p->s_c_rad / 1000.0 + 1e-12)
          jumps++;
        prev_phi2 = st.phi[1][0];
      }
      aq_check(worst <= CLOSURE_TOL_REL * r, "%s set %d closure residual %.3g m",
               arch_files[f], set, worst);
      aq_check(jumps == 0, "%s set %d stays on one branch", arch_files[f], set);
    }
    aq_arch_free(a);
  }
}

/* Rotate point p0 of body b to the deformed state given by the path point. */
static aq_vec2 carry(const aq_path_point *pt, const aq_mass *body0, int b, aq_vec2 p0)
{
  double ph = pt->body[b].phi_rad, c = cos(ph), s = sin(ph);
  double dx = p0.x - body0[b].c.x, dy = p0.y - body0[b].c.y;
  aq_vec2 v = {pt->body[b].x_m + c * dx - s * dy, pt->body[b].y_m + s * dx + c * dy};
  return v;
}

/* At each hinge the corner on the other face of the joint must separate:
 * the counter-clockwise block's corner moves, relative to the clockwise
 * block's, into the counter-clockwise tangential direction (out of the
 * other block).  This checks the opening rule of kinematics.c from the
 * deformed geometry itself. */
AQ_TEST(arch_kinematics_hinges_open)
{
  for (size_t f = 0; f < NFILES; f++) {
    aq_arch *a = aq_test_arch_load(arch_files[f]);
    if (!a)
      continue;
    const aq_geom *g = aq_arch_geom(a);
    for (int set = 0; set < 2; set++) {
      const aq_workpath *w = aq_arch_workpath(a, set);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      const aq_mech *m = aq_workpath_mech(w);
      for (int i = 1; i <= 5; i++) {
        aq_path_point pt;
        double s = p->s_c_rad * (0.2 * i - 0.01);
        p->eval_exact(p->ctx, s, &pt);
        for (int k = 0; k < 4; k++) {
          size_t j = m->hs.joint[k];
          aq_vec2 corner = aq_geom_joint_point(g, j, m->hs.face[k] == 'e' ? 'i' : 'e');
          aq_vec2 cw = k > 0 ? carry(&pt, m->body, k - 1, corner) : corner;
          aq_vec2 ccw = k < 3 ? carry(&pt, m->body, k, corner) : corner;
          double th = g->theta_rad[j];
          double sep = (ccw.x - cw.x) * -sin(th) + (ccw.y - cw.y) * cos(th);
          aq_check(sep > 0, "%s set %d hinge %d opens at s = %g (separation %.3g m)",
                   arch_files[f], set, k + 1, s, sep);
        }
      }
    }
    aq_arch_free(a);
  }
  /* a non-alternating set on oppenheim is refused: hinge 2 cannot open */
  aq_arch_params pp = aq_arch_circular(5.0, 1.25, AQ_PI, 20, 2000.0, 1.0);
  aq_hinge_set bad = {{0, 6, 12, 19}, {'e', 'e', 'i', 'i'}};
  aq_arch *a = NULL;
  aq_error e;
  aq_check(aq_arch_build(&pp, &bad, NULL, NULL, "bad", &a, &e) == AQ_EINADMISSIBLE,
           "eeii is not a mechanism");
  aq_arch_free(a);
}

AQ_TEST(arch_tables_vs_exact)
{
  unsigned seed = 12345u;
  for (size_t f = 0; f < NFILES; f++) {
    aq_arch *a = aq_test_arch_load(arch_files[f]);
    if (!a)
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(a, set);
      if (!p->admissible)
        continue;
      /* scales: the largest magnitude of each quantity along the path */
      double sc[8] = {0}, err[8] = {0};
      aq_path_point E[401], T;
      for (int i = 0; i <= 400; i++) {
        p->eval_exact(p->ctx, p->s_c_rad * i / 400.0, &E[i]);
        double v[8] = {E[i].x_m, E[i].y_m, E[i].dx_m, E[i].dy_m, E[i].d2x_m, E[i].d2y_m,
                       E[i].mgen_kgm2, E[i].dmgen_kgm2};
        for (int k = 0; k < 8; k++)
          sc[k] = fabs(v[k]) > sc[k] ? fabs(v[k]) : sc[k];
      }
      for (int i = 0; i < 2000; i++) {
        seed = seed * 1103515245u + 12345u;
        double s = p->s_c_rad * (double)(seed >> 8) / 16777216.0;
        aq_path_point X;
        p->eval_exact(p->ctx, s, &X);
        p->eval(p->ctx, s, &T);
        double d[8] = {T.x_m - X.x_m, T.y_m - X.y_m, T.dx_m - X.dx_m, T.dy_m - X.dy_m,
                       T.d2x_m - X.d2x_m, T.d2y_m - X.d2y_m, T.mgen_kgm2 - X.mgen_kgm2,
                       T.dmgen_kgm2 - X.dmgen_kgm2};
        for (int k = 0; k < 8; k++)
          err[k] = fabs(d[k]) / sc[k] > err[k] ? fabs(d[k]) / sc[k] : err[k];
      }
      for (int k = 0; k < 8; k++)
        aq_check(err[k] <= TABLE_TOL_REL, "%s set %d quantity %d table error %.3g",
                 arch_files[f], set, k, err[k]);
      aq_check(aq_workpath_table_error(aq_arch_workpath(a, set)) <= TABLE_TOL_REL,
               "measured table error");
      /* ends */
      aq_path_point z;
      aq_check(p->eval(p->ctx, 0.0, &z) == 0 && z.x_m == 0 && z.y_m == 0, "s = 0: undeformed");
      aq_check_rel(z.lambda, p->lambda0, 1e-15, "lambda(0) = lambda0");
      aq_check(p->eval(p->ctx, p->s_c_rad, &z) == 0, "s_c evaluates");
      aq_check(p->eval(p->ctx, -1e-3, &z) != 0 && p->eval(p->ctx, 1.01 * p->s_c_rad, &z) != 0 &&
                   p->eval_exact(p->ctx, 1.01 * p->s_c_rad, &z) != 0,
               "outside [0, s_c] refused");
    }
    aq_arch_free(a);
  }
}

/* Collapse: at s_c dy/ds = 0 (lambda = 0) for an end at the peak, with
 * dy/ds > 0 before; y is the potential energy's maximum. */
AQ_TEST(arch_collapse_at_peak)
{
  for (size_t f = 0; f < NFILES; f++) {
    aq_arch *a = aq_test_arch_load(arch_files[f]);
    if (!a)
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_workpath *w = aq_arch_workpath(a, set);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      aq_check(aq_workpath_end(w) == AQ_END_PEAK, "%s ends at the peak", arch_files[f]);
      aq_path_point e, b;
      p->eval_exact(p->ctx, p->s_c_rad, &e);
      p->eval_exact(p->ctx, 0.999 * p->s_c_rad, &b);
      aq_check_abs(e.dy_m, 0.0, 1e-13 * fabs(b.dy_m) * 1000, "dy/ds = 0 at s_c");
      aq_check(b.dy_m > 0 && e.y_m > b.y_m, "rising before s_c");
      aq_check(e.lambda < 1e-10 * p->lambda0, "lambda(s_c) = 0");
    }
    aq_arch_free(a);
  }
}

/* The potential energy summed voussoir by voussoir (each voussoir carried by
 * its body's rigid motion, fixed voussoirs not moving) equals m_T g y(s). */
AQ_TEST(arch_potential_energy_by_voussoir)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_geom *g = aq_arch_geom(a);
  const double gg = aq_arch_dynamics_of(a)->g_mps2;
  for (int set = 0; set < 2; set++) {
    const aq_workpath *w = aq_arch_workpath(a, set);
    const aq_path *p = aq_workpath_path(w);
    const aq_mech *m = aq_workpath_mech(w);
    for (int i = 1; i <= 3; i++) {
      aq_path_point pt;
      p->eval_exact(p->ctx, p->s_c_rad * 0.31 * i, &pt);
      double pe = 0;
      for (int b = 0; b < 3; b++)
        for (size_t v = m->hs.joint[b]; v < m->hs.joint[b + 1]; v++) {
          aq_vec2 c1 = carry(&pt, m->body, b, g->vous[v].c);
          pe += g->vous[v].mass_kg * gg * (c1.y - g->vous[v].c.y);
        }
      aq_check_rel(pe, p->mass_kg * gg * pt.y_m, 5e-14, "set %d PE at step %d", set, i);
    }
  }
  aq_arch_free(a);
}

/* The near-toggle set below on its semicircle (R 5 m, t 1.25 m, 20
 * voussoirs): g and hs set up, its path built into *w; 0 (g freed) if it
 * does not build. */
static const aq_hinge_set near_toggle_hs = {{0, 4, 5, 18}, {'i', 'e', 'i', 'e'}};

static int near_toggle(aq_geom *g, aq_workpath **w)
{
  aq_arch_params pp = aq_arch_circular(5.0, 1.25, AQ_PI, 20, 2000.0, 1.0);
  aq_error e;
  aq_geom_init(g, &pp, &e);
  *w = NULL;
  if (!aq_check(aq_workpath_build(g, &near_toggle_hs, 9.80665, "x", w, &e) == AQ_OK,
                "builds")) {
    aq_geom_free(g);
    return 0;
  }
  return 1;
}

/* A four-bar near its toggle at s = 0 (two hinges on neighbouring joints):
 * M(0) is ~2e4 times M(s_c) and varies like 1/sqrt(s + delta); the adaptive
 * tables must still follow the exact path, including close to s = 0. */
AQ_TEST(arch_tables_near_toggle)
{
  aq_geom g;
  aq_workpath *w;
  if (!near_toggle(&g, &w))
    return;
  const aq_path *p = aq_workpath_path(w);
  aq_check(p->admissible, "admissible: %s", aq_workpath_reason(w));
  aq_path_point a, b;
  p->eval_exact(p->ctx, 0.0, &a);
  p->eval_exact(p->ctx, p->s_c_rad, &b);
  aq_check(a.mgen_kgm2 > 1e3 * b.mgen_kgm2, "M(0) %g >> M(s_c) %g", a.mgen_kgm2, b.mgen_kgm2);
  double xs = fabs(b.x_m), ys = fabs(b.y_m), worst_m = 0, worst_xy = 0, worst_d = 0;
  for (int i = 0; i <= 4000; i++) {
    double u = i / 4000.0, s = p->s_c_rad * u * u * u * u; /* crowd near 0 */
    aq_path_point x, t;
    p->eval_exact(p->ctx, s, &x);
    p->eval(p->ctx, s, &t);
    double em = fabs(t.mgen_kgm2 - x.mgen_kgm2) / x.mgen_kgm2;
    double exy = fmax(fabs(t.x_m - x.x_m) / xs, fabs(t.y_m - x.y_m) / ys);
    double ed = fmax(fabs(t.dx_m - x.dx_m) / fabs(x.dx_m), fabs(t.dmgen_kgm2 - x.dmgen_kgm2) /
                                                               (fabs(x.dmgen_kgm2) + x.mgen_kgm2 / p->s_c_rad));
    worst_m = fmax(worst_m, em);
    worst_xy = fmax(worst_xy, exy);
    worst_d = fmax(worst_d, ed);
  }
  aq_check(worst_m <= 1e-10, "M relative error %.3g", worst_m);
  aq_check(worst_xy <= 1e-12, "x, y error %.3g", worst_xy);
  aq_check(worst_d <= 1e-8, "dx/ds, dM/ds error %.3g", worst_d);
  aq_workpath_free(w);
  aq_geom_free(&g);
}

/* A path whose tables would need more intervals than allowed is refused in
 * one line that says what ran out and where, not a guess at the cause.
 * The near-toggle set above (M varies like 1/sqrt(s + delta) near s = 0),
 * built with an allowance of one interval less than its Hermite tables
 * take (its Taylor pieces take fewer): the refusal names the tables, their
 * tolerance (4e-12) and the allowance, and its finest interval lies where
 * the path varies fastest, within the first hundredth of [0, q_c]; with
 * the allowance of what it takes the path builds as without one. */
AQ_TEST(arch_tables_too_many_intervals_named)
{
  aq_geom g;
  aq_workpath *w;
  if (!near_toggle(&g, &w))
    return;
  const aq_hinge_set hs = near_toggle_hs;
  aq_error e;
  size_t nt = aq_workpath_table_size(w), np = aq_workpath_piece_count(w);
  double sc = aq_workpath_path(w)->s_c_rad;
  aq_workpath_free(w);
  if (!aq_check(nt > 16 && np < nt, "tables %zu intervals (> the first 16), pieces %zu (fewer)",
                nt, np)) {
    aq_geom_free(&g);
    return;
  }
  char want[160];
  snprintf(want, sizeof want, "expected a work path that the Hermite tables of at most %zu "
           "intervals resolve to 4e-12, got one that needs more: ", nt - 1);
  aq_error_clear(&e);
  w = NULL;
  aq_status st = aq_workpath_build_max(&g, &hs, 9.80665, "x", nt - 1, &w, &e);
  const char *fine = strstr(e.message, "rad; the finest, ");
  const char *at = fine ? strstr(fine, " is at s = ") : NULL;
  double fs = at ? strtod(at + 11, NULL) : NAN;
  aq_check(st == AQ_ENUMERIC && !w && !strcmp(e.field, "hinges") &&
               !strncmp(e.message, want, strlen(want)) && !strchr(e.message, '\n') &&
               !strstr(e.message, "barely"),
           "allowance %zu: refused naming the tables: %s", nt - 1, e.message);
  aq_check(fs >= 0 && fs < 0.01 * sc, "allowance %zu: the finest interval at s = %g rad, "
           "within the first hundredth of q_c = %g rad", nt - 1, fs, sc);
  aq_workpath_free(w);
  w = NULL;
  aq_check(aq_workpath_build_max(&g, &hs, 9.80665, "x", nt, &w, &e) == AQ_OK && w &&
               aq_workpath_table_size(w) == nt && aq_workpath_piece_count(w) == np,
           "allowance %zu: built as without one", nt);
  aq_workpath_free(w);
  aq_geom_free(&g);
}
