/* scale.h: the scaling rule and the arch's lambda0.
 *
 * A run shakes an arch with its subject (at factor 1: the processed record
 * or motion) times a factor:
 *   --scale LIST           each factor of the list;
 *   --scale-to-pga G       G / PGA, PGA the subject's (a motion's: the peak
 *                          of its horizontal vector, the same at every
 *                          azimuth), in g;
 *   --scale-to-lambda0 K   K lambda0 / PGA for each arch, lambda0 the arch's
 *                          static collapse multiplier (the smaller of its
 *                          admissible hinge sets'), so that arches of unlike
 *                          strength are shaken alike (PGA = K lambda0 g).
 * The polarity is the factor's sign (reversed: the subject negated, once,
 * after processing); a vertical component scales with the motion but keeps
 * its sign: turning the arch round does not turn gravity over.
 * Dimensionless factors; PGAs in g.  Nothing here prints. */
#ifndef AQ_JOB_SCALE_H
#define AQ_JOB_SCALE_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../error.h"

typedef struct {
  const double *factors; /* --scale, or NULL */
  size_t nfactor;
  double to_pga_g;       /* --scale-to-pga G (factors NULL, k_lambda0 0) */
  double k_lambda0;      /* --scale-to-lambda0 K > 0 (factors NULL), else 0 */
} aq_scale_rule;

/* The arch's static collapse multiplier lambda0: the smaller of its
 * admissible hinge sets' (NAN when none is admissible). */
double aq_lambda0(const aq_arch *arch);

/* Factor k (< nfactor; 0 without a list) for a subject of PGA pga_g, before
 * the arch: factors[k], to_pga_g / pga_g, or with --scale-to-lambda0 the
 * factor to a PGA of 1 g, 1 / pga_g (aq_scale_for_arch finishes it). */
double aq_scale_factor(const aq_scale_rule *r, size_t k, double pga_g);

/* 1 if the factor depends on the arch (--scale-to-lambda0). */
int aq_scale_per_arch(const aq_scale_rule *r);

/* The factor of an arch of multiplier lambda0 from f = aq_scale_factor:
 * K lambda0 f with --scale-to-lambda0, else f. */
double aq_scale_for_arch(const aq_scale_rule *r, double lambda0, double f);

/* AQ_OK if the rule can scale a subject of PGA pga_g (a list of factors, or
 * pga_g > 0); else AQ_EVALUE naming input and the option. */
aq_status aq_scale_check_subject(const aq_scale_rule *r, const char *input, double pga_g,
                                 aq_error *err);

/* AQ_OK if f (from aq_scale_for_arch) can run; else, with
 * --scale-to-lambda0 and an arch of lambda0 <= 0 or none, AQ_EVALUE naming
 * arch_path. */
aq_status aq_scale_check_arch(const aq_scale_rule *r, const char *arch_path, double lambda0,
                              double f, aq_error *err);

/* The factor the arch feels: f, negated for the reversed polarity. */
static inline double aq_scale_signed(double f, int reversed)
{
  return reversed ? -f : f;
}

#endif
