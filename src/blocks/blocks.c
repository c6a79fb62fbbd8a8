/* blocks.c: the block model's run (blocks.h): the bodies of an arch, the
 * spread of the supports, the record's steps cut into time steps of the
 * model (moreau.c), steps at rest skipped while the static range holds
 * (statics.c), and what a run reports (events.c). */
#include "blocks.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "blocks_run.h"

/* The collapse rule's floor, per the arch's lower energy barrier
 * (events.c; docs/blocks.md). */
static const double COLLAPSE_FLOOR = 0.1;

void aq_blocks_result_free(aq_blocks_result *r)
{
  if (!r)
    return;
  aq_result_free(&r->r);
  free(r->hinges);
  free(r->hist_x_m);
  free(r->hist_y_m);
  free(r->hist_rot_rad);
  memset(r, 0, sizeof *r);
}

void aq_blocks_free(aq_blocks *b)
{
  if (!b)
    return;
  aq_moreau_free(b->m);
  aq_bodies_free(&b->bodies);
  aq_events_free(&b->ev);
  free(b->qstat);
  free(b->closed);
  free(b);
}

/* A new model over b->bodies (built), options at their defaults. */
static aq_status init_model(aq_blocks *b, aq_error *err)
{
  aq_moreau_free(b->m);
  free(b->qstat);
  free(b->closed);
  aq_events_free(&b->ev);
  b->qstat = malloc(3 * b->bodies.nb * sizeof *b->qstat);
  b->closed = malloc(2 * b->bodies.nj);
  b->m = aq_moreau_alloc(&b->bodies, err);
  if (!b->m || !b->qstat || !b->closed || aq_events_init(&b->ev, &b->bodies, err) != AQ_OK) {
    if (b->m && b->qstat && b->closed)
      return err ? err->status : AQ_ENOMEM;
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
  }
  return AQ_OK;
}

static aq_blocks *alloc_common(aq_error *err)
{
  if (aq_siconos_load(err) != AQ_OK)
    return NULL;
  aq_blocks *b = calloc(1, sizeof *b);
  if (!b) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
    return NULL;
  }
  b->mu = NAN;
  b->abutment_m = NAN;
  b->e_n = 0;
  b->dt_s = AQ_BLOCKS_DT_DEFAULT_S;
  b->scale = 1;
  b->rest_skip = b->direct = b->projection = 1;
  b->rest_since = NAN;
  return b;
}

/* The spread's limit: the chain of voussoirs reaches at most the sum of
 * their longest spans from a point of one joint to a point of the next
 * (the diagonals); supports spread farther than that less their nearest
 * distance are out of its reach. */
double aq_blocks_spread_reach(const aq_arch *arch)
{
  const aq_geom *g = aq_arch_geom(arch);
  size_t n = g->p.voussoirs;
  double reach = 0;
  for (size_t k = 0; k < n; k++) {
    aq_vec2 a[2] = {g->ji[k], g->je[k]}, c[2] = {g->ji[k + 1], g->je[k + 1]};
    double d = 0;
    for (int x = 0; x < 2; x++)
      for (int y = 0; y < 2; y++)
        d = fmax(d, hypot(a[x].x - c[y].x, a[x].y - c[y].y));
    reach += d;
  }
  double near = INFINITY;
  aq_vec2 a[2] = {g->ji[0], g->je[0]}, c[2] = {g->ji[n], g->je[n]};
  for (int x = 0; x < 2; x++)
    for (int y = 0; y < 2; y++)
      near = fmin(near, hypot(a[x].x - c[y].x, a[x].y - c[y].y));
  return reach - near;
}

/* spread_m against the limit spread_max (0 for bodies without an arch). */
static aq_status spread_within(double spread_m, double spread_max, aq_error *err)
{
  if (!(spread_m >= 0) || !(spread_m < spread_max || spread_m == 0))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "spread_m",
                        "expected 0 <= spread < %.6g m (beyond it the voussoirs cannot "
                        "reach across the supports), got %g",
                        spread_max, spread_m);
  return AQ_OK;
}

