/* record.c: reading a record file: its format sniffed from its content
 * (sniff.c), the parser of that format (reader.h), what the channel's
 * fields say beyond its values (evidence.c), and the one decision that
 * makes a record of what the parser reports (see record.h). */
#include "record.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <fnmatch.h>
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "../units.h"
#include "evidence.h"

#if defined(__SSE2__) && !defined(AQ_NO_SIMD)
#include <emmintrin.h>
#endif

/* ---- options ---------------------------------------------------------- */

const aq_units_rule *aq_read_opts_rule_for(const aq_read_opts *opts, const char *path)
{
  if (!opts || !path)
    return NULL;
  size_t n = opts->nrules < AQ_UNITS_RULES_MAX ? opts->nrules : AQ_UNITS_RULES_MAX;
  for (size_t i = n; i-- > 0;)
    if (fnmatch(opts->rules[i].glob, path, 0) == 0)
      return &opts->rules[i];
  return NULL;
}

aq_units aq_read_opts_units_for(const aq_read_opts *opts, const char *path)
{
  const aq_units_rule *r = aq_read_opts_rule_for(opts, path);
  return r ? r->units : opts ? opts->units : AQ_UNITS_FILE;
}

/* ---- records ---------------------------------------------------------- */

void aq_record_free(aq_record *rec)
{
  if (!rec)
    return;
  free(rec->path);
  free(rec->name);
  free(rec->acc_mps2);
  memset(rec, 0, sizeof *rec);
}

static aq_status set_names(aq_record *rec, const char *name, aq_error *err)
{
  const char *p = name ? name : "";
  const char *slash = strrchr(p, '/');
  rec->path = strdup(p);
  rec->name = strdup(slash ? slash + 1 : p);
  if (!rec->path || !rec->name) {
    free(rec->path);
    free(rec->name);
    rec->path = rec->name = NULL;
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  }
  return AQ_OK;
}

/* ---- miniSEED and its StationXML ---------------------------------------- */

#define MSEED_XML_SNIFF 1024            /* bytes looked at for "<FDSNStationXML" */

/* aq_mseed_parse, then, with opts->responses, each channel's response
 * (evidence.c). */
static aq_status mseed_read(const unsigned char *buf, size_t n, const char *name,
                            const aq_read_opts *opts, aq_raw_file *raw, aq_error *err)
{
  aq_status s = aq_mseed_parse(buf, n, name, NULL, raw, err);
  if (s != AQ_OK || !opts || !opts->nresponses)
    return s;
  size_t nx = opts->nresponses < AQ_RESPONSES_MAX ? opts->nresponses : AQ_RESPONSES_MAX;
  s = aq_evidence_responses(opts->responses, nx, name, raw, err);
  if (s != AQ_OK)
    aq_raw_file_free(raw);
  return s;
}

size_t aq_read_opts_take_stationxml(char **paths, size_t n, aq_read_opts *ro)
{
  size_t k = 0, nx = 0;
  char **xml = malloc((n ? n : 1) * sizeof *xml);
  if (!xml)
    return n; /* left as records: each refused as not one */
  for (size_t i = 0; i < n; i++) {
    char head[MSEED_XML_SNIFF + 1];
    size_t got = 0;
    FILE *f = fopen(paths[i], "rb");
    if (f) {
      got = fread(head, 1, MSEED_XML_SNIFF, f);
      fclose(f);
    }
    head[got] = '\0';
    int is_xml = got > 0 && memchr(head, '\0', got) == NULL && strstr(head, "<FDSNStationXML");
    if (is_xml && ro->nresponses + nx < AQ_RESPONSES_MAX)
      xml[nx++] = paths[i];
    else
      paths[k++] = paths[i];
  }
  if (k == 0) { /* nothing but StationXML: the reader refuses them as records */
    memcpy(paths, xml, n * sizeof *xml);
    free(xml);
    return n;
  }
  for (size_t j = 0; j < nx; j++) {
    ro->responses[ro->nresponses++] = xml[j];
    paths[k + j] = xml[j];
  }
  free(xml);
  return k;
}

/* ---- deciding -------------------------------------------------------- */

/* A dip this far or farther from horizontal, deg, is vertical (SAC CMPINC 0
 * or 180 is dip -90 or +90; a tilted sensor of a few degrees stays what it
 * was meant to be). */
#define AQ_VERTICAL_DIP_MIN_DEG 45.0

/* "path" or "path#CHANNEL" (the channel's name, or its 1-based number when
 * it has none) into out. */
/* A record's label: its path (at most PATH_MAX, 4096 bytes, or no file
 * could be opened by it), '#' and the channel's name (under 16). */
#define RECORD_LABEL_MAX (4096 + 32)

static void record_label(const aq_raw_file *raw, size_t ichan, const char *path,
                         char *out, size_t cap)
{
  if (raw->nchan <= 1)
    snprintf(out, cap, "%s", path);
  else if (raw->chan[ichan].channel[0])
    snprintf(out, cap, "%s#%s", path, raw->chan[ichan].channel);
  else
    snprintf(out, cap, "%s#%zu", path, ichan + 1);
}

