/* csv.c: CSV / plain-text reader (see reader.h).
 *
 * Rows of numbers separated by ';', ',', tab or blanks (decided by the first
 * data row: ';' if it has one, else ',', else tab, else blanks; with ';' a
 * decimal comma is accepted).  Blank lines and '#' comments are skipped, line
 * ends may be LF, CRLF or CR.  Lines before the first data row form a
 * preamble: "SAMPLING RATE= 100Hz" (or "SAMPLING FREQ"), "DT = 0.01" and
 * "UNIT = gal(cm/s/s)" are understood there, and the line just before the
 * data, if it has as many fields as the data, names the columns ("time,acc
 * (g)", "t,acc_g", "NS,EW,UD").
 *
 * Columns: a column named t/time/sec/seconds (zeit, tiempo, temps) is the time; without a header,
 * two or more columns and no dt known mean (time, acceleration...).  The
 * acceleration is column opts->column (1-based) or the first column that is
 * not time.  Times must be evenly spaced: each step within CSV_TIME_TOL_REL
 * of the median step, and each time within CSV_TIME_TOL_REL of a step of
 * t_0 + k dt, dt = (t_last - t_0) / (n - 1); they need not start at 0
 * (begin_s = t_0).
 *
 * Channels: --column N alone, else every named column that is not time and
 * does not name units other than acceleration ("NS,EW,UD": three channels),
 * else the first column that is not time.
 *
 * Units stated: those of the column name ("acc (g)", "acc_g", "a [cm/s2]"),
 * else the preamble's UNIT line, else none (record.c decides).
 *
 * Start: JMA's "INITIAL TIME = 2016 04 14 21 26 20" (Japan Standard Time,
 * UTC+9) and CWB's "#StartTime(GMT+08): 2018/02/06-23:50:29.000" (the zone
 * stated) are the time of the first row, reported in UTC (begin_s 0); a
 * time that does not parse is reported as unknown ("").
 *
 * The data rows and the time column's steps are read in csv_rows.c, the
 * words (units, quantities, times, keys, channel names) in csv_names.c;
 * csv_impl.h is what the three share.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "csv_impl.h"
#include "fixed.h"
#include "number.h"
#include "reader.h"
#include "units.h"

/* Each time t_k must lie within this fraction of dt of t_0 + k dt (text
 * times are rounded to a few decimals; 1 % of dt tolerates that and still
 * catches a missing or repeated sample). */
#define CSV_TIME_TOL_REL 0.01
/* The step from a time column, (t_last - t_0) / (n - 1), is rounded to this
 * many significant digits (removes binary noise: 31.18 / 1559 -> 0.02). */
#define CSV_DT_SIG_DIGITS 9

/* Next line [*b, *e) (without its end), or 0 at the end of the input. */
/* Next line [*b, *e) (without its end), or 0 at the end of the input. */
static int next_line(csv_cur *c, size_t *b, size_t *e)
{
  if (!aq_text_line(c->s, c->n, &c->pos, b, e))
    return 0;
  c->line++;
  return 1;
}

