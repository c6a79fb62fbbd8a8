/* opt_orient.h: the ground-motion orientation options, declared once for
 * every command that runs records:
 *   --components H1,H2[,V]  one ground motion from two horizontal component
 *                           records and optionally the vertical (repeatable)
 *   --azimuths A1,A2        the azimuths (deg from north) of the preceding
 *                           --components' H1 and H2, for files that state none
 *   --azimuth DEG           the arch's +x azimuth (deg from north, default 0)
 *   --azimuth all[:STEP]    every azimuth 0, STEP, ... < 360 (default 5 deg);
 *                           the TSV shows the worst per (motion, arch, scale)
 *   --all-azimuths          with --azimuth all: every azimuth's row in the TSV
 *   --vertical              run the vertical component V as well
 * Use as opt_record.h: AQ_OPT_ORIENT_LONGOPTS in the getopt_long table,
 * every id through aq_opt_orient_handle(), aq_opt_orient_check() once all
 * options are in, aq_opt_orient_free() at the end.  Bad values are reported
 * as one line on stderr each and counted in *nerr.
 */
#ifndef AQ_APP_OPT_ORIENT_H
#define AQ_APP_OPT_ORIENT_H

#include <getopt.h>
#include <stddef.h>

/* Option ids (the range 1300-1399 belongs to the orientation options). */
enum {
  AQ_OPT_ORIENT_COMPONENTS = 1300,
  AQ_OPT_ORIENT_AZIMUTHS,
  AQ_OPT_ORIENT_AZIMUTH,
  AQ_OPT_ORIENT_ALL_AZIMUTHS,
  AQ_OPT_ORIENT_VERTICAL
};

#define AQ_OPT_ORIENT_LONGOPTS                                               \
  {"components", required_argument, NULL, AQ_OPT_ORIENT_COMPONENTS},         \
      {"azimuths", required_argument, NULL, AQ_OPT_ORIENT_AZIMUTHS},         \
      {"azimuth", required_argument, NULL, AQ_OPT_ORIENT_AZIMUTH},           \
      {"all-azimuths", no_argument, NULL, AQ_OPT_ORIENT_ALL_AZIMUTHS},       \
      {"vertical", no_argument, NULL, AQ_OPT_ORIENT_VERTICAL}

#define AQ_OPT_ORIENT_USAGE                                                       \
  "  --components H1,H2[,V]  one ground motion from two orthogonal horizontal\n" \
  "                      component records (and the vertical V); repeatable.\n"  \
  "                      The arch feels a_x = a1 cos(theta - phi1) +\n"          \
  "                      a2 cos(theta - phi2).  The components must share dt\n"  \
  "                      and start time; the samples they share are run\n"       \
  "  --azimuths A1,A2    azimuths phi1, phi2 (deg from north) of the preceding\n" \
  "                      --components (default: from the files, e.g. PEER's\n"  \
  "                      GIL067 is 67 deg)\n"                                   \
  "  --azimuth DEG       the arch's +x azimuth theta, deg from north (default 0)\n" \
  "  --azimuth all[:STEP]  every theta 0, STEP, ... < 360 (default STEP 5); the\n" \
  "                      TSV shows the worst azimuth per (motion, arch, scale):\n" \
  "                      a failed run, else a collapse (the earliest), else the\n" \
  "                      largest peak_rotation_over_qc; the HDF5 file has all\n" \
  "  --all-azimuths      with --azimuth all: every azimuth's row in the TSV\n"   \
  "  --vertical          run the vertical component V too (without it a V is\n" \
  "                      ignored, with a warning); a step with g + a_v <= 0\n" \
  "                      stops the run: status run:eliftoff\n"

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
/* Handle option id: 1 if it is one of the orientation options, else 0. */
int aq_opt_orient_handle(int id, const char *arg, aq_orient_opts *o, int *nerr);
/* Check the combination once all options are in (--all-azimuths without
 * --azimuth all, --azimuth or --vertical without --components, the same
 * file twice in a motion). */
void aq_opt_orient_check(aq_orient_opts *o, int *nerr);
void aq_opt_orient_free(aq_orient_opts *o);

#endif
