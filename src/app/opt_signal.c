/* opt_signal.c: the check between the signal-processing options (see
 * opt_signal.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_signal.h"

#include <stdio.h>

void aq_opt_signal_check(const aq_signal_opts *o, int *nerr)
{
  /* --no-filter turns off the taper, the pads and the filter: options that
   * set them (to other than their defaults) would be ignored, so refuse */
  aq_signal_opts d;
  aq_signal_opts_default(&d);
  if (!o->filter) {
    const char *given[4] = {o->taper_frac != d.taper_frac ? "--taper" : NULL,
                            o->highpass_hz != d.highpass_hz ? "--highpass" : NULL,
                            o->order != d.order ? "--order" : NULL,
                            o->lowpass_hz != d.lowpass_hz ? "--lowpass" : NULL};
    for (int k = 0; k < 4; k++)
      if (given[k]) {
        fprintf(stderr, "archquake: %s: expected no --no-filter with it (--no-filter "
                        "applies no taper, pads or filter), got both\n", given[k]);
        (*nerr)++;
      }
  }
  if (o->filter && o->lowpass_hz > 0 && !(o->lowpass_hz > o->highpass_hz)) {
    fprintf(stderr,
            "archquake: --lowpass: expected a corner above --highpass %g Hz, "
            "got %g Hz\n",
            o->highpass_hz, o->lowpass_hz);
    (*nerr)++;
  }
}
