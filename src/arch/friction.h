/* friction.h: between friction.c (the programs of the statics with
 * friction) and friction_table.c (the arch's table of the least friction
 * over the load, which starts each node's method from the line of the node
 * before).  Internal to src/arch. */
#ifndef AQ_ARCH_FRICTION_H
#define AQ_ARCH_FRICTION_H

#include <stddef.h>

#include "model.h"

/* aq_friction_least (model.h) from a start: a line of thrust x0 (R0x/W,
 * R0y/W, m0/(W L) at another load, or NULL) whose normal forces at lambda
 * weigh the first program's rows, and mu0 its trial friction (its largest
 * ratio, or any guess, 0: none); the best line into x (3 values, if not
 * NULL), the slope dmu/dlambda there into *dmu (if not NULL; NAN when the
 * last program's multipliers give none), *iters the programs solved.
 * Errors as aq_friction_least's. */
aq_status aq_friction_least_from(const aq_geom *g, int act_sign, double lambda, double mu0,
                                 const double *x0, double *mu, size_t *joint, double *x,
                                 double *dmu, int *iters, aq_error *err);

#endif
