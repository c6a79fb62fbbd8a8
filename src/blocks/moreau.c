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
 * The problem is solved exactly, in one of two ways.  First the contact
 * state of the step before (which corners are closed, which joints stick
 * or slide) is taken as a guess: its conditions are then equations, solved
 * in O(n) along the chain (chain.c), and the solution is checked against
 * every inequality; a violated one changes the guess (a corner whose
 * impulse pulls opens, an open corner that would penetrate closes, a joint
 * whose friction exceeds mu N slides, a sliding joint that would reverse
 * sticks) and the chain is solved again, at most MAX_GUESSES times.  This
 * is the usual case: a rocking arch keeps its hinges from step to step.
 * Otherwise (a new mechanism, an impact that closes the arch, redundant
 * contacts) the whole problem goes to Siconos Numerics, Lemke's method on
 * its linear complementarity form (exact up to rounding), NSGS from
 * Lemke's answer if Lemke's fails the same check, and the state Siconos
 * finds is solved along the chain again when it determines the forces.
 * Every accepted solution meets every contact condition within
 * CHECK_REL of the step's velocity and impulse scales.
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

#include "model.h"

/* Chain solves per step before Siconos is asked; passes of a step whose
 * positions carried an open corner through its contact. */
enum { MAX_GUESSES = 8, MAX_LATE = 3 };
/* Impact stages per step (the global law): a sequence of impacts longer
 * than this ends in the step's plastic law. */
enum { MAX_STAGES = 100 };
/* The contact conditions of an accepted solution hold within this fraction
 * of the step's velocity scale (g h + the bodies' free velocities) and of
 * the impulse scale (the moving mass times it). */
static const double CHECK_REL = 1e-9;
/* Siconos's answers are checked within this (Lemke's pivots on the
 * problem's 3 nc LCP lose some digits on an ill-conditioned W). */
static const double SICONOS_CHECK_REL = 1e-7;
/* The activation threshold, per the bodies' length scale. */
static const double CLOSED_REL = 1e-9;
/* When no attempt meets its tolerance (Lemke's pivoting in double precision
 * on an ill-conditioned problem of 40-odd contacts: gothic, friction 0.6),
 * the best answer is taken if it meets this fraction of the scales. */
static const double LOOSE_REL = 1e-3;
/* Siconos's own stopping tolerance (relative to |q|). */
static const double SICONOS_TOL = 1e-13;

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

static aq_jstate from_closed(int c0, int c1, int slide)
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

/* The per-corner impulses of chain multipliers x for states st. */
static void impulses(aq_moreau *m, const aq_jstate *st, const double *x)
{
  memset(m->pn, 0, 2 * m->nj * sizeof *m->pn);
  memset(m->pt, 0, 2 * m->nj * sizeof *m->pt);
  size_t nr = aq_chain_nrows(m->chain);
  for (size_t r = 0; r < nr; r++) {
    size_t j;
    int kind;
    aq_chain_row(m->chain, r, &j, &kind);
    if (kind == AQ_CHAIN_ROW_T) {
      m->pt[2 * j + (aq_jstate_closed(st[j], 0) ? 0 : 1)] = x[r];
    } else {
      int k = kind == AQ_CHAIN_ROW_N1;
      m->pn[2 * j + k] = x[r];
      if (st[j].slide)
        m->pt[2 * j + k] = -(double)st[j].slide * m->mu * x[r];
    }
  }
}

/* Check the solution vnew with impulses pn, pt against every contact
 * condition of the active corners; when st is not NULL, change st where a
 * condition fails (the next guess).  Returns the number of failures. */
