/* moreau.c: one Moreau-Jean time step of the bodies in frictional contact
 * (model.h).
 *
 * The scheme (J.J. Moreau 1988, Unilateral contact and dry friction in
 * finite freedom dynamics, in Nonsmooth Mechanics and Applications, CISM
 * 302, Springer, 1-82; M. Jean 1999, The non-smooth contact dynamics
 * method, Computer Methods in Applied Mechanics and Engineering 177,
 * 235-257; V. Acary and B. Brogliato 2008, Numerical Methods for Nonsmooth
 * Dynamical Systems, Springer, sec. 10.1, eq. (10.9)-(10.13)):
 *
 *   M (v+ - v-) = h f + H^T P            f = m (-ax, -(g + ay), 0) per body
 *   q+ = q + h (theta v+ + (1 - theta) v-)
 *
 * with, at every corner that is active (its gap predicted at the end of
 * the step, gap + h u_n-, at most the activation threshold), the contact
 * and Coulomb's friction at the level of velocities and impulses:
 * 0 <= P_n  perp  u_n+ + e_t min(u_n-, 0) >= 0,  |P_t| <= mu P_n, and
 * u_t+ = 0 while |P_t| < mu P_n, else P_t = -mu P_n sign(u_t+).
 *
 * Impacts (docs/blocks.md, "Impacts: the global law").  e_t = 0 but under
 * Newton's law per corner (AQ_IMPACT_NEWTON, kept for comparison: e_t =
 * e_n).  Under the global law, with e_n > 0, a step in which an open
 * corner lands (approaching, its predicted gap at most the activation
 * threshold, or carried through its contact by the step's positions)
 * first takes an impact
 * stage: the same problem from v- without the step's forces at e = 0 (the
 * plastic impact v_p) and v+ = v_p + e_n (v_p - v-), which changes the
 * kinetic energy by (e_n^2 - 1)/2 |v_p - v-|^2_M + (1 + e_n) u_t . P_t
 * (<= 0; 0 at e_n = 1 and a sticking impact); impacts that follow within
 * the step from v+ are staged in turn (a corner that lands, and a closed
 * one the stage sent into its contact); then the step from v+ at e = 0.
 *
 * The problem is solved exactly (moreau_solve.c): along the chain for the
 * contact state of the step before, checked and corrected, else by
 * Siconos Numerics.
 *
 * After each step the closed corners are projected back onto their
 * contacts (gap 0, and no slip at a sticking joint): without it, two
 * voussoirs that turn together drift apart by h^2 omega^2 d / 2 per step
 * (d the distance between their centroids: the scheme moves centroids
 * along straight lines), as the prototype of this model showed.  The
 * projection is the least change of configuration in the bodies' mass
 * metric that closes them (one Gauss-Newton step on the same rows, solved
 * along the chain), so the penetration left after a step is the rounding
 * of that solve, and within a step at most h |u_n| / 2 at the corner that
 * lands. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "moreau_impl.h"

/* Passes of a step whose positions carried an open corner through its
 * contact. */
enum { MAX_LATE = 3 };
/* Impact stages per step (the global law): a sequence of impacts longer
 * than this ends in the step's plastic law. */
enum { MAX_STAGES = 100 };
/* The activation threshold, per the bodies' length scale. */
static const double CLOSED_REL = 1e-9;


void aq_moreau_free(aq_moreau *m)
{
  if (!m)
    return;
  free(m->q);
  free(m->v);
  free(m->minv);
  free(m->st);
  free(m->trial);
  free(m->cr);
  free(m->cr1);
  free(m->cr2);
  free(m->un0);
  free(m->ut0);
  free(m->active);
  free(m->force);
  free(m->vstart);
  free(m->un_pre);
  free(m->proj);
  free(m->vfree);
  free(m->vnew);
  free(m->dv);
  free(m->q1);
  free(m->rhs);
  free(m->x);
  free(m->u);
  free(m->pn);
  free(m->pt);
  free(m->keep_v);
  free(m->keep_pn);
  free(m->keep_pt);
  aq_chain_free(m->chain);
  aq_fc2d_free(m->fc);
  free(m->cidx);
  free(m->W);
  free(m->fq);
  free(m->fr);
  free(m->fu);
  free(m->fmu);
  free(m->fd);
  free(m->best_r);
  free(m->sq);
  free(m->sv);
  free(m->sst);
  free(m);
}

