/* stepper.c: dynamic response of a two-set hinge mechanism to constant-
 * acceleration steps (see stepper.h), and the work-path model.
 *
 * The method is that of
 *   G. L. Stockdale, V. Sarhosis, G. Milani, "Work-path approach seismic
 *   modelling of hinge-controlled masonry arches" (sections 2.6-3, Fig. 9),
 * with the corrections of docs/method.md sec. 4-9: the exact energy balance
 *     KE(s) = KE1 - a_g m_T (x(s) - x(s1)) - g m_T (y(s) - y(s1))  (eq. 19,
 *                                                    per docs/method.md sec. 5)
 * and the exact time integral
 *     t - t0 = int sqrt(M(s) / (2 KE(s))) ds       (eqs. 24-25, per docs/method.md
 *                                                    secs. 4 and 6).
 *
 *
 * The leg integrators are apart: leg_taylor.c (default), leg_quad.c
 * (workpath-quad), eom.c (ode), paper.c (paper); making and setting up a
 * stepper is stepper_setup.c's.  This file holds a run: the event rules
 * between legs.
 *
 * Rules (docs/dynamics.md):
 *   - start from rest on set k only when a_g * act_sign_k > lambda0_k g;
 *   - a vertical ground acceleration a_v (steps' av_mps2, positive up)
 *     replaces g by g + a_v for its step, in the balance, the threshold and
 *     every leg (each leg gets a copy of the set's path with that g); a
 *     step with g + a_v <= 0 ends the run with AQ_ELIFTOFF;
 *     quiet steps are skipped with aq_steps_next_outside;
 *   - impact at the return to s = 0: switch to the other set and keep
 *     cor * KE (cor is the kinetic-energy ratio, docs/method.md sec. 7) or, with
 *     the momentum rule, the velocity impact_vel_ratio * |sdot| (a ratio
 *     <= 0: plastic stop, as below);
 *   - the other set inadmissible: plastic stop, the arch rests at s = 0
 *     (docs/method.md sec. 8: an inadmissible set is never integrated);
 *   - rest: after an impact, KE <= rest_tol * E_ref (E_ref = m_T g y(s_c)
 *     of the primary set, the energy that collapses it) ends the motion;
 *     it restarts only when a step's acceleration activates a set;
 *   - collapse: s reaches s_c of the active set (docs/method.md sec. 9); the time is
 *     that of the exact crossing within the step.
 */
#include "stepper.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "stepper_impl.h"

static const size_t MAX_EVENTS_PER_STEP = 2000000; /* beyond: no progress, an error */

static aq_status hist_push(aq_history *h, double t, double q, double x,
                           double ke, double pe, int set)
{
  if (h->n == h->cap) {
    size_t cap = h->cap ? 2 * h->cap : 256;
    double *a = realloc(h->time_s, cap * sizeof *a);
    if (!a)
      return AQ_ENOMEM;
    h->time_s = a;
    if (!(a = realloc(h->rotation_rad, cap * sizeof *a)))
      return AQ_ENOMEM;
    h->rotation_rad = a;
    if (!(a = realloc(h->displacement_m, cap * sizeof *a)))
      return AQ_ENOMEM;
    h->displacement_m = a;
    if (!(a = realloc(h->kinetic_energy_j, cap * sizeof *a)))
      return AQ_ENOMEM;
    h->kinetic_energy_j = a;
    if (!(a = realloc(h->potential_energy_j, cap * sizeof *a)))
      return AQ_ENOMEM;
    h->potential_energy_j = a;
    int *b = realloc(h->set, cap * sizeof *b);
    if (!b)
      return AQ_ENOMEM;
    h->set = b;
    h->cap = cap;
  }
  h->time_s[h->n] = t;
  h->rotation_rad[h->n] = q;
  h->displacement_m[h->n] = x;
  h->kinetic_energy_j[h->n] = ke;
  h->potential_energy_j[h->n] = pe;
  h->set[h->n] = set;
  h->n++;
  return AQ_OK;
}

/* max |x(s)| over [0, smax]: 32 samples, then golden-section search about
 * the largest.  Returns -1 if the path cannot be evaluated. */
