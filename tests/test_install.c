/* test_install.c: `make install DESTDIR=...` into a temporary directory, the
 * installed program run from elsewhere with --arch NAME, its manual page
 * rendered by man(1), and `make uninstall` leaving no file behind.  The
 * expected values come from outside the code under test: the source tree's
 * arches/ and docs/ (what must be installed), the source-tree binary run on
 * the arch file by path (what the installed one must print), the --help
 * texts (what man must show) and find(1) (what is left). */
#define _POSIX_C_SOURCE 200809L
#define _XOPEN_SOURCE 700 /* realpath */
#include <glob.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"

enum { OUT_CAP = 1 << 18, ERR_CAP = 1 << 14 };
static const char prefix[] = "/usr/local";
static const char record[] = "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2";

/* Run the shell command cmd (stdin /dev/null); stdout and stderr into out
 * and err (either may be NULL).  The exit status, or -1. */
static int sh(const char *tmp, const char *cmd, char *out, char *err)
{
  char line[3 * PATH_MAX], o[PATH_MAX + 16], e[PATH_MAX + 16];
  snprintf(o, sizeof o, "%s/sh.out", tmp);
  snprintf(e, sizeof e, "%s/sh.err", tmp);
  snprintf(line, sizeof line, "(%s) </dev/null >%s 2>%s", cmd, o, e);
  int rc = system(line);
  char *bufs[2] = {out, err};
  const char *paths[2] = {o, e};
  size_t caps[2] = {OUT_CAP, ERR_CAP};
  for (int i = 0; i < 2; i++) {
    if (!bufs[i])
      continue;
    char *b = aq_test_read_file(paths[i], NULL);
    snprintf(bufs[i], caps[i], "%s", b ? b : "");
    free(b);
  }
  return rc == -1 || !WIFEXITED(rc) ? -1 : WEXITSTATUS(rc);
}

