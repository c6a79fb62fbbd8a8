/* text_capacity.h: the TSV tables of `archquake capacity` (docs/capacity.md):
 * one row per (record, arch, polarity), and one per (arch, intensity
 * measure) of fragility fits.  Numbers as the text writer prints them
 * (%.17g, nan, inf).  The caller owns the FILE and the rows; both functions
 * return 0, or -1 if a write failed. */
#ifndef AQ_REPORT_TEXT_CAPACITY_H
#define AQ_REPORT_TEXT_CAPACITY_H

#include <stddef.h>
#include <stdio.h>

#include "../capacity/capacity.h"

/* One (record, arch, polarity) as the report writers (text, HDF5) see it. */
typedef struct {
  const char *record, *arch, *polarity; /* as written */
  const char *status;    /* "ok", "never_moves", "read:eio", "run:enumeric", ... */
  const aq_capacity *cap;/* the results, or NULL when there are none */
  double pga_g, pgv_mps; /* the record's PGA (g) and PGV (m/s) at scale 1 */
  const aq_im *im;       /* its measures at scale 1 (NULL: unread) for the
                            fragility IMs of first collapse and cap */
} aq_capacity_row;

/* One fit of one arch and intensity measure. */
typedef struct {
  const char *arch, *im;
  const aq_fragility *fit;
} aq_fragility_row;

int aq_text_capacity(FILE *f, const aq_capacity_row *rows, size_t n);
int aq_text_fragility(FILE *f, const aq_fragility_row *rows, size_t n);

/* The collapse intervals as "lo-hi;lo-hi" ("-" when none) into buf[n]. */
void aq_text_capacity_intervals(const aq_scan_result *s, char *buf, size_t n);

#endif
