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
#include "../io/formats.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "app.h"
#include "opt.h"
#include "opt_arch.h"
#include "opt_dyn.h"
#include "opt_orient.h"
#include "opt_record.h"
#include "opt_signal.h"
#include "suite.h"

#define AQ_RUN_MAX_THREADS 1024

static const char usage_head[] =
    "usage: archquake [OPTIONS] RECORD... --arch FILE [--arch FILE ...]\n"
    "       archquake [OPTIONS] --components H1,H2[,V] ... --arch FILE ...\n"
    "Run every record against every arch (and every scale factor): each record\n"
    "is read and processed once.  One TSV row per run on stdout.\n"
    "  --arch FILE         an arch (.cfg), or an installed arch by name\n"
    "                      (oppenheim); repeatable\n"
    "  -o, --output FILE.h5  write the HDF5 results file (docs/hdf5-layout.md)\n"
    "  --text FILE         write the TSV to FILE instead of stdout\n"
    "  --scale LIST        run each record scaled by each factor, e.g. 0.5,1,2\n"
    "                      (default 1)\n"
    "  --scale-to-pga G    scale each processed record to a PGA of G g instead\n"
    "  --scale-to-lambda0 K  scale each processed record, for each arch, to a PGA\n"
    "                      of K lambda0 g, lambda0 the arch's static collapse\n"
    "                      multiplier (the smaller of its two hinge sets'), so\n"
    "                      that one suite shakes arches of unlike strength alike\n"
    "  -j, --jobs N        worker threads (default: the number of cores); the\n"
    "                      results are the same for every N\n"
    AQ_OPT_DYN_USAGE
    "  --history           write histories (step ends, turning points, impacts)\n"
    "                      to the HDF5 file (with -o)\n"
    "  --store-records     write the processed records to the HDF5 file (with -o)\n"
    "  --resume            continue an interrupted run of this same command (with\n"
    "                      -o): every record done is kept in FILE.h5.journal\n"
    "                      until the results file is complete; the outputs equal\n"
    "                      an uninterrupted run's (not with --history or\n"
    "                      --store-records)\n"
    AQ_OPT_POLARITY_USAGE
    "  -q, --quiet         no progress line (it is shown only on a terminal)\n"
    "  --help              this text;  --version: the version\n"
    "Reading:\n" AQ_OPT_RECORD_USAGE "Orientation:\n" AQ_OPT_ORIENT_USAGE
    "Processing:\n";
static const char usage_tail[] =
    "Output: TSV, one row per run (on a terminal: an aligned table with 6\n"
    "significant digits; pipe or redirect it, or use --text, for the TSV).\n"
    "Columns: record arch model scale pga_g status collapsed collapse_time_s\n"
    "  peak_rotation_rad peak_displacement_m max_kinetic_energy_j impacts\n"
    "  energy_in_j energy_dissipated_j  (status: ok, or read:CODE, process:CODE,\n"
    "  arch:CODE, run:CODE; collapse_time_s is nan for an arch that survives;\n"
    "  then polarity (normal | reversed) lambda0_first (lambda0 of the set the\n"
    "  record drove first; nan if it never moved) peak_rotation_over_qc (peak\n"
    "  rotation / q_c of the set it occurred in) pga_over_lambda0_g (pga_g over\n"
    "  lambda0_first, or over the lower lambda0 if it never moved);\n"
    "  a run whose status is not ok has every result column nan, collapsed\n"
    "  included: no verdict; then azimuth_deg: the arch's azimuth for a\n"
    "  --components motion, nan for a RECORD)\n"
    "Exit status:\n"
    "  0  every record read and every run done\n"
    "  1  some record or run failed (each reported on stderr; the others ran)\n"
    "  2  bad or missing options, or an arch file that cannot be loaded:\n"
    "     nothing was run\n"
    "  3  an output file could not be written (no partial file is left; an\n"
    "     existing file of that name is untouched)\n"
    "  A run ended by SIGINT, SIGTERM, SIGHUP or SIGPIPE removes its\n"
    "  temporaries and ends with that signal.\n";

