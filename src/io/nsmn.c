/* nsmn.c: the ASCII of Turkey's national strong-motion network (NSMN, run
 * by AFAD) before the ESM-like DYNA 1.2 text (reader.h).
 *
 * Line 1 "STRONG GROUND MOTION RECORDS OF TURKIYE", then "KEY : value"
 * lines, place names in ISO-8859-9 (Turkish Latin-5: 0xDD I with dot, 0xFE
 * s cedilla; kept as bytes, shown as '?'), a line naming the columns
 * ("N-S  E-W  U-D") and one row per sample of three blank-separated values.
 * Keys used (read by key, not by line number):
 *   NUMBER OF DATA             npts (the rows must be exactly that many)
 *   SAMPLING INTERVAL (sec)    dt
 *   RECORD TIME                "05/03/2011 12:34:56.500000" (day/month/year,
 *                              UTC): the first sample
 *   STATION ID                 the station
 *   EARTHQUAKE DATE, ... TIME, ... MAGNITUDE   the event
 *   a key naming "(gal)" or "(cm/s^2)" (RAW PGA VALUES (gal)), or UNIT(S):
 *                              the units of the values; none otherwise
 * Columns: named by the line before the data (N-S, E-W, U-D: azimuth 0 and
 * 90, and vertical); without such a line, in the format's order N-S, E-W,
 * U-D.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fixed.h"
#include "reader.h"
#include "units.h"

#define NSMN_MARKER "STRONG GROUND MOTION RECORDS OF TURK" /* TURKIYE, TURKEY */
#define NSMN_NCHAN 3
#define NSMN_HEADER_MAX 60 /* header lines looked at before the data */
#define NSMN_VALUE_MAX 96

int aq_nsmn_sniff(const unsigned char *buf, size_t n)
{
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  return aq_lines_next(&c, &ln) && aq_find_ci(ln.p, ln.len, NSMN_MARKER) != NULL;
}

/* Three numbers separated by blanks, and nothing else: 1 (values in v). */
static int data_row(const aq_line *ln, double v[NSMN_NCHAN]);

/* A row past the count (aq_extra_rows_scan): one value of each channel. */
static size_t extra_row(const aq_line *ln, const void *ctx)
{
  (void)ctx;
  double v[NSMN_NCHAN];
  return data_row(ln, v) ? 1 : 0;
}

static int data_row(const aq_line *ln, double v[NSMN_NCHAN])
{
  const char *p = ln->p, *end = ln->p + ln->len;
  for (int j = 0; j < NSMN_NCHAN; j++) {
    size_t len = aq_next_word(&p, end, "\t");
    if (len == 0 || !aq_field_double(p, len, &v[j]))
      return 0;
    p += len;
  }
  while (p < end && (*p == ' ' || *p == '\t'))
    p++;
  return p == end;
}

/* The value after the first ':' of ln, trimmed, into out; 1 if the key
 * (before it) starts with key, case-insensitive. */
static int key_value(const aq_line *ln, const char *key, char *out, size_t cap)
{
  const char *colon = memchr(ln->p, ':', ln->len);
  const char *k = ln->p;
  while (k < ln->p + ln->len && *k == ' ')
    k++;
  size_t m = strlen(key);
  if (!colon || (size_t)(colon - k) < m || strncasecmp(k, key, m) != 0)
    return 0;
  aq_copy_trim(out, cap, colon + 1, (size_t)(ln->p + ln->len - colon - 1));
  return 1;
}

/* Units named in a key's parentheses or a UNIT key: canonical name or "". */
static void units_of(const aq_line *ln, char *out, size_t cap)
{
  const char *colon = memchr(ln->p, ':', ln->len);
  size_t klen = colon ? (size_t)(colon - ln->p) : ln->len;
  if (aq_find_ci(ln->p, klen, "(gal)") || aq_find_ci(ln->p, klen, "(cm/s^2)") ||
      aq_find_ci(ln->p, klen, "(cm/s2)") || aq_find_ci(ln->p, klen, "(cm/s/s)"))
    snprintf(out, cap, "gal");
  else if (aq_find_ci(ln->p, klen, "(g)"))
    snprintf(out, cap, "g");
}

