/* test_io_decide.c: the one place that decides (aq_record_decide): units
 * stated by the file win over a plain --units, a rule naming the file
 * overrides them and the conflict is kept and reported, an implausible PGA is
 * refused naming the units that would make it plausible, and vertical
 * channels are marked and refused by the main job.
 *
 * Expected values are literals: 1 g = 9.80665 m/s2 (CGPM 1901), 1 gal =
 * 0.01 m/s2, 1 nm/s2 = 1e-9 m/s2; the samples are the text's decimals. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define REC_DIR "tests/data/records/"
/* a sample is strtod of the text times a units factor: one rounding */
#define SAMPLE_REL 1e-15

static const char *const vals[4] = {"0.2385", "-0.3771905", "0.1937", "-0.0514159"};
#define PEAK_TEXT 0.3771905 /* the largest |value| of vals */

/* "HEADER\n0,v0\n0.01,v1\n..." */
static void make_text(const char *header, double scale_text, char *out, size_t cap)
{
  size_t k = (size_t)snprintf(out, cap, "%s\n", header);
  for (size_t i = 0; i < 4; i++)
    k += (size_t)snprintf(out + k, cap - k, "%.2f,%.10g\n", 0.01 * (double)i,
                          strtod(vals[i], NULL) * scale_text);
}

static aq_status parse(const char *text, const char *name, const aq_read_opts *ro,
                       aq_record *r, aq_error *e)
{
  aq_error_clear(e);
  return aq_record_parse((const unsigned char *)text, strlen(text), name, ro, r, e);
}

