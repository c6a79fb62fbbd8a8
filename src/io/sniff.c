/* sniff.c: a record file's format from its content alone (sniff.h): the
 * magic numbers of binary formats, then the first lines of text, asking the
 * readers' own sniffers (reader.h) where a format needs more than a line.
 * record.c dispatches on the result. */
#include "sniff.h"

#include <stdint.h>
#include <string.h>
#include <strings.h>

#include "reader.h"

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

int aq_sniff_is_text(aq_format f)
{
  return f != AQ_FMT_UNKNOWN_BINARY && f != AQ_FMT_SAC && f != AQ_FMT_MSEED &&
         f != AQ_FMT_HDF5 && f != AQ_FMT_GZIP && f != AQ_FMT_EMPTY;
}

size_t aq_sniff_bom(const unsigned char *buf, size_t n)
{
  if (n < 3 || memcmp(buf, "\xEF\xBB\xBF", 3) != 0)
    return 0;
  aq_format f = aq_sniff_format(buf + 3, n - 3);
  return aq_sniff_is_text(f) && f != AQ_FMT_EMPTY ? 3 : 0;
}

aq_format aq_sniff_format(const unsigned char *buf, size_t n)
{
  if (n == 0)
    return AQ_FMT_EMPTY;
  if (n > 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) { /* a UTF-8 byte-order mark, as */
    aq_format f = aq_sniff_format(buf + 3, n - 3);   /* spreadsheets write: the text's */
    if (aq_sniff_is_text(f))                         /* format after it */
      return f;
  }
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

const char *aq_sniff_describe(aq_format fmt)
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
