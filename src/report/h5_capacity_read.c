/* h5_capacity_read.c: the `capacity` group of a results file read back
 * (aq_h5_capacity_read: its rows, collapse intervals, scan points, IMs and
 * fragility fits into an aq_h5_capacity_table) and two such tables compared
 * row by row (aq_h5_capacity_compare).  Every HDF5 call is checked.
 */
#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "h5_capacity.h"
#include "h5_capacity_cols.h"
#include "h5_table.h"
#include "text.h"

/* ---- reading back ---------------------------------------------------------- */

void aq_h5_capacity_table_free(aq_h5_capacity_table *t)
{
  if (!t)
    return;
  free(t->row);
  free(t->interval);
  free(t->fit);
  free(t->point);
  memset(t, 0, sizeof *t);
}

/* Read the 1-D (or n x 2) dataset name of g into buf (n values of type t). */
static herr_t ds_read(hid_t g, const char *name, hid_t t, void *buf, hsize_t n,
                      hsize_t cols)
{
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  if (d < 0)
    return -1;
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  int nd = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
  herr_t rc = -1;
  if (nd >= 1 && dims[0] == n && (cols == 1 ? nd == 1 : nd == 2 && dims[1] == cols))
    rc = n ? H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) : 0;
  if (sp >= 0)
    H5Sclose(sp);
  if (H5Dclose(d) < 0)
    rc = -1;
  return rc;
}

/* A column of n variable-length strings into the records at base (stride
 * bytes apart) at offset off, size cap. */
static herr_t ds_read_strings(hid_t g, const char *name, void *base, size_t stride,
                              size_t n, size_t off, size_t cap)
{
  char **v = calloc(n ? n : 1, sizeof *v);
  hid_t t = H5Tcopy(H5T_C_S1);
  herr_t rc = -1;
  if (v && t >= 0 && H5Tset_size(t, H5T_VARIABLE) >= 0 &&
      ds_read(g, name, t, v, n, 1) >= 0) {
    rc = 0;
    for (size_t i = 0; i < n; i++) /* whole, or not read */
      if (snprintf((char *)base + i * stride + off, cap, "%s", v[i] ? v[i] : "") >= (int)cap)
        rc = -1;
    hsize_t dim = n;
    hid_t sp = H5Screate_simple(1, &dim, NULL);
    if (n && sp >= 0)
      H5Dvlen_reclaim(t, sp, H5P_DEFAULT, v);
    if (sp >= 0)
      H5Sclose(sp);
  }
  if (t >= 0)
    H5Tclose(t);
  free(v);
  return rc;
}

/* The IMs at first collapse and at the cap (NAN when absent: older files). */
/* The column names of the IM matrix d (its columns attribute) into
 * t->im_name; the six of aq_fragility_im_names for a file written before
 * it named them.  The number of columns, or 0. */
static size_t im_columns(hid_t d, aq_h5_capacity_table *t)
{
  hid_t sp = H5Dget_space(d);
  hsize_t dim[2] = {0, 0};
  int nd = sp >= 0 ? H5Sget_simple_extent_dims(sp, dim, NULL) : -1;
  if (sp >= 0)
    H5Sclose(sp);
  size_t m = nd == 2 ? (size_t)dim[1] : 0;
  if (m < AQ_FRAGILITY_NIM || m > AQ_H5_CAP_NIM_MAX)
    return 0;
  for (size_t j = 0; j < AQ_FRAGILITY_NIM; j++)
    snprintf(t->im_name[j], sizeof t->im_name[j], "%s", aq_fragility_im_names[j]);
  hid_t a = H5Aexists(d, "columns") > 0 ? H5Aopen(d, "columns", H5P_DEFAULT) : -1;
  hid_t at = a >= 0 ? H5Aget_type(a) : -1, as = a >= 0 ? H5Aget_space(a) : -1;
  char *v[AQ_H5_CAP_NIM_MAX] = {NULL};
  if (at >= 0 && as >= 0 && H5Tis_variable_str(at) > 0 &&
      H5Sget_simple_extent_npoints(as) == (hssize_t)m && H5Aread(a, at, v) >= 0) {
    for (size_t j = 0; j < m; j++)
      snprintf(t->im_name[j], sizeof t->im_name[j], "%s", v[j] ? v[j] : "");
    H5Dvlen_reclaim(at, as, H5P_DEFAULT, v);
  } else if (m > AQ_FRAGILITY_NIM) {
    m = 0; /* spectral columns without their names */
  }
  if (as >= 0)
    H5Sclose(as);
  if (at >= 0)
    H5Tclose(at);
  if (a >= 0)
    H5Aclose(a);
  return m;
}

