/* cpu.h: the CPU's SIMD sets, for keys of work whose results may depend on
 * them (FFTW's codelets, libm's FMA paths; src/signal/filter.c and
 * src/job/cache_key.c). */
#ifndef AQ_UTIL_CPU_H
#define AQ_UTIL_CPU_H

#include <stddef.h>

/* "cpu sse2 S avx A avx2 A2 fma F avx512f F5" (each 0 or 1: usable, i.e. the
 * CPU has it and the OS enabled it) into buf[n]; "cpu other" off x86-64. */
void aq_cpu_simd(char *buf, size_t n);

#endif
