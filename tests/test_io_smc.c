/* test_io_smc.c: the USGS SMC reader against the numbers in
 * tests/data/records/agency/PROVENANCE.md and the files' own header values
 * (peak and its time in reals #29-#32, npts in integer #17), and its
 * refusals of damaged files. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "raw_fixture.h"

#define SMC_CORR AGENCY_DIR "0165b_a.smc"
#define SMC_UNCORR AGENCY_DIR "0165a_u.smc"
#define CMPS2_TO_MPS2 0.01 /* literal */
#define G_TO_MPS2 9.80665  /* literal */
#define PROV_PGA_REL 5e-4  /* PROVENANCE prints PGA to 4 significant digits */
#define HEADER_PEAK_ABS 5e-5 /* reals #30/#32 carry 7 significant digits (274.4508) */

AQ_TEST(io_smc_corrected_and_uncorrected)
{
  static const char *path[2] = {SMC_CORR, SMC_UNCORR};
  static const size_t npts[2] = {6014, 6012};
  static const double peak_cm[2] = {274.4508, 263.4864}; /* reals #30, #32 */
  static const double t_peak_s[2] = {3.43, 3.40};        /* reals #29, #31 */
  static const double pga_g[2] = {0.2799, 0.2687}, dm_g[2] = {0.2799, 0.2714};
  for (int i = 0; i < 2; i++) {
    aq_raw_file r;
    if (!aq_test_raw_load(aq_smc_parse, path[i], &r))
      continue;
    const aq_raw_channel *c = &r.chan[0];
    aq_check(r.nchan == 1 && c->npts == npts[i], "%s npts %zu", path[i], c->npts);
    aq_check_rel(c->dt_s, 1.0 / 200, 1e-12, "%s dt (200 samples/s)", path[i]);
    aq_check(strcmp(c->units, "cm/s2") == 0, "%s units %s", path[i], c->units);
    double pk = aq_test_peak_abs(c);
    aq_check_abs(pk, peak_cm[i], HEADER_PEAK_ABS * peak_cm[i], "%s header peak", path[i]);
    aq_check(fabs(c->values[(size_t)(t_peak_s[i] / 0.005 + 0.5)]) == pk, "%s peak at %g s",
             path[i], t_peak_s[i]);
    aq_check_rel(pk * CMPS2_TO_MPS2, pga_g[i] * G_TO_MPS2, PROV_PGA_REL, "%s PGA", path[i]);
    aq_check_rel(aq_test_peak_demeaned(c) * CMPS2_TO_MPS2, dm_g[i] * G_TO_MPS2, PROV_PGA_REL,
                 "%s demeaned PGA", path[i]);
    aq_check(strcmp(c->reference, "1987-10-01T14:42:00.000Z") == 0, "%s start %s", path[i],
             c->reference);
    aq_check(i == 0 ? c->vertical == 1 && c->dip_deg == -90
                    : c->vertical == 0 && c->azimuth_deg == 90,
             "%s orientation: vertical %d dip %g azimuth %g", path[i], c->vertical, c->dip_deg,
             c->azimuth_deg);
    aq_raw_file_free(&r);
  }
}

AQ_TEST(io_smc_bad_input)
{
  char msg[1400];
  aq_check(aq_test_raw_altered(aq_smc_parse, SMC_CORR, 1000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, SMC_CORR, "real header"),
           "truncated header: %s", msg);
  aq_check(aq_test_raw_altered(aq_smc_parse, SMC_CORR, 30000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               (aq_test_msg_names(msg, SMC_CORR, "npts") ||
                aq_test_msg_names(msg, SMC_CORR, "data")),
           "truncated data: %s", msg);
  /* sampling rate null: the values must then be (time, value) pairs, and
   * these are not (their "times" go back): malformed, not uneven sampling
   * (test_io_smc_variants.c refuses a file of true pairs) */
  aq_check(aq_test_raw_altered(aq_smc_parse, SMC_CORR, (size_t)-1,
                               "0.1700000E+39  0.2000000E+03", "0.1700000E+39  0.1700000E+39",
                               msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, SMC_CORR, "real header #2") &&
               strstr(msg, "(time, value) pairs") && strstr(msg, "does not follow"),
           "null rate, values not pairs: %s", msg);
  aq_check(aq_test_raw_altered(aq_smc_parse, SMC_CORR, (size_t)-1, "-1.1578E-1", "-1.15x8E-1",
                               msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, SMC_CORR, "\"-1.15x8E-1\""),
           "bad value: %s", msg);
}
