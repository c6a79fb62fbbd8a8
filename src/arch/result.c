/* result.c: freeing a run's result (see result.h). */
#include "result.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void aq_result_free(aq_result *r)
{
  if (!r)
    return;
  aq_history *h = &r->history;
  free(h->time_s);
  free(h->rotation_rad);
  free(h->displacement_m);
  free(h->kinetic_energy_j);
  free(h->potential_energy_j);
  free(h->set);
  memset(h, 0, sizeof *h);
  if (r->bodies) {
    free(r->bodies->hinges_observed);
    free(r->bodies->hinges_first_s);
    free(r->bodies->hist_x_m);
    free(r->bodies->hist_y_m);
    free(r->bodies->hist_rot_rad);
    free(r->bodies);
    r->bodies = NULL;
  }
}

double aq_result_peak_over_qc(const aq_result *r, const aq_path *primary, const aq_path *reverse)
{
  const aq_path *set[2] = {primary, reverse};
  double over = 0;
  for (int k = 0; k < 2; k++) {
    double q = r->peak_rotation_set_rad[k];
    if (!(q > 0))
      continue;
    if (!set[k] || !set[k]->admissible || !(set[k]->s_c_rad > 0))
      return NAN;
    over = fmax(over, q / set[k]->s_c_rad); /* |q| = s on a set */
  }
  return over;
}

int aq_result_marks(double mu_demand, double thrust_ecc_max, double friction, int free_control)
{
  int slides = !isnan(friction) && mu_demand > friction; /* NAN compares false */
  int beyond = free_control && thrust_ecc_max > 1;
  return (slides ? AQ_MARK_SLIDES : 0) | (beyond ? AQ_MARK_BEYOND : 0);
}

const char *aq_result_marks_name(int marks)
{
  static const char *const name[4] = {"ok", "slides", "beyond", "slides+beyond"};
  return name[marks & 3];
}
