/* same.c: one recording in several members of a pool (same.h). */
#include "same.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>

#include "../util/pool.h"

aq_status aq_same_trace_make(const double *acc_mps2, size_t n, double dt_s, aq_same_trace *t,
                             aq_error *err)
{
  const double h = AQ_SAME_STEP_S;
  double span = n > 1 ? (double)(n - 1) * dt_s : 0;
  size_t m = (size_t)floor(span / h + 1e-9);
  if (m == 0)
    m = 1;
  t->n = 0;
  t->x = malloc(m * sizeof *t->x);
  double *c = malloc(n * sizeof *c); /* the running integral at the samples */
  if (!t->x || !c) {
    free(c);
    aq_same_trace_free(t);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  }
  c[0] = 0;
  for (size_t k = 1; k < n; k++)
    c[k] = c[k - 1] + 0.5 * dt_s * (acc_mps2[k - 1] + acc_mps2[k]);
  if (n == 1) {
    t->x[0] = acc_mps2[0];
  } else {
    double prev = 0; /* C(0) */
    for (size_t k = 0; k < m; k++) {
      double tt = (double)(k + 1) * h / dt_s;
      size_t s = (size_t)tt;
      if (s >= n - 1)
        s = n - 2;
      double f = tt - (double)s;
      double cur = c[s] + f * (c[s + 1] - c[s]);
      t->x[k] = (cur - prev) / h;
      prev = cur;
    }
  }
  t->n = m;
  free(c);
  return AQ_OK;
}

void aq_same_trace_free(aq_same_trace *t)
{
  free(t->x);
  t->x = NULL;
  t->n = 0;
}

static size_t pow2_at_least(size_t n)
{
  size_t L = 2;
  while (L < n)
    L *= 2;
  return L;
}

static double energy(const aq_same_trace *a)
{
  double s = 0;
  for (size_t k = 0; k < a->n; k++)
    s += a->x[k] * a->x[k];
  return s;
}

/* a's transform at length L (halfcomplex, GSL's layout) into buf[L]. */
static void transform(const aq_same_trace *a, double *buf, size_t L)
{
  memcpy(buf, a->x, a->n * sizeof *buf);
  memset(buf + a->n, 0, (L - a->n) * sizeof *buf);
  gsl_fft_real_radix2_transform(buf, 1, L);
}

/* The peak of |r| over lags from A = FFT(a), B = FFT(b) at L (B is
 * overwritten): r = IFFT(conj(A) B); r[tau mod L] = sum_t a(t) b(t + tau). */
static double peak(const double *A, double *B, size_t L, long *lag)
{
  B[0] *= A[0];
  B[L / 2] *= A[L / 2];
  for (size_t i = 1; i < L / 2; i++) {
    double a = A[i], b = A[L - i], c = B[i], d = B[L - i];
    B[i] = a * c + b * d;
    B[L - i] = a * d - b * c;
  }
  gsl_fft_halfcomplex_radix2_inverse(B, 1, L);
  double best = 0;
  size_t at = 0;
  for (size_t k = 0; k < L; k++)
    if (fabs(B[k]) > best) {
      best = fabs(B[k]);
      at = k;
    }
  *lag = at <= L / 2 ? (long)at : (long)at - (long)L;
  return best;
}

double aq_same_rho(const aq_same_trace *a, const aq_same_trace *b, double *lag_s)
{
  if (lag_s)
    *lag_s = 0;
  double ea = energy(a), eb = energy(b);
  if (!(ea > 0) || !(eb > 0))
    return 0;
  size_t L = pow2_at_least(a->n + b->n);
  double *A = malloc(L * sizeof *A), *B = malloc(L * sizeof *B);
  if (!A || !B) {
    free(A);
    free(B);
    return -1;
  }
  transform(a, A, L);
  transform(b, B, L);
  long lag;
  double r = peak(A, B, L, &lag) / sqrt(ea * eb);
  if (lag_s)
    *lag_s = (double)lag * AQ_SAME_STEP_S;
  free(A);
  free(B);
  return r;
}

/* ---- the pool, two by two ------------------------------------------------ */

/* A trace at AQ_SAME_COARSE_STEPS times the step (the mean of that many
 * windows) and its transform at L >= twice its length. */
typedef struct {
  aq_same_trace t;
  double *F; /* L, halfcomplex */
  size_t L;
  double e;  /* sum t^2 */
} coarse;

static int coarse_make(const aq_same_trace *a, coarse *c)
{
  const size_t k = AQ_SAME_COARSE_STEPS;
  memset(c, 0, sizeof *c);
  if (!a->n)
    return 1;
  c->t.n = (a->n + k - 1) / k;
  c->L = pow2_at_least(2 * c->t.n);
  c->t.x = malloc(c->t.n * sizeof *c->t.x);
  c->F = malloc(c->L * sizeof *c->F);
  if (!c->t.x || !c->F)
    return 0;
  for (size_t i = 0; i < c->t.n; i++) {
    double s = 0;
    size_t m = 0;
    for (size_t j = i * k; j < a->n && j < (i + 1) * k; j++, m++)
      s += a->x[j];
    c->t.x[i] = s / (double)m;
  }
  c->e = energy(&c->t);
  transform(&c->t, c->F, c->L);
  return 1;
}

static void coarse_free(coarse *c)
{
  free(c->t.x);
  free(c->F);
}

/* rho of two coarse traces, with work[] of room for the larger L and, if
 * their L differ, tmp[] likewise. */