static double path_peak_x(const aq_path *p, int exact, double smax,
                          size_t *evals)
{
  enum { NS = 32 };
  const double gr = 0.5 * (sqrt(5.0) - 1);
  aq_path_point pt;
  double best = -1, sb = 0;
  for (int i = 0; i <= NS; i++) {
    double s = smax * i / NS;
    if (aq_eom_eval(p, exact, s, &pt))
      return -1;
    (*evals)++;
    if (fabs(pt.x_m) > best) {
      best = fabs(pt.x_m);
      sb = s;
    }
  }
  double lo = fmax(0, sb - smax / NS), hi = fmin(smax, sb + smax / NS);
  double c = hi - gr * (hi - lo), d = lo + gr * (hi - lo), fc, fd;
  if (aq_eom_eval(p, exact, c, &pt))
    return -1;
  fc = fabs(pt.x_m);
  if (aq_eom_eval(p, exact, d, &pt))
    return -1;
  fd = fabs(pt.x_m);
  for (int it = 0; it < 80 && hi - lo > 1e-15 * fmax(smax, 1); it++) {
    if (fc > fd) {
      hi = d;
      d = c;
      fd = fc;
      c = hi - gr * (hi - lo);
      if (aq_eom_eval(p, exact, c, &pt))
        return -1;
      fc = fabs(pt.x_m);
    } else {
      lo = c;
      c = d;
      fc = fd;
      d = lo + gr * (hi - lo);
      if (aq_eom_eval(p, exact, d, &pt))
        return -1;
      fd = fabs(pt.x_m);
    }
    (*evals)++;
  }
  return fmax(best, fmax(fc, fd));
}

/* The set that a_mps2 would open from rest under vertical acceleration
 * av_mps2 (positive up), or -1. */
static int activated(const aq_stepper *st, double a, double av)
{
  int best = -1;
  double excess = 0;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = st->path[k];
    if (!p)
      continue;
    double e = a * p->act_sign - p->lambda0 * (p->g_mps2 + av); /* docs/dynamics.md */
    if (e > 0 && e > excess) {
      excess = e;
      best = k;
    }
  }
  return best;
}

/* A leg on set's path p (the set's own, or its copy with g + a_v). */
static aq_status leg(aq_stepper *st, int set, const aq_path *p, double a,
                     aq_motion *m, double dt, double *used, aq_leg_end *end,
                     aq_leg_stats *S, aq_error *err)
{
  switch (st->model) {
  case AQ_MODEL_ODE:
    return aq_eom_leg(st->eom, p, a, m, dt, used, end, S, err);
  case AQ_MODEL_PAPER:
    return aq_paper_leg(st->paper, set, a, m, dt, used, end, S, err);
  default: {
    if (st->taylor && p->piece && !st->exact)
      return aq_taylor_leg(st->taylor, p, a, m, dt, used, end, S, err);
    return aq_quad_leg(st->quad, p, a, m, dt, used, end, S, err);
  }
  }
}

/* History samples at turning points inside legs (aq_leg_stats.turn). */
typedef struct {
  aq_history *h;
  const aq_path *p;
  int set;
  double t0_s; /* record time of the leg's start */
  aq_status rc;
} hist_turn_ctx;

static void hist_turn(void *ctx, double t_s, double s, double x_m, double y_m)
{
  hist_turn_ctx *c = ctx;
  if (c->rc != AQ_OK)
    return;
  const aq_path *p = c->p;
  c->rc = hist_push(c->h, c->t0_s + t_s, p->q_sign * s, x_m, 0,
                    p->mass_kg * p->g_mps2 * y_m, c->set);
}

/* The peak |x| over [0, smax] on p: |x(smax)| where |x| is known to be
 * monotone (path.h x_mono_rad), else path_peak_x.  -1 on failure. */
static double peak_x(const aq_path *p, int exact, double smax, size_t *evals)
{
  if (smax <= p->x_mono_rad) {
    aq_path_point pt;
    (*evals)++;
    return aq_eom_eval(p, exact, smax, &pt) ? -1 : fabs(pt.x_m);
  }
  return path_peak_x(p, exact, smax, evals);
}

