/* select_pool.h: the pool of `archquake select`: every member (a record,
 * or a --components pair) read and processed as the main job does
 * (job/subject.h), then its spectrum at the grid and at T = 0 by the
 * target's rule (select/pool.h), on threads, each member in its own slot.
 *
 * Spectra are kept on disk ("spectra" entries of the cache directory,
 * util/diskcache.h) under a key of everything they depend on: the prepared
 * subject's key (job/subject_cache.h: the files' SHA-256, the reading and
 * processing options, the libraries and build), the grid, the damping,
 * the peak convention and the pair rule, with the traces by which
 * members that are one recording are found (select/same.h).  A member
 * found there is neither read nor processed.
 *
 * Units: periods s, PSA m/s^2.  The pool owns its members' arrays
 * (aq_select_pool_free).  Nothing prints: a member that cannot be read,
 * processed or measured keeps its status and error for the caller. */
#ifndef AQ_APP_SELECT_POOL_H
#define AQ_APP_SELECT_POOL_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"
#include "../select/pool.h"
#include "../select/same.h"
#include "../signal/signal.h"
#include "../signal/spectrum.h"
#include "../util/diskcache.h"

typedef struct {
  const char *name;     /* the record (FILE, FILE#CH) or the pair's label "H1,H2" */
  const char *path[2];  /* the record or H1, and H2 (NULL for a record) */
  double azimuth_deg[2];/* --azimuths of a pair, or NAN */
  aq_status st;         /* AQ_OK: usable */
  aq_error err;
  int vertical;         /* 1: refused as a channel the file identifies as vertical */
  double *psa_mps2;     /* nper, at the grid */
  double psa0_mps2;     /* at T = 0 */
  char channel[32];     /* the record's channel, or the pair rule's name */
  char event[96];       /* the event as the file states it ("" none) */
  char event_key[96];   /* the event, as the rule --max-per-event compares it */
  double dt_s;
  size_t npts;          /* samples as read */
  int cached;           /* 1: its spectrum came from the disk cache */
  aq_same_trace trace[2]; /* its components' traces (select/same.h; n 0: none) */
} aq_select_member;

typedef struct {
  aq_select_member *m;
  size_t n;
  const double *periods_s; /* the grid (the caller's) */
  size_t nper;
  double damping;
  aq_pair_rule pair_rule;
  aq_spectrum_opts sopts;
  const aq_read_opts *read;
  const aq_signal_opts *proc;
  aq_diskcache *cache;  /* NULL: none */
} aq_select_pool;

/* The pool's operands ops[0..n) as files: a directory gives its regular
 * files (not those whose names begin with '.') in name order; a word that
 * names no file and holds a glob character gives its matches (none: an
 * error); anything else is kept as given (FILE#CH, or for the reader to
 * refuse).  *files (malloc'd names, *nfiles of them; free with
 * aq_record_names_free).  AQ_OK, AQ_EIO (a directory that cannot be read,
 * a glob matching nothing: err names it), AQ_ENOMEM. */
aq_status aq_select_pool_files(char *const *ops, size_t n, char ***files, size_t *nfiles,
                               aq_error *err);

/* Prepare every member of pool (members named, the rest set), on threads.
 * Returns AQ_OK (each member's own status says whether it is usable) or
 * AQ_ENOMEM (err). */
aq_status aq_select_pool_prepare(aq_select_pool *pool, long threads, aq_error *err);

void aq_select_pool_free(aq_select_pool *pool);

#endif
