/* demand_grid.c: bounds of a hinge set's joint demands over cells of states
 * (demand_tab.h).
 *
 * A state of a set is (s, a/g, KE/g).  At a fixed s each entry's forms are
 * linear in a/g and w = sdot^2/g = 2 (KE/g) / M(s), so over a cell (a range
 * of s, of a/g and of KE/g) each coefficient lies in the range its cubic
 * takes over the cell's s, 1/M in its own, and interval arithmetic bounds
 * N, T and e: an upper and a lower bound of |T|/N and |e|/N for every entry
 * over the whole cell.  The cell keeps the largest upper bound and the
 * entries whose upper bound reaches the largest lower bound (the
 * candidates: any other entry is, at every state of the cell, below a
 * candidate's value there).
 *
 * The bounds must hold for the values the tracker computes in floating
 * point (aq_dt_cubic, then n0 + a n1 + w n2 and the ratio): each cubic's
 * range is widened by 1e-14 of the sum of its coefficients' magnitudes,
 * each linear form's by 1e-13 of its terms' magnitudes, the ratios by
 * 1e-13, the ranges of s, a/g and KE/g by 1e-9 of their widths. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "demand_tab.h"

#define DG_EPS_C 1e-14
#define DG_EPS_L 1e-13
#define DG_PAD 1e-9

/* fmin and fmax (either NaN: the other), inline. */
static inline double dmin(double a, double b) { return a < b || b != b ? a : b; }
static inline double dmax(double a, double b) { return a > b || b != b ? a : b; }

/* The range of cubic c over u in [ua, ub], widened for rounding. */
void aq_dg_cubic_range(const double c[4], double ua, double ub, double *lo, double *hi)
{
  double a = aq_dt_cubic(c, ua), b = aq_dt_cubic(c, ub);
  double l = dmin(a, b), h = dmax(a, b);
  /* critical points: c1 + 2 c2 u + 3 c3 u^2 = 0 */
  double A = 3 * c[3], B = 2 * c[2], C = c[1], r[2];
  /* none inside when the derivative's Bernstein coefficients over [ua,
   * ub] share a strict sign (it lies within their hull; its rounding moves
   * the ends by a few ulps of the coefficients, well inside the widening) */
  double d0 = C + ua * (B + ua * A), d2 = C + ub * (B + ub * A);
  double d1 = d0 + 0.5 * (ub - ua) * (B + 2 * A * ua);
  int nr = 0;
  if ((d0 > 0 && d1 > 0 && d2 > 0) || (d0 < 0 && d1 < 0 && d2 < 0)) {
    /* monotone: the ends */
  } else if (A == 0) {
    if (B != 0)
      r[nr++] = -C / B;
  } else {
    double disc = B * B - 4 * A * C;
    if (disc >= 0) {
      double q = -0.5 * (B + copysign(sqrt(disc), B));
      r[nr++] = q / A;
      if (q != 0)
        r[nr++] = C / q;
    }
  }
  for (int k = 0; k < nr; k++)
    if (r[k] > ua && r[k] < ub) {
      double v = aq_dt_cubic(c, r[k]);
      l = dmin(l, v), h = dmax(h, v);
    }
  double e = DG_EPS_C * (fabs(c[0]) + fabs(c[1]) + fabs(c[2]) + fabs(c[3]));
  *lo = l - e, *hi = h + e;
}

void aq_dg_free(aq_demand_grid *g)
{
  if (!g)
    return;
  for (unsigned char *c = g->chunk, *up; c; c = up) {
    memcpy(&up, c, sizeof up);
    free(c);
  }
  for (size_t is = 0; is < DG_NS; is++)
    free(g->rng[is]);
  pthread_mutex_destroy(&g->lock);
  free(g->wrng);
  free(g->scratch);
  free(g->hu);
  free(g);
}

