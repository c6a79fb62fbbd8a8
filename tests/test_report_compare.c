/* test_report_compare.c: matching and comparing run summaries, in memory
 * and through `archquake compare` on files whose copy is perturbed through
 * the HDF5 API. */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
  double scale[8]; /* of the run the difference is about (NAN: none) */
} diffs;

static void collect(void *ctx, const aq_diff *d)
{
  diffs *x = ctx;
  if (x->n < 8) {
    snprintf(x->field[x->n], 32, "%s",
             d->field ? d->field->name : d->name ? d->name : "-");
    x->kind[x->n] = d->kind;
    x->rel[x->n] = d->rel;
    x->scale[x->n] = d->a ? d->a->scale : d->b ? d->b->scale : NAN;
  }
  x->n++;
}

/* A suite in memory: runs s[0..n) of record k % 3 of three records whose
 * hashes are given, arch "oppenheim" (index 0) or "thin" (1). */
typedef struct {
  aq_h5_suite S;
  aq_h5_run runs[NRUN];
  aq_h5_input rec[3], arch[2];
  aq_h5_setting set[2];
} mem_suite;

static void make_suite(mem_suite *m, const aq_summary *s, size_t n,
                       const char *const *rec_sha)
{
  memset(m, 0, sizeof *m);
  static const char *const rec_name[3] = {"b.AT2", "a.sac", "c.csv"};
  for (size_t k = 0; k < n; k++) {
    m->runs[k].s = s[k];
    m->runs[k].record_index = (int64_t)(k % 3);
    m->runs[k].arch_index = strcmp(s[k].arch, "thin") == 0;
  }
  for (int k = 0; k < 3; k++) {
    snprintf(m->rec[k].name, sizeof m->rec[k].name, "%s", rec_name[k]);
    snprintf(m->rec[k].sha256, sizeof m->rec[k].sha256, "%s", rec_sha[k]);
  }
  snprintf(m->arch[0].name, sizeof m->arch[0].name, "oppenheim");
  snprintf(m->arch[0].sha256, sizeof m->arch[0].sha256, "9e6c");
  snprintf(m->arch[1].name, sizeof m->arch[1].name, "thin");
  snprintf(m->arch[1].sha256, sizeof m->arch[1].sha256, "77aa");
  snprintf(m->set[0].name, sizeof m->set[0].name, "model");
  snprintf(m->set[0].value, sizeof m->set[0].value, "workpath");
  snprintf(m->set[1].name, sizeof m->set[1].name, "archquake_version");
  snprintf(m->set[1].value, sizeof m->set[1].value, "0.1.0");
  m->S = (aq_h5_suite){m->runs, n, m->rec, m->arch, 3, 2, m->set, 2};
}

static const char *const shas[3] = {"11", "22", "33"};

/* Compare a[0..na) with b[0..nb) as suites in memory. */
static size_t cmp(const aq_summary *a, size_t na, const aq_summary *b, size_t nb,
                  double rtol, double atol, diffs *d)
{
  static mem_suite ma, mb;
  make_suite(&ma, a, na, shas);
  make_suite(&mb, b, nb, shas);
  aq_compare_opts o = {rtol, atol, NULL, 0};
  return aq_compare_suites(&ma.S, &mb.S, &o, d ? collect : NULL, d);
}

