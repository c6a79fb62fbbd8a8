/* opt_orient.h: the values of the ground-motion orientation options (the
 * main job and capacity), their handlers and the check between them:
 *   --components H1,H2[,V]  one ground motion from two horizontal component
 *                           records and optionally the vertical (repeatable)
 *   --azimuths A1,A2        the azimuths (deg from north) of the preceding
 *                           --components' H1 and H2, for files that state none
 *   --azimuth DEG           the arch's +x azimuth (deg from north, default 0)
 *   --azimuth all[:STEP]    every azimuth 0, STEP, ... < 360 (default 5 deg);
 *                           the TSV shows the worst per (motion, arch, scale)
 *   --all-azimuths          with --azimuth all: every azimuth's row in the TSV
 *   --vertical              run the vertical component V as well
 * Their rows in opt_table.c call aq_opt_components, aq_opt_azimuths and
 * aq_opt_azimuth; a command calls aq_opt_orient_check() once all options are
 * in, aq_opt_orient_free() at the end.  Bad values are reported as one line
 * on stderr each and counted in *nerr.
 */
#ifndef AQ_APP_OPT_ORIENT_H
#define AQ_APP_OPT_ORIENT_H

#include <stddef.h>

/* The default step of --azimuth all, deg. */
#define AQ_OPT_ORIENT_STEP_DEFAULT_DEG 5.0

/* One ground motion given by --components. */
typedef struct {
  char *label;           /* the argument as given (the rows' record column) */
  char *path[3];         /* H1, H2 and V (NULL if not given) */
  double azimuth_deg[2]; /* --azimuths, or NAN: from the files */
} aq_orient_motion;

typedef struct {
  aq_orient_motion *motions; /* in the order given */
  size_t nmotions;
  double *azimuths_deg;      /* the arch azimuths to run (default {0}) */
  size_t nazimuth;
  int scan;                  /* --azimuth all */
  int all_azimuths;          /* --all-azimuths */
  int vertical;              /* --vertical */
  int azimuth_given;         /* --azimuth given */
} aq_orient_opts;

/* Zero o and set the defaults. */
void aq_opt_orient_init(aq_orient_opts *o);
/* --components H1,H2[,V], --azimuths A1,A2, --azimuth DEG|all[:STEP]:
 * check arg and add it to o (a bad one: one line on stderr, *nerr += 1). */
void aq_opt_components(const char *arg, aq_orient_opts *o, int *nerr);
void aq_opt_azimuths(const char *arg, aq_orient_opts *o, int *nerr);
void aq_opt_azimuth(const char *arg, aq_orient_opts *o, int *nerr);
/* Check the combination once all options are in (--all-azimuths without
 * --azimuth all, --azimuth or --vertical without --components, the same
 * file twice in a motion). */
void aq_opt_orient_check(aq_orient_opts *o, int *nerr);
void aq_opt_orient_free(aq_orient_opts *o);

#endif
