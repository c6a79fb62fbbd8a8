/* test_arch_geometry.c: voussoir and body mass properties against a 2-D
 * Gauss-Legendre quadrature of the annulus (GSL glfixed, written here), the
 * joint layout, and the rigid-body potential-energy check. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

#include "arch/model.h"
#include "check.h"
#include "units.h"

#define QUAD_NODES 40      /* per direction; exact for these smooth integrands to round-off */
#define MASS_REL_TOL 5e-15 /* closed form vs quadrature (measured 1.4e-16) */

/* Moments of rho*d over r_i<=r<=r_e, th0<=th<=th1 by tensor Gauss-Legendre
 * in (r, theta): m, m*x, m*y and the polar moment about the origin. */
static void quad_sector(double ri, double re, double th0, double th1, double rho,
                        double d, double out[4])
{
  gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(QUAD_NODES);
  out[0] = out[1] = out[2] = out[3] = 0;
  for (size_t i = 0; i < QUAD_NODES; i++) {
    double r, wr;
    gsl_integration_glfixed_point(ri, re, i, &r, &wr, t);
    for (size_t j = 0; j < QUAD_NODES; j++) {
      double th, wt;
      gsl_integration_glfixed_point(th0, th1, j, &th, &wt, t);
      double dm = rho * d * r * wr * wt; /* area element r dr dtheta */
      out[0] += dm;
      out[1] += dm * r * cos(th);
      out[2] += dm * r * sin(th);
      out[3] += dm * r * r;
    }
  }
  gsl_integration_glfixed_table_free(t);
}

static void check_against_quad(aq_mass s, const double q[4], const char *what)
{
  double cx = q[1] / q[0], cy = q[2] / q[0];
  double ic = q[3] - q[0] * (cx * cx + cy * cy);
  aq_check_rel(s.mass_kg, q[0], MASS_REL_TOL, "%s mass", what);
  aq_check_rel(s.c.x, cx, MASS_REL_TOL, "%s centroid x", what);
  aq_check_rel(s.c.y, cy, MASS_REL_TOL, "%s centroid y", what);
  aq_check_rel(s.inertia_kgm2, ic, 1e-11, "%s centroidal inertia", what);
}

AQ_TEST(arch_sector_mass_vs_quadrature)
{
  gsl_set_error_handler_off();
  static const double cases[][6] = {
      {3.217, 4.093, 0.3871, 0.5123, 2137.0, 0.811},
      {1.806, 2.1059766, -0.2, 1.9, 1530.0, 0.25},   /* wide, crossing the x axis */
      {0.0413, 9.87, 2.5, 2.5001, 2600.0, 1.7},       /* needle: small-angle series */
      {4.375, 5.625, 1.5707963, 1.7278759, 2000.0, 1.0},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    const double *c = cases[k];
    double q[4];
    quad_sector(c[0], c[1], c[2], c[3], c[4], c[5], q);
    check_against_quad(aq_sector_mass(c[0], c[1], c[2], c[3], c[4], c[5]), q, "sector");
  }
}

AQ_TEST(arch_geometry_joints_and_bodies)
{
  gsl_set_error_handler_off();
  aq_arch_params p = aq_arch_circular(4.137, 0.913, 157.3 * AQ_DEG_RAD, 23, 1873.0, 0.677);
  aq_geom g;
  aq_error e;
  aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "geometry builds");
  double ri = p.radius_m - 0.5 * p.thickness_m, re = p.radius_m + 0.5 * p.thickness_m;
  aq_check_rel(g.theta_rad[0], 0.5 * AQ_PI - 0.5 * p.embrace_rad, 1e-15, "joint 0 angle");
  aq_check_rel(g.theta_rad[23], 0.5 * AQ_PI + 0.5 * p.embrace_rad, 1e-15, "joint n angle");
  aq_check_rel(g.theta_rad[5] - g.theta_rad[4], p.embrace_rad / 23, 1e-15, "equal voussoirs");
  aq_vec2 e7 = aq_geom_joint_point(&g, 7, 'e'), i7 = aq_geom_joint_point(&g, 7, 'i');
  aq_check_rel(hypot(e7.x, e7.y), re, 1e-15, "extrados radius");
  aq_check_rel(hypot(i7.x, i7.y), ri, 1e-15, "intrados radius");
  aq_check(e7.x * i7.y - e7.y * i7.x == 0 || fabs(e7.x * i7.y - e7.y * i7.x) < 1e-14,
           "joints are radial");
  /* a body of voussoirs [3, 11) is the sector between joints 3 and 11 */
  double q[4];
  quad_sector(ri, re, g.theta_rad[3], g.theta_rad[11], p.density_kg_m3, p.depth_m, q);
  check_against_quad(aq_geom_body(&g, 3, 11), q, "body [3,11)");
  quad_sector(ri, re, g.theta_rad[0], g.theta_rad[23], p.density_kg_m3, p.depth_m, q);
  aq_check_rel(g.mass_kg, q[0], MASS_REL_TOL, "whole arch mass");
  aq_check_rel(g.c.y, q[2] / q[0], MASS_REL_TOL, "whole arch centroid height");
  aq_check_abs(g.c.x, 0.0, 2e-15 * p.radius_m, "symmetric arch: centroid on the axis");
  aq_geom_free(&g);
}

/* Ground link ignored: turn the whole arch rigidly by an angle about a point;
 * the potential energy summed voussoir by voussoir must change exactly as
 * m_T g dy of the centroid, the centroid taken from the closed form of the
 * whole annular sector (r_c = 2/3 (re^3-ri^3)/(re^2-ri^2) sin(b/2)/(b/2)). */
AQ_TEST(arch_rigid_body_potential_energy)
{
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, 20, 2000.0, 1.0);
  aq_geom g;
  aq_error e;
  aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "geometry builds");
  double ri = 4.375, re = 5.625, half = 0.5 * p.embrace_rad;
  double rc = 2.0 / 3.0 * (re * re * re - ri * ri * ri) / (re * re - ri * ri) * sin(half) / half;
  double mt = p.density_kg_m3 * p.depth_m * half * (re * re - ri * ri);
  const double gg = 9.80665;
  static const double turns[] = {-0.31, 0.0173, 0.2291, 1.1};
  aq_vec2 piv = {5.625, 0.0}; /* the extrados of the +x springing */
  for (size_t k = 0; k < sizeof turns / sizeof turns[0]; k++) {
    double a = turns[k], ca = cos(a), sa = sin(a);
    double pe = 0;
    for (size_t v = 0; v < 20; v++) {
      double dx = g.vous[v].c.x - piv.x, dy = g.vous[v].c.y - piv.y;
      double y1 = piv.y + sa * dx + ca * dy;
      pe += g.vous[v].mass_kg * gg * (y1 - g.vous[v].c.y);
    }
    double cy1 = piv.y + sa * (0.0 - piv.x) + ca * (rc - piv.y);
    aq_check_rel(pe, mt * gg * (cy1 - rc), 1e-14, "rigid turn %g rad", a);
  }
  aq_geom_free(&g);
}
