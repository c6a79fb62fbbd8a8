/* cmd_run.c: `archquake [OPTIONS] RECORD... --arch FILE [--arch FILE ...]`:
 * the main job.  Parses and checks every option before any record is read,
 * then hands the suite to suite.c.  The TSV goes to stdout, or with --text
 * FILE to a temporary renamed onto FILE once complete. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../arch/stepper.h"
#include "../io/record.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "app.h"
#include "opt.h"
#include "opt_suite.h"
#include "opt_table.h"
#include "suite.h"

/* 1 if the paths a and b name the same file, existing or not: the same
 * string, the same existing file, or the same name in the same directory
 * (however spelled: "./x", "d/../x"). */
static int same_output(const char *a, const char *b)
{
  struct stat sa, sb;
  if (strcmp(a, b) == 0)
    return 1;
  if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  const char *ba = strrchr(a, '/'), *bb = strrchr(b, '/');
  const char *na = ba ? ba + 1 : a, *nb = bb ? bb + 1 : b;
  if (strcmp(na, nb) != 0)
    return 0;
  char da[PATH_MAX], db[PATH_MAX];
  snprintf(da, sizeof da, "%.*s", ba ? (int)(ba - a) + 1 : 1, ba ? a : ".");
  snprintf(db, sizeof db, "%.*s", bb ? (int)(bb - b) + 1 : 1, bb ? b : ".");
  return stat(da, &sa) == 0 && stat(db, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

/* The disk cache's notes (NULL: none), one line each on stderr. */
static void print_notes(aq_diskcache *c)
{
  char *notes = aq_diskcache_notes(c);
  for (char *line = notes, *nl; line && *line; line = nl + 1) {
    nl = strchr(line, '\n');
    *nl = '\0';
    fprintf(stderr, "archquake: note: %s\n", line);
  }
  free(notes);
}

int aq_cmd_run(int argc, char **argv)
{
  aq_suite_cfg cfg;
  memset(&cfg, 0, sizeof cfg);
  char **labels = NULL;
  const aq_orient_motion **motions = NULL;
  static const double one = 1.0;
  int nerr = 0;
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_RUN);
  /* before getopt_long permutes argv */
  char *cmdline = aq_app_command_line(argc, argv);
  cfg.command_line = cmdline ? cmdline : "";
  if (aq_opts_parse(AQ_CMD_RUN, argc, argv, &o, &nerr)) { /* --help */
    free(cmdline);
    aq_opts_free(&o);
    return AQ_EXIT_OK;
  }
  cfg.proc = o.proc;
  cfg.merge_tol_g = o.merge_tol_g;
  cfg.read = o.read;
  cfg.h5_path = o.output;
  cfg.scale_to_pga_g = o.scale_to_pga_g;
  cfg.scale_to_lambda0 = o.scale_to_lambda0;
  cfg.threads = o.threads;
  cfg.history = o.history;
  cfg.store_records = o.store_records || o.history; /* a history with the ground it answers */
  cfg.polarity = o.polarity;
  cfg.resume = o.resume;
  cfg.narches = o.narches;
  const char *text_path = o.text;
  int quiet = o.quiet;
  int use_cache = !o.no_cache;
  const char *cache_dir = o.cache_dir;
  unsigned long long cache_max = o.cache_max;
  /* what the run owns from here: freed below */
  char **arches = o.arches;
  double *scales = o.scales;
  size_t nscale = o.nscale;
  const char *suite_path = o.suite; /* --suite: argv's string */
  aq_opt_suite suite_in = {0};
  aq_orient_opts orient = o.orient;
  o.arches = NULL;
  o.scales = NULL;
  aq_opt_orient_init(&o.orient);
  aq_opts_free(&o);
  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind),
                                                    &cfg.read);
  if (suite_path && aq_opt_suite_take(suite_path, &argc, &argv, optind, &orient, &suite_in,
                                      &nerr) == 0)
    cfg.record_scales = suite_in.factors; /* each record at its own scale */
  if (optind >= argc && orient.nmotions == 0 && !suite_path) {
    fprintf(stderr, "archquake: expected at least one RECORD or --components (see 'archquake --help')\n");
    nerr++;
  }
  aq_opt_distinct_files("arch file", arches, cfg.narches, &nerr);
  /* the scaling options, --history, --store-records and --resume together:
   * the table's rules (opt_table.c) */
  if (cfg.h5_path && text_path && same_output(cfg.h5_path, text_path)) {
    if (strcmp(cfg.h5_path, text_path) == 0)
      fprintf(stderr, "archquake: --text: expected a file other than -o's, got \"%s\" twice\n",
              text_path);
    else
      fprintf(stderr, "archquake: --text: expected a file other than -o's, got \"%s\", "
                      "the same file as -o \"%s\"\n", text_path, cfg.h5_path);
    nerr++;
  }
  if (optind < argc) {
    char *const *recs = argv + optind;
    size_t nrec = (size_t)(argc - optind);
    aq_opt_distinct_files("record", recs, nrec, &nerr);
    nerr += aq_opt_output_is_input("-o", cfg.h5_path, recs, nrec, arches, cfg.narches);
    nerr += aq_opt_output_is_input("--text", text_path, recs, nrec, arches, cfg.narches);
  }
  for (size_t i = 0; i < orient.nmotions; i++) { /* nor a motion's component */
    aq_orient_motion *m = &orient.motions[i];
    size_t nc = m->path[2] ? 3 : 2;
    nerr += aq_opt_output_is_input("-o", cfg.h5_path, m->path, nc, arches, 0);
    nerr += aq_opt_output_is_input("--text", text_path, m->path, nc, arches, 0);
  }
  /* the rows' record column: each RECORD, then each motion's label */
  size_t nplain = optind < argc ? (size_t)(argc - optind) : 0;
  size_t nall = nplain + orient.nmotions;
  if (!nerr && orient.nmotions) {
    labels = calloc(nall, sizeof *labels);
    motions = calloc(nall, sizeof *motions);
    if (!labels || !motions) {
      fprintf(stderr, "archquake: out of memory\n");
      nerr++;
    }
    for (size_t i = 0; !nerr && i < nall; i++) {
      labels[i] = i < nplain ? argv[optind + (int)i] : orient.motions[i - nplain].label;
      motions[i] = i < nplain ? NULL : &orient.motions[i - nplain];
    }
  }
  if (nerr || aq_opt_output_special("-o", cfg.h5_path) +
                  aq_opt_output_special("--text", text_path)) {
    free(arches);
    free(scales);
    free(cmdline);
    free(labels);
    free(motions);
    aq_opt_orient_free(&orient);
    aq_opt_suite_free(&suite_in);
    return nerr ? AQ_EXIT_USAGE : AQ_EXIT_OUTPUT;
  }

  cfg.records = labels ? labels : argv + optind;
  cfg.nrecords = nall;
  cfg.motions = motions;
  cfg.azimuths_deg = orient.azimuths_deg;
  cfg.nazimuth = orient.nazimuth;
  cfg.all_azimuths = orient.all_azimuths;
  cfg.vertical = orient.vertical;
  cfg.arch_paths = arches;
  cfg.model = (aq_model)o.model;
  cfg.blocks_dt_s = o.blocks_dt_s;
  cfg.check_blocks = o.check_blocks == 0;
  cfg.cor = o.cor;
  cfg.friction = o.friction;
  cfg.units_text = o.units_text[0] ? o.units_text : NULL;
  if (isnan(cfg.scale_to_pga_g) && !(cfg.scale_to_lambda0 > 0)) {
    cfg.scales = scales ? scales : &one;
    cfg.nscale = scales ? nscale : 1;
  }
  cfg.progress = !quiet && isatty(STDERR_FILENO) && !aq_suite_is_remote();

  aq_cleanup_install();
  if (aq_suite_is_follower()) /* archquake-mpi: rank 0 alone writes */
    text_path = NULL;
  if (cfg.resume && !aq_suite_is_follower()) { /* what a killed run could not remove */
    aq_cleanup_stale(cfg.h5_path);
    if (text_path)
      aq_cleanup_stale(text_path);
  }
  aq_outfile tout = {0}; /* --text: its temporary */
  struct stat sb;
  aq_error terr;
  int rc = AQ_EXIT_OK;
  if (text_path && stat(text_path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "archquake: %s: --text: expected a file name, got a directory\n",
            text_path);
    rc = AQ_EXIT_OUTPUT;
  } else if (text_path && aq_outfile_open(&tout, text_path, &terr) != AQ_OK) {
    aq_error_print(&terr, stderr);
    rc = AQ_EXIT_OUTPUT;
  }
  if (rc != AQ_EXIT_OK)
    goto out;
  cfg.text = tout.f ? tout.f : stdout;
  /* TSV for files and pipes */
  cfg.aligned = !tout.f && isatty(STDOUT_FILENO) && !aq_suite_is_remote();

  if (cache_max) /* every store of the run: the bound is the directory's */
    aq_diskcache_set_default_max(cache_max);
  if (use_cache) { /* none without a home for it: the run goes on */
    cfg.cache = aq_diskcache_open(cache_dir, "records", aq_build_string());
    cfg.arch_cache = aq_diskcache_open(cache_dir, "arches", aq_build_string());
  }
  rc = aq_suite_run(&cfg, NULL);
  print_notes(cfg.arch_cache);
  print_notes(cfg.cache);
  aq_diskcache_close(cfg.arch_cache);
  aq_diskcache_close(cfg.cache);

  if (tout.f) {
    if (rc == AQ_EXIT_OUTPUT || rc == AQ_EXIT_USAGE) {
      aq_outfile_abort(&tout);
    } else if (aq_outfile_commit(&tout, &terr) != AQ_OK) {
      aq_error_print(&terr, stderr);
      rc = AQ_EXIT_OUTPUT;
    }
  } else if (fflush(stdout) != 0 || ferror(stdout)) {
    fprintf(stderr, "archquake: stdout: cannot write the text output\n");
    rc = AQ_EXIT_OUTPUT;
  }
out:
  free(cmdline);
  free(arches);
  free(scales);
  free(labels);
  free(motions);
  aq_opt_orient_free(&orient);
  aq_opt_suite_free(&suite_in);
  return rc;
}