AQ_TEST(report_compare_tolerance_and_matching)
{
  aq_summary a[NRUN], b[NRUN];
  make_runs(a);
  make_runs(b);
  diffs d = {0};
  /* identical; the record paths spelt otherwise (the identity is the hash) */
  for (int k = 0; k < NRUN; k++)
    snprintf(b[k].record, sizeof b[k].record, "/data/suite/%s", k % 3 ? "x" : "y");
  aq_check(cmp(a, NRUN, b, NRUN, 0, 0, &d) == 0 && d.n == 0,
           "identical runs agree exactly whatever the paths (%zu)", d.n);
  make_runs(b);

  /* one value moved by 3e-7 relative: beyond 1e-7, within 1e-6 */
  double v = b[4].peak_displacement_m;
  b[4].peak_displacement_m = v * (1 + 3e-7);
  memset(&d, 0, sizeof d);
  aq_check(cmp(a, NRUN, b, NRUN, 1e-7, 0, &d) == 1, "one difference");
  aq_check(strcmp(d.field[0], "peak_displacement_m") == 0, "names the field: %s",
           d.field[0]);
  aq_check_rel(d.rel[0], 3e-7 / (1 + 3e-7), 2e-9, "relative difference");
  aq_check(cmp(a, NRUN, b, NRUN, 1e-6, 0, NULL) == 0, "within 1e-6");
  aq_check(cmp(a, NRUN, b, NRUN, 2e-7, 0, NULL) == 1, "beyond 2e-7");
  /* the rule atol + rtol max(|a|, |b|), at literal numbers */
  aq_check(aq_compare_close(100.0, 100.00015, 1e-6, 0) == 0, "1.5e-6 relative > rtol 1e-6");
  aq_check(aq_compare_close(100.0, 100.00009, 1e-6, 0) == 1, "0.9e-6 relative <= 1e-6");
  aq_check(aq_compare_close(100.0, 100.00019, 1e-6, 1e-4) == 1, "atol adds to rtol");
  aq_check(aq_compare_close(100.0, 100.00021, 1e-6, 1e-4) == 0, "beyond atol + rtol");
  /* absolute tolerance: |diff| = 3e-7 * v */
  aq_check(cmp(a, NRUN, b, NRUN, 0, 4e-7 * v, NULL) == 0, "within atol");
  aq_check(cmp(a, NRUN, b, NRUN, 0, 2e-7 * v, NULL) == 1, "beyond atol");
  b[4].peak_displacement_m = v;

  /* NaN equals NaN; NaN against a number does not */
  aq_check(isnan(a[0].collapse_time_s) && isnan(b[0].collapse_time_s), "survivors");
  b[0].collapse_time_s = 9.5;
  aq_check(cmp(a, NRUN, b, NRUN, 0.5, 1, NULL) == 1,
           "nan against a number differs at any tolerance");
  b[0].collapse_time_s = NAN;

  /* flags and counts are exact, whatever the tolerance */
  b[2].collapsed = !b[2].collapsed;
  b[3].impacts += 1;
  memset(&d, 0, sizeof d);
  aq_check(cmp(a, NRUN, b, NRUN, 0.9, 1e9, &d) == 2,
           "collapsed and impacts must match (%zu)", d.n);
  b[2].collapsed = a[2].collapsed;
  b[3].impacts = a[3].impacts;
  snprintf(b[5].status, sizeof b[5].status, "run:enumeric");
  aq_check(cmp(a, NRUN, b, NRUN, 0.9, 1e9, NULL) == 1, "status");
  b[5] = a[5];

  /* a run only in one file; a scale that moved beyond tolerance */
  memset(&d, 0, sizeof d);
  aq_check(cmp(a, NRUN, b, NRUN - 1, 0, 0, &d) == 1 && d.kind[0] == AQ_DIFF_ONLY_A,
           "only in A");
  memset(&d, 0, sizeof d);
  aq_check(cmp(a, NRUN - 1, b, NRUN, 0, 0, &d) == 1 && d.kind[0] == AQ_DIFF_ONLY_B,
           "only in B");
  b[1].scale *= 1 + 1e-12;
  aq_check(cmp(a, NRUN, b, NRUN, 1e-9, 0, NULL) == 0,
           "scale within tolerance still matches");
  memset(&d, 0, sizeof d);
  aq_check(cmp(a, NRUN, b, NRUN, 0, 0, &d) == 2 && d.kind[0] != AQ_DIFF_VALUE &&
               d.kind[1] != AQ_DIFF_VALUE,
           "scale beyond tolerance: two unmatched runs (%zu)", d.n);
}

