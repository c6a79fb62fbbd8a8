/* workpath.c: the work path of one hinge set (path.h) with its tables.
 *
 * s = q_sign * q >= 0, where q_sign is the sign of q that opens H1 (and, for
 * an admissible set, every hinge).  Along s:
 *   x(s), y(s) = sum_b m_b (c_b(s) - c_b(0)) / m_T        (whole arch, m_T
 *                includes the fixed voussoirs, which do not move)
 *   M(s) = sum_b m_b |dc_b/ds|^2 + I_b (dphi_b/ds)^2        (docs/method.md sec. 4)
 *   lambda(s) = -act_sign (dy/ds) / (dx/ds)                  (virtual work,
 *                docs/method.md sec. 5: sum m_i lambda g dx_i = g sum m_i dy_i)
 *   act_sign = -sign(dx/ds at 0): the inertial force -m a_g pushes along +s
 *                when a_g has the sign act_sign.
 *   s_c: the first s > 0 where dy/ds = 0 (lambda = 0: the unloaded potential
 *        energy peaks, docs/method.md sec. 9), where the four-bar reaches its toggle,
 *        or where a hinge would close again, whichever comes first (located
 *        by bisection to round-off after a scan in steps of SCAN_STEP_RAD).
 *
 * Tables: piecewise quintic Hermite interpolation over [0, s_c] from the
 * exact value, first and second derivative at the breakpoints, of x, y,
 * dx/ds, dy/ds, M and each body's centroid (x, y) and rotation, stored as
 * power-basis coefficients per interval; d2x/ds2 and d2y/ds2 come from the
 * derivative of the dx/ds, dy/ds interpolants (round-off eps/h, not
 * eps/h^2).  The grid starts as TABLE_N0 equal intervals; each is halved
 * until its error against eval_exact, measured where the Hermite error of
 * the values and of the derivatives peaks, is below TABLE_REL_TOL (see
 * refine() for the error measure and the stopping rules).  The grid is thus
 * fine only where the path varies fast (a four-bar near its toggle).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

/* Tabled functions, each from its value, first and second derivative at the
 * nodes.  F_DX, F_DY are dx/ds, dy/ds (from the second and third
 * derivatives), so that d2x/ds2, d2y/ds2 come from a first derivative of an
 * interpolant (round-off eps/h rather than eps/h^2). */
enum { F_X = 0, F_Y, F_DX, F_DY, F_M, F_B0 /* then 3 per body: x, y, phi */, NF = F_B0 + 9 };

#define SCAN_STEP_RAD 5e-4     /* scan for the end of the path */
#define SCAN_MAX_RAD 3.0       /* no mechanism rotates body 1 further than this */
#define TABLE_N0 16            /* initial equal intervals */
#define TABLE_MAX_DEPTH 30     /* halvings of an initial interval at most */
#define TABLE_FLOOR 1e-3       /* error floor of slopes, curvatures: this times their largest value */
#define TABLE_REL_TOL 4e-12    /* target relative error of the tables (round-off floor ~1e-12) */
#define TABLE_STALL 0.5        /* a split must at least halve the error ... */
#define TABLE_ROUNDOFF 1e-8    /* ... unless it is this small already (round-off), times 2^depth */
#define TABLE_T_DERIV 0.2763932 /* (5 - sqrt 5)/10: peak of t^2 (1-t)^2 (1-2t) */
#define TABLE_MAX_INTERVALS 20000 /* at most this many intervals (shipped arches need < 200): a
                                     path that needs more is refused, never tabulated for minutes */
#define S_SLACK_REL 1e-12      /* s within this (relative to s_c) outside [0, s_c] is clamped */

struct aq_workpath {
  aq_path path;
  aq_mech mech;
  const aq_geom *g;
  double g_mps2;
  aq_vec2 c0[3];      /* body centroids at s = 0 as evaluated */
  aq_end end;
  char reason[200];
  char name[16];
  size_t n;           /* table intervals */
  double *bp;         /* n+1 breakpoints, rad */
  double *coef;       /* n * NF * 6 power-basis coefficients in t = (s - bp[i]) / h_i */
  size_t npc;         /* the Taylor leg's pieces (Chebyshev fits) */
  double *pbp;        /* npc+1 breakpoints, rad */
  aq_path_piece *piece; /* npc pieces for path.h */
  size_t pcap;        /* allocated pieces */
  size_t cap;         /* allocated intervals */
  double tab_err;
  double thrust0;     /* max |eccentricity| of the thrust at s = 0 */
  size_t max_n;       /* table intervals and pieces at most (TABLE_MAX_INTERVALS) */
  /* where the tables or the pieces ran out of intervals (build_tables -2):
   * the start of the interval that found none left, rad, and the finest
   * interval so far (its halvings of the first grid, its start, rad) */
  double out_s, fine_s;
  int fine_depth;
};

