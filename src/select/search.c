/* search.c: the exhaustive search and the greedy-then-swaps heuristic
 * (search.h). */
#include "search.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../util/pool.h"

double aq_select_combinations(size_t m, size_t n)
{
  if (n > m)
    return 0;
  if (n > m - n)
    n = m - n;
  double c = 1;
  for (size_t i = 1; i <= n; i++)
    c = c * (double)(m - n + i) / (double)i;
  return floor(c + 0.5);
}

void aq_select_result_free(aq_select_result *r)
{
  free(r->idx);
  r->idx = NULL;
}

/* Indices v[0..n) (NULL: none) that run 0..count-1 (-1: none): count. */
static size_t index_count(const int *v, size_t n)
{
  int top = -1;
  for (size_t i = 0; v && i < n; i++)
    if (v[i] > top)
      top = v[i];
  return (size_t)(top + 1);
}

/* The events' indices run 0..nev-1. */
static size_t event_count(const aq_select_problem *p)
{
  return index_count(p->event, p->nrec);
}

static int limited(const aq_select_problem *p)
{
  return p->event && p->max_per_event > 0;
}

/* The recordings' indices run 0..nrc-1. */
static size_t recording_count(const aq_select_problem *p)
{
  return index_count(p->recording, p->nrec);
}

/* Record i's recording, -1: alone. */
static int recording_of(const aq_select_problem *p, size_t i)
{
  return p->recording ? p->recording[i] : -1;
}

/* ---- exhaustive ---------------------------------------------------------- */

typedef struct {
  const aq_select_prepared *q;
  size_t nev, nrc;
  struct branch {
    size_t *idx, *best_idx;
    double *sums; /* (N + 1) x nper: the running sums at each depth */
    double *zs, *ms;
    size_t *evc;
    char *rcin; /* per recording: 1 if one of its records is in the suite */
    aq_select_eval best;
    int found;
    double evaluated;
    int nomem;
  } *b; /* one per first record */
} exh;

static void dfs(const aq_select_prepared *q, struct branch *b, size_t j, size_t start)
{
  const aq_select_problem *p = q->p;
  size_t N = p->count, M = p->nrec, K = p->nper;
  int lim = limited(p);
  for (size_t i = start; i + (N - j) <= M; i++) {
    int ev = lim ? p->event[i] : -1, rc = recording_of(p, i);
    if ((ev >= 0 && b->evc[ev] >= p->max_per_event) || (rc >= 0 && b->rcin[rc]))
      continue;
    const double *y = q->y + i * K, *s0 = b->sums + j * K;
    double *s1 = b->sums + (j + 1) * K;
    for (size_t k = 0; k < K; k++)
      s1[k] = s0[k] + y[k];
    b->zs[j + 1] = b->zs[j] + (q->z ? q->z[i] : 0);
    b->ms[j + 1] = q->scale[i] > b->ms[j] ? q->scale[i] : b->ms[j];
    b->idx[j] = i;
    if (j + 1 == N) {
      aq_select_eval e;
      aq_select_evaluate_sums(q, N, s1, b->zs[N], b->ms[N], &e);
      b->evaluated += 1;
      if (!b->found || aq_select_better(&e, &b->best)) {
        b->best = e;
        b->found = 1;
        memcpy(b->best_idx, b->idx, N * sizeof *b->idx);
      }
      continue;
    }
    if (ev >= 0)
      b->evc[ev]++;
    if (rc >= 0)
      b->rcin[rc] = 1;
    dfs(q, b, j + 1, i + 1);
    if (ev >= 0)
      b->evc[ev]--;
    if (rc >= 0)
      b->rcin[rc] = 0;
  }
}

