/* cosmos.c: COSMOS strong-motion data format v1.20, V0/V1/V2 (reader.h).
 *
 * Per channel, in this order:
 *   text header, N lines; line 1 says "... (Format v01.20 with N text lines)"
 *   " 100 Integer-header values follow on 10 lines, Format= (10I8)"  + values
 *   " 100 Real-header values follow on 17 lines, Format= (6F13.6)"   + values
 *   "   2 Comment line(s) follow, each starting with a "|":"          + lines
 *   "7000 acceleration pts, approx 70 secs, units=cm/sec2(04),Format=(8F10.5)"
 *   the values, by column width (fields touch: -94.84213-120.18770)
 *   an end-of-data line ("/&  ---  End of data for channel 1", "End-of-data ...")
 * and the next channel, if any.  The header formats are read from their own
 * lines (10I8, 6F13.6, 5F15.6 all occur).
 *
 * Header positions used (1-based, as the format's tables number them):
 *   integer #3 units code (2 g, 4 cm/s^2, 50 counts), #40-#45 start year,
 *   day of year, month, day, hour, minute, #54 orientation (0-360 azimuth,
 *   400 up, 500 down);
 *   real #22 LSB (microvolts/count), #30 start second, #42 sensor
 *   sensitivity (V/g), #47 gain, #62 sampling interval (ms).
 * dt is real #62, never real #34 (which can disagree: the format's own sample
 * file has #34 = 0.005 s for data at 0.01 s).  -999 means "not given".
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "fixed.h"
#include "reader.h"

#define COSMOS_NULL -999.0          /* the format's "unknown" value */
#define COSMOS_NULL_TOL 1e-6        /* |v - (-999)| below this is "unknown" */
#define COSMOS_MIN_INTS 54          /* highest integer position used */
#define COSMOS_MIN_REALS 62         /* highest real position used */
#define COSMOS_MAX_HEADER 1000      /* header counts beyond this are refused */
#define COSMOS_MAX_TEXT_LINES 200

static int is_null(double v) { return fabs(v - COSMOS_NULL) < COSMOS_NULL_TOL; }

/* Leading unsigned integer of a line (after blanks); -1 if none. */
static long leading_int(const aq_line *ln)
{
  size_t i = 0;
  while (i < ln->len && ln->p[i] == ' ')
    i++;
  if (i >= ln->len || !isdigit((unsigned char)ln->p[i]))
    return -1;
  long v = 0;
  for (; i < ln->len && isdigit((unsigned char)ln->p[i]); i++) {
    if (v > 100000000L)
      return -1;
    v = v * 10 + (ln->p[i] - '0');
  }
  return v;
}

static aq_status bad_line(aq_error *err, const char *name, const aq_line *ln,
                          const char *field, const char *expected)
{
  char got[64];
  aq_copy_trim(got, sizeof got, ln->p, ln->len);
  return aq_error_set(err, AQ_EFORMAT, name, ln->line, -1, field,
                      "expected %s, got \"%s\"", expected, got);
}

/* A "N xxx values follow on L lines, Format= (..)" line and its values. */
static aq_status read_header_block(aq_lines *c, const char *name, const char *key,
                                   size_t min_count, double **vals, size_t *count,
                                   aq_error *err)
{
  aq_line ln;
  char field[48];
  snprintf(field, sizeof field, "%s header", key);
  if (!aq_lines_next(c, &ln))
    return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, field,
                        "expected \"N %s-header values follow\", got end of file", key);
  long nv = leading_int(&ln);
  aq_fortran_fmt f;
  const char *fp = aq_find_ci(ln.p, ln.len, "format");
  if (nv < 0 || !aq_find_ci(ln.p, ln.len, key) || !fp ||
      !aq_fortran_fmt_find(fp, ln.len - (size_t)(fp - ln.p), &f))
    return bad_line(err, name, &ln, field,
                    "\"N <kind>-header values follow on L lines, Format= (..)\"");
  if ((size_t)nv < min_count || nv > COSMOS_MAX_HEADER)
    return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, field,
                        "expected %zu to %d values, got %ld", min_count,
                        COSMOS_MAX_HEADER, nv);
  double *v = malloc((size_t)nv * sizeof *v);
  if (!v)
    return aq_error_set(err, AQ_ENOMEM, name, ln.line, -1, field, "out of memory");
  aq_status s = aq_fixed_read(c, (size_t)nv, &f, v, name, field, err);
  if (s != AQ_OK) {
    free(v);
    return s;
  }
  *vals = v;
  *count = (size_t)nv;
  return AQ_OK;
}