/* The units words offered in messages, and tried for a plausible PGA. */
static const aq_units plausible_try[] = {AQ_UNITS_G,     AQ_UNITS_G10,
                                         AQ_UNITS_GAL,   AQ_UNITS_MMPS2,
                                         AQ_UNITS_MPS2,  AQ_UNITS_NMPS2};

/* acc[k] = v[k] * factor and *maxabs = the largest |v[k]| (from its value on
 * entry) for k = 0, 1, ... while the products are finite: returns the first
 * k whose product is not (or n), acc[k] not written (the caller reports
 * that sample).  v and acc may be the same array (a sample is read before
 * its product is stored).  Two samples a vector:
 * the same products and the same maximum (max is exact, in any order) as
 * the one-at-a-time loop, without its branches per sample. */
static size_t scale_samples(const double *v, double *acc, size_t n, double factor,
                            double *maxabs)
{
  size_t k = 0;
#if defined(__SSE2__) && !defined(AQ_NO_SIMD)
  const __m128d f = _mm_set1_pd(factor), big = _mm_set1_pd(DBL_MAX),
                abs = _mm_castsi128_pd(_mm_set1_epi64x(INT64_MAX));
  __m128d mx = _mm_set1_pd(*maxabs);
  for (; n - k >= 4; k += 4) {
    __m128d v0 = _mm_loadu_pd(v + k), v1 = _mm_loadu_pd(v + k + 2);
    __m128d a0 = _mm_mul_pd(v0, f), a1 = _mm_mul_pd(v1, f);
    /* finite: |a| <= DBL_MAX (false for a NaN) */
    __m128d fin = _mm_and_pd(_mm_cmple_pd(_mm_and_pd(a0, abs), big),
                             _mm_cmple_pd(_mm_and_pd(a1, abs), big));
    if (_mm_movemask_pd(fin) != 3)
      break;
    /* maxpd(x, mx) is x > mx ? x : mx, the scalar loop's choice */
    mx = _mm_max_pd(_mm_max_pd(_mm_and_pd(v0, abs), mx), _mm_and_pd(v1, abs));
    _mm_storeu_pd(acc + k, a0);
    _mm_storeu_pd(acc + k + 2, a1);
  }
  double m2[2];
  _mm_storeu_pd(m2, mx);
  *maxabs = m2[0] > m2[1] ? m2[0] : m2[1];
#endif
  double m = *maxabs;
  for (; k < n; k++) {
    double a = v[k] * factor;
    if (!isfinite(a))
      break;
    double x = fabs(v[k]);
    if (x > m)
      m = x;
    acc[k] = a;
  }
  *maxabs = m;
  return k;
}

/* AQ_OK when nothing the file says contradicts acceleration; else
 * AQ_EUNITS naming the evidence (aq_evidence_quantity). */
static aq_status check_acceleration(const aq_raw_channel *ch, const char *path,
                                    const char *label, aq_error *err)
{
  char ev[200];
  const char *what;
  if (aq_evidence_quantity(ch, path, ev, sizeof ev, &what) == AQ_QUANTITY_UNSTATED)
    return AQ_OK;
  return aq_error_set(err, AQ_EUNITS, label, -1, -1, "quantity",
                      "expected ground acceleration, got %s (%s); archquake reads "
                      "acceleration only: convert the record to acceleration first",
                      what, ev);
}

/* --dt and a file's interval within this (relative) are the same: both
 * are decimals as written (0.01, ".0100"), whose doubles differ by a few
 * units of rounding at most. */
#define AQ_DT_SAME_REL 1e-9

/* The event as records are compared by it: name in lower case (ASCII),
 * every run of characters other than letters and digits one space, none at
 * either end ("Imperial Valley-02, 5/19/1940" -> "imperial valley 02 5 19
 * 1940"), so that spacing and punctuation do not make two events of one. */
static void decide_event_key(const char *name, char *key, size_t cap)
{
  size_t k = 0;
  int gap = 0;
  for (const char *p = name; *p && k + 2 < cap; p++) {
    unsigned char c = (unsigned char)*p;
    if (isalnum(c)) {
      if (gap && k)
        key[k++] = ' ';
      key[k++] = (char)tolower(c);
      gap = 0;
    } else
      gap = 1;
  }
  key[k] = '\0';
}

/* aq_record_decide; with in_place (the channel's own values, which the
 * caller gives up on success), the samples are scaled there instead of in a
 * new array. */
