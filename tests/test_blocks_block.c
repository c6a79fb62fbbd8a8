/* test_blocks_block.c: the block model (src/blocks) on a single rigid block
 * on the ground, against closed forms: the rocking onset at tan(alpha),
 * the rocking equation of motion about a corner, Housner's impact ratio,
 * and Newmark's sliding block. */
#include <math.h>
#include <stdlib.h>

#include "blocks/blocks_run.h"
#include "check.h"

static const double G = 9.80665;

/* A block 2b wide and 2h tall on the ground, centroid at (0, h). */
typedef struct {
  double b, h, m;
} block;

static aq_blocks *block_model(block k, double mu, double e_n, double dt)
{
  aq_body body = {k.m, k.m * (4 * k.b * k.b + 4 * k.h * k.h) / 12, {0, k.h}, 0, 0};
  aq_vec2 ends[1][2] = {{{-k.b, 0}, {k.b, 0}}};
  aq_error e;
  aq_error_clear(&e);
  aq_blocks *B = aq_blocks_alloc_bodies(&body, 1, (const aq_vec2(*)[2])ends, 1, G, &e);
  if (!aq_check(B != NULL, "block model: %s", e.message))
    return NULL;
  aq_check(aq_blocks_set_friction(B, mu, &e) == AQ_OK, "friction %g", mu);
  aq_check(aq_blocks_set_restitution(B, e_n, &e) == AQ_OK, "e_n %g", e_n);
  aq_check(aq_blocks_set_dt(B, dt, &e) == AQ_OK, "dt %g", dt);
  return B;
}

/* Steps of step_s each: a1 for n1 of them, then a2 for n2. */
static int two_levels(double a1, size_t n1, double a2, size_t n2, double step_s,
                      aq_steps *s)
{
  size_t n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d), *a = malloc(n * sizeof *a);
  int ok = t && d && a;
  for (size_t i = 0; ok && i < n; i++) {
    t[i] = (double)i * step_s;
    d[i] = step_s;
    a[i] = i < n1 ? a1 : a2;
  }
  aq_error e;
  ok = ok && aq_steps_from_list(t, d, a, n, s, &e) == AQ_OK;
  free(t);
  free(d);
  free(a);
  return aq_check(ok, "steps");
}

static int run(aq_blocks *B, const aq_steps *s, aq_blocks_result *r)
{
  aq_error e;
  aq_error_clear(&e);
  return aq_check(aq_blocks_run(B, s, r, &e) == AQ_OK, "run: %s", e.message);
}

/* A block stands under a constant ground acceleration below g tan(alpha)
 * and rocks above it, both ways, whether steps at rest are skipped (the
 * static range) or every step is solved (the dynamics alone). */
AQ_TEST(blocks_block_rocking_onset)
{
  block k = {0.15, 0.55, 850};
  double ta = k.b / k.h;
  for (int skip = 0; skip < 2; skip++)
    for (int sgn = -1; sgn <= 1; sgn += 2)
      for (int above = 0; above < 2; above++) {
        double f = above ? 1.001 : 0.999;
        aq_blocks *B = block_model(k, 10, 0, 1e-3);
        if (!B)
          return;
        aq_blocks_set_rest_skip(B, skip);
        aq_steps s;
        aq_blocks_result r;
        if (two_levels(sgn * f * G * ta, 200, 0, 0, 1e-3, &s) && run(B, &s, &r)) {
          if (above)
            aq_check(r.r.peak_rotation_rad > 1e-6,
                     "%.3f g tan(alpha), sign %d, skip %d: rocks (peak %g rad)", f, sgn, skip,
                     r.r.peak_rotation_rad);
          else
            aq_check(r.r.peak_rotation_rad < 1e-12 && r.r.peak_displacement_m < 1e-12,
                     "%.3f g tan(alpha), sign %d, skip %d: stands (peak %g rad, %g m)", f,
                     sgn, skip, r.r.peak_rotation_rad, r.r.peak_displacement_m);
          aq_check(r.max_slip_m < 1e-12, "no slip with friction 10 (%g m)", r.max_slip_m);
          aq_blocks_result_free(&r);
        }
        aq_steps_free(&s);
        aq_blocks_free(B);
      }
}

