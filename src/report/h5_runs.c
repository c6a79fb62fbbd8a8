/* h5_runs.c: /summary (one row per run: the run's summary, its indices
 * and the stepper's counters) and /histories (a run's histories, with
 * --history) of the results writer (h5.h, h5_writer.h). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5_writer.h"

/* A row of /summary: the run's summary (every field of aq_summary_fields, so
 * a field added there is a column here), then what only the file keeps. */
typedef struct {
  aq_summary s;
  int64_t record_index, arch_index, scale_index; /* rows of /records, groups of /arches, --scale */
  int64_t reversals, steps_total, steps_moving, path_evaluations; /* stepper counters */
  double timing_run_s;
  char *error;             /* the run's message, whole (owned: freed at the flush) */
  char *record_text; /* a copy of s.record, the column `record` (a variable-length
                        string; owned: freed at the flush) */
} run_row;

#define RUN_COL(f, kind, units) AQ_H5_COL(run_row, f, kind, units)
static const aq_h5_col run_extra_cols[] = {
    RUN_COL(record_index, AQ_H5_INT, "1"),    RUN_COL(arch_index, AQ_H5_INT, "1"),
    RUN_COL(scale_index, AQ_H5_INT, "1"),     RUN_COL(reversals, AQ_H5_INT, "1"),
    RUN_COL(steps_total, AQ_H5_INT, "1"),     RUN_COL(steps_moving, AQ_H5_INT, "1"),
    RUN_COL(path_evaluations, AQ_H5_INT, "1"), RUN_COL(timing_run_s, AQ_H5_DOUBLE, "s"),
    RUN_COL(error, AQ_H5_VSTR, ""),
};
enum { N_RUN_EXTRA = sizeof run_extra_cols / sizeof run_extra_cols[0] };

int aq_h5w_runs_init(aq_h5_writer *w)
{
  w->runs.owned[w->runs.nowned++] = offsetof(run_row, error);
  w->runs.owned[w->runs.nowned++] = offsetof(run_row, record_text);
  w->n_run_cols = aq_summary_nfields + N_RUN_EXTRA;
  w->run_cols = calloc(w->n_run_cols, sizeof *w->run_cols);
  if (!w->run_cols)
    return -1;
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    aq_h5_kind kind = f->kind == AQ_SF_STR      ? AQ_H5_STR
                      : f->kind == AQ_SF_DOUBLE ? AQ_H5_DOUBLE
                                                : AQ_H5_INT;
    w->run_cols[i] = (aq_h5_col){f->name, kind, offsetof(run_row, s) + f->offset, f->size,
                                 aq_summary_units(f)};
    if (strcmp(f->name, "record") == 0) /* whole, not AQ_SUMMARY_RECORD_MAX bytes a row */
      w->run_cols[i] = (aq_h5_col){f->name, AQ_H5_VSTR, offsetof(run_row, record_text),
                                   sizeof(const char *), ""};
  }
  memcpy(w->run_cols + aq_summary_nfields, run_extra_cols, sizeof run_extra_cols);
  return 0;
}

herr_t aq_h5w_runs_open(aq_h5_writer *w)
{
  return aq_h5w_table_open(w, &w->runs, "/summary", w->run_cols, w->n_run_cols, sizeof(run_row),
                           AQ_H5_SUMMARY_CHUNK);
}

/* A history of n values (a series: chunked and compressed). */
static herr_t dataset_doubles(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                              size_t n, const char *units)
{
  return aq_h5w_dataset_1d(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v, n,
                           units, 0, NULL, NULL, 1);
}

/* A history of every voussoir (the block model's): n samples x nv
 * voussoirs, v[i * nv + k], chunked and compressed as the series are, with
 * the columns v0 v1 ... and the same units for each. */
