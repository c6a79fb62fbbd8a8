/* h5_select.c: the file of `archquake select -o` (h5_select.h).  Every
 * HDF5 call is checked. */
#define _POSIX_C_SOURCE 200809L
#include "h5_select.h"

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "h5.h"
#include "h5_table.h"

typedef struct {
  const char *record, *channel, *event;
  double scale, misfit;
  int64_t pool_index;
} suite_row;

static const aq_h5_col suite_cols[] = {
    AQ_H5_COL(suite_row, record, AQ_H5_VSTR, NULL),
    AQ_H5_COL(suite_row, channel, AQ_H5_VSTR, NULL),
    AQ_H5_COL(suite_row, event, AQ_H5_VSTR, NULL),
    AQ_H5_COL(suite_row, scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(suite_row, misfit, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(suite_row, pool_index, AQ_H5_INT, NULL)};
enum { NSUITE = sizeof suite_cols / sizeof suite_cols[0] };

typedef struct {
  const char *name, *detail;
  int64_t holds;
} check_row;

static const aq_h5_col check_cols[] = {
    AQ_H5_COL(check_row, name, AQ_H5_VSTR, NULL),
    AQ_H5_COL(check_row, holds, AQ_H5_INT, NULL),
    AQ_H5_COL(check_row, detail, AQ_H5_VSTR, NULL)};
enum { NCHECK = sizeof check_cols / sizeof check_cols[0] };

typedef struct {
  const char *record, *channel, *event;
  double own_scale, psa0_g;
} pool_row;

static const aq_h5_col pool_cols[] = {
    AQ_H5_COL(pool_row, record, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pool_row, channel, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pool_row, event, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pool_row, own_scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pool_row, psa0_g, AQ_H5_DOUBLE, "g")};
enum { NPOOL = sizeof pool_cols / sizeof pool_cols[0] };

/* A rows x cols dataset of doubles (cols 1: 1-D) with its units. */
static herr_t ds_doubles(hid_t g, const char *name, const double *buf, size_t rows,
                         size_t cols, const char *units)
{
  return aq_h5_array_write(g, name, H5T_NATIVE_DOUBLE, buf, rows, cols, units);
}

static herr_t write_group(aq_h5_writer *w, hid_t file, const aq_h5_select *s)
{
  const aq_select_input *in = s->input;
  const aq_selection *sel = s->sel;
  size_t K = in->nper, N = in->count, M = in->nrec;
  hid_t g = H5Gcreate2(file, "select", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0)
    return -1;
  char desc[512], comments[8192] = "";
  aq_target_describe(in->target, desc, sizeof desc);
  for (size_t i = 0, w = 0; i < s->ncomments && w + 2 < sizeof comments; i++) {
    int k = snprintf(comments + w, sizeof comments - w, "%s\n", s->comments[i]);
    if (k < 0)
      break;
    w += (size_t)k < sizeof comments - w ? (size_t)k : sizeof comments - w - 1;
  }
  const aq_select_eval *e = &sel->search.eval;
  double f = N && sel->search.found ? sel->scale[0] / sel->prep.scale[sel->search.idx[0]] : 1;
  herr_t rc = aq_h5_attr_text(w, g, "target", in->target->spec);
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "target_description", desc);
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "code", aq_target_code(in->target));
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "peaks", s->peaks);
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "pair_rule", s->pair_rule);
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "search", sel->search.kind == AQ_SEARCH_EXHAUSTIVE
                                                      ? "exhaustive" : "greedy-swaps");
  if (rc >= 0) rc = aq_h5_attr_text(w, g, "suite_file_comments", comments);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "damping", in->target->damping);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "band", AQ_SELECT_BAND);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "scale_lo", in->scale_lo);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "scale_hi", in->scale_hi);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "common_factor", f);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "misfit", e->misfit);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "combinations", sel->search.combinations);
  if (rc >= 0) rc = aq_h5_attr_double(w, g, "evaluated", sel->search.evaluated);
  if (rc >= 0)
    rc = aq_h5_attr_double(w, g, "target0_g", sel->problem.target0_mps2 / AQ_G0_MPS2);
  if (rc >= 0) rc = aq_h5_attr_int(w, g, "count", (int64_t)N);
  if (rc >= 0) rc = aq_h5_attr_int(w, g, "max_per_event", (int64_t)in->max_per_event);
  if (rc >= 0) rc = aq_h5_attr_int(w, g, "conditions_hold", sel->all_hold);
  double *v = malloc(((M > N ? M : N) * (K ? K : 1) + K + 1) * sizeof *v);
  if (!v)
    rc = -1;
  if (rc >= 0) rc = ds_doubles(g, "period_s", in->periods_s, K, 1, "s");
  for (size_t k = 0; rc >= 0 && k < K; k++)
    v[k] = sel->target_mps2[k] / AQ_G0_MPS2;
  if (rc >= 0) rc = ds_doubles(g, "target_g", v, K, 1, "g");
  /* the suite: rows and unscaled spectra */
  suite_row *sr = calloc(N ? N : 1, sizeof *sr);
  for (size_t j = 0; rc >= 0 && sr && j < N; j++) {
    size_t i = sel->search.idx[j];
    sr[j] = (suite_row){s->record[i], s->channel[i], s->event[i], sel->scale[j],
                        sel->misfit_one[j], (int64_t)i};
    for (size_t k = 0; k < K; k++)
      v[j * K + k] = in->psa_mps2[i * K + k] / AQ_G0_MPS2;
  }
  if (!sr)
    rc = -1;
  if (rc >= 0)
    rc = aq_h5_table_write(g, "suite", suite_cols, NSUITE, sizeof *sr, sr, N, NULL);
  if (rc >= 0) rc = ds_doubles(g, "suite_psa_g", v, N, K, "g");
  free(sr);
  /* the checks */
  check_row cr[AQ_SELECT_CHECKS_MAX];
  for (size_t i = 0; i < sel->nchecks; i++)
    cr[i] = (check_row){sel->checks[i].name, sel->checks[i].detail, sel->checks[i].holds};
  if (rc >= 0)
    rc = aq_h5_table_write(g, "checks", check_cols, NCHECK, sizeof *cr, cr, sel->nchecks,
                           NULL);
  /* the pool: every usable member, its own scale and spectrum */
  pool_row *pr = calloc(M ? M : 1, sizeof *pr);
  for (size_t i = 0; rc >= 0 && pr && i < M; i++) {
    pr[i] = (pool_row){s->record[i], s->channel[i], s->event[i], sel->prep.scale[i],
                       in->psa0_mps2[i] / AQ_G0_MPS2};
    for (size_t k = 0; k < K; k++)
      v[i * K + k] = in->psa_mps2[i * K + k] / AQ_G0_MPS2;
  }
  if (!pr)
    rc = -1;
  if (rc >= 0)
    rc = aq_h5_table_write(g, "pool", pool_cols, NPOOL, sizeof *pr, pr, M, NULL);
  if (rc >= 0) rc = ds_doubles(g, "pool_psa_g", v, M, K, "g");
  free(pr);
  free(v);
  if (H5Gclose(g) < 0)
    rc = -1;
  return rc;
}