static void exh_task(void *ctx, size_t i0)
{
  exh *X = ctx;
  const aq_select_prepared *q = X->q;
  const aq_select_problem *p = q->p;
  struct branch *b = &X->b[i0];
  size_t N = p->count, K = p->nper;
  b->idx = malloc(N * sizeof *b->idx);
  b->best_idx = malloc(N * sizeof *b->best_idx);
  b->sums = calloc((N + 1) * (K ? K : 1), sizeof *b->sums);
  b->zs = calloc(N + 1, sizeof *b->zs);
  b->ms = calloc(N + 1, sizeof *b->ms);
  b->evc = calloc(X->nev + 1, sizeof *b->evc);
  b->rcin = calloc(X->nrc + 1, 1);
  if (!b->idx || !b->best_idx || !b->sums || !b->zs || !b->ms || !b->evc || !b->rcin) {
    b->nomem = 1;
    return;
  }
  /* the branch of first record i0: depth 0 fixed */
  int ev = limited(p) ? p->event[i0] : -1;
  const double *y = q->y + i0 * K;
  for (size_t k = 0; k < K; k++)
    b->sums[K + k] = y[k];
  b->zs[1] = q->z ? q->z[i0] : 0;
  b->ms[1] = q->scale[i0];
  b->idx[0] = i0;
  if (N == 1) {
    aq_select_evaluate_sums(q, 1, b->sums + K, b->zs[1], b->ms[1], &b->best);
    b->found = 1;
    b->evaluated = 1;
    b->best_idx[0] = i0;
    return;
  }
  if (ev >= 0)
    b->evc[ev]++;
  if (recording_of(p, i0) >= 0)
    b->rcin[recording_of(p, i0)] = 1;
  dfs(q, b, 1, i0 + 1);
}

static void branch_free(struct branch *b)
{
  free(b->idx);
  free(b->best_idx);
  free(b->sums);
  free(b->zs);
  free(b->ms);
  free(b->evc);
  free(b->rcin);
}

aq_status aq_select_exhaustive(const aq_select_prepared *q, long threads,
                               aq_select_result *r, aq_error *err)
{
  const aq_select_problem *p = q->p;
  memset(r, 0, sizeof *r);
  r->kind = AQ_SEARCH_EXHAUSTIVE;
  r->combinations = aq_select_combinations(p->nrec, p->count);
  if (p->count == 0 || p->count > p->nrec)
    return AQ_OK;
  size_t nfirst = p->nrec - p->count + 1;
  exh X = {q, event_count(p), recording_count(p), calloc(nfirst, sizeof *X.b)};
  r->idx = malloc(p->count * sizeof *r->idx);
  aq_status st = X.b && r->idx ? aq_pool_for(nfirst, threads, exh_task, &X, err)
                               : aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select",
                                              "out of memory");
  for (size_t i = 0; st == AQ_OK && i < nfirst; i++) {
    struct branch *b = &X.b[i];
    if (b->nomem) {
      st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
      break;
    }
    r->evaluated += b->evaluated;
    if (b->found && (!r->found || aq_select_better(&b->best, &r->eval))) {
      r->found = 1;
      r->eval = b->best;
      memcpy(r->idx, b->best_idx, p->count * sizeof *r->idx);
    }
  }
  for (size_t i = 0; X.b && i < nfirst; i++)
    branch_free(&X.b[i]);
  free(X.b);
  if (st != AQ_OK)
    aq_select_result_free(r);
  return st;
}

/* ---- greedy, then swaps -------------------------------------------------- */

typedef struct {
  const aq_select_prepared *q;
  size_t *set;   /* n records */
  size_t n;
  char *in;      /* nrec: 1 if in the set */
  size_t *evc;   /* per event */
  size_t *rcc;   /* per recording: its records in the set */
  double *sum;   /* nper: sum of the set's y */
  double *trial; /* nper */
  double zsum;
  double evaluated;
} walk;

static double max_scale(const walk *w, size_t skip, size_t add)
{
  double m = add < w->q->p->nrec ? w->q->scale[add] : 0;
  for (size_t j = 0; j < w->n; j++)
    if (j != skip && w->q->scale[w->set[j]] > m)
      m = w->q->scale[w->set[j]];
  return m;
}

