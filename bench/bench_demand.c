/* bench_demand.c: what tracking the joints' demand (docs/demand.md) costs
 * beside the stepping it watches, measured side by side in one run.
 *
 * Cases: the 12 AT2 records of tests/data/records (read and processed as
 * the main job does, job/subject.h), each scaled to a PGA of 2.5 lambda0 g
 * of each of the nine shipped arches, the work path model.  Per (arch,
 * record) the same run is timed REPS times with a stepper that tracks the
 * demand (the main job's, aq_job_stepper with demand 1, at friction 0.6)
 * and with one that does not, alternately, and each one's median taken.
 * Printed per arch: the sums of the medians, their ratio less one (the
 * demand's cost over the stepping), the states the tracker looked at, how
 * many with every joint evaluated (outside the grid) and how many
 * candidates it evaluated (looks), the moving steps, and the time to build
 * both sets' demand tables and their grids (once per arch, kept with it).
 * Then the totals, and the same stepping with the tracker's reference
 * (every joint at every state, aq_demand_set_every) for scale
 * (--no-reference leaves it out: quicker, for profiles; --only plain or
 * --only demand times one stepper alone, for profiles of it; the environment's
 * AQ_BENCH_REPS sets the repetitions, 15 by default). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/demand.h"
#include "arch/stepper.h"
#include "bench.h"
#include "job/job.h"
#include "job/run.h"
#include "job/scale.h"
#include "signal/signal.h"
#include "units.h"

enum { NREC = 12, NARCH = 9, REPS_MAX = 401 };
static int REPS = 15; /* AQ_BENCH_REPS (at most REPS_MAX): more, for profiles */

static const char *const recs[NREC] = {
    "ARL360.at2",
    "CHY028-N.AT2",
    "IELC180.AT2",
    "RSN1616_DUZCE_362-E.AT2",
    "RSN4013_SANSIMEO_36258021.AT2",
    "RSN4843_CHUETSU_65006NS.AT2",
    "RSN6_IMPVALL.I_I-ELC180-hor1.AT2",
    "RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
    "RSN763_LOMAP_GIL067.AT2",
    "RSN763_LOMAP_GIL337.AT2",
    "RSN77_SFERN_PUL164-hor1.AT2",
    "TCU052-N.AT2"};
static const char *const arches[NARCH] = {"oppenheim", "thin",   "thick",    "segmental", "search",
                                          "gothic",    "bridge", "catenary", "vertical"};

