/* spectrum_rotd.c: RotD of two horizontal components (spectrum.h,
 * spectrum_int.h).
 *
 * RotD (Boore 2010, BSSA 100(4) 1830-1835).  The oscillator is linear, so
 * the response to a1 cos(theta) + a2 sin(theta) is x1 cos(theta) + x2
 * sin(theta): each angle's peak is taken over that combination of the two
 * histories (never from the two peaks).  At the samples, a point whose norm
 * sqrt(x1^2 + x2^2) is below a lower bound L of every angle's peak cannot
 * be any angle's peak; L comes from the four points that peak along 0, 45,
 * 90 and 135 degrees, and only the points above it are projected on every
 * angle.  Between samples the same bounds as one component's (sdof.c), for
 * the two components together, select the intervals to search in each
 * direction.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "spectrum_int.h"

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* cos and sin of angle j of n over [0, 180) degrees, exact at 0 and 90. */
static void angle_cs(size_t j, size_t n, double *c, double *s)
{
  if (j == 0) {
    *c = 1;
    *s = 0;
  } else if (2 * j == n) {
    *c = 0;
    *s = 1;
  } else {
    double th = AQ_PI * (double)j / (double)n;
    *c = cos(th);
    *s = sin(th);
  }
}

static int cmp_pt2(const void *a, const void *b)
{
  const pt2 *p = a, *q = b;
  if (p->x != q->x)
    return (p->x > q->x) - (p->x < q->x);
  return (p->y > q->y) - (p->y < q->y);
}

static inline double cross(pt2 o, pt2 a, pt2 b)
{
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/* The convex hull's vertices of the m points p (sorted in place) into h
 * (room for 2 m): Andrew's monotone chain.  Returns their number. */
static size_t hull2(pt2 *p, size_t m, pt2 *h)
{
  qsort(p, m, sizeof *p, cmp_pt2);
  if (m < 3) {
    memcpy(h, p, m * sizeof *p);
    return m;
  }
  size_t k = 0;
  for (size_t i = 0; i < m; i++) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0)
      k--;
    h[k++] = p[i];
  }
  for (size_t i = m - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0)
      k--;
    h[k++] = p[i];
  }
  return k - 1;
}

/* Directions of the lower bound of every angle's peak (below): 4, then
 * LO_DIRS. */
enum { LO_DIRS = 16 };

/* The nd directions pi d / nd, d = 0..nd-1: cos into dc, sin into ds. */
static void lo_dirs(int nd, double *dc, double *ds)
{
  for (int d = 0; d < nd; d++) {
    dc[d] = cos(AQ_PI * d / nd);
    ds[d] = sin(AQ_PI * d / nd);
  }
}

/* Both components' responses at the samples, x1, y1 of a1 (n1 samples)
 * and x2, y2 of a2 (n2), k = 0..nt-1, the input zero past its samples:
 * each step aq_sdof_respond()'s, the two in one loop (two independent chains, so
 * one's wait is the other's work); and in the same loop the first pass of
 * rotd_peaks(): for each of its 4 first directions, the first sample k
 * where |c x1 + s x2| is largest, into q[4] (any points give a valid
 * lower bound, so q decides only how many points the hull is taken of; the
 * same as rotd_peaks' own scan, so the same work follows).  o is not the
 * PGA's. */
static void respond2(const aq_sdof *o, const double *a1, size_t n1, const double *a2,
                     size_t n2, size_t nt, double *x1, double *y1, double *x2,
                     double *y2, size_t *q)
{
  double dc[4], ds[4], qm[4];
  lo_dirs(4, dc, ds);
  double p00 = o->p[0][0], p01 = o->p[0][1], p10 = o->p[1][0],
         p11 = o->p[1][1];
  double b00 = o->b[0][0], b01 = o->b[0][1], b10 = o->b[1][0],
         b11 = o->b[1][1];
  double xa = 0, ya = 0, xb = 0, yb = 0;
  double aa = acc_at(a1, n1, 0), ab = acc_at(a2, n2, 0);
  x1[0] = y1[0] = x2[0] = y2[0] = 0;
  for (int d = 0; d < 4; d++) {
    qm[d] = fabs(dc[d] * x1[0] + ds[d] * x2[0]);
    q[d] = 0;
  }
  for (size_t k = 0; k + 1 < nt; k++) {
    double na = acc_at(a1, n1, k + 1), nb = acc_at(a2, n2, k + 1);
    double xn = p00 * xa + p01 * ya + b00 * aa + b01 * na;
    double yn = p10 * xa + p11 * ya + b10 * aa + b11 * na;
    double un = p00 * xb + p01 * yb + b00 * ab + b01 * nb;
    double vn = p10 * xb + p11 * yb + b10 * ab + b11 * nb;
    x1[k + 1] = xa = xn;
    y1[k + 1] = ya = yn;
    x2[k + 1] = xb = un;
    y2[k + 1] = yb = vn;
    aa = na;
    ab = nb;
    for (int d = 0; d < 4; d++) {
      double v = fabs(dc[d] * xn + ds[d] * un);
      if (v > qm[d]) {
        qm[d] = v;
        q[d] = k + 1;
      }
    }
  }
}