aq_status aq_blocks_check_spread(const aq_arch *arch, double spread_m, aq_error *err)
{
  return spread_within(spread_m, aq_blocks_spread_reach(arch), err);
}

aq_blocks *aq_blocks_alloc(const aq_arch *arch, aq_error *err)
{
  aq_blocks *b = alloc_common(err);
  if (!b)
    return NULL;
  b->arch = arch;
  for (int k = 0; k < 2; k++) {
    b->set[k] = *aq_arch_hinge_set(arch, k);
    b->have_set[k] = 1;
  }
  const aq_geom *g = aq_arch_geom(arch);
  if (aq_bodies_from_arch(&b->bodies, g, NULL, 0, aq_arch_dynamics_of(arch)->g_mps2, err) !=
          AQ_OK ||
      init_model(b, err) != AQ_OK) {
    aq_blocks_free(b);
    return NULL;
  }
  /* the collapse rule's floor: a fraction of the lower of the two sets'
   * energy barriers m_T g y(s_c) */
  double barrier = INFINITY;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(arch, k);
    aq_path_point pt;
    if (p && p->admissible && p->eval(p->ctx, p->s_c_rad, &pt) == 0 && pt.y_m > 0)
      barrier = fmin(barrier, p->mass_kg * p->g_mps2 * pt.y_m);
  }
  b->dv_floor_j = isfinite(barrier) ? COLLAPSE_FLOOR * barrier : 0;
  b->spread_max = aq_blocks_spread_reach(arch);
  return b;
}

aq_blocks *aq_blocks_for_arch(const aq_arch *arch, double dt_s, aq_error *err)
{
  double mu = aq_arch_friction(arch);
  if (isnan(mu)) {
    aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "friction",
                 "expected a Coulomb coefficient for --model blocks ([contact] friction or "
                 "--friction), got none");
    return NULL;
  }
  aq_blocks *b = aq_blocks_alloc(arch, err);
  if (!b)
    return NULL;
  if (aq_blocks_set_friction(b, mu, err) != AQ_OK ||
      aq_blocks_set_restitution(b, aq_arch_restitution(arch), err) != AQ_OK ||
      aq_blocks_set_dt(b, dt_s, err) != AQ_OK ||
      (aq_arch_control(arch) == AQ_CONTROL_FIXED &&
       aq_blocks_set_control(b, AQ_BLOCKS_FIXED, err) != AQ_OK) ||
      aq_blocks_set_spread(b, aq_arch_spread(arch), err) != AQ_OK ||
      aq_blocks_set_abutment(b, aq_arch_abutment(arch), err) != AQ_OK) {
    aq_blocks_free(b);
    return NULL;
  }
  return b;
}

aq_blocks *aq_blocks_alloc_bodies(const aq_body *body, size_t nb, const aq_vec2 (*ends)[2],
                                  size_t nj, double g_mps2, aq_error *err)
{
  aq_blocks *b = alloc_common(err);
  if (!b)
    return NULL;
  if (aq_bodies_init(&b->bodies, body, nb, ends, nj, g_mps2, err) != AQ_OK ||
      init_model(b, err) != AQ_OK) {
    aq_blocks_free(b);
    return NULL;
  }
  return b;
}

aq_moreau *aq_blocks_moreau(aq_blocks *b) { return b->m; }
void aq_blocks_set_impact_law(aq_blocks *b, aq_impact_law law) { b->law = law; }
const aq_bodies *aq_blocks_bodies(const aq_blocks *b) { return &b->bodies; }

aq_status aq_blocks_set_friction(aq_blocks *b, double mu, aq_error *err)
{
  if (!(mu > 0) || !isfinite(mu))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "friction",
                        "expected a finite coefficient > 0, got %g", mu);
  b->mu = mu;
  return AQ_OK;
}

aq_status aq_blocks_set_restitution(aq_blocks *b, double e_n, aq_error *err)
{
  if (!(e_n >= 0 && e_n <= 1))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "e_n", "expected 0..1, got %g", e_n);
  b->e_n = e_n;
  return AQ_OK;
}

