/* h5_capacity.c: the `capacity` group of a results file: one row per
 * (record, arch, polarity) in column datasets, the collapse intervals as one
 * (n x 2) dataset indexed by interval_start / interval_count, and the
 * fragility fits in `capacity/fragility`.  Every HDF5 call is checked.
 * Reading the group back and comparing two are in h5_capacity_read.c. */
#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "h5_capacity.h"
#include "h5_table.h"
#include "text.h"
#include "h5_capacity_cols.h"

/* The n x nim dataset name of the IMs, its columns named (`columns`) with
 * their units (`units`), one string per column. */
static herr_t ds_ims(hid_t g, const char *name, const double *buf, size_t n, size_t nim,
                     const char *const *names, const char *const *units)
{
  if (aq_h5_array_write(g, name, H5T_NATIVE_DOUBLE, buf, n, nim, NULL) < 0)
    return -1;
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  if (d < 0)
    return -1;
  herr_t rc = aq_h5_attr_strings(d, "columns", names, nim);
  if (rc >= 0)
    rc = aq_h5_attr_strings(d, "units", units, nim);
  if (H5Dclose(d) < 0)
    rc = -1;
  return rc;
}

static herr_t attr_d(hid_t g, const char *name, double v)
{
  hid_t sp = H5Screate(H5S_SCALAR);
  if (sp < 0)
    return -1;
  herr_t rc = aq_h5_attr_write(g, name, H5T_NATIVE_DOUBLE, sp, &v);
  if (H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

/* capacity/scan_points from the pairs' aq_capacity points. */
static herr_t write_points(hid_t g, const aq_h5_capacity *c)
{
  size_t n = 0;
  for (size_t p = 0; p < c->npair; p++)
    n += c->row[p].cap ? c->row[p].cap->npoint : 0;
  h5_point *v = malloc((n ? n : 1) * sizeof *v);
  if (!v)
    return -1;
  for (size_t p = 0, k = 0; p < c->npair; p++)
    for (size_t q = 0; c->row[p].cap && q < c->row[p].cap->npoint; q++) {
      const aq_capacity_point *a = &c->row[p].cap->point[q];
      v[k++] = (h5_point){(int64_t)p, a->scale, a->peak_rotation_rad,
                          a->peak_rotation_over_qc, a->collapsed, a->collapse_time_s};
    }
  herr_t rc = aq_h5_table_write(g, "scan_points", point_cols, NPOINT_COLS, sizeof *v, v, n, NULL);
  free(v);
  return rc;
}

/* A row of /capacity (one per (record, arch, polarity)) and of
 * capacity/fragility (one per fit): each a dataset per column. */
typedef struct {
  const char *record, *arch, *polarity, *status;
  double move_scale, first_collapse_scale, first_collapse_pga_g, first_collapse_pgv_m_s,
      scale_max, lambda0, first_mark_scale;
  int64_t resurrection, runs, interval_start, interval_count;
} pair_row;

static const aq_h5_col pair_cols[] = {
    AQ_H5_COL(pair_row, record, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pair_row, arch, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pair_row, polarity, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pair_row, status, AQ_H5_VSTR, NULL),
    AQ_H5_COL(pair_row, move_scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pair_row, first_collapse_scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pair_row, first_collapse_pga_g, AQ_H5_DOUBLE, "g"),
    AQ_H5_COL(pair_row, first_collapse_pgv_m_s, AQ_H5_DOUBLE, "m/s"),
    AQ_H5_COL(pair_row, scale_max, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pair_row, lambda0, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pair_row, first_mark_scale, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(pair_row, resurrection, AQ_H5_INT, "1"),
    AQ_H5_COL(pair_row, runs, AQ_H5_INT, "1"),
    AQ_H5_COL(pair_row, interval_start, AQ_H5_INT, "1"),
    AQ_H5_COL(pair_row, interval_count, AQ_H5_INT, "1")};
enum { NPAIR_COLS = sizeof pair_cols / sizeof pair_cols[0] };

typedef struct {
  const char *arch, *im;
  int64_t records, censored;
  double median, beta, median_lo, median_hi; /* the median's units: per row, below */
  int64_t rank;
  double beta_per_power; /* what rank orders: beta / the IM's power of the scale */
  int64_t marked;        /* records whose row is marked (docs/capacity.md, "Marks") */
} fit_row;

static const aq_h5_col fit_cols[] = {
    AQ_H5_COL(fit_row, arch, AQ_H5_VSTR, NULL),
    AQ_H5_COL(fit_row, im, AQ_H5_VSTR, NULL),
    AQ_H5_COL(fit_row, records, AQ_H5_INT, "1"),
    AQ_H5_COL(fit_row, censored, AQ_H5_INT, "1"),
    AQ_H5_COL(fit_row, median, AQ_H5_DOUBLE, NULL),
    AQ_H5_COL(fit_row, beta, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(fit_row, median_lo, AQ_H5_DOUBLE, NULL),
    AQ_H5_COL(fit_row, median_hi, AQ_H5_DOUBLE, NULL),
    AQ_H5_COL(fit_row, rank, AQ_H5_INT, "1"),
    AQ_H5_COL(fit_row, beta_per_power, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(fit_row, marked, AQ_H5_INT, "1")};
enum { NFIT_COLS = sizeof fit_cols / sizeof fit_cols[0] };

/* The reader's names of the numeric columns (pair_cols' 5th to 15th). */
const char *const aq_h5_capacity_double_names[AQ_H5_CAP_NDOUBLE] = {
    "move_scale", "first_collapse_scale", "first_collapse_pga_g",
    "first_collapse_pgv_m_s", "scale_max", "lambda0", "first_mark_scale"};
const char *const aq_h5_capacity_int_names[AQ_H5_CAP_NINT] = {
    "resurrection", "runs", "interval_start", "interval_count"};

/* What the writer builds from c. */
typedef struct {
  pair_row *pair; /* npair */
  fit_row *fit;   /* nfit */
  double *iv;     /* intervals, 2 per row */
  size_t niv;
  size_t nim;     /* the six IMs of aq_fragility_im_names, then the spectral ones */
  const char *im_name[AQ_H5_CAP_NIM_MAX], *im_units[AQ_H5_CAP_NIM_MAX];
  double *im[2];  /* npair x nim: the IMs at first collapse, at the cap */
  const char **med_units; /* nfit: the units of each fit's median (its IM's) */
} columns;

static int fill(const aq_h5_capacity *c, columns *k)
{
  size_t n = c->npair ? c->npair : 1, nf = c->nfit ? c->nfit : 1, niv = 0;
  for (size_t p = 0; p < c->npair; p++)
    niv += c->row[p].cap ? c->row[p].cap->scan.ninterval : 0;
  k->pair = malloc(n * sizeof *k->pair);
  k->fit = malloc(nf * sizeof *k->fit);
  k->med_units = malloc(nf * sizeof *k->med_units);
  k->iv = malloc((niv ? niv : 1) * 2 * sizeof(double));
  k->nim = AQ_FRAGILITY_NIM;
  for (size_t m = 0; m < AQ_FRAGILITY_NIM; m++) {
    k->im_name[m] = aq_fragility_im_names[m];
    k->im_units[m] = aq_fragility_im_units[m];
  }
  for (size_t m = 0; m < c->nspectral && k->nim < AQ_H5_CAP_NIM_MAX; m++) {
    k->im_name[k->nim] = c->spectral[m];
    k->im_units[k->nim++] = "g"; /* Sa(T) and Sa_avg (sa_..._g) */
  }
  for (int j = 0; j < 2; j++)
    k->im[j] = malloc(n * k->nim * sizeof(double));
  if (!k->pair || !k->fit || !k->med_units || !k->iv || !k->im[0] || !k->im[1])
    return -1;
  for (size_t p = 0; p < c->npair; p++) {
    const aq_capacity_row *r = &c->row[p];
    const aq_capacity *a = r->cap;
    int v = a != NULL;
    double fc = v ? a->first_collapse_scale : NAN;
    k->pair[p] = (pair_row){r->record,
                            r->arch,
                            r->polarity,
                            r->status,
                            v ? a->move_scale : NAN,
                            fc,
                            fc * r->pga_g,
                            fc * r->pgv_mps,
                            v ? a->scale_max : NAN,
                            v ? a->lambda0 : NAN,
                            v ? a->first_mark_scale : NAN,
                            v ? a->resurrection : 0,
                            v ? (int64_t)a->scan.runs : 0,
                            (int64_t)k->niv,
                            v ? (int64_t)a->scan.ninterval : 0};
    for (size_t m = 0; m < k->nim; m++) { /* what the fits were given */
      int w = v && r->im;
      k->im[0][p * k->nim + m] =
          w && !isnan(fc) ? aq_fragility_im_at(r->im, a->lambda0, (int)m, fc) : NAN;
      k->im[1][p * k->nim + m] =
          w ? aq_fragility_im_at(r->im, a->lambda0, (int)m, a->scale_max) : NAN;
    }
    for (size_t q = 0; v && q < a->scan.ninterval; q++) {
      k->iv[2 * k->niv] = a->scan.interval[q].lo;
      k->iv[2 * k->niv + 1] = a->scan.interval[q].hi;
      k->niv++;
    }
  }
  for (size_t i = 0; i < c->nfit; i++) {
    const aq_fragility *q = c->fit[i].fit;
    const char *im = c->fit[i].im;
    k->fit[i] = (fit_row){c->fit[i].arch, im, (int64_t)q->n, (int64_t)q->ncensored,
                          q->median, q->beta, q->median_lo, q->median_hi, q->rank,
                          aq_fragility_row_ranked(im, q->beta), (int64_t)q->nmarked};
    k->med_units[i] = "1";
    for (int m = 0; m < AQ_FRAGILITY_NIM; m++)
      if (im && strcmp(im, aq_fragility_im_names[m]) == 0)
        k->med_units[i] = aq_fragility_im_units[m];
    if (im && strncmp(im, "sa_", 3) == 0)
      k->med_units[i] = "g"; /* Sa(T) and Sa_avg (sa_..._g) */
  }
  return 0;
}

static void columns_free(columns *k)
{
  free(k->pair);
  free(k->fit);
  free(k->med_units);
  free(k->iv);
  free(k->im[0]);
  free(k->im[1]);
}

aq_status aq_h5_write_capacity(aq_h5_writer *w, const char *target,
                               const aq_h5_capacity *c, aq_error *err)
{
  hid_t file = (hid_t)aq_h5_file_id(w), g = -1, gf = -1;
  columns k;
  memset(&k, 0, sizeof k);
  const char *obj = "/capacity";
  aq_status st = AQ_OK;
  if (fill(c, &k) != 0) {
    columns_free(&k);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, obj, "out of memory");
  }
  const char *what = "H5Gcreate2";
  errno = 0;
  if ((g = H5Gcreate2(file, "capacity", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0)
    goto fail;
  what = "capacity attributes";
  if (attr_d(g, "resolution", c->resolution) < 0 || attr_d(g, "tol", c->tol) < 0 ||
      attr_d(g, "fragility_ci", c->ci) < 0 ||
      aq_h5_attr_string(g, "fragility_method",
             "lognormal maximum likelihood, right-censored at each record's cap; "
             "median interval by profile likelihood") < 0)
    goto fail;
  what = "capacity columns";
  if (aq_h5_columns_write(g, pair_cols, NPAIR_COLS, sizeof *k.pair, k.pair, c->npair) < 0)
    goto fail;
  what = "capacity/intervals";
  static const char *const iv_cols[2] = {"lo", "hi"}, *const iv_units[2] = {"1", "1"};
  hid_t di = -1;
  if (aq_h5_array_write(g, "intervals", H5T_NATIVE_DOUBLE, k.iv, k.niv, 2, NULL) < 0 ||
      (di = H5Dopen2(g, "intervals", H5P_DEFAULT)) < 0 ||
      aq_h5_attr_strings(di, "columns", iv_cols, 2) < 0 ||
      aq_h5_attr_strings(di, "units", iv_units, 2) < 0 || H5Dclose(di) < 0)
    goto fail;
  what = "capacity/im_first_collapse, im_cap";
  if (ds_ims(g, "im_first_collapse", k.im[0], c->npair, k.nim, k.im_name, k.im_units) < 0 ||
      ds_ims(g, "im_cap", k.im[1], c->npair, k.nim, k.im_name, k.im_units) < 0)
    goto fail;
  what = "capacity/scan_points";
  if (write_points(g, c) < 0)
    goto fail;
  obj = "/capacity/fragility";
  what = "fragility columns";
  if ((gf = H5Gcreate2(g, "fragility", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
      aq_h5_columns_write(gf, fit_cols, NFIT_COLS, sizeof *k.fit, k.fit, c->nfit) < 0)
    goto fail;
  /* the median's units are its row's IM's: one string per row */
  for (int j = 0; j < 3 && c->nfit; j++) {
    static const char *const med[3] = {"median", "median_lo", "median_hi"};
    hid_t d = H5Dopen2(gf, med[j], H5P_DEFAULT);
    herr_t rc = d < 0 ? -1 : aq_h5_attr_strings(d, "units", k.med_units, c->nfit);
    if (d >= 0 && H5Dclose(d) < 0)
      rc = -1;
    if (rc < 0)
      goto fail;
  }
  what = "H5Gclose";
  if (H5Gclose(gf) < 0) {
    gf = -1;
    goto fail;
  }
  gf = -1;
  if (H5Gclose(g) < 0) {
    g = -1;
    goto fail;
  }
  g = -1;
  goto out;
fail:
  st = aq_error_set(err, AQ_EIO, target, -1, -1, obj, "HDF5: %s failed%s%s", what,
                    errno ? ": " : "", errno ? strerror(errno) : "");
  H5Eclear2(H5E_DEFAULT);
  if (gf >= 0)
    H5Gclose(gf);
  if (g >= 0)
    H5Gclose(g);
out:
  columns_free(&k);
  return st;
}
