/* test_trust_cli.c: verdicts a screening engineer can trust, through the
 * command line: a failed run carries no verdict (TSV and HDF5), options that
 * cannot take effect are refused, duplicate names, records and scales are
 * refused, and the record's polarity. */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

#define ELC "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"

/* The cell of column `name` in TSV row `row` (1-based; 0 is the header)
 * of text, into buf; 1 if found. */
static int tsv_cell(const char *text, size_t row, const char *name, char *buf, size_t n)
{
  size_t hl = strcspn(text, "\n"), col = 0;
  char head[4096];
  snprintf(head, sizeof head, "%.*s", (int)hl, text);
  char *save = NULL;
  int found = 0;
  for (char *t = strtok_r(head, "\t", &save); t; t = strtok_r(NULL, "\t", &save), col++)
    if (strcmp(t, name) == 0) {
      found = 1;
      break;
    }
  if (!found)
    return 0;
  const char *p = text;
  for (size_t r = 0; r < row && p; r++) {
    p = strchr(p, '\n');
    p = p ? p + 1 : NULL;
  }
  if (!p || !*p)
    return 0;
  for (size_t c = 0; c < col; c++) {
    p += strcspn(p, "\t\n");
    if (*p != '\t')
      return 0;
    p++;
  }
  size_t len = strcspn(p, "\t\n");
  snprintf(buf, n, "%.*s", (int)len, p);
  return 1;
}

/* Column `name` of row `row` (0-based) of the HDF5 /summary table, read
 * through a one-member compound type of the native type t (double or
 * int64) into v (size bytes). */
static int h5_summary_value(const char *path, size_t row, const char *name, hid_t t_mem,
                            size_t size, void *v)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return 0;
  hid_t d = H5Dopen2(f, "/summary", H5P_DEFAULT);
  hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  int ok = 0;
  if (n > 0 && (size_t)n > row) {
    char *all = malloc((size_t)n * size);
    hid_t t = H5Tcreate(H5T_COMPOUND, size);
    H5Tinsert(t, name, 0, t_mem);
    ok = all && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, all) >= 0;
    if (ok)
      memcpy(v, all + row * size, size);
    H5Tclose(t);
    free(all);
  }
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  H5Fclose(f);
  return ok;
}

static int h5_summary_double(const char *path, size_t row, const char *name, double *v)
{
  return h5_summary_value(path, row, name, H5T_NATIVE_DOUBLE, sizeof *v, v);
}

static int h5_summary_int(const char *path, size_t row, const char *name, int64_t *v)
{
  return h5_summary_value(path, row, name, H5T_NATIVE_INT64, sizeof *v, v);
}

static int write_text(const char *path, const char *text)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return 0;
  fputs(text, f);
  return fclose(f) == 0;
}


