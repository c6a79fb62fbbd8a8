/* src/io (record.h): record files of every format in, evenly sampled
 * ground acceleration in m/s^2 (aq_record) out.
 *
 * sniff.c tells a file's format from its content; record.c dispatches to
 * the parser of that format (reader.h), which reports what the file states;
 * evidence.c gathers what a channel's fields say beyond its values (the
 * response of a miniSEED channel matched by identity, anything saying it is
 * not an acceleration, a name saying vertical); and one function in
 * record.c (aq_record_decide) decides for every format alike: the units
 * that apply, whether the magnitude is plausible, whether a channel is
 * vertical.  The record owns its arrays and
 * strings; aq_record_free() releases them (NULL and zeroed records are
 * fine).  Nothing here prints: errors fill an aq_error.
 */
#ifndef AQ_IO_RECORD_H
#define AQ_IO_RECORD_H

#include <stddef.h>

#include "../error.h"
#include "reader.h"
#include "sniff.h"
#include "units.h"

/* How aq_record_decide knew a channel is vertical (aq_record.vertical_by). */
typedef enum {
  AQ_VERTICAL_BY_NONE = 0, /* not vertical */
  AQ_VERTICAL_BY_STATED,   /* the file states it (orientation code, direction word) */
  AQ_VERTICAL_BY_DIP,      /* its dip or incidence angle */
  AQ_VERTICAL_BY_NAME,     /* its channel or column name (Z, UD, Up, vert, ...) */
  AQ_VERTICAL_BY_NAME_OVER_FIELD /* its name, over an orientation field saying
                                    horizontal (the conflict in vertical_note) */
} aq_vertical_by;

typedef struct {
  char *path;           /* file as given on the command line */
  char *name;           /* short name: file name without directories */
  char format[16];      /* "sac-le", "sac-be", "at2", "csv" */
  size_t npts;          /* number of samples */
  double dt_s;          /* sample interval, s (> 0) */
  double begin_s;       /* time of sample 0 relative to the reference time, s (SAC B; 0 if unknown) */
  char reference[40];   /* ISO-8601 UTC reference time ("" if unknown) */
  char network[16], station[16], location[16], channel[16]; /* "" if unknown */
  char units_orig[24];  /* units of the file's values as used (= units_used) */
  double to_mps2;       /* factor applied to the file's values to get m/s^2 */
  double *acc_mps2;     /* npts samples of ground acceleration, m/s^2 */
  /* Decided by aq_record_decide: */
  double azimuth_deg;   /* direction of positive motion, deg from north; NAN if unknown */
  double dip_deg;       /* SEED: 0 horizontal, -90 up, +90 down; NAN if unknown */
  int vertical;         /* 1: the file identifies the channel as vertical */
  int vertical_by;      /* how (aq_vertical_by): stated, dip or channel name; 0 if not */
  char event[96];       /* event as the file states it, "" if none */
  char event_key[96];   /* the event as records are compared by it (select's
                           --max-per-event): the event alone as the file names
                           it (the reader's event_name), in lower case, every
                           run of characters other than letters and digits one
                           space; "" if the file names no event */
  char processing[160]; /* the agency's processing as stated, "" if none */
  char units_stated[24];/* units the file states ("" if none) */
  char units_used[24];  /* units applied (canonical name, e.g. "gal") */
  char units_by[12];    /* where units_used came from: "file" (stated in it),
                           "response" (miniSEED counts, the sensitivity from
                           --response's StationXML), "rule" (--units GLOB=U),
                           "option" (--units, the file stating none) */
  /* Notes name fields, rules and files (a StationXML's name whole, up to
   * NAME_MAX): a text longer than its room ends in "...", never cut unseen. */
  char units_conflict[512]; /* "" or one line: the file states X, the rule GLOB=U uses U */
  char polarity_note[512];  /* "" or one line: the sensitivity is negative, so the
                               samples are reversed by it (to_mps2 < 0) */
  char vertical_note[512];  /* "" or one line: the channel name and an orientation
                               field disagree (vertical_by NAME_OVER_FIELD) */
  char dt_note[120];        /* "" or one line: --dt differs from the sample
                               interval the file states, which is the one used */
  char count_note[200];     /* "" or one line: rows past the count the file
                               states repeat its last row and are not read */
} aq_record;

/* The i-th note a record carries (i = 0, 1, ...), in the order polarity,
 * vertical, dt, data, the empty ones skipped: its text, and in *topic (if
 * not NULL) its word ("polarity", "vertical", "dt", "data"); NULL past the
 * last. */
