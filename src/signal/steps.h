/* steps.h: the constant-acceleration steps the arch stepper consumes.
 *
 * A step is (start time, duration, constant ground acceleration along +x,
 * and optionally constant vertical ground acceleration, positive up).
 * Times are s relative to the original record's first sample (steps in the
 * front pad have negative times).  The block min/max arrays let the stepper
 * skip quiet stretches cheaply (aq_steps_next_outside).  aq_steps owns its
 * arrays (aq_steps_free releases them), except the samples of a list made
 * over the caller's array (aq_steps_over: borrowed, left to the caller).
 */
#ifndef AQ_SIGNAL_STEPS_H
#define AQ_SIGNAL_STEPS_H

#include <stddef.h>

#include "../error.h"

typedef struct {
  size_t n;         /* number of steps */
  double *t_s;      /* start of step i, s; NULL: every step lasts step_s and
                       step i starts at t0_s + i step_s (aq_steps_t) */
  double *dt_s;     /* duration of step i, s (> 0); NULL with t_s */
  double t0_s, step_s; /* the start and the duration of equal steps (t_s NULL) */
  double *a_mps2;   /* ground acceleration during step i, m/s^2 */
  size_t block;     /* steps per block of the quiet index (power of two) */
  size_t nblock;    /* number of blocks */
  double *block_min_mps2; /* min a over each block */
  double *block_max_mps2; /* max a over each block */
  double *av_mps2;  /* vertical ground acceleration during step i, m/s^2,
                       positive up; NULL: none (0), the horizontal-only case */
  int borrowed;     /* 1: a_mps2 is the caller's (aq_steps_over), not freed */
} aq_steps;

/* Start and duration of step i, s.  Equal steps (one per sample: no t_s,
 * dt_s arrays, which were pure arithmetic and 2/3 of a list's memory) give
 * t0_s + i step_s, the very value the arrays held. */
static inline double aq_steps_t(const aq_steps *s, size_t i)
{
  return s->t_s ? s->t_s[i] : s->t0_s + (double)i * s->step_s;
}

static inline double aq_steps_dt(const aq_steps *s, size_t i)
{
  return s->dt_s ? s->dt_s[i] : s->step_s;
}

/* Build steps from n samples at dt_s (zero-order hold: sample i holds over
 * [t0_s + i dt, t0_s + (i+1) dt)).  merge_tol_mps2 > 0 merges runs of
 * consecutive samples that differ by less than it into one step at their
 * duration-weighted mean (t_s, dt_s arrays); 0 keeps one step per sample
 * (equal steps: t_s and dt_s NULL, t0_s and step_s set). */
aq_status aq_steps_from_samples(const double *a_mps2, size_t n, double dt_s,
                                double t0_s, double merge_tol_mps2,
                                aq_steps *out, aq_error *err);

/* Steps of the projection scale (c1 a1[i] + c2 a2[i]) of two component
 * records sampled alike (src/signal/project.h gives c1, c2 for an arch's
 * azimuth), built as aq_steps_from_samples builds them from those samples:
 * each component is processed once and projected here, per azimuth, with no
 * intermediate array.  a2_mps2 may be NULL: the samples are then
 * scale (c1 a1[i]), so c1 = scale = 1 gives the record itself, bit for bit.
 * *peak_mps2 (if not NULL) receives max |sample|, m/s^2. */
aq_status aq_steps_project(const double *a1_mps2, double c1, const double *a2_mps2,
                           double c2, double scale, size_t n, double dt_s,
                           double t0_s, double merge_tol_mps2, aq_steps *out,
                           double *peak_mps2, aq_error *err);

/* As aq_steps_project, with the vertical component: av_mps2[i] (positive
 * up) times vscale becomes each step's av_mps2 (a merged run also keeps its
 * vertical samples within merge_tol_mps2 and takes their mean).  av_mps2
 * NULL: as aq_steps_project (no vertical array). */
aq_status aq_steps_project_v(const double *a1_mps2, double c1, const double *a2_mps2,
                             double c2, double scale, const double *av_mps2,
                             double vscale, size_t n, double dt_s, double t0_s,
                             double merge_tol_mps2, aq_steps *out,
                             double *peak_mps2, aq_error *err);

/* One step per sample over the caller's samples a_mps2[0..n) at dt_s from
 * t0_s, without copying them: out->a_mps2 is a_mps2 (borrowed: it must
 * outlive the list, and aq_steps_free leaves it), and only the quiet index
 * is made.  The same list, bit for bit, as aq_steps_from_samples with
 * merge_tol_mps2 0 makes (whose samples are products by 1, exact).
 * *peak_mps2 (if not NULL) receives max |a_mps2[i]| (0 for n = 0). */
aq_status aq_steps_over(double *a_mps2, size_t n, double dt_s, double t0_s,
                        aq_steps *out, double *peak_mps2, aq_error *err);

/* Give s a vertical acceleration per step (copies av_mps2[0..s->n), m/s^2,
 * positive up).  AQ_EVALUE for a value that is not finite, AQ_ENOMEM. */
aq_status aq_steps_set_vertical(aq_steps *s, const double *av_mps2, aq_error *err);

/* Build from explicit lists (synthetic pulses, tests).  Copies the arrays. */
aq_status aq_steps_from_list(const double *t_s, const double *dt_s,
                             const double *a_mps2, size_t n, aq_steps *out,
                             aq_error *err);

/* Index of the first step i >= from with a_mps2[i] < lo or a_mps2[i] > hi,
 * or s->n if there is none.  Costs O(blocks skipped + block). */
size_t aq_steps_next_outside(const aq_steps *s, size_t from, double lo,
                             double hi);

void aq_steps_free(aq_steps *s);

#endif