aq_moreau *aq_moreau_alloc(const aq_bodies *s, aq_error *err)
{
  aq_moreau *m = calloc(1, sizeof *m);
  if (!m) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
    return NULL;
  }
  m->s = s;
  m->nb = s->nb;
  m->nj = s->nj;
  size_t nb3 = 3 * s->nb, nc = 2 * s->nj, nr = 3 * s->nj;
  m->q = malloc(nb3 * sizeof *m->q);
  m->v = calloc(nb3, sizeof *m->v);
  m->minv = malloc(nb3 * sizeof *m->minv);
  m->st = calloc(s->nj, sizeof *m->st);
  m->trial = calloc(s->nj, sizeof *m->trial);
  m->cr = calloc(nc, sizeof *m->cr);
  m->cr1 = calloc(nc, sizeof *m->cr1);
  m->cr2 = calloc(nc, sizeof *m->cr2);
  m->un0 = calloc(nc, sizeof *m->un0);
  m->ut0 = calloc(nc, sizeof *m->ut0);
  m->active = calloc(nc, 1);
  m->force = calloc(nc, 1);
  m->vstart = calloc(nb3, sizeof *m->vstart);
  m->un_pre = calloc(nc, sizeof *m->un_pre);
  m->proj = calloc(s->nj, sizeof *m->proj);
  m->vfree = calloc(nb3, sizeof *m->vfree);
  m->vnew = calloc(nb3, sizeof *m->vnew);
  m->dv = calloc(nb3, sizeof *m->dv);
  m->q1 = calloc(nb3, sizeof *m->q1);
  m->rhs = calloc(nr, sizeof *m->rhs);
  m->x = calloc(nr, sizeof *m->x);
  m->u = calloc(nr, sizeof *m->u);
  m->pn = calloc(nc, sizeof *m->pn);
  m->pt = calloc(nc, sizeof *m->pt);
  m->keep_v = calloc(nb3, sizeof *m->keep_v);
  m->keep_pn = calloc(2 * nc, sizeof *m->keep_pn); /* also scaled impulses of 2 nc rows */
  m->keep_pt = calloc(nc, sizeof *m->keep_pt);
  m->chain = aq_chain_alloc(s);
  m->fc = aq_fc2d_alloc();
  m->cidx = calloc(nc, sizeof *m->cidx);
  m->W = calloc(4 * nc * nc, sizeof *m->W);
  m->fq = calloc(2 * nc, sizeof *m->fq);
  m->fr = calloc(2 * nc, sizeof *m->fr);
  m->fu = calloc(2 * nc, sizeof *m->fu);
  m->fmu = calloc(nc, sizeof *m->fmu);
  m->fd = calloc(2 * nc, sizeof *m->fd);
  m->best_r = calloc(2 * nc, sizeof *m->best_r);
  m->sq = calloc(nb3, sizeof *m->sq);
  m->sv = calloc(nb3, sizeof *m->sv);
  m->sst = calloc(s->nj, sizeof *m->sst);
  if (!m->q || !m->v || !m->minv || !m->st || !m->trial || !m->cr || !m->cr1 || !m->cr2 || !m->un0 || !m->ut0 ||
      !m->active || !m->force || !m->vstart || !m->un_pre || !m->proj || !m->vfree || !m->vnew || !m->dv || !m->q1 || !m->rhs || !m->x ||
      !m->u || !m->pn || !m->pt || !m->keep_v || !m->keep_pn || !m->keep_pt || !m->chain || !m->fc || !m->cidx || !m->W || !m->fq ||
      !m->fr || !m->fu || !m->fmu || !m->fd || !m->best_r || !m->sq || !m->sv || !m->sst) {
    aq_moreau_free(m);
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
    return NULL;
  }
  for (size_t b = 0; b < s->nb; b++) {
    m->minv[3 * b] = m->minv[3 * b + 1] = 1 / s->body[b].mass_kg;
    m->minv[3 * b + 2] = 1 / s->body[b].inertia_kgm2;
  }
  m->mu = 1;
  m->theta = 0.5;
  m->direct = m->projection = 1;
  m->closed_m = CLOSED_REL * s->length_m;
  aq_moreau_reset(m);
  return m;
}

