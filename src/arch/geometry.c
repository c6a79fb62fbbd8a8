/* geometry.c: the voussoirs of an arch, their joints and their mass
 * properties (see model.h).
 *
 * Circular arches keep their exact closed forms: for the sector
 * r_i <= r <= r_e, |theta - theta_m| <= a (half-angle a), density rho and
 * depth d:
 *   mass      m   = rho d a (r_e^2 - r_i^2)
 *   centroid  r_c = (2/3) (r_e^3 - r_i^3) / (r_e^2 - r_i^2) * sin(a) / a
 *             on the ray theta_m
 *   polar moment about the circle's centre  J_O = rho d a (r_e^4 - r_i^4) / 2
 *   centroidal inertia I = J_O - m r_c^2  (parallel axes).
 * Geometry conventions as in the KCLC (Stockdale et al. 2018, SoftwareX;
 * docs/method.md sec. 10).
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
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "model.h"

#define GL_POINTS 20         /* Gauss-Legendre points per panel */
#define GL_MAX_DEPTH 20      /* halvings of a curve piece at most */
#define GL_ROUNDOFF 1e-12    /* a difference that halving no longer halves and is below this: round-off */
#define GL_REL_TOL 1e-13     /* halves agreeing to this (relative to the integrals' scale): the
                                halves, returned, are then at round-off (an analytic integrand) */
#define OUTLINE_PTS 16       /* points per curved face in the outlines (as the figure had) */
#define CROSS_SAMPLES 32     /* samples of a curve piece when cutting it at the fill's level */
#define CROSS_ITER 200       /* bisection steps locating a crossing (to round-off) */
#define MAX_PIECES 8         /* pieces of a voussoir's or fill's loop before cutting */

const char *const aq_shape_names[AQ_SHAPE_COUNT + 1] = {
    "circular", "pointed", "elliptical", "parabolic", "catenary", "joints", NULL};

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

/* A piece of a boundary: a straight segment p0 -> p1 (curve < 0), or the
 * offset v of the centre line's curve from parameter u0 to u1 (p0, p1 its
 * ends). */
typedef struct {
  int curve;
  double v, u0, u1;
  aq_vec2 p0, p1;
} piece;

/* Region integrals about a local origin o: int 1, X, Y, X^2, Y^2 dA. */
typedef struct {
  double a, sx, sy, sxx, syy;
} moments;

static piece seg(aq_vec2 p0, aq_vec2 p1)
{
  piece s = {-1, 0, 0, 0, p0, p1};
  return s;
}

static piece curve_piece(const aq_centre *s, int c, double v, double u0, double u1)
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
static aq_mass loop_mass(const aq_centre *s, const gsl_integration_glfixed_table *gl,
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
static aq_vec2 piece_at(const aq_centre *s, const piece *pc, double t)
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
    return seg(piece_at(s, pc, t0), piece_at(s, pc, t1));
  piece p = *pc;
  p.u0 = pc->u0 + t0 * (pc->u1 - pc->u0);
  p.u1 = pc->u0 + t1 * (pc->u1 - pc->u0);
  p.p0 = piece_at(s, pc, t0);
  p.p1 = piece_at(s, pc, t1);
  return p;
}

/* The parts of the closed loop in[0..n) below y = level (Sutherland-
 * Hodgman against one half-plane): each piece cut where it crosses the
 * level (a curve sampled CROSS_SAMPLES times, each change bisected to
 * round-off), the parts below kept in order, consecutive parts joined by a
 * segment along the level.  Writes at most n (CROSS_SAMPLES + 2) pieces. */
