/* read.c: the results and capacity files for the page (read.h): the kind
 * of a file, then every attribute and column it holds as text. */
#include <errno.h>
#include <hdf5.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../report/text.h"
#include "read.h"

/* The format this build's page reads (the tables of format 2). */
static const long PAGE_FORMAT = AQ_H5_FORMAT_VERSION;

static void attrs_free(aq_page_attrs *a)
{
  for (size_t i = 0; i < a->n; i++)
    free(a->value[i]);
  free(a->name);
  free(a->value);
  free(a->num);
  memset(a, 0, sizeof *a);
}

static void table_free(aq_page_table *t)
{
  for (size_t i = 0; i < t->nrow * t->ncol; i++)
    free(t->cell[i]);
  free(t->col);
  free(t->cell);
  free(t->num);
  memset(t, 0, sizeof *t);
}

void aq_page_results_free(aq_page_results *r)
{
  attrs_free(&r->root);
  table_free(&r->records);
  for (size_t i = 0; i < r->narch; i++) {
    attrs_free(&r->arch[i]);
    if (r->geom)
      attrs_free(&r->geom[i]);
  }
  free(r->arch);
  free(r->geom);
  aq_h5_suite_free(&r->suite);
  memset(r, 0, sizeof *r);
}

/* The value of attribute or dataset element data of type t (npoints
 * elements) as text; *num the number if it is one. */
static char *value_text(hid_t t, const void *data, size_t npoints, double *num)
{
  *num = NAN;
  H5T_class_t cls = H5Tget_class(t);
  size_t sz = H5Tget_size(t);
  if (cls == H5T_STRING) {
    char *s = malloc(sz + 1);
    if (s) {
      memcpy(s, data, sz);
      s[sz] = '\0';
    }
    return s;
  }
  char *s = malloc(npoints * 32 + 1);
  if (!s)
    return NULL;
  s[0] = '\0';
  for (size_t i = 0; i < npoints; i++) {
    double v = ((const double *)data)[i];
    char one[AQ_TEXT_NUM_MAX];
    aq_text_double(one, sizeof one, v); /* the shortest that reads back */
    strcat(s, i ? ", " : "");
    strcat(s, one);
    if (npoints == 1)
      *num = v;
  }
  return s;
}

typedef struct {
  aq_page_attrs *a;
  int failed;
} iter_ctx;

static herr_t one_attr(hid_t loc, const char *name, const H5A_info_t *info, void *op)
{
  (void)info;
  iter_ctx *c = op;
  aq_page_attrs *a = c->a;
  hid_t at = H5Aopen(loc, name, H5P_DEFAULT);
  hid_t t = at >= 0 ? H5Aget_type(at) : -1, s = at >= 0 ? H5Aget_space(at) : -1;
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
  H5T_class_t cls = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  char *text = NULL;
  double num = NAN;
  if (np >= 1 && cls == H5T_STRING && np == 1 && H5Tis_variable_str(t) == 0) {
    size_t sz = H5Tget_size(t);
    char *buf = calloc(sz + 1, 1);
    hid_t m = H5Tcopy(H5T_C_S1);
    if (buf && m >= 0 && H5Tset_size(m, sz) >= 0 && H5Aread(at, m, buf) >= 0)
      text = value_text(m, buf, 1, &num);
    if (m >= 0)
      H5Tclose(m);
    free(buf);
  } else if (np >= 1 && (cls == H5T_FLOAT || cls == H5T_INTEGER)) {
    double *v = malloc((size_t)np * sizeof *v);
    if (v && H5Aread(at, H5T_NATIVE_DOUBLE, v) >= 0)
      text = value_text(H5T_NATIVE_DOUBLE, v, (size_t)np, &num);
    free(v);
  }
  if (s >= 0)
    H5Sclose(s);
  if (t >= 0)
    H5Tclose(t);
  if (at >= 0)
    H5Aclose(at);
  if (!text)
    return 0; /* another kind of attribute: not shown */
  size_t k = a->n;
  char(*nm)[64] = realloc(a->name, (k + 1) * sizeof *nm);
  if (nm)
    a->name = nm;
  char **vv = realloc(a->value, (k + 1) * sizeof *vv);
  if (vv)
    a->value = vv;
  double *nn = realloc(a->num, (k + 1) * sizeof *nn);
  if (nn)
    a->num = nn;
  if (!nm || !vv || !nn) {
    free(text);
    c->failed = 1;
    return -1;
  }
  snprintf(a->name[k], sizeof a->name[k], "%s", name);
  a->value[k] = text;
  a->num[k] = num;
  a->n++;
  return 0;
}