void aq_moreau_set(aq_moreau *m, double mu, double e_n, double theta, int direct,
                   int projection)
{
  m->mu = mu;
  m->e_n = e_n;
  m->e_t = m->law == AQ_IMPACT_NEWTON ? e_n : 0;
  m->theta = theta;
  m->direct = direct;
  m->projection = projection;
}

void aq_moreau_set_law(aq_moreau *m, aq_impact_law law)
{
  m->law = law;
  m->e_t = law == AQ_IMPACT_NEWTON ? m->e_n : 0;
}

void aq_moreau_reset(aq_moreau *m)
{
  aq_bodies_rest(m->s, m->q);
  memset(m->v, 0, 3 * m->nb * sizeof *m->v);
  m->gx[0] = m->gx[1] = m->gvx[0] = m->gvx[1] = 0;
  for (size_t j = 0; j < m->nj; j++)
    m->st[j] = (aq_jstate){AQ_JOINT_WELD, 0};
  m->cr_valid = 0;
}

void aq_moreau_save(aq_moreau *m)
{
  memcpy(m->sq, m->q, 3 * m->nb * sizeof *m->q);
  memcpy(m->sv, m->v, 3 * m->nb * sizeof *m->v);
  memcpy(m->sst, m->st, m->nj * sizeof *m->st);
  memcpy(m->sgx, m->gx, sizeof m->gx);
  memcpy(m->sgvx, m->gvx, sizeof m->gvx);
}

void aq_moreau_restore(aq_moreau *m)
{
  memcpy(m->q, m->sq, 3 * m->nb * sizeof *m->q);
  memcpy(m->v, m->sv, 3 * m->nb * sizeof *m->v);
  memcpy(m->st, m->sst, m->nj * sizeof *m->st);
  memcpy(m->gx, m->sgx, sizeof m->gx);
  memcpy(m->gvx, m->sgvx, sizeof m->gvx);
  m->cr_valid = 0;
}

double *aq_moreau_q(aq_moreau *m) { return m->q; }
double *aq_moreau_v(aq_moreau *m) { return m->v; }
const double *aq_moreau_gx(const aq_moreau *m) { return m->gx; }
const aq_jstate *aq_moreau_jstate(const aq_moreau *m) { return m->st; }
double aq_moreau_closed_m(const aq_moreau *m) { return m->closed_m; }

void aq_moreau_closed(aq_moreau *m, unsigned char *closed)
{
  const aq_corner *cr = aq_moreau_corners(m);
  for (size_t c = 0; c < 2 * m->nj; c++)
    closed[c] = aq_jstate_closed(m->st[c / 2], (int)(c % 2)) || cr[c].gap_m <= m->closed_m;
}

static void eval_corners(aq_moreau *m, const double *q, const double gx[2],
                         const double gvx[2], aq_corner *cr)
{
  for (size_t j = 0; j < m->nj; j++)
    aq_contact_eval(m->s, j, q, gx, gvx, cr + 2 * j);
}

const aq_corner *aq_moreau_corners(aq_moreau *m)
{
  if (!m->cr_valid) {
    eval_corners(m, m->q, m->gx, m->gvx, m->cr);
    m->cr_valid = 1;
  }
  return m->cr;
}