aq_status aq_h5_select_write(const char *target, const aq_h5_select *s, aq_error *err)
{
  aq_h5_writer *w = NULL;
  aq_status st = aq_h5_open(target, &w, err);
  if (st != AQ_OK)
    return st;
  aq_h5_root root = {.version = s->version, .command_line = s->command_line,
                     .created = s->created, .proc = s->proc, .threads = s->input->threads,
                     .build = s->build};
  st = aq_h5_write_root_kind(w, &root, "select", err);
  if (st == AQ_OK && write_group(w, (hid_t)aq_h5_file_id(w), s) < 0)
    st = aq_error_set(err, AQ_EIO, target, -1, -1, "/select",
                      "could not write the selection (HDF5)");
  if (st == AQ_OK)
    return aq_h5_finish(w, NULL, err);
  aq_h5_abort(w);
  return st;
}

/* ---- reading ------------------------------------------------------------ */

void aq_h5_select_file_free(aq_h5_select_file *f)
{
  for (size_t i = 0; i < f->n; i++) {
    free(f->record ? f->record[i] : NULL);
    free(f->channel ? f->channel[i] : NULL);
    free(f->event ? f->event[i] : NULL);
  }
  for (size_t i = 0; i < f->nchecks; i++) {
    free(f->check_name ? f->check_name[i] : NULL);
    free(f->check_detail ? f->check_detail[i] : NULL);
  }
  free(f->record);
  free(f->channel);
  free(f->event);
  free(f->check_name);
  free(f->check_detail);
  free(f->check_holds);
  free(f->period_s);
  free(f->target_g);
  free(f->scale);
  free(f->misfit_one);
  free(f->psa_g);
  free(f->comments);
  memset(f, 0, sizeof *f);
}

