/* opt_arch.c: --arch NAME finds an installed arch (see opt_arch.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_arch.h"

#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "datadir.h" /* AQ_DATADIR: PREFIX/share/archquake, from the Makefile */

#define ARCH_EXT ".cfg"
enum { NDIRS = 4, MAX_LISTED = 64 };

/* The resolved paths handed out, kept (reachable) until the program ends. */
static char **found;
static size_t nfound;

static int has_suffix(const char *s, const char *suf)
{
  size_t n = strlen(s), m = strlen(suf);
  return n >= m && strcmp(s + n - m, suf) == 0;
}

static int is_regular(const char *path)
{
  struct stat st;
  return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* buf = a followed by b if that fits in cap bytes; returns 1 if it did. */
static int join(char *buf, size_t cap, const char *a, const char *b)
{
  int w = snprintf(buf, cap, "%s%s", a, b);
  return w >= 0 && (size_t)w < cap;
}

/* The arch directories in search order (see opt_arch.h); returns how many,
 * each written into dirs[i] (PATH_MAX bytes).  One too long is left out. */
static size_t arch_dirs(char dirs[NDIRS][PATH_MAX])
{
  size_t n = 0;
  const char *env = getenv("ARCHQUAKE_DATADIR");
  if (env && *env)
    n += join(dirs[n], PATH_MAX, env, "/arches");
  n += join(dirs[n], PATH_MAX, AQ_DATADIR, "/arches");
  char exe[PATH_MAX];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len > 0) {
    exe[len] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) {
      *slash = '\0';
      n += join(dirs[n], PATH_MAX, exe, "/../share/archquake/arches");
      n += join(dirs[n], PATH_MAX, exe, "/arches");
    }
  }
  return n;
}

static int cmp_names(const void *a, const void *b)
{
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* One line: the unknown name, where it was looked for, what is installed. */
static void report_unknown(const char *name, char dirs[NDIRS][PATH_MAX], size_t ndirs)
{
  char *names[MAX_LISTED];
  size_t nn = 0;
  for (size_t d = 0; d < ndirs; d++) {
    DIR *dir = opendir(dirs[d]);
    if (!dir)
      continue;
    for (struct dirent *e; (e = readdir(dir)) != NULL && nn < MAX_LISTED;) {
      size_t len = strlen(e->d_name);
      if (!has_suffix(e->d_name, ARCH_EXT) || len == strlen(ARCH_EXT))
        continue;
      char *stem = strndup(e->d_name, len - strlen(ARCH_EXT));
      if (!stem)
        continue;
      int dup = 0;
      for (size_t i = 0; i < nn && !dup; i++)
        dup = strcmp(names[i], stem) == 0;
      if (dup)
        free(stem);
      else
        names[nn++] = stem;
    }
    closedir(dir);
  }
  qsort(names, nn, sizeof names[0], cmp_names);
  fprintf(stderr, "archquake: --arch %s: expected a path or an installed arch, "
                  "found neither (installed:", name);
  for (size_t i = 0; i < nn; i++)
    fprintf(stderr, "%s %s", i ? "," : "", names[i]);
  fprintf(stderr, "%s; looked in %s", nn ? "" : " none", dirs[0]);
  for (size_t d = 1; d < ndirs; d++)
    fprintf(stderr, ", %s", dirs[d]);
  fprintf(stderr, ")\n");
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
}

/* A copy of path kept until the program ends, or NULL. */
static char *keep(const char *path)
{
  char **grown = realloc(found, (nfound + 1) * sizeof *found);
  if (!grown)
    return NULL;
  found = grown;
  return (found[nfound] = strdup(path)) ? found[nfound++] : NULL;
}

char *aq_opt_arch(char *arg, int *nerr)
{
  if (*arg == '\0' || strchr(arg, '/') || has_suffix(arg, ARCH_EXT))
    return arg; /* a path: loading it reports what is wrong with it */
  char dirs[NDIRS][PATH_MAX];
  size_t ndirs = arch_dirs(dirs);
  char path[2 * PATH_MAX];
  for (size_t d = 0; d < ndirs; d++) {
    int w = snprintf(path, sizeof path, "%s/%s" ARCH_EXT, dirs[d], arg);
    if (w >= 0 && (size_t)w < sizeof path && is_regular(path)) {
      char *kept = keep(path);
      if (!kept) {
        fprintf(stderr, "archquake: --arch %s: out of memory\n", arg);
        ++*nerr;
      }
      return kept ? kept : arg;
    }
  }
  if (is_regular(arg))
    return arg; /* a file of that name here */
  report_unknown(arg, dirs, ndirs);
  ++*nerr;
  return arg;
}

void aq_opt_arch_usage(FILE *f)
{
  fprintf(f,
          "Arches: --arch takes an arch file (a path with a '/', or NAME.cfg) or\n"
          "the name of an installed arch (--arch oppenheim): NAME.cfg in the first\n"
          "of these directories that has it:\n"
          "  $ARCHQUAKE_DATADIR/arches\n"
          "  %s/arches\n"
          "  BINDIR/../share/archquake/arches   (BINDIR: where archquake is)\n"
          "  BINDIR/arches                      (the source tree)\n"
          "An unknown name is reported with the list of installed arches.  The\n"
          "file's sections and keys: archquake help arch-file.\n",
          AQ_DATADIR);
}