/* PEER's refined points of both components, in the intervals where the
 * two components' bounds together (|c x1 + s x2| <= sqrt(b1^2 + b2^2))
 * pass lo_all, the smallest angle's peak at the samples, joined to the nh
 * vertices of the samples' hull (ws->hull): every angle's peak over the
 * hull of all.  s steps dt / steps.  0 when out of memory. */
static int rotd_refined(aq_spectrum_ws *ws, const aq_sdof *o, const aq_sdof *s, size_t steps,
                        const double *a1, size_t n1, const double *a2, size_t n2,
                        size_t nt, size_t na, size_t nh, double lo_all, double *peak)
{
  const double *x1 = ws->x1, *x2 = ws->x2, *y1 = ws->y1, *y2 = ws->y2;
  if (!aq_spectrum_ws_reserve_ref(ws, nh) || !aq_spectrum_ws_reserve_steps(ws, steps))
    return 0;
  memcpy(ws->ref, ws->hull, nh * sizeof *ws->ref);
  size_t m = nh;
  double lo2 = lo_all * lo_all, th = o->theta;
  for (size_t k = 0; k + 1 < nt; k++) {
    double a10 = acc_at(a1, n1, k), a11 = acc_at(a1, n1, k + 1);
    double a20 = acc_at(a2, n2, k), a21 = acc_at(a2, n2, k + 1);
    double s1 = (a11 - a10) * o->inv_theta, s2 = (a21 - a20) * o->inv_theta;
    double b1 = piece_bound(o, th, x1[k], y1[k], x1[k + 1], a10, a11, s1);
    double b2 = piece_bound(o, th, x2[k], y2[k], x2[k + 1], a20, a21, s2);
    if (b1 * b1 + b2 * b2 <= lo2)
      continue;
    substeps(s, steps, x1[k], y1[k], a10, a11, ws->xs1);
    substeps(s, steps, x2[k], y2[k], a20, a21, ws->xs2);
    if (!aq_spectrum_ws_reserve_ref(ws, m + steps - 1))
      return 0;
    for (size_t j = 0; j + 1 < steps; j++)
      ws->ref[m++] = (pt2){ws->xs1[j], ws->xs2[j]};
  }
  if (m == nh)
    return 1;
  size_t nr = hull2(ws->ref, m, ws->ref_hull);
  for (size_t j = 0; j < na; j++) {
    double h = 0, c = ws->cs[j], sn = ws->sn[j];
    for (size_t i = 0; i < nr; i++)
      h = dmax(h, fabs(c * ws->ref_hull[i].x + sn * ws->ref_hull[i].y));
    peak[j] = h;
  }
  return 1;
}

/* Peaks of every angle for one period: ws->x1.. hold the two responses at
 * the samples (nt of them); sub and steps: PEER's refined oscillator.
 * 0 when out of memory. */
