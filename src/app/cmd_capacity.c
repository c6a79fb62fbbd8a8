/* cmd_capacity.c: `archquake capacity RECORD... --arch FILE [--arch FILE]`:
 * the collapse capacity of every (record, arch, polarity) and the lognormal
 * fragility of each arch (src/capacity; docs/capacity.md).  Options are
 * checked before any record is read; records are read and processed once,
 * the pairs run on -j threads, and the rows are written in (record, arch,
 * polarity) order, so the output is the same for every -j.  Outputs go to a
 * temporary beside each target, renamed once complete. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../arch/stepper.h"
#include "../capacity/capacity.h"
#include "../io/record.h"
#include "../job/names.h"
#include "../job/run.h"
#include "../report/h5_capacity.h"
#include "../report/report.h"
#include "../report/text_capacity.h"
#include "../units.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "app.h"
#include "capacity_tasks.h"
#include "opt.h"
#include "opt_suite.h"
#include "opt_table.h"

/* The status cell of pair c of record r. */
static void pair_status(const aq_cap_item *r, const aq_capacity *c, char *st, size_t n)
{
  if (!r->ok)
    snprintf(st, n, "%s", r->status);
  else if (c->status == AQ_CAPACITY_FAILED)
    aq_summary_status(st, n, "run", c->run_status);
  else
    snprintf(st, n, "%s",
             c->status == AQ_CAPACITY_NEVER_MOVES ? "never_moves" : aq_result_marks_name(c->marks));
}

/* Per arch: the fits of every IM over the records that were read (stderr
 * gets the reason of a fit that fails; its row stays nan). */
static int fit_all(size_t nrec, size_t na, const aq_cap_item *R, size_t npol,
                   const aq_capacity *C, int nim, aq_fragility *fits)
{
  const aq_im **im = malloc((nrec ? nrec : 1) * sizeof *im);
  if (!im)
    return -1;
  for (size_t r = 0; r < nrec; r++)
    im[r] = R[r].ok ? &R[r].im[0] : NULL;
  int rc = 0;
  for (size_t a = 0; a < na && rc == 0; a++) {
    aq_error e;
    aq_status s = aq_fragility_fit_records_n(C + a * npol, nrec, na * npol, npol, im, nim,
                                             AQ_FRAGILITY_CI_DEFAULT, fits + a * nim, &e);
    if (s == AQ_ENOMEM)
      rc = -1;
    else if (s != AQ_OK)
      aq_error_print(&e, stderr);
  }
  free(im);
  return rc;
}

/* The report rows: one per (record, arch, polarity), one per (arch, IM). */
typedef struct {
  aq_capacity_row *row;
  char (*status)[48];
  aq_fragility_row *fit;
  size_t nfit;
  char (*im_name)[64]; /* the spectral measures' names */
  size_t nspectral;    /* their number */
} rows;

/* Row i of (subject, arch, polarity) is the worst of its nz azimuths'
 * results C[i * nz ...] (nz = 1 without --azimuth all). */
static int make_rows(rows *o, char **recs, size_t nrec, aq_arch **arches, size_t na,
                     const aq_cap_item *R, const int *pols, size_t npol, const aq_capacity *C,
                     size_t nz, const aq_orient_opts *or, const aq_signal_opts *po,
                     const aq_fragility *fits)
{
  size_t n = nrec * na * npol, nsp = aq_im_spectral_count(po), nim = AQ_FRAGILITY_NIM + nsp;
  size_t nf = na * nim;
  o->row = malloc((n ? n : 1) * sizeof *o->row);
  o->status = malloc((n ? n : 1) * sizeof *o->status);
  o->fit = malloc((nf ? nf : 1) * sizeof *o->fit);
  o->im_name = malloc((nsp ? nsp : 1) * sizeof *o->im_name);
  o->nfit = nf;
  if (!o->row || !o->status || !o->fit || !o->im_name)
    return -1;
  for (size_t k = 0; k < nsp; k++)
    aq_im_spectral_name(po, k, o->im_name[k], sizeof o->im_name[k]);
  o->nspectral = nsp;
  for (size_t i = 0; i < n; i++) {
    size_t r = i / (na * npol), w = 0;
    double lo = NAN, hi = NAN;
    if (R[r].ok)
      w = aq_capacity_worst(C + i * nz, R[r].naz, &lo, &hi);
    const aq_capacity *cw = &C[i * nz + w];
    const aq_im *im = R[r].ok ? &R[r].im[w] : NULL;
    pair_status(&R[r], cw, o->status[i], sizeof o->status[i]);
    int have = R[r].ok && cw->status != AQ_CAPACITY_FAILED;
    o->row[i] = (aq_capacity_row){recs[r], aq_arch_name(arches[i / npol % na]),
                                  aq_opt_polarity_names[pols[i % npol]], o->status[i],
                                  have ? cw : NULL, im ? im->pga_g : NAN,
                                  im ? im->pgv_mps : NAN, im, or->nmotions > 0,
                                  R[r].subj.motion ? or->azimuths_deg[w] : NAN, lo, hi};
  }
  for (size_t i = 0; i < nf; i++)
    o->fit[i] = (aq_fragility_row){aq_arch_name(arches[i / nim]),
                                   i % nim < AQ_FRAGILITY_NIM
                                       ? aq_fragility_im_names[i % nim]
                                       : o->im_name[i % nim - AQ_FRAGILITY_NIM],
                                   &fits[i]};
  return 0;
}