/* The state st restricted to the active corners. */
static aq_jstate mask(aq_jstate st, const unsigned char *act)
{
  int c0 = aq_jstate_closed(st, 0) && act[0], c1 = aq_jstate_closed(st, 1) && act[1];
  aq_jstate r = {c0 && c1 ? AQ_JOINT_WELD
                 : c0     ? AQ_JOINT_HINGE_I
                 : c1     ? AQ_JOINT_HINGE_E
                          : AQ_JOINT_OPEN,
                 st.slide};
  if (r.kind == AQ_JOINT_OPEN)
    r.slide = 0;
  return r;
}


/* Close the closed corners of states st at q1 (rows at q, corners at q1
 * in cr1): gap 0, and no change of s at a sticking joint. */
static void project(aq_moreau *m, const aq_jstate *st0, double *q1, const double gx1[2])
{
  /* the closed corners, and the open ones left inside their contact (a
   * corner that landed and left within the step, by at most h |u_n-| / 2,
   * or one the projection of the others pushes in): those only pushed out
   * (no tangential row: a joint without a closed corner is taken as
   * sliding); a pass that pushes an open corner in is made again with it */
  aq_jstate *st = m->proj;
  for (size_t j = 0; j < m->nj; j++)
    st[j] = st0[j];
  memcpy(m->keep_v, q1, 3 * m->nb * sizeof *q1);
  for (int pass = 0; pass < 2 * MAX_LATE; pass++) {
    int added = 0;
    const aq_corner *now = pass ? m->cr2 : m->cr1;
    for (size_t j = 0; j < m->nj; j++) {
      int c[2], any = 0;
      for (int k = 0; k < 2; k++) {
        c[k] = aq_jstate_closed(st[j], k);
        if (!c[k] && now[2 * j + k].gap_m < -m->closed_m)
          c[k] = added = 1;
        any |= aq_jstate_closed(st0[j], k);
      }
      st[j] = from_closed(c[0], c[1], any ? st0[j].slide : 1);
    }
    if (pass > 0 && !added)
      return;
    memcpy(q1, m->keep_v, 3 * m->nb * sizeof *q1);
    aq_chain_factor(m->chain, m->cr, st, m->mu, 1, 1);
    size_t nr = aq_chain_nrows(m->chain);
    if (nr == 0)
      return;
    for (size_t r = 0; r < nr; r++) {
      size_t j;
      int kind;
      aq_chain_row(m->chain, r, &j, &kind);
      if (kind == AQ_CHAIN_ROW_T) {
        /* the joint's tangential position as it was at the corner that was
         * closed before the step (a landing corner's own s was that of an
         * open joint, off by w (1 - cos phi)) */
        int k = aq_jstate_closed(st[j], 0) ? 0 : 1, p = k;
        if (!aq_jstate_closed(m->st[j], k) && aq_jstate_closed(m->st[j], 1 - k))
          p = 1 - k;
        double w = m->s->joint[j].width_m, s0 = m->cr[2 * j + p].s_m - (p - k) * w;
        /* plus the slip of a joint that slid at the step's start and
         * sticks at its end (the scheme's h (1 - theta) u_t-) */
        if (m->st[j].slide != 0)
          s0 += m->h * (1 - m->theta) * m->ut0[2 * j + p];
        m->rhs[r] = -(m->cr1[2 * j + k].s_m - s0);
      } else {
        m->rhs[r] = -m->cr1[2 * j + (kind == AQ_CHAIN_ROW_N1)].gap_m;
      }
    }
    aq_chain_solve(m->chain, m->rhs, m->x);
    aq_chain_apply(m->chain, m->x, m->dv);
    for (size_t i = 0; i < 3 * m->nb; i++)
      q1[i] += m->dv[i];
    eval_corners(m, q1, gx1, m->gvx, m->cr2);
  }
}

