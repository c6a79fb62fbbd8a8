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

/* The range of cubic c over u in [ua, ub], widened for rounding. */
static void cubic_range(const double c[4], double ua, double ub, double *lo, double *hi)
{
  double a = aq_dt_cubic(c, ua), b = aq_dt_cubic(c, ub);
  double l = fmin(a, b), h = fmax(a, b);
  /* critical points: c1 + 2 c2 u + 3 c3 u^2 = 0 */
  double A = 3 * c[3], B = 2 * c[2], C = c[1], r[2];
  int nr = 0;
  if (A == 0) {
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
      l = fmin(l, v), h = fmax(h, v);
    }
  double e = DG_EPS_C * (fabs(c[0]) + fabs(c[1]) + fabs(c[2]) + fabs(c[3]));
  *lo = l - e, *hi = h + e;
}

void aq_dg_free(aq_demand_grid *g)
{
  if (!g)
    return;
  free(g->hu);
  free(g->cell);
  free(g->pool);
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

/* The top half of the bits of a float at least u (u >= 0): an upper bound
 * with 8 significant bits. */
static uint16_t upper16(double u)
{
  if (!(u < 3e38))
    return 0x7f80; /* INFINITY (and NAN: no bound) */
  float f = (float)u;
  if ((double)f < u)
    f = nextafterf(f, INFINITY);
  uint32_t b;
  memcpy(&b, &f, sizeof b);
  return (uint16_t)((b + 0xffffu) >> 16);
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

enum { DG_AB = 8 }; /* a/g bins per block: the entries below the block's largest
                       lower bound are left out of its cells */

/* Cell bounds of one s-range (its forms' ranges R: lo/hi per form, then
 * 1/M's), every a/g and KE/g bin, into cells[ik * NA + ia] and the pool. */
typedef struct {
  size_t nf;
  const int *hinge;
  double *at, *ab, *cw; /* per entry: the a/g terms' ranges per bin and per block
                           (lo/hi of N T e), the constant and KE terms' for one KE/g bin */
  double *u;            /* per entry: both quantities' bounds (u, l) */
  uint16_t *tmp, *list;
} slab_ws;

static int slab(aq_demand_grid *g, const double *R, slab_ws *W, aq_dg_cell *cells, size_t *cap)
{
  size_t nf = W->nf, nb = DG_NA / DG_AB;
  double rm0 = R[2 * nf * DT_NV], rm1 = R[2 * nf * DT_NV + 1];
  for (size_t j = 0; j < nf; j++)
    for (int f = 0; f < 3; f++) {
      const double *x = R + 2 * (j * DT_NV + 3 * (size_t)f); /* x0 lo hi, x1 lo hi, x2 lo hi */
      for (size_t ia = 0; ia < DG_NA; ia++) {
        double a0, a1, *o = W->at + ((j * DG_NA + ia) * 3 + (size_t)f) * 2;
        bin_a(g, ia, &a0, &a1);
        prod_range(x[2], x[3], a0, a1, &o[0], &o[1]);
        double *ob = W->ab + ((j * nb + ia / DG_AB) * 3 + (size_t)f) * 2;
        if (ia % DG_AB == 0)
          ob[0] = o[0], ob[1] = o[1];
        ob[0] = o[0] < ob[0] ? o[0] : ob[0], ob[1] = o[1] > ob[1] ? o[1] : ob[1];
      }
    }
  for (size_t ik = 0; ik < DG_NK; ik++) {
    double k0, k1;
    bin_k(g, ik, &k0, &k1);
    double w0 = 2 * k0 * rm0 * (1 - DG_EPS_L), w1 = 2 * k1 * rm1 * (1 + DG_EPS_L);
    for (size_t j = 0; j < nf; j++)
      for (int f = 0; f < 3; f++) {
        const double *x = R + 2 * (j * DT_NV + 3 * (size_t)f);
        double lo, hi, m0 = fmax(fabs(x[0]), fabs(x[1])) * DG_EPS_L;
        prod_range(x[4], x[5], w0, w1, &lo, &hi);
        W->cw[6 * j + 2 * (size_t)f] = x[0] + lo - m0;
        W->cw[6 * j + 2 * (size_t)f + 1] = x[1] + hi + m0;
      }
    for (size_t bl = 0; bl < nb; bl++) {
      /* the block's entries: those whose upper bound over the block reaches
       * its largest lower bound, per quantity */
      size_t nq[2] = {0, 0};
      uint16_t *lq[2] = {W->list, W->list + nf};
      for (int q = 0; q < 2; q++) {
        double Lm = 0;
        for (size_t j = 0; j < nf; j++) {
          double *u = W->u + 2 * j;
          if (q == 1 && W->hinge[j])
            u[0] = u[1] = 0;
          else if (!(rm0 > 0))
            u[0] = INFINITY, u[1] = 0;
          else
            ebound(W->cw + 6 * j, W->ab + (j * nb + bl) * 6, q, &u[0], &u[1]);
          Lm = u[1] > Lm ? u[1] : Lm;
        }
        for (size_t j = 0; j < nf; j++)
          if ((q == 0 || !W->hinge[j]) && W->u[2 * j] >= Lm)
            lq[q][nq[q]++] = (uint16_t)j;
      }
      for (size_t ia = bl * DG_AB; ia < (bl + 1) * DG_AB; ia++) {
        aq_dg_cell *cl = cells + ik * DG_NA + ia;
        size_t c0 = 0;
        for (int q = 0; q < 2; q++) {
          double U = 0, L = 0;
          for (size_t m = 0; m < nq[q]; m++) {
            size_t j = lq[q][m];
            double *u = W->u + 2 * j;
            if (!(rm0 > 0))
              u[0] = INFINITY, u[1] = 0;
            else
              ebound(W->cw + 6 * j, W->at + (j * DG_NA + ia) * 6, q, &u[0], &u[1]);
            U = u[0] > U ? u[0] : U;
            L = u[1] > L ? u[1] : L;
          }
          size_t c = 0;
          for (size_t m = 0; m < nq[q]; m++)
            if (W->u[2 * (size_t)lq[q][m]] >= L)
              W->tmp[c0 + c++] = lq[q][m];
          cl->n[q] = c < DG_ALL ? (uint8_t)c : DG_ALL;
          c0 += c < DG_ALL ? c : 0;
          g->hu[2 * (size_t)(cl - g->cell) + (size_t)q] = upper16(U);
        }
        if (c0 <= DG_INLINE) {
          memcpy(cl->c, W->tmp, c0 * sizeof *W->tmp);
          cl->off = 0;
          continue;
        }
        if (g->npool + c0 > *cap) {
          size_t nc = 2 * (g->npool + c0);
          uint16_t *p = realloc(g->pool, nc * sizeof *p);
          if (!p)
            return -1;
          g->pool = p, *cap = nc;
        }
        cl->off = (uint32_t)g->npool;
        memcpy(g->pool + g->npool, W->tmp, c0 * sizeof *W->tmp);
        g->npool += c0;
      }
    }
  }
  return 0;
}

aq_demand_grid *aq_dg_build(const aq_demand_table *t)
{
  size_t nf = t->nf, nr = (size_t)DG_NS * DG_NK * DG_NA;
  if (nf > UINT16_MAX || !(t->lambda0 > 0) || !(t->ke_ref > 0) || !(t->s_c > 0))
    return NULL;
  aq_demand_grid *g = calloc(1, sizeof *g);
  size_t rstride = nf * 2 * DT_NV + 2;
  double *R = malloc(DG_NS * rstride * sizeof *R);
  int *hinge = malloc(nf * sizeof *hinge);
  slab_ws W = {nf, hinge, malloc(nf * DG_NA * 6 * sizeof(double)),
               malloc(nf * (DG_NA / DG_AB) * 6 * sizeof(double)), malloc(nf * 6 * sizeof(double)),
               malloc(nf * 2 * sizeof(double)), malloc(2 * nf * sizeof(uint16_t)),
               malloc(2 * nf * sizeof(uint16_t))};
  size_t cap = 2 * nr;
  if (g) {
    g->cell = malloc(nr * sizeof *g->cell);
    g->hu = malloc(2 * nr * sizeof *g->hu);
    g->pool = malloc(cap * sizeof *g->pool);
  }
  int ok = g && R && hinge && W.at && W.ab && W.cw && W.u && W.tmp && W.list && g->cell && g->hu && g->pool;
  if (ok) {
    for (size_t j = 0; j < nf; j++)
      hinge[j] = t->entry[j].hinge >= 0;
    g->inv_ds = DG_NS / t->s_c;
    g->da = t->lambda0 / 8, g->inv_da = 1 / g->da;
    g->k0 = t->ke_ref / (double)(1 << 10), g->inv_k0 = 1 / g->k0;
  }
  for (size_t is = 0; ok && is < DG_NS; is++) {
    double *Rs = R + is * rstride;
    double s0 = t->s_c * (double)is / DG_NS, s1 = t->s_c * (double)(is + 1) / DG_NS;
    double pad = DG_PAD * (s1 - s0);
    s0 = fmax(0, s0 - pad), s1 = fmin(t->s_c, s1 + pad);
    for (size_t k = 0; k < nf * DT_NV + 1; k++)
      Rs[2 * k] = INFINITY, Rs[2 * k + 1] = -INFINITY;
    for (size_t i = 0; i < t->nint; i++) {
      if (t->bp[i + 1] < s0 || t->bp[i] > s1)
        continue;
      double ua = fmax(0, (s0 - t->bp[i]) * t->ih[i]), ubb = fmin(1, (s1 - t->bp[i]) * t->ih[i]);
      const double *C = t->c + i * t->stride;
      for (size_t k = 0; k <= nf * DT_NV; k++) {
        const double *c = k < nf * DT_NV ? C + k * DT_NC : C + (nf * DT_NV + 3) * DT_NC;
        double lo, hi;
        cubic_range(c, ua, ubb, &lo, &hi);
        Rs[2 * k] = fmin(Rs[2 * k], lo), Rs[2 * k + 1] = fmax(Rs[2 * k + 1], hi);
      }
    }
    ok = slab(g, Rs, &W, g->cell + is * DG_NK * DG_NA, &cap) == 0;
  }
  for (size_t ia = 0; ok && ia < DG_NA; ia++)
    for (int q = 0; q < 2; q++) {
      double m = 0;
      for (size_t is = 0; is < DG_NS; is++)
        m = fmax(m, aq_dg_bound(g, (long)((is * DG_NK) * DG_NA + ia), q));
      g->wall[ia][q] = (float)m; /* a bound as stored: exact in a float */
    }
  free(R), free(hinge), free(W.at), free(W.ab), free(W.cw), free(W.u), free(W.tmp), free(W.list);
  if (!ok) {
    aq_dg_free(g);
    return NULL;
  }
  return g;
}
