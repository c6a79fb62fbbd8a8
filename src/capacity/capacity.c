/* capacity.c: the collapse capacity of one (subject at an azimuth, arch,
 * polarity): the exact scale below which the arch never moves, then the
 * scan of scan.c with one run per verdict on the subject's view (a
 * collapsing run stops at its collapse: the stepper ends there); a result
 * as bytes and back (archquake-mpi's messages); and many such jobs on
 * threads.  Each job makes its own stepper, so a result depends on its job
 * alone, not on the thread that ran it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../signal/steps.h"
#include "../units.h"
#include "../util/pool.h"
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
                              const double *av_mps2, size_t n, double sign, double *lambda0)
{
  double best = INFINITY, l0 = INFINITY;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(arch, k);
    if (!p || !p->admissible)
      continue;
    l0 = fmin(l0, p->lambda0);
    double drive = 0; /* max of act_sign a over the samples, m/s^2 */
    for (size_t i = 0; i < n; i++) /* s act_sign a > lambda0 (g + s a_v) */
      drive = fmax(drive, p->act_sign * (sign * acc_mps2[i]) -
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
  aq_capacity *out; /* gets a point per run */
  size_t cap;       /* points allocated */
  int marks;        /* 1: the runs' marks are followed (aq_job_marks_apply) */
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
  /* the largest |q| / q_c over both sets, as the main job's summary
     (peak_rotation_over_qc) */
  double over = aq_result_peak_over_qc(res, aq_arch_path(c->job->arch, 0),
                                       aq_arch_path(c->job->arch, 1));
  o->point[o->npoint++] = (aq_capacity_point){
      scale, res->peak_rotation_rad, over,
      res->collapsed ? res->collapse_time_s : NAN, res->collapsed ? 1 : 0,
      c->marks ? aq_job_run_marks(c->job->arch, res) : 0};
  return AQ_OK;
}

static int by_scale(const void *a, const void *b)
{
  double x = ((const aq_capacity_point *)a)->scale, y = ((const aq_capacity_point *)b)->scale;
  return (x > y) - (x < y);
}

/* One run at scale: the view with the factor (its sign the polarity)
 * given to the stepper, or without it, merged steps of the scaled series
 * (--merge-tol), as the main job makes them. */