static int exists(const char *dir, const char *sub, const char *name)
{
  char p[3 * PATH_MAX];
  struct stat st;
  snprintf(p, sizeof p, "%s%s/%s", dir, sub, name);
  return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

static const char *base(const char *p)
{
  const char *s = strrchr(p, '/');
  return s ? s + 1 : p;
}

/* Every non-blank line of text (trailing blanks dropped) occurs in page;
 * the headings of --help's Environment and Files as the page's sections
 * ENVIRONMENT and FILES (tools/man.sh). */
static void check_lines_in(const char *text, const char *page, const char *what)
{
  size_t missing = 0, n = 0;
  for (const char *l = text; *l;) {
    size_t len = strcspn(l, "\n");
    size_t t = len;
    while (t > 0 && (l[t - 1] == ' ' || l[t - 1] == '\t'))
      t--;
    if (t > 0) {
      char *want = !strncmp(l, "Environment:\n", 13) ? strdup("\nENVIRONMENT\n")
                   : !strncmp(l, "Files:\n", 7)       ? strdup("\nFILES\n")
                                                       : strndup(l, t);
      n++;
      if (want && !strstr(page, want) && missing++ < 3)
        aq_check(0, "man page lacks this line of %s: \"%s\"", what, want);
      free(want);
    }
    l += len + (l[len] == '\n');
  }
  aq_check(missing == 0 && n > 0, "%s: %zu of %zu lines missing from the man page",
           what, missing, n);
}

/* Every relative link of the installed README ("](docs/x.md)",
 * "](docs/figures/x.png)") names an installed file. */
static void check_readme_links(const char *inst)
{
  char path[4 * PATH_MAX]; /* inst is at most 3 * PATH_MAX */
  snprintf(path, sizeof path, "%s/share/doc/archquake/README.md", inst);
  FILE *f = fopen(path, "r");
  if (!aq_check(f != NULL, "open %s", path))
    return;
  size_t nlink = 0, missing = 0;
  char line[4096];
  while (fgets(line, sizeof line, f))
    for (char *p = strstr(line, "]("); p; p = strstr(p + 2, "](")) {
      char target[1024];
      size_t len = strcspn(p + 2, ")#");
      if (len == 0 || len >= sizeof target || strncmp(p + 2, "http", 4) == 0)
        continue;
      snprintf(target, sizeof target, "%.*s", (int)len, p + 2);
      nlink++;
      if (!exists(inst, "/share/doc/archquake", target) && missing++ < 3)
        aq_check(0, "the installed README links %s, which is not installed", target);
    }
  fclose(f);
  aq_check(nlink > 5 && missing == 0, "README links: %zu, %zu not installed", nlink, missing);
}

AQ_TEST(install_run_man_uninstall)
{
  char tmp[512], root[PATH_MAX], dest[PATH_MAX + 16], cmd[8 * PATH_MAX];
  aq_test_tmpdir(tmp, sizeof tmp);
  if (!aq_check(realpath(tmp, root) != NULL, "realpath %s", tmp))
    return;
  snprintf(dest, sizeof dest, "%s/dest", root);
  char *out = malloc(OUT_CAP), *want = malloc(OUT_CAP), *err = malloc(ERR_CAP);
  if (!aq_check(out && want && err, "memory"))
    goto done;

  /* Install the binary under test (no rebuild); MAKEFLAGS of an enclosing
   * make would hand this one its jobserver. */
  snprintf(cmd, sizeof cmd,
           "env -u MAKEFLAGS -u MAKELEVEL make -s install PREFIX=%s DESTDIR=%s "
           "INSTALL_BIN=%s", prefix, dest, aq_test_bin());
  int rc = sh(root, cmd, out, err);
  if (!aq_check(rc == 0, "make install: exit %d: %s", rc, err))
    goto done;
  char inst[3 * PATH_MAX];
  snprintf(inst, sizeof inst, "%s%s", dest, prefix);
  aq_check(exists(inst, "/bin", "archquake"), "bin/archquake installed");
  aq_check(exists(inst, "/share/man/man1", "archquake.1"), "man1/archquake.1 installed");
  aq_check(exists(inst, "/share/doc/archquake", "README.md"), "README.md installed");
  glob_t g;
  size_t ndoc = 0, narch = 0;
  if (glob("docs/*.md", 0, NULL, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; i++)
      ndoc += exists(inst, "/share/doc/archquake/docs", base(g.gl_pathv[i]));
    aq_check(ndoc == g.gl_pathc && ndoc > 0, "docs installed: %zu of %zu", ndoc,
             (size_t)g.gl_pathc);
    globfree(&g);
  }
  check_readme_links(inst);
  char installed_list[1024] = "";
  if (glob("arches/*.cfg", 0, NULL, &g) == 0) { /* sorted, as the list is */
    for (size_t i = 0; i < g.gl_pathc; i++) {
      const char *b = base(g.gl_pathv[i]);
      narch += exists(inst, "/share/archquake/arches", b);
      size_t l = strlen(installed_list);
      snprintf(installed_list + l, sizeof installed_list - l, "%s%.*s", i ? ", " : "",
               (int)(strlen(b) - 4), b);
    }
    aq_check(narch == g.gl_pathc && narch > 0, "arches installed: %zu of %zu", narch,
             (size_t)g.gl_pathc);
    globfree(&g);
  }

  /* The main job, run by the installed program from another directory with
   * an arch by name, prints what the source-tree program prints for the
   * arch file itself. */
  char cwd[PATH_MAX];
  if (!aq_check(getcwd(cwd, sizeof cwd) != NULL, "getcwd"))
    goto done;
  snprintf(cmd, sizeof cmd, "%s/%s --arch %s/arches/oppenheim.cfg -q", cwd, record, cwd);
  aq_check(aq_test_run(cmd, want, OUT_CAP, err, ERR_CAP) == 0, "source run: %s", err);
  snprintf(cmd, sizeof cmd,
           "cd %s && env -u ARCHQUAKE_DATADIR %s/bin/archquake %s/%s --arch oppenheim -q",
           root, inst, cwd, record);
  rc = sh(root, cmd, out, err);
  aq_check(rc == 0, "installed run: exit %d: %s", rc, err);
  aq_check(strcmp(out, want) == 0 && aq_test_count_lines(out) == 3, /* header, 2 polarities */
           "installed run --arch oppenheim prints the source run's TSV:\n%s---\n%s", out,
           want);
  /* An unknown name: one line, naming the installed arches and where. */
  snprintf(cmd, sizeof cmd, "cd %s && env -u ARCHQUAKE_DATADIR %s/bin/archquake "
           "mechanism --arch nosuch", root, inst);
  rc = sh(root, cmd, out, err);
  char where[3 * PATH_MAX];
  if (snprintf(where, sizeof where, "%s/bin/../share/archquake/arches", inst) >= (int)sizeof where)
    where[0] = '\0';
  aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, "nosuch") &&
               strstr(err, installed_list) && strstr(err, where),
           "unknown arch: exit %d, one line naming [%s] and %s: %s", rc, installed_list,
           where, err);

  /* The page, as man renders it (plain ASCII, wide enough not to wrap the
   * help texts), shows every line of every command's --help. */
  snprintf(cmd, sizeof cmd, "LC_ALL=C MANWIDTH=200 man -l %s/share/man/man1/archquake.1", inst);
  rc = sh(root, cmd, out, err);
  char *page = strdup(out);
  aq_check(rc == 0 && err[0] == '\0', "man -l: exit %d: %s", rc, err);
  if (page && aq_test_run("--help", want, OUT_CAP, NULL, 0) == 0) {
    check_lines_in(want, page, "archquake --help");
    static const char *const cmds[] = {"info", "mechanism", "pulse", "domain", "compare",
                                       "capacity", "plot", "report"};
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
      snprintf(cmd, sizeof cmd, "%s --help", cmds[i]);
      if (aq_check(aq_test_run(cmd, want, OUT_CAP, NULL, 0) == 0, "%s --help", cmds[i]))
        check_lines_in(want, page, cmds[i]);
    }
  }
  free(page);
  /* `man archquake` finds it on the installed prefix's manual path. */
  snprintf(cmd, sizeof cmd, "LC_ALL=C MANPATH=%s/share/man man archquake", inst);
  rc = sh(root, cmd, out, err);
  aq_check(rc == 0 && strstr(out, "ARCHQUAKE(1)"), "man archquake: exit %d: %s", rc, err);

  /* Uninstall: no file is left, nor archquake's own directories. */
  snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MAKELEVEL make -s uninstall PREFIX=%s "
           "DESTDIR=%s", prefix, dest);
  rc = sh(root, cmd, out, err);
  aq_check(rc == 0, "make uninstall: exit %d: %s", rc, err);
  snprintf(cmd, sizeof cmd, "find %s ! -type d; find %s -name '*archquake*'", dest, dest);
  rc = sh(root, cmd, out, err);
  aq_check(rc == 0 && out[0] == '\0', "left after uninstall: %s", out);