/* Item 5: a record that cannot be read gives a row with no verdict. */
AQ_TEST(trust_failed_run_has_no_verdict)
{
  char dir[512], bad[600], h5[700], args[2048];
  static char out[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(bad, sizeof bad, "%s/truncated.AT2", dir);
  aq_check(aq_test_copy_prefix(ELC, bad, 1, 3), "write %s", bad);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(args, sizeof args, "%s %s --arch arches/thin.cfg --polarity normal -o %s", ELC, bad,
           h5);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "exit 1 (a record failed): %d %s", rc, err);
  static const char *const results[] = {
      "collapsed",   "collapse_time_s",      "peak_rotation_rad", "peak_displacement_m",
      "max_kinetic_energy_j", "impacts", "energy_in_j", "energy_dissipated_j"};
  char cell[128];
  aq_check(tsv_cell(out, 2, "status", cell, sizeof cell) && strncmp(cell, "read:", 5) == 0,
           "row 2 is the failed record: %s", cell);
  for (size_t k = 0; k < sizeof results / sizeof results[0]; k++) {
    aq_check(tsv_cell(out, 2, results[k], cell, sizeof cell) && strcmp(cell, "nan") == 0,
             "TSV: failed run's %s is nan: \"%s\"", results[k], cell);
    aq_check(tsv_cell(out, 1, results[k], cell, sizeof cell) && strcmp(cell, "nan") != 0 &&
                 cell[0],
             "TSV: the good run has %s (%s)", results[k], cell);
  }
  int64_t c0 = 5, c1 = 5, i1 = 5;
  double peak = 0;
  int r0 = h5_summary_int(h5, 0, "collapsed", &c0), r1 = h5_summary_int(h5, 1, "collapsed", &c1);
  int r2 = h5_summary_int(h5, 1, "impacts", &i1);
  int r3 = h5_summary_double(h5, 1, "peak_rotation_rad", &peak);
  aq_check(r0 && (c0 == 0 || c0 == 1), "HDF5: the good run's collapsed is 0 or 1: %lld",
           (long long)c0);
  aq_check(r1 && c1 == -1, "HDF5: the failed run's collapsed is the documented -1: %lld",
           (long long)c1);
  aq_check(r2 && i1 == -1, "HDF5: the failed run's impacts is -1: %lld", (long long)i1);
  aq_check(r3 && isnan(peak),
           "HDF5: the failed run's peak rotation is NaN");
}

static int h5_arch_attr_double(const char *path, const char *obj, const char *name, double *v)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return 0;
  hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, v) >= 0;
  if (a >= 0)
    H5Aclose(a);
  H5Fclose(f);
  return ok;
}

/* Item 4: an option that cannot take effect is refused (exit 2, one line
 * with the reason, no output); the results file holds the values used. */
/* --dt is for records that state no sample interval: a record that states
 * its own keeps it (DT= .0100 SEC in ELC's header) and says so in one note
 * when --dt differs, in every command that reads records; a text record
 * without a time column takes --dt, silently. */
AQ_TEST(trust_dt_option_not_silently_ignored)
{
  char dir[512], txt[600], args[2048], cell[64];
  static char out[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(txt, sizeof txt, "%s/plain.txt", dir);
  FILE *f = fopen(txt, "w");
  aq_check(f != NULL, "write %s", txt);
  if (!f)
    return;
  for (int i = 0; i < 400; i++) /* one value per line, no time column */
    fprintf(f, "%.6f\n", 0.05 * sin(0.3 * i));
  fclose(f);
  static const char *const cmds[] = {"info", "", "spectrum --periods 0.5"};
  for (size_t c = 0; c < sizeof cmds / sizeof cmds[0]; c++) {
    const char *arch = c == 1 ? "--arch arches/thin.cfg" : "";
    snprintf(args, sizeof args, "%s %s %s %s --units g --dt 0.02", cmds[c], ELC, txt, arch);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 0, "%s: exit 0: %d %s", args, rc, err);
    aq_check(strstr(err, ELC ": dt: --dt 0.02 s not used: the file states a sample interval "
                         "of 0.01 s") != NULL,
             "%s: one note names the record and both intervals: %s", args, err);
    aq_check(strstr(err, "plain.txt: dt:") == NULL, "%s: no note for the text record: %s",
             args, err);
  }
  /* info's dt_s column: the file's interval for ELC, --dt for the text */
  snprintf(args, sizeof args, "info %s %s --units g --dt 0.02", ELC, txt);
  aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(tsv_cell(out, 1, "dt_s", cell, sizeof cell) && strcmp(cell, "0.01") == 0,
           "ELC keeps DT= .0100: %s", cell);
  aq_check(tsv_cell(out, 2, "dt_s", cell, sizeof cell) && strcmp(cell, "0.02") == 0,
           "the text record takes --dt: %s", cell);
  /* the same interval given again is no news */
  snprintf(args, sizeof args, "info %s --dt 0.01", ELC);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(err, "not used") == NULL, "--dt equal to DT: no note: %s", err);
}

