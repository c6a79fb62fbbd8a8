/* evidence.c: what a channel's fields say beyond its values (evidence.h):
 * the response of a miniSEED channel, matched by identity and epoch across
 * every StationXML given (its units, sensitivity, azimuth and dip); whether
 * anything the file states contradicts acceleration; whether a channel name
 * says vertical.  It gathers and names the evidence; record.c decides. */
#include "evidence.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "fixed.h"

/* ---- responses: miniSEED channels and their StationXML -------------------- */

#define MSEED_XML_MAX_BYTES (64L << 20) /* a StationXML larger than this is refused */

/* The StationXML files of a miniSEED read, each loaded and parsed when a
 * channel first needs it. */
typedef struct {
  const char *name;
  unsigned char *bytes;
  size_t n;
  int state; /* 0 not loaded, 1 bytes, 2 parsed */
  aq_response resp;
} xml_file;

/* The bytes of StationXML x (state 1), or an error naming it. */
static aq_status xml_load(xml_file *x, aq_error *err)
{
  if (x->state)
    return AQ_OK;
  FILE *f = fopen(x->name, "rb");
  long len = -1;
  if (f && fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) >= 0 && len <= MSEED_XML_MAX_BYTES &&
      fseek(f, 0, SEEK_SET) == 0 && (x->bytes = malloc((size_t)len + 1)) != NULL &&
      fread(x->bytes, 1, (size_t)len, f) == (size_t)len) {
    fclose(f);
    x->n = (size_t)len;
    x->state = 1;
    return AQ_OK;
  }
  if (f)
    fclose(f);
  free(x->bytes);
  x->bytes = NULL;
  return aq_error_set(err, AQ_EIO, x->name, -1, -1, "response",
                      "expected a readable StationXML file of at most %ld bytes, %s",
                      MSEED_XML_MAX_BYTES,
                      !f ? "cannot open it" : len > MSEED_XML_MAX_BYTES ? "got a larger one"
                                                                         : "cannot read it");
}

/* Does x mention station sta at all (code="STA")?  Only those are parsed. */
static int xml_mentions(const xml_file *x, const char *sta)
{
  char pat[24];
  int m = snprintf(pat, sizeof pat, "\"%s\"", sta);
  if (m <= 2 || (size_t)m >= sizeof pat)
    return 1;
  for (size_t i = 0; i + (size_t)m <= x->n; i++)
    if (x->bytes[i] == '"' && memcmp(x->bytes + i, pat, (size_t)m) == 0)
      return 1;
  return 0;
}

/* Give channel ch of miniSEED name the one response of xs[0..nx) that
 * matches its identity and start. */
static aq_status match_response(xml_file *xs, size_t nx, aq_raw_channel *ch, const char *name,
                                aq_error *err)
{
  char id[80], field[96];
  snprintf(id, sizeof id, "%s.%s.%s.%s", ch->network, ch->station, ch->location, ch->channel);
  snprintf(field, sizeof field, "channel %s", id);
  double t0;
  if (!aq_iso_parse(ch->reference, &t0))
    return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                        "the record states no start time to choose a response epoch");
  t0 += ch->begin_s;
  const aq_response_epoch *hit = NULL;
  size_t nhit = 0, nsame = 0, first = 0, second = 0; /* files of the first two hits */
  char spans[256] = "";
  for (size_t j = 0; j < nx; j++) {
    aq_status s = xml_load(&xs[j], err);
    if (s != AQ_OK)
      return s;
    if (xs[j].state == 1) {
      if (!xml_mentions(&xs[j], ch->station))
        continue;
      if ((s = aq_stationxml_parse(xs[j].bytes, xs[j].n, xs[j].name, &xs[j].resp, err)) != AQ_OK)
        return s;
      xs[j].state = 2;
    }
    const aq_response_epoch *h;
    size_t k = aq_response_find(&xs[j].resp, ch->network, ch->station, ch->location,
                                ch->channel, t0, &h, &nsame, spans, sizeof spans);
    if (k && nhit == 0) {
      hit = h;
      first = second = j; /* second: j again if it holds two */
    } else if (k && nhit == 1) {
      second = j;
    }
    nhit += k;
  }
  if (nhit == 1)
    return aq_response_apply(hit, xs[first].name, ch, err);
  char list[300] = "", more[80] = "";
  size_t len = 0, shown = 0;
  if (nhit > 1)
    snprintf(list, sizeof list, "%s and %s", xs[first].name, xs[second].name);
  else /* whole names while they fit (the first in any case), then a count */
    for (size_t j = 0; j < nx; j++, shown++) {
      size_t m = strlen(xs[j].name) + (j ? 2 : 0);
      if (j && len + m >= sizeof list)
        break;
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", j ? ", " : "", xs[j].name);
      if (len >= sizeof list)
        len = sizeof list - 1;
    }
  if (nhit > 1)
    return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                        "expected one response for %s at its start %s, got %zu that match: %s",
                        id, ch->reference, nhit, list);
  if (shown < nx)
    snprintf(more, sizeof more, " and %zu more (%zu StationXML files)", nx - shown, nx);
  return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                      "expected a response for %s at its start %s, got none%s%s%s in %s%s",
                      id, ch->reference, nsame ? " (its epochs: " : "", nsame ? spans : "",
                      nsame ? ")" : "", list, more);
}

