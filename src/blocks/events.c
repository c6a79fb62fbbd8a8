/* events.c: what a run of the block model reports (blocks.h), and its
 * collapse rule.
 *
 * Collapse.  The arch has collapsed when it moves away from where it stood
 * at the record's start (the product (q - q0)^T M v of its displacement and
 * velocity in the bodies' mass metric is positive), its potential energy
 * falls (sum m g v_y < 0), and that energy is above where it stood by at
 * least a set fraction of the arch's energy barrier (dv_floor_j).  For a
 * four-hinge mechanism this is the work path's collapse point exactly:
 * along the path the potential energy m g y(s) rises from s = 0 to s_c,
 * where dy/ds = 0 (docs/method.md: lambda(s) = 0), and falls beyond, so
 * moving out (s' > 0) with the energy falling means s > s_c, and the rise
 * there is the barrier itself.  It needs no hinge set and holds for any
 * mechanism the contacts form (hinges that move, sliding joints): it asks
 * only whether the arch has passed the top of the hill it was climbing.
 * The floor keeps the rounding and rattle of a nearly closed arch (a
 * displacement of 1e-9 m along a direction that is not the mechanism's)
 * from passing for that top.  Two bounds end the run as collapsed as well:
 * a body turned by more than COLLAPSE_ROT_RAD, or a joint whose two corners
 * are both open by more than its width or that slid by more than its
 * width (the voussoirs have parted: a voussoir between vertical joints that
 * lose their thrust drops out, its potential energy falling, which the rule
 * above does not take for a collapse). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "blocks_run.h"

/* A velocity is zero to the solvers' accuracy below this fraction of g h
 * (Siconos's answers carry 1e-10 of it from the compliance that makes its
 * problem regular; the arch is then declared at rest only if the static
 * range holds the load, when v = 0 is the step's exact solution). */
static const double STILL_REL = 1e-6;
static const double COLLAPSE_ROT_RAD = AQ_PI / 4;
/* ... or slid along a joint until its two faces no longer overlap
 * (aq_contact_overlap < 0, by the slip at a closed end, or at both ends of
 * an open joint: the voussoirs have parted; for a joint between
 * voussoirs, and at a springing on its support's face as long as the
 * joint, a slip of more than the joint's width). */

aq_status aq_events_init(aq_events *e, const aq_bodies *s, aq_error *err)
{
  memset(e, 0, sizeof *e);
  e->s = s;
  size_t n3 = 3 * s->nb, nv = s->nvous ? s->nvous : s->nb;
  e->q0 = malloc(n3 * sizeof *e->q0);
  e->qprev = malloc(n3 * sizeof *e->qprev);
  e->c0 = malloc(nv * sizeof *e->c0);
  e->open_t = malloc(2 * s->nj * sizeof *e->open_t);
  if (!e->q0 || !e->qprev || !e->c0 || !e->open_t) {
    aq_events_free(e);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
  }
  return AQ_OK;
}

void aq_events_free(aq_events *e)
{
  if (!e)
    return;
  free(e->q0);
  free(e->qprev);
  free(e->c0);
  free(e->open_t);
  memset(e, 0, sizeof *e);
}

/* Voussoir k's (or test body k's) centroid now. */
static aq_vec2 centroid(const aq_bodies *s, const double *q, const double *gx, size_t k)
{
  if (!s->nvous)
    return (aq_vec2){q[3 * k], q[3 * k + 1]};
  return aq_bodies_point(s, s->vous_body[k], q, gx, s->vous_c0[k]);
}

/* Voussoir 0's (test: body 0's) rotation. */
static double rot0(const aq_bodies *s, const double *q)
{
  int b = s->nvous ? s->vous_body[0] : 0;
  return b >= 0 ? q[3 * b + 2] : 0;
}

