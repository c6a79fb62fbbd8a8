/* path.h: the work path of one hinge set, as the dynamic models see it.
 *
 * This is the contract between the static arch model (arch.c, workpath.c)
 * and the dynamic models (stepper.c, eom.c).  A hinge set is a one-degree-
 * of-freedom mechanism; its coordinate s >= 0 (rad) is the rotation of body
 * 1 about H1 taken positive in the direction that opens every hinge
 * (q = q_sign * s in the arch's global convention).  s = 0 is the undeformed
 * arch.
 *
 * For a constant ground acceleration a_g (m/s^2, along +x) the exact energy
 * balance (docs/method.md sec. 5) from s1 is
 *     KE(s) = KE1 - a_g m_T (x(s) - x(s1)) - g m_T (y(s) - y(s1))
 * where (x, y) is the whole arch's centre of mass measured from its
 * undeformed position, and the kinetic energy is T = 1/2 M(s) sdot^2
 * (docs/method.md sec. 4).  Motion along +s needs a_g * act_sign > lambda0 * g.
 *
 * An aq_path does not own ctx; whoever made it (the arch) outlives it.
 */
#ifndef AQ_ARCH_PATH_H
#define AQ_ARCH_PATH_H

#include <stddef.h>

#define AQ_PATH_MAX_BODIES 3

/* Everything about the mechanism at one position s. */
typedef struct {
  double x_m, y_m;       /* whole-arch centroid displacement from s = 0, m */
  double dx_m, dy_m;     /* d/ds of x_m, y_m, m/rad */
  double d2x_m, d2y_m;   /* d2/ds2 of x_m, y_m, m/rad^2 */
  double mgen_kgm2;      /* generalised mass M(s) = sum m_i |dc_i/ds|^2 + I_i (dphi_i/ds)^2, kg m^2 */
  double dmgen_kgm2;     /* dM/ds, kg m^2/rad */
  double lambda;         /* static multiplier by virtual work, -act_sign * dy_m / dx_m at s (lambda(0) = lambda0) */
  size_t nbody;          /* moving bodies (<= AQ_PATH_MAX_BODIES) */
  struct {
    double mass_kg;      /* body mass */
    double inertia_kgm2; /* centroidal moment of inertia */
    double x_m, y_m;     /* centroid, absolute (arch centre at the origin), m */
    double phi_rad;      /* rotation from the undeformed shape, rad */
    double dx_m, dy_m, dphi; /* d/ds of the three, m/rad, m/rad, rad/rad */
  } body[AQ_PATH_MAX_BODIES];
} aq_path_point;

/* Evaluate the path at s (0 <= s <= s_c_rad).  Returns 0 on success, non-zero
 * when s is outside the admissible range or the linkage does not close.
 * (The arch model clamps an s within 1e-12*s_c_rad outside [0, s_c_rad] to
 * the nearer end; see docs/arch-model.md.) */
typedef int (*aq_path_eval_fn)(const void *ctx, double s, aq_path_point *p);

/* One polynomial piece of the path, for the Taylor leg: on [s_lo, s_hi]
 * dx, dy and m are polynomials of degree deg, x and y of degree deg + 1,
 * in the scaled variable t = (s - s_ref) * iscale, power basis, coefficient
 * k of t^k.  (The arch's pieces are Chebyshev interpolants of the exact
 * kinematics with s_ref = s_lo and iscale = 1 / (s_hi - s_lo), t in [0, 1];
 * a piece may as well be a Taylor polynomial about s_ref = s_lo with
 * iscale = 1.)  dx, dy are fitted to the exact slopes; x, y are their
 * integrals (workpath.c) or fitted apart, agreeing to the fit's error.
 *
 * Optionally (has_g != 0) the pieces of the Taylor leg's acceleration,
 * degree deg in t as well: with R = 1/M, xr = x - x(s_lo), yr = y - y(s_lo),
 *     gc = R' = -M'/M^2,   ga = (xr R)',   gb = (yr R)'   (' = d/ds)
 * so that for a ground acceleration a, gravity g and kinetic energy
 * KE = C - m_T (a xr + g yr) the equation of motion is
 *     s'' = (KE/M)' = C gc - m_T (a ga + g gb)      (docs/method.md sec. 4-5)
 * without a division (leg_taylor.c). */
