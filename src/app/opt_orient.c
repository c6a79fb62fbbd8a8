/* opt_orient.c: the orientation options (see opt_orient.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_orient.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "opt.h"

#define AQ_DEG_FULL_TURN 360.0

void aq_opt_orient_init(aq_orient_opts *o)
{
  memset(o, 0, sizeof *o);
}

void aq_opt_orient_free(aq_orient_opts *o)
{
  for (size_t i = 0; i < o->nmotions; i++) {
    free(o->motions[i].label);
    for (int j = 0; j < 3; j++)
      free(o->motions[i].path[j]);
  }
  free(o->motions);
  free(o->azimuths_deg);
  memset(o, 0, sizeof *o);
}

static void oom(int *nerr)
{
  fprintf(stderr, "archquake: out of memory\n");
  (*nerr)++;
}

void aq_opt_components(const char *arg, aq_orient_opts *o, int *nerr)
{
  arg = arg ? arg : "";
  char *parts[4] = {NULL, NULL, NULL, NULL};
  size_t n = 0;
  const char *p = arg;
  int empty = 0;
  while (n < 4) {
    const char *q = strchr(p, ',');
    size_t len = q ? (size_t)(q - p) : strlen(p);
    empty |= len == 0;
    parts[n++] = strndup(p, len);
    if (!q)
      break;
    p = q + 1;
  }
  if (n < 2 || n > 3 || empty) {
    fprintf(stderr, "archquake: --components: expected H1,H2 or H1,H2,V (two or three "
                    "record files), got \"%s\"\n", arg);
    (*nerr)++;
    for (size_t j = 0; j < n; j++)
      free(parts[j]);
    return;
  }
  aq_orient_motion *m = realloc(o->motions, (o->nmotions + 1) * sizeof *m);
  if (!m) {
    for (size_t j = 0; j < n; j++)
      free(parts[j]);
    oom(nerr);
    return;
  }
  o->motions = m;
  m = &o->motions[o->nmotions++];
  memset(m, 0, sizeof *m);
  m->label = strdup(arg);
  for (size_t j = 0; j < n; j++)
    m->path[j] = parts[j];
  m->azimuth_deg[0] = m->azimuth_deg[1] = NAN;
}

void aq_opt_azimuths(const char *arg, aq_orient_opts *o, int *nerr)
{
  arg = arg ? arg : "";
  if (o->nmotions == 0) {
    fprintf(stderr, "archquake: --azimuths: expected after the --components it "
                    "describes, got \"%s\" before any\n", arg);
    (*nerr)++;
    return;
  }
  aq_orient_motion *m = &o->motions[o->nmotions - 1];
  double *v = NULL;
  size_t n = 0;
  int e0 = *nerr;
  aq_opt_list("--azimuths", arg, -AQ_DEG_FULL_TURN, INFINITY, &v, &n, nerr);
  if (*nerr > e0)
    return;
  if (n != 2 || v[0] > AQ_DEG_FULL_TURN || v[1] > AQ_DEG_FULL_TURN) {
    fprintf(stderr, "archquake: --azimuths: expected A1,A2 (two azimuths in deg, "
                    "-360..360), got \"%s\"\n", arg);
    (*nerr)++;
  } else {
    m->azimuth_deg[0] = v[0];
    m->azimuth_deg[1] = v[1];
  }
  free(v);
}

void aq_opt_azimuth(const char *arg, aq_orient_opts *o, int *nerr)
{
  arg = arg ? arg : "";
  double step = AQ_OPT_ORIENT_STEP_DEFAULT_DEG, one = 0;
  int scan = strncmp(arg, "all", 3) == 0 && (arg[3] == '\0' || arg[3] == ':');
  int e0 = *nerr;
  if (scan && arg[3] == ':')
    aq_opt_double_gt("--azimuth all:STEP", arg + 4, 0, AQ_DEG_FULL_TURN / 2, &step, nerr);
  else if (!scan)
    aq_opt_double("--azimuth", arg, -AQ_DEG_FULL_TURN, AQ_DEG_FULL_TURN, &one, nerr);
  if (*nerr > e0)
    return;
  size_t n = scan ? (size_t)ceil(AQ_DEG_FULL_TURN / step - 1e-9) : 1;
  double *v = malloc(n * sizeof *v);
  if (!v) {
    oom(nerr);
    return;
  }
  for (size_t i = 0; i < n; i++)
    v[i] = scan ? (double)i * step : one;
  free(o->azimuths_deg);
  o->azimuths_deg = v;
  o->nazimuth = n;
  o->scan = scan;
  o->azimuth_given = 1;
}

void aq_opt_orient_check(aq_orient_opts *o, int *nerr)
{
  if (o->all_azimuths && !o->scan) {
    fprintf(stderr, "archquake: --all-azimuths: expected --azimuth all[:STEP] as well "
                    "(it shows every azimuth of the scan)\n");
    (*nerr)++;
  }
  int have_v = 0;
  for (size_t i = 0; i < o->nmotions; i++) {
    aq_orient_motion *m = &o->motions[i];
    have_v |= m->path[2] != NULL;
    for (int a = 0; a < 3 && m->path[a]; a++)
      for (int b = 0; b < a; b++)
        if (aq_opt_same_file(m->path[a], m->path[b])) {
          fprintf(stderr, "archquake: --components: expected distinct files, got "
                          "\"%s\" and \"%s\", the same file, in \"%s\"\n",
                  m->path[b], m->path[a], m->label);
          (*nerr)++;
        }
    for (size_t j = 0; j < i; j++)
      if (strcmp(o->motions[j].label, m->label) == 0) {
        fprintf(stderr, "archquake: --components: expected distinct ground motions, "
                        "got \"%s\" twice\n", m->label);
        (*nerr)++;
      }
  }
  if (o->vertical && !have_v) {
    fprintf(stderr, "archquake: --vertical: expected --components H1,H2,V with a "
                    "vertical component, got none\n");
    (*nerr)++;
  }
  if (!o->azimuths_deg) {
    o->azimuths_deg = calloc(1, sizeof *o->azimuths_deg);
    if (!o->azimuths_deg)
      oom(nerr);
    o->nazimuth = 1;
  }
}
