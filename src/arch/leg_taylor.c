/* leg_taylor.c: the default work-path leg (see leg.h, and eom.h for the
 * leg contract): time-Taylor series of s(t) on the path's polynomial
 * pieces (path.h aq_path_piece: for an arch, Chebyshev fits of the exact
 * kinematics, workpath.c).
 *
 * Within one piece the work term
 *     P(s) = dKE/ds = -m_T (a_g dx/ds + g dy/ds)     (eq. (19) per
 *                                            docs/method.md sec. 5, d/ds)
 * and the generalised mass M(s) (docs/method.md sec. 4) are polynomials, so the
 * kinetic energy KE(s) = KE0 + int_s0^s P is a polynomial too.  The energy
 * balance 1/2 M(s) sdot^2 = KE(s), differentiated in time, gives
 *     s'' = F'(s),   F = KE / M                                  (TL)
 * (the Lagrangian equation of motion of eom.h with sdot^2 = 2 KE / M).
 * With KE = C - m_T (a xr + g yr) (xr, yr: x, y from the piece's start; C
 * is constant along the piece within a leg) the right side is
 *     F' = C R' - m_T (a (xr R)' + g (yr R)'),   R = 1/M,
 * a combination of the piece's three fitted functions gc, ga, gb (path.h),
 * so a sub-step from (s0, v0) takes C = 1/2 M(s0) v0^2 + m_T (a xr(s0) +
 * g yr(s0)), combines the three and shifts the one polynomial to s0:
 * G(u) = F'(s0 + u) as a power series in u, with no division.  (Pieces
 * without them, has_g = 0: shift P and M, integrate P into KE, divide by M
 * and differentiate.)  The series of s(t) - s0 = sum_k c_k t^k follows
 * coefficient by coefficient from (TL):
 *     c_{k+2} = [G(u(t))]_k / ((k+1)(k+2)),
 * the composition G(u(t)) built from the powers of u(t), each coefficient
 * needing only c_1..c_{k+1}.  The order grows until the last two terms at
 * the wanted step (the time left in the record step) are below the
 * tolerance relative to the sub-step's motion; past TL_MAX_ORDER the step
 * is shortened instead.
 *
 * s(t) is smooth through turning points, so they need no special handling
 * (one is located, by safeguarded Newton on sdot, only for the peaks, the
 * count and the history).  Crossings of the piece's ends are roots of the
 * series, located by safeguarded Newton: s = 0 closing is an impact, s = s_c
 * opening is collapse, any other end continues on the next piece with the
 * same s and sdot.  Gravity g is the leg's parameter (tl_build,
 * tl_accel0), read from the path once per leg.
 */
#include "leg.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#define TL_MAX_ORDER 20                      /* s(t) series order at most */
enum { TL_MIN_ORDER = 4 };                   /* tail test from this order */
/* The last two terms bound the truncated tail loosely: the next term is
 * typically 0.02-0.07 of the last (geometric mean of the ratio at
 * acceptance on the bench's records), so 1e-14 leaves a tail of about one
 * unit round-off of the sub-step's motion.  (1.1e-16 costs 15-25 % more
 * and moves peaks and collapse times by < 3e-13 relative.) */
static const double TL_TOL_DEFAULT = 1e-14; /* last two terms / sub-step motion */
static const double TL_SHRINK = 0.5;         /* step from the tail's own estimate, times this */
static const int TL_ROOT_ITER = 60;          /* safeguarded Newton iterations at most */
static const double TL_ROOT_EPS = 8 * DBL_EPSILON; /* root located: last Newton step / sub-step */
static const size_t TL_MAX_SUBSTEPS = 2000000; /* per leg; beyond: no progress */
static const int TL_MAX_HALVINGS = 60;       /* of a sub-step with two turning points */

/* M's coefficients times k! (the shift's weights, tl_build; the work
 * term's are scaled after their sum, where a dx and g dy nearly cancel). */
typedef struct {
  double m[AQ_PIECE_MAX_DEG + 1];
} tl_fact;

struct aq_taylor {
  double tol;
  const aq_path *p; /* owner of the cached piece, or NULL */
  aq_path_piece pc;
  tl_fact pf;       /* pc's weights */
  /* M and x - x(s_lo), y - y(s_lo) at the last leg's end (on the cached
   * piece): the next leg starts there */
  double s_end, m_end, xr_end, yr_end;
};

aq_taylor *aq_taylor_alloc(aq_error *err)
{
  aq_taylor *w = calloc(1, sizeof *w);
  if (!w) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "workpath", "out of memory");
    return NULL;
  }
  w->tol = TL_TOL_DEFAULT;
  w->s_end = NAN;
  return w;
}

void aq_taylor_free(aq_taylor *w) { free(w); }

void aq_taylor_set_tol(aq_taylor *w, double tol)
{
  if (isfinite(tol) && tol > 0)
    w->tol = tol;
}

void aq_taylor_reset(aq_taylor *w)
{
  w->p = NULL;
  w->s_end = NAN;
}

/* ------------------------------------------------------------------ */

/* Function c of piece pc (one of its coefficient arrays, degree n) at s. */
static double piece_val(const aq_path_piece *pc, const double *c, int n, double s)
{
  double t = (s - pc->s_ref) * pc->iscale, r = c[n];
  for (int k = n - 1; k >= 0; k--)
    r = r * t + c[k];
  return r;
}

/* M (degree deg) and the work term's slopes at s. */
#define PIECE_M(pc, s) piece_val((pc), (pc)->m, (pc)->deg, (s))
#define PIECE_DX(pc, s) piece_val((pc), (pc)->dx, (pc)->deg, (s))
#define PIECE_DY(pc, s) piece_val((pc), (pc)->dy, (pc)->deg, (s))
/* x, y: degree deg + 1 */
#define PIECE_X(pc, s) piece_val((pc), (pc)->x, (pc)->deg + 1, (s))
#define PIECE_Y(pc, s) piece_val((pc), (pc)->y, (pc)->deg + 1, (s))

/* The degree of an arch's pieces (workpath_piece.c): the per-step polynomial
 * work is compiled for it with constant loop bounds (unrolled); any other
 * degree takes the same code with the bound read from the piece. */
enum { TL_DEG_ARCH = 14 };

/* M, x and y at s in one pass (three independent Horner chains, each
 * rounded as piece_val rounds it); n = pc->deg. */
static inline __attribute__((always_inline)) void
piece_mxy_n(const aq_path_piece *pc, const int n, double s, double *mv,
            double *xv, double *yv)
{
  double t = (s - pc->s_ref) * pc->iscale;
  double rm = pc->m[n], rx = pc->x[n + 1] * t + pc->x[n],
         ry = pc->y[n + 1] * t + pc->y[n];
#pragma GCC unroll 20
  for (int k = n - 1; k >= 0; k--) {
    rm = rm * t + pc->m[k];
    rx = rx * t + pc->x[k];
    ry = ry * t + pc->y[k];
  }
  *mv = rm;
  *xv = rx;
  *yv = ry;
}

static void piece_mxy(const aq_path_piece *pc, double s, double *mv, double *xv,
                      double *yv)
{
  if (pc->deg == TL_DEG_ARCH)
    piece_mxy_n(pc, TL_DEG_ARCH, s, mv, xv, yv);
  else
    piece_mxy_n(pc, pc->deg, s, mv, xv, yv);
}

/* 1 / k for the integral of P (no division in the loop). */
static const double TL_INV[TL_MAX_ORDER + 1] = {
    0,        1,        1.0 / 2,  1.0 / 3,  1.0 / 4,  1.0 / 5,  1.0 / 6,
    1.0 / 7,  1.0 / 8,  1.0 / 9,  1.0 / 10, 1.0 / 11, 1.0 / 12, 1.0 / 13,
    1.0 / 14, 1.0 / 15, 1.0 / 16, 1.0 / 17, 1.0 / 18, 1.0 / 19, 1.0 / 20};

/* sum_{k=0..n} q_k t^k. */
static double horner(const double *q, int n, double t)
{
  double r = q[n];
  for (int k = n - 1; k >= 0; k--)
    r = r * t + q[k];
  return r;
}

/* q(t) and q'(t) in one pass (two interleaved chains). */
static double horner_d(const double *q, int n, double t, double *d)
{
  double r = q[n], r1 = 0;
  for (int k = n - 1; k >= 0; k--) {
    r1 = r1 * t + r;
    r = r * t + q[k];
  }
  *d = r1;
  return r;
}

