/* record.h: the in-memory accelerogram, and the reader entry point.
 *
 * Every reader (sac.c, at2.c, csv.c) produces an aq_record: evenly sampled
 * ground acceleration in m/s^2, dt in s.  The record owns its arrays and
 * strings; aq_record_free() releases them (NULL and zeroed records are fine).
 * Readers report through aq_error and never print.
 */
#ifndef AQ_IO_RECORD_H
#define AQ_IO_RECORD_H

#include <stddef.h>

#include "../error.h"

typedef struct {
  char *path;           /* file as given on the command line */
  char *name;           /* short name: file name without directories */
  char format[16];      /* "sac-le", "sac-be", "at2", "csv" */
  size_t npts;          /* number of samples */
  double dt_s;          /* sample interval, s (> 0) */
  double begin_s;       /* time of sample 0 relative to the reference time, s (SAC B; 0 if unknown) */
  char reference[40];   /* ISO-8601 UTC reference time ("" if unknown) */
  char network[16], station[16], location[16], channel[16]; /* "" if unknown */
  char units_orig[24];  /* units of the file's values: "g", "gal", "m/s2", "nm/s2", "counts", ... */
  double to_mps2;       /* factor applied to the file's values to get m/s^2 */
  double *acc_mps2;     /* npts samples of ground acceleration, m/s^2 */
} aq_record;

/* Units override (--units).  AQ_UNITS_FILE: take the units from the file. */
typedef enum {
  AQ_UNITS_FILE = 0,
  AQ_UNITS_G,
  AQ_UNITS_GAL,   /* = cm/s^2 */
  AQ_UNITS_MPS2,
  AQ_UNITS_NMPS2,
  AQ_UNITS_COUNTS /* divided by the sensitivity (SAC SCALE, counts per m/s^2) */
} aq_units;

/* Reader options.  Zero-initialised means: units from the file, no dt. */
typedef struct {
  aq_units units; /* override, or AQ_UNITS_FILE */
  double dt_s;    /* --dt for single-column text; 0 = not given */
} aq_read_opts;

/* Read the file at path, detecting its format from its content.
 * On success fills *rec (caller frees with aq_record_free) and returns AQ_OK;
 * on failure *rec is left empty and err says where and why. */
aq_status aq_record_read(const char *path, const aq_read_opts *opts,
                         aq_record *rec, aq_error *err);

void aq_record_free(aq_record *rec);

#endif
