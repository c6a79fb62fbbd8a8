/* model.h: the static arch model behind arch.h and path.h (internal to
 * src/arch, used by tests and bench).
 *
 * Geometry (geometry.c, region.c, masses.c, strut.c, shape.c, joints.c):
 * an arch of n voussoirs between n + 1 straight joints, numbered 0..n
 * counter-clockwise from the springing on the +x side; voussoir k lies
 * between joints k and k+1.  A circular arch has equal annular-sector
 * voussoirs with radial joints, the centre of its circle at the origin,
 * joint j at polar angle
 * theta_j = pi/2 - embrace/2 + j*embrace/n (closed forms); pointed,
 * elliptical, parabolic and catenary arches have joints normal to their
 * centre line at equal arc length and faces that are its exact offsets;
 * a joints arch is given joint by joint.  A hinge sits at the extrados end
 * (face 'e') or the intrados end (face 'i') of its joint.
 *
 * Four-bar (kinematics.c): hinges H1..H4 at joints j1 < j2 < j3 < j4; body 1
 * (voussoirs j1..j2-1) turns about H1 by q, body 3 (j3..j4-1) about H4, body
 * 2 (j2..j3-1) rides between; voussoirs outside [j1, j4) are fixed.  q is the
 * global counter-clockwise rotation of body 1 (radians); the closure is by
 * circle intersection on the branch continuous from q = 0 (docs/method.md sec. 1).
 *
 * Equilibrium (kinematics.c): the paper's eq. (3), the 9x9 balance of the
 * three bodies for h1..h4, v1..v4 and the multiplier, in any deformed state.
 *
 * Work path (workpath.c): the aq_path of one hinge set with quintic Hermite
 * tables over s in [0, s_c] (eval, for the ode and workpath-quad;
 * workpath_table.c) and Chebyshev-fitted polynomial pieces (piece, for the
 * Taylor leg; workpath_piece.c).  Search
 * (search.c): the upper-bound mechanism, with GLPK opened on first use
 * (glpk_lazy.c).
 *
 * Units: SI (m, kg, rad, N).  Nothing here prints; errors go to aq_error.
 */
#ifndef AQ_ARCH_MODEL_H
#define AQ_ARCH_MODEL_H

#include <stddef.h>

#include "../error.h"
#include "../util/bytes.h"
#include "arch.h"
#include "path.h"

typedef struct {
  double x, y;
} aq_vec2;

/* ---- shape.c: centre lines ------------------------------------------ */

typedef enum {
  AQ_SHAPE_CIRCULAR = 0, /* radius_m, thickness_m, embrace_deg: exact annular sectors */
  AQ_SHAPE_POINTED,      /* two-centred: span_m, rise_m >= span_m/2, thickness_m */
  AQ_SHAPE_ELLIPTICAL,   /* x = (span/2) cos u, y = rise sin u */
  AQ_SHAPE_PARABOLIC,    /* y = rise (1 - (2x/span)^2) */
  AQ_SHAPE_CATENARY,     /* y = rise - a (cosh(x/a) - 1) */
  AQ_SHAPE_JOINTS,       /* joints (and faces) given point by point */
  AQ_SHAPE_COUNT
} aq_shape;

/* The shape names of the arch file, indexed by aq_shape; NULL after the
 * last (cfg_keys.c's shape = takes them). */
extern const char *const aq_shape_names[AQ_SHAPE_COUNT + 1];

/* A centre line from the springing (span/2, 0) over the crown to
 * (-span/2, 0), on one or two curves (the pointed arch's halves), each with
 * its parameter u increasing that way (shape.c gives each). */
typedef struct {
  aq_shape shape;
  double span, rise, t;  /* m */
  double r, cx;          /* circular, pointed: radius, centre x of curve 0 (m) */
  double a;              /* catenary: y = rise - a (cosh(x/a) - 1), m */
  int ncurve;            /* 1, or 2 (pointed) */
  double u0[2], u1[2];   /* parameter range of each curve */
  double length;         /* centre-line length, m */
} aq_centre;

/* Check span, rise and thickness (the intrados must not fold: t/2 below
 * every radius of curvature; a pointed arch needs rise >= span/2) and set
 * the centre line up.  AQ_EVALUE/AQ_EGEOMETRY with the field. */
aq_status aq_centre_init(aq_centre *s, aq_shape shape, double span_m, double rise_m,
                         double thickness_m, aq_error *err);
/* A circle of radius r from angle u0 to u1 (the circular arch's centre
 * line, for its outlines and its fill). */
void aq_centre_circle(aq_centre *s, double r, double thickness_m, double u0, double u1);
/* C, C', C'' at u on curve. */
void aq_centre_eval(const aq_centre *s, int curve, double u, aq_vec2 d[3]);
/* Signed curvature C' x C'' / |C'|^3 (> 0: turning counter-clockwise). */
double aq_centre_curvature(const aq_centre *s, int curve, double u);
/* The offset C(u) + v N(u), N the unit normal away from the centre of
 * curvature, and (if dp) its derivative d/du = C'(u) (1 + k v). */