/* The median time of REPS runs of st on v at k, and the last run's result. */
static double timed(aq_stepper *st, const aq_view *v, double k, aq_result *res, double *t)
{
  aq_error e;
  for (int rep = 0; rep < REPS; rep++) {
    double t0 = aq_bench_now_s();
    if (aq_job_run_view(st, v, k, res, &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      exit(1);
    }
    t[rep] = aq_bench_now_s() - t0;
    if (rep + 1 < REPS)
      aq_result_free(res);
  }
  return aq_bench_median(t, REPS);
}

int main(int argc, char **argv)
{
  /* --no-reference: leave out the every-joint runs (quicker; for profiles) */
  int reference = !(argc > 1 && strcmp(argv[1], "--no-reference") == 0);
  /* --only plain|demand: time one stepper alone (for counters: perf stat) */
  int only = argc > 2 && strcmp(argv[1], "--only") == 0 ? (strcmp(argv[2], "demand") == 0 ? 2 : 1) : 0;
  if (only)
    reference = 0;
  const char *ev = getenv("AQ_BENCH_REPS");
  if (ev && atoi(ev) > 0)
    REPS = atoi(ev) < REPS_MAX ? atoi(ev) : REPS_MAX;
  aq_error e;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  aq_signal_ws *ws = aq_signal_ws_alloc();
  static aq_subject S[NREC];
  static aq_view V[NREC];
  for (size_t r = 0; r < NREC; r++) {
    char path[256];
    snprintf(path, sizeof path, "tests/data/records/%s", recs[r]);
    aq_subject_src src = {{path, NULL, NULL}, {NAN, NAN}, path};
    aq_subject_opts o = {.read = &ro, .proc = &so};
    if (aq_subject_prepare(&S[r], &src, &o, ws, &e) != AQ_OK ||
        aq_view_make(&V[r], &S[r], 0, &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      return 1;
    }
  }
  printf("bench_demand: the demand's cost beside the stepping, 12 AT2 records at 2.5 lambda0 g,\n"
         "work path, medians of %d, side by side\n\n",
         REPS);
  printf("%-10s %10s %10s %7s %9s %9s %6s %10s %8s %9s %8s %8s\n", "arch", "step_ms", "demand_ms",
         "ratio", "states", "full", "full%", "looks", "moving", "table_ms", "cold_st", "cold_dm");
  double T[3] = {0, 0, 0}, C[2] = {0, 0};
  size_t tot_states = 0, tot_full = 0;
  static double t[REPS_MAX];
  for (size_t a = 0; a < NARCH; a++) {
    char path[256];
    snprintf(path, sizeof path, "arches/%s.cfg", arches[a]);
    aq_arch *A;
    if (aq_arch_load(path, &A, &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      return 1;
    }
    double tb0 = aq_bench_now_s();
    aq_arch_demand_table(A, 0);
    aq_arch_demand_table(A, 1);
    double tb = aq_bench_now_s() - tb0;
    aq_stepper *plain = aq_job_stepper(A, AQ_MODEL_WORKPATH, NAN, 0, 0, &e);
    aq_stepper *dem = plain ? aq_job_stepper(A, AQ_MODEL_WORKPATH, NAN, 0, 0, &e) : NULL;
    aq_stepper *every = dem ? aq_job_stepper(A, AQ_MODEL_WORKPATH, NAN, 0, 0, &e) : NULL;
    aq_demand *d1 = every ? aq_arch_demand_tracker(A, 0.6, &e) : NULL;
    aq_demand *d2 = d1 ? aq_arch_demand_tracker(A, 0.6, &e) : NULL;
    if (!d2) {
      aq_error_print(&e, stderr);
      return 1;
    }
    aq_stepper_set_demand(dem, d1);
    aq_demand_set_every(d2, 1);
    aq_stepper_set_demand(every, d2);
    double l0 = aq_lambda0(A), tt[3] = {0, 0, 0}, cold[2] = {0, 0};
    size_t ns = 0, nf = 0, nl = 0, mv = 0;
    for (size_t r = 0; r < NREC; r++) {
      double k = 2.5 * l0 * AQ_G0_MPS2 / V[r].peak_mps2;
      aq_result res[3];
      for (int m = 0; m < 2; m++) { /* warm: tables, grids and caches (timed: cold) */
        double t0 = aq_bench_now_s();
        if (aq_job_run_view(m ? dem : plain, &V[r], k, &res[m], &e) == AQ_OK)
          aq_result_free(&res[m]);
        cold[m] += aq_bench_now_s() - t0;
      }
      /* alternately, so that the machine's drift falls on both alike */
      double tp[REPS_MAX], td[REPS_MAX];
      for (int rep = 0; rep < REPS; rep++) {
        for (int m = 0; m < 2; m++) {
          if (only && m != only - 1) {
            (m ? td : tp)[rep] = 1;
            continue;
          }
          double t0 = aq_bench_now_s();
          if (aq_job_run_view(m ? dem : plain, &V[r], k, &res[m], &e) != AQ_OK) {
            aq_error_print(&e, stderr);
            return 1;
          }
          (m ? td : tp)[rep] = aq_bench_now_s() - t0;
          if (rep + 1 < REPS)
            aq_result_free(&res[m]);
        }
      }
      if (only)
        memset(&res[only % 2], 0, sizeof res[0]);
      tt[0] += aq_bench_median(tp, REPS);
      tt[1] += aq_bench_median(td, REPS);
      if (reference)
        tt[2] += timed(every, &V[r], k, &res[2], t);
      else
        memset(&res[2], 0, sizeof res[2]);
      ns += res[1].demand_samples;
      nf += res[1].demand_full;
      nl += res[1].demand_looks;
      mv += res[1].steps_moving;
      for (int m = 0; m < 3; m++)
        aq_result_free(&res[m]);
    }
    printf("%-10s %10.3f %10.3f %7.3f %9zu %9zu %6.1f %10zu %8zu %9.2f %8.3f %8.3f\n", arches[a],
           tt[0] * 1e3, tt[1] * 1e3, tt[1] / tt[0] - 1, ns, nf, 100.0 * (double)nf / (double)ns,
           nl, mv, tb * 1e3, cold[0] * 1e3, cold[1] * 1e3);
    C[0] += cold[0], C[1] += cold[1];
    for (int m = 0; m < 3; m++)
      T[m] += tt[m];
    tot_states += ns;
    tot_full += nf;
    aq_stepper_free(plain);
    aq_stepper_free(dem);
    aq_stepper_free(every);
    aq_arch_free(A);
  }
  printf("%-10s %10.3f %10.3f %7.3f %9zu %9zu %6.1f\n", "total", T[0] * 1e3, T[1] * 1e3,
         T[1] / T[0] - 1, tot_states, tot_full, 100.0 * (double)tot_full / (double)tot_states);
  printf("\nthe demand's cost over the stepping: %+.1f %% (target: at most +10 %%)\n",
         100 * (T[1] / T[0] - 1));
  printf("the first run of each record (cold: the grids' blocks of cells made as runs reach "
         "them): %.3f ms against %.3f, %+.1f %%\n", C[1] * 1e3, C[0] * 1e3,
         100 * (C[1] / C[0] - 1));
  if (reference)
    printf("every joint at every state (the tracker's reference): %.3f ms, %+.1f %%\n",
           T[2] * 1e3, 100 * (T[2] / T[0] - 1));
  for (size_t r = 0; r < NREC; r++) {
    aq_view_free(&V[r]);
    aq_subject_free(&S[r]);
  }
  aq_signal_ws_free(ws);
  return 0;
}