enum {
  OPT_ARCH = 2000,
  OPT_TEXT,
  OPT_SCALE,
  OPT_SCALE_PGA,
  OPT_SCALE_LAMBDA0,
  OPT_HISTORY,
  OPT_STORE_RECORDS,
  OPT_POLARITY,
  OPT_RESUME,
  OPT_HELP
};

/* argv joined by spaces, words with shell-special characters in single
 * quotes (malloc'd; NULL when out of memory). */
static char *join_argv(int argc, char **argv)
{
  size_t len = 1;
  for (int i = 0; i < argc; i++)
    len += 4 * strlen(argv[i]) + 3;
  char *s = malloc(len), *p = s;
  if (!s)
    return NULL;
  for (int i = 0; i < argc; i++) {
    const char *w = argv[i];
    int plain = *w != '\0';
    for (const char *q = w; *q; q++)
      if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                  "0123456789-_./=,:+@%", *q))
        plain = 0;
    if (i)
      *p++ = ' ';
    if (plain) {
      strcpy(p, w);
      p += strlen(w);
    } else {
      *p++ = '\'';
      for (const char *q = w; *q; q++) {
        if (*q == '\'') {
          memcpy(p, "'\\''", 4);
          p += 4;
        } else
          *p++ = *q;
      }
      *p++ = '\'';
    }
  }
  *p = '\0';
  return s;
}

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

