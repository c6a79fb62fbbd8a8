/* test_arch_mass_joint.c: a point mass exactly on the joint between two
 * voussoirs (x = 0 on the crown joint of a symmetric arch with an even
 * number of voussoirs, or on a vertical joint of a joints file) may name
 * either voussoir, on every shape; a mass a micrometre beyond a voussoir's
 * vertical strip is refused on its line, naming the strip. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "arch/arch.h"
#include "check.h"

static aq_status load(const char *geom, const char *mass, aq_error *e)
{
  char text[1024];
  snprintf(text, sizeof text, "[arch]\n%sdensity_kg_m3 = 2000\ndepth_m = 1\n[masses]\n%s\n",
           geom, mass);
  aq_arch *a = NULL;
  aq_error_clear(e);
  aq_status st = aq_arch_load_string(text, strlen(text), "arches/m.cfg", &a, e);
  aq_arch_free(a);
  return st;
}

AQ_TEST(arch_mass_on_a_joint_either_voussoir)
{
  gsl_set_error_handler_off();
  static const char *const geoms[] = {
      "radius_m = 5\nthickness_m = 0.6\nembrace_deg = 180\nvoussoirs = 20\n",
      "radius_m = 7.3\nthickness_m = 0.7\nembrace_deg = 131\nvoussoirs = 20\n",
      "shape = pointed\nspan_m = 10\nrise_m = 6\nthickness_m = 0.6\nvoussoirs = 20\n",
      "shape = elliptical\nspan_m = 10\nrise_m = 4\nthickness_m = 0.6\nvoussoirs = 20\n",
      "shape = parabolic\nspan_m = 10\nrise_m = 4\nthickness_m = 0.6\nvoussoirs = 20\n",
      "shape = catenary\nspan_m = 10\nrise_m = 4\nthickness_m = 0.6\nvoussoirs = 20\n",
      /* vertical.csv's joint 6 is at x = 3.6 (1 - 2 (6 - 1)/10) = 0 */
      "shape = joints\njoints_file = vertical.csv\nfaces_file = vertical_faces.csv\n"};
  for (size_t i = 0; i < sizeof geoms / sizeof geoms[0]; i++) {
    int joints = strstr(geoms[i], "joints") != NULL;
    int left = joints ? 6 : 10; /* the voussoir on the -x side of x = 0 */
    char mass[128];
    aq_error e;
    for (int v = left - 1; v <= left; v++) {
      snprintf(mass, sizeof mass, "statue = %d 0 8 450", v);
      aq_status st = load(geoms[i], mass, &e);
      aq_check(st == AQ_OK, "geometry %zu: a mass at x = 0 on voussoir %d: %s", i, v,
               st == AQ_OK ? "taken" : e.message);
    }
    /* a micrometre beyond each strip: refused on the mass's line */
    for (int v = left - 1; v <= left; v++) {
      snprintf(mass, sizeof mass, "statue = %d %s 8 450", v, v == left ? "1e-6" : "-1e-6");
      aq_status st = load(geoms[i], mass, &e);
      long line = 5; /* [arch], the geometry's lines, density, depth, [masses], the mass */
      for (const char *p = geoms[i]; *p; p++)
        line += *p == '\n';
      aq_check(st != AQ_OK && e.line == line &&
                   !strcmp(e.field, "statue") && strstr(e.message, "expected a point on voussoir"),
               "geometry %zu: a mass 1e-6 m beyond voussoir %d's strip refused: %s", i, v,
               st == AQ_OK ? "taken" : e.message);
    }
  }
}
