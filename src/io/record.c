/* record.c: reading a record file: its format sniffed from its content
 * (sniff.c), the parser of that format (reader.h), what the channel's
 * fields say beyond its values (evidence.c), and the one decision that
 * makes a record of what the parser reports (see record.h).  Reading one
 * file is in record_read.c, expanding files into sets in record_set.c; the
 * decision stays here. */
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
#include "record_impl.h"

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

/* ---- deciding -------------------------------------------------------- */

/* A dip this far or farther from horizontal, deg, is vertical (SAC CMPINC 0
 * or 180 is dip -90 or +90; a tilted sensor of a few degrees stays what it
 * was meant to be). */
#define AQ_VERTICAL_DIP_MIN_DEG 45.0

/* "path" or "path#CHANNEL" (the channel's name, or its 1-based number when
 * it has none) into out. */

void aq_record_label(const aq_raw_file *raw, size_t ichan, const char *path,
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
aq_status aq_record_decide_in_place(const aq_raw_file *raw, size_t ichan, const char *path,
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
  aq_record_label(raw, ichan, path ? path : "", label, sizeof label);
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
  return aq_record_decide_in_place(raw, ichan, path, opts, rec, err, NULL);
}

/* Why rec is vertical, for messages: "by its dip, 90 deg", ... */
void aq_record_vertical_why(const aq_record *rec, char *why, size_t cap)
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
  aq_record_vertical_why(rec, why, sizeof why);
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