/* The tipping angle theta about a corner under a constant horizontal body
 * force A per unit mass: (4/3) R theta'' = A cos(alpha - theta) -
 * g sin(alpha - theta) (I_O = 4/3 m R^2), by a test-local RK4 with 1e5
 * steps; rock_angle about a pivot at R from the centroid, at alpha from the
 * vertical, with I_O / m = ip_m. */
static double rock_angle(double A, double alpha, double R, double ip_m, double T)
{
  double th = 0, w = 0, dt = T / 1e5;
  for (int i = 0; i < 100000; i++) {
#define ACC(x) (R / ip_m * (A * cos(alpha - (x)) - G * sin(alpha - (x))))
    double k1t = w, k1w = ACC(th);
    double k2t = w + 0.5 * dt * k1w, k2w = ACC(th + 0.5 * dt * k1t);
    double k3t = w + 0.5 * dt * k2w, k3w = ACC(th + 0.5 * dt * k2t);
    double k4t = w + dt * k3w, k4w = ACC(th + dt * k3t);
#undef ACC
    th += dt / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += dt / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return th;
}

static double tip_angle(double A, double alpha, double R, double T)
{
  return rock_angle(A, alpha, R, 4.0 / 3.0 * R * R, T);
}

/* Rocking about a corner under 1.6 g tan(alpha) for 0.4 s: the rotation at
 * the end against the equation of motion, converging at the scheme's
 * first order as the step halves. */
AQ_TEST(blocks_block_rocking_motion)
{
  block k = {0.15, 0.55, 850};
  double alpha = atan2(k.b, k.h), R = hypot(k.b, k.h), A = 1.6 * G * k.b / k.h;
  double want = tip_angle(A, alpha, R, 0.4), err[2];
  for (int i = 0; i < 2; i++) {
    double dt = i ? 5e-4 : 1e-3;
    aq_blocks *B = block_model(k, 10, 0, dt);
    if (!B)
      return;
    aq_blocks_set_history(B, 1);
    aq_steps s;
    aq_blocks_result r;
    if (two_levels(-A, 400, 0, 0, 1e-3, &s) && run(B, &s, &r)) {
      double got = -r.r.history.rotation_rad[r.r.history.n - 1];
      err[i] = got / want - 1;
      aq_check_rel(got, want, 2e-3, "tipping angle at 0.4 s, dt %g", dt);
      aq_blocks_result_free(&r);
    }
    aq_steps_free(&s);
    aq_blocks_free(B);
  }
  aq_check(fabs(err[0] / err[1] - 2) < 0.3, "first order: errors %.3e, %.3e (ratio %.3f)",
           err[0], err[1], err[0] / err[1]);
}

/* Free rocking after a pulse with e_n = 0: each impact keeps r^2 of the
 * energy, r = 1 - 3/2 sin^2(alpha) (Housner 1963, The behavior of inverted
 * pendulum structures during earthquakes, Bulletin of the Seismological
 * Society of America 53(2), 403-417, eq. (13) for the rectangular block):
 * the energy measured between the first and second impacts over that
 * between the pulse and the first, against r^2, within the scheme's
 * first-order error (which halves with the step). */
AQ_TEST(blocks_block_housner_impact)
{
  block k = {0.15, 0.55, 850};
  double alpha = atan2(k.b, k.h), rr = 1 - 1.5 * sin(alpha) * sin(alpha);
  double err[2];
  for (int i = 0; i < 2; i++) {
    double dt = i ? 2.5e-4 : 5e-4;
    aq_blocks *B = block_model(k, 10, 0, dt);
    if (!B)
      return;
    aq_blocks_set_history(B, 1);
    aq_steps s;
    aq_blocks_result r;
    err[i] = NAN;
    if (two_levels(-1.8 * G * k.b / k.h, 150, 0, 1850, 1e-3, &s) && run(B, &s, &r)) {
      const aq_history *H = &r.r.history;
      /* the energy in each swing: between sign changes of the rotation */
      double e[2] = {0, 0};
      int n[2] = {0, 0}, swing = 0;
      for (size_t j = 151; j + 1 < H->n && swing < 2; j++) {
        if (H->rotation_rad[j] * H->rotation_rad[j + 1] < 0) {
          swing++;
          j++; /* the step with the impact in it */
          continue;
        }
        if (fabs(H->rotation_rad[j]) > 1e-6) {
          e[swing] += H->kinetic_energy_j[j] + H->potential_energy_j[j];
          n[swing]++;
        }
      }
      if (aq_check(n[0] > 10 && n[1] > 10, "two swings (%d, %d samples)", n[0], n[1])) {
        double ratio = (e[1] / n[1]) / (e[0] / n[0]);
        err[i] = ratio / (rr * rr) - 1;
        aq_check_rel(ratio, rr * rr, 2e-2, "energy kept at the impact, dt %g", dt);
      }
      aq_check(r.r.impacts >= 2, "impacts counted (%zu)", r.r.impacts);
      aq_blocks_result_free(&r);
    }
    aq_steps_free(&s);
    aq_blocks_free(B);
  }
  aq_check(fabs(err[1]) < 0.7 * fabs(err[0]), "the error falls with the step: %.3e, %.3e",
           err[0], err[1]);
}

/* A wide block sliding on its base (friction 0.2, tan alpha = 2.4: it
 * never rocks): it stands below mu g and slides above it; under a
 * rectangular pulse A for t0 its slip is Newmark's A t0^2 (A - mu g) /
 * (2 mu g) (Newmark 1965, Effects of earthquakes on dams and embankments,
 * Geotechnique 15(2), 139-160: the rigid block on an inclined plane, here
 * flat, under one rectangular pulse). */
AQ_TEST(blocks_block_newmark_sliding)
{
  block k = {0.6, 0.25, 1234.5};
  double mu = 0.2;
  for (int above = 0; above < 2; above++) {
    aq_blocks *B = block_model(k, mu, 0, 1e-3);
    if (!B)
      return;
    aq_blocks_set_rest_skip(B, 0);
    aq_steps s;
    aq_blocks_result r;
    double f = above ? 1.001 : 0.999;
    if (two_levels(f * mu * G, 300, 0, 0, 1e-3, &s) && run(B, &s, &r)) {
      if (above)
        aq_check(r.max_slip_m > 1e-9 && r.friction_work_j > 0,
                 "slides above mu g (%g m, friction's work %g J)", r.max_slip_m,
                 r.friction_work_j);
      else
        aq_check(r.max_slip_m < 1e-12 && r.friction_work_j == 0,
                 "stands below mu g (%g m, friction's work %g J)", r.max_slip_m,
                 r.friction_work_j);
      aq_check(r.r.peak_rotation_rad < 1e-12, "does not rock (%g)", r.r.peak_rotation_rad);
      aq_blocks_result_free(&r);
    }
    aq_steps_free(&s);
    aq_blocks_free(B);
  }
  double A = 0.45 * G, t0 = 0.4, want = A * t0 * t0 * (A - mu * G) / (2 * mu * G);
  aq_blocks *B = block_model(k, mu, 0, 1e-3);
  if (!B)
    return;
  aq_steps s;
  aq_blocks_result r;
  if (two_levels(A, 400, 0, 1600, 1e-3, &s) && run(B, &s, &r)) {
    aq_check_rel(r.max_slip_m, want, 1e-12, "Newmark's slip");
    /* the friction mu m g slides the block by Newmark's slip, one way */
    aq_check_rel(r.friction_work_j, mu * k.m * G * want, 1e-12, "friction's work: mu m g s");
    aq_check(!isnan(aq_blocks_rest_since(B)), "at rest again");
    aq_blocks_result_free(&r);
  }
  aq_steps_free(&s);
  aq_blocks_free(B);
}

/* Newmark's block pushed one way and then back by the same pulse: it
 * slides by Newmark's s, stops, and slides back by s to where it stood.
 * The friction's work counts the whole path, mu m g 2 s, where the slip
 * (the largest offset) is s; under the pulse reversed, the same. */
AQ_TEST(blocks_block_newmark_friction_work)
{
  block k = {0.6, 0.25, 1234.5};
  double mu = 0.2, A = 0.45 * G, t0 = 0.4;
  double s1 = A * t0 * t0 * (A - mu * G) / (2 * mu * G);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    aq_blocks *B = block_model(k, mu, 0, 1e-3);
    if (!B)
      return;
    /* +A for t0, still for 1.6 s (it stops within 0.6 s), -A for t0, still */
    size_t n = 400 + 1600 + 400 + 1600;
    double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d), *a = malloc(n * sizeof *a);
    aq_steps s;
    aq_error e;
    int ok = t && d && a;
    for (size_t i = 0; ok && i < n; i++) {
      t[i] = (double)i * 1e-3;
      d[i] = 1e-3;
      a[i] = i < 400 ? sgn * A : i >= 2000 && i < 2400 ? -sgn * A : 0;
    }
    ok = ok && aq_steps_from_list(t, d, a, n, &s, &e) == AQ_OK;
    free(t);
    free(d);
    free(a);
    aq_blocks_result r;
    if (aq_check(ok, "steps") && run(B, &s, &r)) {
      aq_check_rel(r.max_slip_m, s1, 1e-12, "sign %d: the slip, Newmark's s", sgn);
      aq_check_rel(r.friction_work_j, 2 * mu * k.m * G * s1, 1e-12,
                   "sign %d: friction's work mu m g 2 s", sgn);
      aq_check(r.r.peak_rotation_rad < 1e-12, "sign %d: does not rock", sgn);
      aq_blocks_result_free(&r);
    }
    if (ok)
      aq_steps_free(&s);
    aq_blocks_free(B);
  }
}