static int read_attrs(hid_t loc, aq_page_attrs *a)
{
  memset(a, 0, sizeof *a);
  iter_ctx c = {a, 0};
  hsize_t idx = 0;
  if (H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, &idx, one_attr, &c) < 0 || c.failed)
    return -1;
  return 0;
}

/* Every column of the compound table at name, as text and numbers. */
static int read_table(hid_t f, const char *name, aq_page_table *t)
{
  memset(t, 0, sizeof *t);
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  if (d < 0)
    return -1;
  hid_t ft = H5Dget_type(d), s = H5Dget_space(d);
  hssize_t nrow = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
  int nm = ft >= 0 && H5Tget_class(ft) == H5T_COMPOUND ? H5Tget_nmembers(ft) : -1;
  int rc = -1;
  if (nrow < 0 || nm <= 0)
    goto out;
  t->ncol = (size_t)nm;
  t->nrow = (size_t)nrow;
  t->col = calloc(t->ncol, sizeof *t->col);
  t->cell = calloc(t->ncol * t->nrow + 1, sizeof *t->cell);
  t->num = calloc(t->ncol * t->nrow + 1, sizeof *t->num);
  if (!t->col || !t->cell || !t->num)
    goto out;
  for (int j = 0; j < nm; j++) {
    char *mname = H5Tget_member_name(ft, (unsigned)j);
    hid_t mt0 = H5Tget_member_type(ft, (unsigned)j);
    int is_str = mt0 >= 0 && H5Tget_class(mt0) == H5T_STRING;
    int is_num = mt0 >= 0 && (H5Tget_class(mt0) == H5T_FLOAT || H5Tget_class(mt0) == H5T_INTEGER);
    int is_vstr = is_str && H5Tis_variable_str(mt0) > 0; /* a string kept whole */
    size_t sz = is_vstr ? sizeof(char *) : is_str ? H5Tget_size(mt0) : sizeof(double);
    snprintf(t->col[j], sizeof t->col[j], "%s", mname ? mname : "?");
    hid_t st = -1, mem = -1;
    if (is_str) {
      st = H5Tcopy(H5T_C_S1);
      H5Tset_size(st, is_vstr ? H5T_VARIABLE : sz);
    }
    char *buf = (is_str || is_num) && mname ? malloc((size_t)nrow * sz + 1) : NULL;
    if (buf) {
      mem = H5Tcreate(H5T_COMPOUND, sz);
      H5Tinsert(mem, mname, 0, is_str ? st : H5T_NATIVE_DOUBLE);
    }
    int got = buf && (nrow == 0 || H5Dread(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    if (got)
      for (size_t i = 0; i < (size_t)nrow; i++) {
        double num = NAN;
        size_t k = i * t->ncol + (size_t)j;
        const char *vs = is_vstr ? *(char **)(void *)(buf + i * sz) : NULL;
        t->cell[k] = is_vstr ? strdup(vs ? vs : "")
                             : value_text(is_str ? st : H5T_NATIVE_DOUBLE, buf + i * sz, 1, &num);
        t->num[k] = is_vstr ? NAN : num;
      }
    if (got && is_vstr && nrow > 0) { /* the strings HDF5 allocated */
      hid_t ms = H5Dget_space(d);
      if (ms >= 0) {
        H5Dvlen_reclaim(mem, ms, H5P_DEFAULT, buf);
        H5Sclose(ms);
      }
    }
    for (size_t i = 0; i < (size_t)nrow; i++) { /* a column not read: empty */
      size_t k = i * t->ncol + (size_t)j;
      if (!t->cell[k]) {
        t->cell[k] = calloc(1, 1);
        t->num[k] = NAN;
      }
    }
    free(buf);
    if (mem >= 0)
      H5Tclose(mem);
    if (st >= 0)
      H5Tclose(st);
    if (mt0 >= 0)
      H5Tclose(mt0);
    H5free_memory(mname);
  }
  rc = 0;
  for (size_t k = 0; k < t->ncol * t->nrow; k++)
    if (!t->cell[k])
      rc = -1;
out:
  if (s >= 0)
    H5Sclose(s);
  if (ft >= 0)
    H5Tclose(ft);
  H5Dclose(d);
  return rc;
}

aq_status aq_page_file_kind(const char *path, aq_page_kind *kind, aq_error *err)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  FILE *fp = fopen(path, "rb");
  if (!fp)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot open: %s", strerror(errno));
  fclose(fp);
  if (H5Fis_hdf5(path) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                        "expected an archquake results file (HDF5), got something else");
  }
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
  aq_status st = AQ_OK;
  long format = 0;
  if (H5Aexists(f, "format_version") > 0) {
    hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    int64_t v = 0;
    if (a >= 0 && H5Aread(a, H5T_NATIVE_INT64, &v) >= 0)
      format = (long)v;
    if (a >= 0)
      H5Aclose(a);
  }
  if (format == 0)
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "format_version",
                      "expected an archquake results file, got an HDF5 file without "
                      "format_version (not written by archquake)");
  else if (format != PAGE_FORMAT)
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "format_version",
                      "expected format_version %ld, got %ld: the report reads files of "
                      "format_version %ld (archquake %s); run the suite again with this "
                      "archquake", PAGE_FORMAT, format, PAGE_FORMAT,
                      format < PAGE_FORMAT ? "since the /summary and /records tables"
                                           : "up to this build");
  else {
    /* the root's kind, else (a file written before it) what it holds */
    char k[32] = "";
    hid_t a = H5Aexists(f, "kind") > 0 ? H5Aopen(f, "kind", H5P_DEFAULT) : -1;
    hid_t at = a >= 0 ? H5Aget_type(a) : -1;
    if (at >= 0 && H5Tget_class(at) == H5T_STRING && !H5Tis_variable_str(at) &&
        H5Tget_size(at) < sizeof k && H5Aread(a, at, k) < 0)
      k[0] = '\0';
    if (at >= 0)
      H5Tclose(at);
    if (a >= 0)
      H5Aclose(a);
    if (!strcmp(k, "capacity") || (!k[0] && H5Lexists(f, "capacity", H5P_DEFAULT) > 0))
      *kind = AQ_PAGE_CAPACITY;
    else if (!strcmp(k, "select") || (!k[0] && H5Lexists(f, "select", H5P_DEFAULT) > 0))
      *kind = AQ_PAGE_SELECT;
    else if (!strcmp(k, "spectrum") || (!k[0] && H5Lexists(f, "spectra", H5P_DEFAULT) > 0))
      *kind = AQ_PAGE_SPECTRUM;
    else if (!k[0] || !strcmp(k, "results"))
      *kind = AQ_PAGE_RESULTS;
    else
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "kind",
                        "expected a results, capacity, select or spectrum file, got a file "
                        "of kind \"%s\" (a later archquake's: report it with that one)", k);
  }
  H5Fclose(f);
  return st;
}