#define AQ_PIECE_MAX_DEG 20
typedef struct {
  double s_lo, s_hi;   /* rad */
  double s_ref;        /* rad */
  double iscale;       /* 1/rad */
  int deg;             /* of dx, dy, m (x, y: deg + 1); deg < AQ_PIECE_MAX_DEG */
  double x[AQ_PIECE_MAX_DEG + 1], y[AQ_PIECE_MAX_DEG + 1];   /* x_m, y_m: m */
  double dx[AQ_PIECE_MAX_DEG + 1], dy[AQ_PIECE_MAX_DEG + 1]; /* dx_m, dy_m: m/rad */
  double m[AQ_PIECE_MAX_DEG + 1];                            /* mgen_kgm2: kg m^2 */
  int has_g;           /* gc, ga, gb are set */
  double gc[AQ_PIECE_MAX_DEG + 1];                           /* 1/(kg m^2 rad) */
  double ga[AQ_PIECE_MAX_DEG + 1], gb[AQ_PIECE_MAX_DEG + 1]; /* m/(kg m^2 rad) */
} aq_path_piece;

/* The piece holding s: for dir > 0 the one with s_lo <= s < s_hi (the last
 * at s = s_c), for dir <= 0 the one with s_lo < s <= s_hi (the first at
 * s = 0).  0 on success, non-zero outside [0, s_c]. */
typedef int (*aq_path_piece_fn)(const void *ctx, double s, int dir,
                                aq_path_piece *pc);

typedef struct {
  const char *name;          /* "primary" or "reverse" */
  aq_path_eval_fn eval;      /* fast evaluation (tables) */
  aq_path_eval_fn eval_exact;/* exact evaluation (closed-form kinematics) */
  aq_path_piece_fn piece;    /* polynomial pieces for the Taylor leg (NULL: none) */
  const void *ctx;
  double mass_kg;            /* m_T: whole arch (moving and fixed parts), kg */
  double g_mps2;             /* gravity used for this arch, m/s^2 */
  double lambda0;            /* static collapse multiplier at s = 0 */
  double s_c_rad;            /* collapse: unloaded potential energy peaks (lambda = 0), or toggle limit */
  int act_sign;              /* +1 or -1: sign of a_g that drives s forward */
  int q_sign;                /* +1 or -1: q = q_sign * s (global rotation of body 1 about H1) */
  int admissible;            /* 0: the set is not an admissible mechanism; never integrate it */
  /* Impact when the arch returns to s = 0 on the OTHER set and continues on
   * this one: post-impact sdot on this set = impact_vel_ratio * |pre-impact
   * sdot on the other set| by the impulse-momentum balance about this set's
   * hinges (the multi-body Housner rule).  Used with impact = momentum;
   * <= 0 (the arriving motion would close this set's hinges): the arch
   * stops there. */
  double impact_vel_ratio;
  /* |x_m| is non-decreasing in s on [0, x_mono_rad] (by the tables' slopes,
   * sampled; 0 when unknown): the peak displacement up to any s there is
   * |x(s)|. */
  double x_mono_rad;
  /* The measured relative error of the Hermite tables (eval), which the ode
   * and workpath-quad read; at a toggle end they cannot follow the branch
   * point and the error is large (aq_stepper_alloc refuses those models
   * then; the Taylor leg's pieces follow it). */
  double table_err;
} aq_path;

/* The largest table_err the ode and workpath-quad accept (the tables of
 * every admissible set away from a toggle: 1e-12 .. 2e-9). */
#define AQ_PATH_TABLE_ERR_MAX 1e-6

#endif
