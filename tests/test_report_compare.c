/* test_report_compare.c: matching and comparing run summaries, in memory
 * and through `archquake compare` on files whose copy is perturbed through
 * the HDF5 API. */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "report/compare.h"
#include "report/h5.h"
#include "report/report.h"

enum { NRUN = 6 };

static void make_runs(aq_summary *s)
{
  static const char *const rec[3] = {"records/b.AT2", "records/a.sac", "records/c.csv"};
  for (int k = 0; k < NRUN; k++) {
    aq_result r;
    memset(&r, 0, sizeof r);
    r.collapsed = k % 3 == 1;
    r.collapse_time_s = r.collapsed ? 4.1875 + 0.37 * k : NAN;
    r.peak_rotation_rad = 0.0137 * (k + 1.618);
    r.peak_displacement_m = 0.00731 * (k + 2.718);
    r.max_kinetic_energy_j = 314.159 * (k + 0.577);
    r.impacts = (size_t)(k * 5 + 1);
    r.energy_in_j = 1234.5 * (k + 1.414);
    r.energy_dissipated_j = k ? 87.125 * k : 0;
    aq_summary_fill(&s[k], rec[k % 3], k < 3 ? "oppenheim" : "thin", "workpath",
                    k % 2 ? 1.5 : 0.75, 0.2816 * (k % 2 ? 1.5 : 0.75), "ok", &r);
  }
}

typedef struct {
  size_t n;
  char field[8][32];
  aq_diff_kind kind[8];
  double rel[8];
  double scale[8]; /* of the run the difference is about */
} diffs;

static void collect(void *ctx, const aq_diff *d)
{
  diffs *x = ctx;
  if (x->n < 8) {
    snprintf(x->field[x->n], 32, "%s", d->field ? d->field->name : "-");
    x->kind[x->n] = d->kind;
    x->rel[x->n] = d->rel;
    x->scale[x->n] = d->a ? d->a->scale : d->b->scale;
  }
  x->n++;
}

AQ_TEST(report_compare_tolerance_and_matching)
{
  aq_summary a[NRUN], b[NRUN];
  make_runs(a);
  make_runs(b);
  diffs d = {0};
  /* identical, in a different order */
  aq_summary rev[NRUN];
  for (int k = 0; k < NRUN; k++)
    rev[k] = b[NRUN - 1 - k];
  aq_check(aq_compare_runs(a, NRUN, rev, NRUN, 0, 0, collect, &d) == 0 && d.n == 0,
           "identical runs in any order agree exactly (%zu)", d.n);

  /* one value moved by 3e-7 relative: beyond 1e-7, within 1e-6 */
  double v = b[4].peak_displacement_m;
  b[4].peak_displacement_m = v * (1 + 3e-7);
  memset(&d, 0, sizeof d);
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 1e-7, 0, collect, &d) == 1, "one difference");
  aq_check(strcmp(d.field[0], "peak_displacement_m") == 0, "names the field: %s",
           d.field[0]);
  aq_check_rel(d.rel[0], 3e-7 / (1 + 3e-7), 2e-9, "relative difference");
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 1e-6, 0, NULL, NULL) == 0, "within 1e-6");
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 2e-7, 0, NULL, NULL) == 1, "beyond 2e-7");
  /* the rule atol + rtol max(|a|, |b|), at literal numbers */
  aq_check(aq_compare_close(100.0, 100.00015, 1e-6, 0) == 0, "1.5e-6 relative > rtol 1e-6");
  aq_check(aq_compare_close(100.0, 100.00009, 1e-6, 0) == 1, "0.9e-6 relative <= 1e-6");
  aq_check(aq_compare_close(100.0, 100.00019, 1e-6, 1e-4) == 1, "atol adds to rtol");
  aq_check(aq_compare_close(100.0, 100.00021, 1e-6, 1e-4) == 0, "beyond atol + rtol");
  /* absolute tolerance: |diff| = 3e-7 * v */
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0, 4e-7 * v, NULL, NULL) == 0, "within atol");
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0, 2e-7 * v, NULL, NULL) == 1, "beyond atol");
  b[4].peak_displacement_m = v;

  /* NaN equals NaN; NaN against a number does not */
  aq_check(isnan(a[0].collapse_time_s) && isnan(b[0].collapse_time_s), "survivors");
  b[0].collapse_time_s = 9.5;
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0.5, 1, NULL, NULL) == 1,
           "nan against a number differs at any tolerance");
  b[0].collapse_time_s = NAN;

  /* flags and counts are exact, whatever the tolerance */
  b[2].collapsed = !b[2].collapsed;
  b[3].impacts += 1;
  memset(&d, 0, sizeof d);
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0.9, 1e9, collect, &d) == 2,
           "collapsed and impacts must match (%zu)", d.n);
  b[2].collapsed = a[2].collapsed;
  b[3].impacts = a[3].impacts;
  snprintf(b[5].status, sizeof b[5].status, "run:enumeric");
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0.9, 1e9, NULL, NULL) == 1, "status");
  b[5] = a[5];

  /* a run only in one file; a scale that moved beyond tolerance */
  memset(&d, 0, sizeof d);
  aq_check(aq_compare_runs(a, NRUN, b, NRUN - 1, 0, 0, collect, &d) == 1 &&
               d.kind[0] == AQ_DIFF_ONLY_A,
           "only in A");
  memset(&d, 0, sizeof d);
  aq_check(aq_compare_runs(a, NRUN - 1, b, NRUN, 0, 0, collect, &d) == 1 &&
               d.kind[0] == AQ_DIFF_ONLY_B,
           "only in B");
  b[1].scale *= 1 + 1e-12;
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 1e-9, 0, NULL, NULL) == 0,
           "scale within tolerance still matches");
  memset(&d, 0, sizeof d);
  aq_check(aq_compare_runs(a, NRUN, b, NRUN, 0, 0, collect, &d) == 2 &&
               d.kind[0] != AQ_DIFF_VALUE && d.kind[1] != AQ_DIFF_VALUE,
           "scale beyond tolerance: two unmatched runs (%zu)", d.n);
}