void aq_centre_offset(const aq_centre *s, int curve, double u, double v, aq_vec2 *p,
                      aq_vec2 *dp);
/* The n + 1 joints equally spaced in centre-line arc length: u[j] on
 * curve[j] (a pointed arch's crown joint ends curve 0; n must be even
 * there). */
aq_status aq_centre_joints(const aq_centre *s, size_t n, double *u, int *curve,
                           aq_error *err);

/* ---- geometry.c ---------------------------------------------------- */

/* A point mass carried by a voussoir (a wall, a statue, a bell). */
typedef struct {
  char name[64];       /* its key in [masses] */
  size_t voussoir;     /* 0..n-1 */
  aq_vec2 p;           /* position, m */
  double mass_kg;      /* > 0, for the arch's depth */
} aq_point_mass;

typedef struct {
  /* AQ_SHAPE_CIRCULAR (the first six, in this order) */
  double radius_m;      /* centre-line radius */
  double thickness_m;   /* radial thickness (every shape but joints: normal to the centre line) */
  double embrace_rad;   /* angle between the springings, (0, pi] */
  size_t voussoirs;     /* >= 4 (joints: the joints given, less one) */
  double density_kg_m3; /* > 0 */
  double depth_m;       /* out-of-plane depth, > 0 */
  aq_shape shape;       /* 0: circular */
  double span_m, rise_m; /* pointed, elliptical, parabolic, catenary */
  /* AQ_SHAPE_JOINTS: the voussoirs + 1 joints' intrados and extrados ends,
   * counter-clockwise from the springing on the +x side; optional faces
   * ([0] intrados, [1] extrados): voussoir k's points strictly between its
   * joints, in order from joint k, are face_pt[f][face_start[f][k] ..
   * face_start[f][k+1]) (face_start NULL: straight faces).  Not owned;
   * copied by aq_geom_init. */
  const aq_vec2 *joint_i, *joint_e;
  const aq_vec2 *face_pt[2];
  const size_t *face_start[2];
  /* fill over the extrados up to a level (when fill_density_kg_m3 > 0) */
  double fill_level_m;       /* height of its horizontal top above y = 0, m */
  double fill_density_kg_m3;
  /* point masses (not owned; copied) */
  size_t nmass;
  const aq_point_mass *mass;
  /* a geometry as stored in a results file (not NULL: every field above
   * but depth, density and shape is unused; copied) */
  const aq_arch_drawing *stored;
  /* statics: how the hinges are chosen (arch.h; 0: fixed) and the Coulomb
   * friction coefficient of every joint (> 0; 0: none) */
  aq_hinge_control control;
  double friction;
  int friction_table; /* 1: with the table of the least friction over the load */
  /* the block model: the contacts' normal restitution [0, 1] and the
   * supports' spread (m, >= 0) */
  double e_n, spread_m;
  double abutment_m; /* the block model's supports' faces beyond the springings, m (>= 0) */
} aq_arch_params;

/* The parameters of a circular arch (no fill, no point masses). */
static inline aq_arch_params aq_arch_circular(double radius_m, double thickness_m,
                                              double embrace_rad, size_t voussoirs,
                                              double density_kg_m3, double depth_m)
{
  aq_arch_params p = {radius_m, thickness_m, embrace_rad, voussoirs, density_kg_m3, depth_m,
                      AQ_SHAPE_CIRCULAR, 0, 0, NULL, NULL, {NULL, NULL}, {NULL, NULL}, 0, 0,
                      0, NULL, NULL, AQ_CONTROL_FIXED, 0, 0, 0, 0, 0};
  return p;
}

/* Mass properties of one voussoir. */
typedef struct {
  double mass_kg;
  aq_vec2 c;           /* centroid, m */
  double inertia_kgm2; /* centroidal moment of inertia (about the out-of-plane axis) */
} aq_mass;

