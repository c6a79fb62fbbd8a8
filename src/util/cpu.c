/* cpu.c: the CPU's SIMD sets (cpu.h).
 *
 * glibc's CPU_FEATURE_ACTIVE reads what the dynamic loader found at start,
 * so asking costs nothing.  GCC's __builtin_cpu_supports, used where that
 * header is missing, links libgcc's constructor, which runs CPUID again in
 * every process (about 0.1 ms of each command's start). */
#include "cpu.h"

#include <stdio.h>

#if defined(__x86_64__) && defined(__has_include)
#if __has_include(<sys/platform/x86.h>)
#include <sys/platform/x86.h>
#define AQ_HAS(f) (!!CPU_FEATURE_ACTIVE(f))
#endif
#endif

void aq_cpu_simd(char *buf, size_t n)
{
#if defined(AQ_HAS)
  snprintf(buf, n, "cpu sse2 %d avx %d avx2 %d fma %d avx512f %d", AQ_HAS(SSE2), AQ_HAS(AVX),
           AQ_HAS(AVX2), AQ_HAS(FMA), AQ_HAS(AVX512F));
#elif defined(__x86_64__)
  __builtin_cpu_init();
  snprintf(buf, n, "cpu sse2 %d avx %d avx2 %d fma %d avx512f %d",
           !!__builtin_cpu_supports("sse2"), !!__builtin_cpu_supports("avx"),
           !!__builtin_cpu_supports("avx2"), !!__builtin_cpu_supports("fma"),
           !!__builtin_cpu_supports("avx512f"));
#else
  snprintf(buf, n, "cpu other");
#endif
}
