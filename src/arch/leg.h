/* leg.h: the work-path leg integrators (the leg contract, aq_motion and
 * aq_leg_stats are in eom.h, beside the ode's leg).
 *
 * aq_taylor (leg_taylor.c, the default model): time-Taylor series of s(t)
 * on the tables' polynomial pieces (path.h aq_path_piece); needs
 * p->piece.  aq_quad (leg_quad.c, --model workpath-quad): the time integral
 * of the energy balance by Chebyshev panels; any path (tables or exact).
 * Each workspace is made once per stepper (alloc) and freed with its free
 * (NULL-safe); errors are reported through aq_error, never printed.
 */
#ifndef AQ_ARCH_LEG_H
#define AQ_ARCH_LEG_H

#include "../error.h"
#include "eom.h"
#include "path.h"

typedef struct aq_taylor aq_taylor;

aq_taylor *aq_taylor_alloc(aq_error *err);
void aq_taylor_free(aq_taylor *w);
/* Truncation tolerance of a sub-step: the series' tail relative to the
 * size of the sub-step's motion (default: about one unit round-off). */
void aq_taylor_set_tol(aq_taylor *w, double tol);
/* Forget the cached piece (start of a run). */
void aq_taylor_reset(aq_taylor *w);
/* The leg of eom.h on p (p->piece must be set).  AQ_OK or AQ_ENUMERIC. */
aq_status aq_taylor_leg(aq_taylor *w, const aq_path *p, double a_mps2,
                        aq_motion *m, double dt_s, double *used_s,
                        aq_leg_end *end, aq_leg_stats *stats, aq_error *err);

typedef struct aq_quad aq_quad;

aq_quad *aq_quad_alloc(aq_error *err);
void aq_quad_free(aq_quad *w);
void aq_quad_set_tol(aq_quad *w, double tol);  /* Chebyshev tail / mean, per panel */
void aq_quad_set_nodes(aq_quad *w, int n);     /* Chebyshev nodes per panel, 4..32 */
void aq_quad_set_exact(aq_quad *w, int exact); /* eval_exact instead of the tables */
void aq_quad_reset(aq_quad *w);                /* forget the cached point */
aq_status aq_quad_leg(aq_quad *w, const aq_path *p, double a_mps2,
                      aq_motion *m, double dt_s, double *used_s,
                      aq_leg_end *end, aq_leg_stats *stats, aq_error *err);

#endif
