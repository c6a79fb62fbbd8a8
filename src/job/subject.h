/* subject.h: what a job runs: a record, or a ground motion of two
 * horizontal components and optionally the vertical, read once, checked,
 * processed once (src/signal), measured (intensity measures of the first
 * component), and seen by an arch at an azimuth as a step list at factor 1
 * (a view) that every run at that azimuth shares.
 *
 * Reading: every component through aq_record_read; a horizontal one that
 * the file identifies as vertical is refused (aq_record_check_horizontal,
 * unless --accept-vertical; a plain record with opts.any_channel is not
 * checked).  A motion's azimuths come from the caller
 * (--azimuths) or the files (aq_project_azimuth_of), must be orthogonal,
 * and its components must share dt and start time; the samples they share
 * are kept.  Its vertical is read only when it is run (opts.vertical); one
 * given and not run is noted in warning.  A record's samples are freed once
 * processed (its metadata stays).
 *
 * With opts.cache, a subject prepared before with the same files, options
 * and build is read from the cache instead (subject_cache.h), and one
 * prepared here is stored there: the same subject either way.
 *
 * Units: m/s^2 and s inside; pga_g in g.  The subject owns everything in it
 * (aq_subject_free, also after a failure); views own their steps
 * (aq_view_free).  Nothing prints: failures fill an aq_error, and stage
 * says where ("read" or "process"). */
#ifndef AQ_JOB_SUBJECT_H
#define AQ_JOB_SUBJECT_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"
#include "../io/sha256.h"
#include "../signal/signal.h"
#include "../util/diskcache.h"

/* Where a subject comes from. */
typedef struct {
  const char *path[3];   /* the record (or H1), H2, V; NULL where none */
  double azimuth_deg[2]; /* H1's and H2's directions as given, deg; NAN: the files' */
  const char *label;     /* a motion's name in messages ("H1,H2[,V]") */
} aq_subject_src;

typedef struct {
  const aq_read_opts *read;
  const aq_signal_opts *proc; /* its scale is not applied: a subject is at factor 1 */
  int vertical;               /* --vertical: run a motion's V */
  size_t keep_bytes_max;      /* > 0: keep the first file's bytes (for its sha256)
                                 when it has at most this many */
  int any_channel;            /* 1: a plain record may be a channel the file
                                 identifies as vertical (spectra: not excitation
                                 of an arch) */
  aq_diskcache *cache;        /* prepared subjects on disk (subject_cache.h),
                                 or NULL: none */
} aq_subject_opts;

typedef struct {
  aq_record rec[3];     /* H1 (or the record), H2, V: metadata once processed */
  aq_processed proc[3];
  int have_rec[3], have_proc[3];
  int motion;           /* 1: two horizontal components */
  int run_v;            /* 1: its vertical is run */
  double phi_deg[2];    /* a motion's components' azimuths, deg */
  aq_im im;             /* intensity measures of proc[0] */
  int have_im;
  double pga_g;         /* the PGA a scaling rule divides, g: the record's, or
                           the peak of a motion's horizontal vector (the same
                           at every azimuth) */
  char warning[512];    /* "" or one sentence: a vertical not run (its path
                           cut, if need be, to "..." and its end, the file's
                           name whole), else residuals above PRISM's limits */
  int v_ignored;        /* 1: a vertical was given and is not run */
  const char *stage;    /* "read" or "process": where it failed */
  unsigned char *bytes; /* the first file's bytes (opts.keep_bytes_max), or NULL */
  size_t nbytes;
  char sha256[AQ_SHA256_HEX]; /* the first file's SHA-256 when the cache key
                                 hashed it (then no bytes are kept), else "" */
  double read_s, process_s; /* wall time, s */
} aq_subject;

/* Read and process the subject src into *s (zeroed first).  Returns AQ_OK,
 * or the failure (err, s->stage). */
aq_status aq_subject_prepare(aq_subject *s, const aq_subject_src *src,
                             const aq_subject_opts *opts, aq_signal_ws *ws, aq_error *err);

/* Multiply the prepared subject by f (> 0): every processed component (a
 * vertical too: it scales with the motion), the PGA and the intensity
 * measures (computed again from the scaled samples), so that the subject at
 * factor 1 is the record at f (capacity's --suite).  Before any view is
 * made.  Returns AQ_OK, or the measures' failure (err). */
aq_status aq_subject_scale(aq_subject *s, double f, aq_error *err);

/* Free the processed samples (what runs need, not what writing needs). */
void aq_subject_shed(aq_subject *s);

void aq_subject_free(aq_subject *s);

/* Samples of each processed component, pads included (0 before processing). */
size_t aq_subject_n(const aq_subject *s);

/* Steps of what an arch at azimuth theta_deg feels (a record: theta is
 * ignored): the in-plane series a_x = a1 cos(theta - phi1) + a2 cos(theta -
 * phi2) (src/signal/project.h) times sa (its sign the polarity), the
 * vertical times sv, split with merge_tol_mps2 (aq_steps_from_samples);
 * *peak_mps2 the peak |a| of the steps' samples.  Fills *out (aq_steps_free). */
aq_status aq_subject_steps(const aq_subject *s, double theta_deg, double sa, double sv,
                           double merge_tol_mps2, aq_steps *out, double *peak_mps2,
                           aq_error *err);

/* A view: the subject at one azimuth and factor 1, one step per sample
 * (steps.a_mps2 is the in-plane series, steps.av_mps2 the vertical when it
 * is run).  A run at factor sa gives sa to the stepper (aq_job_run_view):
 * the stepper forms sa a_i, the very product a list at factor sa holds, so
 * the results are those of a list made at that factor, bit for bit.
 * A plain record's view borrows the subject's processed samples (no copy:
 * aq_steps_over), so it must be freed before aq_subject_shed or
 * aq_subject_free; a motion's owns its projected series. */
typedef struct {
  aq_steps steps;
  double peak_mps2;  /* max |a_i| */
  double dt_s, t0_s; /* the series' sample interval and first time, s */
  aq_processed at;   /* the series as a processed record (acc_mps2 borrowed
                        from steps): for its intensity measures */
} aq_view;

aq_status aq_view_make(aq_view *v, const aq_subject *s, double theta_deg, aq_error *err);

/* Steps from the view's series times sa (the vertical times sv), merged
 * with merge_tol_mps2: as aq_subject_steps at the view's azimuth. */
aq_status aq_view_steps(const aq_view *v, double sa, double sv, double merge_tol_mps2,
                        aq_steps *out, aq_error *err);

void aq_view_free(aq_view *v);

#endif
