/* shape.c: the centre lines of the arches defined by one (model.h,
 * aq_centre): pointed (two-centred), elliptical, parabolic, catenary, and
 * the circle, each from the springing (span/2, 0) on the +x side over the
 * crown to the other, with its parameter u increasing that way:
 *
 *   circular    C(u) = R (cos u, sin u), u in [pi/2 - e/2, pi/2 + e/2]
 *   pointed     two arcs of radius Rc = (rise^2 + span^2/4) / span centred
 *               on the springing line; curve 0 (+x half) about
 *               (span/2 - Rc, 0), C(u) = (span/2 - Rc + Rc cos u, Rc sin u),
 *               u in [0, uc]; curve 1 its mirror about (Rc - span/2, 0),
 *               u in [pi - uc, pi]; cos uc = (Rc - span/2) / Rc
 *   elliptical  C(u) = ((span/2) cos u, rise sin u), u in [0, pi]
 *   parabolic   C(u) = (-u, rise (1 - (2u/span)^2)), u in [-span/2, span/2]
 *   catenary    C(u) = (-u, rise - a (cosh(u/a) - 1)), a such that
 *               C(+-span/2) lies on y = 0, u in [-span/2, span/2]
 *
 * Offsets: N(u) = (T_y, -T_x), T = C'/|C'|, points away from the centre of
 * curvature (the arches turn counter-clockwise: curvature
 * k = C' x C'' / |C'|^3 > 0), so the extrados is C + (t/2) N and the
 * intrados C - (t/2) N.  The offset at v has the tangent
 * d/du (C + v N) = C' (1 + k v), regular while 1 + k v > 0.
 *
 * Arc length: Gauss-Legendre quadrature of |C'| on panels (the integrand
 * is analytic on the closed interval), inverted by Newton's method.
 */
#include <gsl/gsl_integration.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "../units.h"
#include "model.h"

#define ARC_PANELS 64        /* Gauss-Legendre panels over the whole centre line */
#define ARC_GL_POINTS 20     /* points per panel: |C'| is analytic, so 64 x 20 is round-off */
#define NEWTON_ITER 60       /* at most, inverting the arc length */
#define CATENARY_ITER 200    /* bisection steps for a (each halves log a's bracket) */
#define CURV_SAMPLES 4096    /* samples of the curvature (besides its known extremes) */

void aq_centre_eval(const aq_centre *s, int curve, double u, aq_vec2 d[3])
{
  double c = cos(u), sn = sin(u);
  switch (s->shape) {
  case AQ_SHAPE_CIRCULAR:
    d[0] = (aq_vec2){s->r * c, s->r * sn};
    d[1] = (aq_vec2){-s->r * sn, s->r * c};
    d[2] = (aq_vec2){-s->r * c, -s->r * sn};
    return;
  case AQ_SHAPE_POINTED: {
    double cx = curve == 0 ? s->cx : -s->cx;
    d[0] = (aq_vec2){cx + s->r * c, s->r * sn};
    d[1] = (aq_vec2){-s->r * sn, s->r * c};
    d[2] = (aq_vec2){-s->r * c, -s->r * sn};
    return;
  }
  case AQ_SHAPE_ELLIPTICAL:
    d[0] = (aq_vec2){0.5 * s->span * c, s->rise * sn};
    d[1] = (aq_vec2){-0.5 * s->span * sn, s->rise * c};
    d[2] = (aq_vec2){-0.5 * s->span * c, -s->rise * sn};
    return;
  case AQ_SHAPE_PARABOLIC: {
    double k = 8.0 * s->rise / (s->span * s->span); /* y = rise - k u^2 / 2 */
    d[0] = (aq_vec2){-u, s->rise - 0.5 * k * u * u};
    d[1] = (aq_vec2){-1.0, -k * u};
    d[2] = (aq_vec2){0.0, -k};
    return;
  }
  case AQ_SHAPE_CATENARY: {
    double a = s->a, x = u / a;
    d[0] = (aq_vec2){-u, s->rise - a * (cosh(x) - 1.0)};
    d[1] = (aq_vec2){-1.0, -sinh(x)};
    d[2] = (aq_vec2){0.0, -cosh(x) / a};
    return;
  }
  default:
    d[0] = d[1] = d[2] = (aq_vec2){0, 0};
  }
}

