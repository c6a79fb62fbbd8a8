/* h5_table.c: the table writer of the HDF5 files (h5_table.h). */
#include "h5_table.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The HDF5 type of a column (close it). */
static hid_t col_type(const aq_h5_col *c)
{
  if (c->kind == AQ_H5_DOUBLE)
    return H5Tcopy(H5T_NATIVE_DOUBLE);
  if (c->kind == AQ_H5_INT)
    return H5Tcopy(H5T_NATIVE_INT64);
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0)
    return t;
  size_t size = c->kind == AQ_H5_VSTR ? H5T_VARIABLE : c->size ? c->size : 1;
  if (H5Tset_size(t, size) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

hid_t aq_h5_table_type(const aq_h5_col *cols, size_t ncols, size_t rowsize, hid_t *file)
{
  *file = -1;
  hid_t t = H5Tcreate(H5T_COMPOUND, rowsize);
  for (size_t i = 0; t >= 0 && i < ncols; i++) {
    hid_t m = col_type(&cols[i]);
    herr_t rc = m < 0 ? -1 : H5Tinsert(t, cols[i].name, cols[i].offset, m);
    if (m >= 0 && H5Tclose(m) < 0)
      rc = -1;
    if (rc < 0) {
      H5Tclose(t);
      t = -1;
    }
  }
  if (t < 0)
    return -1;
  *file = H5Tcopy(t);
  if (*file < 0 || H5Tpack(*file) < 0) {
    if (*file >= 0)
      H5Tclose(*file);
    *file = -1;
    H5Tclose(t);
    return -1;
  }
  return t;
}

hid_t aq_h5_xfer(hid_t d, hid_t mt, size_t n)
{
  /* HDF5 converts in strips of (buffer size / the larger of the memory type
   * and the type as stored) values.  The dataset's type comes back in its
   * memory form, where a variable-length value takes 8 bytes (a pointer),
   * stored as 16 (length and heap address): the stored type is at most
   * twice as large. */
  hid_t ft = H5Dget_type(d);
  size_t ms = H5Tget_size(mt), fs = ft < 0 ? 0 : H5Tget_size(ft);
  size_t def = H5Pget_buffer(H5P_DATASET_XFER_DEFAULT, NULL, NULL);
  if (ft >= 0 && H5Tclose(ft) < 0)
    fs = 0;
  if (!ms || !fs || !def)
    return -1;
  size_t es = ms > 2 * fs ? ms : 2 * fs;
  /* n values in one strip; from the default size on, the default (a long
   * table converts in the same strips as without this list) */
  size_t size = n && n < def / es ? n * es : def;
  hid_t p = H5Pcreate(H5P_DATASET_XFER);
  if (p >= 0 && H5Pset_buffer(p, size, NULL, NULL) < 0) {
    H5Pclose(p);
    p = -1;
  }
  return p;
}

herr_t aq_h5_attr_write(hid_t loc, const char *name, hid_t type, hid_t space, const void *buf)
{
  hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0)
    return -1;
  herr_t rc = H5Awrite(a, type, buf);
  if (H5Aclose(a) < 0)
    rc = -1;
  return rc;
}

herr_t aq_h5_attr_string(hid_t loc, const char *name, const char *value)
{
  if (!value)
    value = "";
  hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
  herr_t rc = -1;
  if (t >= 0 && sp >= 0 && H5Tset_size(t, strlen(value) + 1) >= 0 &&
      H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0)
    rc = aq_h5_attr_write(loc, name, t, sp, value);
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  if (t >= 0 && H5Tclose(t) < 0)
    rc = -1;
  return rc;
}

herr_t aq_h5_table_units(hid_t d, const aq_h5_col *cols, size_t ncols)
{
  for (size_t i = 0; i < ncols; i++) {
    if (!cols[i].units)
      continue;
    char an[96];
    snprintf(an, sizeof an, "units_%s", cols[i].name);
    if (aq_h5_attr_string(d, an, cols[i].units) < 0)
      return -1;
  }
  return 0;
}

