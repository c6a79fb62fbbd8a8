/* cmd_pulse.c: `archquake pulse --arch FILE --accel-g A --duration S ...`:
 * one arch under a rectangular ground-acceleration pulse; prints the run row
 * (TSV header + row) and optionally the history as CSV. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../arch/arch.h"
#include "../arch/stepper.h"
#include "../blocks/blocks.h"
#include "../job/run.h"
#include "../units.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"

/* Default end: candidate ends are duration + k * REST_CHUNK_S. */
static const double REST_CHUNK_S = 1.0;
static const double REST_CAP_S = 3600; /* after the pulse */
static const double REST_CAP_STEPS = 5e6;
static const double MAX_STEPS = 5e7;

/* Steps of at most dt_s: the pulse, then zero until end_s. */
static aq_status pulse_steps(double a_mps2, double dur_s, double end_s,
                             double dt_s, aq_steps *out, aq_error *err)
{
  size_t n1 = (size_t)ceil(dur_s / dt_s - 1e-9);
  size_t n2 = end_s > dur_s ? (size_t)ceil((end_s - dur_s) / dt_s - 1e-9) : 0;
  if (n1 < 1)
    n1 = 1;
  size_t n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d),
         *a = malloc(n * sizeof *a);
  aq_status rc;
  if (!t || !d || !a) {
    rc = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "steps", "out of memory");
  } else {
    for (size_t i = 0; i < n1; i++) {
      t[i] = dur_s * (double)i / (double)n1;
      d[i] = dur_s * (double)(i + 1) / (double)n1 - t[i];
      a[i] = a_mps2;
    }
    for (size_t i = 0; i < n2; i++) {
      double span = end_s - dur_s;
      t[n1 + i] = dur_s + span * (double)i / (double)n2;
      d[n1 + i] = dur_s + span * (double)(i + 1) / (double)n2 - t[n1 + i];
      a[n1 + i] = 0;
    }
    rc = aq_steps_from_list(t, d, a, n, out, err);
  }
  free(t);
  free(d);
  free(a);
  return rc;
}

/* The history as CSV at path, under a temporary renamed onto it when
 * complete (util/outfile.h); the block model's (b not NULL) with every
 * voussoir's centroid and rotation after the common columns.  Returns
 * AQ_OK, or the failure (err). */
static aq_status write_history(const char *path, const aq_history *h,
                               const aq_blocks_result *b, aq_error *err)
{
  aq_outfile o;
  aq_cleanup_install(); /* a signal removes the temporary */
  aq_status s = aq_outfile_open(&o, path, err);
  if (s != AQ_OK)
    return s;
  int bad = fprintf(o.f, "time_s,rotation_rad,displacement_m,kinetic_energy_j,"
                         "potential_energy_j,set") < 0;
  size_t nv = b ? b->nvous : 0;
  for (size_t k = 0; k < nv && !bad; k++)
    bad = fprintf(o.f, ",v%zu_x_m,v%zu_y_m,v%zu_rot_rad", k, k, k) < 0;
  bad = bad || fputc('\n', o.f) == EOF;
  for (size_t i = 0; i < h->n && !bad; i++) {
    bad = fprintf(o.f, "%s,%s,%s,%s,%s,%d", AQ_TEXT_NUM(h->time_s[i]),
                  AQ_TEXT_NUM(h->rotation_rad[i]), AQ_TEXT_NUM(h->displacement_m[i]),
                  AQ_TEXT_NUM(h->kinetic_energy_j[i]), AQ_TEXT_NUM(h->potential_energy_j[i]),
                  h->set[i]) < 0;
    for (size_t k = 0; k < nv && !bad; k++)
      bad = fprintf(o.f, ",%s,%s,%s", AQ_TEXT_NUM(b->hist_x_m[i * nv + k]),
                    AQ_TEXT_NUM(b->hist_y_m[i * nv + k]),
                    AQ_TEXT_NUM(b->hist_rot_rad[i * nv + k])) < 0;
    bad = bad || fputc('\n', o.f) == EOF;
  }
  if (bad) {
    s = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot write the history: %s",
                     strerror(errno));
    aq_outfile_abort(&o);
    return s;
  }
  return aq_outfile_commit(&o, err);
}

/* The block model of arch for pulse (aq_blocks_for_arch): 0 and *out, or
 * the exit status after one line naming the file and field (2 for the
 * friction it needs and was not given and for a [supports] spread_m beyond
 * the voussoirs' reach, as the main job and capacity refuse it; 1 for
 * another value of the arch file). */
static int pulse_blocks(const char *file, const aq_arch *arch, double dt_s, int history,
                        aq_blocks **out)
{
  *out = NULL;
  if (!isnan(aq_arch_friction(arch)) && aq_opt_blocks_spread(file, 1, arch))
    return AQ_EXIT_USAGE;
  aq_error err;
  aq_error_clear(&err);
  *out = aq_blocks_for_arch(arch, dt_s, &err);
  if (!*out) {
    snprintf(err.input, sizeof err.input, "%s", file);
    aq_error_print(&err, stderr);
    return isnan(aq_arch_friction(arch)) ? AQ_EXIT_USAGE : AQ_EXIT_FAIL;
  }
  aq_blocks_set_history(*out, history);
  return AQ_EXIT_OK;
}

