/* test_io_csmip_variants.c: CSMIP V1 and V2 as CGS's Avol1 and SCSN write
 * them, read as a user would (detection, reader, units decision), against
 * tests/data/records/agency2/PROVENANCE.md and the files' own header peaks:
 * the Avol1 V2 data line "... equally spaced at 0.005 sec, in cm/sec2.
 * (8f10.7)" (units and format in it), and the SCSN V1 header with "Station
 * Id." where CGS writes "Station No.". */
#include <string.h>

#include "agency2_fixture.h"

AQ_TEST(io_csmip_avol1_v2_in_cm_sec2)
{
  /* PROVENANCE: 13000 points, dt 0.005 s, peak -3.87255 cm/s2 = 0.003949 g;
   * header "Peak acceleration = -3.873 cm/sec/sec at 25.030 sec" */
  static const aq_test_expect e = {AGENCY2_DIR "chan006.v2", 13000, 0.005, 0.003949, 5e-7,
                                   "gal"};
  aq_record r;
  if (!aq_test_expect_read(&e, NULL, &r))
    return;
  aq_check(strcmp(r.format, "csmip") == 0, "format %s", r.format);
  aq_check(strcmp(r.channel, "Long") == 0, "channel \"%s\" (\"Chan  4:  Long\")", r.channel);
  aq_check(strcmp(r.station, "58658") == 0, "station %s", r.station);
  aq_check(strcmp(r.reference, "2021-04-26T17:09:54.000Z") == 0, "start %s", r.reference);
  /* the sample at 25.030 s is the peak, -3.87255 cm/s2 (8f10.7 read by width) */
  aq_check_abs(r.acc_mps2[(size_t)(25.030 / 0.005 + 0.5)], -3.8725502 * 0.01, 1e-12,
               "peak sample at 25.030 s");
  aq_check(!r.vertical, "Long is horizontal");
  aq_record_free(&r);
}

AQ_TEST(io_csmip_scsn_v1_station_id)
{
  /* PROVENANCE: channel 1 of CIWLT.RAW cut to 320 points; 100 pts/sec;
   * largest |value| 0.000024 g (stored to 1e-6 g) */
  static const aq_test_expect e = {AGENCY2_DIR "CIWLT-ch1-320pts.V1", 320, 0.01, 0.000024,
                                   5e-7, "g"};
  aq_record r;
  if (!aq_test_expect_read(&e, NULL, &r))
    return;
  aq_check(strcmp(r.format, "csmip") == 0, "format %s", r.format);
  aq_check(strcmp(r.station, "WLT") == 0, "station \"%s\" (\"Station Id. WLT\")", r.station);
  aq_check(strcmp(r.channel, "90") == 0 && r.azimuth_deg == 90, "channel %s azimuth %g",
           r.channel, r.azimuth_deg);
  aq_check(strcmp(r.reference, "2014-03-29T04:09:34.000Z") == 0, "start %s", r.reference);
  aq_record_free(&r);
}
