/* error.h: archquake status codes and the error record.
 *
 * Library code (io, signal, arch, report) never prints and never exits: it
 * fills an aq_error (input, position, field, message) and returns an
 * aq_status.  Only src/app prints, through aq_error_print().  The caller owns
 * the aq_error; it holds no heap memory.
 */
#ifndef AQ_ERROR_H
#define AQ_ERROR_H

#include <stddef.h>
#include <stdio.h>

/* Codes and their texts are kept in one list (as SUNDIALS does). */
#define AQ_STATUS_LIST(X)                                                  \
  X(AQ_OK, 0, "success")                                                   \
  X(AQ_ENOMEM, 1, "out of memory")                                         \
  X(AQ_EIO, 2, "input/output error")                                       \
  X(AQ_EFORMAT, 3, "malformed input")                                      \
  X(AQ_EUNSUPPORTED, 4, "unsupported format")                              \
  X(AQ_EUNITS, 5, "unknown or non-acceleration units")                     \
  X(AQ_EVALUE, 6, "value out of range")                                    \
  X(AQ_EOPTION, 7, "bad option")                                           \
  X(AQ_EGEOMETRY, 8, "impossible geometry")                                \
  X(AQ_EINADMISSIBLE, 9, "inadmissible mechanism")                         \
  X(AQ_ENUMERIC, 10, "numerical failure")                                  \
  X(AQ_EINTERNAL, 11, "internal error")                                    \
  X(AQ_ELIFTOFF, 12, "the arch leaves the ground (g + vertical acceleration <= 0)")

typedef enum {
#define AQ_X_ENUM(name, code, text) name = code,
  AQ_STATUS_LIST(AQ_X_ENUM)
#undef AQ_X_ENUM
} aq_status;

/* Where and what went wrong.  Unknown parts are empty strings or -1. */
typedef struct {
  aq_status status;
  char input[512];   /* file name (or "" when not about a file) */
  long line;         /* 1-based text line, or -1 */
  long byte_offset;  /* byte offset in a binary file, or -1 */
  char field[96];    /* header word, key, column, option... or "" */
  char message[512]; /* "expected ..., got ..." or a short sentence */
} aq_error;

/* Text of a status code; never NULL. */
const char *aq_strerror(aq_status s);

/* Reset to "no error". */
void aq_error_clear(aq_error *e);

/* Fill e (if not NULL) and return s.  input may be NULL; line and byte_offset
 * may be -1; field may be NULL.  fmt is printf-style and forms the message. */
aq_status aq_error_set(aq_error *e, aq_status s, const char *input, long line,
                       long byte_offset, const char *field, const char *fmt,
                       ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

/* One line, no "archquake: " prefix, no newline:
 *   INPUT:LINE: FIELD: MESSAGE       (text input)
 *   INPUT: FIELD (byte N): MESSAGE   (binary input)
 * Parts that are unknown are left out. */
void aq_error_format(const aq_error *e, char *buf, size_t n);

/* Print "archquake: <formatted>\n" to f. */
void aq_error_print(const aq_error *e, FILE *f);

/* Texts of a fixed size never cut unseen.  A path shown in at most max
 * bytes (max >= 4): the path itself when it fits, else "..." and as much
 * of its end as fits, so the file's name (after the last '/') stays whole
 * when it fits in max - 3 bytes (a name of up to NAME_MAX, 255, in any
 * max >= 258); never half a UTF-8 character.  Written into buf[n], n > max;
 * returns buf. */
const char *aq_path_fit(const char *path, size_t max, char *buf, size_t n);

/* snprintf into buf[n] (n >= 4) that marks a cut: a text that does not fit
 * ends in "..." (never half a UTF-8 character).  Returns 1 if it was cut,
 * else 0. */
int aq_text_fit(char *buf, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
