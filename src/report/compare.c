/* compare.c: matching and comparing two suites (see compare.h), and
 * reading a suite back from a results file (aq_h5_read_suite, see h5.h). */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"

#include <errno.h>
#include <hdf5.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int aq_compare_close(double a, double b, double rtol, double atol)
{
  if (isnan(a) || isnan(b))
    return isnan(a) && isnan(b);
  if (a == b) /* equal infinities too */
    return 1;
  double m = fmax(fabs(a), fabs(b));
  return fabs(a - b) <= atol + rtol * m;
}

static int ignored(const aq_compare_opts *o, const char *name)
{
  for (size_t k = 0; k < o->nignore; k++)
    if (strcmp(o->ignore[k], name) == 0)
      return 1;
  return 0;
}

/* ---- identity of a run -------------------------------------------------- */

typedef struct {
  const aq_summary *s;
  const char *record; /* display: the record's file name */
  const char *rec_id; /* sha256 of the record (its name if ignored or unknown) */
  const char *arch;   /* arch name */
  const char *arch_id;/* sha256 of its .cfg ("" if ignored) */
  size_t index;
} entry;

/* The key fields of the summary that are compared as values of the key:
 * all but the record's path and the arch's name, which the identities
 * replace. */
static int key_field(const aq_summary_field *f)
{
  return f->key && strcmp(f->name, "record") != 0 && strcmp(f->name, "arch") != 0;
}

static int cmp_double(double x, double y)
{
  if (isnan(x) || isnan(y))
    return isnan(x) - isnan(y); /* NaN after every number */
  return (x > y) - (x < y);
}

/* Order of two key fields' values; with tol (a tolerance), doubles that
 * agree within it are equal. */
static int cmp_field(const aq_summary *x, const aq_summary *y,
                     const aq_summary_field *f, const aq_compare_opts *tol)
{
  switch (f->kind) {
  case AQ_SF_STR:
    return strcmp(aq_summary_get_str(x, f), aq_summary_get_str(y, f));
  case AQ_SF_INT: {
    int64_t a = aq_summary_get_int(x, f), b = aq_summary_get_int(y, f);
    return (a > b) - (a < b);
  }
  case AQ_SF_DOUBLE: {
    double a = aq_summary_get_double(x, f), b = aq_summary_get_double(y, f);
    if (tol && aq_compare_close(a, b, tol->rtol, tol->atol))
      return 0;
    return cmp_double(a, b);
  }
  }
  return 0;
}

static int cmp_key(const entry *a, const entry *b, const aq_compare_opts *tol)
{
  int c = strcmp(a->rec_id, b->rec_id);
  if (c == 0)
    c = strcmp(a->arch, b->arch);
  if (c == 0)
    c = strcmp(a->arch_id, b->arch_id);
  for (size_t i = 0; c == 0 && i < aq_summary_nfields; i++)
    if (key_field(&aq_summary_fields[i]))
      c = cmp_field(a->s, b->s, &aq_summary_fields[i], tol);
  return c;
}

static int cmp_entry(const void *pa, const void *pb)
{
  const entry *a = pa, *b = pb;
  int c = cmp_key(a, b, NULL);
  if (c == 0)
    c = (a->index > b->index) - (a->index < b->index);
  return c;
}

static const aq_h5_input *input_at(const aq_h5_input *v, size_t n, int64_t i)
{
  return i >= 0 && (uint64_t)i < n ? &v[i] : NULL;
}

/* 1 if an input of either file has no content hash (a file of the first
 * format, or a record that could not be read): then inputs are matched by
 * name in both, and their contents not compared. */
static int some_unhashed(const aq_h5_input *a, size_t na, const aq_h5_input *b, size_t nb)
{
  for (size_t k = 0; k < na; k++)
    if (!a[k].sha256[0])
      return 1;
  for (size_t k = 0; k < nb; k++)
    if (!b[k].sha256[0])
      return 1;
  return 0;
}

static entry *sorted(const aq_h5_suite *S, int by_rec_name, int by_arch_name)
{
  entry *e = malloc((S->nruns ? S->nruns : 1) * sizeof *e);
  if (!e)
    return NULL;
  for (size_t i = 0; i < S->nruns; i++) {
    const aq_h5_run *r = &S->runs[i];
    const aq_h5_input *rec = input_at(S->records, S->nrecords, r->record_index);
    const aq_h5_input *arch = input_at(S->arches, S->narches, r->arch_index);
    e[i].s = &r->s;
    e[i].record = rec && rec->name[0] ? rec->name : r->s.record;
    e[i].rec_id = rec && !by_rec_name ? rec->sha256 : e[i].record;
    e[i].arch = r->s.arch;
    e[i].arch_id = arch && !by_arch_name ? arch->sha256 : "";
    e[i].index = i;
  }
  qsort(e, S->nruns, sizeof *e, cmp_entry);
  return e;
}

/* ---- configuration ------------------------------------------------------ */

static size_t config_row(const char *record, const char *arch, const char *name,
                         const char *va, const char *vb, int counts,
                         aq_diff_fn fn, void *ctx)
{
  aq_diff d = {AQ_DIFF_CONFIG, NULL, NULL, record, arch, NULL, NAN, name, va, vb, counts};
  if (fn)
    fn(ctx, &d);
  return counts ? 1 : 0;
}

