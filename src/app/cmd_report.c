/* cmd_report.c: `archquake report RESULTS.h5 [CAPACITY.h5 ...] -o
 * report.html`: check the options, then write the page with the page
 * stage (src/page) in this one thread. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h> /* optind */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "../page/page.h"
#include "app.h"
#include "../util/cleanup.h"
#include "opt.h"
#include "opt_table.h"

int aq_cmd_report(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_REPORT);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_REPORT, argc, argv, &o, &nerr)) { /* --help */
    aq_opts_free(&o);
    return AQ_EXIT_OK;
  }
  const char *out = o.output;
  if (optind >= argc) {
    fprintf(stderr, "archquake: report: expected a results file (.h5), got none\n");
    nerr++;
  }
  if (out) {
    const char *dot = strrchr(out, '.');
    if (!dot || (strcasecmp(dot, ".html") != 0 && strcasecmp(dot, ".htm") != 0)) {
      fprintf(stderr, "archquake: -o: expected a .html file, got \"%s\"\n", out);
      nerr++;
    }
    nerr += aq_opt_output_special("-o", out);
    for (int i = optind; i < argc; i++)
      if (aq_opt_same_file(out, argv[i])) {
        fprintf(stderr, "archquake: -o: expected a file other than the inputs, got \"%s\"\n",
                out);
        nerr++;
      }
  }
  aq_opts_free(&o);
  if (nerr)
    return AQ_EXIT_USAGE;
  /* the command line, shown at the page's end */
  size_t len = 1;
  for (int i = 0; i < argc; i++)
    len += strlen(argv[i]) + 1;
  char *cmd = malloc(len + 10);
  if (cmd) {
    strcpy(cmd, "archquake");
    for (int i = 0; i < argc; i++) {
      strcat(cmd, " ");
      strcat(cmd, argv[i]);
    }
  }
  /* the results file of the main job (the first of that kind), then every
     other file in the order given; a file that cannot be told is refused */
  const char **others = malloc((size_t)(argc - optind + 1) * sizeof *others);
  const char *results = NULL;
  size_t nothers = 0;
  aq_error err;
  aq_error_clear(&err);
  for (int i = optind; others && i < argc; i++) {
    aq_page_kind kind;
    if (aq_page_file_kind(argv[i], &kind, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      free(others);
      free(cmd);
      return AQ_EXIT_FAIL;
    }
    if (kind == AQ_PAGE_RESULTS && !results)
      results = argv[i];
    else
      others[nothers++] = argv[i];
  }
  if (!others) {
    free(cmd);
    fprintf(stderr, "archquake: report: out of memory\n");
    return AQ_EXIT_FAIL;
  }
  aq_page_input in = {results, others, nothers, cmd, aq_build_string()};
  aq_cleanup_install(); /* a signal removes the page's temporaries (src/page) */
  aq_page_stats st;
  aq_status rc = aq_page_write(&in, out, &st, &err);
  free(others);
  free(cmd);
  if (rc != AQ_OK) {
    aq_error_print(&err, stderr);
    return rc == AQ_EIO ? AQ_EXIT_OUTPUT : AQ_EXIT_FAIL;
  }
  return AQ_EXIT_OK;
}
