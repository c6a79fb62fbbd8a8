/* glpk_lazy.c: GLPK opened when the mechanism search first runs, not when
 * archquake starts (src/util/lazylib.h): linked directly, libglpk and the
 * libraries it needs (AMD, COLAMD, SuiteSparse's config, GMP, ltdl) were
 * mapped and relocated by every command, `archquake --version` included,
 * though only the arch's statics solve linear programs (lp4.c, for search.c and
 * friction.c), and an arch read from the
 * disk cache needs no search at all.
 *
 * The GLPK functions lp4.c calls are defined here as trampolines
 * through pointers set from the library; their prototypes come from
 * glpk.h, so a definition that does not match the library's declaration
 * does not compile.  A GLPK function not listed here fails to link
 * ("undefined reference to glp_xxx"): add it to AQ_GLPK_FUNCS.
 * aq_search_minimum calls aq_glpk_load before any of them, so a missing
 * library is its error, naming the library, before anything is solved;
 * the arch is then refused even when its file names the hinges (arch.c). */
#include <glpk.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../util/lazylib.h"
#include "lazylib_sonames.h" /* build/: AQ_GLPK_SONAME, from the build's libglpk.so */
#include "model.h"

/* V(name, parameters, arguments): returns void; R(type, name, ...): type. */
#define AQ_GLPK_FUNCS(V, R)                                                               \
  R(glp_prob *, glp_create_prob, (void), ())                                             \
  V(glp_delete_prob, (glp_prob *P), (P))                                                  \
  V(glp_set_obj_dir, (glp_prob *P, int dir), (P, dir))                                    \
  R(int, glp_add_rows, (glp_prob *P, int nrs), (P, nrs))                                  \
  R(int, glp_add_cols, (glp_prob *P, int ncs), (P, ncs))                                  \
  V(glp_set_row_bnds, (glp_prob *P, int i, int type, double lb, double ub),               \
    (P, i, type, lb, ub))                                                                 \
  V(glp_set_col_bnds, (glp_prob *P, int j, int type, double lb, double ub),               \
    (P, j, type, lb, ub))                                                                 \
  V(glp_set_obj_coef, (glp_prob *P, int j, double coef), (P, j, coef))                    \
  V(glp_load_matrix, (glp_prob *P, int ne, const int ia[], const int ja[],                \
    const double ar[]), (P, ne, ia, ja, ar))                                              \
  V(glp_init_smcp, (glp_smcp *parm), (parm))                                              \
  V(glp_std_basis, (glp_prob *P), (P))                                                    \
  R(int, glp_simplex, (glp_prob *P, const glp_smcp *parm), (P, parm))                     \
  R(int, glp_exact, (glp_prob *P, const glp_smcp *parm), (P, parm))                       \
  R(int, glp_get_status, (glp_prob *P), (P))                                              \
  R(int, glp_get_it_cnt, (glp_prob *P), (P))                                              \
  R(double, glp_get_obj_val, (glp_prob *P), (P))                                          \
  R(double, glp_get_row_dual, (glp_prob *P, int i), (P, i))                               \
  R(int, glp_get_col_stat, (glp_prob *P, int j), (P, j))                                  \
  R(double, glp_get_col_prim, (glp_prob *P, int j), (P, j))                               \
  R(int, glp_term_out, (int flag), (flag))

AQ_GLPK_FUNCS(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)
static const aq_lazylib_sym glpk_syms[] = {AQ_GLPK_FUNCS(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R)};

static aq_lazylib glpk = {AQ_GLPK_SONAME, "GLPK", glpk_syms,
                          sizeof glpk_syms / sizeof glpk_syms[0], 0, ""};

aq_status aq_glpk_load(aq_error *err)
{
  aq_status st = aq_lazylib_load(&glpk, err);
  if (st != AQ_OK && err) {
    size_t n = strlen(err->message);
    snprintf(err->message + n, sizeof err->message - n, " (needed for the mechanism search)");
  }
  return st;
}

/* A GLPK call before aq_glpk_load: load now; a failure here is a call
 * that bypassed aq_search_minimum's check, a bug, so it stops the program. */
static void need(int resolved)
{
  if (!resolved && aq_lazylib_load(&glpk, NULL) != AQ_OK)
    abort();
}

AQ_GLPK_FUNCS(AQ_LAZYLIB_TRAMPOLINE_V, AQ_LAZYLIB_TRAMPOLINE_R)