static int read_im(hid_t g, aq_h5_capacity_table *t, const char **what)
{
  static const char *const name[2] = {"im_first_collapse", "im_cap"};
  size_t n = t->n, m = AQ_FRAGILITY_NIM;
  for (size_t j = 0; j < AQ_FRAGILITY_NIM; j++)
    snprintf(t->im_name[j], sizeof t->im_name[j], "%s", aq_fragility_im_names[j]);
  if (H5Lexists(g, name[0], H5P_DEFAULT) > 0) {
    hid_t d = H5Dopen2(g, name[0], H5P_DEFAULT);
    m = d >= 0 ? im_columns(d, t) : 0;
    if (d >= 0)
      H5Dclose(d);
    *what = name[0];
    if (m == 0)
      return -1;
  }
  t->nim = m;
  double *v = malloc((n ? n : 1) * m * sizeof *v);
  if (!v)
    return -1;
  int rc = 0;
  for (int k = 0; k < 2 && rc == 0; k++) {
    int have = H5Lexists(g, name[k], H5P_DEFAULT) > 0;
    *what = name[k];
    if (have && ds_read(g, name[k], H5T_NATIVE_DOUBLE, v, n, m) < 0)
      rc = -1;
    for (size_t i = 0; rc == 0 && i < n; i++)
      for (size_t j = 0; j < AQ_H5_CAP_NIM_MAX; j++)
        (k ? t->row[i].im_cap : t->row[i].im_first)[j] = have && j < m ? v[i * m + j] : NAN;
  }
  free(v);
  return rc;
}

/* capacity/fragility, when present. */
static int read_fits(hid_t g, aq_h5_capacity_table *t, const char **what)
{
  *what = "fragility";
  if (H5Lexists(g, "fragility", H5P_DEFAULT) <= 0)
    return 0;
  hid_t gf = H5Gopen2(g, "fragility", H5P_DEFAULT), d = -1, sp = -1;
  hsize_t n = 0;
  int ok = gf >= 0 && (d = H5Dopen2(gf, "arch", H5P_DEFAULT)) >= 0 &&
           (sp = H5Dget_space(d)) >= 0 && H5Sget_simple_extent_dims(sp, &n, NULL) == 1;
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  double *v = malloc((n ? n : 1) * sizeof *v);
  int64_t *iv = malloc((n ? n : 1) * sizeof *iv);
  ok = ok && v && iv && (t->fit = calloc(n ? n : 1, sizeof *t->fit)) != NULL;
  if (ok)
    t->nfit = (size_t)n;
  const size_t sz = sizeof *t->fit;
  ok = ok && ds_read_strings(gf, "arch", t->fit, sz, t->nfit,
                             offsetof(aq_h5_fragility_fit, arch), sizeof t->fit->arch) >= 0;
  ok = ok && ds_read_strings(gf, "im", t->fit, sz, t->nfit, offsetof(aq_h5_fragility_fit, im),
                             sizeof t->fit->im) >= 0;
  static const char *const dn[4] = {"median", "beta", "median_lo", "median_hi"};
  for (int j = 0; ok && j < 4; j++) {
    ok = ds_read(gf, dn[j], H5T_NATIVE_DOUBLE, v, n, 1) >= 0;
    for (size_t i = 0; ok && i < t->nfit; i++)
      *(j == 0   ? &t->fit[i].median
        : j == 1 ? &t->fit[i].beta
        : j == 2 ? &t->fit[i].median_lo
                 : &t->fit[i].median_hi) = v[i];
  }
  for (int j = 0; ok && j < 2; j++) {
    ok = ds_read(gf, j ? "censored" : "records", H5T_NATIVE_INT64, iv, n, 1) >= 0;
    for (size_t i = 0; ok && i < t->nfit; i++)
      *(j ? &t->fit[i].censored : &t->fit[i].records) = iv[i];
  }
  /* the rank and what it orders (files written before: from beta) */
  int have_rank = ok && H5Lexists(gf, "rank", H5P_DEFAULT) > 0;
  if (have_rank)
    ok = ds_read(gf, "rank", H5T_NATIVE_INT64, iv, n, 1) >= 0;
  int have_ranked = ok && H5Lexists(gf, "beta_per_power", H5P_DEFAULT) > 0;
  if (have_ranked)
    ok = ds_read(gf, "beta_per_power", H5T_NATIVE_DOUBLE, v, n, 1) >= 0;
  for (size_t i = 0; ok && i < t->nfit; i++) {
    t->fit[i].rank = have_rank ? iv[i] : 0;
    t->fit[i].beta_per_power =
        have_ranked ? v[i] : aq_fragility_row_ranked(t->fit[i].im, t->fit[i].beta);
  }
  /* the marked records (files written before them: -1) */
  int have_marked = ok && H5Lexists(gf, "marked", H5P_DEFAULT) > 0;
  if (have_marked)
    ok = ds_read(gf, "marked", H5T_NATIVE_INT64, iv, n, 1) >= 0;
  for (size_t i = 0; ok && i < t->nfit; i++)
    t->fit[i].marked = have_marked ? iv[i] : -1;
  free(v);
  free(iv);
  if (gf >= 0)
    H5Gclose(gf);
  return ok ? 0 : -1;
}

