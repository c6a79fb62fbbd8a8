/* test_io_mseed.c: the miniSEED reader (libmseed) with StationXML
 * sensitivities (libxml2) against tests/data/records/agency/PROVENANCE.md
 * (an independent Steim2 decoder in numpy, checked against each record's
 * integration constant) and against the same CI.CLC record as SAC written by
 * Debian's mseed2sac; gaps, overlaps and StationXML without a matching
 * channel or epoch. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "raw_fixture.h"

#define REC_DIR "tests/data/records/"
#define CE_XML AGENCY_DIR "CE.58360.xml"
#define CE_FILE(c) AGENCY_DIR "CE.58360..HN" c "__20191015T053312Z__20191015T054042Z.mseed"
#define G_TO_MPS2 9.80665   /* literal */
#define PROV_PGA_REL 5e-4   /* PROVENANCE prints PGA to 4 significant digits */
#define PROV_MEAN_ABS 0.006 /* means printed to 2 decimals (counts) */
#define SAME_EVENT_REL 0.01 /* the agreement between two formats */
#define MSEED_RECLEN 4096   /* the CE.58360 files: 4 records of 4096 bytes */

/* The StationXML at path with text `from` replaced once by `to` (from
 * NULL: unchanged) written to a file of the test's directory, named name;
 * its path into out.  Returns 1 on success. */
static int xml_file(const char *path, const char *from, const char *to, const char *name,
                    char *out, size_t cap)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  return aq_test_edited_copy(path, from, to, dir, name, out, cap);
}

/* Parse mseed at path with the responses xml[0..nxml) (as --response gives
 * them); AQ status, message in msg. */
static aq_status with_responses(const char *path, const char *const *xml, size_t nxml,
                                aq_raw_file *raw, char *msg, size_t cap)
{
  size_t n;
  char *buf = aq_test_read_file(path, &n);
  memset(raw, 0, sizeof *raw);
  if (!aq_check(buf != NULL, "read %s", path))
    return AQ_EIO;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  for (size_t i = 0; i < nxml; i++)
    ro.responses[ro.nresponses++] = xml[i];
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_raw_parse((const unsigned char *)buf, n, path, &ro, raw, &e);
  aq_error_format(&e, msg, cap);
  free(buf);
  return s;
}

static aq_status with_response(const char *path, const char *xml, aq_raw_file *raw, char *msg,
                               size_t cap)
{
  return with_responses(path, &xml, 1, raw, msg, cap);
}

AQ_TEST(io_mseed_ce58360_with_stationxml)
{
  char msg[1400];
  static const char *comp[3] = {"E", "N", "Z"};
  static const double sens[3] = {152378.61058, 152444.97686, 157251.15408};
  static const double raw_g[3] = {0.08312, 0.05354, 1.031};
  static const double dm_g[3] = {0.07610, 0.05712, 0.03360};
  static const double mean_counts[3] = {-10480.69, 7226.59, 1539918.25};
  static const double az[3] = {90, 0, 0}, dip[3] = {0, 0, -90};
  const char *path[3] = {CE_FILE("E"), CE_FILE("N"), CE_FILE("Z")};
  for (int i = 0; i < 3; i++) {
    aq_raw_file r;
    aq_status s = with_response(path[i], CE_XML, &r, msg, sizeof msg);
    if (!aq_check(s == AQ_OK && r.nchan == 1, "HN%s: %s", comp[i], msg)) {
      aq_raw_file_free(&r);
      continue;
    }
    const aq_raw_channel *c = &r.chan[0];
    aq_check(c->npts == 12400, "HN%s npts %zu", comp[i], c->npts);
    aq_check_rel(c->dt_s, 0.005, 1e-12, "HN%s dt", comp[i]);
    aq_check(strcmp(c->reference, "2019-10-15T05:33:21.000Z") == 0, "start %s", c->reference);
    aq_check(strcmp(c->network, "CE") == 0 && strcmp(c->station, "58360") == 0 &&
                 c->location[0] == '\0',
             "id %s.%s.%s", c->network, c->station, c->location);
    aq_check(strcmp(c->units, "counts") == 0, "units %s", c->units);
    aq_check_rel(c->counts_per_mps2, sens[i], 1e-12, "HN%s sensitivity", comp[i]);
    aq_check_abs(aq_test_mean(c), mean_counts[i], PROV_MEAN_ABS, "HN%s mean counts", comp[i]);
    aq_check_rel(aq_test_peak_abs(c) / sens[i], raw_g[i] * G_TO_MPS2, PROV_PGA_REL,
                 "HN%s raw PGA", comp[i]);
    aq_check_rel(aq_test_peak_demeaned(c) / sens[i], dm_g[i] * G_TO_MPS2, PROV_PGA_REL,
                 "HN%s demeaned PGA", comp[i]);
    aq_check(c->azimuth_deg == az[i] && c->dip_deg == dip[i] && c->vertical == (i == 2),
             "HN%s az %g dip %g vertical %d", comp[i], c->azimuth_deg, c->dip_deg, c->vertical);
    aq_raw_file_free(&r);
  }
}

