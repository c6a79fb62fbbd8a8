/* test_util_lazylib.c: libraries opened on first use (src/util/lazylib.h).
 * The loader against the dynamic linker's own answers (a symbol resolved
 * through it is the one the runner was linked with; a missing library or
 * symbol is an error naming it), and the program against readelf(1) and
 * the loader's trace (LD_DEBUG=files): archquake needs neither PLplot,
 * libxml2, libmseed nor GLPK to start, `--version` and `info` of an AT2
 * record load none of them, a figure loads PLplot, a miniSEED file
 * libmseed, a StationXML file libxml2 and the mechanism search GLPK. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "util/lazylib.h"

AQ_TEST(lazylib_resolves_what_the_linker_resolves)
{
  double (*my_cos)(double) = NULL, (*my_hypot)(double, double) = NULL;
  const aq_lazylib_sym syms[] = {{"cos", &my_cos}, {"hypot", &my_hypot}};
  aq_lazylib lib = {"libm.so.6", "libm", syms, 2, 0, ""};
  aq_error e;
  aq_check(aq_lazylib_load(&lib, &e) == AQ_OK, "libm.so.6: %s", e.message);
  aq_check(my_cos == cos && my_hypot == hypot,
           "the pointers are libm's own cos and hypot, as linked");
  aq_check(my_hypot && my_hypot(3.0, 4.0) == 5.0, "hypot(3, 4) through the pointer");
  aq_check(aq_lazylib_load(&lib, &e) == AQ_OK, "a second load is the first's outcome");
}

AQ_TEST(lazylib_missing_library_or_symbol_is_one_error)
{
  void (*f)(void) = NULL;
  const aq_lazylib_sym none[] = {{"aq_no_such_function", &f}};
  aq_lazylib lib = {"libaq-no-such-library.so.7", "nolib", none, 1, 0, ""};
  aq_error e;
  aq_check(aq_lazylib_load(&lib, &e) == AQ_EUNSUPPORTED, "missing library refused");
  aq_check(strstr(e.message, "libaq-no-such-library.so.7") && strcmp(e.field, "nolib") == 0,
           "the error names the library: %s: %s", e.field, e.message);
  aq_check(aq_lazylib_load(&lib, &e) == AQ_EUNSUPPORTED && strstr(e.message, "cannot load"),
           "the failure is kept for later calls: %s", e.message);
  aq_lazylib m = {"libm.so.6", "libm", none, 1, 0, ""};
  aq_check(aq_lazylib_load(&m, &e) == AQ_EUNSUPPORTED &&
               strstr(e.message, "aq_no_such_function"),
           "a missing symbol is named: %s", e.message);
  aq_check(f == NULL, "nothing is set when a symbol is missing");
}

/* The output of a shell command (stdout and stderr), malloc'd. */
static char *capture(const char *cmd)
{
  char dir[512], path[600], line[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/out", dir);
  snprintf(line, sizeof line, "(%s) </dev/null >%s 2>&1", cmd, path);
  if (system(line) == -1)
    return NULL;
  return aq_test_read_file(path, NULL);
}

/* The libraries the loader opened while running archquake args. */
static char *loaded(const char *args)
{
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "LD_DEBUG=files %s %s 2>&1 >/dev/null | grep 'file='",
           aq_test_bin(), args);
  return capture(cmd);
}

AQ_TEST(lazylib_archquake_starts_without_plplot_libxml2_mseed_or_glpk)
{
  char cmd[700];
  snprintf(cmd, sizeof cmd, "readelf -d %s | grep NEEDED", aq_test_bin());
  char *needed = capture(cmd);
  aq_check(needed && strstr(needed, "libc.so"), "readelf lists the program's libraries");
  aq_check(needed && !strstr(needed, "libplplot") && !strstr(needed, "libxml2") &&
               !strstr(needed, "libglpk") && !strstr(needed, "libmseed"),
           "PLplot, libxml2, libmseed and GLPK are not among the libraries loaded at "
           "start:\n%s",
           needed ? needed : "");
  free(needed);

  char *v = loaded("--version");
  aq_check(v && strstr(v, "libc.so"), "LD_DEBUG traces the loading");
  aq_check(v && !strstr(v, "plplot") && !strstr(v, "libxml2") && !strstr(v, "libicu") &&
               !strstr(v, "libglpk") && !strstr(v, "libgmp") && !strstr(v, "libmseed"),
           "--version loads no PLplot, libxml2, ICU, GLPK, GMP or libmseed:\n%s", v ? v : "");
  free(v);
  char *i = loaded("info records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2");
  aq_check(i && !strstr(i, "plplot") && !strstr(i, "libxml2") && !strstr(i, "libglpk") &&
               !strstr(i, "libmseed"),
           "info on an AT2 record loads none:\n%s", i ? i : "");
  free(i);

  char dir[512], args[1200];
  aq_test_tmpdir(dir, sizeof dir);
  /* an empty cache directory: the arch is built, its hinges searched */
  char mcmd[2000];
  snprintf(mcmd, sizeof mcmd, "XDG_CACHE_HOME=%s LD_DEBUG=files %s mechanism --arch "
           "arches/search.cfg 2>&1 >/dev/null | grep 'file='", dir, aq_test_bin());
  char *m = capture(mcmd);
  aq_check(m && strstr(m, "libglpk") && strstr(m, "dynamically loaded") && strstr(m, "libgmp") &&
               !strstr(m, "plplot"),
           "the mechanism search opens GLPK (and GMP, which it needs), not PLplot:\n%s",
           m ? m : "");
  free(m);

  snprintf(args, sizeof args, "plot arch --arch arches/oppenheim.cfg -o %s/a.png", dir);
  char *p = loaded(args);
  aq_check(p && strstr(p, "libplplot") && strstr(p, "dynamically loaded"),
           "a figure opens PLplot:\n%s", p ? p : "");
  aq_check(p && !strstr(p, "libxml2"), "a figure needs no libxml2");
  free(p);
  char *x = loaded("info tests/data/records/CI.CLC..HNE.mseed "
                   "--response tests/data/records/CI.CLC.xml");
  aq_check(x && strstr(x, "libxml2") && strstr(x, "libmseed") && !strstr(x, "plplot"),
           "a miniSEED file opens libmseed, its StationXML libxml2, not PLplot:\n%s",
           x ? x : "");
  free(x);
}
