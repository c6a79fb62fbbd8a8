/* cpu.c: the readers' AVX2 switch (cpu.h). */
#include "cpu.h"

#include <stdlib.h>
#include <string.h>

#include "number.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(AQ_NO_SIMD) && AQ_NUMBER_EXACT_OK
#define IO_AVX2 1 /* the kernels are built (at2_fields.c, csv_fields.c) */
#else
#define IO_AVX2 0
#endif

static int forced = -1; /* aq_io_avx2_force_ */

void aq_io_avx2_force_(int mode) { forced = mode; }

int aq_io_avx2(void)
{
#if IO_AVX2
  if (!__builtin_cpu_supports("avx2"))
    return 0;
  if (forced >= 0)
    return forced;
  const char *no = getenv("AQ_NO_AVX2");
  return !no || !*no || strcmp(no, "0") == 0;
#else
  return 0;
#endif
}
