/* geonet.c: GeoNet (GNS Science, New Zealand) V1A/V2A strong-motion text
 * format (reader.h; notes in docs/agency-formats.md).
 *
 * One block per component, usually three (two horizontals, then "Up"):
 *     16 text lines  line 1 "Corrected accelerogram ... GNS Science" (V2A) or
 *                    "Uncorrected accelerogram ..." (V1A); line 2 "Site WTMC
 *                    ..."; line 7 the place, line 8 the origin time, line 10
 *                    "Number of points  8192", line 11 "... at 0.020 sec
 *                    intervals", line 12 the filter, line 13 "Component N28W"
 *     40 integers    10I8 on 4 lines
 *     60 reals       10F8 on 6 lines
 *     acceleration   npts values, F8 at 10 a line (the last line short), mm/s^2
 *     V2A only:      velocity (integer #35 values, mm/s) and displacement
 *                    (integer #36 values, mm), same layout, skipped here.
 * Header positions used (1-based): integers #9 #10 #19 #20 #39 #40 the
 * record start (year, month, day, hour, minute, milliseconds); #28 the
 * component azimuth; #31 npts (V1A), #34 npts of acceleration (V2A); real
 * #26 the data interval dt (real #25 is the instrument period, not dt).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "fixed.h"
#include "reader.h"
#include "number.h"

#define GEONET_TEXT_LINES 16
#define GEONET_INTS 40
#define GEONET_REALS 60
#define GEONET_PER_LINE 10
#define GEONET_WIDTH 8
#define GEONET_DT_REL_TOL 1e-3 /* real #26 against text line 11's 3-decimal dt */

/* Which 1-based header words the block uses. */
enum {
  GI_YEAR = 9, GI_MONTH = 10, GI_DAY = 19, GI_HOUR = 20, GI_AZIMUTH = 28,
  GI_NPTS_V1 = 31, GI_NPTS_ACC = 34, GI_NPTS_VEL = 35, GI_NPTS_DIS = 36,
  GI_MINUTE = 39, GI_MSEC = 40, GR_DT = 26
};

static int geonet_starts(const aq_line *ln)
{
  return aq_find_ci(ln->p, ln->len, "accelerogram") != NULL;
}

/* The number after `key` in line ln (blanks skipped); 1 if found. */
static int number_after(const aq_line *ln, const char *key, double *x)
{
  const char *k = aq_find_ci(ln->p, ln->len, key);
  if (!k)
    return 0;
  const char *p = k + strlen(key), *end = ln->p + ln->len;
  return aq_decimal_parse(p, (size_t)(end - p), x) > 0;
}