/* The suite with set[skip] (skip < n) replaced by c, or c added (skip ==
 * n): its evaluation, from the running sums. */
static void try_swap(walk *w, size_t skip, size_t c, aq_select_eval *e)
{
  const aq_select_prepared *q = w->q;
  size_t K = q->p->nper;
  const double *yc = q->y + c * K;
  double zs = w->zsum + (q->z ? q->z[c] : 0);
  size_t n = w->n + (skip == w->n);
  if (skip < w->n) {
    const double *yo = q->y + w->set[skip] * K;
    for (size_t k = 0; k < K; k++)
      w->trial[k] = w->sum[k] - yo[k] + yc[k];
    zs -= q->z ? q->z[w->set[skip]] : 0;
  } else
    for (size_t k = 0; k < K; k++)
      w->trial[k] = w->sum[k] + yc[k];
  aq_select_evaluate_sums(q, n, w->trial, zs, max_scale(w, skip, c), e);
  w->evaluated += 1;
}

/* 1 if c may replace set[skip] (or be added, skip == n) under the event
 * rule and the rule of one record of a recording. */
static int event_allows(const walk *w, size_t skip, size_t c)
{
  const aq_select_problem *p = w->q->p;
  int rc = recording_of(p, c);
  if (rc >= 0 && w->rcc[rc] - (skip < w->n && recording_of(p, w->set[skip]) == rc) > 0)
    return 0;
  if (!limited(p) || p->event[c] < 0)
    return 1;
  size_t have = w->evc[p->event[c]];
  if (skip < w->n && p->event[w->set[skip]] == p->event[c])
    have--;
  return have < p->max_per_event;
}

static void apply(walk *w, size_t skip, size_t c)
{
  const aq_select_prepared *q = w->q;
  const aq_select_problem *p = q->p;
  size_t K = p->nper;
  if (skip < w->n) {
    size_t o = w->set[skip];
    for (size_t k = 0; k < K; k++)
      w->sum[k] -= q->y[o * K + k];
    w->zsum -= q->z ? q->z[o] : 0;
    w->in[o] = 0;
    if (limited(p) && p->event[o] >= 0)
      w->evc[p->event[o]]--;
    if (recording_of(p, o) >= 0)
      w->rcc[recording_of(p, o)]--;
    w->set[skip] = c;
  } else
    w->set[w->n++] = c;
  for (size_t k = 0; k < K; k++)
    w->sum[k] += q->y[c * K + k];
  w->zsum += q->z ? q->z[c] : 0;
  w->in[c] = 1;
  if (limited(p) && p->event[c] >= 0)
    w->evc[p->event[c]]++;
  if (recording_of(p, c) >= 0)
    w->rcc[recording_of(p, c)]++;
}

/* Greedy from record first, then swaps; *e the end's evaluation.  0 if
 * the greedy could not fill N places under the event rule. */
static int greedy_swaps(walk *w, size_t first, aq_select_eval *e)
{
  const aq_select_problem *p = w->q->p;
  size_t N = p->count, M = p->nrec;
  w->n = 0;
  w->zsum = 0;
  memset(w->in, 0, M);
  memset(w->sum, 0, p->nper * sizeof *w->sum);
  if (limited(p))
    memset(w->evc, 0, (event_count(p) + 1) * sizeof *w->evc);
  memset(w->rcc, 0, (recording_count(p) + 1) * sizeof *w->rcc);
  apply(w, 0, first);
  while (w->n < N) {
    aq_select_eval best;
    size_t bc = M;
    for (size_t c = 0; c < M; c++) {
      if (w->in[c] || !event_allows(w, w->n, c))
        continue;
      aq_select_eval t;
      try_swap(w, w->n, c, &t);
      if (bc == M || aq_select_better(&t, &best)) {
        best = t;
        bc = c;
      }
    }
    if (bc == M)
      return 0;
    apply(w, w->n, bc);
  }
  aq_select_evaluate_sums(w->q, N, w->sum, w->zsum, max_scale(w, N, M), e);
  for (;;) { /* the best single exchange, while one improves */
    aq_select_eval best = *e;
    size_t bp = N, bc = M;
    for (size_t j = 0; j < N; j++)
      for (size_t c = 0; c < M; c++) {
        if (w->in[c] || !event_allows(w, j, c))
          continue;
        aq_select_eval t;
        try_swap(w, j, c, &t);
        if (aq_select_better(&t, &best)) {
          best = t;
          bp = j;
          bc = c;
        }
      }
    if (bc == M)
      break;
    apply(w, bp, bc);
    *e = best;
  }
  return 1;
}