/* Write runs s[0..n) to path with the report writer. */
static int write_runs(const char *path, const aq_summary *s, size_t n)
{
  aq_h5_writer *w;
  aq_error err;
  if (aq_h5_open(path, &w, &err) != AQ_OK)
    return -1;
  aq_signal_opts o;
  aq_signal_opts_default(&o);
  aq_h5_root root = {"0", "test", "2026-11-22T00:00:00Z", &o, 0, "file", 0,
                     "workpath", NAN, NULL, 1, 0.3, 0, 1, "normal"};
  if (aq_h5_write_root(w, &root, &err) != AQ_OK)
    goto fail;
  for (size_t k = 0; k < n; k++)
    if (aq_h5_write_run(w, k, 0, 0, &s[k], NULL, NULL, 0, &err) != AQ_OK)
      goto fail;
  return aq_h5_finish(w, NULL, &err) == AQ_OK ? 0 : -1;
fail:
  aq_h5_abort(w);
  return -1;
}

/* Multiply the double attribute name of group /runs/<run> by factor. */
static int perturb(const char *path, const char *run, const char *name,
                   double factor)
{
  int ok = -1;
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t g = f >= 0 ? H5Gopen2(f, run, H5P_DEFAULT) : -1;
  hid_t a = g >= 0 ? H5Aopen(g, name, H5P_DEFAULT) : -1;
  double v;
  if (a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0) {
    v *= factor;
    if (H5Awrite(a, H5T_NATIVE_DOUBLE, &v) >= 0)
      ok = 0;
  }
  if (a >= 0)
    H5Aclose(a);
  if (g >= 0)
    H5Gclose(g);
  if (f >= 0 && H5Fclose(f) < 0)
    ok = -1;
  return ok;
}

