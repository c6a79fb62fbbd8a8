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
#include "../job/run.h"
#include "../units.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"

int aq_cmd_domain(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_DOMAIN);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_DOMAIN, argc, argv, &o, &nerr)) {
    aq_opts_free(&o);
    return AQ_EXIT_OK; /* --help */
  }
  const char *file = o.arch;
  double *ratios = o.ratios, cor = o.cor, rtol = o.ode_rtol, tol = o.domain_tol_s,
         tmax = o.max_duration_s;
  size_t nr = o.nratios;
  int model = o.model;
  o.ratios = NULL; /* freed here */
  aq_opts_free(&o);
  aq_opt_no_operands("domain", argc, argv, optind, &nerr);
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
  aq_arch_options ao = {.friction = o.friction};
  if (aq_arch_load_opts(file, &ao, &arch, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    goto out;
  }
  const aq_arch_dynamics *dyn = aq_arch_dynamics_of(arch);
  if (aq_opt_cor_momentum(file, !isnan(cor), dyn->impact == AQ_IMPACT_MOMENTUM)) {
    status = AQ_EXIT_USAGE;
    goto out;
  }
  const aq_path *pp = aq_arch_path(arch, 0);
  /* each row's shortest collapsing pulse marked as the main job's runs
   * (docs/demand.md), when a mark can apply */
  const int marks = aq_job_marks_apply(arch, (aq_model)model);
  aq_opt_friction_paper(file, model == AQ_MODEL_PAPER, aq_arch_friction(arch), 0);
  st = aq_job_stepper(arch, (aq_model)model, cor, 0,
                      marks ? AQ_JOB_DEMAND_MARKS : AQ_JOB_DEMAND_NONE, &err);
  if (!st) {
    aq_error_print(&err, stderr);
    goto out;
  }
  aq_stepper_set_ode_rtol(st, rtol);
  printf("ratio\taccel_g\tmin_duration_s\tstatus\n");
  for (size_t i = 0; i < nr; i++) {
    double a, dur;
    aq_result run;
    if (aq_domain_min_duration_run(st, pp, ratios[i], tol, tmax, &a, &dur, &run, &err) !=
        AQ_OK) {
      aq_result_free(&run);
      goto runfail;
    }
    int mk = marks && !isinf(dur) ? aq_job_run_marks(arch, &run) : 0;
    aq_result_free(&run);
    printf("%s\t%s\t%s\t%s\n", AQ_TEXT_NUM(ratios[i]), AQ_TEXT_NUM(a / AQ_G0_MPS2),
           isinf(dur) ? "inf" : AQ_TEXT_NUM(dur), isinf(dur) ? "-" : aq_result_marks_name(mk));
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
