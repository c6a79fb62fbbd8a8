/* h5_read.c: reading a suite back from a results file (aq_h5_read_suite,
 * see h5.h), for `archquake compare`.  Table members are read by name, so a
 * file with more columns than this build knows reads alike. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <hdf5.h>
#include <inttypes.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5.h"
#include "text.h"

/* The root attributes compared as configuration, in the order shown. */
static const char *const setting_names[] = {
    "archquake_version", "archquake_build", "model",          "cor",
    "detrend",           "filter",          "taper_frac",     "highpass_hz",
    "highpass_order",    "lowpass_hz",      "merge_tol_g",    "units_override",
    "dt_override_s",     "scale_mode",      "scale_to_pga_g", "polarity",
    "scale_to_lambda0",  "peaks"};
enum { NSETTINGS = sizeof setting_names / sizeof setting_names[0] };

void aq_h5_suite_free(aq_h5_suite *s)
{
  if (!s)
    return;
  free(s->runs);
  free(s->records);
  free(s->arches);
  free(s->settings);
  memset(s, 0, sizeof *s);
}

/* A fixed-length string type of size bytes, or < 0. */
static hid_t str_type(size_t size)
{
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t >= 0 && (H5Tset_size(t, size) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0)) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

/* Scalar attribute name of loc as text into buf[n] (strings as they are,
 * floats as the shortest decimal that reads back (aq_text_double),
 * integers in decimal).  Returns 0, or -1 if absent, not
 * a scalar string or number, or a string longer than n - 1 bytes (never cut). */
static int attr_text(hid_t loc, const char *name, char *buf, size_t n)
{
  if (H5Aexists(loc, name) <= 0)
    return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0)
    return -1;
  int ok = -1;
  hid_t t = H5Aget_type(a), s = H5Aget_space(a);
  H5T_class_t cls = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  if (s >= 0 && H5Sget_simple_extent_npoints(s) == 1) {
    if (cls == H5T_STRING && H5Tis_variable_str(t) == 0) {
      size_t sz = H5Tget_size(t);
      char *tmp = malloc(sz + 1);
      hid_t m = tmp ? str_type(sz + 1) : -1;
      if (m >= 0 && H5Aread(a, m, tmp) >= 0 && strlen(tmp) < n) { /* whole, or not read */
        memcpy(buf, tmp, strlen(tmp) + 1);
        ok = 0;
      }
      if (m >= 0)
        H5Tclose(m);
      free(tmp);
    } else if (cls == H5T_FLOAT) {
      double v;
      if (H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0) {
        aq_text_double(buf, n, v);
        ok = 0;
      }
    } else if (cls == H5T_INTEGER) {
      int64_t v;
      if (H5Aread(a, H5T_NATIVE_INT64, &v) >= 0) {
        snprintf(buf, n, "%" PRId64, v);
        ok = 0;
      }
    }
  }
  if (s >= 0)
    H5Sclose(s);
  if (t >= 0)
    H5Tclose(t);
  H5Aclose(a);
  return ok;
}

/* Insert a member into compound t; returns < 0 on failure. */
static herr_t member(hid_t t, const char *name, aq_summary_kind kind,
                     size_t offset, size_t size)
{
  if (kind == AQ_SF_DOUBLE)
    return H5Tinsert(t, name, offset, H5T_NATIVE_DOUBLE);
  if (kind == AQ_SF_INT)
    return H5Tinsert(t, name, offset, H5T_NATIVE_INT64);
  hid_t s = str_type(size);
  if (s < 0)
    return -1;
  herr_t rc = H5Tinsert(t, name, offset, s);
  H5Tclose(s);
  return rc;
}

/* 1 for the columns without which a run cannot be identified; a key column
 * added later (a polarity) that an older file lacks takes its default. */
static int required(const aq_summary_field *f)
{
  return !strcmp(f->name, "record") || !strcmp(f->name, "arch") || !strcmp(f->name, "scale");
}

/* Read the variable-length string column name of table d (n rows) into
 * the char[size] fields of rows (rowsize bytes apart, at offset).  Returns
 * 1, or -1 when it cannot be read or a string does not fit whole. */
