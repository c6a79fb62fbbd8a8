/* asa.c: the Mexican strong-motion database's ASA 2.0 text ("ARCHIVO
 * ESTANDAR DE ACELERACION", reader.h).
 *
 * A header of Spanish "KEY : value" lines (a blank key continues the key
 * above; "===" rules and section titles such as "DATOS DEL SISMO:" carry no
 * value), per-channel values in lists separated by "/" ("/V/N90E/N00E",
 * "/0.004/0.004/0.004"), then "DATOS DE ACELERACION:", a few lines of
 * rulers and channel names ("CANAL-1 CANAL-2 CANAL-3", "V N90E N00E"), and
 * one row per sample with a column per channel.  Two layouts are met: the
 * UNAM one (an institution banner of asterisks first, keys padded to column
 * 39, lists starting with "/") and the CICESE one (no banner, keys of any
 * width, lists without the leading "/"); both are read by key, not by line
 * number.  Keys used (the "C1-C6" lists cover channels 1 to 6; "C1-C3" is
 * taken the same way):
 *   NUMERO DE CANALES                     the channel count
 *   ORIENTACION C1-C6 (rumbo;orientacion) channel names: V (vertical),
 *                                         N90E, N00E, S45W ... (azimuths)
 *   INTERVALO DE MUESTREO, C1-C6 (s)      dt of each channel
 *   VEL. DE MUESTREO, C1-C6 (muestras/s)  samples per second (checked)
 *   NUM. TOTAL DE MUESTRAS, C1-C6         npts of each channel
 *   DURACION DEL REGISTRO (s), C1-C6      npts x dt (checked)
 *   UNIDADES DE LOS DATOS                 "Gal (cm/s/s)"
 *   FORMATO DATOS (FORTRAN,...)           "3F10.3": fields by width
 *   FECHA DEL SISMO [GMT], HORA EPICENTRO (GMT)   the event
 *   HORA DE LA PRIMERA MUESTRA (GMT)      the first sample's time of day;
 *   FECHA DE LA PRIMERA MUESTRA (GMT)     its date when stated, else the
 *                                         date that puts it nearest the
 *                                         origin (a record after midnight)
 *   CLAVE DE LA ESTACION                  the station code
 * Rows past the declared count (the UNAM file repeats its last row) are not
 * read: they are reported (aq_raw_channel's extra_*) for aq_record_decide,
 * which notes copies of the last row and refuses others; fewer rows, or a
 * line after the data that is not a row, are refused.
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

#define ASA_MARKER "ARCHIVO ESTANDAR DE ACELERACION"
#define ASA_SNIFF_LINES 12   /* the marker is looked for this far */
#define ASA_CHAN_MAX 6       /* channels of the C1-C6 lists */
#define ASA_VALUE_MAX 128    /* characters kept of a header value */
#define ASA_NAME_LINES 8     /* lines after "DATOS DE ACELERACION:" before data */
/* DURACION is printed to 0.01 s; npts x dt must agree with it to a sample. */
#define ASA_DT_REL 1e-3      /* INTERVALO against 1 / VEL. DE MUESTREO */
#define ASA_DAY_S 86400.0

int aq_asa_sniff(const unsigned char *buf, size_t n)
{
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  for (int i = 0; i < ASA_SNIFF_LINES && aq_lines_next(&c, &ln); i++)
    if (aq_find_ci(ln.p, ln.len, ASA_MARKER))
      return 1;
  return 0;
}

/* The header as read: the values of the keys used, with their lines. */
typedef struct {
  const char *key; /* prefix of the key, case-insensitive */
  char value[ASA_VALUE_MAX];
  long line; /* 0: not in the file */
} asa_field;

enum {
  F_NCHAN, F_ORIENT, F_DT, F_RATE, F_NPTS, F_DUR, F_UNITS, F_FORMAT, F_EQ_DATE, F_EQ_TIME,
  F_MAG, F_T0, F_D0, F_STATION, F_COUNT
};

