/* raw_tmp.h: the reader interface (aq_raw_file) until io/readers.h carries
 * it; it is removed when that header does.  See readers.h for the meaning
 * of every field. */
#ifndef AQ_IO_RAW_TMP_H
#define AQ_IO_RAW_TMP_H

#include <stddef.h>

/* One channel (component) as the file states it.  Values are as stored. */
typedef struct {
  char channel[16];       /* the file's own name for it, "" if none */
  double azimuth_deg;     /* direction of positive motion, deg from north; NAN if not stated */
  double dip_deg;         /* SEED: 0 horizontal, -90 up, +90 down; NAN if not stated */
  int vertical;           /* 1 vertical, 0 horizontal, -1 the file does not say */
  size_t npts;
  double dt_s;            /* > 0 */
  double begin_s;         /* time of sample 0 after reference, s */
  char reference[40];     /* ISO-8601 UTC, "" if unknown */
  char units[24];         /* units the file states, "" if none */
  double counts_per_mps2; /* for "counts": stated sensitivity, counts per m/s^2; 0 if none */
  char network[16], station[16], location[16];
  double *values;         /* npts values as stored (owned) */
} aq_raw_channel;

typedef struct {
  char format[16];
  char event[96];
  char processing[160];
  size_t nchan;
  aq_raw_channel *chan;
} aq_raw_file;

void aq_raw_file_free(aq_raw_file *raw);

#endif
