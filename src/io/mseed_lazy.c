/* mseed_lazy.c: libmseed opened when a miniSEED file is first parsed, not
 * when archquake starts (src/util/lazylib.h): libmseed-dev ships no static
 * archive, so linked it was the one library besides libc and libm that
 * every command mapped and relocated, `archquake --version` and a suite of
 * AT2 records included.
 *
 * The libmseed functions mseed.c calls are defined here as trampolines
 * through pointers set from the library; their prototypes come from
 * libmseed.h, so a definition that does not match the library's
 * declaration does not compile.  A libmseed function not listed here fails
 * to link ("undefined reference to msr_xxx"): add it to AQ_MSEED_FUNCS.
 * aq_mseed_parse calls aq_mseed_load first, so a missing library is that
 * file's error, naming the library, before anything is parsed. */
#include <libmseed.h>
#include <stdlib.h>

#include "../util/lazylib.h"
#include "lazylib_sonames.h" /* build/: AQ_MSEED_SONAME, from the build's libmseed.so */
#include "reader.h"

/* V(name, parameters, arguments): returns void; R(type, name, ...): type. */
#define AQ_MSEED_FUNCS(V, R)                                                              \
  R(int, ms_detect, (const char *record, int recbuflen), (record, recbuflen))            \
  R(int, msr_parse, (char *record, int recbuflen, MSRecord **ppmsr, int reclen,          \
    flag dataflag, flag verbose), (record, recbuflen, ppmsr, reclen, dataflag, verbose))  \
  V(msr_free, (MSRecord **ppmsr), (ppmsr))                                                \
  R(char *, ms_errorstr, (int errorcode), (errorcode))                                    \
  V(ms_loginit, (void (*log_print)(char *), const char *logprefix,                        \
    void (*diag_print)(char *), const char *errprefix),                                   \
    (log_print, logprefix, diag_print, errprefix))

AQ_MSEED_FUNCS(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)
static const aq_lazylib_sym mseed_syms[] = {
    AQ_MSEED_FUNCS(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R)};

static aq_lazylib mseed = {AQ_MSEED_SONAME, "libmseed", mseed_syms,
                           sizeof mseed_syms / sizeof mseed_syms[0], 0, ""};

aq_status aq_mseed_load(const char *name, aq_error *err)
{
  aq_error e;
  if (aq_lazylib_load(&mseed, &e) == AQ_OK)
    return AQ_OK;
  return aq_error_set(err, AQ_EUNSUPPORTED, name, -1, -1, "libmseed",
                      "%s (needed for miniSEED)", e.message);
}

/* A libmseed call before aq_mseed_load: load now; a failure here is a call
 * that bypassed aq_mseed_parse's check, a bug, so it stops the program. */
static void need(int resolved)
{
  if (!resolved && aq_lazylib_load(&mseed, NULL) != AQ_OK)
    abort();
}

AQ_MSEED_FUNCS(AQ_LAZYLIB_TRAMPOLINE_V, AQ_LAZYLIB_TRAMPOLINE_R)
