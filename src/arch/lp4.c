/* lp4.c: the linear programs of the arch's statics (search.c, friction.c):
 * the rows that keep a line of thrust inside the arch (aq_thrust_rows), and
 * the solution of programs in four free unknowns x and many rows,
 *
 *   maximize c.x  subject to  G_i x <= h_i  (i = 0..n-1),
 *
 * solved with GLPK (opened on first use, glpk_lazy.c) through the dual
 *
 *   minimize h.y  subject to  G^T y = c,  y >= 0,
 *
 * whose basis has four rows whatever the number of rows i (the joints of
 * an arch), so that a program of a thousand joints costs about what one of
 * ten does.  The primal's x is the dual's row duals; the dual's basic
 * columns are the primal's tight rows.  The vertex GLPK returns in floating
 * point is checked: every row's slack h_i - G_i x, recomputed here in long
 * double, must be >= -tol; when one is not, GLPK's rational simplex
 * (glp_exact) settles the vertex from that basis.  The primal is
 * infeasible when the dual is unbounded, unbounded when the dual is
 * infeasible.
 *
 * Every call of the simplex (floating-point and rational) is given an
 * iteration limit that grows with the program's size, never a time limit,
 * so that a program ends the same way on every machine: a program that
 * reaches it in both (a simplex cycling on a degenerate vertex, or any
 * other failure to converge) is AQ_LP4_ITLIM, which the callers turn into
 * an error, never into a result. */
#include <glpk.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "model.h"

/* The simplex iterations a program of n rows is given, per call: the dual
 * has four rows and n columns, and from GLPK's standard basis its simplex
 * needs fewer pivots than columns (measured: at most 28, on 165 rows, over
 * 589 circles of 8-40 voussoirs and embrace 60-180 degrees built with
 * their tables: docs/arch-model.md).  A simplex that reaches it has cycled
 * (a degenerate vertex of badly scaled rows): the rational simplex goes on
 * from its basis, with the same limit. */
#define LP4_ITER_BASE 1000     /* iterations every program is given */
#define LP4_ITER_PER_ROW 20    /* ... and per row */

size_t aq_lp4_iteration_cap = 0;

int aq_lp4_iteration_limit(size_t n)
{
  double lim = LP4_ITER_BASE + LP4_ITER_PER_ROW * (double)n;
  if (aq_lp4_iteration_cap > 0 && (double)aq_lp4_iteration_cap < lim)
    lim = (double)aq_lp4_iteration_cap;
  return lim < INT_MAX ? (int)lim : INT_MAX;
}

/* The slack of row r at x, in long double: h - G x. */
static long double slack(const aq_lp4_row *r, const long double x[4])
{
  long double gx = 0;
  for (int k = 0; k < 4; k++)
    gx += (long double)r->g[k] * x[k];
  return (long double)r->h - gx;
}

/* 1 if no row but the excluded is violated by more than tol at P's x. */
static int optimal_in_double(glp_prob *P, const aq_lp4_row *row, size_t n,
                             const unsigned char *ex, double tol)
{
  long double x[4];
  for (int k = 0; k < 4; k++)
    x[k] = glp_get_row_dual(P, k + 1);
  for (size_t i = 0; i < n; i++)
    if (!(ex && ex[i]) && slack(&row[i], x) < -tol)
      return 0;
  return 1;
}

void aq_thrust_rows(const aq_geom *g, int s, int relax, aq_lp4_row *lp)
{
  size_t n = g->p.voussoirs;
  double xlo = HUGE_VAL, xhi = -HUGE_VAL, ylo = HUGE_VAL, yhi = -HUGE_VAL;
  for (size_t j = 0; j <= n; j++)
    for (int f = 0; f < 2; f++) {
      aq_vec2 p = aq_geom_joint_point(g, j, f ? 'e' : 'i');
      xlo = fmin(xlo, p.x), xhi = fmax(xhi, p.x), ylo = fmin(ylo, p.y), yhi = fmax(yhi, p.y);
    }
  aq_vec2 o = {0.5 * (xlo + xhi), 0.5 * (ylo + yhi)};
  double L = fmax(xhi - xlo, yhi - ylo), mt = g->mass_kg;
  for (size_t j = 0; j <= n; j++) {
    double mj = g->cum_m[j];
    double sx = g->cum_mx[j] - mj * o.x, sy = g->cum_my[j] - mj * o.y;
    aq_vec2 pi = aq_geom_joint_point(g, j, 'i'), pe = aq_geom_joint_point(g, j, 'e');
    double half = 0.5 * hypot(pe.x - pi.x, pe.y - pi.y) / L;
    for (int f = 0; f < 2; f++) {
      aq_vec2 p = f ? pe : pi;
      double px = p.x - o.x, py = p.y - o.y;
      /* M_j(P) / (W L) = c . (R0x/W, R0y/W, m0/(W L), lambda) + c0 */
      double c[4] = {py / L, -px / L, 1.0, (double)s * (py * mj - sy) / (mt * L)};
      double c0 = (px * mj - sx) / (mt * L);
      double sgn = f ? 1.0 : -1.0; /* intrados: M >= 0, i.e. -M <= 0 */
      aq_lp4_row *r = &lp[2 * j + (size_t)f];
      for (int k = 0; k < 4; k++)
        r->g[k] = k < 3 ? sgn * c[k] : relax ? -half : sgn * c[3];
      r->h = -sgn * c0;
    }
  }
}