/* e_n = 1: after a pulse the block rocks freely; under the global impact
 * law (docs/blocks.md) every impact keeps the energy exactly (it sticks:
 * friction 10; the block leaves the ground on both corners) and the
 * flights between are exact for the scheme, so what is lost over 1.85 s
 * of free motion is the scheme's first-order error while a corner holds
 * (measured 5.7e-4 at 0.0005 s, 2.9e-4 at 0.00025 s; Newton's law per
 * corner with the impact inside the step lost 21 % and 9.7 %): below 2 h
 * per second of step and halving with it. */
AQ_TEST(blocks_block_energy_restitution_one)
{
  block k = {0.15, 0.55, 850};
  double lost[2];
  for (int i = 0; i < 2; i++) {
    double dt = i ? 2.5e-4 : 5e-4;
    aq_blocks *B = block_model(k, 10, 1, dt);
    if (!B)
      return;
    aq_blocks_set_history(B, 1);
    aq_steps s;
    aq_blocks_result r;
    lost[i] = NAN;
    if (two_levels(-1.8 * G * k.b / k.h, 150, 0, 1850, 1e-3, &s) && run(B, &s, &r)) {
      const aq_history *H = &r.r.history;
      double e0 = H->kinetic_energy_j[150] + H->potential_energy_j[150];
      double e1 = H->kinetic_energy_j[H->n - 1] + H->potential_energy_j[H->n - 1];
      lost[i] = 1 - e1 / e0;
      aq_check(r.r.impacts >= 10, "it bounces on (%zu impacts)", r.r.impacts);
      aq_check(fabs(lost[i]) < 2 * dt, "energy lost over the free motion, dt %g: %.3e", dt,
               lost[i]);
      aq_blocks_result_free(&r);
    }
    aq_steps_free(&s);
    aq_blocks_free(B);
  }
  aq_check(fabs(lost[0] / lost[1] - 2) < 0.3, "first order: %.3e -> %.3e", lost[0], lost[1]);
}