static aq_status run_at(void *vctx, double scale, int *collapsed, aq_error *err)
{
  run_ctx *c = vctx;
  const aq_capacity_job *job = c->job;
  double sa = aq_scale_signed(scale, job->reversed);
  aq_result res;
  aq_status s;
  if (job->merge_tol_mps2 == 0 && isfinite(sa)) {
    s = aq_job_run_view(c->st, job->view, sa, &res, err);
  } else {
    aq_steps steps;
    s = aq_view_steps(job->view, sa, scale, job->merge_tol_mps2, &steps, err);
    if (s != AQ_OK)
      return s;
    s = aq_stepper_run(c->st, &steps, &res, err);
    aq_steps_free(&steps);
  }
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
  out->first_collapse_scale = out->first_mark_scale = NAN;
  const aq_steps *v = &job->view->steps; /* one step per sample: the series */
  out->move_scale = aq_capacity_move_scale(job->arch, v->a_mps2, v->av_mps2, v->n,
                                           job->reversed ? -1.0 : 1.0, &out->lambda0);
  double amax = 0; /* PGA, m/s^2 */
  for (size_t i = 0; i < v->n; i++)
    amax = fmax(amax, fabs(v->a_mps2[i]));
  out->scale_max = !isnan(job->scale_max)
                       ? job->scale_max
                       : amax > 0 ? AQ_CAPACITY_CAP_LAMBDA0 * out->lambda0 *
                                        AQ_G0_MPS2 / amax
                                  : INFINITY;
  if (!(out->move_scale < out->scale_max)) {
    out->status = AQ_CAPACITY_NEVER_MOVES;
    return AQ_OK;
  }
  const int marks = aq_job_marks_apply(job->arch, job->model);
  aq_stepper *st = job->model == AQ_MODEL_BLOCKS
                       ? aq_job_stepper_blocks(job->arch, job->blocks_dt_s, 0, err)
                       : aq_job_stepper(job->arch, job->model, job->cor, 0,
                                        marks ? AQ_JOB_DEMAND_MARKS : AQ_JOB_DEMAND_NONE, err);
  if (!st)
    return err->status;
  run_ctx c = {job, st, out, 0, marks};
  aq_status s = aq_scan_run(out->move_scale, out->scale_max, &job->scan, run_at,
                            &c, &out->scan, &out->err);
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
  for (size_t k = 0; k < out->npoint; k++) { /* by increasing scale */
    const aq_capacity_point *q = &out->point[k];
    if (q->marks && isnan(out->first_mark_scale))
      out->first_mark_scale = q->scale;
    if (!(q->scale > out->first_collapse_scale)) /* all when it never collapses */
      out->marks |= q->marks;
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

/* ---- results as bytes ----------------------------------------------------- */

void aq_capacity_encode(const aq_capacity *c, aq_bytes_out *w)
{
  aq_bytes_put_i64(w, c->status);
  aq_bytes_put_i64(w, c->run_status);
  aq_bytes_put_i64(w, c->err.status);
  aq_bytes_put_i64(w, c->err.line);
  aq_bytes_put_i64(w, c->err.byte_offset);
  aq_bytes_put_str(w, c->err.input, sizeof c->err.input);
  aq_bytes_put_str(w, c->err.field, sizeof c->err.field);
  aq_bytes_put_str(w, c->err.message, sizeof c->err.message);
  aq_bytes_put_f64(w, c->lambda0);
  aq_bytes_put_f64(w, c->move_scale);
  aq_bytes_put_f64(w, c->scale_max);
  aq_bytes_put_f64(w, c->first_collapse_scale);
  aq_bytes_put_i64(w, c->resurrection);
  aq_bytes_put_i64(w, c->marks);
  aq_bytes_put_f64(w, c->first_mark_scale);
  aq_bytes_put_i64(w, (int64_t)c->scan.runs);
  aq_bytes_put_i64(w, (int64_t)c->scan.grid_runs);
  aq_bytes_put_i64(w, (int64_t)c->scan.bisect_runs);
  aq_bytes_put_i64(w, (int64_t)c->scan.ninterval);
  for (size_t k = 0; k < c->scan.ninterval; k++) {
    aq_bytes_put_f64(w, c->scan.interval[k].lo);
    aq_bytes_put_f64(w, c->scan.interval[k].hi);
  }
  aq_bytes_put_i64(w, (int64_t)c->npoint);
  for (size_t k = 0; k < c->npoint; k++) {
    const aq_capacity_point *q = &c->point[k];
    aq_bytes_put_f64(w, q->scale);
    aq_bytes_put_f64(w, q->peak_rotation_rad);
    aq_bytes_put_f64(w, q->peak_rotation_over_qc);
    aq_bytes_put_f64(w, q->collapse_time_s);
    aq_bytes_put_i64(w, q->collapsed);
    aq_bytes_put_i64(w, q->marks);
  }
}

aq_status aq_capacity_decode(aq_bytes_in *r, aq_capacity *out, aq_error *err)
{
  memset(out, 0, sizeof *out);
  size_t start = r->at;
  out->status = (aq_capacity_status)aq_bytes_get_int(r, AQ_CAPACITY_OK, AQ_CAPACITY_FAILED,
                                                     "status");
  out->run_status = (aq_status)aq_bytes_get_int(r, INT32_MIN, INT32_MAX, "run_status");
  out->err.status = (aq_status)aq_bytes_get_int(r, INT32_MIN, INT32_MAX, "error status");
  out->err.line = (long)aq_bytes_get_i64(r, "error line");
  out->err.byte_offset = (long)aq_bytes_get_i64(r, "error byte offset");
  aq_bytes_get_str(r, out->err.input, sizeof out->err.input, NULL, "error input");
  aq_bytes_get_str(r, out->err.field, sizeof out->err.field, NULL, "error field");
  aq_bytes_get_str(r, out->err.message, sizeof out->err.message, NULL, "error message");
  out->lambda0 = aq_bytes_get_f64(r, "lambda0");
  out->move_scale = aq_bytes_get_f64(r, "move_scale");
  out->scale_max = aq_bytes_get_f64(r, "scale_max");
  out->first_collapse_scale = aq_bytes_get_f64(r, "first_collapse_scale");
  out->resurrection = (int)aq_bytes_get_int(r, 0, 1, "resurrection");
  out->marks = (int)aq_bytes_get_int(r, 0, 3, "marks");
  out->first_mark_scale = aq_bytes_get_f64(r, "first_mark_scale");
  out->scan.runs = (size_t)aq_bytes_get_i64(r, "runs");
  out->scan.grid_runs = (size_t)aq_bytes_get_i64(r, "grid_runs");
  out->scan.bisect_runs = (size_t)aq_bytes_get_i64(r, "bisect_runs");
  size_t ni = aq_bytes_get_count(r, 2 * sizeof(double), "ninterval");
  if (!r->bad && ni) {
    out->scan.interval = malloc(ni * sizeof *out->scan.interval);
    if (!out->scan.interval)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
    out->scan.ninterval = ni;
    for (size_t k = 0; k < ni; k++) {
      out->scan.interval[k].lo = aq_bytes_get_f64(r, "interval");
      out->scan.interval[k].hi = aq_bytes_get_f64(r, "interval");
    }
  }
  size_t np = aq_bytes_get_count(r, 6 * sizeof(int64_t), "npoint");
  if (!r->bad && np) {
    out->point = malloc(np * sizeof *out->point);
    if (!out->point) {
      aq_capacity_free(out);
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
    }
    out->npoint = np;
    for (size_t k = 0; k < np; k++) {
      aq_capacity_point *q = &out->point[k];
      q->scale = aq_bytes_get_f64(r, "point");
      q->peak_rotation_rad = aq_bytes_get_f64(r, "point");
      q->peak_rotation_over_qc = aq_bytes_get_f64(r, "point");
      q->collapse_time_s = aq_bytes_get_f64(r, "point");
      q->collapsed = (int)aq_bytes_get_int(r, 0, 1, "point collapsed");
      q->marks = (int)aq_bytes_get_int(r, 0, 3, "point marks");
    }
  }
  if (r->bad) {
    aq_capacity_free(out);
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, (long)r->bad_at, r->bad,
                        "expected a capacity result of %zu bytes with a valid %s, got a "
                        "message that ends or is out of range there",
                        r->n - start, r->bad);
  }
  return AQ_OK;
}

/* ---- tasks and the pool --------------------------------------------------- */

void aq_capacity_run_jobs(const aq_capacity_job *jobs, size_t n, aq_capacity *out)
{
  for (size_t i = 0; i < n; i++) {
    aq_error e;
    aq_error_clear(&e);
    aq_status s = aq_capacity_pair(&jobs[i], &out[i], &e);
    if (s != AQ_OK) {
      aq_capacity_free(&out[i]);
      out[i].status = AQ_CAPACITY_FAILED;
      out[i].run_status = s;
      out[i].err = e;
    }
  }
}

typedef struct {
  const aq_capacity_job *jobs;
  aq_capacity *out;
} all_ctx;

static void run_job(void *ctx, size_t i)
{
  all_ctx *A = ctx;
  aq_capacity_run_jobs(&A->jobs[i], 1, &A->out[i]);
}

aq_status aq_capacity_run_all(const aq_capacity_job *jobs, size_t njob,
                              long threads, aq_capacity *out, aq_error *err)
{
  all_ctx A = {jobs, out};
  return aq_pool_for(njob, threads, run_job, &A, err);
}
