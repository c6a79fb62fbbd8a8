/* src/arch: an arch and the physics of its rocking: geometry, hinge sets,
 * work paths, the impact rule and the steppers that run steps to a result.
 *
 * arch.h: an arch built from its .cfg (geometry, hinge sets, dynamics
 * options), with the work paths of its primary and reverse hinge sets.
 * Built once (aq_arch_load, which reads the .cfg: cfg.c), then read-only
 * and safe to share between threads.  aq_arch_free accepts NULL.  Reports through aq_error
 * ("FILE:LINE: KEY: expected ..., got ...").  SI units throughout. */
#ifndef AQ_ARCH_ARCH_H
#define AQ_ARCH_ARCH_H

#include <stddef.h>
#include <stdint.h>

#include "../error.h"
#include "path.h"

typedef struct aq_arch aq_arch;

typedef enum { AQ_IMPACT_COR = 0, AQ_IMPACT_MOMENTUM } aq_impact;

/* [dynamics] section */
typedef struct {
  double cor;       /* kinetic-energy ratio kept at an impact, 0..1 (docs/method.md sec. 7) */
  aq_impact impact; /* cor | momentum */
  double g_mps2;    /* gravity, m/s^2 */
} aq_arch_dynamics;

/* How the arch's hinges are chosen ([hinges] control, docs/arch-file.md):
 *   AQ_CONTROL_FIXED: the hinge-controlled arch: set 0 is the primary
 *     (the file's, or the search's minimum), set 1 the file's reverse or
 *     the primary's face swap; every other joint carries what the thrust
 *     demands.  The default when the file names a primary.
 *   AQ_CONTROL_FREE: any joint may open: set 0 is the minimum-lambda0
 *     mechanism that a ground acceleration of sign -1 drives (act_sign -1),
 *     set 1 that of sign +1 (act_sign +1), each found by the search (a
 *     primary the file names takes its own direction's place).  The
 *     default without a primary. */
typedef enum { AQ_CONTROL_FIXED = 0, AQ_CONTROL_FREE } aq_hinge_control;

/* The names of the control modes ("fixed", "free"), indexed by
 * aq_hinge_control. */
extern const char *const aq_hinge_control_names[2];

/* What a command gives over the arch file's own values (zeroed: none). */
typedef struct {
  double friction; /* --friction: the Coulomb coefficient of every joint, > 0 and
                      finite; 0 or NAN: the file's [contact] friction */
  int friction_table; /* 1: the arch is built with its table of the least friction
                         over the load (aq_arch_mu_least; about 10-30 ms of linear
                         programs for a shipped arch), for the commands that read it
                         for every run (the main job, capacity) */
} aq_arch_options;

aq_status aq_arch_load(const char *path, aq_arch **out, aq_error *err);

/* An arch's sources as read: its .cfg's text and a joints arch's joints
 * and faces files (data[f] NULL where there is none). */
typedef struct {
  const char *text;
  size_t ntext;
  const char *data[2];
  size_t ndata[2];
  double friction;   /* the command's friction over the file's (aq_arch_options),
                        or 0: none */
  int friction_table; /* aq_arch_options' */
} aq_arch_sources;

/* As aq_arch_load with opt (NULL: none) over the file's values. */
aq_status aq_arch_load_opts(const char *path, const aq_arch_options *opt, aq_arch **out,
                            aq_error *err);

/* Where what an arch's build computes (the mechanism search's result, the
 * work paths' tables and pieces, as bytes) is kept between builds, under
 * the arch's sources (src/job/arch_cache.h keeps them on disk): */
typedef struct {
  void *ctx;
  /* The bytes kept for the arch of src: 1 and *bytes, *n, *handle (for
   * release), or 0 when none. */
  int (*get)(void *ctx, const aq_arch_sources *src, const unsigned char **bytes, size_t *n,
             void **handle);
  void (*release)(void *ctx, void *handle);
  /* Keep bytes[0..n) for the arch of src (never fails the build). */
  void (*put)(void *ctx, const aq_arch_sources *src, const unsigned char *bytes, size_t n);
} aq_arch_store;

/* As aq_arch_load, through store (NULL: none): bytes kept for the same
 * sources are taken instead of the search and the tables (the arch is the
 * one aq_arch_load builds, bit for bit); else the arch is built and its
 * bytes are put.  *hit (if not NULL): 1 when the kept bytes were taken. */
aq_status aq_arch_load_stored(const char *path, const aq_arch_store *store, int *hit,
                              aq_arch **out, aq_error *err);