typedef struct {
  aq_arch_params p;     /* as given; its pointers are not kept (NULL after init) */
  aq_centre centre;     /* the centre line (every shape but joints) */
  double r_i_m, r_e_m;  /* circular: intrados and extrados radii */
  double *theta_rad;    /* circular: n+1 joint angles (NULL for the others) */
  aq_vec2 *ji, *je;     /* n+1 joint ends: intrados, extrados */
  /* joint j's line, for the line of thrust: the point jo[j] + r ju[j]
   * (ju a unit vector from the intrados end towards the extrados end) is
   * the joint's middle at r = jmid[j], its ends at jmid -+ jhalf (circular:
   * jo the circle's centre, jmid the mean radius, jhalf t/2) */
  aq_vec2 *jo, *ju;
  double *jmid, *jhalf;
  aq_mass *vous;        /* n voussoirs, each with its fill and point masses */
  /* outlines for figures and the results file: voussoir k's closed polygon
   * (counter-clockwise, curved faces sampled) is outline[outline_start[k]
   * .. outline_start[k+1]), its fill's fill[fill_start[k] ..
   * fill_start[k+1]) (empty without fill) */
  aq_vec2 *outline, *fill;
  size_t *outline_start, *fill_start;
  aq_point_mass *mass;  /* p.nmass point masses (copied) */
  /* internal: analytic shapes' voussoir k lies on curve vcurve[k], its
   * intrados from u = vu[4k] to vu[4k+1], its extrados from vu[4k+2] to
   * vu[4k+3]; a joints arch's faces (copied from p) */
  int *vcurve;
  double *vu;
  aq_vec2 *face_pt[2];
  size_t *face_start[2];
  double stone_kg, fill_kg, point_kg; /* the masonry, the fill, the point masses */
  double mass_kg;       /* whole arch */
  aq_vec2 c;            /* whole-arch centroid */
  /* prefix sums over voussoirs 0..k-1 (n+1 entries): mass, first moments */
  double *cum_m, *cum_mx, *cum_my;
} aq_geom;

/* Exact mass, centroid and centroidal inertia of the annular sector
 * r_i <= r <= r_e, th0 <= theta <= th1 (radians, th1 > th0), density rho
 * (kg/m^3) and depth (m). */
aq_mass aq_sector_mass(double r_i, double r_e, double th0, double th1,
                       double rho, double depth);

/* The sum of two rigidly joined parts (parallel axes). */
aq_mass aq_mass_add(aq_mass a, aq_mass b);

/* Check the parameters (AQ_EVALUE/AQ_EGEOMETRY with field set, no input or
 * line: a parameter's key, "joints_file", "level_m" or a point mass's name)
 * and fill g; aq_geom_free releases it (accepts a zeroed g). */
aq_status aq_geom_init(aq_geom *g, const aq_arch_params *p, aq_error *err);
void aq_geom_free(aq_geom *g);

/* Point of joint j on face 'e' or 'i'. */
aq_vec2 aq_geom_joint_point(const aq_geom *g, size_t j, char face);

/* Mass properties of voussoirs [j0, j1) as one body: mass, centroid and
 * centroidal inertia (parallel-axis sum). */
aq_mass aq_geom_body(const aq_geom *g, size_t j0, size_t j1);

/* Used by aq_geom_init (masses.c): copy the point masses g->p.mass into
 * g->mass and add each to its voussoir's mass properties, once the
 * outlines and fills are built; AQ_EVALUE or AQ_EGEOMETRY (field: the
 * mass's name) for a mass not on its voussoir. */
aq_status aq_geom_add_masses(aq_geom *g, aq_error *err);

/* The straight strut of an arch: the line y = a + b x that crosses every
 * joint between its ends, the intrados end on or below it and the
 * extrados end on or above it (the side on which a thrust pushing from the
 * +x springing towards the other keeps every joint in compression), with
 * the largest margin, the least vertical distance of an end from the line
 * on its side (strut.c, aq_geom_strut).  A margin > 0: the strut fits
 * inside the arch, and a thrust along it, made as large as needed, carries
 * any load: no four-hinge mechanism opens under any horizontal load. */
typedef struct {
  double a, b;        /* the line y = a + b x: m, m/m */
  double margin_m;    /* > 0: it fits; < 0: the least violation */
  size_t tight_i, tight_e; /* the joints whose intrados end and extrados end are
                              nearest the line (both margin_m from it) */
  aq_vec2 p0, pn;     /* where the line meets joint 0 and joint n */
} aq_strut;
void aq_geom_strut(const aq_geom *g, aq_strut *s);

/* AQ_OK if a horizontal load can open the arch into a four-hinge mechanism
 * as far as its geometry tells (no strut fits, aq_geom_strut); else
 * AQ_EINADMISSIBLE with one line (field "thickness_m", or "joints_file" for
 * a joints arch) giving the strut and, for an arch with a centre line, the
 * rise or thickness a mechanism needs. */
aq_status aq_geom_check_strut(const aq_geom *g, aq_error *err);

/* ---- kinematics.c -------------------------------------------------- */

typedef struct {
  size_t joint[4]; /* j1 < j2 < j3 < j4, each in 0..n */
  char face[4];    /* 'e' or 'i' */
} aq_hinge_set;

/* The four-bar of one hinge set, undeformed. */
typedef struct {
  const aq_geom *g;     /* not owned */
  aq_hinge_set hs;
  aq_vec2 h[4];         /* hinge points */
  aq_mass body[3];      /* the moving bodies */
  double l[3];          /* link lengths |H2-H1|, |H3-H2|, |H4-H3| */
  int branch;           /* +1/-1: side of H2'H4 on which H3' lies */
  int open[4];          /* +1: hinge k opens when (rotation of the body on its
                           counter-clockwise side) - (on its clockwise side)
                           grows ('i'); -1: when it shrinks ('e') */
} aq_mech;

