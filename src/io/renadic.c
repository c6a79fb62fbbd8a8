/* renadic.c: RENADIC (Universidad de Chile) V1 text (reader.h).
 *
 * The layout borrows CSMIP V1's headers but not its data.  Per channel:
 *   13 text lines, the first naming an (UN)CORRECTED ACCELEROGRAM; among them
 *     "CHAN  1: EW       (STA CHN:  1)"          the channel's name
 *     "NO. OF POINTS =   7000  RECORD LENGTH = 70.000 SEC"
 *     "UNITS OF UNCOR ACCEL ARE SEC AND G/10.    MAX  = -0.030 G, AT  23.180 SEC"
 *     line 3 "02/27/2010 2:45:26 (GMT)  (ORIGIN: ...)"   the clock of time 0
 *   100 integers (16I5, 7 lines), 50 reals (8F10.3, 7 lines);
 *   NO. OF POINTS (time, value) pairs, 5 pairs to a line in 10F7.3;
 *   "/&  ----------  END OF DATA FOR CHANNEL 1  ----------".
 * There is no dt field: dt is the step of the time column, which must be
 * even (RENADIC_TIME_TOL_S) or the channel is refused.  The channel names are
 * "EW", "NZ", "Z": no azimuth is stated (NAN); "Z" is stated vertical, dip
 * not stated.  Units "SEC AND G/10" are reported as "g/10".
 * The header clock is reported as stated (line 3, with begin_s the first
 * time of the column), though it is not trustworthy: in the one known file
 * the TRIGGER TIME (line 4) is 20 s after line 3, the header MAX times count
 * from the trigger, and neither agrees with the earthquake's origin time
 * (docs/agency-formats.md).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define RENADIC_TEXT_LINES 13
#define RENADIC_INTS 100
#define RENADIC_REALS 50
#define RENADIC_INT_LINES 7
#define RENADIC_REAL_LINES 7
#define RENADIC_PAIRS_PER_LINE 5
#define RENADIC_FIELD_WIDTH 7 /* F7.3 */
#define RENADIC_NPTS_MAX 100000000L
/* Times are printed to 0.001 s (F7.3): each is within 0.0005 s of its true
 * time, and the line through the first and last times within another
 * 0.0005 s; a time farther than this from t0 + k dt is uneven sampling. */
#define RENADIC_TIME_TOL_S 0.001

static const aq_fortran_fmt pair_fmt = {2 * RENADIC_PAIRS_PER_LINE, RENADIC_FIELD_WIDTH, 'F'};

/* The value of field j (0-based, F7) of ln, or 0 if absent or not a number. */
static int pair_field(const aq_line *ln, size_t j, double *out)
{
  size_t b = j * RENADIC_FIELD_WIDTH;
  if (b + RENADIC_FIELD_WIDTH > ln->len)
    return 0;
  return aq_field_double(ln->p + b, RENADIC_FIELD_WIDTH, out);
}

int aq_renadic_sniff(const unsigned char *buf, size_t n)
{
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  if (!aq_lines_next(&c, &ln) || !aq_find_ci(ln.p, ln.len, "ACCELEROGRAM"))
    return 0;
  for (int i = 1; i < RENADIC_TEXT_LINES + RENADIC_INT_LINES + RENADIC_REAL_LINES; i++)
    if (!aq_lines_next(&c, &ln))
      return 0;
  /* the first two data lines: six times in even steps */
  double t[RENADIC_PAIRS_PER_LINE + 1];
  if (!aq_lines_next(&c, &ln))
    return 0;
  for (size_t j = 0; j < RENADIC_PAIRS_PER_LINE; j++)
    if (!pair_field(&ln, 2 * j, &t[j]))
      return 0;
  if (!aq_lines_next(&c, &ln) || !pair_field(&ln, 0, &t[RENADIC_PAIRS_PER_LINE]))
    return 0;
  double step = t[1] - t[0];
  if (!(step > RENADIC_TIME_TOL_S))
    return 0;
  for (size_t j = 2; j <= RENADIC_PAIRS_PER_LINE; j++)
    if (fabs(t[j] - t[j - 1] - step) > RENADIC_TIME_TOL_S)
      return 0;
  return 1;
}

/* "NO. OF POINTS =   7000": the count, or -1. */
static long points_stated(const aq_line *ln)
{
  const char *p = aq_find_ci(ln->p, ln->len, "NO. OF POINTS");
  if (!p)
    return -1;
  const char *end = ln->p + ln->len;
  p += strlen("NO. OF POINTS");
  while (p < end && (*p == ' ' || *p == '='))
    p++;
  long v = 0;
  const char *b = p;
  for (; p < end && *p >= '0' && *p <= '9'; p++) {
    if (v > RENADIC_NPTS_MAX)
      return -1;
    v = v * 10 + (*p - '0');
  }
  if (p == b || (p < end && *p != ' '))
    return -1;
  return v;
}

