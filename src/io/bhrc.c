/* bhrc.c: BHRC (Road, Housing and Urban Development Research Center, Iran)
 * VOL1DS text (reader.h).
 *
 * One block per channel, usually three (L, V, T):
 *   13 text lines: 1 "* VOL1DS FILE:  5522/01" (station 5522, record 01),
 *     3 "Origin Time : 2012/08/11   12:23:16" (the event, not the record),
 *     5 the component letter, 7 "COMP L1" (the channel's name),
 *     8 "... Azimuth L 324   T 54" (azimuths of L and T),
 *     11 "NO. OF POINTS =   9984      DURATION =  49.920",
 *     12 "UNITS ARE SECONDS AND G/10";
 *   7 lines of integers in 14I5 (integer #26 the npts again);
 *   7 lines of reals in 6E13.6, cut at column 70 so that the sixth field of
 *     each line is truncated ("  .00"): only whole fields are read; the
 *     first value of the second line (real #7) is samples per second;
 *   npts values, 10 a line in E13.6 (130 columns, "  .156689E-02");
 *   "/&".
 * dt is 1 / real #7; DURATION must equal npts * dt (BHRC_DT_REL): gmprocess
 * takes DURATION / (npts - 1), 1e-4 too large.  The file states no start
 * time: the reference is left unknown.  V (vertical) is stated vertical
 * without a dip; L and T are horizontal with their azimuths.
 * VOL2DS and other volumes are refused, naming what the file says.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define BHRC_TEXT_LINES 13
#define BHRC_INT_LINES 7
#define BHRC_REAL_LINES 7
#define BHRC_INT_WIDTH 5
#define BHRC_REAL_WIDTH 13
#define BHRC_INTS_MAX 16   /* fields looked at on an integer line */
#define BHRC_REALS_MAX 6   /* fields on a real line (the sixth cut) */
#define BHRC_NPTS_INT 26   /* integer #26: npts */
#define BHRC_RATE_REAL 7   /* real #7: samples per second */
#define BHRC_PER_LINE 10   /* data: 10E13.6 */
/* DURATION is printed to 0.001 s: npts * dt must agree with it to that. */
#define BHRC_DURATION_TOL_S 0.0015

static const char bhrc_marker[] = "* VOL";

int aq_bhrc_sniff(const unsigned char *buf, size_t n)
{
  const char *s = (const char *)buf;
  return n >= 16 && memcmp(s, bhrc_marker, strlen(bhrc_marker)) == 0 &&
         aq_find_ci(s, n < 24 ? n : 24, "DS FILE") != NULL;
}

static int starts_block(const aq_line *ln)
{
  return ln->len >= strlen(bhrc_marker) && memcmp(ln->p, bhrc_marker, strlen(bhrc_marker)) == 0;
}

/* The whole fields of width w on the next line of c into out[max] (a blank
 * field at the end of the line ends it); the count in *got.  A field that is
 * neither blank nor a number is an error naming the line and field. */
static aq_status header_line(aq_lines *c, size_t w, double *out, size_t max, size_t *got,
                             const char *name, const char *what, aq_error *err)
{
  aq_line ln;
  *got = 0;
  if (!aq_lines_next(c, &ln))
    return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, what,
                        "expected a header line, the file ends");
  for (size_t j = 0; j < max && (j + 1) * w <= ln.len; j++) {
    const char *f = ln.p + j * w;
    int blank = 1;
    for (size_t i = 0; i < w && blank; i++)
      blank = f[i] == ' ';
    if (blank)
      break;
    if (!aq_field_double(f, w, &out[j])) {
      char got_s[BHRC_REAL_WIDTH + 1];
      aq_copy_trim(got_s, sizeof got_s, f, w);
      return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, what,
                          "field %zu (columns %zu-%zu): expected a number, got \"%s\"", j + 1,
                          j * w + 1, (j + 1) * w, got_s);
    }
    *got = j + 1;
  }
  return AQ_OK;
}

/* The number after "key =" in ln, or 0. */
static int keyed_number(const aq_line *ln, const char *key, double *out)
{
  const char *k = aq_find_ci(ln->p, ln->len, key);
  if (!k)
    return 0;
  const char *p = k + strlen(key), *end = ln->p + ln->len;
  while (p < end && (*p == ' ' || *p == '='))
    p++;
  const char *b = p;
  while (p < end && *p != ' ')
    p++;
  return aq_field_double(b, (size_t)(p - b), out);
}

