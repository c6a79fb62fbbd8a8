/* cmd_plot.c: `archquake plot FIGURE ... -o FILE`: parse and check the
 * options, read the inputs, then draw with the plot stage (src/plot) in
 * this one thread.  Figures: history, arch, domain, suite, capacity, spectrum. */
#define _GNU_SOURCE /* nl_langinfo's _NL_PAPER_WIDTH, _NL_PAPER_HEIGHT */
#include <getopt.h>
#include <langinfo.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../arch/domain.h"
#include "../job/run.h"
#include "../plot/plot.h"
#include "../report/h5.h"
#include "app.h"
#include "../util/cleanup.h"
#include "opt.h"
#include "opt_arch.h"
#include "opt_table.h"

/* The figures, in the order of their commands in opt_table.h (their names
 * and options: opt_table.c). */
enum { FIG_HISTORY = 0, FIG_ARCH, FIG_DOMAIN, FIG_SUITE, FIG_CAPACITY, FIG_SPECTRUM, FIG_N };
_Static_assert(FIG_N == AQ_CMD_N - AQ_CMD_PLOT - 1, "a figure per plot command");
/* Per figure: whether it takes an input file. */
static const int takes_input[FIG_N] = {1, 0, 0, 1, 1, 1};

/* The locale's paper (LC_PAPER, glibc's page size in mm): Letter or A4. */
static int locale_paper(void)
{
  if (!setlocale(LC_PAPER, ""))
    return AQ_PAPER_A4;
  union {
    char *s;
    unsigned int mm;
  } w, h;
  w.s = nl_langinfo(_NL_PAPER_WIDTH);
  h.s = nl_langinfo(_NL_PAPER_HEIGHT);
  int p = aq_plot_paper_of_size(w.mm, h.mm);
  setlocale(LC_PAPER, "C");
  return p;
}

typedef struct {
  int fig;
  const char *input, *out, *data, *run, *arch, *im, *record, *target;
  int x_rad, y_pga; /* capacity: --x rad, --y pga */
  int paper;        /* an aq_plot_paper; -1: the locale's */
  double rotation_rad, cor, friction;
  double *at_s; /* plot arch --run: the times */
  size_t nat;
  double *ratios;
  size_t nr;
} plot_opts;

