/* model.h: the rigid-block model behind blocks.h (internal to src/blocks,
 * used by its tests and bench).
 *
 * Bodies (bodies.c): rigid bodies in a chain, each with its mass, centroid
 * and centroidal inertia.  Joint k lies between body k-1 (the ground's +x
 * support for k = 0) on its clockwise side, "A", and body k (the -x
 * support for k = nb) on its counter-clockwise side, "B": an arch has
 * nj = nb + 1 joints (both ends on the ground), a stack of blocks on the
 * ground nj = nb (the top free).  A joint is the straight segment between
 * its intrados end p[0] and its extrados end p[1] in the undeformed
 * configuration; its tangent t0 runs from p[0] to p[1] and its normal
 * n0 = rot90(t0) points from A into B (for an arch: along the centre
 * line, counter-clockwise).  An arch's bodies are its voussoirs (free
 * control), or the voussoirs between consecutive free joints joined into
 * one body each (fixed control: every other joint bonded), the voussoirs
 * outside the free joints being part of the ground.
 *
 * Configuration: body b's centroid (x, y) and rotation theta from the
 * undeformed shape, q[3b..3b+2]; velocity v[3b..3b+2] = (vx, vy, omega).
 * Every coordinate is in the frame of the ground (which moves with the
 * record; the record's acceleration acts as the body force -m a), except
 * that the two supports may move apart (the spread): support k's x offset
 * gx[k] and its x velocity gvx[k] (k = 0: +x support, 1: -x support).
 *
 * Contacts (contact.c): each joint has two contacts, at the intrados and
 * extrados ends of the overlap of its two faces: at each end the corner
 * of either side that lies on the other's face (B's corner against A's
 * face line, or A's corner against B's), with its gap (>= 0 open), its
 * tangential coordinate s (the joint's slip there plus 0 or the width,
 * model.h aq_corner) and the rows of the relative velocity of B's
 * material point at the contact point against A's there, along the
 * bearing face's normal and tangent (exactly the rates of gap and s).
 *
 * Units: SI (m, kg, s, rad, N, N s for impulses).  Nothing here prints. */
#ifndef AQ_BLOCKS_MODEL_H
#define AQ_BLOCKS_MODEL_H

#include <stddef.h>

#include "../arch/model.h"
#include "../error.h"

/* ---- bodies.c ------------------------------------------------------- */

#define AQ_GROUND_P (-1) /* the ground's +x support (joint 0's side A) */
#define AQ_GROUND_M (-2) /* the ground's -x support (joint nb's side B) */

typedef struct {
  double mass_kg;
  double inertia_kgm2; /* centroidal */
  aq_vec2 c0;          /* centroid, undeformed, m */
  size_t v0, v1;       /* an arch's voussoirs [v0, v1) (0, 0: a test body) */
} aq_body;

typedef struct {
  int a, b;           /* bodies on the clockwise and counter-clockwise side (or AQ_GROUND_*) */
  size_t arch_joint;  /* the arch's joint number (a test joint: its index) */
  aq_vec2 p[2];       /* undeformed ends: [0] intrados, [1] extrados, m */
  aq_vec2 t0, n0;     /* unit tangent p[0] -> p[1], unit normal A -> B */
  double width_m;     /* |p[1] - p[0]| */
  double ext_m[2];    /* how far side A's [0] and side B's [1] faces run on
                       * beyond both ends of the joint: 0 for a body, a
                       * support's extent for the ground (INFINITY: the
                       * ground under a stack) */
} aq_bjoint;

typedef struct {
  size_t nb, nj;
  aq_body *body;
  aq_bjoint *joint;
  size_t nvous;       /* an arch's voussoirs (0 for test bodies) */
  int *vous_body;     /* the body of voussoir k, or AQ_GROUND_P/M */
  aq_vec2 *vous_c0;   /* voussoir centroids, undeformed */
  double *vous_m;     /* voussoir masses, kg */
  double g_mps2;
  double mass_kg;     /* of the moving bodies */
  double length_m;    /* a length scale: the largest distance between joint ends */
} aq_bodies;

/* Bodies from explicit data: nb bodies, nj = nb or nb + 1 joints with
 * their ends[k][0] (intrados) and ends[k][1] (extrados), gravity g_mps2.
 * The supports' faces: an arch's (nj = nb + 1) are its springing joints
 * (extent 0); the ground under a stack (nj = nb) runs on without end.
 * AQ_EVALUE/AQ_EGEOMETRY (field named) on bad data; aq_bodies_free. */
