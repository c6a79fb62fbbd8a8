/* opt_dyn.h: the dynamics options shared by the run and capacity commands:
 *   --model workpath|ode|paper|workpath-quad   the dynamic model (default workpath)
 *   --cor C                      kinetic-energy ratio kept at an impact, 0..1
 *                                (default: each arch's own)
 * A command puts AQ_OPT_DYN_LONGOPTS into its getopt_long table, passes every
 * option id to aq_opt_dyn_handle(), and appends AQ_OPT_DYN_USAGE to its usage
 * text.  (--polarity is parsed by aq_opt_polarity in opt.h.) */
#ifndef AQ_APP_OPT_DYN_H
#define AQ_APP_OPT_DYN_H

#include <getopt.h>

#include "../arch/stepper.h"

/* Option ids (the range 1200-1299 belongs to the dynamics options). */
enum { AQ_OPT_DYN_MODEL = 1200, AQ_OPT_DYN_COR = 1201 };

#define AQ_OPT_DYN_LONGOPTS                                  \
  {"model", required_argument, NULL, AQ_OPT_DYN_MODEL},      \
      {"cor", required_argument, NULL, AQ_OPT_DYN_COR}

#define AQ_OPT_DYN_USAGE                                                    \
  "  --model M           workpath (default), ode (reference), paper,\n"    \
  "                      workpath-quad\n"                                  \
  "  --cor C             kinetic-energy ratio kept at an impact, 0..1\n"   \
  "                      (default: each arch's [dynamics] cor)\n"

typedef struct {
  aq_model model; /* --model */
  double cor;     /* --cor, or NAN: each arch's own */
} aq_dyn_opts;

/* The defaults: workpath, each arch's own cor. */
void aq_opt_dyn_default(aq_dyn_opts *o);

/* Handle option id with argument arg: returns 1 if id is a dynamics option
 * (a bad value is reported on stderr as one line and counted in *nerr; o is
 * left unchanged then), 0 if it is not one of them. */
int aq_opt_dyn_handle(int id, const char *arg, aq_dyn_opts *o, int *nerr);

/* The name of a model ("workpath", "ode", "paper", "workpath-quad"). */
const char *aq_opt_dyn_model_name(aq_model m);

#endif
