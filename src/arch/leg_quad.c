/* leg_quad.c: the work-path quadrature leg (--model workpath-quad; see
 * leg.h): the time integral of the exact energy balance by Chebyshev panels.
 *
 * The method is that of
 *   G. L. Stockdale, V. Sarhosis, G. Milani, "Work-path approach seismic
 *   modelling of hinge-controlled masonry arches" (sections 2.6-3, Fig. 9),
 * with the corrections of docs/method.md sec. 4-9: the exact energy balance
 *     KE(s) = KE1 - a_g m_T (x(s) - x(s1)) - g m_T (y(s) - y(s1))  (eq. 19,
 *                                                    per docs/method.md sec. 5)
 * and the exact time integral
 *     t - t0 = int sqrt(M(s) / (2 KE(s))) ds       (eqs. 24-25, per docs/method.md
 *                                                    secs. 4 and 6).
 *
 *
 * Work-path leg (aq_quad_leg).  Along the direction of motion, sigma >= 0 is the
 * distance travelled from the leg's start.  The leg is cut into panels
 * [0, L]; on each the 1/sqrt singularities of the integrand at zeros of KE
 * are removed analytically by a change of variable:
 *   - za: distance behind the panel start to a zero of KE (0 when the panel
 *     starts from rest or at a turning point; otherwise the root of the
 *     quadratic Taylor model of KE, or none);
 *   - zb: distance beyond the panel end to a zero of KE (0 at a turning
 *     point, found to round-off by safeguarded Newton on KE).
 *   Both near:  sigma = -za + W sin^2(phi/2), W = za + L + zb, so that
 *               KE ~ (sigma + za)(L + zb - sigma) ~ sin^2 phi cancels the
 *               Jacobian W/2 sin phi;
 *   one near:   sigma + za = w^2 (or L + zb - sigma = w^2);
 *   none near:  sigma linear.
 * The regularised integrand is smooth; it is interpolated at n Chebyshev
 * points of the first kind (which avoid the ends), integrated exactly as a
 * Chebyshev series, and the panel is halved until the series' tail is
 * below the tolerance.  The position at the end of a step solves
 * time(psi) = dt by safeguarded Newton on that series.  A turning point
 * (KE = 0 with s > 0) ends a panel exactly; the motion reverses and the
 * step continues, so several events fit in one step.
 */
#include "leg.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define WP_MAX_NODES 32
static const double WP_PI = 3.14159265358979323846;
enum { WP_DEFAULT_NODES = 12 };
static const double WP_DEFAULT_TOL = 1e-12;  /* Chebyshev tail / mean, per panel */
static const double WP_PANEL_FRAC = 0.125;   /* longest panel, fraction of s_c */
static const double WP_NEAR_ZERO = 2.0;      /* a zero of KE within this many L is "near" */
static const double WP_REACH_MARGIN = 1.3;   /* panel = margin * distance reachable in the step */
static const double WP_NEAR_MIN_FRAC = 0.1;  /* KE minimum this small vs the ends: split there */
static const double WP_NEAR_MIN_SPAN = 0.25; /* sinh map when the minimum's width is within this * L */
static const double WP_NOISE_GAIN = 16;      /* tail floor = this * KE round-off at the nodes */
static const double WP_STALL_GAIN = 0.125;   /* a halving must cut the tail by 8x */
static const double WP_MIN_PANEL_FRAC = 1e-13; /* no halving below this fraction of s_c */
static const double WP_KES_TAIL = 1e-13;     /* dKE/dpsi series tail / KE scale: resolved */
static const double WP_KES_MISMATCH = 1e-9;  /* turning-point mismatch / KE scale: sane */
static const double WP_TP_MISMATCH_ULPS = 32; /* move a turning point when the mismatch exceeds this many ulps of the KE scale */
static const size_t QUAD_MAX_PANELS = 2000000; /* per leg; beyond: no progress, an error */