aq_status aq_bodies_init(aq_bodies *s, const aq_body *body, size_t nb,
                         const aq_vec2 (*ends)[2], size_t nj, double g_mps2,
                         aq_error *err);
/* An arch's bodies: free joints fj[0..nfree) (strictly increasing, in
 * 0..n; NULL: every joint), the voussoirs between consecutive ones joined
 * into one body (aq_geom_body), those before fj[0] and after
 * fj[nfree-1] part of the supports. */
aq_status aq_bodies_from_arch(aq_bodies *s, const aq_geom *g, const size_t *fj,
                              size_t nfree, double g_mps2, aq_error *err);
void aq_bodies_free(aq_bodies *s);

/* Where the body-fixed point p0 (undeformed coordinates) of body b (or a
 * support) is in configuration q with support offsets gx. */
aq_vec2 aq_bodies_point(const aq_bodies *s, int b, const double *q, const double gx[2],
                        aq_vec2 p0);
/* The faces of the supports run ext_m (>= 0, INFINITY allowed) beyond
 * both ends of the joints they bear (a test's support). */
void aq_bodies_set_support_extent(aq_bodies *s, double ext_m);
/* The undeformed configuration (q[3b] = c0, theta = 0). */
void aq_bodies_rest(const aq_bodies *s, double *q);
/* The bodies' kinetic energy at velocities v, and their potential energy
 * m g y at q (gravity g, the ground still), J. */
double aq_bodies_kinetic_j(const aq_bodies *s, const double *v);
double aq_bodies_potential_j(const aq_bodies *s, const double *q);

/* ---- contact.c ------------------------------------------------------ */

/* A row of a contact velocity: u = ga . v_A + gb . v_B + c (c from the
 * supports' motion; a support's own part is 0). */
typedef struct {
  double ga[3], gb[3];
  double c;
} aq_crow;

typedef struct {
  double gap_m;   /* distance of the contact's corner from the other side's
                   * face line, > 0 open */
  double s_m;     /* k w plus the slip at end k: (B's point - A's point) . t
                   * of the corner's two material points (the same point
                   * undeformed), t the bearing face's tangent; for B's
                   * corner on A's face, its coordinate along A's face from
                   * A's intrados end */
  int on_b;       /* 0: B's corner on A's face; 1: A's corner on B's face */
  aq_crow n, t;   /* normal and tangential velocity rows (B against A,
                   * along the bearing face's normal A -> B and tangent) */
} aq_corner;

/* Contacts [0] (intrados) and [1] (extrados) of joint j at (q, gx): the
 * two ends of its faces' overlap; rows with the supports' x velocities
 * gvx. */
void aq_contact_eval(const aq_bodies *s, size_t j, const double *q, const double gx[2],
                     const double gvx[2], aq_corner c[2]);
/* The length of the overlap of joint j's two faces at slip (contact
 * s_m - k w): <= 0 when they have parted. */
double aq_contact_overlap(const aq_bodies *s, size_t j, double slip_m);
/* The velocity of row r at v (the supports' part included). */
double aq_crow_dot(const aq_bodies *s, size_t j, const aq_crow *r, const double *v);

/* ---- chain.c: the direct solve of a guessed contact state ----------- */

typedef enum {
  AQ_JOINT_OPEN = 0, /* no closed corner */
  AQ_JOINT_HINGE_I,  /* closed at the intrados corner only */
  AQ_JOINT_HINGE_E,  /* closed at the extrados corner only */
  AQ_JOINT_WELD      /* closed at both corners */
} aq_joint_kind;

typedef struct {
  unsigned char kind; /* aq_joint_kind */
  signed char slide;  /* 0 sticking; +1/-1 sliding: the sign of B's velocity along A's tangent */
} aq_jstate;

/* 1 if corner k (0 i, 1 e) of a joint in state st is closed. */
static inline int aq_jstate_closed(aq_jstate st, int k)
{
  return st.kind == AQ_JOINT_WELD || st.kind == (k ? AQ_JOINT_HINGE_E : AQ_JOINT_HINGE_I);
}

/* Rows of a joint: closed corners' normals (intrados first), then, if it
 * sticks, one tangential row (at its first closed corner: a closed
 * joint's two tangential rows are one).  A sliding joint's normal
 * impulses carry the friction -slide mu P_n along the tangent (their
 * columns), so its matrix is not symmetric. */
#define AQ_CHAIN_ROW_N0 0 /* normal at the intrados corner */
#define AQ_CHAIN_ROW_N1 1 /* normal at the extrados corner */
#define AQ_CHAIN_ROW_T 2  /* tangential */

typedef struct aq_chain aq_chain;