static int rotd_peaks(aq_spectrum_ws *ws, const aq_sdof *o, const aq_sdof *sub, size_t steps,
                      const double *a1, size_t n1, const double *a2, size_t n2,
                      size_t nt, size_t na, aq_spectrum_peaks peaks, const size_t *q_first,
                      double *peak)
{
  const double *x1 = ws->x1, *x2 = ws->x2, *y1 = ws->y1, *y2 = ws->y2;
  const double *cs = ws->cs, *sn = ws->sn;
  /* At the samples: every angle's peak is at a vertex of the points'
   * convex hull (|projection| on a direction peaks there).  The hull is
   * taken of the points that can reach the smallest peak: a lower bound lo
   * of every angle's peak comes from the points that peak along a few
   * directions (first 4 over all points, then 16 over those above the
   * first bound), and a point of norm below it is no angle's peak.  The
   * first 4 come from respond2 (q_first) unless NULL. */
  double lo = 0;
  size_t np = 0;
  for (int pass = 0; pass < 2; pass++) {
    int nd = pass ? LO_DIRS : 4;
    double dc[LO_DIRS], ds[LO_DIRS], qm[LO_DIRS];
    size_t q[LO_DIRS];
    lo_dirs(nd, dc, ds);
    for (int d = 0; d < nd; d++) {
      qm[d] = -1;
      q[d] = pass || !q_first ? 0 : q_first[d];
    }
    size_t m = pass ? np : nt;
    for (size_t i = 0; i < m && (pass || !q_first); i++) {
      size_t k = pass ? ws->pts[i] : i;
      for (int d = 0; d < nd; d++) {
        double v = fabs(dc[d] * x1[k] + ds[d] * x2[k]);
        if (v > qm[d]) {
          qm[d] = v;
          q[d] = k;
        }
      }
    }
    double l = INFINITY;
    for (size_t j = 0; j < na; j++) {
      double h = 0;
      for (int d = 0; d < nd; d++) {
        double v = fabs(cs[j] * x1[q[d]] + sn[j] * x2[q[d]]);
        h = v > h ? v : h;
      }
      l = h < l ? h : l;
    }
    lo = l > lo ? l : lo;
    double lo2 = lo * lo;
    size_t kept = 0;
    for (size_t i = 0; i < m; i++) {
      size_t k = pass ? ws->pts[i] : i;
      if (x1[k] * x1[k] + x2[k] * x2[k] >= lo2)
        ws->pts[kept++] = k;
    }
    np = kept;
  }
  for (size_t i = 0; i < np; i++) {
    ws->pp[i].x = x1[ws->pts[i]];
    ws->pp[i].y = x2[ws->pts[i]];
  }
  size_t nh = hull2(ws->pp, np, ws->hull);
  double lo_all = INFINITY;
  for (size_t j = 0; j < na; j++) {
    double h = 0, c = cs[j], s = sn[j];
    for (size_t i = 0; i < nh; i++) {
      double v = fabs(c * ws->hull[i].x + s * ws->hull[i].y);
      h = v > h ? v : h;
    }
    peak[j] = h;
    lo_all = h < lo_all ? h : lo_all;
  }
  if (o->pga || peaks == AQ_SPECTRUM_PEAKS_SAMPLES ||
      (peaks == AQ_SPECTRUM_PEAKS_PEER && steps < 2))
    return 1;
  if (peaks == AQ_SPECTRUM_PEAKS_PEER)
    return rotd_refined(ws, o, sub, steps, a1, n1, a2, n2, nt, na, nh, lo_all, peak);
  /* Between samples: an interval can raise an angle's peak only if its
   * larger end's projection plus its slack rho (the chord and transient
   * bounds for both components together: |c u + s v| <= |u| + |v|) passes
   * that peak; first those whose norm could pass the smallest peak. */
  size_t ni = 0;
  double th = o->theta, z2 = 2 * o->zeta;
  for (size_t k = 0; k + 1 < nt; k++) {
    double a10 = acc_at(a1, n1, k), a11 = acc_at(a1, n1, k + 1);
    double a20 = acc_at(a2, n2, k), a21 = acc_at(a2, n2, k + 1);
    double am1 = dmax(fabs(a10), fabs(a11)), am2 = dmax(fabs(a20), fabs(a21));
    double m = am1 + am2 +
               o->kappa * (fabs(x1[k]) + fabs(y1[k]) + fabs(x2[k]) +
                           fabs(y2[k]) + (am1 + am2) * th);
    double s1 = (a11 - a10) * o->inv_theta, s2 = (a21 - a20) * o->inv_theta;
    double rh = fabs(x1[k] + a10 - z2 * s1) + fabs(y1[k] + s1) +
                fabs(x2[k] + a20 - z2 * s2) + fabs(y2[k] + s2);
    double rho = dmin(0.125 * th * th * m, 2 * rh);
    double need = lo_all - rho;
    double r0 = x1[k] * x1[k] + x2[k] * x2[k];
    double r1 = x1[k + 1] * x1[k + 1] + x2[k + 1] * x2[k + 1];
    if (need <= 0 || dmax(r0, r1) > need * need) {
      ws->rho[ni] = rho;
      ws->ivs[ni++] = k;
    }
  }
  for (size_t j = 0; j < na; j++) {
    double c = cs[j], s = sn[j];
    for (size_t i = 0; i < ni; i++) {
      size_t k = ws->ivs[i];
      double p0 = c * x1[k] + s * x2[k], p1 = c * x1[k + 1] + s * x2[k + 1];
      if (dmax(fabs(p0), fabs(p1)) + ws->rho[i] <= peak[j])
        continue;
      double b0 = c * acc_at(a1, n1, k) + s * acc_at(a2, n2, k);
      double b1 = c * acc_at(a1, n1, k + 1) + s * acc_at(a2, n2, k + 1);
      double q0 = c * y1[k] + s * y2[k], sig = (b1 - b0) * o->inv_theta;
      if (piece_bound(o, th, p0, q0, p1, b0, b1, sig) > peak[j])
        aq_sdof_search_interval(o, p0, q0, b0, b1, &peak[j]);
    }
  }
  return 1;
}

