/* cache_key.c: the libraries and the CPU in a disk cache's key (cache_key.h). */
#define _GNU_SOURCE /* gnu_get_libc_version */
#include "cache_key.h"

#include <glpk.h>
#include <gnu/libc-version.h>
#include <gsl/gsl_version.h>
#include <stdio.h>

#include "../util/cpu.h"

void aq_cache_key_platform(aq_bytes_out *b)
{
  char s[256], cpu[96];
  aq_cpu_simd(cpu, sizeof cpu);
  /* GLPK's version as built: asking the library would load it (the search
   * does only when it runs) */
  snprintf(s, sizeof s, "glibc %s; gsl %s; glpk %d.%d; %s", gnu_get_libc_version(), gsl_version,
           GLP_MAJOR_VERSION, GLP_MINOR_VERSION, cpu);
  aq_bytes_put_str(b, s, 0);
}
