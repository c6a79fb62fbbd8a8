/* spectrum_batch.c: the batched kernels of the response spectra
 * (spectrum_int.h).
 *
 * Periods whose peak at the samples is all that is asked (no history kept)
 * run BATCH at a time through one pass over the record: one step of one
 * oscillator waits on its previous step (a product and three sums in a
 * chain, 12 to 16 cycles), so the steps of BATCH independent oscillators
 * fill the wait, and GCC vectorises the loop over them: SSE2 on any x86-64,
 * and a clone for AVX2 chosen at load time where the processor has it
 * (bench_spectrum: 16 at a time with AVX2 is 4 times faster than one at a
 * time; 8 at a time, or SSE2, gains less).  Each oscillator's arithmetic is
 * aq_sdof_respond()'s, in the same order (the sums left to right; no fused
 * multiply-add: -std=c11 turns contraction off and the clone does not
 * enable FMA), so its peak is the same to the bit. */
#include <math.h>

#include "spectrum_int.h"

enum { BATCH = AQ_SPECTRUM_BATCH };
#if defined(__x86_64__) && defined(__GNUC__) && defined(__GLIBC__)
#define BATCH_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BATCH_CLONES
#endif

/* The recursion's coefficients (aq_sdof p and b) of o[0..nb) into the lane
 * arrays c[0..8) (p00 p01 p10 p11 b00 b01 b10 b11, BATCH values each): one
 * array per coefficient with a lane per oscillator, so that the loops over
 * the lanes vectorise; the spare lanes repeat the first. */
static inline void lanes_load(double *const c[8], const aq_sdof *const *o, size_t nb)
{
  for (size_t j = 0; j < BATCH; j++) {
    const aq_sdof *s = o[j < nb ? j : 0];
    c[0][j] = s->p[0][0];
    c[1][j] = s->p[0][1];
    c[2][j] = s->p[1][0];
    c[3][j] = s->p[1][1];
    c[4][j] = s->b[0][0];
    c[5][j] = s->b[0][1];
    c[6][j] = s->b[1][0];
    c[7][j] = s->b[1][1];
  }
}

/* One pass of the recursion of the BATCH lanes (coefficients c, as
 * lanes_load fills them) over the n samples of a, from rest: each lane's
 * largest |x_k| into mx[0..BATCH) and, when my is not NULL, its largest
 * |y_k| into my.  Inlined into each caller (and each of its clones), where
 * my is a constant: without it no |y| is taken. */
static inline __attribute__((always_inline)) void lanes_pass(double *const c[8],
                                                              const double *a, size_t n,
                                                              double *mx, double *my)
{
  const double *p00 = c[0], *p01 = c[1], *p10 = c[2], *p11 = c[3];
  const double *b00 = c[4], *b01 = c[5], *b10 = c[6], *b11 = c[7];
  double x[BATCH], y[BATCH];
  for (size_t j = 0; j < BATCH; j++) {
    x[j] = y[j] = mx[j] = 0;
    if (my)
      my[j] = 0;
  }
  double ak = a[0];
  for (size_t k = 0; k + 1 < n; k++) {
    double an = a[k + 1];
    for (size_t j = 0; j < BATCH; j++) {
      double xn = p00[j] * x[j] + p01[j] * y[j] + b00[j] * ak + b01[j] * an;
      double yn = p10[j] * x[j] + p11[j] * y[j] + b10[j] * ak + b11[j] * an;
      x[j] = xn;
      y[j] = yn;
      double ax = fabs(xn);
      mx[j] = ax > mx[j] ? ax : mx[j];
      if (my) {
        double ay = fabs(yn);
        my[j] = ay > my[j] ? ay : my[j];
      }
    }
    ak = an;
  }
}

/* max |x_k| of the response at the samples of up to BATCH oscillators
 * (o[0..nb), none the PGA's) to the n samples of a, into m[0..nb). */
