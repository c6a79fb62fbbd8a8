/* stepper_impl.h: the stepper's inside, shared by stepper_setup.c (making
 * and setting up a stepper) and stepper.c (a run).  Private to src/arch. */
#ifndef AQ_ARCH_STEPPER_IMPL_H
#define AQ_ARCH_STEPPER_IMPL_H

#include "demand.h"
#include "eom.h"
#include "leg.h"
#include "paper.h"
#include "stepper.h"

struct aq_stepper {
  const aq_path *path[2];
  aq_model model;
  double cor;
  int momentum;
  double ode_rtol;
  int history;
  int exact;
  double scale; /* the steps' accelerations are multiplied by this */
  double rest_tol;
  double e_ref_j;
  double rest_since_s; /* last run: record time since which at rest at its end, or NAN */
  aq_eom *eom;
  aq_paper *paper;
  aq_taylor *taylor; /* default model (paths with pieces, tables) */
  aq_quad *quad;     /* workpath-quad, and the default's fallback */
  aq_path pv[2];     /* the sets' paths with g replaced by the step's g + a_v */
  /* M(0) of each set for the momentum rule, evaluated at the first impact
   * of a run that needs it (NAN: not yet); M depends on s alone */
  double m0_kgm2[2];
  aq_demand *demand; /* the joints' demand (demand.h), owned; NULL: none */
  int delegated;     /* 1: runs are del's (aq_stepper_alloc_delegate) */
  aq_stepper_delegate del;
};

#endif
