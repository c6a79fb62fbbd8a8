/* result.c: freeing a run's result (see result.h). */
#include "result.h"

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
}
