/* subject.c: a record or a ground motion read, checked and processed once,
 * and its views (subject.h). */
#define _POSIX_C_SOURCE 200809L
#include "subject.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../signal/project.h"
#include "subject_cache.h"
#include "../units.h"

/* The room of a vertical's path in the warning: whole up to 460 bytes,
 * else "..." and its end, the file's name whole (NAME_MAX, 255, fits). */
#define AQ_SUBJECT_WARNING_PATH 460

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Read component j (have_rec[j] set on success); a horizontal one must not
 * be identified as vertical.  With keep, the file's bytes as the reader
 * read them. */
static aq_status read_component(aq_subject *s, int j, const char *path, int horizontal,
                                const aq_read_opts *ro, int keep, aq_error *err)
{
  aq_record *rec = &s->rec[j];
  aq_status st = keep ? aq_record_read_keep(path, ro, rec, &s->bytes, &s->nbytes, err)
                      : aq_record_read(path, ro, rec, err);
  if (st == AQ_OK && horizontal && (st = aq_record_check_horizontal(rec, ro, err)) != AQ_OK)
    aq_record_free(rec);
  s->have_rec[j] = st == AQ_OK;
  return st;
}

/* A motion's other components read beside the first: azimuths, orthogonal,
 * aligned, cut to the samples they share. */
static aq_status read_motion(aq_subject *s, const aq_subject_src *src,
                             const aq_subject_opts *o, aq_error *err)
{
  aq_status st = read_component(s, 1, src->path[1], 1, o->read, 0, err);
  if (st != AQ_OK)
    return st;
  s->run_v = src->path[2] && o->vertical;
  if (s->run_v && (st = read_component(s, 2, src->path[2], 0, o->read, 0, err)) != AQ_OK)
    return st;
  const aq_record *all[3] = {&s->rec[0], &s->rec[1], &s->rec[2]};
  size_t nc = s->run_v ? 3 : 2;
  for (int j = 0; j < 2; j++)
    s->phi_deg[j] = isfinite(src->azimuth_deg[j]) ? src->azimuth_deg[j]
                                                  : aq_project_azimuth_of(all[j]);
  st = aq_project_check_pair(src->label, s->phi_deg, err);
  if (st == AQ_OK)
    st = aq_project_check_aligned(all, nc, err);
  if (st != AQ_OK)
    return st;
  size_t npts = aq_project_common_npts(all, nc);
  for (size_t j = 0; j < nc; j++)
    s->rec[j].npts = npts;
  if (src->path[2] && !s->run_v) {
    s->v_ignored = 1;
    char path[AQ_SUBJECT_WARNING_PATH + 1];
    aq_text_fit(s->warning, sizeof s->warning, "vertical component %s ignored (--vertical runs it)",
                aq_path_fit(src->path[2], AQ_SUBJECT_WARNING_PATH, path, sizeof path));
  }
  return AQ_OK;
}

/* Process component j; its samples as read are freed (the processed copy is
 * all that is needed now). */
static aq_status process_component(aq_subject *s, int j, const aq_signal_opts *o,
                                   aq_signal_ws *ws, aq_error *err)
{
  aq_signal_opts po = *o;
  po.scale = 1.0;
  aq_status st = aq_signal_process(&s->rec[j], &po, ws, &s->proc[j], err);
  s->have_proc[j] = st == AQ_OK;
  free(s->rec[j].acc_mps2);
  s->rec[j].acc_mps2 = NULL;
  return st;
}

/* aq_subject_prepare without the cache. */
static aq_status prepare(aq_subject *s, const aq_subject_src *src, const aq_subject_opts *o,
                         aq_signal_ws *ws, aq_error *err)
{
  memset(s, 0, sizeof *s);
  s->motion = src->path[1] != NULL;
  s->stage = "read";
  double t0 = now_s();
  int horizontal = s->motion || !o->any_channel;
  aq_status st =
      read_component(s, 0, src->path[0], horizontal, o->read, o->keep_bytes_max > 0, err);
  if (s->bytes && s->nbytes > o->keep_bytes_max) { /* the caller reads it again to hash it */
    free(s->bytes);
    s->bytes = NULL;
    s->nbytes = 0;
  }
  if (st == AQ_OK && s->motion)
    st = read_motion(s, src, o, err);
  double t1 = now_s();
  s->read_s = t1 - t0;
  if (st != AQ_OK)
    return st;
  s->stage = "process";
  int nc = s->motion ? 2 + s->run_v : 1;
  for (int j = 0; st == AQ_OK && j < nc; j++)
    st = process_component(s, j, o->proc, ws, err);
  for (int j = 1; st == AQ_OK && j < nc; j++)
    if (s->proc[j].n != s->proc[0].n || s->proc[j].pad_front != s->proc[0].pad_front)
      st = aq_error_set(err, AQ_EINTERNAL, src->label ? src->label : src->path[0], -1, -1,
                        NULL, "the components' processed lengths differ (%zu, %zu samples)",
                        s->proc[0].n, s->proc[j].n);
  if (st == AQ_OK)
    st = aq_im_compute(&s->proc[0], &s->im, err);
  if (st == AQ_OK) {
    s->have_im = 1;
    if (!s->warning[0])
      aq_im_residual_warning(&s->im, s->warning, sizeof s->warning);
    s->pga_g = s->motion ? aq_project_peak_horizontal(s->proc[0].acc_mps2,
                                                      s->proc[1].acc_mps2, s->proc[0].n) /
                               AQ_G0_MPS2
                         : s->im.pga_g;
  }
  s->process_s = now_s() - t1;
  return st;
}