int aq_cmd_run(int argc, char **argv)
{
  struct option longopts[40] = {
      AQ_OPT_RECORD_LONGOPTS,
      AQ_OPT_ORIENT_LONGOPTS,
      {"arch", required_argument, NULL, OPT_ARCH},
      {"output", required_argument, NULL, 'o'},
      {"text", required_argument, NULL, OPT_TEXT},
      {"scale", required_argument, NULL, OPT_SCALE},
      {"scale-to-pga", required_argument, NULL, OPT_SCALE_PGA},
      {"scale-to-lambda0", required_argument, NULL, OPT_SCALE_LAMBDA0},
      {"jobs", required_argument, NULL, 'j'},
      AQ_OPT_DYN_LONGOPTS,
      {"history", no_argument, NULL, OPT_HISTORY},
      {"store-records", no_argument, NULL, OPT_STORE_RECORDS},
      {"polarity", required_argument, NULL, OPT_POLARITY},
      {"resume", no_argument, NULL, OPT_RESUME},
      {"quiet", no_argument, NULL, 'q'},
      {"help", no_argument, NULL, OPT_HELP}};
  aq_opt_signal_append(longopts);

  aq_suite_cfg cfg;
  memset(&cfg, 0, sizeof cfg);
  aq_orient_opts orient;
  aq_opt_orient_init(&orient);
  char **labels = NULL;
  const aq_orient_motion **motions = NULL;
  aq_signal_opts_default(&cfg.proc);
  cfg.cor = NAN;
  cfg.scale_to_pga_g = NAN;
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  cfg.threads = ncpu >= 1 ? (ncpu > AQ_RUN_MAX_THREADS ? AQ_RUN_MAX_THREADS : ncpu) : 1;
  static const double one = 1.0;
  double *scales = NULL;
  size_t nscale = 0;
  int quiet = 0, nerr = 0, c;
  aq_dyn_opts dyn;
  aq_opt_dyn_default(&dyn);
  const char *text_path = NULL;
  char **arches = calloc((size_t)argc + 1, sizeof *arches);
  char units_text[1024] = "";
  if (!arches) {
    fprintf(stderr, "archquake: out of memory\n");
    return AQ_EXIT_FAIL;
  }
  /* before getopt_long permutes argv */
  char *cmdline = join_argv(argc, argv);
  cfg.command_line = cmdline ? cmdline : "";
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":o:j:q", longopts, NULL)) != -1) {
    if (aq_opt_signal_handle(c, optarg, &cfg.proc, &cfg.merge_tol_g, &nerr) ||
        aq_opt_dyn_handle(c, optarg, &dyn, &nerr) ||
        aq_opt_orient_handle(c, optarg, &orient, &nerr))
      continue;
    switch (c) {
    case OPT_ARCH:
      arches[cfg.narches++] = aq_opt_arch(optarg, &nerr);
      break;
    case 'o':
      cfg.h5_path = optarg;
      break;
    case OPT_TEXT:
      text_path = optarg;
      break;
    case OPT_SCALE:
      aq_opt_list("--scale", optarg, 0, INFINITY, &scales, &nscale, &nerr);
      break;
    case OPT_SCALE_PGA:
      aq_opt_double_gt("--scale-to-pga", optarg, 0, 100, &cfg.scale_to_pga_g, &nerr);
      break;
    case OPT_SCALE_LAMBDA0:
      aq_opt_double_gt("--scale-to-lambda0", optarg, 0, 100, &cfg.scale_to_lambda0, &nerr);
      break;
    case 'j':
      aq_opt_long("-j", optarg, 1, AQ_RUN_MAX_THREADS, &cfg.threads, &nerr);
      break;
    case OPT_HISTORY:
      cfg.history = 1;
      break;
    case OPT_STORE_RECORDS:
      cfg.store_records = 1;
      break;
    case OPT_POLARITY:
      aq_opt_polarity(optarg, &cfg.polarity, &nerr);
      break;
    case OPT_RESUME:
      cfg.resume = 1;
      break;
    case 'q':
      quiet = 1;
      break;
    case OPT_HELP:
      fputs(usage_head, stdout);
      fputs(aq_opt_signal_usage, stdout);
      fputs(usage_tail, stdout);
      free(arches);
      free(scales);
      free(cmdline);
      aq_opt_orient_free(&orient);
      return AQ_EXIT_OK;
    default:
      if (aq_opt_record_handle(c, optarg, &cfg.read, &nerr)) {
        if (c == AQ_OPT_RECORD_UNITS) {
          size_t k = strlen(units_text);
          snprintf(units_text + k, sizeof units_text - k, "%s%s", k ? " " : "",
                   optarg);
        }
      } else {
        aq_opt_unknown("", argv, optind, optopt, &nerr);
      }
    }
  }
  aq_opt_signal_check(&cfg.proc, &nerr);
  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind),
                                                    &cfg.read);
  aq_opt_orient_check(&orient, &nerr);
  if (optind >= argc && orient.nmotions == 0) {
    fprintf(stderr, "archquake: expected at least one RECORD or --components (see 'archquake --help')\n");
    nerr++;
  }
  if (cfg.narches == 0) {
    fprintf(stderr, "archquake: --arch: expected at least one arch file, got none\n");
    nerr++;
  }
  aq_opt_distinct_files("arch file", arches, cfg.narches, &nerr);
  if ((scales != NULL) + !isnan(cfg.scale_to_pga_g) + (cfg.scale_to_lambda0 > 0) > 1) {
    fprintf(stderr, "archquake: --scale, --scale-to-pga, --scale-to-lambda0: expected one "
                    "of them, got %s\n",
            !scales ? "--scale-to-pga and --scale-to-lambda0"
            : isnan(cfg.scale_to_pga_g) ? "--scale and --scale-to-lambda0"
            : cfg.scale_to_lambda0 > 0  ? "all three"
                                        : "--scale and --scale-to-pga");
    nerr++;
  }
  if (cfg.history && !cfg.h5_path) {
    fprintf(stderr, "archquake: --history: expected -o FILE.h5 as well (histories "
                    "are written only to the results file)\n");
    nerr++;
  }
  if (cfg.store_records && !cfg.h5_path) {
    fprintf(stderr, "archquake: --store-records: expected -o FILE.h5 as well (processed "
                    "records are written only to the results file)\n");
    nerr++;
  }
  if (cfg.resume && (!cfg.h5_path || cfg.history || cfg.store_records)) {
    fprintf(stderr, "archquake: --resume: expected -o FILE.h5 and neither --history nor "
                    "--store-records, got %s (the journal beside the results file holds "
                    "rows and record metadata, not datasets)\n",
            !cfg.h5_path ? "no -o" : cfg.history ? "--history" : "--store-records");
    nerr++;
  }
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
  cfg.model = dyn.model;
  cfg.cor = dyn.cor;
  cfg.units_text = units_text[0] ? units_text : NULL;
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

  rc = aq_suite_run(&cfg, NULL);

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
  return rc;
}
