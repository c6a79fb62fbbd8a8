/* test_io_esm.c: the ESM/ITACA ASCII reader against the files' own header
 * (NDATA, SAMPLING_INTERVAL_S, PGA_CM/S^2 with TIME_PGA_S) and
 * tests/data/records/agency/PROVENANCE.md, and its refusals. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "raw_fixture.h"

#define ESM_E AGENCY_DIR "HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC"
#define ESM_N AGENCY_DIR "HL.DLFA..HNN.D.20190728.160908.C.ACC.ASC"
#define CMPS2_TO_MPS2 0.01 /* literal */
#define G_TO_MPS2 9.80665  /* literal */
#define PROV_PGA_REL 5e-4  /* PROVENANCE prints PGA to 4 significant digits */

AQ_TEST(io_esm_two_components)
{
  static const char *path[2] = {ESM_E, ESM_N}, *stream[2] = {"HNE", "HNN"};
  static const double pga_cm[2] = {-0.227973, 0.190172}; /* PGA_CM/S^2 */
  static const double t_pga_s[2] = {36.31, 36.60};         /* TIME_PGA_S */
  static const double pga_g[2] = {0.0002325, 0.0001939};
  for (int i = 0; i < 2; i++) {
    aq_raw_file r;
    if (!aq_test_raw_load(aq_esm_parse, path[i], &r))
      continue;
    const aq_raw_channel *c = &r.chan[0];
    aq_check(r.nchan == 1 && c->npts == 13876, "%s NDATA %zu", stream[i], c->npts);
    aq_check_rel(c->dt_s, 0.005, 1e-12, "%s dt", stream[i]);
    aq_check(strcmp(c->units, "cm/s2") == 0, "%s units %s", stream[i], c->units);
    size_t kp = (size_t)(t_pga_s[i] / 0.005 + 0.5);
    aq_check(c->values[kp] == pga_cm[i] && aq_test_peak_abs(c) == fabs(pga_cm[i]),
             "%s header PGA %g at %g s (sample %.9g)", stream[i], pga_cm[i], t_pga_s[i],
             c->values[kp]);
    aq_check_rel(aq_test_peak_abs(c) * CMPS2_TO_MPS2, pga_g[i] * G_TO_MPS2, PROV_PGA_REL,
                 "%s PGA", stream[i]);
    aq_check(strcmp(c->channel, stream[i]) == 0 && strcmp(c->network, "HL") == 0 &&
                 strcmp(c->station, "DLFA") == 0 && c->location[0] == '\0',
             "%s id %s.%s.%s.%s", stream[i], c->network, c->station, c->location, c->channel);
    aq_check(strcmp(c->reference, "2019-07-28T16:09:05.700Z") == 0, "start %s", c->reference);
    aq_check(strstr(r.event, "EMSC-20190728_0000106") && strstr(r.processing, "0.200-30.000"),
             "event '%s' processing '%s'", r.event, r.processing);
    aq_raw_file_free(&r);
  }
}

AQ_TEST(io_esm_bad_input)
{
  char msg[1400];
  aq_check(aq_test_raw_altered(aq_esm_parse, ESM_E, 400, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, ESM_E, "SAMPLING_INTERVAL_S"),
           "truncated header: %s", msg);
  aq_check(aq_test_raw_altered(aq_esm_parse, ESM_E, 60000, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               (aq_test_msg_names(msg, ESM_E, "NDATA")),
           "truncated data: %s", msg);
  aq_check(aq_test_raw_altered(aq_esm_parse, ESM_E, (size_t)-1, "SAMPLING_INTERVAL_S: 0.005000",
                               "SAMPLING_INTERVAL_S: -0.005", msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, ESM_E, "SAMPLING_INTERVAL_S") && strstr(msg, "\"-0.005\""),
           "negative dt: %s", msg);
  aq_check(aq_test_raw_altered(aq_esm_parse, ESM_E, (size_t)-1, "NDATA: 13876", "NDATA: 13875",
                               msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, ESM_E, "got more"),
           "NDATA short of the data: %s", msg);
}
