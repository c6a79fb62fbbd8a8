/* test_io_csmip.c: the CSMIP (CGS/CDMG) V1/V2 reader against the numbers in
 * tests/data/records/agency/PROVENANCE.md and the files' own header peaks,
 * and its refusals of damaged files. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "raw_fixture.h"

#define CSMIP_V1 AGENCY_DIR "CE89146.V1"
#define CSMIP_V2 AGENCY_DIR "ce36456p_CE36456.V2"
#define CMPS2_TO_MPS2 0.01 /* literal */
#define G_TO_MPS2 9.80665  /* literal */
#define PROV_PGA_REL 5e-4  /* PROVENANCE prints PGA to 4 significant digits */

AQ_TEST(io_csmip_v1_three_channels_vertical_in_middle)
{
  aq_raw_file r;
  if (!aq_test_raw_load(aq_csmip_parse, CSMIP_V1, &r))
    return;
  aq_check(r.nchan == 3, "nchan %zu", r.nchan);
  if (r.nchan != 3)
    goto out;
  /* header peaks (g): .079 at 30.590, .021 at 30.590, -.045 at 30.575 */
  static const double peak_g[3] = {0.079180, 0.021055, 0.045290};
  static const double t_peak_s[3] = {30.590, 30.590, 30.575};
  static const int vertical[3] = {0, 1, 0};
  static const double az[3] = {360, NAN, 90};
  for (int i = 0; i < 3; i++) {
    const aq_raw_channel *c = &r.chan[i];
    aq_check(c->npts == 13200, "ch %d npts %zu", i + 1, c->npts);
    aq_check_rel(c->dt_s, 1.0 / 200, 1e-12, "ch %d dt (200 pts/sec)", i + 1);
    aq_check(strcmp(c->units, "g") == 0, "ch %d units %s", i + 1, c->units);
    double pk = aq_test_peak_abs(c);
    aq_check_abs(pk, peak_g[i], 5e-7, "ch %d peak g", i + 1);
    aq_check_rel(pk * G_TO_MPS2, peak_g[i] * G_TO_MPS2, PROV_PGA_REL, "ch %d PGA m/s2", i + 1);
    aq_check(fabs(c->values[(size_t)(t_peak_s[i] / 0.005 + 0.5)]) == pk, "ch %d peak time",
             i + 1);
    aq_check(c->vertical == vertical[i] && (vertical[i] || c->azimuth_deg == az[i]),
             "ch %d vertical %d azimuth %g", i + 1, c->vertical, c->azimuth_deg);
    aq_check(strcmp(c->station, "89146") == 0, "station %s", c->station);
    aq_check(strcmp(c->reference, "2012-02-13T21:06:45.000Z") == 0, "start %s", c->reference);
  }
out:
  aq_raw_file_free(&r);
}

AQ_TEST(io_csmip_v2_accel_block_lengths_pdt)
{
  aq_raw_file r;
  if (!aq_test_raw_load(aq_csmip_parse, CSMIP_V2, &r))
    return;
  aq_check(r.nchan == 3, "nchan %zu (ACCEL blocks only)", r.nchan);
  if (r.nchan != 3)
    goto out;
  static const size_t npts[3] = {3251, 3250, 3250};
  /* PEAK ACCELERATION = -267.957 / -94.805 / -256.231 CM/SEC/SEC */
  static const double peak_cm[3] = {267.957, 94.805, 256.231};
  static const double pga_g[3] = {0.2732, 0.09667, 0.2613};
  for (int i = 0; i < 3; i++) {
    const aq_raw_channel *c = &r.chan[i];
    aq_check(c->npts == npts[i], "ch %d npts %zu", i + 1, c->npts);
    aq_check_rel(c->dt_s, 0.02, 1e-12, "ch %d dt", i + 1);
    aq_check(strcmp(c->units, "cm/s2") == 0, "ch %d units %s", i + 1, c->units);
    double pk = aq_test_peak_abs(c);
    aq_check_abs(pk, peak_cm[i], 0.0005, "ch %d header peak cm/s2", i + 1);
    aq_check_rel(pk * CMPS2_TO_MPS2, pga_g[i] * G_TO_MPS2, PROV_PGA_REL, "ch %d PGA", i + 1);
    /* 16:42:48.2 PDT = 23:42:48.2 UTC (gmprocess asserts the same) */
    aq_check(strcmp(c->reference, "1983-05-02T23:42:48.200Z") == 0, "start %s", c->reference);
  }
  aq_check(r.chan[1].vertical == 1 && r.chan[0].azimuth_deg == 90 &&
               r.chan[2].azimuth_deg == 0,
           "orientations");
out:
  aq_raw_file_free(&r);
}

AQ_TEST(io_csmip_bad_input)
{
  char msg[1400];
  /* cut inside the integer header of channel 1 (line 16 of CE89146.V1) */
  aq_check(aq_test_raw_altered(aq_csmip_parse, CSMIP_V1, 1200, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, CSMIP_V1, "data line"),
           "truncated header: %s", msg);
  aq_check(aq_test_raw_altered(aq_csmip_parse, CSMIP_V1, 100000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               (aq_test_msg_names(msg, CSMIP_V1, "NPTS") ||
                aq_test_msg_names(msg, CSMIP_V1, "data of channel 1")),
           "truncated data: %s", msg);
  aq_check(aq_test_raw_altered(aq_csmip_parse, CSMIP_V1, (size_t)-1, "at 200 pts/sec",
                               "at 0 pts/sec", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, CSMIP_V1, "sampling"),
           "zero rate: %s", msg);
  aq_check(aq_test_raw_altered(aq_csmip_parse, CSMIP_V2, (size_t)-1, "    0    01304313043",
                               "    0    0130x313043", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, CSMIP_V2, "integer header"),
           "bad integer header: %s", msg);
  aq_check(aq_test_raw_altered(aq_csmip_parse, AGENCY_DIR "Cosmos12TimeSeriesTest.v1",
                               (size_t)-1, NULL, NULL, msg, sizeof msg) == AQ_EFORMAT,
           "COSMOS given to CSMIP: %s", msg);
}
