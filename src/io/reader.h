/* reader.h: the reader contract.  One parser per format (sac.c, at2.c,
 * csv.c, knet.c, cosmos.c, csmip.c, smc.c, esm.c, mseed.c, geonet.c,
 * renadic.c, bhrc.c, asa.c, nsmn.c, nptsdt.c; stationxml.c for the
 * responses of miniSEED), each parsing a
 * whole file already in memory (so that fuzzers and benches need no files)
 * into an aq_raw_file: what the file states, nothing decided.
 *
 * Readers report, one place decides: a parser says what the file holds
 * (values as stored, the units the file states or none, dt, start time,
 * channel, azimuth, dip, the agency's metadata).  Which units apply, whether
 * the magnitude is plausible and whether a channel is vertical is decided by
 * aq_record_decide() in record.c, for every format alike.  A parser never
 * includes record.h and never looks at --units.  Below the parsers, and
 * shared by them: units.h (units words), fixed.h (lines, fixed-width fields,
 * dates), number.h (decimal numbers), and the raw file helpers declared at
 * the end of this header (raw.c).
 *
 * Every parser takes the file's bytes buf[0..n) (not NUL-terminated; the
 * parser never reads past n), the name to report (the path as given), the
 * reader options (may be NULL; only for what a format cannot state itself:
 * text --dt and --column) and fills *raw (caller frees with
 * aq_raw_file_free) on AQ_OK.  On failure *raw is left empty, err says
 * where (line or byte offset) and what (field, expected, got), and the
 * status is AQ_EFORMAT (malformed), AQ_EUNITS, AQ_EVALUE (NaN/Inf),
 * AQ_EUNSUPPORTED or AQ_ENOMEM.  Memory used is O(n): counts taken from
 * headers are checked against n before anything is allocated.
 */
#ifndef AQ_IO_READER_H
#define AQ_IO_READER_H

#include <stddef.h>

#include "../error.h"
#include "units.h"

/* ---- what a parser fills ------------------------------------------------ */

/* One channel (component) as the file states it.  Values are as stored, not
 * converted.  aq_raw_channel_init() gives the "not stated" of every field. */
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
  char units_said[64];   /* what the file says about units when it is not an
                            acceleration unit, for messages ("header IDEP:
                            IVOL (50, volts)", "line 3: UNITS OF CM/S");
                            "" if nothing */
  long units_line;       /* line (text) where units are stated, or -1/0 */
  char units_from[320];  /* where the file states its units, for messages
                            ("header IDEP: IACC (8)", "X.xml:
                            InstrumentSensitivity": room for a file name of
                            NAME_MAX, 255, whole); "" if units says all */
  int quantity;          /* what the file says the values are (aq_quantity):
                            0 does not say */
  char quantity_said[320];/* where it says so, for messages ("header IDEP:
                            IVEL (7, velocity)", "X.xml: InputUnits M/S",
                            the file's name whole); "" if it does not */
  char orient_said[320]; /* the field that states azimuth, dip or vertical,
                            for messages ("integer header #54: 0", "X.xml:
                            Dip -90"); "" if none or the format's only place */
  /* Rows past the count the file states, before its data end (a reader
   * that reads a stated count looks, aq_extra_rows_scan): npts values were
   * read, extra_values more follow in extra_rows rows from line
   * extra_line; extra_repeat 1 when each of those rows is a copy of the
   * last row read.  aq_record_decide notes a repeat and refuses the rest. */
  size_t extra_rows, extra_values;
  long extra_line;
  int extra_repeat;
  char count_from[48];   /* the field that states the count ("NPTS",
                            "integer header #17"), for those messages */
} aq_raw_channel;

/* A whole file: one or more channels, plus what the file says about the
 * event and processing. */
typedef struct {
  char format[16];       /* "sac-le", "sac-be", "at2", "csv", "cosmos",
                            "csmip", "knet", "kiknet", "smc", "esm", "mseed",
                            ... */
  char event[96];        /* event name / id / origin time as stated, "" if none */
  char event_name[96];   /* the event alone, as the file names it: no station,
                            component or record time (an AT2's text line holds
                            the station and component after the event; CSMIP's
                            "Record of" line is the record's trigger time);
                            "" if the file names no event */
  char processing[160];  /* the agency's processing as stated (e.g. PEER filter
                            corners), "" if none */
  size_t nchan;
  aq_raw_channel *chan;  /* nchan channels in file order (owned) */
} aq_raw_file;

/* What a parser may be told: only what a format cannot state itself.
 * Zero-initialised means nothing given. */
typedef struct {
  double dt_s;   /* --dt: sample interval of text without a time column, s;
                    0 = not given */
  size_t column; /* --column N: 1-based column of a text record to read as
                    acceleration (counting a time column); 0 = the first
                    column that is not time */
} aq_reader_opts;

/* ---- the parsers --------------------------------------------------------- */

/* A parser: the bytes buf[0..n) of the file named name, the reader options
 * (may be NULL) -> *raw (see the top of this header). */