/* "Code:CE-J2236" on text line 5: network and station. */
static void station_code(const aq_line *ln, aq_raw_channel *ch)
{
  const char *p = aq_find_ci(ln->p, ln->len, "code:");
  if (!p)
    return;
  p += 5;
  size_t len = aq_next_word(&p, ln->p + ln->len, "");
  const char *b = p;
  p += len;
  const char *dash = memchr(b, '-', (size_t)(p - b));
  if (dash) {
    aq_copy_trim(ch->network, sizeof ch->network, b, (size_t)(dash - b));
    aq_copy_trim(ch->station, sizeof ch->station, dash + 1, (size_t)(p - dash - 1));
  } else {
    aq_copy_trim(ch->station, sizeof ch->station, b, (size_t)(p - b));
  }
}

/* "Sta Cha:  1: 340 deg (Rcrdr ...)" / "Sta Chan   ?: Up": the first word
 * after the second colon. */
static void channel_name(const aq_line *ln, aq_raw_channel *ch)
{
  const char *end = ln->p + ln->len;
  const char *p = memchr(ln->p, ':', ln->len);
  if (!p)
    return;
  p = memchr(p + 1, ':', (size_t)(end - p - 1));
  if (!p)
    return;
  p++;
  size_t len = aq_next_word(&p, end, "(");
  aq_copy_trim(ch->channel, sizeof ch->channel, p, len);
}

/* A comment "RcrdId: NC.73177305.NP.1795.HNE.--": SEED channel and location. */
static void record_id(const aq_line *ln, aq_raw_channel *ch)
{
  const char *p = aq_find_ci(ln->p, ln->len, "RcrdId:");
  if (!p)
    return;
  p += 7;
  const char *end = ln->p + ln->len;
  while (p < end && *p == ' ')
    p++;
  const char *part[7];
  size_t len[7], k = 0;
  part[0] = p;
  for (; p < end && *p != ' ' && k < 6; p++)
    if (*p == '.') {
      len[k] = (size_t)(p - part[k]);
      part[++k] = p + 1;
    }
  if (k != 5)
    return;
  len[5] = (size_t)(p - part[5]);
  if (len[4] == 0 || len[4] >= sizeof ch->channel)
    return;
  aq_copy_trim(ch->channel, sizeof ch->channel, part[4], len[4]);
  if (!(len[5] == 2 && part[5][0] == '-' && part[5][1] == '-'))
    aq_copy_trim(ch->location, sizeof ch->location, part[5], len[5]);
}

static void units_word(int code, const aq_line *data_line, char *out, size_t cap)
{
  switch (code) {
  case 2: snprintf(out, cap, "g"); return;
  case 4: snprintf(out, cap, "cm/s2"); return;
  case 50: snprintf(out, cap, "counts"); return;
  default: break;
  }
  /* not an acceleration unit this reader knows: report the file's word so
   * that the units decision can name it */
  const char *u = aq_find_ci(data_line->p, data_line->len, "units=");
  if (!u) {
    snprintf(out, cap, "code %d", code);
    return;
  }
  u += 6;
  const char *end = data_line->p + data_line->len, *p = u;
  while (p < end && *p != '(' && *p != ',' && *p != ' ')
    p++;
  aq_copy_trim(out, cap, u, (size_t)(p - u));
}

