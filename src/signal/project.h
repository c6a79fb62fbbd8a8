/* project.h: the in-plane horizontal acceleration of an arch from two
 * horizontal component records (src/signal).
 *
 * An arch whose +x axis points to azimuth theta (deg clockwise from north)
 * feels a_x(t) = a1(t) cos(theta - phi1) + a2(t) cos(theta - phi2) from
 * components whose positive directions point to phi1 and phi2 (deg), if they
 * are orthogonal (docs/dynamics.md, "Orientation and vertical acceleration").
 * A non-orthogonal pair is refused: the rule above is then not the in-plane
 * acceleration (the components are not the coordinates of the horizontal
 * vector), and archquake does not guess a decomposition.
 *
 * Degrees live only in this interface (theta_deg, phi_deg); nothing here
 * allocates; errors go to aq_error, nothing prints.
 */
#ifndef AQ_SIGNAL_PROJECT_H
#define AQ_SIGNAL_PROJECT_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"

/* Two components are orthogonal if their azimuths differ by 90 deg (mod 180)
 * within this, deg. */
#define AQ_PROJECT_ORTHO_TOL_DEG 1.0
/* Components share a sample interval if their dt differ by less than this
 * fraction of dt (a relative tolerance: header dt are printed to 4-7 digits). */
#define AQ_PROJECT_DT_REL_TOL 1e-6
/* Components share a start time if their begin times differ by less than
 * this fraction of dt. */
#define AQ_PROJECT_T0_FRAC_DT 1e-3

/* cos(angle_deg), with the angle first reduced to [0, 360) and the
 * half-turn taken out exactly: cos(d + 180) = -cos(d) bit for bit wherever
 * d + 180 is exact (whole degrees, halves, quarters...), so the arch turned
 * by 180 deg sees exactly the negated record. */
double aq_project_cos_deg(double angle_deg);

/* The coefficients of a_x = c[0] a1 + c[1] a2 at arch azimuth theta_deg for
 * components at phi_deg[0], phi_deg[1]: c[j] = aq_project_cos_deg(theta -
 * phi_j). */
void aq_project_coefs(double theta_deg, const double phi_deg[2], double c[2]);

/* AQ_OK if the azimuths are known (finite) and orthogonal within
 * AQ_PROJECT_ORTHO_TOL_DEG; else AQ_EVALUE with err naming the pair (label)
 * and the reason. */
aq_status aq_project_check_pair(const char *label, const double phi_deg[2],
                                aq_error *err);

/* The direction of positive motion stated for rec, deg from north, or NAN:
 * the header's (rec->azimuth_deg: PEER's component angle, SAC CMPAZ, the
 * agency formats' direction fields), else for a PEER NGA AT2 file its name's
 * (after the station code: ..._GIL067.AT2, ...-ELC180-hor1.AT2: three
 * letters then three digits, 0-360); other formats' names say nothing. */
double aq_project_azimuth_of(const aq_record *rec);

/* AQ_OK if the n records share dt (within AQ_PROJECT_DT_REL_TOL) and start
 * time (same reference time, begin within AQ_PROJECT_T0_FRAC_DT dt); else
 * AQ_EVALUE naming the component and what differs.  Their lengths may
 * differ: the caller keeps the samples they share (aq_project_common_npts). */
aq_status aq_project_check_aligned(const aq_record *const *rec, size_t n,
                                   aq_error *err);

/* max_i sqrt(a1[i]^2 + a2[i]^2): the peak of the horizontal vector, the
 * same whatever the azimuth (units of a1, a2). */
double aq_project_peak_horizontal(const double *a1, const double *a2, size_t n);

/* The number of samples every one of the n records has. */
size_t aq_project_common_npts(const aq_record *const *rec, size_t n);

#endif
