/* suite_record.c: a record of the main job in flight (suite_slot.h):
 * prepared and run through job/ (subject, scale, runs), each run's summary
 * filled for the writer; the suite's arches loaded and checked. */
#define _POSIX_C_SOURCE 200809L
#include "suite_slot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../arch/arch.h"
#include "../arch/model.h"
#include "../job/names.h"
#include "../units.h"
#include "app.h"
#include "opt.h"

double aq_suite_now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Run slot k of an arch: factor k / npol, the record negated (reversed)
 * for the second slot of each factor with --polarity both, or for every
 * slot with --polarity reversed. */
int aq_suite_reversed(const suite *S, size_t k)
{
  return S->cfg->polarity == AQ_POLARITY_REVERSED ||
         (S->cfg->polarity == AQ_POLARITY_BOTH && k % 2 == 1);
}

static const char *slot_polarity(const suite *S, size_t k)
{
  return aq_suite_reversed(S, k) ? "reversed" : "normal";
}

/* Free what record r's runs needed and writing it does not (the processed
 * samples, unless --store-records writes them, and the step lists): a
 * finished record waiting for the writer holds its metadata, measures and
 * run results only.  Called by the thread that finished its last run. */
void aq_suite_slot_shed(suite *S, rec_slot *r)
{
  aq_runs_free(&r->plan); /* first: a record's view borrows its samples */
  aq_processed *first = &r->subj.proc[0], keep = *first;
  first->acc_mps2 = NULL;
  aq_subject_shed(&r->subj);
  if (S->cfg->store_records)
    *first = keep; /* the writer writes it */
  else
    free(keep.acc_mps2);
}

void aq_suite_slot_clear(suite *S, rec_slot *r)
{
  aq_suite_slot_shed(S, r);
  aq_subject_free(&r->subj);
  if (r->runs)
    for (size_t k = 0; k < r->nruns; k++)
      if (r->runs[k].have_res)
        aq_result_free(&r->runs[k].res);
  free(r->runs);
  free(r->scale);
  memset(r, 0, sizeof *r);
}

/* Run i of record r: arch *ai, scale slot *k, azimuth *z. */
void aq_suite_run_index(const suite *S, const rec_slot *r, size_t i, size_t *ai,
                      size_t *k, size_t *z)
{
  *ai = i / (S->nscale * r->naz);
  *k = i / r->naz % S->nscale;
  *z = i % r->naz;
}

/* The arch azimuth of run slot z of r, deg (NAN for a plain record). */
static double run_azimuth(const suite *S, const rec_slot *r, size_t z)
{
  return r->motion ? S->cfg->azimuths_deg[z] : NAN;
}

/* Record i's motion (or NULL), azimuths per (arch, scale) and runs, set
 * in r (before it is prepared or decoded from the journal). */
void aq_suite_slot_orient(const suite *S, size_t i, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  r->motion = c->motions ? c->motions[i] : NULL;
  r->naz = r->motion ? c->nazimuth : 1;
  r->nruns = S->nruns * r->naz;
}

/* The file whose hash identifies record i: the record, or a motion's H1. */
const char *aq_suite_record_file(const suite *S, size_t i)
{
  const aq_suite_cfg *c = S->cfg;
  return c->motions && c->motions[i] ? c->motions[i]->path[0] : c->records[i];
}

/* Every run of a record that failed before any run: status, NAN values. */
static void fail_runs(suite *S, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  for (size_t i = 0; i < r->nruns; i++) {
    size_t a, k, z;
    aq_suite_run_index(S, r, i, &a, &k, &z);
    run_slot *u = &r->runs[i];
    double scale = c->scales ? c->scales[k / S->npol] * aq_suite_record_factor(c, r->index) : NAN;
    aq_summary_fill(&u->sum, c->records[r->index], aq_arch_name(S->arches[a]),
                    S->model_name, scale, NAN, r->status, NULL);
    aq_summary_normalise(&u->sum, slot_polarity(S, k), NULL, NULL, NULL);
    u->sum.azimuth_deg = run_azimuth(S, r, z);
    snprintf(u->sum.control, sizeof u->sum.control, "%s",
             aq_hinge_control_names[aq_arch_control(S->arches[a])]);
  }
}