void aq_events_reset(aq_events *e, aq_moreau *m, const aq_hinge_set *sets, int history,
                     double dv_floor_j, aq_blocks_result *res)
{
  const aq_bodies *s = e->s;
  e->set = sets;
  e->history = history;
  e->dv_floor_j = dv_floor_j;
  e->started = 0;
  e->peak_rot = e->peak_disp = e->max_ke = e->energy_in = e->max_slip = 0;
  e->friction_work = 0;
  e->mech_changed = NAN;
  e->impacts = e->reversals = 0;
  e->away = 0;
  e->armed = 1;
  e->collapsed = 0;
  e->collapse_t = NAN;
  e->first_set = e->peak_set = -1;
  e->peak_set_rot[0] = e->peak_set_rot[1] = 0;
  for (size_t k = 0; k < 2 * s->nj; k++)
    e->open_t[k] = NAN;
  memcpy(e->q0, aq_moreau_q(m), 3 * s->nb * sizeof *e->q0);
  memcpy(e->qprev, e->q0, 3 * s->nb * sizeof *e->q0);
  res->nvous = s->nvous ? s->nvous : s->nb;
}

void aq_events_start(aq_events *e, aq_moreau *m, double t0)
{
  const aq_bodies *s = e->s;
  const double *q = aq_moreau_q(m), *gx = aq_moreau_gx(m);
  (void)t0;
  memcpy(e->q0, q, 3 * s->nb * sizeof *e->q0);
  memcpy(e->qprev, q, 3 * s->nb * sizeof *e->q0);
  size_t nv = s->nvous ? s->nvous : s->nb;
  for (size_t k = 0; k < nv; k++)
    e->c0[k] = centroid(s, q, gx, k);
  e->pe0 = aq_bodies_potential_j(s, q);
  e->started = 1;
}

/* 1 if (joint, face) is in the four-hinge set hs. */
static int in_set(const aq_hinge_set *hs, size_t joint, char face)
{
  for (int i = 0; i < 4; i++)
    if (hs->joint[i] == joint && hs->face[i] == face)
      return 1;
  return 0;
}

/* Which of the sets holds every open hinge: 0, 1, -1 none open, 2 neither. */
static int open_set(const aq_events *e, const double *q)
{
  const aq_bodies *s = e->s;
  int any = 0, in[2] = {1, 1};
  for (size_t j = 0; j < s->nj; j++) {
    int a = s->joint[j].a, b = s->joint[j].b;
    double rel = (b >= 0 ? q[3 * b + 2] : 0) - (a >= 0 ? q[3 * a + 2] : 0);
    rel -= (b >= 0 ? e->q0[3 * b + 2] : 0) - (a >= 0 ? e->q0[3 * a + 2] : 0);
    if (fabs(rel) <= AQ_BLOCKS_HINGE_OPEN_RAD)
      continue;
    any = 1;
    char face = rel > 0 ? 'i' : 'e';
    for (int k = 0; k < 2; k++)
      if (!e->set || !in_set(&e->set[k], s->joint[j].arch_joint, face))
        in[k] = 0;
  }
  return !any ? -1 : in[0] ? 0 : in[1] ? 1 : 2;
}

/* The slip of joint j: the tangential offset of its two faces from where
 * they stood undeformed.  While a corner is closed, its slip (the first
 * closed corner's, as the contacts take it); with both corners open (the
 * faces apart: a body in flight), the smaller of the two ends' slips, the
 * offset by which the faces' overlap falls short of its length, so that a
 * joint whose faces part in flight counts its offset at the step they
 * part (beyond the overlap's length: events_fallen ends the run there). */
static double joint_slip(const aq_bodies *s, const aq_corner *cr, const aq_jstate *st,
                         size_t j)
{
  double w = s->joint[j].width_m;
  for (int k = 0; k < 2; k++)
    if (aq_jstate_closed(st[j], k))
      return fabs(cr[2 * j + k].s_m - (k ? w : 0));
  return fmin(fabs(cr[2 * j].s_m), fabs(cr[2 * j + 1].s_m - w));
}