/* The range of a/g of bin ia and of KE/g of bin ik, widened. */
static void bin_a(const aq_demand_grid *g, size_t ia, double *a0, double *a1)
{
  double lo = ((double)ia - 0.5 * DG_NA) * g->da, hi = lo + g->da;
  *a0 = lo - DG_PAD * g->da, *a1 = hi + DG_PAD * g->da;
}
static void bin_k(const aq_demand_grid *g, size_t ik, double *k0, double *k1)
{
  if (ik == 0) {
    *k0 = 0, *k1 = g->k0 * (1 + DG_PAD);
    return;
  }
  size_t e = (ik - 1) >> DG_KB, m = (ik - 1) & ((1u << DG_KB) - 1);
  double base = g->k0 * ldexp(1.0, (int)e), sub = 1.0 / (1 << DG_KB);
  *k0 = base * (1 + sub * (double)m) * (1 - DG_PAD);
  *k1 = base * (1 + sub * (double)(m + 1)) * (1 + DG_PAD);
}

/* The range of x a over x in [xl, xh], a in [a0, a1], widened. */
static void prod_range(double xl, double xh, double a0, double a1, double *lo, double *hi)
{
  double p0 = xl * a0, p1 = xl * a1, p2 = xh * a0, p3 = xh * a1;
  double l = p0 < p1 ? p0 : p1, h = p0 < p1 ? p1 : p0;
  l = p2 < l ? p2 : l, h = p2 > h ? p2 : h;
  l = p3 < l ? p3 : l, h = p3 > h ? p3 : h;
  double m = (fabs(l) > fabs(h) ? fabs(l) : fabs(h)) * DG_EPS_L;
  *lo = l - m, *hi = h + m;
}

/* Bounds of quantity q (0: |T|/N, 1: |e|/N) of an entry over a box: c the
 * ranges (lo, hi of N, T, e) of its constant and KE terms, t those of its
 * a/g terms; *u an upper bound (INFINITY where N may be <= 0), *l a lower
 * one (INFINITY where N <= 0 throughout). */
static void ebound(const double *c, const double *t, int q, double *u, double *l)
{
  double nl = c[0] + t[0], nh = c[1] + t[1];
  double xl = c[2 + 2 * q] + t[2 + 2 * q], xh = c[3 + 2 * q] + t[3 + 2 * q];
  double axh = fabs(xl) > fabs(xh) ? fabs(xl) : fabs(xh);
  double axl = xl > 0 ? xl : xh < 0 ? -xh : 0;
  *u = nl > 0 ? axh / nl * (1 + DG_EPS_L) : INFINITY;
  *l = nh > 0 ? axl / nh * (1 - DG_EPS_L) : INFINITY;
}

/* The a/g terms' ranges (lo, hi of N, T, e) of entry ranges x (R + 2 j
 * DT_NV) over a/g in [a0, a1]. */
static void a_terms(const double *x, double a0, double a1, double t[6])
{
  for (int f = 0; f < 3; f++)
    prod_range(x[6 * f + 2], x[6 * f + 3], a0, a1, &t[2 * f], &t[2 * f + 1]);
}

enum { DG_CHUNK = 1 << 16 }; /* bytes of a chunk of made blocks */

/* n bytes (a multiple of 8) of the grid's chunks, never moved; NULL: out
 * of memory. */
static void *chunk_take(aq_demand_grid *g, size_t n)
{
  size_t head = sizeof(double);
  if (!g->chunk || g->chunk_used + n > g->chunk_cap) {
    size_t cap = head + (n > DG_CHUNK ? n : DG_CHUNK);
    unsigned char *c = malloc(cap);
    if (!c)
      return NULL;
    memcpy(c, &g->chunk, sizeof g->chunk);
    g->chunk = c, g->chunk_used = head, g->chunk_cap = cap;
  }
  void *p = g->chunk + g->chunk_used;
  g->chunk_used += n;
  return p;
}

/* The cells of block bl (DG_AB a/g bins) of row (is, ik), from range is's
 * forms' ranges R (lo/hi per form, then 1/M's), packed with their pool
 * into g->blk.  0, or -1 (memory). */
