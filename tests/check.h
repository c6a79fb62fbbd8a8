/* check.h: the test harness.  Every tests/test_*.c defines tests with
 * AQ_TEST(name) { ... } and checks with aq_check*; they register themselves
 * and link into one runner (tests/runner.c) whose last line is
 * "N passed, N failed".  A failed check prints file:line and both numbers;
 * passing checks print only with AQ_TEST_VERBOSE set (as gsl_test does).
 *
 * Paths in tests are relative to the repository root (make check runs there).
 * The CLI under test is aq_test_bin() (env AQ_BIN, default build/san/archquake).
 */
#ifndef AQ_TESTS_CHECK_H
#define AQ_TESTS_CHECK_H

#include <stddef.h>

typedef void (*aq_test_fn)(void);
void aq_test_register(const char *name, aq_test_fn fn);

#define AQ_TEST(name)                                                     \
  static void name(void);                                                 \
  __attribute__((constructor)) static void name##_register(void)          \
  {                                                                       \
    aq_test_register(#name, name);                                        \
  }                                                                       \
  static void name(void)

/* Each returns 1 if the check passed. */
int aq_check_(int ok, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
int aq_check_rel_(double got, double want, double rel, const char *file,
                  int line, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));
int aq_check_abs_(double got, double want, double tol, const char *file,
                  int line, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

#define aq_check(cond, ...) aq_check_(!!(cond), __FILE__, __LINE__, __VA_ARGS__)
/* |got - want| <= rel * |want| */
#define aq_check_rel(got, want, rel, ...) \
  aq_check_rel_((got), (want), (rel), __FILE__, __LINE__, __VA_ARGS__)
/* |got - want| <= tol */
#define aq_check_abs(got, want, tol, ...) \
  aq_check_abs_((got), (want), (tol), __FILE__, __LINE__, __VA_ARGS__)

/* Running the CLI: runs `aq_test_bin() args` through /bin/sh with stdin
 * from /dev/null, captures stdout and stderr (each truncated to cap-1 bytes,
 * NUL-terminated; either may be NULL) and returns the exit status (or -1).
 * args is a shell fragment, e.g. "info records/x.AT2". */
const char *aq_test_bin(void);
int aq_test_run(const char *args, char *out, size_t out_cap, char *errbuf,
                size_t err_cap);

/* Running any shell command: cmd through /bin/sh, its stdout and stderr
 * together into out[cap] (NUL-terminated, truncated; out may be NULL to drop
 * them); returns the exit status (or -1). */
int aq_test_sh(const char *cmd, char *out, size_t cap);

/* The bytes of the file at path, NUL-terminated, malloc'd (caller frees);
 * *n (if not NULL) its length.  NULL if it cannot be read. */
char *aq_test_read_file(const char *path, size_t *n);

/* Field k (0-based) of line row (0-based: 0 is a TSV's header, the first
 * line after any comment lines, "# ...") of the text tsv, into buf[n] (""
 * if there is none); returns buf. */
const char *aq_test_tsv_field(const char *tsv, int row, int k, char *buf, size_t n);

/* Lines (newlines) in s. */
size_t aq_test_count_lines(const char *s);

/* Copy the first num/den of the bytes of file from to file to (1, 1: all of
 * it; 1, 3: a truncated copy).  Returns 1 on success. */
int aq_test_copy_prefix(const char *from, const char *to, size_t num, size_t den);

/* Write the file from, with its first occurrence of text a replaced by b
 * (a NULL: unchanged), to dir/name; the path into out.  A missing a fails
 * a check.  Returns 1 on success. */
int aq_test_edited_copy(const char *from, const char *a, const char *b, const char *dir,
                        const char *name, char *out, size_t cap);

/* The names in directory dir that hold part (0 if dir cannot be read). */
int aq_test_count_names(const char *dir, const char *part);

/* 1 if dir/a.tsv and dir/b.tsv are byte-identical (and longer than 500
 * bytes) and the results files dir/a.h5 and dir/b.h5 compare equal with no
 * tolerance (archquake compare --rtol 0 --atol 0). */
int aq_test_same_outputs(const char *dir, const char *a, const char *b);

/* A fresh empty directory for this test under build/tmp (path in buf),
 * removed when the test passes. */
const char *aq_test_tmpdir(char *buf, size_t cap);
/* A fresh empty directory for a fixture that several tests use (made
 * once per runner), kept until the end of the run. */
const char *aq_test_shared_dir(char *buf, size_t cap);
/* A file name in a fresh directory for this test, holding text (path in
 * buf); NULL (and a failed check) if it cannot be written. */
const char *aq_test_tmpfile(char *buf, size_t cap, const char *name, const char *text);

#endif
