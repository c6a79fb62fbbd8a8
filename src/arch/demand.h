/* demand.h: what a hinge set in motion asks of its joints (src/arch/demand.c).
 *
 * At a position s of a hinge set, with gravity g (m/s^2; g + a_v under a
 * vertical ground acceleration), horizontal ground acceleration a (m/s^2,
 * along +x) and speed sdot (rad/s), each piece of the arch is in dynamic
 * equilibrium with its loads and its inertia forces (d'Alembert), the
 * acceleration sddot following from the equation of motion.  Every force
 * across a joint is then linear in z = (g, a, sdot^2):
 *     value = f[0] g + f[1] a + f[2] sdot^2.
 * For each joint the forms give the compressive normal force N (> 0
 * pressing the two sides together), the tangential force T, and the
 * moment of the resultant about the joint's middle over its half-depth,
 * signed so that the thrust's eccentricity is e / N (|e/N| <= 1: the
 * resultant crosses the joint inside the section).  Friction demand at the
 * joint: |T| / N; a joint in tension (N <= 0) demands more than any
 * friction and lets the thrust leave the section.
 *
 * Joints 0..n in order (n voussoirs; at a hinge joint, the forms on the
 * face of the body on its counter-clockwise side), then one entry per
 * hinge for the face of the body on its clockwise side (a hinge is a
 * corner: the two faces have turned apart).  Hinge entries have e = 0.
 *
 * aq_demand (the per-run tracker over a set's table) comes with the
 * stepper hooks; see below.  Units SI; nothing here prints. */
#ifndef AQ_ARCH_DEMAND_H
#define AQ_ARCH_DEMAND_H

#include <stddef.h>

#include "../error.h"
#include "../signal/steps.h"
#include "model.h"

typedef struct {
  size_t joint; /* 0..n */
  int hinge;    /* -1 for a joint inside a piece, else 0..3 */
  double n[3];  /* normal force: N per (m/s^2), N per (m/s^2), N per (rad/s)^2 */
  double t[3];  /* tangential force, same units */
  double e[3];  /* moment about the joint's middle / its half-depth, N per ... */
} aq_joint_form;

/* Entries of a set on an arch of n voussoirs: n + 1 joints and 4 faces. */
static inline size_t aq_demand_nforms(size_t n) { return n + 1 + 4; }

/* The motion's own quantities at s. */
typedef struct {
  double sddot[3];  /* d2s/dt2 as a form in z: rad/s^2 per m/s^2, per m/s^2, per (rad/s)^2 */
  double mgen_kgm2; /* the generalised mass M(s), kg m^2 */
  double x_m, y_m;  /* sum over the moving bodies of m_b c_b / m_T (absolute; the
                       whole arch's centroid less a constant), m */
} aq_demand_kin;

/* The forms of every joint of mechanism m (q = q_sign s) at s (rad):
 * f[aq_demand_nforms(n)], and (kin, if not NULL) the motion's quantities.
 * Returns 0, or -1 when the linkage does not close at s or the balance is
 * singular. */
int aq_demand_forms(const aq_mech *m, int q_sign, double s, aq_joint_form *f,
                    aq_demand_kin *kin);

/* ---- tables (one per hinge set, built once, read-only) ---- */

typedef struct aq_demand_table aq_demand_table;

/* The forms of every joint of set p (its four-bar m) along [0, s_c], as
 * cubics on intervals halved until they are within DT_TOL of the exact
 * forms (relative to the largest normal force at rest; the sdot^2 column
 * against the speed that carries the energy of collapse), with sddot and
 * 1/M beside them.  *out is the caller's (aq_demand_table_free, NULL-safe).
 * AQ_EINADMISSIBLE, AQ_ENUMERIC (a singular balance on the path), AQ_ENOMEM. */
aq_status aq_demand_table_build(const aq_mech *m, const aq_path *p, aq_demand_table **out,
                                aq_error *err);
void aq_demand_table_free(aq_demand_table *t);
size_t aq_demand_table_intervals(const aq_demand_table *t);
/* The tabled forms at s (0 <= s <= s_c) into f[aq_demand_nforms(n)] and
 * (kin, if not NULL) sddot, M, x, y: as aq_demand_forms within the
 * tables' error.  0, or -1 outside [0, s_c]. */
int aq_demand_table_forms(const aq_demand_table *t, double s, aq_joint_form *f,
                          aq_demand_kin *kin);
/* The largest error measured against the exact forms, relative to the
 * table's scale (above the target only where halving stopped). */
double aq_demand_table_error(const aq_demand_table *t);

/* ---- the tracker (one per stepper) ---- */

/* What a run asked of the joints, over every position it moved through
 * (aq_demand_get): */
typedef struct {
  double mu_max;      /* largest |T|/N over the joints; INFINITY: some joint in
                         tension (N <= 0); NAN: never moved (or no table) */
  size_t mu_joint;    /* the joint where it occurred */
  double mu_time_s;   /* when (record time of the sample), s */
  double ecc_max;     /* largest |eccentricity| of the thrust at a non-hinge joint */
  size_t ecc_joint;
  double ecc_time_s;
  double ecc_over_s;  /* first time the eccentricity passed 1, NAN: never */
  double slide_s;     /* first time |T|/N passed the friction limit, NAN: never (or none) */
  size_t samples;     /* states looked at */
  size_t full;        /* of them, with every joint evaluated */
  size_t looks;       /* candidates evaluated (one entry each) */
} aq_demand_result;