void aq_centre_circle(aq_centre *s, double r, double thickness_m, double u0, double u1)
{
  memset(s, 0, sizeof *s);
  s->shape = AQ_SHAPE_CIRCULAR;
  s->r = r;
  s->t = thickness_m;
  s->ncurve = 1;
  s->u0[0] = u0;
  s->u1[0] = u1;
  s->span = 2 * r * sin(0.5 * (u1 - u0));
  s->rise = r * (1 - cos(0.5 * (u1 - u0)));
  s->length = r * (u1 - u0);
}

double aq_centre_curvature(const aq_centre *s, int curve, double u)
{
  aq_vec2 d[3];
  aq_centre_eval(s, curve, u, d);
  double sp = hypot(d[1].x, d[1].y);
  return (d[1].x * d[2].y - d[1].y * d[2].x) / (sp * sp * sp);
}

void aq_centre_offset(const aq_centre *s, int curve, double u, double v, aq_vec2 *p,
                      aq_vec2 *dp)
{
  aq_vec2 d[3];
  aq_centre_eval(s, curve, u, d);
  double sp = hypot(d[1].x, d[1].y);
  aq_vec2 nrm = {d[1].y / sp, -d[1].x / sp};
  p->x = d[0].x + v * nrm.x;
  p->y = d[0].y + v * nrm.y;
  if (dp) {
    double k = (d[1].x * d[2].y - d[1].y * d[2].x) / (sp * sp * sp), f = 1.0 + k * v;
    dp->x = d[1].x * f;
    dp->y = d[1].y * f;
  }
}

/* |C'(u)| */
static double speed(const aq_centre *s, int curve, double u)
{
  aq_vec2 d[3];
  aq_centre_eval(s, curve, u, d);
  return hypot(d[1].x, d[1].y);
}

/* Arc length of curve over [u0, u1] (u1 >= u0), Gauss-Legendre on
 * panels of at most (range of the whole curve) / ARC_PANELS. */
static double arc_length(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                         int curve, double u0, double u1)
{
  double full = s->u1[curve] - s->u0[curve];
  size_t np = (size_t)ceil((u1 - u0) / full * ARC_PANELS);
  if (np < 1)
    np = 1;
  double h = (u1 - u0) / (double)np, sum = 0;
  for (size_t p = 0; p < np; p++) {
    double a = u0 + h * (double)p, b = p + 1 == np ? u1 : a + h;
    for (size_t i = 0; i < gl->n; i++) {
      double xi, wi;
      gsl_integration_glfixed_point(a, b, i, &xi, &wi, gl);
      sum += wi * speed(s, curve, xi);
    }
  }
  return sum;
}

/* The parameter at arc length target from u0 (Newton from the guess
 * u0 + target / |C'(u0)|, safeguarded by the bracket [u0, u1]). */
static double arc_inverse(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                          int curve, double u0, double u1, double target)
{
  double lo = u0, hi = u1, u = u0 + target / speed(s, curve, u0);
  if (!(u > lo && u < hi))
    u = 0.5 * (lo + hi);
  for (int it = 0; it < NEWTON_ITER; it++) {
    double f = arc_length(s, gl, curve, u0, u) - target;
    if (f > 0)
      hi = u;
    else
      lo = u;
    double un = u - f / speed(s, curve, u);
    if (!(un > lo && un < hi))
      un = 0.5 * (lo + hi);
    if (fabs(un - u) <= 4 * DBL_EPSILON * fabs(u1 - u0) + DBL_MIN)
      return un;
    u = un;
  }
  return u;
}