static const char *const field_keys[F_COUNT] = {
    "NUMERO DE CANALES",     "ORIENTACION C1",        "INTERVALO DE MUESTREO, C1",
    "VEL. DE MUESTREO, C1",  "NUM. TOTAL DE MUESTRAS, C1",
    "DURACION DEL REGISTRO (s), C1", "UNIDADES DE LOS DATOS", "FORMATO DATOS",
    "FECHA DEL SISMO",         "HORA EPICENTRO",           "MAGNITUD",
    "HORA DE LA PRIMERA MUESTRA", "FECHA DE LA PRIMERA MUESTRA", "CLAVE DE LA ESTACION"};

/* Split a "/a/b/c" or "a/b/c" list into at most max numbers; the count, or
 * -1 when an item is not a number. */
static int number_list(const char *v, double *out, int max)
{
  int k = 0;
  const char *p = v;
  if (*p == '/')
    p++;
  while (*p && k < max) {
    const char *e = strchr(p, '/');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    if (!aq_field_double(p, len, &out[k]))
      return -1;
    k++;
    if (!e)
      break;
    p = e + 1;
  }
  return k;
}

/* The same for words (channel names). */
static int word_list(const char *v, char out[][16], int max)
{
  int k = 0;
  const char *p = v;
  if (*p == '/')
    p++;
  while (*p && k < max) {
    const char *e = strchr(p, '/');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    aq_copy_trim(out[k++], 16, p, len);
    if (!e)
      break;
    p = e + 1;
  }
  return k;
}

/* "N90E" -> 90, "N00E" -> 0, "N45W" -> 315, "S30E" -> 150, "S30W" -> 210:
 * 1 and the azimuth, or 0 when the name is not such a direction. */
static int direction_deg(const char *s, double *az)
{
  char a = (char)toupper((unsigned char)s[0]);
  size_t n = strlen(s);
  if (n < 3 || (a != 'N' && a != 'S'))
    return 0;
  char b = (char)toupper((unsigned char)s[n - 1]);
  if (b != 'E' && b != 'W')
    return 0;
  double d;
  if (!aq_field_double(s + 1, n - 2, &d) || d < 0 || d > 90)
    return 0;
  double v = a == 'N' ? (b == 'E' ? d : 360 - d) : (b == 'E' ? 180 - d : 180 + d);
  *az = fmod(v, 360);
  return 1;
}

/* "2004/01/01" -> year, month, day: 1 or 0. */
static int ymd(const char *s, int *y, int *m, int *d)
{
  return sscanf(s, "%d/%d/%d", y, m, d) == 3 || sscanf(s, "%d-%d-%d", y, m, d) == 3;
}

/* "23:58:02.7" -> seconds of the day: 1 or 0. */
static int hms(const char *s, double *sec)
{
  int h, mi;
  double x;
  if (sscanf(s, "%d:%d:%lf", &h, &mi, &x) != 3 || h < 0 || h > 23 || mi < 0 || mi > 59 ||
      !(x >= 0 && x < 61))
    return 0;
  *sec = h * 3600.0 + mi * 60.0 + x;
  return 1;
}

/* Epoch seconds of a date at midnight UTC: 1 or 0. */
static int day_epoch(int y, int m, int d, double *out)
{
  char iso[40];
  return aq_iso_time(iso, sizeof iso, y, m, d, 0, 0, 0) && aq_iso_parse(iso, out);
}

/* The first sample's time, ISO-8601 UTC, into out ("" when not stated). */
static void start_time(const asa_field *f, char *out, size_t cap)
{
  out[0] = '\0';
  double t0, day, eq_day, eq_t;
  int y, m, d;
  if (!f[F_T0].line || !hms(f[F_T0].value, &t0))
    return;
  if (f[F_D0].line && ymd(f[F_D0].value, &y, &m, &d)) {
    if (!day_epoch(y, m, d, &day))
      return;
  } else if (f[F_EQ_DATE].line && ymd(f[F_EQ_DATE].value, &y, &m, &d) &&
             day_epoch(y, m, d, &eq_day)) {
    /* the date that puts the first sample nearest the origin */
    day = eq_day;
    if (f[F_EQ_TIME].line && hms(f[F_EQ_TIME].value, &eq_t)) {
      double origin = eq_day + eq_t;
      for (int k = -1; k <= 1; k++)
        if (fabs(eq_day + k * ASA_DAY_S + t0 - origin) < fabs(day + t0 - origin))
          day = eq_day + k * ASA_DAY_S;
    }
  } else {
    return;
  }
  if (!aq_iso_from_ms(out, cap, llround((day + t0) * 1000.0)))
    out[0] = '\0';
}