const char *aq_record_note(const aq_record *rec, size_t i, const char **topic);

/* Plausible peak ground acceleration after conversion, g: a record outside
 * [AQ_PGA_MIN_G, AQ_PGA_MAX_G] is refused unless accept_implausible (the
 * strongest records ever measured are ~4 g; 1e-5 g is below the noise of
 * strong-motion accelerometers). */
#define AQ_PGA_MAX_G 10.0
#define AQ_PGA_MIN_G 1e-5

/* A per-file units rule (--units GLOB=U): records whose path as given
 * matches glob (fnmatch(3), no flags, so '*' also matches '/') are read in
 * units. */
#define AQ_UNITS_RULES_MAX 16
#define AQ_RESPONSES_MAX 4096 /* StationXML files one command takes */
#define AQ_UNITS_GLOB_MAX 256
typedef struct {
  char glob[AQ_UNITS_GLOB_MAX];
  aq_units units;
} aq_units_rule;

/* Reader options.  Zero-initialised means: units from the file, no dt. */
typedef struct {
  aq_units units; /* override, or AQ_UNITS_FILE */
  double dt_s;    /* --dt for single-column text; 0 = not given */
  /* Added with the readers: */
  size_t column;  /* --column N: 1-based column of a text record to read as
                     acceleration (counting a time column); 0 = the first
                     column that is not time */
  size_t nrules;  /* number of --units GLOB=U rules in rules[] */
  aq_units_rule rules[AQ_UNITS_RULES_MAX]; /* the last matching rule wins */
  int accept_implausible; /* --accept-implausible: keep a PGA outside
                             [AQ_PGA_MIN_G, AQ_PGA_MAX_G] */
  int accept_vertical;    /* --accept-vertical: run vertical channels */
  size_t ncomponents;     /* number of --component GLOB=CH rules */
  struct {
    char glob[AQ_UNITS_GLOB_MAX];
    char channel[16];
  } components[AQ_UNITS_RULES_MAX]; /* --component GLOB=CH: the last matching wins */
  size_t nresponses;      /* StationXML files giving the responses of miniSEED
                             channels: each --response, then the StationXML
                             operands (aq_read_opts_take_stationxml) */
  const char *responses[AQ_RESPONSES_MAX]; /* their names (not owned: the
                                              command line's strings) */
} aq_read_opts;

/* Take the StationXML files out of the list of record paths paths[0..n)
 * into ro->responses (after any --response), where a miniSEED channel's
 * response is looked up by its identity.  Returns the number of paths
 * left, in their order; the StationXML ones follow them in paths (n,
 * nothing moved, when all are StationXML: then they are reported as not
 * records).  A file is taken when its first bytes hold "<FDSNStationXML"
 * (read with stdio; unreadable files stay in the list, for the reader to
 * report); beyond AQ_RESPONSES_MAX they stay too (refused as records). */
size_t aq_read_opts_take_stationxml(char **paths, size_t n, aq_read_opts *ro);

/* The units override that applies to path: the last rule whose glob matches
 * path (as given), else opts->units (AQ_UNITS_FILE if none).  opts may be
 * NULL (AQ_UNITS_FILE). */
aq_units aq_read_opts_units_for(const aq_read_opts *opts, const char *path);

/* The --units GLOB=U rule matching path (the last one), or NULL. */
const aq_units_rule *aq_read_opts_rule_for(const aq_read_opts *opts, const char *path);

/* Read the file at path, detecting its format from its content.
 * On success fills *rec (caller frees with aq_record_free) and returns AQ_OK;
 * on failure *rec is left empty and err says where and why. */
aq_status aq_record_read(const char *path, const aq_read_opts *opts,
                         aq_record *rec, aq_error *err);

/* aq_record_read, handing the bytes of the file it read to the caller
 * (*bytes malloc'd, *nbytes of them; the caller frees): path itself, or the
 * FILE of a FILE#CHANNEL name, whether or not they parse as a record; NULL
 * when the file cannot be read.  For a hash of exactly the bytes read,
 * without reading the file twice. */
aq_status aq_record_read_keep(const char *path, const aq_read_opts *opts,
                              aq_record *rec, unsigned char **bytes,
                              size_t *nbytes, aq_error *err);

/* One record of a file read by aq_record_read_all: its name and either the
 * record or why it could not be made. */