/* The rows' velocities at the step's start (at v, rows cr). */
static void start_velocities(aq_moreau *m)
{
  for (size_t c = 0; c < 2 * m->nj; c++) {
    m->un0[c] = aq_crow_dot(m->s, c / 2, &m->cr[c].n, m->v);
    m->ut0[c] = aq_crow_dot(m->s, c / 2, &m->cr[c].t, m->v);
  }
}

/* The step's problem at the start velocities: the active corners, the
 * free velocities (forces 0: none, v itself, for the impact stage), the
 * scales and the guess.  Returns 1 if an active corner that was open
 * lands within the step with an approach velocity (an impact), or, after
 * an impact stage of the step (global law), a closed one approaches faster
 * than at the step's start. */
static int prepare(aq_moreau *m, double h, double ax, double ay, const double gvx1[2],
                   int forces)
{
  const aq_bodies *s = m->s;
  size_t nc = 2 * m->nj;
  /* under the global law a corner predicted within the activation
   * threshold lands too (at e = 0 the count of impacts is as it was) */
  int impact = 0, global = m->law == AQ_IMPACT_GLOBAL && m->e_n > 0;
  /* active: closed in the step before (its rate, evaluated in the new
   * configuration, is O(h omega^2 d) either way), or predicted closed */
  for (size_t c = 0; c < nc; c++)
    m->active[c] = aq_jstate_closed(m->st[c / 2], (int)(c % 2)) ||
                   m->cr[c].gap_m + h * m->un0[c] <= m->closed_m || m->force[c];
  /* the free velocities */
  double vmax = 0;
  for (size_t b = 0; b < m->nb; b++) {
    double *vf = m->vfree + 3 * b;
    const double *v = m->v + 3 * b;
    vf[0] = forces ? v[0] - h * ax : v[0];
    vf[1] = forces ? v[1] - h * (s->g_mps2 + ay) : v[1];
    vf[2] = v[2];
    vmax = fmax(vmax, fmax(fmax(fabs(vf[0]), fabs(vf[1])), fabs(vf[2]) * s->length_m));
  }
  vmax = fmax(vmax, fmax(fabs(gvx1[0]), fabs(gvx1[1])));
  m->vscale = s->g_mps2 * h + vmax;
  m->pscale = s->mass_kg * m->vscale;
  for (size_t j = 0; j < m->nj; j++) {
    m->trial[j] = mask(m->st[j], m->active + 2 * j);
    for (int k = 0; k < 2; k++)
      if (m->active[2 * j + k] && m->un0[2 * j + k] < -CHECK_REL * m->vscale &&
          (m->cr[2 * j + k].gap_m + h * m->un0[2 * j + k] < 0 || m->force[2 * j + k] ||
           (global && m->cr[2 * j + k].gap_m + h * m->un0[2 * j + k] <= m->closed_m)) &&
          !aq_jstate_closed(m->st[j], k))
        impact = 1;
      else if (global && m->staged && aq_jstate_closed(m->st[j], k) &&
               m->un0[2 * j + k] < -CHECK_REL * m->vscale &&
               m->un0[2 * j + k] < m->un_pre[2 * j + k] - CHECK_REL * m->vscale)
        /* a corner closed before the step that an impact stage of this
         * step sent into its contact (it was lifting, and the plastic
         * impact stopped it without pressing it: v+ = 2 v_p - v- reverses
         * its velocity): its impact follows, as any other's */
        impact = 1;
  }
  return impact;
}

/* The impact stage of the global law (prepared without forces): the
 * plastic impact v_p (the step's problem with e = 0 and no force) and
 * v+ = v- + (1 + e_n) (v_p - v-); then the start velocities again. */