typedef aq_status aq_reader_fn(const unsigned char *buf, size_t n, const char *name,
                               const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err);

/* SAC binary, either byte order (sac.c). */
aq_reader_fn aq_sac_parse;

/* PEER NGA .AT2 (at2.c). */
aq_reader_fn aq_at2_parse;

/* Does buf[0..n) hold an AT2 header: a line with NPTS and DT followed by a
 * line of values (at2.c)?  Returns 1 and the non-blank text lines before it
 * ([tb[i], te[i]) offsets, at most max_text, count in *ntext), else 0. */
int aq_at2_sniff(const unsigned char *buf, size_t n, size_t *tb, size_t *te,
                 int *ntext, int max_text);

/* K-NET / KiK-net ASCII (knet.c): counts with the scale factor as the
 * sensitivity; channel NS/EW/UD (K-NET) or NS1..UD2 (KiK-net, 1 borehole, 2
 * surface); reference = Record Time - 15 s, in UTC. */
aq_reader_fn aq_knet_parse;

/* CSV / plain text (csv.c). */
aq_reader_fn aq_csv_parse;

/* The count of channels aq_csv_parse would make of buf[0..n), from its
 * preamble, column names and first row only (the rows are not read): AQ_OK
 * with *nchan, or the error aq_csv_parse reports there.  On AQ_OK,
 * aq_csv_parse gives *nchan channels or reports an error in the rows. */
aq_status aq_csv_channels(const unsigned char *buf, size_t n, const char *name,
                          const aq_reader_opts *opts, size_t *nchan, aq_error *err);

/* COSMOS strong-motion format v1.20, V0/V1/V2, one or more channels
 * (cosmos.c); a file whose first line names an ACCELEROGRAM without
 * "(Format v" is handed to aq_csmip_parse (the CSMIP V1/V2 variant). */
aq_reader_fn aq_cosmos_parse;

/* CSMIP (CGS/CDMG "DMG") V1/V2: the acceleration of every channel (csmip.c). */
aq_reader_fn aq_csmip_parse;

/* USGS SMC, types 1 and 2; acceleration only (smc.c). */
aq_reader_fn aq_smc_parse;

/* ESM / ITACA ASCII (esm.c). */
aq_reader_fn aq_esm_parse;

/* miniSEED 2 through libmseed (mseed.c): one channel per network.station.
 * location.channel; counts with counts_per_mps2 = 0 (the sensitivity comes
 * from a StationXML: evidence.c matches the responses). */
aq_reader_fn aq_mseed_parse;
/* Open libmseed (mseed_lazy.c; once per process, later calls return the
 * first's outcome): AQ_OK, or AQ_EUNSUPPORTED with err naming the file
 * name, the library and the loader's reason. */
aq_status aq_mseed_load(const char *name, aq_error *err);

/* GeoNet (New Zealand) V1A/V2A: the acceleration of every component, mm/s^2
 * (geonet.c). */
aq_reader_fn aq_geonet_parse;

/* RENADIC (Universidad de Chile) V1: CSMIP-like headers, then (time, value)
 * pairs; dt from the even time column; units "g/10" (renadic.c). */
aq_reader_fn aq_renadic_parse;

/* Does buf[0..n) start like a RENADIC V1 channel: a first line naming an
 * ACCELEROGRAM and, after the 13 text and 14 numeric header lines, two lines
 * of (time, value) pairs in 10F7 whose six times step evenly?  1 or 0. */
int aq_renadic_sniff(const unsigned char *buf, size_t n);

/* BHRC (Iran) VOL1DS: three blocks (L, V, T) of 13 text lines, 14I5
 * integers, 6E13.6 reals cut at column 70, and 10E13.6 data; units "g/10";
 * dt from real #7 (samples per second); no start time (bhrc.c). */
aq_reader_fn aq_bhrc_parse;

/* Does buf[0..n) start "* VOL" with "DS FILE" (BHRC VOLnDS)?  1 or 0. */
int aq_bhrc_sniff(const unsigned char *buf, size_t n);

/* The Mexican strong-motion database's ASA 2.0 text, UNAM and CICESE
 * layouts: Spanish "KEY : value" headers with "/"-separated per-channel
 * lists, then one row per sample (asa.c). */
aq_reader_fn aq_asa_parse;

/* Does one of the first lines of buf[0..n) say "ARCHIVO ESTANDAR DE
 * ACELERACION" (ASA 2.0)?  1 or 0. */
int aq_asa_sniff(const unsigned char *buf, size_t n);

/* Turkey's NSMN/AFAD ASCII ("STRONG GROUND MOTION RECORDS OF TURKIYE"):
 * "KEY : value" lines (SAMPLING INTERVAL (sec), NUMBER OF DATA, RECORD
 * TIME), ISO-8859-9 place names, three columns N-S E-W U-D (nsmn.c). */
aq_reader_fn aq_nsmn_parse;

