/* statics.c: under which loads the bodies stand still in their contacts
 * (model.h aq_statics_range): the static theorem with Coulomb friction, as
 * a linear program.
 *
 * At rest (every velocity zero) a step of the time stepper gives zero
 * velocities again exactly when contact impulses at the closed corners,
 * each with P_n >= 0 and |P_t| <= mu P_n, balance the step's loads: then
 * v = 0 with those impulses satisfies every contact condition (closed
 * corners keep u = 0), and if no such impulses exist v = 0 is not a
 * solution.  The loads of a step are the weight m (g + a_v) and the
 * horizontal body force -m a_x on every body, so with r = -a_x / (g + a_v)
 * the question is whether r lies in the range found here; the range is
 * found once per configuration at rest and each step at rest then costs a
 * comparison.  In 2-D the Coulomb cone is two linear inequalities, so the
 * program is exact (no linearised cone): it is the lower-bound theorem of
 * limit analysis with friction (Gilbert, Casapulla, Ahmed 2006, Limit
 * analysis of masonry block structures with non-associative frictional
 * joints using linear programming, Computers & Structures 84(13-14),
 * 873-887, eq. (1)-(4)).  GLPK, opened on first use (src/arch/glpk_lazy.c). */
#include <glpk.h>
#include <math.h>
#include <stdlib.h>

#include "model.h"

/* Solve with the objective direction dir; 1 and *val, 0 infeasible,
 * 2 unbounded, -1 failed. */
static int solve(glp_prob *P, int dir, double *val)
{
  glp_set_obj_dir(P, dir);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  if (glp_simplex(P, &parm) != 0) {
    glp_std_basis(P);
    if (glp_simplex(P, &parm) != 0)
      return -1;
  }
  int s = glp_get_status(P);
  if (s == GLP_NOFEAS)
    return 0;
  if (s == GLP_UNBND)
    return 2;
  if (s != GLP_OPT)
    return -1;
  *val = glp_get_obj_val(P);
  return 1;
}

int aq_statics_range(const aq_bodies *s, const aq_corner *cr, const unsigned char *closed,
                     double mu, double *r_min, double *r_max, aq_error *err)
{
  if (aq_glpk_load(err) != AQ_OK)
    return -1;
  size_t nc = 0;
  for (size_t k = 0; k < 2 * s->nj; k++)
    nc += closed[k] != 0;
  size_t nrow = 3 * s->nb + 2 * nc, ncol = 2 * nc + 1;
  /* each corner column: <= 6 equilibrium entries and 2 friction ones */
  size_t cap = 8 * 2 * nc + s->nb + 1;
  int *ia = malloc(cap * sizeof *ia), *ja = malloc(cap * sizeof *ja);
  double *ar = malloc(cap * sizeof *ar);
  if (!ia || !ja || !ar) {
    free(ia);
    free(ja);
    free(ar);
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "statics", "out of memory");
    return -1;
  }
  double W = s->mass_kg, L = s->length_m; /* forces per total weight, moments per L */
  glp_term_out(GLP_OFF);
  glp_prob *P = glp_create_prob();
  glp_add_rows(P, (int)nrow);
  glp_add_cols(P, (int)ncol);
  size_t z = 1;
  for (size_t b = 0; b < s->nb; b++) {
    glp_set_row_bnds(P, (int)(3 * b + 1), GLP_FX, 0, 0);
    glp_set_row_bnds(P, (int)(3 * b + 2), GLP_FX, s->body[b].mass_kg / W,
                     s->body[b].mass_kg / W);
    glp_set_row_bnds(P, (int)(3 * b + 3), GLP_FX, 0, 0);
    /* the horizontal force r m_b on the x row */
    ia[z] = (int)(3 * b + 1);
    ja[z] = (int)ncol;
    ar[z++] = s->body[b].mass_kg / W;
  }
  glp_set_col_bnds(P, (int)ncol, GLP_FR, 0, 0);
  glp_set_obj_coef(P, (int)ncol, 1);
  size_t col = 0, frow = 3 * s->nb;
  for (size_t j = 0; j < s->nj; j++)
    for (int k = 0; k < 2; k++) {
      const aq_corner *C = &cr[2 * j + k];
      if (!closed[2 * j + k])
        continue;
      int a = s->joint[j].a, b = s->joint[j].b;
      const aq_crow *rows[2] = {&C->n, &C->t};
      for (int t = 0; t < 2; t++) {
        int c = (int)(col + (size_t)t + 1);
        glp_set_col_bnds(P, c, t == 0 ? GLP_LO : GLP_FR, 0, 0);
        for (int i = 0; i < 3; i++) {
          double sc = i == 2 ? 1 / L : 1;
          if (a >= 0 && rows[t]->ga[i] != 0) {
            ia[z] = 3 * a + i + 1;
            ja[z] = c;
            ar[z++] = rows[t]->ga[i] * sc;
          }
          if (b >= 0 && rows[t]->gb[i] != 0) {
            ia[z] = 3 * b + i + 1;
            ja[z] = c;
            ar[z++] = rows[t]->gb[i] * sc;
          }
        }
      }
      /* P_t - mu P_n <= 0 and P_t + mu P_n >= 0 */
      glp_set_row_bnds(P, (int)frow + 1, GLP_UP, 0, 0);
      glp_set_row_bnds(P, (int)frow + 2, GLP_LO, 0, 0);
      int cn = (int)col + 1, ct = (int)col + 2;
      ia[z] = (int)frow + 1, ja[z] = ct, ar[z++] = 1;
      ia[z] = (int)frow + 1, ja[z] = cn, ar[z++] = -mu;
      ia[z] = (int)frow + 2, ja[z] = ct, ar[z++] = 1;
      ia[z] = (int)frow + 2, ja[z] = cn, ar[z++] = mu;
      frow += 2;
      col += 2;
    }
  glp_load_matrix(P, (int)z - 1, ia, ja, ar);
  free(ia);
  free(ja);
  free(ar);
  glp_std_basis(P);
  double hi = 0, lo = 0;
  int sh = solve(P, GLP_MAX, &hi), sl = sh == 1 || sh == 2 ? solve(P, GLP_MIN, &lo) : sh;
  glp_delete_prob(P);
  if (sh < 0 || sl < 0) {
    aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "statics",
                 "the linear program of the static range failed (GLPK)");
    return -1;
  }
  if (sh == 0 || sl == 0)
    return 0;
  *r_max = sh == 2 ? INFINITY : hi;
  *r_min = sl == 2 ? -INFINITY : lo;
  return 1;
}