static int attr_text(hid_t g, const char *name, char *buf, size_t cap)
{
  buf[0] = '\0';
  hid_t a = H5Aexists(g, name) > 0 ? H5Aopen(g, name, H5P_DEFAULT) : -1;
  if (a < 0)
    return -1;
  hid_t t = H5Aget_type(a);
  int rc = -1;
  size_t sz = t >= 0 ? H5Tget_size(t) : 0;
  if (t >= 0 && H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t) && sz < cap)
    rc = H5Aread(a, t, buf) < 0 ? -1 : 0;
  if (t >= 0)
    H5Tclose(t);
  H5Aclose(a);
  buf[cap - 1] = '\0';
  return rc;
}

/* A 1-D (cols 1) or rows x cols dataset of doubles into a new array. */
static double *ds_read_doubles(hid_t g, const char *name, size_t rows, size_t cols)
{
  hid_t d = H5Lexists(g, name, H5P_DEFAULT) > 0 ? H5Dopen2(g, name, H5P_DEFAULT) : -1;
  if (d < 0)
    return NULL;
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  int nd = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
  double *v = malloc((rows * cols > 0 ? rows * cols : 1) * sizeof *v);
  int ok = v && nd >= 1 && dims[0] == rows && (cols == 1 ? nd == 1 : nd == 2 && dims[1] == cols);
  if (ok && rows * cols > 0)
    ok = H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0;
  if (sp >= 0)
    H5Sclose(sp);
  H5Dclose(d);
  if (!ok) {
    free(v);
    return NULL;
  }
  return v;
}

/* The rows of compound table name of g (cols, rowsize) into *rows (malloc'd,
 * variable-length strings to be reclaimed by the caller with reclaim_rows);
 * their number, or -1. */
static hssize_t read_table(hid_t g, const char *name, const aq_h5_col *cols, size_t ncols,
                           size_t rowsize, void **rows, hid_t *mt_out)
{
  hid_t d = H5Lexists(g, name, H5P_DEFAULT) > 0 ? H5Dopen2(g, name, H5P_DEFAULT) : -1;
  if (d < 0)
    return -1;
  hid_t ft = -1, mt = aq_h5_table_type(cols, ncols, rowsize, &ft), sp = H5Dget_space(d);
  hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  void *v = n >= 0 ? calloc((size_t)n + 1, rowsize) : NULL;
  if (mt < 0 || n < 0 || !v || H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    free(v);
    v = NULL;
    n = -1;
  }
  if (sp >= 0)
    H5Sclose(sp);
  if (ft >= 0)
    H5Tclose(ft);
  H5Dclose(d);
  if (n < 0 && mt >= 0)
    H5Tclose(mt);
  *rows = v;
  *mt_out = n < 0 ? -1 : mt;
  return n;
}

static void reclaim_rows(hid_t mt, void *rows, hssize_t n)
{
  if (mt < 0)
    return;
  hsize_t dim = (hsize_t)n;
  hid_t sp = H5Screate_simple(1, &dim, NULL);
  if (n > 0 && sp >= 0)
    H5Dvlen_reclaim(mt, sp, H5P_DEFAULT, rows);
  if (sp >= 0)
    H5Sclose(sp);
  H5Tclose(mt);
}

static char *dup_or_empty(const char *s)
{
  return strdup(s ? s : "");
}