/* Does the first line of buf[0..n) say "STRONG GROUND MOTION RECORDS OF
 * TURK..."?  1 or 0. */
int aq_nsmn_sniff(const unsigned char *buf, size_t n);

/* Text whose first line is the two numbers "NPTS DT" (OpenSees examples),
 * then NPTS values or NPTS (time, value) pairs; no units stated (nptsdt.c). */
aq_reader_fn aq_nptsdt_parse;

/* Is the first non-blank line of buf[0..n) "NPTS DT" (a whole number >= 2
 * and a number > 0) and are the numbers after it NPTS values or NPTS pairs
 * on lines of two?  1 or 0 (reads all of buf). */
int aq_nptsdt_sniff(const unsigned char *buf, size_t n);

/* ---- StationXML: the responses of miniSEED channels (stationxml.c) ------- */

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

/* The epochs of resp of channel net.sta.loc.cha: returns how many cover the
 * time t_s (s since 1970, UTC), the first of them in *hit (NULL if none);
 * *nsame (if not NULL) grows by the number of epochs of that channel, and
 * spans[cap] (if not NULL) gets the spans of the first three appended
 * ("START to END|open", comma-separated). */
size_t aq_response_find(const aq_response *resp, const char *net, const char *sta,
                        const char *loc, const char *cha, double t_s,
                        const aq_response_epoch **hit, size_t *nsame, char *spans, size_t cap);

/* What epoch e of the StationXML xml_name states about channel ch: the
 * quantity its input units measure (quantity, quantity_said); for
 * acceleration the sensitivity in counts per m/s^2, sign kept
 * (counts_per_mps2, units_from); azimuth, dip and vertical (orient_said).
 * AQ_EUNITS naming xml_name for input units it does not know or a
 * sensitivity that is zero or not a number. */
aq_status aq_response_apply(const aq_response_epoch *e, const char *xml_name, aq_raw_channel *ch,
                            aq_error *err);

/* ---- for the parsers: the raw file (raw.c) ------------------------------- */

void aq_raw_file_free(aq_raw_file *raw); /* NULL and zeroed are fine */

/* Allocate raw->chan for nchan channels, each aq_raw_channel_init'ed.
 * AQ_OK or AQ_ENOMEM (err filled, name reported). */
aq_status aq_raw_file_alloc(aq_raw_file *raw, size_t nchan, const char *name,
                            aq_error *err);

/* Zero *c with azimuth and dip NAN, vertical -1 and units_line -1 (nothing
 * stated). */
void aq_raw_channel_init(aq_raw_channel *c);

/* Append an initialised channel to raw; NULL on allocation failure (err
 * filled). */
aq_raw_channel *aq_raw_add_channel(aq_raw_file *raw, const char *name, aq_error *err);

/* The rows past the stated count a reader found (fixed.h aq_extra_rows,
 * each per values of this channel: 2 for (time, value) pairs) into c's
 * extra_* fields, with count_from the field that states the count. */
struct aq_extra_rows_s;
void aq_raw_set_extra(aq_raw_channel *c, const struct aq_extra_rows_s *x, size_t per,
                      const char *count_from);

/* The end of a table of rows, one value of every channel of raw a row,
 * after its stated count (rows, stated by count_from): the rows past it
 * (row() as aq_extra_rows_scan's, last the count's last row) are set on
 * every channel; then nothing but blank lines may follow.  AQ_OK, or
 * AQ_EFORMAT naming the line that does (raw freed). */
struct aq_lines_s;
struct aq_line_s;
aq_status aq_raw_rows_end(struct aq_lines_s *c, const struct aq_line_s *last,
                          size_t (*row)(const struct aq_line_s *, const void *),
                          const void *ctx, size_t rows, const char *count_from,
                          aq_raw_file *raw, const char *name, aq_error *err);

/* Append *c (its values owned by raw from then on) to raw; on allocation
 * failure free c->values and return AQ_ENOMEM (err filled). */
aq_status aq_raw_append_channel(aq_raw_file *raw, aq_raw_channel *c, const char *name,
                                aq_error *err);

/* Walk the channels of a multi-channel text file buf[0..n) (cosmos.c,
 * csmip.c).  Blank lines between channels are skipped; every other line
 * must start a channel (starts(line) != 0, else AQ_EFORMAT "expected
 * <expected>, got ...") and parse(cursor after that line, the line, ...)
 * reads the channel and appends it to raw.  No channel at all is an error;
 * on failure raw is freed; on success raw->format = format. */
struct aq_lines_s;
struct aq_line_s;
typedef aq_status (*aq_raw_channel_parser)(struct aq_lines_s *c, const struct aq_line_s *first,
                                           const char *name, aq_raw_file *raw, aq_error *err);
aq_status aq_raw_parse_channels(const unsigned char *buf, size_t n, const char *name,
                                const char *format, int (*starts)(const struct aq_line_s *),
                                const char *expected, aq_raw_channel_parser parse,
                                aq_raw_file *raw, aq_error *err);

#endif
