/* moreau_impl.h: the inside of a Moreau-Jean stepper (struct aq_moreau),
 * shared by moreau.c (the step: its problem prepared, the impact stages,
 * the projection) and moreau_solve.c (the step's contact problem solved
 * exactly); internal to src/blocks.  Units: SI.  The arrays of struct
 * aq_moreau are owned by it (aq_moreau_free). */
#ifndef AQ_BLOCKS_MOREAU_IMPL_H
#define AQ_BLOCKS_MOREAU_IMPL_H

#include "model.h"

/* The contact conditions of an accepted solution hold within this fraction
 * of the step's velocity scale (g h + the bodies' free velocities) and of
 * the impulse scale (the moving mass times it). */
static const double CHECK_REL = 1e-9;
/* Siconos's answers are checked within this (Lemke's pivots on the
 * problem's 3 nc LCP lose some digits on an ill-conditioned W). */
static const double SICONOS_CHECK_REL = 1e-7;

struct aq_moreau {
  const aq_bodies *s;
  size_t nb, nj;
  double mu, e_n, theta;
  double e_t;               /* the restitution in the step's own conditions:
                             * e_n under Newton's law, 0 under the global law */
  aq_impact_law law;
  int direct, projection;
  double closed_m;
  double *q, *v, *minv;
  double gx[2], gvx[2];
  aq_jstate *st, *trial;
  aq_corner *cr, *cr1, *cr2; /* at q, at q1 before the projection, after a pass */
  int cr_valid;             /* cr holds the corners at q with gvx */
  double *un0, *ut0;        /* normal and tangential velocities at the step's start */
  double h;                 /* the step */
  unsigned char *active;
  unsigned char *force;     /* corners that land within the step though not
                             * predicted (the global law's impact stage) */
  double *vstart;           /* v at the step's start */
  double *un_pre;           /* the corners' normal velocities at the step's
                             * start, before its impact stages */
  int staged;               /* an impact stage was taken in this step */
  aq_jstate *proj;          /* the projection's states */
  double *vfree, *vnew, *dv, *q1;
  double *rhs, *x, *u;
  double *pn, *pt;          /* per corner impulses of the accepted solution */
  double *keep_v, *keep_pn, *keep_pt; /* Siconos's solution while the chain tries it */
  aq_chain *chain;
  aq_fc2d *fc;
  int *cidx;                /* active corners for Siconos */
  double *W, *fq, *fr, *fu, *fmu, *fd, *best_r;
  double vscale, pscale;
  double *sq, *sv, sgx[2], sgvx[2]; /* a saved state (aq_moreau_save) */
  aq_jstate *sst;
};

/* A joint's state from its closed corners and its slide (0 when open). */
static inline aq_jstate from_closed(int c0, int c1, int slide)
{
  aq_jstate r = {c0 && c1 ? AQ_JOINT_WELD
                 : c0     ? AQ_JOINT_HINGE_I
                 : c1     ? AQ_JOINT_HINGE_E
                          : AQ_JOINT_OPEN,
                 (signed char)slide};
  if (r.kind == AQ_JOINT_OPEN)
    r.slide = 0;
  return r;
}

/* The prepared problem (active corners, free velocities vfree, scales,
 * the guess trial) solved exactly: vnew, pn, pt and the states trial;
 * along the chain from the guess, else by Siconos (moreau_solve.c).
 * AQ_ENUMERIC (err) when no solver meets it. */
aq_status aq_moreau_solve(aq_moreau *m, aq_step_info *info, aq_error *err);

#endif
