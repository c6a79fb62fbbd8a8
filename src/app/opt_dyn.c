/* opt_dyn.c: the dynamics options (see opt_dyn.h). */
#include "opt_dyn.h"

#include <math.h>

#include "opt.h"

/* indexed by aq_model */
static const char *const models[] = {"workpath", "ode", "paper", "workpath-quad", NULL};

void aq_opt_dyn_default(aq_dyn_opts *o)
{
  o->model = AQ_MODEL_WORKPATH;
  o->cor = NAN;
}

int aq_opt_dyn_handle(int id, const char *arg, aq_dyn_opts *o, int *nerr)
{
  int m = (int)o->model;
  switch (id) {
  case AQ_OPT_DYN_MODEL:
    aq_opt_choice("--model", arg, models, &m, nerr);
    o->model = (aq_model)m;
    return 1;
  case AQ_OPT_DYN_COR:
    aq_opt_double("--cor", arg, 0, 1, &o->cor, nerr);
    return 1;
  default:
    return 0;
  }
}

const char *aq_opt_dyn_model_name(aq_model m)
{
  return (unsigned)m < sizeof models / sizeof models[0] - 1 ? models[m] : "?";
}