aq_status aq_centre_init(aq_centre *s, aq_shape shape, double span_m, double rise_m,
                         double thickness_m, aq_error *err)
{
  memset(s, 0, sizeof *s);
  s->shape = shape;
  s->span = span_m;
  s->rise = rise_m;
  s->t = thickness_m;
  s->ncurve = 1;
  if (!(span_m > 0) || !isfinite(span_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "span_m",
                        "expected a finite length > 0 m, got %g", span_m);
  if (!(rise_m > 0) || !isfinite(rise_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "rise_m",
                        "expected a finite length > 0 m, got %g", rise_m);
  double half = 0.5 * span_m;
  switch (shape) {
  case AQ_SHAPE_POINTED:
    if (!(rise_m >= half))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "rise_m",
                          "expected a rise >= span_m/2 = %g m for a pointed arch (span_m/2 "
                          "is the semicircle), got %g",
                          half, rise_m);
    s->r = (rise_m * rise_m + half * half) / span_m;
    s->cx = half - s->r;
    s->ncurve = 2;
    s->u0[0] = 0;
    s->u1[0] = atan2(rise_m, -s->cx);
    s->u0[1] = AQ_PI - s->u1[0];
    s->u1[1] = AQ_PI;
    break;
  case AQ_SHAPE_ELLIPTICAL:
    s->u0[0] = 0;
    s->u1[0] = AQ_PI;
    break;
  case AQ_SHAPE_PARABOLIC:
    s->u0[0] = -half;
    s->u1[0] = half;
    break;
  case AQ_SHAPE_CATENARY: {
    /* rise = a (cosh(half/a) - 1) decreases in a from +inf to 0 */
    double lo = 1e-6 * half, hi = 1e6 * half;
    for (int it = 0; it < CATENARY_ITER && hi - lo > 4 * DBL_EPSILON * hi; it++) {
      double mid = sqrt(lo * hi), r = mid * (cosh(half / mid) - 1.0);
      if (r > rise_m)
        lo = mid;
      else
        hi = mid;
    }
    s->a = 0.5 * (lo + hi);
    if (!(s->a * (cosh(half / s->a) - 1.0) > 0.5 * rise_m))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "rise_m",
                          "expected a rise a catenary of span %g m can reach, got %g", span_m,
                          rise_m);
    s->u0[0] = -half;
    s->u1[0] = half;
    break;
  }
  default:
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "shape",
                        "expected pointed, elliptical, parabolic or catenary, got %d",
                        (int)shape);
  }
  /* the intrados offset must stay regular: t/2 below the smallest radius
   * of curvature (at a known extreme, and sampled) */
  double kmax = 0, umax = s->u0[0];
  int cmax = 0;
  for (int c = 0; c < s->ncurve; c++)
    for (int i = 0; i <= CURV_SAMPLES; i++) {
      double u = s->u0[c] + (s->u1[c] - s->u0[c]) * i / CURV_SAMPLES;
      double k = aq_centre_curvature(s, c, u);
      if (k > kmax)
        kmax = k, umax = u, cmax = c;
    }
  if (!(thickness_m > 0) || !isfinite(thickness_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "thickness_m",
                        "expected a finite length > 0 m, got %g", thickness_m);
  if (!(0.5 * thickness_m * kmax < 1)) {
    aq_vec2 d[3];
    aq_centre_eval(s, cmax, umax, d);
    return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "thickness_m",
                        "expected less than twice the centre line's smallest radius of "
                        "curvature, 2 x %.6g m at (%.4g, %.4g) m (a thicker intrados folds "
                        "over itself), got %g",
                        1.0 / kmax, d[0].x, d[0].y, thickness_m);
  }
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(ARC_GL_POINTS);
  if (!gl)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  s->length = 0;
  for (int c = 0; c < s->ncurve; c++)
    s->length += arc_length(s, gl, c, s->u0[c], s->u1[c]);
  gsl_integration_glfixed_table_free(gl);
  return AQ_OK;
}

aq_status aq_centre_joints(const aq_centre *s, size_t n, double *u, int *curve, aq_error *err)
{
  if (s->ncurve == 2 && n % 2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "voussoirs",
                        "expected an even number for a pointed arch (a joint at the crown), "
                        "got %zu",
                        n);
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(ARC_GL_POINTS);
  if (!gl)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  if (s->ncurve == 2) {
    /* two circular arcs: equal arc length is equal angle */
    size_t h = n / 2;
    for (size_t j = 0; j <= n; j++) {
      int c = j < h ? 0 : 1;
      if (j <= h)
        u[j] = s->u0[0] + (s->u1[0] - s->u0[0]) * (double)j / (double)h;
      else
        u[j] = s->u0[1] + (s->u1[1] - s->u0[1]) * (double)(j - h) / (double)h;
      curve[j] = c;
    }
    u[h] = s->u1[0]; /* the crown: the end of curve 0 (curve 1 starts there) */
    u[n] = s->u1[1];
  } else {
    /* each joint from the one before (one short quadrature per Newton
     * step); the last is the far springing itself */
    double step = s->length / (double)n;
    for (size_t j = 0; j <= n; j++) {
      curve[j] = 0;
      u[j] = j == 0   ? s->u0[0]
             : j == n ? s->u1[0]
                      : arc_inverse(s, gl, 0, u[j - 1], s->u1[0], step);
    }
  }
  gsl_integration_glfixed_table_free(gl);
  return AQ_OK;
}
