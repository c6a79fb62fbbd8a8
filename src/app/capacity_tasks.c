/* capacity_tasks.c: the capacity command's (subject, arch) tasks, run here
 * or farmed out (capacity_tasks.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/record.h"
#include "../job/cache.h"
#include "../report/report.h"
#include "capacity_tasks.h"
#include "opt.h"
#include "opt_record.h"

void aq_cap_item_free(aq_cap_item *it)
{
  for (size_t z = 0; it->view && z < it->naz; z++)
    aq_view_free(&it->view[z]);
  free(it->view);
  free(it->im);
  aq_subject_free(&it->subj);
  memset(it, 0, sizeof *it);
}

/* The subject's views at every azimuth, each with its measures. */
static aq_status make_views(const aq_cap_setup *S, aq_cap_item *it, aq_error *err)
{
  const aq_orient_opts *or = S->orient;
  size_t naz = it->subj.motion ? or->nazimuth : 1;
  it->view = calloc(naz, sizeof *it->view);
  it->im = calloc(naz, sizeof *it->im);
  if (!it->view || !it->im)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
  aq_status s = AQ_OK;
  for (size_t z = 0; s == AQ_OK && z < naz; z++) {
    s = aq_view_make(&it->view[z], &it->subj, it->subj.motion ? or->azimuths_deg[z] : 0.0,
                     err);
    it->naz = z + 1;
    if (s == AQ_OK)
      s = aq_im_compute(&it->view[z].at, &it->im[z], err);
  }
  if (it->subj.motion) /* its views hold what the runs need; a record's */
    aq_subject_shed(&it->subj); /* view borrows its samples (job/subject.h) */
  return s;
}

/* Read, process and view subject r; its lines on stderr only when loud (a
 * follower prepares quietly: the leader reports each subject once, when it
 * prepares it). */
static void prepare(const aq_cap_setup *S, size_t r, aq_signal_ws *ws, aq_cap_item *it,
                    int loud)
{
  memset(it, 0, sizeof *it);
  aq_error_clear(&it->err);
  const aq_orient_opts *or = S->orient;
  aq_subject_src src = {{S->paths[r][0], S->paths[r][1], S->paths[r][2]},
                        {S->phi_deg[r][0], S->phi_deg[r][1]},
                        S->labels[r]};
  aq_subject_opts so = {S->ro, S->po, or->vertical, 0, 0, NULL};
  aq_status s = aq_subject_prepare(&it->subj, &src, &so, ws, &it->err);
  const char *stage = it->subj.stage;
  if (s == AQ_OK && S->factor) /* --suite: the suite's record is the subject */
    s = aq_subject_scale(&it->subj, S->factor[r], &it->err);
  if (s == AQ_OK)
    s = make_views(S, it, &it->err);
  aq_summary_status(it->status, sizeof it->status, stage, s);
  it->ok = s == AQ_OK;
  if (loud && !it->ok)
    aq_error_print(&it->err, stderr);
  else if (loud && it->subj.v_ignored)
    fprintf(stderr, "archquake: %s: vertical component ignored (--vertical runs it)\n",
            S->paths[r][2]);
  for (int k = 0; loud && it->ok && k < 3; k++)
    if (it->subj.have_rec[k])
      aq_record_print_notes(&it->subj.rec[k], stderr);
}

void aq_cap_prepare(const aq_cap_setup *S, size_t r, aq_signal_ws *ws, aq_cap_item *it)
{
  prepare(S, r, ws, it, 1);
}

/* Job z of polarity p of subject it with arch a. */
static aq_capacity_job job_of(const aq_cap_setup *S, const aq_cap_item *it, size_t a,
                              size_t p, size_t z)
{
  return (aq_capacity_job){&it->view[z], S->pols[p] == AQ_POLARITY_REVERSED, S->arches[a],
                           S->model, S->cor, S->merge_tol_mps2, S->scale_max, S->scan,
                           S->blocks_dt_s};
}

/* ---- here: one pool over every (subject, arch, polarity, azimuth) -------- */