static aq_status parse_block(aq_lines *c, const aq_line *first, const char *name,
                             aq_raw_file *raw, aq_error *err)
{
  aq_line text[BHRC_TEXT_LINES];
  text[0] = *first;
  if (aq_find_ci(first->p, first->len, "VOL1DS") != first->p + 2) {
    char got[48];
    aq_copy_trim(got, sizeof got, first->p, first->len);
    return aq_error_set(err, AQ_EUNSUPPORTED, name, first->line, -1, "format",
                        "BHRC (Iran) \"%s\": only VOL1DS (uncorrected acceleration) is "
                        "supported",
                        got);
  }
  for (int i = 1; i < BHRC_TEXT_LINES; i++)
    if (!aq_lines_next(c, &text[i]))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "text header",
                          "expected %d text lines of the BHRC VOL1DS block, the file ends "
                          "after %d",
                          BHRC_TEXT_LINES, i);
  double iv[BHRC_INTS_MAX * BHRC_INT_LINES], rv[BHRC_REALS_MAX * BHRC_REAL_LINES];
  size_t nint = 0, nreal = 0, got;
  memset(iv, 0, sizeof iv);
  memset(rv, 0, sizeof rv);
  for (int i = 0; i < BHRC_INT_LINES; i++) {
    double row[BHRC_INTS_MAX];
    aq_status s = header_line(c, BHRC_INT_WIDTH, row, BHRC_INTS_MAX, &got, name,
                              "integer header (14I5)", err);
    if (s != AQ_OK)
      return s;
    memcpy(iv + nint, row, got * sizeof *row);
    nint += got;
  }
  long real_line = c->line;
  for (int i = 0; i < BHRC_REAL_LINES; i++) {
    double row[BHRC_REALS_MAX];
    aq_status s = header_line(c, BHRC_REAL_WIDTH, row, BHRC_REALS_MAX, &got, name,
                              "real header (6E13.6)", err);
    if (s != AQ_OK)
      return s;
    for (size_t j = 0; j < BHRC_REALS_MAX; j++) /* by position: 6 to a line */
      rv[(size_t)i * BHRC_REALS_MAX + j] = j < got ? row[j] : NAN;
    nreal += BHRC_REALS_MAX;
  }
  (void)nreal;

  /* npts: text line 11, and integer #26 when it is there */
  double npts_text = 0, duration_s = NAN;
  const aq_line *pts = &text[10];
  if (!keyed_number(pts, "NO. OF POINTS", &npts_text) || !(npts_text >= 1) ||
      npts_text != floor(npts_text)) {
    char got_s[72];
    aq_copy_trim(got_s, sizeof got_s, pts->p, pts->len);
    return aq_error_set(err, AQ_EFORMAT, name, pts->line, -1, "NO. OF POINTS",
                        "expected \"NO. OF POINTS = N\" with N >= 1, got \"%s\"", got_s);
  }
  if (!keyed_number(pts, "DURATION", &duration_s))
    duration_s = NAN;
  if (nint >= BHRC_NPTS_INT && iv[BHRC_NPTS_INT - 1] != npts_text)
    return aq_error_set(err, AQ_EFORMAT, name, real_line - BHRC_INT_LINES + 1, -1,
                        "integer header #26 (npts)",
                        "expected %.0f as text line 11 states, got %g", npts_text,
                        iv[BHRC_NPTS_INT - 1]);
  double rate = rv[BHRC_RATE_REAL - 1];
  if (!(rate > 0) || !isfinite(1.0 / rate))
    return aq_error_set(err, AQ_EFORMAT, name, real_line + 1, -1,
                        "real header #7 (samples per second)", "expected > 0, got %g", rate);
  double dt_s = 1.0 / rate;
  if (isfinite(duration_s) && fabs(npts_text * dt_s - duration_s) > BHRC_DURATION_TOL_S)
    return aq_error_set(err, AQ_EFORMAT, name, pts->line, -1, "DURATION",
                        "expected NO. OF POINTS x dt = %.0f x %g s = %.3f s (dt from real "
                        "header #7, %g samples/s), got %.3f s",
                        npts_text, dt_s, npts_text * dt_s, rate, duration_s);
  if (npts_text > (double)(c->n - c->pos) / BHRC_REAL_WIDTH + 1)
    return aq_error_set(err, AQ_EFORMAT, name, pts->line, -1, "NO. OF POINTS",
                        "%.0f values of 13 columns cannot fit in the %zu bytes left",
                        npts_text, c->n - c->pos);

  aq_raw_channel tmp;
  aq_raw_channel_init(&tmp);
  tmp.npts = (size_t)npts_text;
  tmp.dt_s = dt_s;
  /* units: "UNITS ARE SECONDS AND G/10" */
  const aq_line *ul = &text[11];
  const char *and = aq_find_ci(ul->p, ul->len, " AND ");
  if (and) {
    const char *b = and + 5;
    size_t len = aq_next_word(&b, ul->p + ul->len, "");
    char word[24];
    aq_copy_trim(word, sizeof word, b, len);
    if (strcmp(word, "G/10") == 0 || strcmp(word, "g/10") == 0)
      snprintf(tmp.units, sizeof tmp.units, "g/10");
    else if (strcmp(word, "G") == 0 || strcmp(word, "g") == 0)
      snprintf(tmp.units, sizeof tmp.units, "g");
  }
  if (!tmp.units[0]) {
    char said[56];
    aq_copy_trim(said, sizeof said, ul->p, ul->len);
    snprintf(tmp.units_said, sizeof tmp.units_said, "line %ld: %s", ul->line, said);
  }
  /* channel: "COMP L1"; its letter says which axis */
  const char *cp = aq_find_ci(text[6].p, text[6].len, "COMP");
  if (cp) {
    cp += 4;
    size_t len = aq_next_word(&cp, text[6].p + text[6].len, "");
    aq_copy_trim(tmp.channel, sizeof tmp.channel, cp, len);
  }
  char axis = tmp.channel[0];
  if (axis == 'V' || axis == 'v') {
    tmp.vertical = 1;
  } else if (axis == 'L' || axis == 'T' || axis == 'l' || axis == 't') {
    tmp.vertical = 0;
    tmp.dip_deg = 0;
    const char *p = aq_find_ci(text[7].p, text[7].len, "Azimuth");
    const char *end = text[7].p + text[7].len;
    for (p = p ? p + 7 : end; p < end;) { /* "Azimuth L 324   T 54": letter, degrees */
      size_t len = aq_next_word(&p, end, "");
      const char *v = p + len;
      size_t vlen = aq_next_word(&v, end, "");
      double deg;
      if (len == 0 || vlen == 0)
        break;
      if (len == 1 && (p[0] | 0x20) == (axis | 0x20) && aq_field_double(v, vlen, &deg) &&
          deg >= 0 && deg <= 360) {
        tmp.azimuth_deg = deg;
        break;
      }
      p = v + vlen;
    }
  }
  /* station: "* VOL1DS FILE:  5522/01" */
  const char *fl = aq_find_ci(first->p, first->len, "FILE:");
  if (fl) {
    fl += 5;
    size_t len = aq_next_word(&fl, first->p + first->len, "/");
    aq_copy_trim(tmp.station, sizeof tmp.station, fl, len);
  }
  tmp.values = malloc(tmp.npts * sizeof *tmp.values);
  if (!tmp.values)
    return aq_error_set(err, AQ_ENOMEM, name, pts->line, -1, "data", "out of memory");
  char what[48];
  snprintf(what, sizeof what, "data of channel %zu (10E13.6)", raw->nchan + 1);
  aq_fortran_fmt fd = {BHRC_PER_LINE, BHRC_REAL_WIDTH, 'E'};
  aq_line ln;
  aq_status s = aq_fixed_read_last(c, tmp.npts, &fd, tmp.values, name, what, &ln, err);
  if (s == AQ_OK) { /* rows past NO. OF POINTS: reported for the decision (record.c) */
    aq_extra_rows x;
    aq_extra_rows_scan(c, &ln, aq_fixed_row, &fd, &x);
    aq_raw_set_extra(&tmp, &x, 1, "NO. OF POINTS");
  }
  while (s == AQ_OK) { /* the block ends with "/&" */
    if (!aq_lines_next(c, &ln)) {
      s = aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "end of block",
                       "expected \"/&\" after the %zu values of channel %zu, the file ends",
                       tmp.npts, raw->nchan + 1);
    } else if (!aq_line_blank(&ln)) {
      if (ln.len < 2 || ln.p[0] != '/' || ln.p[1] != '&') {
        char got_s[48];
        aq_copy_trim(got_s, sizeof got_s, ln.p, ln.len);
        s = aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "end of block",
                         "expected \"/&\" after the %zu values of channel %zu (NO. OF "
                         "POINTS), got \"%s\"",
                         tmp.npts, raw->nchan + 1, got_s);
      }
      break;
    }
  }
  if (s != AQ_OK) {
    free(tmp.values);
    return s;
  }
  if (raw->nchan == 0) {
    aq_copy_trim(raw->event, sizeof raw->event, text[2].p, text[2].len);
    snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
    snprintf(raw->processing, sizeof raw->processing, "BHRC VOL1DS (uncorrected)");
  }
  return aq_raw_append_channel(raw, &tmp, name, err);
}

aq_status aq_bhrc_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  return aq_raw_parse_channels(buf, n, name, "bhrc", starts_block,
                            "a BHRC block starting \"* VOL1DS FILE:\"", parse_block, raw, err);
}