aq_status aq_page_results_read(const char *path, aq_page_results *r, aq_error *err)
{
  memset(r, 0, sizeof *r);
  aq_page_kind kind;
  aq_status st = aq_page_file_kind(path, &kind, err);
  if (st != AQ_OK)
    return st;
  st = aq_h5_read_suite(path, &r->suite, err); /* runs only in a results file */
  if (st != AQ_OK)
    return st;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
  if (read_attrs(f, &r->root) != 0)
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/", "cannot read the root attributes");
  else if (read_table(f, "/records", &r->records) != 0)
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/records",
                      "expected the record table, got none readable");
  r->have_histories = H5Lexists(f, "histories", H5P_DEFAULT) > 0;
  /* the arches (none in a spectrum file) */
  int arches = kind != AQ_PAGE_SPECTRUM || H5Lexists(f, "arches", H5P_DEFAULT) > 0;
  hid_t g = st == AQ_OK && arches ? H5Gopen2(f, "/arches", H5P_DEFAULT) : -1;
  H5G_info_t info = {0};
  if (st == AQ_OK && arches && (g < 0 || H5Gget_info(g, &info) < 0))
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/arches", "expected the arch groups");
  if (st == AQ_OK) {
    r->arch = calloc(info.nlinks + 1, sizeof *r->arch);
    r->geom = calloc(info.nlinks + 1, sizeof *r->geom);
    for (hsize_t k = 0; r->arch && r->geom && k < info.nlinks; k++) {
      char name[32];
      snprintf(name, sizeof name, "%03llu", (unsigned long long)k);
      hid_t a = H5Gopen2(g, name, H5P_DEFAULT);
      if (a < 0 || read_attrs(a, &r->arch[k]) != 0) {
        st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/arches",
                          "cannot read the attributes of /arches/%s", name);
        if (a >= 0)
          H5Gclose(a);
        break;
      }
      r->narch++;
      H5Gclose(a);
      /* its geometry, where the file keeps it */
      char gname[48];
      snprintf(gname, sizeof gname, "/geometry/%s", name);
      hid_t gg = -1;
      if (H5Lexists(f, "geometry", H5P_DEFAULT) > 0 && H5Lexists(f, gname, H5P_DEFAULT) > 0)
        gg = H5Gopen2(f, gname, H5P_DEFAULT);
      int bad = gg >= 0 && read_attrs(gg, &r->geom[k]) != 0;
      if (gg >= 0)
        H5Gclose(gg);
      if (bad) {
        st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/geometry",
                          "cannot read the attributes of %s", gname);
        break;
      }
    }
    if (!r->arch || !r->geom)
      st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  }
  if (g >= 0)
    H5Gclose(g);
  H5Fclose(f);
  if (st != AQ_OK)
    aq_page_results_free(r);
  return st;
}

const char *aq_page_attr(const aq_page_attrs *a, const char *name)
{
  for (size_t i = 0; i < a->n; i++)
    if (strcmp(a->name[i], name) == 0)
      return a->value[i];
  return NULL;
}

double aq_page_attr_num(const aq_page_attrs *a, const char *name)
{
  for (size_t i = 0; i < a->n; i++)
    if (strcmp(a->name[i], name) == 0)
      return a->num[i];
  return NAN;
}

long aq_page_col(const aq_page_table *t, const char *name)
{
  for (size_t j = 0; j < t->ncol; j++)
    if (strcmp(t->col[j], name) == 0)
      return (long)j;
  return -1;
}

const char *aq_page_cell(const aq_page_table *t, size_t row, const char *name)
{
  long j = aq_page_col(t, name);
  return j < 0 || row >= t->nrow ? "" : t->cell[row * t->ncol + (size_t)j];
}

double aq_page_cell_num(const aq_page_table *t, size_t row, const char *name)
{
  long j = aq_page_col(t, name);
  return j < 0 || row >= t->nrow ? NAN : t->num[row * t->ncol + (size_t)j];
}