/* The record file's identity in the results (compare keys on it), when
 * prepare_record asked for it: hashed by the thread that writes the record
 * (or sends it to the leader), so that with -o the hash overlaps the
 * workers' reading and processing of the next records; from the bytes the
 * reader read when they were kept, else from the file.  next, if not NULL,
 * is the next record, done too when both have their bytes. */
void aq_suite_record_sha256(const suite *S, rec_slot *r, rec_slot *next)
{
  aq_subject *a = &r->subj, *b = next ? &next->subj : NULL;
  if (b && r->want_sha && a->bytes && next->want_sha && b->bytes) {
    aq_sha256_hex2(a->bytes, a->nbytes, r->sha256, b->bytes, b->nbytes, next->sha256);
    r->want_sha = next->want_sha = 0;
    free(a->bytes);
    free(b->bytes);
    a->bytes = b->bytes = NULL;
    return;
  }
  if (!r->want_sha)
    return;
  r->want_sha = 0;
  if (a->sha256[0]) { /* the cache's key hashed it (job/subject_cache.h) */
    memcpy(r->sha256, a->sha256, sizeof r->sha256);
    return;
  }
  aq_error herr;
  char file[4096];
  if (a->bytes)
    aq_sha256_hex(a->bytes, a->nbytes, r->sha256);
  else if (aq_sha256_file(aq_record_file(aq_suite_record_file(S, r->index), file, sizeof file),
                          r->sha256, &herr) != AQ_OK)
    r->sha256[0] = '\0'; /* the reader says why it cannot be read */
  free(a->bytes);
  a->bytes = NULL;
}

/* Read, process and measure record r->index (every component of a motion,
 * job/subject.h), then make the step lists its runs share (job/run.h).
 * Returns 1 if its runs can go ahead, 0 if the record failed (its runs are
 * filled as failed). */