AQ_TEST(trust_ineffective_options_are_refused)
{
  char dir[512], h5[700], args[2048];
  static char out[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  /* arches/search.cfg has impact = momentum */
  static const char *const cmds[] = {
      "records/elcentro_chopra.csv --arch arches/search.cfg --cor 0.5 -o %s",
      "pulse --arch arches/search.cfg --accel-g 1.3 --duration 0.2 --cor 0.5",
      "pulse --arch arches/oppenheim.cfg --accel-g 1.3 --duration 0.2 --impact momentum "
      "--cor 0.5",
      "domain --arch arches/search.cfg --ratios 2 --cor 0.3",
      "pulse --arch arches/oppenheim.cfg --accel-g 1.3 --duration 0.2 --ode-rtol 1e-8",
      "domain --arch arches/oppenheim.cfg --ratios 2 --model paper --ode-rtol 1e-8",
      "info " ELC " --no-filter --highpass 0.1",
      "records/elcentro_chopra.csv --arch arches/thin.cfg --no-filter --taper 0.1 -o %s",
      "info " ELC " --merge-tol 0.01"};
  static const char *const why[] = {"momentum",    "momentum",    "momentum",
                                    "momentum",    "--model ode", "--model ode",
                                    "--no-filter", "--no-filter", "main job"};
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    snprintf(args, sizeof args, cmds[k], h5);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, why[k]),
             "%s: exit %d (want 2), one line with the reason: %s", args, rc, err);
    aq_check(access(h5, F_OK) != 0, "no results file");
  }
  /* the values actually used, per arch */
  snprintf(args, sizeof args,
           "records/elcentro_chopra.csv --arch arches/oppenheim.cfg --cor 0.37 -o %s", h5);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  double cor = 0, g = 0;
  aq_check(rc == 0 && h5_arch_attr_double(h5, "/arches/000", "cor", &cor) && cor == 0.37,
           "--cor 0.37 is the arch's cor in the file: %g (exit %d)", cor, rc);
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/search.cfg -o %s",
           h5);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && h5_arch_attr_double(h5, "/arches/000", "cor", &cor) && isnan(cor),
           "impact momentum uses no cor: NaN in the file, got %g (exit %d)", cor, rc);
  /* arches/search.cfg states g_mps2 = 9.81 */
  aq_check(h5_arch_attr_double(h5, "/arches/000", "g_mps2", &g) && g == 9.81,
           "the arch's gravity: %g", g);
}

/* Item 6: one name, one thing; refused before any record is read (the
 * unreadable record in the list is never reported). */
AQ_TEST(trust_duplicates_are_refused)
{
  char dir[512], h5[700], args[4096], twin[700], junk[700];
  static char out[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(junk, sizeof junk, "%s/junk.AT2", dir);
  write_text(junk, "not a record\n");
  /* a different file with the same [arch] name as arches/thin.cfg */
  size_t n = 0;
  char *thin = aq_test_read_file("arches/thin.cfg", &n);
  snprintf(twin, sizeof twin, "%s/thin-copy.cfg", dir);
  aq_check(thin && strstr(thin, "name = thin") && write_text(twin, thin), "write %s", twin);
  free(thin);
  struct {
    const char *args, *says;
  } cases[] = {
      {"%s records/elcentro_chopra.csv ./records/../records/elcentro_chopra.csv "
       "--arch arches/thin.cfg -o %s",
       "the same file as records/elcentro_chopra.csv"},
      {"%s records/elcentro_chopra.csv records/elcentro_chopra.csv --arch arches/thin.cfg "
       "-o %s",
       "twice"},
      {"%s records/elcentro_chopra.csv --arch arches/thin.cfg --scale 0.5,1,0.5 -o %s",
       "--scale"},
      {"%s records/elcentro_chopra.csv --arch arches/thin.cfg --arch arches/./thin.cfg "
       "-o %s",
       "arch file once"},
      {"%s records/elcentro_chopra.csv --arch arches/thin.cfg --arch %s -o %s", "\"thin\""},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    if (k == 4)
      snprintf(args, sizeof args, cases[k].args, junk, twin, h5);
    else
      snprintf(args, sizeof args, cases[k].args, junk, h5);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, cases[k].says) &&
                 !strstr(err, "junk"),
             "%s: exit %d (want 2), one line (%s), no record read: %s", args, rc,
             cases[k].says, err);
    aq_check(access(h5, F_OK) != 0 && out[0] == '\0', "no output");
  }
}

