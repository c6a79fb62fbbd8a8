/* checks.c: the code's conditions on a chosen suite (checks.h). */
#include "checks.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../units.h"

/* Rounding allowed in a condition computed at exactly its bound (the
 * common factor makes the lowest ratio the band itself). */
#define CHECK_REL_SLACK 1e-12

size_t aq_select_min_count(const aq_target *t)
{
  return t->kind == AQ_TARGET_EC8 ? 3 : t->kind == AQ_TARGET_ASCE7 ? 11 : 1;
}

size_t aq_select_checks(const aq_select_prepared *q, const aq_target *t,
                        const double *periods_s, const size_t *idx, size_t n, double f,
                        const char *const *event_key, aq_select_check *out)
{
  const aq_select_problem *p = q->p;
  size_t nc = 0, K = p->nper;
  /* the band: min_k f mean_i y_ik */
  double lo = INFINITY;
  size_t klo = 0;
  for (size_t k = 0; k < K; k++) {
    double m = 0;
    for (size_t j = 0; j < n; j++)
      m += q->y[idx[j] * K + k];
    m = f * m / (double)n;
    if (m < lo)
      lo = m, klo = k;
  }
  aq_select_check *c = &out[nc++];
  c->name = "band";
  c->holds = lo >= p->band * (1 - CHECK_REL_SLACK);
  snprintf(c->detail, sizeof c->detail,
           "the mean scaled spectrum is at least %g %% of the target at every period of "
           "%g to %g s: lowest %.4f of it, at %g s", 100 * p->band, periods_s[0],
           periods_s[K - 1], lo, periods_s[klo]);
  if (q->z) {
    double z = 0;
    for (size_t j = 0; j < n; j++)
      z += q->z[idx[j]];
    z = f * z / (double)n;
    c = &out[nc++];
    c->name = "zero-period";
    c->holds = z >= 1 - CHECK_REL_SLACK;
    snprintf(c->detail, sizeof c->detail,
             "the mean zero-period value (PGA) of the scaled records is at least a_g S = "
             "%.4g g: %.4g g", p->target0_mps2 / AQ_G0_MPS2, z * p->target0_mps2 / AQ_G0_MPS2);
  }
  c = &out[nc++];
  c->name = "events";
  if (!p->event || p->max_per_event == 0) {
    c->holds = 1;
    snprintf(c->detail, sizeof c->detail, "no limit of records per event (--max-per-event)");
  } else {
    size_t most = 0, at = 0, unknown = 0;
    for (size_t j = 0; j < n; j++) {
      if (p->event[idx[j]] < 0) {
        unknown++;
        continue;
      }
      size_t c2 = 0;
      for (size_t i = 0; i < n; i++)
        c2 += p->event[idx[i]] == p->event[idx[j]];
      if (c2 > most)
        most = c2, at = j;
    }
    c->holds = most <= p->max_per_event;
    int w = snprintf(c->detail, sizeof c->detail, "at most %zu records of one event: %zu of "
                     "\"%.80s\"", p->max_per_event, most,
                     most && event_key ? event_key[idx[at]] : "");
    if (unknown && w > 0 && (size_t)w < sizeof c->detail)
      snprintf(c->detail + w, sizeof c->detail - (size_t)w, "; %zu naming no event", unknown);
  }
  size_t need = aq_select_min_count(t);
  c = &out[nc++];
  c->name = "count";
  c->holds = n >= need;
  snprintf(c->detail, sizeof c->detail, "%zu records, at least %zu%s", n, need,
           t->kind == AQ_TARGET_EC8 ? " (EN 1998-1 3.2.3.1.2(3); 7 for the mean response)"
           : t->kind == AQ_TARGET_ASCE7 ? " (ASCE/SEI 7-22 16.2.2)"
                                        : "");
  return nc;
}

int aq_select_checks_hold(const aq_select_check *out, size_t n)
{
  for (size_t i = 0; i < n; i++)
    if (!out[i].holds)
      return 0;
  return 1;
}
