/* sac.c: SAC binary reader (see reader.h; format notes in docs/sac-format.md).
 *
 * A SAC file is a 632-byte header (70 float32 words, 40 int32 words, then
 * 8-byte strings, KEVNM 16) followed by NPTS float32 samples, all in one byte
 * order; header version 7 adds a footer of 22 float64 words after the data.
 * The byte order is the one in which NVHDR (word 76, byte 304) reads 6 or 7.
 * -12345 marks an undefined value.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "fixed.h"
#include "reader.h"

#define SAC_HEADER_BYTES 632
#define SAC_FOOTER7_BYTES (22 * 8)
#define SAC_UNDEF (-12345.0)
#define SAC_IUNDEF (-12345)

/* Float words. */
enum { W_DELTA = 0, W_SCALE = 3, W_B = 5, W_E = 6, W_CMPAZ = 57, W_CMPINC = 58 };
/* Integer words (word numbers, byte = 4 * word). */
enum {
  W_NZYEAR = 70, W_NZJDAY, W_NZHOUR, W_NZMIN, W_NZSEC, W_NZMSEC, W_NVHDR,
  W_NPTS = 79, W_IFTYPE = 85, W_IDEP = 86, W_LEVEN = 105
};
/* Enumerated values. */
enum { SAC_ITIME = 1, SAC_IUNKN = 5, SAC_IDISP = 6, SAC_IVEL = 7, SAC_IACC = 8,
       SAC_IVOLTS = 50 };
/* String byte offsets. */
enum { K_STNM = 440, K_EVNM = 448, K_HOLE = 464, K_CMPNM = 600, K_NETWK = 608 };

/* DELTA is float32: the intended decimal step is recovered as the shortest
 * decimal with at most this many significant digits that rounds to the same
 * float32 (float32 carries 7.2 decimal digits); if none does, DELTA is taken
 * as stored. */
#define SAC_DELTA_SIG_DIGITS 7

/* E, the time of the last sample, must lie within this many samples of
 * B + (NPTS-1) DELTA (float32 E and B of a record 15 h after its reference
 * time are rounded to 0.004 s, 0.2 samples at 100 samples/s). */
#define SAC_E_TOL_SAMPLES 0.5

typedef struct {
  const unsigned char *b;
  int big;
} sac_hdr;

