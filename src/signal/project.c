/* project.c: in-plane acceleration from two horizontal components (see
 * project.h). */
#include "project.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

#include "../units.h"

#define AQ_DEG_PER_HALF_TURN 180.0
#define AQ_DEG_PER_QUARTER_TURN 90.0
#define AQ_DEG_PER_TURN 360.0

double aq_project_cos_deg(double angle_deg)
{
  double d = fmod(angle_deg, AQ_DEG_PER_TURN); /* exact */
  if (d < 0)
    d += AQ_DEG_PER_TURN;
  if (d >= AQ_DEG_PER_HALF_TURN)
    return -cos((d - AQ_DEG_PER_HALF_TURN) * AQ_DEG_RAD);
  return cos(d * AQ_DEG_RAD);
}

void aq_project_coefs(double theta_deg, const double phi_deg[2], double c[2])
{
  c[0] = aq_project_cos_deg(theta_deg - phi_deg[0]);
  c[1] = aq_project_cos_deg(theta_deg - phi_deg[1]);
}

aq_status aq_project_check_pair(const char *label, const double phi_deg[2],
                                aq_error *err)
{
  for (int j = 0; j < 2; j++)
    if (!isfinite(phi_deg[j]))
      return aq_error_set(err, AQ_EVALUE, label, -1, -1, "azimuth",
                          "expected the azimuth of component H%d from its header "
                          "or --azimuths A1,A2, got none",
                          j + 1);
  double d = fmod(fabs(phi_deg[1] - phi_deg[0]), AQ_DEG_PER_HALF_TURN);
  if (fabs(d - AQ_DEG_PER_QUARTER_TURN) > AQ_PROJECT_ORTHO_TOL_DEG)
    return aq_error_set(err, AQ_EVALUE, label, -1, -1, "azimuth",
                        "expected orthogonal horizontal components (azimuths 90 "
                        "deg apart within %g deg), got %g and %g deg: the "
                        "in-plane projection needs orthogonal components",
                        AQ_PROJECT_ORTHO_TOL_DEG, phi_deg[0], phi_deg[1]);
  return AQ_OK;
}

double aq_project_azimuth_of(const aq_record *rec)
{
  if (isfinite(rec->azimuth_deg))
    return rec->azimuth_deg; /* the header's (PEER angle, SAC CMPAZ, ...) */
  if (strcmp(rec->format, "at2") != 0)
    return NAN; /* the naming rule is PEER's */
  const char *s = rec->name ? rec->name : "";
  size_t n = strlen(s);
  /* the last LLLDDD not followed by another digit */
  double az = NAN;
  for (size_t i = 0; i + 6 <= n; i++) {
    const unsigned char *p = (const unsigned char *)s + i;
    if ((i > 0 && isalpha(p[-1])) || !isalpha(p[0]) || !isalpha(p[1]) ||
        !isalpha(p[2]) || !isdigit(p[3]) || !isdigit(p[4]) || !isdigit(p[5]) ||
        (i + 6 < n && isdigit(p[6])))
      continue;
    int v = (p[3] - '0') * 100 + (p[4] - '0') * 10 + (p[5] - '0');
    if (v <= 360)
      az = v;
  }
  return az;
}

/* The room of the other component's path in a message of 512 bytes. */
#define AQ_PROJECT_PATH_SHOWN 300

aq_status aq_project_check_aligned(const aq_record *const *rec, size_t n,
                                   aq_error *err)
{
  char ap[AQ_PROJECT_PATH_SHOWN + 1]; /* the other file in the message: its name whole */
  for (size_t j = 1; j < n; j++) {
    const aq_record *a = rec[0], *b = rec[j];
    aq_path_fit(a->path, AQ_PROJECT_PATH_SHOWN, ap, sizeof ap);
    if (fabs(b->dt_s - a->dt_s) > AQ_PROJECT_DT_REL_TOL * a->dt_s)
      return aq_error_set(err, AQ_EVALUE, b->path, -1, -1, "dt",
                          "expected the sample interval of %s (%.9g s), got %.9g s",
                          ap, a->dt_s, b->dt_s);
    if (strcmp(a->reference, b->reference) != 0 ||
        fabs(b->begin_s - a->begin_s) > AQ_PROJECT_T0_FRAC_DT * a->dt_s)
      return aq_error_set(err, AQ_EVALUE, b->path, -1, -1, "start time",
                          "expected the start of %s (%s%s%.6f s), got %s%s%.6f s",
                          ap, a->reference, a->reference[0] ? " + " : "",
                          a->begin_s, b->reference, b->reference[0] ? " + " : "",
                          b->begin_s);
  }
  return AQ_OK;
}

size_t aq_project_common_npts(const aq_record *const *rec, size_t n)
{
  size_t m = n ? rec[0]->npts : 0;
  for (size_t j = 1; j < n; j++)
    m = rec[j]->npts < m ? rec[j]->npts : m;
  return m;
}

double aq_project_peak_horizontal(const double *a1, const double *a2, size_t n)
{
  double peak = 0;
  for (size_t i = 0; i < n; i++)
    peak = fmax(peak, hypot(a1[i], a2[i]));
  return peak;
}