/* capacity/scan_points, when present: rows by pair (each < t->n, not
 * decreasing) then by scale. */
static int read_points(hid_t g, aq_h5_capacity_table *t, const char **what)
{
  *what = "scan_points";
  if (H5Lexists(g, "scan_points", H5P_DEFAULT) <= 0)
    return 0;
  hid_t d = H5Dopen2(g, "scan_points", H5P_DEFAULT), sp = -1, ft = -1,
        mt = aq_h5_table_type(point_cols, NPOINT_COLS, sizeof(h5_point), &ft);
  hsize_t n = 0;
  int ok = d >= 0 && mt >= 0 && (sp = H5Dget_space(d)) >= 0 &&
           H5Sget_simple_extent_dims(sp, &n, NULL) == 1;
  h5_point *v = ok ? malloc((n ? n : 1) * sizeof *v) : NULL;
  ok = ok && v && (t->point = malloc((n ? n : 1) * sizeof *t->point)) != NULL;
  ok = ok && (n == 0 || H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
  for (size_t i = 0; ok && i < n; i++) {
    const h5_point *q = &v[i];
    ok = q->pair >= 0 && (uint64_t)q->pair < t->n &&
         (i == 0 || q->pair > v[i - 1].pair ||
          (q->pair == v[i - 1].pair && !(q->scale < v[i - 1].scale)));
    if (!ok)
      break;
    aq_h5_capacity_row *r = &t->row[q->pair];
    if (r->point_count++ == 0)
      r->point_start = i;
    t->point[i] = (aq_capacity_point){q->scale, q->peak_rotation_rad,
                                      q->peak_rotation_over_qc, q->collapse_time_s,
                                      q->collapsed != 0, 0};
  }
  if (ok) {
    t->npoint = (size_t)n;
    t->have_points = 1;
  }
  free(v);
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  if (mt >= 0)
    H5Tclose(mt);
  if (ft >= 0)
    H5Tclose(ft);
  return ok ? 0 : -1;
}

aq_status aq_h5_capacity_read(const char *path, aq_h5_capacity_table *t, int *present,
                              aq_error *err)
{
  memset(t, 0, sizeof *t);
  *present = 0;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "expected a readable HDF5 results file");
  aq_status st = AQ_OK;
  if (H5Lexists(f, "capacity", H5P_DEFAULT) <= 0) {
    H5Fclose(f);
    return AQ_OK;
  }
  *present = 1;
  hid_t pa = H5Aexists(f, "peaks") > 0 ? H5Aopen(f, "peaks", H5P_DEFAULT) : -1;
  hid_t pt = pa >= 0 ? H5Aget_type(pa) : -1;
  if (pt >= 0 && H5Tget_class(pt) == H5T_STRING && !H5Tis_variable_str(pt) &&
      H5Tget_size(pt) < sizeof t->peaks && H5Aread(pa, pt, t->peaks) < 0)
    t->peaks[0] = '\0';
  if (pt >= 0)
    H5Tclose(pt);
  if (pa >= 0)
    H5Aclose(pa);
  hid_t g = H5Gopen2(f, "capacity", H5P_DEFAULT), d = -1, sp = -1;
  hsize_t n = 0, ni[2] = {0, 0};
  const char *what = "record";
  if (g < 0 || (d = H5Dopen2(g, "record", H5P_DEFAULT)) < 0 ||
      (sp = H5Dget_space(d)) < 0 || H5Sget_simple_extent_dims(sp, &n, NULL) != 1)
    goto bad;
  H5Sclose(sp);
  H5Dclose(d);
  sp = d = -1;
  what = "intervals";
  if ((d = H5Dopen2(g, "intervals", H5P_DEFAULT)) < 0 || (sp = H5Dget_space(d)) < 0 ||
      H5Sget_simple_extent_dims(sp, ni, NULL) != 2 || ni[1] != 2)
    goto bad;
  H5Sclose(sp);
  H5Dclose(d);
  sp = d = -1;
  t->row = calloc(n ? n : 1, sizeof *t->row);
  t->interval = malloc((ni[0] ? ni[0] : 1) * 2 * sizeof(double));
  double *col = malloc((n ? n : 1) * sizeof *col);
  int64_t *icol = malloc((n ? n : 1) * sizeof *icol);
  if (!t->row || !t->interval || !col || !icol) {
    free(col);
    free(icol);
    H5Gclose(g);
    H5Fclose(f);
    aq_h5_capacity_table_free(t);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, "capacity", "out of memory");
  }
  t->n = (size_t)n;
  t->ninterval = (size_t)ni[0];
  int ok = 1;
  what = "record, arch, polarity, status";
  ok = ok && ds_read_strings(g, "record", t->row, sizeof *t->row, t->n, offsetof(aq_h5_capacity_row, record),
                             sizeof t->row->record) >= 0;
  ok = ok && ds_read_strings(g, "arch", t->row, sizeof *t->row, t->n, offsetof(aq_h5_capacity_row, arch),
                             sizeof t->row->arch) >= 0;
  ok = ok && ds_read_strings(g, "polarity", t->row, sizeof *t->row, t->n,
                             offsetof(aq_h5_capacity_row, polarity),
                             sizeof t->row->polarity) >= 0;
  ok = ok && ds_read_strings(g, "status", t->row, sizeof *t->row, t->n, offsetof(aq_h5_capacity_row, status),
                             sizeof t->row->status) >= 0;
  for (int j = 0; ok && j < AQ_H5_CAP_NDOUBLE; j++) {
    what = dnames[j];
    if (j == AQ_H5_CAP_NDOUBLE - 1 && H5Lexists(g, dnames[j], H5P_DEFAULT) <= 0) {
      for (size_t i = 0; i < t->n; i++) /* first_mark_scale: a file written before it */
        t->row[i].d[j] = NAN;
      continue;
    }
    ok = ds_read(g, dnames[j], H5T_NATIVE_DOUBLE, col, n, 1) >= 0;
    for (size_t i = 0; ok && i < t->n; i++)
      t->row[i].d[j] = col[i];
  }
  for (int j = 0; ok && j < AQ_H5_CAP_NINT; j++) {
    what = inames[j];
    ok = ds_read(g, inames[j], H5T_NATIVE_INT64, icol, n, 1) >= 0;
    for (size_t i = 0; ok && i < t->n; i++)
      t->row[i].i[j] = icol[i];
  }
  what = "intervals";
  ok = ok && ds_read(g, "intervals", H5T_NATIVE_DOUBLE, t->interval, ni[0], 2) >= 0;
  for (size_t i = 0; ok && i < t->n; i++) /* interval rows within the dataset */
    ok = t->row[i].i[2] >= 0 && t->row[i].i[3] >= 0 &&
         (uint64_t)(t->row[i].i[2] + t->row[i].i[3]) <= (uint64_t)t->ninterval;
  if (ok)
    ok = read_im(g, t, &what) == 0 && read_fits(g, t, &what) == 0 &&
         read_points(g, t, &what) == 0;
  free(col);
  free(icol);
  H5Gclose(g);
  H5Fclose(f);
  H5Eclear2(H5E_DEFAULT);
  if (!ok) {
    aq_h5_capacity_table_free(t);
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/capacity",
                        "expected the capacity datasets (docs/capacity.md), "
                        "could not read %s", what);
  }
  return st;
