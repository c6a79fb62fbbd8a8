/* at2_fields.h: PEER's fixed AT2 fields four at a time (AVX2), for at2.c.
 *
 * NGA-West2 writes the values five a line in 15-character fields,
 * "   .7273025E-06" or "  -.6521952E-06" (docs/at2-format.md).  The kernel
 * here checks and converts four such fields per step in 256-bit vectors,
 * each value correctly rounded as strtod gives it (m <= 10^7 and |e| <= 22:
 * one IEEE multiply or divide by an exact power of ten, else the field is
 * left to the caller).  It runs only on an x86-64 CPU with AVX2, chosen at
 * run time; at2.c's one-field reading covers every other CPU, build and
 * line (the switch: aq_io_avx2, cpu.h).  Pure functions of the bytes; no
 * allocation; thread-safe. */
#ifndef AQ_IO_AT2_FIELDS_H
#define AQ_IO_AT2_FIELDS_H

#include <stddef.h>

#define AQ_AT2_FIELD_W 15 /* characters of one PEER field */

/* Reads whole groups of four PEER fields from *p on (line *line) into
 * acc[k..npts), while every field of a group has PEER's exact shape
 * (bytes 0-1 blanks, 2 a blank or '-', 3 '.', 4-10 digits, 11 'E' or 'e',
 * 12 '+' or '-', 13-14 digits, 15 a blank, LF or CR: the next field's first
 * blank or a line end), all 16 bytes of each inside [*p, end), and its value
 * is exact by one operation.  One line end may precede each field.  Stops
 * before the first group that is anything else, with *p and *line there
 * (a line end before it not taken), fewer than four values to go, or the
 * end of the bytes near.  Returns the new k.  Call only when
 * aq_io_avx2() is 1. */
size_t aq_at2_fields4(const char **p, const char *end, long *line, double *acc, size_t k,
                      size_t npts);

#endif