/* Item 8: polarity.  The arch's two sets from `mechanism` (the reference
 * for lambda0 and q_c): a hinge-controlled arch swaps faces on the same
 * joints, so its response depends on the record's sign. */
static int mechanism_set(const char *out, const char *set, double *lambda0, double *qc,
                         int *act)
{
  char key[32];
  snprintf(key, sizeof key, "\n%s\t", set);
  const char *p = strstr(out, key);
  if (!p)
    return 0;
  p += strlen(key);
  for (int k = 0; k < 2; k++) /* joints, faces */
    p = strchr(p, '\t') + 1;
  char *end;
  *lambda0 = strtod(p, &end);
  *qc = strtod(end + 1, &end);
  strtol(end + 1, &end, 10); /* admissible */
  *act = (int)strtol(end + 1, &end, 10);
  return 1;
}

static double cell_double(const char *out, size_t row, const char *name)
{
  char cell[128];
  return tsv_cell(out, row, name, cell, sizeof cell) ? strtod(cell, NULL) : NAN;
}

AQ_TEST(trust_polarity_and_normalised_results)
{
  static char out[16384], ode[16384], err[8192], mech[8192];
  int rc = aq_test_run("mechanism --arch arches/thin.cfg", mech, sizeof mech, err, sizeof err);
  double l0[2], qc[2];
  int act[2];
  aq_check(rc == 0 && mechanism_set(mech, "primary", &l0[0], &qc[0], &act[0]) &&
               mechanism_set(mech, "reverse", &l0[1], &qc[1], &act[1]),
           "mechanism thin.cfg: %s", err);
  /* the figures: 0.047 one way, 0.80 the other */
  aq_check_abs(l0[0], 0.047, 0.0005, "thin.cfg primary lambda0 (issue: 0.047)");
  aq_check_abs(l0[1], 0.80, 0.005, "thin.cfg reverse lambda0 (issue: 0.80)");
  aq_check(act[0] == -act[1], "the two sets open under opposite signs: %+d %+d", act[0],
           act[1]);
  /* the figures were measured with the processing defaults of the
   * time (5 % Hann taper, 0.05 Hz corner, mean removal): pin them */
#define OLD_PROC " --taper 0.05 --highpass 0.05 --detrend mean"
  rc = aq_test_run(ELC OLD_PROC " --arch arches/thin.cfg --scale 0.5,0.73 --polarity both", out,
                   sizeof out, err, sizeof err);
  int rc2 = aq_test_run(ELC OLD_PROC " --arch arches/thin.cfg --scale 0.5,0.73 --polarity both "
                        "--model ode", ode, sizeof ode, err, sizeof err);
  aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == 5,
           "--polarity both: two rows per factor (%zu lines): %s", aq_test_count_lines(out), err);
  char pol[4][32];
  for (size_t r = 0; r < 4; r++)
    tsv_cell(out, r + 1, "polarity", pol[r], sizeof pol[r]);
  aq_check(!strcmp(pol[0], "normal") && !strcmp(pol[1], "reversed") &&
               !strcmp(pol[2], "normal") && !strcmp(pol[3], "reversed"),
           "each row says which: %s %s %s %s", pol[0], pol[1], pol[2], pol[3]);
  /* the figures at 0.5: 0.0049 as recorded, 0.011 negated; the ode
   * model (the exact equation of motion) as the second method */
  double pn = cell_double(out, 1, "peak_rotation_rad"), pr = cell_double(out, 2, "peak_rotation_rad");
  aq_check_abs(pn, 0.0049, 0.00005, "peak rotation at 0.5 as recorded (issue: 0.0049)");
  aq_check_abs(pr, 0.011, 0.0005, "peak rotation at 0.5 negated (issue: 0.011)");
  for (size_t r = 1; r <= 4; r++) {
    static const char *const cols[] = {"peak_rotation_rad", "lambda0_first",
                                       "peak_rotation_over_qc", "pga_over_lambda0"};
    for (size_t k = 0; k < 4; k++)
      aq_check_rel(cell_double(out, r, cols[k]), cell_double(ode, r, cols[k]), 1e-9,
                   "row %zu %s: workpath = ode", r, cols[k]);
    double lf = cell_double(out, r, "lambda0_first"), peak = cell_double(out, r, "peak_rotation_rad");
    double ratio = cell_double(out, r, "peak_rotation_over_qc");
    aq_check(fabs(lf - l0[0]) <= 1e-9 * l0[0] || fabs(lf - l0[1]) <= 1e-9 * l0[1],
             "row %zu: lambda0_first %.10g is one of mechanism's %.10g %.10g", r, lf, l0[0],
             l0[1]);
    aq_check(fabs(ratio * qc[0] - peak) <= 1e-8 * peak || fabs(ratio * qc[1] - peak) <= 1e-8 * peak,
             "row %zu: peak / q_c of one of mechanism's sets (ratio %.6g)", r, ratio);
    aq_check_rel(cell_double(out, r, "pga_over_lambda0"),
                 cell_double(out, r, "pga_g") / lf, 1e-12, "row %zu: PGA/(lambda0 g)", r);
  }
  /* a PGA of 0.14 g cannot reach the reverse set's 0.80: the record drives
   * the primary first whichever its sign */
  aq_check_rel(cell_double(out, 2, "lambda0_first"), l0[0], 1e-9, "reversed: primary first");
  /* the HDF5 summary holds the same values, the reversed run its own group */
  char dir[512], h5[700], args[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/p.h5", dir);
  snprintf(args, sizeof args, ELC OLD_PROC " --arch arches/thin.cfg --scale 0.5,0.73 "
                              "--polarity both --history -o %s", h5);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  static const char *const cols[] = {"lambda0_first", "peak_rotation_over_qc",
                                     "pga_over_lambda0", "peak_rotation_rad"};
  for (size_t r = 0; r < 4; r++)
    for (size_t k = 0; k < 4; k++) {
      double v = NAN;
      int ok = h5_summary_double(h5, r, cols[k], &v);
      aq_check(rc == 0 && ok && v == cell_double(out, r + 1, cols[k]),
               "HDF5 summary row %zu %s = TSV: %.17g", r, cols[k], v);
    }
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0 && H5Lexists(f, "/histories/00000_000_001r", H5P_DEFAULT) > 0,
           "the reversed run of factor 2 has its histories");
  if (f >= 0)
    H5Fclose(f);
}