/* Skip count values laid out 10 a line (velocity or displacement). */
static aq_status skip_series(aq_lines *c, double count, const char *name, const char *what,
                             aq_error *err)
{
  double lines = ceil(count / GEONET_PER_LINE);
  for (double i = 0; i < lines; i++) {
    aq_line ln;
    if (!aq_lines_next(c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, what,
                          "expected %g lines of %g values, the file ends after %g", lines,
                          count, i);
  }
  return AQ_OK;
}

static aq_status geonet_block(aq_lines *c, const aq_line *first, const char *name,
                              aq_raw_file *raw, aq_error *err)
{
  aq_line text[GEONET_TEXT_LINES];
  text[0] = *first;
  for (int i = 1; i < GEONET_TEXT_LINES; i++)
    if (!aq_lines_next(c, &text[i]))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "text header",
                          "expected %d text lines, the file ends after %d",
                          GEONET_TEXT_LINES, i);
  int v1 = aq_find_ci(first->p, first->len, "uncorrected") != NULL;
  double iv[GEONET_INTS], rv[GEONET_REALS];
  aq_fortran_fmt fi = {GEONET_PER_LINE, GEONET_WIDTH, 'I'};
  aq_fortran_fmt fr = {GEONET_PER_LINE, GEONET_WIDTH, 'F'};
  long int_line = c->line;
  aq_status s = aq_fixed_read(c, GEONET_INTS, &fi, iv, name, "integer header (10I8)", err);
  if (s != AQ_OK)
    return s;
  long real_line = c->line;
  s = aq_fixed_read(c, GEONET_REALS, &fr, rv, name, "real header (10F8)", err);
  if (s != AQ_OK)
    return s;
  /* the line of 1-based header word k, 10 to a line */
#define WORD_LINE(base, k) ((base) + ((k) - 1) / GEONET_PER_LINE)

  int npts_word = v1 ? GI_NPTS_V1 : GI_NPTS_ACC;
  double npts = iv[npts_word - 1];
  size_t left = c->n - c->pos;
  if (!(npts >= 1) || npts > (double)left / GEONET_WIDTH + 1) {
    char field[48];
    snprintf(field, sizeof field, "integer header #%d (npts)", npts_word);
    return aq_error_set(err, AQ_EFORMAT, name, WORD_LINE(int_line, npts_word), -1, field,
                        "expected 1 to the %zu values the %zu bytes left can hold, got %g",
                        left / GEONET_WIDTH + 1, left, npts);
  }
  double stated;
  if (!v1 && number_after(&text[9], "Number of points", &stated) && stated != npts)
    return aq_error_set(err, AQ_EFORMAT, name, text[9].line, -1, "Number of points",
                        "expected %g as integer header #%d states, got %g", npts,
                        GI_NPTS_ACC, stated);
  double dt = rv[GR_DT - 1];
  if (!(dt > 0))
    return aq_error_set(err, AQ_EFORMAT, name, WORD_LINE(real_line, GR_DT), -1,
                        "real header #26 (dt)", "expected a sample interval > 0 s, got %g",
                        dt);
  if (number_after(&text[10], " at ", &stated) &&
      fabs(stated - dt) > GEONET_DT_REL_TOL * dt)
    return aq_error_set(err, AQ_EFORMAT, name, WORD_LINE(real_line, GR_DT), -1,
                        "real header #26 (dt)",
                        "expected the interval of text line %ld (%g s), got %g s",
                        text[10].line, stated, dt);

  aq_raw_channel *ch = aq_raw_add_channel(raw, name, err);
  if (!ch)
    return AQ_ENOMEM;
  ch->npts = (size_t)npts;
  ch->dt_s = dt;
  ch->values = malloc(ch->npts * sizeof *ch->values);
  if (!ch->values)
    return aq_error_set(err, AQ_ENOMEM, name, c->line, -1, "data", "out of memory");
  char what[64];
  snprintf(what, sizeof what, "acceleration of component %zu (10F8)", raw->nchan);
  aq_line last;
  s = aq_fixed_read_last(c, ch->npts, &fr, ch->values, name, what, &last, err);
  if (s != AQ_OK)
    return s;
  if (v1) { /* rows past the count, before the next component's text: reported
               for the decision (record.c); in a V2A the velocity follows at
               once, so there the counts alone divide the series */
    aq_extra_rows x;
    aq_extra_rows_scan(c, &last, aq_fixed_row, &fr, &x);
    aq_raw_set_extra(ch, &x, 1, "integer header #31");
  }
  if (!v1) {
    double nvel = iv[GI_NPTS_VEL - 1], ndis = iv[GI_NPTS_DIS - 1];
    if (!(nvel >= 0) || !(ndis >= 0) || nvel > (double)left || ndis > (double)left)
      return aq_error_set(err, AQ_EFORMAT, name, WORD_LINE(int_line, GI_NPTS_VEL), -1,
                          "integer header #35/#36 (velocity, displacement points)",
                          "expected counts >= 0 the file can hold, got %g and %g", nvel,
                          ndis);
    snprintf(what, sizeof what, "velocity of component %zu", raw->nchan);
    if ((s = skip_series(c, nvel, name, what, err)) != AQ_OK)
      return s;
    snprintf(what, sizeof what, "displacement of component %zu", raw->nchan);
    if ((s = skip_series(c, ndis, name, what, err)) != AQ_OK)
      return s;
  }
#undef WORD_LINE

  snprintf(ch->units, sizeof ch->units, "mm/s2");
  snprintf(ch->network, sizeof ch->network, "NZ");
  const char *p = text[1].p, *end = text[1].p + text[1].len;
  size_t w = aq_next_word(&p, end, "");
  if (w == 4 && strncmp(p, "Site", 4) == 0) {
    p += w;
    w = aq_next_word(&p, end, "");
    aq_copy_trim(ch->station, sizeof ch->station, p, w);
  }
  p = text[12].p;
  end = text[12].p + text[12].len;
  w = aq_next_word(&p, end, "");
  if (w == 9 && strncmp(p, "Component", 9) == 0) {
    p += w;
    w = aq_next_word(&p, end, "");
    aq_copy_trim(ch->channel, sizeof ch->channel, p, w);
  }
  int up = strcmp(ch->channel, "Up") == 0, down = strcmp(ch->channel, "Down") == 0;
  double az = iv[GI_AZIMUTH - 1];
  if (up || down) {
    ch->vertical = 1;
    ch->dip_deg = up ? -90.0 : 90.0;
  } else if (ch->channel[0]) {
    ch->vertical = 0;
    ch->dip_deg = 0.0;
    if (az >= 0 && az <= 360)
      ch->azimuth_deg = az;
  }
  if (!aq_iso_time(ch->reference, sizeof ch->reference, aq_header_int(iv[GI_YEAR - 1]),
                   aq_header_int(iv[GI_MONTH - 1]), aq_header_int(iv[GI_DAY - 1]),
                   aq_header_int(iv[GI_HOUR - 1]), aq_header_int(iv[GI_MINUTE - 1]),
                   iv[GI_MSEC - 1] * 1e-3))
    ch->reference[0] = '\0';
  if (raw->nchan == 1) {
    char when[44], where[44];
    aq_copy_trim(when, sizeof when, text[7].p, text[7].len);
    aq_copy_trim(where, sizeof where, text[6].p, text[6].len);
    snprintf(raw->event, sizeof raw->event, "%s, %s", when, where);
    snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
    char kind[24], corr[64], filt[64];
    snprintf(kind, sizeof kind, "%s", v1 ? "V1A uncorrected" : "V2A corrected");
    aq_copy_trim(corr, sizeof corr, text[10].p, text[10].len);
    aq_copy_trim(filt, sizeof filt, text[11].p, text[11].len);
    snprintf(raw->processing, sizeof raw->processing, "%s; %s; %s", kind, corr, filt);
  }
  return AQ_OK;
}

aq_status aq_geonet_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts; /* a GeoNet file states everything it can */
  return aq_raw_parse_channels(buf, n, name, "geonet", geonet_starts,
                            "\"Corrected accelerogram\" or \"Uncorrected accelerogram\"",
                            geonet_block, raw, err);
}
