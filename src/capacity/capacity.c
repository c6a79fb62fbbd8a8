/* capacity.c: the collapse capacity of one (processed record, arch,
 * polarity): the exact scale below which the arch never moves, then the
 * scan of scan.c with one dynamic run per verdict (a collapsing run stops
 * at its collapse: the stepper ends there); a result as bytes and back
 * (archquake-mpi's messages); and a pool of threads over many such jobs or
 * tasks.  Each job makes its own stepper, so a result depends on its
 * job alone, not on the thread that ran it. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
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

/* ---- results as bytes ----------------------------------------------------- */

/* A cursor over a message: writing when p is NULL only counts. */
typedef struct {
  unsigned char *p;
  size_t n;
} wcur;

static void put(wcur *w, const void *v, size_t k)
{
  if (w->p)
    memcpy(w->p + w->n, v, k);
  w->n += k;
}

static void put_i64(wcur *w, int64_t v) { put(w, &v, sizeof v); }
static void put_f64(wcur *w, double v) { put(w, &v, sizeof v); }

static void put_str(wcur *w, const char *s, size_t cap)
{
  size_t k = strnlen(s, cap - 1);
  put_i64(w, (int64_t)k);
  put(w, s, k);
}

static size_t encode(const aq_capacity *c, unsigned char *buf)
{
  wcur w = {buf, 0};
  put_i64(&w, c->status);
  put_i64(&w, c->run_status);
  put_i64(&w, c->err.status);
  put_i64(&w, c->err.line);
  put_i64(&w, c->err.byte_offset);
  put_str(&w, c->err.input, sizeof c->err.input);
  put_str(&w, c->err.field, sizeof c->err.field);
  put_str(&w, c->err.message, sizeof c->err.message);
  put_f64(&w, c->lambda0);
  put_f64(&w, c->move_scale);
  put_f64(&w, c->scale_max);
  put_f64(&w, c->first_collapse_scale);
  put_i64(&w, c->resurrection);
  put_i64(&w, (int64_t)c->scan.runs);
  put_i64(&w, (int64_t)c->scan.grid_runs);
  put_i64(&w, (int64_t)c->scan.bisect_runs);
  put_i64(&w, (int64_t)c->scan.ninterval);
  for (size_t k = 0; k < c->scan.ninterval; k++) {
    put_f64(&w, c->scan.interval[k].lo);
    put_f64(&w, c->scan.interval[k].hi);
  }
  put_i64(&w, (int64_t)c->npoint);
  for (size_t k = 0; k < c->npoint; k++) {
    const aq_capacity_point *q = &c->point[k];
    put_f64(&w, q->scale);
    put_f64(&w, q->peak_rotation_rad);
    put_f64(&w, q->peak_rotation_over_qc);
    put_f64(&w, q->collapse_time_s);
    put_i64(&w, q->collapsed);
  }
  return w.n;
}

size_t aq_capacity_encoded_size(const aq_capacity *c)
{
  return encode(c, NULL);
}

size_t aq_capacity_encode(const aq_capacity *c, unsigned char *buf)
{
  return encode(c, buf);
}

/* A cursor reading a message of n bytes; bad: it ran past the end, or a
 * value was out of range (what names it, bad_at is where it starts). */
typedef struct {
  const unsigned char *p;
  size_t n, at;
  const char *bad;
  size_t bad_at;
} rcur;

static void bad(rcur *r, const char *what, size_t at)
{
  if (!r->bad) {
    r->bad = what;
    r->bad_at = at;
  }
}

static int64_t get_i64(rcur *r, const char *what)
{
  int64_t v = 0;
  if (r->bad)
    return 0;
  if (r->n - r->at < sizeof v) {
    bad(r, what, r->at);
    return 0;
  }
  memcpy(&v, r->p + r->at, sizeof v);
  r->at += sizeof v;
  return v;
}

static double get_f64(rcur *r, const char *what)
{
  int64_t b = get_i64(r, what);
  double v;
  memcpy(&v, &b, sizeof v);
  return v;
}

static size_t get_count(rcur *r, size_t item_bytes, const char *what)
{
  int64_t v = get_i64(r, what);
  if (!r->bad && (v < 0 || (uint64_t)v > (r->n - r->at) / (item_bytes ? item_bytes : 1))) {
    bad(r, what, r->at - sizeof v);
    return 0;
  }
  return (size_t)v;
}