bad:
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  if (g >= 0)
    H5Gclose(g);
  H5Fclose(f);
  H5Eclear2(H5E_DEFAULT);
  return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/capacity",
                      "expected a one-dimensional %s dataset", what);
}

static int same_key(const aq_h5_capacity_row *x, const aq_h5_capacity_row *y)
{
  return strcmp(x->record, y->record) == 0 && strcmp(x->arch, y->arch) == 0 &&
         strcmp(x->polarity, y->polarity) == 0;
}

static size_t emit(aq_h5_capacity_diff_fn fn, void *ctx, const aq_h5_capacity_row *a,
                   const aq_h5_capacity_row *b, const char *field, double va, double vb,
                   const char *sa, const char *sb)
{
  aq_h5_capacity_diff d = {a, b, field, "", "", NAN};
  if (sa) {
    snprintf(d.a_text, sizeof d.a_text, "%s", sa);
    snprintf(d.b_text, sizeof d.b_text, "%s", sb);
  } else if (field) {
    aq_text_double(d.a_text, sizeof d.a_text, va);
    aq_text_double(d.b_text, sizeof d.b_text, vb);
    double m = fmax(fabs(va), fabs(vb));
    d.rel = m > 0 ? fabs(va - vb) / m : 0;
  }
  if (fn)
    fn(ctx, &d);
  return 1;
}

