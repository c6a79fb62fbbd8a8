/* test_capacity_scan.c: the scan and bisection of src/capacity/scan.c on
 * synthetic verdicts whose changes are known exactly: every window of
 * either verdict wider than the resolution is found, each change to tol,
 * and the number of runs is the grid plus one bisection per change. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../src/capacity/capacity.h"
#include "check.h"

/* Collapse for s >= t[0], survival from t[1], collapse from t[2], ... */
typedef struct {
  const double *t;
  size_t n;
  size_t calls;
} steps_verdict;

static aq_status verdict(void *ctx, double s, int *collapsed, aq_error *err)
{
  (void)err;
  steps_verdict *v = ctx;
  size_t k = 0;
  while (k < v->n && v->t[k] <= s)
    k++;
  *collapsed = (int)(k % 2);
  v->calls++;
  return AQ_OK;
}

static aq_status failing(void *ctx, double s, int *collapsed, aq_error *err)
{
  (void)ctx;
  *collapsed = 0;
  return s > 2.0 ? aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "stepper",
                                "no progress") : AQ_OK;
}

AQ_TEST(capacity_scan_finds_every_window_wider_than_the_resolution)
{
  const double r = 0.01, tol = 1e-6;
  /* windows of both verdicts just wider than r (ratio 1.0102), placed off
   * any grid, and a collapse holding to the cap */
  const double t[] = {1.37311, 1.37311 * 1.0102, 1.37311 * 1.0102 * 1.0102,
                      2.918147, 3.5512, 3.5512 * 1.0103, 6.02};
  steps_verdict v = {t, sizeof t / sizeof t[0], 0};
  aq_scan_opts o = {r, tol};
  aq_scan_result res;
  aq_error e;
  aq_status s = aq_scan_run(0.8123, 7.5, &o, verdict, &v, &res, &e);
  aq_check(s == AQ_OK, "scan status %d", (int)s);
  aq_check(res.ninterval == 4, "intervals %zu, want 4", res.ninterval);
  for (size_t i = 0; i < res.ninterval && i < 4; i++) {
    double lo = t[2 * i], hi = 2 * i + 1 < v.n ? t[2 * i + 1] : INFINITY;
    /* collapse observed at lo' in [t, t (1 + tol)], at hi' in [t' (1 - tol), t') */
    aq_check(res.interval[i].lo >= lo && res.interval[i].lo <= lo * (1 + tol),
             "interval %zu lo %.12g, change at %.12g", i, res.interval[i].lo, lo);
    if (isinf(hi))
      aq_check(isinf(res.interval[i].hi), "last interval open to the cap");
    else
      aq_check(res.interval[i].hi < hi && res.interval[i].hi >= hi * (1 - tol),
               "interval %zu hi %.12g, change at %.12g", i, res.interval[i].hi, hi);
  }
  /* runs: the grid (ceil(ln(hi/lo) / ln(1 + r))) and at most
   * ceil(log2(r / tol)) + 1 per change */
  size_t grid = (size_t)ceil(log(7.5 / 0.8123) / log1p(r));
  size_t per = (size_t)ceil(log2(r / tol)) + 1;
  aq_check(res.grid_runs == grid, "grid runs %zu, want %zu", res.grid_runs, grid);
  aq_check(res.bisect_runs <= 7 * per && res.bisect_runs >= 7 * (per - 2),
           "bisection runs %zu for 7 changes (%zu each at most)", res.bisect_runs, per);
  aq_check(res.runs == v.calls && res.runs == res.grid_runs + res.bisect_runs,
           "runs %zu, verdicts asked %zu", res.runs, v.calls);
  aq_scan_result_free(&res);
}

AQ_TEST(capacity_scan_limits_and_errors)
{
  aq_scan_opts o = {0.01, 1e-6};
  aq_scan_result res;
  aq_error e;
  /* a window narrower than the resolution that falls between grid points
   * is not seen (the documented limit), and nothing else is reported */
  const double lo = 1.0, k = log1p(0.01);
  const double t[] = {exp(10.3 * k), exp(10.6 * k)};
  steps_verdict v = {t, 2, 0};
  aq_check(aq_scan_run(lo, 2.0, &o, verdict, &v, &res, &e) == AQ_OK, "scan ok");
  aq_check(res.ninterval == 0, "narrow window between grid points: %zu intervals",
           res.ninterval);
  aq_scan_result_free(&res);
  /* nothing to scan: no runs */
  v.calls = 0;
  aq_status s0 = aq_scan_run(2.0, 2.0, &o, verdict, &v, &res, &e);
  aq_check(s0 == AQ_OK && res.runs == 0 && v.calls == 0, "empty range: %zu runs",
           res.runs);
  aq_scan_result_free(&res);
  /* a failing verdict stops the scan with its status */
  aq_check(aq_scan_run(1.0, 3.0, &o, failing, NULL, &res, &e) == AQ_ENUMERIC,
           "failing verdict stops the scan");
  aq_scan_result_free(&res);
  /* options out of range are named */
  aq_scan_opts bad[] = {{0, 1e-6}, {2.0, 1e-6}, {0.01, 0.02}, {0.01, 1e-15}, {NAN, 1e-6}};
  const char *field[] = {"resolution", "resolution", "tol", "tol", "resolution"};
  for (size_t i = 0; i < 5; i++) {
    aq_status s = aq_scan_run(1.0, 2.0, &bad[i], verdict, &v, &res, &e);
    aq_check(s == AQ_EOPTION && strcmp(e.field, field[i]) == 0,
             "bad options %zu: status %d field %s", i, (int)s, e.field);
    aq_scan_result_free(&res);
  }
}