/* A root of q (degree n) in (ta, tb], where fa = q(ta) and fb = q(tb)
 * differ in sign or fb = 0, from the guess t0: Newton, kept inside the
 * shrinking bracket. */
static double poly_root(const double *q, int n, double ta, double tb,
                        double fa, double fb, double t0)
{
  if (fb == 0)
    return tb;
  double lo = ta, hi = tb;
  int neg_lo = fa < 0;
  double t = t0;
  if (!(t > lo && t < hi))
    t = fa != fb ? ta + (tb - ta) * fa / (fa - fb) : 0.5 * (ta + tb);
  if (!(t > lo && t < hi))
    t = 0.5 * (lo + hi);
  for (int it = 0; it < TL_ROOT_ITER; it++) {
    double d, f = horner_d(q, n, t, &d);
    if (f == 0)
      return t;
    if ((f < 0) == neg_lo)
      lo = t;
    else
      hi = t;
    double tn = d != 0 ? t - f / d : NAN;
    if (!(tn > lo && tn < hi))
      tn = 0.5 * (lo + hi);
    if (fabs(tn - t) <= TL_ROOT_EPS * tb || hi - lo <= TL_ROOT_EPS * tb)
      return tn;
    t = tn;
  }
  return hi;
}

/* The smallest positive root of b t + a t^2 = r (a quadratic model), or
 * NAN. */
static double quad_guess(double a, double b, double r)
{
  double disc = b * b + 4 * a * r;
  if (!(disc >= 0))
    return NAN;
  double sq = sqrt(disc);
  double t1 = 2 * r / (b + (b >= 0 ? sq : -sq)); /* stable form */
  double t2 = a != 0 ? (-b + (b >= 0 ? -sq : sq)) / (2 * a) : NAN;
  if (t1 > 0 && (!(t2 > 0) || t1 < t2))
    return t1;
  return t2 > 0 ? t2 : NAN;
}

/* sum_i w_{j+i} q_i for the work term (wp) and M (wm), i = 0..d-j: the
 * Taylor coefficient j of a shifted polynomial (tl_build), two chains. */
static void tl_shift_j(const double *wp, const double *wm, const double *q,
                       int d, int j, double *pj, double *mj)
{
  double sp0 = 0, sp1 = 0, sm0 = 0, sm1 = 0;
  const double *a = wp + j, *b = wm + j;
  int n = d - j, i = 0;
  for (; i < n; i += 2) {
    sp0 += a[i] * q[i];
    sm0 += b[i] * q[i];
    sp1 += a[i + 1] * q[i + 1];
    sm1 += b[i + 1] * q[i + 1];
  }
  if (i == n) {
    sp0 += a[i] * q[i];
    sm0 += b[i] * q[i];
  }
  *pj = sp0 + sp1;
  *mj = sm0 + sm1;
}

/* The series of one sub-step: s(t) = s0 + sum_{k=1..n} c_k t^k. */
typedef struct {
  int n;
  double c[TL_MAX_ORDER + 1];
} tl_series;

/* k! */
static const double TL_FACT[AQ_PIECE_MAX_DEG + 1] = {
    1, 1, 2, 6, 24, 120, 720, 5040, 40320, 362880, 3628800, 39916800,
    479001600, 6227020800.0, 87178291200.0, 1307674368000.0,
    20922789888000.0, 355687428096000.0, 6402373705728000.0,
    121645100408832000.0, 2432902008176640000.0};

static void tl_fact_make(const aq_path_piece *pc, tl_fact *pf)
{
  for (int k = 0; k <= pc->deg; k++)
    pf->m[k] = pc->m[k] * TL_FACT[k];
}

/* sum_i w_{j+i} q_i, i = 0..d-j (tl_shift_j for one polynomial). */
static inline __attribute__((always_inline)) double
tl_shift1(const double *w, const double *q, int d, int j)
{
  double s0 = 0, s1 = 0;
  const double *a = w + j;
  int n = d - j, i = 0;
#pragma GCC unroll 20
  for (; i < n; i += 2) {
    s0 += a[i] * q[i];
    s1 += a[i + 1] * q[i + 1];
  }
  if (i == n)
    s0 += a[i] * q[i];
  return s0 + s1;
}