BATCH_CLONES
static void peaks_batch(const aq_sdof *const *o, size_t nb, const double *a, size_t n,
                        double *m)
{
  double p00[BATCH], p01[BATCH], p10[BATCH], p11[BATCH];
  double b00[BATCH], b01[BATCH], b10[BATCH], b11[BATCH];
  double mx[BATCH];
  double *const c[8] = {p00, p01, p10, p11, b00, b01, b10, b11};
  lanes_load(c, o, nb);
  lanes_pass(c, a, n, mx, NULL);
  for (size_t j = 0; j < nb; j++)
    m[j] = mx[j];
}

size_t aq_spectrum_batch_peaks(const aq_sdof *const *o, const size_t *idx, size_t nb,
                               const double *a, size_t n, double *psa)
{
  double m[BATCH];
  if (nb)
    peaks_batch(o, nb, a, n, m);
  for (size_t j = 0; j < nb; j++)
    psa[idx[j]] = m[j];
  return 0;
}

/* aq_sdof_peak_refined() for up to BATCH oscillators o[0..nb) (none the PGA's),
 * s[j] each one's over dt / steps[j] (steps[j] >= 2), with no history
 * kept: a first pass of the recursion gives each one's peak at the samples
 * and largest |y|, so its slack g; a second pass, the same arithmetic so
 * the same states, tests each interval as aq_sdof_peak_refined() does, in the same
 * order, and refines those that pass (one oscillator at a time: few do).
 * The peaks into m[0..nb); amax: max |a|.  The same values to the bit. */
BATCH_CLONES
static void refined_batch(const aq_sdof *const *o, const aq_sdof *const *s, const size_t *steps,
                          size_t nb, const double *a, size_t n, double amax, double *m)
{
  double p00[BATCH], p01[BATCH], p10[BATCH], p11[BATCH];
  double b00[BATCH], b01[BATCH], b10[BATCH], b11[BATCH];
  double x[BATCH], y[BATCH], mx[BATCH], my[BATCH], g[BATCH], xo[BATCH], yo[BATCH];
  int hit[BATCH];
  double *const c[8] = {p00, p01, p10, p11, b00, b01, b10, b11};
  lanes_load(c, o, nb);
  lanes_pass(c, a, n, mx, my);
  for (size_t j = 0; j < BATCH; j++) {
    g[j] = slack_of(o[j < nb ? j : 0], mx[j], my[j], amax);
    x[j] = y[j] = 0;
  }
  double ak = a[0];
  for (size_t k = 0; k + 1 < n; k++) {
    double an = a[k + 1];
    int any = 0;
    for (size_t j = 0; j < BATCH; j++) {
      double xn = p00[j] * x[j] + p01[j] * y[j] + b00[j] * ak + b01[j] * an;
      double yn = p10[j] * x[j] + p11[j] * y[j] + b10[j] * ak + b11[j] * an;
      double ax = fabs(x[j]), axn = fabs(xn);
      hit[j] = (ax > axn ? ax : axn) + g[j] > mx[j];
      any |= hit[j];
      xo[j] = x[j];
      yo[j] = y[j];
      x[j] = xn;
      y[j] = yn;
    }
    for (size_t j = 0; any && j < nb; j++) {
      if (!hit[j])
        continue;
      double sig = (an - ak) * o[j]->inv_theta;
      if (piece_bound(o[j], o[j]->theta, xo[j], yo[j], x[j], ak, an, sig) > mx[j])
        mx[j] = dmax(mx[j], substeps(s[j], steps[j], xo[j], yo[j], ak, an, NULL));
    }
    ak = an;
  }
  for (size_t j = 0; j < nb; j++)
    m[j] = mx[j];
}

size_t aq_spectrum_batch_refined(const aq_sdof *const *o, const aq_sdof *const *s,
                                 const size_t *steps, const size_t *idx, size_t nr,
                                 const double *a, size_t n, double amax, double *psa)
{
  double m[BATCH];
  if (nr)
    refined_batch(o, s, steps, nr, a, n, amax, m);
  for (size_t j = 0; j < nr; j++)
    psa[idx[j]] = m[j];
  return 0;
}