static aq_status bad(aq_error *err, const char *name, long line, const char *field,
                     const char *expected, const char *got)
{
  return aq_error_set(err, AQ_EFORMAT, name, line, -1, field, "expected %s, got \"%s\"",
                      expected, got);
}

/* One data row: nchan fields, by width w when w > 0, else blank-separated. */
static int row_fields(const aq_line *ln, int nchan, int w, double *out);

/* A row past the count (aq_extra_rows_scan): ctx holds nchan and the width. */
typedef struct {
  int nchan, width;
} row_shape;

static size_t extra_row(const aq_line *ln, const void *ctx)
{
  const row_shape *r = ctx;
  double v[ASA_CHAN_MAX];
  return row_fields(ln, r->nchan, r->width, v) ? 1 : 0;
}

static int row_fields(const aq_line *ln, int nchan, int w, double *out)
{
  if (w > 0) {
    for (int j = 0; j < nchan; j++) {
      size_t b = (size_t)j * (size_t)w;
      if (b >= ln->len)
        return 0;
      size_t e = b + (size_t)w < ln->len ? b + (size_t)w : ln->len;
      if (!aq_field_double(ln->p + b, e - b, &out[j]))
        return 0;
    }
    for (size_t i = (size_t)nchan * (size_t)w; i < ln->len; i++)
      if (ln->p[i] != ' ' && ln->p[i] != '\t')
        return 0;
    return 1;
  }
  const char *p = ln->p, *end = ln->p + ln->len;
  for (int j = 0; j < nchan; j++) {
    size_t len = aq_next_word(&p, end, "\t");
    if (len == 0 || !aq_field_double(p, len, &out[j]))
      return 0;
    p += len;
  }
  while (p < end && (*p == ' ' || *p == '\t'))
    p++;
  return p == end;
}

