/* masses.c: the point masses an arch carries (a wall, a statue, a bell):
 * each checked to lie on its voussoir and added to that voussoir's mass
 * properties (see model.h, aq_geom_add_masses).
 */
#include <math.h>

#include "model.h"

/* Point masses: each inside its voussoir's vertical strip (between the
 * lowest and highest x of its outline and fill) and above the arch's
 * lowest point, each to MASS_ON_JOINT_REL of the arch's size: a mass on the
 * joint between two voussoirs (at x = 0 on a crown joint, which the
 * outlines place within round-off of it, on either side) may name either,
 * which carries it. */
#define MASS_ON_JOINT_REL 1e-9
aq_status aq_geom_add_masses(aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  double ylo = HUGE_VAL, size = 0;
  for (size_t i = 0; i < g->outline_start[n]; i++) {
    ylo = fmin(ylo, g->outline[i].y);
    size = fmax(size, fmax(fabs(g->outline[i].x), fabs(g->outline[i].y)));
  }
  double tol = MASS_ON_JOINT_REL * size;
  for (size_t m = 0; m < g->p.nmass; m++) {
    aq_point_mass pm = g->p.mass[m];
    g->mass[m] = pm;
    if (pm.voussoir >= n)
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, pm.name,
                          "expected a voussoir in 0..%zu, got %zu", n - 1, pm.voussoir);
    if (!(pm.mass_kg > 0) || !isfinite(pm.mass_kg))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, pm.name,
                          "expected a mass > 0 kg, got %g", pm.mass_kg);
    size_t k = pm.voussoir;
    double xlo = HUGE_VAL, xhi = -HUGE_VAL;
    for (size_t i = g->outline_start[k]; i < g->outline_start[k + 1]; i++)
      xlo = fmin(xlo, g->outline[i].x), xhi = fmax(xhi, g->outline[i].x);
    for (size_t i = g->fill_start[k]; i < g->fill_start[k + 1]; i++)
      xlo = fmin(xlo, g->fill[i].x), xhi = fmax(xhi, g->fill[i].x);
    if (!(pm.p.x >= xlo - tol && pm.p.x <= xhi + tol && pm.p.y >= ylo - tol) ||
        !isfinite(pm.p.y))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, pm.name,
                          "expected a point on voussoir %zu (x in [%.6g, %.6g] m, above or "
                          "below it; y >= %.6g m, the arch's lowest point), got (%g, %g) m",
                          k, fabs(xlo) < tol ? 0.0 : xlo, fabs(xhi) < tol ? 0.0 : xhi,
                          fabs(ylo) < tol ? 0.0 : ylo, pm.p.x, pm.p.y);
    aq_mass pt = {pm.mass_kg, pm.p, 0};
    g->vous[k] = aq_mass_add(g->vous[k], pt);
    g->point_kg += pm.mass_kg;
  }
  return AQ_OK;
}
