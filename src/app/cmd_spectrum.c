/* cmd_spectrum.c: `archquake spectrum RECORD|--components H1,H2 ...`: the
 * elastic response spectra of processed records (src/signal/spectrum.h;
 * docs/spectrum.md).  Options are checked before any record is read; each
 * record or pair is read, processed (as the main job does: a pair checked
 * orthogonal and aligned and cut to the samples both have) and its spectra
 * computed on -j threads, into its own slot; nothing is printed or written
 * until every one succeeded, then the rows go out in the order given (the
 * plain RECORDs, then the --components pairs), the same for every -j. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../job/job.h"
#include "../report/h5_spectrum.h"
#include "../report/text.h"
#include "../signal/spectrum.h"
#include "../units.h"
#include "../util/cleanup.h"
#include "../util/pool.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"
#include "opt_record.h"

/* The rows of one spectrum source: a record gives one component (its
 * channel), a pair three. */
static const char *const pair_names[3] = {"RotD50", "RotD100", "GeoMean"};

typedef struct {
  const char *label;  /* as given */
  const char *path[3]; /* [1] NULL: a record */
  double phi[2];      /* --azimuths, or NAN */
  aq_subject in;      /* read and processed (job/subject.h) */
  aq_im im[2];        /* of each component, for the records table */
  char channel[16];   /* the component column of a record */
  double *psa_mps2;   /* ncomp x ndamp x nper */
  size_t ncomp;
  aq_status st;
  aq_error err;
} source;

typedef struct {
  source *src;
  const aq_read_opts *ro;
  const aq_signal_opts *po;
  aq_signal_ws *sws;
  const double *periods, *damping;
  size_t nper, ndamp;
  aq_spectrum_opts so;
} job;

static aq_status spectra_of(const job *J, source *s, aq_spectrum_ws *ws)
{
  const aq_processed *p = &s->in.proc[0], *q = &s->in.proc[1];
  size_t np = J->nper;
  s->ncomp = s->path[1] ? 3 : 1;
  s->psa_mps2 = malloc(s->ncomp * J->ndamp * np * sizeof(double));
  aq_rotd *rd = s->path[1] ? malloc(np * sizeof *rd) : NULL;
  if (!s->psa_mps2 || (s->path[1] && !rd)) {
    free(rd);
    return aq_error_set(&s->err, AQ_ENOMEM, s->label, -1, -1, "spectrum", "out of memory");
  }
  aq_status st = AQ_OK;
  for (size_t d = 0; st == AQ_OK && d < J->ndamp; d++) {
    if (!s->path[1]) {
      st = aq_spectrum_psa(ws, &J->so, p->acc_mps2, p->n, p->dt_s, J->damping[d],
                           J->periods, np, s->psa_mps2 + d * np, &s->err);
      continue;
    }
    st = aq_spectrum_rotd(ws, &J->so, p->acc_mps2, p->n, q->acc_mps2, q->n, p->dt_s,
                          J->damping[d], J->periods, np, rd, NULL, &s->err);
    for (size_t i = 0; st == AQ_OK && i < np; i++) {
      double v[3] = {rd[i].rotd50_mps2, rd[i].rotd100_mps2, rd[i].geomean_mps2};
      for (size_t c = 0; c < 3; c++)
        s->psa_mps2[(c * J->ndamp + d) * np + i] = v[c];
    }
  }
  free(rd);
  return st;
}

/* Task k: read, process, measure, spectra. */
static void run_source(void *ctx, size_t k)
{
  const job *J = ctx;
  source *s = &J->src[k];
  aq_error_clear(&s->err);
  aq_subject_src src = {{s->path[0], s->path[1], s->path[2]}, {s->phi[0], s->phi[1]},
                        s->label};
  aq_subject_opts so = {J->ro, J->po, 0, 0, 1, NULL}; /* a spectrum of any channel */
  s->st = aq_subject_prepare(&s->in, &src, &so, J->sws, &s->err);
  for (int c = 0; s->st == AQ_OK && c < (s->path[1] ? 2 : 1); c++)
    s->st = aq_im_compute(&s->in.proc[c], &s->im[c], &s->err);
  aq_spectrum_ws *ws = s->st == AQ_OK ? aq_spectrum_ws_alloc() : NULL;
  if (s->st == AQ_OK && !ws)
    s->st = aq_error_set(&s->err, AQ_ENOMEM, s->label, -1, -1, "spectrum", "out of memory");
  if (s->st == AQ_OK)
    s->st = spectra_of(J, s, ws);
  aq_spectrum_ws_free(ws);
  if (s->st != AQ_OK && !s->err.input[0])
    snprintf(s->err.input, sizeof s->err.input, "%s", s->label);
  if (s->st == AQ_OK && !s->path[1])
    snprintf(s->channel, sizeof s->channel, "%s",
             s->in.rec[0].channel[0] ? s->in.rec[0].channel : "-");
}