/* Exact values f[k][0..2] (value, d/ds, d2/ds2) of every tabled function. */
static int exact_f(const aq_workpath *w, double s, double f[NF][3],
                   aq_mech_state *stout)
{
  aq_mech_state st;
  int qs = w->path.q_sign;
  if (aq_mech_eval(&w->mech, (double)qs * s, &st) != 0)
    return -1;
  double mt = w->path.mass_kg;
  double X[4] = {0, 0, 0, 0}, Y[4] = {0, 0, 0, 0}, M[3] = {0, 0, 0};
  for (int b = 0; b < 3; b++) {
    double mb = w->mech.body[b].mass_kg, ib = w->mech.body[b].inertia_kgm2;
    aq_vec2 *c = st.c[b];
    double *p = st.phi[b];
    X[0] += mb * (c[0].x - w->c0[b].x);
    Y[0] += mb * (c[0].y - w->c0[b].y);
    X[1] += mb * c[1].x;
    Y[1] += mb * c[1].y;
    X[2] += mb * c[2].x;
    Y[2] += mb * c[2].y;
    X[3] += mb * c[3].x;
    Y[3] += mb * c[3].y;
    M[0] += mb * (c[1].x * c[1].x + c[1].y * c[1].y) + ib * p[1] * p[1];
    M[1] += 2.0 * (mb * (c[1].x * c[2].x + c[1].y * c[2].y) + ib * p[1] * p[2]);
    M[2] += 2.0 * (mb * (c[2].x * c[2].x + c[2].y * c[2].y + c[1].x * c[3].x +
                         c[1].y * c[3].y) +
                   ib * (p[2] * p[2] + p[1] * p[3]));
    double *bx = f[F_B0 + 3 * b], *by = f[F_B0 + 3 * b + 1], *bp = f[F_B0 + 3 * b + 2];
    bx[0] = c[0].x, bx[1] = qs * c[1].x, bx[2] = c[2].x;
    by[0] = c[0].y, by[1] = qs * c[1].y, by[2] = c[2].y;
    bp[0] = p[0], bp[1] = qs * p[1], bp[2] = p[2];
  }
  f[F_X][0] = X[0] / mt, f[F_X][1] = qs * X[1] / mt, f[F_X][2] = X[2] / mt;
  f[F_Y][0] = Y[0] / mt, f[F_Y][1] = qs * Y[1] / mt, f[F_Y][2] = Y[2] / mt;
  f[F_DX][0] = f[F_X][1], f[F_DX][1] = X[2] / mt, f[F_DX][2] = qs * X[3] / mt;
  f[F_DY][0] = f[F_Y][1], f[F_DY][1] = Y[2] / mt, f[F_DY][2] = qs * Y[3] / mt;
  f[F_M][0] = M[0], f[F_M][1] = qs * M[1], f[F_M][2] = M[2];
  if (stout)
    *stout = st;
  return 0;
}

static void fill_point(const aq_workpath *w, double f[NF][3], aq_path_point *p)
{
  p->x_m = f[F_X][0], p->dx_m = f[F_DX][0], p->d2x_m = f[F_DX][1];
  p->y_m = f[F_Y][0], p->dy_m = f[F_DY][0], p->d2y_m = f[F_DY][1];
  p->mgen_kgm2 = f[F_M][0];
  p->dmgen_kgm2 = f[F_M][1];
  p->lambda = -(double)w->path.act_sign * p->dy_m / p->dx_m;
  p->nbody = 3;
  for (int b = 0; b < 3; b++) {
    p->body[b].mass_kg = w->mech.body[b].mass_kg;
    p->body[b].inertia_kgm2 = w->mech.body[b].inertia_kgm2;
    p->body[b].x_m = f[F_B0 + 3 * b][0];
    p->body[b].dx_m = f[F_B0 + 3 * b][1];
    p->body[b].y_m = f[F_B0 + 3 * b + 1][0];
    p->body[b].dy_m = f[F_B0 + 3 * b + 1][1];
    p->body[b].phi_rad = f[F_B0 + 3 * b + 2][0];
    p->body[b].dphi = f[F_B0 + 3 * b + 2][1];
  }
}

/* s checked and clamped into [0, s_c]; -1 outside. */
static int clamp_s(const aq_workpath *w, double *s)
{
  double sc = w->path.s_c_rad, slack = S_SLACK_REL * sc;
  if (!w->path.admissible || !(*s >= -slack) || !(*s <= sc + slack))
    return -1;
  if (*s < 0)
    *s = 0;
  if (*s > sc)
    *s = sc;
  return 0;
}

static int eval_exact(const void *ctx, double s, aq_path_point *p)
{
  const aq_workpath *w = ctx;
  double f[NF][3];
  if (clamp_s(w, &s) != 0 || exact_f(w, s, f, NULL) != 0)
    return -1;
  fill_point(w, f, p);
  return 0;
}

/* Table: value and first derivative of function k at interval i, local t. */
static void table_f(const aq_workpath *w, size_t i, double t, int k, double out[3])
{
  const double *c = w->coef + (i * NF + (size_t)k) * 6;
  double ih = 1.0 / (w->bp[i + 1] - w->bp[i]);
  out[0] = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
  out[1] = (c[1] + t * (2 * c[2] + t * (3 * c[3] + t * (4 * c[4] + t * 5 * c[5])))) * ih;
  out[2] = 0; /* second derivatives come from the F_DX, F_DY interpolants */
}

static void table_all(const aq_workpath *w, double s, double f[NF][3])
{
  /* the interval holding s: bp[lo] <= s < bp[lo+1] (binary search) */
  size_t lo = 0, hi = w->n;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (s < w->bp[mid])
      hi = mid;
    else
      lo = mid;
  }
  double t = (s - w->bp[lo]) / (w->bp[lo + 1] - w->bp[lo]);
  for (int k = 0; k < NF; k++)
    table_f(w, lo, t, k, f[k]);
}

static int eval_table(const void *ctx, double s, aq_path_point *p)
{
  const aq_workpath *w = ctx;
  double f[NF][3];
  if (clamp_s(w, &s) != 0)
    return -1;
  table_all(w, s, f);
  fill_point(w, f, p);
  return 0;
}

static int eval_piece(const void *ctx, double s, int dir, aq_path_piece *pc)
{
  const aq_workpath *w = ctx;
  if (clamp_s(w, &s) != 0)
    return -1;
  size_t lo = 0, hi = w->npc; /* the piece holding s for dir (binary search) */
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (dir > 0 ? s < w->pbp[mid] : s <= w->pbp[mid])
      hi = mid;
    else
      lo = mid;
  }
  *pc = w->piece[lo];
  return 0;
}