/* isspace() of the C locale, without the library call. */
int aq_csv_is_space(char c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Strip a '#' comment and surrounding blanks. */
void aq_csv_trim_line(const char *s, size_t *b, size_t *e)
{
  for (size_t i = *b; i < *e; i++)
    if (s[i] == '#') {
      *e = i;
      break;
    }
  while (*b < *e && aq_csv_is_space(s[*b]))
    (*b)++;
  while (*e > *b && aq_csv_is_space(s[*e - 1]))
    (*e)--;
}

static char pick_sep(const char *s, size_t b, size_t e)
{
  if (memchr(s + b, ';', e - b))
    return ';';
  if (memchr(s + b, ',', e - b))
    return ',';
  if (memchr(s + b, '\t', e - b))
    return '\t';
  return ' ';
}

/* Split [b, e) at sep (' ' = runs of blanks/tabs).  Fields are trimmed and
 * stripped of double quotes.  Writes at most max fields; returns the count
 * (which may exceed max). */
typedef struct {
  size_t b, e;
} span;

static size_t split(const char *s, size_t b, size_t e, char sep, span *f, size_t max)
{
  size_t k = 0, i = b;
  if (b >= e)
    return 0;
  for (;;) {
    size_t fb = i, fe;
    if (sep == ' ') {
      while (i < e && s[i] != ' ' && s[i] != '\t')
        i++;
      fe = i;
      while (i < e && (s[i] == ' ' || s[i] == '\t'))
        i++;
    } else {
      while (i < e && s[i] != sep)
        i++;
      fe = i;
      if (i < e)
        i++;
    }
    while (fb < fe && aq_csv_is_space(s[fb]))
      fb++;
    while (fe > fb && aq_csv_is_space(s[fe - 1]))
      fe--;
    if (fe - fb >= 2 && s[fb] == '"' && s[fe - 1] == '"')
      fb++, fe--;
    if (k < max)
      f[k].b = fb, f[k].e = fe;
    k++;
    if (i >= e) {
      if (sep != ' ' && e > b && s[e - 1] == sep) { /* trailing empty field */
        if (k < max)
          f[k].b = f[k].e = e;
        k++;
      }
      break;
    }
  }
  return k;
}

/* A field as a number: 1 finite, 2 NaN/Inf, 0 not a number. */
static int field_num(const char *s, span f, int decimal_comma, double *x)
{
  char tok[CSV_FIELD_MAX];
  size_t len = f.e - f.b;
  if (!decimal_comma && len > 0 && s[f.b] != ' ' && s[f.b] != '\t') {
    double v; /* plain decimals: the fast parser (same double as strtod) */
    if (aq_decimal_parse(s + f.b, len, &v) == len) {
      *x = v;
      return isfinite(v) ? 1 : 2;
    }
  }
  if (len == 0 || len >= sizeof tok)
    return 0;
  for (size_t i = 0; i < len; i++) {
    char ch = s[f.b + i];
    if (ch == '\0')
      return 0;
    tok[i] = (decimal_comma && ch == ',') ? '.' : ch;
  }
  tok[len] = '\0';
  /* hexadecimal floats are not numbers here */
  for (size_t i = 0; i < len; i++)
    if (tok[i] == 'x' || tok[i] == 'X' || tok[i] == 'p' || tok[i] == 'P')
      return 0;
  char *end;
  errno = 0;
  double v = strtod(tok, &end);
  if (end == tok || *end)
    return 0;
  *x = v;
  return isfinite(v) ? 1 : 2;
}

static void copy_field(const char *s, span f, char *out, size_t cap)
{
  size_t k = 0;
  for (size_t i = f.b; i < f.e && k + 1 < cap; i++)
    out[k++] = isprint((unsigned char)s[i]) ? s[i] : '?';
  out[k] = '\0';
}

/* aq_csv_parse; with columns_only, *columns_only gets the count of
 * channels once the columns are known, and the rows are not read (raw stays
 * empty). */
static aq_status csv_parse(const unsigned char *buf, size_t n, const char *name,
                           const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err,
                           size_t *columns_only)
{
  memset(raw, 0, sizeof *raw);
  csv_cur c = {(const char *)buf, n, 0, 0};
  const char *s = c.s;
  if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0) /* UTF-8 byte-order mark */
    c.pos = 3;
  size_t b, e;
  enum { MAXF = CSV_COLS_MAX };
  span f[MAXF];
  double x;

  /* Preamble. */
  double pre_dt = 0;
  int pre_units = 0; /* 1 acceleration units stated, -1 other units */
  aq_units pre_u = AQ_UNITS_FILE;
  long pre_line = -1;
  char pre_said[48] = "";
  char start[40] = "";         /* the first row's time, ISO-8601 UTC, if stated */
  char event[96] = "";         /* CWB's "#Origin Time(GMT+08): ...": the event */
  size_t seq_b = 0, seq_e = 0; /* a "#DataSequence:" list of column names */
  long seq_line = -1;
  size_t hb = 0, he = 0; /* last non-numeric line before the data */
  long hline = -1;
  char sep = 0;
  int dcomma = 0;
  size_t ncols = 0;
  size_t first_pos = 0; /* where the first row's line starts */
  for (;;) {
    first_pos = c.pos;
    if (!next_line(&c, &b, &e))
      return aq_error_set(err, AQ_EFORMAT, name, -1, -1, NULL,
                          "expected rows of numbers (time, acceleration or "
                          "acceleration only), found none in %ld lines",
                          c.line);
    if (b < e && s[b] == '#') { /* CWB: "#AmplitudeUnit: gal.", "#DataSequence: Time U(+); N(+)" */
      const char *v;
      if ((v = aq_csv_kv(s, b + 1, e, "AmplitudeUnit"))) {
        char val[CSV_NAME_MAX];
        copy_field(s, (span){(size_t)(v - s), e}, val, sizeof val);
        val[strcspn(val, " \t")] = '\0';
        size_t l = strlen(val);
        if (l > 0 && val[l - 1] == '.')
          val[l - 1] = '\0';
        int r = aq_csv_units_in(val, &pre_u);
        pre_units = r > 0 ? 1 : r < 0 ? -1 : 0;
        pre_line = c.line;
        snprintf(pre_said, sizeof pre_said, "%.40s", val);
      } else if ((v = aq_csv_kv(s, b + 1, e, "DataSequence"))) {
        seq_b = (size_t)(v - s), seq_e = e, seq_line = c.line;
      } else if (e - b > 11 && strncasecmp(s + b + 1, "Origin Time", 11) == 0) {
        size_t l = e - b - 1 < sizeof event - 1 ? e - b - 1 : sizeof event - 1;
        memcpy(event, s + b + 1, l);
        event[l] = '\0';
      } else {
        aq_csv_cwb_start(s, b + 1, e, start, sizeof start);
      }
    }
    aq_csv_trim_line(s, &b, &e);
    if (b == e)
      continue;
    char sp = pick_sep(s, b, e);
    size_t nf = split(s, b, e, sp, f, MAXF);
    int numeric = nf > 0 && nf <= MAXF, dc = 0;
    for (size_t i = 0; numeric && i < nf; i++)
      numeric = field_num(s, f[i], 0, &x) != 0;
    if (!numeric && sp == ';' && nf <= MAXF) { /* decimal comma? */
      numeric = nf > 0;
      for (size_t i = 0; numeric && i < nf; i++)
        numeric = field_num(s, f[i], 1, &x) != 0;
      dc = numeric;
    }
    if (numeric) {
      sep = sp;
      dcomma = dc;
      ncols = nf;
      break;
    }
    const char *v;
    char val[CSV_NAME_MAX];
    if ((v = aq_csv_kv(s, b, e, "SAMPLING RATE")) || (v = aq_csv_kv(s, b, e, "SAMPLING FREQ"))) {
      char tmp[CSV_FIELD_MAX];
      copy_field(s, (span){(size_t)(v - s), e}, tmp, sizeof tmp);
      double hz = strtod(tmp, NULL);
      if (!(hz > 0) || !isfinite(hz))
        return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "SAMPLING RATE",
                            "expected a rate > 0 Hz, got \"%s\"", tmp);
      pre_dt = 1.0 / hz;
    } else if ((v = aq_csv_kv(s, b, e, "DT")) || (v = aq_csv_kv(s, b, e, "DELTA"))) {
      char tmp[CSV_FIELD_MAX];
      copy_field(s, (span){(size_t)(v - s), e}, tmp, sizeof tmp);
      double d = strtod(tmp, NULL);
      if (!(d > 0) || !isfinite(d))
        return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "DT",
                            "expected a sample interval > 0 s, got \"%s\"", tmp);
      pre_dt = d;
    } else if ((v = aq_csv_kv(s, b, e, "INITIAL TIME"))) {
      if (!aq_csv_jma_start(v, s + e, start, sizeof start))
        start[0] = '\0';
    } else if ((v = aq_csv_kv(s, b, e, "UNITS")) || (v = aq_csv_kv(s, b, e, "UNIT"))) {
      copy_field(s, (span){(size_t)(v - s), e}, val, sizeof val);
      int r = aq_csv_units_in(val, &pre_u);
      pre_units = r > 0 ? 1 : r < 0 ? -1 : 0;
      pre_line = c.line;
      snprintf(pre_said, sizeof pre_said, "%.40s", val);
    } else {
      hb = b, he = e, hline = c.line; /* may name the columns */
    }
  }
  long first_line = c.line;
  size_t first_b = b, first_e = e;
  if (ncols > MAXF)
    return aq_error_set(err, AQ_EUNSUPPORTED, name, first_line, -1, NULL,
                        "expected at most %d columns, got %zu", MAXF, ncols);

  /* Column names: the line just before the data, if it has as many fields. */
  char names[MAXF][CSV_NAME_MAX];
  int have_names = 0;
  if (hline > 0) {
    span hf[MAXF];
    char hsep = sep == ' ' ? pick_sep(s, hb, he) : sep;
    size_t hnf = split(s, hb, he, hsep, hf, MAXF);
    if (hsep == ' ' && hnf <= MAXF) { /* "acc (g)": units belong to the name */
      size_t m = 0;
      for (size_t i = 0; i < hnf; i++)
        if (m > 0 && (s[hf[i].b] == '(' || s[hf[i].b] == '['))
          hf[m - 1].e = hf[i].e;
        else
          hf[m++] = hf[i];
      hnf = m;
    }
    if (hnf == ncols) {
      have_names = 1;
      for (size_t i = 0; i < ncols; i++)
        copy_field(s, hf[i], names[i], CSV_NAME_MAX);
    }
  }
  if (!have_names && seq_line > 0) { /* "Time U(+); N(+); E(+)" */
    span hf[MAXF];
    size_t hnf = split(s, seq_b, seq_e, ' ', hf, MAXF);
    if (hnf == ncols) {
      have_names = 1;
      hline = seq_line;
      for (size_t i = 0; i < ncols; i++) {
        copy_field(s, hf[i], names[i], CSV_NAME_MAX);
        names[i][strcspn(names[i], ";(")] = '\0';
      }
    }
  }

  /* Which column is time, which is acceleration. */
  /* the file's DT over --dt, which is for files that state none */
  double dt_known = pre_dt > 0 ? pre_dt : opts && opts->dt_s > 0 ? opts->dt_s : 0;
  long tcol = -1;
  if (have_names) {
    for (size_t i = 0; i < ncols; i++)
      if (aq_csv_is_time_name(names[i])) {
        tcol = (long)i;
        break;
      }
  } else if (ncols >= 2 && !(dt_known > 0)) {
    tcol = 0;
  }
  /* The acceleration columns (channels): --column N, else every named
   * column that is not time and does not name other units, else the first
   * column that is not time. */
  size_t chcol[MAXF], nch = 0;
  if (opts && opts->column > 0) {
    if (opts->column > ncols)
      return aq_error_set(err, AQ_EOPTION, name, first_line, -1, "--column",
                          "expected a column in 1..%zu, got %zu", ncols, opts->column);
    if ((long)opts->column - 1 == tcol)
      return aq_error_set(err, AQ_EOPTION, name, first_line, -1, "--column",
                          "expected an acceleration column, got %zu (the time)",
                          opts->column);
    chcol[nch++] = opts->column - 1;
  } else {
    if (have_names)
      for (size_t i = 0; i < ncols; i++) {
        aq_units cu;
        if ((long)i != tcol && aq_csv_units_in(names[i], &cu) >= 0)
          chcol[nch++] = i;
      }
    if (nch == 0) {
      chcol[nch++] = tcol == 0 ? 1 : 0;
      if (chcol[0] >= ncols)
        return aq_error_set(err, AQ_EFORMAT, name, first_line, -1, NULL,
                            "expected an acceleration column beside the time, "
                            "got %zu column",
                            ncols);
    }
  }
  if (tcol < 0 && !(dt_known > 0))
    return aq_error_set(err, AQ_EFORMAT, name, first_line, -1, "dt",
                        "no time column and no sample interval: give --dt S "
                        "(or a time column, or a \"SAMPLING RATE= N Hz\" line)");
  int chof[MAXF]; /* column -> channel index, or -1 */
  for (size_t i = 0; i < MAXF; i++)
    chof[i] = -1;
  for (size_t j = 0; j < nch; j++)
    chof[chcol[j]] = (int)j;
  if (columns_only) {
    *columns_only = nch;
    return AQ_OK;
  }

  /* Rows: as many as the rest holds at the first row's length, plus a
   * quarter; the arrays grow if more come. */
  csv_rows rows = {raw, NULL, 0};
  size_t row_bytes = first_e - first_b + 1;
  size_t cap = (n - first_b) / row_bytes + (n - first_b) / row_bytes / 16 + 16;
  aq_status st = aq_raw_file_alloc(raw, nch, name, err);
  if (st != AQ_OK)
    return st;
  if (!aq_csv_rows_grow(&rows, cap, tcol >= 0)) {
    aq_csv_rows_free_time(&rows);
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  }
  size_t k = 0;
  b = first_b, e = first_e;
  long line = first_line;
  aq_number_shape shape[MAXF];
  for (size_t i = 0; i < ncols; i++)
    shape[i].len = 0, shape[i].misses = 0;
  const plain_row pr = {ncols, sep, tcol, chof, shape};
  for (;;) {
    if (k >= rows.cap && !aq_csv_rows_grow(&rows, 2 * rows.cap, tcol >= 0)) {
      st = aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
      break;
    }
    double *tt = rows.tt;
    size_t nf = split(s, b, e, sep, f, MAXF);
    if (nf != ncols) {
      st = aq_error_set(err, AQ_EFORMAT, name, line, -1, NULL,
                        "expected %zu fields like line %ld, got %zu", ncols,
                        first_line, nf);
      break;
    }
    for (size_t i = 0; i < nf && st == AQ_OK; i++) {
      int r = field_num(s, f[i], dcomma, &x);
      if (r == 1) {
        if (chof[i] >= 0)
          raw->chan[chof[i]].values[k] = x;
        if ((long)i == tcol)
          tt[k] = x;
        continue;
      }
      char fld[CSV_NAME_MAX + 16], got[CSV_FIELD_MAX];
      if (have_names)
        snprintf(fld, sizeof fld, "column %zu (%s)", i + 1, names[i]);
      else
        snprintf(fld, sizeof fld, "column %zu", i + 1);
      copy_field(s, f[i], got, sizeof got);
      st = aq_error_set(err, r == 2 ? AQ_EVALUE : AQ_EFORMAT, name, line, -1, fld,
                          "expected a %snumber, got \"%s\"", r == 2 ? "finite " : "",
                          got);
    }
    if (st != AQ_OK)
      break;
    k++;
    if (!dcomma) /* the rows that follow, while they are plain */
      k = aq_csv_plain_rows(&c, &pr, &rows, k);
    int more = 0;
    while (next_line(&c, &b, &e)) {
      aq_csv_trim_line(s, &b, &e);
      if (b < e) {
        more = 1;
        break;
      }
    }
    if (!more)
      break;
    line = c.line;
  }
  double *tt = rows.tt;

  double dt = dt_known, begin = 0;
  if (st == AQ_OK && tcol >= 0) {
    if (k < 2) {
      st = aq_error_set(err, AQ_EFORMAT, name, first_line, -1, "time",
                        "expected at least 2 rows to find the step, got %zu", k);
    } else {
      double est = (tt[k - 1] - tt[0]) / (double)(k - 1);
      char txt[40];
      snprintf(txt, sizeof txt, "%.*e", CSV_DT_SIG_DIGITS - 1, est);
      dt = strtod(txt, NULL);
      begin = tt[0];
      if (!(dt > 0) || !isfinite(dt)) {
        st = aq_error_set(err, AQ_EFORMAT, name,
                          aq_csv_row_line(s, n, first_pos, first_line, k - 1), -1, "time",
                          "expected increasing times, got %.9g after %.9g at "
                          "line %ld",
                          tt[k - 1], tt[0], first_line);
      } else {
        /* a step that is off (a missing or repeated row) is named at its
         * line; then a slow drift of the times is caught cumulatively */
        double lo, hi;
        size_t off = aq_csv_step_range(tt, k, est, CSV_TIME_TOL_REL * est, &lo, &hi);
        /* The median step lies in [lo, hi]: when hi - lo <= tol * lo, no
         * step is farther than tol * median from it (the differences of
         * steps so close are exact), and the median is not needed. */
        int even = lo > 0 && hi - lo <= CSV_TIME_TOL_REL * lo;
        double med = even ? lo : aq_csv_median_step(tt, k);
        if (isnan(med))
          st = aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
        for (size_t i = 1; i < k && st == AQ_OK && !even; i++)
          if (fabs(tt[i] - tt[i - 1] - med) > CSV_TIME_TOL_REL * med)
            st = aq_error_set(
                err, AQ_EFORMAT, name, aq_csv_row_line(s, n, first_pos, first_line, i), -1, "time",
                "expected evenly spaced times (step %.9g s within %g %%), got a "
                "step of %.9g s from %.15g to %.15g",
                med, 100 * CSV_TIME_TOL_REL, tt[i] - tt[i - 1], tt[i - 1], tt[i]);
        if (off && st == AQ_OK) {
          size_t i = off;
          st = aq_error_set(
                err, AQ_EFORMAT, name, aq_csv_row_line(s, n, first_pos, first_line, i), -1, "time",
                "expected evenly spaced times (%.15g + k * %.9g s, within %g %% of "
                "the step), got %.15g for sample %zu",
                tt[0], dt, 100 * CSV_TIME_TOL_REL, tt[i], i);
        }
      }
    }
  }
  free(tt);
  if (st == AQ_OK && k == 0)
    st = aq_error_set(err, AQ_EFORMAT, name, first_line, -1, NULL,
                      "expected at least one row of numbers, got none");
  if (st != AQ_OK) {
    aq_raw_file_free(raw);
    return st;
  }
  snprintf(raw->format, sizeof raw->format, "csv");
  snprintf(raw->event, sizeof raw->event, "%s", event);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", event); /* the event alone */
  for (size_t j = 0; j < nch; j++) {
    aq_raw_channel *ch = &raw->chan[j];
    size_t col = chcol[j];
    ch->npts = k;
    ch->dt_s = dt;
    ch->begin_s = start[0] ? 0 : begin; /* a stated start is the first row's time */
    snprintf(ch->reference, sizeof ch->reference, "%s", start);
    aq_units cu;
    int r = have_names ? aq_csv_units_in(names[col], &cu) : 0;
    if (have_names)
      aq_csv_channel_name(names[col], ch->channel, sizeof ch->channel);
    if (r > 0) {
      snprintf(ch->units, sizeof ch->units, "%s", aq_units_name(cu));
      ch->units_line = hline;
    } else if (r < 0) {
      snprintf(ch->units_said, sizeof ch->units_said, "line %ld: column \"%.40s\"",
               hline, names[col]);
      ch->quantity = (int)aq_csv_quantity_in(names[col]);
      snprintf(ch->quantity_said, sizeof ch->quantity_said, "%s", ch->units_said);
    } else if (pre_units > 0) {
      snprintf(ch->units, sizeof ch->units, "%s", aq_units_name(pre_u));
      ch->units_line = pre_line;
    } else if (pre_units < 0) {
      snprintf(ch->units_said, sizeof ch->units_said, "line %ld: UNIT = %s",
               pre_line, pre_said);
      ch->quantity = (int)aq_csv_quantity_in(pre_said);
      snprintf(ch->quantity_said, sizeof ch->quantity_said, "%s", ch->units_said);
    }
  }
  return AQ_OK;
}

aq_status aq_csv_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  return csv_parse(buf, n, name, opts, raw, err, NULL);
}

aq_status aq_csv_channels(const unsigned char *buf, size_t n, const char *name,
                          const aq_reader_opts *opts, size_t *nchan, aq_error *err)
{
  aq_raw_file none;
  *nchan = 0;
  return csv_parse(buf, n, name, opts, &none, err, nchan);
}