static int check(aq_moreau *m, aq_jstate *st, double tol_u, double tol_p)
{
  const aq_bodies *s = m->s;
  int bad = 0;
  for (size_t j = 0; j < m->nj; j++) {
    const unsigned char *act = m->active + 2 * j;
    if (!act[0] && !act[1])
      continue;
    aq_jstate cur = st ? st[j] : (aq_jstate){AQ_JOINT_OPEN, 0};
    int closed[2], want[2];
    double un[2], ut[2];
    for (int k = 0; k < 2; k++) {
      const aq_corner *C = &m->cr[2 * j + k];
      un[k] = aq_crow_dot(s, j, &C->n, m->vnew) + m->e_t * fmin(m->un0[2 * j + k], 0);
      ut[k] = aq_crow_dot(s, j, &C->t, m->vnew);
      closed[k] = st ? aq_jstate_closed(cur, k) : m->pn[2 * j + k] > tol_p;
      want[k] = closed[k];
    }
    int slide = cur.slide;
    double N = 0, T = 0;
    for (int k = 0; k < 2; k++) {
      if (!act[k])
        continue;
      double pn = m->pn[2 * j + k];
      if (pn < -tol_p) {
        want[k] = 0;
        bad++;
      } else if (!closed[k] && un[k] < -tol_u) {
        want[k] = 1;
        bad++;
      } else if (closed[k] && pn > tol_p && fabs(un[k]) > tol_u) {
        bad++; /* a pressed corner that moves off its contact (Siconos only) */
      }
      N += fmax(pn, 0);
      T += m->pt[2 * j + k];
    }
    int first = closed[0] ? 0 : 1;
    if (closed[0] || closed[1]) {
      if (fabs(T) > m->mu * N + tol_p) {
        slide = T > 0 ? -1 : 1;
        bad++;
      } else if (st && slide != 0 && slide * ut[first] <= tol_u) {
        /* not sliding that way: it sticks, or slides back (the sticking
         * solve then says which) */
        slide = 0;
        bad++;
      } else if (!st && fabs(T) < m->mu * N - tol_p && fabs(ut[first]) > tol_u) {
        bad++; /* Siconos: below the cone but slipping */
      } else if (!st && fabs(ut[first]) > tol_u && T * ut[first] > 0) {
        bad++; /* Siconos: friction along the slip */
      }
    }
    if (st) {
      if (!want[0] && !want[1])
        slide = 0;
      else if (!(closed[0] || closed[1]))
        slide = 0;
      st[j] = from_closed(want[0], want[1], slide);
    }
  }
  return bad;
}

/* Solve with the chain for states st (modified on failure); 1 when a
 * solution meets every condition, 0 when not after max guesses or the rows
 * are redundant.  *iters counts the solves. */
static int solve_chain(aq_moreau *m, aq_jstate *st, int max, int *iters)
{
  double tol_u = CHECK_REL * m->vscale, tol_p = CHECK_REL * m->pscale;
  size_t nr;
  for (int it = 0; it < max; it++) {
    if (aq_chain_factor(m->chain, m->cr, st, m->mu, 0, 0) != 0)
      return 0;
    ++*iters;
    nr = aq_chain_nrows(m->chain);
    aq_chain_rows_dot(m->chain, m->vfree, m->u);
    for (size_t r = 0; r < nr; r++) {
      size_t j;
      int kind;
      aq_chain_row(m->chain, r, &j, &kind);
      double target = kind == AQ_CHAIN_ROW_T
                          ? 0
                          : -m->e_t * fmin(m->un0[2 * j + (kind == AQ_CHAIN_ROW_N1)], 0);
      m->rhs[r] = target - m->u[r];
    }
    aq_chain_solve(m->chain, m->rhs, m->x);
    aq_chain_apply(m->chain, m->x, m->dv);
    for (size_t i = 0; i < 3 * m->nb; i++)
      m->vnew[i] = m->vfree[i] + m->dv[i];
    impulses(m, st, m->x);
    if (check(m, st, tol_u, tol_p) == 0)
      return 1;
  }
  return 0;
}

/* vnew, pn, pt from Siconos's (scaled) impulses fr of the nc active
 * corners cidx, times scale. */
static void from_impulses(aq_moreau *m, int nc, double scale)
{
  const aq_bodies *s = m->s;
  memcpy(m->vnew, m->vfree, 3 * m->nb * sizeof *m->vnew);
  memset(m->pn, 0, 2 * m->nj * sizeof *m->pn);
  memset(m->pt, 0, 2 * m->nj * sizeof *m->pt);
  for (int i = 0; i < nc; i++) {
    int c = m->cidx[i];
    size_t j = (size_t)c / 2;
    m->pn[c] = m->fr[2 * i] * scale;
    m->pt[c] = m->fr[2 * i + 1] * scale;
    int a = s->joint[j].a, b = s->joint[j].b;
    for (int d = 0; d < 3; d++) {
      double fa = m->cr[c].n.ga[d] * m->pn[c] + m->cr[c].t.ga[d] * m->pt[c];
      double fb = m->cr[c].n.gb[d] * m->pn[c] + m->cr[c].t.gb[d] * m->pt[c];
      if (a >= 0)
        m->vnew[3 * a + d] += m->minv[3 * a + d] * fa;
      if (b >= 0)
        m->vnew[3 * b + d] += m->minv[3 * b + d] * fb;
    }
  }
}

