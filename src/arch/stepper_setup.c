/* stepper_setup.c: making a stepper and setting it up (stepper.h); its
 * runs are stepper.c's. */
#include <math.h>
#include <stdlib.h>

#include "stepper_impl.h"

const char *const aq_model_names[] = {"workpath", "ode", "paper", "workpath-quad", "blocks",
                                      NULL};

const char *aq_model_name(aq_model m)
{
  return (unsigned)m <= AQ_MODEL_BLOCKS ? aq_model_names[m] : "?";
}

static const double REST_TOL_DEFAULT = 1e-12; /* KE / E_ref at which impacts end */


/* ------------------------------------------------------------------ */
/* The stepper                                                         */

static int path_usable(const aq_path *p)
{
  return p && p->admissible && p->eval && p->eval_exact &&
         isfinite(p->mass_kg) && p->mass_kg > 0 && isfinite(p->g_mps2) &&
         p->g_mps2 > 0 && isfinite(p->lambda0) && p->lambda0 >= 0 &&
         isfinite(p->s_c_rad) && p->s_c_rad > 0 &&
         (p->act_sign == 1 || p->act_sign == -1) &&
         (p->q_sign == 1 || p->q_sign == -1);
}

aq_stepper *aq_stepper_alloc(const aq_path *primary, const aq_path *reverse,
                             aq_model model, aq_error *err)
{
  if (!path_usable(primary)) {
    aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "primary",
                 "expected an admissible primary hinge set with finite "
                 "mass, g > 0, lambda0 >= 0, s_c > 0 and signs +-1");
    return NULL;
  }
  if (model != AQ_MODEL_WORKPATH && model != AQ_MODEL_ODE &&
      model != AQ_MODEL_PAPER && model != AQ_MODEL_WORKPATH_QUAD) {
    aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "model",
                 "expected workpath, ode, paper or workpath-quad, got %d", (int)model);
    return NULL;
  }
  /* the ode and workpath-quad read the Hermite tables (unless set to the
   * exact path): a path they resolve only coarsely (a toggle end) would
   * give them a wrong time to collapse, silently */
  for (int k = 0; k < 2 && (model == AQ_MODEL_ODE || model == AQ_MODEL_WORKPATH_QUAD); k++) {
    const aq_path *p = k ? reverse : primary;
    if (k && !path_usable(p))
      break;
    if (!(p->table_err <= AQ_PATH_TABLE_ERR_MAX)) {
      aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                   "expected a work path that the Hermite tables of --model %s resolve to "
                   "%g, got one they resolve only to %.3g (q_c = %.6g rad); --model "
                   "workpath, the default, follows it",
                   model == AQ_MODEL_ODE ? "ode" : "workpath-quad", AQ_PATH_TABLE_ERR_MAX,
                   p->table_err, p->s_c_rad);
      return NULL;
    }
  }
  aq_stepper *st = calloc(1, sizeof *st);
  if (!st) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "stepper", "out of memory");
    return NULL;
  }
  st->path[0] = primary;
  st->path[1] = path_usable(reverse) ? reverse : NULL;
  st->pv[0] = *primary;
  if (st->path[1])
    st->pv[1] = *reverse;
  st->model = model;
  st->ode_rtol = 1e-10;
  st->scale = 1;
  st->rest_tol = REST_TOL_DEFAULT;
  st->rest_since_s = NAN;
  aq_path_point pt;
  if (primary->eval_exact(primary->ctx, primary->s_c_rad, &pt) != 0) {
    aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "primary",
                 "path evaluation failed at s_c = %.9g rad", primary->s_c_rad);
    free(st);
    return NULL;
  }
  st->e_ref_j = primary->mass_kg * primary->g_mps2 * fabs(pt.y_m);
  if (!(st->e_ref_j > 0))
    st->e_ref_j = primary->mass_kg * primary->g_mps2 * primary->s_c_rad;
  if (model == AQ_MODEL_WORKPATH || model == AQ_MODEL_WORKPATH_QUAD) {
    st->quad = aq_quad_alloc(err);
    st->taylor = st->quad && model == AQ_MODEL_WORKPATH ? aq_taylor_alloc(err) : NULL;
    if (!st->quad || (model == AQ_MODEL_WORKPATH && !st->taylor)) {
      aq_stepper_free(st);
      return NULL;
    }
  } else if (model == AQ_MODEL_ODE) {
    st->eom = aq_eom_alloc(err);
    if (!st->eom) {
      free(st);
      return NULL;
    }
    aq_eom_set_tol(st->eom, st->ode_rtol);
  } else if (model == AQ_MODEL_PAPER) {
    st->paper = aq_paper_alloc(primary, st->path[1], err);
    if (!st->paper) {
      free(st);
      return NULL;
    }
  }
  return st;
}

aq_stepper *aq_stepper_alloc_delegate(aq_model model, const aq_stepper_delegate *d,
                                      aq_error *err)
{
  aq_stepper *st = calloc(1, sizeof *st);
  if (!st) {
    if (d->free)
      d->free(d->ctx);
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "stepper", "out of memory");
    return NULL;
  }
  st->model = model;
  st->scale = 1;
  st->rest_since_s = NAN;
  st->delegated = 1;
  st->del = *d;
  return st;
}

void aq_stepper_free(aq_stepper *st)
{
  if (!st)
    return;
  if (st->delegated && st->del.free)
    st->del.free(st->del.ctx);
  aq_eom_free(st->eom);
  aq_paper_free(st->paper);
  aq_taylor_free(st->taylor);
  aq_quad_free(st->quad);
  aq_demand_free(st->demand);
  free(st);
}

void aq_stepper_set_cor(aq_stepper *st, double cor)
{
  if (isfinite(cor))
    st->cor = cor < 0 ? 0 : (cor > 1 ? 1 : cor);
}
void aq_stepper_set_impact(aq_stepper *st, int momentum) { st->momentum = momentum != 0; }
void aq_stepper_set_ode_rtol(aq_stepper *st, double rtol)
{
  if (isfinite(rtol) && rtol > 0) {
    st->ode_rtol = rtol;
    if (st->eom)
      aq_eom_set_tol(st->eom, rtol);
  }
}
void aq_stepper_set_history(aq_stepper *st, int on) { st->history = on != 0; }
void aq_stepper_set_exact_path(aq_stepper *st, int on)
{
  st->exact = on != 0;
  if (st->eom)
    aq_eom_set_exact(st->eom, st->exact);
  if (st->quad)
    aq_quad_set_exact(st->quad, st->exact);
}
void aq_stepper_set_wp_tol(aq_stepper *st, double tol)
{
  if (st->quad)
    aq_quad_set_tol(st->quad, tol);
}
void aq_stepper_set_wp_nodes(aq_stepper *st, int n)
{
  if (st->quad)
    aq_quad_set_nodes(st->quad, n);
}
void aq_stepper_set_taylor_tol(aq_stepper *st, double tol)
{
  if (st->taylor)
    aq_taylor_set_tol(st->taylor, tol);
}
void aq_stepper_set_scale(aq_stepper *st, double scale)
{
  if (isfinite(scale))
    st->scale = scale;
}
void aq_stepper_set_rest_tol(aq_stepper *st, double tol)
{
  if (isfinite(tol) && tol >= 0)
    st->rest_tol = tol;
}

double aq_stepper_rest_since(const aq_stepper *st)
{
  return st->delegated ? st->del.rest_since(st->del.ctx) : st->rest_since_s;
}

void aq_stepper_set_demand(aq_stepper *st, aq_demand *d)
{
  aq_demand_free(st->demand);
  st->demand = d;
}