static aq_status impact_stage(aq_moreau *m, aq_step_info *info, aq_error *err)
{
  double e_t = m->e_t, ke0 = aq_bodies_kinetic_j(m->s, m->v), w0 = info->friction_j;
  m->e_t = 0;
  aq_status rc = aq_moreau_solve(m, info, err);
  m->e_t = e_t;
  if (rc != AQ_OK)
    return rc;
  /* the friction's work: (1 + e) u_t . P_t at v_p (0 at a sticking impact) */
  for (size_t c = 0; c < 2 * m->nj; c++)
    if (m->pt[c] != 0)
      info->friction_j +=
          (1 + m->e_n) * m->pt[c] * aq_crow_dot(m->s, c / 2, &m->cr[c].t, m->vnew);
  for (size_t i = 0; i < 3 * m->nb; i++)
    m->v[i] += (1 + m->e_n) * (m->vnew[i] - m->v[i]);
  info->stage_err_j += aq_bodies_kinetic_j(m->s, m->v) - ke0 - (info->friction_j - w0);
  start_velocities(m);

  return AQ_OK;
}

aq_status aq_moreau_step(aq_moreau *m, double h, double ax, double ay, const double gx1[2],
                         aq_step_info *info, aq_error *err)
{
  size_t nc = 2 * m->nj, nb3 = 3 * m->nb;
  int global = m->law == AQ_IMPACT_GLOBAL && m->e_n > 0;
  memset(info, 0, sizeof *info);
  double gvx1[2] = {(gx1[0] - m->gx[0]) / h, (gx1[1] - m->gx[1]) / h};
  /* the corners at q; the normal velocities before the step */
  aq_moreau_corners(m);
  m->h = h;
  start_velocities(m);
  if (gvx1[0] != m->gvx[0] || gvx1[1] != m->gvx[1])
    eval_corners(m, m->q, m->gx, gvx1, m->cr);
  if (global) {
    memcpy(m->vstart, m->v, nb3 * sizeof *m->v);
    memcpy(m->un_pre, m->un0, nc * sizeof *m->un0);
  }
  for (int redo = 0;; redo++) {
    m->staged = 0;
    info->stage = 0;
    info->friction_j = 0;
    info->stage_err_j = 0;
    info->impact = prepare(m, h, ax, ay, gvx1, 1);
    /* the global law: the impact first, apart from the step's forces,
     * then the step with e = 0 from its velocities; an impact that sends
     * other corners into their contacts within the step is followed by
     * theirs (a sequence of impacts, each keeping the energy at e = 1) */
    for (int k = 0; info->impact && global && k < MAX_STAGES; k++) {
      prepare(m, h, ax, ay, gvx1, 0);
      aq_status rc = impact_stage(m, info, err);
      if (rc != AQ_OK)
        return rc;
      info->stage++;
      m->staged = 1;
      if (!prepare(m, h, ax, ay, gvx1, 1))
        break;
    }
    /* solve; a corner left out as open that the step's positions carry
     * through its contact (its predicted gap missed the step's
     * acceleration) joins the problem and the step is solved again; under
     * the global law one that approaches lands in the impact stage: the
     * step is taken again from its start with it */
    int again = 0;
    for (int pass = 0;; pass++) {
      aq_status rc = aq_moreau_solve(m, info, err);
      if (rc != AQ_OK)
        return rc;
      /* positions */
      for (size_t i = 0; i < nb3; i++)
        m->q1[i] = m->q[i] + h * (m->theta * m->vnew[i] + (1 - m->theta) * m->v[i]);
      eval_corners(m, m->q1, gx1, gvx1, m->cr1);
      int late = 0;
      for (size_t c = 0; c < nc; c++)
        if (!m->active[c] && m->cr1[c].gap_m < -m->closed_m) {
          m->active[c] = 1;
          late = 1;
          if (global && redo < MAX_LATE && m->un0[c] < -CHECK_REL * m->vscale)
            m->force[c] = again = 1;
          else if (global && m->un0[c] < -CHECK_REL * m->vscale)
            info->late_plastic = 1;
        }
      if (again || !late || pass == MAX_LATE)
        break;
    }
    if (!again)
      break;
    memcpy(m->v, m->vstart, nb3 * sizeof *m->v);
    start_velocities(m);
  }
  if (global)
    memset(m->force, 0, nc);
  /* the friction's work at the joints that slide at the step's start or
   * end, or close, open or change corners in it: P_t times the tangential
   * velocity at the step's middle.  After an impact stage a joint whose
   * state sticks may slide at the step's start (the stage left its
   * tangential velocity, -e_n times that before, at a corner the plastic
   * impact stuck): stopping it is the friction's work too.  A joint that
   * sticks throughout does work only by the scheme's error (stick_j). */
  for (size_t c = 0; c < nc; c++) {
    if (m->pt[c] == 0)
      continue;
    double w = m->pt[c] * 0.5 * (aq_crow_dot(m->s, c / 2, &m->cr[c].t, m->vnew) + m->ut0[c]);
    if (m->trial[c / 2].slide != 0 || m->st[c / 2].slide != 0 ||
        m->trial[c / 2].kind != m->st[c / 2].kind ||
        (info->stage > 0 && fabs(m->ut0[c]) > SICONOS_CHECK_REL * m->vscale))
      info->friction_j += w;
    else
      info->stick_j += w;
  }
  m->gvx[0] = gvx1[0];
  m->gvx[1] = gvx1[1];
  if (m->projection) {
    double pe0 = aq_bodies_potential_j(m->s, m->q1);
    project(m, m->trial, m->q1, gx1);
    info->proj_pe_j = aq_bodies_potential_j(m->s, m->q1) - pe0;
  }
  memcpy(m->q, m->q1, nb3 * sizeof *m->q);
  memcpy(m->v, m->vnew, nb3 * sizeof *m->v);
  m->gx[0] = gx1[0];
  m->gx[1] = gx1[1];
  memcpy(m->st, m->trial, m->nj * sizeof *m->st);
  m->cr_valid = 0;
  return AQ_OK;
}

