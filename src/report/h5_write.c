/* h5_write.c: the results writer's HDF5 primitives (h5_writer.h): a failed
 * call as one aq_error, scalar attributes, groups made when first needed,
 * 1-D datasets (series chunked and compressed). */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "h5_writer.h"

/* ---- error reporting ---------------------------------------------------- */

static herr_t walk_cb(unsigned n, const H5E_error2_t *e, void *data)
{
  char *buf = data;
  if (n == 0 && e->desc && e->desc[0]) { /* innermost: where it started */
    snprintf(buf, 200, "%s", e->desc);
    char *extra = strstr(buf, ": time = "); /* drop the low-level details */
    if (extra)
      *extra = '\0';
  }
  return 0;
}

aq_status aq_h5w_fail(aq_error *err, const char *input, const char *object,
                      const char *what, int errno_)
{
  char desc[200] = "";
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walk_cb, desc);
  H5Eclear2(H5E_DEFAULT);
  return aq_error_set(err, AQ_EIO, input, -1, -1, object,
                      "HDF5: %s failed%s%s%s%s", what, desc[0] ? ": " : "",
                      desc, errno_ ? ": " : "", errno_ ? strerror(errno_) : "");
}

/* ---- attribute and dataset helpers (return < 0 on failure) -------------- */

hid_t aq_h5w_str_type(size_t size)
{
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0)
    return t;
  if (H5Tset_size(t, size ? size : 1) < 0 ||
      H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

herr_t aq_h5w_attr_str(aq_h5_writer *w, hid_t loc, const char *name,
                       const char *value)
{
  if (!value)
    value = "";
  if (H5Tset_size(w->t_str, strlen(value) + 1) < 0)
    return -1;
  return aq_h5_attr_write(loc, name, w->t_str, w->sp_scalar, value);
}

herr_t aq_h5w_attr_double(aq_h5_writer *w, hid_t loc, const char *name, double v)
{
  return aq_h5_attr_write(loc, name, H5T_NATIVE_DOUBLE, w->sp_scalar, &v);
}

herr_t aq_h5w_attr_int(aq_h5_writer *w, hid_t loc, const char *name, int64_t v)
{
  return aq_h5_attr_write(loc, name, H5T_NATIVE_INT64, w->sp_scalar, &v);
}

int aq_h5_attr_text(aq_h5_writer *w, int64_t loc, const char *name, const char *value)
{
  return aq_h5w_attr_str(w, (hid_t)loc, name, value) < 0 ? -1 : 0;
}

int aq_h5_attr_int(aq_h5_writer *w, int64_t loc, const char *name, int64_t v)
{
  return aq_h5w_attr_int(w, (hid_t)loc, name, v) < 0 ? -1 : 0;
}

int aq_h5_attr_double(aq_h5_writer *w, int64_t loc, const char *name, double v)
{
  return aq_h5w_attr_double(w, (hid_t)loc, name, v) < 0 ? -1 : 0;
}

herr_t aq_h5w_attr_doubles(hid_t loc, const char *name, const double *v,
                           size_t n)
{
  hsize_t dim = n;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  if (s < 0)
    return -1;
  herr_t rc = aq_h5_attr_write(loc, name, H5T_NATIVE_DOUBLE, s, v);
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

hid_t aq_h5w_lazy_group(aq_h5_writer *w, hid_t *g, const char *name)
{
  if (*g < 0)
    *g = H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  return *g;
}

/* The creation properties of a long series of n values (a history, a
 * waveform): chunks of AQ_H5_SERIES_CHUNK values, each byte-shuffled then
 * deflated at the writer's level (docs/hdf5-layout.md, "Compression"); or
 * H5P_DEFAULT (contiguous) when the level is 0, n is 0 or HDF5 has no
 * deflate filter.  Close it with H5Pclose unless H5P_DEFAULT; < 0 on
 * failure. */
static hid_t series_dcpl(const aq_h5_writer *w, size_t n)
{
  if (w->deflate <= 0 || n == 0 || H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    return H5P_DEFAULT;
  hsize_t chunk = n < AQ_H5_SERIES_CHUNK ? n : AQ_H5_SERIES_CHUNK;
  hid_t p = H5Pcreate(H5P_DATASET_CREATE);
  if (p >= 0 && (H5Pset_chunk(p, 1, &chunk) < 0 || H5Pset_shuffle(p) < 0 ||
                 H5Pset_deflate(p, (unsigned)w->deflate) < 0)) {
    H5Pclose(p);
    return -1;
  }
  return p;
}

void aq_h5_set_deflate(aq_h5_writer *w, int level)
{
  w->deflate = level < 0 ? 0 : level > 9 ? 9 : level;
}

/* (series: chunked and compressed, series_dcpl) */
herr_t aq_h5w_dataset_1d(aq_h5_writer *w, hid_t loc, const char *name,
                         hid_t ftype, hid_t mtype, const void *v, size_t n,
                         const char *units, size_t nd,
                         const char *const *dname, const double *dval, int series)
{
  hsize_t dim = n;
  hid_t dcpl = series ? series_dcpl(w, n) : H5P_DEFAULT;
  if (dcpl < 0)
    return -1;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  hid_t d = s < 0 ? -1 : H5Dcreate2(loc, name, ftype, s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dcpl != H5P_DEFAULT)
    H5Pclose(dcpl);
  if (s < 0)
    return -1;
  herr_t rc = d < 0 ? -1 : 0;
  if (rc == 0 && n > 0)
    rc = H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    aq_h5w_sync_hint(w, n * H5Tget_size(ftype));
  if (rc == 0)
    rc = aq_h5w_attr_str(w, d, "units", units);
  for (size_t k = 0; rc == 0 && k < nd; k++)
    rc = aq_h5w_attr_double(w, d, dname[k], dval[k]);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}