static void rows_free(rows *o)
{
  free(o->row);
  free(o->status);
  free(o->fit);
  free(o->im_name);
}

/* The results file: root, arches, records, then the capacity group. */
static int write_h5(const char *path, int argc, char **argv, char **recs, size_t nrec,
                    char **arch_paths, aq_arch **arches, size_t na, const aq_cap_item *R,
                    const rows *o, size_t npair, const aq_scan_opts *so,
                    const aq_signal_opts *po, double merge_tol_g, aq_model model,
                    double cor, long threads, int pol)
{
  char cmd[4096] = "", created[64];
  for (int i = 0, k = 0; i < argc && k < (int)sizeof cmd - 2; i++)
    k += snprintf(cmd + k, sizeof cmd - (size_t)k, "%s%s", i ? " " : "archquake ", argv[i]);
  aq_error e;
  aq_h5_writer *w = NULL;
  time_t t = time(NULL);
  struct tm tm;
  if (!gmtime_r(&t, &tm) || !strftime(created, sizeof created, "%Y-%m-%dT%H:%M:%SZ", &tm))
    snprintf(created, sizeof created, "unknown");
  aq_h5_root root = {.version = AQ_VERSION,
                     .command_line = cmd,
                     .created = created,
                     .proc = po,
                     .merge_tol_g = merge_tol_g,
                     .units = "file",
                     .model = aq_model_name(model),
                     .cor = cor,
                     .scale_to_pga_g = NAN,
                     .threads = threads,
                     .build = aq_build_string(),
                     .polarity = aq_opt_polarity_names[pol]};
  aq_status s = aq_h5_open(path, &w, &e);
  if (s == AQ_OK)
    s = aq_h5_write_root_kind(w, &root, "capacity", &e);
  for (size_t a = 0; s == AQ_OK && a < na; a++) {
    aq_arch_dynamics used = aq_job_dynamics(arches[a], cor); /* the values the runs use */
    s = aq_h5_write_arch_of(w, a, arches[a], arch_paths[a], &used, &e);
  }
  for (size_t r = 0; s == AQ_OK && r < nrec; r++) {
    aq_h5_record hr = {.source_file = recs[r],
                       .rec = R[r].subj.have_rec[0] ? &R[r].subj.rec[0] : NULL,
                       .proc = R[r].subj.have_proc[0] ? &R[r].subj.proc[0] : NULL,
                       .im = R[r].ok ? &R[r].im[0] : NULL,
                       .status = R[r].status};
    s = aq_h5_write_record(w, r, &hr, &e);
  }
  const char *spectral[AQ_IM_SA_MAX + 1];
  size_t nsp = 0;
  for (; nsp < o->nspectral && nsp < AQ_IM_SA_MAX + 1; nsp++)
    spectral[nsp] = o->im_name[nsp];
  aq_h5_capacity hc = {o->row, npair, o->fit, o->nfit, so->resolution,
                       so->tol, AQ_FRAGILITY_CI_DEFAULT, nsp, spectral};
  if (s == AQ_OK)
    s = aq_h5_write_capacity(w, path, &hc, &e);
  if (s == AQ_OK) {
    s = aq_h5_finish(w, NULL, &e);
    w = NULL;
  }
  if (s != AQ_OK)
    aq_error_print(&e, stderr);
  aq_h5_abort(w);
  return s == AQ_OK ? 0 : -1;
}

