/* friction.c: the static theorem of limit analysis with Coulomb friction
 * at the joints, as linear programs (lp4.c, GLPK).
 *
 * A line of thrust of the arch under its weight and a horizontal body
 * force lambda g per unit mass (along -act_sign x: the inertia force of a
 * ground acceleration lambda g of sign act_sign) is given, as in the
 * mechanism search (search.c), by the force (R0x, R0y) and moment m0 that
 * the ground exerts across joint 0: the resultant carried across joint j
 * is then
 *
 *   F_j = (R0x + s lambda g m_j,  R0y - g m_j)        (s = -act_sign)
 *
 * with m_j the mass of voussoirs 0..j-1 (fill and point masses included),
 * and its moments about the joint's ends are linear in (R0x, R0y, m0,
 * lambda) (search.c's rows): the line lies inside the arch when at every
 * joint the moment about the intrados end is >= 0 and about the extrados
 * end <= 0, which also makes the normal force N_j = F_j . n_j >= 0 (n_j the
 * joint's unit normal into voussoir j).  With T_j = F_j . u_j (u_j along
 * the joint, intrados to extrados) Coulomb's condition |T_j| <= mu N_j is
 * two more linear rows per joint,
 *
 *   ( u_j - mu n_j) . F_j <= 0,     (-u_j - mu n_j) . F_j <= 0,
 *
 * so that in the plane the friction cone is exact, not linearised
 * (Gilbert, Casapulla & Ahmed 2006, "Limit analysis of masonry block
 * structures with non-associative frictional joints using linear
 * programming", Computers & Structures 84(13-14), 873-887, eq. (1)-(4),
 * whose contact forces at a joint's two corners sum to the resultant used
 * here).  A resultant with |T| <= mu N between the joint's ends splits into
 * two corner forces parallel to it, each inside the cone, and two corner
 * forces inside the cone sum to such a resultant, so the two forms are the
 * same program.
 *
 * aq_friction_lambda maximizes lambda over these rows: by the static
 * (lower-bound) theorem the largest lambda at which some line of thrust
 * stands with friction mu.  With friction the theorem is a bound, not the
 * collapse load (the flow rule of Coulomb friction is not associated: the
 * joints slide without dilating), so lambda_friction is the load that
 * archquake's rigid, non-sliding model may be trusted to: up to it a
 * line of thrust within the arch and within every joint's friction cone
 * exists.  Without friction (mu INFINITY) the rows are the search's, and
 * the optimum is the arch's minimum multiplier over every mechanism of that
 * direction (the kinematic theorem: the dual of the program), lambda0 of
 * the direction's minimum four-hinge set, or below it where a mechanism
 * with a joint lifting off governs (search.c).
 *
 * aq_friction_least finds, at a given lambda, the least mu for which such
 * a line exists: min over the lines of thrust of max_j |T_j| / N_j, a
 * generalised fractional program, solved by the Dinkelbach-type method of
 * Crouzeix, Ferland & Schaible 1985 ("An algorithm for generalized
 * fractional programs", Journal of Optimization Theory and Applications
 * 47(1), 35-49): with mu_k the largest ratio of the line x_k found so far,
 * the next line minimizes max_j (|T_j| - mu_k N_j) / N_j(x_k), a linear
 * program, and mu_{k+1} is its largest ratio; the mu_k decrease to the
 * least friction, each the largest ratio of an actual line of thrust.
 * The arch's table of it over the load is friction_table.c's.
 *
 * Forces are scaled by the arch's weight W = m_T g and moments by W L (L
 * the joints' extent), as in search.c.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "friction.h"
#include "model.h"

#define OPT_TOL 1e-13      /* a row (scaled) violated by more at GLPK's vertex: solved again
                              in rational arithmetic (as search.c) */
#define TIGHT_REL 1e-9     /* a row within this of its bound counts as tight */
#define LEAST_MU_START 1e3 /* the first trial friction of aq_friction_least (any value
                              works: the iteration falls from the first line's ratio) */
#define LEAST_REL 1e-12    /* aq_friction_least stops when mu falls by less (relative) */
#define LEAST_ITER 60      /* programs at most; unsettled after them: an error (the most
                              measured is 21: docs/arch-model.md) */
#define LEAST_W_FLOOR 1e-3 /* a friction row's weight at least this times the largest
                              (weights()) */
#define LEAST_TIE 1e-9     /* joints whose ratios differ by less (relative) tie: the lowest is
                              named (the least-friction line often needs it at several) */

