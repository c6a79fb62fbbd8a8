/* capacity.c: the collapse capacity of one (processed record, arch,
 * polarity): the exact scale below which the arch never moves, then the
 * scan of scan.c with one dynamic run per verdict (a collapsing run stops
 * at its collapse: the stepper ends there); and a pool of threads over many
 * such jobs.  Each job makes its own stepper, so a result depends on its
 * job alone, not on the thread that ran it. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "../signal/steps.h"
#include "../units.h"
#include "capacity.h"

void aq_capacity_free(aq_capacity *c)
{
  if (!c)
    return;
  aq_scan_result_free(&c->scan);
  free(c->point);
  c->point = NULL;
  c->npoint = 0;
}

double aq_capacity_move_scale(const aq_arch *arch, const double *acc_mps2,
                              size_t n, double *lambda0)
{
  return aq_capacity_move_scale_v(arch, acc_mps2, NULL, n, lambda0);
}

double aq_capacity_move_scale_v(const aq_arch *arch, const double *acc_mps2,
                                const double *av_mps2, size_t n, double *lambda0)
{
  double best = INFINITY, l0 = INFINITY;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(arch, k);
    if (!p || !p->admissible)
      continue;
    l0 = fmin(l0, p->lambda0);
    double drive = 0; /* max of act_sign a over the samples, m/s^2 */
    for (size_t i = 0; i < n; i++) /* s act_sign a > lambda0 (g + s a_v) */
      drive = fmax(drive, p->act_sign * acc_mps2[i] -
                              (av_mps2 ? p->lambda0 * av_mps2[i] : 0.0));
    if (drive > 0) /* motion needs act_sign a > lambda0 (g + a_v) (stepper.c) */
      best = fmin(best, p->lambda0 * p->g_mps2 / drive);
  }
  if (lambda0)
    *lambda0 = l0;
  return best;
}

typedef struct {
  const aq_capacity_job *job;
  aq_stepper *st;
  double *buf;      /* proc->n scaled samples */
  aq_capacity *out; /* gets a point per run */
  size_t cap;       /* points allocated */
} run_ctx;

/* Record the run at scale in c->out's points. */
static aq_status add_point(run_ctx *c, double scale, const aq_result *res, aq_error *err)
{
  aq_capacity *o = c->out;
  if (o->npoint == c->cap) {
    size_t nc = c->cap ? 2 * c->cap : 64;
    aq_capacity_point *p = realloc(o->point, nc * sizeof *p);
    if (!p)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
    o->point = p;
    c->cap = nc;
  }
  /* peak over the collapse rotation of the set it peaked in, as the main
     job's summary (peak_rotation_over_qc) */
  const aq_path *ps = res->peak_set >= 0 ? aq_arch_path(c->job->arch, res->peak_set) : NULL;
  double over = ps && ps->admissible ? res->peak_rotation_rad / ps->s_c_rad
                : res->peak_rotation_rad == 0 ? 0
                                              : NAN;
  o->point[o->npoint++] = (aq_capacity_point){
      scale, res->peak_rotation_rad, over,
      res->collapsed ? res->collapse_time_s : NAN, res->collapsed ? 1 : 0};
  return AQ_OK;
}

static int by_scale(const void *a, const void *b)
{
  double x = ((const aq_capacity_point *)a)->scale, y = ((const aq_capacity_point *)b)->scale;
  return (x > y) - (x < y);
}

/* One run at scale: steps as the main job makes them (the processed record
 * times the scale, split with --merge-tol), then the stepper. */
static aq_status run_at(void *vctx, double scale, int *collapsed, aq_error *err)
{
  run_ctx *c = vctx;
  const aq_processed *p = c->job->proc;
  aq_steps steps;
  aq_status s;
  if (c->job->av_mps2) { /* the vertical scales with the motion */
    double peak;
    s = aq_steps_project_v(c->job->acc_mps2, 1.0, NULL, 0.0, scale, c->job->av_mps2,
                           scale, p->n, p->dt_s, -(double)p->pad_front * p->dt_s,
                           c->job->merge_tol_mps2, &steps, &peak, err);
  } else {
    for (size_t i = 0; i < p->n; i++)
      c->buf[i] = scale * c->job->acc_mps2[i];
    s = aq_steps_from_samples(c->buf, p->n, p->dt_s, -(double)p->pad_front * p->dt_s,
                              c->job->merge_tol_mps2, &steps, err);
  }
  if (s != AQ_OK)
    return s;
  aq_result res;
  s = aq_stepper_run(c->st, &steps, &res, err);
  aq_steps_free(&steps);
  if (s != AQ_OK) {
    size_t len = strlen(err->message);
    snprintf(err->message + len, sizeof err->message - len, " (scale %.9g)", scale);
    return s;
  }
  *collapsed = res.collapsed;
  s = add_point(c, scale, &res, err);
  aq_result_free(&res);
  return s;
}