/* cos(pi k (j + 1/2) / n) for the current n (node j is row k = 1). */
typedef struct {
  int n;
  double cs[WP_MAX_NODES][WP_MAX_NODES];
  /* integral from -1 of the interpolant of nodal values v: at node j,
   * sum_i iq[j][i] v_i; to +1, sum_i iw[i] v_i (cheb_quad_init) */
  double iq[WP_MAX_NODES][WP_MAX_NODES];
  double iw[WP_MAX_NODES];
} wp_cos;

struct aq_quad {
  double wp_tol;
  int wp_nodes;
  int exact;
  wp_cos ccos; /* Chebyshev cosines for wp_nodes */
  /* one cached path evaluation (the end of the previous leg) */
  const aq_path *cache_p;
  double cache_s;
  aq_path_point cache_pt;
};

typedef struct {
  aq_quad *st;
  const aq_path *p;
  double a;      /* ground acceleration, m/s^2 */
  double mt, g;  /* m_T, g */
  double sa;     /* leg start, rad */
  int dir;
  double ke_a, xa, ya; /* energy reference at the leg start */
  aq_leg_stats *stats;
} wp_ctx;

typedef struct {
  double sigma, s;
  double ke;  /* KE from the energy balance, J (may be <= 0 beyond a zero) */
  double k1;  /* dKE/dsigma, J/rad */
  double k2;  /* d2KE/dsigma2, J/rad^2 */
  double m;   /* M(s), kg m^2 */
  double x, y;
} wp_pt;

static int wp_eval(wp_ctx *c, double s, aq_path_point *pt)
{
  aq_quad *st = c->st;
  if (st->cache_p == c->p && st->cache_s == s) {
    *pt = st->cache_pt;
    return 0;
  }
  c->stats->evals++;
  int rc = c->st->exact ? c->p->eval_exact(c->p->ctx, s, pt)
                        : c->p->eval(c->p->ctx, s, pt);
  if (rc == 0) {
    st->cache_p = c->p;
    st->cache_s = s;
    st->cache_pt = *pt;
  }
  return rc;
}

static int wp_point(wp_ctx *c, double sigma, wp_pt *o)
{
  double s = c->sa + c->dir * sigma;
  if (s < 0)
    s = 0;
  if (s > c->p->s_c_rad)
    s = c->p->s_c_rad;
  aq_path_point pt;
  if (wp_eval(c, s, &pt) != 0)
    return -1;
  o->sigma = sigma;
  o->s = s;
  o->x = pt.x_m;
  o->y = pt.y_m;
  /* eq. (19), per docs/method.md sec. 5 */
  o->ke = c->ke_a - c->mt * (c->a * (pt.x_m - c->xa) + c->g * (pt.y_m - c->ya));
  o->k1 = -c->dir * c->mt * (c->a * pt.dx_m + c->g * pt.dy_m);
  o->k2 = -c->mt * (c->a * pt.d2x_m + c->g * pt.d2y_m);
  o->m = pt.mgen_kgm2;
  return 0;
}

/* Distance to a zero of the quadratic model ke + k1 z + k2/2 z^2 (z >= 0)
 * when ke > 0 and k1 < 0; INFINITY when the model has none. */
static double zero_ahead(double ke, double k1, double k2)
{
  if (ke <= 0)
    return 0;
  if (!(k1 < 0))
    return INFINITY;
  double disc = k1 * k1 - 2 * k2 * ke;
  if (disc < 0)
    return INFINITY;
  return 2 * ke / (-k1 + sqrt(disc));
}

/* The change of variable of one panel: psi in [-1, 1] -> sigma in [0, L]. */
typedef struct {
  int kind; /* 0 linear, 1 zero behind, 2 zero ahead, 3 both, 4/5 near-zero
              minimum at the start / end (sinh) */
  double L, za, zb, W, u0, u1;
} wp_map;

