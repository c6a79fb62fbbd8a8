/* heap.c: the allocator policy of every archquake command (app.h).
 *
 * Each record allocates and frees arrays of 10^4-10^5 doubles (the file's
 * bytes, the samples, the processed series, the step list).  With glibc's
 * defaults, blocks above 128 KiB come from fresh mmaps, and the heap's top is
 * handed back to the kernel whenever more than 128 KiB of it is free: either
 * way the next record takes every page anew, one page fault each (a quarter
 * of a quiet suite's CPU time, and 150 faults per read of a 20 000-row CSV).
 * Blocks up to AQ_HEAP_MMAP_BYTES therefore come from the heap, and the heap
 * keeps up to twice that free.  Only glibc has these knobs; elsewhere the
 * allocator's own policy stands. */
#include <malloc.h>

#include "app.h"

#define AQ_HEAP_MMAP_BYTES (256L << 20)

void aq_app_heap_policy(void)
{
#if defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
  mallopt(M_MMAP_THRESHOLD, (int)AQ_HEAP_MMAP_BYTES);
  mallopt(M_TRIM_THRESHOLD, (int)(2 * AQ_HEAP_MMAP_BYTES));
#endif
}
