/* cmd_domain.c: placeholder until the stage behind it lands. */
#include <stdio.h>

#include "app.h"

int aq_cmd_domain(int argc, char **argv)
{
  (void)argc;
  (void)argv;
  fprintf(stderr, "archquake: domain: not available in this build\n");
  return AQ_EXIT_USAGE;
}