static int read_vlen_column(hid_t d, hsize_t n, const char *name, size_t size, void *rows,
                            size_t rowsize, size_t offset)
{
  char **col = calloc(n ? n : 1, sizeof *col);
  hid_t s = H5Tcopy(H5T_C_S1), t = H5Tcreate(H5T_COMPOUND, sizeof(char *));
  int ok = -1;
  if (col && s >= 0 && t >= 0 && H5Tset_size(s, H5T_VARIABLE) >= 0 &&
      H5Tinsert(t, name, 0, s) >= 0 &&
      (n == 0 || H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, col) >= 0)) {
    ok = 1;
    for (hsize_t i = 0; i < n; i++) {
      const char *v = col[i] ? col[i] : "";
      if (strlen(v) >= size)
        ok = -1;
      else
        memcpy((char *)rows + i * rowsize + offset, v, strlen(v) + 1);
    }
    hid_t sp = H5Dget_space(d);
    if (n && sp >= 0)
      H5Dvlen_reclaim(t, sp, H5P_DEFAULT, col);
    if (sp >= 0)
      H5Sclose(sp);
  }
  if (t >= 0)
    H5Tclose(t);
  if (s >= 0)
    H5Tclose(s);
  free(col);
  return ok;
}

/* Read column name of table d (n rows) into rows of rowsize bytes at offset
 * (a member of size bytes, of kind kind).  Returns 1 if read, 0 if the table
 * has no such column, -1 on failure. */
static int read_column(hid_t d, hid_t ftype, hsize_t n, const char *name,
                       aq_summary_kind kind, size_t size, void *rows,
                       size_t rowsize, size_t offset)
{
  if (H5Tget_member_index(ftype, name) < 0) {
    H5Eclear2(H5E_DEFAULT);
    return 0;
  }
  int ok = -1;
  hid_t m = H5Tget_member_type(ftype, (unsigned)H5Tget_member_index(ftype, name));
  int vlen = kind == AQ_SF_STR && m >= 0 && H5Tis_variable_str(m) > 0;
  if (m >= 0)
    H5Tclose(m);
  if (vlen) /* a string written whole (variable length): copied whole or refused */
    return read_vlen_column(d, n, name, size, rows, rowsize, offset);
  unsigned char *col = malloc((n ? n : 1) * size);
  hid_t t = H5Tcreate(H5T_COMPOUND, size);
  if (col && t >= 0 && member(t, name, kind, 0, size) >= 0 &&
      (n == 0 || H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, col) >= 0)) {
    for (hsize_t i = 0; i < n; i++)
      memcpy((unsigned char *)rows + i * rowsize + offset, col + i * size, size);
    ok = 1;
  }
  if (t >= 0)
    H5Tclose(t);
  free(col);
  return ok;
}

/* A compound table name of f opened for read_column: *d, *ft, its rows *np
 * and a zeroed array of them (rowsize bytes each), or NULL (*d < 0 then,
 * or close it with table_done). */
static void *table_rows(hid_t f, const char *name, size_t rowsize, hid_t *d, hid_t *ft,
                        hssize_t *np)
{
  *ft = -1;
  *np = -1;
  *d = H5Dopen2(f, name, H5P_DEFAULT);
  if (*d < 0)
    return NULL;
  *ft = H5Dget_type(*d);
  hid_t sp = H5Dget_space(*d);
  *np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  if (sp >= 0)
    H5Sclose(sp);
  return *np >= 0 && *ft >= 0 && H5Tget_class(*ft) == H5T_COMPOUND
             ? calloc((size_t)*np ? (size_t)*np : 1, rowsize)
             : NULL;
}

static void table_done(hid_t d, hid_t ft)
{
  if (ft >= 0)
    H5Tclose(ft);
  if (d >= 0)
    H5Dclose(d);
}

/* Columns renamed since files were written: read under the former name
 * when the file lacks the present one. */
static const char *former_name(const char *name)
{
  static const char *const renamed[][2] = {
      {"pga_over_lambda0", "pga_over_lambda0_g"}, /* a ratio, not in g */
  };
  for (size_t k = 0; k < sizeof renamed / sizeof renamed[0]; k++)
    if (strcmp(name, renamed[k][0]) == 0)
      return renamed[k][1];
  return NULL;
}

