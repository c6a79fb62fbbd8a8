/* cmd_compare.c: placeholder until the stage behind it lands. */
#include <stdio.h>

#include "app.h"

int aq_cmd_compare(int argc, char **argv)
{
  (void)argc;
  (void)argv;
  fprintf(stderr, "archquake: compare: not available in this build\n");
  return AQ_EXIT_USAGE;
}