aq_lp4_status aq_lp4_solve(const aq_lp4_row *row, size_t n, const double c[4],
                           const unsigned char *ex, const aq_lp4_opts *o, aq_lp4_result *out)
{
  glp_prob *P = glp_create_prob();
  size_t nz = n * 4;
  int *ia = malloc((nz + 1) * sizeof *ia), *ja = malloc((nz + 1) * sizeof *ja);
  double *ar = malloc((nz + 1) * sizeof *ar);
  aq_lp4_status st = AQ_LP4_FAILED;
  out->ntight = out->nbasic = 0;
  out->iterations = 0;
  for (size_t i = 0; out->y && i < n; i++)
    out->y[i] = 0;
  if (!P || !ia || !ja || !ar)
    goto done;
  glp_term_out(GLP_OFF);
  glp_set_obj_dir(P, GLP_MIN);
  glp_add_rows(P, 4);
  for (int k = 0; k < 4; k++)
    glp_set_row_bnds(P, k + 1, GLP_FX, c[k], 0.0);
  glp_add_cols(P, (int)n);
  size_t z = 0;
  for (size_t i = 0; i < n; i++) {
    if (ex && ex[i])
      glp_set_col_bnds(P, (int)i + 1, GLP_FX, 0.0, 0.0);
    else
      glp_set_col_bnds(P, (int)i + 1, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(P, (int)i + 1, row[i].h);
    for (int k = 0; k < 4; k++) {
      double v = row[i].g[k];
      if (v == 0)
        continue;
      z++;
      ia[z] = k + 1;
      ja[z] = (int)i + 1;
      ar[z] = v;
    }
  }
  glp_load_matrix(P, (int)z, ia, ja, ar);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.it_lim = aq_lp4_iteration_limit(n);
  glp_std_basis(P);
  int rc = glp_simplex(P, &parm);
  /* the floating-point simplex stopped at its limit (it cycles on a degenerate
     vertex of badly scaled rows): the rational one, from where it stopped */
  if (rc == GLP_EITLIM)
    rc = glp_exact(P, &parm);
  else if (rc == 0 && glp_get_status(P) == GLP_OPT &&
           (o->exact || !optimal_in_double(P, row, n, ex, o->opt_tol)))
    rc = glp_exact(P, &parm);
  out->iterations = (size_t)glp_get_it_cnt(P);
  if (rc == GLP_EITLIM)
    st = AQ_LP4_ITLIM;
  if (rc != 0)
    goto done;
  int s = glp_get_status(P);
  if (s == GLP_UNBND || s == GLP_NOFEAS) {
    st = s == GLP_UNBND ? AQ_LP4_INFEASIBLE : AQ_LP4_UNBOUNDED;
    goto done;
  }
  if (s != GLP_OPT)
    goto done;
  out->obj = glp_get_obj_val(P);
  for (size_t i = 0; out->y && i < n; i++)
    out->y[i] = glp_get_col_prim(P, (int)i + 1);
  long double x[4];
  for (int k = 0; k < 4; k++) {
    x[k] = glp_get_row_dual(P, k + 1);
    out->x[k] = (double)x[k];
  }
  /* the basic columns (the vertex), then the columns of zero reduced cost */
  for (int pass = 0; pass < 2; pass++)
    for (size_t i = 0; i < n && out->ntight < o->max_tight; i++) {
      int basic = glp_get_col_stat(P, (int)i + 1) == GLP_BS;
      if (ex && ex[i])
        continue;
      if (pass == 0 ? basic : (!basic && fabsl(slack(&row[i], x)) <= o->tight_tol))
        out->tight[out->ntight++] = i;
      if (pass == 0)
        out->nbasic = out->ntight;
    }
  st = AQ_LP4_OPT;
done:
  free(ia);
  free(ja);
  free(ar);
  if (P)
    glp_delete_prob(P);
  return st;
}
