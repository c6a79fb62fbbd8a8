/* lazylib.c: open a shared library on first use (see lazylib.h). */
#include "lazylib.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

/* dlopen and dlerror share state between threads: one lock for every lib. */
static pthread_mutex_t lazylib_lock = PTHREAD_MUTEX_INITIALIZER;

static int open_all(aq_lazylib *lib)
{
  void *h = dlopen(lib->soname, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *why = dlerror();
    aq_text_fit(lib->fail, sizeof lib->fail, "cannot load %s: %s", lib->soname,
                why ? why : "unknown reason");
    return -1;
  }
  for (size_t i = 0; i < lib->nsym; i++) {
    dlerror();
    void *p = dlsym(h, lib->sym[i].name);
    if (!p) {
      const char *why = dlerror();
      aq_text_fit(lib->fail, sizeof lib->fail, "%s has no %s: %s", lib->soname,
                  lib->sym[i].name, why ? why : "null symbol");
      return -1; /* the handle stays open: dlclose could run its destructors twice */
    }
    /* POSIX (dlsym): a function pointer is stored through a void * */
    memcpy(lib->sym[i].slot, &p, sizeof p);
  }
  return 1;
}

aq_status aq_lazylib_load(aq_lazylib *lib, aq_error *err)
{
  pthread_mutex_lock(&lazylib_lock);
  if (lib->state == 0)
    lib->state = open_all(lib);
  int state = lib->state;
  pthread_mutex_unlock(&lazylib_lock);
  if (state > 0)
    return AQ_OK;
  return aq_error_set(err, AQ_EUNSUPPORTED, NULL, -1, -1, lib->what, "%s", lib->fail);
}
