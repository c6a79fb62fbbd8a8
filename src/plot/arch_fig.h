/* arch_fig.h: the arch figure's state (arch.c), shared with arch_h5.c,
 * which fills it from a results file; internal to src/plot.  Units: m,
 * rad, s.  The figure borrows the arch and the arrays it points to;
 * aq_plot_arch_render frees thrust and ratio[].
 */
#ifndef AQ_PLOT_ARCH_FIG_H
#define AQ_PLOT_ARCH_FIG_H

#include <stddef.h>

#include "../arch/model.h"
#include "plot.h"

typedef struct {
  const aq_arch *arch;
  const aq_geom *g;
  int set;             /* deformed set, -1: none */
  double s_rad;        /* its rotation, rad (>= 0) */
  aq_mech_state st;    /* deformed four-bar */
  const aq_mech *m;    /* the deformed set's four-bar */
  int thrust_set;      /* the set whose line of thrust is drawn, -1: none */
  double thrust_lambda;/* its multiplier */
  size_t nthrust;      /* points of the line of thrust */
  aq_vec2 *thrust;     /* n + 1 */
  double *ratio[2];    /* each set's friction demand |T|/N per joint at lambda0 (n + 1;
                          NULL: inadmissible set) */
  double ratio_max;    /* the panel's top */
  /* the block model's voussoirs at nat times (none: 0): voussoir k at
   * time i has its centroid at (bx, by)[i * n + k], turned by br[i * n + k] */
  size_t nat;
  const double *at_s, *bx, *by, *br;
  const char *run;     /* the run's key */
  size_t nlegend;      /* legend entries */
  int height;          /* figure height, pixels */
} fig;

/* Draw f (its state set), write its data when asked, free its line of
 * thrust and its friction demands. */
aq_status aq_plot_arch_render(fig *f, const char *target, const char *data, double *draw_s,
                              aq_error *err);

#endif
