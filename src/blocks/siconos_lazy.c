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
  SolverOptions *opt[3];
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
  for (int k = 0; k < 3; k++)
    if (w->opt[k]) {
      solver_options_delete(w->opt[k]);
      free(w->opt[k]); /* solver_options_delete leaves the struct itself */
    }
  free(w);
}

int aq_fc2d_solve(aq_fc2d *w, aq_fc2d_solver solver, int nc, const double *W,
                  const double *q, const double *mu, double tol, double *r, double *u,
                  int *iters)
{
  static const int ids[3] = {SICONOS_FRICTION_2D_LEMKE, SICONOS_FRICTION_2D_NSGS,
                             SICONOS_FRICTION_2D_ENUM};
  int n = 2 * nc;
  if (nc < 1 || (int)solver < 0 || (int)solver > 2)
    return -1;
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
    o->iparam[SICONOS_IPARAM_MAX_ITER] = 20000;
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