static size_t cut_below(const aq_centre *s, const piece *in, size_t n, double level,
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
      aq_vec2 p = piece_at(s, pc, t);
      int below0 = prev.y < level, below1 = p.y < level;
      if (below0 != below1) {
        double lo = (double)(j - 1) / ns, hi = t; /* lo on prev's side */
        if (pc->curve < 0) {
          lo = hi = (level - pc->p0.y) / (pc->p1.y - pc->p0.y);
        } else {
          for (int it = 0; it < CROSS_ITER && hi - lo > 1e-17; it++) {
            double mid = 0.5 * (lo + hi);
            if ((piece_at(s, pc, mid).y < level) == below0)
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
      joined[m++] = seg(out[i - 1].p1, out[i].p0);
    joined[m++] = out[i];
  }
  if (out[k - 1].p1.x != out[0].p0.x || out[k - 1].p1.y != out[0].p0.y)
    joined[m++] = seg(out[k - 1].p1, out[0].p0);
  memmove(out, joined, m * sizeof *out);
  return m;
}

/* ---- the voussoirs ------------------------------------------------------ */

void aq_geom_free(aq_geom *g)
{
  if (!g)
    return;
  free(g->theta_rad);
  free(g->ji);
  free(g->je);
  free(g->jo);
  free(g->ju);
  free(g->jmid);
  free(g->jhalf);
  free(g->vous);
  free(g->outline);
  free(g->outline_start);
  free(g->fill);
  free(g->fill_start);
  free(g->mass);
  free(g->vcurve);
  free(g->vu);
  for (int f = 0; f < 2; f++) {
    free(g->face_pt[f]);
    free(g->face_start[f]);
  }
  free(g->cum_m);
  free(g->cum_mx);
  free(g->cum_my);
  memset(g, 0, sizeof *g);
}

/* The loop of voussoir k: joint k up, the extrados, joint k+1 down, the
 * intrados back.  Returns the number of pieces (at most MAX_PIECES, or
 * 4 plus the face points for a joints arch: out must hold that many). */
static size_t voussoir_loop(const aq_geom *g, size_t k, piece *out)
{
  size_t n = 0;
  out[n++] = seg(g->ji[k], g->je[k]);
  if (g->p.shape == AQ_SHAPE_JOINTS) {
    aq_vec2 prev = g->je[k];
    if (g->face_start[1])
      for (size_t i = g->face_start[1][k]; i < g->face_start[1][k + 1]; i++) {
        out[n++] = seg(prev, g->face_pt[1][i]);
        prev = g->face_pt[1][i];
      }
    out[n++] = seg(prev, g->je[k + 1]);
    out[n++] = seg(g->je[k + 1], g->ji[k + 1]);
    prev = g->ji[k + 1];
    if (g->face_start[0])
      for (size_t i = g->face_start[0][k + 1]; i-- > g->face_start[0][k];) {
        out[n++] = seg(prev, g->face_pt[0][i]);
        prev = g->face_pt[0][i];
      }
    out[n++] = seg(prev, g->ji[k]);
    return n;
  }
  const double *u = g->vu + 4 * k; /* intrados u0 u1, extrados u0 u1 */
  double h = 0.5 * g->p.thickness_m;
  piece e = curve_piece(&g->centre, g->vcurve[k], h, u[2], u[3]);
  piece i = curve_piece(&g->centre, g->vcurve[k], -h, u[1], u[0]);
  e.p0 = g->je[k]; /* the joints' ends exactly (the pointed crown's are set) */
  e.p1 = g->je[k + 1];
  i.p0 = g->ji[k + 1];
  i.p1 = g->ji[k];
  out[n++] = e;
  out[n++] = seg(g->je[k + 1], g->ji[k + 1]);
  out[n++] = i;
  return n;
}

/* The loop of voussoir k's fill before it is cut at the level: up from
 * the extrados end of joint k to the level, along it to above the extrados
 * end of joint k+1, down to it, and back along the extrados. */
static size_t fill_loop(const aq_geom *g, size_t k, piece *out)
{
  double L = g->p.fill_level_m;
  aq_vec2 a = g->je[k], b = g->je[k + 1];
  aq_vec2 at = {a.x, L}, bt = {b.x, L};
  size_t n = 0;
  out[n++] = seg(a, at);
  out[n++] = seg(at, bt);
  out[n++] = seg(bt, b);
  if (g->p.shape == AQ_SHAPE_JOINTS) {
    aq_vec2 prev = b;
    if (g->face_start[1])
      for (size_t i = g->face_start[1][k + 1]; i-- > g->face_start[1][k];) {
        out[n++] = seg(prev, g->face_pt[1][i]);
        prev = g->face_pt[1][i];
      }
    out[n++] = seg(prev, a);
    return n;
  }
  piece loop[MAX_PIECES];
  voussoir_loop(g, k, loop);
  piece e = loop[1]; /* the extrados, reversed */
  piece r = e;
  r.u0 = e.u1, r.u1 = e.u0, r.p0 = e.p1, r.p1 = e.p0;
  out[n++] = r;
  return n;
}

/* Sample a loop into pts (each piece from its start; a curve OUTLINE_PTS
 * times). */
static size_t sample_loop(const aq_centre *s, const piece *pc, size_t n, aq_vec2 *pts)
{
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    int ns = pc[i].curve < 0 ? 1 : OUTLINE_PTS;
    for (int j = 0; j < ns; j++)
      pts[m++] = piece_at(s, &pc[i], (double)j / ns);
  }
  return m;
}

static size_t sample_count(const piece *pc, size_t n)
{
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    m += pc[i].curve < 0 ? 1 : OUTLINE_PTS;
  return m;
}

/* Joints of a circular arch (the closed forms), of an analytic shape (normal
 * to the centre line at equal arc length; a pointed arch's crown joint
 * vertical, between the points where the two halves' faces meet), or as
 * given. */
static aq_status place_joints(aq_geom *g, aq_error *err)
{
  const aq_arch_params *p = &g->p;
  size_t n = p->voussoirs;
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    double th_start = 0.5 * AQ_PI - 0.5 * p->embrace_rad;
    for (size_t j = 0; j <= n; j++) {
      double th = th_start + p->embrace_rad * (double)j / (double)n;
      g->theta_rad[j] = th;
      g->ji[j] = (aq_vec2){g->r_i_m * cos(th), g->r_i_m * sin(th)};
      g->je[j] = (aq_vec2){g->r_e_m * cos(th), g->r_e_m * sin(th)};
      g->jo[j] = (aq_vec2){0, 0};
      g->ju[j] = (aq_vec2){cos(th), sin(th)};
      g->jmid[j] = p->radius_m;
      g->jhalf[j] = 0.5 * p->thickness_m;
    }
    for (size_t k = 0; k < n; k++) {
      g->vcurve[k] = 0;
      g->vu[4 * k] = g->vu[4 * k + 2] = g->theta_rad[k];
      g->vu[4 * k + 1] = g->vu[4 * k + 3] = g->theta_rad[k + 1];
    }
    return AQ_OK;
  }
  if (p->shape == AQ_SHAPE_JOINTS) {
    memcpy(g->ji, p->joint_i, (n + 1) * sizeof *g->ji);
    memcpy(g->je, p->joint_e, (n + 1) * sizeof *g->je);
  } else {
    double *u = malloc((n + 1) * sizeof *u);
    int *c = malloc((n + 1) * sizeof *c);
    if (!u || !c) {
      free(u);
      free(c);
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    }
    aq_status st = aq_centre_joints(&g->centre, n, u, c, err);
    if (st != AQ_OK) {
      free(u);
      free(c);
      return st;
    }
    double h = 0.5 * p->thickness_m;
    for (size_t j = 0; j <= n; j++) {
      aq_centre_offset(&g->centre, c[j], u[j], -h, &g->ji[j], NULL);
      aq_centre_offset(&g->centre, c[j], u[j], h, &g->je[j], NULL);
    }
    for (size_t k = 0; k < n; k++) {
      g->vcurve[k] = c[k];
      g->vu[4 * k] = g->vu[4 * k + 2] = u[k];
      g->vu[4 * k + 1] = g->vu[4 * k + 3] = c[k + 1] == c[k] ? u[k + 1] : g->centre.u1[c[k]];
    }
    if (g->centre.ncurve == 2) {
      /* the crown joint: vertical, from where the halves' intrados meet to
       * where their extrados meet (curve 0 about (cx, 0), curve 1 about
       * (-cx, 0): x = cx + (r -+ h) cos u = 0) */
      size_t m = n / 2;
      double r = g->centre.r, cx = g->centre.cx;
      double ui = acos(-cx / (r - h)), ue = acos(-cx / (r + h));
      if (!(g->vu[4 * (m - 1)] < ui)) {
        /* the radial joint beside the crown reaches past x = 0 at the
         * intrados: at most uc / (uc - ui) voussoirs a half */
        double uc = g->centre.u1[0];
        size_t most = 2 * (size_t)floor(uc / (uc - ui) * (1 - 1e-12));
        free(u);
        free(c);
        return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "voussoirs",
                            "expected at most %zu voussoirs for a pointed arch this thick "
                            "(more put the joints beside the crown past the crown joint at "
                            "the intrados), got %zu",
                            most, n);
      }
      g->vu[4 * (m - 1) + 1] = ui;
      g->vu[4 * (m - 1) + 3] = ue;
      g->vu[4 * m] = AQ_PI - ui;
      g->vu[4 * m + 2] = AQ_PI - ue;
      g->vcurve[m] = 1;
      g->ji[m] = (aq_vec2){0, sqrt((r - h) * (r - h) - cx * cx)};
      g->je[m] = (aq_vec2){0, sqrt((r + h) * (r + h) - cx * cx)};
    }
    free(u);
    free(c);
  }
  for (size_t j = 0; j <= n; j++) {
    double dx = g->je[j].x - g->ji[j].x, dy = g->je[j].y - g->ji[j].y, l = hypot(dx, dy);
    if (!(l > 0))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "joints_file",
                          "expected joints of length > 0, got joint %zu of length 0", j);
    g->jo[j] = g->ji[j];
    g->ju[j] = (aq_vec2){dx / l, dy / l};
    g->jmid[j] = g->jhalf[j] = 0.5 * l;
  }
  return AQ_OK;
}

