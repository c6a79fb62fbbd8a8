/* scan.c: every change of verdict of a scale factor in (lo, hi]: a
 * geometric scan of ratio 1 + resolution, then a bisection of each change
 * to a relative tolerance.
 *
 * Vamvatsikos & Cornell's hunt-and-fill (Earthquake Engng Struct. Dyn.
 * 31(3), 491-514, 2002) hunts upwards with growing steps to the first
 * collapse, then fills by bisection; a rocking arch's verdict is not
 * monotonic in the scale, so here the hunt is a scan at a fixed ratio: any
 * window of either verdict whose ends differ by more than the ratio holds a
 * grid point and is found; the bisection, the only fine work, places its
 * ends to tol (docs/capacity.md). */
#include <math.h>
#include <stdlib.h>

#include "capacity.h"

aq_status aq_scan_check(const aq_scan_opts *o, aq_error *err)
{
  if (!(o->resolution >= AQ_SCAN_RESOLUTION_MIN &&
        o->resolution <= AQ_SCAN_RESOLUTION_MAX))
    return aq_error_set(err, AQ_EOPTION, NULL, -1, -1, "resolution",
                        "expected %g to %g, got %g", AQ_SCAN_RESOLUTION_MIN,
                        AQ_SCAN_RESOLUTION_MAX, o->resolution);
  if (!(o->tol >= AQ_SCAN_TOL_MIN && o->tol <= o->resolution))
    return aq_error_set(err, AQ_EOPTION, NULL, -1, -1, "tol",
                        "expected %g to the resolution %g, got %g",
                        AQ_SCAN_TOL_MIN, o->resolution, o->tol);
  return AQ_OK;
}

void aq_scan_result_free(aq_scan_result *r)
{
  if (!r)
    return;
  free(r->interval);
  r->interval = NULL;
  r->ninterval = 0;
}

typedef struct {
  aq_scan_verdict_fn fn;
  void *ctx;
  aq_scan_result *out;
  size_t cap;
} scan_state;

static aq_status ask(scan_state *S, double scale, int *v, size_t *counter,
                     aq_error *err)
{
  aq_status s = S->fn(S->ctx, scale, v, err);
  S->out->runs++;
  (*counter)++;
  return s;
}

/* Bisect (a, b) with verdicts va != vb until b - a <= tol a: *lo, *hi are
 * the final ends (verdicts va at *lo and vb at *hi). */
static aq_status bisect(scan_state *S, double a, double b, int va, double tol,
                        double *lo, double *hi, aq_error *err)
{
  while (b - a > tol * a) {
    double m = sqrt(a * b);
    if (!(m > a && m < b))
      break; /* adjacent doubles */
    int vm;
    aq_status s = ask(S, m, &vm, &S->out->bisect_runs, err);
    if (s != AQ_OK)
      return s;
    if (vm == va)
      a = m;
    else
      b = m;
  }
  *lo = a;
  *hi = b;
  return AQ_OK;
}

static aq_status push(scan_state *S, double lo, double hi, aq_error *err)
{
  aq_scan_result *o = S->out;
  if (o->ninterval == S->cap) {
    size_t nc = S->cap ? 2 * S->cap : 8;
    aq_scan_interval *p = realloc(o->interval, nc * sizeof *p);
    if (!p)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "scan", "out of memory");
    o->interval = p;
    S->cap = nc;
  }
  o->interval[o->ninterval++] = (aq_scan_interval){lo, hi};
  return AQ_OK;
}

aq_status aq_scan_run(double scale_lo, double scale_hi, const aq_scan_opts *o,
                      aq_scan_verdict_fn verdict, void *ctx,
                      aq_scan_result *out, aq_error *err)
{
  *out = (aq_scan_result){0, NULL, 0, 0, 0};
  aq_status s = aq_scan_check(o, err);
  if (s != AQ_OK)
    return s;
  if (!(scale_lo > 0 && isfinite(scale_lo) && isfinite(scale_hi)) ||
      !(scale_hi > scale_lo))
    return AQ_OK;
  scan_state S = {verdict, ctx, out, 0};
  const double lr = log1p(o->resolution);
  /* grid points lo e^(i lr), i = 1..n-1, then hi: n runs */
  double span = log(scale_hi / scale_lo) / lr;
  size_t n = (size_t)ceil(span);
  if (n < 1)
    n = 1;
  double prev = scale_lo, open_lo = NAN;
  int vprev = 0;
  for (size_t i = 1; i <= n; i++) {
    double sc = i == n ? scale_hi : scale_lo * exp((double)i * lr);
    if (i < n && sc >= scale_hi)
      sc = scale_hi, i = n; /* rounding put a point on the cap */
    int v;
    if ((s = ask(&S, sc, &v, &out->grid_runs, err)) != AQ_OK)
      return s;
    if (v != vprev) {
      double lo, hi;
      if ((s = bisect(&S, prev, sc, vprev, o->tol, &lo, &hi, err)) != AQ_OK)
        return s;
      if (v) {
        open_lo = hi; /* collapse observed at hi */
      } else if ((s = push(&S, open_lo, lo, err)) != AQ_OK) {
        return s;
      }
    }
    prev = sc;
    vprev = v;
  }
  if (vprev && (s = push(&S, open_lo, INFINITY, err)) != AQ_OK)
    return s;
  return AQ_OK;
}
