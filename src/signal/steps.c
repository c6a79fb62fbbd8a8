/* steps.c: constant-acceleration steps and their quiet index (see steps.h). */
#include "steps.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__SSE2__) && !defined(AQ_NO_SIMD)
#include <emmintrin.h>
#endif

enum { AQ_STEPS_BLOCK = 64 }; /* steps per quiet-index block */

void aq_steps_free(aq_steps *s)
{
  if (!s)
    return;
  free(s->t_s);
  free(s->dt_s);
  if (!s->borrowed)
    free(s->a_mps2);
  free(s->block_min_mps2);
  free(s->block_max_mps2);
  free(s->av_mps2);
  memset(s, 0, sizeof *s);
}

/* n steps; times: 1 for t_s and dt_s arrays, 0 for equal steps; borrow:
 * a_mps2 (the caller's) instead of an array of samples. */
static aq_status steps_alloc_over(aq_steps *s, size_t n, int times, double *borrow,
                                  aq_error *err)
{
  memset(s, 0, sizeof *s);
  size_t m = n ? n : 1;
  s->block = AQ_STEPS_BLOCK;
  s->nblock = (n + s->block - 1) / s->block;
  size_t nb = s->nblock ? s->nblock : 1;
  if (times) {
    s->t_s = malloc(m * sizeof *s->t_s);
    s->dt_s = malloc(m * sizeof *s->dt_s);
  }
  s->borrowed = borrow != NULL;
  s->a_mps2 = borrow ? borrow : malloc(m * sizeof *s->a_mps2);
  s->block_min_mps2 = malloc(nb * sizeof *s->block_min_mps2);
  s->block_max_mps2 = malloc(nb * sizeof *s->block_max_mps2);
  if ((times && (!s->t_s || !s->dt_s)) || !s->a_mps2 || !s->block_min_mps2 ||
      !s->block_max_mps2) {
    aq_steps_free(s);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "steps",
                        "cannot allocate %zu steps", n);
  }
  s->n = n;
  return AQ_OK;
}

static aq_status steps_alloc(aq_steps *s, size_t n, int times, aq_error *err)
{
  return steps_alloc_over(s, n, times, NULL, err);
}

/* The least and the greatest of a[0..n), n > 0 (finite values: which of
 * two equal zeros is kept does not matter, every use compares them). */
static void extremes(const double *a, size_t n, double *lo_out, double *hi_out)
{
  double lo = a[0], hi = a[0];
  size_t i = 1;
#if defined(__SSE2__) && !defined(AQ_NO_SIMD) /* every x86-64 CPU */
  if (n >= 8) { /* eight running extremes in four pairs: 3.6x the loop below */
    __m128d l0 = _mm_loadu_pd(a), l1 = _mm_loadu_pd(a + 2), l2 = _mm_loadu_pd(a + 4),
            l3 = _mm_loadu_pd(a + 6);
    __m128d h0 = l0, h1 = l1, h2 = l2, h3 = l3;
    for (i = 8; i + 8 <= n; i += 8) {
      __m128d x0 = _mm_loadu_pd(a + i), x1 = _mm_loadu_pd(a + i + 2),
              x2 = _mm_loadu_pd(a + i + 4), x3 = _mm_loadu_pd(a + i + 6);
      l0 = _mm_min_pd(x0, l0);
      l1 = _mm_min_pd(x1, l1);
      l2 = _mm_min_pd(x2, l2);
      l3 = _mm_min_pd(x3, l3);
      h0 = _mm_max_pd(x0, h0);
      h1 = _mm_max_pd(x1, h1);
      h2 = _mm_max_pd(x2, h2);
      h3 = _mm_max_pd(x3, h3);
    }
    double l[2], h[2];
    _mm_storeu_pd(l, _mm_min_pd(_mm_min_pd(l0, l1), _mm_min_pd(l2, l3)));
    _mm_storeu_pd(h, _mm_max_pd(_mm_max_pd(h0, h1), _mm_max_pd(h2, h3)));
    lo = l[1] < l[0] ? l[1] : l[0];
    hi = h[1] > h[0] ? h[1] : h[0];
  }
#endif
  for (; i < n; i++) {
    if (a[i] < lo)
      lo = a[i];
    if (a[i] > hi)
      hi = a[i];
  }
  *lo_out = lo;
  *hi_out = hi;
}

