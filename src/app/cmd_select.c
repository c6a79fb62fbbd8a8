/* cmd_select.c: `archquake select POOL... --target SPEC --count N`: a
 * suite of records chosen and scaled to a target spectrum (src/select;
 * docs/select.md).  Every option, the target and the range are checked
 * before any record is read; the pool is read, processed and measured on
 * threads (select_pool.h); the selection (select/choose.h) then either
 * meets the code's conditions and is written (the suite file to stdout or
 * --text, the HDF5 file with -o), or is not and nothing is written (unless
 * --best-effort), one line saying by how much the best falls short. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../job/names.h"
#include "../report/h5_select.h"
#include "../select/choose.h"
#include "../select/range.h"
#include "../select/same.h"
#include "../select/suite_file.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"
#include "select_pool.h"

/* Write the suite file to f. */
static int write_suite(FILE *f, char lines[][AQ_SELECTION_LINE_MAX], size_t nlines,
                       const aq_selection *s, const aq_select_member *const *use, size_t N)
{
  aq_suite_row *rows = calloc(N ? N : 1, sizeof *rows);
  if (!rows)
    return -1;
  for (size_t j = 0; j < N; j++) {
    const aq_select_member *m = use[s->search.idx[j]];
    rows[j].record = (char *)m->name;
    snprintf(rows[j].channel, sizeof rows[j].channel, "%s", m->channel);
    rows[j].scale = s->scale[j];
    rows[j].misfit = s->misfit_one[j];
    snprintf(rows[j].event, sizeof rows[j].event, "%s", m->event);
  }
  const char *comment[AQ_SELECTION_LINES_MAX];
  for (size_t i = 0; i < nlines; i++)
    comment[i] = lines[i];
  int r = aq_suite_file_write(f, comment, nlines, rows, N);
  free(rows);
  return r;
}

/* -o: the selection into an HDF5 file; 0, or -1 (one line on stderr, no
 * file left). */
static int write_h5(const char *path, const aq_select_input *in, const aq_selection *sel,
                    aq_select_member *const *use, char lines[][AQ_SELECTION_LINE_MAX],
                    size_t nlines, const char *cmdline, const aq_signal_opts *proc,
                    const aq_select_pool *P)
{
  char created[64];
  aq_app_now_utc(created, sizeof created);
  size_t M = in->nrec;
  const char **rec = malloc(M * sizeof *rec), **chan = malloc(M * sizeof *chan),
             **ev = malloc(M * sizeof *ev), *comment[AQ_SELECTION_LINES_MAX];
  for (size_t i = 0; i < nlines; i++)
    comment[i] = lines[i];
  for (size_t i = 0; rec && chan && ev && i < M; i++) {
    rec[i] = use[i]->name;
    chan[i] = use[i]->channel;
    ev[i] = use[i]->event;
  }
  aq_h5_select hs = {.input = in, .sel = sel, .record = rec, .channel = chan, .event = ev,
                     .comments = comment, .ncomments = nlines, .version = AQ_VERSION,
                     .build = aq_build_string(), .command_line = cmdline ? cmdline : "",
                     .created = created, .proc = proc,
                     .peaks = aq_select_peaks_name(&P->sopts),
                     .pair_rule = aq_select_pair_name(P->pair_rule)};
  aq_error err;
  aq_status st = rec && chan && ev ? aq_h5_select_write(path, &hs, &err)
                                   : aq_error_set(&err, AQ_ENOMEM, path, -1, -1, NULL,
                                                  "out of memory");
  free(rec);
  free(chan);
  free(ev);
  if (st != AQ_OK)
    aq_error_print(&err, stderr);
  return st == AQ_OK ? 0 : -1;
}

/* The sentence on the members that are one recording, pairs[0..np) of the
 * usable members use, into buf[n]: the pairs and their correlation, as many
 * as the line holds. */
static void same_sentence(const aq_same_pair *pairs, size_t np,
                          aq_select_member *const *use, char *buf, size_t n)
{
  size_t w = (size_t)snprintf(buf, n, "%zu pair%s of the pool's records taken as one "
                              "recording (peak normalised cross-correlation of the "
                              "accelerations >= %g), at most one of each in the suite:",
                              np, np == 1 ? "" : "s", AQ_SAME_RHO_MIN);
  for (size_t k = 0; k < np && w < n; k++) {
    char one[600];
    snprintf(one, sizeof one, "%s %s and %s (%.3f)", k ? ";" : "", use[pairs[k].i]->name,
             use[pairs[k].j]->name, pairs[k].rho);
    if (w + strlen(one) + 24 >= n) {
      snprintf(buf + w, n - w, "; and %zu more", np - k);
      break;
    }
    w += (size_t)snprintf(buf + w, n - w, "%s", one);
  }
}