int aq_suite_prepare(suite *S, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  const char *path = c->records[r->index];
  aq_suite_slot_orient(S, r->index, r);
  r->runs = calloc(r->nruns ? r->nruns : 1, sizeof *r->runs);
  r->scale = calloc(S->nscale, sizeof *r->scale);
  double *slot_sa = calloc(S->nscale, sizeof *slot_sa);
  if (!r->runs || !r->scale || !slot_sa) {
    free(r->runs);
    free(slot_sa);
    r->runs = NULL; /* the writer reports it; no run rows can be made */
    r->failed = 1;
    aq_error_set(&r->err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    aq_summary_status(r->status, sizeof r->status, "read", AQ_ENOMEM);
    return 0;
  }
  const aq_orient_motion *m = r->motion;
  aq_subject_src src = {{m ? m->path[0] : path, m ? m->path[1] : NULL, m ? m->path[2] : NULL},
                        {m ? m->azimuth_deg[0] : NAN, m ? m->azimuth_deg[1] : NAN},
                        path};
  r->want_sha = c->h5_path != NULL; /* hashed by record_sha256 */
  aq_subject_opts so = {&c->read, &c->proc, c->vertical, r->want_sha ? S->keep_max : 0, 0,
                        c->cache};
  aq_status s = aq_subject_prepare(&r->subj, &src, &so, S->ws, &r->err);
  if (s == AQ_OK)
    s = aq_scale_check_subject(&S->rule, path, r->subj.pga_g, &r->err);
  for (size_t k = 0; s == AQ_OK && k < S->nscale; k++) {
    r->scale[k] = aq_scale_factor(&S->rule, k / S->npol, r->subj.pga_g) *
                  aq_suite_record_factor(c, r->index);
    slot_sa[k] = aq_scale_signed(r->scale[k], aq_suite_reversed(S, k));
  }
  if (s == AQ_OK)
    s = aq_runs_init(&r->plan, &r->subj, r->naz, r->motion ? c->azimuths_deg[0] : 0.0,
                     c->merge_tol_g * AQ_G0_MPS2, slot_sa, S->nscale,
                     aq_scale_per_arch(&S->rule), &r->err);
  free(slot_sa);
  if (s != AQ_OK) {
    r->failed = 1;
    aq_summary_status(r->status, sizeof r->status, r->subj.stage, s);
    fail_runs(S, r);
    return 0;
  }
  snprintf(r->status, sizeof r->status, "ok");
  return 1;
}

/* --check blocks: slot k's motion at azimuth az, factor sa, again under
 * the block model of arch ai (a stepper of its own, made here: the marked
 * runs are few), its verdict into u's summary beside the four-hinge
 * model's; a re-run that fails leaves "failed" there and its error in
 * u->check_err (u->check_failed = 1), reported when the record is written. */
static void check_blocks(suite *S, rec_slot *r, size_t k, double az, double sa, size_t ai,
                         run_slot *u)
{
  aq_error *e = &u->check_err;
  aq_error_clear(e);
  aq_result b;
  memset(&b, 0, sizeof b);
  aq_stepper *st = aq_job_stepper_blocks(S->arches[ai], S->cfg->blocks_dt_s, 0, e);
  double pga_g = 0;
  int failed = 0, ran = 0;
  aq_status rs =
      st ? aq_runs_run(&r->plan, k, az, sa, st, &b, &pga_g, &failed, &ran, e) : AQ_EINTERNAL;
  int ok = rs == AQ_OK && ran && !failed;
  aq_summary_check(&u->sum, ok ? &b : NULL);
  u->check_failed = !ok;
  if (!ok && e->status == AQ_OK) /* a failure that left no error of its own */
    aq_error_set(e, rs != AQ_OK ? rs : AQ_EINTERNAL, NULL, -1, -1, NULL, "%s",
                 !st     ? "the block model could not be set up for this arch"
                 : !ran  ? "the block model ran nothing"
                         : "the block model's run failed");
  aq_result_free(&b);
  aq_stepper_free(st);
}

/* Run i of prepared record r with this thread's steppers (st[a] NULL when
 * arch a cannot run). */
void aq_suite_run_one(suite *S, rec_slot *r, size_t i, aq_stepper **st)
{
  const aq_suite_cfg *c = S->cfg;
  size_t ai, k, z;
  aq_suite_run_index(S, r, i, &ai, &k, &z);
  run_slot *u = &r->runs[i];
  double t0 = aq_suite_now_s();
  double scale = aq_scale_for_arch(&S->rule, S->lambda0[ai], r->scale[k]);
  double sa = aq_scale_signed(scale, aq_suite_reversed(S, k)), pga_g = 0;
  int steps_failed = 0, ran = 0;
  aq_status rs = AQ_OK;
  if (aq_scale_per_arch(&S->rule) && !st[ai])
    ; /* the arch's own failure is reported below */
  else if ((rs = aq_scale_check_arch(&S->rule, c->arch_paths[ai], S->lambda0[ai], scale,
                                     &u->err)) != AQ_OK)
    steps_failed = 1;
  else
    rs = aq_runs_run(&r->plan, k, r->motion ? c->azimuths_deg[z] : 0.0, sa, st[ai], &u->res,
                     &pga_g, &steps_failed, &ran, &u->err);
  const char *stage = "run";
  if (steps_failed) {
    stage = "process";
  } else if (!st[ai]) {
    rs = S->arch_err[ai].status != AQ_OK ? S->arch_err[ai].status : AQ_EINTERNAL;
    u->err = S->arch_err[ai];
    stage = "arch";
  }
  u->have_res = ran;
  char status[AQ_SUMMARY_STATUS_MAX];
  aq_summary_status(status, sizeof status, stage, rs);
  u->failed = rs != AQ_OK;
  if (u->failed && u->have_res) {
    aq_result_free(&u->res);
    u->have_res = 0;
  }
  aq_summary_fill(&u->sum, c->records[r->index], aq_arch_name(S->arches[ai]),
                  S->model_name, scale, pga_g, status,
                  u->have_res ? &u->res : NULL);
  aq_summary_normalise(&u->sum, slot_polarity(S, k), u->have_res ? &u->res : NULL,
                       aq_arch_path(S->arches[ai], 0), aq_arch_path(S->arches[ai], 1));
  u->sum.azimuth_deg = run_azimuth(S, r, z);
  snprintf(u->sum.control, sizeof u->sum.control, "%s",
           aq_hinge_control_names[aq_arch_control(S->arches[ai])]);
  aq_summary_mark(&u->sum, aq_arch_friction(S->arches[ai]),
                  aq_arch_control(S->arches[ai]) == AQ_CONTROL_FREE);
  if (c->check_blocks && u->have_res && strcmp(u->sum.status, "ok") != 0)
    check_blocks(S, r, k, r->motion ? c->azimuths_deg[z] : 0.0, sa, ai, u);
  u->run_s = aq_suite_now_s() - t0;
}

/* A stepper for arch a with the suite's settings, or NULL (err filled). */
aq_stepper *aq_suite_stepper(const suite *S, size_t a, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  if (c->model == AQ_MODEL_BLOCKS)
    return aq_job_stepper_blocks(S->arches[a], c->blocks_dt_s, c->history, err);
  return aq_job_stepper(S->arches[a], c->model, c->cor, c->history, 1, err);
}

/* Arches: loaded once, every bad one reported; nothing runs if any is.
 * One name, one arch: rows are labelled and compared by name.  An option
 * that cannot act on an arch is refused, not ignored. */
int aq_suite_arches(suite *S)
{
  const aq_suite_cfg *c = S->cfg;
  int rc = AQ_EXIT_OK;
  int bad_arch = 0;
  for (size_t a = 0; a < c->narches; a++) {
    aq_error e;
    aq_error_clear(&e);
    aq_arch_options ao = {.friction = c->friction, .friction_table = 1};
    if (aq_arch_cache_load(c->arch_cache, c->arch_paths[a], &ao, NULL, &S->arches[a], &e) !=
        AQ_OK) {
      aq_error_print(&e, stderr);
      bad_arch = 1;
    }
  }
  for (size_t a = 0; !bad_arch && a < c->narches; a++) {
    if (strlen(aq_arch_name(S->arches[a])) >= AQ_SUMMARY_ARCH_MAX) { /* stored whole or not */
      fprintf(stderr, "archquake: %s: name: expected at most %d bytes (the results' arch "
                      "field), got %zu\n",
              c->arch_paths[a], AQ_SUMMARY_ARCH_MAX - 1, strlen(aq_arch_name(S->arches[a])));
      bad_arch = 1;
      break;
    }
    for (size_t b = 0; b < a; b++)
      if (strcmp(aq_arch_name(S->arches[a]), aq_arch_name(S->arches[b])) == 0) {
        fprintf(stderr, "archquake: %s: name: expected a name unlike the other arches', "
                        "got \"%s\", the name of %s too\n",
                c->arch_paths[a], aq_arch_name(S->arches[a]), c->arch_paths[b]);
        bad_arch = 1;
        break;
      }
    aq_mechanism_warn_minimum(c->arch_paths[a], S->arches[a]);
    int blocks = c->model == AQ_MODEL_BLOCKS || c->check_blocks;
    if (aq_opt_blocks_spread(c->arch_paths[a], blocks, S->arches[a]))
      bad_arch = 1; /* the spread's refusal alone, not its warning too */
    else
      aq_opt_spread_four_hinge(c->arch_paths[a], c->model != AQ_MODEL_BLOCKS,
                               aq_arch_spread(S->arches[a]));
    aq_opt_friction_paper(c->arch_paths[a], c->model == AQ_MODEL_PAPER,
                          aq_arch_friction(S->arches[a]), 1);
    bad_arch |= aq_opt_blocks_friction(c->arch_paths[a], blocks,
                                       aq_arch_friction(S->arches[a]));
    bad_arch |= aq_opt_cor_momentum(c->arch_paths[a], !isnan(c->cor),
                                    aq_arch_dynamics_of(S->arches[a])->impact ==
                                        AQ_IMPACT_MOMENTUM);
  }
  if (bad_arch)
    return AQ_EXIT_USAGE;
  for (size_t a = 0; a < c->narches; a++)
    S->lambda0[a] = aq_lambda0(S->arches[a]);
  /* An arch whose stepper cannot be made (no admissible mechanism...) is
   * reported once; its runs fail. */
  for (size_t a = 0; a < c->narches; a++) {
    aq_error_clear(&S->arch_err[a]);
    aq_stepper *st = aq_suite_stepper(S, a, &S->arch_err[a]);
    S->arch_ok[a] = st != NULL;
    if (!st) {
      char msg[1200];
      aq_error_format(&S->arch_err[a], msg, sizeof msg);
      fprintf(stderr, "archquake: %s: arch %s cannot run: %s\n", c->arch_paths[a],
              aq_arch_name(S->arches[a]), msg);
      rc = AQ_EXIT_FAIL;
    }
    aq_stepper_free(st);
  }

  return rc;
}

/* The records of cfg (every channel of a multi-channel file a record of its
 * own, FILE#CH) into *names (*n), with cfg->motions each one's motion in
 * *mo (NULL without motions). */
aq_status aq_suite_names(const aq_suite_cfg *cfg, char ***names_out, size_t *n_out,
                         const aq_orient_motion ***mo_out, char ***notes, size_t *nnotes,
                         aq_error *err)
{
  *notes = NULL;
  *nnotes = 0;
  char **names = NULL;
  size_t n = 0;
  const aq_orient_motion **mo = NULL;
  aq_status st = AQ_OK;
  if (!cfg->motions) {
    st = aq_job_names(cfg->records, cfg->nrecords, &cfg->read, cfg->threads, &names, &n, notes,
                      nnotes, err);
  } else { /* plain records expanded one by one, motions kept beside them */
    for (size_t i = 0; st == AQ_OK && i < cfg->nrecords; i++) {
      char **one = NULL;
      size_t k = 1;
      if (cfg->motions[i]) {
        one = malloc(sizeof *one);
        if (one && !(one[0] = strdup(cfg->records[i]))) {
          free(one);
          one = NULL;
        }
        st = one ? AQ_OK : aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
      } else {
        char **nt = NULL, **g;
        size_t nn = 0;
        st = aq_record_expand_horizontal(cfg->records + i, 1, &cfg->read, &one, &k, &nt, &nn, err);
        g = nn ? realloc(*notes, (*nnotes + nn) * sizeof *g) : *notes;
        if (nn && g) { /* the verticals left out of this file */
          memcpy(g + *nnotes, nt, nn * sizeof *g);
          *notes = g;
          *nnotes += nn;
          free(nt);
        } else {
          aq_record_names_free(nt, nn);
        }
      }
      char **nn = st == AQ_OK ? realloc(names, (n + k) * sizeof *nn) : NULL;
      const aq_orient_motion **nm = nn ? realloc(mo, (n + k) * sizeof *nm) : NULL;
      if (nn)
        names = nn;
      if (nm)
        mo = nm;
      if (st == AQ_OK && (!nn || !nm)) {
        aq_record_names_free(one, k);
        st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        break;
      }
      for (size_t j = 0; st == AQ_OK && j < k; j++) {
        names[n + j] = one[j];
        mo[n + j] = cfg->motions[i];
      }
      if (st == AQ_OK) {
        free(one);
        n += k;
      }
    }
  }
  /* a record's name is stored whole or not at all: refused before any run
   * when it does not fit the results' record fields */
  for (size_t i = 0; st == AQ_OK && i < n; i++)
    if (strlen(names[i]) >= AQ_SUMMARY_RECORD_MAX)
      st = aq_error_set(err, AQ_EVALUE, names[i], -1, -1, "record name",
                        "expected at most %d bytes (the results' record and source_file "
                        "fields), got %zu: run it from a shorter path",
                        AQ_SUMMARY_RECORD_MAX - 1, strlen(names[i]));
  *names_out = names;
  *n_out = n;
  *mo_out = mo;
  return st;
}