static int block(aq_demand_grid *g, size_t is, size_t ik, size_t bl, const double *R)
{
  const aq_demand_table *T = g->t;
  size_t nf = T->nf, row_i = is * DG_NK + ik, bi = row_i * DG_NB + bl;
  aq_dg_cell cells[DG_AB];
  uint32_t codes[DG_AB];
  double rm0 = R[2 * nf * DT_NV], rm1 = R[2 * nf * DT_NV + 1], k0, k1;
  bin_k(g, ik, &k0, &k1);
  double w0 = 2 * k0 * rm0 * (1 - DG_EPS_L), w1 = 2 * k1 * rm1 * (1 + DG_EPS_L);
  /* per entry: cw 6, u 4, at 6, then (as integers) the stamp, both lists
   * and the block's candidates (at most 2 DG_AB per entry) */
  if (!g->scratch && !(g->scratch = malloc(nf * (16 * sizeof(double) + sizeof(size_t) +
                                                 2 * sizeof(uint16_t) +
                                                 2 * DG_AB * sizeof(aq_dg_cand)))))
    return -1;
  double *cw = g->scratch, *u = cw + 6 * nf, *at = u + 4 * nf;
  size_t *stamp = (size_t *)(void *)(at + 6 * nf);
  uint16_t *list = (uint16_t *)(void *)(stamp + nf);
  aq_dg_cand *pool = (aq_dg_cand *)(void *)(list + 2 * nf);
  size_t np = 0;
  memset(stamp, 0, nf * sizeof *stamp);
  for (size_t j = 0; j < nf; j++) /* the constant and KE terms */
    for (int f = 0; f < 3; f++) {
      const double *x = R + 2 * (j * DT_NV + 3 * (size_t)f);
      double lo, hi, m0 = dmax(fabs(x[0]), fabs(x[1])) * DG_EPS_L;
      prod_range(x[4], x[5], w0, w1, &lo, &hi);
      cw[6 * j + 2 * (size_t)f] = x[0] + lo - m0;
      cw[6 * j + 2 * (size_t)f + 1] = x[1] + hi + m0;
    }
  /* the block's entries: those whose upper bound over the block reaches
   * its largest lower bound, per quantity */
  double a0, a1, e0, e1, t[6];
  bin_a(g, bl * DG_AB, &a0, &e0);
  bin_a(g, bl * DG_AB + DG_AB - 1, &e1, &a1);
  size_t nq[2] = {0, 0};
  uint16_t *lq[2] = {list, list + nf};
  double Lm[2] = {0, 0};
  for (size_t j = 0; j < nf; j++) {
    double *uj = u + 4 * j;
    if (rm0 > 0)
      a_terms(R + 2 * j * DT_NV, a0, a1, t);
    for (int q = 0; q < 2; q++) {
      if (q == 1 && T->entry[j].hinge >= 0)
        uj[2] = uj[3] = 0;
      else if (!(rm0 > 0))
        uj[2 * q] = INFINITY, uj[2 * q + 1] = 0;
      else
        ebound(cw + 6 * j, t, q, &uj[2 * q], &uj[2 * q + 1]);
      Lm[q] = uj[2 * q + 1] > Lm[q] ? uj[2 * q + 1] : Lm[q];
    }
  }
  for (int q = 0; q < 2; q++)
    for (size_t j = 0; j < nf; j++)
      if ((q == 0 || T->entry[j].hinge < 0) && u[4 * j + 2 * (size_t)q] >= Lm[q])
        lq[q][nq[q]++] = (uint16_t)j;
  for (size_t ia = bl * DG_AB; ia < (bl + 1) * DG_AB; ia++) {
    aq_dg_cell *cl = cells + ia % DG_AB;
    aq_dg_cand *tmp = pool + np;
    size_t c0 = 0;
    uint32_t hc = 0;
    bin_a(g, ia, &a0, &a1);
    for (int q = 0; q < 2; q++) {
      double U = 0, L = 0;
      for (size_t m = 0; m < nq[q]; m++) {
        size_t j = lq[q][m];
        double *uj = u + 4 * j;
        if (!(rm0 > 0)) {
          uj[2 * q] = INFINITY, uj[2 * q + 1] = 0;
        } else {
          double *tj = at + 6 * j;
          if (stamp[j] != ia + 1) { /* an entry of both lists: its terms once */
            a_terms(R + 2 * j * DT_NV, a0, a1, tj);
            stamp[j] = ia + 1;
          }
          ebound(cw + 6 * j, tj, q, &uj[2 * q], &uj[2 * q + 1]);
        }
        U = uj[2 * q] > U ? uj[2 * q] : U;
        L = uj[2 * q + 1] > L ? uj[2 * q + 1] : L;
      }
      size_t c = 0;
      for (size_t m = 0; m < nq[q]; m++)
        if (u[4 * (size_t)lq[q][m] + 2 * (size_t)q] >= L)
          tmp[c0 + c++] = (aq_dg_cand)aq_dg_upper16(u[4 * (size_t)lq[q][m] + 2 * (size_t)q]) << 16 |
                          lq[q][m];
      cl->n[q] = c < DG_ALL ? (uint8_t)c : DG_ALL;
      c0 += c < DG_ALL ? c : 0;
      hc |= (uint32_t)aq_dg_upper16(U) << (16 * q);
    }
    codes[ia % DG_AB] = hc;
    if (c0 <= DG_INLINE) {
      memcpy(cl->c, tmp, c0 * sizeof *tmp);
      continue;
    }
    cl->c[0] = (aq_dg_cand)np; /* kept where they are: the pool */
    np += c0;
  }
  aq_dg_cell *b = chunk_take(g, (sizeof cells + np * sizeof *pool + 7) / 8 * 8);
  if (!b)
    return -1;
  memcpy(b, cells, sizeof cells);
  memcpy(b + DG_AB, pool, np * sizeof *pool);
  g->blk[bi] = b;
  for (size_t m = 0; m < DG_AB; m++)
    atomic_store_explicit(&g->hu[row_i * DG_NA + bl * DG_AB + m], codes[m],
                          memory_order_relaxed);
  return 0;
}

