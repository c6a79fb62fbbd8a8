/* choose.c: a selection from start to end (choose.h). */
#include "choose.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"

/* Events as indices: records naming the same event share one. */
static size_t index_events(const char *const *key, size_t n, int *event)
{
  size_t nev = 0;
  for (size_t i = 0; i < n; i++) {
    event[i] = -1;
    if (!key || !key[i] || !key[i][0])
      continue;
    for (size_t j = 0; j < i; j++)
      if (event[j] >= 0 && !strcmp(key[j], key[i])) {
        event[i] = event[j];
        break;
      }
    if (event[i] < 0)
      event[i] = (int)nev++;
  }
  return nev;
}

aq_status aq_select_choose(const aq_select_input *in, aq_selection *s, aq_error *err)
{
  memset(s, 0, sizeof *s);
  size_t K = in->nper, M = in->nrec, N = in->count;
  s->target_mps2 = malloc((K ? K : 1) * sizeof *s->target_mps2);
  s->event = malloc((M ? M : 1) * sizeof *s->event);
  s->scale = calloc(N ? N : 1, sizeof *s->scale);
  s->misfit_one = calloc(N ? N : 1, sizeof *s->misfit_one);
  if (!s->target_mps2 || !s->event || !s->scale || !s->misfit_one) {
    aq_selection_free(s);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  }
  for (size_t k = 0; k < K; k++)
    s->target_mps2[k] = aq_target_psa(in->target, in->periods_s[k]);
  s->nevents = index_events(in->event_key, M, s->event);
  aq_select_problem *p = &s->problem;
  *p = (aq_select_problem){.nrec = M, .nper = K, .psa_mps2 = in->psa_mps2,
                           .pga_mps2 = in->psa0_mps2, .event = s->event,
                           .target_mps2 = s->target_mps2, .band = AQ_SELECT_BAND,
                           .scale_lo = in->scale_lo, .scale_hi = in->scale_hi, .count = N,
                           .max_per_event = in->max_per_event, .recording = in->recording};
  if (in->target->kind == AQ_TARGET_EC8) /* EN 1998-1 3.2.3.1.2(4)a: a_g S */
    p->target0_mps2 = in->target->ag_mps2 * in->target->soil;
  aq_status st = aq_select_prepare(p, &s->prep, err);
  if (st == AQ_OK)
    st = aq_select_search(&s->prep, in->exhaustive_max, in->threads, &s->search, err);
  if (st != AQ_OK) {
    aq_selection_free(s);
    return st;
  }
  if (!s->search.found)
    return AQ_OK;
  const aq_select_eval *e = &s->search.eval;
  double f = e->feasible ? e->factor : in->scale_hi / e->max_scale; /* as far as allowed */
  if (f < 1)
    f = 1;
  s->raised = f > 1;
  for (size_t j = 0; j < N; j++) {
    size_t i = s->search.idx[j];
    s->scale[j] = f * s->prep.scale[i];
    s->misfit_one[j] = aq_select_misfit_one(in->psa_mps2 + i * K, s->scale[j], s->target_mps2, K);
  }
  s->nchecks = aq_select_checks(&s->prep, in->target, in->periods_s, s->search.idx, N, f,
                                in->event_key, s->checks);
  s->all_hold = e->feasible && aq_select_checks_hold(s->checks, s->nchecks);
  return AQ_OK;
}

void aq_selection_free(aq_selection *s)
{
  aq_select_result_free(&s->search);
  aq_select_prepared_free(&s->prep);
  free(s->target_mps2);
  free(s->event);
  free(s->scale);
  free(s->misfit_one);
  s->target_mps2 = s->scale = s->misfit_one = NULL;
  s->event = NULL;
}

void aq_selection_shortfall(const aq_selection *s, const aq_select_input *in, char *buf,
                            size_t n)
{
  if (!s->search.found) {
    size_t alone = 0; /* records less those that repeat a recording */
    for (size_t i = 0; i < in->nrec; i++) {
      int first = 1;
      for (size_t j = 0; in->recording && in->recording[i] >= 0 && j < i; j++)
        first &= in->recording[j] != in->recording[i];
      alone += first;
    }
    if (in->max_per_event)
      snprintf(buf, n, "no suite of %zu records holds at most %zu records of one event and "
               "one of each recording: the pool's %zu usable records name %zu events and "
               "are %zu recordings", in->count, in->max_per_event, in->nrec, s->nevents,
               alone);
    else
      snprintf(buf, n, "no suite of %zu records holds one of each recording: the pool's %zu "
               "usable records are %zu recordings", in->count, in->nrec, alone);
    return;
  }
  size_t w = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < s->nchecks && w + 1 < n; i++) {
    if (s->checks[i].holds)
      continue;
    int k = snprintf(buf + w, n - w, "%s%s: %s", w ? "; " : "", s->checks[i].name,
                     s->checks[i].detail);
    if (k < 0)
      break;
    w += (size_t)k < n - w ? (size_t)k : n - w - 1;
  }
  if (!s->search.eval.feasible && w + 1 < n)
    snprintf(buf + w, n - w, "%s(the best suite raised as far as the scale range allows, by "
             "%.4g, its largest scale then %g; it needs %.4g)", w ? " " : "",
             in->scale_hi / s->search.eval.max_scale, in->scale_hi, s->search.eval.factor);
}

