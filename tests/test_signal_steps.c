/* test_signal_steps.c: steps from samples and the quiet index, against
 * brute force on irregular records. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "signal/signal.h"
#include "signal/steps.h"

/* xorshift64*: reproducible irregular numbers in [0, 1) */
static double urand(unsigned long long *s)
{
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return (double)((*s * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

AQ_TEST(signal_steps_quiet_index_matches_brute_force)
{
  enum { N = 5003 };
  double *a = malloc(N * sizeof *a);
  unsigned long long seed = 0x9e3779b97f4a7c15ULL;
  /* quiet stretches (|a| < 0.05) broken by loud bursts of random length */
  for (size_t i = 0; i < N; i++) {
    int loud = (i / 211) % 3 == 1 && (i % 211) < 17 + (i / 211) % 40;
    a[i] = (loud ? 3.0 : 0.05) * (2 * urand(&seed) - 1);
  }
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_samples(a, N, 0.005, -0.3, 0, &s, &e) == AQ_OK,
           "build");
  size_t bad = 0;
  for (int q = 0; q < 3000; q++) {
    size_t from = (size_t)(urand(&seed) * (N + 2));
    double lo = -0.1 * urand(&seed) - (q % 5 == 0 ? 1.0 : 0.0);
    double hi = 0.1 * urand(&seed) + (q % 7 == 0 ? 1.0 : 0.0);
    size_t want = N;
    for (size_t i = from; i < N; i++)
      if (a[i] < lo || a[i] > hi) {
        want = i;
        break;
      }
    size_t got = aq_steps_next_outside(&s, from, lo, hi);
    if (got != want && bad++ < 5)
      aq_check(0, "from %zu [%g, %g]: got %zu, want %zu", from, lo, hi, got,
               want);
  }
  aq_check(bad == 0, "quiet index agrees with brute force (%zu disagree)",
           bad);
  aq_steps_free(&s);
  free(a);
}

AQ_TEST(signal_steps_merge_matches_brute_force)
{
  enum { N = 3001 };
  double *a = malloc(N * sizeof *a);
  unsigned long long seed = 12345;
  for (size_t i = 0; i < N; i++)
    a[i] = sin(0.003 * (double)i) + 0.02 * urand(&seed);
  const double tol = 0.0713, dt = 0.01;
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_samples(a, N, dt, 0, tol, &s, &e) == AQ_OK, "build");
  /* brute force: each step covers consecutive samples whose spread is below
   * tol, cannot be extended by the next sample, and holds their mean */
  size_t i = 0, k = 0;
  int ok = 1;
  for (; k < s.n && ok; k++) {
    size_t m = (size_t)lround(aq_steps_dt(&s, k) / dt);
    double lo = a[i], hi = a[i], sum = 0;
    for (size_t j = i; j < i + m; j++) {
      lo = fmin(lo, a[j]);
      hi = fmax(hi, a[j]);
      sum += a[j];
    }
    int maximal = i + m == N || fmax(hi, a[i + m]) - fmin(lo, a[i + m]) >= tol;
    ok = m >= 1 && i + m <= N && hi - lo < tol && maximal &&
         fabs(aq_steps_t(&s, k) - (double)i * dt) < 1e-12 &&
         fabs(s.a_mps2[k] - sum / (double)m) < 1e-12;
    i += m;
  }
  aq_check(ok && i == N && k == s.n, "merged steps: step %zu", k);
  aq_check(s.n > 10 && s.n < N / 5, "merging shortens the list: %zu", s.n);
  aq_steps_free(&s);
  free(a);
}

AQ_TEST(signal_steps_from_processed_record)
{
  /* a processed record by hand: 3 pad samples, 4 record samples, 2 pad */
  double a[9] = {0, 0, 0, 1.25, -0.5, 0.75, 2.0, 0, 0};
  aq_processed p = {0};
  p.n = 9;
  p.dt_s = 0.02;
  p.pad_front = 3;
  p.pad_back = 2;
  p.n_orig = 4;
  p.acc_mps2 = a;
  aq_steps s;
  aq_error e;
  aq_status st0 = aq_steps_from_processed(&p, 0, &s, &e);
  aq_check(st0 == AQ_OK && s.n == 9, "one step per sample: %zu", s.n);
  aq_check_abs(aq_steps_t(&s, 0), -0.06, 1e-15, "front pad at negative time");
  aq_check_abs(aq_steps_t(&s, 3), 0.0, 1e-15, "record starts at t = 0");
  aq_check(s.a_mps2[3] == 1.25 && aq_steps_dt(&s, 3) == 0.02, "zero-order hold");
  aq_steps_free(&s);
  aq_status st = aq_steps_from_processed(&p, 0.1, &s, &e);
  /* zeros | 1.25 | -0.5 | 0.75 | 2.0 | zeros: each pair differs by > 0.1 */
  aq_check(st == AQ_OK && s.n == 6, "merge-tol joins the pad zeros: %zu steps",
           s.n);
  aq_check_abs(aq_steps_t(&s, 1), 0.0, 1e-15, "second step starts the record");
  aq_steps_free(&s);
}