/* The four-bar at one q with derivatives d/dq up to the third. */
typedef struct {
  double q;
  double phi[3][4];  /* phi_b and its 1st..3rd derivatives (phi_1 = q) */
  aq_vec2 h2, h3;    /* deformed H2', H3' */
  aq_vec2 c[3][4];   /* body centroid and its 1st..3rd derivatives */
  double toggle;     /* (H3'-H2') x (H4-H3') / (l23 l34): 0 at the toggle */
} aq_mech_state;

/* Format "0e 6i 12e 19i" (the arch file's syntax) into buf[n]. */
void aq_hinge_set_text(const aq_hinge_set *hs, char *buf, size_t n);

/* Format "0,6,12,19" and "eiei". */
void aq_hinge_set_format(const aq_hinge_set *hs, char *joints, size_t nj,
                         char *faces, size_t nf);

/* Set up the four-bar of hinge set hs on geometry g (joints checked). */
aq_status aq_mech_init(aq_mech *m, const aq_geom *g, const aq_hinge_set *hs,
                       aq_error *err);

/* Evaluate at q (rad, global).  Returns 0, or -1 when the circles do not
 * intersect (past the toggle) or the linkage is at its toggle. */
int aq_mech_eval(const aq_mech *m, double q, aq_mech_state *st);

/* Rotations of the four hinges (counter-clockwise body minus clockwise
 * body, rad) at st; each opens when open[k] * rel[k] > 0. */
void aq_mech_hinge_rel(const aq_mech_state *st, double rel[4]);

/* |loop closure residual| (m) of st: R(q)u1 + R(phi2)u2 + R(phi3)u3 - (H4-H1). */
double aq_mech_closure_residual(const aq_mech *m, const aq_mech_state *st);

/* Loads for the equilibrium solve: dead load is always gravity g on every
 * body; the live load (times the multiplier) is either the horizontal body
 * force -act_sign*m_b*g on every body (AQ_LIVE_HORIZONTAL: lambda is the
 * acceleration multiplier) or a vertical downward unit point load (N) at the
 * body-fixed point `point` (undeformed position) carried by body
 * `point_body` (AQ_LIVE_POINT: lambda is the load in N). */
typedef enum { AQ_LIVE_HORIZONTAL = 0, AQ_LIVE_POINT } aq_live_kind;
typedef struct {
  aq_live_kind kind;
  int act_sign;
  aq_vec2 point;
  int point_body;
  double g_mps2;
} aq_live;

typedef struct {
  double h[4], v[4]; /* hinge reactions (N): force on the counter-clockwise body */
  double lambda;     /* multiplier */
  double normal[4];  /* compressive normal component (N), the smaller of the
                        two faces' normals; > 0 means compressive */
} aq_equil;

/* Solve eq. (3) (9x9, GSL LU) at state st.  AQ_ENUMERIC if singular. */
aq_status aq_mech_equilibrium(const aq_mech *m, const aq_mech_state *st,
                              const aq_live *live, aq_equil *out,
                              aq_error *err);

/* Line of thrust at every joint that is not a hinge (the lower-bound
 * check): the resultant carried across joint j, found from the equilibrium
 * of the voussoirs between j and the nearest hinge on the side of j towards
 * that hinge (the hinge reaction of `eq` plus their dead and live loads,
 * AQ_LIVE_HORIZONTAL only), crosses the joint's line jo + r ju (model.h
 * aq_geom) at r.  Fills ecc[j] = (r - jmid) / jhalf for j = 0..n (a
 * circular arch: (r - R) / (t/2)); |ecc| <= 1: inside the section;
 * hinge joints get their face, +1 or -1) and returns the largest |ecc|;
 * *tension (if not NULL) is set to 1 if some joint's resultant pulls. */
double aq_mech_thrust(const aq_mech *m, const aq_mech_state *st,
                      const aq_live *live, const aq_equil *eq, double *ecc,
                      int *tension);

/* aq_mech_thrust, and (pt, dir not NULL, n+1 each) where the resultant
 * crosses each joint (the hinge itself at a hinge joint) and its
 * direction, in the deformed arch: the line of thrust is the funicular
 * polygon through the crossings, each resultant's line running on to meet
 * the next one's on the voussoir's load line. */
double aq_mech_thrust_line(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                           const aq_equil *eq, double *ecc, int *tension, aq_vec2 *pt,
                           aq_vec2 *dir);

/* The friction each joint needs in the state st: ratio[j] = |T|/N (j =
 * 0..n) of the resultant carried across joint j as aq_mech_thrust finds it
 * (a hinge joint: the hinge reaction of eq; another joint: the hinge
 * reaction plus the loads of the voussoirs between it and that hinge), T
 * along the joint and N normal to it, both with the joint as it lies in
 * st (a hinge joint: the counter-clockwise body's face); INFINITY where
 * the resultant pulls (N <= 0).  Fills ecc as aq_mech_thrust does; returns
 * the largest ratio and its joint in *joint (if not NULL; the lowest such
 * joint).  The Coulomb condition |T| <= mu N holds at every joint exactly
 * when mu >= the return value. */