static void get_str(rcur *r, char *s, size_t cap, const char *what)
{
  size_t k = get_count(r, 1, what);
  if (!r->bad && k >= cap)
    bad(r, what, r->at - sizeof(int64_t));
  if (r->bad) {
    s[0] = '\0';
    return;
  }
  memcpy(s, r->p + r->at, k);
  s[k] = '\0';
  r->at += k;
}

static int get_int(rcur *r, int64_t lo, int64_t hi, const char *what)
{
  int64_t v = get_i64(r, what);
  if (!r->bad && (v < lo || v > hi))
    bad(r, what, r->at - sizeof v);
  return (int)v;
}

aq_status aq_capacity_decode(const unsigned char *buf, size_t n, size_t *used,
                             aq_capacity *out, aq_error *err)
{
  memset(out, 0, sizeof *out);
  rcur r = {buf, n, 0, NULL, 0};
  out->status = (aq_capacity_status)get_int(&r, AQ_CAPACITY_OK, AQ_CAPACITY_FAILED, "status");
  out->run_status = (aq_status)get_int(&r, INT32_MIN, INT32_MAX, "run_status");
  out->err.status = (aq_status)get_int(&r, INT32_MIN, INT32_MAX, "error status");
  out->err.line = (long)get_i64(&r, "error line");
  out->err.byte_offset = (long)get_i64(&r, "error byte offset");
  get_str(&r, out->err.input, sizeof out->err.input, "error input");
  get_str(&r, out->err.field, sizeof out->err.field, "error field");
  get_str(&r, out->err.message, sizeof out->err.message, "error message");
  out->lambda0 = get_f64(&r, "lambda0");
  out->move_scale = get_f64(&r, "move_scale");
  out->scale_max = get_f64(&r, "scale_max");
  out->first_collapse_scale = get_f64(&r, "first_collapse_scale");
  out->resurrection = get_int(&r, 0, 1, "resurrection");
  out->scan.runs = (size_t)get_i64(&r, "runs");
  out->scan.grid_runs = (size_t)get_i64(&r, "grid_runs");
  out->scan.bisect_runs = (size_t)get_i64(&r, "bisect_runs");
  size_t ni = get_count(&r, 2 * sizeof(double), "ninterval");
  if (!r.bad && ni) {
    out->scan.interval = malloc(ni * sizeof *out->scan.interval);
    if (!out->scan.interval)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
    out->scan.ninterval = ni;
    for (size_t k = 0; k < ni; k++) {
      out->scan.interval[k].lo = get_f64(&r, "interval");
      out->scan.interval[k].hi = get_f64(&r, "interval");
    }
  }
  size_t np = get_count(&r, 5 * sizeof(int64_t), "npoint");
  if (!r.bad && np) {
    out->point = malloc(np * sizeof *out->point);
    if (!out->point) {
      aq_capacity_free(out);
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
    }
    out->npoint = np;
    for (size_t k = 0; k < np; k++) {
      aq_capacity_point *q = &out->point[k];
      q->scale = get_f64(&r, "point");
      q->peak_rotation_rad = get_f64(&r, "point");
      q->peak_rotation_over_qc = get_f64(&r, "point");
      q->collapse_time_s = get_f64(&r, "point");
      q->collapsed = get_int(&r, 0, 1, "point collapsed");
    }
  }
  if (r.bad) {
    aq_capacity_free(out);
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, (long)r.bad_at, r.bad,
                        "expected a capacity result of %zu bytes with a valid %s, got a "
                        "message that ends or is out of range there", n, r.bad);
  }
  *used = r.at;
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
  size_t ntask, next;
  aq_capacity_task_fn fn;
  void *ctx;
  pthread_mutex_t lock;
} pool;

static void *worker(void *arg)
{
  pool *P = arg;
  for (;;) {
    pthread_mutex_lock(&P->lock);
    size_t i = P->next < P->ntask ? P->next++ : P->ntask;
    pthread_mutex_unlock(&P->lock);
    if (i >= P->ntask)
      return NULL;
    P->fn(P->ctx, i);
  }
}

aq_status aq_capacity_run_tasks(size_t ntask, long threads, aq_capacity_task_fn fn,
                                void *ctx, aq_error *err)
{
  pool P = {ntask, 0, fn, ctx, PTHREAD_MUTEX_INITIALIZER};
  size_t nt = threads < 1 ? 1 : (size_t)threads;
  if (nt > ntask)
    nt = ntask ? ntask : 1;
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
  return aq_capacity_run_tasks(njob, threads, run_job, &A, err);
}