static uint32_t rd_u32(const unsigned char *p, int big)
{
  return big ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]
             : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static float rd_f32(const unsigned char *p, int big)
{
  uint32_t u = rd_u32(p, big);
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static double rd_f64(const unsigned char *p, int big)
{
  uint64_t u = 0;
  for (int i = 0; i < 8; i++)
    u |= (uint64_t)p[big ? i : 7 - i] << (8 * (7 - i));
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}

static float hf(const sac_hdr *h, int word) { return rd_f32(h->b + 4 * word, h->big); }
static int32_t hi(const sac_hdr *h, int word) { return (int32_t)rd_u32(h->b + 4 * word, h->big); }

/* Copy a header string (len bytes at off), cut at NUL, trailing blanks
 * removed, "-12345" meaning undefined -> "". */
static void hstr(const sac_hdr *h, int off, int len, char *out, size_t cap)
{
  size_t k = 0;
  for (int i = 0; i < len && k + 1 < cap; i++) {
    unsigned char c = h->b[off + i];
    if (c == 0)
      break;
    out[k++] = (c >= 0x20 && c < 0x7f) ? (char)c : '?';
  }
  while (k > 0 && out[k - 1] == ' ')
    k--;
  out[k] = '\0';
  /* leading blanks too */
  size_t s = 0;
  while (out[s] == ' ')
    s++;
  if (s)
    memmove(out, out + s, k - s + 1);
  if (strcmp(out, "-12345") == 0)
    out[0] = '\0';
}

static const char *idep_name(int32_t v)
{
  switch (v) {
  case SAC_IUNDEF:
    return "undefined (-12345)";
  case SAC_IUNKN:
    return "IUNKN (5)";
  case SAC_IDISP:
    return "IDISP (6, displacement)";
  case SAC_IVEL:
    return "IVEL (7, velocity)";
  case SAC_IACC:
    return "IACC (8)";
  case SAC_IVOLTS:
    return "IVOLTS (50, volts)";
  }
  return "an unknown code";
}

/* Recover the intended decimal step from a float32 DELTA (rule above). */
static double sac_delta_decimal(float f)
{
  for (int digits = 1; digits <= SAC_DELTA_SIG_DIGITS; digits++) {
    char txt[40];
    snprintf(txt, sizeof txt, "%.*e", digits - 1, (double)f);
    double d = strtod(txt, NULL);
    if ((float)d == f)
      return d;
  }
  return (double)f;
}

/* NZYEAR..NZMSEC -> "YYYY-MM-DDTHH:MM:SS.mmmZ", or "" if any is undefined
 * or out of range. */
static void sac_reference(const sac_hdr *h, char *out, size_t cap)
{
  long y = hi(h, W_NZYEAR), jd = hi(h, W_NZJDAY), hh = hi(h, W_NZHOUR),
       mi = hi(h, W_NZMIN), ss = hi(h, W_NZSEC), ms = hi(h, W_NZMSEC);
  int mon, day;
  out[0] = '\0';
  if (hh < 0 || hh > 23 || mi < 0 || mi > 59 || ss < 0 || ss > 60 || ms < 0 || ms > 999 ||
      !aq_month_day((int)y, (int)jd, &mon, &day) ||
      !aq_iso_time(out, cap, (int)y, mon, day, (int)hh, (int)mi, (double)ss + ms * 1e-3))
    out[0] = '\0';
}

aq_status aq_sac_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts; /* a SAC file states everything it can */
  memset(raw, 0, sizeof *raw);
  if (n < SAC_HEADER_BYTES)
    return aq_error_set(err, AQ_EFORMAT, name, -1, (long)n, "header",
                        "expected a %d-byte SAC header, got only %zu bytes",
                        SAC_HEADER_BYTES, n);
  sac_hdr h = {buf, 0};
  int32_t nv = hi(&h, W_NVHDR);
  if (nv != 6 && nv != 7) {
    h.big = 1;
    nv = hi(&h, W_NVHDR);
  }
  if (nv != 6 && nv != 7)
    return aq_error_set(err, AQ_EFORMAT, name, -1, 4L * W_NVHDR, "header NVHDR",
                        "expected 6 in either byte order, got %ld (little-endian) "
                        "and %ld (big-endian)",
                        (long)(int32_t)rd_u32(buf + 4 * W_NVHDR, 0),
                        (long)(int32_t)rd_u32(buf + 4 * W_NVHDR, 1));

  int32_t iftype = hi(&h, W_IFTYPE), leven = hi(&h, W_LEVEN), npts = hi(&h, W_NPTS);
  if (iftype != SAC_ITIME)
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, 4L * W_IFTYPE,
                        "header IFTYPE",
                        "expected ITIME (1, a time series), got %ld", (long)iftype);
  if (leven != 1)
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, 4L * W_LEVEN,
                        "header LEVEN",
                        "expected 1 (evenly sampled), got %ld", (long)leven);
  if (npts < 1)
    return aq_error_set(err, AQ_EFORMAT, name, -1, 4L * W_NPTS, "header NPTS",
                        "expected a positive number of samples, got %ld", (long)npts);
  size_t footer = nv == 7 ? SAC_FOOTER7_BYTES : 0;
  size_t data_bytes = n - SAC_HEADER_BYTES;
  size_t want = (size_t)npts * 4 + footer;
  if (data_bytes != want)
    return aq_error_set(
        err, AQ_EFORMAT, name, -1, 4L * W_NPTS, "header NPTS",
        "expected %zu bytes after the header for NPTS = %ld%s, got %zu (%s)", want,
        (long)npts, footer ? " and the version-7 footer" : "", data_bytes,
        data_bytes < want ? "file truncated" : "trailing bytes");

  float delta_f = hf(&h, W_DELTA);
  double delta = sac_delta_decimal(delta_f), b = hf(&h, W_B), e = hf(&h, W_E);
  if (nv == 7) { /* the footer's float64 DELTA, B and E, where they agree
                   with the header's float32 copies */
    const unsigned char *ft = buf + SAC_HEADER_BYTES + (size_t)npts * 4;
    double d64 = rd_f64(ft, h.big), b64 = rd_f64(ft + 8, h.big), e64 = rd_f64(ft + 16, h.big);
    if (isfinite(d64) && (float)d64 == delta_f)
      delta = d64;
    if (isfinite(b64) && (float)b64 == (float)b)
      b = b64;
    if (isfinite(e64) && (float)e64 == (float)e)
      e = e64;
  }
  if (!isfinite(delta) || !(delta > 0) || delta == SAC_UNDEF)
    return aq_error_set(err, AQ_EFORMAT, name, -1, 4L * W_DELTA, "header DELTA",
                        "expected a sample interval > 0 s, got %g", delta);
  if (!isfinite(b) || b == SAC_UNDEF)
    b = 0.0;
  else if (isfinite(e) && e != SAC_UNDEF) {
    /* the last sample's time, as the header states it twice */
    double last = b + (double)(npts - 1) * delta;
    if (fabs(e - last) > SAC_E_TOL_SAMPLES * delta)
      return aq_error_set(err, AQ_EFORMAT, name, -1, 4L * W_E, "header E",
                          "expected B + (NPTS-1)*DELTA = %.9g + %ld*%.9g = %.9g s (within "
                          "half a sample), got E = %.9g s: the header contradicts itself",
                          b, (long)npts - 1, delta, last, e);
  }

  aq_status s = aq_raw_file_alloc(raw, 1, name, err);
  if (s != AQ_OK)
    return s;
  aq_raw_channel *ch = &raw->chan[0];
  double *v = malloc((size_t)npts * sizeof *v);
  if (!v) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL,
                        "out of memory for %ld samples", (long)npts);
  }
  for (size_t k = 0; k < (size_t)npts; k++) {
    size_t off = SAC_HEADER_BYTES + 4 * k;
    float x = rd_f32(buf + off, h.big);
    if (!isfinite(x)) {
      free(v);
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_EVALUE, name, -1, (long)off, "sample",
                          "expected a finite number at sample %zu, got %s", k,
                          isnan(x) ? "NaN" : "Inf");
    }
    v[k] = (double)x;
  }
  ch->values = v;
  ch->npts = (size_t)npts;
  ch->dt_s = delta;
  ch->begin_s = b;
  snprintf(raw->format, sizeof raw->format, "%s", h.big ? "sac-be" : "sac-le");
  sac_reference(&h, ch->reference, sizeof ch->reference);
  hstr(&h, K_NETWK, 8, ch->network, sizeof ch->network);
  hstr(&h, K_STNM, 8, ch->station, sizeof ch->station);
  hstr(&h, K_HOLE, 8, ch->location, sizeof ch->location);
  hstr(&h, K_CMPNM, 8, ch->channel, sizeof ch->channel);
  hstr(&h, K_EVNM, 16, raw->event, sizeof raw->event);
  snprintf(raw->event_name, sizeof raw->event_name, "%s", raw->event); /* KEVNM: the event alone */

  /* Units: IDEP = IACC states nm/s^2; SCALE is the sensitivity that
   * mseed2sac -M writes (counts per m/s^2), used when the values are counts;
   * its sign is kept (a negative sensitivity: the channel's polarity,
   * which record.c applies and reports). */
  int32_t idep = hi(&h, W_IDEP);
  if (idep == SAC_IACC)
    snprintf(ch->units, sizeof ch->units, "nm/s2");
  else
    snprintf(ch->units_said, sizeof ch->units_said, "header IDEP: %s",
             idep_name(idep));
  if (idep == SAC_IACC || idep == SAC_IVEL || idep == SAC_IDISP) {
    ch->quantity = idep == SAC_IACC   ? AQ_QUANTITY_ACCELERATION
                   : idep == SAC_IVEL ? AQ_QUANTITY_VELOCITY
                                      : AQ_QUANTITY_DISPLACEMENT;
    snprintf(ch->quantity_said, sizeof ch->quantity_said, "header IDEP: %s", idep_name(idep));
    snprintf(ch->units_from, sizeof ch->units_from, "header IDEP: %s", idep_name(idep));
  }
  double scale = hf(&h, W_SCALE);
  if (isfinite(scale) && scale != 0 && scale != SAC_UNDEF) {
    ch->counts_per_mps2 = scale;
    if (!ch->units_from[0])
      snprintf(ch->units_from, sizeof ch->units_from, "header SCALE");
  }

  /* Orientation: CMPAZ (deg from north), CMPINC (deg from vertical up). */
  double az = hf(&h, W_CMPAZ), inc = hf(&h, W_CMPINC);
  if (isfinite(az) && az != SAC_UNDEF)
    ch->azimuth_deg = az;
  if (isfinite(inc) && inc != SAC_UNDEF && inc >= 0 && inc <= 180) {
    ch->dip_deg = inc - 90.0; /* SEED dip: CMPINC 0 (up) is -90 */
    snprintf(ch->orient_said, sizeof ch->orient_said, "header CMPINC: %g", inc);
  }
  return AQ_OK;
}