aq_status aq_asa_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  asa_field f[F_COUNT];
  for (int i = 0; i < F_COUNT; i++) {
    f[i].key = field_keys[i];
    f[i].value[0] = '\0';
    f[i].line = 0;
  }
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  int marker = 0, data = 0;
  while (!data && aq_lines_next(&c, &ln)) {
    if (aq_find_ci(ln.p, ln.len, ASA_MARKER))
      marker = 1;
    if (!marker && ln.line >= ASA_SNIFF_LINES)
      break;
    const char *colon = memchr(ln.p, ':', ln.len);
    if (!colon)
      continue;
    size_t klen = (size_t)(colon - ln.p);
    if (aq_find_ci(ln.p, klen, "DATOS DE ACELERACION")) {
      data = 1;
      break;
    }
    for (int i = 0; i < F_COUNT; i++) {
      size_t m = strlen(f[i].key);
      const char *k = ln.p;
      while (k < colon && *k == ' ')
        k++;
      if (!f[i].line && (size_t)(colon - k) >= m && strncasecmp(k, f[i].key, m) == 0) {
        aq_copy_trim(f[i].value, sizeof f[i].value, colon + 1,
                     (size_t)(ln.p + ln.len - colon - 1));
        f[i].line = ln.line;
        break;
      }
    }
  }
  if (!marker || !data)
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "header",
                        "expected an ASA 2.0 header (\"" ASA_MARKER "\") ending with "
                        "\"DATOS DE ACELERACION:\", %s",
                        marker ? "the file ends before the data" : "found no such line");
  /* channels */
  double nchan_d = 0;
  if (!f[F_NCHAN].line || !aq_field_double(f[F_NCHAN].value, strlen(f[F_NCHAN].value), &nchan_d) ||
      nchan_d < 1 || nchan_d > ASA_CHAN_MAX || nchan_d != floor(nchan_d))
    return bad(err, name, f[F_NCHAN].line, "NUMERO DE CANALES", "1 to 6", f[F_NCHAN].value);
  int nchan = (int)nchan_d;
  char names[ASA_CHAN_MAX][16];
  double dt[ASA_CHAN_MAX], rate[ASA_CHAN_MAX], npts[ASA_CHAN_MAX], dur[ASA_CHAN_MAX];
  if (word_list(f[F_ORIENT].value, names, ASA_CHAN_MAX) < nchan)
    return bad(err, name, f[F_ORIENT].line, "ORIENTACION C1-C6",
               "a name for each channel (/V/N90E/N00E)", f[F_ORIENT].value);
  if (number_list(f[F_DT].value, dt, ASA_CHAN_MAX) < nchan)
    return bad(err, name, f[F_DT].line, "INTERVALO DE MUESTREO",
               "a sample interval for each channel (/0.004/0.004/0.004)", f[F_DT].value);
  if (number_list(f[F_NPTS].value, npts, ASA_CHAN_MAX) < nchan)
    return bad(err, name, f[F_NPTS].line, "NUM. TOTAL DE MUESTRAS",
               "a count for each channel (/17500/17500/17500)", f[F_NPTS].value);
  int nrate = f[F_RATE].line ? number_list(f[F_RATE].value, rate, ASA_CHAN_MAX) : 0;
  int ndur = f[F_DUR].line ? number_list(f[F_DUR].value, dur, ASA_CHAN_MAX) : 0;
  size_t rows = 0;
  for (int j = 0; j < nchan; j++) {
    char got[48];
    if (!(dt[j] > 0) || !isfinite(1.0 / dt[j])) {
      snprintf(got, sizeof got, "%g", dt[j]);
      return bad(err, name, f[F_DT].line, "INTERVALO DE MUESTREO", "> 0 s", got);
    }
    if (!(npts[j] >= 1) || npts[j] != floor(npts[j]) || npts[j] > (double)n) {
      snprintf(got, sizeof got, "%g", npts[j]);
      return bad(err, name, f[F_NPTS].line, "NUM. TOTAL DE MUESTRAS",
                 "a whole count >= 1 that the file can hold", got);
    }
    if (j < nrate && fabs(rate[j] * dt[j] - 1) > ASA_DT_REL)
      return aq_error_set(err, AQ_EFORMAT, name, f[F_RATE].line, -1, "VEL. DE MUESTREO",
                          "channel %d: expected 1 / %g s (INTERVALO DE MUESTREO), got %g "
                          "samples/s",
                          j + 1, dt[j], rate[j]);
    if (j < ndur && fabs(npts[j] * dt[j] - dur[j]) > dt[j])
      return aq_error_set(err, AQ_EFORMAT, name, f[F_DUR].line, -1, "DURACION DEL REGISTRO",
                          "channel %d: expected %.0f samples x %g s = %g s, got %g s", j + 1,
                          npts[j], dt[j], npts[j] * dt[j], dur[j]);
    if ((size_t)npts[j] > rows)
      rows = (size_t)npts[j];
  }
  /* units */
  char units[24] = "";
  {
    const char *v = f[F_UNITS].value;
    const char *p = v;
    size_t len = aq_next_word(&p, v + strlen(v), "(");
    char word[24];
    aq_copy_trim(word, sizeof word, p, len);
    const char *par = strchr(v, '(');
    char inner[24] = "";
    if (par) {
      const char *e = strchr(par, ')');
      aq_copy_trim(inner, sizeof inner, par + 1, e ? (size_t)(e - par - 1) : strlen(par + 1));
    }
    aq_units u;
    if (aq_units_parse(word, &u) || aq_units_parse(inner, &u))
      snprintf(units, sizeof units, "%s", aq_units_name(u));
  }
  /* the data's format: "3F10.3" -> fields of 10 columns */
  int width = 0;
  if (f[F_FORMAT].line) {
    char tmp[ASA_VALUE_MAX + 2];
    snprintf(tmp, sizeof tmp, "(%s)", f[F_FORMAT].value);
    aq_fortran_fmt ff;
    if (!aq_fortran_fmt_find(tmp, strlen(tmp), &ff) || ff.kind == 'I' || ff.per_line != nchan)
      return bad(err, name, f[F_FORMAT].line, "FORMATO DATOS",
                 "a Fortran format with a field per channel (3F10.3)", f[F_FORMAT].value);
    width = ff.width;
  }
  /* the data: the first line that is a row of numbers, within a few lines */
  double v[ASA_CHAN_MAX];
  int found = 0;
  for (int i = 0; i < ASA_NAME_LINES && aq_lines_next(&c, &ln); i++)
    if ((found = row_fields(&ln, nchan, width, v)))
      break;
  if (!found)
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "data",
                        "expected rows of %d values%s%s within %d lines of \"DATOS DE "
                        "ACELERACION:\"",
                        nchan, width ? " in " : "", width ? f[F_FORMAT].value : "",
                        ASA_NAME_LINES);
  aq_status s = aq_raw_file_alloc(raw, (size_t)nchan, name, err);
  if (s != AQ_OK)
    return s;
  char start[40];
  start_time(f, start, sizeof start);
  for (int j = 0; j < nchan; j++) {
    aq_raw_channel *ch = &raw->chan[j];
    ch->npts = (size_t)npts[j];
    ch->dt_s = dt[j];
    ch->values = malloc(ch->npts * sizeof *ch->values);
    if (!ch->values) {
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_ENOMEM, name, -1, -1, "data", "out of memory");
    }
    snprintf(ch->channel, sizeof ch->channel, "%.15s", names[j]);
    snprintf(ch->units, sizeof ch->units, "%s", units);
    if (!units[0])
      snprintf(ch->units_said, sizeof ch->units_said, "UNIDADES DE LOS DATOS: %.40s",
               f[F_UNITS].value);
    ch->units_line = f[F_UNITS].line;
    snprintf(ch->reference, sizeof ch->reference, "%s", start);
    aq_copy_trim(ch->station, sizeof ch->station, f[F_STATION].value,
                 strlen(f[F_STATION].value));
    double az;
    if (strcasecmp(names[j], "V") == 0) {
      ch->vertical = 1;
    } else if (direction_deg(names[j], &az)) {
      ch->vertical = 0;
      ch->dip_deg = 0;
      ch->azimuth_deg = az;
    }
  }
  size_t k = 0;
  long first_row = ln.line;
  for (;;) {
    for (int j = 0; j < nchan; j++)
      if (k < raw->chan[j].npts)
        raw->chan[j].values[k] = v[j];
    if (++k == rows)
      break;
    if (!aq_lines_next(&c, &ln) || !row_fields(&ln, nchan, width, v)) {
      long at = c.line - 1;
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_EFORMAT, name, at, -1, "data",
                          "expected %zu rows of %d values (NUM. TOTAL DE MUESTRAS) from line "
                          "%ld, %s after %zu",
                          rows, nchan, first_row,
                          aq_lines_at_end(&c) ? "the file ends" : "a row that is not", k);
    }
  }
  row_shape shape = {nchan, width};
  aq_status rs = aq_raw_rows_end(&c, &ln, extra_row, &shape, rows, "NUM. TOTAL DE MUESTRAS",
                                 raw, name, err);
  if (rs != AQ_OK)
    return rs;
  snprintf(raw->event, sizeof raw->event, "%.12s %.16s %.60s", f[F_EQ_DATE].value,
           f[F_EQ_TIME].value, f[F_MAG].value);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  snprintf(raw->format, sizeof raw->format, "asa");
  return AQ_OK;
}
