/* test_io_smc_variants.c: USGS SMC files beside the corrected and uncorrected
 * accelerograms, against tests/data/records/agency2/PROVENANCE.md: a file
 * converted from another format (data type 0, "UNKNOWN"), read with the
 * units the user gives and refused without; and a type 1 file of unevenly
 * sampled (time, value) pairs, refused in one line that says what it holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "agency2_fixture.h"

#define SMC_TYPE0 AGENCY2_DIR "0165b-type0-400pts.smc"
#define SMC_UNEVEN AGENCY2_DIR "891018_1.sma-1.0444a.smc"

AQ_TEST(io_smc_type0_unknown)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  aq_record r;
  aq_error err;
  /* the quantity is not stated: no units to take, and the message says why */
  aq_check(aq_record_read(SMC_TYPE0, &ro, &r, &err) == AQ_EUNITS &&
               strstr(err.message, "data type 0 (UNKNOWN)") && strstr(err.message, "--units"),
           "type 0 without --units: %s", err.message);
  /* PROVENANCE: the first 400 values of 0165b_a.smc, 200 samples/s, largest
   * 150.91 cm/s2 = 0.153885 g */
  ro.units = AQ_UNITS_GAL;
  static const aq_test_expect e = {SMC_TYPE0, 400, 0.005, 0.153885, 5e-7, ""};
  if (!aq_test_expect_read(&e, &ro, &r))
    return;
  aq_check(strcmp(r.format, "smc") == 0 && strcmp(r.units_used, "gal") == 0, "%s %s", r.format,
           r.units_used);
  aq_check(strcmp(r.reference, "1987-10-01T14:42:00.000Z") == 0, "start %s", r.reference);
  aq_record_free(&r);
}

AQ_TEST(io_smc_uneven_pairs_refused)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_record r;
  aq_error err;
  char msg[1400];
  aq_status s = aq_record_read(SMC_UNEVEN, &ro, &r, &err);
  aq_error_format(&err, msg, sizeof msg);
  /* PROVENANCE: 20620 pairs from 0 to 29.655 s, steps 0.0007 to 0.037 s */
  aq_check(s == AQ_EUNSUPPORTED && strstr(msg, SMC_UNEVEN ":18:") && strstr(msg, "USGS SMC") &&
               strstr(msg, "20620 (time, value) pairs") && strstr(msg, "0.0007 to 0.037 s") &&
               strstr(msg, "0 to 29.655 s") && strstr(msg, "not supported") &&
               !strchr(msg, '\n'),
           "uneven pairs: %s", msg);
}

/* An SMC file written by a converter (PEER's PEA2SMC, as pyrotd keeps it;
 * PROVENANCE: A-CAT090.AT2.smc): data type 0 on line 1, five values a line
 * in E14.7 whose fields touch (`1.1365572E-02-5.7981615E-03`), a comment
 * block that quotes PEER's header "IN UNITS OF G" while the values are
 * cm/s^2 (PEER's g x 981).  The layout comes from the file's own line
 * length and count; the units from no quoted text: without --units the
 * record is refused saying the file states none (data type 0), with
 * --units gal it reads whole.  Expected: integer #17 1646 values, real #2
 * 50 samples/s, the extremes and their times in reals #29-#32 (41.35543 at
 * 11.42 s, -38.42714 at 6.16 s), the first and last values as printed. */
#define SMC_PEA2SMC AGENCY2_DIR "A-CAT090.AT2.smc"
AQ_TEST(io_smc_converter_layout)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_record r;
  aq_error err;
  aq_check(aq_record_read(SMC_PEA2SMC, &ro, &r, &err) == AQ_EUNITS &&
               strstr(err.message, "data type 0 (UNKNOWN)") && !strstr(err.message, "OF G"),
           "no units from the quoted PEER header: %s", err.message);
  ro.units = AQ_UNITS_GAL;
  if (!aq_check(aq_record_read(SMC_PEA2SMC, &ro, &r, &err) == AQ_OK, "read: %s", err.message))
    return;
  aq_check(r.npts == 1646 && fabs(r.dt_s - 0.02) < 1e-15, "npts %zu dt %g", r.npts, r.dt_s);
  size_t kmax = 0, kmin = 0;
  for (size_t k = 0; k < r.npts; k++) {
    kmax = r.acc_mps2[k] > r.acc_mps2[kmax] ? k : kmax;
    kmin = r.acc_mps2[k] < r.acc_mps2[kmin] ? k : kmin;
  }
  aq_check_rel(r.acc_mps2[kmax], 41.35543 * 0.01, 1e-7, "the largest value (real #30)");
  aq_check(kmax == 571, "at 11.42 s (real #29): sample %zu", kmax);
  aq_check_rel(r.acc_mps2[kmin], -38.42714 * 0.01, 1e-7, "the smallest (real #32)");
  aq_check(kmin == 308, "at 6.16 s (real #31): sample %zu", kmin);
  aq_check_rel(r.acc_mps2[0], 9.5746585E-04 * 0.01, 1e-15, "the first value");
  aq_check_rel(r.acc_mps2[6], -5.7981615E-03 * 0.01, 1e-15, "a glued value (line 38)");
  aq_check_rel(r.acc_mps2[1645], 4.1989844E-02 * 0.01, 1e-15, "the last value");
  aq_record_free(&r);
}