/* Item 8: the reversed row equals a run of the record negated, written
 * here as CSV (time, acceleration in g) from the AT2's values. */
AQ_TEST(trust_polarity_reversed_equals_negated_copy)
{
  char dir[512], csv[700], neg[700], args[2048];
  static char out[16384], out2[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  char *at2 = aq_test_read_file(ELC, NULL);
  if (!aq_check(at2 != NULL, "read " ELC))
    return;
  const char *p = at2;
  for (int l = 0; l < 4 && p; l++) { /* four header lines; NPTS 5372, DT 0.01 s */
    p = strchr(p, '\n');
    p = p ? p + 1 : NULL;
  }
  snprintf(csv, sizeof csv, "%s/elc180.csv", dir);
  snprintf(neg, sizeof neg, "%s/elc180-negated.csv", dir);
  FILE *f = fopen(csv, "w"), *g = fopen(neg, "w");
  size_t n = 0;
  if (f && g) {
    fputs("time,acc (g)\n", f);
    fputs("time,acc (g)\n", g);
    char *end;
    for (double v = strtod(p, &end); end != p; v = strtod(p, &end)) {
      p = end;
      fprintf(f, "%.2f,%.17g\n", 0.01 * (double)n, v);
      fprintf(g, "%.2f,%.17g\n", 0.01 * (double)n, -v);
      n++;
    }
  }
  if (f)
    fclose(f);
  if (g)
    fclose(g);
  free(at2);
  aq_check(n == 5372, "5372 samples (PEER header): %zu", n);
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg --arch arches/oppenheim.cfg "
                              "--scale 0.5,2.2 --polarity both", csv);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg --arch arches/oppenheim.cfg "
                              "--scale 0.5,2.2 --polarity normal", neg);
  int rc2 = aq_test_run(args, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == 9 && aq_test_count_lines(out2) == 5,
           "rows: %zu and %zu: %s", aq_test_count_lines(out), aq_test_count_lines(out2), err);
  static const char *const cols[] = {"collapsed", "collapse_time_s", "peak_rotation_rad",
                                     "peak_displacement_m", "max_kinetic_energy_j",
                                     "impacts", "energy_in_j", "lambda0_first",
                                     "peak_rotation_over_qc", "pga_over_lambda0"};
  int collapsed = 0;
  for (size_t r = 1; r <= 4; r++) {
    char pol[32];
    tsv_cell(out, 2 * r, "polarity", pol, sizeof pol);
    aq_check(strcmp(pol, "reversed") == 0, "row %zu reversed", 2 * r);
    for (size_t k = 0; k < sizeof cols / sizeof cols[0]; k++) {
      double a = cell_double(out, 2 * r, cols[k]), b = cell_double(out2, r, cols[k]);
      aq_check((isnan(a) && isnan(b)) || fabs(a - b) <= 1e-9 * fabs(b),
               "reversed row %zu %s %.17g = negated copy's %.17g", 2 * r, cols[k], a, b);
    }
    collapsed += cell_double(out2, r, "collapsed") == 1;
  }
  aq_check(collapsed > 0 && collapsed < 4, "both verdicts among the rows (%d collapsed)",
           collapsed);
}

