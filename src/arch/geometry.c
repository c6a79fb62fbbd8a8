/* geometry.c: voussoirs as exact annular sectors (see model.h).
 *
 * For the sector r_i <= r <= r_e, |theta - theta_m| <= a (half-angle a),
 * density rho and depth d:
 *   mass      m   = rho d a (r_e^2 - r_i^2)
 *   centroid  r_c = (2/3) (r_e^3 - r_i^3) / (r_e^2 - r_i^2) * sin(a) / a
 *             on the ray theta_m
 *   polar moment about the circle's centre  J_O = rho d a (r_e^4 - r_i^4) / 2
 *   centroidal inertia I = J_O - m r_c^2  (parallel axes).
 * Geometry conventions as in the KCLC (Stockdale et al. 2018, SoftwareX;
 * docs/method.md sec. 10).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "model.h"

aq_mass aq_sector_mass(double r_i, double r_e, double th0, double th1,
                       double rho, double depth)
{
  double a = 0.5 * (th1 - th0), tm = 0.5 * (th0 + th1);
  double e2 = r_e * r_e, i2 = r_i * r_i;
  double m = rho * depth * a * (e2 - i2);
  /* (r_e^3 - r_i^3)/(r_e^2 - r_i^2) without cancellation */
  double ratio = (e2 + r_e * r_i + i2) / (r_e + r_i);
  double sinc = a > 1e-4 ? sin(a) / a : 1.0 - a * a / 6.0 + a * a * a * a / 120.0;
  double rc = 2.0 / 3.0 * ratio * sinc;
  double jo = 0.5 * rho * depth * a * (e2 * e2 - i2 * i2);
  aq_mass s;
  s.mass_kg = m;
  s.c.x = rc * cos(tm);
  s.c.y = rc * sin(tm);
  s.inertia_kgm2 = jo - m * rc * rc;
  return s;
}

void aq_geom_free(aq_geom *g)
{
  if (!g)
    return;
  free(g->theta_rad);
  free(g->vous);
  free(g->cum_m);
  free(g->cum_mx);
  free(g->cum_my);
  memset(g, 0, sizeof *g);
}

aq_status aq_geom_init(aq_geom *g, const aq_arch_params *p, aq_error *err)
{
  memset(g, 0, sizeof *g);
  if (!(p->radius_m > 0) || !isfinite(p->radius_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "radius_m",
                        "expected a finite length > 0 m, got %g", p->radius_m);
  if (!(p->thickness_m > 0) || !isfinite(p->thickness_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "thickness_m",
                        "expected a finite length > 0 m, got %g", p->thickness_m);
  if (!(p->thickness_m < 2.0 * p->radius_m))
    return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "thickness_m",
                        "expected less than the diameter 2*radius_m = %g m, got %g",
                        2.0 * p->radius_m, p->thickness_m);
  if (!(p->embrace_rad > 0) || !(p->embrace_rad <= AQ_PI * (1 + 1e-15)))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "embrace_deg",
                        "expected an angle in (0, 180] deg, got %g",
                        p->embrace_rad / AQ_DEG_RAD);
  if (p->voussoirs < 4)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "voussoirs",
                        "expected an integer >= 4, got %zu", p->voussoirs);
  if (!(p->density_kg_m3 > 0) || !isfinite(p->density_kg_m3))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "density_kg_m3",
                        "expected a finite density > 0 kg/m^3, got %g",
                        p->density_kg_m3);
  if (!(p->depth_m > 0) || !isfinite(p->depth_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "depth_m",
                        "expected a finite length > 0 m, got %g", p->depth_m);
  size_t n = p->voussoirs;
  g->p = *p;
  g->r_i_m = p->radius_m - 0.5 * p->thickness_m;
  g->r_e_m = p->radius_m + 0.5 * p->thickness_m;
  g->theta_rad = malloc((n + 1) * sizeof *g->theta_rad);
  g->vous = malloc(n * sizeof *g->vous);
  g->cum_m = malloc((n + 1) * sizeof *g->cum_m);
  g->cum_mx = malloc((n + 1) * sizeof *g->cum_mx);
  g->cum_my = malloc((n + 1) * sizeof *g->cum_my);
  if (!g->theta_rad || !g->vous || !g->cum_m || !g->cum_mx || !g->cum_my) {
    aq_geom_free(g);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  double th_start = 0.5 * AQ_PI - 0.5 * p->embrace_rad;
  for (size_t j = 0; j <= n; j++)
    g->theta_rad[j] = th_start + p->embrace_rad * (double)j / (double)n;
  g->cum_m[0] = g->cum_mx[0] = g->cum_my[0] = 0;
  for (size_t k = 0; k < n; k++) {
    g->vous[k] = aq_sector_mass(g->r_i_m, g->r_e_m, g->theta_rad[k],
                                g->theta_rad[k + 1], p->density_kg_m3, p->depth_m);
    g->cum_m[k + 1] = g->cum_m[k] + g->vous[k].mass_kg;
    g->cum_mx[k + 1] = g->cum_mx[k] + g->vous[k].mass_kg * g->vous[k].c.x;
    g->cum_my[k + 1] = g->cum_my[k] + g->vous[k].mass_kg * g->vous[k].c.y;
  }
  aq_mass all = aq_geom_body(g, 0, n);
  g->mass_kg = all.mass_kg;
  g->c = all.c;
  return AQ_OK;
}

aq_vec2 aq_geom_joint_point(const aq_geom *g, size_t j, char face)
{
  double r = face == 'e' ? g->r_e_m : g->r_i_m;
  aq_vec2 v = {r * cos(g->theta_rad[j]), r * sin(g->theta_rad[j])};
  return v;
}

aq_mass aq_geom_body(const aq_geom *g, size_t j0, size_t j1)
{
  aq_mass b = {0, {0, 0}, 0};
  double sx = 0, sy = 0;
  for (size_t k = j0; k < j1; k++) {
    b.mass_kg += g->vous[k].mass_kg;
    sx += g->vous[k].mass_kg * g->vous[k].c.x;
    sy += g->vous[k].mass_kg * g->vous[k].c.y;
  }
  if (b.mass_kg > 0) {
    b.c.x = sx / b.mass_kg;
    b.c.y = sy / b.mass_kg;
  }
  for (size_t k = j0; k < j1; k++) {
    double dx = g->vous[k].c.x - b.c.x, dy = g->vous[k].c.y - b.c.y;
    b.inertia_kgm2 += g->vous[k].inertia_kgm2 + g->vous[k].mass_kg * (dx * dx + dy * dy);
  }
  return b;
}
