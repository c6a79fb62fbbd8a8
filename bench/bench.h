/* bench.h: timing helpers for make bench (never part of make check). */
#ifndef AQ_BENCH_H
#define AQ_BENCH_H

#include <stdlib.h>
#include <time.h>

static inline double aq_bench_now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int aq_bench_cmp_(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median of n samples (sorts v in place). */
static inline double aq_bench_median(double *v, size_t n)
{
  qsort(v, n, sizeof *v, aq_bench_cmp_);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif
