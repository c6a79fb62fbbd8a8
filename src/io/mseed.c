/* mseed.c: miniSEED 2 through libmseed (reader.h).
 *
 * libmseed unpacks each record (msr_parse: header, blockettes, Steim1/2,
 * integer and float encodings); this file groups the records by
 * network.station.location.channel, orders them in time and joins them into
 * one evenly sampled series per channel.  A gap (next record later than the
 * expected next sample by more than half a sample) is refused, naming the
 * channel, the time and the length; an overlap is merged when the
 * overlapping samples are equal and refused otherwise.  Values stay counts
 * (units "counts", counts_per_mps2 = 0): the sensitivity is the StationXML's
 * (stationxml.c).  libmseed's log output is silenced: this library never
 * prints.  libmseed is opened on first use (mseed_lazy.c).
 */
#include <libmseed.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

#define MSEED_MIN_RECLEN 48 /* fixed header 48 bytes: nothing shorter is a record */
#define MSEED_MAX_RECLEN (1 << 20)
#define MSEED_SAME_RATE_REL 1e-4 /* sample rates differing less agree (as libmseed) */

typedef struct {
  size_t chan;      /* index in the channel list */
  int64_t start_us; /* first sample, microseconds since 1970 */
  double rate_hz;
  size_t n;
  double *v;
  long offset; /* byte offset of the record, for messages */
} mseed_piece;

static void log_nothing(char *msg) { (void)msg; }
static pthread_once_t log_once = PTHREAD_ONCE_INIT;
static void silence_libmseed(void) { ms_loginit(log_nothing, NULL, log_nothing, NULL); }

static int cmp_piece(const void *a, const void *b)
{
  const mseed_piece *x = a, *y = b;
  if (x->chan != y->chan)
    return x->chan < y->chan ? -1 : 1;
  if (x->start_us != y->start_us)
    return x->start_us < y->start_us ? -1 : 1;
  return x->offset < y->offset ? -1 : x->offset > y->offset;
}

/* ISO-8601 of a libmseed time (microseconds since 1970), to the ms. */
static void iso_us(int64_t us, char *out, size_t cap)
{
  int64_t ms = us >= 0 ? (us + 500) / 1000 : -((-us + 500) / 1000);
  if (!aq_iso_from_ms(out, cap, (long long)ms))
    out[0] = '\0';
}

static aq_status add_piece(mseed_piece **pieces, size_t *np, size_t *cap, const MSRecord *msr,
                           size_t chan, long offset, const char *name, aq_error *err)
{
  if (*np == *cap) {
    size_t nc = *cap ? *cap * 2 : 16;
    mseed_piece *p = realloc(*pieces, nc * sizeof *p);
    if (!p)
      return aq_error_set(err, AQ_ENOMEM, name, -1, offset, "record", "out of memory");
    *pieces = p;
    *cap = nc;
  }
  size_t n = (size_t)msr->numsamples;
  double *v = malloc((n ? n : 1) * sizeof *v);
  if (!v)
    return aq_error_set(err, AQ_ENOMEM, name, -1, offset, "record", "out of memory");
  for (size_t k = 0; k < n; k++) {
    double x;
    switch (msr->sampletype) {
    case 'i': x = ((const int32_t *)msr->datasamples)[k]; break;
    case 'f': x = ((const float *)msr->datasamples)[k]; break;
    default: x = ((const double *)msr->datasamples)[k]; break;
    }
    if (!isfinite(x)) {
      free(v);
      return aq_error_set(err, AQ_EVALUE, name, -1, offset, "data",
                          "sample %zu of this record: expected a finite number, got %g", k, x);
    }
    v[k] = x;
  }
  mseed_piece *p = &(*pieces)[(*np)++];
  p->chan = chan;
  p->start_us = msr->starttime;
  p->rate_hz = msr->samprate;
  p->n = n;
  p->v = v;
  p->offset = offset;
  return AQ_OK;
}

