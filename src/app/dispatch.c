/* dispatch.c: archquake's command line to a command (app.h): the commands
 * by name, help and the version; anything else is the main job.  Called by
 * main (src/main.c) and by archquake-mpi's main (mpi.c). */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "app.h"
#include "opt_table.h"

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

int aq_app_is_command(const char *name)
{
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (strcmp(name, commands[i].name) == 0)
      return 1;
  return 0;
}

int aq_app_is_main_job(int argc, char **argv)
{
  static const char *const other[] = {"help", "-h", "--help", "--version"};
  if (argc < 2 || aq_app_is_command(argv[1]))
    return 0;
  for (size_t k = 0; k < sizeof other / sizeof other[0]; k++)
    if (strcmp(argv[1], other[k]) == 0)
      return 0;
  return 1;
}

int aq_app_main(int argc, char **argv)
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
