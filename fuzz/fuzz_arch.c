/* fuzz_arch.c: libFuzzer harness for the arch-file loader
 * (aq_arch_load_string, the in-memory body of aq_arch_load), run by make
 * fuzz with the shipped arches as seeds.  A loaded arch must have a finite,
 * positive collapse multiplier and collapse rotation on its primary set and
 * a name; a failure must format to one line and leave *out NULL.  Anything
 * else aborts. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  aq_arch *a = (aq_arch *)data; /* must be overwritten with NULL or an arch */
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_arch_load_string((const char *)data, size, "fuzz.cfg", &a, &e);
  if (s == AQ_OK) {
    const aq_path *p = aq_arch_path(a, 0);
    if (!a || !p || !p->admissible || !aq_arch_name(a)[0] ||
        !aq_arch_config_text(a) || !(isfinite(p->lambda0) && p->lambda0 > 0) ||
        !(isfinite(p->s_c_rad) && p->s_c_rad > 0) ||
        !(isfinite(p->mass_kg) && p->mass_kg > 0))
      abort();
    aq_arch_free(a);
  } else {
    char buf[1400];
    aq_error_format(&e, buf, sizeof buf);
    if (a || strchr(buf, '\n') || !buf[0])
      abort();
  }
  return 0;
}
