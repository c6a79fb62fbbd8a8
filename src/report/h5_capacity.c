/* h5_capacity.c: the `capacity` group of a results file: one row per
 * (record, arch, polarity) in column datasets, the collapse intervals as one
 * (n x 2) dataset indexed by interval_start / interval_count, and the
 * fragility fits in `capacity/fragility`.  Every HDF5 call is checked. */
#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "h5_capacity.h"

/* n variable-length strings as a 1-D dataset. */
static herr_t ds_strings(hid_t g, const char *name, const char *const *v, size_t n)
{
  hsize_t dim = n;
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0)
    return -1;
  hid_t sp = H5Screate_simple(1, &dim, NULL);
  herr_t rc = -1;
  if (sp >= 0 && H5Tset_size(t, H5T_VARIABLE) >= 0) {
    hid_t d = H5Dcreate2(g, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (d >= 0) {
      rc = n ? H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) : 0;
      if (H5Dclose(d) < 0)
        rc = -1;
    }
  }
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  if (H5Tclose(t) < 0)
    rc = -1;
  return rc;
}

/* A dataset of n rows x cols of type t from buf. */
static herr_t ds_write(hid_t g, const char *name, hid_t t, const void *buf, size_t n,
                       size_t cols)
{
  hsize_t dim[2] = {n, cols};
  hid_t sp = H5Screate_simple(cols > 1 ? 2 : 1, dim, NULL);
  if (sp < 0)
    return -1;
  herr_t rc = -1;
  hid_t d = H5Dcreate2(g, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (d >= 0) {
    rc = n ? H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) : 0;
    if (H5Dclose(d) < 0)
      rc = -1;
  }
  if (H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

static herr_t attr_d(hid_t g, const char *name, double v)
{
  hid_t sp = H5Screate(H5S_SCALAR);
  if (sp < 0)
    return -1;
  herr_t rc = -1;
  hid_t a = H5Acreate2(g, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    rc = H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
    if (H5Aclose(a) < 0)
      rc = -1;
  }
  if (H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

static herr_t attr_s(hid_t g, const char *name, const char *v)
{
  hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
  herr_t rc = -1;
  if (t >= 0 && sp >= 0 && H5Tset_size(t, strlen(v) + 1) >= 0) {
    hid_t a = H5Acreate2(g, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    if (a >= 0) {
      rc = H5Awrite(a, t, v);
      if (H5Aclose(a) < 0)
        rc = -1;
    }
  }
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  if (t >= 0 && H5Tclose(t) < 0)
    rc = -1;
  return rc;
}

/* Per-pair and per-fit numeric columns, filled from c. */
typedef struct {
  double *d[6];  /* move_scale first_collapse_scale first_collapse_pga_g
                    first_collapse_pgv_m_s scale_max lambda0 */
  int64_t *i[4]; /* resurrection runs interval_start interval_count */
  double *iv;    /* intervals, 2 per row */
  size_t niv;
} columns;

static const char *const dnames[6] = {"move_scale", "first_collapse_scale",
                                      "first_collapse_pga_g", "first_collapse_pgv_m_s",
                                      "scale_max", "lambda0"};
static const char *const inames[4] = {"resurrection", "runs", "interval_start",
                                      "interval_count"};

static int fill(const aq_h5_capacity *c, columns *k)
{
  size_t n = c->npair ? c->npair : 1, niv = 0;
  for (size_t p = 0; p < c->npair; p++)
    niv += c->valid[p] ? c->cap[p].scan.ninterval : 0;
  for (int j = 0; j < 6; j++)
    if (!(k->d[j] = malloc(n * sizeof(double))))
      return -1;
  for (int j = 0; j < 4; j++)
    if (!(k->i[j] = malloc(n * sizeof(int64_t))))
      return -1;
  if (!(k->iv = malloc((niv ? niv : 1) * 2 * sizeof(double))))
    return -1;
  for (size_t p = 0; p < c->npair; p++) {
    const aq_capacity *a = &c->cap[p];
    int v = c->valid[p];
    double fc = v ? a->first_collapse_scale : NAN;
    k->d[0][p] = v ? a->move_scale : NAN;
    k->d[1][p] = fc;
    k->d[2][p] = fc * c->pga_g[p];
    k->d[3][p] = fc * c->pgv_mps[p];
    k->d[4][p] = v ? a->scale_max : NAN;
    k->d[5][p] = v ? a->lambda0 : NAN;
    k->i[0][p] = v ? a->resurrection : 0;
    k->i[1][p] = v ? (int64_t)a->scan.runs : 0;
    k->i[2][p] = (int64_t)k->niv;
    k->i[3][p] = v ? (int64_t)a->scan.ninterval : 0;
    for (size_t q = 0; v && q < a->scan.ninterval; q++) {
      k->iv[2 * k->niv] = a->scan.interval[q].lo;
      k->iv[2 * k->niv + 1] = a->scan.interval[q].hi;
      k->niv++;
    }
  }
  return 0;
}

static void columns_free(columns *k)
{
  for (int j = 0; j < 6; j++)
    free(k->d[j]);
  for (int j = 0; j < 4; j++)
    free(k->i[j]);
  free(k->iv);
}

aq_status aq_h5_write_capacity(aq_h5_writer *w, const char *target,
                               const aq_h5_capacity *c, aq_error *err)
{
  hid_t file = (hid_t)aq_h5_file_id(w), g = -1, gf = -1;
  columns k;
  memset(&k, 0, sizeof k);
  const char *obj = "/capacity";
  if (fill(c, &k) != 0) {
    columns_free(&k);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, obj, "out of memory");
  }
  size_t nf = c->nfit ? c->nfit : 1;
  double *fd[4] = {malloc(nf * sizeof(double)), malloc(nf * sizeof(double)),
                   malloc(nf * sizeof(double)), malloc(nf * sizeof(double))};
  int64_t *fn[2] = {malloc(nf * sizeof(int64_t)), malloc(nf * sizeof(int64_t))};
  aq_status st = AQ_OK;
  if (!fd[0] || !fd[1] || !fd[2] || !fd[3] || !fn[0] || !fn[1]) {
    st = aq_error_set(err, AQ_ENOMEM, target, -1, -1, obj, "out of memory");
    goto out;
  }
  for (size_t i = 0; i < c->nfit; i++) {
    fd[0][i] = c->fit[i].median;
    fd[1][i] = c->fit[i].beta;
    fd[2][i] = c->fit[i].median_lo;
    fd[3][i] = c->fit[i].median_hi;
    fn[0][i] = (int64_t)c->fit[i].n;
    fn[1][i] = (int64_t)c->fit[i].ncensored;
  }
  const char *what = "H5Gcreate2";
  errno = 0;
  if ((g = H5Gcreate2(file, "capacity", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0)
    goto fail;
  what = "capacity attributes";
  if (attr_d(g, "resolution", c->resolution) < 0 || attr_d(g, "tol", c->tol) < 0 ||
      attr_d(g, "fragility_ci", c->ci) < 0 ||
      attr_s(g, "fragility_method",
             "lognormal maximum likelihood, right-censored at each record's cap; "
             "median interval by profile likelihood") < 0)
    goto fail;
  what = "capacity columns";
  if (ds_strings(g, "record", c->record, c->npair) < 0 ||
      ds_strings(g, "arch", c->arch, c->npair) < 0 ||
      ds_strings(g, "polarity", c->polarity, c->npair) < 0 ||
      ds_strings(g, "status", c->status, c->npair) < 0)
    goto fail;
  for (int j = 0; j < 6; j++)
    if (ds_write(g, dnames[j], H5T_NATIVE_DOUBLE, k.d[j], c->npair, 1) < 0)
      goto fail;
  for (int j = 0; j < 4; j++)
    if (ds_write(g, inames[j], H5T_NATIVE_INT64, k.i[j], c->npair, 1) < 0)
      goto fail;
  what = "capacity/intervals";
  if (ds_write(g, "intervals", H5T_NATIVE_DOUBLE, k.iv, k.niv, 2) < 0)
    goto fail;
  obj = "/capacity/fragility";
  what = "fragility columns";
  if ((gf = H5Gcreate2(g, "fragility", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
      ds_strings(gf, "arch", c->fit_arch, c->nfit) < 0 ||
      ds_strings(gf, "im", c->fit_im, c->nfit) < 0 ||
      ds_write(gf, "records", H5T_NATIVE_INT64, fn[0], c->nfit, 1) < 0 ||
      ds_write(gf, "censored", H5T_NATIVE_INT64, fn[1], c->nfit, 1) < 0 ||
      ds_write(gf, "median", H5T_NATIVE_DOUBLE, fd[0], c->nfit, 1) < 0 ||
      ds_write(gf, "beta", H5T_NATIVE_DOUBLE, fd[1], c->nfit, 1) < 0 ||
      ds_write(gf, "median_lo", H5T_NATIVE_DOUBLE, fd[2], c->nfit, 1) < 0 ||
      ds_write(gf, "median_hi", H5T_NATIVE_DOUBLE, fd[3], c->nfit, 1) < 0)
    goto fail;
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
  for (int j = 0; j < 4; j++)
    free(fd[j]);
  free(fn[0]);
  free(fn[1]);
  columns_free(&k);
  return st;
}