static int parse(int argc, char **argv, plot_opts *o)
{
  aq_opts a;
  aq_cmd cmd = (aq_cmd)(AQ_CMD_PLOT_HISTORY + o->fig);
  aq_opts_init(&a, cmd);
  int nerr = 0;
  if (aq_opts_parse(cmd, argc, argv, &a, &nerr)) {
    aq_opts_free(&a);
    return -1; /* --help */
  }
  o->out = a.output;
  o->data = a.data;
  o->run = a.run;
  o->arch = a.arch;
  o->im = a.im;
  o->record = a.record;
  o->target = a.target;
  o->x_rad = a.x_rad;
  o->y_pga = a.y_pga;
  o->paper = a.paper;
  o->rotation_rad = a.rotation_rad;
  o->cor = a.cor;
  o->friction = a.friction;
  o->ratios = a.ratios; /* freed by the caller */
  o->nr = a.nratios;
  a.ratios = NULL;
  o->at_s = a.at_s; /* freed by the caller */
  o->nat = a.nat;
  a.at_s = NULL;
  aq_opts_free(&a);
  if (o->fig == FIG_ARCH && optind < argc) /* a results file: its arch by name */
    o->input = argv[optind++];
  else if (o->fig == FIG_ARCH && o->arch) /* an arch file, or an installed one */
    o->arch = aq_opt_arch((char *)o->arch, &nerr); /* argv's own string */
  if (takes_input[o->fig]) {
    if (optind < argc)
      o->input = argv[optind++];
    else {
      fprintf(stderr, "archquake: %s: expected a results file (.h5), got none\n",
              aq_opt_commands[cmd].name);
      nerr++;
    }
  }
  aq_opt_no_operands("plot", argc, argv, optind, &nerr);
  if (o->fig == FIG_ARCH && o->run && !o->input) {
    fprintf(stderr, "archquake: plot arch: --run: expected a results file to read the run "
                    "from, got none\n");
    nerr++;
  } else if (o->fig == FIG_ARCH && !o->input && !o->arch) { /* AQ_OPT_ARCH_DRAWN */
    fprintf(stderr, "archquake: plot arch: expected --arch ARCH or a results file, got "
                    "neither\n");
    nerr++;
  }
  aq_error err;
  if (o->out && aq_plot_device(o->out, NULL, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    nerr++;
  }
  if (aq_opt_output_special("-o", o->out) || aq_opt_output_special("--data", o->data))
    nerr++;
  if (o->paper >= 0 && o->out) { /* a page size only a PDF has */
    const char *dot = strrchr(o->out, '.');
    if (!dot || strcasecmp(dot, ".pdf") != 0) {
      fprintf(stderr, "archquake: --paper: expected a .pdf output (-o), got \"%s\"\n", o->out);
      nerr++;
    }
  }
  if (o->out && o->data && aq_opt_same_file(o->out, o->data)) {
    fprintf(stderr, "archquake: --data: expected a file other than -o, got \"%s\"\n",
            o->data);
    nerr++;
  }
  return nerr ? 1 : 0;
}

static int fail(const aq_error *err)
{
  aq_error_print(err, stderr);
  return err->status == AQ_EIO ? AQ_EXIT_OUTPUT
         : err->status == AQ_EOPTION || !strcmp(err->field, "--run") ||
                 !strcmp(err->field, "--rotation") || !strcmp(err->field, "--at") ||
                 !strcmp(err->field, "--arch") || !strcmp(err->field, "--im") ||
                 !strcmp(err->field, "--record") ||
                 !strcmp(err->field, "--y")
             ? AQ_EXIT_USAGE
             : AQ_EXIT_FAIL;
}

static int plot_domain(const plot_opts *o, const aq_arch *arch, aq_error *err)
{
  static const double def[] = {1.02, 1.05, 1.1, 1.2, 1.35, 1.5, 1.75, 2, 2.5, 3, 4, 5};
  const double TOL_S = 1e-6, TMAX_S = 100; /* bisection tolerance, search limit */
  const double *ratio = o->nr ? o->ratios : def;
  size_t n = o->nr ? o->nr : sizeof def / sizeof def[0];
  const aq_arch_dynamics *dyn = aq_arch_dynamics_of(arch);
  if (aq_opt_cor_momentum(o->arch, !isnan(o->cor), dyn->impact == AQ_IMPACT_MOMENTUM))
    return AQ_EXIT_USAGE;
  const aq_path *pp = aq_arch_path(arch, 0);
  double *dur = malloc(n * sizeof *dur);
  aq_stepper *st = aq_job_stepper(arch, AQ_MODEL_WORKPATH, o->cor, 0, 0, err);
  int rc = AQ_EXIT_OK;
  if (!dur || !st) {
    rc = dur ? fail(err) : AQ_EXIT_FAIL;
    goto out;
  }
  for (size_t i = 0; i < n; i++) {
    double a;
    if (aq_domain_min_duration(st, pp, ratio[i], TOL_S, TMAX_S, &a, &dur[i], err) != AQ_OK) {
      snprintf(err->input, sizeof err->input, "%s", o->arch);
      rc = fail(err);
      goto out;
    }
  }
  if (aq_plot_domain(aq_arch_name(arch), pp->lambda0, ratio, dur, n, TMAX_S, o->out,
                     o->data, NULL, err) != AQ_OK)
    rc = fail(err);
out:
  aq_stepper_free(st);
  free(dur);
  return rc;
}

/* plot spectrum: a spectrum file's spectra, or with --target against it;
 * a select file's suite against its target (or --target's). */
static int plot_spectrum(const plot_opts *o)
{
  aq_error err;
  aq_target tg;
  int have = o->target != NULL, rc = AQ_EXIT_OK;
  if (have && aq_target_parse(o->target, &tg, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    return AQ_EXIT_USAGE;
  }
  if (aq_h5_is_select(o->input)) {
    aq_h5_select_file f;
    if (o->record) {
      fprintf(stderr, "archquake: plot spectrum: --record: expected a file of archquake "
                      "spectrum -o, got %s, a suite of archquake select (drawn whole)\n",
              o->input);
      rc = AQ_EXIT_USAGE;
    } else if (aq_h5_select_read(o->input, &f, &err) != AQ_OK) {
      rc = fail(&err);
    } else {
      if (aq_plot_select(&f, have ? &tg : NULL, o->input, o->out, o->data, NULL, &err) != AQ_OK)
        rc = fail(&err);
      aq_h5_select_file_free(&f);
    }
  } else {
    aq_h5_spectra_table t;
    if (aq_h5_spectra_read(o->input, &t, &err) != AQ_OK) {
      rc = fail(&err);
    } else {
      if ((have ? aq_plot_spectra_target(&t, o->record, &tg, o->input, o->out, o->data, NULL,
                                         &err)
                : aq_plot_spectrum(&t, o->record, o->input, o->out, o->data, NULL, &err)) !=
          AQ_OK)
        rc = fail(&err);
      aq_h5_spectra_table_free(&t);
    }
  }
  if (have)
    aq_target_free(&tg);
  return rc;
}

int aq_cmd_plot(int argc, char **argv)
{
  if (argc < 2 || aq_opt_is(AQ_OPT_HELP, argv[1])) {
    aq_opts_help(AQ_CMD_PLOT, argc < 2 ? stderr : stdout);
    return argc < 2 ? AQ_EXIT_USAGE : AQ_EXIT_OK;
  }
  plot_opts o = {.rotation_rad = 0};
  int cmd = aq_opts_figure(argv[1]);
  if (cmd < 0)
    return AQ_EXIT_USAGE;
  o.fig = cmd - (AQ_CMD_PLOT + 1);
  int p = parse(argc - 1, argv + 1, &o);
  if (p) {
    free(o.ratios);
    free(o.at_s);
    return p < 0 ? AQ_EXIT_OK : AQ_EXIT_USAGE;
  }
  aq_plot_set_paper(o.paper >= 0 ? (aq_plot_paper)o.paper : (aq_plot_paper)locale_paper());
  aq_error err;
  aq_error_clear(&err);
  int rc = AQ_EXIT_OK;
  aq_arch *arch = NULL;
  aq_cleanup_install(); /* a signal while drawing removes the temporaries (util/outfile.h) */
  aq_plot_hold(o.data != NULL); /* the figure renamed once its data are written */
  if (o.arch && o.fig != FIG_CAPACITY && !(o.fig == FIG_ARCH && o.input) &&
      aq_arch_load_opts(o.arch, &(aq_arch_options){.friction = o.friction}, &arch, &err) !=
          AQ_OK) {
    rc = fail(&err);
    goto out;
  }
  switch (o.fig) {
  case FIG_HISTORY: {
    aq_plot_run run;
    if (aq_plot_run_read(o.input, o.run, &run, &err) != AQ_OK) {
      rc = fail(&err);
      break;
    }
    if (aq_plot_history(&run, o.out, o.data, NULL, &err) != AQ_OK)
      rc = fail(&err);
    aq_plot_run_free(&run);
    break;
  }
  case FIG_ARCH:
    if (o.run) {
      if (aq_plot_arch_run(o.input, o.arch, o.run, o.at_s, o.nat, o.out, o.data, NULL, &err) !=
          AQ_OK)
        rc = fail(&err);
      break;
    }
    if ((o.input ? aq_plot_arch_h5(o.input, o.arch, o.rotation_rad, o.out, o.data, NULL, &err)
                 : aq_plot_arch(arch, o.rotation_rad, o.out, o.data, NULL, &err)) != AQ_OK)
      rc = fail(&err);
    break;
  case FIG_DOMAIN:
    rc = plot_domain(&o, arch, &err);
    break;
  case FIG_SUITE: {
    aq_h5_suite S;
    if (aq_h5_read_suite(o.input, &S, &err) != AQ_OK) {
      rc = fail(&err);
      break;
    }
    if (aq_plot_suite(S.runs, S.nruns, o.input, o.out, o.data, NULL, &err) != AQ_OK)
      rc = fail(&err);
    aq_h5_suite_free(&S);
    break;
  }
  case FIG_CAPACITY: {
    aq_h5_capacity_table t;
    int present = 0;
    if (aq_h5_capacity_read(o.input, &t, &present, &err) != AQ_OK) {
      rc = fail(&err);
      break;
    }
    aq_plot_capacity_opts co = {o.arch, o.im, o.x_rad, o.y_pga};
    if (aq_plot_capacity(&t, &co, o.input, o.out, o.data, NULL, &err) != AQ_OK)
      rc = fail(&err);
    aq_h5_capacity_table_free(&t);
    break;
  }
  case FIG_SPECTRUM:
    rc = plot_spectrum(&o);
    break;
  }
out:
  if (aq_plot_held_finish(rc == AQ_EXIT_OK, &err) != AQ_OK)
    rc = fail(&err);
  aq_arch_free(arch);
  free(o.ratios);
  free(o.at_s);
  return rc;
}