/* x_mono_rad (path.h): the first s where the tabled slope dx/ds, sampled
 * at X_MONO_SAMPLES points per interval, leaves the sign it has at s = 0. */
#define X_MONO_SAMPLES 8
static double x_mono(const aq_workpath *w)
{
  double sgn = 0;
  for (size_t i = 0; i < w->n; i++) {
    const double *c = w->coef + (i * NF + (size_t)F_DX) * 6;
    for (int j = 0; j <= X_MONO_SAMPLES; j++) {
      double t = (double)j / X_MONO_SAMPLES;
      double v = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
      if (sgn == 0)
        sgn = v > 0 ? 1 : (v < 0 ? -1 : 0);
      if (sgn == 0 || !(v * sgn > 0))
        return w->bp[i];
    }
  }
  return w->path.s_c_rad;
}

/* Quintic Hermite on one interval as power-basis coefficients in t. */
static void hermite5(double p0, double d0, double e0, double p1, double d1,
                     double e1, double h, double c[6])
{
  double hd0 = h * d0, hd1 = h * d1, he0 = h * h * e0, he1 = h * h * e1;
  c[0] = p0;
  c[1] = hd0;
  c[2] = 0.5 * he0;
  c[3] = -10 * p0 - 6 * hd0 - 1.5 * he0 + 0.5 * he1 - 4 * hd1 + 10 * p1;
  c[4] = 15 * p0 + 8 * hd0 + 1.5 * he0 - he1 + 7 * hd1 - 15 * p1;
  c[5] = -6 * p0 - 3 * hd0 - 0.5 * he0 + 0.5 * he1 - 3 * hd1 + 6 * p1;
}

typedef double fvals[NF][3];

/* The contract's quantities checked in the tables: (function, derivative),
 * and how their error is measured: relative to the quantity's largest
 * magnitude over the path (x, y), or to its local magnitude plus a floor of
 * TABLE_FLOOR times that (slopes, curvatures), or to M itself (M, dM/ds,
 * the latter with M/s_c as its floor). */
static const int chk[8][2] = {{F_X, 0}, {F_Y, 0}, {F_DX, 0}, {F_DY, 0},
                              {F_DX, 1}, {F_DY, 1}, {F_M, 0}, {F_M, 1}};

typedef struct {
  aq_workpath *w;
  double scale[8]; /* largest magnitudes over the initial nodes */
  double err;      /* largest accepted error */
  int failed;
  int too_many;    /* failed because of w->max_n */
} refine_ctx;

static int append_interval(aq_workpath *w, double s0, const fvals f0, double s1,
                           const fvals f1)
{
  if (w->n == w->cap) {
    size_t cap = w->cap ? 2 * w->cap : 64;
    double *bp = realloc(w->bp, (cap + 1) * sizeof *bp);
    if (!bp)
      return -1;
    w->bp = bp;
    double *coef = realloc(w->coef, cap * NF * 6 * sizeof *coef);
    if (!coef)
      return -1;
    w->coef = coef;
    w->cap = cap;
  }
  double h = s1 - s0;
  for (int k = 0; k < NF; k++)
    hermite5(f0[k][0], f0[k][1], f0[k][2], f1[k][0], f1[k][1], f1[k][2], h,
             w->coef + (w->n * NF + (size_t)k) * 6);
  w->bp[w->n] = s0;
  w->bp[w->n + 1] = s1;
  w->n++;
  return 0;
}

/* Error of the Hermite interpolant on [s0, s1] (coefficients at slot
 * w->n, not yet counted) against exact values ex at local t. */
static double interval_error(const refine_ctx *rc, size_t slot, double h, double t,
                             const fvals ex)
{
  const aq_workpath *w = rc->w;
  double err = 0;
  for (int c = 0; c < 8; c++) {
    const double *cf = w->coef + (slot * NF + (size_t)chk[c][0]) * 6;
    double v;
    if (chk[c][1] == 0)
      v = cf[0] + t * (cf[1] + t * (cf[2] + t * (cf[3] + t * (cf[4] + t * cf[5]))));
    else
      v = (cf[1] + t * (2 * cf[2] + t * (3 * cf[3] + t * (4 * cf[4] + t * 5 * cf[5])))) / h;
    double x = ex[chk[c][0]][chk[c][1]], ref;
    if (c < 2)
      ref = rc->scale[c];
    else if (c < 6)
      ref = fabs(x) + TABLE_FLOOR * rc->scale[c];
    else if (c == 6)
      ref = fabs(x);
    else
      ref = fabs(x) + ex[F_M][0] / w->path.s_c_rad;
    double e = fabs(v - x) / (ref > 0 ? ref : 1);
    if (e > err)
      err = e;
  }
  return err;
}

/* Accept [s0, s1] if its error (at the midpoint, where the Hermite value
 * error, proportional to t^3 (1-t)^3, peaks, and at t = TABLE_T_DERIV,
 * where the derivatives' error, proportional to t^2 (1-t)^2 (1-2t), peaks)
 * is below TABLE_REL_TOL, or splitting stopped halving an error already
 * below TABLE_ROUNDOFF 2^depth (round-off: the derivative of an interpolant
 * over h carries the round-off of the exact values divided by h, so the
 * bound doubles with each halving; without that a flat arch, whose exact
 * dx/ds carries round-off of 1e-14 relative near the end of its path, was
 * halved to TABLE_MAX_DEPTH there, past TABLE_MAX_INTERVALS), or
 * the interval is TABLE_MAX_DEPTH halvings deep; else split at the
 * midpoint (already evaluated) and refine both halves. */