/* A suite of one record, to rank the first records. */
typedef struct {
  aq_select_eval e;
  size_t i;
} single_suite;

/* qsort's comparison: the better suite first, ties by index. */
static int by_single(const void *a, const void *b)
{
  const single_suite *x = a, *y = b;
  if (aq_select_better(&x->e, &y->e))
    return -1;
  if (aq_select_better(&y->e, &x->e))
    return 1;
  return (x->i > y->i) - (x->i < y->i);
}

static int cmp_size(const void *a, const void *b)
{
  size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return (x > y) - (x < y);
}

aq_status aq_select_heuristic(const aq_select_prepared *q, size_t starts, double budget,
                              aq_select_result *r, aq_error *err)
{
  const aq_select_problem *p = q->p;
  size_t M = p->nrec, N = p->count, K = p->nper;
  memset(r, 0, sizeof *r);
  r->kind = AQ_SEARCH_HEURISTIC;
  r->combinations = aq_select_combinations(M, N);
  if (N == 0 || N > M)
    return AQ_OK;
  walk w = {.q = q};
  w.set = malloc(N * sizeof *w.set);
  w.in = malloc(M);
  w.evc = calloc(event_count(p) + 1, sizeof *w.evc);
  w.rcc = calloc(recording_count(p) + 1, sizeof *w.rcc);
  w.sum = malloc((K ? K : 1) * sizeof *w.sum);
  w.trial = malloc((K ? K : 1) * sizeof *w.trial);
  single_suite *single = malloc(M * sizeof *single);
  r->idx = malloc(N * sizeof *r->idx);
  aq_status st = AQ_OK;
  if (!w.set || !w.in || !w.evc || !w.rcc || !w.sum || !w.trial || !single || !r->idx) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
    goto done;
  }
  /* the first records: the best suites of one, in order */
  for (size_t c = 0; c < M; c++) {
    aq_select_evaluate(q, &c, 1, &single[c].e);
    single[c].i = c;
    r->evaluated += 1;
  }
  qsort(single, M, sizeof *single, by_single);
  for (size_t s = 0; s < M && (s < starts || r->evaluated * (double)K < budget); s++) {
    r->starts = s + 1;
    aq_select_eval e;
    w.evaluated = 0;
    int ok = greedy_swaps(&w, single[s].i, &e);
    r->evaluated += w.evaluated;
    if (ok && (!r->found || aq_select_better(&e, &r->eval))) {
      r->found = 1;
      r->eval = e;
      memcpy(r->idx, w.set, N * sizeof *r->idx);
    }
  }
  if (r->found)
    qsort(r->idx, N, sizeof *r->idx, cmp_size);
done:
  free(w.set);
  free(w.in);
  free(w.evc);
  free(w.rcc);
  free(w.sum);
  free(w.trial);
  free(single);
  if (st != AQ_OK)
    aq_select_result_free(r);
  return st;
}

aq_status aq_select_search(const aq_select_prepared *q, double exhaustive_max, long threads,
                           aq_select_result *r, aq_error *err)
{
  if (aq_select_combinations(q->p->nrec, q->p->count) <= exhaustive_max)
    return aq_select_exhaustive(q, threads, r, err);
  return aq_select_heuristic(q, AQ_SELECT_STARTS, AQ_SELECT_HEURISTIC_BUDGET, r, err);
}
