/* csmip.c: CSMIP (CGS / CDMG "DMG") V1 and V2 text (reader.h).
 *
 * Per channel: free-text header lines (13 in V1, 25 in V2); 100 integers in
 * 16I5 (7 lines); reals in 8F10 (50 on 7 lines in V1, 100 on 13 lines in
 * V2); then a data line that gives npts, dt and units:
 *   V1: "13200 Accelerogram points at 200 pts/sec in units of g . Format: (8f9.6)"
 *   V2: "3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)"
 * and the values by column width (V2 states no format: 8F10).  A V2 channel
 * then carries velocity and displacement, which are skipped: only the ACCEL
 * block is read.  Each channel ends with "/&  ---  End of Data for Channel N".
 * Channels may differ in length.  Fields touch (`5.0000000-999.00000`,
 * `50013200`); the file may end with DOS end-of-file bytes (0x1A).
 * The channel line is "Chan  1: 360 Deg" or "CHAN  2:  UP"; the start time
 * "Start time:  2/13/12, 21:06:45.0 UTC" (V1) or "TRIGGER TIME: 05/02/83,
 * 16:42:48.2 PDT" (V2), local zones converted to UTC.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define CSMIP_MAX_HEADER_LINES 80 /* the data line is looked for this far */
#define CSMIP_INTS 100
#define CSMIP_INT_LINES 7
#define CSMIP_V1_REALS 50
#define CSMIP_V2_REALS 100
#define CSMIP_V2_FIELDS 8  /* V2 data: 8F10 when no format is stated */
#define CSMIP_V2_WIDTH 10

static long leading_long(const char *p, const char *end)
{
  while (p < end && *p == ' ')
    p++;
  if (p >= end || !isdigit((unsigned char)*p))
    return -1;
  long v = 0;
  for (; p < end && isdigit((unsigned char)*p); p++) {
    if (v > 100000000L)
      return -1;
    v = v * 10 + (*p - '0');
  }
  return v;
}

/* The number that starts at p (after blanks), as long as it goes. */
static int number_at(const char *p, const char *end, double *out)
{
  while (p < end && *p == ' ')
    p++;
  const char *b = p;
  while (p < end && (isdigit((unsigned char)*p) || *p == '.'))
    p++;
  return aq_field_double(b, (size_t)(p - b), out);
}

/* "13200 Accelerogram points at 200 pts/sec in units of g" (1) or
 * "3251 POINTS OF ACCEL DATA EQUALLY SPACED AT .020 SEC. (UNITS: ...)" (2). */
static int data_line_kind(const aq_line *ln, int *qty)
{
  *qty = AQ_QUANTITY_ACCELERATION;
  if (leading_long(ln->p, ln->p + ln->len) < 1)
    return 0;
  if (aq_find_ci(ln->p, ln->len, "accelerogram points"))
    return 1;
  if (aq_find_ci(ln->p, ln->len, "points of accel data"))
    return 2;
  /* a channel whose first block is velocity or displacement: read as it is,
   * for the decision to refuse (record.c) */
  *qty = aq_find_ci(ln->p, ln->len, "points of veloc data")   ? AQ_QUANTITY_VELOCITY
         : aq_find_ci(ln->p, ln->len, "points of displ data") ? AQ_QUANTITY_DISPLACEMENT
                                                             : AQ_QUANTITY_UNSTATED;
  return *qty != AQ_QUANTITY_UNSTATED ? 2 : 0;
}

static void units_from(const char *b, const char *end, char *out, size_t cap)
{
  while (b < end && *b == ' ')
    b++;
  const char *p = b;
  while (p < end && *p != ' ' && *p != ')' && *p != ',')
    p++;
  size_t n = (size_t)(p - b);
  if (n > 1 && b[n - 1] == '.') /* "in cm/sec2." ends the sentence */
    n--;
  if (n == 1 && (*b == 'g' || *b == 'G'))
    snprintf(out, cap, "g");
  else if (aq_find_ci(b, n, "cm/sec/sec") || aq_find_ci(b, n, "cm/sec2"))
    snprintf(out, cap, "cm/s2");
  else
    aq_copy_trim(out, cap, b, n);
}

/* "[Start time:|TRIGGER TIME:] 5/02/83, 16:42:48.2 PDT" -> ISO UTC. */
static void start_time(const aq_line *ln, char *out, size_t cap)
{
  const char *p = aq_find_ci(ln->p, ln->len, "start time:");
  if (!p)
    p = aq_find_ci(ln->p, ln->len, "trigger time:");
  if (!p)
    return;
  p = memchr(p, ':', (size_t)(ln->p + ln->len - p)) + 1;
  int mo, d, y, h, mi, used = 0;
  double s;
  char zone[8], tmp[96];
  aq_copy_trim(tmp, sizeof tmp, p, (size_t)(ln->p + ln->len - p));
  if (sscanf(tmp, "%d/%d/%d, %d:%d:%lf %7s%n", &mo, &d, &y, &h, &mi, &s, zone, &used) < 7)
    return;
  int east;
  if (!aq_zone_offset(zone, strlen(zone), &east))
    return;
  if (y < 100)
    y += y < 50 ? 2000 : 1900;
  if (!aq_iso_time_local(out, cap, y, mo, d, h, mi, s, east))
    out[0] = '\0';
}