/* Join the time-ordered pieces [a, b) of one channel into ch. */
static aq_status join(const mseed_piece *pc, size_t a, size_t b, aq_raw_channel *ch,
                      const char *id, const char *name, aq_error *err)
{
  size_t total = 0;
  for (size_t i = a; i < b; i++)
    total += pc[i].n;
  ch->values = malloc((total ? total : 1) * sizeof *ch->values);
  if (!ch->values)
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, id, "out of memory");
  double rate = pc[a].rate_hz;
  double period_us = 1e6 / rate;
  size_t k = 0;
  for (size_t i = a; i < b; i++) {
    const mseed_piece *p = &pc[i];
    if (fabs(p->rate_hz / rate - 1.0) > MSEED_SAME_RATE_REL)
      return aq_error_set(err, AQ_EFORMAT, name, -1, p->offset, id,
                          "sample rate %g Hz differs from the channel's %g Hz", p->rate_hz,
                          rate);
    size_t skip = 0;
    if (k > 0) {
      double expect_us = (double)pc[a].start_us + (double)k * period_us;
      double off_samples = ((double)p->start_us - expect_us) / period_us;
      char when[40];
      iso_us(p->start_us, when, sizeof when);
      if (off_samples > 0.5)
        return aq_error_set(err, AQ_EFORMAT, name, -1, p->offset, id,
                            "gap of %.6g s before %s: expected contiguous data (cut the "
                            "record at the gap, e.g. with dataselect)",
                            off_samples / rate, when);
      if (off_samples < -0.5) {
        double over = floor(-off_samples + 0.5);
        if (over > (double)k)
          over = (double)k;
        skip = (size_t)over;
        if (skip > p->n)
          skip = p->n;
        for (size_t j = 0; j < skip; j++)
          if (p->v[j] != ch->values[k - (size_t)over + j])
            return aq_error_set(err, AQ_EFORMAT, name, -1, p->offset, id,
                                "overlap of %zu samples at %s whose values differ (sample "
                                "%zu: %.10g vs %.10g): expected agreeing or no overlap",
                                (size_t)over, when, j, p->v[j],
                                ch->values[k - (size_t)over + j]);
      }
    }
    memcpy(ch->values + k, p->v + skip, (p->n - skip) * sizeof *p->v);
    k += p->n - skip;
  }
  ch->npts = k;
  ch->dt_s = 1.0 / rate;
  iso_us(pc[a].start_us, ch->reference, sizeof ch->reference);
  ch->begin_s = 0;
  return AQ_OK;
}

/* Bytes per sample of the encodings read; 0 for others. */
static int sample_bytes(int encoding)
{
  switch (encoding) {
  case DE_INT16: return 2;
  case DE_INT32: return 4;
  case DE_FLOAT32: return 4;
  case DE_FLOAT64: return 8;
  case DE_STEIM1:
  case DE_STEIM2: return 1; /* compressed: at most the 64-byte frames present */
  default: return 0;
  }
}

/* Unpack the header of the record at rec (reclen bytes) into a copy in
 * scratch and check that its payload lies inside the record before libmseed
 * decodes it: libmseed 2 copies samplecnt x sample size bytes from the data
 * offset without checking them against the record length. */
static aq_status check_payload(const unsigned char *rec, int reclen, char *scratch,
                               const char *name, long pos, aq_error *err)
{
  memcpy(scratch, rec, (size_t)reclen);
  MSRecord *msr = NULL;
  int rc = msr_parse(scratch, reclen, &msr, reclen, 0, 0);
  if (rc != MS_NOERROR || !msr || !msr->fsdh) {
    msr_free(&msr);
    return aq_error_set(err, AQ_EFORMAT, name, -1, pos, "record header",
                        "libmseed could not unpack this %d-byte record header (%s)", reclen,
                        rc > 0 ? "record incomplete" : ms_errorstr(rc));
  }
  long off = msr->fsdh->data_offset;
  int64_t cnt = msr->samplecnt;
  int enc = msr->encoding, size = sample_bytes(enc);
  msr_free(&msr);
  if (cnt == 0)
    return AQ_OK;
  if (size == 0)
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, pos, "encoding",
                        "expected integer, float or Steim1/2 samples, got encoding %d", enc);
  if (off < MSEED_MIN_RECLEN || off >= reclen || cnt < 0 ||
      (size > 1 && cnt * size > (int64_t)(reclen - off)))
    return aq_error_set(err, AQ_EFORMAT, name, -1, pos, "data offset",
                        "expected %lld samples of %d bytes from byte %ld inside the %d-byte "
                        "record, they do not fit",
                        (long long)cnt, size, off, reclen);
  return AQ_OK;
}