static void record_step(aq_events *e, aq_moreau *m, double t, double ax, double ay)
{
  const aq_bodies *s = e->s;
  const double *q = aq_moreau_q(m), *v = aq_moreau_v(m), *gx = aq_moreau_gx(m);
  /* work of the ground's inertia forces over the step */
  for (size_t b = 0; b < s->nb; b++)
    e->energy_in += -s->body[b].mass_kg *
                    (ax * (q[3 * b] - e->qprev[3 * b]) + ay * (q[3 * b + 1] - e->qprev[3 * b + 1]));
  double r0 = fabs(rot0(s, q) - rot0(s, e->q0));
  int set = open_set(e, q);
  if (e->first_set < 0 && (set == 0 || set == 1))
    e->first_set = set;
  if (set == 0 || set == 1)
    e->peak_set_rot[set] = fmax(e->peak_set_rot[set], r0);
  if (r0 > e->peak_rot) {
    e->peak_rot = r0;
    e->peak_set = set == 0 || set == 1 ? set : -1;
  }
  if (set == 2 && isnan(e->mech_changed) && e->set)
    e->mech_changed = t;
  size_t nv = s->nvous ? s->nvous : s->nb;
  for (size_t k = 0; k < nv; k++) {
    aq_vec2 c = centroid(s, q, gx, k);
    e->peak_disp = fmax(e->peak_disp, hypot(c.x - e->c0[k].x, c.y - e->c0[k].y));
  }
  e->max_ke = fmax(e->max_ke, aq_bodies_kinetic_j(s, v));
  /* hinges and slip */
  const aq_corner *cr = aq_moreau_corners(m);
  const aq_jstate *st = aq_moreau_jstate(m);
  for (size_t j = 0; j < s->nj; j++) {
    int a = s->joint[j].a, b = s->joint[j].b;
    double rel = (b >= 0 ? q[3 * b + 2] : 0) - (a >= 0 ? q[3 * a + 2] : 0);
    rel -= (b >= 0 ? e->q0[3 * b + 2] : 0) - (a >= 0 ? e->q0[3 * a + 2] : 0);
    if (fabs(rel) > AQ_BLOCKS_HINGE_OPEN_RAD) {
      double *ot = &e->open_t[2 * j + (rel > 0)];
      if (isnan(*ot))
        *ot = t;
    }
    e->max_slip = fmax(e->max_slip, joint_slip(s, cr, st, j));
  }
}

/* The displacement from the start times the velocity (mass metric). */
static double away_rate(const aq_events *e, const double *q, const double *v)
{
  const aq_bodies *s = e->s;
  double D = 0;
  for (size_t b = 0; b < s->nb; b++) {
    const double *qb = q + 3 * b, *q0 = e->q0 + 3 * b, *vb = v + 3 * b;
    D += s->body[b].mass_kg * ((qb[0] - q0[0]) * vb[0] + (qb[1] - q0[1]) * vb[1]) +
         s->body[b].inertia_kgm2 * (qb[2] - q0[2]) * vb[2];
  }
  return D;
}

int aq_events_fallen(const aq_events *e, aq_moreau *m)
{
  const aq_bodies *s = e->s;
  const double *q = aq_moreau_q(m);
  for (size_t b = 0; b < s->nb; b++)
    if (fabs(q[3 * b + 2] - e->q0[3 * b + 2]) > COLLAPSE_ROT_RAD)
      return 1;
  const aq_corner *cr = aq_moreau_corners(m);
  const aq_jstate *st = aq_moreau_jstate(m);
  for (size_t j = 0; j < s->nj; j++) {
    double w = s->joint[j].width_m;
    if (cr[2 * j].gap_m > w && cr[2 * j + 1].gap_m > w)
      return 1;
    /* the faces' overlap by the slip at a closed end, or at both ends of
     * an open joint (a body that left the other's face in flight would
     * land on its line beyond it) */
    double ov[2];
    for (int k = 0; k < 2; k++)
      ov[k] = aq_contact_overlap(s, j, cr[2 * j + k].s_m - (k ? w : 0));
    for (int k = 0; k < 2; k++)
      if (aq_jstate_closed(st[j], k) && ov[k] < 0)
        return 1;
    if (st[j].kind == AQ_JOINT_OPEN && ov[0] < 0 && ov[1] < 0)
      return 1;
  }
  return 0;
}

