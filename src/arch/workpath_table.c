/* workpath_table.c: the Hermite tables of a work path (workpath_impl.h),
 * from which the ode and workpath-quad evaluate it (path.h eval).
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
#include <stdlib.h>

#include "workpath_impl.h"

#define TABLE_N0 16            /* initial equal intervals */
#define TABLE_MAX_DEPTH 30     /* halvings of an initial interval at most */
#define TABLE_FLOOR 1e-3       /* error floor of slopes, curvatures: this times their largest value */
#define TABLE_ROUNDOFF 1e-8    /* ... (TABLE_STALL) unless it is this small already (round-off),
                                  times 2^depth */
#define TABLE_T_DERIV 0.2763932 /* (5 - sqrt 5)/10: peak of t^2 (1-t)^2 (1-2t) */

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

int aq_workpath_eval_table(const void *ctx, double s, aq_path_point *p)
{
  const aq_workpath *w = ctx;
  double f[NF][3];
  if (aq_workpath_clamp_s(w, &s) != 0)
    return -1;
  table_all(w, s, f);
  aq_workpath_fill_point(w, f, p);
  return 0;
}

/* x_mono_rad (path.h): the first s where the tabled slope dx/ds, sampled
 * at X_MONO_SAMPLES points per interval, leaves the sign it has at s = 0. */
#define X_MONO_SAMPLES 8
double aq_workpath_x_mono(const aq_workpath *w)
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
      aq_workpath_exact_f(w, s0 + 0.5 * h, fm, NULL) != 0 ||
      aq_workpath_exact_f(w, s0 + TABLE_T_DERIV * h, fd, NULL) != 0) {
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

/* Tables over [0, s_c]: TABLE_N0 equal intervals, each refined by halving
 * where needed (refine), so that the grid is fine only where the path
 * varies fast (near a toggle); then the Taylor leg's pieces.  -1 on failure
 * (memory, or the linkage), -2 when the tables would need more than
 * w->max_n intervals, -3 when the pieces would (w->out_s, fine_s and
 * fine_depth say where). */
int aq_workpath_build_tables(aq_workpath *w)
{
  double sc = w->path.s_c_rad;
  fvals node[TABLE_N0 + 1];
  refine_ctx rc = {w, {0}, 0, 0, 0};
  for (size_t i = 0; i <= TABLE_N0; i++) {
    if (aq_workpath_exact_f(w, i == TABLE_N0 ? sc : sc * (double)i / TABLE_N0, node[i], NULL) != 0)
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
  int pr = aq_workpath_build_pieces(w);
  return pr == -2 ? -3 : pr;
}
