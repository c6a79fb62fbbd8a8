/* compare.c: matching and comparing run summaries (see compare.h), and
 * reading them back from a results file (aq_h5_read_runs, see h5.h). */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "h5.h"

int aq_compare_close(double a, double b, double rtol, double atol)
{
  if (isnan(a) || isnan(b))
    return isnan(a) && isnan(b);
  if (a == b) /* equal infinities too */
    return 1;
  double m = fmax(fabs(a), fabs(b));
  return fabs(a - b) <= atol + rtol * m;
}

/* ---- matching ----------------------------------------------------------- */

typedef struct {
  const aq_summary *s;
  size_t index;
} entry;

static int cmp_scale(double x, double y)
{
  if (isnan(x) || isnan(y))
    return isnan(x) - isnan(y); /* NaN after every number */
  return (x > y) - (x < y);
}

static int cmp_key(const aq_summary *x, const aq_summary *y)
{
  int c = strcmp(x->record, y->record);
  if (c == 0)
    c = strcmp(x->arch, y->arch);
  return c;
}

static int cmp_entry(const void *pa, const void *pb)
{
  const entry *a = pa, *b = pb;
  int c = cmp_key(a->s, b->s);
  if (c == 0)
    c = cmp_scale(a->s->scale, b->s->scale);
  if (c == 0)
    c = (a->index > b->index) - (a->index < b->index);
  return c;
}

static entry *sorted(const aq_summary *s, size_t n)
{
  entry *e = malloc((n ? n : 1) * sizeof *e);
  if (!e)
    return NULL;
  for (size_t i = 0; i < n; i++) {
    e[i].s = &s[i];
    e[i].index = i;
  }
  qsort(e, n, sizeof *e, cmp_entry);
  return e;
}

static size_t compare_pair(const aq_summary *a, const aq_summary *b,
                           double rtol, double atol, aq_diff_fn fn, void *ctx)
{
  size_t nd = 0;
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    if (f->key)
      continue;
    aq_diff d = {AQ_DIFF_VALUE, a, b, f, NAN};
    int same = 1;
    switch (f->kind) {
    case AQ_SF_STR:
      same = strcmp(aq_summary_get_str(a, f), aq_summary_get_str(b, f)) == 0;
      break;
    case AQ_SF_INT: {
      int64_t x = aq_summary_get_int(a, f), y = aq_summary_get_int(b, f);
      same = x == y;
      double m = fmax(fabs((double)x), fabs((double)y));
      d.rel = x == AQ_SUMMARY_INT_NONE || y == AQ_SUMMARY_INT_NONE ? NAN
              : m > 0                                              ? fabs((double)x - (double)y) / m
                                                                   : 0;
      break;
    }
    case AQ_SF_DOUBLE: {
      double x = aq_summary_get_double(a, f), y = aq_summary_get_double(b, f);
      same = aq_compare_close(x, y, rtol, atol);
      double m = fmax(fabs(x), fabs(y));
      d.rel = isnan(x) || isnan(y) ? NAN : m > 0 ? fabs(x - y) / m : 0;
      break;
    }
    }
    if (!same) {
      nd++;
      if (fn)
        fn(ctx, &d);
    }
  }
  return nd;
}

size_t aq_compare_runs(const aq_summary *a, size_t na, const aq_summary *b,
                       size_t nb, double rtol, double atol, aq_diff_fn fn,
                       void *ctx)
{
  entry *ea = sorted(a, na), *eb = sorted(b, nb);
  if (!ea || !eb) {
    free(ea);
    free(eb);
    return (size_t)-1;
  }
  size_t i = 0, j = 0, nd = 0;
  while (i < na || j < nb) {
    int c;
    if (i == na)
      c = 1;
    else if (j == nb)
      c = -1;
    else {
      c = cmp_key(ea[i].s, eb[j].s);
      if (c == 0 &&
          !aq_compare_close(ea[i].s->scale, eb[j].s->scale, rtol, atol))
        c = cmp_scale(ea[i].s->scale, eb[j].s->scale);
    }
    if (c == 0) {
      nd += compare_pair(ea[i].s, eb[j].s, rtol, atol, fn, ctx);
      i++;
      j++;
    } else {
      aq_diff d = {c < 0 ? AQ_DIFF_ONLY_A : AQ_DIFF_ONLY_B,
                   c < 0 ? ea[i].s : NULL, c < 0 ? NULL : eb[j].s, NULL, NAN};
      nd++;
      if (fn)
        fn(ctx, &d);
      if (c < 0)
        i++;
      else
        j++;
    }
  }
  free(ea);
  free(eb);
  return nd;
}

/* ---- reading a results file --------------------------------------------- */

/* Read string attribute name of loc into buf[n] (fixed or variable length).
 * Returns 0 or -1. */