/* Settings present in one file only, or with other values. */
static size_t compare_settings(const aq_h5_suite *a, const aq_h5_suite *b,
                               const aq_compare_opts *o, aq_diff_fn fn, void *ctx)
{
  size_t nd = 0;
  for (int side = 0; side < 2; side++) {
    const aq_h5_suite *x = side ? b : a, *y = side ? a : b;
    for (size_t i = 0; i < x->nsettings; i++) {
      const aq_h5_setting *sx = &x->settings[i];
      const aq_h5_setting *sy = NULL;
      for (size_t j = 0; j < y->nsettings && !sy; j++)
        if (strcmp(y->settings[j].name, sx->name) == 0)
          sy = &y->settings[j];
      if ((side == 1 && sy) || (sy && strcmp(sx->value, sy->value) == 0) ||
          ignored(o, sx->name))
        continue; /* the pair was seen from a's side */
      /* the version and the build are shown, but do not make files differ;
       * nor does a setting that one file does not state (written before
       * it existed: its runs say what it did) */
      int counts = strncmp(sx->name, "archquake_", 10) != 0 && sy != NULL;
      const char *va = side ? (sy ? sy->value : "") : sx->value;
      const char *vb = side ? sx->value : (sy ? sy->value : "");
      nd += config_row(NULL, NULL, sx->name, va, vb, counts, fn, ctx);
    }
  }
  return nd;
}

static int has_input(const aq_h5_input *v, size_t n, const char *name,
                     const char *sha)
{
  for (size_t k = 0; k < n; k++)
    if (strcmp(v[k].name, name) == 0 && strcmp(v[k].sha256, sha) == 0)
      return 1;
  return 0;
}

/* The distinct contents of the inputs of x named name that y has no input
 * of that name and content for, into out (at most nx); returns their number. */
static size_t contents_only(const aq_h5_input *x, size_t nx, const aq_h5_input *y,
                            size_t ny, const char *name, const char **out)
{
  size_t n = 0;
  for (size_t k = 0; k < nx; k++) {
    if (strcmp(x[k].name, name) != 0 || has_input(y, ny, name, x[k].sha256) ||
        has_input(x, k, name, x[k].sha256))
      continue;
    out[n++] = x[k].sha256;
  }
  return n;
}

/* Inputs of one name whose contents differ between the files: the contents
 * of a not in b are paired, in order, with those of b not in a.  Returns the
 * number of rows, or (size_t)-1 when out of memory. */
static size_t compare_inputs(const aq_h5_input *a, size_t na, const aq_h5_input *b,
                             size_t nb, int is_arch, aq_diff_fn fn, void *ctx)
{
  size_t nd = 0;
  const char **la = malloc((na ? na : 1) * sizeof *la);
  const char **lb = malloc((nb ? nb : 1) * sizeof *lb);
  if (!la || !lb) {
    free(la);
    free(lb);
    return (size_t)-1;
  }
  for (size_t i = 0; i < na; i++) {
    int seen = 0;
    for (size_t k = 0; k < i && !seen; k++)
      seen = strcmp(a[k].name, a[i].name) == 0;
    if (seen)
      continue;
    size_t ka = contents_only(a, na, b, nb, a[i].name, la);
    size_t kb = contents_only(b, nb, a, na, a[i].name, lb);
    for (size_t k = 0; k < ka && k < kb; k++)
      nd += config_row(is_arch ? NULL : a[i].name, is_arch ? a[i].name : NULL,
                       is_arch ? "arch_sha256" : "record_sha256", la[k], lb[k], 1,
                       fn, ctx);
  }
  free(la);
  free(lb);
  return nd;
}

/* ---- runs ------------------------------------------------------------------ */

static size_t compare_pair(const entry *ea, const entry *eb,
                           const aq_compare_opts *o, aq_diff_fn fn, void *ctx)
{
  const aq_summary *a = ea->s, *b = eb->s;
  size_t nd = 0;
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    if (f->key || ignored(o, f->name))
      continue;
    aq_diff d = {AQ_DIFF_VALUE, a, b, ea->record, ea->arch, f, NAN, NULL, NULL, NULL, 1};
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
      same = aq_compare_close(x, y, o->rtol, o->atol);
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

size_t aq_compare_suites(const aq_h5_suite *A, const aq_h5_suite *B,
                         const aq_compare_opts *o, aq_diff_fn fn, void *ctx)
{
  int by_name[2] = {
      ignored(o, "record_sha256") ||
          some_unhashed(A->records, A->nrecords, B->records, B->nrecords),
      ignored(o, "arch_sha256") || some_unhashed(A->arches, A->narches, B->arches, B->narches)};
  entry *ea = sorted(A, by_name[0], by_name[1]), *eb = sorted(B, by_name[0], by_name[1]);
  if (!ea || !eb) {
    free(ea);
    free(eb);
    return (size_t)-1;
  }
  size_t nd = compare_settings(A, B, o, fn, ctx);
  for (int is_arch = 0; is_arch < 2; is_arch++) {
    if (by_name[is_arch])
      continue;
    size_t k = is_arch ? compare_inputs(A->arches, A->narches, B->arches, B->narches, 1, fn, ctx)
                       : compare_inputs(A->records, A->nrecords, B->records, B->nrecords, 0,
                                        fn, ctx);
    if (k == (size_t)-1) {
      free(ea);
      free(eb);
      return k;
    }
    nd += k;
  }
  size_t i = 0, j = 0, na = A->nruns, nb = B->nruns;
  while (i < na || j < nb) {
    int c = i == na ? 1 : j == nb ? -1 : cmp_key(&ea[i], &eb[j], o);
    if (c == 0) {
      nd += compare_pair(&ea[i], &eb[j], o, fn, ctx);
      i++;
      j++;
    } else {
      const entry *e = c < 0 ? &ea[i] : &eb[j];
      aq_diff d = {c < 0 ? AQ_DIFF_ONLY_A : AQ_DIFF_ONLY_B,
                   c < 0 ? e->s : NULL, c < 0 ? NULL : e->s, e->record, e->arch,
                   NULL, NAN, NULL, NULL, NULL, 1};
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
