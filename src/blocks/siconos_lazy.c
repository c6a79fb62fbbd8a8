/* siconos_lazy.c: Siconos Numerics opened when the block model first needs
 * a frictional contact problem solved, not when archquake starts
 * (src/util/lazylib.h): the library and what it needs (OpenBLAS, LAPACK,
 * MUMPS, SCOTCH, gfortran) would otherwise be mapped by every command.
 *
 * The functions called here are defined as trampolines through pointers
 * set from the library, with the prototypes of Siconos's own headers
 * (Debian's libsiconos-numerics-dev: FrictionContactProblem, fc2d_driver
 * with the Lemke, NSGS and enumerative solvers, SolverOptions,
 * NumericsMatrix).  A fatal error inside the library (numerics_error)
 * longjmps to the buffer armed around each call instead of aborting the
 * process (sn_error_handling.h), so it fails the run, not the program.
 *
 * Reference: V. Acary, O. Bonnefon, M. Brémond, O. Huber, F. Pérignon,
 * S. Sinclair (2019), An introduction to Siconos, INRIA technical report
 * RT-0340; V. Acary and B. Brogliato (2008), Numerical methods for
 * nonsmooth dynamical systems, Springer, ch. 12-13 (the 2-D frictional
 * contact problem and its LCP form solved by Lemke's method). */
#include <dlfcn.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "LinearComplementarityProblem.h"
#include "lcp_cst.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "sn_error_handling.h"

#include "../util/lazylib.h"
#include "lazylib_sonames.h" /* build/: AQ_SICONOS_SONAME */
#include "model.h"

/* V(name, parameters, arguments): returns void; R(type, name, ...): type. */
#define AQ_SICONOS_FUNCS(V, R)                                                            \
  R(int, fc2d_driver,                                                                    \
    (FrictionContactProblem * problem, double *reaction, double *velocity,               \
     SolverOptions *options),                                                            \
    (problem, reaction, velocity, options))                                              \
  R(int, linearComplementarity_driver,                                                   \
    (LinearComplementarityProblem * problem, double *z, double *w, SolverOptions *options), \
    (problem, z, w, options))                                                            \
  R(SolverOptions *, solver_options_create, (int solverId), (solverId))                  \
  V(solver_options_delete, (SolverOptions * options), (options))                         \
  R(RawNumericsMatrix *, NM_create, (NM_types storageType, int size0, int size1),        \
    (storageType, size0, size1))                                                         \
  R(NumericsMatrix *, NM_free, (NumericsMatrix * m), (m))                                \
  R(jmp_buf *, sn_get_jmp_buf, (void), ())                                               \
  V(sn_release_jmp_buf, (void), ())

AQ_SICONOS_FUNCS(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)
static const aq_lazylib_sym siconos_syms[] = {
    AQ_SICONOS_FUNCS(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R)};

static aq_lazylib siconos = {AQ_SICONOS_SONAME, "Siconos Numerics", siconos_syms,
                             sizeof siconos_syms / sizeof siconos_syms[0], 0, ""};

/* Siconos calls BLAS for norms and products of a few dozen numbers; an
 * OpenBLAS behind it would start a thread per core and keep them yielding
 * between calls (a fifth of a run's time, measured), so it is asked for
 * one thread, once, if it is the BLAS loaded. */
static pthread_once_t blas_once = PTHREAD_ONCE_INIT;

static void blas_one_thread(void)
{
  void *h = dlopen("libopenblas.so.0", RTLD_NOW | RTLD_NOLOAD);
  if (!h)
    return;
  void (*set)(int);
  *(void **)&set = dlsym(h, "openblas_set_num_threads");
  if (set)
    set(1);
  dlclose(h);
}

aq_status aq_siconos_load(aq_error *err)
{
  aq_status st = aq_lazylib_load(&siconos, err);
  if (st != AQ_OK && err) {
    size_t n = strlen(err->message);
    snprintf(err->message + n, sizeof err->message - n, " (needed by --model blocks)");
  }
  if (st == AQ_OK)
    pthread_once(&blas_once, blas_one_thread);
  return st;
}

