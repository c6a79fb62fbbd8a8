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
  /* NDATA short of the data.  By one: the value past it, -0.000014, is a
     copy of the last row read (the file's last three values are alike), so
     it is noted and not read (so it is for the last 69, all -0.000014); by
     76: the rows past it hold -0.000013 too, are not all copies, and
     the record is refused naming both counts (the rule of every reader
     that reads a stated count, record.c) */
  char dir[512], p[700];
  aq_test_tmpdir(dir, sizeof dir);
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_record r;
  aq_error e;
  if (aq_test_edited_copy(ESM_E, "NDATA: 13876", "NDATA: 13875", dir, "one.ASC", p,
                          sizeof p) &&
      aq_check(aq_record_read(p, &ro, &r, &e) == AQ_OK, "one short: %s", e.message)) {
    aq_check(r.npts == 13875 && strstr(r.count_note, "holds 13876 values, NDATA states 13875") &&
                 strstr(r.count_note, "the row at line 13940 repeats"),
             "NDATA one short, a copy: %s", r.count_note);
    aq_record_free(&r);
  }
  if (aq_test_edited_copy(ESM_E, "NDATA: 13876", "NDATA: 13800", dir, "short.ASC", p,
                          sizeof p)) {
    aq_status s = aq_record_read(p, &ro, &r, &e);
    aq_error_format(&e, msg, sizeof msg);
    aq_check(s == AQ_EFORMAT && strstr(msg, "short.ASC:13865: data: expected 13800 values "
                                            "(NDATA), got 13876: the 76 rows from line 13865"),
             "NDATA short of the data: %s", msg);
  }
}
