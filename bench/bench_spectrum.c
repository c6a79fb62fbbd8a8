/* bench_spectrum.c: median time of a response spectrum (PEER's 111 periods,
 * 5 %) of a 20,000-sample record, one component and RotD over 180 angles,
 * with the peak at PEER's refined samples (the default), over continuous
 * time and at the samples only, side by side in one run; and the cost per
 * period per sample (CPU time).  The samples and peer rows are also run
 * with one_at_a_time (each oscillator's own loop, as before the periods
 * were grouped and RotD's two components joined in one loop: the same
 * values), and the speed-up printed (before / after, CPU and wall).
 *
 * The record: two horizontal components of 100 s at dt = 0.005 s, each a
 * sum of 40 sines from 0.1 to 20 Hz with fixed pseudo-random phases under a
 * 10 s rise and an exponential decay, so that the oscillators swing at every
 * period as a real record makes them. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench.h"
#include "signal/spectrum.h"

enum { REPS = 9, NPTS = 20000, NSINES = 40 };

/* The process's CPU time, s: on a shared machine the wall time also counts
 * the waits for a core; ns_per_period_sample and the ratio use CPU time. */
static double cpu_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void make_record(double *a, unsigned seed)
{
  const double dt = 0.005;
  double f[NSINES], ph[NSINES];
  for (int j = 0; j < NSINES; j++) {
    seed = seed * 1103515245u + 12345u;
    f[j] = 0.1 * pow(200.0, (double)j / (NSINES - 1));
    ph[j] = 6.283185307179586 * (double)(seed >> 8) / 16777216.0;
  }
  for (size_t i = 0; i < NPTS; i++) {
    double t = (double)i * dt, s = 0;
    for (int j = 0; j < NSINES; j++)
      s += sin(6.283185307179586 * f[j] * t + ph[j]) / sqrt(1 + f[j]);
    double env = t < 10 ? t / 10 : exp(-(t - 10) / 25);
    a[i] = 0.4 * env * s;
  }
}

int main(void)
{
  gsl_set_error_handler_off();
  double *a1 = malloc(NPTS * sizeof *a1), *a2 = malloc(NPTS * sizeof *a2);
  double psa[AQ_SPECTRUM_PEER_N];
  aq_rotd rd[AQ_SPECTRUM_PEER_N];
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  if (!a1 || !a2 || !ws)
    return 1;
  make_record(a1, 7);
  make_record(a2, 1234567);
  const size_t np = AQ_SPECTRUM_PEER_N;
  printf("spectrum of %d samples, %zu periods 0.01-20 s, 5 %%, %d repetitions\n",
         NPTS, np, REPS);
  printf("what\tpeaks\tperiods\tmedian_ms\tcpu_ms\tns_per_period_sample\t"
         "ratio_to_sampled\n");
  double sink = 0;
  for (int rotd = 0; rotd < 2; rotd++) {
    double med[3];
    /* samples first: the ratios are to it; samples and peer also one
     * period and component at a time (one_at_a_time: the loops before the
     * periods were grouped and RotD's components joined), before the
     * default rows, and the speed-up; exact: "-", the default only */
    static const aq_spectrum_peaks modes[3] = {AQ_SPECTRUM_PEAKS_SAMPLES,
                                               AQ_SPECTRUM_PEAKS_PEER,
                                               AQ_SPECTRUM_PEAKS_EXACT};
    double alone[3] = {0}, alone_wall[3] = {0}, grouped_wall[3] = {0};
    for (int m = 0; m < 3; m++)
      for (int sep = m == 2 ? 0 : 1; sep >= 0; sep--) {
        aq_spectrum_opts o;
        aq_spectrum_opts_default(&o);
        o.peaks = modes[m];
        o.one_at_a_time = sep;
        double t[REPS], c[REPS];
        for (int k = 0; k < REPS; k++) {
          aq_error e;
          double c0 = cpu_s(), t0 = aq_bench_now_s();
          aq_status st =
              rotd ? aq_spectrum_rotd(ws, &o, a1, NPTS, a2, NPTS, 0.005, 0.05,
                                      aq_spectrum_peer_periods_s, np, rd, NULL, &e)
                   : aq_spectrum_psa(ws, &o, a1, NPTS, 0.005, 0.05,
                                     aq_spectrum_peer_periods_s, np, psa, &e);
          t[k] = aq_bench_now_s() - t0;
          c[k] = cpu_s() - c0;
          if (st != AQ_OK) {
            fprintf(stderr, "bench_spectrum: %s\n", e.message);
            return 1;
          }
          sink += rotd ? rd[50].rotd50_mps2 : psa[50];
        }
        double cm = aq_bench_median(c, REPS), wm = aq_bench_median(t, REPS);
        if (sep) {
          alone[m] = cm;
          alone_wall[m] = wm;
        } else {
          med[m] = cm;
          grouped_wall[m] = wm;
        }
        printf("%s\t%s\t%s\t%.2f\t%.2f\t%.2f\t%.2f\n",
               rotd ? "rotd_180_angles" : "one_component",
               aq_spectrum_peaks_names[modes[m]],
               sep ? "one_at_a_time" : m == 2 ? "-" : rotd ? "two_in_one_loop" : "grouped",
               1e3 * wm, 1e3 * cm, 1e9 * cm / ((double)np * NPTS),
               cm / (sep ? alone[0] : med[0]));
      }
    for (int m = 0; m < 2; m++)
      printf("speed-up, %s, %s: cpu %.2fx, wall %.2fx\n",
             rotd ? "rotd (components in one loop)" : "one component (periods grouped)",
             aq_spectrum_peaks_names[modes[m]], alone[m] / med[m],
             alone_wall[m] / grouped_wall[m]);
  }
  printf("%s", sink == 1.2345 ? " \n" : "");
  aq_spectrum_ws_free(ws);
  free(a1);
  free(a2);
  return 0;
}