static void steps_index(aq_steps *s)
{
  s->nblock = (s->n + s->block - 1) / s->block;
  for (size_t b = 0; b < s->nblock; b++) {
    size_t i0 = b * s->block, i1 = i0 + s->block;
    if (i1 > s->n)
      i1 = s->n;
    extremes(s->a_mps2 + i0, i1 - i0, &s->block_min_mps2[b], &s->block_max_mps2[b]);
  }
}

/* The sample i of a projection: s (c1 a1[i] + c2 a2[i]), or s c1 a1[i]
 * without a2 (so that s = c1 = 1 gives a1[i] itself). */
static inline double sample(const double *a1, double c1, const double *a2,
                            double c2, double s, size_t i)
{
  return a2 ? s * (c1 * a1[i] + c2 * a2[i]) : s * (c1 * a1[i]);
}

/* dt_s must be a finite step > 0 s. */
static aq_status check_dt(double dt_s, aq_error *err)
{
  if (!(dt_s > 0) || !isfinite(dt_s))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "dt",
                        "expected a finite step > 0 s, got %g", dt_s);
  return AQ_OK;
}

static aq_status steps_build(const double *a1, double c1, const double *a2,
                             double c2, double sc, const double *v, double sv,
                             size_t n, double dt_s, double t0_s,
                             double merge_tol_mps2, aq_steps *out,
                             double *peak_mps2, aq_error *err)
{
  if (check_dt(dt_s, err) != AQ_OK)
    return AQ_EVALUE;
  if (!(merge_tol_mps2 >= 0) || !isfinite(merge_tol_mps2))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "merge-tol",
                        "expected a finite tolerance >= 0, got %g",
                        merge_tol_mps2);
  aq_status st = steps_alloc(out, n, merge_tol_mps2 > 0, err);
  if (st != AQ_OK)
    return st;
  if (v && !(out->av_mps2 = malloc((n ? n : 1) * sizeof *out->av_mps2))) {
    aq_steps_free(out);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "steps",
                        "cannot allocate %zu steps", n);
  }
  size_t k = 0;
  double peak = 0;
  if (merge_tol_mps2 == 0) {
    /* one step per sample (the default): the loop below with j = i + 1,
     * whose divisions by 1 and products by 1 are exact, without them; the
     * times it would store are t0_s + i dt_s and dt_s (aq_steps_t, _dt) */
    out->t0_s = t0_s;
    out->step_s = dt_s;
    for (size_t i = 0; i < n; i++) {
      double a = sample(a1, c1, a2, c2, sc, i), fa = fabs(a);
      peak = fa > peak ? fa : peak;
      out->a_mps2[i] = a;
      if (v)
        out->av_mps2[i] = sv * v[i];
    }
    k = n;
  }
  for (size_t i = k; i < n;) {
    size_t j = i + 1;
    double first = sample(a1, c1, a2, c2, sc, i), sum = first;
    double vfirst = v ? sv * v[i] : 0, vsum = vfirst;
    peak = fabs(first) > peak ? fabs(first) : peak; /* finite: as fmax, inline */
    if (merge_tol_mps2 > 0) {
      /* grow the run while every sample stays within tol of the run's first */
      double lo = first, hi = first, vlo = vfirst, vhi = vfirst;
      while (j < n) {
        double a = sample(a1, c1, a2, c2, sc, j), b = v ? sv * v[j] : 0;
        double nlo = a < lo ? a : lo, nhi = a > hi ? a : hi;
        double nvlo = b < vlo ? b : vlo, nvhi = b > vhi ? b : vhi;
        if (nhi - nlo >= merge_tol_mps2 || nvhi - nvlo >= merge_tol_mps2)
          break;
        lo = nlo;
        hi = nhi;
        vlo = nvlo;
        vhi = nvhi;
        sum += a;
        vsum += b;
        peak = fabs(a) > peak ? fabs(a) : peak;
        j++;
      }
    }
    if (v)
      out->av_mps2[k] = vsum / (double)(j - i);
    /* index arithmetic from t0 keeps times free of accumulated round-off */
    out->t_s[k] = t0_s + (double)i * dt_s;
    out->dt_s[k] = (double)(j - i) * dt_s;
    out->a_mps2[k] = sum / (double)(j - i);
    k++;
    i = j;
  }
  out->n = k;
  steps_index(out);
  if (peak_mps2)
    *peak_mps2 = peak;
  return AQ_OK;
}