/* tl_comp and tl_build: GCC cannot see that tl_build's switch reaches case
 * k only after cases 0..k-1 filled rows 0..k-1 of U, and warns that they
 * may be read uninitialized. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

/* Coefficient k of G(u(t)), u(t) = sum_{i>=1} c_i t^i, from the powers of
 * u: U[j][k] is coefficient k of u(t)^j (U[1][k] = c_k, U[j][k] = sum_i
 * c_i U[j-1][k-i]); row k of U is filled here (c_1..c_k are known).
 * Inlined with k a constant (tl_build's switch), the loops unroll into
 * straight-line code with no branch. */
static inline __attribute__((always_inline)) double
tl_comp(const int k, double U[][TL_MAX_ORDER + 1], const double *c,
        const double *G)
{
  U[1][k] = c[k];
  double comp = k == 0 ? G[0] : G[1] * c[k];
#pragma GCC unroll 20
  for (int j = 2; j <= k; j++) {
    const double *up = &U[j - 1][k - 1]; /* U[j-1][k-i] = up[1 - i] */
    double sum = 0;
#pragma GCC unroll 20
    for (int i = 1; i <= k - j + 1; i++)
      sum += c[i] * up[1 - i];
    U[j][k] = sum;
    comp += G[j] * sum;
  }
  return comp;
}

/* Build the series from (s0, v0) on piece pc under ground acceleration a
 * for a wanted step *h; *h is shortened when TL_MAX_ORDER cannot reach the
 * tolerance there.  e0: with the acceleration's pieces (pc->has_g), the
 * energy C of path.h, KE(s0) + m_T (a xr(s0) + g yr(s0)) (J). */