aq_status aq_capacity_pair(const aq_capacity_job *job, aq_capacity *out,
                           aq_error *err)
{
  memset(out, 0, sizeof *out);
  out->first_collapse_scale = NAN;
  const aq_processed *p = job->proc;
  out->move_scale = aq_capacity_move_scale_v(job->arch, job->acc_mps2, job->av_mps2,
                                             p->n, &out->lambda0);
  double amax = 0; /* PGA, m/s^2 */
  for (size_t i = 0; i < p->n; i++)
    amax = fmax(amax, fabs(job->acc_mps2[i]));
  out->scale_max = !isnan(job->scale_max)
                       ? job->scale_max
                       : amax > 0 ? AQ_CAPACITY_CAP_LAMBDA0 * out->lambda0 *
                                        AQ_G0_MPS2 / amax
                                  : INFINITY;
  if (!(out->move_scale < out->scale_max)) {
    out->status = AQ_CAPACITY_NEVER_MOVES;
    return AQ_OK;
  }
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(job->arch, 0),
                                    aq_arch_path(job->arch, 1), job->model, err);
  if (!st)
    return err->status;
  const aq_arch_dynamics *d = aq_arch_dynamics_of(job->arch);
  aq_stepper_set_cor(st, isnan(job->cor) ? d->cor : job->cor);
  aq_stepper_set_impact(st, d->impact == AQ_IMPACT_MOMENTUM);
  run_ctx c = {job, st, malloc((p->n ? p->n : 1) * sizeof(double)), out, 0};
  if (!c.buf) {
    aq_stepper_free(st);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
  }
  aq_status s = aq_scan_run(out->move_scale, out->scale_max, &job->scan, run_at,
                            &c, &out->scan, &out->err);
  free(c.buf);
  aq_stepper_free(st);
  if (out->npoint) /* grid and bisection runs interleave */
    qsort(out->point, out->npoint, sizeof *out->point, by_scale);
  if (s == AQ_ENOMEM)
    return aq_error_set(err, s, NULL, -1, -1, "capacity", "out of memory");
  if (s != AQ_OK) {
    out->status = AQ_CAPACITY_FAILED;
    out->run_status = s;
    return AQ_OK;
  }
  const aq_scan_result *r = &out->scan;
  if (r->ninterval) {
    out->first_collapse_scale = r->interval[0].lo;
    out->resurrection = r->ninterval > 1 || isfinite(r->interval[0].hi);
  }
  return AQ_OK;
}

size_t aq_capacity_worst(const aq_capacity *c, size_t n, double *fcs_min,
                         double *fcs_max)
{
  size_t w = 0;
  double lo = NAN, hi = NAN;
  for (size_t z = 0; z < n; z++) {
    double f = c[z].first_collapse_scale;
    if (c[z].status != AQ_CAPACITY_FAILED && !isnan(f)) {
      lo = isnan(lo) ? f : fmin(lo, f);
      hi = isnan(hi) ? f : fmax(hi, f);
    }
    if (c[w].status == AQ_CAPACITY_FAILED)
      continue;
    if (c[z].status == AQ_CAPACITY_FAILED ||
        (!isnan(f) && (isnan(c[w].first_collapse_scale) || f < c[w].first_collapse_scale)))
      w = z;
  }
  *fcs_min = lo;
  *fcs_max = hi;
  return w;
}

/* ---- the pool ------------------------------------------------------------ */

typedef struct {
  const aq_capacity_job *jobs;
  size_t njob, next;
  aq_capacity *out;
  pthread_mutex_t lock;
} pool;

static void *worker(void *arg)
{
  pool *P = arg;
  for (;;) {
    pthread_mutex_lock(&P->lock);
    size_t i = P->next < P->njob ? P->next++ : P->njob;
    pthread_mutex_unlock(&P->lock);
    if (i >= P->njob)
      return NULL;
    aq_error e;
    aq_error_clear(&e);
    aq_status s = aq_capacity_pair(&P->jobs[i], &P->out[i], &e);
    if (s != AQ_OK) {
      aq_capacity_free(&P->out[i]);
      P->out[i].status = AQ_CAPACITY_FAILED;
      P->out[i].run_status = s;
      P->out[i].err = e;
    }
  }
}

aq_status aq_capacity_run_all(const aq_capacity_job *jobs, size_t njob,
                              long threads, aq_capacity *out, aq_error *err)
{
  pool P = {jobs, njob, 0, out, PTHREAD_MUTEX_INITIALIZER};
  size_t nt = threads < 1 ? 1 : (size_t)threads;
  if (nt > njob)
    nt = njob ? njob : 1;
  pthread_t *tid = calloc(nt, sizeof *tid);
  if (!tid)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "threads", "out of memory");
  size_t started = 0;
  for (; started + 1 < nt; started++)
    if (pthread_create(&tid[started], NULL, worker, &P) != 0)
      break;
  worker(&P); /* the calling thread works too */
  for (size_t t = 0; t < started; t++)
    pthread_join(tid[t], NULL);
  free(tid);
  return AQ_OK;
}
