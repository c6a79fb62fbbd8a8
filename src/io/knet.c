/* knet.c: K-NET and KiK-net ASCII reader (see reader.h; format notes in
 * docs/knet-format.md).
 *
 * NIED's ASCII files: 17 header lines, each a key in columns 1-18 and its
 * value after it,
 *     Origin Time       2008/06/14 08:43:00      (JST)
 *     Station Code      AOM017
 *     Record Time       2008/06/14 08:44:18      (JST; the record starts 15 s
 *                                                 before it)
 *     Sampling Freq(Hz) 100Hz
 *     Duration Time(s)  115
 *     Dir.              N-S                      (K-NET: N-S, E-W, U-D;
 *                                                 KiK-net: 1-3 borehole, 4-6
 *                                                 surface, N-S E-W U-D)
 *     Scale Factor      3920(gal)/6182761
 *     Memo.
 * then integer counts, 8 per line (the last line short).  One channel per
 * file: counts x the scale factor are gal, stated here as counts with the
 * sensitivity in counts per m/s^2; record.c converts.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define KNET_HEADER_LINES 17
#define KNET_KEY_COLS 18           /* the key's columns */
#define KNET_RECORD_DELAY_S 15.0   /* Record Time is this long after sample 0 */
#define KNET_JST_OFFSET_S (9 * 3600) /* JST = UTC + 9 h */
#define KNET_GAL_MPS2 0.01         /* m/s^2 per gal */

typedef struct {
  const char *s;
  size_t n, pos;
  long line; /* 1-based line of pos */
} knet_cur;

static void next_line(knet_cur *c, size_t *b, size_t *e)
{
  if (aq_text_line(c->s, c->n, &c->pos, b, e))
    c->line++;
  else
    *b = *e = c->pos;
}

/* Copy s[b..e) trimmed into out (printable only). */
static void copy_trim(const char *s, size_t b, size_t e, char *out, size_t cap)
{
  while (b < e && isspace((unsigned char)s[b]))
    b++;
  while (e > b && isspace((unsigned char)s[e - 1]))
    e--;
  size_t k = 0;
  for (size_t i = b; i < e && k + 1 < cap; i++)
    out[k++] = isprint((unsigned char)s[i]) ? s[i] : '?';
  out[k] = '\0';
}

static const char *const knet_keys[KNET_HEADER_LINES] = {
    "Origin Time",  "Lat.",         "Long.",           "Depth. (km)",
    "Mag.",         "Station Code", "Station Lat.",    "Station Long.",
    "Station Height(m)", "Record Time", "Sampling Freq(Hz)", "Duration Time(s)",
    "Dir.",         "Scale Factor", "Max. Acc. (gal)", "Last Correction",
    "Memo."};
enum { K_ORIGIN, K_LAT, K_LON, K_DEPTH, K_MAG, K_STATION, K_SLAT, K_SLON, K_SHEIGHT,
       K_RECORD, K_FREQ, K_DURATION, K_DIR, K_SCALE, K_MAXACC, K_LASTCORR, K_MEMO };

/* "YYYY/MM/DD hh:mm:ss" (JST) minus shift_s -> ISO-8601 UTC; 0 if malformed. */
static int jst_to_utc(const char *v, double shift_s, char *out, size_t cap)
{
  int y, mo, d, h, mi, sec;
  char extra;
  if (sscanf(v, "%d/%d/%d %d:%d:%d %c", &y, &mo, &d, &h, &mi, &sec, &extra) != 6 ||
      y < 1900 || y > 9999 || mo < 1 || mo > 12 || d < 1 || d > 31 || h < 0 || h > 23 ||
      mi < 0 || mi > 59 || sec < 0 || sec > 60)
    return 0;
  char iso[40];
  double t_s;
  snprintf(iso, sizeof iso, "%04d-%02d-%02dT%02d:%02d:%02d", y, mo, d, h, mi, sec);
  if (!aq_iso_parse(iso, &t_s))
    return 0;
  t_s -= KNET_JST_OFFSET_S + shift_s;
  return aq_iso_from_ms(out, cap, (long long)llround(t_s * 1000.0));
}

