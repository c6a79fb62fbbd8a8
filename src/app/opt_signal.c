/* opt_signal.c: the signal-processing options (see opt_signal.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_signal.h"

#include <stdio.h>
#include <string.h>

#include "opt.h"

#define AQ_OPT_ORDER_MAX 20  /* Butterworth orders used in practice are 1-8 */
#define AQ_OPT_FREQ_MAX_HZ 1e6

const struct option aq_opt_signal_longopts[AQ_OPT_SIGNAL_NOPTS] = {
    {"detrend", required_argument, NULL, AQ_OPT_DETREND},
    {"taper", required_argument, NULL, AQ_OPT_TAPER},
    {"highpass", required_argument, NULL, AQ_OPT_HIGHPASS},
    {"order", required_argument, NULL, AQ_OPT_ORDER},
    {"lowpass", required_argument, NULL, AQ_OPT_LOWPASS},
    {"no-filter", no_argument, NULL, AQ_OPT_NO_FILTER},
    {"merge-tol", required_argument, NULL, AQ_OPT_MERGE_TOL},
};

const char aq_opt_signal_usage[] =
    "  --detrend D     remove the least-squares line (linear, default), the\n"
    "                  mean (mean) or nothing (none)\n"
    "  --taper FRAC    Hann taper over FRAC of the record at each end, 0-0.5\n"
    "                  (default 0: only the zero pads' junctions are tapered)\n"
    "  --highpass HZ   acausal Butterworth high-pass corner (default 0.03 Hz,\n"
    "                  or 1/duration for a record shorter than 33.3 s)\n"
    "  --order N       Butterworth order, 1-20 (default 4)\n"
    "  --lowpass HZ    acausal Butterworth low-pass corner (default off)\n"
    "  --no-filter     no taper, pads or filter (detrend still applies)\n"
    "  --merge-tol G   merge consecutive samples differing by less than G (g)\n"
    "                  into one constant-acceleration step (default 0: none)\n";

void aq_opt_signal_append(struct option *dst)
{
  size_t at = 0;
  while (dst[at].name)
    at++;
  memcpy(dst + at, aq_opt_signal_longopts, sizeof aq_opt_signal_longopts);
  dst[at + AQ_OPT_SIGNAL_NOPTS] = (struct option){NULL, 0, NULL, 0};
}

int aq_opt_signal_handle(int id, const char *arg, aq_signal_opts *o,
                         double *merge_tol_g, int *nerr)
{
  static const char *const detrends[] = {"mean", "linear", "none", NULL};
  int k;
  long l;
  switch (id) {
  case AQ_OPT_DETREND:
    k = (int)o->detrend;
    aq_opt_choice("--detrend", arg, detrends, &k, nerr);
    o->detrend = (aq_detrend)k;
    return 1;
  case AQ_OPT_TAPER:
    aq_opt_double("--taper", arg, 0, 0.5, &o->taper_frac, nerr);
    return 1;
  case AQ_OPT_HIGHPASS:
    aq_opt_double_gt("--highpass", arg, 0, AQ_OPT_FREQ_MAX_HZ, &o->highpass_hz,
                     nerr);
    o->highpass_auto = 0; /* an explicit corner is checked as given */
    return 1;
  case AQ_OPT_ORDER:
    l = o->order;
    aq_opt_long("--order", arg, 1, AQ_OPT_ORDER_MAX, &l, nerr);
    o->order = (int)l;
    return 1;
  case AQ_OPT_LOWPASS:
    aq_opt_double_gt("--lowpass", arg, 0, AQ_OPT_FREQ_MAX_HZ, &o->lowpass_hz,
                     nerr);
    return 1;
  case AQ_OPT_NO_FILTER:
    o->filter = 0;
    return 1;
  case AQ_OPT_MERGE_TOL: {
    double g = 0;
    int before = *nerr;
    aq_opt_double("--merge-tol", arg, 0, 10, &g, nerr);
    if (*nerr == before && !merge_tol_g) { /* refused, not ignored */
      fprintf(stderr, "archquake: --merge-tol: expected it only where records are "
                      "split into steps (the main job), got it here\n");
      (*nerr)++;
    } else if (*nerr == before) {
      *merge_tol_g = g;
    }
    return 1;
  }
  default:
    return 0;
  }
}

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
