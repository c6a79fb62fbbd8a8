/* region.c: mass properties of the plane regions an arch is made of (see
 * region.h): the voussoirs and the fill above them.
 *
 * Circular arches keep their exact closed forms: for the sector
 * r_i <= r <= r_e, |theta - theta_m| <= a (half-angle a), density rho and
 * depth d:
 *   mass      m   = rho d a (r_e^2 - r_i^2)
 *   centroid  r_c = (2/3) (r_e^3 - r_i^3) / (r_e^2 - r_i^2) * sin(a) / a
 *             on the ray theta_m
 *   polar moment about the circle's centre  J_O = rho d a (r_e^4 - r_i^4) / 2
 *   centroidal inertia I = J_O - m r_c^2  (parallel axes).
 *
 * Every other region (a voussoir bounded by its two joints and two faces
 * that are offsets of a centre line, or polylines; the fill above a
 * voussoir) is a closed loop of pieces, straight segments or offset
 * curves, and its area, first and second moments follow from Green's
 * theorem along the loop, with w = X Y' - Y X' (X, Y from a local origin):
 *   A = (1/2) int w,  int X dA = (1/3) int X w,  int Y dA = (1/3) int Y w,
 *   int X^2 dA = (1/4) int X^2 w,  int Y^2 dA = (1/4) int Y^2 w.
 * On a segment w is constant and these are the polygon formulas; on an
 * offset curve they are integrated by Gauss-Legendre quadrature, halving
 * the interval until the halves agree to round-off: the faces are the
 * exact curves, not polygons.  The fill above voussoir k is the loop
 * extrados end of joint k, straight up to the level, along it to above the
 * extrados end of joint k+1, down to it and back along the extrados, cut
 * at the level (the part of the loop below it, pieces cut where they cross,
 * the cuts joined along the level).
 */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <string.h>

#include "region.h"

#define GL_MAX_DEPTH 20      /* halvings of a curve piece at most */
#define GL_ROUNDOFF 1e-12    /* a difference that halving no longer halves and is below this: round-off */
#define GL_REL_TOL 1e-13     /* halves agreeing to this (relative to the integrals' scale): the
                                halves, returned, are then at round-off (an analytic integrand) */
#define OUTLINE_PTS 16       /* points per curved face in the outlines (as the figure had) */
#define CROSS_ITER 200       /* bisection steps locating a crossing (to round-off) */

aq_mass aq_sector_mass(double r_i, double r_e, double th0, double th1,
                       double rho, double depth)
{
  double a = 0.5 * (th1 - th0), tm = 0.5 * (th0 + th1);
  double e2 = r_e * r_e, i2 = r_i * r_i;
  double m = rho * depth * a * (e2 - i2);
  /* (r_e^3 - r_i^3)/(r_e^2 - r_i^2) without cancellation */
  double ratio = (e2 + r_e * r_i + i2) / (r_e + r_i);
  double sinc = a > 1e-4 ? sin(a) / a : 1.0 - a * a / 6.0 + a * a * a * a / 120.0;
  double rc = 2.0 / 3.0 * ratio * sinc;
  double jo = 0.5 * rho * depth * a * (e2 * e2 - i2 * i2);
  aq_mass s;
  s.mass_kg = m;
  s.c.x = rc * cos(tm);
  s.c.y = rc * sin(tm);
  s.inertia_kgm2 = jo - m * rc * rc;
  return s;
}

aq_mass aq_mass_add(aq_mass a, aq_mass b)
{
  aq_mass s;
  s.mass_kg = a.mass_kg + b.mass_kg;
  if (!(s.mass_kg > 0))
    return a;
  s.c.x = (a.mass_kg * a.c.x + b.mass_kg * b.c.x) / s.mass_kg;
  s.c.y = (a.mass_kg * a.c.y + b.mass_kg * b.c.y) / s.mass_kg;
  double ax = a.c.x - s.c.x, ay = a.c.y - s.c.y, bx = b.c.x - s.c.x, by = b.c.y - s.c.y;
  s.inertia_kgm2 = a.inertia_kgm2 + a.mass_kg * (ax * ax + ay * ay) + b.inertia_kgm2 +
                   b.mass_kg * (bx * bx + by * by);
  return s;
}

/* ---- loops of pieces and their moments ---------------------------------- */

/* Region integrals about a local origin o: int 1, X, Y, X^2, Y^2 dA. */
typedef struct {
  double a, sx, sy, sxx, syy;
} moments;

piece aq_region_seg(aq_vec2 p0, aq_vec2 p1)
{
  piece s = {-1, 0, 0, 0, p0, p1};
  return s;
}

piece aq_region_curve(const aq_centre *s, int c, double v, double u0, double u1)
{
  piece p = {c, v, u0, u1, {0, 0}, {0, 0}};
  aq_centre_offset(s, c, u0, v, &p.p0, NULL);
  aq_centre_offset(s, c, u1, v, &p.p1, NULL);
  return p;
}