/* The friction rows of joint j for direction s and friction mu: rows[0]
 * (u - mu n) . F <= 0 and rows[1] (-u - mu n) . F <= 0, F/W in the
 * program's unknowns (R0x/W, R0y/W, m0/(W L), lambda). */
static void friction_rows(const aq_geom *g, size_t j, int s, double mu, aq_lp4_row rows[2])
{
  aq_vec2 pi = aq_geom_joint_point(g, j, 'i'), pe = aq_geom_joint_point(g, j, 'e');
  double len = hypot(pe.x - pi.x, pe.y - pi.y);
  aq_vec2 u = {(pe.x - pi.x) / len, (pe.y - pi.y) / len}, n = {-u.y, u.x};
  double mj = g->cum_m[j] / g->mass_kg;
  for (int k = 0; k < 2; k++) {
    double sg = k ? -1.0 : 1.0;
    aq_vec2 v = {sg * u.x - mu * n.x, sg * u.y - mu * n.y};
    /* F/W = (R0x/W + s lambda m_j/m_T, R0y/W - m_j/m_T) */
    rows[k].g[0] = v.x;
    rows[k].g[1] = v.y;
    rows[k].g[2] = 0;
    rows[k].g[3] = (double)s * v.x * mj;
    rows[k].h = v.y * mj;
  }
}

/* N_j and T_j (scaled by W) of joint j at the program's x (lambda in x[3]). */
static void joint_force(const aq_geom *g, size_t j, int s, const double x[4], double *nf,
                        double *tf)
{
  aq_vec2 pi = aq_geom_joint_point(g, j, 'i'), pe = aq_geom_joint_point(g, j, 'e');
  double len = hypot(pe.x - pi.x, pe.y - pi.y);
  aq_vec2 u = {(pe.x - pi.x) / len, (pe.y - pi.y) / len};
  double mj = g->cum_m[j] / g->mass_kg;
  aq_vec2 f = {x[0] + (double)s * x[3] * mj, x[1] - mj};
  *nf = -f.x * u.y + f.y * u.x;
  *tf = f.x * u.x + f.y * u.y;
}

/* A program of nrows rows that ended without its optimum (st): the error,
 * on "friction", of the caller expecting what. */
static aq_status lp_failed(aq_error *err, aq_lp4_status st, size_t nrows, const char *what)
{
  if (st == AQ_LP4_ITLIM)
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                        "expected %s, got a linear program of %zu rows that GLPK's simplex "
                        "left unsolved at its limit of %d iterations",
                        what, nrows, aq_lp4_iteration_limit(nrows));
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                      "expected %s, got a linear program that GLPK failed to solve", what);
}

aq_status aq_friction_lambda(const aq_geom *g, int act_sign, double mu, double *lambda,
                             size_t *joint, aq_error *err)
{
  if (aq_glpk_load(err) != AQ_OK)
    return AQ_EUNSUPPORTED;
  size_t n = g->p.voussoirs, nm = 2 * (n + 1);
  int fr = mu > 0 && isfinite(mu), s = act_sign < 0 ? 1 : -1;
  size_t nrows = nm + (fr ? nm : 0);
  aq_lp4_row *row = malloc(nrows * sizeof *row);
  if (!row)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  aq_thrust_rows(g, s, 0, row);
  for (size_t j = 0; fr && j <= n; j++)
    friction_rows(g, j, s, mu, row + nm + 2 * j);
  static const double c[4] = {0, 0, 0, 1};
  const aq_lp4_opts o = {OPT_TOL, TIGHT_REL, AQ_LP4_MAX_TIGHT, 0};
  aq_lp4_result r = {.y = NULL};
  aq_lp4_status st = aq_lp4_solve(row, nrows, c, NULL, &o, &r);
  free(row);
  if (st == AQ_LP4_INFEASIBLE)
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "friction",
                        "expected a line of thrust within the arch and within friction %g at "
                        "some horizontal load, got none", mu);
  if (st == AQ_LP4_UNBOUNDED) { /* no mechanism of that direction at all */
    *lambda = INFINITY;
    if (joint)
      *joint = SIZE_MAX;
    return AQ_OK;
  }
  if (st != AQ_LP4_OPT) {
    char what[96];
    snprintf(what, sizeof what, "the largest load of a line of thrust with friction %g", mu);
    return lp_failed(err, st, nrows, what);
  }
  *lambda = r.obj;
  if (joint) { /* a friction row of the vertex: the joint that slides */
    *joint = SIZE_MAX;
    for (size_t k = 0; k < r.nbasic && *joint == SIZE_MAX; k++)
      if (r.tight[k] >= nm)
        *joint = (r.tight[k] - nm) / 2;
  }
  return AQ_OK;
}

