/* capacity_tasks.h: the capacity command's work as tasks, one per (subject,
 * arch) with every polarity and azimuth of it, run here on threads or
 * farmed out to other processes (archquake-mpi, src/app/mpi.c).
 *
 * A process that runs a task reads and processes its subject itself, once:
 * archquake prepares every subject before the tasks run; farmed, every
 * task goes out at once, the leader prepares a subject when it runs a task
 * of it or the first result of it comes (and keeps it, for its outputs),
 * and a follower prepares one when a task of it comes and keeps the last
 * few for the next tasks of the same subject (both through job/cache.h,
 * the main job's farm's cache too).  Results
 * travel as aq_capacity_encode's bytes, so the leader's copy is bit for bit
 * the follower's.  The caller owns every array it passes in. */
#ifndef AQ_APP_CAPACITY_TASKS_H
#define AQ_APP_CAPACITY_TASKS_H

#include <stddef.h>

#include "../capacity/capacity.h"
#include "../error.h"
#include "farm.h"
#include "opt_orient.h"

/* ---- the capacity tasks ------------------------------------------------- */

/* A subject (record or ground motion) as read and processed (job/subject.h)
 * with its view at each azimuth and their intensity measures, or the stage
 * where it failed (status, err). */
typedef struct {
  aq_subject subj;   /* metadata once its views are made */
  size_t naz;        /* views: one per azimuth (1 for a record) */
  aq_view *view;
  aq_im *im;         /* per view: the measures of its in-plane series */
  char status[48];
  int ok;
  aq_error err;
} aq_cap_item;

/* Free what an item holds (a zeroed item is fine). */
void aq_cap_item_free(aq_cap_item *it);

/* What every task shares, read-only. */
typedef struct {
  size_t nrec;
  char *const *labels;           /* per subject: its name (a motion's label) */
  const char *const (*paths)[3]; /* per subject: its files (read by aq_cap_prepare) */
  const double (*phi_deg)[2];    /* per subject: its components' azimuths, or NAN */
  const aq_orient_opts *orient;
  const aq_read_opts *ro;
  const aq_signal_opts *po;
  int polarity;                  /* --polarity (opt.h) */
  const int *pols;               /* the npol polarities run */
  size_t npol;
  size_t nz;                     /* result slots per (subject, arch, polarity) */
  aq_arch *const *arches;
  size_t na;
  aq_model model;
  double blocks_dt_s;            /* --blocks-dt */
  double cor;                    /* --cor, or NAN */
  double merge_tol_mps2;
  double scale_max;              /* --scale-max, or NAN */
  aq_scan_opts scan;
  const double *factor;          /* --suite: per subject, its suite scale (the
                                    subject's factor 1 is the suite's); NULL: none */
} aq_cap_setup;

/* Read, process and project subject r into *it (errors printed on stderr,
 * one line, and kept in it->err). */
void aq_cap_prepare(const aq_cap_setup *S, size_t r, aq_signal_ws *ws, aq_cap_item *it);

/* Leader or archquake: prepare R[0..nrec) (nrec zeroed items; the caller
 * frees them) and run the tasks of every subject that was read, on
 * threads threads here or farmed out, into
 * C[((r na + a) npol + p) nz + z] (zeroed by the caller; slots of azimuths a
 * subject lacks stay zero).  Follower: run the tasks handed out, preparing
 * their subjects as they come (job/cache.h keeps the last few; R is not
 * touched); C is NULL.  Returns 0, or -1 (a line on stderr): out of memory or the
 * exchange failed, and nothing may be written. */
int aq_cap_run(const aq_cap_setup *S, aq_cap_item *R, aq_capacity *C, long threads);

#endif
