/* test_io_stated.c: what a file states is used, as a user reads it: the
 * sample interval a text header states over --dt (which is for files that
 * state none), and the channel's name as written, never a cut phrase
 * ("Acceleration (g" from a column "Acceleration (g)") nor a word of a
 * sentence or a Fortran format taken for PEER's component ("8" from "8
 * values per line (8F10.5)"). */
#include <math.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

static int parse_text(const char *text, const aq_read_opts *ro, aq_record *r)
{
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_record_parse((const unsigned char *)text, strlen(text), "stated.txt", ro, r, &e);
  return aq_check(s == AQ_OK, "parse: %s", e.message);
}

AQ_TEST(io_stated_dt_over_option)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.dt_s = 0.05;
  ro.units = AQ_UNITS_G;
  aq_record r;
  if (parse_text("Station X\nDT= 0.02\n0.125\n-0.25\n0.0625\n", &ro, &r)) {
    aq_check(r.dt_s == 0.02 && r.npts == 3, "dt %g (the file's 0.02 s, not --dt 0.05)", r.dt_s);
    aq_record_free(&r);
  }
  if (parse_text("Station X\n0.125\n-0.25\n0.0625\n", &ro, &r)) { /* states none */
    aq_check(r.dt_s == 0.05, "dt %g (--dt, the file states none)", r.dt_s);
    aq_record_free(&r);
  }
}

AQ_TEST(io_stated_channel_names)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_record r;
  if (parse_text("Time (s), Acceleration (g)\n0, 0.125\n0.01, -0.25\n0.02, 0.0625\n", &ro, &r)) {
    aq_check(strcmp(r.channel, "Acceleration") == 0 && strcmp(r.units_stated, "g") == 0,
             "channel \"%s\" units %s", r.channel, r.units_stated);
    aq_record_free(&r);
  }
  /* a name that fits is kept as written, units and all */
  if (parse_text("time,acc (g)\n0,0.125\n0.01,-0.25\n0.02,0.0625\n", &ro, &r)) {
    aq_check(strcmp(r.channel, "acc (g)") == 0, "channel \"%s\"", r.channel);
    aq_record_free(&r);
  }
  static const char *const line2[] = {
      "Imperial Valley, 5/19/40, El Centro, 8 values per line (8F10.5)",
      "Imperial Valley, 5/19/40, El Centro, 8F10.5"};
  for (int i = 0; i < 2; i++) {
    char text[400];
    snprintf(text, sizeof text,
             "PEER NGA STRONG MOTION DATABASE RECORD\n%s\nACCELERATION TIME SERIES IN UNITS "
             "OF G\nNPTS=  3, DT= .0100 SEC\n 0.125 -0.25 0.0625\n",
             line2[i]);
    if (parse_text(text, &ro, &r)) {
      aq_check(r.channel[0] == '\0' && isnan(r.azimuth_deg), "\"%s\": channel \"%s\" azimuth %g",
               line2[i], r.channel, r.azimuth_deg);
      aq_record_free(&r);
    }
  }
  /* PEER's own last fields stay components: "180", "N (CWB)" */
  static const char *const peer[][2] = {{"Imperial Valley-02, 5/19/1940, El Centro Array #9, 180", "180"},
                                        {"CHI-CHI 09/20/99, CHY028, N (CWB)", "N"}};
  for (int i = 0; i < 2; i++) {
    char text[400];
    snprintf(text, sizeof text,
             "PEER NGA STRONG MOTION DATABASE RECORD\n%s\nACCELERATION TIME SERIES IN UNITS "
             "OF G\nNPTS=  3, DT= .0100 SEC\n 0.125 -0.25 0.0625\n",
             peer[i][0]);
    if (parse_text(text, &ro, &r)) {
      aq_check(strcmp(r.channel, peer[i][1]) == 0, "\"%s\": channel \"%s\"", peer[i][0], r.channel);
      aq_record_free(&r);
    }
  }
}