/* The ranges of the nine forms of every entry and of 1/M over s in
 * [s0, s1] (widened), into R (lo, hi each). */
static void ranges_in(const aq_demand_table *t, double s0, double s1, double *R)
{
  size_t nf = t->nf;
  double pad = DG_PAD * (s1 - s0);
  s0 = dmax(0, s0 - pad), s1 = dmin(t->s_c, s1 + pad);
  for (size_t k = 0; k < nf * DT_NV + 1; k++)
    R[2 * k] = INFINITY, R[2 * k + 1] = -INFINITY;
  for (size_t i = 0; i < t->nint; i++) {
    if (t->bp[i + 1] < s0 || t->bp[i] > s1)
      continue;
    double ua = dmax(0, (s0 - t->bp[i]) * t->ih[i]), ub = dmin(1, (s1 - t->bp[i]) * t->ih[i]);
    const double *C = t->c + i * t->stride;
    for (size_t k = 0; k <= nf * DT_NV; k++) {
      const double *c = k < nf * DT_NV ? C + k * DT_NC : C + (nf * DT_NV + 3) * DT_NC;
      double lo, hi;
      aq_dg_cubic_range(c, ua, ub, &lo, &hi);
      R[2 * k] = dmin(R[2 * k], lo), R[2 * k + 1] = dmax(R[2 * k + 1], hi);
    }
  }
}

/* The same over range is of s. */
static void ranges(const aq_demand_table *t, size_t is, double *R)
{
  ranges_in(t, t->s_c * (double)is / DG_NS, t->s_c * (double)(is + 1) / DG_NS, R);
}

/* The bound of either quantity, as stored: a float at least u (INFINITY
 * for no bound, NAN included). */
static float upper_f(double u)
{
  if (!(u < 3e38))
    return INFINITY;
  float f = (float)u;
  return (double)f < u ? nextafterf(f, INFINITY) : f;
}

/* The walls' bounds of a/g bin ia: over each range of s of wrng, each
 * entry's forms at KE 0 (w = 0: the KE terms vanish, as in a row whose
 * KE/g range is [0, 0]).  1, or 2 (out of memory). */