aq_status aq_mseed_parse(const unsigned char *buf, size_t n, const char *name,
                         const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  if (aq_mseed_load(name, err) != AQ_OK)
    return AQ_EUNSUPPORTED;
  pthread_once(&log_once, silence_libmseed);
  mseed_piece *pc = NULL;
  size_t np = 0, cap = 0;
  char (*ids)[64] = NULL; /* NET.STA.LOC.CHA of each channel */
  size_t nid = 0;
  char *scratch = NULL;
  aq_status s = AQ_OK;
  size_t pos = 0;
  while (pos < n && s == AQ_OK) {
    size_t left = n - pos;
    if (left < MSEED_MIN_RECLEN) {
      s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "record",
                       "expected a %d-byte miniSEED header, got %zu bytes (file truncated?)",
                       MSEED_MIN_RECLEN, left);
      break;
    }
    int blen = left > MSEED_MAX_RECLEN ? MSEED_MAX_RECLEN : (int)left;
    int reclen = ms_detect((const char *)buf + pos, blen);
    if (reclen <= 0 || (size_t)reclen > left) {
      if (reclen > 0) {
        s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "record length",
                         "expected %d bytes for this record, got %zu (file truncated?)",
                         reclen, left);
      } else {
        s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "record",
                         "expected a miniSEED 2 record (sequence number, quality "
                         "D/R/Q/M), got bytes that are not one%s",
                         left >= 2 && buf[pos] == 'M' && buf[pos + 1] == 'S'
                             ? " (miniSEED 3 is not read: convert it to miniSEED 2)"
                             : "");
      }
      break;
    }
    char *tmp = realloc(scratch, (size_t)reclen);
    if (!tmp) {
      s = aq_error_set(err, AQ_ENOMEM, name, -1, (long)pos, "record", "out of memory");
      break;
    }
    scratch = tmp;
    MSRecord *msr = NULL;
    s = check_payload(buf + pos, reclen, scratch, name, (long)pos, err);
    if (s != AQ_OK)
      break;
    memcpy(scratch, buf + pos, (size_t)reclen);
    int rc = msr_parse(scratch, reclen, &msr, reclen, 1, 0);
    if (rc != MS_NOERROR || !msr) {
      s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "record",
                       "libmseed could not unpack this %d-byte record (%s)", reclen,
                       rc > 0 ? "record incomplete" : ms_errorstr(rc));
      msr_free(&msr);
      break;
    }
    if (msr->numsamples > 0) {
      if (msr->sampletype != 'i' && msr->sampletype != 'f' && msr->sampletype != 'd') {
        s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "encoding",
                         "expected numeric samples, got sample type '%c'", msr->sampletype);
      } else if (!(msr->samprate > 0) || !isfinite(msr->samprate)) {
        s = aq_error_set(err, AQ_EFORMAT, name, -1, (long)pos, "sample rate",
                         "expected > 0 Hz, got %g", msr->samprate);
      } else {
        char id[64];
        snprintf(id, sizeof id, "%s.%s.%s.%s", msr->network, msr->station, msr->location,
                 msr->channel);
        size_t c = 0;
        while (c < nid && strcmp(ids[c], id) != 0)
          c++;
        if (c == nid) {
          void *t = realloc(ids, (nid + 1) * sizeof *ids);
          if (!t) {
            s = aq_error_set(err, AQ_ENOMEM, name, -1, (long)pos, "record", "out of memory");
          } else {
            ids = t;
            snprintf(ids[nid++], sizeof ids[0], "%s", id);
            aq_raw_channel *ch = aq_raw_add_channel(raw, name, err);
            if (!ch) {
              s = AQ_ENOMEM;
            } else {
              snprintf(ch->network, sizeof ch->network, "%s", msr->network);
              snprintf(ch->station, sizeof ch->station, "%s", msr->station);
              snprintf(ch->location, sizeof ch->location, "%s", msr->location);
              snprintf(ch->channel, sizeof ch->channel, "%s", msr->channel);
              snprintf(ch->units, sizeof ch->units, "counts");
            }
          }
        }
        if (s == AQ_OK)
          s = add_piece(&pc, &np, &cap, msr, c, (long)pos, name, err);
      }
    }
    msr_free(&msr);
    pos += (size_t)reclen;
  }
  free(scratch);
  if (s == AQ_OK && np == 0)
    s = aq_error_set(err, AQ_EFORMAT, name, -1, 0, "records",
                     "expected data records with samples, got none");
  if (s == AQ_OK) {
    qsort(pc, np, sizeof *pc, cmp_piece);
    for (size_t a = 0; a < np && s == AQ_OK;) {
      size_t b = a;
      while (b < np && pc[b].chan == pc[a].chan)
        b++;
      s = join(pc, a, b, &raw->chan[pc[a].chan], ids[pc[a].chan], name, err);
      a = b;
    }
  }
  for (size_t i = 0; i < np; i++)
    free(pc[i].v);
  free(pc);
  free(ids);
  if (s != AQ_OK) {
    aq_raw_file_free(raw);
    return s;
  }
  snprintf(raw->format, sizeof raw->format, "mseed");
  return AQ_OK;
}