double aq_mech_friction(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                        const aq_equil *eq, double *ecc, double *ratio, size_t *joint);

/* Velocity field of a set at s = 0 per unit ds: for voussoir k, centroid
 * velocity u[k] (m/rad) and rotation rate w[k] (rad/rad), zero for fixed
 * voussoirs.  q_sign converts d/dq to d/ds. */
void aq_mech_field0(const aq_mech *m, int q_sign, aq_vec2 *u, double *w);

/* sum_k m_k u_a[k].u_b[k] + I_k w_a[k] w_b[k] over n rigid parts. */
double aq_field_dot(const aq_mass *parts, size_t n, const aq_vec2 *u_a,
                    const double *w_a, const aq_vec2 *u_b, const double *w_b);

/* ---- workpath.c ---------------------------------------------------- */

/* Why the path ends at s_c. */
typedef enum { AQ_END_PEAK = 0, AQ_END_TOGGLE, AQ_END_HINGE, AQ_END_NONE } aq_end;

typedef struct aq_workpath aq_workpath;

/* Build the work path of hinge set hs (tables included).  The set is always
 * built; path->admissible says whether it may be used and
 * aq_workpath_reason() why not.  AQ_ENOMEM/AQ_EGEOMETRY on failure. */
aq_status aq_workpath_build(const aq_geom *g, const aq_hinge_set *hs,
                            double g_mps2, const char *name, aq_workpath **out,
                            aq_error *err);
/* aq_workpath_build with at most max_intervals table intervals and as many
 * Taylor pieces (aq_workpath_build: 20000).  A path that needs more is
 * refused, AQ_ENUMERIC on field "hinges", naming the tables or the pieces,
 * their tolerance and where they ran out. */
aq_status aq_workpath_build_max(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                                const char *name, size_t max_intervals, aq_workpath **out,
                                aq_error *err);
void aq_workpath_free(aq_workpath *w);
const aq_path *aq_workpath_path(const aq_workpath *w);
const aq_mech *aq_workpath_mech(const aq_workpath *w);
/* "" if admissible, else a short reason. */
const char *aq_workpath_reason(const aq_workpath *w);
aq_end aq_workpath_end(const aq_workpath *w);
/* Table size (intervals) and its measured max relative error against
 * eval_exact (over x, y, their derivatives, M, dM; relative to each
 * function's max magnitude on [0, s_c]). */
size_t aq_workpath_table_size(const aq_workpath *w);
double aq_workpath_table_error(const aq_workpath *w);
/* The number of the Taylor leg's pieces (path.h aq_path_piece, Chebyshev
 * fits of the exact kinematics, workpath_piece.c). */
size_t aq_workpath_piece_count(const aq_workpath *w);
/* Largest |eccentricity| of the line of thrust over the joints at s = 0
 * (aq_mech_thrust): <= 1 when the thrust stays within the arch, i.e. the
 * set is also statically admissible and lambda0 is the collapse multiplier
 * (upper bound = lower bound); 0 if the set is inadmissible. */
double aq_workpath_thrust0(const aq_workpath *w);
/* Equilibrium (horizontal live load) at s; AQ_EVALUE outside [0, s_c]. */
aq_status aq_workpath_equilibrium(const aq_workpath *w, double s,
                                  aq_equil *out, aq_error *err);
/* Set impact_vel_ratio of b for impacts arriving on a (see path.h). */
void aq_workpath_set_impact(aq_workpath *b, const aq_workpath *a);
/* The built path w as bytes (everything aq_workpath_build and
 * aq_workpath_set_impact computed beyond the four-bar: the path's
 * constants, its end, the tables and the pieces), for the arch's tables
 * kept between processes (arch.c). */
void aq_workpath_put(const aq_workpath *w, aq_bytes_out *b);
/* The path of hs on g from bytes of aq_workpath_put (the four-bar set up
 * again by aq_mech_init, nothing else computed: bit for bit the path
 * built).  AQ_EFORMAT (field name) when the bytes are not such a path. */
aq_status aq_workpath_get(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                          const char *name, aq_bytes_in *r, aq_workpath **out,
                          aq_error *err);

/* ---- lp4.c: linear programs in four free unknowns (GLPK) ------------ */

/* One row G x <= h. */
typedef struct {
  double g[4], h;
} aq_lp4_row;

typedef enum {
  AQ_LP4_OPT,
  AQ_LP4_INFEASIBLE,
  AQ_LP4_UNBOUNDED,
  AQ_LP4_FAILED, /* GLPK failed, or ended with no optimum, or out of memory */
  AQ_LP4_ITLIM   /* the simplex reached its iteration limit (aq_lp4_iteration_limit) */
} aq_lp4_status;