/* CI.CLC HNE: miniSEED + StationXML here, and the SAC that mseed2sac wrote
 * from it read by the SAC reader; demeaned PGA 0.3433 g in PROVENANCE. */
AQ_TEST(io_mseed_ci_clc_agrees_with_sac)
{
  char msg[1400];
  aq_raw_file r;
  aq_status s = with_response(REC_DIR "CI.CLC..HNE.mseed", REC_DIR "CI.CLC.xml", &r, msg,
                              sizeof msg);
  if (!aq_check(s == AQ_OK && r.nchan == 1, "%s", msg)) {
    aq_raw_file_free(&r);
    return;
  }
  const aq_raw_channel *c = &r.chan[0];
  double pga_mseed = aq_test_peak_demeaned(c) / c->counts_per_mps2;
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_COUNTS;
  aq_record sac;
  aq_error e;
  aq_error_clear(&e);
  s = aq_record_read(REC_DIR "CI.CLC..HNE.D.2019.187.031923.SAC", &ro, &sac, &e);
  if (aq_check(s == AQ_OK, "SAC: %s", e.message)) {
    aq_raw_channel view = {.npts = sac.npts, .values = sac.acc_mps2};
    double pga_sac = aq_test_peak_demeaned(&view);
    aq_check(sac.npts == c->npts, "npts SAC %zu mseed %zu", sac.npts, c->npts);
    aq_check_rel(pga_mseed, pga_sac, SAME_EVENT_REL, "demeaned PGA mseed+xml vs SAC (m/s2)");
    aq_check_rel(sac.dt_s, c->dt_s, 1e-6, "dt");
    aq_record_free(&sac);
  }
  aq_check_rel(pga_mseed, 0.3433 * G_TO_MPS2, PROV_PGA_REL, "demeaned PGA vs PROVENANCE");
  aq_raw_file_free(&r);
}

/* The HNE file with its records rearranged: bytes of records in `order`. */
static aq_status rearranged(const int *order, size_t nrec, aq_raw_file *raw, char *msg,
                            size_t cap)
{
  size_t n;
  char *buf = aq_test_read_file(CE_FILE("E"), &n);
  memset(raw, 0, sizeof *raw);
  if (!aq_check(buf && n == 4 * MSEED_RECLEN, "read HNE"))
    return AQ_EIO;
  char *out = malloc(nrec * MSEED_RECLEN);
  for (size_t i = 0; i < nrec; i++)
    memcpy(out + i * MSEED_RECLEN, buf + (size_t)order[i] * MSEED_RECLEN, MSEED_RECLEN);
  aq_status s =
      aq_test_raw_parse_buf(aq_mseed_parse, out, nrec * MSEED_RECLEN, CE_FILE("E"), raw, msg, cap);
  free(out);
  free(buf);
  return s;
}

