/* cmd_domain.c: `archquake domain --arch FILE [--ratios LIST] ...`: the
 * half-cycle collapse domain of the paper's section 4.1, computed by
 * aq_domain_min_duration (src/arch/domain.c) for each ratio. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/arch.h"
#include "../arch/domain.h"
#include "../arch/stepper.h"
#include "../units.h"
#include "app.h"
#include "opt.h"
#include "opt_arch.h"

/* Smallest --tol, s: a finer bisection of durations of 0.01-100 s would reach
 * the spacing of doubles, where hi - lo stops shrinking. */
#define AQ_DOMAIN_TOL_MIN_S 1e-12

static const char usage[] =
    "usage: archquake domain --arch FILE [OPTIONS]\n"
    "Half-cycle collapse domain: for each ratio r, the shortest rectangular\n"
    "pulse of r lambda0 g (direction opening the primary set) that collapses\n"
    "the arch, by bisection (the direction is the set's own, so domain takes no\n"
    "--polarity).\n"
    "  --arch FILE      the arch file (.cfg), or an installed arch by name\n"
    "  --ratios LIST    comma-separated r > 1 (default 1.05,1.1,1.2,1.5,2,3,4)\n"
    "  --cor C          kinetic-energy ratio kept at an impact, 0..1 (default:\n"
    "                   the arch file's [dynamics] cor; refused with impact\n"
    "                   momentum, which the runs then follow)\n"
    "  --model M        workpath (default) | ode | paper | workpath-quad\n"
    "  --ode-rtol R     ode model tolerance (default 1e-10; only with --model ode)\n"
    "  --tol S          bisection tolerance on the duration, s, 1e-12..1 (default 1e-9)\n"
    "  --max-duration S give up above this duration, s (default 100)\n"
    "  --help           this text\n"
    "Columns: ratio accel_g min_duration_s (inf: no collapse up to\n"
    "  --max-duration)\n"
    "Exit status: 0 success, 1 the arch or a run failed, 2 bad options (or an\n"
    "option the arch makes ineffective, as --cor with impact momentum).\n";

static const char *const models[] = {"workpath", "ode", "paper", "workpath-quad", NULL};

int aq_cmd_domain(int argc, char **argv)
{
  static const struct option longopts[] = {
      {"arch", required_argument, NULL, 'a'},
      {"ratios", required_argument, NULL, 'R'},
      {"cor", required_argument, NULL, 'c'},
      {"model", required_argument, NULL, 'm'},
      {"ode-rtol", required_argument, NULL, 'r'},
      {"tol", required_argument, NULL, 't'},
      {"max-duration", required_argument, NULL, 'M'},
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  const char *file = NULL;
  double *ratios = NULL, cor = NAN, rtol = 1e-10, tol = 1e-9, tmax = 100;
  size_t nr = 0;
  int model = 0, nerr = 0, c, rtol_given = 0;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
    switch (c) {
    case 'a':
      file = aq_opt_arch(optarg, &nerr);
      break;
    case 'R':
      aq_opt_list("--ratios", optarg, 1, &ratios, &nr, &nerr);
      break;
    case 'c':
      aq_opt_double("--cor", optarg, 0, 1, &cor, &nerr);
      break;
    case 'm':
      aq_opt_choice("--model", optarg, models, &model, &nerr);
      break;
    case 'r':
      aq_opt_double_gt("--ode-rtol", optarg, 0, 0.1, &rtol, &nerr);
      rtol_given = 1;
      break;
    case 't':
      aq_opt_double("--tol", optarg, AQ_DOMAIN_TOL_MIN_S, 1, &tol, &nerr);
      break;
    case 'M':
      aq_opt_double_gt("--max-duration", optarg, 0, 3600, &tmax, &nerr);
      break;
    case 'h':
      free(ratios);
      fputs(usage, stdout);
      return AQ_EXIT_OK;
    default:
      aq_opt_unknown("domain", argv, optind, optopt, &nerr);
    }
  }
  aq_opt_no_operands("domain", argc, argv, optind, &nerr);
  aq_opt_require("domain", "--arch FILE", file != NULL, &nerr);
  aq_opt_ode_rtol(rtol_given, models[model], &nerr);
  for (size_t i = 0; i < nr; i++)
    if (!(ratios[i] <= 1000)) {
      fprintf(stderr, "archquake: --ratios: expected ratios in (1, 1000], "
                      "got %g\n", ratios[i]);
      nerr++;
      break;
    }
  if (nerr) {
    free(ratios);
    return AQ_EXIT_USAGE;
  }
  if (!ratios) {
    static const double def[] = {1.05, 1.1, 1.2, 1.5, 2, 3, 4};
    nr = sizeof def / sizeof def[0];
    ratios = malloc(sizeof def);
    if (!ratios) {
      fprintf(stderr, "archquake: domain: out of memory\n");
      return AQ_EXIT_FAIL;
    }
    memcpy(ratios, def, sizeof def);
  }

  aq_error err;
  aq_error_clear(&err);
  aq_arch *arch = NULL;
  int status = AQ_EXIT_FAIL;
  aq_stepper *st = NULL;
  if (aq_arch_load(file, &arch, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    goto out;
  }
  const aq_arch_dynamics *dyn = aq_arch_dynamics_of(arch);
  if (aq_opt_cor_momentum(file, !isnan(cor), dyn->impact == AQ_IMPACT_MOMENTUM)) {
    status = AQ_EXIT_USAGE;
    goto out;
  }
  const aq_path *pp = aq_arch_path(arch, 0);
  st = aq_stepper_alloc(pp, aq_arch_path(arch, 1), (aq_model)model, &err);
  if (!st) {
    aq_error_print(&err, stderr);
    goto out;
  }
  aq_stepper_set_cor(st, isnan(cor) ? dyn->cor : cor);
  aq_stepper_set_impact(st, dyn->impact == AQ_IMPACT_MOMENTUM);
  aq_stepper_set_ode_rtol(st, rtol);
  printf("ratio\taccel_g\tmin_duration_s\n");
  for (size_t i = 0; i < nr; i++) {
    double a, dur;
    if (aq_domain_min_duration(st, pp, ratios[i], tol, tmax, &a, &dur, &err) != AQ_OK)
      goto runfail;
    if (isinf(dur))
      printf("%.9g\t%.9g\tinf\n", ratios[i], a / AQ_G0_MPS2);
    else
      printf("%.9g\t%.9g\t%.12g\n", ratios[i], a / AQ_G0_MPS2, dur);
  }
  status = fflush(stdout) == 0 ? AQ_EXIT_OK : AQ_EXIT_OUTPUT;
  goto out;
runfail:
  snprintf(err.input, sizeof err.input, "%s", file);
  aq_error_print(&err, stderr);
out:
  free(ratios);
  aq_stepper_free(st);
  aq_arch_free(arch);
  return status;
}