/* The kinetic energy of the test's bodies at v. */
static double kinetic_j(const aq_bodies *s, const double *v)
{
  double k = 0;
  for (size_t b = 0; b < s->nb; b++)
    k += 0.5 * s->body[b].mass_kg * (v[3 * b] * v[3 * b] + v[3 * b + 1] * v[3 * b + 1]) +
         0.5 * s->body[b].inertia_kgm2 * v[3 * b + 2] * v[3 * b + 2];
  return k;
}

/* The impact stage of the global law (docs/blocks.md) on a block rocking
 * about its intrados corner whose extrados corner lands (turned by 1e-9
 * rad, omega = -1.37 rad/s): the plastic impact is Housner's (1963: the
 * block turns on about the landing corner at r omega, r = 1 - 3/2
 * sin^2(alpha), the other corner lifting), and the law's v+ = v_p + e (v_p
 * - v-) keeps (1 - (1 - e^2)(1 - r^2)) of the kinetic energy, all of it at
 * e = 1 (a sticking impact: friction 10). */
AQ_TEST(blocks_block_impact_stage_housner)
{
  block k = {0.15, 0.55, 850};
  double alpha = atan2(k.b, k.h), rr = 1 - 1.5 * sin(alpha) * sin(alpha);
  double th = 1e-9, w = -1.37, cs = cos(th), sn = sin(th);
  /* about the intrados corner (-b, 0): the centroid at (-b, 0) + R(th) (b, h) */
  double rx = cs * k.b - sn * k.h, ry = sn * k.b + cs * k.h;
  double q[3] = {-k.b + rx, ry, th}, v[3] = {-w * ry, w * rx, w};
  static const double es[] = {0, 0.5, 1};
  for (int i = 0; i < 3; i++) {
    double e_n = es[i];
    aq_blocks *B = block_model(k, 10, e_n, 1e-3);
    if (!B)
      return;
    aq_moreau *m = aq_blocks_moreau(B);
    const aq_bodies *s = aq_blocks_bodies(B);
    aq_moreau_set(m, 10, e_n, 0.5, 1, 1);
    aq_jstate st[1] = {{AQ_JOINT_HINGE_I, 0}};
    aq_moreau_set_state(m, q, v, st);
    aq_step_info info;
    aq_error e;
    aq_error_clear(&e);
    if (aq_check(aq_moreau_impact(m, 1e-3, &info, &e) == AQ_OK, "impact: %s", e.message) &&
        aq_check(info.impact, "the extrados corner lands, e %g", e_n)) {
      const double *vp = aq_moreau_v(m);
      /* Housner's v_p: about the extrados corner (b, 0) at r w */
      double wp = rr * w, px = -k.b, py = k.h; /* the centroid from (b, 0), flat */
      double want[3] = {(1 + e_n) * -wp * py - e_n * v[0], (1 + e_n) * wp * px - e_n * v[1],
                        (1 + e_n) * wp - e_n * v[2]};
      for (int c = 0; c < 3; c++)
        aq_check_abs(vp[c], want[c], 1e-7, "e %g: v+[%d] against Housner's", e_n, c);
      double ke0 = kinetic_j(s, v), ke1 = kinetic_j(s, vp);
      aq_check_rel(ke1 / ke0, 1 - (1 - e_n * e_n) * (1 - rr * rr), e_n == 1 ? 1e-12 : 1e-8,
                   "e %g: kinetic energy kept", e_n);
      aq_check(fabs(info.friction_j) <= 1e-12 * ke0, "e %g: it sticks (friction %g J)", e_n,
               info.friction_j);
    }
    aq_blocks_free(B);
  }
}