static aq_status decide(const aq_raw_file *raw, size_t ichan, const char *path,
                        const aq_read_opts *opts, aq_record *rec, aq_error *err,
                        double *in_place)
{
  memset(rec, 0, sizeof *rec);
  rec->azimuth_deg = rec->dip_deg = NAN;
  if (!raw || ichan >= raw->nchan || !raw->chan)
    return aq_error_set(err, AQ_EINTERNAL, path, -1, -1, NULL,
                        "channel %zu of %zu", ichan + 1, raw ? raw->nchan : 0);
  const aq_raw_channel *ch = &raw->chan[ichan];
  char label[RECORD_LABEL_MAX];
  record_label(raw, ichan, path ? path : "", label, sizeof label);
  if (ch->npts == 0 || !ch->values)
    return aq_error_set(err, AQ_EFORMAT, label, -1, -1, NULL,
                        "expected at least one sample, got none");
  if (!(ch->dt_s > 0) || !isfinite(ch->dt_s))
    return aq_error_set(err, AQ_EFORMAT, label, -1, -1, "dt",
                        "expected a sample interval > 0 s, got %g", ch->dt_s);
  aq_status sq = check_acceleration(ch, path ? path : "", label, err);
  if (sq != AQ_OK)
    return sq;
  /* Rows past the count the file states: a copy of its last row (an
   * agency padding its block) is said and not read; anything else means
   * the count or the data is wrong, and is refused naming both counts. */
  char rows[64];
  if (ch->extra_rows == 1)
    snprintf(rows, sizeof rows, "the row at line %ld", ch->extra_line);
  else
    snprintf(rows, sizeof rows, "the %zu rows from line %ld", ch->extra_rows, ch->extra_line);
  if (ch->extra_values > 0 && ch->extra_repeat)
    snprintf(rec->count_note, sizeof rec->count_note,
             "the file holds %zu values, %s states %zu: %s %s the last and %s not read",
             ch->npts + ch->extra_values, ch->count_from, ch->npts, rows,
             ch->extra_rows == 1 ? "repeats" : "repeat", ch->extra_rows == 1 ? "is" : "are");
  else if (ch->extra_values > 0)
    return aq_error_set(err, AQ_EFORMAT, label, ch->extra_line, -1, "data",
                        "expected %zu values (%s), got %zu: %s %s",
                        ch->npts, ch->count_from, ch->npts + ch->extra_values, rows,
                        ch->extra_rows == 1 ? "is not a copy of the last row"
                                            : "are not all copies of the last row");
  /* --dt is for records that state no sample interval: one that states its
   * own keeps it, and says so when the two differ (a suite may mix both) */
  if (opts && opts->dt_s > 0 && fabs(ch->dt_s - opts->dt_s) > AQ_DT_SAME_REL * opts->dt_s)
    snprintf(rec->dt_note, sizeof rec->dt_note,
             "--dt %g s not used: the file states a sample interval of %g s", opts->dt_s,
             ch->dt_s);

  /* Units: a rule naming the file, else the file's own, else --units. */
  aq_units stated = AQ_UNITS_FILE, used;
  int has_stated = ch->units[0] && aq_units_parse(ch->units, &stated);
  const aq_units_rule *rule = aq_read_opts_rule_for(opts, path);
  aq_units global = opts ? opts->units : AQ_UNITS_FILE;
  const char *how; /* for the plausibility message */
  const char *units_by; /* rec->units_by */
  if (rule && rule->units != AQ_UNITS_FILE) {
    used = rule->units;
    how = "by --units rule";
    units_by = "rule";
    if (has_stated && stated != used)
      aq_text_fit(rec->units_conflict, sizeof rec->units_conflict,
                  "the file states %s, the rule --units '%s=%s' reads it as %s",
                  aq_units_name(stated), rule->glob, aq_units_name(used),
                  aq_units_name(used));
  } else if (has_stated) {
    used = stated;
    how = "as the file states";
    units_by = stated == AQ_UNITS_COUNTS && opts && opts->nresponses > 0 && strcmp(raw->format, "mseed") == 0
             ? "response"
             : "file";
  } else if (global != AQ_UNITS_FILE && !rule) {
    used = global;
    how = "by --units";
    units_by = "option";
  } else {
    const char *said = ch->units_said[0] ? ch->units_said : ch->units;
    return aq_error_set(err, AQ_EUNITS, label, -1, -1, "units",
                        "expected acceleration units stated in the file, %s%s%s; "
                        "if the values are ground acceleration, say in what with "
                        "--units g|g/10|gal|cm/s2|mm/s2|m/s2|nm/s2|counts (or "
                        "--units 'GLOB=U')",
                        said[0] ? "got \"" : "found none", said,
                        said[0] ? "\"" : "");
  }
  double factor;
  if (used == AQ_UNITS_COUNTS) {
    if (ch->counts_per_mps2 == 0 || !isfinite(ch->counts_per_mps2)) /* < 0: reversed polarity */
      return aq_error_set(err, AQ_EUNITS, label, -1, -1, "sensitivity",
                          "counts need the sensitivity in counts per m/s2 "
                          "stated in the file (SAC SCALE, as mseed2sac -M writes "
                          "it; K-NET scale factor; StationXML by --response for "
                          "miniSEED; ...), found none");
    factor = 1.0 / ch->counts_per_mps2;
  } else {
    factor = aq_units_to_mps2(used);
  }

  double *acc = in_place ? in_place : malloc(ch->npts * sizeof *acc);
  if (!acc)
    return aq_error_set(err, AQ_ENOMEM, label, -1, -1, NULL,
                        "out of memory for %zu samples", ch->npts);
  double maxabs = 0;
  size_t k = scale_samples(ch->values, acc, ch->npts, factor, &maxabs);
  if (k < ch->npts) { /* the first sample whose product is not finite */
    if (!in_place)
      free(acc);
    char fld[40];
    snprintf(fld, sizeof fld, "value %zu", k + 1);
    return aq_error_set(err, AQ_EVALUE, label, -1, -1, fld,
                        "expected a value that is finite in m/s2, got %g %s "
                        "(overflows)", ch->values[k], aq_units_name(used));
  }

  /* Plausibility: |PGA| in [AQ_PGA_MIN_G, AQ_PGA_MAX_G] (a negative
   * sensitivity gives a negative factor: the channel's polarity). */
  double pga_g = maxabs * fabs(factor) / AQ_G0_MPS2;
  /* the file states the conversion: its own units, or counts with the
   * sensitivity it states; then no other units are offered */
  int file_states = used == AQ_UNITS_COUNTS || (has_stated && used == stated);
  if (!(pga_g >= AQ_PGA_MIN_G && pga_g <= AQ_PGA_MAX_G) &&
      !(opts && opts->accept_implausible)) {
    if (!in_place)
      free(acc);
    char hint[AQ_UNITS_GLOB_MAX + 300];
    if (used == AQ_UNITS_COUNTS)
      snprintf(hint, sizeof hint, "the sensitivity is %.9g counts per m/s2%s%s%s: check it",
               ch->counts_per_mps2, ch->units_from[0] ? " (" : "", ch->units_from,
               ch->units_from[0] ? ")" : "");
    else if (file_states)
      snprintf(hint, sizeof hint,
               "%s is what the file states%s%s%s: if the file is wrong, say what its "
               "values are in with --units '%s=U'",
               aq_units_name(used), ch->units_from[0] ? " (" : "", ch->units_from,
               ch->units_from[0] ? ")" : "", path);
    else {
      char alt[160] = "";
      size_t len = 0;
      for (size_t i = 0; i < sizeof plausible_try / sizeof plausible_try[0]; i++) {
        double p = maxabs * aq_units_to_mps2(plausible_try[i]) / AQ_G0_MPS2;
        if (p >= AQ_PGA_MIN_G && p <= AQ_PGA_MAX_G && len + 24 < sizeof alt)
          len += (size_t)snprintf(alt + len, sizeof alt - len, "%s%s (%.3g g)",
                                  len ? ", " : "", aq_units_name(plausible_try[i]), p);
      }
      if (!alt[0])
        snprintf(hint, sizeof hint, "no units make it plausible");
      else
        snprintf(hint, sizeof hint, "plausible in %s: say which with --units %s%s%sU%s",
                 alt, has_stated ? "'" : "", has_stated ? path : "", has_stated ? "=" : "",
                 has_stated ? "'" : "");
    }
    return aq_error_set(err, AQ_EUNITS, label, -1, -1, "units",
                        "PGA %.3g g with the values in %s (%s) is implausible "
                        "(expected %g to %g g); %s; or keep it with "
                        "--accept-implausible",
                        pga_g, aq_units_name(used), how, AQ_PGA_MIN_G, AQ_PGA_MAX_G,
                        hint);
  }
  if (factor < 0) /* a negative sensitivity: the channel's polarity, applied */
    aq_text_fit(rec->polarity_note, sizeof rec->polarity_note,
                "reversed: the sensitivity is %.9g counts per m/s2%s%s%s, and its sign is "
                "applied to the samples",
                ch->counts_per_mps2, ch->units_from[0] ? " (" : "", ch->units_from,
                ch->units_from[0] ? ")" : "");

  /* Vertical: what the file states, else its dip, else the channel name;
   * a name saying vertical over a field saying horizontal is vertical, and
   * the conflict is noted. */
  aq_vertical_by by = AQ_VERTICAL_BY_NONE;
  int says = aq_evidence_says_vertical(ch->channel);
  if (ch->vertical > 0)
    by = AQ_VERTICAL_BY_STATED;
  else if (ch->vertical < 0 && isfinite(ch->dip_deg) &&
           fabs(ch->dip_deg) >= AQ_VERTICAL_DIP_MIN_DEG)
    by = AQ_VERTICAL_BY_DIP;
  else if (says && ch->vertical < 0 && !isfinite(ch->dip_deg))
    by = AQ_VERTICAL_BY_NAME;
  else if (says) { /* a field says horizontal: stated, or a dip near 0 */
    by = AQ_VERTICAL_BY_NAME_OVER_FIELD;
    char field[sizeof ch->orient_said];
    if (ch->orient_said[0])
      snprintf(field, sizeof field, "%s", ch->orient_said);
    else if (isfinite(ch->dip_deg))
      snprintf(field, sizeof field, "dip %g deg", ch->dip_deg);
    else
      snprintf(field, sizeof field, "azimuth %g deg", ch->azimuth_deg);
    aq_text_fit(rec->vertical_note, sizeof rec->vertical_note,
                "channel \"%s\" says vertical, the orientation field (%s) says horizontal: "
                "taken as vertical",
                ch->channel, field);
  }
  int vert = by != AQ_VERTICAL_BY_NONE;

  aq_status s = set_names(rec, label, err);
  if (s != AQ_OK) {
    if (!in_place)
      free(acc);
    return s;
  }
  snprintf(rec->format, sizeof rec->format, "%s", raw->format);
  rec->npts = ch->npts;
  rec->dt_s = ch->dt_s;
  rec->begin_s = ch->begin_s;
  snprintf(rec->reference, sizeof rec->reference, "%s", ch->reference);
  snprintf(rec->network, sizeof rec->network, "%s", ch->network);
  snprintf(rec->station, sizeof rec->station, "%s", ch->station);
  snprintf(rec->location, sizeof rec->location, "%s", ch->location);
  snprintf(rec->channel, sizeof rec->channel, "%s", ch->channel);
  snprintf(rec->event, sizeof rec->event, "%s", raw->event);
  decide_event_key(raw->event_name, rec->event_key, sizeof rec->event_key);
  snprintf(rec->processing, sizeof rec->processing, "%s", raw->processing);
  if (has_stated)
    snprintf(rec->units_stated, sizeof rec->units_stated, "%s", aq_units_name(stated));
  snprintf(rec->units_used, sizeof rec->units_used, "%s", aq_units_name(used));
  snprintf(rec->units_orig, sizeof rec->units_orig, "%s", aq_units_name(used));
  snprintf(rec->units_by, sizeof rec->units_by, "%s", units_by);
  rec->azimuth_deg = ch->azimuth_deg;
  rec->dip_deg = ch->dip_deg;
  rec->vertical = vert;
  rec->vertical_by = (int)by;
  rec->to_mps2 = factor;
  rec->acc_mps2 = acc;
  return AQ_OK;
}

