/* kernels.h: a test run with each of the text readers' kernels.  The AT2
 * and CSV readers take AVX2 kernels (at2_fields.c, csv_fields.c) where the
 * CPU has them and a one-at-a-time reading everywhere else; a test declared
 * BOTH_KERNELS(name) with its body in name##_ runs once with each. */
#ifndef AQ_TESTS_KERNELS_H
#define AQ_TESTS_KERNELS_H

#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "io/cpu.h"

#define BOTH_KERNELS(name)                                                                          \
  static void name##_(void);                                                                        \
  AQ_TEST(name)                                                                                     \
  {                                                                                                 \
    for (int avx2 = 1; avx2 >= 0; avx2--) {                                                         \
      aq_io_avx2_force_(avx2);                                                                      \
      if (getenv("AQ_TEST_VERBOSE"))                                                                \
        printf("  " #name ": %s\n", aq_io_avx2() ? "AVX2 kernel" : "one-at-a-time");                \
      name##_();                                                                                    \
    }                                                                                               \
    aq_io_avx2_force_(-1);                                                                          \
  }

#endif