static aq_status check_params(const aq_arch_params *p, aq_error *err)
{
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    if (!(p->radius_m > 0) || !isfinite(p->radius_m))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "radius_m",
                          "expected a finite length > 0 m, got %g", p->radius_m);
    if (!(p->thickness_m > 0) || !isfinite(p->thickness_m))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "thickness_m",
                          "expected a finite length > 0 m, got %g", p->thickness_m);
    if (!(p->thickness_m < 2.0 * p->radius_m))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "thickness_m",
                          "expected less than the diameter 2*radius_m = %g m, got %g",
                          2.0 * p->radius_m, p->thickness_m);
    if (!(p->embrace_rad > 0) || !(p->embrace_rad <= AQ_PI * (1 + 1e-15)))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "embrace_deg",
                          "expected an angle in (0, 180] deg, got %g",
                          p->embrace_rad / AQ_DEG_RAD);
  }
  if (p->voussoirs < 4)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "voussoirs",
                        "expected an integer >= 4, got %zu", p->voussoirs);
  if (!(p->density_kg_m3 > 0) || !isfinite(p->density_kg_m3))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "density_kg_m3",
                        "expected a finite density > 0 kg/m^3, got %g",
                        p->density_kg_m3);
  if (!(p->depth_m > 0) || !isfinite(p->depth_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "depth_m",
                        "expected a finite length > 0 m, got %g", p->depth_m);
  if (p->shape == AQ_SHAPE_JOINTS && (!p->joint_i || !p->joint_e))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "joints_file",
                        "expected the joints, got none");
  if (p->fill_density_kg_m3 != 0 &&
      (!(p->fill_density_kg_m3 > 0) || !isfinite(p->fill_density_kg_m3)))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "density_kg_m3",
                        "expected a finite fill density > 0 kg/m^3, got %g",
                        p->fill_density_kg_m3);
  return AQ_OK;
}

