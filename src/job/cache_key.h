/* cache_key.h: what every disk cache's key holds beyond the executable's
 * build (which the store adds: util/diskcache.h) and the entry's own
 * inputs: the shared libraries that compute an entry and the CPU features
 * they choose their code by.  glibc's libm picks its sin, cos, atan2, exp
 * (FMA or not) by the CPU, and a new glibc or GSL may round differently,
 * so an entry written under other ones is not used.  Used by
 * subject_cache.h and arch_cache.h. */
#ifndef AQ_JOB_CACHE_KEY_H
#define AQ_JOB_CACHE_KEY_H

#include "../util/bytes.h"

/* Put the libraries' versions (glibc, GSL as run; GLPK as built) and the
 * CPU's SIMD sets into b. */
void aq_cache_key_platform(aq_bytes_out *b);

#endif
