/* bench_signal.c: median time to process a record (detrend, taper, pad,
 * acausal filter, intensity measures) against the floor: one FFTW r2c + c2r
 * pair of the padded length, timed side by side in the same run.
 *
 * Each record gets a fresh output array, whose pages the kernel must map in
 * (glibc serves arrays above its mmap threshold with mmap/munmap).  The table
 * is printed twice: with glibc's default malloc, and with mallopt() keeping
 * freed memory for reuse, which shows the processing without that cost. */
#include <fftw3.h>
#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "signal/signal.h"

enum { REPS = 41 };

/* The quiet index: find the one loud step at the end of a quiet stretch of
 * n steps (|a| < 0.01 g) with aq_steps_next_outside, against a plain scan. */
static int bench_quiet(void)
{
  static const size_t sizes[] = {20000, 80000, 320000};
  printf("\nquiet_steps\tindex_us\tscan_us\tscan/index\n");
  for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
    size_t n = sizes[s];
    double *a = malloc(n * sizeof *a);
    if (!a)
      return 1;
    for (size_t i = 0; i < n; i++)
      a[i] = 0.05 * sin(0.37 * (double)i);
    a[n - 1] = 3.0;
    aq_steps st;
    aq_error e;
    if (aq_steps_from_samples(a, n, 0.005, 0, 0, &st, &e) != AQ_OK)
      return 1;
    double ti[REPS], ts[REPS];
    size_t sink = 0;
    for (int k = 0; k < REPS; k++) {
      double t0 = aq_bench_now_s();
      sink += aq_steps_next_outside(&st, (size_t)k, -0.098, 0.098);
      double t1 = aq_bench_now_s();
      size_t i = (size_t)k;
      while (i < st.n && fabs(st.a_mps2[i]) <= 0.098)
        i++;
      sink += i;
      double t2 = aq_bench_now_s();
      ti[k] = t1 - t0;
      ts[k] = t2 - t1;
    }
    double mi = aq_bench_median(ti, REPS), ms = aq_bench_median(ts, REPS);
    printf("%zu\t%.2f\t%.2f\t%.1f%s\n", n, 1e6 * mi, 1e6 * ms, ms / mi,
           sink == 1 ? " " : "");
    aq_steps_free(&st);
    free(a);
  }
  return 0;
}

int main(void)
{
  static const size_t sizes[] = {5000, 20000, 80000};
  const double dt = 0.01;
  aq_signal_ws *ws = aq_signal_ws_alloc();
  if (!ws)
    return 1;
  printf("npts\tpadded\tprocess_ms\tfft_pair_ms\tratio\tdetrend\tmalloc\n");
  for (int reuse = 0; reuse < 2; reuse++) {
    if (reuse) {
      mallopt(M_MMAP_THRESHOLD, 256 << 20);
      mallopt(M_TRIM_THRESHOLD, 512 << 20);
    }
    for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
      size_t n = sizes[s];
      aq_record r;
      memset(&r, 0, sizeof r);
      r.path = "bench";
      r.npts = n;
      r.dt_s = dt;
      r.acc_mps2 = malloc(n * sizeof(double));
      if (!r.acc_mps2)
        return 1;
      for (size_t i = 0; i < n; i++) {
        double t = (double)i * dt;
        r.acc_mps2[i] = 0.2 + 0.001 * t + sin(2.1 * t) * exp(-0.01 * t) +
                        0.3 * sin(17.3 * t + 0.4);
      }
      for (int lin = 0; lin < 2; lin++) {
        aq_signal_opts o;
        aq_signal_opts_default(&o);
        o.detrend = lin ? AQ_DETREND_LINEAR : AQ_DETREND_MEAN;
        aq_processed p;
        aq_im im;
        aq_error e;
        double tp[REPS], tf[REPS], sink = 0;
        if (aq_signal_process(&r, &o, ws, &p, &e) != AQ_OK) { /* warm-up */
          fprintf(stderr, "bench: %s\n", e.message);
          return 1;
        }
        size_t np = p.n;
        aq_processed_free(&p);
        double *x = fftw_malloc(np * sizeof *x);
        fftw_complex *X = fftw_malloc((np / 2 + 1) * sizeof *X);
        fftw_plan f = fftw_plan_dft_r2c_1d((int)np, x, X, FFTW_ESTIMATE);
        fftw_plan b = fftw_plan_dft_c2r_1d((int)np, X, x, FFTW_ESTIMATE);
        if (!x || !X || !f || !b)
          return 1;
        for (size_t i = 0; i < np; i++)
          x[i] = sin(0.001 * (double)i);
        for (int k = 0; k < REPS; k++) {
          double t0 = aq_bench_now_s();
          aq_signal_process(&r, &o, ws, &p, &e);
          aq_im_compute(&p, &im, &e);
          double t1 = aq_bench_now_s();
          sink += im.arias_mps;
          aq_processed_free(&p);
          double t2 = aq_bench_now_s();
          fftw_execute(f);
          fftw_execute(b);
          double t3 = aq_bench_now_s();
          sink += x[np / 3];
          tp[k] = t1 - t0;
          tf[k] = t3 - t2;
        }
        double mp = aq_bench_median(tp, REPS), mf = aq_bench_median(tf, REPS);
        printf("%zu\t%zu\t%.3f\t%.3f\t%.2f\t%s\t%s%s\n", n, np, 1e3 * mp,
               1e3 * mf, mp / mf, lin ? "linear" : "mean",
               reuse ? "reused" : "default", sink == 12345.678 ? " " : "");
        fftw_destroy_plan(f);
        fftw_destroy_plan(b);
        fftw_free(x);
        fftw_free(X);
      }
      free(r.acc_mps2);
    }
  }
  aq_signal_ws_free(ws);
  return bench_quiet();
}
