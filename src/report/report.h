/* src/report: results written and read back: TSV rows, the HDF5 results
 * file, the journal of a run in progress, and compare.
 *
 * report.h: the results of a suite as the report writers see them
 * (src/report).  One run = (record, arch, scale); its summary is one
 * aq_summary, a plain struct with fixed-size strings (none of them cut: see
 * the limits below), which is at once a text
 * row (text.c), a row of the HDF5 summary table (h5.c), and what
 * `archquake compare` matches and compares (compare.c).  The field table aq_summary_fields[] lists the
 * summary's fields in column order; every writer and the reader use it, so a
 * name is the same everywhere.
 *
 * Units: SI (s, m, rad, J); pga_g in g; scale dimensionless.
 * Nothing here allocates; no function prints.
 */
#ifndef AQ_REPORT_REPORT_H
#define AQ_REPORT_REPORT_H

#include <stddef.h>
#include <stdint.h>

#include "../arch/path.h"
#include "../arch/result.h"
#include "../error.h"

/* A record as given is a path the system can open: PATH_MAX (4096) bytes
 * with its NUL.  It is kept whole: the main job refuses a longer one before
 * any run (src/app/suite_record.c), and the HDF5 files store it as a
 * variable-length string (docs/hdf5-layout.md). */
#define AQ_SUMMARY_RECORD_MAX 4096
#define AQ_SUMMARY_ARCH_MAX 128
#define AQ_SUMMARY_MODEL_MAX 16
#define AQ_SUMMARY_STATUS_MAX 48
#define AQ_SUMMARY_POLARITY_MAX 16
#define AQ_SUMMARY_CONTROL_MAX 8
#define AQ_SUMMARY_CHECK_MAX 8 /* "agrees", "differs", "failed", "-" */
#define AQ_SUMMARY_HINGES_MAX 160 /* the block model's hinge lists, truncated with ",..." */

/* An integer result that a failed run did not compute (collapsed, impacts):
 * the text writers show it as "nan", the HDF5 file stores it as is. */
#define AQ_SUMMARY_INT_NONE (-1)

/* One run's summary.  A run that failed (or whose record failed) has status
 * other than "ok" and no verdict: every result field (collapsed onwards) is
 * NAN, or AQ_SUMMARY_INT_NONE for the integers. */
typedef struct {
  char record[AQ_SUMMARY_RECORD_MAX]; /* record file as given on the command line */
  char arch[AQ_SUMMARY_ARCH_MAX];     /* arch name ([arch] name) */
  char model[AQ_SUMMARY_MODEL_MAX];   /* workpath | ode | paper */
  double scale;                       /* factor applied to the processed record */
  double pga_g;                       /* PGA of the scaled processed record, g */
  char status[AQ_SUMMARY_STATUS_MAX]; /* "ok" or a short code such as "read:eformat" */
  int64_t collapsed;                  /* 1 collapsed, 0 survived, AQ_SUMMARY_INT_NONE failed */
  double collapse_time_s;             /* record time of collapse, s; NAN if it survived */
  double peak_rotation_rad;           /* max |q|, rad */
  double peak_displacement_m;         /* max |x - x0| of the arch's centroid, m */
  double max_kinetic_energy_j;        /* J */
  int64_t impacts;                    /* returns to the undeformed shape (or _NONE) */
  double energy_in_j;                 /* work done by the ground, J */
  double energy_dissipated_j;         /* lost at impacts, J */
  char polarity[AQ_SUMMARY_POLARITY_MAX]; /* "normal" (record as read) or "reversed" (negated) */
  /* normalised results (NAN for a failed run) */
  double lambda0_first;         /* lambda0 of the set the record drove first; NAN if it never moved */
  double peak_rotation_over_qc; /* peak rotation / q_c of the set it occurred in (0 if never moved) */
  double pga_over_lambda0;    /* pga_g / lambda0 of the set driven first (if none: the lower
                                   admissible lambda0) */
  double azimuth_deg;           /* the arch's +x azimuth, deg from north, for a ground
                                   motion given as components; NAN for one in-plane record */
  char control[AQ_SUMMARY_CONTROL_MAX]; /* the arch's hinge control, "fixed" or "free"
                                           (arch.h aq_hinge_control) */
  /* what the motion asked of the joints (docs/demand.md); NAN for a run that
   * did not move or failed, and under the paper model */
  double mu_demand;             /* largest |T|/N at any joint (inf: a joint pulled apart) */
  int64_t mu_demand_joint;      /* the joint where it occurred (or _NONE) */
  double thrust_ecc_max;        /* largest |eccentricity| of the thrust at a non-hinge joint */
  double thrust_ecc_time_s;     /* first time the eccentricity passed 1, s; NAN: never */
  double slide_time_s;          /* first time mu_demand passed the friction given, s; NAN:
                                   never, or no friction given */
  /* the block model's own (docs/blocks.md); NAN and "-" for the four-hinge
   * models and a failed run */
  double max_slip_m;            /* largest tangential slip at any joint, m */
  char hinges_observed[AQ_SUMMARY_HINGES_MAX]; /* the joints and faces that opened,
                                                  "0e,6i,12e,19i" ("-": none) */
  char hinges_first_s[AQ_SUMMARY_HINGES_MAX];  /* their first opening times, s */
  double mechanism_changed_s;   /* first time the opened set left the arch's sets; NAN: never */
  /* --check blocks: the block model's verdict on a run the four-hinge
   * model marked ("-", NONE and NAN for a run not checked) */
  char check_blocks[AQ_SUMMARY_CHECK_MAX]; /* "agrees", "differs", "failed" or "-" */
  int64_t check_collapsed;      /* the block model's collapsed */
  double check_collapse_time_s; /* its collapse_time_s */
  double check_peak_rotation_rad; /* its peak_rotation_rad */
  /* the block model's (NAN as max_slip_m): the work its joints' friction
   * took from the record's start, J */
  double friction_work_j;
} aq_summary;

