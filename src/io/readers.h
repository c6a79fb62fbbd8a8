/* readers.h: the per-format readers behind aq_record_read(), each parsing a
 * whole file already in memory (so that fuzzers and benches need no files),
 * the content sniffer that chooses between them, and the one function that
 * turns what a reader found into an aq_record (aq_record_decide).
 *
 * Readers report, one place decides: a parser only says what the file holds
 * (values as stored, the units the file states or none, dt, start time,
 * channel, azimuth, dip, the agency's metadata) in an aq_raw_file.  Which
 * units apply, whether the magnitude is plausible and whether a channel is
 * vertical is decided by aq_record_decide() in record.c, for every format
 * alike.  Parsers never look at --units.
 *
 * Every parser takes the file's bytes buf[0..n) (not NUL-terminated; the
 * parser never reads past n), the name to report (the path as given), the
 * reader options (may be NULL; only for what a format cannot state itself:
 * CSV --dt, --column) and fills *raw (caller frees with aq_raw_file_free) on
 * AQ_OK.  On failure *raw is left empty, err says where (line or byte
 * offset) and what (field, expected, got), and the status is AQ_EFORMAT
 * (malformed), AQ_EUNITS, AQ_EVALUE (NaN/Inf), AQ_EUNSUPPORTED or
 * AQ_ENOMEM.  Memory used is O(n): counts taken from headers are checked
 * against n before anything is allocated.
 */
#ifndef AQ_IO_READERS_H
#define AQ_IO_READERS_H

#include <stddef.h>

#include "number.h"
#include "record.h"

/* One channel (component) as the file states it.  Values are as stored, not
 * converted. */
typedef struct {
  char channel[16];      /* the file's own name for it: "HNE", "EW", "NS", "UD",
                            "360", "Up", "" if none */
  double azimuth_deg;    /* direction of positive motion, deg clockwise from
                            north; NAN if not stated */
  double dip_deg;        /* SEED convention: 0 horizontal, -90 up, +90 down;
                            NAN if not stated */
  int vertical;          /* what the file states: 1 vertical, 0 horizontal,
                            -1 does not say */
  size_t npts;
  double dt_s;           /* > 0 */
  double begin_s;        /* time of sample 0 after `reference`, s (0 if unknown) */
  char reference[40];    /* ISO-8601 UTC of the reference time, "" if unknown */
  char units[24];        /* units the file states, a word aq_units_parse()
                            accepts ("g", "gal", "cm/s2", "m/s2", "mm/s2",
                            "nm/s2", "g/10", "counts"); "" if the file states
                            none */
  double counts_per_mps2;/* for units "counts": the sensitivity the file
                            states, counts per m/s^2 (SAC SCALE, K-NET scale
                            factor, COSMOS LSB/sensitivity, StationXML); 0 if
                            none */
  char network[16], station[16], location[16];
  double *values;        /* npts values as stored (owned) */
  /* Added by the io readers (optional for a parser; zero means none): */
  char units_said[64];   /* what the file says about units when it is not an
                            acceleration unit, for messages ("header IDEP:
                            IVEL (7, velocity)", "line 3: UNITS OF CM/S") */
  long units_line;       /* line (text) where units are stated, or -1/0 */
} aq_raw_channel;

/* A whole file: one or more channels, plus what the file says about the
 * event and processing. */
typedef struct {
  char format[16];       /* "sac-le", "sac-be", "at2", "csv", "cosmos",
                            "csmip", "knet", "kiknet", "smc", "esm", "mseed",
                            ... */
  char event[96];        /* event name / id / origin time as stated, "" if none */
  char processing[160];  /* the agency's processing as stated (e.g. PEER filter
                            corners), "" if none */
  size_t nchan;
  aq_raw_channel *chan;  /* nchan channels in file order (owned) */
} aq_raw_file;

void aq_raw_file_free(aq_raw_file *raw); /* NULL and zeroed are fine */

/* Allocate raw->chan for nchan channels, each zeroed with azimuth_deg and
 * dip_deg NAN and vertical -1 (for parsers).  AQ_OK or AQ_ENOMEM (err filled,
 * name reported). */