static void refine(refine_ctx *rc, double s0, const fvals f0, double s1, const fvals f1,
                   int depth, double parent_err)
{
  aq_workpath *w = rc->w;
  if (rc->failed)
    return;
  double h = s1 - s0;
  fvals fm, fd;
  if (w->n >= w->max_n) {
    rc->failed = rc->too_many = 1;
    w->out_s = s0;
    return;
  }
  if (depth > w->fine_depth) {
    w->fine_depth = depth;
    w->fine_s = s0;
  }
  if (append_interval(w, s0, f0, s1, f1) != 0 ||
      exact_f(w, s0 + 0.5 * h, fm, NULL) != 0 ||
      exact_f(w, s0 + TABLE_T_DERIV * h, fd, NULL) != 0) {
    rc->failed = 1;
    return;
  }
  w->n--; /* tentative: the slot is reused below */
  double e1 = interval_error(rc, w->n, h, 0.5, fm);
  double e2 = interval_error(rc, w->n, h, TABLE_T_DERIV, fd);
  double err = e1 > e2 ? e1 : e2;
  if (err <= TABLE_REL_TOL || depth >= TABLE_MAX_DEPTH ||
      (err > TABLE_STALL * parent_err && err < ldexp(TABLE_ROUNDOFF, depth))) {
    w->n++;
    if (err > rc->err)
      rc->err = err;
    return;
  }
  double sm = s0 + 0.5 * h;
  refine(rc, s0, f0, sm, fm, depth + 1, err);
  refine(rc, sm, fm, s1, f1, depth + 1, err);
}

/* ---- The Taylor leg's pieces ----
 * Away from a toggle the kinematics are analytic in s, so dx/ds, dy/ds and
 * M are fitted on intervals as wide as their Chebyshev series allow, by
 * interpolation of degree PIECE_DEG at the Chebyshev points of the first
 * kind from the exact evaluation (exact_f; the Hermite tables above are not
 * used, so the ode and workpath-quad references stay as they are).  An
 * interval is accepted when the last three Chebyshev coefficients of each
 * function are below PIECE_TAIL_TOL relative to its scale (dx/ds and dy/ds
 * together, and M: their largest magnitude on the interval), or when
 * halving stopped halving a tail already at round-off; else it is halved.
 * Each fit is converted to the power basis in t = (s - s_lo) / (s_hi - s_lo)
 * in [0, 1] (the monomial coefficients of a fast-decaying Chebyshev series
 * stay of the size of the function), its constant term set to the exact
 * value at s_lo (a change of the fit's own error): near the threshold the
 * start from rest at s = 0 depends on a dx + g dy at s = 0, which nearly
 * cancel, so those values are exact there.  x and y are the integrals of the
 * fitted slopes from their exact values at s_lo (degree PIECE_DEG + 1), so
 * that the potential energy m_T g y(s) is that of the work integral the leg
 * uses (the energy balance holds to round-off of y, not of the arch's
 * coordinates, even for tiny rocking near s = 0).  The acceleration's
 * pieces gc = R', ga = (xr R)', gb = (yr R)' (path.h; R = 1/M, xr, yr the
 * displacements from s_lo) are fitted alike from the exact M, M', x, y and
 * slopes, with their constant terms exact at s_lo, and share the test of
 * the tails (gc alone, ga and gb together), so that the leg needs no
 * division by M. */
#define PIECE_DEG 14            /* of the fits; x, y one more (< AQ_PIECE_MAX_DEG) */
#define PIECE_TAIL_TOL 2e-15    /* Chebyshev tail / scale (about ten unit round-offs) */
#define PIECE_ROUNDOFF 1e-10    /* a tail that halving no longer halves and is below this: round-off
                                   (flat arches: 1e-11 near their end) */
#define PIECE_MAX_DEPTH 40      /* halvings of [0, s_c] at most */
enum { PC_DX = 0, PC_DY, PC_M, PC_GC, PC_GA, PC_GB, NPC_F, PN = PIECE_DEG + 1 };
_Static_assert(PIECE_DEG < AQ_PIECE_MAX_DEG, "x, y need degree PIECE_DEG + 1");

typedef struct {
  aq_workpath *w;
  double cosk[PN][PN]; /* cos(pi k (j + 1/2) / PN) */
  double tnode[PN];    /* Chebyshev points of the first kind on [-1, 1] */
  int failed, too_many;
} piece_ctx;

/* The fitted functions at one s from the exact values f there and fa at
 * the piece's start (path.h aq_path_piece: gc, ga, gb). */
static void piece_g(const double f[NF][3], const double fa[NF][3], double v[NPC_F])
{
  double r = 1 / f[F_M][0], rp = -f[F_M][1] * r * r; /* R = 1/M, R' */
  v[PC_DX] = f[F_DX][0];
  v[PC_DY] = f[F_DY][0];
  v[PC_M] = f[F_M][0];
  v[PC_GC] = rp;
  v[PC_GA] = f[F_DX][0] * r + (f[F_X][0] - fa[F_X][0]) * rp;
  v[PC_GB] = f[F_DY][0] * r + (f[F_Y][0] - fa[F_Y][0]) * rp;
}

/* Chebyshev coefficients c of dx/ds, dy/ds, M and the acceleration's
 * pieces gc, ga, gb (path.h) on [a, b], and their tail relative to the
 * scales (dx/ds and dy/ds together, M, gc, ga and gb together: their
 * largest magnitudes on the interval); fa the exact values at a (for
 * piece_append); -1 when the linkage fails. */