typedef enum { AQ_SF_STR = 0, AQ_SF_DOUBLE, AQ_SF_INT } aq_summary_kind;

typedef struct {
  const char *name;     /* column, attribute and compound member name */
  aq_summary_kind kind; /* AQ_SF_STR: char[size]; DOUBLE: double; INT: int64_t */
  size_t offset;        /* offsetof(aq_summary, field) */
  size_t size;          /* sizeof the field */
  int key;              /* 1 for the fields that identify a run (record, arch, scale, polarity) */
  int optional;         /* 1: absent from files written before the field existed; read
                           back as aq_summary_fill leaves it (polarity normal, NAN) */
} aq_summary_field;

/* The fields in column order (record arch model scale pga_g status collapsed
 * collapse_time_s peak_rotation_rad peak_displacement_m max_kinetic_energy_j
 * impacts energy_in_j energy_dissipated_j polarity lambda0_first
 * peak_rotation_over_qc pga_over_lambda0 azimuth_deg control mu_demand
 * mu_demand_joint thrust_ecc_max thrust_ecc_time_s slide_time_s max_slip_m
 * hinges_observed hinges_first_s mechanism_changed_s check_blocks
 * check_collapsed check_collapse_time_s check_peak_rotation_rad friction_work_j). */
/* The most fields a summary may have (fixed-size tables of columns). */
#define AQ_SUMMARY_FIELDS_MAX 64
extern const aq_summary_field aq_summary_fields[];
extern const size_t aq_summary_nfields;

/* Fill s for one run (control "fixed": the caller sets the arch's).
 * record, arch, model and status are copied (record
 * must be shorter than AQ_SUMMARY_RECORD_MAX, arch than AQ_SUMMARY_ARCH_MAX:
 * the callers refuse longer ones before any run; model and status are the
 * program's own short words); res may be NULL for a run that did not happen (then
 * the result fields are as documented above).  pga_g may be NAN. */
void aq_summary_fill(aq_summary *s, const char *record, const char *arch,
                     const char *model, double scale, double pga_g,
                     const char *status, const aq_result *res);

/* Set the polarity ("normal" or "reversed"; aq_summary_fill sets "normal")
 * and the normalised fields of a run that has a result res, from the two
 * hinge sets' paths of its arch (either may be NULL or inadmissible). */
void aq_summary_normalise(aq_summary *s, const char *polarity, const aq_result *res,
                          const aq_path *primary, const aq_path *reverse);

/* The marks of a run that ran (status "ok"), as its status: "slides" when
 * a friction was given (friction, NAN: none) and the run's friction demand
 * passed it, "beyond" under free control (free_control 1) when the thrust
 * left a joint's section, "slides+beyond" both; "ok" when neither.  A
 * failed run keeps its status (it has no verdict to mark). */
void aq_summary_mark(aq_summary *s, double friction, int free_control);
/* --check blocks: the block model's run b of the same motion as s's
 * (NULL: it failed) into s's check columns and block columns; "agrees"
 * when both say collapsed or both survived. */
void aq_summary_check(aq_summary *s, const aq_result *b);

/* 1 if status is a failure's ("stage:code"), 0 for "ok" and the marks. */
int aq_summary_failed(const char *status);

/* Short status code for a failure in a stage: "<stage>:<code>", e.g.
 * "read:eformat", "run:enumeric" (code = the aq_status name in lower case
 * without "AQ_"); buf receives it (NUL-terminated, truncated to n). */
void aq_summary_status(char *buf, size_t n, const char *stage, aq_status st);

/* The worst of n runs of one (ground motion, arch, scale) at different
 * azimuths, as a screening verdict: a failed run first (no verdict can be
 * given), then a collapse (the earliest), then the largest peak rotation /
 * q_c; ties go to the first.  Returns its index (0 for n = 0). */
size_t aq_summary_worst(const aq_summary *const *rows, size_t n);

/* Units of a field, from its name's suffix as the naming rule gives them:
 * "s", "rad", "m", "J", "g", "deg" for *_s, *_rad, *_m, *_j, *_g, *_deg; "" for strings;
 * "1" for a ratio (*_over_*) and every other number (scale, counts,
 * lambda0).  Never NULL. */
const char *aq_summary_units(const aq_summary_field *f);

/* Field value access by table entry. */
double aq_summary_get_double(const aq_summary *s, const aq_summary_field *f);
int64_t aq_summary_get_int(const aq_summary *s, const aq_summary_field *f);
const char *aq_summary_get_str(const aq_summary *s, const aq_summary_field *f);

#endif