int aq_friction_least_cap = 0;

/* The weights of the next program's friction rows from the normal forces
 * w[0..n) of the line found (N_j / W): each its own, but at least
 * LEAST_W_FLOOR times the largest (1 where none pushes).  Crouzeix, Ferland
 * & Schaible weigh row j by N_j at the last line, for a superlinear rate;
 * any positive weights keep the method's two properties (a program of
 * optimum t < 0 gives a line whose every ratio is below mu_k; t = 0 proves
 * mu_k the least), so the floor costs at most some rate.  Without it a
 * line with one joint barely pushing (N/W about 1e-15 on a thick
 * 120-degree circle, from the line of the table's previous node) scaled
 * that joint's rows by 1e15: GLPK's vertex of such a program is its
 * round-off, and the method stalled at 1.4e4 where the least is 1.06. */
static void weights(double *w, size_t n)
{
  double top = 0;
  for (size_t j = 0; j < n; j++)
    top = fmax(top, w[j]);
  for (size_t j = 0; j < n; j++)
    w[j] = w[j] > 0 ? fmax(w[j], LEAST_W_FLOOR * top) : 1;
}

/* friction.h */
aq_status aq_friction_least_from(const aq_geom *g, int act_sign, double lambda, double mu0,
                                 const double *x0, double *mu, size_t *joint, double *x,
                                 double *dmu, int *iters, aq_error *err)
{
  if (aq_glpk_load(err) != AQ_OK)
    return AQ_EUNSUPPORTED;
  size_t n = g->p.voussoirs, nm = 2 * (n + 1), nrows = 2 * nm + 1;
  int s = act_sign < 0 ? 1 : -1;
  aq_lp4_row *row = malloc(nrows * sizeof *row);
  double *w = malloc((n + 1) * sizeof *w), *y = malloc(nrows * sizeof *y);
  double *g3 = malloc(nrows * sizeof *g3); /* each row's lambda coefficient */
  if (!row || !w || !y || !g3) {
    free(row);
    free(w);
    free(y);
    free(g3);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  /* the moment rows with lambda fixed: the fourth unknown is t */
  aq_thrust_rows(g, s, 0, row);
  for (size_t i = 0; i < nm; i++) {
    g3[i] = row[i].g[3];
    row[i].h -= row[i].g[3] * lambda;
    row[i].g[3] = 0;
  }
  g3[nrows - 1] = 0;
  row[nrows - 1] = (aq_lp4_row){{0, 0, 0, -1}, 1}; /* t >= -h: bounded (h below) */
  for (size_t j = 0; j <= n; j++) {
    double nf = 1, tf;
    if (x0) {
      double xs[4] = {x0[0], x0[1], x0[2], lambda};
      joint_force(g, j, s, xs, &nf, &tf);
    }
    w[j] = nf;
  }
  weights(w, n + 1);
  static const double c[4] = {0, 0, 0, -1}; /* minimize t */
  const aq_lp4_opts o = {OPT_TOL, TIGHT_REL, AQ_LP4_MAX_TIGHT, 0};
  double muk = mu0 > 0 && isfinite(mu0) ? mu0 : LEAST_MU_START, best = INFINITY;
  size_t best_j = 0;
  aq_status ret = AQ_OK;
  int settled = 0;      /* the method ended: no program lowered mu by LEAST_REL */
  double before = NAN;  /* the best before the last program's */
  *iters = 0;
  int programs = aq_friction_least_cap > 0 && aq_friction_least_cap < LEAST_ITER
                     ? aq_friction_least_cap : LEAST_ITER;
  for (int it = 0; it < programs && ret == AQ_OK; it++) {
    /* (+-T_j - mu_k N_j) / w_j - t <= 0 */
    /* t >= -max(1, mu_k / 2): bounded, yet loose enough that a line whose
       ratios are far below mu_k is reached in a few programs (t >= -1 let
       mu_k fall by about 1 per program) */
    row[nrows - 1].h = fmax(1, 0.5 * muk);
    for (size_t j = 0; j <= n; j++) {
      aq_lp4_row fr[2];
      friction_rows(g, j, s, muk, fr);
      for (int k = 0; k < 2; k++) {
        aq_lp4_row *r = &row[nm + 2 * j + (size_t)k];
        r->g[0] = fr[k].g[0] / w[j];
        r->g[1] = fr[k].g[1] / w[j];
        r->g[2] = 0;
        r->g[3] = -1;
        r->h = (fr[k].h - fr[k].g[3] * lambda) / w[j];
        g3[nm + 2 * j + (size_t)k] = fr[k].g[3] / w[j];
      }
    }
    aq_lp4_result r = {.y = y};
    aq_lp4_status st = aq_lp4_solve(row, nrows, c, NULL, &o, &r);
    ++*iters;
    if (st == AQ_LP4_INFEASIBLE) { /* no line of thrust at lambda at all; after a line
                                      was found (it stays feasible), the vertex's
                                      round-off: keep it */
      settled = 1;
      break;
    }
    if (st != AQ_LP4_OPT) {
      char what[96];
      snprintf(what, sizeof what, "the least friction of a line of thrust at lambda = %.9g",
               lambda);
      ret = lp_failed(err, st, nrows, what);
      break;
    }
    double xr[4] = {r.x[0], r.x[1], r.x[2], lambda}, next = 0;
    size_t next_j = 0;
    /* with V(lambda, mu) = max -t and its multipliers y (the envelope
     * theorem): dV/dlambda = -sum y_i (row i's lambda coefficient), dV/dmu =
     * sum over the friction rows y_i N_j / w_j; the least friction keeps V
     * at 0, so dmu/dlambda = -(dV/dlambda) / (dV/dmu) */
    double dv_dl = 0, dv_dm = 0;
    for (size_t i = 0; i < nrows; i++)
      dv_dl -= y[i] * g3[i];
    for (size_t j = 0; j <= n; j++) {
      double nf, tf;
      joint_force(g, j, s, xr, &nf, &tf);
      dv_dm += (y[nm + 2 * j] + y[nm + 2 * j + 1]) * nf / w[j];
      double ratio = nf > 0 ? fabs(tf) / nf : tf == 0 ? 0 : INFINITY;
      if (ratio > next * (1 + LEAST_TIE)) /* the lowest of joints that tie */
        next_j = j;
      next = fmax(next, ratio);
      w[j] = nf;
    }
    weights(w, n + 1);
    if (dmu)
      *dmu = dv_dm > 0 ? -dv_dl / dv_dm : NAN;
    int improved = next < best * (1 - LEAST_REL);
    before = best;
    if (next < best) {
      best = next;
      best_j = next_j;
      if (x)
        for (int k = 0; k < 3; k++)
          x[k] = xr[k];
    }
    if (!improved && (isfinite(best) || muk > 1e12)) {
      settled = 1;
      break;
    }
    /* a joint that does not push (N = 0) on that line: try a larger mu */
    muk = isfinite(best) ? best : muk * 1e3;
  }
  free(row);
  free(w);
  free(y);
  free(g3);
  if (ret == AQ_OK && !settled) /* never a quiet unconverged value */
    ret = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                       "expected the least friction of a line of thrust at lambda = %.9g, got "
                       "none settled: %d linear programs lowered it from %.9g to %.9g, by more "
                       "than %g (relative) in the last",
                       lambda, programs, before, best, LEAST_REL);
  if (ret != AQ_OK)
    return ret;
  *mu = best;
  if (joint)
    *joint = best_j;
  return AQ_OK;
}

