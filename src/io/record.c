/* record.c: reading a record file: its format sniffed from its content,
 * the parser of that format (reader.h), and the decision that makes a
 * record of what the parser reports (see record.h). */
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
#include "fixed.h"

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

/* ---- detection -------------------------------------------------------- */

/* Bytes sniffed to decide text or binary, and lines of a text header looked
 * at to recognise a format. */
#define AQ_SNIFF_BYTES 8192
#define AQ_SNIFF_LINES 8
/* Text has no NUL and at most this percentage of other control bytes (a form
 * feed or a stray escape may occur in exported text). */
#define AQ_SNIFF_CTRL_PERCENT 1

static int32_t get_i32(const unsigned char *p, int big)
{
  uint32_t u = big ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 |
                         (uint32_t)p[2] << 8 | p[3]
                   : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 |
                         (uint32_t)p[1] << 8 | p[0];
  return (int32_t)u;
}

/* Case-insensitive search for needle in s[0..n). */
static int has_ci(const char *s, size_t n, const char *needle)
{
  size_t m = strlen(needle);
  char c0 = (char)(needle[0] | 0x20); /* lower case of a letter (or itself) */
  for (size_t i = 0; i + m <= n; i++)
    if ((char)(s[i] | 0x20) == c0 && strncasecmp(s + i, needle, m) == 0)
      return 1;
  return 0;
}

static int starts_ci(const char *s, size_t n, const char *prefix)
{
  size_t m = strlen(prefix);
  return n >= m && strncasecmp(s, prefix, m) == 0;
}

