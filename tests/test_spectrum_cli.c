/* test_spectrum_cli.c: `archquake spectrum` end to end: PEER's NGA-West2
 * flatfile through the command, the columns (SD and PSV against PSA and
 * the period, computed here), the default periods, -j, the results file
 * read back, the Nyquist warning, and bad input (one line, nothing
 * written). */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "report/h5_spectrum.h"

#define R "tests/data/records/"
#define PAIR R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2," R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"
#define G0 9.80665
#define PI 3.14159265358979323846
enum { BIG = 1 << 20 };

#define field aq_test_tsv_field

static double num_at(const char *tsv, int row, int k)
{
  char b[64];
  return strtod(field(tsv, row, k, b, sizeof b), NULL);
}

/* The flatfile's RotD50 of RSN6 at 5 % (g), as in test_signal_spectrum.c,
 * through the command: the files as published, peaks at the samples. */
AQ_TEST(spectrum_cli_flatfile_rsn6)
{
  char *out = malloc(BIG), err[4096], b[64];
  int rc = aq_test_run("spectrum --no-filter --detrend none --sampled-peaks "
                       "--periods 0.1,0.2,0.5,1,2 --components " PAIR,
                       out, BIG, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  const double flat[] = {0.42696, 0.57773, 0.629952, 0.351286, 0.215745};
  const double half[] = {5e-6, 5e-6, 5e-7, 5e-7, 5e-7};
  aq_check(aq_test_count_lines(out) == 17, "comment, header + 3 x 5 rows: %zu lines",
           aq_test_count_lines(out));
  for (int i = 0; i < 5; i++) {
    aq_check(strcmp(field(out, 1 + i, 1, b, sizeof b), "RotD50") == 0,
             "row %d is RotD50: %s", 1 + i, b);
    aq_check_abs(num_at(out, 1 + i, 4), flat[i], half[i], "RSN6 RotD50 at %g s",
                 num_at(out, 1 + i, 3));
  }
  free(out);
}

/* The columns: SD = PSA / w^2 and PSV = PSA / w with PSA in m/s^2; the
 * channel names a record's rows; each damping gives a spectrum, the lower
 * damping the larger PSA at resonant periods. */
AQ_TEST(spectrum_cli_columns)
{
  char *out = malloc(BIG), err[4096], b[128];
  int rc = aq_test_run("spectrum " R "ARL360.at2 --periods 0.1,0.37,1.5 --damping "
                       "0.02,0.05", out, BIG, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  const char *head = "record\tcomponent\tdamping\tperiod_s\tpsa_g\tsd_m\tpsv_m_s\n";
  const char *nl = strchr(out, '\n');
  aq_check(strncmp(out, "# peaks: peer: ", 15) == 0, "a comment line first: %.80s", out);
  aq_check(nl && strncmp(nl + 1, head, strlen(head)) == 0, "then the header: %.80s",
           nl ? nl + 1 : "");
  aq_check(aq_test_count_lines(out) == 8, "6 rows: %zu lines", aq_test_count_lines(out));
  for (int r = 1; r <= 6; r++) {
    double T = num_at(out, r, 3), psa = num_at(out, r, 4) * G0, w = 2 * PI / T;
    aq_check(strcmp(field(out, r, 1, b, sizeof b), "360") == 0, "channel: %s", b);
    aq_check(num_at(out, r, 2) == (r <= 3 ? 0.02 : 0.05), "damping of row %d", r);
    aq_check_rel(num_at(out, r, 5), psa / (w * w), 1e-15, "sd_m, row %d", r);
    aq_check_rel(num_at(out, r, 6), psa / w, 1e-15, "psv_m_s, row %d", r);
  }
  for (int i = 1; i <= 3; i++)
    aq_check(num_at(out, i, 4) > num_at(out, i + 3, 4), "T = %g: 2 %% above 5 %%",
             num_at(out, i, 3));
  free(out);
}

/* Without --periods: PEER's 111, 0.01 to 20 s, in order. */
AQ_TEST(spectrum_cli_default_periods)
{
  char *out = malloc(BIG), err[4096];
  int rc = aq_test_run("spectrum " R "IELC180.AT2", out, BIG, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  aq_check(aq_test_count_lines(out) == 113, "111 rows: %zu lines",
           aq_test_count_lines(out));
  aq_check(num_at(out, 1, 3) == 0.01 && num_at(out, 111, 3) == 20, "0.01 to 20 s");
  int sorted = 1;
  for (int r = 2; r <= 111; r++)
    sorted &= num_at(out, r, 3) > num_at(out, r - 1, 3);
  aq_check(sorted, "periods increasing");
  aq_check(strstr(err, "Nyquist") != NULL, "0.01 s < 2 dt warned of: %s", err);
  free(out);
}

/* One warning line for the periods below 2 dt, whatever their number and
 * the records', and the rows still written. */
AQ_TEST(spectrum_cli_nyquist_warning_once)
{
  char *out = malloc(BIG), err[4096];
  int rc = aq_test_run("spectrum " R "ARL360.at2 " R "IELC180.AT2 --periods "
                       "0.005,0.01,0.03,0.5", out, BIG, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, "warning") &&
               strstr(err, "linear between samples"),
           "one line: %s", err);
  /* ARL360 has dt = 0.02 s: three periods below 0.04 s */
  aq_check(strstr(err, "3 of the periods") && strstr(err, "ARL360"), "names them: %s", err);
  aq_check(aq_test_count_lines(out) == 10, "8 rows: %zu", aq_test_count_lines(out));
  free(out);
}

/* -j 1 and -j 3 write the same bytes to stdout and the same spectra to
 * the results file, which holds what the TSV says. */
AQ_TEST(spectrum_cli_jobs_and_results_file)
{
  char dir[512], cmd[2048], h1[600], h3[600], err[4096];
  char *o1 = malloc(BIG), *o3 = malloc(BIG);
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h1, sizeof h1, "%s/j1.h5", dir);
  snprintf(h3, sizeof h3, "%s/j3.h5", dir);
  const char *args = R "ARL360.at2 " R "Q4149CF2.csv --components " PAIR
                       " --periods 0.05,0.3,1.7 --damping 0.05,0.1";
  snprintf(cmd, sizeof cmd, "spectrum -j 1 %s -o %s", args, h1);
  aq_check(aq_test_run(cmd, o1, BIG, err, sizeof err) == 0, "-j 1: %s", err);
  snprintf(cmd, sizeof cmd, "spectrum -j 3 %s -o %s", args, h3);
  aq_check(aq_test_run(cmd, o3, BIG, err, sizeof err) == 0, "-j 3: %s", err);
  aq_check(strcmp(o1, o3) == 0, "the same TSV at -j 1 and -j 3");
  /* ARL360 and Q4149CF2.csv's NS, EW and UD: 4 x 2 x 3; the pair: 3 x 2 x 3 */
  aq_check(aq_test_count_lines(o1) == 2 + 24 + 18, "rows: %zu", aq_test_count_lines(o1));
  aq_h5_spectra_table t1, t3;
  aq_error e;
  aq_check(aq_h5_spectra_read(h1, &t1, &e) == AQ_OK, "read %s: %s", h1, e.message);
  aq_check(aq_h5_spectra_read(h3, &t3, &e) == AQ_OK, "read %s: %s", h3, e.message);
  aq_check(t1.n == 42 && t3.n == 42, "42 rows: %zu %zu", t1.n, t3.n);
  size_t same = 0, agree = 0;
  char b[512];
  for (size_t i = 0; i < t1.n && i < t3.n; i++) {
    same += t1.psa_g[i] == t3.psa_g[i] && t1.sd_m[i] == t3.sd_m[i] &&
            strcmp(t1.component[i], t3.component[i]) == 0;
    agree += strcmp(t1.record[i], field(o1, (int)i + 1, 0, b, sizeof b)) == 0 &&
             strcmp(t1.component[i], field(o1, (int)i + 1, 1, b, sizeof b)) == 0 &&
             t1.damping[i] == num_at(o1, (int)i + 1, 2) &&
             t1.period_s[i] == num_at(o1, (int)i + 1, 3) &&
             t1.psa_g[i] == num_at(o1, (int)i + 1, 4) &&
             t1.psv_m_s[i] == num_at(o1, (int)i + 1, 6);
  }
  aq_check(same == 42, "-j 1 and -j 3 files: %zu of 42 rows the same", same);
  aq_check(agree == 42, "file = TSV: %zu of 42 rows", agree);
  aq_check(t1.peaks == AQ_SPECTRUM_PEAKS_PEER, "peaks: peer, the default (%d)", t1.peaks);
  hid_t f = H5Fopen(h1, H5F_ACC_RDONLY, H5P_DEFAULT);
  char kind[32] = "";
  hid_t a = f >= 0 ? H5Aopen(f, "kind", H5P_DEFAULT) : -1, at = a >= 0 ? H5Aget_type(a) : -1;
  if (at >= 0 && H5Tget_size(at) < sizeof kind)
    H5Aread(a, at, kind);
  aq_check(strcmp(kind, "spectrum") == 0, "root attribute kind: \"%s\"", kind);
  aq_check(f >= 0 && H5Aexists(f, "model") == 0 && H5Aexists(f, "detrend") > 0,
           "no run options at the root, the processing there");
  if (at >= 0)
    H5Tclose(at);
  if (a >= 0)
    H5Aclose(a);
  if (f >= 0)
    H5Fclose(f);
  aq_h5_spectra_table_free(&t1);
  aq_h5_spectra_table_free(&t3);
  free(o1);
  free(o3);
}

/* --peaks: the comment line and the results file say the rule; PEER's
 * (the default) equals the samples' at T >= 10 dt and lies between the
 * samples' and the continuous peak below; --sampled-peaks is --peaks
 * samples, byte for byte. */
AQ_TEST(spectrum_cli_peaks)
{
  static const char *const rule[] = {"", "--peaks peer", "--peaks exact", "--peaks samples",
                                     "--sampled-peaks"};
  static const char *const says[] = {"peer", "peer", "exact", "samples", "samples"};
  char *out[5], dir[512], h5[700], cmd[2048], err[4096], b[64];
  aq_test_tmpdir(dir, sizeof dir);
  for (int m = 0; m < 5; m++) {
    out[m] = malloc(BIG);
    snprintf(h5, sizeof h5, "%s/peaks%d.h5", dir, m);
    snprintf(cmd, sizeof cmd, "spectrum " R "ARL360.at2 --periods 0.013,0.05,0.21,1.1 %s -o %s",
             rule[m], h5);
    aq_check(aq_test_run(cmd, out[m], BIG, err, sizeof err) == 0, "%s: %s", rule[m], err);
    char want[64];
    snprintf(want, sizeof want, "# peaks: %s: ", says[m]);
    aq_check(strncmp(out[m], want, strlen(want)) == 0, "%s: %.60s", rule[m], out[m]);
    aq_h5_spectra_table t;
    aq_error e;
    if (aq_check(aq_h5_spectra_read(h5, &t, &e) == AQ_OK, "read %s: %s", h5, e.message)) {
      aq_check(t.peaks >= 0 && strcmp(aq_spectrum_peaks_names[t.peaks], says[m]) == 0,
               "%s: the file's peaks %d", rule[m], t.peaks);
      aq_h5_spectra_table_free(&t);
    }
  }
  aq_check(strcmp(out[0], out[1]) == 0, "peer is the default");
  aq_check(strcmp(out[3], out[4]) == 0, "--sampled-peaks = --peaks samples");
  /* ARL360: dt = 0.02 s, so 10 dt = 0.2 s: rows 1, 2 refined (N = 16, 4) */
  for (int r = 1; r <= 4; r++) {
    double p = num_at(out[0], r, 4), x = num_at(out[2], r, 4), s = num_at(out[3], r, 4);
    aq_check(s <= p && p <= x, "T = %s: samples %.9g <= peer %.9g <= exact %.9g",
             field(out[0], r, 3, b, sizeof b), s, p, x);
    if (r >= 3)
      aq_check(p == s, "T = %s >= 10 dt: peer = samples", b);
    else
      aq_check(p > s && p < x, "T = %s < 10 dt: peer strictly between", b);
  }
  for (int m = 0; m < 5; m++)
    free(out[m]);
}

/* Bad input: one line on stderr, no rows, no results file. */
AQ_TEST(spectrum_cli_bad_input)
{
  static const struct {
    const char *args, *says;
    int rc;
  } cases[] = {
      {"--periods 0", "--periods", 2},
      {"--periods 0.5,-0.2", "--periods", 2},
      {"--periods 0.1,x", "--periods", 2},
      {"--damping 0", "--damping", 2},
      {"--damping 1", "--damping", 2},
      {"--damping 0.05,1.5", "--damping", 2},
      {"--damping -0.05", "--damping", 2},
      {"--components " PAIR "," R "IELC180.AT2", "vertical", 2},
      {"--azimuth 30 --components " PAIR, "--azimuth", 2},
      /* a pair of different dt (0.02 s and 0.01 s) */
      {"--components " R "ARL360.at2," R "IELC180.AT2 --azimuths 0,90", "dt", 1},
      /* a pair not orthogonal */
      {"--components " PAIR " --azimuths 0,45", "orthogonal", 1},
      {R "no-such-file.AT2", "no-such-file", 1},
      {"--peaks exactly", "--peaks", 2},
      {"--peaks sample", "--peaks", 2},
      {"--peaks", "--peaks", 2},
      {"--peaks peer --sampled-peaks", "--sampled-peaks", 2},
      /* PEER's rule at dt = 0.02 s: 10 dt / T = 20000 steps, past the most */
      {"--periods 0.00001", "peer", 1},
  };
  char dir[512], h5[600], cmd[2048], err[4096];
  char *out = malloc(BIG);
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/bad.h5", dir);
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    snprintf(cmd, sizeof cmd, "spectrum " R "ARL360.at2 %s -o %s", cases[i].args, h5);
    int rc = aq_test_run(cmd, out, BIG, err, sizeof err);
    aq_check(rc == cases[i].rc, "%s: exit %d (want %d)", cases[i].args, rc, cases[i].rc);
    aq_check(aq_test_count_lines(err) == 1 && strstr(err, cases[i].says),
             "%s: one line saying %s: %s", cases[i].args, cases[i].says, err);
    aq_check(out[0] == '\0', "%s: nothing on stdout: %.60s", cases[i].args, out);
    aq_check(access(h5, F_OK) != 0, "%s: no results file", cases[i].args);
  }
  free(out);
}
