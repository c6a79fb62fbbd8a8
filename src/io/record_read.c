/* record_read.c: reading one record file (see record.h): its bytes, its
 * format sniffed from them (sniff.c), the parser of that format
 * (reader.h; miniSEED with the responses of its StationXML), the channel
 * asked for, then the one decision of record.c (aq_record_decide).
 */
#include <errno.h>
#include <fnmatch.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "evidence.h"
#include "record.h"
#include "record_impl.h"

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

/* What a parser may be told of opts (NULL for NULL), in *ro. */
const aq_reader_opts *aq_record_reader_opts(const aq_read_opts *opts, aq_reader_opts *ro)
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
  const aq_reader_opts *rop = aq_record_reader_opts(opts, &ro);
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
aq_status aq_record_select_channel(const aq_raw_file *raw, const char *want,
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
    s = aq_record_select_channel(&raw, want, path, opts, &ichan, err);
  if (s == AQ_OK) { /* the samples are scaled where the reader put them */
    s = aq_record_decide_in_place(&raw, ichan, path, opts, rec, err, raw.chan[ichan].values);
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
aq_status aq_record_read_bytes(const char *path, unsigned char **buf, size_t *size,
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
void aq_record_split_channel(const char *path, char *file, size_t cap, const char **want)
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
  aq_record_split_channel(name, buf, cap, &want);
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
  aq_record_split_channel(path, file, sizeof file, &want);
  unsigned char *buf;
  size_t size = 0;
  aq_status s = aq_record_read_bytes(file, &buf, &size, err);
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