static int run_here(const aq_cap_setup *S, const aq_cap_item *R, aq_capacity *C,
                    long threads)
{
  size_t nout = S->npol * S->nz, njob = S->nrec * S->na * nout, nrun = 0;
  aq_capacity_job *jobs = calloc(njob ? njob : 1, sizeof *jobs);
  size_t *slot = calloc(njob ? njob : 1, sizeof *slot);
  aq_capacity *out = calloc(njob ? njob : 1, sizeof *out);
  aq_error e;
  int rc = jobs && slot && out ? 0 : -1;
  for (size_t i = 0; rc == 0 && i < njob; i++) {
    size_t t = i / nout, r = t / S->na, p = i % nout / S->nz, z = i % S->nz;
    if (!R[r].ok || z >= R[r].naz)
      continue;
    jobs[nrun] = job_of(S, &R[r], t % S->na, p, z);
    slot[nrun++] = i;
  }
  if (rc == 0 && aq_capacity_run_all(jobs, nrun, threads, out, &e) != AQ_OK)
    rc = -1;
  for (size_t k = 0; rc == 0 && k < nrun; k++)
    C[slot[k]] = out[k];
  if (rc != 0)
    fprintf(stderr, "archquake: out of memory\n");
  free(jobs);
  free(slot);
  free(out);
  return rc;
}

/* ---- tasks: a (subject, arch) with its subject prepared where it runs ---- */

/* Subjects a follower keeps prepared beyond those in use, for the next
 * tasks of the same subject. */
#define AQ_CAP_KEEP_EXTRA 2

typedef struct {
  const aq_cap_setup *S;
  aq_capacity *C;
  int leader;           /* keep every subject prepared (for the outputs), report it */
  aq_cache *cache;      /* subjects prepared here (job/cache.h): the leader's
                           item r is R[r]; a follower keeps the last few */
  pthread_mutex_t prep; /* one subject prepared at a time (ws, FFTW plans) */
  aq_signal_ws *ws;
} tasks;

/* The cache's preparing of subject r into item (job/cache.h). */
static void task_prepare(void *ctx, size_t r, void *item)
{
  tasks *X = ctx;
  pthread_mutex_lock(&X->prep);
  prepare(X->S, r, X->ws, item, X->leader);
  pthread_mutex_unlock(&X->prep);
}

static void task_clear(void *ctx, void *item)
{
  (void)ctx;
  aq_cap_item_free(item);
}

/* Task t into out[npol nz] (zeroed). */
static void run_task(tasks *X, size_t t, aq_capacity *out)
{
  const aq_cap_setup *S = X->S;
  size_t r = t / S->na, a = t % S->na;
  const aq_cap_item *it = aq_cache_acquire(X->cache, r);
  for (size_t p = 0; p < S->npol; p++)
    for (size_t z = 0; z < S->nz; z++) {
      aq_capacity *o = &out[p * S->nz + z];
      if (!it->ok) { /* not read here (the leader reports it, or has read it) */
        o->status = AQ_CAPACITY_FAILED;
        o->run_status = it->err.status;
        o->err = it->err;
      } else if (z < it->naz) {
        aq_capacity_job job = job_of(S, it, a, p, z);
        aq_capacity_run_jobs(&job, 1, o);
      }
    }
  aq_cache_release(X->cache, (void *)it);
}

static int task_run(void *ctx, size_t t, unsigned char **msg, size_t *n)
{
  tasks *X = ctx;
  size_t nout = X->S->npol * X->S->nz;
  aq_capacity *out = calloc(nout, sizeof *out);
  if (!out)
    return -1;
  run_task(X, t, out);
  aq_bytes_out w = {0};
  for (size_t k = 0; k < nout; k++) {
    aq_capacity_encode(&out[k], &w);
    aq_capacity_free(&out[k]);
  }
  free(out);
  if (w.oom) {
    free(w.data);
    return -1;
  }
  *msg = w.data;
  *n = w.n;
  return 0;
}

