/* opt_signal.h: the check between the signal-processing options (--detrend,
 * --taper, --highpass, --order, --lowpass, --no-filter), made once all
 * options are in; each option's own value is checked by its row of the
 * table (opt_table.c).  Checks that need the record (the Nyquist frequency,
 * the record length) are made by aq_signal_process. */
#ifndef AQ_APP_OPT_SIGNAL_H
#define AQ_APP_OPT_SIGNAL_H

#include "../signal/signal.h"

/* Check the combination (--lowpass above --highpass; no filter option
 * with --no-filter); prints one line per problem and increments *nerr. */
void aq_opt_signal_check(const aq_signal_opts *o, int *nerr);

#endif