/* compare still reads a file written before the polarity and normalised
 * columns existed: they read as polarity normal and NaN, so the runs match
 * and the new values are reported as differences, not as a bad file. */
AQ_TEST(trust_compare_reads_files_without_the_new_columns)
{
  char dir[512], a[700], b[700], args[2048];
  static char out[16384], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a, "%s/a.h5", dir);
  snprintf(b, sizeof b, "%s/b.h5", dir);
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg "
                              "--scale 0.4,1.7 --polarity normal -o %s", a);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && aq_test_copy_prefix(a, b, 1, 1), "suite: %d %s", rc, err);
  /* b's run table without the four columns (rewritten by h5py) */
  char cmd[2048];
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, sys\n"
           "with h5py.File(sys.argv[1], 'r+') as f:\n"
           "  t = f['summary'][:]\n"
           "  added = ('polarity', 'lambda0_first', 'peak_rotation_over_qc', 'pga_over_lambda0')\n"
           "  keep = [n for n in t.dtype.names if n not in added]\n"
           "  assert len(keep) == len(t.dtype.names) - 4\n"
           "  del f['summary']\n"
           "  f['summary'] = t[keep]\n"
           "\" '%s' 2>&1",
           b);
  aq_check(system(cmd) == 0, "columns removed");
  snprintf(args, sizeof args, "compare %s %s", a, b);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "\tlambda0_first\t") && !strstr(out, "present"),
           "exit %d (want 1: values differ), runs matched: %s %s", rc, out, err);
}