aq_chain *aq_chain_alloc(const aq_bodies *s);
void aq_chain_free(aq_chain *c);
/* Assemble the Delassus matrix of the rows of states st (geometry cr,
 * 2 nj corners) block by block along the chain, friction mu; sym != 0
 * takes the columns equal to the rows (sliding as sticking normals only:
 * for projections), and factor it by block elimination from joint 0.
 * Returns 0, or 1 when a pivot vanishes (the rows are redundant: the
 * contact forces are not determined by them); allow_singular != 0 then
 * factors on, leaving those rows' multipliers 0 (least change: for
 * projections). */
int aq_chain_factor(aq_chain *c, const aq_corner *cr, const aq_jstate *st, double mu,
                    int sym, int allow_singular);
/* Rows of the last factorisation, and for row r its joint and kind
 * (AQ_CHAIN_ROW_*). */
size_t aq_chain_nrows(const aq_chain *c);
void aq_chain_row(const aq_chain *c, size_t r, size_t *joint, int *kind);
/* Solve W x = rhs (both nrows long). */
void aq_chain_solve(const aq_chain *c, const double *rhs, double *x);
/* Velocity change dv (3 nb) = M^-1 C^T x of multipliers x. */
void aq_chain_apply(const aq_chain *c, const double *x, double *dv);
/* Row velocity G_r v + (constant) for every row into u (nrows). */
void aq_chain_rows_dot(const aq_chain *c, const double *v, double *u);

/* ---- siconos_lazy.c: the frictional contact problem (Siconos) -------- */

/* Open Siconos Numerics (once per process): AQ_OK or AQ_EUNSUPPORTED with
 * err naming the library. */
aq_status aq_siconos_load(aq_error *err);

typedef enum {
  AQ_FC2D_LEMKE = 0, /* lexicographic Lemke on the problem's LCP (exact, pivoting) */
  AQ_FC2D_NSGS,      /* non-smooth Gauss-Seidel to a tolerance */
  AQ_FC2D_ENUM,      /* enumeration of the LCP's cases (small problems) */
  AQ_FC2D_AP         /* Lemke's method on Anitescu and Potra's LCP of the problem */
} aq_fc2d_solver;

typedef struct aq_fc2d aq_fc2d;
aq_fc2d *aq_fc2d_alloc(void);
void aq_fc2d_free(aq_fc2d *w);
/* Solve u = W r + q, 0 <= r_n perp u_n >= 0, Coulomb |r_t| <= mu r_n
 * (2-D, nc contacts; W column-major 2nc x 2nc, each contact's normal
 * then tangential component), r warm-started from r's content.  Returns
 * the solver's info (0: converged), or -1 when the library stopped with a
 * fatal error.  *iters (if not NULL): its iterations (pivots). */
int aq_fc2d_solve(aq_fc2d *w, aq_fc2d_solver solver, int nc, const double *W,
                  const double *q, const double *mu, double tol, double *r, double *u,
                  int *iters);

/* ---- statics.c: the loads under which the arch stands --------------- */

/* Of the horizontal body force r m g_eff and the weight m g_eff on every
 * body, the range r_min <= r <= r_max for which contact forces at the
 * closed corners (closed[k] != 0, 2 nj) balance every body with
 * |T| <= mu N (the static theorem, a linear program, GLPK).  Returns 1
 * and the range, 0 when no r is possible, -1 when GLPK failed (err). */
int aq_statics_range(const aq_bodies *s, const aq_corner *cr, const unsigned char *closed,
                     double mu, double *r_min, double *r_max, aq_error *err);


/* ---- moreau.c: one Moreau-Jean step --------------------------------- */

/* How a step's contact problem was solved. */
typedef enum {
  AQ_STEP_DIRECT = 0, /* the chain, state of the step before (or corrected) */
  AQ_STEP_SICONOS     /* Siconos (then the chain with its state, when it applies) */
} aq_step_path;

typedef struct {
  aq_step_path path;
  int iters;          /* chain solves */
  int pivots;         /* Siconos's pivots or sweeps */
  int loose;          /* 1: Siconos's best answer met only LOOSE_REL (moreau_solve.c) */
  int impact;         /* 1: a contact closed with an approach velocity */
  int stage;          /* the global law's impact stages taken (a sequence) */
  double friction_j;  /* the work of friction in the step (<= 0): at the
                       * impact stages exactly, (1 + e_n) u_t . P_t; in the
                       * step at the joints sliding at its start (by their
                       * state, or after an impact stage by their tangential
                       * velocity) or end, P_t times the mean of u_t at its
                       * start and end */
  /* what the energy balance is made of (diagnostics, bench energy) */
  int late_plastic;   /* 1: a corner that approached joined the step late
                       * and landed by the step's plastic law (its impact
                       * stage missed MAX_LATE times) */
  double proj_pe_j;   /* the projection's change of potential energy, J
                       * (gravity g, the ground still) */
  double stick_j;     /* P_t times the mean of u_t at the joints that stick
                       * throughout the step (no work but the scheme's
                       * error; not in friction_j) */
  double stage_err_j; /* the impact stages' change of kinetic energy less
                       * their friction's work (0 to rounding by the law) */
} aq_step_info;

