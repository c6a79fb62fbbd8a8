/* opt.h: checked option values.  Each parser prints one line
 *   archquake: --OPTION: expected ..., got "..."
 * on stderr, increments *nerr on failure and leaves *out unchanged.  The
 * table of options (opt_table.h) checks each value with them, and a
 * command the combinations with the rest, so that every bad option is
 * reported, not just the first. */
#ifndef AQ_APP_OPT_H
#define AQ_APP_OPT_H

#include <stddef.h>

typedef struct aq_arch aq_arch;

/* A finite number in [lo, hi]. */
void aq_opt_double(const char *opt, const char *arg, double lo, double hi,
                   double *out, int *nerr);
/* A finite number with lo < x (strict) and x <= hi. */
void aq_opt_double_gt(const char *opt, const char *arg, double lo, double hi,
                      double *out, int *nerr);
/* An integer in [lo, hi]. */
void aq_opt_long(const char *opt, const char *arg, long lo, long hi, long *out,
                 int *nerr);
/* A comma-separated list of distinct finite numbers each in (lo, hi] (hi
 * may be INFINITY); *out is malloc'd (caller frees), *n its length. */
void aq_opt_list(const char *opt, const char *arg, double lo, double hi, double **out,
                 size_t *n, int *nerr);
/* The same, each in (lo, hi) when hi_open (hi itself refused). */
void aq_opt_list_range(const char *opt, const char *arg, double lo, double hi, int hi_open,
                       double **out, size_t *n, int *nerr);
/* Options that cannot take effect are refused, never ignored:
 * --ode-rtol given with a --model other than ode (one line, *nerr += 1). */
void aq_opt_ode_rtol(int given, const char *model, int *nerr);
/* --cor given for an arch whose [dynamics] impact (or --impact) is
 * momentum: one line naming the arch file; returns 1 (refuse, exit 2). */
int aq_opt_cor_momentum(const char *arch_path, int cor_given, int momentum);
/* The block model needs a friction: 1 (after one line naming the arch
 * file) when blocks is set and the arch has none (friction NAN), else 0. */
int aq_opt_blocks_friction(const char *arch_path, int blocks, double friction);
/* The block model (blocks set) can never span supports spread farther
 * than the arch's voussoirs reach ([supports] spread_m,
 * aq_blocks_check_spread): 1 after one line naming the arch file, the
 * field and the limit, else 0. */
int aq_opt_blocks_spread(const char *arch_path, int blocks, const aq_arch *arch);
/* An arch file's [supports] spread_m (> 0) under a four-hinge model
 * (four_hinge): one warning line, since only the block model spreads the
 * supports; the four-hinge model runs the arch as drawn.  1 if warned. */
int aq_opt_spread_four_hinge(const char *arch_path, int four_hinge, double spread_m);
/* A friction (not NAN) under --model paper (paper): one warning line, since
 * it marks only the runs in which the arch never moves (the statics' demand;
 * paper's fits carry no joint forces once it moves), and none at all for a
 * command whose runs all move (still_runs 0: capacity).  1 if warned. */
int aq_opt_friction_paper(const char *arch_path, int paper, double friction, int still_runs);
/* --polarity's words, indexed by AQ_POLARITY_*, NULL-terminated: the sign
 * of the records a command runs (the record as read, negated, or each
 * record both ways, each row saying which). */
enum { AQ_POLARITY_NORMAL = 0, AQ_POLARITY_REVERSED, AQ_POLARITY_BOTH,
       AQ_POLARITY_AUTO /* not given: aq_opt_polarity_resolve decides */ };
extern const char *const aq_opt_polarity_names[];
/* The polarity a command runs: pol as given, or (AQ_POLARITY_AUTO, the
 * default) both, unless every arch answers a record and its negation alike
 * (arch.h aq_arch_one_polarity: free hinges, mirror-symmetric), or every
 * subject is a ground motion (all_motions) run at azimuths az[0..naz-1]
 * each of which has its opposite among them (theta + 180 deg is the
 * negated motion): then normal.  A verdict never rests on the record's
 * sign convention unless the user asks for one polarity. */
int aq_opt_polarity_resolve(int pol, aq_arch *const *arches, size_t n, int all_motions,
                            const double *az, size_t naz);
/* 1 if paths a and b name the same file: the same string, or the same
 * existing file however spelled (device and inode). */
int aq_opt_same_file(const char *a, const char *b);
/* Report (one line each, naming both spellings) every path among paths[0..n)
 * that names the same file as an earlier one; what: "record", "arch file". */
void aq_opt_distinct_files(const char *what, char *const *paths, size_t n, int *nerr);
/* One of the words in choices (NULL-terminated); *out = its index. */
void aq_opt_choice(const char *opt, const char *arg, const char *const *choices,
                   int *out, int *nerr);
/* Report operands (argv[optind_..argc-1]) that a command does not take. */
void aq_opt_no_operands(const char *cmd, int argc, char **argv, int optind_,
                        int *nerr);
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
/* If the word getopt_long just took as an option (argv[optind_after - 1],
 * or the cluster holding optopt_) names an existing file whose name begins
 * with '-', report it once, with the hint to put it after '--' (cmd: the
 * command as typed, "" the main job), and return 1; else 0. */
int aq_opt_dash_file(const char *cmd, char **argv, int optind_after, int optopt_,
                     int *nerr);
/* Report the option getopt_long rejected (argv[optind-1], optopt). */
void aq_opt_unknown(const char *cmd, char **argv, int optind_after, int optopt_,
                    int *nerr);

#endif
