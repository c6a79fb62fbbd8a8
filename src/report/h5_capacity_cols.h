/* h5_capacity_cols.h: what the writer of the `capacity` group
 * (h5_capacity.c) shares with its reader (h5_capacity_read.c): the scan
 * points' columns, and the short names of the rows' numeric columns;
 * internal to src/report.
 */
#ifndef AQ_REPORT_H5_CAPACITY_COLS_H
#define AQ_REPORT_H5_CAPACITY_COLS_H

#include <stdint.h>

#include "h5_capacity.h"
#include "h5_table.h"

/* capacity/scan_points: one row per run of the scans, by pair then scale.
 * The fields with their units (a units_<field> attribute each). */
typedef struct {
  int64_t pair;
  double scale, peak_rotation_rad, peak_rotation_over_qc;
  int64_t collapsed;
  double collapse_time_s;
} h5_point;

static const aq_h5_col point_cols[] = {
    AQ_H5_COL(h5_point, pair, AQ_H5_INT, "1"),
    AQ_H5_COL(h5_point, scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(h5_point, peak_rotation_rad, AQ_H5_DOUBLE, "rad"),
    AQ_H5_COL(h5_point, peak_rotation_over_qc, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(h5_point, collapsed, AQ_H5_INT, "1"),
    AQ_H5_COL(h5_point, collapse_time_s, AQ_H5_DOUBLE, "s")};

enum { NPOINT_COLS = sizeof point_cols / sizeof point_cols[0] };

#define dnames aq_h5_capacity_double_names

#define inames aq_h5_capacity_int_names

#endif