/* A block on a support as wide as its base (support extent 0), slid by s
 * along it, sticking (friction 10).  Its base and the support's face
 * overlap over 2b - |s|, and the contacts are the overlap's two ends: the
 * block's own corner on the side away from the slide, the support's corner
 * on the side of it.  So it tips towards the slide about the support's
 * corner, at g (b - |s|) / h, and away from it about its own corner, at
 * g b / h (rigid-body statics: the weight's line through the pivot).
 * Above the onset towards the slide its rotation after 0.4 s is that of a
 * rigid body about the support's corner (rock_angle with the pivot at
 * R' = hypot(b - |s|, h) and I_O / m = R^2 / 3 + R'^2), and that corner
 * stays where it was (the block's material point there moves by 1.8e-8 m
 * in 0.4 s: the sticking contact's drift; 1e-6 m allowed, where the
 * block's own corner is 0.1 m away).
 * Both slides, +s and -s (mirror images).  Contacts at the block's
 * corners against the support's face line (running on beyond it) would
 * tip it at g b / h both ways, about its corner. */
static aq_moreau *slid_block_on(block k, double s0, double ext_m, aq_bodies *S);

static aq_moreau *slid_block(block k, double s0, aq_bodies *S)
{
  return slid_block_on(k, s0, 0, S);
}

/* The same on a support whose face runs ext_m beyond both ends of the
 * joint ([supports] abutment_m). */
