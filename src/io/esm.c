/* esm.c: ESM / ITACA ASCII (the "DYNA 1.x" header) (reader.h).
 *
 * Layout: "KEY: value" header lines (about 64, some values empty), then
 * NDATA values, one per line (blank-separated values on a line are taken
 * too).  Keys read: EVENT_ID, EVENT_NAME, NETWORK, STATION_CODE, LOCATION,
 * STREAM (the channel), UNITS (e.g. "cm/s^2"), DATA_TYPE (ACCELERATION,
 * VELOCITY, DISPLACEMENT), SAMPLING_INTERVAL_S, NDATA,
 * DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS ("20190728_160905.700"), and the
 * processing keys BASELINE_CORRECTION, FILTER_TYPE, FILTER_ORDER,
 * LOW_CUT_FREQUENCY_HZ, HIGH_CUT_FREQUENCY_HZ.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define ESM_MAX_HEADER_LINES 200

typedef struct {
  const char *key;
  aq_line val; /* trimmed value; len 0 if absent or empty */
  long line;
} esm_key;

enum {
  K_EVENT_ID, K_EVENT_NAME, K_NETWORK, K_STATION, K_LOCATION, K_STREAM, K_UNITS,
  K_DATA_TYPE, K_DT, K_NDATA, K_START, K_BASELINE, K_FILTER, K_ORDER, K_LOW, K_HIGH, K_COUNT
};

/* "KEY: value": 1 and the key's extent if the line starts with an upper
 * case key (letters, digits, _ / ^ .) followed by a colon. */
static int key_line(const aq_line *ln, size_t *klen)
{
  size_t i = 0;
  while (i < ln->len && (isupper((unsigned char)ln->p[i]) || isdigit((unsigned char)ln->p[i]) ||
                         strchr("_/^.", ln->p[i])))
    i++;
  if (i == 0 || i >= ln->len || ln->p[i] != ':' || !isupper((unsigned char)ln->p[0]))
    return 0;
  *klen = i;
  return 1;
}

static double key_number(const esm_key *k, int *ok)
{
  double v = NAN;
  *ok = k->val.len > 0 && aq_field_double(k->val.p, k->val.len, &v);
  return v;
}

