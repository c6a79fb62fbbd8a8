/* opt.h: checked option values.  Each parser prints one line
 *   archquake: --OPTION: expected ..., got "..."
 * on stderr, increments *nerr on failure and leaves *out unchanged.
 * Commands use getopt_long with opterr = 0 and aq_opt_unknown() so that
 * every bad option is reported, not just the first. */
#ifndef AQ_APP_OPT_H
#define AQ_APP_OPT_H

#include <stddef.h>

/* A finite number in [lo, hi]. */
void aq_opt_double(const char *opt, const char *arg, double lo, double hi,
                   double *out, int *nerr);
/* A finite number with lo < x (strict) and x <= hi. */
void aq_opt_double_gt(const char *opt, const char *arg, double lo, double hi,
                      double *out, int *nerr);
/* An integer in [lo, hi]. */
void aq_opt_long(const char *opt, const char *arg, long lo, long hi, long *out,
                 int *nerr);
/* A comma-separated list of finite numbers each > lo; *out is malloc'd
 * (caller frees), *n its length. */
void aq_opt_list(const char *opt, const char *arg, double lo, double **out,
                 size_t *n, int *nerr);
/* One of the words in choices (NULL-terminated); *out = its index. */
void aq_opt_choice(const char *opt, const char *arg, const char *const *choices,
                   int *out, int *nerr);
/* --polarity normal|reversed|both: *out = AQ_POLARITY_* bits (both: the
 * record as read and negated, the worse governs). */
enum { AQ_POLARITY_NORMAL = 1, AQ_POLARITY_REVERSED = 2, AQ_POLARITY_BOTH = 3 };
void aq_opt_polarity(const char *arg, int *out, int *nerr);
/* Report operands (argv[optind_..argc-1]) that a command does not take. */
void aq_opt_no_operands(const char *cmd, int argc, char **argv, int optind_,
                        int *nerr);
/* Report a required option that was not given ("--arch FILE"). */
void aq_opt_require(const char *cmd, const char *what, int given, int *nerr);
/* An existing output path that is not a regular file (a device such as
 * /dev/null, a FIFO, a socket) would be replaced when the output's
 * temporary is renamed onto it: report it in one line naming opt and
 * return 1; 0 for a regular file, a directory (reported by the caller), a
 * missing path or NULL. */
int aq_opt_output_special(const char *opt, const char *path);
/* An output path out that names an existing input (one of the nrec
 * records or narch arch files, possibly under another spelling) would
 * destroy it: report it in one line naming opt and return 1; else 0. */
int aq_opt_output_is_input(const char *opt, const char *out, char *const *records,
                           size_t nrec, char *const *arches, size_t narch);
/* Report the option getopt_long rejected (argv[optind-1], optopt). */
void aq_opt_unknown(const char *cmd, char **argv, int optind_after, int optopt_,
                    int *nerr);

#endif