aq_status aq_record_decide(const aq_raw_file *raw, size_t ichan, const char *path,
                           const aq_read_opts *opts, aq_record *rec, aq_error *err)
{
  return decide(raw, ichan, path, opts, rec, err, NULL);
}

/* Why rec is vertical, for messages: "by its dip, 90 deg", ... */
static void vertical_why(const aq_record *rec, char *why, size_t cap)
{
  if (rec->vertical_by == AQ_VERTICAL_BY_NAME_OVER_FIELD)
    aq_text_fit(why, cap, "by its channel name: %s", rec->vertical_note);
  else if (rec->vertical_by == AQ_VERTICAL_BY_DIP)
    snprintf(why, cap, "by its dip, %g deg", rec->dip_deg);
  else if (rec->vertical_by == AQ_VERTICAL_BY_NAME)
    snprintf(why, cap, "by its channel name");
  else
    snprintf(why, cap, "as the file states");
}

aq_status aq_record_check_horizontal(const aq_record *rec, const aq_read_opts *opts,
                                     aq_error *err)
{
  if (!rec->vertical || (opts && opts->accept_vertical))
    return AQ_OK;
  char why[sizeof rec->vertical_note + 32];
  vertical_why(rec, why, sizeof why);
  return aq_error_set(err, AQ_EUNSUPPORTED, rec->path, -1, -1, "channel",
                      "expected a horizontal component, got channel \"%s\", which "
                      "the file identifies as vertical (%s); a vertical "
                      "component is not horizontal excitation (give "
                      "--accept-vertical to run it anyway)",
                      rec->channel, why);
}