int aq_cmd_pulse(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_PULSE);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_PULSE, argc, argv, &o, &nerr))
    return AQ_EXIT_OK; /* --help */
  const char *file = o.arch, *hist = o.history_file;
  double acc_g = o.accel_g, dur = o.duration_s, end = o.end_s, cap = o.max_end_s,
         dt = o.pulse_dt_s, cor = o.cor, rtol = o.ode_rtol;
  int model = o.model, impact = o.impact;
  aq_opt_no_operands("pulse", argc, argv, optind, &nerr);
  /* --end, --max-end and --duration together: the table's rules */
  if (hist && !*hist) {
    fprintf(stderr, "archquake: --history: expected a file name, got \"\"\n");
    nerr++;
  }
  double last = isnan(end) ? (isnan(cap) ? dur : cap) : end;
  if (!isnan(dur) && last / dt > MAX_STEPS) {
    fprintf(stderr, "archquake: --dt: expected at most %g steps, got %g\n",
            MAX_STEPS, last / dt);
    nerr++;
  }
  if (nerr)
    return AQ_EXIT_USAGE;
  if (aq_opt_output_special("--history", hist))
    return AQ_EXIT_OUTPUT;
  struct stat hsb;
  if (hist && stat(hist, &hsb) == 0 && S_ISDIR(hsb.st_mode)) {
    fprintf(stderr, "archquake: %s: --history: expected a file name, got a directory\n", hist);
    return AQ_EXIT_OUTPUT;
  }
  int until_rest = isnan(end);
  if (until_rest && isnan(cap))
    cap = dur + fmin(REST_CAP_S, REST_CAP_STEPS * dt);

  aq_error err;
  aq_error_clear(&err);
  aq_arch *arch = NULL;
  /* with its table of the least friction: a pulse that never moves the
   * arch has the statics' demand at its peak, as in the main job */
  aq_arch_options ao = {.friction = o.friction, .friction_table = model != AQ_MODEL_BLOCKS};
  if (aq_arch_load_opts(file, &ao, &arch, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return AQ_EXIT_FAIL;
  }
  aq_mechanism_warn_minimum(file, arch); /* as mechanism and the main job */
  aq_opt_friction_paper(file, model == AQ_MODEL_PAPER, aq_arch_friction(arch), 1);
  const aq_arch_dynamics *dyn = aq_arch_dynamics_of(arch);
  if (impact < 0 && aq_opt_cor_momentum(file, !isnan(cor), dyn->impact == AQ_IMPACT_MOMENTUM)) {
    aq_arch_free(arch);
    return AQ_EXIT_USAGE;
  }
  if (isnan(cor))
    cor = dyn->cor;
  if (impact < 0)
    impact = dyn->impact == AQ_IMPACT_MOMENTUM;
  int status = AQ_EXIT_FAIL;
  aq_steps steps = {0};
  aq_result res;
  memset(&res, 0, sizeof res);
  aq_blocks_result bres;
  memset(&bres, 0, sizeof bres);
  aq_result *R = &res; /* the run's row: the stepper's, or the block model's */
  aq_stepper *st = NULL;
  aq_blocks *bk = NULL;
  if (model == AQ_MODEL_BLOCKS) {
    R = &bres.r;
    status = pulse_blocks(file, arch, o.blocks_dt_s, hist != NULL, &bk);
    if (status != AQ_EXIT_OK)
      goto out;
    status = AQ_EXIT_FAIL;
  } else {
    aq_opt_spread_four_hinge(file, 1, aq_arch_spread(arch));
    st = aq_stepper_alloc(aq_arch_path(arch, 0), aq_arch_path(arch, 1), (aq_model)model,
                          &err);
    if (!st) {
      aq_error_print(&err, stderr);
      goto out;
    }
    aq_stepper_set_cor(st, cor);
    aq_stepper_set_impact(st, impact);
    aq_stepper_set_ode_rtol(st, rtol);
    aq_stepper_set_history(st, hist != NULL);
    /* what the pulse asks of the joints, against the friction, and the
     * run's marks, as the main job's (docs/demand.md) */
    aq_demand *dm = aq_arch_demand_tracker(arch, aq_arch_friction(arch), &err);
    if (!dm) {
      aq_error_print(&err, stderr);
      goto out;
    }
    aq_stepper_set_demand(st, dm);
  }
  /* Default end: runs to duration + k chunks with k = 1, 2, 4, ... (each
   * from the start, so that the row is that of --end) until the arch rests
   * or collapses or the cap is reached; then the first chunk end at or
   * after the rest (collapse) time, checked by its own run. */
  double kmax = until_rest ? floor((cap - dur) / REST_CHUNK_S + 1e-9) : 0;
  double k = kmax < 1 ? kmax : 1, klo = -1; /* klo: largest k known not done */
  int capped = 0, settled = 0;
  for (;;) {
    double e = until_rest ? (k >= kmax ? cap : dur + k * REST_CHUNK_S) : end;
    aq_result_free(&res);
    aq_blocks_result_free(&bres);
    aq_steps_free(&steps);
    if (pulse_steps(acc_g * AQ_G0_MPS2, dur, e, dt, &steps, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      goto out;
    }
    if ((bk ? aq_blocks_run(bk, &steps, &bres, &err) : aq_stepper_run(st, &steps, &res, &err)) !=
        AQ_OK) {
      snprintf(err.input, sizeof err.input, "%s", file);
      aq_error_print(&err, stderr);
      goto out;
    }
    end = e;
    if (!until_rest)
      break;
    double t_ev = R->collapsed ? R->collapse_time_s
                  : bk      ? aq_blocks_rest_since(bk)
                            : aq_stepper_rest_since(st);
    if (isnan(t_ev)) { /* still moving at e */
      klo = k;
      if (k >= kmax) {
        capped = 1;
        break;
      }
      if (settled) /* the chunk after a near-boundary rest */
        k = k + 1;
      else
        k = fmin(2 * k, kmax);
      continue;
    }
    /* done at e: the first chunk end at or after t_ev, if not this one */
    double kf = fmax(ceil((t_ev - dur) / REST_CHUNK_S - 1e-12), klo + 1);
    settled = 1;
    if (kf >= k || e >= cap)
      break;
    k = kf;
  }
  if (capped)
    fprintf(stderr,
            "archquake: %s: still moving at the cap t = %g s (--max-end); "
            "the row is that of --end %g\n",
            file, end, end);
  aq_error herr;
  if (hist && write_history(hist, &R->history, bk ? &bres : NULL, &herr) != AQ_OK) {
    aq_error_print(&herr, stderr);
    status = AQ_EXIT_OUTPUT;
    goto out;
  }
  printf("model\taccel_g\tduration_s\tend_s\tcollapsed\tcollapse_time_s\t"
         "peak_rotation_rad\tpeak_displacement_m\tmax_kinetic_energy_j\timpacts\t"
         "reversals\tenergy_in_j\tenergy_dissipated_j\tsteps_moving\tevals%s\n",
         bk ? "\tmax_slip_m\thinges_observed\thinges_first_s\tmechanism_changed_s"
            "\tfriction_work_j"
            : "\tstatus\tmu_demand\tmu_demand_joint\tthrust_ecc_max\tthrust_ecc_time_s"
              "\tslide_time_s");
  printf("%s\t%s\t%s\t%s\t%d\t%s\t%s\t%s\t%s\t%zu\t%zu\t%s\t"
         "%s\t%zu\t%zu",
         aq_model_name((aq_model)model), AQ_TEXT_NUM(acc_g), AQ_TEXT_NUM(dur), AQ_TEXT_NUM(end),
         R->collapsed, AQ_TEXT_NUM(R->collapse_time_s), AQ_TEXT_NUM(R->peak_rotation_rad),
         AQ_TEXT_NUM(R->peak_displacement_m), AQ_TEXT_NUM(R->max_kinetic_energy_j), R->impacts,
         R->reversals, AQ_TEXT_NUM(R->energy_in_j), AQ_TEXT_NUM(R->energy_dissipated_j),
         R->steps_moving, R->evals);
  if (bk) {
    size_t cap = 24 * (bres.nhinges + 1);
    char *hb = malloc(cap), *tb = malloc(cap);
    if (!hb || !tb) {
      free(hb);
      free(tb);
      fprintf(stderr, "archquake: out of memory\n");
      goto out;
    }
    aq_blocks_hinges_text(&bres, hb, cap, tb, cap);
    printf("\t%s\t%s\t%s\t%s\t%s", AQ_TEXT_NUM(bres.max_slip_m), hb[0] ? hb : "-",
           tb[0] ? tb : "-", AQ_TEXT_NUM(bres.mechanism_changed_s),
           AQ_TEXT_NUM(bres.friction_work_j));
    free(hb);
    free(tb);
  } else {
    printf("\t%s\t%s\t", aq_result_marks_name(aq_job_run_marks(arch, R)),
           AQ_TEXT_NUM(R->mu_demand));
    if (isnan(R->mu_demand))
      fputs("-", stdout);
    else
      printf("%zu", R->mu_demand_joint);
    printf("\t%s\t%s\t%s", AQ_TEXT_NUM(R->thrust_ecc_max), AQ_TEXT_NUM(R->thrust_ecc_time_s),
           AQ_TEXT_NUM(R->slide_time_s));
  }
  putchar('\n');
  status = fflush(stdout) == 0 ? AQ_EXIT_OK : AQ_EXIT_OUTPUT;
out:
  aq_result_free(&res);
  aq_blocks_result_free(&bres);
  aq_steps_free(&steps);
  aq_stepper_free(st);
  aq_blocks_free(bk);
  aq_arch_free(arch);
  return status;
}
