/* smc.c: USGS SMC strong-motion text format (reader.h).
 *
 * Layout: 11 text lines (line 1 "2 CORRECTED ACCELEROGRAM": the leading
 * number is the data type, 1 uncorrected and 2 corrected acceleration,
 * 3 velocity, 4 displacement; line 3 the station code; line 4 the event;
 * line 6 "station = ... component= 90"), 48 integers (8I10, 6 lines),
 * 50 reals (5E15.7, 10 lines), integer #16 comment lines starting "|", then
 * integer #17 values, 8 per line in E10.4 whose fields touch
 * (`-2.7715E+0-1.1578E-1`).  Acceleration is in cm/s^2.  Files written by
 * converters lay the values out otherwise (PEER's PEA2SMC: 5 per line in
 * E14.7, `1.1365572E-02-5.7981615E-03`), so the layout is read from the
 * file itself: the first data line's length is a whole number of fields of
 * one width, each of which reads as a number (data_layout).
 * Header positions used (1-based): integers #2-#7 start year, day of year,
 * hour, minute, second, millisecond; #13 angle from vertical (0 up, 180
 * down, 90 horizontal); #14 azimuth; #16 comment lines; #17 npts.  Real #2
 * samples per second: without it the samples are (time, value) pairs of
 * uneven sampling, which are refused.  Null values: -32768 and 1.7E+38.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define SMC_TEXT_LINES 11
#define SMC_INTS 48
#define SMC_REALS 50
#define SMC_INT_NULL -32768
#define SMC_REAL_NULL_MIN 1e38 /* 1.7E+38 (and anything as large) is null */
/* The widths a data field may have: E10.4 (the standard) to E24.16 and
 * more; a narrower field cannot hold an E-format number with a digit
 * after the point and a two-character exponent. */
#define SMC_WIDTH_MIN 6
#define SMC_WIDTH_MAX 40

static aq_status smc_bad(aq_error *err, const char *name, long line, const char *field,
                         const char *fmt, double got)
{
  return aq_error_set(err, AQ_EFORMAT, name, line, -1, field, fmt, got);
}

/* The layout of the nvalues data values from the next line of c on: the
 * first data line's length (trailing blanks aside) is per x width, every
 * one of its per fields reads as a number, and per <= nvalues.  Among
 * several such (F-format digits can read at two widths), the one whose
 * line count, ceil(nvalues / per), is the file's count of lines left; the
 * standard 8E10 when none reads the line (aq_fixed_read then names the
 * line and columns that do not).  Returns 0 (err filled) when two layouts
 * fit alike; fills *fd and what (the layout in words for messages). */
static int data_layout(const aq_lines *c, double nvalues, aq_fortran_fmt *fd, char *what,
                       size_t what_n, const char *name, aq_error *err)
{
  *fd = (aq_fortran_fmt){8, 10, 'E'};
  aq_lines peek = *c;
  aq_line first;
  size_t left = 0;
  int have = aq_lines_next(&peek, &first);
  for (aq_line ln; have && aq_lines_next(&peek, &ln);)
    left += !aq_line_blank(&ln);
  left += have;
  size_t len = have ? first.len : 0;
  while (len > 0 && (first.p[len - 1] == ' ' || first.p[len - 1] == '\t'))
    len--;
  aq_fortran_fmt fit[SMC_WIDTH_MAX];
  size_t nfit = 0, nexact = 0, exact = 0;
  for (size_t w = SMC_WIDTH_MIN; w <= SMC_WIDTH_MAX && w <= len; w++) {
    size_t per = len / w;
    if (len % w != 0 || (double)per > nvalues)
      continue;
    int ok = 1;
    double v;
    for (size_t j = 0; ok && j < per; j++)
      ok = aq_field_double(first.p + j * w, w, &v);
    if (!ok)
      continue;
    if ((size_t)ceil(nvalues / (double)per) == left) {
      nexact++;
      exact = nfit;
    }
    fit[nfit++] = (aq_fortran_fmt){(int)per, (int)w, 'E'};
  }
  if (nfit == 1 || nexact == 1)
    *fd = fit[nfit == 1 ? 0 : exact];
  else if (nfit > 1)
    return aq_error_set(err, AQ_EFORMAT, name, first.line, -1, "data",
                        "expected values in fields of one width, got a line that reads "
                        "as %d values of %d columns and as %d of %d",
                        fit[0].per_line, fit[0].width, fit[1].per_line, fit[1].width) ==
           AQ_OK;
  snprintf(what, what_n, "data (%dE%d: %d values of %d columns a line)", fd->per_line,
           fd->width, fd->per_line, fd->width);
  return 1;
}

