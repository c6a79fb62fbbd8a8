/* test_io_cosmos.c: the COSMOS v1.20 reader against the numbers in
 * tests/data/records/agency/PROVENANCE.md (an independent numpy parser) and
 * the files' own header values (peak, mean, sampling), and its refusals of
 * damaged files. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "raw_fixture.h"

#define COSMOS_SAMPLE AGENCY_DIR "Cosmos12TimeSeriesTest.v1"
#define COSMOS_V0 AGENCY_DIR "NP1795-n.305.v0c"
#define CMPS2_TO_MPS2 0.01     /* literal: 1 cm/s^2 = 0.01 m/s^2 */
#define G_TO_MPS2 9.80665      /* literal: standard gravity */
#define HEADER_PEAK_ABS 0.0005 /* header peaks are printed to 3 decimals */
#define PROV_PGA_REL 5e-4      /* PROVENANCE prints PGA to 4 significant digits */
#define PROV_SCALE_REL 1e-6    /* the scale 6.49469e-6 is printed to 6 digits */
#define PROV_MEAN_ABS 0.006    /* means printed to 2 decimals (counts) */

AQ_TEST(io_cosmos_sample_v2)
{
  aq_raw_file r;
  if (!aq_test_raw_load(aq_cosmos_parse, COSMOS_SAMPLE, &r))
    return;
  aq_check(r.nchan == 1, "nchan %zu", r.nchan);
  const aq_raw_channel *c = &r.chan[0];
  aq_check(c->npts == 7000, "npts %zu", c->npts);
  /* real #62 = 10 ms; real #34 (0.005) must not be taken */
  aq_check_rel(c->dt_s, 0.01, 1e-12, "dt from real #62");
  aq_check(strcmp(c->units, "cm/s2") == 0, "units %s", c->units);
  double peak = aq_test_peak_abs(c);
  aq_check_abs(peak, 161.962, HEADER_PEAK_ABS, "peak vs header Max = -161.962 cm/sec2");
  aq_check_rel(peak * CMPS2_TO_MPS2, 0.1652 * G_TO_MPS2, PROV_PGA_REL, "PGA m/s2");
  /* the header's peak time 27.85 s is sample 2785 only with dt = 0.01 s */
  aq_check_abs(c->values[2785], -161.9618, 1e-9, "sample at 27.85 s");
  aq_check(strcmp(c->network, "CE") == 0 && strcmp(c->station, "J2236") == 0,
           "station %s.%s", c->network, c->station);
  aq_check(strcmp(c->reference, "2005-06-16T20:53:04.400Z") == 0, "start %s", c->reference);
  aq_check(c->azimuth_deg == 340 && c->vertical == 0, "azimuth %g vertical %d",
           c->azimuth_deg, c->vertical);
  aq_check(strstr(r.processing, "filtered") != NULL, "processing '%s'", r.processing);
  aq_raw_file_free(&r);
}

