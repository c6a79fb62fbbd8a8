/* formats.h: the agency-format parsers (cosmos.c, csmip.c, smc.c, esm.c,
 * mseed.c, stationxml.c).  Each parses a whole file already in memory,
 * buf[0..n) (not NUL-terminated; never read past n), and fills *raw with
 * what the file states: values as stored, the stated units, dt, channel,
 * orientation, start time and the agency's metadata (see aq_raw_file).
 * They never decide units and never look at --units: record.c does.
 * On AQ_OK the caller frees *raw with aq_raw_file_free(); on failure *raw
 * is left empty and err names the file, the line (or byte) and the field.
 * Memory is O(n): counts from headers are checked against n first.
 */
#ifndef AQ_IO_FORMATS_H
#define AQ_IO_FORMATS_H

#include <stddef.h>

#include "readers.h"

/* COSMOS strong-motion format v1.20, V0/V1/V2, one or more channels; a
 * file whose first line names an ACCELEROGRAM without "(Format v" is handed
 * to aq_csmip_parse (the CSMIP V1/V2 variant). */
aq_status aq_cosmos_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* CSMIP (CGS/CDMG "DMG") V1/V2: the acceleration of every channel. */
aq_status aq_csmip_parse(const unsigned char *buf, size_t n, const char *name,
                         const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* USGS SMC (types 1 and 2; acceleration only). */
aq_status aq_smc_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* ESM / ITACA ASCII. */
aq_status aq_esm_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* miniSEED 2 through libmseed: one channel per network.station.location.
 * channel; counts with counts_per_mps2 = 0 (the sensitivity comes from
 * StationXML, see aq_stationxml_apply). */
aq_status aq_mseed_parse(const unsigned char *buf, size_t n, const char *name,
                         const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* aq_mseed_parse, then, if opts->response names a StationXML file, read it
 * and aq_stationxml_apply() it (record.c dispatches miniSEED here). */
aq_status aq_mseed_read_(const unsigned char *buf, size_t n, const char *name,
                         const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Take the StationXML files out of the list of record paths paths[0..n):
 * the first becomes ro->response (unless --response gave one), and the
 * others are dropped as well (responses are looked up in the first only).
 * Returns the number of paths left, in their order (n, untouched, when all
 * are StationXML: then they are reported as not records).  A file is taken when
 * its first bytes hold "<FDSNStationXML" (read with stdio; unreadable files
 * stay in the list, for the reader to report). */
size_t aq_read_opts_take_stationxml(char **paths, size_t n, aq_read_opts *ro);

/* One channel epoch of a StationXML file. */
typedef struct {
  char network[16], station[16], location[16], channel[16];
  char start[40], end[40];  /* ISO-8601 as written; end "" if open */
  double sensitivity;       /* InstrumentSensitivity Value, counts per input unit (sign kept) */
  char input_units[24];     /* InputUnits Name as written ("M/S**2") */
  double azimuth_deg, dip_deg; /* NAN if absent */
} aq_response_epoch;

typedef struct {
  size_t n;
  aq_response_epoch *epoch; /* owned */
} aq_response;

/* Parse FDSN StationXML (libxml2) into *resp (free with aq_response_free). */
aq_status aq_stationxml_parse(const unsigned char *buf, size_t n, const char *name,
                              aq_response *resp, aq_error *err);
void aq_response_free(aq_response *resp);

/* For every channel of raw whose units are "counts": find the epoch of resp
 * with the same network, station, location and channel that covers the
 * channel's start, and set counts_per_mps2 (from the sensitivity and its
 * input units: m/s^2, nm/s^2 or g; the sign is kept), azimuth and dip.  No
 * matching channel, no covering epoch or input units that are not
 * acceleration: AQ_EUNITS naming xml_name and the channel. */
aq_status aq_stationxml_apply(const aq_response *resp, const char *xml_name,
                              aq_raw_file *raw, const char *name, aq_error *err);

/* GeoNet (New Zealand) V1A/V2A: the acceleration of every component, mm/s^2. */
aq_status aq_geonet_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Shared by the parsers (formats.c): append a zeroed channel (azimuth and
 * dip NAN, vertical -1) to raw; NULL on allocation failure (err filled). */
aq_raw_channel *aq_raw_add_channel_(aq_raw_file *raw, const char *name, aq_error *err);

/* Shared: append *c (its values owned by raw from then on) to raw; on
 * allocation failure free c->values and return AQ_ENOMEM (err filled). */
aq_status aq_raw_append_channel_(aq_raw_file *raw, aq_raw_channel *c, const char *name,
                                 aq_error *err);

/* Shared: zero *c with azimuth and dip NAN and vertical -1 (not stated). */
void aq_raw_channel_init_(aq_raw_channel *c);

/* Shared by the multi-channel text parsers (cosmos.c, csmip.c): walk the
 * channels of buf[0..n).  Blank lines between channels are skipped; every
 * other line must start a channel (starts(line) != 0, else AQ_EFORMAT
 * "expected <expected>, got ...") and parse(cursor after that line, the
 * line, ...) reads the channel and appends it to raw.  No channel at all is
 * an error; on failure raw is freed; on success raw->format = format. */
struct aq_lines_s;
struct aq_line_s;
typedef aq_status (*aq_channel_parser_)(struct aq_lines_s *c, const struct aq_line_s *first,
                                        const char *name, aq_raw_file *raw, aq_error *err);
aq_status aq_parse_channels_(const unsigned char *buf, size_t n, const char *name,
                             const char *format, int (*starts)(const struct aq_line_s *),
                             const char *expected, aq_channel_parser_ parse, aq_raw_file *raw,
                             aq_error *err);

/* RENADIC (Universidad de Chile) V1: CSMIP-like headers, then (time, value)
 * pairs; dt from the even time column; units "g/10". */
aq_status aq_renadic_parse(const unsigned char *buf, size_t n, const char *name,
                           const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Does buf[0..n) start like a RENADIC V1 channel: a first line naming an
 * ACCELEROGRAM and, after the 13 text and 14 numeric header lines, two lines
 * of (time, value) pairs in 10F7 whose six times step evenly?  1 or 0. */
int aq_renadic_sniff(const unsigned char *buf, size_t n);

/* BHRC (Iran) VOL1DS: three blocks (L, V, T) of 13 text lines, 14I5
 * integers, 6E13.6 reals cut at column 70, and 10E13.6 data; units "g/10";
 * dt from real #7 (samples per second); no start time (bhrc.c). */
aq_status aq_bhrc_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Does buf[0..n) start "* VOL" with "DS FILE" (BHRC VOLnDS)?  1 or 0. */
int aq_bhrc_sniff(const unsigned char *buf, size_t n);

/* The Mexican strong-motion database's ASA 2.0 text, UNAM and CICESE
 * layouts: Spanish "KEY : value" headers with "/"-separated per-channel
 * lists, then one row per sample (asa.c). */
aq_status aq_asa_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Does one of the first lines of buf[0..n) say "ARCHIVO ESTANDAR DE
 * ACELERACION" (ASA 2.0)?  1 or 0. */
int aq_asa_sniff(const unsigned char *buf, size_t n);

/* Turkey's NSMN/AFAD ASCII ("STRONG GROUND MOTION RECORDS OF TURKIYE"):
 * "KEY : value" lines (SAMPLING INTERVAL (sec), NUMBER OF DATA, RECORD
 * TIME), ISO-8859-9 place names, three columns N-S E-W U-D (nsmn.c). */
aq_status aq_nsmn_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Does the first line of buf[0..n) say "STRONG GROUND MOTION RECORDS OF
 * TURK..."?  1 or 0. */
int aq_nsmn_sniff(const unsigned char *buf, size_t n);

/* Text whose first line is the two numbers "NPTS DT" (OpenSees examples),
 * then NPTS values or NPTS (time, value) pairs; no units stated (nptsdt.c). */
aq_status aq_nptsdt_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Is the first non-blank line of buf[0..n) "NPTS DT" (a whole number >= 2
 * and a number > 0) and are the numbers after it NPTS values or NPTS pairs
 * on lines of two?  1 or 0 (reads all of buf). */
int aq_nptsdt_sniff(const unsigned char *buf, size_t n);

/* Shared (csmip.c, renadic.c): 1 if the line names an ACCELEROGRAM (any
 * case), the start of a channel's text header. */
int aq_line_names_accelerogram_(const struct aq_line_s *ln);

/* Shared: seconds east of UTC for a zone word ("UTC", "GMT", "PDT", "PST",
 * "JST", ...); 1 if known. */
int aq_zone_offset_(const char *s, size_t n, int *hours_east);

#endif