AQ_TEST(report_compare_cli_files)
{
  aq_summary s[NRUN];
  make_runs(s);
  char dir[512], a[600], b[600], c[600], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a, "%s/a.h5", dir);
  snprintf(b, sizeof b, "%s/b.h5", dir);
  snprintf(c, sizeof c, "%s/c.h5", dir);
  aq_check(write_runs(a, s, NRUN) == 0, "write a");
  aq_check(write_runs(b, s, NRUN) == 0, "write b");
  aq_check(write_runs(c, s, NRUN - 2) == 0, "write c");
  static char out[16384], err[4096];

  snprintf(args, sizeof args, "compare %s %s", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "same files: exit 0 (%s)", err);

  /* perturb b's run 3 max_kinetic_energy_j by 2.5e-6 relative */
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  aq_check(perturb(b, "/runs/00003_000_000", "max_kinetic_energy_j", 1 + 2.5e-6) == 0,
           "perturb");
  snprintf(args, sizeof args, "compare %s %s --rtol 1e-6", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 1,
           "beyond tolerance: exit 1");
  aq_check(strstr(out, "max_kinetic_energy_j") != NULL &&
               strstr(out, s[3].record) != NULL && strstr(out, "thin") != NULL,
           "lists run and field: %s", out);
  char want_a[64];
  snprintf(want_a, sizeof want_a, "%.17g", s[3].max_kinetic_energy_j);
  aq_check(strstr(out, want_a) != NULL, "shows the first value %s", want_a);
  snprintf(args, sizeof args, "compare %s %s --rtol 1e-5", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "within tolerance: exit 0");
  snprintf(args, sizeof args, "compare --rtol 0 --atol 1e-2 %s %s", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "within absolute tolerance (%.3g J): exit 0",
           2.5e-6 * s[3].max_kinetic_energy_j);

  /* runs present in one file only */
  snprintf(args, sizeof args, "compare %s %s --rtol 1", a, c);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 1,
           "missing runs: exit 1");
  size_t present = 0;
  for (const char *p = out; (p = strstr(p, "\tpresent\tyes\tno")); p++)
    present++;
  aq_check(present == 2, "two runs only in A: %zu\n%s", present, out);

  /* bad options and unreadable files: exit 2, nothing compared */
  snprintf(args, sizeof args, "compare %s %s --rtol -1 --atol x --bogus", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "bad options");
  aq_check(strstr(err, "--rtol") && strstr(err, "--atol") && strstr(err, "--bogus"),
           "every bad option reported: %s", err);
  snprintf(args, sizeof args, "compare %s", a);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "one file");
  snprintf(args, sizeof args, "compare %s %s/missing.h5", a, dir);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "missing file");
  aq_check(strstr(err, "missing.h5") != NULL, "names it: %s", err);
  snprintf(args, sizeof args, "compare %s records/elcentro_chopra.csv", a);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "not HDF5");
  aq_check(strstr(err, "expected an HDF5 file") != NULL, "says so: %s", err);
}

/* A survivor's collapse time is NaN in the summary, whatever the result
 * struct holds (README: "collapse_time_s is nan for an arch that survives"). */
AQ_TEST(report_summary_survivor_has_nan_collapse_time)
{
  aq_result r;
  memset(&r, 0, sizeof r);
  r.collapsed = 0;
  r.collapse_time_s = 2.5;
  r.energy_in_j = 7.25;
  r.energy_dissipated_j = 3.5;
  aq_summary s;
  aq_summary_fill(&s, "rec", "arch", "workpath", 1.5, 0.3, "ok", &r);
  aq_check(isnan(s.collapse_time_s), "survivor: nan, got %g", s.collapse_time_s);
  aq_check(s.energy_in_j == 7.25 && s.energy_dissipated_j == 3.5, "energies copied");
  r.collapsed = 1;
  aq_summary_fill(&s, "rec", "arch", "workpath", 1.5, 0.3, "ok", &r);
  aq_check(s.collapse_time_s == 2.5 && s.collapsed == 1, "collapse time kept");
}

/* Differences come in the order of the sorted keys (compare.h), a NaN scale
 * (a record that failed) after every number. */
AQ_TEST(report_compare_nan_scale_sorts_last)
{
  aq_summary a[3];
  memset(a, 0, sizeof a);
  for (int k = 0; k < 3; k++) {
    snprintf(a[k].record, sizeof a[k].record, "records/x.AT2");
    snprintf(a[k].arch, sizeof a[k].arch, "thin");
  }
  a[0].scale = NAN;
  a[1].scale = 2.5;
  a[2].scale = 0.75;
  diffs d = {0};
  aq_check(aq_compare_runs(a, 3, NULL, 0, 0, 0, collect, &d) == 3, "three runs only in a");
  aq_check(d.n == 3 && d.scale[0] == 0.75 && d.scale[1] == 2.5 && isnan(d.scale[2]),
           "order 0.75, 2.5, nan: got %g %g %g", d.scale[0], d.scale[1], d.scale[2]);
}