/* As aq_arch_load_stored with opt (NULL: none) over the file's values
 * (their bytes kept apart from the file's: aq_arch_sources). */
aq_status aq_arch_load_stored_opts(const char *path, const aq_arch_options *opt,
                                   const aq_arch_store *store, int *hit, aq_arch **out,
                                   aq_error *err);
/* As aq_arch_load, from the len bytes at data (need not be NUL-terminated;
 * a NUL byte inside is an error); path names the input in messages and
 * gives the default name.  The bytes are copied; *out is the caller's
 * (aq_arch_free), NULL on failure. */
aq_status aq_arch_load_string(const char *data, size_t len, const char *path,
                              aq_arch **out, aq_error *err);
/* As aq_arch_load_string with opt (NULL: none) over the file's values. */
aq_status aq_arch_load_string_opts(const char *data, size_t len, const char *path,
                                   const aq_arch_options *opt, aq_arch **out, aq_error *err);
void aq_arch_free(aq_arch *a);

const char *aq_arch_name(const aq_arch *a);
/* The .cfg text exactly as read (for the results file). */
const char *aq_arch_config_text(const aq_arch *a);
/* The arch's content digest, 64 hex digits and a NUL into hex: SHA-256 of
 * the .cfg's bytes, followed by those of its joints and faces files for a
 * `shape = joints` arch (so for every other arch that of the .cfg alone). */
void aq_arch_sha256(const aq_arch *a, char hex[65]);
/* The arch's sources as read, those aq_arch_sha256 covers (owned by the
 * arch; the files' bytes NUL-terminated). */
void aq_arch_sources_of(const aq_arch *a, aq_arch_sources *src);
const aq_arch_dynamics *aq_arch_dynamics_of(const aq_arch *a);
/* The arch's generated geometry as plain arrays, for the results file and
 * for figures read back from it: owned by the arch, valid while it lives.
 * Voussoir k lies between joints k and k+1; its outline (a closed polygon,
 * counter-clockwise, curved faces sampled) is rows outline_start[k] ..
 * outline_start[k+1] of outline, its fill's rows fill_start[k] ..
 * fill_start[k+1] of fill (none without fill). */
typedef struct {
  const char *shape;          /* circular, pointed, elliptical, parabolic, catenary, joints */
  size_t voussoirs;           /* n */
  const double *joints;       /* (n+1) x 4: xi_m, yi_m, xe_m, ye_m (intrados, extrados end) */
  const double *parts;        /* n x 4: mass_kg, x_m, y_m, inertia_kgm2 of each voussoir with its
                                 fill and point masses (centroid; centroidal inertia, kg m^2) */
  size_t noutline, nfill;     /* rows of outline and fill */
  const double *outline;      /* noutline x 2: x_m, y_m */
  const int64_t *outline_start; /* n+1 */
  const double *fill;         /* nfill x 2: x_m, y_m */
  const int64_t *fill_start;  /* n+1 */
  size_t nmass;               /* point masses */
  const double *mass;         /* nmass x 4: voussoir, x_m, y_m, mass_kg */
  double stone_kg, fill_kg, point_kg; /* masonry, fill, point masses */
} aq_arch_drawing;
void aq_arch_drawing_of(const aq_arch *a, aq_arch_drawing *d);

/* set 0: primary, 1: reverse.  Check ->admissible before integrating.
 * Free control (aq_arch_control): set 0 is driven by act_sign -1, set 1 by
 * act_sign +1, each its direction's minimum mechanism. */
const aq_path *aq_arch_path(const aq_arch *a, int set);

/* The arch's hinge control (see aq_hinge_control). */
aq_hinge_control aq_arch_control(const aq_arch *a);
/* The Coulomb friction coefficient of every joint in effect (the file's
 * [contact] friction, or the command's --friction over it), NAN when none
 * was given. */
double aq_arch_friction(const aq_arch *a);
/* The block model's ([contact] e_n, [supports] spread_m): the contacts'
 * normal restitution (default 0) and the supports' spread, m (default 0). */
double aq_arch_restitution(const aq_arch *a);
double aq_arch_spread(const aq_arch *a);
/* The block model's [supports] abutment_m: how far each support's face runs
 * beyond both ends of its springing joint, m (default 0). */
double aq_arch_abutment(const aq_arch *a);

/* 1 if the arch is its own mirror image about the vertical line midway
 * between its springings: joints, voussoirs with their fill and point
 * masses (mass, centroid, inertia), to 1e-9 of its size (of each mass and
 * inertia). */