/* The runs of /summary, column by column: a column this build knows that
 * the file lacks (written before it existed) keeps the value a run without
 * a result has (aq_summary_fill); columns this build does not know are
 * left alone.  A file of a kind without runs (capacity, spectrum) has
 * none. */
static long read_runs(hid_t f, aq_h5_run **out)
{
  *out = NULL;
  hid_t d, ft;
  hssize_t np;
  aq_h5_run *v = table_rows(f, "/summary", sizeof *v, &d, &ft, &np);
  if (d < 0)
    return -1;
  int ok = v != NULL;
  for (hssize_t i = 0; ok && i < np; i++)
    aq_summary_fill(&v[i].s, "", "", "", NAN, NAN, "", NULL);
  for (size_t i = 0; ok && i < aq_summary_nfields; i++) {
    const aq_summary_field *fl = &aq_summary_fields[i];
    int rc = read_column(d, ft, (hsize_t)np, fl->name, fl->kind, fl->size, v, sizeof *v,
                         offsetof(aq_h5_run, s) + fl->offset);
    if (rc == 0 && former_name(fl->name))
      rc = read_column(d, ft, (hsize_t)np, former_name(fl->name), fl->kind, fl->size, v,
                       sizeof *v, offsetof(aq_h5_run, s) + fl->offset);
    ok = rc > 0 || (rc == 0 && !required(fl));
  }
  static const struct {
    const char *name;
    size_t offset;
  } idx[3] = {{"record_index", offsetof(aq_h5_run, record_index)},
              {"arch_index", offsetof(aq_h5_run, arch_index)},
              {"scale_index", offsetof(aq_h5_run, scale_index)}};
  for (int k = 0; ok && k < 3; k++)
    ok = read_column(d, ft, (hsize_t)np, idx[k].name, AQ_SF_INT, sizeof(int64_t), v,
                     sizeof *v, idx[k].offset) > 0;
  table_done(d, ft);
  if (!ok) {
    free(v);
    return -1;
  }
  *out = v;
  return (long)np;
}

static hid_t input_type(void)
{
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(aq_h5_input));
  if (t >= 0 && (member(t, "name", AQ_SF_STR, offsetof(aq_h5_input, name),
                        sizeof(((aq_h5_input *)0)->name)) < 0 ||
                 member(t, "sha256", AQ_SF_STR, offsetof(aq_h5_input, sha256),
                        sizeof(((aq_h5_input *)0)->sha256)) < 0)) {
    H5Tclose(t);
    t = -1;
  }
  return t;
}

/* The name and sha256 of each row of /records (format 2), or -1. */
static long read_inputs(hid_t f, void **out)
{
  *out = NULL;
  hid_t d, ft;
  hssize_t np;
  aq_h5_input *v = table_rows(f, "/records", sizeof *v, &d, &ft, &np);
  if (d < 0)
    return -1;
  int ok = v && read_column(d, ft, (hsize_t)np, "name", AQ_SF_STR, sizeof v->name, v, sizeof *v,
                            offsetof(aq_h5_input, name)) > 0 &&
           read_column(d, ft, (hsize_t)np, "sha256", AQ_SF_STR, sizeof v->sha256, v, sizeof *v,
                       offsetof(aq_h5_input, sha256)) > 0;
  table_done(d, ft);
  if (!ok) {
    free(v);
    return -1;
  }
  *out = v;
  return (long)np;
}

/* ---- format 1: a group per run and per record, summaries as attributes */

int aq_h5_attr_num(hid_t loc, const char *name, hid_t mtype, void *out)
{
  if (H5Aexists(loc, name) <= 0)
    return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, mtype, out) >= 0 ? 0 : -1;
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

/* The names of group path's members in name order (zero-padded indices:
 * command-line order) into a malloc'd array of 64-byte names. */