static size_t at_least_one(size_t n) { return n ? n : 1; }

static aq_status alloc_all(aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  int ok = 1;
#define ALLOC(f, count) ok &= (g->f = calloc(at_least_one(count), sizeof *g->f)) != NULL
  ALLOC(theta_rad, n + 1);
  ALLOC(ji, n + 1);
  ALLOC(je, n + 1);
  ALLOC(jo, n + 1);
  ALLOC(ju, n + 1);
  ALLOC(jmid, n + 1);
  ALLOC(jhalf, n + 1);
  ALLOC(vous, n);
  ALLOC(outline_start, n + 1);
  ALLOC(fill_start, n + 1);
  ALLOC(mass, g->p.nmass);
  ALLOC(vcurve, n);
  ALLOC(vu, 4 * n);
  ALLOC(cum_m, n + 1);
  ALLOC(cum_mx, n + 1);
  ALLOC(cum_my, n + 1);
#undef ALLOC
  if (!ok)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  if (g->p.shape == AQ_SHAPE_JOINTS)
    for (int f = 0; f < 2; f++)
      if (g->p.face_start[f]) {
        size_t np = g->p.face_start[f][n];
        g->face_start[f] = malloc((n + 1) * sizeof *g->face_start[f]);
        g->face_pt[f] = malloc((np ? np : 1) * sizeof *g->face_pt[f]);
        if (!g->face_start[f] || !g->face_pt[f])
          return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        memcpy(g->face_start[f], g->p.face_start[f], (n + 1) * sizeof *g->face_start[f]);
        if (np)
          memcpy(g->face_pt[f], g->p.face_pt[f], np * sizeof *g->face_pt[f]);
      }
  return AQ_OK;
}

/* The most pieces a voussoir's loop or its fill's has (before cutting). */
static size_t max_loop(const aq_geom *g)
{
  size_t most = MAX_PIECES, n = g->p.voussoirs;
  if (g->p.shape == AQ_SHAPE_JOINTS)
    for (size_t k = 0; k < n; k++) {
      size_t m = 5;
      for (int f = 0; f < 2; f++)
        if (g->face_start[f])
          m += g->face_start[f][k + 1] - g->face_start[f][k];
      if (m > most)
        most = m;
    }
  return most;
}