/* "CHAN  1: EW  (STA CHN:  1)": the name; "Z" is vertical. */
static void channel_line(const aq_line *ln, aq_raw_channel *ch)
{
  const char *end = ln->p + ln->len;
  const char *p = memchr(ln->p, ':', ln->len);
  if (!p)
    return;
  p++;
  size_t len = aq_next_word(&p, end, "(");
  aq_copy_trim(ch->channel, sizeof ch->channel, p, len);
  if (len == 1 && (*p == 'Z' || *p == 'z'))
    ch->vertical = 1;
}

/* "UNITS OF UNCOR ACCEL ARE SEC AND G/10.": "g/10" or "g"; otherwise the
 * words are kept for messages (units_said) and no units are stated. */
static void units_line(const aq_line *ln, aq_raw_channel *ch)
{
  const char *p = aq_find_ci(ln->p, ln->len, "SEC AND ");
  if (!p) {
    aq_copy_trim(ch->units_said, sizeof ch->units_said, ln->p, ln->len);
    ch->units_line = ln->line;
    return;
  }
  p += strlen("SEC AND ");
  const char *end = ln->p + ln->len;
  size_t len = aq_next_word(&p, end, "");
  while (len > 0 && p[len - 1] == '.')
    len--;
  if (len == 4 && aq_find_ci(p, len, "G/10") == p)
    snprintf(ch->units, sizeof ch->units, "g/10");
  else if (len == 1 && (*p == 'G' || *p == 'g'))
    snprintf(ch->units, sizeof ch->units, "g");
  else {
    aq_copy_trim(ch->units_said, sizeof ch->units_said, ln->p, ln->len);
    ch->units_line = ln->line;
  }
}

/* Line 3 "02/27/2010 2:45:26 (GMT)": ISO UTC into out, or "". */
static void start_time(const aq_line *ln, char *out, size_t cap)
{
  char tmp[96], zone[8];
  int mo, d, y, h, mi, east;
  double s;
  out[0] = '\0';
  aq_copy_trim(tmp, sizeof tmp, ln->p, ln->len);
  if (sscanf(tmp, "%d/%d/%d %d:%d:%lf (%7[A-Za-z])", &mo, &d, &y, &h, &mi, &s, zone) != 7 ||
      !aq_zone_offset(zone, strlen(zone), &east))
    return;
  if (!aq_iso_time_local(out, cap, y, mo, d, h, mi, s, east))
    out[0] = '\0';
}

/* Check that the time column t[0..npts) is even, set dt; data_line is the
 * line of the first pair. */
static aq_status even_times(const double *t, size_t npts, long data_line, const char *name,
                            double *dt_s, aq_error *err)
{
  if (npts < 2)
    return aq_error_set(err, AQ_EFORMAT, name, data_line, -1, "NO. OF POINTS",
                        "expected at least 2 points (dt is the step of the time column), "
                        "got %zu",
                        npts);
  double dt = (t[npts - 1] - t[0]) / (double)(npts - 1);
  if (!(dt > RENADIC_TIME_TOL_S) || !isfinite(dt))
    return aq_error_set(err, AQ_EFORMAT, name, data_line, -1, "time column",
                        "expected times increasing by more than %g s, got %g s to %g s "
                        "over %zu points",
                        RENADIC_TIME_TOL_S, t[0], t[npts - 1], npts);
  for (size_t k = 1; k < npts; k++) {
    double want = t[0] + (double)k * dt;
    if (fabs(t[k] - want) > RENADIC_TIME_TOL_S)
      return aq_error_set(err, AQ_EFORMAT, name,
                          data_line + (long)(k / RENADIC_PAIRS_PER_LINE), -1, "time column",
                          "expected even sampling, time of point %zu = %.3f s "
                          "(t0 %.3f s + %zu x dt %.6f s, within %g s), got %.3f s",
                          k + 1, want, t[0], k, dt, RENADIC_TIME_TOL_S, t[k]);
  }
  *dt_s = dt;
  return AQ_OK;
}

