/* eom.c: the Lagrangian equation of motion of one hinge set and the ode
 * model (see eom.h): GSL odeiv2 rk8pd with events located by Newton
 * iteration on single rk8pd steps taken from the last accepted step.
 *
 *     M(s) s'' + 1/2 M'(s) s'^2 + g m_T dy/ds = -a_g m_T dx/ds
 *
 * (docs/method.md sec. 4-5; derivation in eom.h and docs/dynamics.md).
 */
#include "eom.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>

static const double EOM_ABS_SCALE = 0.1;    /* rad and rad/s: atol = rtol * this */
static const double EOM_H0_S = 1e-3;        /* first trial step, s */
static const int EOM_LOCATE_ITER = 40;      /* Newton iterations on an event time */
static const size_t EOM_MAX_STEPS = 5000000; /* per leg; beyond: no progress */

int aq_eom_eval(const aq_path *p, int exact, double s, aq_path_point *pt)
{
  double sc = p->s_c_rad;
  double s0 = s < 0 ? 0 : (s > sc ? sc : s);
  int rc = exact ? p->eval_exact(p->ctx, s0, pt) : p->eval(p->ctx, s0, pt);
  if (rc)
    return rc;
  double d = s - s0;
  if (d != 0) { /* Taylor continuation beyond the ends */
    pt->x_m += d * (pt->dx_m + 0.5 * d * pt->d2x_m);
    pt->y_m += d * (pt->dy_m + 0.5 * d * pt->d2y_m);
    pt->dx_m += d * pt->d2x_m;
    pt->dy_m += d * pt->d2y_m;
    pt->mgen_kgm2 += d * pt->dmgen_kgm2;
  }
  return 0;
}

double aq_eom_accel(const aq_path *p, const aq_path_point *pt, double sdot,
                    double a_mps2)
{
  double mt = p->mass_kg;
  return (-mt * (p->g_mps2 * pt->dy_m + a_mps2 * pt->dx_m) -
          0.5 * pt->dmgen_kgm2 * sdot * sdot) /
         pt->mgen_kgm2;
}

struct aq_eom {
  gsl_odeiv2_step *step;   /* the evolving integrator */
  gsl_odeiv2_step *probe;  /* single steps for event location */
  gsl_odeiv2_control *ctl;
  gsl_odeiv2_evolve *evo;
  double rtol;
  int exact;
  double h;
};

typedef struct {
  const aq_path *p;
  double a;
  int exact;
  size_t evals;
  int failed;
} eom_par;

static int eom_rhs(double t, const double y[], double f[], void *params)
{
  (void)t;
  eom_par *q = params;
  aq_path_point pt;
  q->evals++;
  if (aq_eom_eval(q->p, q->exact, y[0], &pt) != 0 || !(pt.mgen_kgm2 > 0)) {
    q->failed = 1;
    return GSL_EBADFUNC;
  }
  f[0] = y[1];
  f[1] = aq_eom_accel(q->p, &pt, y[1], q->a);
  return GSL_SUCCESS;
}

static void eom_release(aq_eom *w)
{
  if (w->evo)
    gsl_odeiv2_evolve_free(w->evo);
  if (w->ctl)
    gsl_odeiv2_control_free(w->ctl);
  if (w->step)
    gsl_odeiv2_step_free(w->step);
  if (w->probe)
    gsl_odeiv2_step_free(w->probe);
  w->evo = NULL;
  w->ctl = NULL;
  w->step = w->probe = NULL;
}

static int eom_make(aq_eom *w)
{
  eom_release(w);
  w->step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
  w->probe = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
  w->ctl = gsl_odeiv2_control_y_new(w->rtol * EOM_ABS_SCALE, w->rtol);
  w->evo = gsl_odeiv2_evolve_alloc(2);
  return w->step && w->probe && w->ctl && w->evo;
}

aq_eom *aq_eom_alloc(aq_error *err)
{
  aq_eom *w = calloc(1, sizeof *w);
  if (w) {
    w->rtol = 1e-10;
    w->h = EOM_H0_S;
    if (eom_make(w))
      return w;
    eom_release(w);
    free(w);
  }
  aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "ode", "cannot allocate rk8pd");
  return NULL;
}

void aq_eom_free(aq_eom *w)
{
  if (!w)
    return;
  eom_release(w);
  free(w);
}