static herr_t dataset_voussoirs(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                                size_t n, size_t nv, const char *units)
{
  hsize_t dim[2] = {n, nv};
  hsize_t rows = AQ_H5_SERIES_CHUNK / nv ? AQ_H5_SERIES_CHUNK / nv : 1;
  hsize_t chunk[2] = {n < rows ? n : rows, nv};
  hid_t dcpl = H5P_DEFAULT;
  if (w->deflate > 0 && n > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (dcpl < 0 || H5Pset_chunk(dcpl, 2, chunk) < 0 || H5Pset_shuffle(dcpl) < 0 ||
        H5Pset_deflate(dcpl, (unsigned)w->deflate) < 0) {
      if (dcpl >= 0)
        H5Pclose(dcpl);
      return -1;
    }
  }
  char *names = malloc(nv * 24);
  const char **col = malloc(nv * sizeof *col), **un = malloc(nv * sizeof *un);
  hid_t s = H5Screate_simple(2, dim, NULL);
  hid_t d = s < 0 ? -1 : H5Dcreate2(loc, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  herr_t rc = d < 0 || !names || !col || !un ? -1 : 0;
  for (size_t k = 0; rc == 0 && k < nv; k++) {
    snprintf(names + 24 * k, 24, "v%zu", k);
    col[k] = names + 24 * k;
    un[k] = units;
  }
  if (rc == 0 && n > 0)
    rc = H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    aq_h5w_sync_hint(w, n * nv * sizeof(double));
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "columns", col, nv);
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "units", un, nv);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (s >= 0 && H5Sclose(s) < 0)
    rc = -1;
  if (s < 0)
    rc = -1;
  if (dcpl != H5P_DEFAULT)
    H5Pclose(dcpl);
  free(names);
  free(col);
  free(un);
  return rc;
}

aq_status aq_h5_write_run(aq_h5_writer *w, size_t ri, size_t ai, size_t si,
                          const aq_summary *s, const aq_result *res,
                          const char *error, double timing_run_s,
                          aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/summary";
  hid_t g = -1;
  if (w->no_runs)
    return aq_error_set(err, AQ_EINTERNAL, w->target, -1, -1, obj,
                        "a run written to a file of another kind than results");
  if (!w->runs.buf) /* no root written: a results file */
    CK(aq_h5w_runs_open(w), "table");
  run_row *row = aq_h5w_table_row(w, &w->runs);
  CK(row ? 0 : -1, "rows");
  row->s = *s;
  row->record_index = (int64_t)ri;
  row->arch_index = (int64_t)ai;
  row->scale_index = (int64_t)si;
  row->timing_run_s = timing_run_s;
  row->record_text = aq_h5w_row_string(row->s.record);
  row->error = aq_h5w_row_string(error);
  CK(row->record_text && row->error ? 0 : -1, "rows (out of memory)");
  if (!res)
    return AQ_OK;
  row->reversals = (int64_t)res->reversals;
  row->steps_total = (int64_t)res->steps_total;
  row->steps_moving = (int64_t)res->steps_moving;
  row->path_evaluations = (int64_t)res->evals;
  const aq_history *h = &res->history;
  if (!h->time_s)
    return AQ_OK;
  char name[128], az[32] = ""; /* runs of one scale at several azimuths */
  if (isfinite(s->azimuth_deg))
    snprintf(az, sizeof az, "_az%.6g", s->azimuth_deg);
  snprintf(name, sizeof name, "/histories/%05zu_%03zu_%03zu%s%s", ri, ai, si,
           strcmp(s->polarity, "reversed") == 0 ? "r" : "", az);
  obj = "/histories";
  CK(aq_h5w_lazy_group(w, &w->g_histories, obj), "H5Gcreate");
  obj = name;
  g = H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(dataset_doubles(w, g, "time_s", h->time_s, h->n, "s"), "time_s");
  CK(dataset_doubles(w, g, "rotation_rad", h->rotation_rad, h->n, "rad"),
     "rotation_rad");
  CK(dataset_doubles(w, g, "displacement_m", h->displacement_m, h->n, "m"),
     "displacement_m");
  CK(dataset_doubles(w, g, "kinetic_energy_j", h->kinetic_energy_j, h->n, "J"),
     "kinetic_energy_j");
  CK(dataset_doubles(w, g, "potential_energy_j", h->potential_energy_j, h->n, "J"),
     "potential_energy_j");
  if (h->set) /* 64-bit in the file, as every integer */
    CK(aq_h5w_dataset_1d(w, g, "hinge_set", H5T_STD_I64LE, H5T_NATIVE_INT, h->set, h->n,
                         "1 (0 primary, 1 reverse, -1 at rest)", 0, NULL, NULL, 1),
       "hinge_set");
  const aq_result_bodies *B = res->bodies;
  if (B && B->hist_x_m && B->nvous > 0) { /* the block model's: every voussoir */
    CK(dataset_voussoirs(w, g, "voussoir_x_m", B->hist_x_m, h->n, B->nvous, "m"),
       "voussoir_x_m");
    CK(dataset_voussoirs(w, g, "voussoir_y_m", B->hist_y_m, h->n, B->nvous, "m"),
       "voussoir_y_m");
    CK(dataset_voussoirs(w, g, "voussoir_rotation_rad", B->hist_rot_rad, h->n, B->nvous,
                         "rad"),
       "voussoir_rotation_rad");
  }
  CK(H5Gclose(g), "H5Gclose");
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}