int aq_events_away(const aq_events *e, aq_moreau *m)
{
  return away_rate(e, aq_moreau_q(m), aq_moreau_v(m)) > 0;
}

/* The collapse rule (file comment): 1 fallen, 2 at the top of the hill
 * (the first step of it), else 0. */
static int collapse_rule(aq_events *e, aq_moreau *m)
{
  const aq_bodies *s = e->s;
  const double *q = aq_moreau_q(m), *v = aq_moreau_v(m);
  if (aq_events_fallen(e, m))
    return 1;
  double vy = 0;
  for (size_t b = 0; b < s->nb; b++)
    vy += s->body[b].mass_kg * v[3 * b + 1];
  int away = away_rate(e, q, v) > 0;
  if (e->away && !away)
    e->reversals++;
  e->away = away;
  /* moving away, going down, and up by a fraction of the arch's barrier */
  int top = away && vy < 0 && aq_bodies_potential_j(s, q) - e->pe0 >= e->dv_floor_j;
  int fire = top && e->armed;
  e->armed = !top;
  return fire ? 2 : 0;
}

int aq_events_step(aq_events *e, aq_moreau *m, double t, double h, double ax, double ay,
                   const aq_step_info *info, int record)
{
  (void)h;
  if (record && e->started) {
    record_step(e, m, t, ax, ay);
    e->impacts += info->impact != 0;
    e->friction_work -= info->friction_j;
  }
  memcpy(e->qprev, aq_moreau_q(m), 3 * e->s->nb * sizeof *e->qprev);
  int r = collapse_rule(e, m);
  if (r == 1)
    aq_events_collapse(e, t);
  return r;
}

void aq_events_collapse(aq_events *e, double t)
{
  e->collapsed = 1;
  e->collapse_t = t;
}

int aq_events_still(const aq_events *e, aq_moreau *m, double h)
{
  const aq_bodies *s = e->s;
  const double *v = aq_moreau_v(m);
  double tol = STILL_REL * s->g_mps2 * h;
  for (size_t b = 0; b < s->nb; b++)
    if (fabs(v[3 * b]) > tol || fabs(v[3 * b + 1]) > tol ||
        fabs(v[3 * b + 2]) * s->length_m > tol)
      return 0;
  return 1;
}

/* Grow the history's arrays to hold one more sample. */
static int grow(aq_blocks_result *res)
{
  aq_history *H = &res->r.history;
  if (H->n < H->cap)
    return 1;
  size_t cap = H->cap ? 2 * H->cap : 256, nv = res->nvous;
  double *p;
#define GROW(f, cnt)                                                                      \
  p = realloc((void *)(f), (cnt) * sizeof *(f));                                          \
  if (!p)                                                                                 \
    return 0;                                                                             \
  (f) = (void *)p;
  GROW(H->time_s, cap)
  GROW(H->rotation_rad, cap)
  GROW(H->displacement_m, cap)
  GROW(H->kinetic_energy_j, cap)
  GROW(H->potential_energy_j, cap)
  int *ip = realloc(H->set, cap * sizeof *H->set);
  if (!ip)
    return 0;
  H->set = ip;
  GROW(res->hist_x_m, cap * nv)
  GROW(res->hist_y_m, cap * nv)
  GROW(res->hist_rot_rad, cap * nv)
#undef GROW
  H->cap = cap;
  return 1;
}