/* The scan points of two matched rows (capacity/scan_points): the count
 * exactly, then each run's scale, peak rotation, peak / q_c and collapse
 * time as numbers, its verdict exactly (field "scan_point[k].NAME"). */
static size_t compare_points(const aq_h5_capacity_table *a, const aq_h5_capacity_row *x,
                             const aq_h5_capacity_table *b, const aq_h5_capacity_row *y,
                             double rtol, double atol, aq_h5_capacity_diff_fn fn, void *ctx)
{
  if (x->point_count != y->point_count)
    return emit(fn, ctx, x, y, "scan_points", (double)x->point_count,
                (double)y->point_count, NULL, NULL);
  static const char *const names[] = {"scale", "peak_rotation_rad", "peak_rotation_over_qc",
                                      "collapse_time_s", "collapsed"};
  size_t nd = 0;
  for (size_t q = 0; q < x->point_count; q++) {
    const aq_capacity_point *pa = &a->point[x->point_start + q], *pb = &b->point[y->point_start + q];
    double va[5] = {pa->scale, pa->peak_rotation_rad, pa->peak_rotation_over_qc,
                    pa->collapse_time_s, pa->collapsed};
    double vb[5] = {pb->scale, pb->peak_rotation_rad, pb->peak_rotation_over_qc,
                    pb->collapse_time_s, pb->collapsed};
    for (int c = 0; c < 5; c++) {
      if (c == 4 ? va[c] == vb[c] : aq_compare_close(va[c], vb[c], rtol, atol))
        continue;
      char name[64];
      snprintf(name, sizeof name, "scan_point[%zu].%s", q, names[c]);
      nd += emit(fn, ctx, x, y, name, va[c], vb[c], NULL, NULL);
    }
  }
  return nd;
}

size_t aq_h5_capacity_compare(const aq_h5_capacity_table *a,
                              const aq_h5_capacity_table *b, double rtol, double atol,
                              aq_h5_capacity_diff_fn fn, void *ctx)
{
  size_t nd = 0, j = 0;
  for (size_t i = 0; i < a->n; i++) {
    const aq_h5_capacity_row *x = &a->row[i];
    size_t k = j;
    while (k < b->n && !same_key(x, &b->row[k]))
      k++;
    if (k == b->n) {
      nd += emit(fn, ctx, x, NULL, NULL, 0, 0, NULL, NULL);
      continue;
    }
    for (; j < k; j++) /* rows of b skipped over: in b only */
      nd += emit(fn, ctx, NULL, &b->row[j], NULL, 0, 0, NULL, NULL);
    const aq_h5_capacity_row *y = &b->row[j++];
    if (strcmp(x->status, y->status) != 0)
      nd += emit(fn, ctx, x, y, "status", 0, 0, x->status, y->status);
    for (int c = 0; c < AQ_H5_CAP_NDOUBLE; c++)
      if (!aq_compare_close(x->d[c], y->d[c], rtol, atol))
        nd += emit(fn, ctx, x, y, dnames[c], x->d[c], y->d[c], NULL, NULL);
    for (int c = 0; c < AQ_H5_CAP_NINT; c++)
      if (c != 2 && x->i[c] != y->i[c]) /* interval_start depends on earlier rows */
        nd += emit(fn, ctx, x, y, inames[c], (double)x->i[c], (double)y->i[c], NULL,
                   NULL);
    if (x->i[3] == y->i[3])
      for (int64_t q = 0; q < x->i[3]; q++)
        for (int e = 0; e < 2; e++) {
          double va = a->interval[2 * (x->i[2] + q) + e],
                 vb = b->interval[2 * (y->i[2] + q) + e];
          char name[48];
          snprintf(name, sizeof name, "interval_%s[%lld]", e ? "hi" : "lo", (long long)q);
          if (!aq_compare_close(va, vb, rtol, atol))
            nd += emit(fn, ctx, x, y, name, va, vb, NULL, NULL);
        }
    if (a->have_points && b->have_points)
      nd += compare_points(a, x, b, y, rtol, atol, fn, ctx);
  }
  for (; j < b->n; j++)
    nd += emit(fn, ctx, NULL, &b->row[j], NULL, 0, 0, NULL, NULL);
  return nd;
}