const char *aq_record_note(const aq_record *rec, size_t i, const char **topic)
{
  const struct {
    const char *topic, *text;
  } note[] = {{"polarity", rec->polarity_note},
              {"vertical", rec->vertical_note},
              {"dt", rec->dt_note},
              {"data", rec->count_note}};
  for (size_t k = 0; k < sizeof note / sizeof note[0]; k++)
    if (note[k].text[0] && i-- == 0) {
      if (topic)
        *topic = note[k].topic;
      return note[k].text;
    }
  return NULL;
}

/* What a parser may be told of opts (NULL for NULL), in *ro. */
static const aq_reader_opts *reader_opts(const aq_read_opts *opts, aq_reader_opts *ro)
{
  if (!opts)
    return NULL;
  ro->dt_s = opts->dt_s;
  ro->column = opts->column;
  return ro;
}

static atomic_ulong parses; /* aq_record_parses_ */

unsigned long aq_record_parses_(void) { return atomic_load(&parses); }

aq_status aq_raw_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err)
{
  memset(raw, 0, sizeof *raw);
  atomic_fetch_add(&parses, 1);
  aq_reader_opts ro;
  const aq_reader_opts *rop = reader_opts(opts, &ro);
  size_t bom = aq_sniff_bom(buf, n); /* a text's byte-order mark: its readers skip it */
  buf += bom;
  n -= bom;
  aq_format fmt = aq_sniff_format(buf, n);
  switch (fmt) {
  case AQ_FMT_SAC:
    return aq_sac_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_AT2:
    return aq_at2_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_TEXT:
    return aq_csv_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_COSMOS:
    return aq_cosmos_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_MSEED:
    return mseed_read(buf, n, name, opts, raw, err);
  case AQ_FMT_SMC:
    return aq_smc_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_ESM:
    return aq_esm_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_KNET:
    return aq_knet_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_GEONET:
    return aq_geonet_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_RENADIC:
    return aq_renadic_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_BHRC:
    return aq_bhrc_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_ASA:
    return aq_asa_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_NSMN:
    return aq_nsmn_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_NPTS_DT:
    return aq_nptsdt_parse(buf, n, name, rop, raw, err);
  case AQ_FMT_EMPTY:
    return aq_error_set(err, AQ_EFORMAT, name, -1, -1, NULL,
                        "expected a record, got an empty file (0 bytes)");
  case AQ_FMT_UNKNOWN_BINARY:
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "format",
                        "expected a record: SAC or miniSEED (binary), or text "
                        "(docs/agency-formats.md), got %s",
                        aq_sniff_describe(fmt));
  default:
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "format",
                        "looks like %s", aq_sniff_describe(fmt));
  }
}