static void map_init(wp_map *mp, double L, double za, double zb)
{
  mp->L = L;
  int near_a = za <= WP_NEAR_ZERO * L, near_b = zb <= WP_NEAR_ZERO * L;
  mp->za = near_a ? za : 0;
  mp->zb = near_b ? zb : 0;
  if (near_a && near_b) {
    mp->kind = 3;
    mp->W = za + L + zb;
    mp->u0 = 2 * asin(fmin(1.0, sqrt(za / mp->W)));
    mp->u1 = 2 * asin(fmin(1.0, sqrt((za + L) / mp->W)));
  } else if (near_a) {
    mp->kind = 1;
    mp->u0 = sqrt(za);
    mp->u1 = sqrt(za + L);
  } else if (near_b) {
    mp->kind = 2;
    mp->u0 = sqrt(L + zb);
    mp->u1 = sqrt(zb);
  } else {
    mp->kind = 0;
    mp->u0 = 0;
    mp->u1 = L;
  }
}

/* A near-zero minimum of KE at or just beyond an end, from the quadratic
 * model there: KE ~ KE_m + k2/2 (sigma - sigma_m)^2.  The substitution
 * sigma - sigma_m = h sinh(w), h = sqrt(2 KE_m / k2), makes KE ~ KE_m
 * cosh^2 w cancel the Jacobian h cosh w: the near-singular integrand of a
 * slow passage over a saddle becomes smooth.  Start side first. */
static void map_near_min(wp_map *mp, double kea, double k1a, double k2a,
                         double keb, double k1b, double k2b)
{
  double L = mp->L;
  if (kea > 0 && k2a > 0 && k1a >= 0) {
    double sm = -k1a / k2a, km = kea - k1a * k1a / (2 * k2a);
    if (km > 0) {
      double h = sqrt(2 * km / k2a);
      if (-sm + h < WP_NEAR_MIN_SPAN * L) {
        mp->kind = 4;
        mp->W = h;
        mp->za = sm; /* centre, relative to the start (<= 0) */
        mp->u0 = asinh(-sm / h);
        mp->u1 = asinh((L - sm) / h);
        return;
      }
    }
  }
  if (keb > 0 && k2b > 0 && k1b <= 0) {
    double sm = -k1b / k2b, km = keb - k1b * k1b / (2 * k2b);
    if (km > 0) {
      double h = sqrt(2 * km / k2b);
      if (sm + h < WP_NEAR_MIN_SPAN * L) {
        mp->kind = 5;
        mp->W = h;
        mp->zb = sm; /* centre, beyond the end (>= 0) */
        mp->u0 = asinh((L + sm) / h);
        mp->u1 = asinh(sm / h);
      }
    }
  }
}

/* sigma(psi) and dsigma/dpsi. */
static double map_sigma(const wp_map *mp, double psi, double *jac)
{
  double h = 0.5 * (mp->u1 - mp->u0);
  double u = mp->u0 + h * (psi + 1);
  double sg;
  switch (mp->kind) {
  case 3: {
    double sn = sin(0.5 * u);
    sg = -mp->za + mp->W * sn * sn;
    *jac = 0.5 * mp->W * sin(u) * h;
    break;
  }
  case 1:
    sg = u * u - mp->za;
    *jac = 2 * u * h;
    break;
  case 2:
    sg = mp->L + mp->zb - u * u;
    *jac = -2 * u * h;
    break;
  case 4:
    sg = mp->za + mp->W * sinh(u);
    *jac = mp->W * cosh(u) * h;
    break;
  case 5:
    sg = mp->L + mp->zb - mp->W * sinh(u);
    *jac = -mp->W * cosh(u) * h;
    break;
  default:
    sg = u;
    *jac = h;
  }
  if (sg < 0)
    sg = 0;
  if (sg > mp->L)
    sg = mp->L;
  return sg;
}

/* Chebyshev series helpers: f(x) = sum' c_k T_k(x) (c_0 halved). */
static double cheb_eval(const double *c, int n, double x)
{
  double b1 = 0, b2 = 0;
  for (int k = n - 1; k >= 1; k--) {
    double b0 = 2 * x * b1 - b2 + c[k];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + 0.5 * c[0];
}

typedef struct {
  int n;
  double c[WP_MAX_NODES + 1];  /* integrand series */
  double ci[WP_MAX_NODES + 2]; /* antiderivative series, zero at psi = -1 */
  double total;                /* panel time, s */
  double tail;                 /* |c_{n-1}| + |c_{n-2}| relative to |c_0| */
} wp_cheb;

static void cheb_cos_init(wp_cos *t, int n)
{
  t->n = n;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++)
      t->cs[k][j] = cos(WP_PI * k * (j + 0.5) / n);
}