aq_status aq_evidence_responses(const char *const *xml, size_t nx, const char *name,
                                aq_raw_file *raw, aq_error *err)
{
  aq_status s = AQ_OK;
  xml_file *xs = calloc(nx ? nx : 1, sizeof *xs);
  struct stat *st = calloc(nx ? nx : 1, sizeof *st);
  if (!xs || !st)
    s = aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  /* one file given twice (--response X and X among the records, or two
   * names of it) is searched once: it is one response, not two */
  size_t nk = 0;
  for (size_t j = 0; s == AQ_OK && j < nx; j++) {
    int found = stat(xml[j], &st[nk]) == 0, dup = 0;
    for (size_t k = 0; k < nk && !dup; k++)
      dup = strcmp(xs[k].name, xml[j]) == 0 ||
            (found && st[k].st_dev == st[nk].st_dev &&
             st[k].st_ino == st[nk].st_ino && st[k].st_ino != 0);
    if (!dup) {
      if (!found)
        memset(&st[nk], 0, sizeof st[nk]);
      xs[nk++].name = xml[j];
    }
  }
  free(st);
  for (size_t i = 0; s == AQ_OK && i < raw->nchan; i++)
    s = match_response(xs, nk, &raw->chan[i], name, err);
  for (size_t j = 0; xs && j < nk; j++) {
    free(xs[j].bytes);
    aq_response_free(&xs[j].resp);
  }
  free(xs);
  return s;
}

/* ---- the quantity ------------------------------------------------------- */

/* SEED instrument codes (the second letter of a three-letter channel code
 * after a band code) of sensors that do not record acceleration: H and L
 * seismometers (high and low gain), P geophones, M mass position (SEED
 * manual, appendix A); N is an accelerometer. */
static const char *instrument_not_acceleration(const char *channel)
{
  static const char bands[] = "FGDCESHBMLVURPTQAIO";
  if (strlen(channel) != 3 || !strchr(bands, channel[0]) || !isalnum((unsigned char)channel[2]))
    return NULL;
  switch (channel[1]) {
  case 'H':
    return "a high-gain seismometer (velocity)";
  case 'L':
    return "a low-gain seismometer (velocity)";
  case 'P':
    return "a geophone (velocity)";
  case 'M':
    return "a mass position";
  default:
    return NULL;
  }
}

/* The quantity the words of s say (split at anything not a letter or
 * digit, and between a lower- and an upper-case letter: "RawVel"): velocity
 * (vel, velo, veloc, velocity, VT2) or displacement (disp, displ,
 * displacement, DT2); the word in *word. */
