/* text_capacity.h: the TSV tables of `archquake capacity` (docs/capacity.md):
 * one row per (record, arch, polarity), and one per (arch, intensity
 * measure) of fragility fits.  Numbers as the text writer prints them
 * (aq_text_double: the shortest that reads back, nan, inf).  The caller owns the FILE and the rows;
 * both functions return 0, or -1 if a write failed. */
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
  int oriented;          /* 1: three more columns (the same for every row) */
  double azimuth_deg;    /* the arch azimuth of the row (NAN: a plain record) */
  double fcs_min, fcs_max; /* first_collapse_scale's range over the azimuths */
} aq_capacity_row;

/* One fit of one arch and intensity measure. */
typedef struct {
  const char *arch, *im;
  const aq_fragility *fit;
} aq_fragility_row;

/* What a fit's rank orders: its beta over the power of the scale its IM
 * grows with (aq_fragility_im_power: 2 for arias_m_s, 1 for the others,
 * spectral ones included); NAN without a fit. */
double aq_fragility_row_ranked(const char *im, double beta);

/* With rows[0].oriented the columns azimuth_deg, first_collapse_scale_min
 * and first_collapse_scale_max follow scale_max. */
int aq_text_capacity(FILE *f, const aq_capacity_row *rows, size_t n);
int aq_text_fragility(FILE *f, const aq_fragility_row *rows, size_t n);

/* The collapse intervals as "lo-hi;lo-hi" ("-" when none) into buf[n]. */
void aq_text_capacity_intervals(const aq_scan_result *s, char *buf, size_t n);

#endif