/* Leader: subject r prepared here, when the first result of it comes
 * before any task of it ran here (its rows, fits and /records need it). */
static const aq_cap_item *ensure(tasks *X, size_t r)
{
  const aq_cap_item *it = aq_cache_acquire(X->cache, r);
  aq_cache_release(X->cache, (void *)it);
  return it;
}

static int task_take(void *ctx, size_t t, const unsigned char *msg, size_t n, aq_error *err)
{
  tasks *X = ctx;
  size_t nout = X->S->npol * X->S->nz;
  aq_capacity *o = X->C + t * nout;
  const aq_cap_item *it = ensure(X, t / X->S->na);
  aq_bytes_in r = {msg, n, 0, NULL, 0};
  for (size_t k = 0; k < nout; k++) {
    aq_capacity_free(&o[k]);
    if (aq_capacity_decode(&r, &o[k], err) != AQ_OK)
      return -1;
  }
  if (r.at != n)
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, (long)r.at, NULL,
                        "expected %zu capacity results of task %zu in %zu bytes, got "
                        "bytes left over", nout, t, n), -1;
  for (size_t k = 0; !it->ok && k < nout; k++) { /* unread here: no results (its status) */
    aq_capacity_free(&o[k]);
    memset(&o[k], 0, sizeof o[k]);
  }
  return 0;
}

int aq_cap_run(const aq_cap_setup *S, aq_cap_item *R, aq_capacity *C, long threads)
{
  const aq_farm *farm_hook = aq_farm_get();
  if (!farm_hook || !farm_hook->farm) {
    aq_signal_ws *ws = aq_signal_ws_alloc();
    if (!ws)
      return fprintf(stderr, "archquake: out of memory\n"), -1;
    for (size_t r = 0; r < S->nrec; r++)
      aq_cap_prepare(S, r, ws, &R[r]);
    aq_signal_ws_free(ws);
    return run_here(S, R, C, threads);
  }
  /* farmed: every task goes out at once; each process prepares a subject
   * when it runs a task of it, the leader also when a result of it comes
   * first (as the main job's farm, suite_farm.c) */
  int leader = !farm_hook->follower;
  size_t nkeep = leader ? S->nrec : (size_t)(threads > 0 ? threads : 1) + AQ_CAP_KEEP_EXTRA;
  aq_cap_item *kept = leader ? R : calloc(nkeep, sizeof *kept);
  tasks X = {.S = S, .C = C, .leader = leader};
  aq_cache_cfg cc = {S->nrec, nkeep, kept, sizeof *kept, task_prepare, task_clear, &X};
  pthread_mutex_init(&X.prep, NULL);
  size_t ntask = S->nrec * S->na, ntodo = leader ? ntask : 0;
  size_t *todo = calloc(ntask ? ntask : 1, sizeof *todo);
  X.ws = aq_signal_ws_alloc();
  X.cache = kept ? aq_cache_alloc(&cc) : NULL;
  int rc = todo && X.ws && X.cache ? 0 : -1;
  for (size_t t = 0; rc == 0 && t < ntodo; t++)
    todo[t] = t;
  aq_farm_tasks T = {ntask, threads, S->na, 0, task_run, task_take, &X};
  aq_error e;
  aq_error_clear(&e);
  if (rc != 0)
    fprintf(stderr, "archquake: out of memory\n");
  else if (farm_hook->farm(farm_hook->ctx, &T, todo, ntodo, &e) != 0) {
    aq_error_print(&e, stderr);
    rc = -1;
  }
  for (size_t r = 0; rc == 0 && leader && r < S->nrec; r++)
    ensure(&X, r); /* every subject, for the outputs (none left without arches) */
  aq_cache_free(X.cache);
  if (!leader) {
    for (size_t k = 0; kept && k < nkeep; k++)
      aq_cap_item_free(&kept[k]);
    free(kept);
  }
  aq_signal_ws_free(X.ws);
  free(todo);
  pthread_mutex_destroy(&X.prep);
  return rc;
}