aq_status aq_knet_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts; /* a K-NET file states everything it can */
  memset(raw, 0, sizeof *raw);
  knet_cur c = {(const char *)buf, n, 0, 1};
  const char *s = c.s;
  char val[KNET_HEADER_LINES][80];
  long vline[KNET_HEADER_LINES];
  for (int k = 0; k < KNET_HEADER_LINES; k++) {
    if (c.pos >= c.n)
      return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, knet_keys[k],
                          "expected the %d K-NET header lines, got %d: header "
                          "truncated",
                          KNET_HEADER_LINES, k);
    size_t b, e;
    vline[k] = c.line;
    next_line(&c, &b, &e);
    size_t kl = strlen(knet_keys[k]);
    if (e - b < kl || memcmp(s + b, knet_keys[k], kl) != 0) {
      char got[40];
      copy_trim(s, b, e < b + 30 ? e : b + 30, got, sizeof got);
      return aq_error_set(err, AQ_EFORMAT, name, vline[k], -1, knet_keys[k],
                          "expected the header key \"%s\", got \"%s\"", knet_keys[k],
                          got);
    }
    size_t vb = b + (e - b > KNET_KEY_COLS ? KNET_KEY_COLS : e - b);
    if (vb < b + kl)
      vb = b + kl;
    copy_trim(s, vb, e, val[k], sizeof val[k]);
  }

  /* Sampling rate, scale factor, direction. */
  char *end;
  double hz = strtod(val[K_FREQ], &end);
  if (!(hz > 0) || !isfinite(hz) || (strcmp(end, "Hz") != 0 && *end))
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_FREQ], -1, "Sampling Freq(Hz)",
                        "expected a rate > 0 such as \"100Hz\", got \"%s\"",
                        val[K_FREQ]);
  double gal_num = strtod(val[K_SCALE], &end), counts_den = NAN;
  if (strncmp(end, "(gal)/", 6) == 0) {
    char *end2;
    counts_den = strtod(end + 6, &end2);
    if (*end2)
      counts_den = NAN;
  }
  if (!(gal_num > 0) || !isfinite(gal_num) || !(counts_den > 0) || !isfinite(counts_den))
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_SCALE], -1, "Scale Factor",
                        "expected GAL(gal)/COUNTS with both > 0, such as "
                        "\"3920(gal)/6182761\", got \"%s\"",
                        val[K_SCALE]);
  double dur = strtod(val[K_DURATION], &end);
  if (!(dur > 0) || !isfinite(dur) || *end || dur * hz > 1e10)
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_DURATION], -1, "Duration Time(s)",
                        "expected a duration > 0 s, got \"%s\"", val[K_DURATION]);
  /* Dir.: N-S, E-W, U-D (K-NET) or 1-6 (KiK-net: 1-3 borehole, 4-6 surface) */
  static const char *const dirs[3] = {"N-S", "E-W", "U-D"};
  static const char *const codes[3] = {"NS", "EW", "UD"};
  int comp = -1, kik = 0;
  for (int i = 0; i < 3; i++)
    if (strcmp(val[K_DIR], dirs[i]) == 0)
      comp = i;
  if (comp < 0 && val[K_DIR][0] >= '1' && val[K_DIR][0] <= '6' && !val[K_DIR][1]) {
    int d = val[K_DIR][0] - '1';
    comp = d % 3;
    kik = 1 + d / 3; /* 1 borehole, 2 surface */
  }
  if (comp < 0)
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_DIR], -1, "Dir.",
                        "expected N-S, E-W, U-D or 1 to 6, got \"%s\"", val[K_DIR]);
  char start[40];
  if (!jst_to_utc(val[K_RECORD], KNET_RECORD_DELAY_S, start, sizeof start))
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_RECORD], -1, "Record Time",
                        "expected YYYY/MM/DD hh:mm:ss, got \"%s\"", val[K_RECORD]);

  /* Values: integer counts, blank-separated, duration x rate of them. */
  double want_d = floor(dur * hz + 0.5);
  size_t want = (size_t)want_d;
  if (want < 1 || want > (c.n - c.pos) / 2 + 1)
    return aq_error_set(err, AQ_EFORMAT, name, vline[K_DURATION], -1, "Duration Time(s)",
                        "expected %s s x %g Hz = %zu values, but only %zu bytes "
                        "follow: file truncated",
                        val[K_DURATION], hz, want, c.n - c.pos);
  aq_status st = aq_raw_file_alloc(raw, 1, name, err);
  if (st != AQ_OK)
    return st;
  aq_raw_channel *ch = &raw->chan[0];
  double *v = malloc(want * sizeof *v);
  if (!v) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  }
  ch->values = v;
  size_t k = 0;
  while (c.pos < c.n && k < want) {
    char ch0 = s[c.pos];
    if (ch0 == ' ' || ch0 == '\t') {
      c.pos++;
      continue;
    }
    if (ch0 == '\n' || ch0 == '\r') {
      size_t b, e;
      next_line(&c, &b, &e);
      continue;
    }
    size_t b = c.pos, i = b;
    if (s[i] == '-' || s[i] == '+')
      i++;
    size_t d0 = i;
    long long x = 0;
    while (i < c.n && s[i] >= '0' && s[i] <= '9' && i - d0 < 12)
      x = x * 10 + (s[i++] - '0');
    int ok = i > d0 && (i == c.n || s[i] == ' ' || s[i] == '\t' || s[i] == '\n' ||
                        s[i] == '\r');
    if (!ok) {
      char got[24], fld[32];
      size_t e = b;
      while (e < c.n && e - b < 20 && !isspace((unsigned char)s[e]))
        e++;
      copy_trim(s, b, e, got, sizeof got);
      snprintf(fld, sizeof fld, "value %zu", k + 1);
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, fld,
                          "expected an integer count, got \"%s\"", got);
    }
    v[k++] = (double)(s[b] == '-' ? -x : x);
    c.pos = i;
  }
  if (k < want) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "Duration Time(s)",
                        "expected %zu values (%s s x %g Hz), got %zu: file truncated",
                        want, val[K_DURATION], hz, k);
  }
  /* values past the count, reported for the decision (record.c): numbers
   * left on the last value's line (never a copy of a row), else rows of
   * them after it; anything else after the data is refused */
  aq_extra_rows x;
  memset(&x, 0, sizeof x);
  size_t lb = c.pos, lend = aq_text_line_end(s, c.pos, c.n);
  while (lb > 0 && s[lb - 1] != '\n' && s[lb - 1] != '\r')
    lb--;
  aq_line last = {s + lb, lend - lb, c.line}, rest = {s + c.pos, lend - c.pos, c.line};
  aq_lines after = {s, c.n, lend, c.line};
  if (!aq_line_blank(&rest)) {
    x.values = aq_numbers_row(&rest, NULL);
    x.rows = 1;
    x.line = c.line;
    aq_lines_next(&after, &rest);
  } else {
    aq_extra_rows_scan(&after, &last, NULL, NULL, &x);
  }
  if ((x.rows > 0 && x.values == 0) || !aq_lines_at_end(&after)) {
    long at = x.rows > 0 && x.values == 0 ? x.line : after.line;
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, at, -1, "Duration Time(s)",
                        "expected the end of the file after %zu values (%s s x %g Hz), got "
                        "more that are not values",
                        want, val[K_DURATION], hz);
  }
  aq_raw_set_extra(ch, &x, 1, "Duration Time(s) x Sampling Freq(Hz)");

  snprintf(raw->format, sizeof raw->format, "%s", kik ? "kiknet" : "knet");
  snprintf(raw->event, sizeof raw->event, "%.19s JST M%.6s %.8sN %.8sE %.6s km",
           val[K_ORIGIN], val[K_MAG], val[K_LAT], val[K_LON], val[K_DEPTH]);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  ch->npts = want;
  ch->dt_s = 1.0 / hz;
  ch->begin_s = 0.0;
  snprintf(ch->reference, sizeof ch->reference, "%s", start);
  snprintf(ch->units, sizeof ch->units, "counts");
  ch->counts_per_mps2 = counts_den / gal_num / KNET_GAL_MPS2;
  snprintf(ch->station, sizeof ch->station, "%.15s", val[K_STATION]);
  if (kik)
    snprintf(ch->channel, sizeof ch->channel, "%s%d", codes[comp], kik);
  else
    snprintf(ch->channel, sizeof ch->channel, "%s", codes[comp]);
  snprintf(ch->location, sizeof ch->location, "%s",
           kik == 1 ? "borehole" : kik == 2 ? "surface" : "");
  ch->vertical = comp == 2;
  ch->azimuth_deg = comp == 0 ? 0.0 : comp == 1 ? 90.0 : NAN;
  ch->dip_deg = comp == 2 ? -90.0 : 0.0;
  return AQ_OK;
}
