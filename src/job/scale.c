/* scale.c: the scaling rule and lambda0 (scale.h). */
#include "scale.h"

#include <math.h>

double aq_lambda0(const aq_arch *arch)
{
  double l0 = NAN;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(arch, k);
    if (p && p->admissible && (isnan(l0) || p->lambda0 < l0))
      l0 = p->lambda0;
  }
  return l0;
}

int aq_scale_per_arch(const aq_scale_rule *r)
{
  return !r->factors && r->k_lambda0 > 0;
}

double aq_scale_factor(const aq_scale_rule *r, size_t k, double pga_g)
{
  return r->factors           ? r->factors[k]
         : r->k_lambda0 > 0   ? 1.0 / pga_g
                              : r->to_pga_g / pga_g;
}

double aq_scale_for_arch(const aq_scale_rule *r, double lambda0, double f)
{
  /* lambda0 g: the arch's static collapse acceleration */
  return aq_scale_per_arch(r) ? r->k_lambda0 * lambda0 * f : f;
}

aq_status aq_scale_check_subject(const aq_scale_rule *r, const char *input, double pga_g,
                                 aq_error *err)
{
  if (r->factors || pga_g > 0)
    return AQ_OK;
  return aq_error_set(err, AQ_EVALUE, input, -1, -1,
                      r->k_lambda0 > 0 ? "--scale-to-lambda0" : "--scale-to-pga",
                      "expected a record with PGA > 0 to scale, got PGA %g g", pga_g);
}

aq_status aq_scale_check_arch(const aq_scale_rule *r, const char *arch_path, double lambda0,
                              double f, aq_error *err)
{
  if (!aq_scale_per_arch(r) || f > 0)
    return AQ_OK;
  return aq_error_set(err, AQ_EVALUE, arch_path, -1, -1, "--scale-to-lambda0",
                      "expected an arch with a static collapse multiplier lambda0 > 0, "
                      "got %g", lambda0);
}