int aq_arch_mirror_symmetric(const aq_arch *a);
/* 1 if the arch answers a record and the negated record alike, up to the
 * mirror: free hinges (each direction's minimum mechanism), the arch
 * mirror-symmetric and set 1 set 0's mirror (joint j of one where joint
 * n - j of the other is, same faces), both admissible.  One polarity is
 * then enough for its verdicts (docs/arch-model.md, "Polarity"). */
int aq_arch_one_polarity(const aq_arch *a);

/* The forces across the joints of set 0 or 1 along its path, tabled
 * (src/arch/demand.h): built on the first call (safe from any thread) and
 * kept with the arch; NULL when the set is not admissible or they cannot
 * be built. */
typedef struct aq_demand_table aq_demand_table;
const aq_demand_table *aq_arch_demand_table(const aq_arch *a, int set);
/* A tracker of what a run of a asks of its joints (demand.h), for
 * aq_stepper_set_demand, checking the friction mu_limit (NAN: none).
 * NULL (err) out of memory. */
typedef struct aq_demand aq_demand;
aq_demand *aq_arch_demand_tracker(const aq_arch *a, double mu_limit, aq_error *err);

/* ---- Statics with friction (friction.c; docs/arch-model.md, "Friction")
 * lambda is a horizontal ground acceleration of lambda g with the sign
 * act_sign (-1 or +1), as path.h's lambda0: the arch carries gravity and
 * the inertia force lambda g per unit mass along -act_sign x.  A "line of
 * thrust stands" when, at every joint, the resultant it carries passes
 * between the joint's ends and pushes, and (with a friction mu) its shear
 * T and normal force N satisfy |T| <= mu N.  Every function below is a
 * read of what the arch's build computed (no linear program is solved):
 * safe from any thread. */

/* The least friction with which a line of thrust stands at rest, and (if
 * joint is not NULL) the joint that needs it.  An arch whose friction is
 * below it is never built ("cannot stand with friction ..."). */
double aq_arch_mu_rest(const aq_arch *a, size_t *joint);
/* The least friction with which a line of thrust stands under lambda >= 0
 * of direction act_sign, from the arch's table (built with
 * aq_arch_options.friction_table; NAN without one: model.h
 * aq_friction_least computes one value exactly, from one thread): exact
 * values and slopes (the linear programs, friction.c) at nodes from 0 to
 * aq_arch_lambda_static, a cubic between them, refined until it is within
 * 1e-6 of the largest value at every interval's middle (within 5.4e-5
 * relative anywhere on the shipped arches: test_arch_friction), or until
 * its 256 nodes run out (model.h aq_statics_resolved 0: flagged); INFINITY
 * above aq_arch_lambda_static (no line of thrust at all), and above the
 * load where the least friction passes 1e3 when that is below it (a
 * lift-off's pole: the table ends there, docs/arch-model.md "Friction");
 * NAN for lambda < 0.  *joint (if not NULL): where the nearest node's
 * line needs it. */
double aq_arch_mu_least(const aq_arch *a, int act_sign, double lambda, size_t *joint);
/* The largest lambda of direction act_sign at which a line of thrust stands
 * with friction mu (lambda_friction): exact (the linear program) when mu is
 * the arch's own friction, else from aq_arch_mu_least's table (NAN without
 * one; model.h aq_friction_lambda computes it exactly); NAN when no line
 * stands with mu even at rest, or (from a table that ends below the top)
 * for mu above 1e3. */
double aq_arch_lambda_friction(const aq_arch *a, int act_sign, double mu);
/* The largest lambda of direction act_sign at which a line of thrust
 * stands without friction: that direction's minimum over every mechanism
 * (the four-hinge minimum's lambda0, or a lift-off mechanism's below it:
 * aq_arch_liftoff). */
double aq_arch_lambda_static(const aq_arch *a, int act_sign);
/* The friction that hinge set `set` (0, 1) needs at each joint in its
 * collapse state (s = 0, lambda = its lambda0): ratio[j] = |T|/N, j =
 * 0..n (model.h aq_mech_friction; ratio may be NULL), the forces from the
 * 9x9 hinge reactions and each piece's statics between a hinge and the
 * joint.  Returns the largest (mu_required) and its joint in *joint (if
 * not NULL); NAN (and joint SIZE_MAX) for an inadmissible set. */
double aq_arch_joint_friction(const aq_arch *a, int set, double *ratio, size_t *joint);

#endif