AQ_TEST(io_decide_stated_units_win)
{
  char text[512];
  aq_read_opts gal = {0};
  gal.units = AQ_UNITS_GAL;
  aq_record r;
  aq_error e;
  /* a CSV headed t,acc_g under --units gal stays in g */
  make_text("t,acc_g", 1.0, text, sizeof text);
  if (aq_check(parse(text, "stated.csv", &gal, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check(strcmp(r.units_used, "g") == 0 && strcmp(r.units_stated, "g") == 0 &&
                 r.units_conflict[0] == '\0',
             "used %s stated %s conflict '%s'", r.units_used, r.units_stated,
             r.units_conflict);
    for (size_t i = 0; i < 4; i++)
      aq_check_rel(r.acc_mps2[i], strtod(vals[i], NULL) * 9.80665, SAMPLE_REL,
                   "sample %zu in m/s2", i);
    aq_record_free(&r);
  }
  /* the same under a rule naming the file: read as gal, conflict kept */
  aq_read_opts rule = {0};
  snprintf(rule.rules[0].glob, sizeof rule.rules[0].glob, "*stated*");
  rule.rules[0].units = AQ_UNITS_GAL;
  rule.nrules = 1;
  make_text("t,acc_g", 981.0, text, sizeof text); /* gal values under a g header */
  if (aq_check(parse(text, "stated.csv", &rule, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check(strcmp(r.units_used, "gal") == 0 && strcmp(r.units_stated, "g") == 0 &&
                 strstr(r.units_conflict, "states g") &&
                 strstr(r.units_conflict, "*stated*=gal"),
             "used %s stated %s conflict '%s'", r.units_used, r.units_stated,
             r.units_conflict);
    aq_check_rel(r.acc_mps2[1], -0.3771905 * 981.0 * 0.01, 1e-9, "sample 1 as gal");
    aq_record_free(&r);
  }
  /* a file that states none takes the plain --units */
  make_text("t,acc", 981.0, text, sizeof text);
  if (aq_check(parse(text, "plain.csv", &gal, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check(strcmp(r.units_used, "gal") == 0 && r.units_stated[0] == '\0',
             "used %s stated '%s'", r.units_used, r.units_stated);
    aq_check_rel(r.acc_mps2[0], 0.2385 * 981.0 * 0.01, 1e-9, "sample 0 as gal");
    aq_record_free(&r);
  }
  /* new units words: g/10 and mm/s2 */
  aq_read_opts g10 = {0}, mm = {0};
  g10.units = AQ_UNITS_G10;
  mm.units = AQ_UNITS_MMPS2;
  make_text("t,acc", 1.0, text, sizeof text);
  if (aq_check(parse(text, "plain.csv", &g10, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check_rel(r.acc_mps2[0], 0.2385 * 0.980665, SAMPLE_REL, "g/10");
    aq_record_free(&r);
  }
  make_text("t,acc", 1000.0, text, sizeof text);
  if (aq_check(parse(text, "plain.csv", &mm, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check_rel(r.acc_mps2[0], 0.2385, SAMPLE_REL, "mm/s2");
    aq_record_free(&r);
  }
  aq_units u;
  aq_check(aq_units_parse("g/10", &u) && u == AQ_UNITS_G10 && aq_units_parse("mm/s2", &u) &&
               u == AQ_UNITS_MMPS2,
           "units words g/10 and mm/s2");
}

AQ_TEST(io_decide_implausible_refused)
{
  char text[512];
  aq_record r;
  aq_error e;
  char msg[1400];
  /* gal values (peak 370 gal) read as g: 370 g */
  aq_read_opts g = {0};
  g.units = AQ_UNITS_G;
  make_text("t,acc", 981.0, text, sizeof text);
  aq_status s = parse(text, "galvals.csv", &g, &r, &e);
  aq_error_format(&e, msg, sizeof msg);
  aq_check(s == AQ_EUNITS && !strchr(msg, '\n') && strstr(msg, "galvals.csv") &&
               strstr(msg, "PGA 370 g") && strstr(msg, "gal (0.377 g)") &&
               strstr(msg, "--accept-implausible"),
           "370 g refused: %s", msg);
  /* m/s2 values (peak 0.377 m/s2) read as nm/s2: 3.85e-11 g */
  aq_read_opts nm = {0};
  nm.units = AQ_UNITS_NMPS2;
  make_text("t,acc", 1.0, text, sizeof text);
  s = parse(text, "mvals.csv", &nm, &r, &e);
  aq_error_format(&e, msg, sizeof msg);
  aq_check(s == AQ_EUNITS && strstr(msg, "mvals.csv") && strstr(msg, "PGA 3.85e-11 g") &&
               strstr(msg, "m/s2 (0.0385 g)") && strstr(msg, "g (0.377 g)"),
           "4e-11 g refused: %s", msg);
  /* explicitly accepted */
  nm.accept_implausible = 1;
  if (aq_check(parse(text, "mvals.csv", &nm, &r, &e) == AQ_OK, "%s", e.message)) {
    aq_check_rel(r.acc_mps2[1], -0.3771905e-9, SAMPLE_REL, "kept as nm/s2");
    aq_record_free(&r);
  }
  /* the bounds: 9.9 g and 1.1e-5 g pass, 10.1 g and 0.9e-5 g do not */
  static const struct {
    double peak_g;
    int ok;
  } b[] = {{9.9, 1}, {10.1, 0}, {1.1e-5, 1}, {0.9e-5, 0}};
  for (size_t i = 0; i < 4; i++) {
    snprintf(text, sizeof text, "t,acc_g\n0,%.10g\n0.01,0\n", b[i].peak_g);
    s = parse(text, "bound.csv", NULL, &r, &e);
    aq_check((s == AQ_OK) == b[i].ok, "PGA %g g: status %d", b[i].peak_g, (int)s);
    aq_record_free(&r);
  }
}

AQ_TEST(io_decide_cli_units)
{
  static char out[8192], err[4096];
  /* an AT2 states g: --units gal leaves it (PROVENANCE PGA 0.3129 g) */
  int st = aq_test_run("info --no-filter --detrend none --units gal " REC_DIR "IELC180.AT2",
                       out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "\tg\t0.31") && !strstr(out, "\tgal\t"),
           "AT2 under --units gal: exit %d: %s %s", st, out, err);
  /* a rule naming it overrides: 0.3129 g / 980.665, conflict on stderr */
  st = aq_test_run("info --no-filter --detrend none --units '*IELC180*=gal' "
                   REC_DIR "IELC180.AT2",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "\tgal\t0.000319") &&
               strstr(err, "IELC180.AT2: units: the file states g") &&
               strchr(err, '\n') == strrchr(err, '\n'),
           "AT2 under a gal rule: exit %d: %s %s", st, out, err);
  /* read as nm/s2 it would be 3.2e-11 g: refused, g suggested */
  st = aq_test_run("info --units '*IELC180*=nm/s2' " REC_DIR "IELC180.AT2", out,
                   sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "IELC180.AT2") && strstr(err, "implausible") &&
               strstr(err, "'" REC_DIR "IELC180.AT2=U'") && strstr(err, "g (0.313 g)"),
           "AT2 as nm/s2 refused: exit %d: %s", st, err);
}

AQ_TEST(io_decide_vertical)
{
  /* SAC channel HNZ (CMPINC 0); JMA CSV column UD; a column named Up */
  aq_read_opts ro = {0};
  snprintf(ro.rules[0].glob, sizeof ro.rules[0].glob, "*CJ.T001230*");
  ro.rules[0].units = AQ_UNITS_G; /* IACC stated, values in g */
  ro.nrules = 1;
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_read(REC_DIR "20190706031952.CJ.T001230.HNZ.sac", &ro, &r, &e) ==
                   AQ_OK,
               "%s", e.message)) {
    aq_check(r.vertical == 1 && strcmp(r.channel, "HNZ") == 0, "HNZ vertical %d", r.vertical);
    /* SAC CMPINC 0: the dip says it, not the name */
    aq_check(aq_record_check_horizontal(&r, &ro, &e) == AQ_EUNSUPPORTED &&
                 strstr(e.message, "HNZ") && strstr(e.message, "--accept-vertical") &&
                 strstr(e.message, "by its dip, -90 deg") &&
                 r.vertical_by == AQ_VERTICAL_BY_DIP,
             "refused: %s", e.message);
    ro.accept_vertical = 1;
    aq_check(aq_record_check_horizontal(&r, &ro, &e) == AQ_OK, "accepted");
    ro.accept_vertical = 0;
    aq_record_free(&r);
  }
  if (aq_check(aq_record_read(REC_DIR "20190706031952.CJ.T001230.HNE.sac", &ro, &r, &e) ==
                   AQ_OK,
               "%s", e.message)) {
    aq_check(r.vertical == 0, "HNE horizontal");
    aq_check(aq_record_check_horizontal(&r, &ro, &e) == AQ_OK, "HNE runs");
    aq_record_free(&r);
  }
  static const struct {
    const char *header;
    int vertical;
  } c[] = {{"t,UD (gal)", 1}, {"time,Up (gal)", 1}, {"t,acc_V (gal)", 1},
           {"t,vert (gal)", 1}, {"t,Z (gal)", 1},     {"t,EW (gal)", 0},
           {"t,acc (gal)", 0},  {"t,HNZ (gal)", 1},   {"t,HN2 (gal)", 0}};
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    char text[512];
    make_text(c[i].header, 100.0, text, sizeof text);
    if (aq_check(parse(text, "col.csv", NULL, &r, &e) == AQ_OK, "%s: %s", c[i].header,
                 e.message)) {
      aq_check(r.vertical == c[i].vertical, "%s: vertical %d", c[i].header, r.vertical);
      /* a CSV column states no orientation: only its name can say vertical */
      aq_check(r.vertical_by == (c[i].vertical ? AQ_VERTICAL_BY_NAME : AQ_VERTICAL_BY_NONE),
               "%s: vertical_by %d", c[i].header, r.vertical_by);
      if (c[i].vertical)
        aq_check(aq_record_check_horizontal(&r, NULL, &e) == AQ_EUNSUPPORTED &&
                     strstr(e.message, "by its channel name"),
                 "%s: %s", c[i].header, e.message);
      aq_record_free(&r);
    }
  }
}

/* K-NET states the direction (Dir. UD): refused "as the file states"; the
 * EW file of the same station runs. */
AQ_TEST(io_decide_vertical_stated)
{
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_read(REC_DIR "AOM0170806140843.UD", NULL, &r, &e) == AQ_OK, "%s",
               e.message)) {
    aq_check(r.vertical == 1 && r.vertical_by == AQ_VERTICAL_BY_STATED, "UD: %d by %d",
             r.vertical, r.vertical_by);
    aq_check(aq_record_check_horizontal(&r, NULL, &e) == AQ_EUNSUPPORTED &&
                 strstr(e.message, "as the file states"),
             "UD refused: %s", e.message);
    aq_record_free(&r);
  }
  if (aq_check(aq_record_read(REC_DIR "AOM0170806140843.EW", NULL, &r, &e) == AQ_OK, "%s",
               e.message)) {
    aq_check(r.vertical == 0 && r.vertical_by == AQ_VERTICAL_BY_NONE, "EW: %d by %d",
             r.vertical, r.vertical_by);
    aq_check(aq_record_check_horizontal(&r, NULL, &e) == AQ_OK, "EW runs");
    aq_record_free(&r);
  }
}

AQ_TEST(io_decide_vertical_cli)
{
  static char out[16384], err[4096];
  /* info shows it, does not refuse */
  int st = aq_test_run("info --units '*CJ*=g' " REC_DIR "20190706031952.CJ.T001230.HNZ.sac",
                       out, sizeof out, err, sizeof err);
  aq_check(st == 0 && strstr(out, "\tHNZ\tyes"), "info: exit %d: %s %s", st, out, err);
  /* the main job refuses it naming the channel, runs the horizontal one */
  st = aq_test_run("--arch arches/thick.cfg --scale 0.5 --units '*CJ*=g' "
                   REC_DIR "20190706031952.CJ.T001230.HNZ.sac "
                   REC_DIR "20190706031952.CJ.T001230.HNE.sac",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "HNZ.sac: channel: expected a horizontal") &&
               strstr(err, "\"HNZ\"") && !strstr(err, "HNE.sac: channel"),
           "run refuses HNZ: exit %d: %s", st, err);
  st = aq_test_run("--arch arches/thick.cfg --scale 0.5 --units '*CJ*=g' --accept-vertical "
                   REC_DIR "20190706031952.CJ.T001230.HNZ.sac",
                   out, sizeof out, err, sizeof err);
  aq_check(st == 0, "--accept-vertical runs it: exit %d: %s", st, err);
  /* the UD column of the JMA CSV */
  st = aq_test_run("--arch arches/thick.cfg --scale 0.5 " REC_DIR "Q4149CF2.csv#UD", out,
                   sizeof out, err, sizeof err);
  aq_check(st == 1 && strstr(err, "Q4149CF2.csv#UD: channel") && strstr(err, "\"UD\""),
           "run refuses UD: exit %d: %s", st, err);
}

/* SAC orientation: CMPINC 0 (up) or 180 (down) is vertical whatever the
 * channel code; 90 is horizontal (test.sac, IDEP undefined, read as m/s2). */
AQ_TEST(io_decide_sac_cmpinc)
{
  FILE *f = fopen(REC_DIR "test.sac", "rb");
  unsigned char b[1032];
  size_t n = f ? fread(b, 1, sizeof b, f) : 0;
  if (f)
    fclose(f);
  if (!aq_check(n == 1032, "test.sac read"))
    return;
  memcpy(b + 600, "HN3     ", 8); /* KCMPNM: not a Z code */
  static const struct {
    float cmpinc;
    int vertical;
  } c[] = {{0.0f, 1}, {180.0f, 1}, {90.0f, 0}, {-12345.0f, 0}};
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_MPS2;
  ro.accept_implausible = 1;
  for (size_t i = 0; i < 4; i++) {
    memcpy(b + 4 * 58, &c[i].cmpinc, 4); /* CMPINC, float word 58; host little-endian */
    aq_record r;
    aq_error e;
    if (aq_check(aq_record_parse(b, sizeof b, "inc.sac", &ro, &r, &e) == AQ_OK, "%s",
                 e.message)) {
      aq_check(r.vertical == c[i].vertical, "CMPINC %g: vertical %d", c[i].cmpinc,
               r.vertical);
      aq_record_free(&r);
    }
  }
}