/* Open the temporary of an output (util/outfile.h): 0, or -1 (a line on
 * stderr). */
static int out_open(aq_outfile *o, const char *path)
{
  aq_error e;
  if (aq_outfile_open(o, path, &e) == AQ_OK)
    return 0;
  aq_error_print(&e, stderr);
  return -1;
}

/* Rename o's temporary onto its target if ok, else remove it: 0 or -1. */
static int out_close(aq_outfile *o, int ok)
{
  aq_error e;
  if (!ok) {
    aq_outfile_abort(o);
    return -1;
  }
  if (aq_outfile_commit(o, &e) == AQ_OK)
    return 0;
  aq_error_print(&e, stderr);
  return -1;
}

int aq_cmd_capacity(int argc, char **argv)
{
  aq_opts opts;
  aq_opts_init(&opts, AQ_CMD_CAPACITY);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_CAPACITY, argc, argv, &opts, &nerr)) { /* --help */
    aq_opts_free(&opts);
    return AQ_EXIT_OK;
  }
  aq_read_opts ro = opts.read;
  aq_signal_opts po = opts.proc;
  double merge_tol_g = opts.merge_tol_g, smax = opts.scale_max;
  aq_model model = (aq_model)opts.model;
  double cor = opts.cor;
  aq_arch_options ao = {.friction = opts.friction, .friction_table = 1};
  aq_scan_opts so = {opts.resolution, opts.scan_tol};
  long threads = opts.threads;
  int pol = opts.polarity;
  const char *h5 = opts.output, *text = opts.text, *frag = opts.fragility;
  /* what the command owns from here: freed below */
  char **arch_paths = opts.arches;
  size_t na = opts.narches;
  aq_orient_opts orient = opts.orient;
  const char *suite_path = opts.suite; /* --suite: argv's string */
  aq_opt_suite suite_in = {0};
  opts.arches = NULL;
  aq_opt_orient_init(&opts.orient);
  aq_opts_free(&opts);
  for (int i = 0; i < 2 && orient.nmotions; i++)
    if (i ? frag != NULL : h5 != NULL) {
      fprintf(stderr, "archquake: %s: expected plain RECORDs only, got --components (the "
                      "results file and fragility fits of ground motions are not "
                      "implemented)\n", i ? "--fragility" : "-o");
      nerr++;
    }
  /* --tol <= --resolution: the table's rule */
  aq_error se;
  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind), &ro);
  if (suite_path)
    aq_opt_suite_take(suite_path, &argc, &argv, optind, &orient, &suite_in, &nerr);
  if (optind >= argc && orient.nmotions == 0 && !suite_path) {
    fprintf(stderr, "archquake: capacity: expected at least one RECORD or --components\n");
    nerr++;
  }
  aq_opt_distinct_files("arch file", arch_paths, na, &nerr);
  if (optind < argc)
    aq_opt_distinct_files("record", argv + optind, (size_t)(argc - optind), &nerr);
  const char *outs[3] = {h5, text, frag};
  for (int i = 0; i < 3; i++)
    for (int j = i + 1; j < 3; j++)
      if (outs[i] && outs[j] && strcmp(outs[i], outs[j]) == 0) {
        fprintf(stderr, "archquake: %s: expected different output files, got it twice\n",
                outs[i]);
        nerr++;
      }
  if (optind < argc)
    for (int i = 0; i < 3; i++)
      nerr += aq_opt_output_is_input(i == 0 ? "-o" : i == 1 ? "--text" : "--fragility",
                                     outs[i], argv + optind, (size_t)(argc - optind),
                                     arch_paths, na);
  /* the RECORDs as the main job names them (job/names.h): every channel of
   * a multi-channel file a record of its own, its vertical left out with a
   * note unless named */
  char **names = NULL, **notes = NULL;
  size_t nplain = 0, nnotes = 0;
  int bad_out = nerr ? 0
                     : aq_opt_output_special("-o", h5) + aq_opt_output_special("--text", text) +
                           aq_opt_output_special("--fragility", frag);
  if (!nerr && !bad_out && optind < argc) {
    if (aq_job_names(argv + optind, (size_t)(argc - optind), &ro, threads, &names, &nplain,
                     &notes, &nnotes, &se) != AQ_OK) {
      aq_error_print(&se, stderr);
      aq_opt_orient_free(&orient);
      free(arch_paths);
      aq_opt_suite_free(&suite_in);
      return AQ_EXIT_FAIL;
    }
    for (size_t i = 0; !aq_farm_is_follower() && i < nnotes; i++)
      fprintf(stderr, "archquake: %s\n", notes[i]); /* a vertical left out (io/record.h) */
    aq_record_names_free(notes, nnotes);
  }
  char **recs = NULL;
  const char *(*paths)[3] = NULL;
  double(*phi)[2] = NULL;
  size_t nrec = nplain + orient.nmotions;
  if (!nerr) { /* subjects: each RECORD, then each motion */
    recs = calloc(nrec ? nrec : 1, sizeof *recs);
    paths = calloc(nrec ? nrec : 1, sizeof *paths);
    phi = calloc(nrec ? nrec : 1, sizeof *phi);
    if (!recs || !paths || !phi) {
      fprintf(stderr, "archquake: out of memory\n");
      nerr++;
    }
    for (size_t i = 0; !nerr && i < nrec; i++) {
      const aq_orient_motion *m = i < nplain ? NULL : &orient.motions[i - nplain];
      recs[i] = m ? m->label : names[i];
      paths[i][0] = m ? m->path[0] : recs[i];
      paths[i][1] = m ? m->path[1] : NULL;
      paths[i][2] = m ? m->path[2] : NULL;
      phi[i][0] = m ? m->azimuth_deg[0] : NAN;
      phi[i][1] = m ? m->azimuth_deg[1] : NAN;
    }
  }
  if (nerr || bad_out) {
    free(arch_paths);
    free(recs);
    free(paths);
    free(phi);
    aq_record_names_free(names, nplain);
    aq_opt_orient_free(&orient);
    aq_opt_suite_free(&suite_in);
    return nerr ? AQ_EXIT_USAGE : AQ_EXIT_OUTPUT;
  }

  int rc = AQ_EXIT_OK;
  size_t nz = orient.nmotions ? orient.nazimuth : 1; /* result slots per row */
  aq_arch **arches = calloc(na, sizeof *arches);
  int pols[2];
  size_t npol = 0;
  aq_cap_item *R = NULL;
  aq_capacity *C = NULL;
  aq_fragility *fits = NULL;
  size_t nrow = 0, njob = 0;
  int nim = AQ_FRAGILITY_NIM + (int)aq_im_spectral_count(&po);
  if (!arches) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t a = 0; a < na; a++) {
    if (aq_arch_load_opts(arch_paths[a], &ao, &arches[a], &se) != AQ_OK) {
      aq_error_print(&se, stderr);
      rc = AQ_EXIT_USAGE;
      continue;
    }
    aq_mechanism_warn_minimum(arch_paths[a], arches[a]); /* as the main job */
    if (aq_opt_cor_momentum(arch_paths[a], !isnan(cor),
                            aq_arch_dynamics_of(arches[a])->impact == AQ_IMPACT_MOMENTUM) ||
        aq_opt_blocks_friction(arch_paths[a], model == AQ_MODEL_BLOCKS,
                               aq_arch_friction(arches[a])) ||
        aq_opt_blocks_spread(arch_paths[a], model == AQ_MODEL_BLOCKS, arches[a]))
      rc = AQ_EXIT_USAGE;
    else
      aq_opt_spread_four_hinge(arch_paths[a], model != AQ_MODEL_BLOCKS,
                               aq_arch_spread(arches[a]));
    aq_opt_friction_paper(arch_paths[a], model == AQ_MODEL_PAPER, aq_arch_friction(arches[a]),
                          0);
  }
  if (rc != AQ_EXIT_OK)
    goto done;
  /* both polarities unless every arch answers a record and its negation
   * alike (or the user asked for one) */
  pol = aq_opt_polarity_resolve(pol, arches, na, nplain == 0 && orient.nmotions > 0,
                                orient.azimuths_deg, orient.nazimuth);
  if (pol != AQ_POLARITY_REVERSED)
    pols[npol++] = AQ_POLARITY_NORMAL;
  if (pol != AQ_POLARITY_NORMAL)
    pols[npol++] = AQ_POLARITY_REVERSED;
  nrow = nrec * na * npol, njob = nrow * nz;
  R = calloc(nrec ? nrec : 1, sizeof *R);
  C = calloc(njob ? njob : 1, sizeof *C);
  fits = calloc(na * (size_t)nim, sizeof *fits);
  if (!R || !C || !fits) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  aq_cap_setup S = {nrec, recs, (const char *const (*)[3])paths, (const double (*)[2])phi,
                     &orient, &ro, &po, pol, pols, npol, nz, arches, na, model,
                     opts.blocks_dt_s, cor, merge_tol_g * AQ_G0_MPS2, smax, so,
                     suite_in.factors};
  if (aq_farm_is_follower()) { /* archquake-mpi: run what rank 0 hands out */
    rc = aq_cap_run(&S, R, NULL, threads) == 0 ? AQ_EXIT_OK : AQ_EXIT_FAIL;
    goto done;
  }
  if (aq_cap_run(&S, R, C, threads) != 0) { /* prepares R[0..nrec) */
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t r = 0; r < nrec; r++)
    if (!R[r].ok)
      rc = AQ_EXIT_FAIL;
  for (size_t i = 0; i < njob; i++) {
    size_t j = i / nz, r = j / (na * npol);
    if (R[r].ok && i % nz < R[r].naz && C[i].status == AQ_CAPACITY_FAILED) {
      char msg[1200], az[64] = "";
      aq_error_format(&C[i].err, msg, sizeof msg);
      if (R[r].subj.motion)
        snprintf(az, sizeof az, ", azimuth %g deg", orient.azimuths_deg[i % nz]);
      fprintf(stderr, "archquake: %s: arch %s, polarity %s%s: %s\n", recs[r],
              aq_arch_name(arches[j / npol % na]), aq_opt_polarity_names[pols[j % npol]],
              az, msg);
      rc = AQ_EXIT_FAIL;
    }
  }

  /* outputs: every temporary is complete before any is renamed */
  aq_cleanup_install();
  aq_outfile ot = {0}, of = {0};
  int ok = (!text || out_open(&ot, text) == 0) && (!frag || out_open(&of, frag) == 0);
  FILE *ft = text ? ot.f : stdout, *ff = of.f;
  rows o = {NULL, NULL, NULL, 0, NULL, 0};
  if (ok && (ff || h5) && fit_all(nrec, na, R, npol, C, nim, fits) != 0)
    ok = 0;
  if (ok &&
      make_rows(&o, recs, nrec, arches, na, R, pols, npol, C, nz, &orient, &po, fits) != 0) {
    fprintf(stderr, "archquake: out of memory\n");
    ok = 0;
  }
  if (ok && aq_text_capacity(ft, o.row, nrow) != 0)
    ok = 0;
  if (ok && ff && aq_text_fragility(ff, o.fit, o.nfit) != 0)
    ok = 0;
  if (ok && h5 &&
      write_h5(h5, argc, argv, recs, nrec, arch_paths, arches, na, R, &o, nrow, &so, &po,
               merge_tol_g, model, cor, threads, pol) != 0)
    ok = 0;
  rows_free(&o);
  if (frag && out_close(&of, ok) != 0)
    ok = 0;
  if (text && out_close(&ot, ok) != 0)
    ok = 0;
  if (!text && (fflush(stdout) != 0 || ferror(stdout)))
    ok = 0;
  if (!ok)
    rc = AQ_EXIT_OUTPUT;
done:
  for (size_t i = 0; i < njob && C; i++)
    aq_capacity_free(&C[i]);
  for (size_t r = 0; r < nrec && R; r++)
    aq_cap_item_free(&R[r]);
  for (size_t a = 0; a < na && arches; a++)
    aq_arch_free(arches[a]);
  free(arches);
  free(R);
  free(C);
  free(fits);
  free(arch_paths);
  free(recs);
  free(paths);
  free(phi);
  aq_record_names_free(names, nplain);
  aq_opt_orient_free(&orient);
  aq_opt_suite_free(&suite_in);
  return rc;
}
