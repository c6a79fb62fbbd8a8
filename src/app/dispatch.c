/* dispatch.c: archquake's command line to a command (app.h).  The commands
 * are the rows of the table of commands (aq_opt_commands, opt_table.c):
 * their names, entry points and help; anything else is the main job, whose
 * options include --help and --version.  Called by main (src/main.c) and
 * by archquake-mpi's main (mpi.c). */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "opt.h"
#include "opt_table.h"

/* 1 if word looks like a command, not a record: a word of letters, digits,
 * '-' and '_' (no '.', '/', '#' or glob character) naming no file. */
static int looks_like_command(const char *word)
{
  if (!word[0] || word[0] == '-' || word[strspn(word, "abcdefghijklmnopqrstuvwxyz"
                                                   "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                   "0123456789-_")] != '\0')
    return 0;
  return access(word, F_OK) != 0;
}

/* The line that refuses word, which names no command (what: how it was
 * taken, e.g. "a command or an existing RECORD"). */
static void no_command(const char *prefix, const char *word, const char *what)
{
  char names[512];
  aq_opt_command_names(names, sizeof names);
  fprintf(stderr, "archquake: %sexpected %s, got \"%s\" (commands: %s)\n", prefix, what,
          word, names);
}

/* Each command's entry point, by its row in aq_opt_commands: argv[0] is
 * its name (the main job: the program's).  plot's figures have none:
 * plot's entry point runs them. */
static int (*const entry[AQ_CMD_N])(int argc, char **argv) = {
    [AQ_CMD_RUN] = aq_cmd_run,         [AQ_CMD_INFO] = aq_cmd_info,
    [AQ_CMD_MECHANISM] = aq_cmd_mechanism, [AQ_CMD_PULSE] = aq_cmd_pulse,
    [AQ_CMD_DOMAIN] = aq_cmd_domain,   [AQ_CMD_COMPARE] = aq_cmd_compare,
    [AQ_CMD_CAPACITY] = aq_cmd_capacity, [AQ_CMD_REPORT] = aq_cmd_report,
    [AQ_CMD_SPECTRUM] = aq_cmd_spectrum, [AQ_CMD_HELP] = aq_cmd_help,
    [AQ_CMD_SELECT] = aq_cmd_select,
    [AQ_CMD_PLOT] = aq_cmd_plot,
};

/* Run command c (a row of aq_opt_commands that is not a figure). */
static int run(const aq_opt_command *c, int argc, char **argv)
{
  return entry[c - aq_opt_commands](argc, argv);
}

int aq_cmd_help(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_HELP);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_HELP, argc, argv, &o, &nerr)) { /* help --help */
    aq_opts_free(&o);
    return AQ_EXIT_OK;
  }
  aq_opts_free(&o);
  const aq_opt_command *c = NULL;
  int arch_file = optind < argc && !strcmp(argv[optind], AQ_HELP_ARCH_FILE);
  if (optind < argc && !arch_file && !(c = aq_opt_command_named(argv[optind]))) {
    no_command("help: ", argv[optind], "a command or " AQ_HELP_ARCH_FILE);
    nerr++;
  }
  if (optind + 1 < argc)
    aq_opt_no_operands("help", argc, argv, optind + 1, &nerr);
  if (nerr)
    return AQ_EXIT_USAGE;
  if (arch_file) {
    aq_help_arch_file(stdout);
    return AQ_EXIT_OK;
  }
  if (!c) { /* archquake help: archquake --help */
    aq_opts_main_help(stdout);
    return AQ_EXIT_OK;
  }
  char h[] = "--help";
  char *av[] = {argv[optind], h, NULL};
  return run(c, 2, av);
}

int aq_app_farms(int argc, char **argv)
{
  if (argc < 2 || aq_opt_is(AQ_OPT_HELP, argv[1]) || aq_opt_is(AQ_OPT_VERSION, argv[1]))
    return 0;
  const aq_opt_command *c = aq_opt_command_named(argv[1]);
  if (!c && looks_like_command(argv[1]))
    return 0; /* refused */
  return (c ? c : &aq_opt_commands[AQ_CMD_RUN])->farmed;
}

int aq_app_main(int argc, char **argv)
{
  gsl_set_error_handler_off(); /* GSL's default handler aborts */
  aq_app_heap_policy();        /* records' arrays stay in the heap */
  if (argc < 2) { /* nothing to run: the usage, and the status of a usage error */
    fflush(stdout);
    aq_opts_main_help(stdout);
    return AQ_EXIT_USAGE;
  }
  const aq_opt_command *c = aq_opt_command_named(argv[1]);
  if (c)
    return run(c, argc - 1, argv + 1);
  if (looks_like_command(argv[1])) {
    no_command("", argv[1], "a command or an existing RECORD");
    return AQ_EXIT_USAGE;
  }
  return entry[AQ_CMD_RUN](argc, argv);
}