/* Voussoirs, fills and outlines. */
static aq_status build_parts(aq_geom *g, aq_error *err)
{
  const aq_arch_params *p = &g->p;
  size_t n = p->voussoirs, cap = max_loop(g);
  piece *loop = malloc(cap * sizeof *loop);
  piece *cut = malloc(2 * cap * (CROSS_SAMPLES + 2) * sizeof *cut);
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(GL_POINTS);
  size_t nout = 0, nfill = 0, ocap = 0, fcap = 0;
  aq_status st = AQ_OK;
  int fill = p->fill_density_kg_m3 > 0;
  double rho_d = p->density_kg_m3 * p->depth_m, fill_d = p->fill_density_kg_m3 * p->depth_m;
  if (!loop || !cut || !gl) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (size_t k = 0; k < n; k++) {
    size_t nl = voussoir_loop(g, k, loop), ns = sample_count(loop, nl);
    double area = 0;
    if (p->shape == AQ_SHAPE_CIRCULAR) {
      g->vous[k] = aq_sector_mass(g->r_i_m, g->r_e_m, g->theta_rad[k], g->theta_rad[k + 1],
                                  p->density_kg_m3, p->depth_m);
    } else {
      g->vous[k] = loop_mass(&g->centre, gl, loop, nl, rho_d, &area);
      if (!(area > 0)) {
        st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "joints_file",
                          "expected voussoirs of positive area (counter-clockwise from the "
                          "springing on the +x side), got voussoir %zu of area %.6g m^2",
                          k, area);
        goto done;
      }
    }
    g->stone_kg += g->vous[k].mass_kg;
    if (nout + ns > ocap) {
      ocap = 2 * (nout + ns) + 64;
      aq_vec2 *o = realloc(g->outline, ocap * sizeof *o);
      if (!o) {
        st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        goto done;
      }
      g->outline = o;
    }
    g->outline_start[k] = nout;
    nout += sample_loop(&g->centre, loop, nl, g->outline + nout);
    g->fill_start[k] = nfill;
    if (fill) {
      size_t nf = fill_loop(g, k, loop);
      nf = cut_below(&g->centre, loop, nf, p->fill_level_m, cut);
      aq_mass fm = loop_mass(&g->centre, gl, cut, nf, fill_d, &area);
      if (area < -1e-12 * p->thickness_m * p->thickness_m) {
        st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "level_m",
                          "expected an extrados the fill lies on (its x decreasing from "
                          "joint %zu to %zu), got voussoir %zu's turning back (fill area "
                          "%.6g m^2)",
                          k, k + 1, k, area);
        goto done;
      }
      if (area > 0 && fm.mass_kg > 0) {
        g->vous[k] = aq_mass_add(g->vous[k], fm);
        g->fill_kg += fm.mass_kg;
        size_t nsf = sample_count(cut, nf);
        if (nfill + nsf > fcap) {
          fcap = 2 * (nfill + nsf) + 64;
          aq_vec2 *f = realloc(g->fill, fcap * sizeof *f);
          if (!f) {
            st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
            goto done;
          }
          g->fill = f;
        }
        nfill += sample_loop(&g->centre, cut, nf, g->fill + nfill);
      }
    }
  }
  g->outline_start[n] = nout;
  g->fill_start[n] = nfill;
done:
  free(loop);
  free(cut);
  if (gl)
    gsl_integration_glfixed_table_free(gl);
  return st;
}

/* The springing level: the lower of the two springing joints' middles. */
static double springing_level(const aq_geom *g)
{
  size_t n = g->p.voussoirs;
  double a = 0.5 * (g->ji[0].y + g->je[0].y), b = 0.5 * (g->ji[n].y + g->je[n].y);
  return a < b ? a : b;
}

/* Point masses: each inside its voussoir's vertical strip (between the
 * lowest and highest x of its outline and fill) and above the arch's
 * lowest point, each to MASS_ON_JOINT_REL of the arch's size: a mass on the
 * joint between two voussoirs (at x = 0 on a crown joint, which the
 * outlines place within round-off of it, on either side) may name either,
 * which carries it. */