static aq_quantity words_quantity(const char *s, char *word, size_t cap)
{
  static const char *const vel[] = {"vel", "velo", "veloc", "velocity", "velocities", "vt2"};
  static const char *const disp[] = {"disp", "displ", "displacement", "displacements", "dt2"};
  const char *p = s;
  while (*p) {
    while (*p && !isalnum((unsigned char)*p))
      p++;
    const char *b = p;
    while (*p && isalnum((unsigned char)*p) &&
           !(p > b && islower((unsigned char)p[-1]) && isupper((unsigned char)*p)))
      p++;
    size_t len = (size_t)(p - b);
    for (size_t i = 0; len && i < sizeof vel / sizeof vel[0]; i++)
      if (strlen(vel[i]) == len && strncasecmp(b, vel[i], len) == 0) {
        snprintf(word, cap, "%.*s", (int)len, b);
        return AQ_QUANTITY_VELOCITY;
      }
    for (size_t i = 0; len && i < sizeof disp / sizeof disp[0]; i++)
      if (strlen(disp[i]) == len && strncasecmp(b, disp[i], len) == 0) {
        snprintf(word, cap, "%.*s", (int)len, b);
        return AQ_QUANTITY_DISPLACEMENT;
      }
  }
  return AQ_QUANTITY_UNSTATED;
}

aq_quantity aq_evidence_quantity(const aq_raw_channel *ch, const char *path, char *ev,
                                 size_t cap, const char **what)
{
  char word[64];
  aq_quantity q = AQ_QUANTITY_UNSTATED;
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  ev[0] = '\0';
  if (ch->quantity == AQ_QUANTITY_VELOCITY || ch->quantity == AQ_QUANTITY_DISPLACEMENT) {
    q = (aq_quantity)ch->quantity;
    snprintf(ev, cap, "%s", ch->quantity_said[0] ? ch->quantity_said : "the file says so");
  } else if ((q = aq_units_quantity(ch->units)) == AQ_QUANTITY_VELOCITY ||
             q == AQ_QUANTITY_DISPLACEMENT) {
    snprintf(ev, cap, "units \"%s\"%s%s", ch->units, ch->units_from[0] ? ", " : "",
             ch->units_from);
  } else if ((q = words_quantity(base, word, sizeof word)) != AQ_QUANTITY_UNSTATED) {
    snprintf(ev, cap, "the file name says \"%s\"", word);
  } else if (ch->quantity != AQ_QUANTITY_ACCELERATION &&
             (q = words_quantity(ch->channel, word, sizeof word)) != AQ_QUANTITY_UNSTATED) {
    snprintf(ev, cap, "the channel's name \"%s\"", ch->channel);
  } else if (ch->quantity != AQ_QUANTITY_ACCELERATION && instrument_not_acceleration(ch->channel)) {
    q = ch->channel[1] == 'M' ? AQ_QUANTITY_DISPLACEMENT : AQ_QUANTITY_VELOCITY;
    snprintf(ev, cap, "SEED channel %s: instrument code %c, %s", ch->channel,
             ch->channel[1], instrument_not_acceleration(ch->channel));
  }
  if (!ev[0])
    return AQ_QUANTITY_UNSTATED;
  *what = ch->channel[1] == 'M' && q == AQ_QUANTITY_DISPLACEMENT && strstr(ev, "mass position")
              ? "a mass position"
              : aq_quantity_name(q);
  return q;
}

/* ---- vertical ----------------------------------------------------------- */

/* Does a channel name say vertical?  Its words (split at anything not a
 * letter or digit, trailing digits dropped: KiK-net "UD2") UD, UP, U, Z, V,
 * VERT, VERTICAL, DOWN, or a SEED code of three letters ending in Z. */
int aq_evidence_says_vertical(const char *name)
{
  static const char *const words[] = {"UD", "UP", "U", "Z", "V", "VERT",
                                      "VERTICAL", "DOWN", "DWN", "DU", NULL};
  const char *p = name;
  while (*p) {
    while (*p && !isalnum((unsigned char)*p))
      p++;
    const char *b = p;
    while (*p && isalnum((unsigned char)*p))
      p++;
    size_t len = (size_t)(p - b);
    size_t alpha = len;
    while (alpha > 0 && isdigit((unsigned char)b[alpha - 1]))
      alpha--;
    if (alpha == 0)
      continue;
    for (int i = 0; words[i]; i++)
      if (strlen(words[i]) == alpha && strncasecmp(b, words[i], alpha) == 0)
        return 1;
    if (len == 3 && alpha == 3 && isalpha((unsigned char)b[0]) &&
        isalpha((unsigned char)b[1]) && (b[2] == 'Z' || b[2] == 'z'))
      return 1;
  }
  return 0;
}