/* isspace() of the "C" locale, without the library call per byte. */
static int is_c_space(char c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

aq_status aq_esm_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  esm_key k[K_COUNT] = {
      {"EVENT_ID", {0}, 0},  {"EVENT_NAME", {0}, 0},  {"NETWORK", {0}, 0},
      {"STATION_CODE", {0}, 0}, {"LOCATION", {0}, 0}, {"STREAM", {0}, 0},
      {"UNITS", {0}, 0},     {"DATA_TYPE", {0}, 0},   {"SAMPLING_INTERVAL_S", {0}, 0},
      {"NDATA", {0}, 0},     {"DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", {0}, 0},
      {"BASELINE_CORRECTION", {0}, 0}, {"FILTER_TYPE", {0}, 0}, {"FILTER_ORDER", {0}, 0},
      {"LOW_CUT_FREQUENCY_HZ", {0}, 0}, {"HIGH_CUT_FREQUENCY_HZ", {0}, 0}};
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  aq_lines data_start;
  int nkeys = 0;
  for (;;) {
    data_start = c;
    if (!aq_lines_next(&c, &ln))
      break;
    size_t kl;
    if (!key_line(&ln, &kl))
      break;
    if (++nkeys > ESM_MAX_HEADER_LINES)
      return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "header",
                          "expected at most %d KEY: value lines", ESM_MAX_HEADER_LINES);
    for (int i = 0; i < K_COUNT; i++)
      if (strlen(k[i].key) == kl && memcmp(k[i].key, ln.p, kl) == 0) {
        const char *v = ln.p + kl + 1, *e = ln.p + ln.len;
        while (v < e && isspace((unsigned char)*v))
          v++;
        while (e > v && isspace((unsigned char)e[-1]))
          e--;
        k[i].val.p = v;
        k[i].val.len = (size_t)(e - v);
        k[i].line = ln.line;
      }
  }
  if (nkeys == 0)
    return aq_error_set(err, AQ_EFORMAT, name, 1, -1, "header",
                        "expected ESM \"KEY: value\" header lines (EVENT_NAME: ...)");
  int ok;
  double dt_s = key_number(&k[K_DT], &ok);
  if (!ok || !(dt_s > 0)) {
    char got[48];
    aq_copy_trim(got, sizeof got, k[K_DT].val.p, k[K_DT].val.len);
    return aq_error_set(err, AQ_EFORMAT, name, k[K_DT].line ? k[K_DT].line : -1, -1,
                        "SAMPLING_INTERVAL_S", "expected a number > 0, got \"%s\"", got);
  }
  double nd = key_number(&k[K_NDATA], &ok);
  if (!ok || nd < 1 || nd != floor(nd) || nd > (double)(n - data_start.pos) / 2 + 1) {
    char got[48];
    aq_copy_trim(got, sizeof got, k[K_NDATA].val.p, k[K_NDATA].val.len);
    return aq_error_set(err, AQ_EFORMAT, name, k[K_NDATA].line ? k[K_NDATA].line : -1, -1,
                        "NDATA",
                        "expected a whole number from 1 to what the file can hold, got \"%s\"",
                        got);
  }
  aq_raw_channel *ch = aq_raw_add_channel(raw, name, err);
  if (!ch)
    return AQ_ENOMEM;
  ch->npts = (size_t)nd;
  ch->dt_s = dt_s;
  ch->values = malloc(ch->npts * sizeof *ch->values);
  if (!ch->values) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, "data", "out of memory");
  }
  /* the values: blank-separated numbers on the remaining lines */
  c = data_start;
  size_t got = 0;
  aq_extra_rows x; /* values past NDATA: reported for the decision (record.c) */
  memset(&x, 0, sizeof x);
  while (got < ch->npts && aq_lines_next(&c, &ln)) {
    size_t i = 0;
    while (i < ln.len) {
      while (i < ln.len && is_c_space(ln.p[i]))
        i++;
      size_t b = i;
      while (i < ln.len && !is_c_space(ln.p[i]))
        i++;
      if (i == b)
        break;
      if (got == ch->npts) { /* more on NDATA's last line: never a copy of a row */
        aq_line rest = {ln.p + b, ln.len - b, ln.line};
        x.values = aq_numbers_row(&rest, NULL);
        x.rows = 1;
        x.line = ln.line;
        break;
      }
      if (!aq_field_double(ln.p + b, i - b, &ch->values[got])) {
        char tok[48];
        aq_copy_trim(tok, sizeof tok, ln.p + b, i - b);
        aq_raw_file_free(raw);
        return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "data",
                            "value %zu: expected a number, got \"%s\"", got + 1, tok);
      }
      got++;
    }
  }
  if (got < ch->npts) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "data",
                        "expected NDATA = %.0f values, the file ends after %zu", nd, got);
  }
  if (x.rows == 0)
    aq_extra_rows_scan(&c, &ln, NULL, NULL, &x);
  if (x.rows > 0 && x.values == 0) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, x.line, -1, "data",
                        "expected the end of the data after NDATA = %.0f values, got more "
                        "on this line", nd);
  }
  if (!aq_lines_at_end(&c)) {
    aq_lines_next(&c, &ln);
    char tok[48];
    aq_copy_trim(tok, sizeof tok, ln.p, ln.len);
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "data",
                        "expected the end of the file after NDATA = %.0f values, got \"%s\"",
                        nd, tok);
  }
  aq_raw_set_extra(ch, &x, 1, "NDATA");
  /* what the header states */
  aq_copy_trim(ch->network, sizeof ch->network, k[K_NETWORK].val.p, k[K_NETWORK].val.len);
  aq_copy_trim(ch->station, sizeof ch->station, k[K_STATION].val.p, k[K_STATION].val.len);
  aq_copy_trim(ch->location, sizeof ch->location, k[K_LOCATION].val.p, k[K_LOCATION].val.len);
  aq_copy_trim(ch->channel, sizeof ch->channel, k[K_STREAM].val.p, k[K_STREAM].val.len);
  char units[24], type[24];
  aq_copy_trim(units, sizeof units, k[K_UNITS].val.p, k[K_UNITS].val.len);
  aq_copy_trim(type, sizeof type, k[K_DATA_TYPE].val.p, k[K_DATA_TYPE].val.len);
  if (strcmp(units, "cm/s^2") == 0 || strcmp(units, "cm/s2") == 0)
    snprintf(ch->units, sizeof ch->units, "cm/s2");
  else
    snprintf(ch->units, sizeof ch->units, "%s", units);
  if (type[0] && strcmp(type, "ACCELERATION") != 0)
    snprintf(ch->units_said, sizeof ch->units_said, "DATA_TYPE: %.20s, UNITS: %.20s", type,
             units);
  if (type[0]) {
    ch->quantity = strcmp(type, "ACCELERATION") == 0   ? AQ_QUANTITY_ACCELERATION
                   : strcmp(type, "VELOCITY") == 0     ? AQ_QUANTITY_VELOCITY
                   : strcmp(type, "DISPLACEMENT") == 0 ? AQ_QUANTITY_DISPLACEMENT
                                                       : AQ_QUANTITY_UNSTATED;
    snprintf(ch->quantity_said, sizeof ch->quantity_said, "line %ld: DATA_TYPE: %.20s",
             k[K_DATA_TYPE].line, type);
  }
  if (units[0])
    snprintf(ch->units_from, sizeof ch->units_from, "line %ld: UNITS: %.20s", k[K_UNITS].line,
             units);
  ch->units_line = k[K_UNITS].line;
  {
    char t[40];
    int y, mo, d, h, mi;
    double s;
    aq_copy_trim(t, sizeof t, k[K_START].val.p, k[K_START].val.len);
    if (sscanf(t, "%4d%2d%2d_%2d%2d%lf", &y, &mo, &d, &h, &mi, &s) != 6 ||
        !aq_iso_time(ch->reference, sizeof ch->reference, y, mo, d, h, mi, s))
      ch->reference[0] = '\0';
  }
  char id[48], ev[48];
  aq_copy_trim(id, sizeof id, k[K_EVENT_ID].val.p, k[K_EVENT_ID].val.len);
  aq_copy_trim(ev, sizeof ev, k[K_EVENT_NAME].val.p, k[K_EVENT_NAME].val.len);
  snprintf(raw->event, sizeof raw->event, "%s%s%s", id, id[0] && ev[0] ? " " : "", ev);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* the event alone */
  char base[40], filt[24], ord[8], lo[16], hi[16];
  aq_copy_trim(base, sizeof base, k[K_BASELINE].val.p, k[K_BASELINE].val.len);
  aq_copy_trim(filt, sizeof filt, k[K_FILTER].val.p, k[K_FILTER].val.len);
  aq_copy_trim(ord, sizeof ord, k[K_ORDER].val.p, k[K_ORDER].val.len);
  aq_copy_trim(lo, sizeof lo, k[K_LOW].val.p, k[K_LOW].val.len);
  aq_copy_trim(hi, sizeof hi, k[K_HIGH].val.p, k[K_HIGH].val.len);
  snprintf(raw->processing, sizeof raw->processing, "%s; %s order %s, %s-%s Hz", base, filt,
           ord, lo, hi);
  snprintf(raw->format, sizeof raw->format, "esm");
  return AQ_OK;
}