AQ_TEST(report_compare_identity_and_configuration)
{
  aq_summary a[NRUN], b[NRUN];
  make_runs(a);
  make_runs(b);
  static mem_suite ma, mb;
  diffs d = {0};
  aq_compare_opts o = {0, 0, NULL, 0};

  /* two arches of one name are told apart by their configuration, whatever
   * their order: b lists them the other way round, and its runs too */
  make_suite(&ma, a, NRUN, shas);
  make_suite(&mb, b, NRUN, shas);
  for (int k = 0; k < NRUN; k++) {
    snprintf(ma.runs[k].s.arch, sizeof ma.runs[k].s.arch, "oppenheim");
    snprintf(mb.runs[k].s.arch, sizeof mb.runs[k].s.arch, "oppenheim");
    mb.runs[k].arch_index = !mb.runs[k].arch_index;
  }
  snprintf(ma.arch[1].name, sizeof ma.arch[1].name, "oppenheim");
  aq_h5_input t = mb.arch[0];
  mb.arch[0] = mb.arch[1];
  mb.arch[1] = t;
  snprintf(mb.arch[0].name, sizeof mb.arch[0].name, "oppenheim");
  aq_check(aq_compare_suites(&ma.S, &mb.S, &o, collect, &d) == 0,
           "same-named arches matched by configuration, not order (%zu)", d.n);
  /* the configuration is part of the key: swap b's hashes back and the
   * runs no longer find their partners */
  snprintf(mb.arch[0].sha256, sizeof mb.arch[0].sha256, "9e6c");
  snprintf(mb.arch[1].sha256, sizeof mb.arch[1].sha256, "77aa");
  aq_check(aq_compare_suites(&ma.S, &mb.S, &o, NULL, NULL) == 2 * NRUN,
           "arches matched by order instead: every run unmatched");

  /* a record changed in place: a configuration row, and its runs unmatched */
  static const char *const other[3] = {"11", "2f", "33"};
  make_suite(&ma, a, NRUN, shas);
  make_suite(&mb, b, NRUN, other);
  memset(&d, 0, sizeof d);
  size_t nd = aq_compare_suites(&ma.S, &mb.S, &o, collect, &d);
  aq_check(nd == 5 && d.kind[0] == AQ_DIFF_CONFIG &&
               strcmp(d.field[0], "record_sha256") == 0,
           "record content row first, then 2 x 2 unmatched runs (%zu, %s)", nd,
           d.field[0]);
  const char *ign[1] = {"record_sha256"};
  aq_compare_opts oi = {0, 0, ign, 1};
  aq_check(aq_compare_suites(&ma.S, &mb.S, &oi, NULL, NULL) == 0,
           "--ignore record_sha256 matches by file name");

  /* another model: a configuration row and a model row per run; ignoring
   * model leaves the numbers */
  make_suite(&ma, a, NRUN, shas);
  make_suite(&mb, b, NRUN, shas);
  snprintf(mb.set[0].value, sizeof mb.set[0].value, "ode");
  for (int k = 0; k < NRUN; k++)
    snprintf(mb.runs[k].s.model, sizeof mb.runs[k].s.model, "ode");
  memset(&d, 0, sizeof d);
  nd = aq_compare_suites(&ma.S, &mb.S, &o, collect, &d);
  aq_check(nd == 1 + NRUN && d.kind[0] == AQ_DIFF_CONFIG && strcmp(d.field[0], "model") == 0,
           "model: one setting row then %d field rows (%zu)", NRUN, nd);
  const char *ig[1] = {"model"};
  aq_compare_opts om = {0, 0, ig, 1};
  mb.runs[2].s.peak_rotation_rad *= 1.5;
  memset(&d, 0, sizeof d);
  nd = aq_compare_suites(&ma.S, &mb.S, &om, collect, &d);
  aq_check(nd == 1 && strcmp(d.field[0], "peak_rotation_rad") == 0,
           "--ignore model compares the numbers (%zu, %s)", nd, d.field[0]);

  /* another version is shown but does not count */
  make_suite(&ma, a, NRUN, shas);
  make_suite(&mb, b, NRUN, shas);
  snprintf(mb.set[1].value, sizeof mb.set[1].value, "0.2.0");
  memset(&d, 0, sizeof d);
  nd = aq_compare_suites(&ma.S, &mb.S, &o, collect, &d);
  aq_check(nd == 0 && d.n == 1 && strcmp(d.field[0], "archquake_version") == 0,
           "version shown (%zu rows), not counted (%zu)", d.n, nd);
}