/* A call before aq_siconos_load: a bug (aq_blocks_alloc loads it first),
 * so it stops the program. */
static void need(int resolved)
{
  if (!resolved && aq_lazylib_load(&siconos, NULL) != AQ_OK)
    abort();
}

AQ_SICONOS_FUNCS(AQ_LAZYLIB_TRAMPOLINE_V, AQ_LAZYLIB_TRAMPOLINE_R)

struct aq_fc2d {
  NumericsMatrix *M; /* dense, its buffer for cap x cap */
  int cap;
  NumericsMatrix *L; /* the LCP's (AQ_FC2D_AP): lcap x lcap */
  int lcap;
  double *lq, *lz, *lw;
  SolverOptions *opt[4];
};

aq_fc2d *aq_fc2d_alloc(void)
{
  return calloc(1, sizeof(aq_fc2d));
}

void aq_fc2d_free(aq_fc2d *w)
{
  if (!w)
    return;
  if (w->M)
    NM_free(w->M);
  if (w->L)
    NM_free(w->L);
  free(w->lq);
  free(w->lz);
  free(w->lw);
  for (int k = 0; k < 4; k++)
    if (w->opt[k]) {
      solver_options_delete(w->opt[k]);
      free(w->opt[k]); /* solver_options_delete leaves the struct itself */
    }
  free(w);
}

/* The problem as the LCP of Anitescu and Potra (1997, Formulating
 * dynamic multi-rigid-body contact problems with friction as solvable
 * linear complementarity problems, Nonlinear Dynamics 14, 231-247,
 * eq. (20)-(23), its polyhedral cone exact in 2-D): per contact the normal
 * impulse p, the tangential ones b1, b2 along +t and -t (P_t = b1 - b2) and
 * the slip rate l, with
 *   0 <= p  perp  u_n >= 0,        0 <= b1 perp  l + u_t >= 0,
 *   0 <= b2 perp  l - u_t >= 0,    0 <= l  perp  mu p - b1 - b2 >= 0;
 * Lemke's method processes it (its matrix is copositive-plus for W
 * positive semidefinite), where the problem's own LCP form (fc2d_tolcp)
 * stops on a ray for some large-friction problems. */
