/* bench_same.c: the peak normalised cross-correlation (select/same.h) of
 * every two records of a pool, and its cost.
 *
 * The pool: the files named on the command line, or by default every
 * record of tests/data/records, tests/data/records/agency and
 * tests/data/records/agency2 (every horizontal channel a record, read and
 * processed as `archquake select` reads and processes them by default).
 * For a pool of up to 100 records, prints every two records whose rho is
 * at least 0.1 (largest first; the
 * rest are below), the lag of the peak, and the time of comparing every two
 * (aq_same_groups, one thread and two, medians of 5).  The classes (one
 * recording, one station, one event) are read from the names and the
 * files' provenance by the reader of the output: docs/select.md gives the
 * table. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/select_pool.h"
#include "bench.h"
#include "job/names.h"
#include "select/same.h"

typedef struct {
  size_t i, j;
  double rho, lag_s, ratio;
} row;

/* The largest factor between two spectra (the grid and T = 0). */
static double spectrum_ratio(const aq_select_member *a, const aq_select_member *b, size_t nper)
{
  double r = fabs(log(a->psa0_mps2 / b->psa0_mps2));
  for (size_t k = 0; k < nper; k++)
    if (fabs(log(a->psa_mps2[k] / b->psa_mps2[k])) > r)
      r = fabs(log(a->psa_mps2[k] / b->psa_mps2[k]));
  return exp(r);
}

static int by_rho(const void *a, const void *b)
{
  const row *x = a, *y = b;
  return (x->rho < y->rho) - (x->rho > y->rho);
}

static aq_read_opts ro;

int main(int argc, char **argv)
{
  static char *dflt[] = {"tests/data/records", "tests/data/records/agency",
                         "tests/data/records/agency2"};
  char **ops = argc > 1 ? argv + 1 : dflt;
  size_t nops = argc > 1 ? (size_t)argc - 1 : 3;
  aq_error err;
  char **files = NULL, **names = NULL, **notes = NULL;
  size_t nfiles = 0, nnames = 0, nnotes = 0;
  if (aq_select_pool_files(ops, nops, &files, &nfiles, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return 1;
  }
  nfiles = aq_read_opts_take_stationxml(files, nfiles, &ro);
  if (aq_job_names(files, nfiles, &ro, 2, &names, &nnames, &notes, &nnotes, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return 1;
  }
  aq_signal_opts proc;
  aq_signal_opts_default(&proc);
  double *grid;
  size_t nper;
  if (aq_select_grid(0.1, 1.0, NULL, 0, &grid, &nper, &err) != AQ_OK)
    return 1;
  aq_select_pool P = {calloc(nnames, sizeof *P.m), nnames, grid, nper, 0.05, AQ_PAIR_MEAN,
                      {0}, &ro, &proc, NULL};
  aq_spectrum_opts_default(&P.sopts);
  for (size_t i = 0; i < nnames; i++)
    P.m[i].name = P.m[i].path[0] = names[i];
  if (aq_select_pool_prepare(&P, 2, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return 1;
  }
  size_t M = 0;
  aq_same_trace *tr = calloc(2 * nnames, sizeof *tr);
  const char **nm = calloc(nnames, sizeof *nm);
  const aq_select_member **use = calloc(nnames, sizeof *use);
  double *psa = malloc(nnames * nper * sizeof *psa), *psa0 = malloc(nnames * sizeof *psa0);
  for (size_t i = 0; i < nnames; i++)
    if (P.m[i].st != AQ_OK) {
      char line[1200];
      aq_error_format(&P.m[i].err, line, sizeof line);
      fprintf(stderr, "left out: %s\n", line);
    } else {
      tr[2 * M] = P.m[i].trace[0];
      memcpy(psa + M * nper, P.m[i].psa_mps2, nper * sizeof *psa);
      psa0[M] = P.m[i].psa0_mps2;
      use[M] = &P.m[i];
      nm[M++] = P.m[i].name;
    }
  row *rows = malloc(M * M * sizeof *rows);
  size_t nr = 0, below = 0;
  for (size_t i = 0; M <= 100 && i < M; i++) /* the table for pools of up to 100 */
    for (size_t j = i + 1; j < M; j++) {
      row r = {i, j, 0, 0, spectrum_ratio(use[i], use[j], nper)};
      r.rho = aq_same_rho(&tr[2 * i], &tr[2 * j], &r.lag_s);
      if (r.rho >= 0.1)
        rows[nr++] = r;
      else
        below++;
    }
  qsort(rows, nr, sizeof *rows, by_rho);
  printf("%zu usable records of %zu, %zu pairs; rho >= 0.1:\n", M, nnames, M * (M - 1) / 2);
  printf("rho\tlag_s\tspectra_factor\trecord\trecord\n");
  for (size_t k = 0; k < nr; k++)
    printf("%.3f\t%.2f\t%.3g\t%s\t%s\n", rows[k].rho, rows[k].lag_s, rows[k].ratio,
           nm[rows[k].i], nm[rows[k].j]);
  printf("(%zu pairs below 0.1)\n", below);
  int *group = malloc(M * sizeof *group);
  for (int pre = 0; pre < 2; pre++)
  for (long th = 1; th <= 2; th++) {
    double t[5];
    size_t nc = 0;
    for (int r = 0; r < 5; r++) {
      aq_same_pair *pairs;
      size_t np, ng;
      double t0 = aq_bench_now_s();
      aq_same_groups(tr, M, pre ? psa : NULL, nper, pre ? psa0 : NULL, AQ_SAME_RHO_MIN, th,
                     group, &ng, &pairs, &np, &nc, &err);
      t[r] = aq_bench_now_s() - t0;
      free(pairs);
    }
    printf("aq_same_groups, %zu records, %s, -j %ld: %zu correlated, %.4f s (median of 5)\n",
           M, pre ? "spectra within the factor first" : "every two", th, nc,
           aq_bench_median(t, 5));
  }
  free(group);
  free(use);
  free(psa);
  free(psa0);
  free(grid);
  free(rows);
  free(tr);
  free(nm);
  aq_select_pool_free(&P);
  aq_record_names_free(files, nfiles);
  aq_record_names_free(names, nnames);
  aq_record_names_free(notes, nnotes);
  return 0;
}