/* The whole problem by Siconos; 0 and vnew, pn, pt, or AQ_ENUMERIC. */
static aq_status solve_siconos(aq_moreau *m, int *pivots, int *loose, aq_error *err)
{
  double best_rel = INFINITY;
  const aq_bodies *s = m->s;
  int nc = 0;
  for (size_t c = 0; c < 2 * m->nj; c++)
    if (m->active[c])
      m->cidx[nc++] = (int)c;
  memcpy(m->vnew, m->vfree, 3 * m->nb * sizeof *m->vnew);
  memset(m->pn, 0, 2 * m->nj * sizeof *m->pn);
  memset(m->pt, 0, 2 * m->nj * sizeof *m->pt);
  if (nc == 0)
    return AQ_OK;
  int n = 2 * nc;
  /* W = H M^-1 H^T over the active corners' rows */
  for (int i = 0; i < n; i++) {
    int ci = m->cidx[i / 2];
    size_t ji = (size_t)ci / 2;
    const aq_crow *ri = i % 2 ? &m->cr[ci].t : &m->cr[ci].n;
    int ai = s->joint[ji].a, bi = s->joint[ji].b;
    for (int k = 0; k < n; k++) {
      int ck = m->cidx[k / 2];
      size_t jk = (size_t)ck / 2;
      const aq_crow *rk = k % 2 ? &m->cr[ck].t : &m->cr[ck].n;
      int ak = s->joint[jk].a, bk = s->joint[jk].b;
      double w = 0;
      const double *gi[2] = {ri->ga, ri->gb}, *gk[2] = {rk->ga, rk->gb};
      int bodi[2] = {ai, bi}, bodk[2] = {ak, bk};
      for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++)
          if (bodi[x] >= 0 && bodi[x] == bodk[y]) {
            const double *mi = m->minv + 3 * bodi[x];
            w += gi[x][0] * mi[0] * gk[y][0] + gi[x][1] * mi[1] * gk[y][1] +
                 gi[x][2] * mi[2] * gk[y][2];
          }
      m->W[i + (size_t)n * (size_t)k] = w;
    }
    m->fq[i] = aq_crow_dot(s, ji, ri, m->vfree) + (i % 2 ? 0 : m->e_t * fmin(m->un0[ci], 0));
    m->fr[i] = 0;
    if (i % 2 == 0)
      m->fmu[i / 2] = m->mu;
  }
  /* Lemke's method on the problem's LCP stalls on the redundant contacts
   * of closed joints (W singular: two corners, four unknowns, three
   * freedoms), and its pivoting tolerances are absolute: the problem goes
   * to it scaled (W by its largest diagonal entry, q by its largest
   * entry, so both are of order 1), with a compliance eps on W's diagonal
   * that makes it definite and changes velocities by eps of the scale.
   * Its pivoting still fails now and then on these degenerate problems
   * (the answer fails the check below, against the true W): it is tried
   * again with a larger compliance, then NSGS from its answer. */
  double dmax = 0, qmax = 0;
  for (int i = 0; i < n; i++) {
    m->fd[i] = m->W[i + (size_t)n * (size_t)i];
    dmax = fmax(dmax, m->fd[i]);
    qmax = fmax(qmax, fabs(m->fq[i]));
  }
  if (!(dmax > 0) || !(qmax > 0))
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "contact",
                        "a contact problem without a scale (W %g, q %g)", dmax, qmax);
  for (size_t i = 0; i < (size_t)n * (size_t)n; i++)
    m->W[i] /= dmax;
  for (int i = 0; i < n; i++) {
    m->fd[i] /= dmax;
    m->fq[i] /= qmax;
  }
  static const struct {
    aq_fc2d_solver solver;
    double eps;
  } attempts[] = {{AQ_FC2D_LEMKE, 1e-12}, {AQ_FC2D_AP, 1e-12}, {AQ_FC2D_LEMKE, 1e-10},
                  {AQ_FC2D_AP, 1e-10}, {AQ_FC2D_LEMKE, 1e-8}, {AQ_FC2D_NSGS, 1e-12}};
  for (size_t attempt = 0; attempt < sizeof attempts / sizeof attempts[0]; attempt++) {
    double eps = attempts[attempt].eps;
    for (int i = 0; i < n; i++)
      m->W[i + (size_t)n * (size_t)i] = m->fd[i] + eps;
    double rel = fmax(SICONOS_CHECK_REL, 100 * eps);
    double tol_u = rel * m->vscale, tol_p = rel * m->pscale;
    int it = 0;
    int info = aq_fc2d_solve(m->fc, attempts[attempt].solver, nc, m->W, m->fq, m->fmu,
                             SICONOS_TOL, m->fr, m->fu, &it);
    *pivots += it;
    if (info < 0)
      continue;
    from_impulses(m, nc, qmax / dmax);
    if (check(m, NULL, tol_u, tol_p) != 0) {
      /* the best so far of the answers that fail: by the tolerance they meet */
      for (double r = 10 * rel; r <= LOOSE_REL && r < best_rel; r *= 10)
        if (check(m, NULL, r * m->vscale, r * m->pscale) == 0) {
          best_rel = r;
          memcpy(m->best_r, m->fr, (size_t)n * sizeof *m->fr);
          break;
        }
      continue;
    }
    if (eps > attempts[0].eps) {
      /* polish a looser answer: NSGS from it at the first compliance */
      memcpy(m->keep_v, m->vnew, 3 * m->nb * sizeof *m->keep_v);
      memcpy(m->keep_pn, m->fr, (size_t)n * sizeof *m->fr); /* scaled impulses */
      for (int i = 0; i < n; i++)
        m->W[i + (size_t)n * (size_t)i] = m->fd[i] + attempts[0].eps;
      it = 0;
      info = aq_fc2d_solve(m->fc, AQ_FC2D_NSGS, nc, m->W, m->fq, m->fmu, SICONOS_TOL, m->fr,
                           m->fu, &it);
      *pivots += it;
      double r0 = SICONOS_CHECK_REL;
      if (info >= 0) {
        from_impulses(m, nc, qmax / dmax);
        if (check(m, NULL, r0 * m->vscale, r0 * m->pscale) == 0)
          return AQ_OK;
      }
      memcpy(m->fr, m->keep_pn, (size_t)n * sizeof *m->fr);
      from_impulses(m, nc, qmax / dmax);
    }
    return AQ_OK;
  }
  if (best_rel <= LOOSE_REL) {
    /* none met its tolerance: the best, within LOOSE_REL of the step's scales
     * (the chain then tries the state it gives, exactly) */
    memcpy(m->fr, m->best_r, (size_t)n * sizeof *m->fr);
    from_impulses(m, nc, qmax / dmax);
    ++*loose;
    return AQ_OK;
  }
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "contact",
                      "the frictional contact problem of %d contacts was not solved "
                      "(Siconos: Lemke, NSGS)",
                      nc);
}

