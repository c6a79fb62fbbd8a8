/* cmd_run.c: placeholder until the stage behind it lands. */
#include <stdio.h>

#include "app.h"

int aq_cmd_run(int argc, char **argv)
{
  (void)argc;
  (void)argv;
  fprintf(stderr, "archquake: run: not available in this build\n");
  return AQ_EXIT_USAGE;
}