static inline __attribute__((always_inline)) void
tl_build_d(const aq_path_piece *pc, const int d, const tl_fact *pf, double mt,
           double g, double a, double s0, double v0, double e0, double tol,
           double *h, tl_series *ts)
{
  enum { N = TL_MAX_ORDER, D = AQ_PIECE_MAX_DEG };
  const int has_g = pc->has_g;
  /* The piece's polynomials shifted to s0, in powers of u = s - s0 (Taylor
   * coefficients at t0 of the piece's polynomials in t, t0 in [0, 1]):
   *   [u^j] = iscale^j / j! sum_i (c_{j+i} (j+i)!) (t0^i / i!)
   * (independent sums, not a chain of Horner shifts, and only as far as
   * the order needs).  With has_g one polynomial, s'' = G(u) (path.h);
   * else the work term P and M, KE = KE0 + int P, and G = (KE / M)'. */
  const double t0 = (s0 - pc->s_ref) * pc->iscale;
  double wp[D + 1], q[D + 1];
  const double *wm = pf->m;
  double qi = 1;
  q[0] = 1;
  if (has_g) {
    wp[0] = e0 * pc->gc[0] - mt * (a * pc->ga[0] + g * pc->gb[0]); /* s'' */
    for (int k = 1; k <= d; k++) {
      qi *= t0 * TL_INV[k];
      q[k] = qi;
      wp[k] = (e0 * pc->gc[k] - mt * (a * pc->ga[k] + g * pc->gb[k])) * TL_FACT[k];
    }
  } else {
    wp[0] = -mt * (a * pc->dx[0] + g * pc->dy[0]); /* P(s) */
    for (int k = 1; k <= d; k++) {
      qi *= t0 * TL_INV[k];
      q[k] = qi;
      wp[k] = -mt * (a * pc->dx[k] + g * pc->dy[k]) * TL_FACT[k];
    }
  }
  /* coefficients taken as the order needs them (the series usually stops
   * near order 10, before the piece's degree) */
  double mm[D + 2], sj = 1; /* sj = iscale^j / j! for the next j */
  double K[N + 1], F[N + 1], G[N];
  double pj, mj, im0 = 0;
  int jm = 1; /* P and M known up to u^(jm - 1) */
  if (!has_g) {
    tl_shift_j(wp, wm, q, d, 0, &pj, &mj);
    mm[0] = mj;
    K[1] = pj;
    K[0] = 0.5 * mm[0] * v0 * v0; /* KE0 */
    im0 = 1.0 / mm[0];
    F[0] = K[0] * im0;
  }
  /* U[j][k]: coefficient k of u(t)^j, u(t) = s(t) - s0 */
  double U[N + 1][N + 1];
  double *c = ts->c;
  c[0] = 0;
  c[1] = v0;
  const double hh = *h;
  double hn1 = hh, hn = hh; /* h^(n-1), h^n for the order n reached */
  int n = 1;
  double scale = 0;
  for (int k = 0; k + 2 <= N; k++) {
    if (has_g) {
      if (k > 0)
        sj *= pc->iscale * TL_INV[k];
      /* G[k] in the switch below, with k a constant */
    } else {
      /* P's u^k (into K_{k+1}) and M's u^(k+1) */
      if (jm <= k + 1) {
        if (jm <= d) {
          sj *= pc->iscale * TL_INV[jm];
          tl_shift_j(wp, wm, q, d, jm, &pj, &mj);
          K[jm + 1] = pj * sj * TL_INV[jm + 1];
          mm[jm] = mj * sj;
        } else {
          K[jm + 1] = 0;
          mm[jm] = 0;
        }
        jm++;
      }
      /* F_{k+1} = (K_{k+1} - sum_j m_j F_{k+1-j}) / m_0 */
      double f = K[k + 1];
      for (int j = 1, jn = d < k + 1 ? d : k + 1; j <= jn; j++)
        f -= mm[j] * F[k + 1 - j];
      F[k + 1] = f * im0;
      G[k] = (k + 1) * F[k + 1];
    }
    double comp;
    switch (k) { /* tl_comp with k a constant: straight-line code */
#define TL_COMP_CASE(K)                                                        \
  case K:                                                                      \
    if (has_g)                                                                 \
      G[K] = K <= d ? sj * tl_shift1(wp, q, d, K) : 0;                         \
    comp = tl_comp(K, U, c, G);                                                \
    break;
      TL_COMP_CASE(0) TL_COMP_CASE(1) TL_COMP_CASE(2) TL_COMP_CASE(3)
      TL_COMP_CASE(4) TL_COMP_CASE(5) TL_COMP_CASE(6) TL_COMP_CASE(7)
      TL_COMP_CASE(8) TL_COMP_CASE(9) TL_COMP_CASE(10) TL_COMP_CASE(11)
      TL_COMP_CASE(12) TL_COMP_CASE(13) TL_COMP_CASE(14) TL_COMP_CASE(15)
      TL_COMP_CASE(16) TL_COMP_CASE(17)
#undef TL_COMP_CASE
    default:
      if (has_g)
        G[k] = k <= d ? sj * tl_shift1(wp, q, d, k) : 0;
      comp = tl_comp(k, U, c, G);
      break;
    }
    c[k + 2] = comp * TL_INV[k + 1] * TL_INV[k + 2];
    n = k + 2;
    hn1 = hn;
    hn *= hh;
    if (n == 3) /* the sub-step's motion */
      scale = fabs(c[1]) * hh + fabs(c[2]) * hn1 + fabs(c[3]) * hn;
    if (n >= TL_MIN_ORDER &&
        fabs(c[n]) * hn + fabs(c[n - 1]) * hn1 <= tol * scale)
      break;
  }
  if (n == N) {
    /* not converged at *h: the step where the last two terms each reach
     * the tolerance (Jorba and Zou's rule), shrunk for safety */
    double h1 = fabs(c[n]) > 0 ? pow(tol * scale / fabs(c[n]), 1.0 / n) : hh;
    double h2 = fabs(c[n - 1]) > 0 ? pow(tol * scale / fabs(c[n - 1]), 1.0 / (n - 1)) : hh;
    double hn = TL_SHRINK * fmin(h1, h2);
    if (hn < hh)
      *h = hn;
  }
  ts->n = n;
}

static void tl_build(const aq_path_piece *pc, const tl_fact *pf, double mt,
                     double g, double a, double s0, double v0, double e0,
                     double tol, double *h, tl_series *ts)
{
  if (pc->deg == TL_DEG_ARCH)
    tl_build_d(pc, TL_DEG_ARCH, pf, mt, g, a, s0, v0, e0, tol, h, ts);
  else
    tl_build_d(pc, pc->deg, pf, mt, g, a, s0, v0, e0, tol, h, ts);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

static aq_status tl_fail(aq_error *err, const aq_path *p, const char *what,
                         double s)
{
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "workpath: %s at s = %.9g rad", what, s);
}

