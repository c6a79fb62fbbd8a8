/* eom.h: the equation of motion of one hinge set, and the leg interface that
 * every dynamic model (work path, ode, paper) implements for the stepper.
 *
 * The Lagrangian of a one-degree-of-freedom path (path.h) under a uniform
 * ground acceleration a_g (m/s^2, along +x) is
 *     L = 1/2 M(s) sdot^2 - m_T (g y(s) + a_g x(s)),
 * the inertial field -a_g acting on every mass like a horizontal gravity.
 * Euler-Lagrange, d/dt (M sdot) - 1/2 M' sdot^2 + m_T (g y' + a_g x') = 0:
 *     M(s) s'' + 1/2 M'(s) s'^2 + g m_T dy/ds = -a_g m_T dx/ds        (EOM)
 * which is docs/method.md sec. 4-5 in differential form; its first integral is
 * the energy balance KE(s) = KE1 - a_g m_T (x - x1) - g m_T (y - y1).
 *
 * A leg is the motion on one set within one constant-acceleration step until
 * the step's time is used up or an event ends it: a return to s = 0 (impact,
 * handled by the stepper), s passing s_c (collapse), or a stop at s = 0 with
 * no kinetic energy and no acceleration that would move it (rest).  Turning
 * points (zero velocity, s > 0) are handled inside the leg and counted.
 *
 * The ode model's workspace (aq_eom) holds GSL odeiv2 objects; it is made
 * once per stepper (aq_eom_alloc) and freed with aq_eom_free (NULL-safe).
 */
#ifndef AQ_ARCH_EOM_H
#define AQ_ARCH_EOM_H

#include <stddef.h>

#include "../error.h"
#include "path.h"

/* The mechanical state on the active set. */
typedef struct {
  double s;        /* coordinate on the active set, rad, 0 <= s <= s_c */
  double ke_j;     /* kinetic energy, J, >= 0 */
  int dir;         /* +1 opening (s increasing), -1 closing */
  double x_m, y_m; /* whole-arch centroid displacement at s, m */
} aq_motion;

typedef enum {
  AQ_LEG_TIME = 0, /* the whole time was used; m is the end state */
  AQ_LEG_IMPACT,   /* reached s = 0 closing; m->ke_j is the pre-impact KE */
  AQ_LEG_COLLAPSE, /* reached s_c opening; *used_s is the time to it */
  AQ_LEG_REST      /* at s = 0 with KE = 0 and no acceleration opening it */
} aq_leg_end;

/* Counters and peaks a leg adds to (never reset by a leg). */
typedef struct {
  size_t reversals; /* turning points passed */
  size_t evals;     /* path (or right-hand side) evaluations */
  double peak_s;    /* max s seen (turning points, ends), rad */
  double peak_ke_j; /* max KE seen, J */
  double peak_x_m;  /* max |x| seen, m */
  size_t substeps;  /* integrator steps (Taylor sub-steps, panels, rk8pd steps) */
  /* Optional (NULL: none): called at each turning point inside a leg with
   * the time since the leg's start (s), s (rad) and x, y (m) there. */
  void (*turn)(void *ctx, double t_s, double s, double x_m, double y_m);
  void *turn_ctx;
} aq_leg_stats;

/* Evaluate p at s, with s clamped to [0, s_c] and the functions continued
 * by their Taylor expansion outside (ODE stages may probe slightly beyond
 * the ends).  exact != 0 uses p->eval_exact.  Returns 0 or the path's
 * non-zero code. */
int aq_eom_eval(const aq_path *p, int exact, double s, aq_path_point *pt);

/* Right-hand side of (EOM): s'' at (s, sdot) for ground acceleration
 * a_mps2, from a path point pt evaluated at s.  rad/s^2. */
double aq_eom_accel(const aq_path *p, const aq_path_point *pt, double sdot,
                    double a_mps2);

typedef struct aq_eom aq_eom;

/* ODE workspace: rk8pd with relative tolerance rtol (also the absolute
 * tolerance on s scaled by s_c and on sdot scaled by v_ref_radps). */
aq_eom *aq_eom_alloc(aq_error *err);
void aq_eom_free(aq_eom *w);
void aq_eom_set_tol(aq_eom *w, double rtol);
void aq_eom_set_exact(aq_eom *w, int exact);
/* Forget the step size carried between legs (call at the start of a run, so
 * that a run does not depend on the runs before it). */
void aq_eom_reset(aq_eom *w);

/* Integrate (EOM) on p from state m for at most dt_s at constant a_mps2.
 * Events (impact at s = 0, collapse at s_c) are located by Newton iteration
 * on single rk8pd steps from the last accepted step.  *used_s is the time
 * integrated.  Returns AQ_OK or AQ_ENUMERIC (GSL failure, err filled). */
aq_status aq_eom_leg(aq_eom *w, const aq_path *p, double a_mps2, aq_motion *m,
                     double dt_s, double *used_s, aq_leg_end *end,
                     aq_leg_stats *stats, aq_error *err);

#endif