/* Periods below 2 dt lie above a record's Nyquist frequency: one warning
 * for the whole run, naming the record of the largest dt among them. */
static void warn_nyquist(const source *src, size_t n, const double *periods, size_t np)
{
  double tmin = INFINITY, dt = 0;
  const char *who = NULL;
  for (size_t i = 0; i < np; i++)
    tmin = periods[i] < tmin ? periods[i] : tmin;
  for (size_t k = 0; k < n; k++)
    if (tmin < 2 * src[k].in.proc[0].dt_s && src[k].in.proc[0].dt_s > dt) {
      dt = src[k].in.proc[0].dt_s;
      who = src[k].label;
    }
  if (!who)
    return;
  size_t below = 0;
  for (size_t i = 0; i < np; i++)
    below += periods[i] < 2 * dt;
  fprintf(stderr, "archquake: spectrum: warning: %zu of the periods (the shortest %g s) "
                  "are below 2 dt = %g s of %s, above its Nyquist frequency (%g Hz): they "
                  "are computed for the record taken as linear between samples (PSA tends "
                  "to the PGA as T -> 0)\n", below, tmin, 2 * dt, who, 0.5 / dt);
}

/* The rows, after one comment line saying where the peaks were taken. */
static void print_rows(const job *J, size_t n)
{
  printf("# peaks: %s\n", aq_spectrum_peaks_text(J->so.peaks));
  printf("record\tcomponent\tdamping\tperiod_s\tpsa_g\tsd_m\tpsv_m_s\n");
  for (size_t k = 0; k < n; k++) {
    const source *s = &J->src[k];
    for (size_t c = 0; c < s->ncomp; c++)
      for (size_t d = 0; d < J->ndamp; d++)
        for (size_t i = 0; i < J->nper; i++) {
          double a = s->psa_mps2[(c * J->ndamp + d) * J->nper + i];
          double w = 2 * AQ_PI / J->periods[i];
          printf("%s\t%s\t%s\t%s\t%s\t%s\t%s\n", s->label, s->path[1] ? pair_names[c] : s->channel,
                 AQ_TEXT_NUM(J->damping[d]), AQ_TEXT_NUM(J->periods[i]),
                 AQ_TEXT_NUM(a / AQ_G0_MPS2), AQ_TEXT_NUM(a / (w * w)), AQ_TEXT_NUM(a / w));
        }
  }
}

/* -o: the root, the records table (each component of a pair its row), the
 * spectra.  0 written, -1 not (reported; no file left). */
