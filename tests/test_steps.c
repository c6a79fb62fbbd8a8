/* test_steps.c: zero-order-hold steps, merging and the quiet index. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "signal/steps.h"

AQ_TEST(steps_zoh_and_quiet_index)
{
  enum { N = 1000 };
  double a[N];
  for (size_t i = 0; i < N; i++)
    a[i] = 0.01 * sin(0.37 * (double)i); /* quiet */
  a[777] = 2.385;                         /* one loud sample */
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_samples(a, N, 0.005, -1.25, 0, &s, &e) == AQ_OK, "build");
  aq_check(s.n == N, "one step per sample: %zu", s.n);
  aq_check_abs(aq_steps_t(&s, 400), -1.25 + 400 * 0.005, 1e-15, "step time from index");
  aq_check(aq_steps_next_outside(&s, 0, -0.5, 0.5) == 777, "first loud step");
  aq_check(aq_steps_next_outside(&s, 778, -0.5, 0.5) == N, "none after");
  /* brute force agrees for thresholds near the quiet amplitude */
  for (double thr = 0.0; thr < 0.011; thr += 0.0017) {
    size_t want = N;
    for (size_t i = 5; i < N; i++)
      if (fabs(a[i]) > thr) {
        want = i;
        break;
      }
    aq_check(aq_steps_next_outside(&s, 5, -thr, thr) == want, "thr %g", thr);
  }
  aq_steps_free(&s);
}

AQ_TEST(steps_merge_keeps_impulse)
{
  enum { N = 500 };
  double a[N], imp = 0;
  for (size_t i = 0; i < N; i++) {
    a[i] = 0.3 * sin(0.01 * (double)i) + (i > 250 ? 1.7 : 0.0);
    imp += a[i] * 0.01;
  }
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_samples(a, N, 0.01, 0, 0.05, &s, &e) == AQ_OK, "build");
  double got = 0, dur = 0;
  for (size_t i = 0; i < s.n; i++) {
    got += s.a_mps2[i] * aq_steps_dt(&s, i);
    dur += aq_steps_dt(&s, i);
  }
  aq_check(s.n < N / 3, "merging reduces the steps: %zu", s.n);
  aq_check_rel(got, imp, 2e-14, "merged steps keep the impulse");
  aq_check_rel(dur, N * 0.01, 5e-15, "and the duration");
  aq_steps_free(&s);
}

/* A list over the caller's samples: no copy, the index and peak from the
 * samples themselves, and the caller's array untouched by the free. */
AQ_TEST(steps_over_borrows_the_samples)
{
  enum { N = 1003 }; /* 15 whole blocks of 64 and a part block of 43 */
  double *a = malloc(N * sizeof *a);
  aq_check(a != NULL, "memory");
  if (!a)
    return;
  double want_peak = 0;
  for (size_t i = 0; i < N; i++) {
    a[i] = 0.02 * sin(0.37 * (double)i) - (i % 97 == 5 ? 0.9 : 0.0);
    if (fabs(a[i]) > want_peak)
      want_peak = fabs(a[i]);
  }
  a[1001] = -2.385; /* the peak, negative, in the part block */
  a[1002] = 1.9;    /* its greatest, its last sample */
  want_peak = 2.385;
  aq_steps s;
  aq_error e;
  double peak = -1;
  aq_check(aq_steps_over(a, N, 0.005, -1.25, &s, &peak, &e) == AQ_OK, "build");
  aq_check(s.a_mps2 == a && s.borrowed, "the caller's samples, not a copy");
  aq_check(s.n == N && !s.t_s && !s.dt_s, "one equal step per sample: %zu", s.n);
  aq_check(aq_steps_t(&s, 400) == -1.25 + 400 * 0.005 && aq_steps_dt(&s, 7) == 0.005,
           "times t0 + i dt");
  aq_check(peak == want_peak, "peak %.17g, want %.17g", peak, want_peak);
  for (size_t b = 0; b * 64 < N; b++) { /* each block's extremes, by hand */
    double lo = a[b * 64], hi = lo;
    for (size_t i = b * 64; i < N && i < (b + 1) * 64; i++) {
      lo = fmin(lo, a[i]);
      hi = fmax(hi, a[i]);
    }
    aq_check(s.block_min_mps2[b] == lo && s.block_max_mps2[b] == hi, "block %zu", b);
  }
  aq_check(aq_steps_next_outside(&s, 0, -2, 2) == 1001, "the loud step");
  aq_steps_free(&s);
  aq_check(a[1001] == -2.385, "the samples stay the caller's"); /* ASan: not freed */
  free(a);
  aq_check(aq_steps_over(&peak, 1, 0, 0, &s, NULL, &e) == AQ_EVALUE, "dt 0 refused");
}