/* The impact law at e_n > 0 (at e_n = 0 both are the plastic law and the
 * step is the same). */
typedef enum {
  AQ_IMPACT_GLOBAL = 0, /* the default: at a step where a corner lands, the
                         * plastic impact P_p of every active corner from the
                         * velocities before it, without the step's forces,
                         * applied (1 + e_n) times; then the step at e = 0 */
  AQ_IMPACT_NEWTON      /* Newton's law per corner within the step:
                         * u_n+ >= -e_n u_n- (the law before the global one;
                         * kept for comparison) */
} aq_impact_law;

typedef struct aq_moreau aq_moreau;

/* A stepper over s (not owned; it outlives the stepper), at rest in the
 * undeformed configuration with every joint closed. */
aq_moreau *aq_moreau_alloc(const aq_bodies *s, aq_error *err);
void aq_moreau_free(aq_moreau *m);
/* Friction mu, restitution e_n, theta (1/2 default); direct 0: every step
 * by Siconos; projection 0: none. */
void aq_moreau_set(aq_moreau *m, double mu, double e_n, double theta, int direct,
                   int projection);
/* The impact law (default AQ_IMPACT_GLOBAL). */
void aq_moreau_set_law(aq_moreau *m, aq_impact_law law);
/* Back to rest, undeformed, supports at gx = 0. */
void aq_moreau_reset(aq_moreau *m);
/* Keep the state (one level) and return to it. */
void aq_moreau_save(aq_moreau *m);
void aq_moreau_restore(aq_moreau *m);
/* One step of h s under the ground acceleration (ax, ay) (m/s^2, y up:
 * body forces -m ax and -m (g + ay)), the supports moving to gx1 by its
 * end; at e_n > 0 under the global law, the impact stages of the corners
 * that land in it first (moreau.c).  AQ_ENUMERIC (err) when a contact
 * problem could not be solved. */
aq_status aq_moreau_step(aq_moreau *m, double h, double ax, double ay, const double gx1[2],
                         aq_step_info *info, aq_error *err);
/* The global law's impact stage alone at the present state (no force,
 * supports still): if an open corner lands within h s with an approach
 * velocity (info->impact 1), v becomes v_p + e_n (v_p - v) with v_p the
 * plastic impact of the active corners, and info->friction_j the work of
 * friction in it; q and the states are unchanged.  AQ_ENUMERIC (err) when
 * its contact problem could not be solved. */
aq_status aq_moreau_impact(aq_moreau *m, double h, aq_step_info *info, aq_error *err);
/* Set the state: q, v (3 nb) and the joints' states (nj), copied. */
void aq_moreau_set_state(aq_moreau *m, const double *q, const double *v, const aq_jstate *st);
/* The state (owned by m): q, v (3 nb each), the supports' offsets gx[2]
 * and velocities gvx[2], the joints' contact states (nj) and corners at q
 * (2 nj, after the last step). */
double *aq_moreau_q(aq_moreau *m);
double *aq_moreau_v(aq_moreau *m);
const double *aq_moreau_gx(const aq_moreau *m);
const aq_jstate *aq_moreau_jstate(const aq_moreau *m);
const aq_corner *aq_moreau_corners(aq_moreau *m);
/* The accelerations (3 nb, per unit time) gravity alone would give the
 * bodies from rest in the present configuration with the present closed
 * contacts sticking (the equations of the chain; 0 where they are
 * redundant): the collapse rule's test. */
void aq_moreau_gravity_accel(aq_moreau *m, double *acc);
/* Closed corners count as closed within this gap, m (the activation
 * threshold: a corner enters a step's problem when it was closed in the
 * step before or its gap predicted at the end of the step with its
 * present velocity is at most this). */
double aq_moreau_closed_m(const aq_moreau *m);
/* The corners a step at rest would hold closed (2 nj): closed in the
 * present state or within the threshold. */
void aq_moreau_closed(aq_moreau *m, unsigned char *closed);

#endif