static void mom_segment(moments *m, aq_vec2 p0, aq_vec2 p1, aq_vec2 o)
{
  double x0 = p0.x - o.x, y0 = p0.y - o.y, x1 = p1.x - o.x, y1 = p1.y - o.y;
  double c = x0 * y1 - x1 * y0;
  m->a += c / 2;
  m->sx += (x0 + x1) * c / 6;
  m->sy += (y0 + y1) * c / 6;
  m->sxx += (x0 * x0 + x0 * x1 + x1 * x1) * c / 12;
  m->syy += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12;
}

/* Gauss-Legendre over [a, b] of the curve piece's five integrands. */
static void gl_panel(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                     const piece *pc, aq_vec2 o, double a, double b, double out[5])
{
  for (int k = 0; k < 5; k++)
    out[k] = 0;
  for (size_t i = 0; i < gl->n; i++) {
    double u, w;
    gsl_integration_glfixed_point(a, b, i, &u, &w, gl);
    aq_vec2 p, dp;
    aq_centre_offset(s, pc->curve, u, pc->v, &p, &dp);
    double x = p.x - o.x, y = p.y - o.y, c = x * dp.y - y * dp.x;
    out[0] += w * c / 2;
    out[1] += w * x * c / 3;
    out[2] += w * y * c / 3;
    out[3] += w * x * x * c / 4;
    out[4] += w * y * y * c / 4;
  }
}

/* The halves' sum, halved again until each of the five integrals of the
 * halves agrees with their whole to GL_REL_TOL of its scale (scale[k]: the
 * size of that integral over a region of the piece's extent), or halving
 * stops halving a difference already below GL_ROUNDOFF of it (round-off),
 * or GL_MAX_DEPTH. */
static void gl_adapt(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                     const piece *pc, aq_vec2 o, double a, double b, const double whole[5],
                     const double scale[5], int depth, double parent, double out[5])
{
  double m = 0.5 * (a + b), l[5], r[5], worst = 0;
  gl_panel(s, gl, pc, o, a, m, l);
  gl_panel(s, gl, pc, o, m, b, r);
  for (int k = 0; k < 5; k++)
    worst = fmax(worst, fabs(l[k] + r[k] - whole[k]) / scale[k]);
  if (worst <= GL_REL_TOL || depth >= GL_MAX_DEPTH ||
      (worst > 0.5 * parent && worst <= GL_ROUNDOFF)) {
    for (int k = 0; k < 5; k++)
      out[k] = l[k] + r[k];
    return;
  }
  double lo[5], hi[5];
  gl_adapt(s, gl, pc, o, a, m, l, scale, depth + 1, worst, lo);
  gl_adapt(s, gl, pc, o, m, b, r, scale, depth + 1, worst, hi);
  for (int k = 0; k < 5; k++)
    out[k] = lo[k] + hi[k];
}

static void mom_piece(moments *m, const aq_centre *s, const gsl_integration_glfixed_table *gl,
                      const piece *pc, aq_vec2 o)
{
  if (pc->curve < 0) {
    mom_segment(m, pc->p0, pc->p1, o);
    return;
  }
  /* the extent: the piece's ends and their distance from o, with the
   * thickness (a piece is never far from the region it bounds) */
  double L = fmax(hypot(pc->p0.x - o.x, pc->p0.y - o.y), hypot(pc->p1.x - o.x, pc->p1.y - o.y));
  L = fmax(L, hypot(pc->p1.x - pc->p0.x, pc->p1.y - pc->p0.y)) + s->t;
  const double scale[5] = {L * L, L * L * L, L * L * L, L * L * L * L, L * L * L * L};
  double whole[5], v[5];
  gl_panel(s, gl, pc, o, pc->u0, pc->u1, whole);
  gl_adapt(s, gl, pc, o, pc->u0, pc->u1, whole, scale, 0, HUGE_VAL, v);
  m->a += v[0];
  m->sx += v[1];
  m->sy += v[2];
  m->sxx += v[3];
  m->syy += v[4];
}

/* Mass properties of the loop pc[0..n) at density rho and depth d; *area
 * the signed area (> 0 counter-clockwise). */
aq_mass aq_region_mass(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                       const piece *pc, size_t n, double rho_d, double *area)
{
  aq_mass r = {0, {0, 0}, 0};
  *area = 0;
  if (n == 0)
    return r;
  aq_vec2 o = pc[0].p0;
  moments m = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < n; i++)
    mom_piece(&m, s, gl, &pc[i], o);
  *area = m.a;
  if (!(m.a > 0))
    return r;
  double cx = m.sx / m.a, cy = m.sy / m.a;
  r.mass_kg = rho_d * m.a;
  r.c.x = o.x + cx;
  r.c.y = o.y + cy;
  r.inertia_kgm2 = rho_d * (m.sxx + m.syy) - r.mass_kg * (cx * cx + cy * cy);
  return r;
}