aq_format aq_record_detect(const unsigned char *buf, size_t n)
{
  if (n == 0)
    return AQ_FMT_EMPTY;
  if (n >= 2 && buf[0] == 0x1f && buf[1] == 0x8b)
    return AQ_FMT_GZIP;
  if (n >= 4 && memcmp(buf, "PK\x03\x04", 4) == 0)
    return AQ_FMT_GZIP;
  if (n >= 8 && memcmp(buf, "\x89HDF\r\n\x1a\n", 8) == 0)
    return AQ_FMT_HDF5;
  if (n >= 632) { /* SAC: NVHDR is header word 76 (byte 304) */
    int32_t le = get_i32(buf + 304, 0), be = get_i32(buf + 304, 1);
    if (le == 6 || le == 7 || be == 6 || be == 7)
      return AQ_FMT_SAC;
  }
  if (n >= 3 && buf[0] == 'M' && buf[1] == 'S' && buf[2] == 3)
    return AQ_FMT_MSEED; /* miniSEED 3 */
  if (n >= 48) {         /* miniSEED 2: 6-char sequence number, quality, blank */
    int ok = 1;
    for (int i = 0; i < 6 && ok; i++)
      ok = (buf[i] >= '0' && buf[i] <= '9') || buf[i] == ' ' || buf[i] == 0;
    if (ok && strchr("DRQM", buf[6]) && buf[6] && (buf[7] == ' ' || buf[7] == 0))
      return AQ_FMT_MSEED;
  }
  /* Text or binary: NUL or control bytes other than white space mean binary
   * (bytes >= 0x80 are allowed: Shift-JIS, Latin-1, UTF-8 in headers). */
  size_t m = n < AQ_SNIFF_BYTES ? n : AQ_SNIFF_BYTES, ctrl = 0;
  for (size_t i = 0; i < m; i++) {
    unsigned char c = buf[i];
    if (c == 0)
      return AQ_FMT_UNKNOWN_BINARY;
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v')
      ctrl++;
  }
  if (ctrl * 100 > AQ_SNIFF_CTRL_PERCENT * m)
    return AQ_FMT_UNKNOWN_BINARY;

  const char *s = (const char *)buf;
  size_t i = 0;
  if (m >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0) /* UTF-8 byte-order mark */
    i = 3;
  while (i < m && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n'))
    i++;
  if (i < m && s[i] == '<')
    return AQ_FMT_XML;

  /* The first lines. */
  const char *line[AQ_SNIFF_LINES];
  size_t len[AQ_SNIFF_LINES], nl = 0, p = 0;
  while (nl < AQ_SNIFF_LINES && p < m) {
    size_t q = p;
    while (q < m && s[q] != '\n' && s[q] != '\r')
      q++;
    line[nl] = s + p;
    len[nl] = q - p;
    nl++;
    if (q < m && s[q] == '\r' && q + 1 < m && s[q + 1] == '\n')
      q++;
    p = q + 1;
  }
  if (nl == 0)
    return AQ_FMT_TEXT;
  if (starts_ci(line[0], len[0], "Origin Time"))
    return AQ_FMT_KNET;
  if (has_ci(line[0], len[0], "accelerogram") && has_ci(line[0], len[0], "GNS Science"))
    return AQ_FMT_GEONET;
  for (size_t k = 0; k < nl; k++)
    if (starts_ci(line[k], len[k], "EVENT_NAME:") ||
        starts_ci(line[k], len[k], "EVENT_ID:") ||
        starts_ci(line[k], len[k], "ESM_"))
      return AQ_FMT_ESM;
  if (has_ci(line[0], len[0], "(Format v") && has_ci(line[0], len[0], "lines)"))
    return AQ_FMT_COSMOS;
  if (len[0] >= 2 && line[0][0] >= '0' && line[0][0] <= '9' && line[0][1] == ' ' &&
      (has_ci(line[0], len[0], "ACCELEROGRAM") || has_ci(line[0], len[0], "UNKNOWN") ||
       has_ci(line[0], len[0], "VELOCITY") || has_ci(line[0], len[0], "DISPLACEMENT")))
    return AQ_FMT_SMC; /* (velocity and displacement read to be refused as such) */
  if (aq_bhrc_sniff(buf, m))
    return AQ_FMT_BHRC;
  if (aq_asa_sniff(buf, m))
    return AQ_FMT_ASA;
  if (aq_nsmn_sniff(buf, m))
    return AQ_FMT_NSMN;
  if (aq_renadic_sniff(buf, m)) /* before CSMIP, whose headers it shares */
    return AQ_FMT_RENADIC;
  for (size_t k = 1; k < nl; k++) /* CSMIP V1/V2, read by the COSMOS reader */
    if (has_ci(line[0], len[0], "ACCELEROGRAM") &&
        (has_ci(line[k], len[k], "STATION NO.") || has_ci(line[k], len[k], "STATION ID.")))
      return AQ_FMT_COSMOS;
  if (aq_nptsdt_sniff(buf, n)) /* the whole file: its count decides */
    return AQ_FMT_NPTS_DT;
  /* PEER: a line with NPTS and DT followed by values, after free text */
  size_t tb[AQ_SNIFF_LINES], te[AQ_SNIFF_LINES];
  int nt = 0;
  if (aq_at2_sniff(buf, m, tb, te, &nt, AQ_SNIFF_LINES)) {
    for (int j = 0; j < nt; j++) {
      if (has_ci(s + tb[j], te[j] - tb[j], "VELOCITY"))
        return AQ_FMT_PEER_VT2;
      if (has_ci(s + tb[j], te[j] - tb[j], "DISPLACEMENT"))
        return AQ_FMT_PEER_DT2;
    }
    return AQ_FMT_AT2;
  }
  return AQ_FMT_TEXT;
}

const char *aq_format_describe(aq_format fmt)
{
  switch (fmt) {
  case AQ_FMT_UNKNOWN_BINARY:
    return "binary data that is neither SAC (NVHDR, header word 76 at byte 304, "
           "is not 6 in either byte order) nor miniSEED";
  case AQ_FMT_SAC:
    return "SAC binary";
  case AQ_FMT_AT2:
    return "PEER NGA acceleration (.AT2)";
  case AQ_FMT_TEXT:
    return "CSV or plain text";
  case AQ_FMT_PEER_VT2:
    return "a PEER velocity time series (.VT2), not acceleration: read the .AT2 "
           "of the same record";
  case AQ_FMT_PEER_DT2:
    return "a PEER displacement time series (.DT2), not acceleration: read the "
           ".AT2 of the same record";
  case AQ_FMT_MSEED:
    return "miniSEED";
  case AQ_FMT_COSMOS:
    return "COSMOS strong-motion format (or CSMIP V1/V2)";
  case AQ_FMT_SMC:
    return "USGS SMC format";
  case AQ_FMT_KNET:
    return "K-NET/KiK-net ASCII";
  case AQ_FMT_ESM:
    return "ESM/ITACA ASCII";
  case AQ_FMT_XML:
    return "XML (StationXML or QuakeML metadata?), not a record";
  case AQ_FMT_HDF5:
    return "HDF5 (an archquake results file?), not a record";
  case AQ_FMT_GZIP:
    return "a compressed file (gzip or zip), which is not supported: "
           "decompress it first";
  case AQ_FMT_EMPTY:
    return "an empty file (0 bytes)";
  case AQ_FMT_GEONET:
    return "GeoNet V1A/V2A";
  case AQ_FMT_RENADIC:
    return "RENADIC (Chile) V1";
  case AQ_FMT_BHRC:
    return "BHRC (Iran) VOL1DS";
  case AQ_FMT_ASA:
    return "Mexican ASA 2.0";
  case AQ_FMT_NSMN:
    return "AFAD/NSMN (Turkey) ASCII";
  case AQ_FMT_NPTS_DT:
    return "text with \"NPTS DT\" on its first line";
  }
  return "?";
}

/* ---- miniSEED and its StationXML ---------------------------------------- */

#define MSEED_XML_MAX_BYTES (64L << 20) /* a StationXML larger than this is refused */
#define MSEED_XML_SNIFF 1024            /* bytes looked at for "<FDSNStationXML" */

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
  char list[300] = "";
  size_t len = 0, shown = 0;
  if (nhit > 1)
    snprintf(list, sizeof list, "%s and %s", xs[first].name, xs[second].name);
  else
    for (size_t j = 0; j < nx && len + 60 < sizeof list; j++, shown++)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", j ? ", " : "", xs[j].name);
  if (nhit > 1)
    return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                        "expected one response for %s at its start %s, got %zu that match: %s",
                        id, ch->reference, nhit, list);
  return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                      "expected a response for %s at its start %s, got none%s%s%s in %s%s",
                      id, ch->reference, nsame ? " (its epochs: " : "", nsame ? spans : "",
                      nsame ? ")" : "", list,
                      shown < nx ? " and more" : "");
}