#define MASS_ON_JOINT_REL 1e-9
static aq_status add_masses(aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  double ylo = HUGE_VAL, size = 0;
  for (size_t i = 0; i < g->outline_start[n]; i++) {
    ylo = fmin(ylo, g->outline[i].y);
    size = fmax(size, fmax(fabs(g->outline[i].x), fabs(g->outline[i].y)));
  }
  double tol = MASS_ON_JOINT_REL * size;
  for (size_t m = 0; m < g->p.nmass; m++) {
    aq_point_mass pm = g->p.mass[m];
    g->mass[m] = pm;
    if (pm.voussoir >= n)
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, pm.name,
                          "expected a voussoir in 0..%zu, got %zu", n - 1, pm.voussoir);
    if (!(pm.mass_kg > 0) || !isfinite(pm.mass_kg))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, pm.name,
                          "expected a mass > 0 kg, got %g", pm.mass_kg);
    size_t k = pm.voussoir;
    double xlo = HUGE_VAL, xhi = -HUGE_VAL;
    for (size_t i = g->outline_start[k]; i < g->outline_start[k + 1]; i++)
      xlo = fmin(xlo, g->outline[i].x), xhi = fmax(xhi, g->outline[i].x);
    for (size_t i = g->fill_start[k]; i < g->fill_start[k + 1]; i++)
      xlo = fmin(xlo, g->fill[i].x), xhi = fmax(xhi, g->fill[i].x);
    if (!(pm.p.x >= xlo - tol && pm.p.x <= xhi + tol && pm.p.y >= ylo - tol) ||
        !isfinite(pm.p.y))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, pm.name,
                          "expected a point on voussoir %zu (x in [%.6g, %.6g] m, above or "
                          "below it; y >= %.6g m, the arch's lowest point), got (%g, %g) m",
                          k, fabs(xlo) < tol ? 0.0 : xlo, fabs(xhi) < tol ? 0.0 : xhi,
                          fabs(ylo) < tol ? 0.0 : ylo, pm.p.x, pm.p.y);
    aq_mass pt = {pm.mass_kg, pm.p, 0};
    g->vous[k] = aq_mass_add(g->vous[k], pt);
    g->point_kg += pm.mass_kg;
  }
  return AQ_OK;
}

/* The geometry as stored (p->stored), copied: joints, voussoirs, outlines,
 * fill and point masses as they are. */
static aq_status from_stored(aq_geom *g, aq_error *err)
{
  const aq_arch_drawing *d = g->p.stored;
  size_t n = d->voussoirs;
  if (n < 4 || !d->joints || !d->parts || d->outline_start[0] != 0 ||
      (size_t)d->outline_start[n] != d->noutline || (size_t)d->fill_start[n] != d->nfill)
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                        "expected a stored geometry of at least 4 voussoirs with its outlines, "
                        "got %zu voussoirs", n);
  for (size_t k = 0; k < n; k++)
    if (d->outline_start[k] > d->outline_start[k + 1] || d->fill_start[k] > d->fill_start[k + 1] ||
        !(d->parts[4 * k] > 0))
      return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                          "expected voussoir %zu's mass > 0 and its outline's rows in order, "
                          "got neither", k);
  g->p.voussoirs = n;
  g->p.nmass = d->nmass;
  aq_status st = alloc_all(g, err);
  if (st != AQ_OK)
    return st;
  g->outline = malloc((d->noutline ? d->noutline : 1) * sizeof *g->outline);
  g->fill = malloc((d->nfill ? d->nfill : 1) * sizeof *g->fill);
  if (!g->outline || !g->fill)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  for (size_t j = 0; j <= n; j++) {
    const double *r = d->joints + 4 * j;
    g->ji[j] = (aq_vec2){r[0], r[1]};
    g->je[j] = (aq_vec2){r[2], r[3]};
    double dx = r[2] - r[0], dy = r[3] - r[1], l = hypot(dx, dy);
    if (!(l > 0))
      return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                          "expected joints of length > 0, got joint %zu of length 0", j);
    g->jo[j] = g->ji[j];
    g->ju[j] = (aq_vec2){dx / l, dy / l};
    g->jmid[j] = g->jhalf[j] = 0.5 * l;
    g->outline_start[j] = (size_t)d->outline_start[j];
    g->fill_start[j] = (size_t)d->fill_start[j];
  }
  for (size_t k = 0; k < n; k++) {
    const double *r = d->parts + 4 * k;
    g->vous[k] = (aq_mass){r[0], {r[1], r[2]}, r[3]};
  }
  for (size_t i = 0; i < d->noutline; i++)
    g->outline[i] = (aq_vec2){d->outline[2 * i], d->outline[2 * i + 1]};
  for (size_t i = 0; i < d->nfill; i++)
    g->fill[i] = (aq_vec2){d->fill[2 * i], d->fill[2 * i + 1]};
  for (size_t i = 0; i < d->nmass; i++) {
    const double *r = d->mass + 4 * i;
    g->mass[i] = (aq_point_mass){"", (size_t)r[0], {r[1], r[2]}, r[3]};
    snprintf(g->mass[i].name, sizeof g->mass[i].name, "mass %zu", i);
  }
  g->stone_kg = d->stone_kg;
  g->fill_kg = d->fill_kg;
  g->point_kg = d->point_kg;
  free(g->theta_rad);
  g->theta_rad = NULL;
  return AQ_OK;
}