static long member_names(hid_t f, const char *path, char (**out)[64])
{
  *out = NULL;
  hid_t g = H5Gopen2(f, path, H5P_DEFAULT);
  H5G_info_t info;
  if (g < 0 || H5Gget_info(g, &info) < 0) {
    if (g >= 0)
      H5Gclose(g);
    return -1;
  }
  char(*v)[64] = calloc(info.nlinks ? info.nlinks : 1, sizeof *v);
  long n = v ? (long)info.nlinks : -1;
  for (hsize_t k = 0; v && k < info.nlinks; k++)
    if (H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, v[k], sizeof v[k],
                           H5P_DEFAULT) < 0)
      n = -1;
  H5Gclose(g);
  if (n < 0)
    free(v);
  else
    *out = v;
  return n;
}

/* One element per member group of path (in name order), filled by fill from
 * the group: a malloc'd array of n elements of elsize bytes in *out.
 * Returns n, or -1 (nothing allocated) when a group cannot be read. */
static long read_groups(hid_t f, const char *path, size_t elsize,
                        int (*fill)(hid_t g, void *elem), void **out)
{
  *out = NULL;
  char(*names)[64];
  long n = member_names(f, path, &names);
  if (n < 0)
    return -1;
  unsigned char *v = calloc((size_t)n ? (size_t)n : 1, elsize);
  int ok = v != NULL;
  for (long k = 0; ok && k < n; k++) {
    char obj[160];
    snprintf(obj, sizeof obj, "%s/%s", path, names[k]);
    hid_t g = H5Gopen2(f, obj, H5P_DEFAULT);
    ok = g >= 0 && fill(g, v + (size_t)k * elsize) == 0;
    if (g >= 0)
      H5Gclose(g);
  }
  free(names);
  if (!ok) {
    free(v);
    return -1;
  }
  *out = v;
  return n;
}

/* A run of a format-1 file: its group's attributes. */
static int fill_run_v1(hid_t g, void *elem)
{
  aq_h5_run *r = elem;
  aq_summary_fill(&r->s, "", "", "", NAN, NAN, "", NULL);
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *fl = &aq_summary_fields[i];
    char *p = (char *)&r->s + fl->offset;
    int rc = fl->kind == AQ_SF_STR      ? attr_text(g, fl->name, p, fl->size)
             : fl->kind == AQ_SF_DOUBLE ? aq_h5_attr_num(g, fl->name, H5T_NATIVE_DOUBLE, p)
                                        : aq_h5_attr_num(g, fl->name, H5T_NATIVE_INT64, p);
    if (rc != 0 && (required(fl) || H5Aexists(g, fl->name) != 0))
      return -1;
  }
  return aq_h5_attr_num(g, "record_index", H5T_NATIVE_INT64, &r->record_index) == 0 &&
                 aq_h5_attr_num(g, "arch_index", H5T_NATIVE_INT64, &r->arch_index) == 0 &&
                 aq_h5_attr_num(g, "scale_index", H5T_NATIVE_INT64, &r->scale_index) == 0
             ? 0
             : -1;
}

/* A record of a format-1 file: its name (its file name; the source's last
 * part for a record that could not be read); no hash. */
static int fill_record_v1(hid_t g, void *elem)
{
  aq_h5_input *in = elem;
  char src[AQ_SUMMARY_RECORD_MAX];
  if (attr_text(g, "name", in->name, sizeof in->name) == 0)
    return 0;
  if (attr_text(g, "source_file", src, sizeof src) != 0)
    return -1;
  const char *base = strrchr(src, '/');
  snprintf(in->name, sizeof in->name, "%s", base ? base + 1 : src);
  return 0;
}