done:
  free(out);
  free(want);
  free(err);
}

/* A data directory named by the environment is searched first; a path
 * (NAME.cfg, or one with a '/') is still a path. */
AQ_TEST(install_arch_by_name)
{
  char tmp[512], out[8192], want[8192], err[2048], cmd[1200];
  aq_test_tmpdir(tmp, sizeof tmp);
  snprintf(cmd, sizeof cmd, "%s/arches", tmp);
  mkdir(cmd, 0777);
  snprintf(cmd, sizeof cmd, "%s/arches/mine.cfg", tmp);
  aq_check(aq_test_copy_prefix("arches/thin.cfg", cmd, 1, 1), "copy to %s", cmd);
  aq_check(aq_test_run("mechanism --arch arches/thin.cfg", want, sizeof want, err,
                       sizeof err) == 0, "by path: %s", err);
  setenv("ARCHQUAKE_DATADIR", tmp, 1);
  int rc = aq_test_run("mechanism --arch mine", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strcmp(out, want) == 0,
           "--arch mine from $ARCHQUAKE_DATADIR/arches: exit %d, %s", rc, err);
  rc = aq_test_run("mechanism --arch nosuch", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, "installed: mine"),
           "unknown name lists the data directory's arches first: %s", err);
  unsetenv("ARCHQUAKE_DATADIR");
  rc = aq_test_run("mechanism --arch mine.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc != 0 && strstr(err, "mine.cfg") && !strstr(err, "installed"),
           "mine.cfg is a path (not found), not a name: exit %d, %s", rc, err);
  rc = aq_test_run("mechanism --arch ./thin", out, sizeof out, err, sizeof err);
  aq_check(rc != 0 && strstr(err, "./thin") && !strstr(err, "installed"),
           "./thin is a path (not found), not a name: exit %d, %s", rc, err);
}
