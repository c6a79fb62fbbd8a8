/* readers.h: the per-format readers behind aq_record_read(), each parsing a
 * whole file already in memory (so that fuzzers and benches need no files),
 * and the content sniffer that chooses between them.
 *
 * Every parser takes the file's bytes buf[0..n) (not NUL-terminated; the
 * parser never reads past n), the name to report and to match --units GLOB
 * rules against (the path as given), the reader options (may be NULL), and
 * fills *rec (acceleration in m/s^2, dt in s; caller frees with
 * aq_record_free) on AQ_OK.  On failure *rec is left empty, err says where
 * (line or byte offset) and what (field, expected, got), and the status is
 * AQ_EFORMAT (malformed), AQ_EUNITS (units unknown or not acceleration),
 * AQ_EVALUE (NaN/Inf or out-of-range value), AQ_EUNSUPPORTED or AQ_ENOMEM.
 * Memory used is O(n): counts taken from headers are checked against n
 * before anything is allocated.
 */
#ifndef AQ_IO_READERS_H
#define AQ_IO_READERS_H

#include <stddef.h>

#include "record.h"

/* What the bytes look like. */
typedef enum {
  AQ_FMT_UNKNOWN_BINARY = 0, /* binary, not recognised */
  AQ_FMT_SAC,                /* SAC binary, NVHDR = 6 (or 7) in one byte order */
  AQ_FMT_AT2,                /* PEER NGA acceleration (.AT2) */
  AQ_FMT_TEXT,               /* anything else that is text: tried as CSV */
  AQ_FMT_PEER_VT2,           /* PEER velocity (.VT2): refused */
  AQ_FMT_PEER_DT2,           /* PEER displacement (.DT2): refused */
  AQ_FMT_MSEED,              /* miniSEED 2 or 3: refused */
  AQ_FMT_COSMOS,             /* COSMOS V0/V1/V2: refused */
  AQ_FMT_SMC,                /* USGS SMC: refused */
  AQ_FMT_KNET,               /* K-NET / KiK-net ASCII: refused */
  AQ_FMT_ESM,                /* ESM / ITACA ASCII: refused */
  AQ_FMT_XML,                /* XML (StationXML, QuakeML): refused */
  AQ_FMT_HDF5,               /* HDF5 (e.g. an archquake results file): refused */
  AQ_FMT_GZIP,               /* gzip/zip compressed: refused */
  AQ_FMT_EMPTY               /* zero bytes */
} aq_format;

/* Classify buf[0..n) by content only.  Never fails. */
aq_format aq_record_detect(const unsigned char *buf, size_t n);

/* A short description of what fmt looks like, for messages
 * ("miniSEED (SEED data records)", ...). */
const char *aq_format_describe(aq_format fmt);

/* Parse from memory: dispatch on aq_record_detect(). */
aq_status aq_record_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_record *rec,
                          aq_error *err);

/* SAC binary (sac.c), either byte order. */
aq_status aq_sac_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_record *rec, aq_error *err);

/* PEER NGA .AT2 (at2.c): values in g. */
aq_status aq_at2_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_record *rec, aq_error *err);

/* CSV / plain text (csv.c). */
aq_status aq_csv_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_record *rec, aq_error *err);

/* Shared by the readers (record.c): set rec->path to name and rec->name to
 * its last path component.  Returns AQ_OK or AQ_ENOMEM (err filled). */
aq_status aq_record_set_names_(aq_record *rec, const char *name, aq_error *err);

#endif