aq_status aq_nsmn_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln, prev = {NULL, 0, 0};
  char npts_s[NSMN_VALUE_MAX] = "", dt_s_s[NSMN_VALUE_MAX] = "", t0[NSMN_VALUE_MAX] = "";
  char station[NSMN_VALUE_MAX] = "", date[NSMN_VALUE_MAX] = "", time_s[NSMN_VALUE_MAX] = "";
  char mag[NSMN_VALUE_MAX] = "", units[24] = "", val[NSMN_VALUE_MAX];
  long npts_line = 0, dt_line = 0, units_line = -1;
  double v[NSMN_NCHAN];
  int found = 0;
  for (int i = 0; i < NSMN_HEADER_MAX && aq_lines_next(&c, &ln); i++) {
    if ((found = data_row(&ln, v)))
      break;
    if (i == 0 && !aq_find_ci(ln.p, ln.len, NSMN_MARKER))
      return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "header",
                          "expected \"" NSMN_MARKER "IYE\" on line 1");
    if (key_value(&ln, "NUMBER OF DATA", npts_s, sizeof npts_s))
      npts_line = ln.line;
    else if (key_value(&ln, "SAMPLING INTERVAL", dt_s_s, sizeof dt_s_s))
      dt_line = ln.line;
    else if (!key_value(&ln, "RECORD TIME", t0, sizeof t0) &&
             !key_value(&ln, "STATION ID", station, sizeof station) &&
             !key_value(&ln, "EARTHQUAKE DATE", date, sizeof date) &&
             !key_value(&ln, "EARTHQUAKE TIME", time_s, sizeof time_s) &&
             !key_value(&ln, "EARTHQUAKE MAGNITUDE", mag, sizeof mag) &&
             key_value(&ln, "UNIT", val, sizeof val)) {
      aq_units u;
      if (aq_units_parse(val, &u))
        snprintf(units, sizeof units, "%s", aq_units_name(u));
      units_line = ln.line;
    }
    if (!units[0]) {
      units_of(&ln, units, sizeof units);
      if (units[0])
        units_line = ln.line;
    }
    if (!aq_line_blank(&ln))
      prev = ln;
  }
  if (!found)
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "data",
                        "expected rows of three values (N-S, E-W, U-D) within %d lines of "
                        "the NSMN header, found none",
                        NSMN_HEADER_MAX);
  double npts_d, dt;
  if (!npts_line || !aq_field_double(npts_s, strlen(npts_s), &npts_d) || !(npts_d >= 1) ||
      npts_d != floor(npts_d) || npts_d > (double)n)
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NUMBER OF DATA",
                        "expected a count >= 1 that the file can hold, got \"%s\"", npts_s);
  if (!dt_line || !aq_field_double(dt_s_s, strlen(dt_s_s), &dt) || !(dt > 0) ||
      !isfinite(1.0 / dt))
    return aq_error_set(err, AQ_EFORMAT, name, dt_line, -1, "SAMPLING INTERVAL (sec)",
                        "expected a sample interval > 0 s, got \"%s\"", dt_s_s);
  aq_status s = aq_raw_file_alloc(raw, NSMN_NCHAN, name, err);
  if (s != AQ_OK)
    return s;
  /* column names: "N-S E-W U-D" on the line before the data */
  static const char *const fixed_names[NSMN_NCHAN] = {"N-S", "E-W", "U-D"};
  char names[NSMN_NCHAN][16];
  int named = 0;
  if (prev.p) {
    const char *p = prev.p, *end = prev.p + prev.len;
    for (named = 0; named < NSMN_NCHAN; named++) {
      size_t len = aq_next_word(&p, end, "\t");
      if (len == 0 || len >= 16 || isdigit((unsigned char)*p) || memchr(p, ':', len))
        break;
      aq_copy_trim(names[named], 16, p, len);
      p += len;
    }
    while (p < end && (*p == ' ' || *p == '\t'))
      p++;
    if (p != end)
      named = 0;
  }
  char start[40] = "";
  int d, mo, y, h, mi;
  double sec;
  if (sscanf(t0, "%d/%d/%d %d:%d:%lf", &d, &mo, &y, &h, &mi, &sec) == 6 &&
      !aq_iso_time(start, sizeof start, y, mo, d, h, mi, sec))
    start[0] = '\0';
  size_t np = (size_t)npts_d;
  for (int j = 0; j < NSMN_NCHAN; j++) {
    aq_raw_channel *ch = &raw->chan[j];
    ch->npts = np;
    ch->dt_s = dt;
    ch->values = malloc(np * sizeof *ch->values);
    if (!ch->values) {
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_ENOMEM, name, -1, -1, "data", "out of memory");
    }
    snprintf(ch->channel, sizeof ch->channel, "%.15s", named == NSMN_NCHAN ? names[j] : fixed_names[j]);
    snprintf(ch->units, sizeof ch->units, "%s", units);
    ch->units_line = units_line;
    snprintf(ch->reference, sizeof ch->reference, "%s", start);
    snprintf(ch->station, sizeof ch->station, "%.15s", station);
    snprintf(ch->network, sizeof ch->network, "TK");
    const char *cn = ch->channel;
    if (strcasecmp(cn, "N-S") == 0 || strcasecmp(cn, "NS") == 0) {
      ch->vertical = 0, ch->dip_deg = 0, ch->azimuth_deg = 0;
    } else if (strcasecmp(cn, "E-W") == 0 || strcasecmp(cn, "EW") == 0) {
      ch->vertical = 0, ch->dip_deg = 0, ch->azimuth_deg = 90;
    } else if (strcasecmp(cn, "U-D") == 0 || strcasecmp(cn, "UD") == 0) {
      ch->vertical = 1;
    }
  }
  size_t k = 0;
  long first = ln.line;
  for (;;) {
    for (int j = 0; j < NSMN_NCHAN; j++)
      raw->chan[j].values[k] = v[j];
    if (++k == np)
      break;
    if (!aq_lines_next(&c, &ln) || !data_row(&ln, v)) {
      long at = c.line - 1;
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_EFORMAT, name, at, -1, "data",
                          "expected %zu rows of three values (NUMBER OF DATA) from line %ld, "
                          "%s after %zu",
                          np, first, aq_lines_at_end(&c) ? "the file ends" : "got a row that is not",
                          k);
    }
  }
  /* rows past NUMBER OF DATA: reported for the decision (record.c) */
  aq_status rs = aq_raw_rows_end(&c, &ln, extra_row, NULL, np, "NUMBER OF DATA", raw, name, err);
  if (rs != AQ_OK)
    return rs;
  snprintf(raw->event, sizeof raw->event, "%.20s %.20s %.40s", date, time_s, mag);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  snprintf(raw->format, sizeof raw->format, "nsmn");
  return AQ_OK;
}