static int wall_bin(aq_demand_grid *g, size_t ia)
{
  const aq_demand_table *T = g->t;
  size_t nf = T->nf, per = 2 * (nf * DT_NV + 1);
  if (!g->wrng) {
    if (!(g->wrng = malloc(DG_WS * per * sizeof *g->wrng)))
      return 2;
    for (size_t ws = 0; ws < DG_WS; ws++)
      ranges_in(T, T->s_c * (double)ws / DG_WS, T->s_c * (double)(ws + 1) / DG_WS,
                g->wrng + ws * per);
  }
  double a0, a1, W[2] = {0, 0};
  bin_a(g, ia, &a0, &a1);
  for (size_t ws = 0; ws < DG_WS; ws++)
    for (size_t j = 0; j < nf; j++) {
      const double *R = g->wrng + ws * per, *x = R + 2 * j * DT_NV;
      double c[6], t[6], u, l;
      for (int f = 0; f < 3; f++) {
        const double *y = x + 6 * f;
        double m0 = dmax(fabs(y[0]), fabs(y[1])) * DG_EPS_L;
        c[2 * f] = y[0] - m0, c[2 * f + 1] = y[1] + m0;
      }
      a_terms(x, a0, a1, t);
      for (int q = 0; q < 2; q++) {
        if (q == 1 && T->entry[j].hinge >= 0)
          continue;
        ebound(c, t, q, &u, &l);
        W[q] = !(u <= W[q]) ? (isnan(u) ? INFINITY : u) : W[q];
      }
    }
  g->wall[ia][0] = upper_f(W[0]), g->wall[ia][1] = upper_f(W[1]);
  return 1;
}

int aq_dg_make_wall(aq_demand_grid *g, size_t ia)
{
  pthread_mutex_lock(&g->lock);
  int b = atomic_load_explicit(&g->wall_made[ia], memory_order_relaxed);
  if (b == 0) {
    b = wall_bin(g, ia);
    atomic_store_explicit(&g->wall_made[ia], b, memory_order_release);
  }
  pthread_mutex_unlock(&g->lock);
  return b;
}

int aq_dg_make(aq_demand_grid *g, size_t k)
{
  size_t is = k / (DG_NK * DG_NB), ik = k / DG_NB % DG_NK;
  pthread_mutex_lock(&g->lock);
  int b = atomic_load_explicit(&g->built[k], memory_order_relaxed);
  if (b == 0) {
    if (!g->rng[is] && (g->rng[is] = malloc((g->t->nf * 2 * DT_NV + 2) * sizeof(double))))
      ranges(g->t, is, g->rng[is]);
    b = g->rng[is] && block(g, is, ik, k % DG_NB, g->rng[is]) == 0 ? 1 : 2;
    atomic_store_explicit(&g->built[k], b, memory_order_release);
  }
  pthread_mutex_unlock(&g->lock);
  return b == 1 ? 0 : -1;
}

aq_demand_grid *aq_dg_build(const aq_demand_table *t)
{
  size_t nr = (size_t)DG_NS * DG_NK * DG_NA;
  if (t->nf > UINT16_MAX || !(t->lambda0 > 0) || !(t->ke_ref > 0) || !(t->s_c > 0))
    return NULL;
  aq_demand_grid *g = calloc(1, sizeof *g);
  if (!g)
    return NULL;
  g->hu = malloc(nr * sizeof *g->hu);
  if (!g->hu || pthread_mutex_init(&g->lock, NULL) != 0) {
    free(g->hu), free(g);
    return NULL;
  }
  g->t = t;
  for (size_t c = 0; c < nr; c++)
    atomic_init(&g->hu[c], (uint32_t)DG_UNMADE << 16 | DG_UNMADE);
  for (size_t b = 0; b < DG_NBLK; b++)
    atomic_init(&g->built[b], 0);
  for (size_t ia = 0; ia < DG_NA; ia++)
    atomic_init(&g->wall_made[ia], 0);
  g->inv_ds = DG_NS / t->s_c;
  g->da = t->lambda0 / 8, g->inv_da = 1 / g->da;
  g->k0 = t->ke_ref / (double)(1 << 10), g->inv_k0 = 1 / g->k0;
  return g;
}
