/* arch_impl.h: the arch object's inside, shared by arch.c (building it)
 * and arch_query.c (what it is asked).  Private to src/arch. */
#ifndef AQ_ARCH_ARCH_IMPL_H
#define AQ_ARCH_ARCH_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "arch.h"
#include "demand.h"
#include "model.h"

struct aq_arch {
  char *name;
  char *text;
  aq_arch_dynamics dyn;
  aq_geom geom;
  aq_hinge_set hs[2];
  int searched;
  aq_workpath *wp[2];
  aq_hinge_set min_hs;  /* the admissible set of lowest lambda0 (search.c) */
  double min_lambda0;
  aq_search_info min_info; /* programs solved, a lower lift-off mechanism */
  int min_known;        /* 0: the search found no admissible set (the file's [hinges] is used) */
  aq_hinge_control control; /* fixed, or free: each direction's own minimum */
  double friction;      /* Coulomb coefficient of every joint; 0: none */
  aq_statics *statics;  /* the statics with friction (friction.c) */
  double e_n, spread_m; /* the block model's restitution and spread of the supports */
  double abutment_m;    /* the block model's supports' faces beyond the springings */
  char *data[2];        /* a joints arch's joints and faces files as read (or NULL) */
  size_t ndata[2];
  /* aq_arch_drawing's arrays (drawing_make) */
  double *d_joints, *d_parts, *d_outline, *d_fill, *d_mass;
  int64_t *d_ostart, *d_fstart;
  /* the joints' demand tables (demand.h), built on first use */
  aq_demand_table *demand[2];
  int demand_tried[2];
};

#endif
