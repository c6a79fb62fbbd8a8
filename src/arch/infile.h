/* infile.h: what the arch's input files share (infile.c; internal to
 * src/arch): a text file read whole, and a number read from a field.  Used
 * by cfg.c (the .cfg) and joints.c (the joints and faces files).  Nothing
 * here prints; errors go to aq_error. */
#ifndef AQ_ARCH_INFILE_H
#define AQ_ARCH_INFILE_H

#include <stddef.h>

#include "../error.h"

/* The bytes of path, at most max_bytes + 1 of them (so that the caller can
 * tell a file longer than max_bytes), NUL-terminated, into a buffer the
 * caller frees; *len their count.  NULL, with *st and err set (input path)
 * to AQ_EIO ("expected a readable WHAT, got ...": the system's reason, a
 * directory or a read error) or AQ_ENOMEM. */
char *aq_infile_read(const char *path, size_t max_bytes, const char *what, size_t *len,
                     aq_status *st, aq_error *err);

/* 1 and *x if s is a whole finite number (strtod's syntax, nothing after
 * it, no overflow), else 0 and *x untouched. */
int aq_infile_number(const char *s, double *x);

#endif
