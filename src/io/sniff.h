/* sniff.h: what a file's bytes look like, from its content alone
 * (sniff.c), and a description of that for messages.  record.c dispatches
 * on it to the parser of the format (reader.h). */
#ifndef AQ_IO_SNIFF_H
#define AQ_IO_SNIFF_H

#include <stddef.h>

/* What the bytes look like. */
typedef enum {
  AQ_FMT_UNKNOWN_BINARY = 0, /* binary, not recognised */
  AQ_FMT_SAC,                /* SAC binary, NVHDR = 6 (or 7) in one byte order */
  AQ_FMT_AT2,                /* PEER NGA acceleration (.AT2) */
  AQ_FMT_TEXT,               /* anything else that is text: tried as CSV */
  AQ_FMT_PEER_VT2,           /* PEER velocity (.VT2): refused */
  AQ_FMT_PEER_DT2,           /* PEER displacement (.DT2): refused */
  AQ_FMT_MSEED,              /* miniSEED 2 (mseed.c); 3 refused */
  AQ_FMT_COSMOS,             /* COSMOS V0/V1/V2 (cosmos.c), CSMIP (csmip.c) */
  AQ_FMT_SMC,                /* USGS SMC (smc.c) */
  AQ_FMT_KNET,               /* K-NET / KiK-net ASCII (knet.c) */
  AQ_FMT_ESM,                /* ESM / ITACA ASCII (esm.c) */
  AQ_FMT_XML,                /* XML (StationXML, QuakeML): refused */
  AQ_FMT_HDF5,               /* HDF5 (e.g. an archquake results file): refused */
  AQ_FMT_GZIP,               /* gzip/zip compressed: refused */
  AQ_FMT_EMPTY,              /* zero bytes */
  AQ_FMT_GEONET,             /* GeoNet V1A/V2A (geonet.c) */
  AQ_FMT_RENADIC,            /* RENADIC (Chile) V1 (renadic.c) */
  AQ_FMT_BHRC,               /* BHRC (Iran) VOL1DS (bhrc.c) */
  AQ_FMT_ASA,                /* Mexican ASA 2.0 (asa.c) */
  AQ_FMT_NSMN,               /* AFAD / NSMN (Turkey) ASCII (nsmn.c) */
  AQ_FMT_NPTS_DT             /* text whose first line is "NPTS DT" (nptsdt.c) */
} aq_format;

/* 1 if f is a text format (a record's text, or XML): not binary, not
 * empty. */
int aq_sniff_is_text(aq_format f);

/* The length of a UTF-8 byte-order mark at buf that a text format follows
 * (3), as spreadsheets write one; else 0.  Every text reader is given the
 * bytes after it (record.c), so that a file saved with one reads as the
 * same file without; the format is sniffed after it too. */
size_t aq_sniff_bom(const unsigned char *buf, size_t n);

/* Classify buf[0..n) by content only.  Never fails. */
aq_format aq_sniff_format(const unsigned char *buf, size_t n);

/* A short description of what fmt looks like, for messages
 * ("miniSEED", "K-NET/KiK-net ASCII", ...); a static string. */
const char *aq_sniff_describe(aq_format fmt);

#endif