aq_status aq_moreau_impact(aq_moreau *m, double h, aq_step_info *info, aq_error *err)
{
  memset(info, 0, sizeof *info);
  m->cr_valid = 0;
  aq_moreau_corners(m);
  m->h = h;
  m->staged = 0;
  start_velocities(m);
  info->impact = prepare(m, h, 0, 0, m->gvx, 0);
  if (!info->impact)
    return AQ_OK;
  info->stage = 1;
  return impact_stage(m, info, err);
}

void aq_moreau_set_state(aq_moreau *m, const double *q, const double *v, const aq_jstate *st)
{
  memcpy(m->q, q, 3 * m->nb * sizeof *m->q);
  memcpy(m->v, v, 3 * m->nb * sizeof *m->v);
  memcpy(m->st, st, m->nj * sizeof *m->st);
  m->cr_valid = 0;
}

void aq_moreau_gravity_accel(aq_moreau *m, double *acc)
{
  const aq_bodies *s = m->s;
  aq_moreau_corners(m);
  for (size_t j = 0; j < m->nj; j++) {
    m->trial[j] = m->st[j];
    m->trial[j].slide = 0;
  }
  memset(acc, 0, 3 * m->nb * sizeof *acc);
  if (aq_chain_factor(m->chain, m->cr, m->trial, m->mu, 1, 0) != 0)
    return; /* redundant rows: no mechanism (at most two open hinges) */
  size_t nr = aq_chain_nrows(m->chain);
  /* unit time: free acceleration -g on every body, rows' rates 0 */
  for (size_t b = 0; b < m->nb; b++)
    m->vfree[3 * b + 1] = -s->g_mps2, m->vfree[3 * b] = m->vfree[3 * b + 2] = 0;
  aq_chain_rows_dot(m->chain, m->vfree, m->u);
  for (size_t r = 0; r < nr; r++)
    m->rhs[r] = -m->u[r];
  aq_chain_solve(m->chain, m->rhs, m->x);
  aq_chain_apply(m->chain, m->x, m->dv);
  for (size_t i = 0; i < 3 * m->nb; i++)
    acc[i] = m->vfree[i] + m->dv[i];
}