#define AQ_LP4_MAX_TIGHT 12
typedef struct {
  double opt_tol;   /* a row violated by more than this (in the rows' units) at GLPK's
                       floating-point vertex: solved again in rational arithmetic */
  double tight_tol; /* a nonbasic row within this of its bound is a tie (tight) */
  size_t max_tight; /* tight rows reported at most (<= AQ_LP4_MAX_TIGHT) */
  int exact;        /* 1: the vertex always settled in rational arithmetic */
} aq_lp4_opts;

typedef struct {
  double x[4];                     /* the optimal x */
  double obj;                      /* c.x there */
  double *y;                       /* NULL, or n values: the rows' multipliers (the dual's
                                      solution, >= 0; 0 for a row that is not tight),
                                      filled when not NULL */
  size_t tight[AQ_LP4_MAX_TIGHT];  /* the rows of the vertex (the dual's basic columns,
                                      tight[0..nbasic)), then ties */
  size_t ntight, nbasic;
  size_t iterations;               /* simplex iterations used (floating-point and rational) */
} aq_lp4_result;

/* The 2 (n + 1) rows that keep a line of thrust inside the arch g
 * (search.c's comment): row 2j the intrados end of joint j (moment >= 0),
 * row 2j+1 the extrados end (moment <= 0), in the unknowns x = (R0x/W,
 * R0y/W, m0/(W L), lambda): the force and moment the ground exerts across
 * joint 0 (W the arch's weight, L the joints' extent, moments about the
 * middle of their bounding box) and the horizontal body force s lambda g
 * per unit mass; relax: x[3] is sigma instead, and every row is loosened
 * by sigma times its joint's half length, lambda 0.  lp: 2 (n + 1) rows. */
void aq_thrust_rows(const aq_geom *g, int s, int relax, aq_lp4_row *lp);

/* maximize c.x over the rows row[0..n) (ex[i] != 0: row i left out; ex may
 * be NULL), solved through its dual (lp4.c).  AQ_LP4_OPT and *out;
 * AQ_LP4_INFEASIBLE, AQ_LP4_UNBOUNDED, AQ_LP4_ITLIM (the simplex reached
 * aq_lp4_iteration_limit(n) iterations) or AQ_LP4_FAILED (GLPK failed or
 * out of memory).  GLPK must be loaded (aq_glpk_load). */
aq_lp4_status aq_lp4_solve(const aq_lp4_row *row, size_t n, const double c[4],
                           const unsigned char *ex, const aq_lp4_opts *o, aq_lp4_result *out);
/* The simplex iterations a program of n rows is given (each call of GLPK's
 * floating-point and rational simplex): deterministic, growing with n. */
int aq_lp4_iteration_limit(size_t n);
/* For tests only: when > 0, every program's iteration limit is at most
 * this (0, the default: the limit above alone). */
extern size_t aq_lp4_iteration_cap;

/* ---- search.c ------------------------------------------------------ */

/* What the search found besides the set. */
typedef struct {
  size_t programs;       /* linear programs solved */
  int enumerated;        /* 1: a direction's branch and bound ran out and every set was
                            enumerated instead (search.c) */
  /* 1: a mechanism in which joint liftoff_joint lifts off (both its ends
   * open: no four-hinge set does that) has the multiplier liftoff_lambda,
   * lower than the four-hinge minimum, whose lambda0 is then above the
   * arch's (the four-hinge models do not describe the arch; the block
   * model does) */
  int liftoff;
  size_t liftoff_joint;
  double liftoff_lambda;
} aq_search_info;

/* The admissible four-hinge set (every hinge opens, every hinge reaction
 * compressive at s = 0) with the lowest lambda0 over all joints and faces,
 * lambda0 <= 0 included: *best and *lambda0 (if not NULL), found by linear
 * programming (search.c); *info (if not NULL).  A minimum lambda0 <= 0
 * means the arch cannot stand.  AQ_EINADMISSIBLE if no set is found. */
aq_status aq_search_minimum(const aq_geom *g, double g_mps2, aq_hinge_set *best,
                            double *lambda0, aq_search_info *info, aq_error *err);

/* As aq_search_minimum over the sets that ground acceleration of sign
 * act_sign drives (path.h act_sign; -1 or +1) alone: that direction's
 * minimum-lambda0 admissible set.  For an arch that stands (its
 * aq_search_minimum above 0); AQ_EINADMISSIBLE (field "hinges") if that
 * direction has none. */
aq_status aq_search_direction(const aq_geom *g, double g_mps2, int act_sign,
                              aq_hinge_set *best, double *lambda0, aq_search_info *info,
                              aq_error *err);

/* The sign of the ground acceleration that drives hs (path.h act_sign, as
 * aq_workpath_build sets it), or 0 when hs is no mechanism (joints out of
 * range or order, a hinge that does not open). */
int aq_search_act_sign(const aq_geom *g, const aq_hinge_set *hs);

/* ---- friction.c: the static theorem with Coulomb friction ----------- */

