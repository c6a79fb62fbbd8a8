/* main.c: archquake's entry point.  It only dispatches to a subcommand
 * (src/app); every stage lives in its own module:
 *   src/io -> src/signal -> src/arch -> src/report.
 *
 * archquake implements the work-path approach of
 *   G. L. Stockdale, V. Sarhosis, G. Milani, "Work-path approach seismic
 *   modelling of hinge-controlled masonry arches" (the paper in docs and
 *   ../shared/paper), with the corrections of its ERRATA.md.
 */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "app/app.h"

static const struct {
  const char *name;
  int (*fn)(int, char **);
} commands[] = {
    {"info", aq_cmd_info},       {"mechanism", aq_cmd_mechanism},
    {"pulse", aq_cmd_pulse},     {"domain", aq_cmd_domain},
    {"compare", aq_cmd_compare},   {"capacity", aq_cmd_capacity},
};

int main(int argc, char **argv)
{
  gsl_set_error_handler_off(); /* GSL's default handler aborts */
  if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
    printf("archquake %s\n", AQ_VERSION);
    return AQ_EXIT_OK;
  }
  if (argc >= 2)
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
      if (strcmp(argv[1], commands[i].name) == 0)
        return commands[i].fn(argc - 1, argv + 1);
  return aq_cmd_run(argc, argv);
}