aq_status aq_subject_prepare(aq_subject *s, const aq_subject_src *src,
                             const aq_subject_opts *o, aq_signal_ws *ws, aq_error *err)
{
  aq_subject_key k;
  double t0 = now_s();
  if (!o->cache || !aq_subject_cache_key(src, o, &k))
    return prepare(s, src, o, ws, err);
  double t1 = now_s();
  aq_status st = AQ_OK;
  if (aq_subject_cache_get(o->cache, &k, s)) {
    s->read_s = t1 - t0;
    s->process_s = now_s() - t1;
  } else {
    aq_subject_opts once = *o; /* the key hashed the bytes already */
    once.keep_bytes_max = 0;
    if ((st = prepare(s, src, &once, ws, err)) == AQ_OK)
      aq_subject_cache_put(o->cache, &k, s);
  }
  if (st == AQ_OK) { /* hashed already: the caller need not hash the bytes */
    memcpy(s->sha256, k.sha256[0], sizeof s->sha256);
    free(s->bytes);
    s->bytes = NULL;
    s->nbytes = 0;
  }
  aq_subject_key_free(&k);
  return st;
}

size_t aq_subject_n(const aq_subject *s)
{
  return s->have_proc[0] ? s->proc[0].n : 0;
}

aq_status aq_subject_scale(aq_subject *s, double f, aq_error *err)
{
  for (int j = 0; j < 3; j++)
    for (size_t i = 0; s->have_proc[j] && s->proc[j].acc_mps2 && i < s->proc[j].n; i++)
      s->proc[j].acc_mps2[i] *= f;
  s->pga_g *= f;
  return s->have_im ? aq_im_compute(&s->proc[0], &s->im, err) : AQ_OK;
}

void aq_subject_shed(aq_subject *s)
{
  for (int j = 0; j < 3; j++) {
    free(s->proc[j].acc_mps2);
    s->proc[j].acc_mps2 = NULL; /* the metadata stays */
  }
}

void aq_subject_free(aq_subject *s)
{
  for (int j = 0; j < 3; j++) {
    aq_record_free(&s->rec[j]);
    aq_processed_free(&s->proc[j]);
  }
  free(s->bytes);
  memset(s, 0, sizeof *s);
}

aq_status aq_subject_steps(const aq_subject *s, double theta_deg, double sa, double sv,
                           double merge_tol_mps2, aq_steps *out, double *peak_mps2,
                           aq_error *err)
{
  const aq_processed *p = &s->proc[0];
  double c[2] = {1.0, 0.0};
  *peak_mps2 = 0;
  if (s->motion)
    aq_project_coefs(theta_deg, s->phi_deg, c);
  return aq_steps_project_v(p->acc_mps2, c[0], s->motion ? s->proc[1].acc_mps2 : NULL, c[1],
                            sa, s->run_v ? s->proc[2].acc_mps2 : NULL, sv, p->n, p->dt_s,
                            -(double)p->pad_front * p->dt_s, merge_tol_mps2, out,
                            peak_mps2, err);
}

aq_status aq_view_make(aq_view *v, const aq_subject *s, double theta_deg, aq_error *err)
{
  memset(v, 0, sizeof *v);
  const aq_processed *p = &s->proc[0];
  v->dt_s = p->dt_s;
  v->t0_s = -(double)p->pad_front * p->dt_s;
  aq_status st =
      s->motion || s->run_v
          ? aq_subject_steps(s, theta_deg, 1.0, 1.0, 0, &v->steps, &v->peak_mps2, err)
          : aq_steps_over(p->acc_mps2, p->n, p->dt_s, v->t0_s, &v->steps, &v->peak_mps2, err);
  v->at = *p;
  v->at.acc_mps2 = st == AQ_OK ? v->steps.a_mps2 : NULL;
  return st;
}

aq_status aq_view_steps(const aq_view *v, double sa, double sv, double merge_tol_mps2,
                        aq_steps *out, aq_error *err)
{
  double peak;
  return aq_steps_project_v(v->steps.a_mps2, 1.0, NULL, 0.0, sa, v->steps.av_mps2, sv,
                            v->steps.n, v->dt_s, v->t0_s, merge_tol_mps2, out, &peak, err);
}

void aq_view_free(aq_view *v)
{
  aq_steps_free(&v->steps);
  memset(v, 0, sizeof *v);
}