static aq_moreau *slid_block_on(block k, double s0, double ext_m, aq_bodies *S)
{
  aq_body body = {k.m, k.m * (4 * k.b * k.b + 4 * k.h * k.h) / 12, {0, k.h}, 0, 0};
  aq_vec2 ends[1][2] = {{{-k.b, 0}, {k.b, 0}}};
  aq_error e;
  aq_error_clear(&e);
  if (!aq_check(aq_bodies_init(S, &body, 1, (const aq_vec2(*)[2])ends, 1, G, &e) == AQ_OK,
                "bodies: %s", e.message))
    return NULL;
  aq_bodies_set_support_extent(S, ext_m);
  aq_moreau *M = aq_moreau_alloc(S, &e);
  if (!aq_check(M != NULL, "stepper: %s", e.message)) {
    aq_bodies_free(S);
    return NULL;
  }
  aq_moreau_set(M, 10, 0, 0.5, 1, 1);
  double q[3] = {s0, k.h, 0}, v[3] = {0, 0, 0};
  aq_jstate st[1] = {{AQ_JOINT_WELD, 0}};
  aq_moreau_set_state(M, q, v, st);
  return M;
}

/* Steps of h under ground acceleration ax for T s; 0 on a failed step. */
static int push(aq_moreau *M, double ax, double h, double T)
{
  double gx[2] = {0, 0};
  size_t n = (size_t)llround(T / h);
  for (size_t i = 0; i < n; i++) {
    aq_step_info info;
    aq_error e;
    aq_error_clear(&e);
    if (!aq_check(aq_moreau_step(M, h, ax, 0, gx, &info, &e) == AQ_OK, "step: %s", e.message))
      return 0;
  }
  return 1;
}

/* The block slid by s on a support whose face runs ext_m beyond the
 * joint, under a constant ground acceleration of 0.999 (above 0) or 1.001
 * (above 1) times g ta pushing it to tip towards the slide (dir 0) or away
 * (dir 1) for 0.3 s: it stands (to 1e-12) or tips.  0 if the model could
 * not be made. */
static int stands_or_tips(block k, double s, double ext_m, int dir, int above, double ta)
{
  double f = above ? 1.001 : 0.999, sgn = s < 0 ? -1 : 1;
  /* the body force -m ax points along the tipping side */
  double ax = -(dir ? -sgn : sgn) * f * G * ta;
  aq_bodies S;
  aq_moreau *M = slid_block_on(k, s, ext_m, &S);
  if (!M)
    return 0;
  if (push(M, ax, 1e-3, 0.3)) {
    const double *q = aq_moreau_q(M);
    if (above)
      aq_check(fabs(q[2]) > 1e-6, "slid %+g on %g m, %s: %.3f of its onset tips (%g rad)", s,
               ext_m, dir ? "away" : "towards", f, q[2]);
    else
      aq_check(fabs(q[2]) < 1e-12 && fabs(q[0] - s) < 1e-12,
               "slid %+g on %g m, %s: %.3f of its onset stands (%g rad, x %g m)", s, ext_m,
               dir ? "away" : "towards", f, q[2], q[0]);
  }
  aq_moreau_free(M);
  aq_bodies_free(&S);
  return 1;
}

AQ_TEST(blocks_block_slid_tips_about_overlap_end)
{
  block k = {0.3, 0.6, 900};
  double s = 0.1, toward = (k.b - s) / k.h, away = k.b / k.h;
  for (int sgn = -1; sgn <= 1; sgn += 2)
    for (int dir = 0; dir < 2; dir++) /* 0 towards the slide, 1 away */
      for (int above = 0; above < 2; above++)
        if (!stands_or_tips(k, sgn * s, 0, dir, above, dir ? away : toward))
          return;
  /* the motion about the support's corner */
  double Rp = hypot(k.b - s, k.h), R = hypot(k.b, k.h), ap = atan2(k.b - s, k.h);
  double A = 1.6 * G * toward, want = rock_angle(A, ap, Rp, R * R / 3 + Rp * Rp, 0.4);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    aq_bodies S;
    aq_moreau *M = slid_block(k, sgn * s, &S);
    if (!M)
      return;
    if (push(M, -sgn * A, 5e-4, 0.4)) {
      double *q = aq_moreau_q(M), gx[2] = {0, 0};
      aq_check_rel(-sgn * q[2], want, 2e-3, "slid %+g: tipping angle at 0.4 s", sgn * s);
      /* the block's material point at the support's corner (sgn b, 0) */
      aq_vec2 p = aq_bodies_point(&S, 0, q, gx, (aq_vec2){sgn * (k.b - s), 0});
      aq_check(hypot(p.x - sgn * k.b, p.y) < 1e-6, "slid %+g: the pivot stays (%g, %g)",
               sgn * s, p.x - sgn * k.b, p.y);
    }
    aq_moreau_free(M);
    aq_bodies_free(&S);
  }
}