/* Write runs s[0..n) to path with the report writer: run k of record k % 3
 * (three records), of arch 0 (oppenheim) or 1 (thin) by name. */
static int write_runs(const char *path, const aq_summary *s, size_t n)
{
  aq_h5_writer *w;
  aq_error err;
  if (aq_h5_open(path, &w, &err) != AQ_OK)
    return -1;
  aq_signal_opts o;
  aq_signal_opts_default(&o);
  aq_h5_root root = {"0", "test", "2026-11-22T00:00:00Z", &o, 0, "file", 0,
                     "workpath", NAN, NULL, 1, 0.3, 0, 1, NULL, 0, "normal", NAN};
  if (aq_h5_write_root(w, &root, &err) != AQ_OK)
    goto fail;
  for (size_t k = 0; k < 2; k++) {
    aq_h5_arch ha = {k ? "thin" : "oppenheim", "x.cfg", "", NULL, {NULL, NULL},
                     k ? "77aa" : "9e6c", 0, {NULL, NULL}, {NULL, NULL}, NULL, {NULL, NULL}};
    if (aq_h5_write_arch(w, k, &ha, &err) != AQ_OK)
      goto fail;
  }
  for (size_t k = 0; k < 3; k++) {
    aq_h5_record hr = {s[k].record, NULL, NULL, NULL, "ok", NULL, shas[k], 0, 0};
    if (aq_h5_write_record(w, k, &hr, &err) != AQ_OK)
      goto fail;
  }
  for (size_t k = 0; k < n; k++)
    if (aq_h5_write_run(w, k % 3, strcmp(s[k].arch, "thin") == 0, 0, &s[k], NULL, NULL,
                        0, &err) != AQ_OK)
      goto fail;
  return aq_h5_finish(w, NULL, &err) == AQ_OK ? 0 : -1;
fail:
  aq_h5_abort(w);
  return -1;
}