AQ_TEST(io_mseed_gaps_overlaps_truncation)
{
  char msg[1400];
  aq_raw_file whole, r;
  if (!aq_test_raw_load(aq_mseed_parse, CE_FILE("E"), &whole))
    return;
  /* record 2 missing: a gap, refused */
  static const int gap[3] = {0, 2, 3};
  aq_check(rearranged(gap, 3, &r, msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, CE_FILE("E"), "gap of") && strstr(msg, "HNE"),
           "gap: %s", msg);
  /* record 2 twice and the records out of order: agreeing overlap, merged */
  static const int dup[5] = {1, 0, 1, 3, 2};
  if (aq_check(rearranged(dup, 5, &r, msg, sizeof msg) == AQ_OK, "overlap: %s", msg)) {
    int same = r.chan[0].npts == whole.chan[0].npts;
    for (size_t k = 0; same && k < whole.chan[0].npts; k++)
      same = r.chan[0].values[k] == whole.chan[0].values[k];
    aq_check(same, "merged overlap equals the file (npts %zu)", r.chan[0].npts);
    aq_raw_file_free(&r);
  }
  /* record 2 again, its start one sample later (BTIME ticks, bytes 28-29,
     big-endian, + 50 x 0.1 ms = 5 ms = dt): it overlaps record 2 with its
     values shifted by a sample, which differ: refused, naming the overlap */
  size_t nb;
  unsigned char *ce = (unsigned char *)aq_test_read_file(CE_FILE("E"), &nb);
  if (aq_check(ce && nb == 4 * MSEED_RECLEN, "read HNE")) {
    unsigned char *out = malloc(5 * MSEED_RECLEN);
    static const int ord[5] = {0, 1, 1, 2, 3};
    for (size_t i = 0; out && i < 5; i++)
      memcpy(out + i * MSEED_RECLEN, ce + (size_t)ord[i] * MSEED_RECLEN, MSEED_RECLEN);
    if (out) {
      unsigned char *t = out + 2 * MSEED_RECLEN + 28;
      unsigned ticks = (unsigned)t[0] << 8 | t[1];
      aq_check(ticks == 4700, "record 2 starts at 05:33:46.4700 (ticks %u)", ticks);
      ticks += 50;
      t[0] = (unsigned char)(ticks >> 8), t[1] = (unsigned char)ticks;
      aq_check(aq_test_raw_parse_buf(aq_mseed_parse, (char *)out, 5 * MSEED_RECLEN,
                                     CE_FILE("E"), &r, msg, sizeof msg) == AQ_EFORMAT &&
                   aq_test_msg_names(msg, CE_FILE("E"), "overlap of") &&
                   strstr(msg, "values differ"),
               "disagreeing overlap: %s", msg);
      free(out);
    }
  }
  free(ce);
  /* truncated inside record 3 */
  aq_check(aq_test_raw_altered(aq_mseed_parse, CE_FILE("E"), 2 * MSEED_RECLEN + 1000, NULL, NULL,
                               msg, sizeof msg) == AQ_EFORMAT &&
               aq_test_msg_names(msg, CE_FILE("E"), "byte 8192"),
           "truncated data: %s", msg);
  /* truncated inside the first header */
  aq_check(aq_test_raw_altered(aq_mseed_parse, CE_FILE("E"), 30, NULL, NULL, msg, sizeof msg) ==
                   AQ_EFORMAT &&
               aq_test_msg_names(msg, CE_FILE("E"), "byte 0"),
           "truncated header: %s", msg);
  aq_raw_file_free(&whole);
}