static void cheb_build(wp_cheb *ch, const wp_cos *t, const double *g, int n)
{
  ch->n = n;
  for (int k = 0; k < n; k++) {
    double sum = 0;
    for (int j = 0; j < n; j++)
      sum += g[j] * t->cs[k][j];
    ch->c[k] = 2.0 * sum / n;
  }
  ch->c[n] = 0;
  /* antiderivative: C_k = (c_{k-1} - c_{k+1}) / (2k), c_0 taken whole */
  for (int k = 1; k <= n; k++) {
    double cm = k == 1 ? ch->c[0] : ch->c[k - 1];
    double cp = k + 1 <= n ? ch->c[k + 1] : 0;
    ch->ci[k] = (cm - cp) / (2.0 * k);
  }
  ch->ci[0] = 0;
  double at_m1 = cheb_eval(ch->ci, n + 1, -1.0);
  ch->ci[0] = -2 * at_m1;
  ch->total = cheb_eval(ch->ci, n + 1, 1.0);
  double mean = fabs(ch->c[0]) > 0 ? fabs(ch->c[0]) : 1;
  ch->tail = (fabs(ch->c[n - 1]) + fabs(ch->c[n - 2])) / mean;
}

/* The integration weights of cheb_build's antiderivative at the nodes and
 * at +1, column by column (the map from nodal values is linear). */
static void cheb_quad_init(wp_cos *t)
{
  const int n = t->n;
  double e[WP_MAX_NODES] = {0};
  wp_cheb ch;
  for (int i = 0; i < n; i++) {
    e[i] = 1;
    cheb_build(&ch, t, e, n);
    e[i] = 0;
    for (int j = 0; j < n; j++)
      t->iq[j][i] = cheb_eval(ch.ci, n + 1, t->cs[1][j]);
    t->iw[i] = ch.total;
  }
}

/* KE along a panel from the integral of dKE/dsigma (see wp_leg). */
typedef struct {
  int on;       /* 0: use eq. (19) as it stands */
  int n;
  double ke_a;  /* KE at the panel start, J */
  double mis;   /* KE at a turning-point end by the series (0 by the end's location), J */
  double L;     /* panel length, rad */
  double total; /* integral of dKE/dpsi over the panel, J */
  double fk[WP_MAX_NODES]; /* dKE/dpsi at the nodes, J */
} wp_kes;

/* KE at psi (sigma = sg) by the series: the start's KE plus the integral
 * of dKE/dpsi, less the mismatch at a turning-point end spread in
 * proportion to sigma (so that KE ~ (L - sigma) stays a smooth product). */
static double kes_at(const wp_kes *k, const wp_cos *t, double psi, double sg)
{
  wp_cheb f;
  cheb_build(&f, t, k->fk, k->n);
  return k->ke_a + cheb_eval(f.ci, k->n + 1, psi) - k->mis * (sg / k->L);
}

typedef struct {
  double L;
  int kind;
  wp_pt PB;
  wp_map mp;
  wp_cheb ch;
  wp_kes ks;
} wp_panel;

/* psi in [-1, 1] where the time reaches tau (0 <= tau <= total). */
static double cheb_solve(const wp_cheb *ch, double tau)
{
  double lo = -1, hi = 1;
  double x = -1 + 2 * tau / ch->total;
  for (int it = 0; it < 100; it++) {
    double f = cheb_eval(ch->ci, ch->n + 1, x) - tau;
    if (f > 0)
      hi = x;
    else
      lo = x;
    double d = cheb_eval(ch->c, ch->n, x);
    double xn = d > 0 ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi))
      xn = 0.5 * (lo + hi);
    if (fabs(xn - x) <= 4 * DBL_EPSILON)
      return xn;
    x = xn;
    if (hi - lo <= 1e-16)
      break;
  }
  return x;
}