static int piece_fit(piece_ctx *pc, double a, double b, double c[NPC_F][PN],
                     double *tail, double fa[NF][3])
{
  double v[PN][NPC_F], mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sdxy = 0, sm = 0, sgc = 0, sgab = 0;
  if (exact_f(pc->w, a, fa, NULL) != 0)
    return -1;
  for (int j = 0; j < PN; j++) {
    double f[NF][3];
    if (exact_f(pc->w, mid + half * pc->tnode[j], f, NULL) != 0)
      return -1;
    piece_g(f, fa, v[j]);
    sdxy = fmax(sdxy, fmax(fabs(v[j][PC_DX]), fabs(v[j][PC_DY])));
    sm = fmax(sm, fabs(v[j][PC_M]));
    sgc = fmax(sgc, fabs(v[j][PC_GC]));
    sgab = fmax(sgab, fmax(fabs(v[j][PC_GA]), fabs(v[j][PC_GB])));
  }
  const double scale[NPC_F] = {sdxy, sdxy, sm, sgc, sgab, sgab};
  *tail = 0;
  for (int f = 0; f < NPC_F; f++) {
    for (int k = 0; k < PN; k++) {
      double sum = 0;
      for (int j = 0; j < PN; j++)
        sum += v[j][f] * pc->cosk[k][j];
      c[f][k] = (k == 0 ? 1.0 : 2.0) * sum / PN;
    }
    for (int k = PN - 3; k < PN; k++) {
      double e = fabs(c[f][k]) / (scale[f] > 0 ? scale[f] : 1);
      if (!(e <= *tail)) /* NaN propagates as a failed fit */
        *tail = isnan(e) ? HUGE_VAL : e;
    }
  }
  return 0;
}

/* Append the piece [a, b] from its Chebyshev coefficients and the exact
 * values fa at a; -1 on failure. */
static int piece_append(aq_workpath *w, double a, double b, double c[NPC_F][PN],
                        const double fa[NF][3])
{
  if (w->npc == w->pcap) {
    size_t cap = w->pcap ? 2 * w->pcap : 16;
    double *bp = realloc(w->pbp, (cap + 1) * sizeof *bp);
    if (!bp)
      return -1;
    w->pbp = bp;
    aq_path_piece *pp = realloc(w->piece, cap * sizeof *pp);
    if (!pp)
      return -1;
    w->piece = pp;
    w->pcap = cap;
  }
  aq_path_piece *pc = &w->piece[w->npc];
  memset(pc, 0, sizeof *pc);
  pc->s_lo = a;
  pc->s_hi = b;
  pc->s_ref = a;
  pc->iscale = 1.0 / (b - a);
  pc->deg = PIECE_DEG;
  double *dst[NPC_F] = {pc->dx, pc->dy, pc->m, pc->gc, pc->ga, pc->gb};
  double exact_a[NPC_F];
  piece_g(fa, fa, exact_a);
  pc->has_g = 1;
  for (int f = 0; f < NPC_F; f++) {
    /* sum c_k T_k(tau) in powers of tau: T_{k+1} = 2 tau T_k - T_{k-1} */
    double tp[PN] = {1}, tc[PN] = {0, 1};
    double *d = dst[f];
    d[0] = c[f][0];
    d[1] = c[f][1];
    for (int k = 2; k < PN; k++) {
      double tn[PN];
      tn[0] = -tp[0];
      for (int i = 1; i < PN; i++)
        tn[i] = 2 * tc[i - 1] - tp[i];
      for (int i = 0; i < PN; i++) {
        tp[i] = tc[i];
        tc[i] = tn[i];
        d[i] += c[f][k] * tn[i];
      }
    }
    /* tau = 2 t - 1: shift to tau = -1, then scale by 2^k */
    for (int k = 0; k < PIECE_DEG; k++)
      for (int j = PIECE_DEG - 1; j >= k; j--)
        d[j] -= d[j + 1];
    for (int k = 1, p2 = 2; k < PN; k++, p2 *= 2)
      d[k] *= p2;
    d[0] = exact_a[f];
  }
  /* x, y: the integrals of the slopes (ds = (b - a) dt) from s_lo */
  const double *slope[2] = {pc->dx, pc->dy};
  double *val[2] = {pc->x, pc->y};
  val[0][0] = fa[F_X][0];
  val[1][0] = fa[F_Y][0];
  for (int f = 0; f < 2; f++)
    for (int k = 0; k < PN; k++)
      val[f][k + 1] = (b - a) * slope[f][k] / (k + 1);
  w->pbp[w->npc] = a;
  w->pbp[w->npc + 1] = b;
  w->npc++;
  return 0;
}

static void piece_refine(piece_ctx *pc, double a, double b, int depth,
                         double parent_tail)
{
  if (pc->failed)
    return;
  if (pc->w->npc >= pc->w->max_n) {
    pc->failed = pc->too_many = 1;
    pc->w->out_s = a;
    return;
  }
  if (depth > pc->w->fine_depth) {
    pc->w->fine_depth = depth;
    pc->w->fine_s = a;
  }
  double c[NPC_F][PN], tail, fa[NF][3];
  if (piece_fit(pc, a, b, c, &tail, fa) != 0) {
    pc->failed = 1;
    return;
  }
  if (tail <= PIECE_TAIL_TOL || depth >= PIECE_MAX_DEPTH ||
      (tail > TABLE_STALL * parent_tail && tail < PIECE_ROUNDOFF)) {
    if (piece_append(pc->w, a, b, c, fa) != 0)
      pc->failed = 1;
    return;
  }
  double m = a + 0.5 * (b - a);
  piece_refine(pc, a, m, depth + 1, tail);
  piece_refine(pc, m, b, depth + 1, tail);
}

/* The pieces over [0, s_c]; 0, -1 on failure, -2 when too many. */
static int build_pieces(aq_workpath *w)
{
  piece_ctx pc;
  const double pi = acos(-1.0);
  memset(&pc, 0, sizeof pc);
  pc.w = w;
  for (int j = 0; j < PN; j++) {
    pc.tnode[j] = cos(pi * (j + 0.5) / PN);
    for (int k = 0; k < PN; k++)
      pc.cosk[k][j] = cos(pi * k * (j + 0.5) / PN);
  }
  piece_refine(&pc, 0.0, w->path.s_c_rad, 0, HUGE_VAL);
  return pc.too_many ? -2 : pc.failed ? -1 : 0;
}