static aq_status parse_channel(aq_lines *c, const aq_line *first, const char *name,
                               aq_raw_file *raw, aq_error *err)
{
  aq_line hdr[RENADIC_TEXT_LINES];
  hdr[0] = *first;
  for (int i = 1; i < RENADIC_TEXT_LINES; i++)
    if (!aq_lines_next(c, &hdr[i]))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "text header",
                          "expected %d text lines, the file ends after %d",
                          RENADIC_TEXT_LINES, i);
  aq_raw_channel tmp;
  aq_raw_channel_init(&tmp);
  long npts = -1;
  for (int i = 1; i < RENADIC_TEXT_LINES; i++) {
    const aq_line *h = &hdr[i];
    const char *p = h->p, *end = h->p + h->len;
    while (p < end && *p == ' ')
      p++;
    if (!tmp.channel[0] && aq_find_ci(p, (size_t)(end - p), "CHAN") == p)
      channel_line(h, &tmp);
    if (npts < 0 && aq_find_ci(h->p, h->len, "NO. OF POINTS")) {
      npts = points_stated(h);
      if (npts < 1) {
        char got[96];
        aq_copy_trim(got, sizeof got, h->p, h->len);
        return aq_error_set(err, AQ_EFORMAT, name, h->line, -1, "NO. OF POINTS",
                            "expected a positive integer, got \"%s\"", got);
      }
    }
    if (!tmp.units[0] && !tmp.units_said[0] && aq_find_ci(h->p, h->len, "UNITS OF"))
      units_line(h, &tmp);
    const char *sn = aq_find_ci(h->p, h->len, "STATION NO.");
    const char *ser = sn ? aq_find_ci(sn, (size_t)(end - sn), "S/N") : NULL;
    if (ser && !tmp.station[0]) {
      ser += 3;
      size_t len = aq_next_word(&ser, end, "(");
      aq_copy_trim(tmp.station, sizeof tmp.station, ser, len);
    }
  }
  if (npts < 0)
    return aq_error_set(err, AQ_EFORMAT, name, first->line, -1, "NO. OF POINTS",
                        "expected \"NO. OF POINTS = N\" in the %d text lines of the channel",
                        RENADIC_TEXT_LINES);
  start_time(&hdr[2], tmp.reference, sizeof tmp.reference);
  /* the numeric headers, by column width, to know the file is whole */
  {
    double iv[RENADIC_INTS], rv[RENADIC_REALS];
    aq_fortran_fmt fi = {16, 5, 'I'}, fr = {8, 10, 'F'};
    aq_status s = aq_fixed_read(c, RENADIC_INTS, &fi, iv, name, "integer header (16I5)", err);
    if (s == AQ_OK)
      s = aq_fixed_read(c, RENADIC_REALS, &fr, rv, name, "real header (8F10.3)", err);
    if (s != AQ_OK)
      return s;
  }
  size_t left = c->n - c->pos;
  if ((size_t)npts > left / (2 * RENADIC_FIELD_WIDTH) + 1)
    return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "NO. OF POINTS",
                        "%ld (time, value) pairs of %d columns cannot fit in the %zu bytes left",
                        npts, 2 * RENADIC_FIELD_WIDTH, left);
  tmp.npts = (size_t)npts;
  double *pairs = malloc(2 * tmp.npts * sizeof *pairs);
  double *t = malloc(tmp.npts * sizeof *t);
  tmp.values = malloc(tmp.npts * sizeof *tmp.values);
  aq_status s = AQ_OK;
  if (!pairs || !t || !tmp.values)
    s = aq_error_set(err, AQ_ENOMEM, name, c->line, -1, "data", "out of memory");
  long data_line = c->line;
  if (s == AQ_OK) {
    char what[64];
    aq_line last;
    snprintf(what, sizeof what, "(time, value) pairs of channel %zu", raw->nchan + 1);
    s = aq_fixed_read_last(c, 2 * tmp.npts, &pair_fmt, pairs, name, what, &last, err);
    if (s == AQ_OK) { /* pairs past NO. OF POINTS: reported for the decision (record.c) */
      aq_extra_rows x;
      aq_extra_rows_scan(c, &last, aq_fixed_row, &pair_fmt, &x);
      aq_raw_set_extra(&tmp, &x, 2, "NO. OF POINTS");
    }
  }
  if (s == AQ_OK) {
    for (size_t k = 0; k < tmp.npts; k++) {
      t[k] = pairs[2 * k];
      tmp.values[k] = pairs[2 * k + 1];
    }
    s = even_times(t, tmp.npts, data_line, name, &tmp.dt_s, err);
    tmp.begin_s = t[0];
  }
  free(pairs);
  free(t);
  if (s == AQ_OK) { /* the end line */
    aq_line ln;
    int got_line;
    while ((got_line = aq_lines_next(c, &ln)) && aq_line_blank(&ln))
      ;
    if (!got_line || ln.len < 2 || ln.p[0] != '/' || ln.p[1] != '&' ||
        !aq_find_ci(ln.p, ln.len, "END OF DATA")) {
      char got[64];
      if (got_line)
        aq_copy_trim(got, sizeof got, ln.p, ln.len);
      s = aq_error_set(err, AQ_EFORMAT, name, got_line ? ln.line : c->line, -1, "end of data",
                       "expected \"/&  ----------  END OF DATA FOR CHANNEL %zu\" after %ld "
                       "pairs, got %s%s%s",
                       raw->nchan + 1, npts, got_line ? "\"" : "the end of the file",
                       got_line ? got : "", got_line ? "\"" : "");
    }
  }
  if (s != AQ_OK) {
    free(tmp.values);
    return s;
  }
  if (raw->nchan == 0) {
    aq_copy_trim(raw->processing, sizeof raw->processing, first->p, first->len);
    aq_copy_trim(raw->event, sizeof raw->event, hdr[1].p, hdr[1].len);
    snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  }
  return aq_raw_append_channel(raw, &tmp, name, err);
}

aq_status aq_renadic_parse(const unsigned char *buf, size_t n, const char *name,
                           const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  return aq_raw_parse_channels(buf, n, name, "renadic", aq_line_names_accelerogram,
                            "a channel header naming an UNCORRECTED ACCELEROGRAM",
                            parse_channel, raw, err);
}
