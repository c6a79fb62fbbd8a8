/* region.h: plane regions bounded by loops of pieces, straight segments
 * or offsets of an arch's centre line, and their mass properties by
 * Green's theorem (region.c; internal to src/arch, used by geometry.c).
 * Units: SI (m, kg).  Nothing is allocated here: the caller owns every
 * array of pieces and points.
 */
#ifndef AQ_ARCH_REGION_H
#define AQ_ARCH_REGION_H

#include <gsl/gsl_integration.h>
#include <stddef.h>

#include "model.h"

#define GL_POINTS 20         /* Gauss-Legendre points per panel */
#define CROSS_SAMPLES 32     /* samples of a curve piece when cutting it at the fill's level */

/* A piece of a boundary: a straight segment p0 -> p1 (curve < 0), or the
 * offset v of the centre line's curve from parameter u0 to u1 (p0, p1 its
 * ends). */
typedef struct {
  int curve;
  double v, u0, u1;
  aq_vec2 p0, p1;
} piece;

/* The region's pieces (aq_sector_mass and aq_mass_add, also here, are
 * declared in model.h). */

/* A straight segment p0 -> p1. */
piece aq_region_seg(aq_vec2 p0, aq_vec2 p1);

/* The offset v of curve c of the centre line s from parameter u0 to u1. */
piece aq_region_curve(const aq_centre *s, int c, double v, double u0, double u1);

/* Mass properties of the loop pc[0..n) at density rho and depth d; *area
 * the signed area (> 0 counter-clockwise). */
aq_mass aq_region_mass(const aq_centre *s, const gsl_integration_glfixed_table *gl,
                       const piece *pc, size_t n, double rho_d, double *area);

/* Point t in [0, 1] of a piece. */
aq_vec2 aq_region_at(const aq_centre *s, const piece *pc, double t);

/* The parts of the closed loop in[0..n) below y = level (Sutherland-
 * Hodgman against one half-plane): each piece cut where it crosses the
 * level (a curve sampled CROSS_SAMPLES times, each change bisected to
 * round-off), the parts below kept in order, consecutive parts joined by a
 * segment along the level.  Writes at most n (CROSS_SAMPLES + 2) pieces. */
size_t aq_region_cut_below(const aq_centre *s, const piece *in, size_t n, double level,
                           piece *out);

/* Sample a loop into pts (each piece from its start; a curve OUTLINE_PTS
 * times). */
size_t aq_region_sample(const aq_centre *s, const piece *pc, size_t n, aq_vec2 *pts);

/* The number of points aq_region_sample writes for the loop pc[0..n). */
size_t aq_region_sample_count(const piece *pc, size_t n);

#endif