/* Tables over [0, s_c]: TABLE_N0 equal intervals, each refined by halving
 * where needed (refine), so that the grid is fine only where the path
 * varies fast (near a toggle); then the Taylor leg's pieces.  -1 on failure
 * (memory, or the linkage), -2 when the tables would need more than
 * w->max_n intervals, -3 when the pieces would (w->out_s, fine_s and
 * fine_depth say where). */
static int build_tables(aq_workpath *w)
{
  double sc = w->path.s_c_rad;
  fvals node[TABLE_N0 + 1];
  refine_ctx rc = {w, {0}, 0, 0, 0};
  for (size_t i = 0; i <= TABLE_N0; i++) {
    if (exact_f(w, i == TABLE_N0 ? sc : sc * (double)i / TABLE_N0, node[i], NULL) != 0)
      return -1;
    for (int c = 0; c < 8; c++)
      if (fabs(node[i][chk[c][0]][chk[c][1]]) > rc.scale[c])
        rc.scale[c] = fabs(node[i][chk[c][0]][chk[c][1]]);
  }
  for (size_t i = 0; i < TABLE_N0 && !rc.failed; i++)
    refine(&rc, i == 0 ? 0.0 : sc * (double)i / TABLE_N0, node[i],
           i + 1 == TABLE_N0 ? sc : sc * (double)(i + 1) / TABLE_N0, node[i + 1], 0, HUGE_VAL);
  w->tab_err = rc.err;
  if (rc.too_many || rc.failed)
    return rc.too_many ? -2 : -1;
  w->fine_depth = 0;
  w->fine_s = 0;
  int pr = build_pieces(w);
  return pr == -2 ? -3 : pr;
}

static int hinges_open(const aq_workpath *w, const aq_mech_state *st)
{
  double rel[4];
  aq_mech_hinge_rel(st, rel);
  for (int k = 0; k < 4; k++)
    if (!(w->mech.open[k] * rel[k] > 0))
      return 0;
  return 1;
}

/* 0: fine at s; else the reason it is past the end. */
static aq_end past_end(const aq_workpath *w, double s)
{
  double f[NF][3];
  aq_mech_state st;
  if (exact_f(w, s, f, &st) != 0)
    return AQ_END_TOGGLE;
  if (!(f[F_Y][1] > 0))
    return AQ_END_PEAK;
  if (!hinges_open(w, &st))
    return AQ_END_HINGE;
  return AQ_END_NONE;
}

static void find_end(aq_workpath *w)
{
  double lo = 0, hi = 0;
  aq_end why = AQ_END_NONE;
  for (double s = SCAN_STEP_RAD; s <= SCAN_MAX_RAD; s += SCAN_STEP_RAD) {
    why = past_end(w, s);
    if (why != AQ_END_NONE) {
      hi = s;
      break;
    }
    lo = s;
  }
  if (why == AQ_END_NONE) {
    w->path.s_c_rad = lo;
    w->end = AQ_END_NONE;
    return;
  }
  for (int it = 0; it < 200 && hi - lo > 2 * __DBL_EPSILON__ * hi; it++) {
    double mid = 0.5 * (lo + hi);
    aq_end e = past_end(w, mid);
    if (e == AQ_END_NONE)
      lo = mid;
    else {
      hi = mid;
      why = e;
    }
  }
  w->path.s_c_rad = lo;
  w->end = why;
}

void aq_workpath_free(aq_workpath *w)
{
  if (!w)
    return;
  free(w->coef);
  free(w->piece);
  free(w->pbp);
  free(w->bp);
  free(w);
}

static const char *face_name(char f) { return f == 'e' ? "extrados" : "intrados"; }

/* A path of hs on g with its four-bar set up and its functions (tables,
 * exact, pieces) in place, nothing else computed, into *out. */
static aq_status path_alloc(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                            const char *name, aq_workpath **out, aq_error *err)
{
  *out = NULL;
  aq_workpath *w = calloc(1, sizeof *w);
  if (!w)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  aq_status st = aq_mech_init(&w->mech, g, hs, err);
  if (st != AQ_OK) {
    free(w);
    return st;
  }
  w->g = g;
  w->g_mps2 = g_mps2;
  snprintf(w->name, sizeof w->name, "%s", name ? name : "");
  aq_path *p = &w->path;
  p->name = w->name;
  p->eval = eval_table;
  p->eval_exact = eval_exact;
  p->piece = eval_piece;
  p->ctx = w;
  p->mass_kg = g->mass_kg;
  p->g_mps2 = g_mps2;
  p->q_sign = w->mech.open[0];
  *out = w;
  return AQ_OK;
}

aq_status aq_workpath_build(const aq_geom *g, const aq_hinge_set *hs,
                            double g_mps2, const char *name, aq_workpath **out,
                            aq_error *err)
{
  return aq_workpath_build_max(g, hs, g_mps2, name, TABLE_MAX_INTERVALS, out, err);
}