/* The channel of raw that want names (exact, then case-insensitive, then a
 * 1-based number), or that a --component rule matching path names, or the
 * only one.  Returns AQ_OK with *ichan, or an error naming the channels. */
static aq_status select_channel(const aq_raw_file *raw, const char *want,
                                const char *path, const aq_read_opts *opts,
                                size_t *ichan, aq_error *err)
{
  if (!want && opts && raw->nchan > 1) /* a rule chooses among several */
    for (size_t i = opts->ncomponents < AQ_UNITS_RULES_MAX ? opts->ncomponents
                                                           : AQ_UNITS_RULES_MAX;
         i-- > 0;)
      if (fnmatch(opts->components[i].glob, path, 0) == 0) {
        want = opts->components[i].channel;
        break;
      }
  char list[200] = "";
  size_t len = 0;
  for (size_t i = 0; i < raw->nchan && len + 20 < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "",
                            raw->chan[i].channel[0] ? raw->chan[i].channel : "(unnamed)");
  if (!want) {
    if (raw->nchan == 1) {
      *ichan = 0;
      return AQ_OK;
    }
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "channel",
                        "expected one channel, the file holds %zu (%s): name one as "
                        "FILE#CHANNEL or with --component 'GLOB=CHANNEL'",
                        raw->nchan, list);
  }
  for (int pass = 0; pass < 2; pass++)
    for (size_t i = 0; i < raw->nchan; i++)
      if (pass ? strcasecmp(raw->chan[i].channel, want) == 0
               : strcmp(raw->chan[i].channel, want) == 0) {
        *ichan = i;
        return AQ_OK;
      }
  char *end;
  long k = strtol(want, &end, 10);
  if (*want && !*end && k >= 1 && (size_t)k <= raw->nchan) {
    *ichan = (size_t)k - 1;
    return AQ_OK;
  }
  return aq_error_set(err, AQ_EOPTION, path, -1, -1, "channel",
                      "expected one of the file's channels (%s), got \"%s\"", list,
                      want);
}

/* Parse and decide channel want (NULL: the only one or a --component rule's). */
static aq_status parse_one(const unsigned char *buf, size_t n, const char *path,
                           const char *want, const aq_read_opts *opts,
                           aq_record *rec, aq_error *err)
{
  aq_raw_file raw;
  aq_status s = aq_raw_parse(buf, n, path, opts, &raw, err);
  size_t ichan = 0;
  if (s == AQ_OK)
    s = select_channel(&raw, want, path, opts, &ichan, err);
  if (s == AQ_OK) { /* the samples are scaled where the reader put them */
    s = decide(&raw, ichan, path, opts, rec, err, raw.chan[ichan].values);
    if (s == AQ_OK)
      raw.chan[ichan].values = NULL; /* rec->acc_mps2 now */
  }
  aq_raw_file_free(&raw);
  return s;
}

aq_status aq_record_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_record *rec,
                          aq_error *err)
{
  memset(rec, 0, sizeof *rec);
  return parse_one(buf, n, name, NULL, opts, rec, err);
}

/* The bytes of the regular file at path (*buf malloc'd, caller frees). */
static aq_status read_bytes(const char *path, unsigned char **buf, size_t *size,
                            aq_error *err)
{
  struct stat st;
  *buf = NULL;
  if (stat(path, &st) != 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot open: %s",
                        strerror(errno));
  if (S_ISDIR(st.st_mode))
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "expected a record file, got a directory");
  if (!S_ISREG(st.st_mode))
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "expected a regular record file, got a device, pipe "
                        "or socket");
  FILE *f = fopen(path, "rb");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot open: %s",
                        strerror(errno));
  size_t n = (size_t)st.st_size;
  unsigned char *b = malloc(n ? n : 1);
  if (!b) {
    fclose(f);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL,
                        "out of memory reading %zu bytes", n);
  }
  size_t got = fread(b, 1, n, f);
  int rerr = ferror(f);
  fclose(f);
  if (rerr || got != n) {
    free(b);
    return aq_error_set(err, AQ_EIO, path, -1, (long)got, NULL,
                        "read error: expected %zu bytes, got %zu", n, got);
  }
  *buf = b;
  *size = n;
  return AQ_OK;
}

/* FILE#CHANNEL names one channel of a file when no file has the whole name:
 * file (cap bytes) gets FILE and *want CHANNEL; otherwise *want is NULL and
 * file is path. */
static void split_channel(const char *path, char *file, size_t cap, const char **want)
{
  struct stat st;
  const char *hash = strrchr(path, '#');
  *want = NULL;
  snprintf(file, cap, "%s", path);
  if (stat(path, &st) == 0 || !hash || hash == path || !hash[1] ||
      (size_t)(hash - path) >= cap)
    return;
  memcpy(file, path, (size_t)(hash - path));
  file[hash - path] = '\0';
  if (stat(file, &st) == 0)
    *want = hash + 1;
  else
    snprintf(file, cap, "%s", path);
}

const char *aq_record_file(const char *name, char *buf, size_t cap)
{
  const char *want;
  split_channel(name, buf, cap, &want);
  return buf;
}

