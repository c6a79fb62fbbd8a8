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