aq_status aq_geom_init(aq_geom *g, const aq_arch_params *p, aq_error *err)
{
  memset(g, 0, sizeof *g);
  if (p->stored) {
    g->p = *p;
    aq_status st = from_stored(g, err);
    if (st != AQ_OK) {
      aq_geom_free(g);
      return st;
    }
    goto sums;
  }
  aq_status st = check_params(p, err);
  if (st != AQ_OK)
    return st;
  size_t n = p->voussoirs;
  g->p = *p;
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    g->r_i_m = p->radius_m - 0.5 * p->thickness_m;
    g->r_e_m = p->radius_m + 0.5 * p->thickness_m;
    double a = 0.5 * AQ_PI - 0.5 * p->embrace_rad;
    aq_centre_circle(&g->centre, p->radius_m, p->thickness_m, a, a + p->embrace_rad);
  } else if (p->shape != AQ_SHAPE_JOINTS) {
    st = aq_centre_init(&g->centre, p->shape, p->span_m, p->rise_m, p->thickness_m, err);
    if (st != AQ_OK)
      return st;
  }
  if ((st = alloc_all(g, err)) != AQ_OK || (st = place_joints(g, err)) != AQ_OK)
    goto fail;
  if (p->fill_density_kg_m3 > 0) {
    double lo = springing_level(g);
    if (!(p->fill_level_m > lo) || !isfinite(p->fill_level_m)) {
      st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "level_m",
                        "expected a fill level above the springings (y > %.6g m), got %g", lo,
                        p->fill_level_m);
      goto fail;
    }
  }
  if ((st = build_parts(g, err)) != AQ_OK || (st = add_masses(g, err)) != AQ_OK)
    goto fail;
  if (p->shape != AQ_SHAPE_CIRCULAR)
    free(g->theta_rad), g->theta_rad = NULL;
sums:
  n = g->p.voussoirs;
  g->cum_m[0] = g->cum_mx[0] = g->cum_my[0] = 0;
  for (size_t k = 0; k < n; k++) {
    g->cum_m[k + 1] = g->cum_m[k] + g->vous[k].mass_kg;
    g->cum_mx[k + 1] = g->cum_mx[k] + g->vous[k].mass_kg * g->vous[k].c.x;
    g->cum_my[k + 1] = g->cum_my[k] + g->vous[k].mass_kg * g->vous[k].c.y;
  }
  aq_mass all = aq_geom_body(g, 0, n);
  g->mass_kg = all.mass_kg;
  g->c = all.c;
  g->p.joint_i = g->p.joint_e = NULL;
  g->p.face_pt[0] = g->p.face_pt[1] = NULL;
  g->p.face_start[0] = g->p.face_start[1] = NULL;
  g->p.mass = NULL;
  g->p.stored = NULL;
  return AQ_OK;
fail:
  aq_geom_free(g);
  return st;
}

aq_vec2 aq_geom_joint_point(const aq_geom *g, size_t j, char face)
{
  return face == 'e' ? g->je[j] : g->ji[j];
}

aq_mass aq_geom_body(const aq_geom *g, size_t j0, size_t j1)
{
  aq_mass b = {0, {0, 0}, 0};
  double sx = 0, sy = 0;
  for (size_t k = j0; k < j1; k++) {
    b.mass_kg += g->vous[k].mass_kg;
    sx += g->vous[k].mass_kg * g->vous[k].c.x;
    sy += g->vous[k].mass_kg * g->vous[k].c.y;
  }
  if (b.mass_kg > 0) {
    b.c.x = sx / b.mass_kg;
    b.c.y = sy / b.mass_kg;
  }
  for (size_t k = j0; k < j1; k++) {
    double dx = g->vous[k].c.x - b.c.x, dy = g->vous[k].c.y - b.c.y;
    b.inertia_kgm2 += g->vous[k].inertia_kgm2 + g->vous[k].mass_kg * (dx * dx + dy * dy);
  }
  return b;
}

/* ---- the straight strut -------------------------------------------------- */

#define STRUT_SLOPE_MAX 1e4    /* slopes searched, m/m: lines within 0.006 deg of vertical */
#define STRUT_BISECTIONS 200   /* halvings of the slope's bracket (to round-off) */
#define STRUT_MARGIN_REL 1e-9  /* a margin above this (relative to the arch's size) fits */

/* For slope b: the best offset *a and the margin (half the gap between the
 * lowest extrados end and the highest intrados end, each measured from the
 * line y = b x); *dgap the gap's slope in b (a supergradient); *ti, *te
 * the joints of those two ends. */