/* "Chan  1: 360 Deg" / "CHAN  2:  UP": name, azimuth or vertical. */
static void channel_line(const aq_line *ln, aq_raw_channel *ch)
{
  const char *end = ln->p + ln->len;
  const char *p = memchr(ln->p, ':', ln->len);
  if (!p)
    return;
  p++;
  size_t len = aq_next_word(&p, end, "");
  const char *b = p;
  p += len;
  aq_copy_trim(ch->channel, sizeof ch->channel, b, len);
  double az;
  if (aq_field_double(b, len, &az) && az >= 0 && az <= 360) {
    ch->azimuth_deg = az;
    ch->dip_deg = 0;
    ch->vertical = 0;
    snprintf(ch->orient_said, sizeof ch->orient_said, "line %ld: %.*s deg", ln->line, (int)len,
             b);
  } else if (aq_find_ci(b, (size_t)(p - b), "up")) {
    ch->dip_deg = -90;
    ch->vertical = 1;
  } else if (aq_find_ci(b, (size_t)(p - b), "down")) {
    ch->dip_deg = 90;
    ch->vertical = 1;
  }
}

static aq_status parse_channel(aq_lines *c, const aq_line *first, const char *name,
                               aq_raw_file *raw, aq_error *err)
{
  aq_line hdr[CSMIP_MAX_HEADER_LINES];
  size_t nh = 0;
  int kind = 0, qty = AQ_QUANTITY_UNSTATED;
  hdr[nh++] = *first;
  aq_lines hstart = *c; /* just after the first line */
  aq_line ln;
  while (!kind) {
    if (nh >= CSMIP_MAX_HEADER_LINES || !aq_lines_next(c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, first->line, -1, "data line",
                          "expected \"N Accelerogram points at R pts/sec\" or \"N POINTS "
                          "OF ACCEL DATA ...\" within %d lines of the channel start",
                          CSMIP_MAX_HEADER_LINES);
    kind = data_line_kind(&ln, &qty);
    if (!kind)
      hdr[nh++] = ln;
  }
  const aq_line data = ln;
  size_t nreal = kind == 1 ? CSMIP_V1_REALS : CSMIP_V2_REALS;
  size_t real_lines = (nreal + 7) / 8;
  if (nh < 1 + CSMIP_INT_LINES + real_lines)
    return aq_error_set(err, AQ_EFORMAT, name, data.line, -1, "header",
                        "expected text, %d integer and %zu real header lines before the "
                        "data line, got %zu lines",
                        CSMIP_INT_LINES, real_lines, nh);
  size_t ntext = nh - CSMIP_INT_LINES - real_lines;
  /* the numeric headers, by column width, to know the file is whole */
  {
    double iv[CSMIP_INTS], rv[CSMIP_V2_REALS];
    aq_fortran_fmt fi = {16, 5, 'I'}, fr = {8, 10, 'F'};
    aq_lines h = hstart;
    for (size_t i = 1; i < ntext; i++)
      aq_lines_next(&h, &ln);
    aq_status s = aq_fixed_read(&h, CSMIP_INTS, &fi, iv, name, "integer header (16I5)", err);
    if (s == AQ_OK)
      s = aq_fixed_read(&h, nreal, &fr, rv, name, "real header (8F10)", err);
    if (s != AQ_OK)
      return s;
  }
  aq_raw_channel tmp;
  aq_raw_channel_init(&tmp);
  {
    char said[72];
    aq_copy_trim(said, sizeof said, data.p, data.len);
    tmp.quantity = qty;
    snprintf(tmp.quantity_said, sizeof tmp.quantity_said, "line %ld: \"%.64s\"", data.line,
             said);
    snprintf(tmp.units_from, sizeof tmp.units_from, "line %ld (the data line)", data.line);
  }
  for (size_t i = 0; i < ntext; i++) {
    const char *p = hdr[i].p, *end = p + hdr[i].len;
    while (p < end && *p == ' ')
      p++;
    if (!tmp.channel[0] && aq_find_ci(p, (size_t)(end - p), "chan") == p)
      channel_line(&hdr[i], &tmp);
    const char *st = aq_find_ci(hdr[i].p, hdr[i].len, "station no.");
    if (!st) /* SCSN: "Station Id. WLT" */
      st = aq_find_ci(hdr[i].p, hdr[i].len, "station id.");
    if (st && !tmp.station[0]) {
      st += 11;
      size_t len = aq_next_word(&st, end, "");
      aq_copy_trim(tmp.station, sizeof tmp.station, st, len);
    }
    if (!tmp.reference[0])
      start_time(&hdr[i], tmp.reference, sizeof tmp.reference);
  }
  /* npts, dt, units, format from the data line */
  const char *dend = data.p + data.len;
  long npts = leading_long(data.p, dend);
  double dt_s = 0;
  aq_fortran_fmt f = {CSMIP_V2_FIELDS, CSMIP_V2_WIDTH, 'F'};
  const char *u;
  if (kind == 1) {
    const char *at = aq_find_ci(data.p, data.len, " at ");
    double rate;
    if (at && aq_find_ci(data.p, data.len, "pts/sec") && number_at(at + 4, dend, &rate) &&
        rate > 0)
      dt_s = 1.0 / rate;
    u = aq_find_ci(data.p, data.len, "units of ");
    if (u)
      units_from(u + 9, dend, tmp.units, sizeof tmp.units);
  } else {
    const char *at = aq_find_ci(data.p, data.len, "spaced at");
    if (at && !number_at(at + 9, dend, &dt_s))
      dt_s = 0;
    u = aq_find_ci(data.p, data.len, "units:");
    if (u)
      units_from(u + 6, dend, tmp.units, sizeof tmp.units);
    else if ((u = aq_find_ci(data.p, data.len, ", in "))) /* Avol1: ", in cm/sec2." */
      units_from(u + 5, dend, tmp.units, sizeof tmp.units);
  }
  const char *fp = aq_find_ci(data.p, data.len, "format");
  if (!fp) /* Avol1 V2: "... in cm/sec2. (8f10.7)", the format in the last parentheses */
    for (const char *q = dend; q > data.p; q--)
      if (q[-1] == '(') {
        aq_fortran_fmt g;
        if (aq_fortran_fmt_find(q - 1, (size_t)(dend - q + 1), &g))
          f = g;
        break;
      }
  if (fp && !aq_fortran_fmt_find(fp, (size_t)(dend - fp), &f)) {
    char got[96];
    aq_copy_trim(got, sizeof got, fp, (size_t)(dend - fp));
    return aq_error_set(err, AQ_EFORMAT, name, data.line, -1, "data format",
                        "expected a Fortran format such as (8f9.6), got \"%s\"", got);
  }
  if (!(dt_s > 0) || !isfinite(1.0 / dt_s)) {
    char got[96];
    aq_copy_trim(got, sizeof got, data.p, data.len);
    return aq_error_set(err, AQ_EFORMAT, name, data.line, -1, "sampling",
                        kind == 1 ? "expected \"at R pts/sec\" with R > 0, got \"%s\""
                                  : "expected \"EQUALLY SPACED AT DT SEC\" with DT > 0, got \"%s\"",
                        got);
  }
  if ((size_t)npts > (c->n - c->pos) / (size_t)f.width + 1)
    return aq_error_set(err, AQ_EFORMAT, name, data.line, -1, "NPTS",
                        "%ld values of %d columns cannot fit in the %zu bytes left", npts,
                        f.width, c->n - c->pos);
  tmp.npts = (size_t)npts;
  tmp.dt_s = dt_s;
  tmp.values = malloc(tmp.npts * sizeof *tmp.values);
  if (!tmp.values)
    return aq_error_set(err, AQ_ENOMEM, name, data.line, -1, "data", "out of memory");
  char what[48];
  snprintf(what, sizeof what, "data of channel %zu", raw->nchan + 1);
  aq_line last;
  aq_status s = aq_fixed_read_last(c, tmp.npts, &f, tmp.values, name, what, &last, err);
  if (s != AQ_OK) {
    free(tmp.values);
    return s;
  }
  /* rows past the count (before the next block's data line or the end
   * line): reported for the decision (record.c) */
  aq_extra_rows x;
  aq_extra_rows_scan(c, &last, aq_fixed_row, &f, &x);
  char from[48];
  snprintf(from, sizeof from, "the data line (line %ld)", data.line);
  aq_raw_set_extra(&tmp, &x, 1, from);
  /* skip velocity and displacement (V2) up to and including the end line */
  aq_lines peek = *c;
  while (aq_lines_next(&peek, &ln)) {
    if (ln.len >= 2 && ln.p[0] == '/' && ln.p[1] == '&') {
      *c = peek;
      break;
    }
    if (kind == 1 && !aq_line_blank(&ln))
      break; /* V1: nothing else belongs to this channel */
  }
  if (raw->nchan == 0) {
    aq_copy_trim(raw->processing, sizeof raw->processing, first->p, first->len);
    for (size_t i = 1; i < ntext && i < 4; i++)
      if (aq_find_ci(hdr[i].p, hdr[i].len, "earthquake") ||
          aq_find_ci(hdr[i].p, hdr[i].len, "record of")) {
        aq_copy_trim(raw->event, sizeof raw->event, hdr[i].p, hdr[i].len);
        if (aq_find_ci(hdr[i].p, hdr[i].len, "earthquake")) /* not a record's time */
          snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event);
        break;
      }
  }
  return aq_raw_append_channel(raw, &tmp, name, err);
}

aq_status aq_csmip_parse(const unsigned char *buf, size_t n, const char *name,
                         const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  return aq_raw_parse_channels(buf, n, name, "csmip", aq_line_names_accelerogram,
                            "a channel header naming an (UN)CORRECTED ACCELEROGRAM",
                            parse_channel, raw, err);
}
