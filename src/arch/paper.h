/* paper.h: the work-path method as printed in the paper (for measuring its
 * error only; never the default model).
 *
 * Per hinge set, sampled at alpha1 = 0, 0.1, 0.2 ... deg up to s_c:
 *   y(x) quadratic fit (eqs. 10-11, slope 2 A1 x + A2 per docs/method.md sec. 2),
 *   lever-arm angles theta_i(x) quadratic fits (eqs. 12-13, slope likewise),
 *   W_min(x) = int F dx + sum int tau_i dtheta_i (eq. 14, torque terms kept,
 *   trapezoid over the samples), quartic fit (eq. 16),
 *   KE(x) = KE1 + F_app (x - x1) - W_min(x) + W_min(x1)         (eq. 19),
 *   M_p(x) = m_T (1 + dy/dx)^2 + sum m_i l_i^2 (dtheta_i/dx)^2    (eq. 23),
 *   t - t0 = int sqrt(M_p / (2 KE)) dx by the trapezoid rule over the
 *   sampled x, skipping points where KE <= 0 (eqs. 24-25), and the position
 *   at the end of a step from a quartic fit x(t) of those samples (eq. 25).
 * x here is the centroid's horizontal displacement along the direction of
 * motion (u = -act_sign x_m >= 0).
 *
 * The lever arms need the whole arch's centroid: it is rebuilt from the
 * moving bodies and the path's displacement (see paper.c).
 * aq_paper_free accepts NULL.
 */
#ifndef AQ_ARCH_PAPER_H
#define AQ_ARCH_PAPER_H

#include "../error.h"
#include "eom.h"
#include "path.h"

typedef struct aq_paper aq_paper;

/* Build the fits for both sets (reverse may be NULL or inadmissible: then
 * only the primary is fitted).  Returns NULL with err filled on failure. */
aq_paper *aq_paper_alloc(const aq_path *primary, const aq_path *reverse,
                         aq_error *err);
void aq_paper_free(aq_paper *w);

/* The paper's potential W_min along set k at coordinate s, J (its total
 * mechanical energy is KE + W_min). */
double aq_paper_wmin(const aq_paper *w, int set, double s);

/* One leg on set k (0 primary, 1 reverse): see aq_eom_leg. */
aq_status aq_paper_leg(aq_paper *w, int set, double a_mps2, aq_motion *m,
                       double dt_s, double *used_s, aq_leg_end *end,
                       aq_leg_stats *stats, aq_error *err);

#endif