/* A 1-D dataset of n values of type t (as stored: the same) from buf. */
static hid_t dataset(hid_t loc, const char *name, hid_t t, const void *buf, size_t n)
{
  hsize_t dim = n;
  hid_t sp = H5Screate_simple(1, &dim, NULL);
  if (sp < 0)
    return -1;
  hid_t d = H5Dcreate2(loc, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t xfer = d >= 0 && n ? aq_h5_xfer(d, t, n) : -1;
  if (d >= 0 && n && (xfer < 0 || H5Dwrite(d, t, H5S_ALL, H5S_ALL, xfer, buf) < 0)) {
    H5Dclose(d);
    d = -1;
  }
  if (xfer >= 0 && H5Pclose(xfer) < 0 && d >= 0) {
    H5Dclose(d);
    d = -1;
  }
  if (H5Sclose(sp) < 0 && d >= 0) {
    H5Dclose(d);
    d = -1;
  }
  return d;
}

herr_t aq_h5_table_write(hid_t loc, const char *name, const aq_h5_col *cols, size_t ncols,
                         size_t rowsize, const void *rows, size_t nrows, hid_t *out)
{
  if (out)
    *out = -1;
  hid_t ft = -1, mt = aq_h5_table_type(cols, ncols, rowsize, &ft);
  if (mt < 0)
    return -1;
  hsize_t dim = nrows;
  hid_t sp = H5Screate_simple(1, &dim, NULL);
  hid_t d = sp < 0 ? -1 : H5Dcreate2(loc, name, ft, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t xfer = d >= 0 && nrows ? aq_h5_xfer(d, mt, nrows) : -1;
  herr_t rc = d < 0 ? -1 : !nrows ? 0 : xfer < 0 ? -1 : H5Dwrite(d, mt, H5S_ALL, H5S_ALL, xfer, rows);
  if (xfer >= 0 && H5Pclose(xfer) < 0)
    rc = -1;
  if (rc >= 0)
    rc = aq_h5_table_units(d, cols, ncols);
  if (rc >= 0 && out)
    *out = d;
  else if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  if (H5Tclose(ft) < 0 || H5Tclose(mt) < 0)
    rc = -1;
  if (rc < 0 && out && *out >= 0) {
    H5Dclose(*out);
    *out = -1;
  }
  return rc;
}

herr_t aq_h5_columns_write(hid_t loc, const aq_h5_col *cols, size_t ncols, size_t rowsize,
                           const void *rows, size_t nrows)
{
  herr_t rc = 0;
  for (size_t i = 0; rc >= 0 && i < ncols; i++) {
    const aq_h5_col *c = &cols[i];
    size_t sz = c->kind == AQ_H5_VSTR ? sizeof(const char *) : c->size;
    unsigned char *buf = malloc((nrows ? nrows : 1) * sz);
    hid_t t = buf ? col_type(c) : -1;
    for (size_t r = 0; t >= 0 && r < nrows; r++) {
      const unsigned char *src = (const unsigned char *)rows + r * rowsize + c->offset;
      memcpy(buf + r * sz, src, sz);
      if (c->kind == AQ_H5_VSTR && !*(const char *const *)src)
        *(const char **)(void *)(buf + r * sz) = "";
    }
    hid_t d = t < 0 ? -1 : dataset(loc, c->name, t, buf, nrows);
    rc = d < 0 ? -1 : 0;
    if (rc >= 0 && c->units)
      rc = aq_h5_attr_string(d, "units", c->units);
    if (d >= 0 && H5Dclose(d) < 0)
      rc = -1;
    if (t >= 0 && H5Tclose(t) < 0)
      rc = -1;
    free(buf);
  }
  return rc;
}

herr_t aq_h5_attr_strings(hid_t loc, const char *name, const char *const *v, size_t n)
{
  hsize_t dim = n;
  hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate_simple(1, &dim, NULL);
  herr_t rc = -1;
  if (t >= 0 && sp >= 0 && H5Tset_size(t, H5T_VARIABLE) >= 0)
    rc = aq_h5_attr_write(loc, name, t, sp, v);
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  if (t >= 0 && H5Tclose(t) < 0)
    rc = -1;
  return rc;
}

herr_t aq_h5_array_write(hid_t g, const char *name, hid_t t, const void *buf, size_t n,
                         size_t cols, const char *units)
{
  hsize_t dim[2] = {n, cols};
  hid_t sp = H5Screate_simple(cols > 1 ? 2 : 1, dim, NULL);
  if (sp < 0)
    return -1;
  herr_t rc = -1;
  hid_t d = H5Dcreate2(g, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (d >= 0) {
    rc = n ? H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) : 0;
    if (rc >= 0 && units)
      rc = aq_h5_attr_string(d, "units", units);
    if (H5Dclose(d) < 0)
      rc = -1;
  }
  if (H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

aq_status aq_h5_open_output(const char *path, const char *command, const char *name,
                            H5I_type_t kind, const char *missing, hid_t *file, hid_t *obj,
                            aq_error *err)
{
  *obj = -1;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  *file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (*file < 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "expected an HDF5 file of archquake %s -o, got one HDF5 cannot open",
                        command);
  *obj = H5Lexists(*file, name, H5P_DEFAULT) > 0 ? H5Oopen(*file, name, H5P_DEFAULT) : -1;
  if (*obj >= 0 && H5Iget_type(*obj) == kind)
    return AQ_OK;
  if (*obj >= 0)
    H5Oclose(*obj);
  *obj = -1;
  H5Fclose(*file);
  *file = -1;
  char field[64];
  snprintf(field, sizeof field, "/%s", name);
  return aq_error_set(err, AQ_EFORMAT, path, -1, -1, field, "expected %s", missing);
}
