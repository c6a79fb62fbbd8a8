/* record.h: the in-memory accelerogram, and the reader entry point.
 *
 * Every reader (sac.c, at2.c, csv.c, ...; see readers.h) reports what a file
 * states, and aq_record_decide() (record.c) makes an aq_record of it: evenly
 * sampled ground acceleration in m/s^2, dt in s.  The record owns its arrays and
 * strings; aq_record_free() releases them (NULL and zeroed records are fine).
 * Readers report through aq_error and never print.
 */
#ifndef AQ_IO_RECORD_H
#define AQ_IO_RECORD_H

#include <stddef.h>

#include "../error.h"

/* How aq_record_decide knew a channel is vertical (aq_record.vertical_by). */
typedef enum {
  AQ_VERTICAL_BY_NONE = 0, /* not vertical */
  AQ_VERTICAL_BY_STATED,   /* the file states it (orientation code, direction word) */
  AQ_VERTICAL_BY_DIP,      /* its dip or incidence angle */
  AQ_VERTICAL_BY_NAME      /* its channel or column name (Z, UD, Up, vert, ...) */
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
  /* Decided by aq_record_decide (readers.h): */
  double azimuth_deg;   /* direction of positive motion, deg from north; NAN if unknown */
  double dip_deg;       /* SEED: 0 horizontal, -90 up, +90 down; NAN if unknown */
  int vertical;         /* 1: the file identifies the channel as vertical */
  int vertical_by;      /* how (aq_vertical_by): stated, dip or channel name; 0 if not */
  char event[96];       /* event as the file states it, "" if none */
  char processing[160]; /* the agency's processing as stated, "" if none */
  char units_stated[24];/* units the file states ("" if none) */
  char units_used[24];  /* units applied (canonical name, e.g. "gal") */
  char units_conflict[200]; /* "" or one line: the file states X, the rule GLOB=U uses U */
} aq_record;

/* Plausible peak ground acceleration after conversion, g: a record outside
 * [AQ_PGA_MIN_G, AQ_PGA_MAX_G] is refused unless accept_implausible (the
 * strongest records ever measured are ~4 g; 1e-5 g is below the noise of
 * strong-motion accelerometers). */
#define AQ_PGA_MAX_G 10.0
#define AQ_PGA_MIN_G 1e-5

/* Units override (--units).  AQ_UNITS_FILE: take the units from the file. */
typedef enum {
  AQ_UNITS_FILE = 0,
  AQ_UNITS_G,
  AQ_UNITS_GAL,   /* = cm/s^2 */
  AQ_UNITS_MPS2,
  AQ_UNITS_NMPS2,
  AQ_UNITS_COUNTS, /* divided by the sensitivity (SAC SCALE, counts per m/s^2) */
  AQ_UNITS_G10,   /* tenths of g (some agency formats) */
  AQ_UNITS_MMPS2  /* mm/s^2 */
} aq_units;

/* A per-file units rule (--units GLOB=U): records whose path as given
 * matches glob (fnmatch(3), no flags, so '*' also matches '/') are read in
 * units. */
#define AQ_UNITS_RULES_MAX 16
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
  char response[AQ_UNITS_GLOB_MAX]; /* --response FILE.xml: StationXML giving the
                                       sensitivity of miniSEED counts; "" none */
} aq_read_opts;

/* The units override that applies to path: the last rule whose glob matches
 * path (as given), else opts->units (AQ_UNITS_FILE if none).  opts may be
 * NULL (AQ_UNITS_FILE). */
aq_units aq_read_opts_units_for(const aq_read_opts *opts, const char *path);

/* The --units GLOB=U rule matching path (the last one), or NULL. */
const aq_units_rule *aq_read_opts_rule_for(const aq_read_opts *opts, const char *path);

/* Parse a units word: g, gal, cm/s2 (also cm/s^2, cm/s/s, cm/sec2, cmps2),
 * m/s2 (m/s^2, m/s/s, mps2), mm/s2, nm/s2 (nm/s^2), g/10, counts;
 * case-insensitive.
 * Returns 1 and sets *out on success, 0 if s is not one of them. */
int aq_units_parse(const char *s, aq_units *out);

/* The canonical name of u ("g", "gal", "m/s2", "nm/s2", "counts", "file"). */
const char *aq_units_name(aq_units u);

/* Metres per second squared per unit of u (g: 9.80665, gal: 0.01, ...);
 * 0 for AQ_UNITS_FILE and AQ_UNITS_COUNTS (counts need a sensitivity). */
double aq_units_to_mps2(aq_units u);

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

/* Record names for operands paths[0..n): a file of several channels, named
 * without #CHANNEL and chosen by no --component rule, becomes one name per
 * channel, "FILE#CHANNEL", in file order; any other operand is kept as given
 * (an unreadable one is reported when it is read).  On AQ_OK *out holds
 * *nout malloc'd names (free with aq_record_names_free); else AQ_ENOMEM. */
aq_status aq_record_expand(char *const *paths, size_t n, const aq_read_opts *opts,
                           char ***out, size_t *nout, aq_error *err);
void aq_record_names_free(char **names, size_t n);

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

#endif