/* A zero of KE in (lo, hi]: lo.ke > 0 >= hi.ke.  Safeguarded Newton on KE;
 * the result is the turning point with ke set to 0. */
static int wp_turn(wp_ctx *c, wp_pt lo, wp_pt hi, wp_pt *out)
{
  double tol = 4 * DBL_EPSILON * fmax(c->p->s_c_rad, 1.0);
  wp_pt best = hi;
  for (int it = 0; it < 200 && hi.sigma - lo.sigma > tol; it++) {
    wp_pt *from = fabs(lo.ke) < fabs(hi.ke) ? &lo : &hi;
    double x = from->k1 < 0 ? from->sigma - from->ke / from->k1 : NAN;
    if (!(x > lo.sigma && x < hi.sigma))
      x = 0.5 * (lo.sigma + hi.sigma);
    wp_pt q;
    if (wp_point(c, x, &q))
      return -1;
    if (fabs(q.ke) <= fabs(best.ke))
      best = q;
    if (q.ke > 0)
      lo = q;
    else
      hi = q;
    if (fabs(q.ke) == 0)
      break;
  }
  if (fabs(lo.ke) < fabs(best.ke))
    best = lo;
  *out = best;
  out->ke = 0;
  return 0;
}

/* Where dKE/dsigma = 0 in (a, b) with a.k1 < 0 < b.k1: the minimum of KE. */
static int wp_min(wp_ctx *c, wp_pt a, wp_pt b, wp_pt *out)
{
  double tol = 4 * DBL_EPSILON * fmax(c->p->s_c_rad, 1.0);
  wp_pt q = a;
  for (int it = 0; it < 200 && b.sigma - a.sigma > tol; it++) {
    double x = q.k2 > 0 ? q.sigma - q.k1 / q.k2 : NAN;
    if (!(x > a.sigma && x < b.sigma))
      x = 0.5 * (a.sigma + b.sigma);
    if (wp_point(c, x, &q))
      return -1;
    if (q.k1 < 0)
      a = q;
    else
      b = q;
    if (q.ke <= 0)
      break; /* a zero is certain already */
  }
  *out = q;
  return 0;
}

static aq_status wp_fail(aq_error *err, const aq_path *p, double s)
{
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "path evaluation failed at s = %.9g rad", s);
}

