/* moreau_solve.c: the contact problem of one Moreau-Jean step (moreau.c)
 * solved exactly.
 *
 * The problem: at every active corner the contact and Coulomb's friction
 * at the level of velocities and impulses, 0 <= P_n perp u_n+ +
 * e_t min(u_n-, 0) >= 0, |P_t| <= mu P_n, u_t+ = 0 while |P_t| < mu P_n,
 * else P_t = -mu P_n sign(u_t+), with v+ = vfree + M^-1 H^T P.  First the
 * contact state of the step before (which corners are closed, which joints
 * stick or slide) is taken as a guess: its conditions are then equations,
 * solved in O(n) along the chain (chain.c), and the solution is checked
 * against every inequality; a violated one changes the guess (a corner
 * whose impulse pulls opens, an open corner that would penetrate closes, a
 * joint whose friction exceeds mu N slides, a sliding joint that would
 * reverse sticks) and the chain is solved again, at most MAX_GUESSES
 * times.  This is the usual case: a rocking arch keeps its hinges from
 * step to step.  Otherwise (a new mechanism, an impact that closes the
 * arch, redundant contacts) the whole problem goes to Siconos Numerics,
 * Lemke's method on its linear complementarity form (exact up to
 * rounding), then Anitescu and Potra's form, NSGS from Lemke's answer if
 * Lemke's fails the same check, and the state Siconos finds is solved
 * along the chain again when it determines the forces.  Every accepted
 * solution meets every contact condition within CHECK_REL of the step's
 * velocity and impulse scales (SICONOS_CHECK_REL for Siconos's own). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "moreau_impl.h"

/* Chain solves per step before Siconos is asked. */
enum { MAX_GUESSES = 8 };
/* When no attempt meets its tolerance (Lemke's pivoting in double precision
 * on an ill-conditioned problem of 40-odd contacts: gothic, friction 0.6),
 * the best answer is taken if it meets this fraction of the scales. */
static const double LOOSE_REL = 1e-3;
/* Siconos's own stopping tolerance (relative to |q|). */
static const double SICONOS_TOL = 1e-13;

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

/* The prepared problem solved: vnew, pn, pt and the states trial. */
aq_status aq_moreau_solve(aq_moreau *m, aq_step_info *info, aq_error *err)
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