aq_status aq_stepper_run(aq_stepper *st, const aq_steps *steps, aq_result *res,
                         aq_error *err)
{
  if (st->delegated)
    return st->del.run(st->del.ctx, steps, st->scale, st->history, res, err);
  memset(res, 0, sizeof *res);
  res->collapse_time_s = NAN;
  res->first_set = res->peak_set = -1;
  res->steps_total = steps->n;
  if (st->quad)
    aq_quad_reset(st->quad);
  if (st->taylor)
    aq_taylor_reset(st->taylor);
  st->rest_since_s = NAN;
  st->m0_kgm2[0] = st->m0_kgm2[1] = NAN;
  double rest_since = steps->n ? aq_steps_t(steps, 0) : 0; /* at rest from the start */
  if (st->eom)
    aq_eom_reset(st->eom);
  /* the joints' demand: followed along the legs under every model but
   * paper, whose printed fits carry no joint forces; a run in which the arch
   * never moves has the statics' demand under every model (docs/demand.md) */
  aq_demand *const dem = st->demand;
  const int dem_legs = dem && st->model != AQ_MODEL_PAPER;
  aq_leg_stats S = {0};
  hist_turn_ctx hc = {&res->history, NULL, 0, 0, AQ_OK};
  if (st->history) {
    S.turn = hist_turn;
    S.turn_ctx = &hc;
  }
  /* Vertical acceleration (scaled with the motion, never negated): the run
   * ends before the first step with g + a_v <= 0 (n_end), and the quiet
   * band uses the lowest g + a_v before it. */
  const double *avs = steps->av_mps2, vscale = fabs(st->scale);
  size_t n_end = steps->n;
  double av_min = 0, g_min = st->path[0]->g_mps2;
  for (int k = 1; k < 2; k++)
    if (st->path[k])
      g_min = fmin(g_min, st->path[k]->g_mps2);
  if (avs && st->model == AQ_MODEL_PAPER) {
    aq_error_set(err, AQ_EUNSUPPORTED, NULL, -1, -1, "model",
                 "expected workpath, workpath-quad or ode with a vertical "
                 "acceleration, got paper (its fits assume g)");
    aq_result_free(res);
    return AQ_EUNSUPPORTED;
  }
  for (size_t k = 0; avs && k < steps->n; k++) {
    double av = vscale * avs[k];
    if (!(g_min + av > 0)) {
      n_end = k;
      break;
    }
    av_min = k == 0 ? av : fmin(av_min, av);
  }
  double lo = -INFINITY, hi = INFINITY; /* quiet band at rest */
  for (int k = 0; k < 2; k++) {
    const aq_path *p = st->path[k];
    if (!p)
      continue;
    double thr = p->lambda0 * (p->g_mps2 + av_min);
    if (p->act_sign > 0)
      hi = fmin(hi, thr);
    else
      lo = fmax(lo, -thr);
  }
  /* the band of the unscaled steps: scale * a in [lo, hi], widened by a few
   * ulps so that a step at the edge is looked at (activated() decides) */
  const double scale = st->scale;
  double blo = -INFINITY, bhi = INFINITY;
  if (scale != 0) {
    blo = (scale > 0 ? lo : hi) / scale;
    bhi = (scale > 0 ? hi : lo) / scale;
    blo -= 4 * DBL_EPSILON * fabs(blo);
    bhi += 4 * DBL_EPSILON * fabs(bhi);
  }
  if (dem)
    aq_demand_begin(dem);
  int rest = 1, set = -1;
  double smax[2] = {0, 0}; /* largest s reached on each set */
  aq_motion m = {0, 0, 1, 0, 0};
  aq_status rc = AQ_OK;
  double e_in = 0;
  size_t i = 0;
  while (i < n_end) {
    if (rest) {
      size_t j = aq_steps_next_outside(steps, i, blo, bhi);
      if (st->history)
        for (; i < j; i++)
          if ((rc = hist_push(&res->history, aq_steps_t(steps, i) + aq_steps_dt(steps, i),
                              0, 0, 0, 0, -1)) != AQ_OK)
            goto nomem;
      i = j;
      if (i >= n_end)
        break;
    }
    const double a = scale * steps->a_mps2[i], dt = aq_steps_dt(steps, i);
    const double av = avs ? vscale * avs[i] : 0;
    if (avs)
      for (int k = 0; k < 2; k++)
        if (st->path[k])
          st->pv[k].g_mps2 = st->path[k]->g_mps2 + av; /* docs/dynamics.md */
    double t_in = 0; /* time used within step i */
    res->steps_moving++;
    for (size_t nev = 0; t_in < dt; nev++) {
      if (nev > MAX_EVENTS_PER_STEP) {
        rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "stepper",
                          "no progress at t = %.3f s (%zu events in one step)",
                          aq_steps_t(steps, i) + t_in, nev);
        goto fail;
      }
      if (rest) {
        int k = activated(st, a, av);
        if (k < 0)
          break;
        rest = 0;
        rest_since = NAN;
        set = k;
        if (res->first_set < 0)
          res->first_set = k;
        m = (aq_motion){0, 0, 1, 0, 0};
      }
      double used = 0, x0 = m.x_m, y0 = m.y_m, peak_s_all = S.peak_s;
      aq_leg_end end = AQ_LEG_TIME;
      /* legs locate only turning points above the set's largest s so far */
      S.peak_s = fmax(m.s, smax[set]);
      hc.p = st->path[set];
      hc.set = set;
      hc.t0_s = aq_steps_t(steps, i) + t_in;
      const double g_leg = avs ? st->pv[set].g_mps2 : st->path[set]->g_mps2;
      const size_t rev0 = S.reversals;
      const double s0 = m.s, ke0 = m.ke_j;
      rc = leg(st, set, avs ? &st->pv[set] : st->path[set], a, &m, dt - t_in, &used,
               &end, &S, err);
      aq_demand_leg_rec *r;
      if (dem_legs && rc == AQ_OK && (r = aq_demand_slot(dem)))
        *r = (aq_demand_leg_rec){s0, ke0, hc.t0_s, m.s, m.ke_j,
                                 hc.t0_s + (end == AQ_LEG_TIME ? dt - t_in : used), a, g_leg,
                                 set, m.dir, S.reversals - rev0};
      if (hc.rc != AQ_OK)
        goto nomem;
      if (end == AQ_LEG_COLLAPSE)
        S.peak_s = st->path[set]->s_c_rad;
      smax[set] = fmax(smax[set], S.peak_s);
      S.peak_s = fmax(S.peak_s, peak_s_all);
      if (rc != AQ_OK) {
        size_t len = strlen(err->message);
        snprintf(err->message + len, sizeof err->message - len,
                 " at t = %.3f s", aq_steps_t(steps, i) + t_in);
        goto fail;
      }
      e_in += -a * st->path[set]->mass_kg * (m.x_m - x0);
      if (avs) /* the vertical ground motion's work */
        e_in += -av * st->path[set]->mass_kg * (m.y_m - y0);
      if (m.ke_j > S.peak_ke_j)
        S.peak_ke_j = m.ke_j;
      if (fabs(m.x_m) > S.peak_x_m)
        S.peak_x_m = fabs(m.x_m);
      t_in = end == AQ_LEG_TIME ? dt : t_in + used;
      if (end == AQ_LEG_COLLAPSE) {
        res->collapsed = 1;
        res->collapse_time_s = aq_steps_t(steps, i) + t_in;
        S.peak_s = fmax(S.peak_s, st->path[set]->s_c_rad);
        break;
      }
      if (end == AQ_LEG_REST) {
        rest = 1;
        rest_since = aq_steps_t(steps, i) + t_in;
        m = (aq_motion){0, 0, 1, 0, 0};
        if (activated(st, a, av) == set || activated(st, a, av) < 0)
          break; /* nothing moves it within this step */
        continue;
      }
      if (end == AQ_LEG_IMPACT) {
        res->impacts++;
        double ke_pre = m.ke_j, ke_post = 0;
        if (st->history &&
            (rc = hist_push(&res->history, aq_steps_t(steps, i) + t_in, 0, 0, ke_pre,
                            0, set)) != AQ_OK)
          goto nomem;
        int other = 1 - set;
        const aq_path *q = st->path[other];
        if (q) {
          if (st->momentum) {
            for (int k = 0; k < 2; k++) {
              aq_path_point p0;
              if (isnan(st->m0_kgm2[k])) {
                if (aq_eom_eval(st->path[k], st->exact, 0, &p0)) {
                  rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "stepper",
                                    "path evaluation failed at s = 0");
                  goto fail;
                }
                st->m0_kgm2[k] = p0.mgen_kgm2;
              }
            }
            S.evals += 2; /* counted at every impact, as when evaluated there */
            double sdot = sqrt(2 * ke_pre / st->m0_kgm2[set]);
            /* a ratio <= 0: the arriving motion would close the new set's
             * hinges, so no impulse at them opens it; the set arrived on
             * cannot reopen either (its projection is -|sdot|): the arch
             * stops, plastic (docs/arch-model.md, "Impacts") */
            double v1 = fmax(q->impact_vel_ratio, 0.0) * sdot;
            ke_post = 0.5 * st->m0_kgm2[other] * v1 * v1;
          } else {
            ke_post = st->cor * ke_pre; /* eq. (26): cor = KE_f / KE_i */
          }
        }
        res->energy_dissipated_j += ke_pre - ke_post;
        m = (aq_motion){0, ke_post, 1, 0, 0};
        if (q && ke_post > st->rest_tol * st->e_ref_j) {
          set = other;
        } else { /* rest, or plastic stop before an inadmissible set */
          res->energy_dissipated_j += ke_post;
          m.ke_j = 0;
          rest = 1;
          rest_since = aq_steps_t(steps, i) + t_in;
        }
      }
    }
    if (st->history) {
      const aq_path *p = set >= 0 ? st->path[set] : st->path[0];
      double tt = res->collapsed ? res->collapse_time_s : aq_steps_t(steps, i) + dt;
      rc = hist_push(&res->history, tt, rest ? 0 : p->q_sign * m.s,
                     rest ? 0 : m.x_m, rest ? 0 : m.ke_j,
                     rest ? 0 : p->mass_kg * p->g_mps2 * m.y_m,
                     rest ? -1 : set);
      if (rc != AQ_OK)
        goto nomem;
    }
    if (res->collapsed)
      break;
    i++;
  }
  if (n_end < steps->n && !res->collapsed) {
    double av = vscale * avs[n_end];
    rc = aq_error_set(err, AQ_ELIFTOFF, NULL, -1, -1, "vertical",
                      "at t = %.3f s: g + a_v = %.6g m/s^2 (a_v = %.6g m/s^2): "
                      "the arch leaves the ground, which the model does not cover",
                      aq_steps_t(steps, n_end), g_min + av, av);
    goto fail;
  }
  res->peak_rotation_rad = S.peak_s;
  res->peak_set = smax[1] > smax[0] ? 1 : smax[0] > 0 ? 0 : -1; /* peak_s = max(smax) */
  res->peak_rotation_set_rad[0] = smax[0];
  res->peak_rotation_set_rad[1] = smax[1];
  /* |x| depends on s alone: its peak is that of the path over the range of
   * s each set covered (exact, whatever the model's sampling) */
  res->peak_displacement_m = 0;
  for (int k = 0; k < 2; k++)
    if (st->path[k] && smax[k] > 0) {
      double px = peak_x(st->path[k], st->exact, smax[k], &S.evals);
      if (!(px >= 0)) {
        rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, st->path[k]->name,
                          "path evaluation failed in [0, %.9g] rad", smax[k]);
        goto fail;
      }
      res->peak_displacement_m = fmax(res->peak_displacement_m, px);
    }
  res->max_kinetic_energy_j = S.peak_ke_j;
  res->mu_demand = res->thrust_ecc_max = NAN;
  res->thrust_ecc_time_s = res->slide_time_s = NAN;
  if (dem_legs || (dem && res->first_set < 0)) {
    aq_demand_result dr;
    aq_demand_flush(dem);
    if (res->first_set < 0) /* never moved: the statics at the record's peak */
      aq_demand_still(dem, steps, n_end, scale, vscale, g_min);
    aq_demand_get(dem, &dr);
    res->mu_demand = dr.mu_max;
    res->mu_demand_joint = dr.mu_joint;
    res->thrust_ecc_max = dr.ecc_max;
    res->thrust_ecc_time_s = dr.ecc_over_s;
    res->slide_time_s = dr.slide_s;
    res->demand_samples = dr.samples;
    res->demand_full = dr.full;
    res->demand_looks = dr.looks;
  }
  res->energy_in_j = e_in;
  res->reversals = S.reversals;
  res->evals = S.evals;
  res->substeps = S.substeps;
  st->rest_since_s = rest && !res->collapsed ? rest_since : NAN;
  return AQ_OK;
nomem:
  rc = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "history", "out of memory");
fail:
  aq_result_free(res);
  return rc;
}