/* Make w->pc the piece of p holding s for the direction dir. */
static int tl_piece(aq_taylor *w, const aq_path *p, double s, int dir,
                    aq_leg_stats *S)
{
  const aq_path_piece *pc = &w->pc;
  if (w->p == p && s >= pc->s_lo && s <= pc->s_hi &&
      !(dir > 0 && s == pc->s_hi && pc->s_hi < p->s_c_rad) &&
      !(dir <= 0 && s == pc->s_lo && pc->s_lo > 0))
    return 0;
  S->evals++;
  w->s_end = NAN; /* M at the last end was on another piece */
  if (p->piece(p->ctx, s, dir, &w->pc) != 0) {
    w->p = NULL;
    return -1;
  }
  w->p = p;
  tl_fact_make(&w->pc, &w->pf);
  return 0;
}

/* s'' at rest (sdot = 0) on the cached piece: P / M. */
static double tl_accel0(const aq_taylor *w, const aq_path *p, double a, double g,
                        double s)
{
  const aq_path_piece *pc = &w->pc;
  return -p->mass_kg * (a * PIECE_DX(pc, s) + g * PIECE_DY(pc, s)) /
         PIECE_M(pc, s);
}

static int sgn(double x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

aq_status aq_taylor_leg(aq_taylor *w, const aq_path *p, double a, aq_motion *m,
                        double dt, double *used, aq_leg_end *end,
                        aq_leg_stats *S, aq_error *err)
{
  const double sc = p->s_c_rad, g = p->g_mps2;
  double s = m->s < 0 ? 0 : (m->s > sc ? sc : m->s);
  int dir = m->dir >= 0 ? 1 : -1;
  if (tl_piece(w, p, s, dir, S))
    return tl_fail(err, p, "no path piece", s);
  double mass = s == w->s_end ? w->m_end : PIECE_M(&w->pc, s);
  double v = dir * sqrt(2 * fmax(m->ke_j, 0) / mass);
  double t = 0;
  *end = AQ_LEG_TIME;
  if (s <= 0 && v <= 0 && tl_accel0(w, p, a, g, s) <= 0) {
    *used = 0;
    *end = AQ_LEG_REST;
    return AQ_OK;
  }
  if (s >= sc && v >= 0) {
    *used = 0;
    *end = AQ_LEG_COLLAPSE;
    return AQ_OK;
  }
  for (size_t nst = 0; t < dt; nst++) {
    if (nst > TL_MAX_SUBSTEPS)
      return tl_fail(err, p, "no progress", s);
    /* the piece ahead: by the velocity, or the acceleration at rest */
    int d = sgn(v);
    if (d == 0)
      d = sgn(tl_accel0(w, p, a, g, s));
    if (tl_piece(w, p, s, d, S))
      return tl_fail(err, p, "no path piece", s);
    const aq_path_piece *pc = &w->pc;
    if ((d > 0 && s >= pc->s_hi && s < sc) || (d < 0 && s <= pc->s_lo && s > 0))
      return tl_fail(err, p, "the path piece ahead ends where it starts", s);
    double h = dt - t;
    double e0 = 0; /* path.h C, for pieces with the acceleration's pieces */
    if (pc->has_g) {
      double ms, xr, yr;
      if (s == w->s_end) {
        ms = w->m_end;
        xr = w->xr_end;
        yr = w->yr_end;
      } else {
        piece_mxy(pc, s, &ms, &xr, &yr);
        xr -= pc->x[0];
        yr -= pc->y[0];
      }
      e0 = 0.5 * ms * v * v + p->mass_kg * (a * xr + g * yr);
    }
    tl_series ts;
    tl_build(pc, &w->pf, p->mass_kg, g, a, s, v, e0, w->tol, &h, &ts);
    S->substeps++;
    const int n = ts.n;
    double dq[TL_MAX_ORDER + 1]; /* sdot(t) */
    for (int k = 0; k < n; k++)
      dq[k] = (k + 1) * ts.c[k + 1];
    /* the start's direction (at rest: that of s''), and at most one
     * turning point within the sub-step (else halve it) */
    int s0 = v != 0 ? sgn(v) : sgn(ts.c[2]);
    double vh, uh = horner_d(ts.c, n, h, &vh); /* s - s0 and sdot at h */
    int halved = 0;
    for (int it = 0; it < TL_MAX_HALVINGS && s0 != 0 && sgn(vh) == s0; it++) {
      double vm = horner(dq, n - 1, 0.5 * h);
      if (sgn(vm) != -s0)
        break;
      h *= 0.5;
      vh = vm;
      halved = 1;
    }
    if (halved)
      uh = horner(ts.c, n, h);
    double seg[3] = {0, h, h};
    int nseg = 1, turn = 0;
    if (s0 != 0 && sgn(vh) == -s0) {
      /* a turning point: located only when it may set a peak, cross a
       * piece end before it (bound: sum |c_k| h^k), end the sub-step
       * beyond a piece end (the crossing after it needs the split), or be
       * sampled */
      double bound = 0, tk = h;
      for (int k = 1; k <= n; k++, tk *= h)
        bound += fabs(ts.c[k]) * tk;
      double sh = s + uh;
      turn = 1;
      if (S->turn || (s0 > 0 && (s + bound > S->peak_s || s + bound > pc->s_hi)) ||
          (s0 < 0 && s - bound < pc->s_lo) || sh > pc->s_hi || sh < pc->s_lo) {
        seg[1] = poly_root(dq, n - 1, 0, h, dq[0], vh,
                           ts.c[2] != 0 ? -ts.c[1] / (2 * ts.c[2]) : NAN);
        nseg = 2;
        turn = 2;
      }
    }
    /* the first crossing of a piece end, segment by segment (s monotone in
     * each) */
    int cross = 0; /* +1 through s_hi, -1 through s_lo */
    double tx = h;
    double ua = 0; /* s - s0 at the segment's start */
    for (int k = 0; k < nseg && !cross; k++) {
      double ub = seg[k + 1] == h ? uh : horner(ts.c, n, seg[k + 1]), sb = s + ub;
      if (sb > pc->s_hi)
        cross = 1;
      else if (sb < pc->s_lo)
        cross = -1;
      if (cross) {
        double q[TL_MAX_ORDER + 1];
        for (int i = 0; i <= n; i++)
          q[i] = ts.c[i];
        q[0] = s - (cross > 0 ? pc->s_hi : pc->s_lo);
        tx = poly_root(q, n, seg[k], seg[k + 1], q[0] + ua, q[0] + ub,
                       k == 0 ? quad_guess(ts.c[2], ts.c[1], -q[0]) : NAN);
        if (k == 0 && nseg == 2)
          turn = 0; /* the turning point lies beyond the crossing */
      }
      ua = ub;
    }
    if (turn == 1 && (s > 0 || s + uh > 0)) {
      S->reversals++;
    } else if (turn == 2) {
      double st = s + horner(ts.c, n, seg[1]);
      if (st > 0) {
        S->reversals++;
        if (st > S->peak_s)
          S->peak_s = fmin(st, sc);
        if (S->turn) {
          S->turn(S->turn_ctx, t + seg[1], st, PIECE_X(pc, st),
                  PIECE_Y(pc, st));
        }
      }
    }
    double vn = vh, un = uh;
    if (tx != h)
      un = horner_d(ts.c, n, tx, &vn);
    if (cross > 0) {
      s = pc->s_hi;
    } else if (cross < 0) {
      s = pc->s_lo;
    } else {
      s += un;
      s = s < pc->s_lo ? pc->s_lo : (s > pc->s_hi ? pc->s_hi : s);
    }
    v = vn;
    t = cross || tx < dt - t ? t + tx : dt;
    if (s > S->peak_s)
      S->peak_s = s;
    if (cross > 0 && s >= sc) {
      *end = AQ_LEG_COLLAPSE;
      if (!(v > 0))
        v = 0;
      break;
    }
    if (cross < 0 && s <= 0) {
      *end = AQ_LEG_IMPACT;
      if (!(v < 0))
        v = -0.0;
      break;
    }
  }
  const aq_path_piece *pc = &w->pc;
  *used = *end == AQ_LEG_TIME ? dt : t;
  double mass_end;
  piece_mxy(pc, s, &mass_end, &m->x_m, &m->y_m);
  w->s_end = s;
  w->m_end = mass_end;
  w->xr_end = m->x_m - pc->x[0];
  w->yr_end = m->y_m - pc->y[0];
  m->s = s;
  m->ke_j = 0.5 * mass_end * v * v;
  if (v != 0)
    m->dir = v > 0 ? 1 : -1;
  if (m->ke_j > S->peak_ke_j)
    S->peak_ke_j = m->ke_j;
  return AQ_OK;
}
