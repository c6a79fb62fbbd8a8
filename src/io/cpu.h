/* cpu.h: whether the readers' AVX2 kernels run (at2_fields.c, the AT2
 * reader's four fields a step; csv_fields.c, the CSV reader's four rows a
 * step).  One switch for both: each kernel gives exactly the values of the
 * one-at-a-time reading it stands in for, so the choice changes speed only. */
#ifndef AQ_IO_CPU_H
#define AQ_IO_CPU_H

/* 1 when the AVX2 kernels run: an x86-64 build on a CPU with AVX2, unless
 * the environment sets AQ_NO_AVX2 (to anything but "0") or the test hook
 * below says otherwise. */
int aq_io_avx2(void);

/* Test hook: -1 as the CPU and environment say (the default), 0 never the
 * AVX2 kernels, 1 the AVX2 kernels where the CPU has them.  Set it before
 * any reading thread starts. */
void aq_io_avx2_force_(int mode);

#endif