aq_status aq_record_read(const char *path, const aq_read_opts *opts,
                         aq_record *rec, aq_error *err)
{
  return aq_record_read_keep(path, opts, rec, NULL, NULL, err);
}

aq_status aq_record_read_keep(const char *path, const aq_read_opts *opts,
                              aq_record *rec, unsigned char **bytes,
                              size_t *nbytes, aq_error *err)
{
  memset(rec, 0, sizeof *rec);
  if (bytes)
    *bytes = NULL;
  if (!path || !*path)
    return aq_error_set(err, AQ_EIO, "", -1, -1, NULL,
                        "expected a record file name, got an empty string");
  char file[4096];
  const char *want;
  split_channel(path, file, sizeof file, &want);
  unsigned char *buf;
  size_t size = 0;
  aq_status s = read_bytes(file, &buf, &size, err);
  if (s != AQ_OK)
    return s;
  s = parse_one(buf, size, file, want, opts, rec, err);
  if (bytes) { /* the file's bytes, whichever of its channels was read */
    *bytes = buf;
    *nbytes = size;
  } else {
    free(buf);
  }
  return s;
}

void aq_record_names_free(char **names, size_t n)
{
  for (size_t i = 0; names && i < n; i++)
    free(names[i]);
  free(names);
}

void aq_record_set_free(aq_record_set *set)
{
  if (!set)
    return;
  for (size_t i = 0; set->item && i < set->n; i++) {
    free(set->item[i].name);
    aq_record_free(&set->item[i].rec);
  }
  free(set->item);
  free(set->bytes);
  memset(set, 0, sizeof *set);
}

/* The last --component rule matching path, or NULL. */
static const char *component_rule(const aq_read_opts *opts, const char *path)
{
  const char *ch = NULL;
  for (size_t r = 0; opts && r < opts->ncomponents && r < AQ_UNITS_RULES_MAX; r++)
    if (fnmatch(opts->components[r].glob, path, 0) == 0)
      ch = opts->components[r].channel;
  return ch;
}

/* Append an item named name (a copy) to set: its record from channel ichan
 * of raw (scaled in place, its values taken from raw), or the status s with
 * e when s is not AQ_OK.  AQ_OK, or AQ_ENOMEM for the set itself. */
static aq_status add_item(aq_record_set *set, const char *name, aq_raw_file *raw, size_t ichan,
                          const char *file, const aq_read_opts *opts, aq_status s,
                          const aq_error *e)
{
  aq_record_item *it = realloc(set->item, (set->n + 1) * sizeof *it);
  if (!it)
    return AQ_ENOMEM;
  set->item = it;
  it += set->n;
  memset(it, 0, sizeof *it);
  if (!(it->name = strdup(name)))
    return AQ_ENOMEM;
  set->n++;
  aq_error_clear(&it->err);
  if (s == AQ_OK) {
    s = decide(raw, ichan, file, opts, &it->rec, &it->err, raw->chan[ichan].values);
    if (s == AQ_OK)
      raw->chan[ichan].values = NULL; /* it->rec.acc_mps2 now */
  } else {
    it->err = *e;
  }
  it->status = s;
  return AQ_OK;
}

/* aq_record_read_all of the bytes buf[0..size) of file, for the operand
 * path (want: the channel it names, or NULL). */
static aq_status read_all_bytes(const unsigned char *buf, size_t size, const char *path,
                                const char *file, const char *want,
                                const aq_read_opts *opts, aq_record_set *set)
{
  aq_raw_file raw;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_raw_parse(buf, size, file, opts, &raw, &e), st = AQ_OK;
  if (s != AQ_OK)
    return add_item(set, path, NULL, 0, file, opts, s, &e);
  const char *rule = want ? NULL : component_rule(opts, path);
  if (want || raw.nchan == 1 || rule) { /* one channel: as aq_record_read */
    size_t ichan = 0;
    char name[RECORD_LABEL_MAX];
    snprintf(name, sizeof name, "%s", path);
    if (!want && raw.nchan > 1)
      snprintf(name, sizeof name, "%s#%s", path, rule);
    s = select_channel(&raw, want, file, opts, &ichan, &e);
    st = add_item(set, name, &raw, ichan, file, opts, s, &e);
  } else {
    for (size_t c = 0; c < raw.nchan && st == AQ_OK; c++) {
      char label[RECORD_LABEL_MAX];
      record_label(&raw, c, path, label, sizeof label);
      st = add_item(set, label, &raw, c, file, opts, AQ_OK, NULL);
    }
  }
  aq_raw_file_free(&raw);
  return st;
}

aq_status aq_record_read_all(const char *path, const aq_read_opts *opts, int keep_bytes,
                             aq_record_set *set, aq_error *err)
{
  memset(set, 0, sizeof *set);
  aq_error e;
  aq_error_clear(&e);
  aq_status st;
  if (!path || !*path) {
    aq_error_set(&e, AQ_EIO, "", -1, -1, NULL,
                 "expected a record file name, got an empty string");
    st = add_item(set, path ? path : "", NULL, 0, "", opts, AQ_EIO, &e);
  } else {
    char file[4096];
    const char *want;
    split_channel(path, file, sizeof file, &want);
    unsigned char *buf = NULL;
    size_t size = 0;
    aq_status s = read_bytes(file, &buf, &size, &e);
    st = s == AQ_OK ? read_all_bytes(buf, size, path, file, want, opts, set)
                    : add_item(set, path, NULL, 0, file, opts, s, &e);
    if (keep_bytes && buf) {
      set->bytes = buf;
      set->nbytes = size;
    } else {
      free(buf);
    }
  }
  if (st != AQ_OK) {
    aq_record_set_free(set);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  }
  return AQ_OK;
}

