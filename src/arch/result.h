/* result.h: what one dynamic run of one arch under one step list yields.
 * Plain data; the optional history arrays are owned by the result and freed
 * by aq_result_free (NULL-safe).  SI units; rotation in rad. */
#ifndef AQ_ARCH_RESULT_H
#define AQ_ARCH_RESULT_H

#include <stddef.h>

#include "path.h"

typedef struct {
  size_t n, cap;
  /* One sample at each step end, and (default and workpath-quad models) one
   * at each turning point inside a step (KE = 0, the true peak) and at each
   * impact (q = 0, the KE before it); in time order. */
  double *time_s;             /* sample times, s */
  double *rotation_rad;       /* q at the sample (global sign), rad */
  double *displacement_m;     /* x of the whole arch's centroid from rest, m */
  double *kinetic_energy_j;   /* J */
  double *potential_energy_j; /* J, from the undeformed arch */
  int *set;                   /* 0 primary, 1 reverse, -1 at rest */
} aq_history;

/* The block model's own outputs (src/blocks/blocks.h, docs/blocks.md);
 * owned by the result. */
typedef struct {
  double max_slip_m;          /* largest tangential slip at any joint, m */
  char *hinges_observed;      /* the joints and faces that opened, "0e,6i,12e,19i" ("" none) */
  char *hinges_first_s;       /* their first opening times, s, in the same order */
  double mechanism_changed_s; /* first time the opened set left the arch's sets; NAN: never */
  size_t steps_siconos;       /* steps whose contact problem went to Siconos */
  size_t steps_loose;         /* of them, solved to 1e-3 of the step's scales only */
  /* with a history: every voussoir's centroid and rotation at each sample,
   * sample i, voussoir k at [i * nvous + k] (m, m, rad) */
  size_t nvous;
  double *hist_x_m, *hist_y_m, *hist_rot_rad;
  double friction_work_j;     /* the work the joints' friction took, J (>= 0) */
} aq_result_bodies;

typedef struct {
  int collapsed;               /* 1 if q passed q_c of the active set */
  double collapse_time_s;      /* NAN if it survived; s in record time */
  double peak_rotation_rad;    /* max |q| */
  double peak_displacement_m;  /* max |x - x0| of the whole arch's centroid */
  double max_kinetic_energy_j; /* J */
  double energy_in_j;          /* work done by the ground on the arch, J */
  double energy_dissipated_j;  /* lost at impacts, J */
  size_t impacts;              /* returns to the undeformed shape */
  int first_set;               /* set the record drove first: 0 primary, 1 reverse, -1 none */
  int peak_set;                /* set in which peak_rotation_rad occurred, -1 if it never moved */
  double peak_rotation_set_rad[2]; /* max |q| on the primary (0) and reverse (1) set, rad
                                      (0 on a set it never moved on) */
  size_t reversals;            /* zero-velocity turning points */
  size_t steps_total;          /* steps in the input */
  size_t steps_moving;         /* steps integrated in motion (not skipped at rest) */
  size_t evals;                /* path (or right-hand side) evaluations; table pieces fetched */
  size_t substeps;             /* integrator steps: Taylor sub-steps, panels, rk8pd steps */
  /* What the motion asked of the joints (demand.h), NAN when not tracked
   * or the arch never moved: */
  double mu_demand;            /* largest |T|/N at any joint (INFINITY: a joint in tension) */
  size_t mu_demand_joint;      /* where */
  double thrust_ecc_max;       /* largest |eccentricity| of the thrust at a non-hinge joint */
  double thrust_ecc_time_s;    /* first time it passed 1 (record time), NAN: never */
  double slide_time_s;         /* first time mu_demand passed the friction given, NAN: never */
  size_t demand_samples;       /* states looked at */
  size_t demand_full;          /* of them, with every joint evaluated */
  size_t demand_looks;         /* candidates evaluated (one entry each) */
  aq_history history;          /* filled only when asked */
  aq_result_bodies *bodies;    /* the block model's own; NULL for the four-hinge models */
} aq_result;

void aq_result_free(aq_result *r);

/* The largest |q| / q_c over both sets (primary, reverse: NULL or not
 * admissible where the arch has none): 1 for a run that collapsed (it stops
 * at q_c), 0 if it never moved, NAN if it moved on a set with no path. */
double aq_result_peak_over_qc(const aq_result *r, const aq_path *primary, const aq_path *reverse);

/* The marks of a run against the four-hinge models' assumptions
 * (docs/demand.md): AQ_MARK_SLIDES when a friction was given (NAN: none)
 * and the run's friction demand passed it, AQ_MARK_BEYOND under free
 * control when the thrust left a joint's section (thrust_ecc_max > 1). */
enum { AQ_MARK_SLIDES = 1, AQ_MARK_BEYOND = 2 };
int aq_result_marks(double mu_demand, double thrust_ecc_max, double friction, int free_control);
/* marks as a status: "ok" (none), "slides", "beyond" or "slides+beyond". */
const char *aq_result_marks_name(int marks);

#endif
