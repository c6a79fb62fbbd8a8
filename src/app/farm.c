/* farm.c: the farm set by archquake-mpi (farm.h). */
#include "farm.h"

static const aq_farm *farm_hook;

void aq_farm_set(const aq_farm *f)
{
  farm_hook = f;
}

const aq_farm *aq_farm_get(void)
{
  return farm_hook;
}

int aq_farm_is_follower(void)
{
  return farm_hook && farm_hook->follower;
}