static int read_attr_str(hid_t loc, const char *name, char *buf, size_t n)
{
  int ok = -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0)
    return -1;
  hid_t t = H5Aget_type(a);
  if (t >= 0 && H5Tget_class(t) == H5T_STRING) {
    htri_t var = H5Tis_variable_str(t);
    if (var > 0) {
      hid_t m = H5Tcopy(H5T_C_S1);
      char *p = NULL;
      if (m >= 0 && H5Tset_size(m, H5T_VARIABLE) >= 0 &&
          H5Aread(a, m, &p) >= 0) {
        snprintf(buf, n, "%s", p ? p : "");
        H5free_memory(p);
        ok = 0;
      }
      if (m >= 0)
        H5Tclose(m);
    } else if (var == 0) {
      size_t sz = H5Tget_size(t);
      char *tmp = sz ? malloc(sz + 1) : NULL;
      hid_t m = H5Tcopy(H5T_C_S1);
      if (tmp && m >= 0 && H5Tset_size(m, sz) >= 0 &&
          H5Tset_strpad(m, H5T_STR_NULLPAD) >= 0 && H5Aread(a, m, tmp) >= 0) {
        tmp[sz] = '\0';
        snprintf(buf, n, "%s", tmp);
        ok = 0;
      }
      if (m >= 0)
        H5Tclose(m);
      free(tmp);
    }
  }
  if (t >= 0)
    H5Tclose(t);
  H5Aclose(a);
  return ok;
}

static int read_attr_num(hid_t loc, const char *name, hid_t mtype, void *out)
{
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0)
    return -1;
  int ok = -1;
  hid_t s = H5Aget_space(a);
  if (s >= 0 && H5Sget_simple_extent_npoints(s) == 1 &&
      H5Aread(a, mtype, out) >= 0)
    ok = 0;
  if (s >= 0)
    H5Sclose(s);
  H5Aclose(a);
  return ok;
}

aq_status aq_h5_read_runs(const char *path, aq_summary **out, size_t *n,
                          aq_error *err)
{
  *out = NULL;
  *n = 0;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  aq_status st = AQ_OK;
  hid_t f = -1, runs = -1;
  aq_summary *v = NULL;
  htri_t is = H5Fis_hdf5(path);
  if (is <= 0) {
    H5Eclear2(H5E_DEFAULT);
    FILE *fp = fopen(path, "rb");
    if (!fp)
      return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                          "cannot open: %s", strerror(errno));
    fclose(fp);
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                        "expected an HDF5 file, got something else");
  }
  f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) {
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
    goto done;
  }
  runs = H5Gopen2(f, "/runs", H5P_DEFAULT);
  if (runs < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/runs",
                      "expected an archquake results file (group /runs), "
                      "got none");
    goto done;
  }
  H5G_info_t info;
  if (H5Gget_info(runs, &info) < 0) {
    st = aq_error_set(err, AQ_EIO, path, -1, -1, "/runs", "HDF5: H5Gget_info failed");
    goto done;
  }
  v = calloc(info.nlinks ? info.nlinks : 1, sizeof *v);
  if (!v) {
    st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (hsize_t k = 0; k < info.nlinks; k++) {
    char name[256], obj[300];
    if (H5Lget_name_by_idx(runs, ".", H5_INDEX_NAME, H5_ITER_INC, k, name,
                           sizeof name, H5P_DEFAULT) < 0) {
      st = aq_error_set(err, AQ_EIO, path, -1, -1, "/runs",
                        "HDF5: cannot read link %llu", (unsigned long long)k);
      goto done;
    }
    snprintf(obj, sizeof obj, "/runs/%s", name);
    hid_t g = H5Gopen2(runs, name, H5P_DEFAULT);
    if (g < 0) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                        "expected a run group, got something else");
      goto done;
    }
    aq_summary *s = &v[k];
    aq_summary_fill(s, "", "", "", NAN, NAN, "", NULL); /* what an older file lacks */
    for (size_t i = 0; i < aq_summary_nfields; i++) {
      const aq_summary_field *fl = &aq_summary_fields[i];
      char *p = (char *)s + fl->offset;
      int rc = -1;
      if (fl->optional && H5Aexists(g, fl->name) == 0)
        continue;
      switch (fl->kind) {
      case AQ_SF_STR:
        rc = read_attr_str(g, fl->name, p, fl->size);
        break;
      case AQ_SF_DOUBLE:
        rc = read_attr_num(g, fl->name, H5T_NATIVE_DOUBLE, p);
        break;
      case AQ_SF_INT:
        rc = read_attr_num(g, fl->name, H5T_NATIVE_INT64, p);
        break;
      }
      if (rc < 0) {
        H5Gclose(g);
        H5Eclear2(H5E_DEFAULT);
        st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                          "expected attribute %s (%s), got none readable",
                          fl->name,
                          fl->kind == AQ_SF_STR      ? "string"
                          : fl->kind == AQ_SF_DOUBLE ? "number"
                                                     : "integer");
        goto done;
      }
    }
    H5Gclose(g);
  }
  *out = v;
  *n = info.nlinks;
  v = NULL;
done:
  free(v);
  H5E_BEGIN_TRY
  {
    if (runs >= 0)
      H5Gclose(runs);
    if (f >= 0)
      H5Fclose(f);
  }
  H5E_END_TRY;
  return st;
}