aq_status aq_spectrum_rotd(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                           const double *acc1_mps2, size_t n1,
                           const double *acc2_mps2, size_t n2, double dt_s,
                           double damping, const double *period_s,
                           size_t n_periods, aq_rotd *out,
                           double *angle_peaks_mps2, aq_error *err)
{
  aq_spectrum_opts def;
  if (!opts) {
    aq_spectrum_opts_default(&def);
    opts = &def;
  }
  aq_status st =
      aq_spectrum_check_args(acc1_mps2, n1, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = aq_spectrum_check_args(acc2_mps2, n2, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = aq_spectrum_check_peaks(opts, err);
  if (st != AQ_OK)
    return st;
  size_t na = opts->n_angles;
  if (na < 2 || na % 2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "n_angles",
                        "expected an even number of angles >= 2, got %zu", na);
  size_t n = n1 > n2 ? n1 : n2;
  if (!aq_spectrum_ws_reserve(ws, n, na))
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                        "out of memory for %zu samples", n);
  for (size_t j = 0; j < na; j++)
    angle_cs(j, na, &ws->cs[j], &ws->sn[j]);
  for (size_t i = 0; i < n_periods; i++) {
    aq_sdof o, sub;
    size_t steps = 1;
    st = aq_sdof_init(&o, period_s[i], damping, dt_s, err);
    if (st == AQ_OK && opts->peaks == AQ_SPECTRUM_PEAKS_PEER)
      st = aq_sdof_peer_init(&sub, &steps, period_s[i], damping, dt_s, err);
    if (st != AQ_OK)
      return st;
    size_t q[4];
    if (o.pga || opts->one_at_a_time) {
      aq_sdof_respond(&o, acc1_mps2, n1, n, ws->x1, ws->y1);
      aq_sdof_respond(&o, acc2_mps2, n2, n, ws->x2, ws->y2);
    } else {
      respond2(&o, acc1_mps2, n1, acc2_mps2, n2, n, ws->x1, ws->y1, ws->x2, ws->y2, q);
    }
    double *pk = ws->sorted; /* the angles' peaks, then sorted in place */
    if (!rotd_peaks(ws, &o, &sub, steps, acc1_mps2, n1, acc2_mps2, n2, n, na, opts->peaks,
                    o.pga || opts->one_at_a_time ? NULL : q, pk))
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                          "out of memory for the refined points of %zu samples", n);
    if (angle_peaks_mps2)
      memcpy(angle_peaks_mps2 + i * na, pk, na * sizeof *pk);
    aq_rotd *r = &out[i];
    r->psa1_mps2 = pk[0];
    r->psa2_mps2 = pk[na / 2];
    r->geomean_mps2 = sqrt(r->psa1_mps2 * r->psa2_mps2);
    qsort(pk, na, sizeof *pk, cmp_double);
    r->rotd50_mps2 = 0.5 * (pk[na / 2 - 1] + pk[na / 2]);
    r->rotd100_mps2 = pk[na - 1];
  }
  return AQ_OK;
}