typedef struct {
  char *name;       /* the record's name: the operand as given, or
                       "FILE#CHANNEL" for each channel of a file of several
                       (as aq_record_expand names them) */
  aq_status status; /* AQ_OK: rec holds the record; else err says why */
  aq_record rec;
  aq_error err;
} aq_record_item;

/* The records of one operand (aq_record_read_all). */
typedef struct {
  size_t n;
  aq_record_item *item;  /* n items, in file order */
  unsigned char *bytes;  /* with keep_bytes: the file's bytes (whatever its
                            channels hold), NULL when it cannot be read */
  size_t nbytes;
} aq_record_set;

/* Every record of the operand path from one parse of its file: FILE#CHANNEL
 * (or a --component rule matching a file of several channels) gives that
 * channel; a file of several channels with none chosen gives every channel,
 * each decided on its own (aq_record_decide) and named FILE#CHANNEL; any
 * other operand gives one record.  A file that cannot be read or parsed is
 * one item carrying that error.  The same names, records and errors as
 * aq_record_expand followed by aq_record_read of each name, which parses a
 * file of N channels N + 1 times.  Returns AQ_OK with *set filled (free with
 * aq_record_set_free), or AQ_ENOMEM (err filled, *set empty). */
aq_status aq_record_read_all(const char *path, const aq_read_opts *opts, int keep_bytes,
                             aq_record_set *set, aq_error *err);
void aq_record_set_free(aq_record_set *set); /* NULL and zeroed are fine */

/* Test hook: how many files aq_raw_parse has parsed in this process. */
unsigned long aq_record_parses_(void);

/* Record names for operands paths[0..n): a file of several channels, named
 * without #CHANNEL and chosen by no --component rule, becomes one name per
 * channel, "FILE#CHANNEL", in file order; any other operand is kept as given
 * (an unreadable one is reported when it is read).  On AQ_OK *out holds
 * *nout malloc'd names (free with aq_record_names_free); else AQ_ENOMEM.
 * The names of a file that may hold several channels are those of
 * aq_record_read_all. */
aq_status aq_record_expand(char *const *paths, size_t n, const aq_read_opts *opts,
                           char ***out, size_t *nout, aq_error *err);
void aq_record_names_free(char **names, size_t n);

/* aq_record_expand for a run of horizontal excitation: a channel that the
 * file identifies as vertical, of a file of several channels named with
 * neither #CHANNEL nor a --component rule, is left out (unless
 * opts->accept_vertical), and one line says so in *notes ("FILE#UD:
 * skipped: the file identifies channel \"UD\" as vertical (...) ..."; *nnotes
 * of them, in operand order; free with aq_record_names_free).  A channel
 * named by the user is kept, for the run to refuse. */
aq_status aq_record_expand_horizontal(char *const *paths, size_t n, const aq_read_opts *opts,
                                      char ***out, size_t *nout, char ***notes, size_t *nnotes,
                                      aq_error *err);

/* The file a record name reads: NAME itself, or FILE for a channel named
 * FILE#CHANNEL when NAME is not a file and FILE is (as aq_record_read
 * resolves it).  Written to buf[cap] (truncated to fit); returns buf. */
const char *aq_record_file(const char *name, char *buf, size_t cap);

/* AQ_OK if rec may be run as horizontal excitation: it is not identified as
 * vertical, or opts->accept_vertical.  Otherwise AQ_EUNSUPPORTED with err
 * naming the record and its channel. */
aq_status aq_record_check_horizontal(const aq_record *rec, const aq_read_opts *opts,
                                     aq_error *err);

void aq_record_free(aq_record *rec);

/* ---- dispatching and deciding (record.c; the format from sniff.h) ------- */

/* Parse from memory into a raw file: dispatch on aq_sniff_format() (and,
 * for miniSEED with opts->responses, give each channel the one response
 * whose network, station, location, channel and epoch match it, searched
 * across every StationXML; none, or two, is an error naming the files). */
aq_status aq_raw_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err);

/* Parse from memory and decide one record: dispatch on aq_sniff_format(),
 * then aq_record_decide() on the file's only channel, or on the channel that
 * name's "#CHANNEL" suffix or a --component rule selects (a file of several
 * channels with none selected is refused, naming the channels). */
aq_status aq_record_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_read_opts *opts, aq_record *rec,
                          aq_error *err);

/* Turn channel ichan of raw into an aq_record in m/s^2:
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

#endif