/* The friction the set of w needs at each joint in its collapse state (s =
 * 0, lambda = its lambda0): ratio[j] = |T|/N (aq_mech_friction; ratio may
 * be NULL, else n + 1 values); returns the largest and its joint (*joint,
 * if not NULL).  NAN (joint SIZE_MAX) for an inadmissible set. */
double aq_workpath_friction(const aq_workpath *w, double *ratio, size_t *joint);

/* The largest lambda at which a line of thrust lies inside the arch g (at
 * every joint its resultant between the joint's ends) and, when mu > 0 is
 * finite, within every joint's friction cone |T| <= mu N, under gravity
 * and a horizontal body force lambda g along -act_sign x (a ground
 * acceleration lambda g of sign act_sign), into *lambda (below 0 when the
 * arch needs a push the other way to stand with mu).  mu INFINITY or 0:
 * without friction, the minimum multiplier of that direction over every
 * mechanism.  *joint (if not NULL): a joint whose friction is exhausted at
 * the optimum, SIZE_MAX when none is.  AQ_EINADMISSIBLE (field
 * "friction") when no lambda at all lets a line of thrust stand with mu;
 * AQ_EUNSUPPORTED when GLPK cannot be opened.  friction.c. */
aq_status aq_friction_lambda(const aq_geom *g, int act_sign, double mu, double *lambda,
                             size_t *joint, aq_error *err);

/* The least Coulomb coefficient with which a line of thrust lies inside
 * the arch g under gravity and the horizontal body force lambda g along
 * -act_sign x: *mu (INFINITY when no line of thrust lies inside at lambda
 * at all) and *joint (if not NULL) where that line's |T|/N is largest.
 * AQ_ENUMERIC when a program fails (GLPK's error or its iteration limit),
 * and when its method has not settled after its limit of programs: never
 * an unconverged value.  friction.c. */
aq_status aq_friction_least(const aq_geom *g, int act_sign, double lambda, double *mu,
                            size_t *joint, aq_error *err);
/* For tests only: when > 0, aq_friction_least (and the tables) solve at
 * most this many programs at a load, fewer than its own limit (0, the
 * default: that limit, 60). */
extern int aq_friction_least_cap;

/* The arch's statics with friction, built once with the arch (friction.c;
 * read-only after, safe to share between threads): the least friction at
 * rest, and for each direction of ground acceleration (act_sign -1, +1)
 * the largest load without friction and with the arch's, and a table of
 * the least friction over the load (exact at its nodes from 0 to the
 * largest, a cubic Hermite between them, within 1e-6 of the table's
 * largest value at every interval's middle; where the least friction
 * passes 1e3 (AQ_CFG_FRICTION_MAX) below the largest load, as below a
 * lift-off mechanism's, the table ends there, its cubic in 1/mu where
 * both nodes need at least 1, within 1e-6 of max(mu, 1)). */
typedef struct aq_statics aq_statics;

/* Build for g and the friction coefficient of its joints (0: none), with
 * the tables of the least friction over the load when table is 1 (else
 * aq_statics_mu_least and aq_statics_lambda_at give NAN).
 * AQ_EINADMISSIBLE (field "friction") when the arch cannot stand at rest
 * with that friction; errors of the programs as aq_friction_lambda's.
 * Free with aq_statics_free (NULL accepted). */
aq_status aq_statics_build(const aq_geom *g, double friction, int table, aq_statics **out,
                           aq_error *err);
void aq_statics_free(aq_statics *s);
/* As bytes, for the arch's tables kept between processes (arch.c), and
 * back (AQ_EFORMAT when the bytes are not such statics). */
void aq_statics_put(const aq_statics *s, aq_bytes_out *b);
aq_status aq_statics_get(aq_bytes_in *r, size_t voussoirs, aq_statics **out);
/* The least friction with which a line of thrust stands at rest, and the
 * joint (if not NULL) where it is needed. */
double aq_statics_mu_rest(const aq_statics *s, size_t *joint);
/* The largest lambda of direction act_sign at which a line of thrust
 * stands, without friction. */
double aq_statics_lambda_top(const aq_statics *s, int act_sign);
/* ... with the arch's friction (NAN: none given); *joint where it is
 * exhausted (SIZE_MAX: nowhere: the load is lambda_top's). */
double aq_statics_lambda_friction(const aq_statics *s, int act_sign, size_t *joint);
/* The least friction at lambda >= 0 (the table's interpolant; INFINITY
 * above lambda_top, and above the end of a table that ends where the least
 * friction passes 1e3; NAN below 0), *joint the nearest node's joint. */
double aq_statics_mu_least(const aq_statics *s, int act_sign, double lambda, size_t *joint);
/* The nodes of direction act_sign's table (0: none). */
int aq_statics_nodes(const aq_statics *s, int act_sign);
/* 1 if direction act_sign's table met its tolerance at every interval (or
 * has none); 0 if its nodes ran out first (256: the least friction's
 * kinks, where its line of thrust changes the joint faces it touches, can
 * need more): then aq_statics_mu_least is its interpolant, off by more
 * than the tolerance somewhere (the commands that build the table warn:
 * aq_mechanism_warn_minimum). */
