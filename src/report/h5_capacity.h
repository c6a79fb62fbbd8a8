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
#include <stdint.h>

#include "../capacity/capacity.h"
#include "h5.h"
#include "text_capacity.h"

typedef struct {
  const aq_capacity_row *row;   /* one per (record, arch, polarity) */
  size_t npair;
  const aq_fragility_row *fit;  /* one per (arch, intensity measure) */
  size_t nfit;
  double resolution, tol, ci;   /* the options used */
  size_t nspectral;             /* the spectral measures fitted after the six, */
  const char *const *spectral;  /* their names (aq_im_spectral_name), nspectral */
} aq_h5_capacity;

aq_status aq_h5_write_capacity(aq_h5_writer *w, const char *target,
                               const aq_h5_capacity *c, aq_error *err);

/* ---- reading back and comparing (archquake compare) ---------------------- */

enum { AQ_H5_CAP_NDOUBLE = 7, AQ_H5_CAP_NINT = 4 };
/* The most intensity measures a row holds: the six of the fits, then the
 * spectral ones (Sa(T) at each period, Sa_avg). */
enum { AQ_H5_CAP_NIM_MAX = AQ_FRAGILITY_NIM + AQ_IM_SA_MAX + 1 };
/* Names of the numeric columns, in the order of aq_h5_capacity_row. */
extern const char *const aq_h5_capacity_double_names[AQ_H5_CAP_NDOUBLE];
extern const char *const aq_h5_capacity_int_names[AQ_H5_CAP_NINT];

typedef struct {
  char record[AQ_SUMMARY_RECORD_MAX], arch[AQ_SUMMARY_ARCH_MAX], polarity[16], status[48];
  double d[AQ_H5_CAP_NDOUBLE]; /* move_scale first_collapse_scale first_collapse_pga_g
                                  first_collapse_pgv_m_s scale_max lambda0
                                  first_mark_scale (NAN in files written before it) */
  int64_t i[AQ_H5_CAP_NINT];   /* resurrection runs interval_start interval_count */
  /* the fragility IMs (the table's im_name: aq_fragility_im_names, then the
     spectral ones) at first collapse (NAN: none) and at the cap; NAN when
     the file does not hold them */
  double im_first[AQ_H5_CAP_NIM_MAX], im_cap[AQ_H5_CAP_NIM_MAX];
  size_t point_start, point_count; /* its rows of the table's point[] */
} aq_h5_capacity_row;

/* One fit of capacity/fragility. */
typedef struct {
  char arch[AQ_SUMMARY_ARCH_MAX], im[32];
  double median, beta, median_lo, median_hi;
  int64_t records, censored;
  int64_t rank;          /* 1 for the arch's best measure; 0 unfitted (or not in the file) */
  double beta_per_power; /* what rank orders: beta over the IM's power of the scale */
  int64_t marked;        /* records whose row is marked; -1 in a file written before it */
} aq_h5_fragility_fit;

typedef struct {
  size_t n;
  aq_h5_capacity_row *row; /* malloc'd */
  size_t ninterval;
  double *interval;        /* 2 per interval (lo, hi), malloc'd */
  size_t nfit;
  aq_h5_fragility_fit *fit; /* malloc'd; none when the file has no fits */
  int have_points;          /* 1: the file holds capacity/scan_points */
  size_t npoint;
  aq_capacity_point *point; /* malloc'd: every scanned scale, by row then scale */
  char peaks[16];           /* the root's peaks attribute (where the spectral
                               measures' peaks were taken), "" if none */
  size_t nim;               /* columns of the rows' im_first and im_cap: the six
                               of aq_fragility_im_names, then the spectral
                               measures (files written before them: 6) */
  char im_name[AQ_H5_CAP_NIM_MAX][32];
} aq_h5_capacity_table;

/* Read the capacity group of the results file at path into *t (free with
 * aq_h5_capacity_table_free); a file written before scan_points reads with
 * have_points = 0 and no points.  Returns AQ_OK, with t->n = 0 and
 * *present = 0 when the file has no capacity group; AQ_EFORMAT/AQ_EIO (err
 * filled) when it cannot be read. */
aq_status aq_h5_capacity_read(const char *path, aq_h5_capacity_table *t, int *present,
                              aq_error *err);
void aq_h5_capacity_table_free(aq_h5_capacity_table *t);

/* One difference between two capacity tables: rows are matched by (record,
 * arch, polarity) in order; numbers agree as aq_compare_close; status and
 * the integer columns exactly; intervals pairwise (field "interval_lo[k]"
 * or "interval_hi[k]"); when both files hold capacity/scan_points, each
 * row's points pairwise ("scan_points" for a different count, else
 * "scan_point[k].FIELD").  a or b NULL: the row is in one table only. */
typedef struct {
  const aq_h5_capacity_row *a, *b;
  const char *field; /* NULL for a row in one table only */
  char a_text[40], b_text[40];
  double rel;
} aq_h5_capacity_diff;

typedef void (*aq_h5_capacity_diff_fn)(void *ctx, const aq_h5_capacity_diff *d);

/* Returns the number of differences (fn, which may be NULL, gets each). */
size_t aq_h5_capacity_compare(const aq_h5_capacity_table *a,
                              const aq_h5_capacity_table *b, double rtol, double atol,
                              aq_h5_capacity_diff_fn fn, void *ctx);

#endif
