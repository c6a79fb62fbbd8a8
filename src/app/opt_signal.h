/* opt_signal.h: the signal-processing options shared by `archquake info`
 * and the run command:
 *   --detrend mean|linear|none  --taper FRAC  --highpass HZ  --order N
 *   --lowpass HZ  --no-filter  --merge-tol G
 * Values are checked as they are parsed (opt.h style: one line on stderr per
 * bad value, *nerr incremented); aq_opt_signal_check() then checks the
 * combination once all options are in.  Checks that need the record (the
 * Nyquist frequency, the record length) are made by aq_signal_process.
 *
 * Use: append aq_opt_signal_longopts (AQ_OPT_SIGNAL_NOPTS entries, ids in
 * [AQ_OPT_SIGNAL_ID_MIN, AQ_OPT_SIGNAL_ID_MAX]) to the command's own
 * struct option array (aq_opt_signal_append), and in the getopt_long switch
 * pass every id to aq_opt_signal_handle first. */
#ifndef AQ_APP_OPT_SIGNAL_H
#define AQ_APP_OPT_SIGNAL_H

#include <getopt.h>
#include <stddef.h>

#include "../signal/signal.h"

enum {
  AQ_OPT_SIGNAL_ID_MIN = 1100,
  AQ_OPT_DETREND = 1100,
  AQ_OPT_TAPER,
  AQ_OPT_HIGHPASS,
  AQ_OPT_ORDER,
  AQ_OPT_LOWPASS,
  AQ_OPT_NO_FILTER,
  AQ_OPT_MERGE_TOL,
  AQ_OPT_SIGNAL_ID_MAX = 1199
};

#define AQ_OPT_SIGNAL_NOPTS 7
extern const struct option aq_opt_signal_longopts[AQ_OPT_SIGNAL_NOPTS];

/* Usage lines for the options above (each ends in '\n'). */
extern const char aq_opt_signal_usage[];

/* Append the signal options after the last entry of dst (the first whose
 * name is NULL: a command's table is declared larger than its own entries,
 * the rest zero) and terminate it with a {0} entry.  dst has room for its
 * entries + AQ_OPT_SIGNAL_NOPTS + 1. */
void aq_opt_signal_append(struct option *dst);

/* Handle option id with argument arg (getopt's optarg).  Returns 1 if id is
 * one of the signal options (its value stored in *o or *merge_tol_g, or an
 * error printed and *nerr incremented), 0 if it is not (nothing touched).
 * merge_tol_g (g) may be NULL for commands that make no steps. */
int aq_opt_signal_handle(int id, const char *arg, aq_signal_opts *o,
                         double *merge_tol_g, int *nerr);

/* Check the combination (--lowpass above --highpass); prints one line per
 * problem and increments *nerr. */
void aq_opt_signal_check(const aq_signal_opts *o, int *nerr);

#endif