static double coarse_rho(const coarse *a, const coarse *b, double *work, double *tmp)
{
  if (!(a->e > 0) || !(b->e > 0))
    return 0;
  size_t L = a->L > b->L ? a->L : b->L;
  const double *A = a->F;
  if (a->L != L) {
    transform(&a->t, tmp, L);
    A = tmp;
  }
  if (b->L == L)
    memcpy(work, b->F, L * sizeof *work);
  else
    transform(&b->t, work, L);
  long lag;
  return peak(A, work, L, &lag) / sqrt(a->e * b->e);
}

typedef struct {
  const aq_same_trace *tr;
  const coarse *co; /* 2 m */
  size_t m;
  const double *psa, *psa0;
  size_t nper;
  double rho_min;
  size_t *compared; /* m: per row */
  double *rho; /* m x m, upper triangle: the largest rho of members i < j */
  int nomem;
} groups_ctx;

/* 1 if members i and j have spectra within AQ_SAME_SPECTRUM_RATIO_MAX of
 * each other at every period and at T = 0. */
static int spectra_near(const groups_ctx *G, size_t i, size_t j)
{
  const double lim = AQ_SAME_SPECTRUM_RATIO_MAX;
  if (!G->psa)
    return 1;
  double r = G->psa0[i] / G->psa0[j];
  if (!(r <= lim && r >= 1 / lim))
    return 0;
  const double *a = G->psa + i * G->nper, *b = G->psa + j * G->nper;
  for (size_t k = 0; k < G->nper; k++) {
    r = a[k] / b[k];
    if (!(r <= lim && r >= 1 / lim))
      return 0;
  }
  return 1;
}

/* Row i: member i against every later member. */
static void row(void *vctx, size_t i)
{
  groups_ctx *G = vctx;
  size_t L = 2;
  for (size_t k = 0; k < 2 * G->m; k++)
    L = G->co[k].L > L ? G->co[k].L : L;
  double *work = malloc(2 * L * sizeof *work);
  if (!work) {
    G->nomem = 1;
    return;
  }
  for (size_t j = i + 1; j < G->m; j++) {
    double best = 0;
    if (!spectra_near(G, i, j))
      continue;
    G->compared[i]++;
    for (size_t u = 0; u < 2; u++)
      for (size_t v = 0; v < 2; v++) {
        const aq_same_trace *a = &G->tr[2 * i + u], *b = &G->tr[2 * j + v];
        if (!a->n || !b->n)
          continue;
        double r = coarse_rho(&G->co[2 * i + u], &G->co[2 * j + v], work, work + L);
        if (r >= AQ_SAME_RHO_COARSE)
          r = aq_same_rho(a, b, NULL);
        if (r < 0) {
          G->nomem = 1;
          free(work);
          return;
        }
        if (r > best)
          best = r;
      }
    G->rho[i * G->m + j] = best;
  }
  free(work);
}

static size_t root(size_t *parent, size_t i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

aq_status aq_same_groups(const aq_same_trace *tr, size_t m, const double *psa_mps2,
                         size_t nper, const double *psa0_mps2, double rho_min, long threads,
                         int *group, size_t *ngroups, aq_same_pair **pairs, size_t *npairs,
                         size_t *compared, aq_error *err)
{
  *pairs = NULL;
  *npairs = 0;
  *ngroups = 0;
  *compared = 0;
  coarse *co = calloc(2 * m + 1, sizeof *co);
  groups_ctx G = {tr, co, m, psa_mps2, psa0_mps2, nper, rho_min,
                  calloc(m ? m : 1, sizeof *G.compared), calloc(m ? m * m : 1, sizeof *G.rho),
                  0};
  size_t *parent = malloc((m ? m : 1) * sizeof *parent);
  int *id = malloc((m ? m : 1) * sizeof *id);
  int made = co != NULL;
  for (size_t i = 0; made && i < 2 * m; i++)
    made = coarse_make(&tr[i], &co[i]);
  aq_status st = made && G.rho && G.compared && parent && id ? aq_pool_for(m, threads, row, &G, err)
                                       : aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select",
                                                      "out of memory");
  if (st == AQ_OK && G.nomem)
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  size_t np = 0;
  for (size_t i = 0; st == AQ_OK && i < m; i++)
    *compared += G.compared[i];
  for (size_t i = 0; st == AQ_OK && i < m; i++)
    for (size_t j = i + 1; j < m; j++)
      np += G.rho[i * m + j] >= rho_min;
  if (st == AQ_OK && np && !(*pairs = malloc(np * sizeof **pairs)))
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  if (st == AQ_OK) {
    for (size_t i = 0; i < m; i++)
      parent[i] = i;
    for (size_t i = 0; i < m; i++)
      for (size_t j = i + 1; j < m; j++)
        if (G.rho[i * m + j] >= rho_min) {
          (*pairs)[(*npairs)++] = (aq_same_pair){i, j, G.rho[i * m + j]};
          size_t a = root(parent, i), b = root(parent, j);
          if (a != b)
            parent[a > b ? a : b] = a < b ? a : b;
        }
    /* a group for every root with another member; numbered in order */
    for (size_t i = 0; i < m; i++)
      id[i] = -1;
    for (size_t i = 0; i < m; i++) {
      size_t r = root(parent, i);
      group[i] = -1;
      int shared = r != i;
      for (size_t j = i + 1; !shared && j < m; j++)
        shared = root(parent, j) == r;
      if (!shared)
        continue;
      if (id[r] < 0)
        id[r] = (int)(*ngroups)++;
      group[i] = id[r];
    }
  }
  for (size_t i = 0; co && i < 2 * m; i++)
    coarse_free(&co[i]);
  free(co);
  free(G.rho);
  free(G.compared);
  free(parent);
  free(id);
  return st;
}