typedef struct aq_demand aq_demand;

/* A tracker reading the table of set k from get(ctx, k) (called once per
 * set, the first time the set moves; NULL: none, the run's demand is then
 * NAN).  NULL (err) out of memory.  aq_demand_free accepts NULL. */
aq_demand *aq_demand_alloc(const aq_demand_table *(*get)(void *ctx, int set), void *ctx,
                           aq_error *err);
void aq_demand_free(aq_demand *d);
/* on: evaluate every joint at every state, the regions aside (the
 * tracker's reference, for tests and the bench). */
void aq_demand_set_every(aq_demand *d, int on);
/* The friction coefficient a run is checked against (NAN: none). */
void aq_demand_set_limit(aq_demand *d, double mu);
/* Marks only (capacity, docs/capacity.md): a run's results are asked for
 * whether |T|/N passed the limit (slide 1) and whether the eccentricity
 * passed 1 (ecc 1), and nothing more.  Each quantity is left once it has
 * passed (or from the start when it is not asked for), so the maxima, their
 * entries and times are those of the run up to there only; slide_s and
 * ecc_over_s, and so the marks, are the full tracker's, to the bit. */
void aq_demand_set_marks_only(aq_demand *d, int slide, int ecc);
/* Start a run. */
void aq_demand_begin(aq_demand *d);
/* The state of a run on set k: position s (rad), kinetic energy ke_j (J),
 * ground acceleration a_mps2 along +x, gravity g_mps2 (g + a_v), record
 * time t_s. */
void aq_demand_at(aq_demand *d, int k, double s, double ke_j, double a_mps2, double g_mps2,
                  double t_s);
/* The end of a leg on set k at (s, ke_j), moving in direction dir (+1
 * opening, -1 closing), under constant a_mps2 and g_mps2, after rev
 * turning points inside it: its walls (the last one behind the end, and
 * the one before on the other side), located from the end to second order
 * in the distance, then the end itself, at record time t_s. */
void aq_demand_leg(aq_demand *d, int k, double s, double ke_j, int dir, size_t rev,
                   double a_mps2, double g_mps2, double t_s);
/* ---- the stepper's hooks: a leg at a time, queued ----
 * A leg of set k from (s0, ke0) at record time t0 to (s1, ke1) at t1,
 * moving in direction dir at its end, with rev turning points inside it,
 * under a_mps2 and g_mps2: the results of aq_demand_at of its start, then
 * aq_demand_leg of its end, to the bit, worked out when the queue is full
 * or flushed (the stepper's loop fills a record per leg, aq_demand_slot). */
typedef struct {
  double s0, ke0, t0, s1, ke1, t1, a_mps2, g_mps2;
  int k, dir;
  size_t rev;
} aq_demand_leg_rec;
typedef struct {
  aq_demand_leg_rec *rec;
  size_t n, cap;
  int closed; /* 1: nothing a leg could add (the maxima are infinite, or no table) */
} aq_demand_queue;
/* Look at every queued leg now (before aq_demand_still and aq_demand_get). */
void aq_demand_flush(aq_demand *d);
/* The next leg's record, to fill in (NULL: nothing a leg could add). */
static inline aq_demand_leg_rec *aq_demand_slot(aq_demand *d)
{
  aq_demand_queue *q = (aq_demand_queue *)(void *)d; /* the tracker's first member */
  if (q->n == q->cap && !q->closed)
    aq_demand_flush(d);
  return q->closed ? NULL : q->rec + q->n++;
}
/* ---- a run in which the arch never moves ----
 * Its demand is that of the statics: the least friction with which a line
 * of thrust stands at the record's peak (docs/demand.md, "A run that never
 * moves").  least(ctx, act_sign, lambda, joint) gives that friction under a
 * ground acceleration lambda g of sign act_sign (lambda >= 0; INFINITY: no
 * line of thrust stands; NAN: unknown), nondecreasing in lambda, and the
 * joint where it is needed.  Without it (NULL) such a run's demand is NAN. */
typedef double (*aq_demand_least_fn)(void *ctx, int act_sign, double lambda, size_t *joint);
void aq_demand_set_least(aq_demand *d, aq_demand_least_fn least, void *ctx);
/* The run that began with aq_demand_begin ended with the arch at rest
 * throughout, on steps[0..n_end) scaled by scale (vertical by vscale) under
 * gravity g_mps2: each direction's peak of the ground acceleration over
 * g + a_v drives its own act_sign; the demand is the larger of the two
 * directions' least friction, its joint, and (over the limit) the first
 * step whose load needs more than the limit.  No effect on a run that
 * moved. */
void aq_demand_still(aq_demand *d, const aq_steps *steps, size_t n_end, double scale,
                     double vscale, double g_mps2);
void aq_demand_get(const aq_demand *d, aq_demand_result *r);
/* For the tests: the cell of set t's grid that holds the state (s rad,
 * a/g, KE/g): the upper bounds of both quantities over it (u), and its
 * candidates, those of |T|/N then those of |e|/N (n[2] of them, into
 * cand[cap]).  1, 0 for a state outside the grid, -1 when cap is short. */
int aq_demand_grid_cell(const aq_demand_table *t, double s, double al, double kg, double u[2],
                        size_t *cand, size_t cap, size_t n[2]);

#endif