void aq_eom_set_tol(aq_eom *w, double rtol)
{
  if (!(rtol > 0) || !isfinite(rtol) || rtol == w->rtol)
    return;
  w->rtol = rtol;
  if (w->ctl)
    gsl_odeiv2_control_free(w->ctl);
  w->ctl = gsl_odeiv2_control_y_new(w->rtol * EOM_ABS_SCALE, w->rtol);
}

void aq_eom_set_exact(aq_eom *w, int exact) { w->exact = exact != 0; }

void aq_eom_reset(aq_eom *w) { w->h = EOM_H0_S; }

/* Time in (ta, tb] where component k of the solution from (ta, ya) equals v:
 * Newton on single rk8pd steps from ta, bracketed.  yv gets the state. */
static int eom_locate(aq_eom *w, gsl_odeiv2_system *sys, double ta,
                      const double ya[2], double tb, const double yb[2], int k,
                      double v, double *tv, double yv[2])
{
  double fa = ya[k] - v, fb = yb[k] - v;
  int pos_a = !(fb > 0); /* the side of ta (fa may be 0: a root at ta is not wanted) */
  double lo = ta, hi = tb;
  double t = fa != 0 && fb != fa ? ta + (tb - ta) * fa / (fa - fb)
                                 : 0.5 * (ta + tb);
  if (!(t > lo && t <= hi))
    t = 0.5 * (lo + hi);
  double y[2], yerr[2], f[2];
  for (int it = 0; it < EOM_LOCATE_ITER; it++) {
    y[0] = ya[0];
    y[1] = ya[1];
    gsl_odeiv2_step_reset(w->probe);
    if (t > ta) {
      if (gsl_odeiv2_step_apply(w->probe, ta, t - ta, y, yerr, NULL, NULL,
                                sys) != GSL_SUCCESS)
        return -1;
    }
    if (sys->function(t, y, f, sys->params) != GSL_SUCCESS)
      return -1;
    double r = y[k] - v, d = f[k];
    yv[0] = y[0];
    yv[1] = y[1];
    *tv = t;
    if (r == 0)
      break;
    if ((r > 0) == pos_a)
      lo = t;
    else
      hi = t;
    double tn = d != 0 ? t - r / d : NAN;
    if (!(tn > lo && tn < hi))
      tn = 0.5 * (lo + hi);
    if (fabs(tn - t) <= 2 * DBL_EPSILON * fmax(1.0, fabs(t)))
      break;
    t = tn;
  }
  return 0;
}

/* A turning point (sdot from > 0 to <= 0) in (ta, tb]: raise S->peak_s to
 * its s when it can exceed it (s_turn <= s(ta) + sdot(ta) (tb - ta) while
 * decelerating, a bound that spares most locations). */
static void eom_peak(aq_eom *w, gsl_odeiv2_system *sys, double ta,
                     const double ya[2], double tb, const double yb[2],
                     double sc, aq_leg_stats *S)
{
  double bound = fmax(ya[0], yb[0]) + ya[1] * (tb - ta);
  double tv, yv[2];
  if (bound <= S->peak_s)
    return;
  if (eom_locate(w, sys, ta, ya, tb, yb, 1, 0.0, &tv, yv) == 0 &&
      yv[0] > S->peak_s)
    S->peak_s = fmin(yv[0], sc);
}

static aq_status eom_fail(aq_error *err, const aq_path *p, const char *what,
                          double s)
{
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "ode: %s at s = %.9g rad", what, s);
}