AQ_TEST(io_cosmos_v0_counts_three_channels)
{
  aq_raw_file r;
  if (!aq_test_raw_load(aq_cosmos_parse, COSMOS_V0, &r))
    return;
  aq_check(r.nchan == 3, "nchan %zu", r.nchan);
  if (r.nchan != 3)
    goto out;
  static const char *names[3] = {"HNE", "HNN", "HNZ"};
  static const double az[3] = {90, 360, NAN};
  static const double raw_g[3] = {0.6529, 0.8886, 1.575};
  static const double dm_g[3] = {0.002231, 0.0002082, 0.0002325};
  static const double mean_counts[3] = {-982511.90, -1341617.32, -2378631.07};
  for (int i = 0; i < 3; i++) {
    const aq_raw_channel *c = &r.chan[i];
    aq_check(strcmp(c->channel, names[i]) == 0, "channel %d '%s'", i, c->channel);
    aq_check(c->npts == 20000, "%s npts %zu", names[i], c->npts);
    aq_check_rel(c->dt_s, 0.005, 1e-12, "%s dt", names[i]);
    aq_check(strcmp(c->units, "counts") == 0, "%s units %s", names[i], c->units);
    /* LSB 0.794729 uV / (1.2 V/g x gain 1) = 6.49469e-6 m/s2 per count */
    aq_check_rel(1.0 / c->counts_per_mps2, 6.49469e-6, PROV_SCALE_REL, "%s m/s2 per count",
                 names[i]);
    aq_check_abs(aq_test_mean(c), mean_counts[i], PROV_MEAN_ABS, "%s mean (real #66)",
                 names[i]);
    aq_check_rel(aq_test_peak_abs(c) * 6.49469e-6, raw_g[i] * G_TO_MPS2, PROV_PGA_REL,
                 "%s raw PGA", names[i]);
    aq_check_rel(aq_test_peak_demeaned(c) * 6.49469e-6, dm_g[i] * G_TO_MPS2, 2 * PROV_PGA_REL,
                 "%s demeaned PGA", names[i]);
    aq_check(i == 2 ? c->vertical == 1 && c->dip_deg == -90
                    : c->vertical == 0 && c->azimuth_deg == az[i],
             "%s orientation az %g dip %g vertical %d", names[i], c->azimuth_deg, c->dip_deg,
             c->vertical);
    aq_check(strcmp(c->reference, "2019-05-05T06:47:39.932Z") == 0, "%s start %s", names[i],
             c->reference);
  }
  /* the header's maximum is printed without its sign: -985881 counts */
  aq_check(r.chan[0].values[(size_t)(45.29 / 0.005 + 0.5)] == -985881, "HNE at 45.29 s");
out:
  aq_raw_file_free(&r);
}

AQ_TEST(io_cosmos_bad_input)
{
  char msg[1400];
  /* truncated in the real header (line 20 of 41 header lines) */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, COSMOS_SAMPLE, 1900, NULL, NULL, msg,
                               sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, COSMOS_SAMPLE, "real header"),
           "truncated header: %s", msg);
  /* truncated in the data */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, COSMOS_SAMPLE, 40000, NULL, NULL, msg,
                               sizeof msg) == AQ_EFORMAT &&
               (aq_test_msg_names(msg, COSMOS_SAMPLE, "NPTS") ||
                aq_test_msg_names(msg, COSMOS_SAMPLE, "data of channel 1")),
           "truncated data: %s", msg);
  /* sensor sensitivity (real #42) stated as 0 */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, COSMOS_V0, (size_t)-1, "       1.200000",
                               "       0.000000", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, COSMOS_V0, "real header #42"),
           "zero sensitivity: %s", msg);
  /* sampling interval (real #62) unknown */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, COSMOS_SAMPLE, (size_t)-1,
                               "  -999.000000    10.000000", "  -999.000000  -999.000000",
                               msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, COSMOS_SAMPLE, "real header #62"),
           "no dt: %s", msg);
  /* a letter inside a glued data field */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, COSMOS_SAMPLE, (size_t)-1, "-94.84213",
                               "-94.8x213", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, COSMOS_SAMPLE, "\"-94.8x213\""),
           "bad value: %s", msg);
  /* not COSMOS at all */
  aq_check(aq_test_raw_altered(aq_cosmos_parse, "tests/data/records/IELC180.AT2", (size_t)-1,
                               NULL, NULL, msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, "IELC180.AT2:1", "Format v01.20"),
           "AT2 given to COSMOS: %s", msg);
}

AQ_TEST(io_cosmos_cli_channels)
{
  char out[4096], errb[4096];
  /* each channel of a multi-channel file is a record of its own */
  int rc = aq_test_run("info '" COSMOS_V0 "#HNZ' " COSMOS_SAMPLE, out, sizeof out, errb,
                       sizeof errb);
  aq_check(rc == 0 && strstr(out, "v0c#HNZ\tcosmos\t20000\t0.005\t") &&
               strstr(out, "\tHNZ\tyes") && strstr(out, "v1\tcosmos\t7000\t0.01\t"),
           "exit %d: %s%s", rc, out, errb);
  rc = aq_test_run("info " AGENCY_DIR "CE89146.V1#Up", out, sizeof out, errb, sizeof errb);
  aq_check(rc == 0 && strstr(out, "#Up\tcsmip\t13200\t0.005\t") && strstr(out, "\tUp\tyes"),
           "CSMIP vertical: exit %d: %s%s", rc, out, errb);
}
