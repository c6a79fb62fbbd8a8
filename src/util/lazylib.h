/* lazylib.h: a shared library opened on first use instead of at process
 * start.  The dynamic loader maps and relocates every library a program is
 * linked with before main(), whatever the command: PLplot (with freetype,
 * shapelib, csiro, qsastime) and libxml2 (with ICU and libstdc++) took
 * three quarters of `archquake --version`.  A module that needs such a
 * library lists the symbols it calls; aq_lazylib_load opens the library
 * (by its soname, found at build time) and resolves all of them at once,
 * so a missing library or symbol is one error before anything is called.
 *
 * The module defines the library's functions itself as trampolines that
 * call through the resolved pointers (src/plot/plplot_lazy.c,
 * src/io/xml_lazy.c, src/io/mseed_lazy.c, src/arch/glpk_lazy.c,
 * src/blocks/siconos_lazy.c), so its
 * callers include the library's own header and are unchanged.  Thread-safe; the library stays loaded until exit.
 * Nothing prints: a failure fills an aq_error naming the library. */
#ifndef AQ_UTIL_LAZYLIB_H
#define AQ_UTIL_LAZYLIB_H

#include <stddef.h>

#include "../error.h"

/* One symbol to resolve: its name, and the function pointer to set. */
typedef struct {
  const char *name;
  void *slot; /* address of a function pointer variable */
} aq_lazylib_sym;

typedef struct {
  const char *soname;         /* e.g. "libplplot.so.17" */
  const char *what;           /* the field of errors, e.g. "PLplot" */
  const aq_lazylib_sym *sym;  /* the symbols to resolve */
  size_t nsym;
  int state;                  /* 0 not tried, 1 loaded, -1 failed (under the lock) */
  char fail[400];             /* why it failed, kept for later calls */
} aq_lazylib;

/* The module's side, for an X-macro list of the library's functions,
 * V(name, (parameters), (arguments)) for those returning void and
 * R(type, name, (parameters), (arguments)) for the others:
 *   LIST(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)  the pointers p_NAME;
 *   static const aq_lazylib_sym syms[] =
 *       {LIST(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R)};   what to resolve;
 *   LIST(AQ_LAZYLIB_TRAMPOLINE_V, AQ_LAZYLIB_TRAMPOLINE_R)  the functions,
 * each of which calls need(p_NAME != NULL) (the module's own function: it
 * loads the library or stops) and then the library's. */
#define AQ_LAZYLIB_POINTER_V(name, params, args) static void(*p_##name) params;
#define AQ_LAZYLIB_POINTER_R(type, name, params, args) static type(*p_##name) params;
#define AQ_LAZYLIB_SYM_V(name, params, args) {#name, &p_##name},
#define AQ_LAZYLIB_SYM_R(type, name, params, args) {#name, &p_##name},
#define AQ_LAZYLIB_TRAMPOLINE_V(name, params, args)                                        \
  void name params                                                                        \
  {                                                                                       \
    need(p_##name != NULL);                                                               \
    p_##name args;                                                                        \
  }
#define AQ_LAZYLIB_TRAMPOLINE_R(type, name, params, args)                                  \
  type name params                                                                        \
  {                                                                                       \
    need(p_##name != NULL);                                                               \
    return p_##name args;                                                                 \
  }

/* Open lib and resolve its symbols, once per process (later calls return
 * the first call's outcome).  AQ_OK, or AQ_EUNSUPPORTED with err naming the
 * library and dlerror()'s reason (library not installed, symbol missing). */
aq_status aq_lazylib_load(aq_lazylib *lib, aq_error *err);

#endif
