/* record.c: reading a record file, detecting its format from its content,
 * and the units helpers shared by the readers (see record.h, readers.h). */
#include "record.h"

#include <errno.h>
#include <fnmatch.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "../units.h"
#include "readers.h"

/* ---- units ------------------------------------------------------------ */

static const struct {
  const char *word;
  aq_units units;
} units_words[] = {
    {"g", AQ_UNITS_G},           {"gal", AQ_UNITS_GAL},
    {"cm/s2", AQ_UNITS_GAL},     {"cm/s^2", AQ_UNITS_GAL},
    {"cm/s/s", AQ_UNITS_GAL},    {"cm/sec2", AQ_UNITS_GAL},
    {"cm/sec^2", AQ_UNITS_GAL},  {"cm/sec/sec", AQ_UNITS_GAL},
    {"cmps2", AQ_UNITS_GAL},     {"m/s2", AQ_UNITS_MPS2},
    {"m/s^2", AQ_UNITS_MPS2},    {"m/s/s", AQ_UNITS_MPS2},
    {"m/s**2", AQ_UNITS_MPS2},   {"mps2", AQ_UNITS_MPS2},
    {"nm/s2", AQ_UNITS_NMPS2},   {"nm/s^2", AQ_UNITS_NMPS2},
    {"nm/s/s", AQ_UNITS_NMPS2},  {"counts", AQ_UNITS_COUNTS},
};

int aq_units_parse(const char *s, aq_units *out)
{
  if (!s)
    return 0;
  for (size_t i = 0; i < sizeof units_words / sizeof units_words[0]; i++)
    if (strcasecmp(s, units_words[i].word) == 0) {
      *out = units_words[i].units;
      return 1;
    }
  return 0;
}

const char *aq_units_name(aq_units u)
{
  switch (u) {
  case AQ_UNITS_FILE:
    return "file";
  case AQ_UNITS_G:
    return "g";
  case AQ_UNITS_GAL:
    return "gal";
  case AQ_UNITS_MPS2:
    return "m/s2";
  case AQ_UNITS_NMPS2:
    return "nm/s2";
  case AQ_UNITS_COUNTS:
    return "counts";
  }
  return "?";
}

double aq_units_to_mps2(aq_units u)
{
  switch (u) {
  case AQ_UNITS_G:
    return AQ_G0_MPS2;
  case AQ_UNITS_GAL:
    return 0.01;
  case AQ_UNITS_MPS2:
    return 1.0;
  case AQ_UNITS_NMPS2:
    return 1e-9;
  case AQ_UNITS_FILE:
  case AQ_UNITS_COUNTS:
    break;
  }
  return 0.0;
}

aq_units aq_read_opts_units_for(const aq_read_opts *opts, const char *path)
{
  if (!opts)
    return AQ_UNITS_FILE;
  size_t n = opts->nrules < AQ_UNITS_RULES_MAX ? opts->nrules : AQ_UNITS_RULES_MAX;
  for (size_t i = n; i-- > 0;)
    if (path && fnmatch(opts->rules[i].glob, path, 0) == 0)
      return opts->rules[i].units;
  return opts->units;
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

aq_status aq_record_set_names_(aq_record *rec, const char *name, aq_error *err)
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
  for (size_t i = 0; i + m <= n; i++)
    if (strncasecmp(s + i, needle, m) == 0)
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
  for (size_t k = 0; k < nl; k++)
    if (starts_ci(line[k], len[k], "EVENT_NAME:") ||
        starts_ci(line[k], len[k], "EVENT_ID:") ||
        starts_ci(line[k], len[k], "ESM_"))
      return AQ_FMT_ESM;
  if (has_ci(line[0], len[0], "(Format v") && has_ci(line[0], len[0], "lines)"))
    return AQ_FMT_COSMOS;
  if (len[0] >= 2 && line[0][0] >= '0' && line[0][0] <= '9' && line[0][1] == ' ' &&
      has_ci(line[0], len[0], "ACCELEROGRAM"))
    return AQ_FMT_SMC;
  for (size_t k = 0; k < nl && k < 6; k++)
    if (has_ci(line[k], len[k], "NPTS")) {
      for (size_t j = 0; j < k; j++) {
        if (has_ci(line[j], len[j], "VELOCITY"))
          return AQ_FMT_PEER_VT2;
        if (has_ci(line[j], len[j], "DISPLACEMENT"))
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
    return "miniSEED, which is not supported: convert it with mseed2sac -M "
           "'NET,STA,LOC,CHA,...,SENSITIVITY,...' and read the SAC file with "
           "--units counts";
  case AQ_FMT_COSMOS:
    return "COSMOS strong-motion format, which is not supported: export it as "
           "CSV (time, acceleration)";
  case AQ_FMT_SMC:
    return "USGS SMC format, which is not supported: export it as CSV (time, "
           "acceleration)";
  case AQ_FMT_KNET:
    return "K-NET/KiK-net ASCII, which is not supported: export it as CSV "
           "(time, acceleration) in gal";
  case AQ_FMT_ESM:
    return "ESM/ITACA ASCII, which is not supported: export it as CSV (time, "
           "acceleration)";
  case AQ_FMT_XML:
    return "XML (StationXML or QuakeML metadata?), not a record";
  case AQ_FMT_HDF5:
    return "HDF5 (an archquake results file?), not a record";
  case AQ_FMT_GZIP:
    return "a compressed file (gzip or zip), which is not supported: "
           "decompress it first";
  case AQ_FMT_EMPTY:
    return "an empty file (0 bytes)";
  }
  return "?";
}

aq_status aq_record_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_record *rec,
                          aq_error *err)
{
  memset(rec, 0, sizeof *rec);
  aq_format fmt = aq_record_detect(buf, n);
  switch (fmt) {
  case AQ_FMT_SAC:
    return aq_sac_parse(buf, n, name, opts, rec, err);
  case AQ_FMT_AT2:
    return aq_at2_parse(buf, n, name, opts, rec, err);
  case AQ_FMT_TEXT:
    return aq_csv_parse(buf, n, name, opts, rec, err);
  case AQ_FMT_EMPTY:
    return aq_error_set(err, AQ_EFORMAT, name, -1, -1, NULL,
                        "expected a record, got an empty file (0 bytes)");
  case AQ_FMT_UNKNOWN_BINARY:
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "format",
                        "expected SAC, PEER AT2 or CSV, got %s",
                        aq_format_describe(fmt));
  default:
    return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "format",
                        "looks like %s", aq_format_describe(fmt));
  }
}

aq_status aq_record_read(const char *path, const aq_read_opts *opts,
                         aq_record *rec, aq_error *err)
{
  memset(rec, 0, sizeof *rec);
  struct stat st;
  if (!path || !*path)
    return aq_error_set(err, AQ_EIO, "", -1, -1, NULL,
                        "expected a record file name, got an empty string");
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
  size_t size = (size_t)st.st_size;
  unsigned char *buf = malloc(size ? size : 1);
  if (!buf) {
    fclose(f);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL,
                        "out of memory reading %zu bytes", size);
  }
  size_t got = fread(buf, 1, size, f);
  int rerr = ferror(f);
  fclose(f);
  if (rerr || got != size) {
    free(buf);
    return aq_error_set(err, AQ_EIO, path, -1, (long)got, NULL,
                        "read error: expected %zu bytes, got %zu", size, got);
  }
  aq_status s = aq_record_parse(buf, size, path, opts, rec, err);
  free(buf);
  return s;
}