/* The faces part when they no longer overlap: a block on a support as wide
 * as its base (2b = 0.6 m) slid by 0.55 m still bears (overlap 0.05 m),
 * slid by 0.61 m it has parted, whether it still touches the support's
 * face line (closed) or flies 1 mm above it (open: it would land on the
 * line beyond the face). */
AQ_TEST(blocks_block_faces_part)
{
  block k = {0.3, 0.6, 900};
  static const struct {
    double slide_m, lift_m;
    int open, parted;
  } cases[] = {{0.55, 0, 0, 0}, {-0.55, 0, 0, 0}, {0.61, 0, 0, 1}, {-0.61, 0, 0, 1},
               {0.55, 1e-3, 1, 0}, {0.61, 1e-3, 1, 1}, {-0.61, 1e-3, 1, 1}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    aq_bodies S;
    aq_moreau *M = slid_block(k, 0, &S);
    if (!M)
      return;
    aq_events ev;
    aq_error e;
    aq_blocks_result res = {0};
    if (aq_check(aq_events_init(&ev, &S, &e) == AQ_OK, "events")) {
      aq_events_reset(&ev, M, NULL, 0, 0, &res);
      double q[3] = {cases[i].slide_m, k.h + cases[i].lift_m, 0}, v[3] = {0, 0, 0};
      aq_jstate st[1] = {{cases[i].open ? AQ_JOINT_OPEN : AQ_JOINT_WELD, 0}};
      aq_moreau_set_state(M, q, v, st);
      aq_check(aq_events_fallen(&ev, M) == cases[i].parted,
               "slid %+g m, %s: parted %d expected", cases[i].slide_m,
               cases[i].open ? "open" : "closed", cases[i].parted);
      aq_events_free(&ev);
    }
    aq_moreau_free(M);
    aq_bodies_free(&S);
  }
}

/* A joint whose faces part in flight.  Newmark's block (friction 0.2) on a
 * support as wide as its base (2b = 1.2 m) slides by Newmark's
 * s = A t0^2 (A - mu g) / (2 mu g) = 0.441 m under A = 0.45 g for 0.4 s and
 * stops (its overlap with the support 0.759 m: it neither tips nor parts).
 * Then the ground drops at 2 g and pulls on at g the same way: in the
 * frame of the ground the block is lifted at g and driven along the
 * support at g, so it leaves the support at once, without turning, and
 * its face runs on along the support's until they no longer overlap, at
 * the offset 2b, t_f = sqrt(2 (2b - s) / g) = 0.393 s into the flight
 * (risen by 2b - s = 0.759 m: it has not yet cleared the joint's width,
 * the other parting bound).  The run ends collapsed there, and the joint's
 * slip is its faces' offset when they parted: between 2b and 2b plus one
 * step's drift (g t_f h).  Counting the slip at closed corners only
 * reported s, the slip before the flight. */