static int write_h5(const char *path, const char *cmdline, const job *J, size_t n,
                    long threads)
{
  char created[64];
  aq_app_now_utc(created, sizeof created);
  aq_h5_root root = {.version = AQ_VERSION, .command_line = cmdline, .created = created,
                     .proc = J->po, .threads = threads, .build = aq_build_string()};
  size_t nrow = 0;
  for (size_t k = 0; k < n; k++)
    nrow += J->src[k].ncomp * J->ndamp * J->nper;
  aq_spectrum_row *rows = malloc((nrow ? nrow : 1) * sizeof *rows);
  aq_error e;
  aq_h5_writer *w = NULL;
  aq_status s = rows ? aq_h5_open(path, &w, &e)
                     : aq_error_set(&e, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  if (s == AQ_OK)
    s = aq_h5_write_root_kind(w, &root, "spectrum", &e);
  size_t ri = 0, r = 0;
  for (size_t k = 0; s == AQ_OK && k < n; k++) {
    const source *src = &J->src[k];
    for (int c = 0; s == AQ_OK && c < (src->path[1] ? 2 : 1); c++) {
      aq_h5_record hr = {.source_file = src->path[1] ? src->path[c] : src->label,
                         .rec = &src->in.rec[c], .proc = &src->in.proc[c],
                         .im = &src->im[c], .status = "ok"};
      s = aq_h5_write_record(w, ri++, &hr, &e);
    }
    for (size_t c = 0; c < src->ncomp; c++)
      for (size_t d = 0; d < J->ndamp; d++)
        for (size_t i = 0; i < J->nper; i++) {
          double a = src->psa_mps2[(c * J->ndamp + d) * J->nper + i];
          double om = 2 * AQ_PI / J->periods[i];
          rows[r++] = (aq_spectrum_row){src->label, src->path[1] ? pair_names[c] : src->channel,
                                        J->damping[d], J->periods[i], a / AQ_G0_MPS2,
                                        a / (om * om), a / om};
        }
  }
  aq_h5_spectra hs = {rows, nrow, J->so.peaks, J->so.n_angles};
  if (s == AQ_OK)
    s = aq_h5_write_spectra(w, path, &hs, &e);
  if (s == AQ_OK) {
    s = aq_h5_finish(w, NULL, &e);
    w = NULL;
  }
  if (s != AQ_OK)
    aq_error_print(&e, stderr);
  aq_h5_abort(w);
  free(rows);
  return s == AQ_OK ? 0 : -1;
}

int aq_cmd_spectrum(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_SPECTRUM);
  int nerr = 0;
  /* before getopt_long permutes argv: "archquake spectrum ..." */
  char *words = aq_app_command_line(argc, argv);
  size_t clen = words ? strlen(words) + 12 : 1;
  char *cmdline = malloc(clen);
  if (cmdline)
    snprintf(cmdline, clen, "%s%s", words ? "archquake " : "", words ? words : "");
  free(words);
  if (aq_opts_parse(AQ_CMD_SPECTRUM, argc, argv, &o, &nerr)) { /* --help */
    free(cmdline);
    aq_opts_free(&o);
    return AQ_EXIT_OK;
  }
  for (size_t i = 0; i < o.orient.nmotions; i++)
    if (o.orient.motions[i].path[2]) {
      fprintf(stderr, "archquake: spectrum: --components %s: expected two horizontal "
                      "components H1,H2 (RotD takes no vertical; give it as a RECORD "
                      "for its own spectrum)\n", o.orient.motions[i].label);
      nerr++;
    }
  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind),
                                                    &o.read);
  if (optind >= argc && o.orient.nmotions == 0) {
    fprintf(stderr, "archquake: spectrum: expected at least one RECORD or --components\n");
    nerr++;
  }
  if (o.output && optind < argc)
    nerr += aq_opt_output_is_input("-o", o.output, argv + optind, (size_t)(argc - optind),
                                   NULL, 0);
  if (o.output && aq_opt_output_special("-o", o.output))
    nerr++;
  if (nerr) {
    free(cmdline);
    aq_opts_free(&o);
    return AQ_EXIT_USAGE;
  }
  static const double damping_default = 0.05;
  job J = {.ro = &o.read, .po = &o.proc,
           .periods = o.periods ? o.periods : aq_spectrum_peer_periods_s,
           .nper = o.periods ? o.nperiods : AQ_SPECTRUM_PEER_N,
           .damping = o.dampings ? o.dampings : &damping_default,
           .ndamp = o.dampings ? o.ndampings : 1};
  aq_spectrum_opts_default(&J.so);
  J.so.peaks = o.proc.peaks;

  char **names = NULL;
  size_t nnames = 0, n = 0;
  aq_error err;
  int rc = AQ_EXIT_OK;
  if (optind < argc && aq_record_expand(argv + optind, (size_t)(argc - optind), &o.read,
                                        &names, &nnames, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    free(cmdline);
    aq_opts_free(&o);
    return AQ_EXIT_FAIL;
  }
  J.src = calloc(nnames + o.orient.nmotions + 1, sizeof *J.src);
  J.sws = aq_signal_ws_alloc();
  if (!J.src || !J.sws) {
    fprintf(stderr, "archquake: spectrum: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t i = 0; i < nnames; i++, n++) { /* every channel a record (FILE#CH) */
    J.src[n].label = J.src[n].path[0] = names[i];
    J.src[n].phi[0] = J.src[n].phi[1] = NAN;
  }
  for (size_t i = 0; i < o.orient.nmotions; i++, n++) {
    const aq_orient_motion *m = &o.orient.motions[i];
    J.src[n].label = m->label;
    J.src[n].path[0] = m->path[0];
    J.src[n].path[1] = m->path[1];
    J.src[n].phi[0] = m->azimuth_deg[0];
    J.src[n].phi[1] = m->azimuth_deg[1];
  }
  if (aq_pool_for(n, o.threads, run_source, &J, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t k = 0; k < n; k++)
    if (J.src[k].st != AQ_OK) {
      aq_error_print(&J.src[k].err, stderr);
      rc = AQ_EXIT_FAIL;
    }
  if (rc != AQ_EXIT_OK)
    goto done; /* nothing is written */
  for (size_t k = 0; k < n; k++) {
    if (J.src[k].in.rec[0].units_conflict[0])
      fprintf(stderr, "archquake: %s: units: %s\n", J.src[k].in.rec[0].path,
              J.src[k].in.rec[0].units_conflict);
    for (int c = 0; c < 3; c++)
      if (J.src[k].in.have_rec[c])
        aq_record_print_notes(&J.src[k].in.rec[c], stderr);
  }
  warn_nyquist(J.src, n, J.periods, J.nper);
  if (o.output && write_h5(o.output, cmdline ? cmdline : "", &J, n, o.threads) != 0) {
    rc = AQ_EXIT_OUTPUT;
    goto done;
  }
  print_rows(&J, n);
  if (fflush(stdout) != 0)
    rc = AQ_EXIT_OUTPUT;
done:
  for (size_t k = 0; J.src && k < n; k++) {
    aq_subject_free(&J.src[k].in);
    free(J.src[k].psa_mps2);
  }
  free(J.src);
  aq_signal_ws_free(J.sws);
  aq_record_names_free(names, nnames);
  free(cmdline);
  aq_opts_free(&o);
  return rc;
}