aq_status aq_raw_file_alloc(aq_raw_file *raw, size_t nchan, const char *name,
                            aq_error *err);

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
  AQ_FMT_KNET,               /* K-NET / KiK-net ASCII (knet.c) */
  AQ_FMT_ESM,                /* ESM / ITACA ASCII: refused */
  AQ_FMT_XML,                /* XML (StationXML, QuakeML): refused */
  AQ_FMT_HDF5,               /* HDF5 (e.g. an archquake results file): refused */
  AQ_FMT_GZIP,               /* gzip/zip compressed: refused */
  AQ_FMT_EMPTY,              /* zero bytes */
  AQ_FMT_GEONET,             /* GeoNet V1A/V2A (geonet.c) */
  AQ_FMT_RENADIC             /* RENADIC (Chile) V1 (renadic.c) */
} aq_format;

/* Classify buf[0..n) by content only.  Never fails. */
aq_format aq_record_detect(const unsigned char *buf, size_t n);

/* A short description of what fmt looks like, for messages
 * ("miniSEED (SEED data records)", ...). */
const char *aq_format_describe(aq_format fmt);

/* Parse from memory into a raw file: dispatch on aq_record_detect(). */
aq_status aq_raw_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Parse from memory and decide one record: dispatch on aq_record_detect(),
 * then aq_record_decide() on the file's only channel, or on the channel that
 * name's "#CHANNEL" suffix or a --component rule selects (a file of several
 * channels with none selected is refused, naming the channels). */
aq_status aq_record_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_record *rec,
                          aq_error *err);

/* Turn channel ichan of raw into an aq_record in m/s^2 (see record.h):
 * choose the units (the file's stated units win; a global --units U applies
 * only to files that state none; a --units 'GLOB=U' rule matching path may
 * override stated units, and the conflict is recorded in rec->units_conflict);
 * counts need a sensitivity; check plausibility (PGA after conversion in
 * [AQ_PGA_MIN_G, AQ_PGA_MAX_G], else refuse naming the PGA found and the units
 * that would make it plausible, unless opts->accept_implausible); mark the
 * record vertical when the file says so (vertical flag, dip, or a channel
 * code ending in Z / named UD, Up, V, Vert).  path is the name reported and
 * matched against rules (the file path as given, without "#CHANNEL");
 * rec->name gets "#CHANNEL" appended when raw has several channels.
 * The values are copied: raw is unchanged. */
aq_status aq_record_decide(const aq_raw_file *raw, size_t ichan, const char *path,
                           const aq_read_opts *opts, aq_record *rec, aq_error *err);

/* SAC binary (sac.c), either byte order. */
aq_status aq_sac_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* PEER NGA .AT2 (at2.c). */
aq_status aq_at2_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Does buf[0..n) hold an AT2 header: a line with NPTS and DT followed by a
 * line of values (at2.c)?  Returns 1 and the non-blank text lines before it
 * ([tb[i], te[i]) offsets, at most max_text, count in *ntext), else 0. */
int aq_at2_sniff(const unsigned char *buf, size_t n, size_t *tb, size_t *te,
                 int *ntext, int max_text);

/* K-NET / KiK-net ASCII (knet.c): counts with the scale factor as the
 * sensitivity; channel NS/EW/UD (K-NET) or NS1..UD2 (KiK-net, 1 borehole, 2
 * surface); reference = Record Time - 15 s, in UTC. */
aq_status aq_knet_parse(const unsigned char *buf, size_t n, const char *name,
                        const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* CSV / plain text (csv.c). */
aq_status aq_csv_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* The count of channels aq_csv_parse would make of buf[0..n), from its
 * preamble, column names and first row only (the rows are not read): AQ_OK
 * with *nchan, or the error aq_csv_parse reports there.  On AQ_OK,
 * aq_csv_parse gives *nchan channels or reports an error in the rows. */
aq_status aq_csv_channels(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, size_t *nchan, aq_error *err);

/* aq_decimal_parse, aq_number_parse: the decimal parser, number.h. */

/* Shared by the readers (record.c): set rec->path to name and rec->name to
 * its last path component.  Returns AQ_OK or AQ_ENOMEM (err filled). */
aq_status aq_record_set_names_(aq_record *rec, const char *name, aq_error *err);

#endif