AQ_TEST(io_mseed_stationxml_choices_and_refusals)
{
  char msg[1400], xp[700];
  aq_response resp;
  aq_raw_file r;
  /* another station's StationXML: no matching channel */
  aq_check(with_response(CE_FILE("E"), REC_DIR "CI.CLC.xml", &r, msg, sizeof msg) ==
                   AQ_EUNITS &&
               strstr(msg, "CI.CLC.xml") && strstr(msg, "CE.58360..HNE") &&
               strstr(msg, "got none"),
           "no channel: %s", msg);
  aq_raw_file_free(&r);
  /* the only HNE epoch starts after the record */
  if (xml_file(CE_XML, "endDate=\"3000-01-01T00:00:00\" locationCode=\"\" startDate=\"2008-01-23",
               "endDate=\"3000-01-01T00:00:00\" locationCode=\"\" startDate=\"2020-01-23",
               "later.xml", xp, sizeof xp)) {
    aq_check(with_response(CE_FILE("E"), xp, &r, msg, sizeof msg) == AQ_EUNITS &&
                 strstr(msg, "later.xml") && strstr(msg, "epochs") &&
                 strstr(msg, "2019-10-15T05:33:21") && strstr(msg, "2020-01-23"),
             "no epoch: %s", msg);
    aq_raw_file_free(&r);
  }
  /* velocity input units: the record is velocity (refused when decided) */
  if (xml_file(CE_XML, "<Name>M/S**2</Name>", "<Name>M/S</Name>", "vel.xml", xp, sizeof xp)) {
    if (aq_check(with_response(CE_FILE("E"), xp, &r, msg, sizeof msg) == AQ_OK, "vel: %s", msg))
      aq_check(r.chan[0].quantity == AQ_QUANTITY_VELOCITY &&
                   strstr(r.chan[0].quantity_said, "M/S"),
               "velocity stated: %d %s", r.chan[0].quantity, r.chan[0].quantity_said);
    aq_raw_file_free(&r);
  }
  /* input units volts: refused naming them */
  if (xml_file(CE_XML, "<Name>M/S**2</Name>", "<Name>V</Name>", "volts.xml", xp, sizeof xp)) {
    aq_check(with_response(CE_FILE("E"), xp, &r, msg, sizeof msg) == AQ_EUNITS &&
                 aq_test_msg_names(msg, "volts.xml", "InputUnits") && strstr(msg, "\"V\""),
             "volts: %s", msg);
    aq_raw_file_free(&r);
  }
  /* input units g: counts per g / 9.80665 */
  if (xml_file(CE_XML, "<Name>M/S**2</Name>", "<Name>g</Name>", "g.xml", xp, sizeof xp)) {
    if (aq_check(with_response(CE_FILE("E"), xp, &r, msg, sizeof msg) == AQ_OK, "g: %s", msg))
      aq_check_rel(r.chan[0].counts_per_mps2, 152378.61058 / G_TO_MPS2, 1e-12, "per g");
    aq_raw_file_free(&r);
  }
  /* nm/s2 and a negative sensitivity (reversed polarity), sign kept */
  if (xml_file(CE_XML, "<Value>152378.61058</Value>\n      <Frequency>1.0</Frequency>\n      "
                       "<InputUnits>\n       <Name>M/S**2</Name>",
               "<Value>-1.5237861058e-4</Value>\n      <Frequency>1.0</Frequency>\n      "
               "<InputUnits>\n       <Name>NM/S**2</Name>",
               "neg.xml", xp, sizeof xp)) {
    if (aq_check(with_response(CE_FILE("E"), xp, &r, msg, sizeof msg) == AQ_OK,
                 "nm/s2: %s", msg))
      aq_check_rel(r.chan[0].counts_per_mps2, -152378.61058, 1e-9, "negative, per nm/s2 (%.10g)",
                   r.chan[0].counts_per_mps2);
    aq_raw_file_free(&r);
  }
  /* a StationXML cut in the middle */
  size_t n;
  char *x = aq_test_read_file(CE_XML, &n);
  if (x) {
    aq_error e;
    aq_error_clear(&e);
    aq_check(aq_stationxml_parse((const unsigned char *)x, n / 2, CE_XML, &resp, &e) ==
                     AQ_EFORMAT && resp.n == 0,
             "truncated XML refused");
    aq_error_format(&e, msg, sizeof msg);
    aq_check(aq_test_msg_names(msg, CE_XML, "XML"), "truncated XML: %s", msg);
    free(x);
  }
}

/* The column `col` (0-based) of the second line of a TSV table, as a number. */
static double tsv_field(const char *out, int col)
{
  const char *p = strchr(out, '\n');
  for (int i = 0; p && i < col; i++)
    p = strchr(p + 1, '\t');
  return p ? atof(p + 1) : NAN;
}

AQ_TEST(io_mseed_cli_response_and_xml_among_records)
{
  char out[4096], errb[4096];
  /* StationXML given among the records; PGA after info's baseline removal
   * against the demeaned PGA in PROVENANCE */
  int rc = aq_test_run("info " REC_DIR "CI.CLC.xml " REC_DIR "CI.CLC..HNE.mseed", out, sizeof out,
                       errb, sizeof errb);
  if (aq_check(rc == 0, "exit %d: %s", rc, errb))
    aq_check_rel(tsv_field(out, 6), 0.3433, SAME_EVENT_REL, "pga_g of CI.CLC HNE: %s", out);
  rc = aq_test_run("info --response " CE_XML " " CE_FILE("Z"), out, sizeof out, errb,
                   sizeof errb);
  if (aq_check(rc == 0, "exit %d: %s", rc, errb))
    aq_check(strstr(out, "\tHNZ\tyes") != NULL, "HNZ marked vertical: %s", out);
  /* the wrong station's StationXML: one line naming the XML and the channel */
  rc = aq_test_run("info --response " REC_DIR "CI.CLC.xml " CE_FILE("E"), out, sizeof out, errb,
                   sizeof errb);
  aq_check(rc == 1 && strstr(errb, "CI.CLC.xml") && strstr(errb, "CE.58360..HNE") &&
               strchr(errb, '\n') == errb + strlen(errb) - 1,
           "wrong XML: exit %d: %s", rc, errb);
}
