/* main.c: archquake's entry point.  It only dispatches to a subcommand
 * (src/app); every stage lives in its own module:
 *   src/io -> src/signal -> src/arch -> src/report.
 *
 * archquake implements the work-path approach of Stockdale, Sarhosis &
 * Milani, with the departures from the printed formulas that docs/method.md
 * gives (each with its reason).
 */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "app/app.h"
#include "app/opt_table.h"

static const struct {
  const char *name;
  int (*fn)(int, char **);
} commands[] = {
    {"info", aq_cmd_info},       {"mechanism", aq_cmd_mechanism},
    {"pulse", aq_cmd_pulse},     {"domain", aq_cmd_domain},
    {"compare", aq_cmd_compare}, {"plot", aq_cmd_plot},
    {"capacity", aq_cmd_capacity}, {"report", aq_cmd_report},
    {"spectrum", aq_cmd_spectrum},
};

/* The main job's usage and the command list, on stdout. */
static void usage(void)
{
  fflush(stdout);
  aq_opts_main_help(stdout);
}

/* 1 if name is a command (archquake-mpi runs those on rank 0 alone). */
int aq_main_is_command(const char *name);
int aq_main_is_command(const char *name)
{
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (strcmp(name, commands[i].name) == 0)
      return 1;
  return 0;
}

/* archquake-mpi builds this file as aq_main_serial, called by its own main
 * (src/app/mpi.c). */
#ifndef AQ_MAIN
#define AQ_MAIN main
#endif
int AQ_MAIN(int argc, char **argv);
int AQ_MAIN(int argc, char **argv)
{
  gsl_set_error_handler_off(); /* GSL's default handler aborts */
  aq_app_heap_policy();        /* records' arrays stay in the heap */
  if (argc < 2) { /* nothing to run: the usage, and the status of a usage error */
    usage();
    return AQ_EXIT_USAGE;
  }
  if (strcmp(argv[1], "--version") == 0) {
    printf("archquake %s\n", AQ_VERSION);
    return AQ_EXIT_OK;
  }
  int help = strcmp(argv[1], "help") == 0;
  if (help && argc >= 3) { /* archquake help COMMAND = archquake COMMAND --help */
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
      if (strcmp(argv[2], commands[i].name) == 0) {
        char h[] = "--help";
        char *av[] = {argv[2], h, NULL};
        return commands[i].fn(2, av);
      }
    fprintf(stderr, "archquake: help: expected a command (");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
      fprintf(stderr, "%s%s", i ? ", " : "", commands[i].name);
    fprintf(stderr, "), got \"%s\"\n", argv[2]);
    return AQ_EXIT_USAGE;
  }
  if (help || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
    usage();
    return AQ_EXIT_OK;
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (strcmp(argv[1], commands[i].name) == 0)
      return commands[i].fn(argc - 1, argv + 1);
  return aq_cmd_run(argc, argv);
}