aq_status aq_friction_least(const aq_geom *g, int act_sign, double lambda, double *mu,
                            size_t *joint, aq_error *err)
{
  int iters;
  return aq_friction_least_from(g, act_sign, lambda, 0, NULL, mu, joint, NULL, NULL, &iters,
                                err);
}

double aq_workpath_friction(const aq_workpath *w, double *ratio, size_t *joint)
{
  const aq_path *p = aq_workpath_path(w);
  const aq_mech *m = aq_workpath_mech(w);
  size_t n = m->g->p.voussoirs;
  if (joint)
    *joint = SIZE_MAX;
  for (size_t j = 0; ratio && j <= n; j++)
    ratio[j] = NAN;
  if (!p->admissible)
    return NAN;
  aq_mech_state st;
  aq_equil eq;
  aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, p->g_mps2};
  double *buf = malloc(2 * (n + 1) * sizeof *buf), worst = NAN;
  if (buf && aq_mech_eval(m, 0.0, &st) == 0 &&
      aq_mech_equilibrium(m, &st, &live, &eq, NULL) == AQ_OK) {
    worst = aq_mech_friction(m, &st, &live, &eq, buf, buf + n + 1, joint);
    for (size_t j = 0; ratio && j <= n; j++)
      ratio[j] = buf[n + 1 + j];
  }
  free(buf);
  return worst;
}