aq_status aq_blocks_set_dt(aq_blocks *b, double dt_s, aq_error *err)
{
  if (!(dt_s > 0) || !isfinite(dt_s))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "blocks-dt",
                        "expected a finite step > 0 s, got %g", dt_s);
  b->dt_s = dt_s;
  return AQ_OK;
}

double aq_blocks_spread_max(const aq_blocks *b) { return b->spread_max; }

aq_status aq_blocks_set_spread(aq_blocks *b, double spread_m, aq_error *err)
{
  aq_status rc = spread_within(spread_m, b->spread_max, err);
  if (rc != AQ_OK)
    return rc;
  b->spread_m = spread_m;
  return AQ_OK;
}

/* The supports' faces run abutment_m beyond the springing joints (an
 * arch's joints 0 and n, where a support bears on a voussoir; under fixed
 * control a support that carries bonded voussoirs bears with a voussoir's
 * joint, which keeps its own length), or beyond every joint of the ground
 * (test bodies).  NAN: as aq_bodies made them. */
static void apply_abutment(aq_blocks *b)
{
  aq_bodies *s = &b->bodies;
  if (isnan(b->abutment_m))
    return;
  size_t n = s->nvous;
  for (size_t k = 0; k < s->nj; k++) {
    aq_bjoint *J = &s->joint[k];
    if (J->a < 0 && (!b->arch || J->arch_joint == 0))
      J->ext_m[0] = b->abutment_m;
    if (J->b < 0 && (!b->arch || J->arch_joint == n))
      J->ext_m[1] = b->abutment_m;
  }
}

aq_status aq_blocks_set_control(aq_blocks *b, aq_blocks_control c, aq_error *err)
{
  if (!b->arch)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "control",
                        "expected an arch for hinge control");
  size_t free_j[8], nf = 0;
  if (c == AQ_BLOCKS_FIXED) {
    /* the joints of both sets (the reverse set is, by default, the
     * primary's joints with the faces swapped) */
    for (int k = 0; k < 2; k++)
      for (int i = 0; i < 4; i++) {
        size_t j = b->set[k].joint[i], p = 0;
        while (p < nf && free_j[p] < j)
          p++;
        if (p < nf && free_j[p] == j)
          continue;
        memmove(free_j + p + 1, free_j + p, (nf - p) * sizeof *free_j);
        free_j[p] = j;
        nf++;
      }
  }
  aq_bodies nb;
  if (aq_bodies_from_arch(&nb, aq_arch_geom(b->arch), c == AQ_BLOCKS_FIXED ? free_j : NULL,
                          nf, aq_arch_dynamics_of(b->arch)->g_mps2, err) != AQ_OK)
    return err ? err->status : AQ_EVALUE;
  aq_moreau_free(b->m);
  b->m = NULL;
  aq_bodies_free(&b->bodies);
  b->bodies = nb;
  b->control = c;
  apply_abutment(b);
  return init_model(b, err);
}