/* aq_mseed_parse, then, with opts->responses, each channel's response. */
static aq_status mseed_read(const unsigned char *buf, size_t n, const char *name,
                            const aq_read_opts *opts, aq_raw_file *raw, aq_error *err)
{
  aq_status s = aq_mseed_parse(buf, n, name, NULL, raw, err);
  if (s != AQ_OK || !opts || !opts->nresponses)
    return s;
  size_t nx = opts->nresponses < AQ_RESPONSES_MAX ? opts->nresponses : AQ_RESPONSES_MAX;
  xml_file *xs = calloc(nx, sizeof *xs);
  if (!xs)
    s = aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  for (size_t j = 0; xs && j < nx; j++)
    xs[j].name = opts->responses[j];
  for (size_t i = 0; s == AQ_OK && i < raw->nchan; i++)
    s = match_response(xs, nx, &raw->chan[i], name, err);
  for (size_t j = 0; xs && j < nx; j++) {
    free(xs[j].bytes);
    aq_response_free(&xs[j].resp);
  }
  free(xs);
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

/* Does a channel name say vertical?  Its words (split at anything not a
 * letter or digit, trailing digits dropped: KiK-net "UD2") UD, UP, U, Z, V,
 * VERT, VERTICAL, DOWN, or a SEED code of three letters ending in Z. */
static int channel_says_vertical(const char *name)
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

/* "path" or "path#CHANNEL" (the channel's name, or its 1-based number when
 * it has none) into out. */
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

/* The quantity the file name says, by its words (split at anything not a
 * letter or digit, and between a lower- and an upper-case letter: "RawVel"):
 * velocity (vel, velo, veloc, velocity, VT2) or displacement (disp, displ,
 * displacement, DT2); the word in *word. */
static aq_quantity name_quantity(const char *path, char *word, size_t cap)
{
  static const char *const vel[] = {"vel", "velo", "veloc", "velocity", "velocities", "vt2"};
  static const char *const disp[] = {"disp", "displ", "displacement", "displacements", "dt2"};
  const char *base = strrchr(path, '/');
  const char *p = base ? base + 1 : path;
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

/* AQ_OK when nothing the file says contradicts acceleration; else
 * AQ_EUNITS naming the evidence: what the file says the values are, units
 * of velocity or displacement, the file's name, or a SEED instrument code
 * of a sensor that does not record acceleration (unless the file states
 * acceleration itself: a record converted by the user keeps its code). */
static aq_status check_acceleration(const aq_raw_channel *ch, const char *path,
                                    const char *label, aq_error *err)
{
  char ev[200] = "", word[64];
  aq_quantity q = AQ_QUANTITY_UNSTATED;
  if (ch->quantity == AQ_QUANTITY_VELOCITY || ch->quantity == AQ_QUANTITY_DISPLACEMENT) {
    q = (aq_quantity)ch->quantity;
    snprintf(ev, sizeof ev, "%s", ch->quantity_said[0] ? ch->quantity_said : "the file says so");
  } else if ((q = aq_units_quantity(ch->units)) == AQ_QUANTITY_VELOCITY ||
             q == AQ_QUANTITY_DISPLACEMENT) {
    snprintf(ev, sizeof ev, "units \"%s\"%s%s", ch->units, ch->units_from[0] ? ", " : "",
             ch->units_from);
  } else if ((q = name_quantity(path, word, sizeof word)) != AQ_QUANTITY_UNSTATED) {
    snprintf(ev, sizeof ev, "the file name says \"%s\"", word);
  } else if (ch->quantity != AQ_QUANTITY_ACCELERATION && instrument_not_acceleration(ch->channel)) {
    q = ch->channel[1] == 'M' ? AQ_QUANTITY_DISPLACEMENT : AQ_QUANTITY_VELOCITY;
    snprintf(ev, sizeof ev, "SEED channel %s: instrument code %c, %s", ch->channel,
             ch->channel[1], instrument_not_acceleration(ch->channel));
  }
  if (!ev[0])
    return AQ_OK;
  return aq_error_set(err, AQ_EUNITS, label, -1, -1, "quantity",
                      "expected ground acceleration, got %s (%s); archquake reads "
                      "acceleration only: convert the record to acceleration first",
                      ch->channel[1] == 'M' && q == AQ_QUANTITY_DISPLACEMENT &&
                              strstr(ev, "mass position")
                          ? "a mass position"
                          : aq_quantity_name(q),
                      ev);
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
  char label[AQ_UNITS_GLOB_MAX + 24];
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
      snprintf(rec->units_conflict, sizeof rec->units_conflict,
               "the file states %s, the rule --units '%.120s=%s' reads it as %s",
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
    snprintf(rec->polarity_note, sizeof rec->polarity_note,
             "reversed: the sensitivity is %.9g counts per m/s2%s%s%s, and its sign is "
             "applied to the samples",
             ch->counts_per_mps2, ch->units_from[0] ? " (" : "", ch->units_from,
             ch->units_from[0] ? ")" : "");

  /* Vertical: what the file states, else its dip, else the channel name;
   * a name saying vertical over a field saying horizontal is vertical, and
   * the conflict is noted. */
  aq_vertical_by by = AQ_VERTICAL_BY_NONE;
  int says = channel_says_vertical(ch->channel);
  if (ch->vertical > 0)
    by = AQ_VERTICAL_BY_STATED;
  else if (ch->vertical < 0 && isfinite(ch->dip_deg) &&
           fabs(ch->dip_deg) >= AQ_VERTICAL_DIP_MIN_DEG)
    by = AQ_VERTICAL_BY_DIP;
  else if (says && ch->vertical < 0 && !isfinite(ch->dip_deg))
    by = AQ_VERTICAL_BY_NAME;
  else if (says) { /* a field says horizontal: stated, or a dip near 0 */
    by = AQ_VERTICAL_BY_NAME_OVER_FIELD;
    char field[96];
    if (ch->orient_said[0])
      snprintf(field, sizeof field, "%s", ch->orient_said);
    else if (isfinite(ch->dip_deg))
      snprintf(field, sizeof field, "dip %g deg", ch->dip_deg);
    else
      snprintf(field, sizeof field, "azimuth %g deg", ch->azimuth_deg);
    snprintf(rec->vertical_note, sizeof rec->vertical_note,
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
    snprintf(why, cap, "by its channel name: %s", rec->vertical_note);
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
  char why[260];
  vertical_why(rec, why, sizeof why);
  return aq_error_set(err, AQ_EUNSUPPORTED, rec->path, -1, -1, "channel",
                      "expected a horizontal component, got channel \"%s\", which "
                      "the file identifies as vertical (%s); a vertical "
                      "component is not horizontal excitation (give "
                      "--accept-vertical to run it anyway)",
                      rec->channel, why);
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
  aq_format fmt = aq_record_detect(buf, n);
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
                        aq_format_describe(fmt));
  default:
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "format",
                        "looks like %s", aq_format_describe(fmt));
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
    char name[4200];
    snprintf(name, sizeof name, "%s", path);
    if (!want && raw.nchan > 1)
      snprintf(name, sizeof name, "%s#%s", path, rule);
    s = select_channel(&raw, want, file, opts, &ichan, &e);
    st = add_item(set, name, &raw, ichan, file, opts, s, &e);
  } else {
    for (size_t c = 0; c < raw.nchan && st == AQ_OK; c++) {
      char label[4200];
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
  char why[260], line[4600];
  vertical_why(&it->rec, why, sizeof why);
  snprintf(line, sizeof line,
           "%s: skipped: the file identifies channel \"%s\" as vertical (%s), which is not "
           "horizontal excitation (give --accept-vertical to run it)",
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
      aq_format fmt = aq_record_detect(buf, size);
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