static aq_status read_group(hid_t g, const char *path, aq_h5_select_file *f, aq_error *err)
{
  char comments[8192];
  if (attr_text(g, "target", f->target, sizeof f->target) < 0 ||
      attr_text(g, "target_description", f->description, sizeof f->description) < 0 ||
      attr_text(g, "code", f->code, sizeof f->code) < 0 ||
      attr_text(g, "peaks", f->peaks, sizeof f->peaks) < 0 ||
      aq_h5_attr_num(g, "damping", H5T_NATIVE_DOUBLE, &f->damping) < 0 ||
      aq_h5_attr_num(g, "band", H5T_NATIVE_DOUBLE, &f->band) < 0 ||
      aq_h5_attr_num(g, "common_factor", H5T_NATIVE_DOUBLE, &f->factor) < 0 ||
      aq_h5_attr_num(g, "misfit", H5T_NATIVE_DOUBLE, &f->misfit) < 0 ||
      aq_h5_attr_num(g, "target0_g", H5T_NATIVE_DOUBLE, &f->target0_g) < 0 ||
      aq_h5_attr_num(g, "conditions_hold", H5T_NATIVE_INT, &f->conditions_hold) < 0)
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/select",
                        "expected the attributes of archquake select -o, got a group "
                        "without them");
  attr_text(g, "suite_file_comments", comments, sizeof comments);
  f->comments = strdup(comments);
  hid_t d = H5Dopen2(g, "period_s", H5P_DEFAULT), sp = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t nper = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  if (nper < 1)
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/select/period_s",
                        "expected the grid of periods, got none");
  f->nper = (size_t)nper;
  f->period_s = ds_read_doubles(g, "period_s", f->nper, 1);
  f->target_g = ds_read_doubles(g, "target_g", f->nper, 1);
  void *rows = NULL;
  hid_t mt;
  hssize_t n = read_table(g, "suite", suite_cols, NSUITE, sizeof(suite_row), &rows, &mt);
  if (n < 1 || !f->period_s || !f->target_g) {
    free(rows);
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/select/suite",
                        "expected the suite's table and the grid, got a file HDF5 cannot "
                        "read as such");
  }
  f->psa_g = ds_read_doubles(g, "suite_psa_g", (size_t)n, f->nper);
  f->record = calloc((size_t)n, sizeof *f->record);
  f->channel = calloc((size_t)n, sizeof *f->channel);
  f->event = calloc((size_t)n, sizeof *f->event);
  f->scale = malloc((size_t)n * sizeof *f->scale);
  f->misfit_one = malloc((size_t)n * sizeof *f->misfit_one);
  aq_status st = AQ_OK;
  if (!f->psa_g || !f->record || !f->channel || !f->event || !f->scale || !f->misfit_one)
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/select/suite_psa_g",
                      "expected the suite's spectra, got none HDF5 can read");
  const suite_row *sr = rows;
  for (size_t j = 0; st == AQ_OK && j < (size_t)n; j++) {
    f->n = j + 1;
    f->record[j] = dup_or_empty(sr[j].record);
    f->channel[j] = dup_or_empty(sr[j].channel);
    f->event[j] = dup_or_empty(sr[j].event);
    f->scale[j] = sr[j].scale;
    f->misfit_one[j] = sr[j].misfit;
    if (!f->record[j] || !f->channel[j] || !f->event[j])
      st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  }
  reclaim_rows(mt, rows, n);
  free(rows);
  if (st != AQ_OK)
    return st;
  n = read_table(g, "checks", check_cols, NCHECK, sizeof(check_row), &rows, &mt);
  if (n < 0)
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/select/checks",
                        "expected the checks' table, got none HDF5 can read");
  f->check_name = calloc((size_t)n + 1, sizeof *f->check_name);
  f->check_detail = calloc((size_t)n + 1, sizeof *f->check_detail);
  f->check_holds = calloc((size_t)n + 1, sizeof *f->check_holds);
  const check_row *cr = rows;
  for (size_t i = 0; f->check_name && f->check_detail && f->check_holds && i < (size_t)n;
       i++) {
    f->nchecks = i + 1;
    f->check_name[i] = dup_or_empty(cr[i].name);
    f->check_detail[i] = dup_or_empty(cr[i].detail);
    f->check_holds[i] = (int)cr[i].holds;
  }
  reclaim_rows(mt, rows, n);
  free(rows);
  if (f->nchecks != (size_t)n)
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  return AQ_OK;
}

aq_status aq_h5_select_read(const char *path, aq_h5_select_file *f, aq_error *err)
{
  memset(f, 0, sizeof *f);
  hid_t file, g;
  aq_status st = aq_h5_open_output(path, "select", "select", H5I_GROUP,
                                   "the selection of archquake select -o, got a file without it",
                                   &file, &g, err);
  if (st != AQ_OK)
    return st;
  st = read_group(g, path, f, err);
  H5Oclose(g);
  H5Fclose(file);
  if (st != AQ_OK)
    aq_h5_select_file_free(f);
  return st;
}

int aq_h5_is_select(const char *path)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  if (H5Fis_hdf5(path) <= 0)
    return 0;
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0)
    return 0;
  int yes = H5Lexists(file, "select", H5P_DEFAULT) > 0;
  H5Fclose(file);
  return yes;
}