/* The states of Siconos's solution (pn, pt, vnew) into st. */
static void states_of(aq_moreau *m, aq_jstate *st)
{
  double tol_p = SICONOS_CHECK_REL * m->pscale, tol_u = SICONOS_CHECK_REL * m->vscale;
  for (size_t j = 0; j < m->nj; j++) {
    int c0 = m->active[2 * j] && m->pn[2 * j] > tol_p;
    int c1 = m->active[2 * j + 1] && m->pn[2 * j + 1] > tol_p;
    int slide = 0;
    if (c0 || c1) {
      double ut = aq_crow_dot(m->s, j, &m->cr[2 * j + (c0 ? 0 : 1)].t, m->vnew);
      if (fabs(ut) > tol_u)
        slide = ut > 0 ? 1 : -1;
    }
    st[j] = from_closed(c0, c1, slide);
  }
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

/* The prepared problem solved: vnew, pn, pt and the states trial. */
static aq_status solve_problem(aq_moreau *m, aq_step_info *info, aq_error *err)
{
  size_t nc = 2 * m->nj, nb3 = 3 * m->nb;
  if (m->direct && solve_chain(m, m->trial, MAX_GUESSES, &info->iters))
    return AQ_OK;
  info->path = AQ_STEP_SICONOS;
  aq_status rc = solve_siconos(m, &info->pivots, &info->loose, err);
  if (rc != AQ_OK)
    return rc;
  states_of(m, m->trial);
  /* the same state along the chain, when it determines the impulses */
  memcpy(m->keep_v, m->vnew, nb3 * sizeof *m->keep_v);
  memcpy(m->keep_pn, m->pn, nc * sizeof *m->keep_pn);
  memcpy(m->keep_pt, m->pt, nc * sizeof *m->keep_pt);
  if (!(m->direct && solve_chain(m, m->trial, MAX_GUESSES, &info->iters))) {
    memcpy(m->vnew, m->keep_v, nb3 * sizeof *m->keep_v);
    memcpy(m->pn, m->keep_pn, nc * sizeof *m->keep_pn);
    memcpy(m->pt, m->keep_pt, nc * sizeof *m->keep_pt);
    states_of(m, m->trial);
  }
  return AQ_OK;
}

/* The impact stage of the global law (prepared without forces): the
 * plastic impact v_p (the step's problem with e = 0 and no force) and
 * v+ = v- + (1 + e_n) (v_p - v-); then the start velocities again. */
static aq_status impact_stage(aq_moreau *m, aq_step_info *info, aq_error *err)
{
  double e_t = m->e_t, ke0 = aq_bodies_kinetic_j(m->s, m->v), w0 = info->friction_j;
  m->e_t = 0;
  aq_status rc = solve_problem(m, info, err);
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
      aq_status rc = solve_problem(m, info, err);
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