aq_status aq_workpath_build_max(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                                const char *name, size_t max_intervals, aq_workpath **out,
                                aq_error *err)
{
  aq_status st = path_alloc(g, hs, g_mps2, name, out, err);
  if (st != AQ_OK)
    return st;
  aq_workpath *w = *out;
  *out = NULL;
  w->max_n = max_intervals;
  aq_path *p = &w->path;
  p->act_sign = 1;
  p->admissible = 0;
  aq_mech_state s0;
  if (aq_mech_eval(&w->mech, 0.0, &s0) != 0) {
    snprintf(w->reason, sizeof w->reason, "the linkage does not close at s = 0");
    *out = w;
    return AQ_OK;
  }
  for (int b = 0; b < 3; b++)
    w->c0[b] = s0.c[b][0];
  double f[NF][3];
  exact_f(w, 0.0, f, NULL);
  p->act_sign = f[F_X][1] > 0 ? -1 : 1;
  p->lambda0 = f[F_X][1] != 0 ? -(double)p->act_sign * f[F_Y][1] / f[F_X][1] : 0;
  /* first-order opening of every hinge: rates of the relative rotations */
  double rate[4] = {1.0, s0.phi[1][1] - 1.0, s0.phi[2][1] - s0.phi[1][1], -s0.phi[2][1]};
  for (int k = 0; k < 4; k++)
    if (!(w->mech.open[k] * p->q_sign * rate[k] > 0)) {
      snprintf(w->reason, sizeof w->reason,
               "hinge %d (joint %zu, %s) does not open when H1 opens", k + 1,
               hs->joint[k], face_name(hs->face[k]));
      *out = w;
      return AQ_OK;
    }
  if (!(p->lambda0 > 0) || !isfinite(p->lambda0)) {
    snprintf(w->reason, sizeof w->reason,
             "lambda0 = %.6g: the mechanism does not lift the arch's centroid",
             p->lambda0);
    *out = w;
    return AQ_OK;
  }
  aq_equil eq;
  aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, g_mps2};
  aq_error e2;
  aq_error_clear(&e2);
  if (aq_mech_equilibrium(&w->mech, &s0, &live, &eq, &e2) != AQ_OK) {
    snprintf(w->reason, sizeof w->reason, "singular equilibrium at s = 0");
    *out = w;
    return AQ_OK;
  }
  for (int k = 0; k < 4; k++)
    if (!(eq.normal[k] > 0)) {
      snprintf(w->reason, sizeof w->reason,
               "hinge %d (joint %zu, %s) in tension at s = 0 (normal force %.6g N)",
               k + 1, hs->joint[k], face_name(hs->face[k]), eq.normal[k]);
      *out = w;
      return AQ_OK;
    }
  double *ecc = malloc((g->p.voussoirs + 1) * sizeof *ecc);
  if (!ecc) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  w->thrust0 = aq_mech_thrust(&w->mech, &s0, &live, &eq, ecc, NULL);
  free(ecc);
  find_end(w);
  if (!(p->s_c_rad > 0) || w->end == AQ_END_NONE) {
    snprintf(w->reason, sizeof w->reason, "no end of the path found in (0, %g] rad",
             SCAN_MAX_RAD);
    *out = w;
    return AQ_OK;
  }
  p->admissible = 1;
  int tab = build_tables(w);
  if (tab == -2 || tab == -3) {
    /* what ran out and where: the tables (or the pieces) halve an interval
     * until it meets its tolerance, so the count runs out where the path
     * varies fastest or where round-off keeps an error from halving */
    int pieces = tab == -3;
    double lambda0 = p->lambda0, s_c = p->s_c_rad, out_s = w->out_s, fine_s = w->fine_s;
    int depth = w->fine_depth;
    size_t max_n = w->max_n;
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "hinges",
                        "expected a work path that %s of at most %zu intervals resolve to "
                        "%g, got one that needs more: they ran out at s = %.6g rad of q_c = "
                        "%.6g rad; the finest, %d halvings of %s, is at s = %.6g rad "
                        "(lambda0 = %.6g)",
                        pieces ? "the Taylor leg's pieces (Chebyshev tails)"
                               : "the Hermite tables",
                        max_n, pieces ? PIECE_TAIL_TOL : TABLE_REL_TOL, out_s, s_c, depth,
                        pieces ? "[0, q_c]" : "one of the first 16", fine_s, lambda0);
  }
  if (tab != 0) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL,
                        "out of memory (or the linkage failed) building tables");
  }
  p->x_mono_rad = x_mono(w);
  *out = w;
  return AQ_OK;
}

const aq_path *aq_workpath_path(const aq_workpath *w) { return &w->path; }
const aq_mech *aq_workpath_mech(const aq_workpath *w) { return &w->mech; }
const char *aq_workpath_reason(const aq_workpath *w) { return w->reason; }
aq_end aq_workpath_end(const aq_workpath *w) { return w->end; }
size_t aq_workpath_table_size(const aq_workpath *w) { return w->n; }
size_t aq_workpath_piece_count(const aq_workpath *w) { return w->npc; }
double aq_workpath_table_error(const aq_workpath *w) { return w->tab_err; }
double aq_workpath_thrust0(const aq_workpath *w) { return w->thrust0; }

aq_status aq_workpath_equilibrium(const aq_workpath *w, double s, aq_equil *out,
                                  aq_error *err)
{
  aq_mech_state st;
  if (w->path.admissible && clamp_s(w, &s) != 0)
    s = -1;
  if (!(s >= 0) || aq_mech_eval(&w->mech, (double)w->path.q_sign * s, &st) != 0)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "s",
                        "expected a position in [0, %g] rad, got %g",
                        w->path.s_c_rad, s);
  aq_live live = {AQ_LIVE_HORIZONTAL, w->path.act_sign, {0, 0}, 0, w->g_mps2};
  return aq_mech_equilibrium(&w->mech, &st, &live, out, err);
}