void aq_selection_factor_note(const aq_selection *s, const aq_select_input *in, char *buf,
                              size_t n)
{
  const aq_select_eval *e = &s->search.eval;
  if (!s->search.found || !s->raised) {
    snprintf(buf, n, "1 (the suite's own scales meet the conditions)");
    return;
  }
  double f = s->scale[0] / s->prep.scale[s->search.idx[0]];
  const char *why = "its mean fell below";
  if (!isnan(e->zero_ratio) && -log(e->zero_ratio) > log(AQ_SELECT_BAND / e->min_ratio))
    snprintf(buf, n, "%.6g: the suite's mean zero-period value was %.4g of a_g S, so every "
             "scale is raised by this factor", f, e->zero_ratio);
  else
    snprintf(buf, n, "%.6g: %s %g %% of the target at %g s (%.4g of it), so every scale is "
             "raised by this factor", f, why, 100 * AQ_SELECT_BAND,
             in->periods_s[e->min_k], e->min_ratio);
}

size_t aq_selection_describe(const aq_selection *s, const aq_select_input *in,
                             const aq_selection_context *c,
                             char lines[][AQ_SELECTION_LINE_MAX])
{
  size_t n = 0;
  char t[512];
  const size_t L = AQ_SELECTION_LINE_MAX;
  snprintf(lines[n++], L, "archquake select (%s): a suite of %zu for the target %s", c->build,
           in->count, in->target->spec);
  aq_target_describe(in->target, t, sizeof t);
  snprintf(lines[n++], L, "target: %s", t);
  snprintf(lines[n++], L, "range: %g to %g s (%s); %zu periods, where the misfit and the "
           "checks are computed", in->periods_s[0], in->periods_s[in->nper - 1],
           c->range_from, in->nper);
  snprintf(lines[n++], L, "spectra: damping %g, peaks %s, pairs %s; processing: %s",
           in->target->damping, c->peaks, c->pair_rule, c->processing);
  char ev[64] = "no limit of records per event";
  if (in->max_per_event)
    snprintf(ev, sizeof ev, "at most %zu records of one event", in->max_per_event);
  snprintf(lines[n++], L, "rule: %s: the mean scaled spectrum at least %g %% of the target "
           "over the range%s; %s; at least %zu records; each scale within %g to %g",
           aq_target_code(in->target), 100 * AQ_SELECT_BAND,
           in->target->kind == AQ_TARGET_EC8 ? ", the mean PGA at least a_g S" : "", ev,
           aq_select_min_count(in->target), in->scale_lo, in->scale_hi);
  snprintf(lines[n++], L, "search: %s over a pool of %zu usable records, %.0f combinations, "
           "%.0f suites evaluated",
           s->search.kind == AQ_SEARCH_EXHAUSTIVE
               ? "exhaustive (every combination)"
               : "greedy, then swaps (Jayaram, Lin & Baker 2011)",
           c->nusable, s->search.combinations, s->search.evaluated);
  if (c->same)
    snprintf(lines[n++], L, "same recording: %s", c->same);
  aq_selection_factor_note(s, in, t, sizeof t);
  snprintf(lines[n++], L, "common factor: %s", t);
  snprintf(lines[n++], L, "misfit: %.6g (mean over the periods of (ln mean scaled PSA - ln "
           "target)^2)", s->search.eval.misfit);
  for (size_t i = 0; i < s->nchecks; i++)
    snprintf(lines[n++], L, "check %s: %s: %s", s->checks[i].name,
             s->checks[i].holds ? "holds" : "FAILS", s->checks[i].detail);
  snprintf(lines[n++], L, "conditions: %s", s->all_hold ? "all hold" : "NOT ALL HOLD");
  return n;
}