static double strut_at(const aq_geom *g, double b, double *a, double *dgap, size_t *ti,
                       size_t *te)
{
  size_t n = g->p.voussoirs;
  double lo_e = HUGE_VAL, hi_i = -HUGE_VAL;
  *ti = *te = 0;
  for (size_t j = 0; j <= n; j++) {
    double e = g->je[j].y - b * g->je[j].x, i = g->ji[j].y - b * g->ji[j].x;
    if (e < lo_e)
      lo_e = e, *te = j;
    if (i > hi_i)
      hi_i = i, *ti = j;
  }
  *a = 0.5 * (lo_e + hi_i);
  *dgap = -g->je[*te].x + g->ji[*ti].x;
  return 0.5 * (lo_e - hi_i);
}

/* Where the line y = a + b x meets the segment from p to q (clamped to it). */
static aq_vec2 strut_meets(double a, double b, aq_vec2 p, aq_vec2 q)
{
  double den = (q.y - p.y) - b * (q.x - p.x);
  double t = den != 0 ? (a + b * p.x - p.y) / den : 0.5;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  aq_vec2 r = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
  return r;
}

void aq_geom_strut(const aq_geom *g, aq_strut *s)
{
  /* the margin is concave in the slope b (a minimum of lines minus a
   * maximum of lines): bisection on the sign of its supergradient */
  double lo = -STRUT_SLOPE_MAX, hi = STRUT_SLOPE_MAX, a, d;
  size_t ti, te;
  for (int k = 0; k < STRUT_BISECTIONS && hi - lo > 0; k++) {
    double mid = 0.5 * (lo + hi);
    strut_at(g, mid, &a, &d, &ti, &te);
    if (d > 0)
      lo = mid;
    else if (d < 0)
      hi = mid;
    else
      lo = hi = mid;
  }
  double b = 0.5 * (lo + hi);
  s->margin_m = strut_at(g, b, &a, &d, &s->tight_i, &s->tight_e);
  s->a = a;
  s->b = b;
  size_t n = g->p.voussoirs;
  s->p0 = strut_meets(a, b, g->ji[0], g->je[0]);
  s->pn = strut_meets(a, b, g->ji[n], g->je[n]);
}

aq_status aq_geom_check_strut(const aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  double size = 0;
  for (size_t j = 0; j <= n; j++)
    size = fmax(size, fmax(fmax(fabs(g->ji[j].x), fabs(g->ji[j].y)),
                           fmax(fabs(g->je[j].x), fabs(g->je[j].y))));
  aq_strut s;
  aq_geom_strut(g, &s);
  if (!(s.margin_m > STRUT_MARGIN_REL * size))
    return AQ_OK;
  int joints = g->p.shape == AQ_SHAPE_JOINTS;
  char rule[400] = "";
  if (!joints) {
    /* joints normal to the centre line: the intrados end rises to the
     * crown, the extrados end is lowest at a springing, so with a joint at
     * the crown a strut fits while f - t/2 <= (t/2) cos(phi): the rise f
     * at most (t/2)(1 + cos phi), phi the centre line's slope at the
     * springings (docs/arch-model.md) */
    double t = g->p.thickness_m;
    double f = g->p.shape == AQ_SHAPE_CIRCULAR
                   ? g->p.radius_m * (1 - cos(0.5 * g->p.embrace_rad))
                   : g->p.rise_m;
    double ux = g->je[0].x - g->ji[0].x, uy = g->je[0].y - g->ji[0].y;
    double cphi = uy / hypot(ux, uy), phi_deg = acos(fmin(1, fmax(-1, cphi))) / AQ_DEG_RAD;
    snprintf(rule, sizeof rule,
             "; a mechanism needs a rise above (t/2)(1 + cos %.3g deg) = %.4g m (here %.4g; "
             "%.3g deg: the springings' slope) or t below %.4g m (here %.4g)",
             phi_deg, 0.5 * t * (1 + cphi), f, phi_deg, 2 * f / (1 + cphi), t);
  }
  return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, joints ? "joints_file" : "thickness_m",
                      "expected an arch a horizontal load can open into four hinges, got one "
                      "too flat for its thickness: a straight strut from joint 0 at (%.4g, "
                      "%.4g) m to joint %zu at (%.4g, %.4g) m passes %.4g m inside every joint "
                      "(nearest: joint %zu's intrados, joint %zu's extrados) and carries any "
                      "horizontal load%s",
                      s.p0.x, s.p0.y, n, s.pn.x, s.pn.y, s.margin_m, s.tight_i, s.tight_e,
                      rule);
}
