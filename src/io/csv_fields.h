/* csv_fields.h: plain CSV rows four at a time (AVX2), for csv.c.
 *
 * Once each column's shape is learned (number.h: "%.3f" gives "12.345" row
 * after row), four rows are checked and converted together: their fields
 * are found from the shapes and the signs alone, each field's bytes checked
 * against its shape in 256-bit vectors, its mantissa digits gathered by one
 * byte shuffle and summed in vector lanes, and each column's four values
 * come from one vector multiply or divide by an exact power of ten
 * (IEEE-exact per lane, as one mulsd or divsd: the value strtod gives, as
 * aq_number_exact).  It runs only on an x86-64 CPU with AVX2, chosen at run
 * time by aq_io_avx2() (the same AQ_NO_AVX2 switch and test hook);
 * csv.c's one-row reading covers every other CPU, build and row.  Pure
 * function of the bytes and shapes; no allocation; thread-safe. */
#ifndef AQ_IO_CSV_FIELDS_H
#define AQ_IO_CSV_FIELDS_H

#include <stddef.h>

#include "number.h"

#define AQ_CSV_FIELDS_COLS_MAX 4 /* columns the kernel takes */

/* Reads whole groups of four rows from *pp on into dst[i][k..cap) (column i
 * nowhere when dst[i] is NULL) while every row is ncols fields, each an
 * optional sign and then exactly its column's shape shape[i] (learned:
 * len > 0, flags 0), separated by sep (not a blank) and ended by LF or CR
 * LF, with the 17 bytes from each field's start inside [*pp, end), and
 * each value exact by one operation.  Stops before the first group that is
 * anything else, with *pp there, or fewer than four rows to cap.  Returns
 * the new k; one line per row taken.  Call only with ncols <=
 * AQ_CSV_FIELDS_COLS_MAX, every shape learned, and aq_io_avx2() 1. */
size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap);

/* The steps of the times t[0..n) from i0 on (i0 >= 1), four at a time:
 * for each i in [i0, returned), *lo = min(*lo, t[i] - t[i-1]) and *hi =
 * max(*hi, ...) (as d < lo ? d : lo and d > hi ? d : hi), and *off the
 * first such i (if *off is 0) where |t[i] - (t[0] + i est)| > tol, each
 * term the IEEE operations of that formula.  Returns where it stopped
 * (fewer than four steps left); csv.c's loop does the rest.  Call only
 * when aq_io_avx2() is 1. */
size_t aq_csv_steps4(const double *t, size_t n, size_t i0, double est, double tol, double *lo,
                     double *hi, size_t *off);

#endif