aq_status aq_blocks_set_abutment(aq_blocks *b, double abutment_m, aq_error *err)
{
  if (!(abutment_m >= 0) || !isfinite(abutment_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "abutment_m",
                        "expected a finite length >= 0 m, got %g", abutment_m);
  b->abutment_m = abutment_m;
  apply_abutment(b);
  return AQ_OK;
}

void aq_blocks_set_history(aq_blocks *b, int on) { b->history = on != 0; }
void aq_blocks_set_scale(aq_blocks *b, double scale) { b->scale = scale; }
void aq_blocks_set_rest_skip(aq_blocks *b, int on) { b->rest_skip = on != 0; }
void aq_blocks_set_direct(aq_blocks *b, int on) { b->direct = on != 0; }
void aq_blocks_set_projection(aq_blocks *b, int on) { b->projection = on != 0; }
double aq_blocks_rest_since(const aq_blocks *b) { return b->rest_since; }

/* The static range of the present configuration (cached by
 * configuration): 1 and the range, 0 none, -1 failed (err). */
static int static_range(aq_blocks *b, double *lo, double *hi, aq_error *err)
{
  const double *q = aq_moreau_q(b->m);
  size_t n3 = 3 * b->bodies.nb;
  double tol = 1e-12 * b->bodies.length_m;
  if (b->stat_valid) {
    int same = 1;
    for (size_t i = 0; i < n3 && same; i++)
      same = fabs(q[i] - b->qstat[i]) <= (i % 3 == 2 ? tol / b->bodies.length_m : tol);
    if (same) {
      *lo = b->stat_lo;
      *hi = b->stat_hi;
      return b->stat_ok;
    }
  }
  aq_moreau_closed(b->m, b->closed);
  int ok = aq_statics_range(&b->bodies, aq_moreau_corners(b->m), b->closed, b->mu,
                            &b->stat_lo, &b->stat_hi, err);
  if (ok < 0)
    return -1;
  b->counters.statics++;
  memcpy(b->qstat, q, n3 * sizeof *q);
  b->stat_valid = 1;
  b->stat_ok = ok;
  *lo = b->stat_lo;
  *hi = b->stat_hi;
  return ok;
}

/* 1 if the load (ax, ay) keeps the bodies at rest where they are. */
static int holds(aq_blocks *b, double ax, double ay, int *fail, aq_error *err)
{
  double geff = b->bodies.g_mps2 + ay, lo, hi;
  if (!(geff > 0))
    return 0;
  int ok = static_range(b, &lo, &hi, err);
  if (ok < 0) {
    *fail = 1;
    return 0;
  }
  double r = -ax / geff;
  return ok && r > lo && r < hi;
}

/* 1 if every joint is closed at both corners and sticks. */
static int all_closed(const aq_blocks *b)
{
  const aq_jstate *st = aq_moreau_jstate(b->m);
  for (size_t j = 0; j < b->bodies.nj; j++)
    if (st[j].kind != AQ_JOINT_WELD || st[j].slide != 0)
      return 0;
  return 1;
}

/* At the top of the hill the arch climbs (events.c): it has collapsed if,
 * the ground now still, gravity carries it on until it falls (a body
 * turned by 45 degrees, a joint parted) rather than back (it turns towards
 * where it stood).  Run ahead from the present state, at most
 * LOOK_AHEAD_S, and come back.  *fell: 1 if it fell. */
static const double LOOK_AHEAD_S = 10.0;

static aq_status look_ahead(aq_blocks *b, double h, int *fell, aq_error *err)
{
  aq_moreau_save(b->m);
  double gx[2];
  memcpy(gx, aq_moreau_gx(b->m), sizeof gx);
  size_t n = (size_t)ceil(LOOK_AHEAD_S / h);
  aq_status rc = AQ_OK;
  *fell = 0;
  for (size_t i = 0; i < n; i++) {
    aq_step_info info;
    rc = aq_moreau_step(b->m, h, 0, 0, gx, &info, err);
    if (rc != AQ_OK)
      break;
    b->counters.ahead++;
    if (aq_events_fallen(&b->ev, b->m)) {
      *fell = 1;
      break;
    }
    if (!aq_events_away(&b->ev, b->m))
      break;
  }
  aq_moreau_restore(b->m);
  return rc;
}

/* The run's time steps over [t, t + dt) under (ax, ay); returns AQ_OK, or
 * the failure.  *stop: collapsed. */
static aq_status advance(aq_blocks *b, double t, double dt, double ax, double ay,
                         const double gx0[2], const double gx1[2], int record, int *stop,
                         aq_error *err)
{
  size_t m = (size_t)ceil(dt / b->dt_s - 1e-9);
  if (m < 1)
    m = 1;
  double h = dt / (double)m;
  for (size_t i = 0; i < m; i++) {
    double f = (double)(i + 1) / (double)m, gx[2] = {gx0[0] + f * (gx1[0] - gx0[0]),
                                                     gx0[1] + f * (gx1[1] - gx0[1])};
    int moving_ground = gx1[0] != gx0[0] || gx1[1] != gx0[1];
    if (b->at_rest && !moving_ground) {
      int fail = 0;
      if (b->rest_skip && holds(b, ax, ay, &fail, err))
        return AQ_OK; /* the rest of the step too: its load is constant */
      if (fail)
        return err->status;
      b->at_rest = 0;
    }
    aq_step_info info;
    double tend = t + dt * f;
    aq_status rc = aq_moreau_step(b->m, h, ax, ay, gx, &info, err);
    if (rc != AQ_OK) {
      size_t n = strlen(err->message);
      snprintf(err->message + n, sizeof err->message - n, " at t = %.3f s",
               tend - dt * (1.0 / (double)m));
      return rc;
    }
    b->counters.steps++;
    if (info.path == AQ_STEP_DIRECT)
      b->counters.direct++;
    else
      b->counters.siconos++;
    b->counters.iters += (size_t)info.iters;
    b->counters.pivots += (size_t)info.pivots;
    b->counters.loose += (size_t)info.loose;
    int ev = aq_events_step(&b->ev, b->m, tend, h, ax, ay, &info, record);
    if (ev == 2) {
      int fell = 0;
      rc = look_ahead(b, h, &fell, err);
      if (rc != AQ_OK)
        return rc;
      if (fell)
        aq_events_collapse(&b->ev, tend);
      ev = fell;
    }
    if (ev == 1) {
      *stop = 1;
      return AQ_OK;
    }
    /* at rest: every velocity zero to rounding, or every joint closed and
     * sticking (no freedom left: v = 0 to the solver's tolerance), and
     * the load held */
    if (!moving_ground && b->rest_skip &&
        (aq_events_still(&b->ev, b->m, h) || all_closed(b))) {
      int fail = 0;
      if (holds(b, ax, ay, &fail, err)) {
        memset(aq_moreau_v(b->m), 0, 3 * b->bodies.nb * sizeof(double));
        b->at_rest = 1;
        if (isnan(b->rest_since))
          b->rest_since = tend;
        return AQ_OK;
      }
      if (fail)
        return err->status;
    }
    if (record)
      b->rest_since = NAN;
  }
  return AQ_OK;
}

/* The supports move apart by spread_m: each by half of it along x, on
 * (1 - cos(pi t / T)) / 2, with T such that the supports' acceleration
 * stays within SPREAD_ACCEL_G g (quasi-static: far below any arch's
 * lambda0), then held while the arch settles.  *stop: collapsed. */
static const double SPREAD_ACCEL_G = 1e-3;
static const double SPREAD_SETTLE_S = 1.0;

static aq_status spread(aq_blocks *b, int *stop, aq_error *err)
{
  double d = b->spread_m / 2, g = b->bodies.g_mps2;
  double T = fmax(0.5, AQ_PI * sqrt(d / (2 * SPREAD_ACCEL_G * g)));
  size_t n = (size_t)ceil(T / b->dt_s);
  double h = T / (double)n;
  for (size_t i = 0; i < n && !*stop; i++) {
    double f0 = 0.5 * (1 - cos(AQ_PI * (double)i / (double)n));
    double f1 = 0.5 * (1 - cos(AQ_PI * (double)(i + 1) / (double)n));
    double gx0[2] = {d * f0, -d * f0}, gx1[2] = {d * f1, -d * f1};
    aq_status rc = advance(b, (double)i * h - T - SPREAD_SETTLE_S, h, 0, 0, gx0, gx1, 0, stop,
                           err);
    if (rc != AQ_OK)
      return rc;
  }
  double gx[2] = {d, -d};
  size_t ns = (size_t)ceil(SPREAD_SETTLE_S / b->dt_s);
  for (size_t i = 0; i < ns && !*stop && !b->at_rest; i++) {
    aq_status rc = advance(b, -SPREAD_SETTLE_S + (double)i * b->dt_s, b->dt_s, 0, 0, gx, gx,
                           0, stop, err);
    if (rc != AQ_OK)
      return rc;
  }
  return AQ_OK;
}

aq_status aq_blocks_run(aq_blocks *b, const aq_steps *steps, aq_blocks_result *res,
                        aq_error *err)
{
  memset(res, 0, sizeof *res);
  res->mechanism_changed_s = NAN;
  res->r.collapse_time_s = NAN;
  res->r.first_set = res->r.peak_set = -1;
  b->rest_since = NAN;
  if (isnan(b->mu))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "friction",
                        "the blocks model needs a friction coefficient ([contact] friction "
                        "or --friction)");
  if (steps->n == 0)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "steps", "expected steps, got none");
  aq_moreau_set_law(b->m, b->law);
  aq_moreau_set(b->m, b->mu, b->e_n, 0.5, b->direct, b->projection);
  aq_moreau_reset(b->m);
  memset(&b->counters, 0, sizeof b->counters);
  b->at_rest = 0;
  b->stat_valid = 0;
  aq_events_reset(&b->ev, b->m, b->have_set[0] ? b->set : NULL, b->history, b->dv_floor_j,
                  res);
  int stop = 0;
  aq_status rc = AQ_OK;
  double t0 = aq_steps_t(steps, 0);
  if (b->spread_m > 0) {
    rc = spread(b, &stop, err);
    if (rc != AQ_OK)
      goto fail;
    if (stop) {
      res->spread_collapsed = 1;
      res->r.collapsed = 1;
      res->r.collapse_time_s = t0;
      goto done;
    }
  }
  aq_events_start(&b->ev, b->m, t0);
  b->rest_since = NAN;
  const double *gx = aq_moreau_gx(b->m);
  double gxs[2] = {gx[0], gx[1]};
  double vs = fabs(b->scale);
  /* at rest from the start if the first load holds */
  b->at_rest = 1;
  for (size_t i = 0; i < steps->n && !stop; i++) {
    double t = aq_steps_t(steps, i), dt = aq_steps_dt(steps, i);
    double ax = b->scale * steps->a_mps2[i];
    double ay = steps->av_mps2 ? vs * steps->av_mps2[i] : 0;
    int was_rest = b->at_rest;
    rc = advance(b, t, dt, ax, ay, gxs, gxs, 1, &stop, err);
    if (rc != AQ_OK)
      goto fail;
    if (!(was_rest && b->at_rest))
      res->r.steps_moving++;
    else if (isnan(b->rest_since))
      b->rest_since = t;
    if (aq_events_sample(&b->ev, b->m, t + dt, res) != AQ_OK) {
      rc = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "history", "out of memory");
      goto fail;
    }
  }