aq_status aq_quad_leg(aq_quad *st, const aq_path *p, double a,
                        aq_motion *m, double dt, double *used, aq_leg_end *end,
                        aq_leg_stats *S, aq_error *err)
{
  wp_ctx c = {.st = st, .p = p, .a = a, .mt = p->mass_kg, .g = p->g_mps2,
              .stats = S};
  const double sc = p->s_c_rad;
  const int n = st->wp_nodes;
  double t = 0;
  for (size_t nev = 0;; nev++) {
    if (nev > QUAD_MAX_PANELS)
      return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                          "no progress after %zu panels", nev);
    double rem = dt - t;
    if (rem <= 0) {
      *used = dt;
      *end = AQ_LEG_TIME;
      return AQ_OK;
    }
    c.sa = m->s;
    c.dir = m->dir;
    c.ke_a = m->ke_j > 0 ? m->ke_j : 0;
    c.xa = m->x_m;
    c.ya = m->y_m;
    wp_pt P0;
    if (wp_point(&c, 0, &P0))
      return wp_fail(err, p, m->s);
    c.xa = P0.x; /* the energy reference is the path itself */
    c.ya = P0.y;
    P0.ke = c.ke_a;
    if (c.ke_a <= 0) {
      double kf = c.dir * P0.k1; /* dKE/ds */
      int nd = kf > 0 ? 1 : (kf < 0 ? -1 : 0);
      m->ke_j = 0;
      if (m->s <= 0 && nd <= 0) {
        *used = t;
        *end = AQ_LEG_REST;
        return AQ_OK;
      }
      if (nd == 0) { /* static equilibrium at s > 0 (measure zero) */
        *used = dt;
        *end = AQ_LEG_TIME;
        return AQ_OK;
      }
      if (nd != m->dir) {
        m->dir = nd;
        if (m->s > 0)
          S->reversals++;
      }
      c.dir = nd;
      P0.k1 = fabs(kf);
    }
    double smax = c.dir > 0 ? sc - m->s : m->s;
    if (smax <= 0) {
      *used = t;
      *end = c.dir > 0 ? AQ_LEG_COLLAPSE : AQ_LEG_IMPACT;
      return AQ_OK;
    }
    double v = sqrt(2 * c.ke_a / P0.m), acc = P0.k1 / P0.m;
    double reach = v * rem + 0.5 * fmax(acc, 0) * rem * rem;
    double L = fmin(WP_REACH_MARGIN * reach, WP_PANEL_FRAC * sc);
    if (!(L > 0))
      L = WP_PANEL_FRAC * sc;

    int kind = 0; /* panel end: 0 interior, 1 turning point, 2 s = 0 or s_c */
    wp_pt PB;
    wp_map mp;
    wp_cheb ch;
    double g[WP_MAX_NODES];
    wp_kes ks = {0};
    double tp_L = -1; /* a turning point moved to where the series' KE vanishes */
    int tp_done = 0;
    wp_panel prev = {0};
    int have_prev = 0;
    for (int halv = 0;; halv++) {
      kind = 0;
      if (L >= smax) {
        L = smax;
        kind = 2;
      }
      if (wp_point(&c, L = tp_L > 0 ? tp_L : L, &PB))
        return wp_fail(err, p, m->s + c.dir * L);
      if (tp_L > 0) {
        PB.ke = 0;
        kind = 1;
        tp_L = -1;
        tp_done = 1;
      } else if (PB.ke <= 0) {
        if (wp_turn(&c, P0, PB, &PB))
          return wp_fail(err, p, m->s);
        L = PB.sigma;
        kind = 1;
      } else if (P0.k1 < 0 && PB.k1 > 0) {
        wp_pt Pm;
        if (wp_min(&c, P0, PB, &Pm))
          return wp_fail(err, p, m->s);
        if (Pm.ke <= 0) {
          if (wp_turn(&c, P0, Pm, &PB))
            return wp_fail(err, p, m->s);
          L = PB.sigma;
          kind = 1;
        } else if (Pm.ke < WP_NEAR_MIN_FRAC * fmin(c.ke_a, PB.ke) &&
                   Pm.sigma > 0 && Pm.sigma < L) {
          /* a near-zero minimum of KE (a saddle of the potential): end
           * the panel there, so that it sits at an end of two panels */
          L = Pm.sigma;
          PB = Pm;
          kind = 0;
        }
      }
      if (!(L > 0)) { /* a turning point at the start itself */
        PB = P0;
        PB.ke = 0;
        kind = 1;
        ch.total = 0;
        break;
      }
      double za = c.ke_a <= 0 ? 0 : zero_ahead(c.ke_a, -P0.k1, P0.k2);
      double zb = kind == 1 ? 0 : zero_ahead(PB.ke, PB.k1, PB.k2);
      map_init(&mp, L, za, zb);
      if (mp.kind == 0)
        map_near_min(&mp, c.ke_a, P0.k1, P0.k2, PB.ke, PB.k1, PB.k2);
      int redo = 0;
      double noise = 0; /* largest relative round-off of KE at the nodes */
      double fk[WP_MAX_NODES], kd[WP_MAX_NODES], sgs[WP_MAX_NODES],
          mj[WP_MAX_NODES], jb[WP_MAX_NODES];
      for (int j = 0; j < n; j++) {
        double psi = st->ccos.cs[1][j], jac;
        double sg = map_sigma(&mp, psi, &jac);
        wp_pt q;
        if (wp_point(&c, sg, &q))
          return wp_fail(err, p, m->s + c.dir * sg);
        fk[j] = q.k1 * jac; /* dKE/dpsi */
        if (q.ke <= 0) {
          if (kind != 1 && sg > 0 && c.ke_a > 0) {
            /* a zero the end tests did not see: end the panel there */
            if (wp_turn(&c, P0, q, &PB))
              return wp_fail(err, p, m->s);
            L = PB.sigma;
            redo = 1;
            break;
          }
          /* round-off at a node closer to a zero of KE than the zero's
           * own precision: use the linear model about the nearer zero */
          double kb = fabs(PB.k1) * (L - sg), ka = fabs(P0.k1) * sg;
          q.ke = kind == 1 && (c.ke_a > 0 || L - sg < sg) ? kb : ka;
          if (!(q.ke > 0))
            q.ke = DBL_MIN;
        }
        kd[j] = q.ke;
        sgs[j] = sg;
        mj[j] = q.m;
        jb[j] = fabs(jac);
        /* round-off of KE at this node (eq. (19) as computed) */
        double dke = DBL_EPSILON * (c.ke_a + c.mt * (fabs(c.a) * (fabs(q.x) + fabs(c.xa)) +
                                                    c.g * (fabs(q.y) + fabs(c.ya))));
        noise = fmax(noise, dke / q.ke);
      }
      if (redo) {
        halv--;
        continue;
      }
      /* KE at the nodes.  Eq. (19) subtracts x(s1) from x(s), each known to
       * ~1e-15 m only (the tables carry the round-off of absolute centroid
       * positions), while the slopes dx/ds, dy/ds are known to round-off
       * relative to themselves; in a KE built from millimetre increments
       * that is a relative error ~1e-13, a steady bias of the time
       * integral (measured: 6e-15 rad of drift in 0.2 s of a constant
       * pulse).  So KE is the start's KE plus the integral of
       * dKE/dsigma = -m_T (a x' + g y') along the panel, exactly as a
       * Chebyshev series on the same nodes (no more path evaluations).
       * At a turning-point end the series' KE(L) differs from 0 by the
       * location's round-off; that mismatch is spread along the panel.
       * Eq. (19) as it stands is kept where the series is not resolved. */
      ks.n = n;
      ks.ke_a = c.ke_a;
      ks.L = L;
      memcpy(ks.fk, fk, (size_t)n * sizeof *fk);
      double kscale; /* the KE scale of the panel, J */
      {
        double tot = 0, c0 = 0, c1 = 0, c2 = 0;
        for (int i = 0; i < n; i++) {
          tot += st->ccos.iw[i] * fk[i];
          c0 += fk[i];
          c1 += fk[i] * st->ccos.cs[n - 1][i];
          c2 += fk[i] * st->ccos.cs[n - 2][i];
        }
        ks.total = tot;
        ks.mis = kind == 1 ? c.ke_a + tot : 0;
        kscale = c.ke_a + fabs(tot) + fabs(2.0 * c0 / n);
        double ftail = 2.0 * (fabs(c1) + fabs(c2)) / n;
        ks.on = kscale > 0 && ftail <= WP_KES_TAIL * kscale &&
                fabs(ks.mis) <= WP_KES_MISMATCH * kscale;
      }
      if (ks.on && kind == 1 && !tp_done && PB.k1 < 0 &&
          fabs(ks.mis) > WP_TP_MISMATCH_ULPS * DBL_EPSILON * kscale) {
        /* the series puts the turning point mis / |dKE/dsigma| further:
         * move the end there (once), so that the turning points follow
         * the same KE as the panels (else each one resets the energy to
         * eq. (19)'s, a drift over many cycles) */
        double Ln = L + ks.mis / fabs(PB.k1);
        if (Ln > 0 && Ln < smax) {
          tp_L = Ln;
          halv--;
          continue;
        }
      }
      for (int j = 0; j < n; j++) {
        double ke = kd[j];
        if (ks.on) {
          double kj = c.ke_a - ks.mis * (sgs[j] / L);
          for (int i = 0; i < n; i++)
            kj += st->ccos.iq[j][i] * fk[i];
          if (kj > 0)
            ke = kj;
        }
        g[j] = sqrt(0.5 * mj[j]) / sqrt(ke) * jb[j];
      }
      cheb_build(&ch, &st->ccos, g, n);
      /* the tail cannot fall below the round-off of the integrand (half
       * that of KE), amplified by the transform: accept it there */
      if (ch.tail <= fmax(st->wp_tol, WP_NOISE_GAIN * noise) ||
          !(L > WP_MIN_PANEL_FRAC * sc) || halv > 80)
        break;
      if (have_prev && !(ch.tail < WP_STALL_GAIN * prev.ch.tail)) {
        /* halving no longer pays: the tail is round-off in KE near a zero
         * (x, y differences), not truncation.  Keep the longer panel. */
        L = prev.L;
        kind = prev.kind;
        PB = prev.PB;
        mp = prev.mp;
        ch = prev.ch;
        ks = prev.ks;
        break;
      }
      prev = (wp_panel){L, kind, PB, mp, ch, ks};
      have_prev = 1;
      L *= 0.5;
    }
    if (!isfinite(ch.total))
      return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                          "time integral not finite at s = %.9g rad", m->s);

    if (ch.total >= rem) {
      S->substeps++;
      double psi = cheb_solve(&ch, rem), jac;
      double sg = map_sigma(&mp, psi, &jac);
      wp_pt E;
      if (wp_point(&c, sg, &E))
        return wp_fail(err, p, m->s + c.dir * sg);
      if (ks.on) {
        double ke = kes_at(&ks, &st->ccos, psi, sg);
        E.ke = ke > 0 ? ke : 0;
      }
      m->s = E.s;
      m->ke_j = E.ke > 0 ? E.ke : 0;
      m->x_m = E.x;
      m->y_m = E.y;
      if (m->s > S->peak_s)
        S->peak_s = m->s;
      *used = dt;
      *end = AQ_LEG_TIME;
      return AQ_OK;
    }
    t += ch.total;
    S->substeps++;
    if (ks.on && kind != 1 && L > 0) {
      double ke = ks.ke_a + ks.total;
      PB.ke = ke > 0 ? ke : 0;
    }
    if (PB.ke > S->peak_ke_j) /* a point actually reached */
      S->peak_ke_j = PB.ke;
    m->s = PB.s;
    m->x_m = PB.x;
    m->y_m = PB.y;
    if (m->s > S->peak_s)
      S->peak_s = m->s;
    if (kind == 1) {
      m->ke_j = 0;
      m->dir = -m->dir;
      S->reversals++;
      if (S->turn)
        S->turn(S->turn_ctx, t, m->s, m->x_m, m->y_m);
      continue;
    }
    m->ke_j = PB.ke > 0 ? PB.ke : 0;
    if (kind == 2) {
      *used = t;
      if (c.dir > 0) {
        m->s = sc;
        *end = AQ_LEG_COLLAPSE;
      } else {
        m->s = 0;
        *end = AQ_LEG_IMPACT;
      }
      return AQ_OK;
    }
  }
}

aq_quad *aq_quad_alloc(aq_error *err)
{
  aq_quad *w = calloc(1, sizeof *w);
  if (!w) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "workpath", "out of memory");
    return NULL;
  }
  w->wp_tol = WP_DEFAULT_TOL;
  aq_quad_set_nodes(w, WP_DEFAULT_NODES);
  return w;
}

void aq_quad_free(aq_quad *w) { free(w); }

void aq_quad_set_tol(aq_quad *w, double tol)
{
  if (isfinite(tol) && tol > 0)
    w->wp_tol = tol;
}

void aq_quad_set_nodes(aq_quad *w, int n)
{
  if (n >= 4 && n <= WP_MAX_NODES) {
    w->wp_nodes = n;
    cheb_cos_init(&w->ccos, n);
    cheb_quad_init(&w->ccos);
  }
}

void aq_quad_set_exact(aq_quad *w, int exact) { w->exact = exact != 0; }

void aq_quad_reset(aq_quad *w) { w->cache_p = NULL; }
