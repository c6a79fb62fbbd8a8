/* h5_spectrum.c: the /spectra table of a spectrum file (h5_spectrum.h): a
 * compound dataset whose two text fields are variable-length strings.
 * Every HDF5 call is checked. */
#include "h5_spectrum.h"

#include <hdf5.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5_table.h"

/* A row as stored. */
typedef struct {
  const char *record, *component;
  double damping, period_s, psa_g, sd_m, psv_m_s;
} h5_row;

static const aq_h5_col cols[] = {
    AQ_H5_COL(h5_row, record, AQ_H5_VSTR, ""),
    AQ_H5_COL(h5_row, component, AQ_H5_VSTR, ""),
    AQ_H5_COL(h5_row, damping, AQ_H5_DOUBLE, "1"),
    AQ_H5_COL(h5_row, period_s, AQ_H5_DOUBLE, "s"),
    AQ_H5_COL(h5_row, psa_g, AQ_H5_DOUBLE, "g"),
    AQ_H5_COL(h5_row, sd_m, AQ_H5_DOUBLE, "m"),
    AQ_H5_COL(h5_row, psv_m_s, AQ_H5_DOUBLE, "m/s")};
enum { NCOLS = sizeof cols / sizeof cols[0] };

aq_status aq_h5_write_spectra(aq_h5_writer *w, const char *target,
                              const aq_h5_spectra *s, aq_error *err)
{
  hid_t file = (hid_t)aq_h5_file_id(w), d = -1;
  h5_row *v = malloc((s->n ? s->n : 1) * sizeof *v);
  herr_t rc = v ? 0 : -1;
  for (size_t i = 0; rc == 0 && i < s->n; i++) {
    const aq_spectrum_row *r = &s->row[i];
    v[i] = (h5_row){r->record, r->component, r->damping, r->period_s,
                    r->psa_g, r->sd_m, r->psv_m_s};
  }
  if (rc >= 0)
    rc = aq_h5_table_write(file, "spectra", cols, NCOLS, sizeof(h5_row), v, s->n, &d);
  if (rc >= 0)
    rc = aq_h5_attr_text(w, d, "peaks", aq_spectrum_peaks_names[s->peaks]);
  if (rc >= 0)
    rc = aq_h5_attr_text(w, d, "peaks_text", aq_spectrum_peaks_text(s->peaks));
  if (rc >= 0)
    rc = aq_h5_attr_int(w, d, "rotd_angles", (int64_t)s->n_angles);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  free(v);
  if (rc < 0)
    return aq_error_set(err, AQ_EIO, target, -1, -1, "/spectra",
                        "could not write the spectra table (HDF5)");
  return AQ_OK;
}

void aq_h5_spectra_table_free(aq_h5_spectra_table *t)
{
  for (size_t i = 0; i < t->n; i++) {
    free(t->record[i]);
    free(t->component[i]);
  }
  free(t->record);
  free(t->component);
  free(t->damping);
  free(t->period_s);
  free(t->psa_g);
  free(t->sd_m);
  free(t->psv_m_s);
  memset(t, 0, sizeof *t);
}

/* The table's rows from the open dataset d into t. */
static aq_status read_rows(hid_t d, const char *path, aq_h5_spectra_table *t,
                           aq_error *err)
{
  hid_t ft = -1, mt = aq_h5_table_type(cols, NCOLS, sizeof(h5_row), &ft), sp = H5Dget_space(d);
  hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  h5_row *v = n >= 0 ? calloc((size_t)n + 1, sizeof *v) : NULL;
  aq_status st = AQ_OK;
  if (mt < 0 || n < 0 || !v || H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/spectra",
                      "expected the spectrum table of archquake spectrum -o, "
                      "got one HDF5 cannot read as such");
    n = 0;
  }
  size_t m = (size_t)n + 1;
  t->record = malloc(m * sizeof *t->record);
  t->component = malloc(m * sizeof *t->component);
  double **col[] = {&t->damping, &t->period_s, &t->psa_g, &t->sd_m, &t->psv_m_s};
  int ok = t->record && t->component;
  for (size_t j = 0; j < sizeof col / sizeof *col; j++)
    ok = (*col[j] = malloc(m * sizeof(double))) != NULL && ok;
  if (st == AQ_OK && !ok)
    st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, "/spectra", "out of memory");
  for (size_t i = 0; st == AQ_OK && i < (size_t)n; i++) {
    t->record[i] = strdup(v[i].record ? v[i].record : "");
    t->component[i] = strdup(v[i].component ? v[i].component : "");
    t->n = i + 1; /* what aq_h5_spectra_table_free frees */
    if (!t->record[i] || !t->component[i])
      st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, "/spectra", "out of memory");
    t->damping[i] = v[i].damping;
    t->period_s[i] = v[i].period_s;
    t->psa_g[i] = v[i].psa_g;
    t->sd_m[i] = v[i].sd_m;
    t->psv_m_s[i] = v[i].psv_m_s;
  }
  if (st == AQ_OK)
    t->n = (size_t)n;
  if (v && n > 0)
    H5Dvlen_reclaim(mt, sp, H5P_DEFAULT, v);
  free(v);
  if (sp >= 0)
    H5Sclose(sp);
  if (mt >= 0)
    H5Tclose(mt);
  if (ft >= 0)
    H5Tclose(ft);
  return st;
}

aq_status aq_h5_spectra_read(const char *path, aq_h5_spectra_table *t, aq_error *err)
{
  memset(t, 0, sizeof *t);
  hid_t f, d;
  aq_status st = aq_h5_open_output(path, "spectrum", "spectra", H5I_DATASET,
                                   "the spectra of archquake spectrum -o, got a file without them",
                                   &f, &d, err);
  if (st != AQ_OK)
    return st;
  st = read_rows(d, path, t, err);
  char peaks[16] = "";
  hid_t a = H5Aexists(d, "peaks") > 0 ? H5Aopen(d, "peaks", H5P_DEFAULT) : -1;
  if (a >= 0) {
    hid_t at = H5Aget_type(a);
    if (at >= 0 && H5Tget_size(at) < sizeof peaks)
      H5Aread(a, at, peaks);
    if (at >= 0)
      H5Tclose(at);
    H5Aclose(a);
  }
  t->peaks = aq_spectrum_peaks_parse(peaks);
  H5Oclose(d);
  H5Fclose(f);
  if (st != AQ_OK)
    aq_h5_spectra_table_free(t);
  return st;
}