static int solve_ap(aq_fc2d *w, int nc, const double *W, const double *q, const double *mu,
                    double tol, double *r, double *u, int *iters)
{
  int n = 2 * nc, N = 4 * nc;
  if (N > w->lcap) {
    if (w->L)
      NM_free(w->L);
    free(w->lq);
    free(w->lz);
    free(w->lw);
    w->L = NM_create(NM_DENSE, N, N);
    w->lq = malloc((size_t)N * sizeof *w->lq);
    w->lz = malloc((size_t)N * sizeof *w->lz);
    w->lw = malloc((size_t)N * sizeof *w->lw);
    w->lcap = w->L && w->lq && w->lz && w->lw ? N : 0;
    if (!w->lcap)
      return -1;
  }
  if (!w->opt[3] && !(w->opt[3] = solver_options_create(SICONOS_LCP_LEMKE)))
    return -1;
  SolverOptions *o = w->opt[3];
  o->dparam[SICONOS_DPARAM_TOL] = tol;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
  w->L->size0 = w->L->size1 = N;
  double *A = w->L->matrix0;
  memset(A, 0, (size_t)N * (size_t)N * sizeof *A);
#define AP(row, col) A[(size_t)(row) + (size_t)N * (size_t)(col)]
#define WW(row, col) W[(size_t)(row) + (size_t)n * (size_t)(col)]
  for (int i = 0; i < nc; i++) {
    for (int j = 0; j < nc; j++) {
      double nn = WW(2 * i, 2 * j), nt = WW(2 * i, 2 * j + 1), tn = WW(2 * i + 1, 2 * j),
             tt = WW(2 * i + 1, 2 * j + 1);
      AP(i, j) = nn;
      AP(i, nc + j) = nt;
      AP(i, 2 * nc + j) = -nt;
      AP(nc + i, j) = tn;
      AP(nc + i, nc + j) = tt;
      AP(nc + i, 2 * nc + j) = -tt;
      AP(2 * nc + i, j) = -tn;
      AP(2 * nc + i, nc + j) = -tt;
      AP(2 * nc + i, 2 * nc + j) = tt;
    }
    AP(nc + i, 3 * nc + i) = 1;
    AP(2 * nc + i, 3 * nc + i) = 1;
    AP(3 * nc + i, i) = mu[i];
    AP(3 * nc + i, nc + i) = -1;
    AP(3 * nc + i, 2 * nc + i) = -1;
    w->lq[i] = q[2 * i];
    w->lq[nc + i] = q[2 * i + 1];
    w->lq[2 * nc + i] = -q[2 * i + 1];
    w->lq[3 * nc + i] = 0;
  }
#undef AP
#undef WW
  memset(w->lz, 0, (size_t)N * sizeof *w->lz);
  LinearComplementarityProblem p = {N, w->L, w->lq};
  volatile int info = -1;
  if (setjmp(*sn_get_jmp_buf()) == 0) {
    info = linearComplementarity_driver(&p, w->lz, w->lw, o);
    sn_release_jmp_buf();
  } else {
    info = -1;
  }
  if (iters)
    *iters = o->iparam[SICONOS_IPARAM_ITER_DONE];
  for (int i = 0; i < nc; i++) {
    r[2 * i] = w->lz[i];
    r[2 * i + 1] = w->lz[nc + i] - w->lz[2 * nc + i];
  }
  for (int i = 0; i < n; i++) {
    double s = q[i];
    for (int j = 0; j < n; j++)
      s += W[(size_t)i + (size_t)n * (size_t)j] * r[j];
    u[i] = s;
  }
  return info;
}

int aq_fc2d_solve(aq_fc2d *w, aq_fc2d_solver solver, int nc, const double *W,
                  const double *q, const double *mu, double tol, double *r, double *u,
                  int *iters)
{
  static const int ids[3] = {SICONOS_FRICTION_2D_LEMKE, SICONOS_FRICTION_2D_NSGS,
                             SICONOS_FRICTION_2D_ENUM};
  int n = 2 * nc;
  if (nc < 1 || (int)solver < 0 || (int)solver > 3)
    return -1;
  if (solver == AQ_FC2D_AP)
    return solve_ap(w, nc, W, q, mu, tol, r, u, iters);
  if (n > w->cap) {
    if (w->M)
      NM_free(w->M);
    w->M = NM_create(NM_DENSE, n, n);
    w->cap = w->M ? n : 0;
    if (!w->M)
      return -1;
  }
  if (!w->opt[solver] && !(w->opt[solver] = solver_options_create(ids[solver])))
    return -1;
  SolverOptions *o = w->opt[solver];
  o->dparam[SICONOS_DPARAM_TOL] = tol;
  if (solver == AQ_FC2D_NSGS)
    o->iparam[SICONOS_IPARAM_MAX_ITER] = 2000; /* a polish from a near answer */
  /* the problem over the first n x n entries of the buffer */
  w->M->size0 = w->M->size1 = n;
  memcpy(w->M->matrix0, W, (size_t)n * (size_t)n * sizeof *W);
  FrictionContactProblem p;
  memset(&p, 0, sizeof p);
  p.dimension = 2;
  p.numberOfContacts = nc;
  p.M = w->M;
  p.q = (double *)q;
  p.mu = (double *)mu;
  volatile int info = -1;
  if (setjmp(*sn_get_jmp_buf()) == 0) {
    info = fc2d_driver(&p, r, u, o);
    sn_release_jmp_buf();
  } else {
    info = -1; /* the library's fatal error */
  }
  if (iters)
    *iters = o->iparam[SICONOS_IPARAM_ITER_DONE];
  return info;
}