aq_status aq_eom_leg(aq_eom *w, const aq_path *p, double a_mps2, aq_motion *m,
                     double dt_s, double *used_s, aq_leg_end *end,
                     aq_leg_stats *S, aq_error *err)
{
  eom_par par = {p, a_mps2, w->exact, 0, 0};
  gsl_odeiv2_system sys = {eom_rhs, NULL, 2, &par};
  const double sc = p->s_c_rad;
  aq_path_point pt;
  par.evals++;
  if (aq_eom_eval(p, w->exact, m->s, &pt) != 0)
    return eom_fail(err, p, "path evaluation failed", m->s);
  double y[2] = {m->s, m->dir * sqrt(2 * fmax(m->ke_j, 0) / pt.mgen_kgm2)};
  aq_status rc = AQ_OK;
  if (y[0] <= 0 && y[1] <= 0 && aq_eom_accel(p, &pt, 0, a_mps2) <= 0) {
    *used_s = 0;
    *end = AQ_LEG_REST;
    goto done;
  }
  if (y[0] >= sc && y[1] >= 0) {
    *used_s = 0;
    *end = AQ_LEG_COLLAPSE;
    goto done;
  }
  gsl_odeiv2_evolve_reset(w->evo);
  gsl_odeiv2_step_reset(w->step);
  double t = 0, h = w->h > 0 && w->h <= dt_s ? w->h : fmin(dt_s, EOM_H0_S);
  *end = AQ_LEG_TIME;
  for (size_t nst = 0; t < dt_s; nst++) {
    if (nst > EOM_MAX_STEPS) {
      rc = eom_fail(err, p, "no progress", y[0]);
      goto done;
    }
    double ta = t, ya[2] = {y[0], y[1]};
    int gs = gsl_odeiv2_evolve_apply(w->evo, w->ctl, w->step, &sys, &t, dt_s,
                                     &h, y);
    if (gs != GSL_SUCCESS || par.failed) {
      rc = eom_fail(err, p, gsl_strerror(gs), y[0]);
      goto done;
    }
    double tv, yv[2], tb = t, yb[2] = {y[0], y[1]};
    if (y[0] >= 0 && ya[1] < 0 && y[1] > 0) {
      /* closing, then opening: did s dip below 0 in between (a grazing
       * impact)?  Take s at the turning point. */
      if (eom_locate(w, &sys, ta, ya, t, y, 1, 0.0, &tv, yv)) {
        rc = eom_fail(err, p, "turning point location failed", y[0]);
        goto done;
      }
      if (yv[0] < 0) {
        tb = tv;
        yb[0] = yv[0];
        yb[1] = yv[1];
      }
    }
    if (y[0] > sc || (ya[1] > 0 && y[1] < 0)) {
      /* opening, then closing: did s pass s_c in between? */
      double tc = t, yc[2] = {y[0], y[1]};
      if (ya[1] > 0 && y[1] < 0) {
        if (eom_locate(w, &sys, ta, ya, t, y, 1, 0.0, &tv, yv)) {
          rc = eom_fail(err, p, "turning point location failed", y[0]);
          goto done;
        }
        if (yv[0] > sc) {
          tc = tv;
          yc[0] = yv[0];
          yc[1] = yv[1];
        }
      }
      if (yc[0] > sc) { /* collapse */
        if (eom_locate(w, &sys, ta, ya, tc, yc, 0, sc, &tv, yv)) {
          rc = eom_fail(err, p, "collapse location failed", y[0]);
          goto done;
        }
        t = tv;
        y[0] = sc;
        y[1] = yv[1];
        *end = AQ_LEG_COLLAPSE;
        break;
      }
    }
    if (yb[0] < 0) { /* impact: s = 0 closing */
      if (eom_locate(w, &sys, ta, ya, tb, yb, 0, 0.0, &tv, yv)) {
        rc = eom_fail(err, p, "impact location failed", y[0]);
        goto done;
      }
      t = tv;
      y[0] = 0;
      y[1] = yv[1] < 0 ? yv[1] : -0.0;
      if (ya[1] > 0) { /* it turned within this step */
        S->reversals++;
        eom_peak(w, &sys, ta, ya, tb, yb, sc, S);
      }
      *end = AQ_LEG_IMPACT;
      break;
    }
    if ((ya[1] > 0 && y[1] <= 0) || (ya[1] < 0 && y[1] >= 0)) {
      /* a turning point: count it and take its s for the peaks */
      if (ya[1] > 0 && y[1] <= 0)
        eom_peak(w, &sys, ta, ya, t, y, sc, S);
      if (ya[0] > 0 || y[0] > 0)
        S->reversals++;
    }
    if (y[0] > S->peak_s)
      S->peak_s = y[0];
  }
  w->h = h;
  *used_s = *end == AQ_LEG_TIME ? dt_s : t;
  par.evals++;
  if (aq_eom_eval(p, w->exact, y[0], &pt) != 0) {
    rc = eom_fail(err, p, "path evaluation failed", y[0]);
    goto done;
  }
  m->s = y[0] < 0 ? 0 : (y[0] > sc ? sc : y[0]);
  m->ke_j = 0.5 * pt.mgen_kgm2 * y[1] * y[1];
  if (y[1] != 0)
    m->dir = y[1] > 0 ? 1 : -1;
  m->x_m = pt.x_m;
  m->y_m = pt.y_m;
  if (m->s > S->peak_s)
    S->peak_s = m->s;
  if (m->ke_j > S->peak_ke_j)
    S->peak_ke_j = m->ke_j;
done:
  S->evals += par.evals;
  return rc;
}