AQ_TEST(blocks_block_slip_parts_in_flight)
{
  block k = {0.6, 0.25, 1234.5};
  double mu = 0.2, A = 0.45 * G, t0 = 0.4, h = 1e-3, w = 2 * k.b;
  double s1 = A * t0 * t0 * (A - mu * G) / (2 * mu * G), tf = sqrt(2 * (w - s1) / G);
  aq_blocks *B = block_model(k, mu, 0, h);
  if (!B)
    return;
  aq_error e;
  aq_error_clear(&e);
  aq_check(aq_blocks_set_abutment(B, 0, &e) == AQ_OK, "a support as wide as the base: %s",
           e.message);
  /* the slip before the flight: the same record cut at 2 s */
  aq_steps s;
  aq_blocks_result r;
  if (two_levels(A, 400, 0, 1600, h, &s) && run(B, &s, &r)) {
    aq_check_rel(r.max_slip_m, s1, 1e-12, "before the flight: Newmark's slip");
    aq_check(!r.r.collapsed, "it stands on the support before the flight");
    aq_blocks_result_free(&r);
    aq_steps_free(&s);
  }
  size_t n = 2600;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d), *a = malloc(n * sizeof *a),
         *av = malloc(n * sizeof *av);
  int ok = t && d && a && av;
  for (size_t i = 0; ok && i < n; i++) {
    t[i] = (double)i * h;
    d[i] = h;
    a[i] = i < 400 || i >= 2000 ? (i < 400 ? A : G) : 0;
    av[i] = i >= 2000 ? -2 * G : 0;
  }
  ok = ok && aq_steps_from_list(t, d, a, n, &s, &e) == AQ_OK;
  if (ok && aq_steps_set_vertical(&s, av, &e) != AQ_OK) {
    aq_steps_free(&s);
    ok = 0;
  }
  free(t);
  free(d);
  free(a);
  free(av);
  if (aq_check(ok, "steps: %s", e.message) && run(B, &s, &r)) {
    aq_check(r.r.collapsed && fabs(r.r.collapse_time_s - (2.0 + tf)) <= 1.01 * h,
             "parted in flight at %.4f s (collapsed %d at %.4f s)", 2.0 + tf, r.r.collapsed,
             r.r.collapse_time_s);
    aq_check(r.max_slip_m >= w && r.max_slip_m <= w + G * tf * h,
             "slip %.6f m: the faces' offset when they parted, [%.6f, %.6f] m (before the "
             "flight %.6f m)",
             r.max_slip_m, w, w + G * tf * h, s1);
    aq_check(r.r.peak_rotation_rad < 1e-9, "it does not turn (%g rad)", r.r.peak_rotation_rad);
    aq_blocks_result_free(&r);
  }
  if (ok)
    aq_steps_free(&s);
  aq_blocks_free(B);
}

/* A block slid beyond the end of its support's joint still bears on a
 * wider abutment.  The support's face runs e = 0.5 m on beyond both ends of
 * the joint under the block's base (2b = 0.6 m, 2h = 1.2 m; [supports]
 * abutment_m).  Slid by |s| = 0.61 m, past the joint's end (with e = 0 its
 * faces have parted, blocks_block_faces_part), it bears on the overlap
 * from its own corner to the abutment's, which lies b + e - |s| = 0.19 m
 * beyond its centroid: it tips towards the slide about the abutment's
 * corner at g (b + e - |s|) / h (the closed form g (b - |s|) / h of a
 * support as wide as the base, the slide counted from the abutment's end,
 * |s| - e), and away from it about its own corner at g b / h.  Slid by
 * |s| = 0.3 m, within the abutment, it bears on its whole base and tips
 * at g b / h both ways.  At 0.999 and 1.001 of each onset, for +s and -s:
 * it stands (to 1e-12) and tips; its faces have not parted. */
AQ_TEST(blocks_block_wide_abutment)
{
  block k = {0.3, 0.6, 900};
  double ext = 0.5;
  static const double slides[] = {0.61, 0.3};
  for (size_t c = 0; c < 2; c++) {
    double s = slides[c], reach = fmin(k.b, k.b + ext - s);
    double toward = reach / k.h, away = k.b / k.h;
    for (int sgn = -1; sgn <= 1; sgn += 2)
      for (int dir = 0; dir < 2; dir++) /* 0 towards the slide, 1 away */
        for (int above = 0; above < 2; above++)
          if (!stands_or_tips(k, sgn * s, ext, dir, above, dir ? away : toward))
            return;
    /* it bears: its faces have not parted */
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      aq_bodies S;
      aq_moreau *M = slid_block_on(k, sgn * s, ext, &S);
      if (!M)
        return;
      aq_events ev;
      aq_error e;
      aq_blocks_result res = {0};
      if (aq_check(aq_events_init(&ev, &S, &e) == AQ_OK, "events")) {
        aq_events_reset(&ev, M, NULL, 0, 0, &res);
        aq_check(!aq_events_fallen(&ev, M), "slid %+g on an abutment of %g m: it bears",
                 sgn * s, ext);
        aq_events_free(&ev);
      }
      aq_moreau_free(M);
      aq_bodies_free(&S);
    }
  }
}