aq_status aq_h5_read_suite(const char *path, aq_h5_suite *out, aq_error *err)
{
  memset(out, 0, sizeof *out);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  htri_t is = H5Fis_hdf5(path);
  if (is <= 0) {
    H5Eclear2(H5E_DEFAULT);
    FILE *fp = fopen(path, "rb");
    if (!fp)
      return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot open: %s",
                          strerror(errno));
    fclose(fp);
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                        "expected an HDF5 file, got something else");
  }
  aq_status st = AQ_OK;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT), mt = -1, arches = -1;
  if (f < 0) {
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
    goto done;
  }
  char ver[64];
  long format = attr_text(f, "format_version", ver, sizeof ver) < 0 ? 0 : strtol(ver, NULL, 10);
  if (format < 1 || format > AQ_H5_FORMAT_VERSION) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "format_version",
                      "expected an archquake results file of format_version 1 to %d, "
                      "got %s", AQ_H5_FORMAT_VERSION, format ? ver : "none");
    goto done;
  }
  out->settings = calloc(NSETTINGS, sizeof *out->settings);
  if (!out->settings) {
    st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (size_t k = 0; k < NSETTINGS; k++) {
    aq_h5_setting *s = &out->settings[out->nsettings];
    if (attr_text(f, setting_names[k], s->value, sizeof s->value) == 0) {
      snprintf(s->name, sizeof s->name, "%s", setting_names[k]);
      out->nsettings++;
    }
  }
  void *v = NULL;
  long n = -1;
  aq_h5_run *runs = NULL;
  void *rv = NULL;
  /* a file of a kind without runs (capacity) or arches (spectrum) holds
     no such objects; one written before the kinds had them empty */
  char kind[32] = "results";
  attr_text(f, "kind", kind, sizeof kind);
  int results = strcmp(kind, "results") == 0;
  if (!results && H5Lexists(f, "/summary", H5P_DEFAULT) <= 0) {
    n = 0;
  } else if (format == 1) {
    n = read_groups(f, "/runs", sizeof *runs, fill_run_v1, &rv);
    runs = rv;
  } else {
    n = read_runs(f, &runs);
  }
  if (n < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/summary",
                      "expected the run table of a results file (with record, arch, "
                      "scale and their indices), got none readable");
    goto done;
  }
  out->runs = runs;
  out->nruns = (size_t)n;
  if (format == 1) {
    mt = input_type();
    n = read_groups(f, "/records", sizeof(aq_h5_input), fill_record_v1, &v);
  } else {
    n = read_inputs(f, &v); /* by column: a name written whole is of variable length */
  }
  if ((format == 1 && mt < 0) || n < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/records",
                      "expected the record table of a results file, got none readable");
    goto done;
  }
  out->records = v;
  out->nrecords = (size_t)n;
  H5G_info_t info = {0};
  if (!results && H5Lexists(f, "/arches", H5P_DEFAULT) <= 0) /* a spectrum file */
    arches = -1;
  else if ((arches = H5Gopen2(f, "/arches", H5P_DEFAULT)) < 0 ||
           H5Gget_info(arches, &info) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/arches",
                      "expected the arch groups of a results file, got none readable");
    goto done;
  }
  out->arches = calloc(info.nlinks ? info.nlinks : 1, sizeof *out->arches);
  if (!out->arches) {
    st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    goto done;
  }
  /* /arches/NNN: by name, zero-padded, is by index */
  for (hsize_t k = 0; k < info.nlinks; k++) {
    char name[64];
    aq_h5_input *a = &out->arches[k];
    hid_t g = -1;
    if (H5Lget_name_by_idx(arches, ".", H5_INDEX_NAME, H5_ITER_INC, k, name,
                           sizeof name, H5P_DEFAULT) >= 0)
      g = H5Gopen2(arches, name, H5P_DEFAULT);
    int ok = g >= 0 && attr_text(g, "name", a->name, sizeof a->name) == 0 &&
             (attr_text(g, "sha256", a->sha256, sizeof a->sha256) == 0 || format == 1);
    if (g >= 0)
      H5Gclose(g);
    if (!ok) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/arches",
                        "expected attributes name and sha256 in arch group %llu, "
                        "got none readable", (unsigned long long)k);
      goto done;
    }
    out->narches++;
  }
done:
  H5E_BEGIN_TRY
  {
    if (mt >= 0)
      H5Tclose(mt);
    if (arches >= 0)
      H5Gclose(arches);
    if (f >= 0)
      H5Fclose(f);
  }
  H5E_END_TRY;
  H5Eclear2(H5E_DEFAULT);
  if (st != AQ_OK)
    aq_h5_suite_free(out);
  return st;
}