/* Multiply member name of row `row` of /summary by factor. */
static int perturb(const char *path, size_t row, const char *name, double factor)
{
  int ok = -1;
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t d = f >= 0 ? H5Dopen2(f, "/summary", H5P_DEFAULT) : -1;
  hid_t mt = H5Tcreate(H5T_COMPOUND, sizeof(double));
  H5Tinsert(mt, name, 0, H5T_NATIVE_DOUBLE);
  hid_t fs = d >= 0 ? H5Dget_space(d) : -1;
  hsize_t start = row, count = 1;
  hid_t ms = H5Screate_simple(1, &count, NULL);
  double v;
  if (fs >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL) >= 0 &&
      H5Dread(d, mt, ms, fs, H5P_DEFAULT, &v) >= 0) {
    v *= factor;
    if (H5Dwrite(d, mt, ms, fs, H5P_DEFAULT, &v) >= 0)
      ok = 0;
  }
  H5Sclose(ms);
  if (fs >= 0)
    H5Sclose(fs);
  H5Tclose(mt);
  if (d >= 0)
    H5Dclose(d);
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
  aq_check(perturb(b, 3, "max_kinetic_energy_j", 1 + 2.5e-6) == 0, "perturb");
  snprintf(args, sizeof args, "compare %s %s --rtol 1e-6", a, b);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 1,
           "beyond tolerance: exit 1");
  aq_check(strstr(out, "max_kinetic_energy_j") != NULL &&
               strstr(out, "\nb.AT2\tthin\t") != NULL,
           "lists run and field: %s", out);
  /* the first value as the fewest digits that read back to it (counted up
     from 1 here), a whole field */
  char want_a[64];
  double v = s[3].max_kinetic_energy_j;
  for (int p = 1; p <= 17; p++) {
    snprintf(want_a, sizeof want_a, "\t%.*g\t", p, v);
    if (strtod(want_a + 1, NULL) == v)
      break;
  }
  aq_check(strstr(out, want_a) != NULL, "shows the first value%s", want_a);
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
  /* a file whose /summary lacks a column (written before it existed): the
   * column reads as NaN, the rest compares; without a key column it is no
   * results file */
  char lack[600], nokey[600], cmd[2400];
  snprintf(lack, sizeof lack, "%s/lack.h5", dir);
  snprintf(nokey, sizeof nokey, "%s/nokey.h5", dir);
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, shutil, sys\n"
           "for out, col in ((sys.argv[2], 'energy_dissipated_j'), (sys.argv[3], 'scale')):\n"
           "  shutil.copy(sys.argv[1], out)\n"
           "  with h5py.File(out, 'r+') as f:\n"
           "    t = f['summary'][:]\n"
           "    keep = [n for n in t.dtype.names if n != col]\n"
           "    del f['summary']\n"
           "    f['summary'] = t[keep]\n"
           "\" '%s' '%s' '%s' 2>&1",
           a, lack, nokey);
  aq_check(system(cmd) == 0, "h5py rewrites the table without a column");
  snprintf(args, sizeof args, "compare %s %s", a, lack);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 1, "a column missing");
  size_t nrow = 0;
  for (const char *p = out; (p = strchr(p, '\n')); p++)
    nrow++;
  aq_check(strstr(out, "\tenergy_dissipated_j\t") && nrow == 1 + NRUN,
           "that column's rows only, one per run (NaN against a number): %s", out);
  snprintf(args, sizeof args, "compare %s %s --ignore energy_dissipated_j", a, lack);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "the rest agrees: %s", out);
  snprintf(args, sizeof args, "compare %s %s", a, nokey);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2 &&
               strstr(err, "nokey.h5") && strstr(err, "/summary"),
           "without the scale column: exit 2: %s", err);

  /* a results file of a later format than this build knows: named as such */
  char later[600];
  snprintf(later, sizeof later, "%s/format3.h5", dir);
  hid_t f3 = H5Fcreate(later, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t sp3 = H5Screate(H5S_SCALAR);
  long long three = 3;
  hid_t at3 = H5Acreate2(f3, "format_version", H5T_STD_I64LE, sp3, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at3, H5T_NATIVE_LLONG, &three);
  H5Aclose(at3);
  H5Sclose(sp3);
  H5Fclose(f3);
  snprintf(args, sizeof args, "compare %s %s", a, later);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "format 3: exit 2");
  aq_check(strstr(err, "format3.h5") && strstr(err, "format_version 1 to 2") &&
               strstr(err, "got 3"),
           "says which formats it reads and what it got: %s", err);
  snprintf(args, sizeof args, "compare %s records/elcentro_chopra.csv", a);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 2, "not HDF5");
  aq_check(strstr(err, "expected an HDF5 file") != NULL, "says so: %s", err);
}

/* Last night's file written before format 2 (tests/data/results/PROVENANCE.md)
 * against the same suite run today: equal; against another suite: not. */
