/* test_app_commands.c: the one table of commands (aq_opt_commands,
 * src/app/opt_table.c), through the program:
 *   - every command archquake --help lists is dispatched by its name and
 *     has its own --help (usage: archquake NAME), the same text as
 *     `archquake help NAME`; every command of the table is listed;
 *   - an unknown command is refused in one line naming it and listing the
 *     commands, exit 2, and nothing on stdout; a record (a file name) is
 *     still the main job's;
 *   - --version and --help are the main job's options. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/opt_table.h"
#include "check.h"

enum { OUT_CAP = 1 << 17 };

/* The commands archquake --help lists ("  archquake NAME ..." under
 * "Commands"), as words into names[], their count returned. */
static size_t listed(const char *help, char names[][32], size_t cap)
{
  const char *p = strstr(help, "\nCommands");
  size_t n = 0;
  while (p && (p = strstr(p, "\n  archquake ")) && n < cap) {
    p += strlen("\n  archquake ");
    if (*p == '[' || *p == '-') /* the main job's synopsis */
      continue;
    size_t len = strcspn(p, " \n");
    snprintf(names[n++], sizeof names[0], "%.*s", (int)len, p);
  }
  return n;
}

AQ_TEST(app_every_listed_command_dispatches_with_its_help)
{
  char *out = malloc(OUT_CAP), *again = malloc(OUT_CAP), err[4096], args[128];
  if (!aq_check(out && again, "memory"))
    goto done;
  int rc = aq_test_run("--help", out, OUT_CAP, err, sizeof err);
  char names[64][32];
  size_t n = listed(out, names, 64);
  aq_check(rc == 0 && n >= 10, "archquake --help: exit %d, %zu commands listed", rc, n);
  for (size_t k = 0; k < n; k++) {
    snprintf(args, sizeof args, "%s --help", names[k]);
    rc = aq_test_run(args, out, OUT_CAP, err, sizeof err);
    char want[64];
    snprintf(want, sizeof want, "usage: archquake %s ", names[k]);
    aq_check(rc == 0 && strncmp(out, want, strlen(want)) == 0 && err[0] == '\0',
             "%s: exit %d, want \"%s...\", got \"%.60s\" %s", args, rc, want, out, err);
    snprintf(args, sizeof args, "help %s", names[k]);
    rc = aq_test_run(args, again, OUT_CAP, err, sizeof err);
    aq_check(rc == 0 && strcmp(out, again) == 0, "%s: exit %d, the text of %s --help", args,
             rc, names[k]);
  }
  /* every command of the table (not plot's figures) is among them */
  for (int c = 0; c < AQ_CMD_N; c++) {
    const char *name = aq_opt_commands[c].name;
    if (!name[0] || AQ_CMD_IS_FIGURE(c))
      continue;
    int found = 0;
    for (size_t k = 0; k < n; k++)
      found |= strcmp(names[k], name) == 0;
    aq_check(found, "archquake --help lists %s", name);
  }
done:
  free(out);
  free(again);
}

AQ_TEST(app_unknown_command_refused_naming_the_commands)
{
  static const char *const typos[] = {"frob", "capacty", "Info", "plot_suite"};
  char out[4096], err[4096], help[1 << 16];
  aq_test_run("--help", help, sizeof help, NULL, 0);
  char names[64][32];
  size_t n = listed(help, names, 64);
  for (size_t k = 0; k < sizeof typos / sizeof typos[0]; k++) {
    char args[128], quoted[64];
    snprintf(args, sizeof args, "%s --arch arches/thin.cfg", typos[k]);
    snprintf(quoted, sizeof quoted, "\"%s\"", typos[k]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    int all = n >= 10;
    for (size_t i = 0; i < n; i++)
      all &= strstr(err, names[i]) != NULL;
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 strstr(err, quoted) && all,
             "%s: exit %d (want 2), one line naming it and the %zu commands: %s", args, rc, n,
             err);
  }
  /* help with an unknown command: the same list */
  int rc = aq_test_run("help frob", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
               strstr(err, "\"frob\"") && strstr(err, "capacity"),
           "help frob: exit %d, %s", rc, err);
  /* a record that does not exist is the main job's: named as a record */
  rc = aq_test_run("nosuch.AT2 --arch arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "nosuch.AT2: cannot open") && !strstr(err, "commands:"),
           "nosuch.AT2: exit %d, %s", rc, err);
}

AQ_TEST(app_version_and_help_are_main_job_options)
{
  char out[4096], err[4096];
  int rc = aq_test_run("--version", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strncmp(out, "archquake ", 10) == 0 && aq_test_count_lines(out) == 1 &&
               err[0] == '\0',
           "--version: exit %d, \"%s\"", rc, out);
  static char h[1 << 16], hh[1 << 16], none[1 << 16];
  int r1 = aq_test_run("--help", h, sizeof h, NULL, 0);
  int r2 = aq_test_run("-h", hh, sizeof hh, NULL, 0);
  int r3 = aq_test_run("help", none, sizeof none, NULL, 0);
  aq_check(r1 == 0 && r2 == 0 && r3 == 0 && strcmp(h, hh) == 0 && strcmp(h, none) == 0 &&
               strstr(h, "  --version "),
           "--help, -h and help: exit %d %d %d, one text listing --version", r1, r2, r3);
  rc = aq_test_run("info --version", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "info: --version: not an option of this command"),
           "info --version: exit %d, %s", rc, err);
}