void aq_workpath_set_impact(aq_workpath *b, const aq_workpath *a)
{
  b->path.impact_vel_ratio = 0;
  if (!b->path.admissible)
    return; /* never entered */
  size_t n = b->g->p.voussoirs;
  aq_vec2 *ua = malloc(2 * n * sizeof *ua);
  double *wa = malloc(2 * n * sizeof *wa);
  double f[NF][3];
  if (ua && wa && exact_f(b, 0.0, f, NULL) == 0 && f[F_M][0] > 0) {
    aq_mech_field0(&a->mech, a->path.q_sign, ua, wa);
    aq_mech_field0(&b->mech, b->path.q_sign, ua + n, wa + n);
    double d = aq_field_dot(b->g->vous, n, ua, wa, ua + n, wa + n);
    b->path.impact_vel_ratio = -d / f[F_M][0];
  }
  free(ua);
  free(wa);
}

/* ---- The built path as bytes (arch.c's aq_arch_tables_put and _get) ----
 * Everything aq_workpath_build computed past the four-bar, each double as
 * its bits: a path read back is the path built, bit for bit.  The four-bar
 * itself (aq_mech_init: closed forms from the geometry) is set up again. */
void aq_workpath_put(const aq_workpath *w, aq_bytes_out *b)
{
  const aq_path *p = &w->path;
  aq_bytes_put_i64(b, p->admissible);
  aq_bytes_put_i64(b, p->act_sign);
  aq_bytes_put_f64(b, p->lambda0);
  aq_bytes_put_f64(b, p->s_c_rad);
  aq_bytes_put_f64(b, p->impact_vel_ratio);
  aq_bytes_put_f64(b, p->x_mono_rad);
  for (int k = 0; k < 3; k++) {
    aq_bytes_put_f64(b, w->c0[k].x);
    aq_bytes_put_f64(b, w->c0[k].y);
  }
  aq_bytes_put_i64(b, w->end);
  aq_bytes_put_str(b, w->reason, sizeof w->reason);
  aq_bytes_put_f64(b, w->tab_err);
  aq_bytes_put_f64(b, w->thrust0);
  aq_bytes_put_i64(b, (int64_t)w->n);
  if (w->n) {
    aq_bytes_put(b, w->bp, (w->n + 1) * sizeof *w->bp);
    aq_bytes_put(b, w->coef, w->n * NF * 6 * sizeof *w->coef);
  }
  aq_bytes_put_i64(b, (int64_t)w->npc);
  if (w->npc) {
    aq_bytes_put(b, w->pbp, (w->npc + 1) * sizeof *w->pbp);
    aq_bytes_put(b, w->piece, w->npc * sizeof *w->piece);
  }
}

/* n + extra items of size bytes each from r into a new array *out
 * (NULL when n is 0; n is bounded by the caller); -1 when r cannot hold
 * them or out of memory. */
static int get_array(aq_bytes_in *r, size_t n, size_t extra, size_t size, void **out,
                     const char *what)
{
  *out = NULL;
  if (!n)
    return 0;
  size_t bytes = (n + extra) * size;
  if (r->bad || bytes > r->n - r->at ||
      !(*out = malloc(bytes))) {
    r->bad = r->bad ? r->bad : what;
    return -1;
  }
  return aq_bytes_get(r, *out, bytes, what);
}

aq_status aq_workpath_get(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                          const char *name, aq_bytes_in *r, aq_workpath **out,
                          aq_error *err)
{
  aq_status st = path_alloc(g, hs, g_mps2, name, out, err);
  if (st != AQ_OK)
    return st;
  aq_workpath *w = *out;
  *out = NULL;
  aq_path *p = &w->path;
  p->admissible = (int)aq_bytes_get_int(r, 0, 1, "admissible");
  p->act_sign = aq_bytes_get_int(r, -1, 1, "act_sign") < 0 ? -1 : 1;
  p->lambda0 = aq_bytes_get_f64(r, "lambda0");
  p->s_c_rad = aq_bytes_get_f64(r, "s_c");
  p->impact_vel_ratio = aq_bytes_get_f64(r, "impact_vel_ratio");
  p->x_mono_rad = aq_bytes_get_f64(r, "x_mono");
  for (int k = 0; k < 3; k++) {
    w->c0[k].x = aq_bytes_get_f64(r, "c0");
    w->c0[k].y = aq_bytes_get_f64(r, "c0");
  }
  w->end = (aq_end)aq_bytes_get_int(r, AQ_END_PEAK, AQ_END_NONE, "end");
  aq_bytes_get_str(r, w->reason, sizeof w->reason, NULL, "reason");
  w->tab_err = aq_bytes_get_f64(r, "table_error");
  w->thrust0 = aq_bytes_get_f64(r, "thrust0");
  w->n = w->cap = (size_t)aq_bytes_get_int(r, 0, TABLE_MAX_INTERVALS, "table_n");
  void *bp, *coef, *pbp, *piece;
  get_array(r, w->n, 1, sizeof *w->bp, &bp, "breakpoints");
  w->bp = bp;
  get_array(r, w->n * NF * 6, 0, sizeof *w->coef, &coef, "coefficients");
  w->coef = coef;
  w->npc = w->pcap = (size_t)aq_bytes_get_int(r, 0, TABLE_MAX_INTERVALS, "pieces");
  get_array(r, w->npc, 1, sizeof *w->pbp, &pbp, "piece breakpoints");
  w->pbp = pbp;
  get_array(r, w->npc, 0, sizeof *w->piece, &piece, "pieces");
  w->piece = piece;
  for (size_t i = 0; i < w->npc && !r->bad; i++)
    if (w->piece[i].deg < 0 || w->piece[i].deg >= AQ_PIECE_MAX_DEG)
      r->bad = "piece degree";
  /* a path that may be integrated has its tables and pieces */
  if (!r->bad && p->admissible && (!w->n || !w->npc || !(p->s_c_rad > 0)))
    r->bad = "tables";
  if (r->bad) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, name,
                        "expected a stored work path, got bytes that are not one (%s)",
                        r->bad);
  }
  *out = w;
  return AQ_OK;
}