int aq_statics_resolved(const aq_statics *s, int act_sign);
/* The largest lambda >= 0 at which a line stands with friction mu, from
 * the table (NAN when none does, not even at rest, and when mu is above
 * the 1e3 where a table ends below lambda_top; lambda_top when mu is at
 * least the last friction of a table that reaches it). */
double aq_statics_lambda_at(const aq_statics *s, int act_sign, double mu);

/* Open GLPK, which the search calls through glpk_lazy.c (once per process;
 * later calls return the first's outcome): AQ_OK, or AQ_EUNSUPPORTED with
 * err naming the library and the loader's reason. */
aq_status aq_glpk_load(aq_error *err);

/* lambda0 and opening test at s = 0 only (cheap; no tables, no equilibrium):
 * returns 1 if every hinge opens at first order and fills *lambda0 (its sign
 * as computed), else 0 (also for joints out of range or order). */
int aq_search_lambda0(const aq_geom *g, const aq_hinge_set *hs,
                       double *lambda0);

/* ---- arch.c (the arch object; cfg.c reads its .cfg) ------------------ */

/* An arch from its geometry as stored in a results file (aq_arch_drawing:
 * joints, the voussoirs' mass properties, outlines, fill, point masses)
 * and its hinge sets: no integration, the stored masses as they are; for
 * drawing a result again without its .cfg.  shape names the shape (for
 * titles); friction: its joints' coefficient (0 or NAN: none).  Errors as
 * aq_arch_build's. */
aq_status aq_arch_from_drawing(const aq_arch_drawing *d, const aq_hinge_set *primary,
                               const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                               double friction, const char *name, aq_arch **out,
                               aq_error *err);

/* Build an arch from parameters (no file): primary NULL runs the search,
 * reverse NULL takes the primary's face swap; with p->control free, the
 * sets are each direction's minimum (arch.h aq_hinge_control; a reverse is
 * refused, AQ_EVALUE field "reverse").  dyn NULL: cor 0, impact cor,
 * standard gravity.  The caller frees with aq_arch_free. */
aq_status aq_arch_build(const aq_arch_params *p, const aq_hinge_set *primary,
                        const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                        const char *name, aq_arch **out, aq_error *err);
/* As aq_arch_build, with kept[0..nkept) (aq_arch_tables_put's bytes of an
 * arch built before, or NULL) taken for the search and the work paths
 * when they are of the hinge sets that primary and reverse ask for: *used
 * (if not NULL) is then 1 and the arch is, bit for bit, the one they were
 * put from, provided p is its parameters (the caller's key: the arch's
 * sources, src/job/arch_cache.h).  Bytes that are not such tables are
 * passed over (*used 0: built). */
aq_status aq_arch_build_kept(const aq_arch_params *p, const aq_hinge_set *primary,
                             const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                             const char *name, const unsigned char *kept, size_t nkept,
                             int *used, aq_arch **out, aq_error *err);
/* What the search and the work paths computed for a, as bytes, for
 * aq_arch_build_kept. */
void aq_arch_tables_put(const aq_arch *a, aq_bytes_out *b);
/* The arch takes text (its .cfg as read, NUL-terminated) and data[f]
 * (a joints arch's joints and faces files as read, ndata[f] bytes, or
 * NULL): aq_arch_config_text and aq_arch_sha256 give them back, and
 * aq_arch_free frees them (cfg.c, after aq_arch_build). */
void aq_arch_keep_sources(aq_arch *a, char *text, char *data[2], const size_t ndata[2]);
const aq_geom *aq_arch_geom(const aq_arch *a);
const aq_workpath *aq_arch_workpath(const aq_arch *a, int set);
/* 1 if the primary came from the search. */
int aq_arch_searched(const aq_arch *a);
/* The hinge set used for set 0 (primary) or 1 (reverse). */
const aq_hinge_set *aq_arch_hinge_set(const aq_arch *a, int set);

/* The admissible set of lowest lambda0 over every joint and face
 * (aq_search_minimum): 1 and *hs, *lambda0 (either may be NULL); 0 when the
 * search found none (the arch then has [hinges]).  An arch whose minimum is <= 0 is never built. */
int aq_arch_minimum(const aq_arch *a, aq_hinge_set *hs, double *lambda0);

/* 1 if a mechanism in which a joint lifts off (both its ends open) has a
 * lower multiplier than every four-hinge set (aq_search_info): *joint and
 * *lambda (either may be NULL); the four-hinge models do not describe it,
 * and their lambda0 then overestimates the arch's. */
int aq_arch_liftoff(const aq_arch *a, size_t *joint, double *lambda);

/* The arch's statics with friction (friction.c). */
const aq_statics *aq_arch_statics(const aq_arch *a);

#endif
