/* domain.h: the half-cycle collapse domain (the paper's section 4.1,
 * Oppenheim 1992): for an amplitude ratio r, the shortest rectangular pulse
 * of r lambda0 g, in the direction that opens the primary set, that
 * collapses the arch, by bisection on the duration (not the paper's 0.02 s
 * stepping).  Used by `archquake domain` and `archquake plot domain`.
 * Reports through aq_error; nothing here prints.  SI units. */
#ifndef AQ_ARCH_DOMAIN_H
#define AQ_ARCH_DOMAIN_H

#include "../error.h"
#include "path.h"
#include "stepper.h"

/* For ratio r (> 1): the pulse's acceleration *accel_mps2 (signed, along
 * +x) and its shortest collapsing duration *dur_s (s), to tol_s; INFINITY
 * when no pulse up to tmax_s collapses it.  st is a stepper on the arch's
 * two sets (options set by the caller); primary is the set it opens.
 * AQ_OK, or the stepper's status with err filled. */
aq_status aq_domain_min_duration(aq_stepper *st, const aq_path *primary,
                                 double ratio, double tol_s, double tmax_s,
                                 double *accel_mps2, double *dur_s,
                                 aq_error *err);
/* As aq_domain_min_duration, and *run (not NULL) the result of the run of
 * the shortest collapsing pulse (its marks: what the verdict rests on),
 * zeroed when none collapses; free it with aq_result_free. */
aq_status aq_domain_min_duration_run(aq_stepper *st, const aq_path *primary, double ratio,
                                     double tol_s, double tmax_s, double *accel_mps2,
                                     double *dur_s, aq_result *run, aq_error *err);

#endif
