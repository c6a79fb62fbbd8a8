/* cmd_report.c: `archquake report RESULTS.h5 [CAPACITY.h5 ...] -o
 * report.html`: check the options, then write the page with the page
 * stage (src/page) in this one thread. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "../page/figure.h"
#include "../page/page.h"
#include "app.h"
#include "../util/cleanup.h"
#include "opt.h"

static const char usage[] =
    "usage: archquake report RESULTS.h5 [CAPACITY.h5 ...] -o REPORT.html\n"
    "One self-contained HTML page of a screening, to hand on: per arch its\n"
    "verdict table (sortable, filterable by verdict) and figures (the arch\n"
    "and its hinge sets, the suite's verdict map, the history of each\n"
    "collapsed run and of the strongest surviving one when the results hold\n"
    "histories), the capacity files' first collapses, collapse intervals,\n"
    "fragility curves and the ranking of the intensity measures, the failed\n"
    "records with their reasons, and the run: command line, build, date,\n"
    "options, every record and every arch.  Figures are inline SVG, text as\n"
    "text; nothing is fetched; it prints on A4 and Letter.\n"
    "RESULTS.h5 is the main job's results file (archquake ... -o), each\n"
    "CAPACITY.h5 one of archquake capacity -o.\n"
    "Options:\n"
    "  -o, --output FILE  the page (.html)\n"
    "  --help             this text\n"
    "Exit status: 0 written, 1 an input could not be read, 2 bad options,\n"
    "3 the page could not be written.  No partial file is left under FILE.\n";

int aq_cmd_report(int argc, char **argv)
{
  static const struct option longopts[] = {{"output", required_argument, NULL, 'o'},
                                           {"help", no_argument, NULL, 'h'},
                                           {NULL, 0, NULL, 0}};
  const char *out = NULL;
  int nerr = 0, c;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":o:", longopts, NULL)) != -1) {
    if (c == 'h') {
      fputs(usage, stdout);
      return AQ_EXIT_OK;
    }
    if (c == 'o')
      out = optarg;
    else
      aq_opt_unknown("report", argv, optind, optopt, &nerr);
  }
  if (optind >= argc) {
    fprintf(stderr, "archquake: report: expected a results file (.h5), got none\n");
    nerr++;
  }
  aq_opt_require("report", "-o FILE", out != NULL, &nerr);
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
  aq_page_input in = {argv[optind], (const char *const *)argv + optind + 1,
                      (size_t)(argc - optind - 1), cmd, aq_build_string()};
  char tmp[2][1100];
  snprintf(tmp[0], sizeof tmp[0], "%s.tmp.%ld", out, (long)getpid());
  aq_page_figure_temp(out, tmp[1], sizeof tmp[1]);
  aq_cleanup_install();
  int slot[2] = {aq_cleanup_add(tmp[0]), aq_cleanup_add(tmp[1])};
  aq_error err;
  aq_error_clear(&err);
  aq_page_stats st;
  aq_status rc = aq_page_write(&in, out, &st, &err);
  aq_cleanup_remove(slot[0]);
  aq_cleanup_remove(slot[1]);
  free(cmd);
  if (rc != AQ_OK) {
    aq_error_print(&err, stderr);
    return rc == AQ_EIO ? AQ_EXIT_OUTPUT : AQ_EXIT_FAIL;
  }
  return AQ_EXIT_OK;
}