/* The values of a type 0 file's data lines (8E10.4, read here by column),
 * written again n_per to a line in fields of width w (%w.12E): the reader
 * must find the layout and read the same values.  Then a data line of 73
 * characters (no width fills it) is refused naming its line and columns,
 * and F10.4 values, which also read as fields of 5 columns, take the
 * layout whose line count the file has. */
static int rewrite(const char *from, const char *to, int n_per, int w, const char *fmt,
                   double *vals, size_t *nv)
{
  size_t n;
  char *buf = aq_test_read_file(from, &n);
  FILE *f = buf ? fopen(to, "wb") : NULL;
  if (!aq_check(f != NULL, "write %s", to)) {
    free(buf);
    return 0;
  }
  char *save = NULL;
  int line = 0;
  *nv = 0;
  for (char *l = strtok_r(buf, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) {
    size_t len = strcspn(l, "\r");
    if (++line <= 27 + 11) { /* 11 text, 6 integer, 10 real, 11 comment lines */
      fprintf(f, "%.*s\r\n", (int)len, l);
      continue;
    }
    for (size_t b = 0; b + 10 <= len; b += 10) {
      char fld[11];
      memcpy(fld, l + b, 10);
      fld[10] = '\0';
      vals[(*nv)++] = strtod(fld, NULL);
    }
  }
  for (size_t k = 0; k < *nv; k++)
    fprintf(f, fmt, w, vals[k], (k + 1) % (size_t)n_per == 0 || k + 1 == *nv ? "\r\n" : "");
  free(buf);
  return fclose(f) == 0;
}

AQ_TEST(io_smc_data_width_from_the_file)
{
  char dir[512], p[700];
  aq_test_tmpdir(dir, sizeof dir);
  double v[400];
  size_t nv;
  static const struct {
    int per, w;
    const char *fmt;
  } lay[] = {{3, 20, "%*.12E%s"}, {5, 14, "%*.7E%s"}, {8, 10, "%*.4F%s"}, {1, 16, "%*.9E%s"}};
  for (size_t i = 0; i < sizeof lay / sizeof *lay; i++) {
    snprintf(p, sizeof p, "%s/w%d.smc", dir, lay[i].w);
    if (!rewrite(SMC_TYPE0, p, lay[i].per, lay[i].w, lay[i].fmt, v, &nv))
      continue;
    aq_check(nv == 400, "400 values in the original: %zu", nv);
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.units = AQ_UNITS_GAL;
    ro.accept_vertical = 1;
    aq_record r;
    aq_error err;
    if (!aq_check(aq_record_read(p, &ro, &r, &err) == AQ_OK, "%d per line of %d: %s",
                  lay[i].per, lay[i].w, err.message))
      continue;
    double worst = 0;
    for (size_t k = 0; k < nv && k < r.npts; k++) {
      char t[64];
      snprintf(t, sizeof t, lay[i].fmt, lay[i].w, v[k], ""); /* the value as written */
      double want = strtod(t, NULL) * 0.01;
      worst = fmax(worst, fabs(r.acc_mps2[k] - want));
    }
    aq_check(r.npts == 400 && worst == 0, "%d per line of %d columns: %zu values, worst "
             "difference %g", lay[i].per, lay[i].w, r.npts, worst);
    aq_record_free(&r);
  }
  /* a line that no width fills: the first data line of w14.smc, 3 columns
     longer */
  char msg[1400], line[128] = "", longer[140];
  for (int k = 0; k < 5; k++) {
    size_t l = strlen(line);
    snprintf(line + l, sizeof line - l, "%14.7E", v[k]);
  }
  snprintf(longer, sizeof longer, "%s123\r\n", line);
  strcat(line, "\r\n");
  snprintf(p, sizeof p, "%s/w14.smc", dir);
  aq_check(aq_test_edited_copy(p, line, longer, dir, "bad.smc", p, sizeof p), "edited copy");
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.units = AQ_UNITS_GAL;
  aq_record r;
  aq_error err;
  aq_status s = aq_record_read(p, &ro, &r, &err);
  aq_error_format(&err, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && strstr(msg, "bad.smc:") && strstr(msg, "columns"),
           "a data line of no width: %s", msg);
}