/* Append to notes[0..*n) the line saying why item it, a channel the file
 * identifies as vertical, is left out of a run. */
static aq_status add_note(char ***notes, size_t *n, const aq_record_item *it)
{
  char why[sizeof it->rec.vertical_note + 32], line[5400];
  vertical_why(&it->rec, why, sizeof why);
  aq_text_fit(line, sizeof line,
              "%s: skipped: the file identifies channel \"%s\" as vertical (%s), which is "
              "not horizontal excitation (give --accept-vertical to run it)",
              it->name, it->rec.channel, why);
  char **g = realloc(*notes, (*n + 1) * sizeof *g);
  if (!g)
    return AQ_ENOMEM;
  *notes = g;
  if (!(g[*n] = strdup(line)))
    return AQ_ENOMEM;
  (*n)++;
  return AQ_OK;
}

/* Formats that hold one channel per file (SAC, AT2, K-NET, NPTS DT) are not
 * parsed here, nor text that has one column of acceleration (only its
 * columns are read); the others are read as aq_record_read_all reads them,
 * and named as it names them. */
static aq_status expand(char *const *paths, size_t n, const aq_read_opts *opts, int skip_vertical,
                        char ***out, size_t *nout, char ***notes, size_t *nnotes, aq_error *err)
{
  size_t cap = n + 1, k = 0;
  char **names = malloc(cap * sizeof *names);
  *out = NULL;
  *nout = 0;
  size_t nn = 0;
  char **nt = NULL;
  if (!names)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  aq_status st = AQ_OK;
  for (size_t i = 0; i < n && st == AQ_OK; i++) {
    aq_record_set set;
    memset(&set, 0, sizeof set);
    char file[4096];
    const char *want;
    split_channel(paths[i], file, sizeof file, &want);
    unsigned char *buf = NULL;
    size_t size = 0;
    aq_error ignored;
    if (!want && read_bytes(paths[i], &buf, &size, &ignored) == AQ_OK) {
      aq_format fmt = aq_sniff_format(buf, size);
      int single = fmt == AQ_FMT_SAC || fmt == AQ_FMT_AT2 || fmt == AQ_FMT_KNET ||
                   fmt == AQ_FMT_NPTS_DT;
      size_t nch;
      aq_reader_opts ro;
      /* text of one channel, or that fails before its rows, keeps its name
       * whatever its rows hold: only its columns are read */
      if (fmt == AQ_FMT_TEXT &&
          (aq_csv_channels(buf, size, paths[i], reader_opts(opts, &ro), &nch, &ignored) !=
               AQ_OK ||
           nch <= 1))
        single = 1;
      if (!single && read_all_bytes(buf, size, paths[i], paths[i], NULL, opts, &set) != AQ_OK)
        st = AQ_ENOMEM;
    }
    free(buf);
    size_t add = set.n > 1 ? set.n : 1;
    if (st == AQ_OK && k + add > cap) {
      size_t ncap = 2 * cap + add;
      char **g = realloc(names, ncap * sizeof *names);
      if (!g)
        st = AQ_ENOMEM;
      else {
        names = g;
        cap = ncap;
      }
    }
    for (size_t c = 0; c < add && st == AQ_OK; c++) {
      /* (a file that fails to parse is one item named as given: reported
       * when it is read) */
      const char *name = set.n ? set.item[c].name : paths[i];
      if (skip_vertical && set.n > 1 && set.item[c].status == AQ_OK &&
          set.item[c].rec.vertical && !(opts && opts->accept_vertical)) {
        st = add_note(&nt, &nn, &set.item[c]);
        continue;
      }
      if (!(names[k] = strdup(name)))
        st = AQ_ENOMEM;
      else
        k++;
    }
    aq_record_set_free(&set);
    if (st != AQ_OK)
      aq_error_set(err, AQ_ENOMEM, paths[i], -1, -1, NULL, "out of memory");
  }
  if (st != AQ_OK) {
    aq_record_names_free(names, k);
    aq_record_names_free(nt, nn);
    return st;
  }
  *out = names;
  *nout = k;
  if (notes) {
    *notes = nt;
    *nnotes = nn;
  }
  return AQ_OK;
}

aq_status aq_record_expand(char *const *paths, size_t n, const aq_read_opts *opts,
                           char ***out, size_t *nout, aq_error *err)
{
  return expand(paths, n, opts, 0, out, nout, NULL, NULL, err);
}

aq_status aq_record_expand_horizontal(char *const *paths, size_t n, const aq_read_opts *opts,
                                      char ***out, size_t *nout, char ***notes, size_t *nnotes,
                                      aq_error *err)
{
  *notes = NULL;
  *nnotes = 0;
  return expand(paths, n, opts, 1, out, nout, notes, nnotes, err);
}