/* One channel, from its first text line (already read) to its end line. */
static aq_status parse_channel(aq_lines *c, const aq_line *first, const char *name,
                               aq_raw_file *raw, aq_error *err)
{
  aq_status s;
  long ntext = 13;
  const char *w = aq_find_ci(first->p, first->len, "with");
  if (w) {
    aq_line t = {w + 4, first->len - (size_t)(w + 4 - first->p), first->line};
    ntext = leading_int(&t);
  }
  if (ntext < 1 || ntext > COSMOS_MAX_TEXT_LINES)
    return bad_line(err, name, first, "text header", "\"(Format v01.20 with N text lines)\"");
  aq_line text[13];
  memset(text, 0, sizeof text);
  text[0] = *first;
  for (long i = 1; i < ntext; i++) {
    aq_line ln;
    if (!aq_lines_next(c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "text header",
                          "expected %ld text lines, the file ends after %ld", ntext, i);
    if (i < 13)
      text[i] = ln;
  }
  double *iv = NULL, *rv = NULL;
  size_t ni = 0, nr = 0;
  s = read_header_block(c, name, "integer", COSMOS_MIN_INTS, &iv, &ni, err);
  if (s != AQ_OK)
    return s;
  s = read_header_block(c, name, "real", COSMOS_MIN_REALS, &rv, &nr, err);
  if (s != AQ_OK) {
    free(iv);
    return s;
  }
  aq_raw_channel tmp;
  aq_raw_channel_init(&tmp);
  if (ntext >= 5)
    station_code(&text[4], &tmp);
  if (ntext >= 9)
    channel_name(&text[8], &tmp);

  aq_line ln;
  long ncomment;
  if (!aq_lines_next(c, &ln) || (ncomment = leading_int(&ln)) < 0 ||
      !aq_find_ci(ln.p, ln.len, "comment")) {
    s = aq_lines_at_end(c) ? aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "comment count",
                                          "expected \"N Comment line(s) follow\", got end of file")
                           : bad_line(err, name, &ln, "comment count",
                                      "\"N Comment line(s) follow\"");
    goto fail;
  }
  for (long i = 0; i < ncomment; i++) {
    aq_line cl;
    if (!aq_lines_next(c, &cl)) {
      s = aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "comments",
                       "expected %ld comment lines, the file ends after %ld", ncomment, i);
      goto fail;
    }
    record_id(&cl, &tmp);
  }

  /* the data line */
  aq_fortran_fmt f;
  long npts;
  const char *fp;
  if (!aq_lines_next(c, &ln)) {
    s = aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "data line",
                     "expected \"NPTS ... pts, ..., units=..., Format=(..)\", got end of file");
    goto fail;
  }
  npts = leading_int(&ln);
  fp = aq_find_ci(ln.p, ln.len, "format");
  if (npts < 1 || !aq_find_ci(ln.p, ln.len, "pts") || !fp ||
      !aq_fortran_fmt_find(fp, ln.len - (size_t)(fp - ln.p), &f)) {
    s = bad_line(err, name, &ln, "data line", "\"NPTS ... pts, ..., units=..., Format=(..)\"");
    goto fail;
  }
  if ((size_t)npts > (c->n - c->pos) / (size_t)f.width + 1) {
    s = aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "NPTS",
                     "%ld values of %d columns cannot fit in the %zu bytes left", npts,
                     f.width, c->n - c->pos);
    goto fail;
  }

  /* header fields: validate before reading the data */
  double dt_ms = rv[61];
  if (!(dt_ms > 0) || is_null(dt_ms)) {
    s = aq_error_set(err, AQ_EFORMAT, name, ln.line, -1,
                     "real header #62 (sampling interval, ms)", "expected > 0, got %g", dt_ms);
    goto fail;
  }
  int code = aq_header_int(iv[2]);
  {
    /* the data line's "(NN)" code wins over integer #3 when both are given */
    const char *u = aq_find_ci(ln.p, ln.len, "units=");
    const char *par = u ? memchr(u, '(', ln.len - (size_t)(u - ln.p)) : NULL;
    if (par && par + 1 < ln.p + ln.len && isdigit((unsigned char)par[1]))
      code = atoi(par + 1);
  }
  units_word(code, &ln, tmp.units, sizeof tmp.units);
  {
    /* the data line names what its values are ("7000 acceleration pts") */
    static const struct {
      const char *word;
      int q;
    } kinds[] = {{"accel", AQ_QUANTITY_ACCELERATION},
                 {"veloc", AQ_QUANTITY_VELOCITY},
                 {"displ", AQ_QUANTITY_DISPLACEMENT}};
    const char *pts = aq_find_ci(ln.p, ln.len, "pts");
    size_t before = pts ? (size_t)(pts - ln.p) : ln.len;
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
      if (aq_find_ci(ln.p, before, kinds[i].word)) {
        char said[64];
        aq_copy_trim(said, sizeof said, ln.p, before + (pts ? 3 : 0));
        tmp.quantity = kinds[i].q;
        snprintf(tmp.quantity_said, sizeof tmp.quantity_said, "line %ld: \"%s\"", ln.line,
                 said);
        break;
      }
    snprintf(tmp.units_from, sizeof tmp.units_from, "line %ld: units code %d", ln.line, code);
  }
  if (code == 50) {
    double lsb_uv = rv[21], sens_v_per_g = rv[41], gain = rv[46];
    static const char *const fld[3] = {"real header #22 (LSB, microvolts/count)",
                                        "real header #42 (sensor sensitivity, V/g)",
                                        "real header #47 (gain)"};
    double v[3] = {lsb_uv, sens_v_per_g, gain};
    int known = 1;
    for (int i = 0; i < 3; i++) {
      if (is_null(v[i])) {
        known = 0;
        continue;
      }
      if (!(v[i] > 0)) {
        s = aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, fld[i],
                         "expected > 0 (or -999 if unknown), got %g", v[i]);
        goto fail;
      }
    }
    /* counts per (m/s^2) = (V/g * gain) / (V/count) / (m/s^2 per g) */
    if (known)
      tmp.counts_per_mps2 = sens_v_per_g * gain / (lsb_uv * 1e-6) / AQ_G0_MPS2;
  }
  {
    double orient = iv[53];
    if (orient >= 0 && orient <= 360) {
      tmp.azimuth_deg = orient;
      tmp.dip_deg = 0;
      tmp.vertical = 0;
      snprintf(tmp.orient_said, sizeof tmp.orient_said,
               "integer header #54 (orientation): %g", orient);
    } else if (orient == 400 || orient == 500) {
      tmp.dip_deg = orient == 400 ? -90 : 90;
      tmp.vertical = 1;
    }
  }
  {
    int year = aq_header_int(iv[39]), jday = aq_header_int(iv[40]);
    int mon = aq_header_int(iv[41]), day = aq_header_int(iv[42]);
    int hour = aq_header_int(iv[43]), min = aq_header_int(iv[44]);
    double sec = rv[29];
    if ((mon < 1 || day < 1) && !aq_month_day(year, jday, &mon, &day))
      mon = 0;
    if (is_null(sec))
      sec = 0;
    if (!aq_iso_time(tmp.reference, sizeof tmp.reference, year, mon, day, hour, min, sec))
      tmp.reference[0] = '\0';
  }
  tmp.dt_s = dt_ms * 1e-3;
  tmp.npts = (size_t)npts;
  tmp.values = malloc(tmp.npts * sizeof *tmp.values);
  if (!tmp.values) {
    s = aq_error_set(err, AQ_ENOMEM, name, ln.line, -1, "data", "out of memory");
    goto fail;
  }
  {
    char what[48];
    snprintf(what, sizeof what, "data of channel %zu", raw->nchan + 1);
    aq_line last;
    s = aq_fixed_read_last(c, tmp.npts, &f, tmp.values, name, what, &last, err);
    if (s != AQ_OK)
      goto fail;
    /* rows past the count: reported for the decision (record.c) */
    aq_extra_rows x;
    aq_extra_rows_scan(c, &last, aq_fixed_row, &f, &x);
    aq_raw_set_extra(&tmp, &x, 1, "the data header");
  }
  /* the end line, if present */
  {
    aq_lines peek = *c;
    aq_line el;
    if (aq_lines_next(&peek, &el) &&
        (aq_find_ci(el.p, el.len, "end of data") || aq_find_ci(el.p, el.len, "end-of-data") ||
         (el.len >= 2 && el.p[0] == '/' && el.p[1] == '&')))
      *c = peek;
  }
  if (raw->nchan == 0) {
    aq_copy_trim(raw->event, sizeof raw->event, text[1].p, text[1].len);
    snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
    const char *fmt = aq_find_ci(first->p, first->len, "(format");
    size_t kind_len = fmt ? (size_t)(fmt - first->p) : first->len;
    char kind[64], filt[96];
    aq_copy_trim(kind, sizeof kind, first->p, kind_len);
    aq_copy_trim(filt, sizeof filt, text[11].p, ntext >= 12 ? text[11].len : 0);
    snprintf(raw->processing, sizeof raw->processing, "%.60s%s%.95s", kind,
             filt[0] ? "; " : "", filt);
  }
  free(iv);
  free(rv);
  return aq_raw_append_channel(raw, &tmp, name, err);
fail:
  free(tmp.values);
  free(iv);
  free(rv);
  return s;
}

static int cosmos_starts(const aq_line *ln) { return aq_find_ci(ln->p, ln->len, "(Format v") != NULL; }

aq_status aq_cosmos_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  aq_lines c;
  aq_line ln = {NULL, 0, 0};
  aq_lines_init(&c, buf, n);
  while (aq_lines_next(&c, &ln) && aq_line_blank(&ln))
    ;
  if (c.line > 1 && !cosmos_starts(&ln) && aq_find_ci(ln.p, ln.len, "accelerogram"))
    return aq_csmip_parse(buf, n, name, opts, raw, err); /* the CSMIP variant */
  return aq_raw_parse_channels(buf, n, name, "cosmos", cosmos_starts,
                            "\"... (Format v01.20 with N text lines)\"", parse_channel, raw, err);
}