/* Point t in [0, 1] of a piece. */
aq_vec2 aq_region_at(const aq_centre *s, const piece *pc, double t)
{
  if (t <= 0)
    return pc->p0;
  if (t >= 1)
    return pc->p1;
  if (pc->curve < 0) {
    aq_vec2 p = {pc->p0.x + t * (pc->p1.x - pc->p0.x), pc->p0.y + t * (pc->p1.y - pc->p0.y)};
    return p;
  }
  aq_vec2 p;
  aq_centre_offset(s, pc->curve, pc->u0 + t * (pc->u1 - pc->u0), pc->v, &p, NULL);
  return p;
}

/* The part [t0, t1] of a piece (a curve's ends computed again). */
static piece piece_part(const aq_centre *s, const piece *pc, double t0, double t1)
{
  if (pc->curve < 0)
    return aq_region_seg(aq_region_at(s, pc, t0), aq_region_at(s, pc, t1));
  piece p = *pc;
  p.u0 = pc->u0 + t0 * (pc->u1 - pc->u0);
  p.u1 = pc->u0 + t1 * (pc->u1 - pc->u0);
  p.p0 = aq_region_at(s, pc, t0);
  p.p1 = aq_region_at(s, pc, t1);
  return p;
}

/* The parts of the closed loop in[0..n) below y = level (Sutherland-
 * Hodgman against one half-plane): each piece cut where it crosses the
 * level (a curve sampled CROSS_SAMPLES times, each change bisected to
 * round-off), the parts below kept in order, consecutive parts joined by a
 * segment along the level.  Writes at most n (CROSS_SAMPLES + 2) pieces. */
size_t aq_region_cut_below(const aq_centre *s, const piece *in, size_t n, double level,
                           piece *out)
{
  size_t k = 0;
  for (size_t i = 0; i < n; i++) {
    const piece *pc = &in[i];
    int ns = pc->curve < 0 ? 1 : CROSS_SAMPLES;
    double t_in = -1; /* start of the current part below, -1: none */
    aq_vec2 prev = pc->p0;
    if (prev.y < level)
      t_in = 0;
    for (int j = 1; j <= ns; j++) {
      double t = (double)j / ns;
      aq_vec2 p = aq_region_at(s, pc, t);
      int below0 = prev.y < level, below1 = p.y < level;
      if (below0 != below1) {
        double lo = (double)(j - 1) / ns, hi = t; /* lo on prev's side */
        if (pc->curve < 0) {
          lo = hi = (level - pc->p0.y) / (pc->p1.y - pc->p0.y);
        } else {
          for (int it = 0; it < CROSS_ITER && hi - lo > 1e-17; it++) {
            double mid = 0.5 * (lo + hi);
            if ((aq_region_at(s, pc, mid).y < level) == below0)
              lo = mid;
            else
              hi = mid;
          }
        }
        double tc = 0.5 * (lo + hi);
        if (below0) {
          out[k++] = piece_part(s, pc, t_in, tc);
          t_in = -1;
        } else {
          t_in = tc;
        }
      }
      prev = p;
    }
    if (t_in >= 0)
      out[k++] = piece_part(s, pc, t_in, 1);
  }
  /* join the parts along the level */
  if (k == 0)
    return 0;
  piece *joined = out + n * (CROSS_SAMPLES + 2) / 2;
  size_t m = 0;
  for (size_t i = 0; i < k; i++) {
    if (i > 0 && (out[i - 1].p1.x != out[i].p0.x || out[i - 1].p1.y != out[i].p0.y))
      joined[m++] = aq_region_seg(out[i - 1].p1, out[i].p0);
    joined[m++] = out[i];
  }
  if (out[k - 1].p1.x != out[0].p0.x || out[k - 1].p1.y != out[0].p0.y)
    joined[m++] = aq_region_seg(out[k - 1].p1, out[0].p0);
  memmove(out, joined, m * sizeof *out);
  return m;
}

/* Sample a loop into pts (each piece from its start; a curve OUTLINE_PTS
 * times). */
size_t aq_region_sample(const aq_centre *s, const piece *pc, size_t n, aq_vec2 *pts)
{
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    int ns = pc[i].curve < 0 ? 1 : OUTLINE_PTS;
    for (int j = 0; j < ns; j++)
      pts[m++] = aq_region_at(s, &pc[i], (double)j / ns);
  }
  return m;
}

size_t aq_region_sample_count(const piece *pc, size_t n)
{
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    m += pc[i].curve < 0 ? 1 : OUTLINE_PTS;
  return m;
}

