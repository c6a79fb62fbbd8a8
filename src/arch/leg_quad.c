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
 * step continues, so several events fit in one step.  The panels' change of
 * variable and the Chebyshev series are in quad_series.c.
 */
#include "leg.h"
#include "quad_series.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { WP_DEFAULT_NODES = 12 };
static const double WP_DEFAULT_TOL = 1e-12;  /* Chebyshev tail / mean, per panel */
static const double WP_PANEL_FRAC = 0.125;   /* longest panel, fraction of s_c */
static const double WP_REACH_MARGIN = 1.3;   /* panel = margin * distance reachable in the step */
static const double WP_NEAR_MIN_FRAC = 0.1;  /* KE minimum this small vs the ends: split there */
static const double WP_NOISE_GAIN = 16;      /* tail floor = this * KE round-off at the nodes */
static const double WP_STALL_GAIN = 0.125;   /* a halving must cut the tail by 8x */
static const double WP_MIN_PANEL_FRAC = 1e-13; /* no halving below this fraction of s_c */
static const double WP_KES_TAIL = 1e-13;     /* dKE/dpsi series tail / KE scale: resolved */
static const double WP_KES_MISMATCH = 1e-9;  /* turning-point mismatch / KE scale: sane */
static const double WP_TP_MISMATCH_ULPS = 32; /* move a turning point when the mismatch exceeds this many ulps of the KE scale */
static const size_t QUAD_MAX_PANELS = 2000000; /* per leg; beyond: no progress, an error */

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

typedef struct {
  double L;
  int kind;
  wp_pt PB;
  wp_map mp;
  wp_cheb ch;
  wp_kes ks;
} wp_panel;

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
      double za = c.ke_a <= 0 ? 0 : aq_quad_zero_ahead(c.ke_a, -P0.k1, P0.k2);
      double zb = kind == 1 ? 0 : aq_quad_zero_ahead(PB.ke, PB.k1, PB.k2);
      aq_quad_map_init(&mp, L, za, zb);
      if (mp.kind == 0)
        aq_quad_map_near_min(&mp, c.ke_a, P0.k1, P0.k2, PB.ke, PB.k1, PB.k2);
      int redo = 0;
      double noise = 0; /* largest relative round-off of KE at the nodes */
      double fk[WP_MAX_NODES], kd[WP_MAX_NODES], sgs[WP_MAX_NODES],
          mj[WP_MAX_NODES], jb[WP_MAX_NODES];
      for (int j = 0; j < n; j++) {
        double psi = st->ccos.cs[1][j], jac;
        double sg = aq_quad_map_sigma(&mp, psi, &jac);
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
      aq_quad_cheb_build(&ch, &st->ccos, g, n);
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
      double psi = aq_quad_cheb_solve(&ch, rem), jac;
      double sg = aq_quad_map_sigma(&mp, psi, &jac);
      wp_pt E;
      if (wp_point(&c, sg, &E))
        return wp_fail(err, p, m->s + c.dir * sg);
      if (ks.on) {
        double ke = aq_quad_kes_at(&ks, &st->ccos, psi, sg);
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
    aq_quad_cheb_cos_init(&w->ccos, n);
    aq_quad_cheb_quad_init(&w->ccos);
  }
}

void aq_quad_set_exact(aq_quad *w, int exact) { w->exact = exact != 0; }

void aq_quad_reset(aq_quad *w) { w->cache_p = NULL; }