/* A file whose real #2 (samples per second) is null holds (time, value)
 * pairs of uneven sampling (film digitised at its own times): they are not
 * resampled here.  Check that they are such pairs (times increasing) and
 * refuse them in one line that says what they are; c is at the comments. */
static aq_status uneven(aq_lines *c, int type, double ncomment, double nvalues,
                        long real_line, const char *name, aq_error *err)
{
  if (!(nvalues >= 2) || fmod(nvalues, 2) != 0 || ncomment < 0 || ncomment > (double)c->n ||
      nvalues > (double)(c->n - c->pos) / SMC_WIDTH_MIN + 1)
    return smc_bad(err, name, real_line - 5, "integer header #17 (npts)",
                   "expected an even count of values, (time, value) pairs, that the file "
                   "can hold, got %g",
                   nvalues);
  for (double i = 0; i < ncomment; i++) {
    aq_line ln;
    if (!aq_lines_next(c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, "comments",
                          "expected %g comment lines, the file ends after %g", ncomment, i);
  }
  long data_line = c->line;
  aq_fortran_fmt fd;
  char what[64];
  if (!data_layout(c, nvalues, &fd, what, sizeof what, name, err))
    return err->status;
  size_t nv = (size_t)nvalues;
  double *v = malloc(nv * sizeof *v);
  if (!v)
    return aq_error_set(err, AQ_ENOMEM, name, c->line, -1, "data", "out of memory");
  aq_status s = aq_fixed_read(c, nv, &fd, v, name, what, err);
  double step_min = INFINITY, step_max = 0;
  for (size_t k = 2; s == AQ_OK && k < nv; k += 2) {
    double step = v[k] - v[k - 2];
    if (!(step > 0)) {
      s = aq_error_set(err, AQ_EFORMAT, name, data_line + (long)(k / (size_t)fd.per_line), -1,
                       "data",
                       "real header #2 (samples per second) is null, so the values are "
                       "(time, value) pairs, but time %zu (%g s) does not follow %g s",
                       k / 2 + 1, v[k], v[k - 2]);
      break;
    }
    step_min = fmin(step_min, step);
    step_max = fmax(step_max, step);
  }
  if (s == AQ_OK)
    s = aq_error_set(err, AQ_EUNSUPPORTED, name, real_line, -1,
                     "real header #2 (samples per second)",
                     "USGS SMC type %d with no sampling rate holds %zu (time, value) pairs, "
                     "unevenly sampled (steps %.2g to %.2g s, %g to %g s), which is not "
                     "supported: archquake does not resample; use the agency's corrected "
                     "(type 2) file of this record",
                     type, nv / 2, step_min, step_max, v[0],
                     v[nv - 2]);
  free(v);
  return s;
}

aq_status aq_smc_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line text[SMC_TEXT_LINES];
  for (int i = 0; i < SMC_TEXT_LINES; i++)
    if (!aq_lines_next(&c, &text[i]))
      return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "text header",
                          "expected %d text lines, the file ends after %d", SMC_TEXT_LINES, i);
  double type;
  if (text[0].len < 2 || text[0].p[1] != ' ' || !aq_field_double(text[0].p, 1, &type) ||
      (!aq_find_ci(text[0].p, text[0].len, "ACCELEROGRAM") &&
       !aq_find_ci(text[0].p, text[0].len, "VELOCITY") &&
       !aq_find_ci(text[0].p, text[0].len, "DISPLACEMENT") &&
       !aq_find_ci(text[0].p, text[0].len, "UNKNOWN"))) {
    char got[64];
    aq_copy_trim(got, sizeof got, text[0].p, text[0].len);
    return aq_error_set(err, AQ_EFORMAT, name, 1, -1, "data type",
                        "expected \"N (UN)CORRECTED ACCELEROGRAM\", got \"%s\"", got);
  }
  if (type < 0 || type > 4) {
    char got[64];
    aq_copy_trim(got, sizeof got, text[0].p, text[0].len);
    return aq_error_set(err, AQ_EUNSUPPORTED, name, 1, -1, "data type",
                        "expected a time series (1 to 4), got \"%s\"", got);
  }
  double iv[SMC_INTS], rv[SMC_REALS];
  aq_fortran_fmt fi = {8, 10, 'I'}, fr = {5, 15, 'E'}, fd;
  aq_status s = aq_fixed_read(&c, SMC_INTS, &fi, iv, name, "integer header (8I10)", err);
  if (s != AQ_OK)
    return s;
  long real_line = c.line;
  s = aq_fixed_read(&c, SMC_REALS, &fr, rv, name, "real header (5E15.7)", err);
  if (s != AQ_OK)
    return s;
  double ncomment = iv[15], npts = iv[16], rate = rv[1];
  if (ncomment < 0 || ncomment > (double)n)
    return smc_bad(err, name, real_line - 5, "integer header #16 (comment lines)",
                   "expected >= 0, got %g", ncomment);
  if (rate >= SMC_REAL_NULL_MIN)
    return uneven(&c, (int)type, ncomment, npts, real_line, name, err);
  if (!(rate > 0))
    return smc_bad(err, name, real_line, "real header #2 (samples per second)",
                   "expected > 0, got %g", rate);
  if (!(npts >= 1) || npts > (double)(c.n - c.pos) / SMC_WIDTH_MIN + 1)
    return smc_bad(err, name, real_line - 5, "integer header #17 (npts)",
                   "expected 1 to the number of values the file can hold, got %g", npts);
  for (double i = 0; i < ncomment; i++) {
    aq_line ln;
    if (!aq_lines_next(&c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "comments",
                          "expected %g comment lines, the file ends after %g", ncomment, i);
  }
  char what[64];
  if (!data_layout(&c, npts, &fd, what, sizeof what, name, err))
    return err->status;
  aq_raw_channel *ch = aq_raw_add_channel(raw, name, err);
  if (!ch)
    return AQ_ENOMEM;
  ch->npts = (size_t)npts;
  ch->dt_s = 1.0 / rate;
  ch->values = malloc(ch->npts * sizeof *ch->values);
  if (!ch->values) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, c.line, -1, "data", "out of memory");
  }
  aq_line last;
  s = aq_fixed_read_last(&c, ch->npts, &fd, ch->values, name, what, &last, err);
  if (s != AQ_OK) {
    aq_raw_file_free(raw);
    return s;
  }
  /* rows past integer #17: reported for the decision (record.c) */
  aq_extra_rows x;
  aq_extra_rows_scan(&c, &last, aq_fixed_row, &fd, &x);
  aq_raw_set_extra(ch, &x, 1, "integer header #17");
  static const char *const units[5] = {"", "cm/s2", "cm/s2", "cm/s", "cm"};
  snprintf(ch->units, sizeof ch->units, "%s", units[(int)type]);
  if (type == 0) /* converted from another format: the quantity is not stated */
    snprintf(ch->units_said, sizeof ch->units_said, "line 1: data type 0 (UNKNOWN)");
  if (type >= 1) {
    static const int qty[5] = {AQ_QUANTITY_UNSTATED, AQ_QUANTITY_ACCELERATION,
                               AQ_QUANTITY_ACCELERATION, AQ_QUANTITY_VELOCITY,
                               AQ_QUANTITY_DISPLACEMENT};
    char said[48];
    aq_copy_trim(said, sizeof said, text[0].p, text[0].len);
    ch->quantity = qty[(int)type];
    snprintf(ch->quantity_said, sizeof ch->quantity_said, "line 1: data type \"%s\"", said);
    snprintf(ch->units_from, sizeof ch->units_from, "line 1: data type %d", (int)type);
  }
  double from_vertical = iv[12], az = iv[13];
  if (from_vertical == 0 || from_vertical == 180) {
    ch->dip_deg = from_vertical == 0 ? -90 : 90;
    ch->vertical = 1;
  } else if (from_vertical == 90) {
    ch->dip_deg = 0;
    ch->vertical = 0;
    snprintf(ch->orient_said, sizeof ch->orient_said,
             "integer header #13 (angle from vertical): 90");
    if (az != SMC_INT_NULL && az >= 0 && az <= 360)
      ch->azimuth_deg = az;
  }
  const char *comp = aq_find_ci(text[5].p, text[5].len, "component=");
  if (comp) {
    comp += 10;
    aq_copy_trim(ch->channel, sizeof ch->channel, comp,
                 (size_t)(text[5].p + text[5].len - comp));
  }
  aq_copy_trim(ch->station, sizeof ch->station, text[2].p, text[2].len);
  int year = aq_header_int(iv[1]), jday = aq_header_int(iv[2]), mon, day;
  double sec = iv[5] == SMC_INT_NULL ? 0 : iv[5];
  if (iv[6] != SMC_INT_NULL)
    sec += iv[6] * 1e-3;
  if (!aq_month_day(year, jday, &mon, &day) ||
      !aq_iso_time(ch->reference, sizeof ch->reference, year, mon, day, aq_header_int(iv[3]),
                   aq_header_int(iv[4]), sec))
    ch->reference[0] = '\0';
  aq_copy_trim(raw->event, sizeof raw->event, text[3].p, text[3].len);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  aq_copy_trim(raw->processing, sizeof raw->processing, text[0].p + 2, text[0].len - 2);
  snprintf(raw->format, sizeof raw->format, "smc");
  return AQ_OK;
}