done:
  aq_events_finish(&b->ev, b->m, res);
  res->r.steps_total = steps->n;
  res->steps = b->counters.steps;
  res->steps_direct = b->counters.direct;
  res->steps_siconos = b->counters.siconos;
  res->active_set_iters = b->counters.iters;
  res->siconos_pivots = b->counters.pivots;
  res->statics = b->counters.statics;
  res->steps_loose = b->counters.loose;
  res->r.substeps = b->counters.steps;
  res->r.evals = b->counters.iters;
  if (res->r.collapsed || !b->at_rest)
    b->rest_since = NAN;
  return AQ_OK;
fail:
  b->rest_since = NAN;
  aq_blocks_result_free(res);
  return rc;
}

void aq_blocks_hinges_text(const aq_blocks_result *r, char *buf, size_t n, char *tbuf,
                           size_t tn)
{
  size_t k = 0, kt = 0;
  if (n)
    buf[0] = 0;
  if (tbuf && tn)
    tbuf[0] = 0;
  for (size_t i = 0; i < r->nhinges; i++) {
    int w = snprintf(buf + k, k < n ? n - k : 0, "%s%zu%c", i ? "," : "", r->hinges[i].joint,
                     r->hinges[i].face);
    k += w > 0 ? (size_t)w : 0;
    if (tbuf) {
      w = snprintf(tbuf + kt, kt < tn ? tn - kt : 0, "%s%.6g", i ? "," : "",
                   r->hinges[i].time_s);
      kt += w > 0 ? (size_t)w : 0;
    }
  }
}