aq_status aq_steps_from_samples(const double *a_mps2, size_t n, double dt_s,
                                double t0_s, double merge_tol_mps2,
                                aq_steps *out, aq_error *err)
{
  return steps_build(a_mps2, 1.0, NULL, 0.0, 1.0, NULL, 0.0, n, dt_s, t0_s,
                     merge_tol_mps2, out, NULL, err);
}

aq_status aq_steps_project(const double *a1_mps2, double c1, const double *a2_mps2,
                           double c2, double scale, size_t n, double dt_s,
                           double t0_s, double merge_tol_mps2, aq_steps *out,
                           double *peak_mps2, aq_error *err)
{
  return steps_build(a1_mps2, c1, a2_mps2, c2, scale, NULL, 0.0, n, dt_s, t0_s,
                     merge_tol_mps2, out, peak_mps2, err);
}

aq_status aq_steps_project_v(const double *a1_mps2, double c1, const double *a2_mps2,
                             double c2, double scale, const double *av_mps2,
                             double vscale, size_t n, double dt_s, double t0_s,
                             double merge_tol_mps2, aq_steps *out,
                             double *peak_mps2, aq_error *err)
{
  return steps_build(a1_mps2, c1, a2_mps2, c2, scale, av_mps2, vscale, n, dt_s,
                     t0_s, merge_tol_mps2, out, peak_mps2, err);
}

aq_status aq_steps_over(double *a_mps2, size_t n, double dt_s, double t0_s,
                        aq_steps *out, double *peak_mps2, aq_error *err)
{
  aq_status st = check_dt(dt_s, err);
  if (st == AQ_OK)
    st = steps_alloc_over(out, n, 0, a_mps2, err);
  if (st != AQ_OK)
    return st;
  out->t0_s = t0_s;
  out->step_s = dt_s;
  steps_index(out);
  /* max |a| over the blocks' extremes: each is a sample, and every sample
   * lies between its block's, so this is max |a_i| itself */
  double peak = 0;
  for (size_t b = 0; b < out->nblock; b++) {
    double lo = fabs(out->block_min_mps2[b]), hi = fabs(out->block_max_mps2[b]);
    peak = lo > peak ? lo : peak;
    peak = hi > peak ? hi : peak;
  }
  if (peak_mps2)
    *peak_mps2 = peak;
  return AQ_OK;
}

aq_status aq_steps_set_vertical(aq_steps *s, const double *av_mps2, aq_error *err)
{
  for (size_t i = 0; i < s->n; i++)
    if (!isfinite(av_mps2[i]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "step",
                          "step %zu: expected a finite vertical acceleration, got %g",
                          i, av_mps2[i]);
  double *v = malloc((s->n ? s->n : 1) * sizeof *v);
  if (!v)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "steps",
                        "cannot allocate %zu steps", s->n);
  if (s->n)
    memcpy(v, av_mps2, s->n * sizeof *v);
  free(s->av_mps2);
  s->av_mps2 = v;
  return AQ_OK;
}

aq_status aq_steps_from_list(const double *t_s, const double *dt_s,
                             const double *a_mps2, size_t n, aq_steps *out,
                             aq_error *err)
{
  for (size_t i = 0; i < n; i++) {
    if (!(dt_s[i] > 0) || !isfinite(dt_s[i]) || !isfinite(t_s[i]) ||
        !isfinite(a_mps2[i]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "step",
                          "step %zu: expected finite values and a duration "
                          "> 0 s, got t=%g dt=%g a=%g",
                          i, t_s[i], dt_s[i], a_mps2[i]);
  }
  aq_status st = steps_alloc(out, n, 1, err);
  if (st != AQ_OK)
    return st;
  if (n) {
    memcpy(out->t_s, t_s, n * sizeof *t_s);
    memcpy(out->dt_s, dt_s, n * sizeof *dt_s);
    memcpy(out->a_mps2, a_mps2, n * sizeof *a_mps2);
  }
  steps_index(out);
  return AQ_OK;
}

size_t aq_steps_next_outside(const aq_steps *s, size_t from, double lo,
                             double hi)
{
  size_t i = from;
  while (i < s->n) {
    size_t b = i / s->block;
    if (i % s->block == 0 && s->block_min_mps2[b] >= lo &&
        s->block_max_mps2[b] <= hi) {
      i += s->block; /* whole block quiet */
      continue;
    }
    double a = s->a_mps2[i];
    if (a < lo || a > hi)
      return i;
    i++;
  }
  return s->n;
}