aq_status aq_events_sample(aq_events *e, aq_moreau *m, double t, aq_blocks_result *res)
{
  if (!e->history)
    return AQ_OK;
  const aq_bodies *s = e->s;
  if (!grow(res))
    return AQ_ENOMEM;
  aq_history *H = &res->r.history;
  const double *q = aq_moreau_q(m), *v = aq_moreau_v(m), *gx = aq_moreau_gx(m);
  size_t i = H->n++, nv = res->nvous;
  double mx = 0, mx0 = 0, mt = 0;
  for (size_t k = 0; k < nv; k++) {
    aq_vec2 c = centroid(s, q, gx, k);
    int b = s->nvous ? s->vous_body[k] : (int)k;
    double mk = s->nvous ? s->vous_m[k] : s->body[k].mass_kg;
    res->hist_x_m[i * nv + k] = c.x;
    res->hist_y_m[i * nv + k] = c.y;
    res->hist_rot_rad[i * nv + k] = b >= 0 ? q[3 * b + 2] : 0;
    mx += mk * c.x;
    mx0 += mk * e->c0[k].x;
    mt += mk;
  }
  H->time_s[i] = t;
  H->rotation_rad[i] = rot0(s, q) - rot0(s, e->q0);
  H->displacement_m[i] = (mx - mx0) / mt;
  H->kinetic_energy_j[i] = aq_bodies_kinetic_j(s, v);
  H->potential_energy_j[i] = aq_bodies_potential_j(s, q) - e->pe0;
  int set = open_set(e, q);
  H->set[i] = H->kinetic_energy_j[i] == 0 && set < 0 ? -1 : set;
  return AQ_OK;
}

static int cmp_hinge(const void *a, const void *b)
{
  const aq_blocks_hinge *x = a, *y = b;
  if (x->joint != y->joint)
    return x->joint < y->joint ? -1 : 1;
  return (x->face > y->face) - (x->face < y->face);
}

void aq_events_finish(aq_events *e, aq_moreau *m, aq_blocks_result *res)
{
  const aq_bodies *s = e->s;
  aq_result *r = &res->r;
  r->collapsed = e->collapsed;
  r->collapse_time_s = e->collapsed ? e->collapse_t : NAN;
  r->peak_rotation_rad = e->peak_rot;
  r->peak_displacement_m = e->peak_disp;
  r->max_kinetic_energy_j = e->max_ke;
  r->energy_in_j = e->energy_in;
  double ke = aq_bodies_kinetic_j(s, aq_moreau_v(m)),
         pe = aq_bodies_potential_j(s, aq_moreau_q(m)) - e->pe0;
  r->energy_dissipated_j = e->started ? e->energy_in - ke - pe : 0;
  r->impacts = e->impacts;
  r->reversals = e->reversals;
  r->first_set = e->first_set;
  r->peak_set = e->peak_set;
  r->peak_rotation_set_rad[0] = e->peak_set_rot[0];
  r->peak_rotation_set_rad[1] = e->peak_set_rot[1];
  res->max_slip_m = e->max_slip;
  res->friction_work_j = e->friction_work;
  res->mechanism_changed_s = e->mech_changed;
  size_t nh = 0;
  for (size_t k = 0; k < 2 * s->nj; k++)
    nh += !isnan(e->open_t[k]);
  free(res->hinges);
  res->hinges = nh ? malloc(nh * sizeof *res->hinges) : NULL;
  res->nhinges = 0;
  for (size_t k = 0; k < 2 * s->nj && res->hinges; k++)
    if (!isnan(e->open_t[k]))
      res->hinges[res->nhinges++] =
          (aq_blocks_hinge){s->joint[k / 2].arch_joint, k % 2 ? 'i' : 'e', e->open_t[k]};
  if (res->nhinges)
    qsort(res->hinges, res->nhinges, sizeof *res->hinges, cmp_hinge);
}
