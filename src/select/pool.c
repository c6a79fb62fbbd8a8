/* pool.c: the grid and a pool member's spectrum (pool.h). */
#include "pool.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

aq_pair_rule aq_select_pair_rule(const aq_target *t)
{
  return t->kind == AQ_TARGET_EC8     ? AQ_PAIR_MEAN
         : t->kind == AQ_TARGET_ASCE7 ? AQ_PAIR_ROTD100
                                      : AQ_PAIR_ROTD50;
}

const char *aq_select_pair_name(aq_pair_rule r)
{
  return r == AQ_PAIR_MEAN ? "mean of H1 and H2" : r == AQ_PAIR_ROTD100 ? "RotD100" : "RotD50";
}

const char *aq_select_peaks_name(const aq_spectrum_opts *opts)
{
  return aq_spectrum_peaks_names[opts->peaks];
}

aq_status aq_select_grid(double t1_s, double t2_s, const double *user, size_t n_user,
                         double **periods, size_t *n, aq_error *err)
{
  size_t cap = (n_user ? n_user : AQ_SPECTRUM_PEER_N) + 2, k = 0;
  double *v = malloc(cap * sizeof *v);
  if (!v)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  if (n_user) {
    for (size_t i = 0; i < n_user; i++)
      if (user[i] >= t1_s && user[i] <= t2_s)
        v[k++] = user[i];
  } else {
    v[k++] = t1_s;
    for (size_t i = 0; i < AQ_SPECTRUM_PEER_N; i++)
      if (aq_spectrum_peer_periods_s[i] > t1_s && aq_spectrum_peer_periods_s[i] < t2_s)
        v[k++] = aq_spectrum_peer_periods_s[i];
    v[k++] = t2_s;
  }
  /* ascending and distinct (a user's list is distinct, in any order) */
  for (size_t i = 1; i < k; i++)
    for (size_t j = i; j > 0 && v[j - 1] > v[j]; j--) {
      double x = v[j];
      v[j] = v[j - 1];
      v[j - 1] = x;
    }
  if (k == 0) {
    free(v);
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--period-grid",
                        "expected periods within the range %g to %g s, got none", t1_s, t2_s);
  }
  *periods = v;
  *n = k;
  return AQ_OK;
}

aq_status aq_select_spectrum(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                             const aq_processed *a, const aq_processed *b, aq_pair_rule rule,
                             double damping, const double *periods, size_t n,
                             double *psa_mps2, double *psa0_mps2, aq_error *err)
{
  /* the grid and T = 0 in one call */
  double *T = malloc((n + 1) * sizeof *T);
  double *out = malloc(2 * (n + 1) * sizeof *out);
  aq_rotd *rd = b && rule != AQ_PAIR_MEAN ? malloc((n + 1) * sizeof *rd) : NULL;
  aq_status st = AQ_OK;
  if (!T || !out || (b && rule != AQ_PAIR_MEAN && !rd)) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
    goto done;
  }
  T[0] = 0;
  memcpy(T + 1, periods, n * sizeof *T);
  if (!b) {
    st = aq_spectrum_psa(ws, opts, a->acc_mps2, a->n, a->dt_s, damping, T, n + 1, out, err);
  } else if (rule == AQ_PAIR_MEAN) {
    st = aq_spectrum_psa(ws, opts, a->acc_mps2, a->n, a->dt_s, damping, T, n + 1, out, err);
    if (st == AQ_OK)
      st = aq_spectrum_psa(ws, opts, b->acc_mps2, b->n, b->dt_s, damping, T, n + 1,
                           out + n + 1, err);
    for (size_t k = 0; st == AQ_OK && k <= n; k++)
      out[k] = 0.5 * (out[k] + out[n + 1 + k]);
  } else {
    st = aq_spectrum_rotd(ws, opts, a->acc_mps2, a->n, b->acc_mps2, b->n, a->dt_s, damping, T,
                          n + 1, rd, NULL, err);
    for (size_t k = 0; st == AQ_OK && k <= n; k++)
      out[k] = rule == AQ_PAIR_ROTD100 ? rd[k].rotd100_mps2 : rd[k].rotd50_mps2;
  }
  if (st == AQ_OK) {
    *psa0_mps2 = out[0];
    memcpy(psa_mps2, out + 1, n * sizeof *psa_mps2);
  }
done:
  free(T);
  free(out);
  free(rd);
  return st;
}