AQ_TEST(report_compare_reads_format1)
{
  char dir[512], args[4096];
  aq_test_tmpdir(dir, sizeof dir);
  char *cwd = getcwd(NULL, 0);
  static char out[16384], err[4096];
  /* 0: the same suite with the processing and polarity of the day the file
   * was written; 1: another scale; 2: today's defaults (both polarities) */
  static const char *const opts[3] = {
      "--scale 1,3.5 --detrend mean --taper 0.05 --highpass 0.05 --order 4 --polarity normal",
      "--scale 1,3.25 --detrend mean --taper 0.05 --highpass 0.05 --order 4 --polarity normal",
      "--scale 1,3.5"};
  for (int k = 0; k < 3; k++) {
    snprintf(args, sizeof args,
             "--version >/dev/null && (cd tests/data/records && %s/%s elcentro_chopra.csv "
             "--arch ../../../arches/thin.cfg %s -q -o %s/%s/today%d.h5 >/dev/null)",
             cwd, aq_test_bin(), opts[k], cwd, dir, k);
    aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "suite %d: %s", k, err);
  }
  free(cwd);
  /* columns added after format 1 read as NaN there: left out */
  const char *ign = "--ignore lambda0_first,peak_rotation_over_qc,pga_over_lambda0,mu_demand,"
                    "mu_demand_joint,thrust_ecc_max,thrust_ecc_time_s,slide_time_s";
  snprintf(args, sizeof args,
           "compare tests/data/results/format1-elcentro-thin.h5 %s/today0.h5 --rtol 1e-6 %s",
           dir, ign);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "present") == NULL,
           "format 1 against today's same suite: exit %d: %s%s", rc, out, err);
  snprintf(args, sizeof args,
           "compare tests/data/results/format1-elcentro-thin.h5 %s/today1.h5 %s", dir, ign);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "elcentro_chopra.csv\tthin\t3.5\tnormal\tpresent\tyes\tno"),
           "against another scale: exit %d: %s", rc, out);
  /* today's defaults: the same runs, and rows saying which settings moved */
  snprintf(args, sizeof args,
           "compare tests/data/results/format1-elcentro-thin.h5 %s/today2.h5 %s", dir, ign);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && !strstr(out, "normal\tpresent") &&
               strstr(out, "\tthin\t1\treversed\tpresent\tno\tyes\t") &&
               strstr(out, "\tthin\t3.5\treversed\tpresent\tno\tyes\t") &&
               strstr(out, "\n*\t*\t*\t*\tpolarity\t\tboth\t") &&
               strstr(out, "\n*\t*\t*\t*\tdetrend\tmean\tlinear\t") &&
               strstr(out, "\n*\t*\t*\t*\ttaper_frac\t"),
           "today's defaults: the normal runs matched, the reversed ones new, the settings "
           "named: exit %d: %s", rc, out);
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

/* Runs come in the order of the sorted keys (compare.h), a NaN scale (a
 * record that failed) after every number. */
AQ_TEST(report_compare_nan_scale_sorts_last)
{
  aq_summary a[3];
  memset(a, 0, sizeof a);
  for (int k = 0; k < 3; k++) {
    snprintf(a[k].record, sizeof a[k].record, "records/b.AT2");
    snprintf(a[k].arch, sizeof a[k].arch, "thin");
  }
  a[0].scale = NAN;
  a[1].scale = 2.5;
  a[2].scale = 0.75;
  static mem_suite ma, mb;
  make_suite(&ma, a, 3, shas);
  make_suite(&mb, a, 0, shas);
  for (int k = 0; k < 3; k++) /* one record, one arch */
    ma.runs[k].record_index = 0;
  aq_compare_opts o = {0, 0, NULL, 0};
  diffs d = {0};
  aq_check(aq_compare_suites(&ma.S, &mb.S, &o, collect, &d) == 3, "three runs only in a");
  aq_check(d.n == 3 && d.scale[0] == 0.75 && d.scale[1] == 2.5 && isnan(d.scale[2]),
           "order 0.75, 2.5, nan: got %g %g %g", d.scale[0], d.scale[1], d.scale[2]);
}
