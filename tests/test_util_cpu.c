/* test_util_cpu.c: the CPU's SIMD sets as the cache keys hold them
 * (util/cpu.h), against GCC's own CPUID reading. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "util/cpu.h"

AQ_TEST(util_cpu_simd_agrees_with_cpuid)
{
  char got[96], want[96];
  aq_cpu_simd(got, sizeof got);
#if defined(__x86_64__)
  __builtin_cpu_init();
  snprintf(want, sizeof want, "cpu sse2 %d avx %d avx2 %d fma %d avx512f %d",
           !!__builtin_cpu_supports("sse2"), !!__builtin_cpu_supports("avx"),
           !!__builtin_cpu_supports("avx2"), !!__builtin_cpu_supports("fma"),
           !!__builtin_cpu_supports("avx512f"));
#else
  snprintf(want, sizeof want, "cpu other");
#endif
  aq_check(strcmp(got, want) == 0, "SIMD sets: \"%s\", CPUID says \"%s\"", got, want);
  /* x86-64 always has SSE2: a reading of all zeros is a broken one */
#if defined(__x86_64__)
  aq_check(strncmp(got, "cpu sse2 1", 10) == 0, "SSE2 on x86-64: %s", got);
#endif
}
