/* opt_table_impl.h: what the option table's files share (opt_table.c, the
 * table of options; opt_handlers.c, the options that are more than a value
 * and the checks across options; opt_commands.c, the commands, their help
 * and the defaults).  Private to src/app. */
#ifndef AQ_APP_OPT_TABLE_IMPL_H
#define AQ_APP_OPT_TABLE_IMPL_H

#include <stddef.h>

#include "opt_table.h"

/* The commands an option applies to. */
#define C(x) (1u << AQ_CMD_##x)
#define PLOT_ALL (C(PLOT_HISTORY) | C(PLOT_ARCH) | C(PLOT_DOMAIN) | C(PLOT_SUITE) | C(PLOT_CAPACITY) | \
                  C(PLOT_SPECTRUM))
#define ALL_CMDS ((1u << AQ_CMD_N) - 1)
#define RECORDS (C(RUN) | C(INFO) | C(CAPACITY) | C(SPECTRUM)) /* the commands that read records */
#define SUITES (C(RUN) | C(CAPACITY))            /* ... and run them against arches */
#define READS (RECORDS | C(SELECT)) /* reading and processing: select's pool too */
#define DYNAMICS (SUITES | C(PULSE) | C(DOMAIN))  /* the commands that run the stepper */

/* Where a value goes. */
#define DEST(f) .dest = offsetof(aq_opts, f)
#define DEST_LIST(f, n) .dest = offsetof(aq_opts, f), .dest_n = offsetof(aq_opts, n)
/* A list of options for a rule (.requires, .conflicts, .not_below, .not_above). */
#define OPTS(...) ((const int[]){__VA_ARGS__, -1})

#define AQ_MAX_THREADS 1024
#define AQ_OPT_FREQ_MAX_HZ 1e6
#define AQ_OPT_ORDER_MAX 20 /* Butterworth orders used in practice are 1-8 */
/* Smallest domain --tol, s: a finer bisection of durations of 0.01-100 s
 * would reach the spacing of doubles, where hi - lo stops shrinking. */
#define AQ_DOMAIN_TOL_MIN_S 1e-12
/* compare's defaults: a nightly rerun of the same build reproduces every
 * value exactly; 1e-9 leaves room only for a different compiler or libm. */
#define AQ_COMPARE_RTOL_DEFAULT 1e-9
#define AQ_COMPARE_ATOL_DEFAULT 0.0

/* The handlers (opt_handlers.c): an option's argument into the options,
 * or a check across options once all are parsed; each prints one line and
 * counts an error in *nerr when it refuses. */
void aq_opth_add_arch(char *arg, aq_opts *o, int *nerr);
void aq_opth_one_arch(char *arg, aq_opts *o, int *nerr);
void aq_opth_ignore(char *arg, aq_opts *o, int *nerr);
void aq_opth_units(char *arg, aq_opts *o, int *nerr);
void aq_opth_im_periods(char *arg, aq_opts *o, int *nerr);
void aq_opth_sa_avg(char *arg, aq_opts *o, int *nerr);
void aq_opth_select_periods(char *arg, aq_opts *o, int *nerr);
void aq_opth_scale_range(char *arg, aq_opts *o, int *nerr);
void aq_opth_sampled_peaks_alias(aq_opts *o, int *nerr);
void aq_opth_lowpass_above_highpass(aq_opts *o, int *nerr);
void aq_opth_ode_rtol_needs_ode(aq_opts *o, int *nerr);
void aq_opth_output_names_hdf5(aq_opts *o, int *nerr);
void aq_opth_text_names_text(aq_opts *o, int *nerr);
void aq_opth_fragility_names_text(aq_opts *o, int *nerr);
void aq_opth_blocks_model_applies(aq_opts *o, int *nerr);
void aq_opth_blocks_dt_needs_blocks(aq_opts *o, int *nerr);
void aq_opth_check_not_blocks(aq_opts *o, int *nerr);
void aq_opth_cor_not_blocks(aq_opts *o, int *nerr);
void aq_opth_momentum_takes_no_cor(aq_opts *o, int *nerr);
void aq_opth_orientation(aq_opts *o, int *nerr);
void aq_opth_cache_dir_needs_cache(aq_opts *o, int *nerr);
void aq_opth_cache_max(char *arg, aq_opts *o, int *nerr);
void aq_opth_highpass_given(char *arg, aq_opts *o, int *nerr);

#endif