int aq_cmd_select(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_SELECT);
  int nerr = 0, rc = AQ_EXIT_OK;
  char *words = aq_app_command_line(argc, argv); /* before getopt_long permutes argv */
  size_t clen = words ? strlen(words) + 12 : 1;
  char *cmdline = malloc(clen);
  if (cmdline)
    snprintf(cmdline, clen, "%s%s", words ? "archquake " : "", words ? words : "");
  free(words);
  if (aq_opts_parse(AQ_CMD_SELECT, argc, argv, &o, &nerr)) { /* --help */
    free(cmdline);
    aq_opts_free(&o);
    return AQ_EXIT_OK;
  }
  aq_target target = {0};
  aq_error err;
  char **files = NULL, lines[AQ_SELECTION_LINES_MAX][AQ_SELECTION_LINE_MAX];
  size_t nfiles = 0, nlines = 0;
  char **names = NULL, **notes = NULL;
  size_t nnames = 0, nnotes = 0;
  double *grid = NULL;
  size_t nper = 0;
  aq_select_pool P = {0};
  aq_select_member **use = NULL;
  double *psa = NULL, *psa0 = NULL;
  const char **keys = NULL;
  aq_same_trace *traces = NULL;
  aq_same_pair *pairs = NULL;
  int *recording = NULL;
  size_t npairs = 0, ngroups = 0;
  char same[AQ_SELECTION_LINE_MAX - 32];
  aq_selection sel = {0};
  aq_diskcache *cache = NULL;
  int have_sel = 0;

  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind),
                                                    &o.read);
  if (optind >= argc && o.orient.nmotions == 0) {
    fprintf(stderr, "archquake: select: expected a POOL of records (files, directories or "
                    "globs) or --components pairs, got none\n");
    nerr++;
  }
  for (size_t i = 0; i < o.orient.nmotions; i++)
    if (o.orient.motions[i].path[2]) {
      fprintf(stderr, "archquake: select: --components %s: expected two horizontal "
                      "components H1,H2 (a suite is matched in the horizontal)\n",
              o.orient.motions[i].label);
      nerr++;
    }
  if (o.output && aq_opt_output_special("-o", o.output))
    nerr++;
  if (o.text && aq_opt_output_special("--text", o.text))
    nerr++;
  if (o.output && o.text && !strcmp(o.output, o.text)) {
    fprintf(stderr, "archquake: select: --text: expected a file other than -o's, got \"%s\" "
                    "twice\n", o.text);
    nerr++;
  }
  if (optind < argc) {
    nerr += aq_opt_output_is_input("-o", o.output, argv + optind, (size_t)(argc - optind),
                                   NULL, 0);
    nerr += aq_opt_output_is_input("--text", o.text, argv + optind, (size_t)(argc - optind),
                                   NULL, 0);
  }
  /* the target and the range, before any record is read */
  if (o.target && aq_target_parse(o.target, &target, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    nerr++;
  }
  double t1 = o.range_s[0], t2 = o.range_s[1];
  char range_from[200] = "--periods";
  if (!nerr && isnan(t1) && o.fragility_in) {
    char im[128];
    if (aq_select_range_from_fragility(o.fragility_in, o.arch, &t1, &t2, im, sizeof im,
                                       &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      nerr++;
    } else
      snprintf(range_from, sizeof range_from, "the range of %s, the best-ranked spectral "
               "measure of %s", im, o.fragility_in);
  } else if (isnan(t1)) {
    t1 = AQ_SELECT_T1_DEFAULT_S;
    t2 = AQ_SELECT_T2_DEFAULT_S;
    snprintf(range_from, sizeof range_from, "the default: no --periods or --fragility");
  }
  if (!nerr) {
    double lo, hi;
    aq_target_periods(&target, &lo, &hi);
    if (t1 < lo || t2 > hi) {
      fprintf(stderr, "archquake: select: --periods: expected a range within the target's "
                      "periods, %g to %g s, got %g to %g s (%s)\n", lo, hi, t1, t2,
              range_from);
      nerr++;
    } else if (aq_select_grid(t1, t2, o.period_grid, o.nperiod_grid, &grid, &nper, &err) !=
               AQ_OK) {
      aq_error_print(&err, stderr);
      nerr++;
    }
  }
  if (nerr) {
    rc = AQ_EXIT_USAGE;
    goto done;
  }
  /* the pool: files, names (every horizontal channel a record), pairs */
  if (aq_select_pool_files(argv + optind, (size_t)(argc - optind), &files, &nfiles, &err) !=
      AQ_OK) {
    aq_error_print(&err, stderr);
    rc = err.status == AQ_ENOMEM ? AQ_EXIT_FAIL : AQ_EXIT_USAGE;
    goto done;
  }
  if (nfiles && aq_job_names(files, nfiles, &o.read, o.threads, &names, &nnames, &notes,
                             &nnotes, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t i = 0; i < nnotes; i++)
    fprintf(stderr, "archquake: select: note: %s\n", notes[i]);
  P.n = nnames + o.orient.nmotions;
  if (P.n < o.count) {
    fprintf(stderr, "archquake: select: --count: expected a pool of at least %zu records, got "
                    "%zu\n", o.count, P.n);
    rc = AQ_EXIT_USAGE;
    goto done;
  }
  P.m = calloc(P.n, sizeof *P.m);
  if (!P.m) {
    fprintf(stderr, "archquake: select: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t i = 0; i < P.n; i++) {
    aq_select_member *m = &P.m[i];
    m->azimuth_deg[0] = m->azimuth_deg[1] = NAN;
    if (i < nnames) {
      m->name = m->path[0] = names[i];
      continue;
    }
    const aq_orient_motion *mo = &o.orient.motions[i - nnames];
    m->name = mo->label;
    m->path[0] = mo->path[0];
    m->path[1] = mo->path[1];
    m->azimuth_deg[0] = mo->azimuth_deg[0];
    m->azimuth_deg[1] = mo->azimuth_deg[1];
  }
  P.periods_s = grid;
  P.nper = nper;
  P.damping = target.damping;
  P.pair_rule = aq_select_pair_rule(&target);
  aq_spectrum_opts_default(&P.sopts);
  P.sopts.peaks = o.proc.peaks; /* --peaks: where each oscillator's peak is taken */
  P.read = &o.read;
  P.proc = &o.proc;
  if (o.cache_max)
    aq_diskcache_set_default_max(o.cache_max);
  if (!o.no_cache)
    cache = aq_diskcache_open(o.cache_dir, "spectra", aq_build_string());
  P.cache = cache;
  if (aq_select_pool_prepare(&P, o.threads, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  /* the usable members, each refusal named */
  use = malloc(P.n * sizeof *use);
  psa = malloc(P.n * nper * sizeof *psa);
  psa0 = malloc(P.n * sizeof *psa0);
  keys = malloc(P.n * sizeof *keys);
  if (!use || !psa || !psa0 || !keys) {
    fprintf(stderr, "archquake: select: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  size_t M = 0, refused = 0;
  for (size_t i = 0; i < P.n; i++) {
    aq_select_member *m = &P.m[i];
    if (m->st != AQ_OK) {
      char line[1200];
      aq_error_format(&m->err, line, sizeof line);
      fprintf(stderr, "archquake: select: left out of the pool: %s\n", line);
      refused++;
      continue;
    }
    use[M] = m;
    memcpy(psa + M * nper, m->psa_mps2, nper * sizeof *psa);
    psa0[M] = m->psa0_mps2;
    keys[M] = m->event_key;
    M++;
  }
  if (refused)
    rc = AQ_EXIT_FAIL;
  if (M < o.count) {
    fprintf(stderr, "archquake: select: --count: expected at least %zu usable records, got "
                    "%zu of %zu (%zu left out, named above); nothing written\n",
            o.count, M, P.n, refused);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  /* the members that are one recording (select/same.h) */
  traces = calloc(2 * M, sizeof *traces);
  recording = malloc(M * sizeof *recording);
  if (!traces || !recording) {
    fprintf(stderr, "archquake: select: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  for (size_t i = 0; i < M; i++) {
    traces[2 * i] = use[i]->trace[0];
    traces[2 * i + 1] = use[i]->trace[1];
  }
  size_t compared = 0;
  if (aq_same_groups(traces, M, psa, nper, psa0, AQ_SAME_RHO_MIN, o.threads, recording,
                     &ngroups, &pairs, &npairs, &compared, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  if (npairs) {
    same_sentence(pairs, npairs, use, same, sizeof same);
    fprintf(stderr, "archquake: select: note: same recording: %s\n", same);
  }
  aq_select_input in = {.target = &target, .periods_s = grid, .nper = nper, .nrec = M,
                        .psa_mps2 = psa, .psa0_mps2 = psa0, .event_key = keys,
                        .count = o.count, .scale_lo = o.scale_range[0],
                        .scale_hi = o.scale_range[1], .max_per_event = o.max_per_event,
                        .recording = recording,
                        .exhaustive_max = AQ_SELECT_EXHAUSTIVE_MAX, .threads = o.threads};
  if (aq_select_choose(&in, &sel, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_FAIL;
    goto done;
  }
  have_sel = 1;
  if (!sel.all_hold) {
    char why[2048];
    aq_selection_shortfall(&sel, &in, why, sizeof why);
    fprintf(stderr, "archquake: select: no suite of %zu meets the conditions within the scale "
                    "range %g to %g: %s%s\n", o.count, o.scale_range[0], o.scale_range[1],
            why, o.best_effort ? " (--best-effort: the closest is written)"
                               : "; nothing written (--best-effort writes the closest)");
    rc = AQ_EXIT_FAIL;
    if (!o.best_effort || !sel.search.found)
      goto done;
  }
  char proc_text[160];
  snprintf(proc_text, sizeof proc_text, "detrend %s, %s",
           o.proc.detrend == AQ_DETREND_LINEAR ? "linear"
           : o.proc.detrend == AQ_DETREND_MEAN ? "mean"
                                               : "none",
           o.proc.filter ? "pads and high-pass as the main job" : "no filter");
  aq_selection_context ctx = {aq_build_string(), range_from, aq_select_peaks_name(&P.sopts),
                              aq_select_pair_name(P.pair_rule), proc_text, M,
                              npairs ? same : NULL};
  nlines = aq_selection_describe(&sel, &in, &ctx, lines);
  aq_cleanup_install();
  aq_outfile tout = {0};
  if (o.text && aq_outfile_open(&tout, o.text, &err) != AQ_OK) {
    aq_error_print(&err, stderr);
    rc = AQ_EXIT_OUTPUT;
    goto done;
  }
  if (o.output && write_h5(o.output, &in, &sel, use, lines, nlines, cmdline, &o.proc, &P) != 0) {
    aq_outfile_abort(&tout);
    rc = AQ_EXIT_OUTPUT;
    goto done;
  }
  FILE *tf = tout.f ? tout.f : stdout;
  if (write_suite(tf, lines, nlines, &sel, (const aq_select_member *const *)use, o.count) != 0 ||
      (tout.f && aq_outfile_commit(&tout, &err) != AQ_OK) ||
      (!tout.f && fflush(stdout) != 0)) {
    if (tout.f)
      aq_error_print(&err, stderr);
    else
      fprintf(stderr, "archquake: select: stdout: cannot write the suite\n");
    if (tout.f)
      aq_outfile_abort(&tout);
    rc = AQ_EXIT_OUTPUT;
  }
done:
  if (cache) {
    char *cn = aq_diskcache_notes(cache);
    for (char *line = cn, *nl; line && *line; line = nl + 1) {
      nl = strchr(line, '\n');
      *nl = '\0';
      fprintf(stderr, "archquake: note: %s\n", line);
    }
    free(cn);
    aq_diskcache_close(cache);
  }
  if (have_sel)
    aq_selection_free(&sel);
  free(use);
  free(psa);
  free(psa0);
  free(keys);
  free(traces); /* the members' own arrays, freed with the pool */
  free(pairs);
  free(recording);
  aq_select_pool_free(&P);
  free(grid);
  aq_record_names_free(files, nfiles);
  aq_record_names_free(names, nnames);
  aq_record_names_free(notes, nnotes);
  aq_target_free(&target);
  free(cmdline);
  aq_opts_free(&o);
  return rc;
}
