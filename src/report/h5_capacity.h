/* h5_capacity.h: the `capacity` group of a results file (layout in
 * docs/capacity.md): per (record, arch, polarity) the results of
 * src/capacity with their collapse intervals, and the fragility fits.
 * Written into a file opened by aq_h5_open (after aq_h5_write_root), before
 * aq_h5_finish, which renames it onto the target; so the file appears
 * complete or not at all.  Reports through aq_error; the caller keeps
 * ownership of everything passed. */
#ifndef AQ_REPORT_H5_CAPACITY_H
#define AQ_REPORT_H5_CAPACITY_H

#include <stddef.h>

#include "../capacity/capacity.h"
#include "h5.h"

typedef struct {
  size_t npair;
  const char *const *record;   /* npair record paths */
  const char *const *arch;     /* arch names */
  const char *const *polarity; /* "normal" | "reversed" */
  const char *const *status;   /* "ok", "never_moves", "read:eio", ... */
  const aq_capacity *cap;      /* npair results */
  const int *valid;            /* 1 where cap[i] holds results (the record was read) */
  const double *pga_g;         /* the record's PGA at scale 1, g (NAN if unread) */
  const double *pgv_mps;       /* its PGV, m/s */
  size_t nfit;
  const char *const *fit_arch; /* nfit arch names */
  const char *const *fit_im;   /* intensity measure names */
  const aq_fragility *fit;
  double resolution, tol, ci;  /* the options used */
} aq_h5_capacity;

aq_status aq_h5_write_capacity(aq_h5_writer *w, const char *target,
                               const aq_h5_capacity *c, aq_error *err);

#endif
