/* opt_suite.c: --suite FILE of the main job and capacity (opt_suite.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_suite.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void aq_opt_suite_free(aq_opt_suite *s)
{
  aq_suite_file_free(&s->file);
  free(s->argv);
  free(s->factors);
  memset(s, 0, sizeof *s);
}

int aq_opt_suite_take(const char *path, int *argc, char ***argv, int optind_,
                      aq_orient_opts *orient, aq_opt_suite *s, int *nerr)
{
  memset(s, 0, sizeof *s);
  if (*argc > optind_ || orient->nmotions) {
    fprintf(stderr, "archquake: --suite: expected no RECORD or --components with it (the "
                    "suite names the records), got %s\n",
            *argc > optind_ ? (*argv)[optind_] : orient->motions[0].label);
    (*nerr)++;
    return -1;
  }
  aq_error err;
  if (aq_suite_file_read(path, &s->file, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    (*nerr)++;
    return -1;
  }
  size_t n = s->file.n;
  s->argv = calloc((size_t)optind_ + n + 1, sizeof *s->argv);
  s->factors = malloc(n * sizeof *s->factors);
  if (!s->argv || !s->factors) {
    fprintf(stderr, "archquake: out of memory\n");
    aq_opt_suite_free(s);
    (*nerr)++;
    return -1;
  }
  memcpy(s->argv, *argv, (size_t)optind_ * sizeof *s->argv);
  for (size_t i = 0; i < n; i++) /* the plain records first, as the command runs them */
    if (!strchr(s->file.row[i].record, ',')) {
      s->factors[s->nplain] = s->file.row[i].scale;
      s->argv[optind_ + (int)s->nplain++] = s->file.row[i].record;
    }
  size_t k = s->nplain;
  int before = *nerr;
  for (size_t i = 0; i < n; i++)
    if (strchr(s->file.row[i].record, ',')) {
      aq_opt_components(s->file.row[i].record, orient, nerr);
      s->factors[k++] = s->file.row[i].scale;
    }
  if (*nerr != before) {
    aq_opt_suite_free(s);
    return -1;
  }
  *argv = s->argv;
  *argc = optind_ + (int)s->nplain;
  return 0;
}
