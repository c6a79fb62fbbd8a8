/* opt_handlers.c: the options that are more than a value (their
 * handlers, named in the table of opt_table.c) and the checks across
 * options once all are parsed. */
#define _POSIX_C_SOURCE 200809L
#include "opt_table_impl.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../arch/arch.h"
#include "../arch/stepper.h"
#include "../blocks/blocks.h"
#include "../capacity/capacity.h"
#include "../select/misfit.h"
#include "../signal/spectrum.h"
#include "app.h"
#include "opt.h"
#include "opt_arch.h"
#include "opt_record.h"

/* The handlers of the options that are more than a value. */
void aq_opth_add_arch(char *arg, aq_opts *o, int *nerr)
{
  char **a = realloc(o->arches, (o->narches + 1) * sizeof *a);
  if (!a) {
    fprintf(stderr, "archquake: out of memory\n");
    (*nerr)++;
    return;
  }
  o->arches = a;
  a[o->narches++] = aq_opt_arch(arg, nerr);
}

void aq_opth_one_arch(char *arg, aq_opts *o, int *nerr)
{
  o->arch = aq_opt_arch(arg, nerr);
}

void aq_opth_ignore(char *arg, aq_opts *o, int *nerr)
{
  size_t cap = sizeof o->ignore / sizeof o->ignore[0];
  for (const char *p = arg; *p;) {
    size_t len = strcspn(p, ",");
    if (len == 0 || len >= sizeof o->ignore_buf[0] || o->nignore == cap) {
      fprintf(stderr, "archquake: compare: --ignore: expected up to %zu names of "
                      "settings or fields, comma-separated, got \"%s\"\n", cap, arg);
      (*nerr)++;
      return;
    }
    snprintf(o->ignore_buf[o->nignore], sizeof o->ignore_buf[0], "%.*s", (int)len, p);
    o->ignore[o->nignore] = o->ignore_buf[o->nignore];
    o->nignore++;
    p += len + (p[len] == ',');
  }
}

void aq_opth_units(char *arg, aq_opts *o, int *nerr)
{
  aq_opt_units(arg, &o->read, nerr);
  size_t k = strlen(o->units_text); /* the rules as given, for the results file */
  snprintf(o->units_text + k, sizeof o->units_text - k, "%s%s", k ? " " : "", arg);
}

/* The intensity measures' periods: "none" (no period), or a list of nmin
 * to nmax distinct periods in s, each in (0, 1e4], ascending if asked, into
 * v[0..nmax).  Returns their number; 0 for none or a bad list (one line
 * naming opt and what it expects). */
static size_t periods(const char *opt, const char *arg, size_t nmin, size_t nmax,
                      int ascending, const char *what, double *v, int *nerr)
{
  if (!strcmp(arg, "none"))
    return 0;
  double *got = NULL;
  size_t n = 0;
  int before = *nerr;
  aq_opt_list(opt, arg, 0, 1e4, &got, &n, nerr);
  int ok = *nerr == before && n >= nmin && n <= nmax;
  for (size_t i = 1; ok && ascending && i < n; i++)
    ok = got[i - 1] < got[i];
  if (ok)
    memcpy(v, got, n * sizeof *v);
  else if (*nerr == before) {
    fprintf(stderr, "archquake: %s: expected %s, got \"%s\"\n", opt, what, arg);
    (*nerr)++;
  }
  free(got);
  return ok ? n : 0;
}

/* --im-periods LIST: Sa(T) at up to AQ_IM_SA_MAX periods; "none": no Sa(T). */
void aq_opth_im_periods(char *arg, aq_opts *o, int *nerr)
{
  char what[64];
  snprintf(what, sizeof what, "at most %d periods in s, or none", AQ_IM_SA_MAX);
  o->proc.im_nsa = periods("--im-periods", arg, 1, AQ_IM_SA_MAX, 0, what,
                           o->proc.im_period_s, nerr);
}

/* --sa-avg T1,T2: the range of Sa_avg, 0 < T1 < T2; "none": no Sa_avg. */
void aq_opth_sa_avg(char *arg, aq_opts *o, int *nerr)
{
  double v[2] = {0, 0};
  periods("--sa-avg", arg, 2, 2, 1, "two periods T1,T2 in s with T1 < T2, or none", v, nerr);
  o->proc.sa_avg_lo_s = v[0];
  o->proc.sa_avg_hi_s = v[1];
}

/* select --periods T1,T2: the period range, 0 < T1 < T2. */
void aq_opth_select_periods(char *arg, aq_opts *o, int *nerr)
{
  double v[2] = {NAN, NAN};
  if (periods("--periods", arg, 2, 2, 1, "two periods T1,T2 in s with 0 < T1 < T2", v,
              nerr) == 2) {
    o->range_s[0] = v[0];
    o->range_s[1] = v[1];
  }
}

/* --scale-range LO,HI: 0 < LO <= HI (equal: one scale for every record). */
void aq_opth_scale_range(char *arg, aq_opts *o, int *nerr)
{
  char *comma = strchr(arg, ',');
  if (!comma || strchr(comma + 1, ',')) {
    fprintf(stderr, "archquake: --scale-range: expected two factors LO,HI with 0 < LO <= HI, "
                    "got \"%s\"\n", arg);
    (*nerr)++;
    return;
  }
  int before = *nerr;
  double v[2];
  *comma = '\0';
  aq_opt_double_gt("--scale-range", arg, 0, 1e6, &v[0], nerr);
  aq_opt_double_gt("--scale-range", comma + 1, 0, 1e6, &v[1], nerr);
  *comma = ',';
  if (*nerr != before)
    return;
  if (!(v[0] <= v[1])) {
    fprintf(stderr, "archquake: --scale-range: expected LO <= HI, got \"%s\"\n", arg);
    (*nerr)++;
    return;
  }
  o->scale_range[0] = v[0];
  o->scale_range[1] = v[1];
}

/* The checks between options (the rows' .check), made after parsing. */

/* --sampled-peaks is --peaks samples (their rows refuse the two together). */
void aq_opth_sampled_peaks_alias(aq_opts *o, int *nerr)
{
  (void)nerr;
  if (o->sampled_peaks)
    o->proc.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
}

/* Checks that need the record (the Nyquist frequency, the record length)
 * are made by aq_signal_process. */
void aq_opth_lowpass_above_highpass(aq_opts *o, int *nerr)
{
  const aq_signal_opts *p = &o->proc;
  if (p->filter && p->lowpass_hz > 0 && !(p->lowpass_hz > p->highpass_hz)) {
    fprintf(stderr, "archquake: --lowpass: expected a corner above --highpass %g Hz, "
                    "got %g Hz\n", p->highpass_hz, p->lowpass_hz);
    (*nerr)++;
  }
}

void aq_opth_ode_rtol_needs_ode(aq_opts *o, int *nerr)
{
  aq_opt_ode_rtol(o->given[AQ_OPT_ODE_RTOL] > 0, aq_model_name((aq_model)o->model), nerr);
}

/* The extension of path's last component, without its dot ("" if none). */
static const char *name_ext(const char *path)
{
  const char *base = strrchr(path, '/'), *dot;
  base = base ? base + 1 : path;
  dot = strrchr(base, '.');
  return dot && dot != base ? dot + 1 : "";
}

/* 1 if path names an existing file that is an operand or an arch: the
 * command refuses that (aq_opt_output_is_input) in its own one line. */
static int names_an_input(const aq_opts *o, const char *path)
{
  struct stat so, si;
  if (stat(path, &so) != 0 || !S_ISREG(so.st_mode))
    return 0;
  for (int i = 0; i < o->noperands + (int)o->narches; i++) {
    const char *in = i < o->noperands ? o->operands[i] : o->arches[i - o->noperands];
    if (stat(in, &si) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino)
      return 1;
  }
  return 0;
}

/* 1 if ext (any case) is one of the NULL-ended list. */
static int ext_in(const char *ext, const char *const *list)
{
  for (; *list; list++)
    if (strcasecmp(ext, *list) == 0)
      return 1;
  return 0;
}

/* -o of the commands that write HDF5 and --text/--fragility (their TSV)
 * each refuse a name that says it is another kind of file: a results
 * file named out.tsv would be HDF5 under a text name, and a table named
 * out.h5 text under an HDF5 name (plot and report check their own -o). */
static const char *const not_hdf5[] = {"tsv", "txt", "csv", "dat", "html", "htm", "png", "svg",
                                       "pdf", "json", "cfg", "at2", "sac", "mseed", NULL};
static const char *const not_text[] = {"h5", "hdf5", "hdf", "he5", "html", "htm", "png",
                                       "svg", "pdf", "cfg", "at2", "sac", "mseed", NULL};

void aq_opth_output_names_hdf5(aq_opts *o, int *nerr)
{
  if (o->output && ext_in(name_ext(o->output), not_hdf5) && !names_an_input(o, o->output)) {
    fprintf(stderr, "archquake: -o: expected an HDF5 file name (FILE.h5), got \"%s\" "
                    "(the table goes to stdout or --text FILE)\n", o->output);
    (*nerr)++;
  }
}

static void text_name(const aq_opts *o, const char *opt, const char *path, int *nerr)
{
  if (path && ext_in(name_ext(path), not_text) && !names_an_input(o, path)) {
    fprintf(stderr, "archquake: %s: expected a text file name (FILE.tsv), got \"%s\" "
                    "(the HDF5 results go to -o FILE.h5)\n", opt, path);
    (*nerr)++;
  }
}
void aq_opth_text_names_text(aq_opts *o, int *nerr) { text_name(o, "--text", o->text, nerr); }
void aq_opth_fragility_names_text(aq_opts *o, int *nerr)
{
  text_name(o, "--fragility", o->fragility, nerr);
}

/* The block model runs in pulse, the main job and capacity
 * (src/blocks/blocks.h); domain's half-cycles are the four-hinge model's. */
void aq_opth_blocks_model_applies(aq_opts *o, int *nerr)
{
  if (o->model == AQ_MODEL_BLOCKS && o->cmd == AQ_CMD_DOMAIN) {
    fprintf(stderr, "archquake: --model: expected workpath, ode, paper or workpath-quad here "
                    "(domain's half-cycles are the four-hinge model's), got blocks\n");
    (*nerr)++;
  }
}

void aq_opth_blocks_dt_needs_blocks(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_BLOCKS_DT] && o->model != AQ_MODEL_BLOCKS && o->check_blocks < 0) {
    fprintf(stderr, "archquake: --blocks-dt: expected --model blocks or --check blocks with "
                    "it, got --model %s\n", aq_model_name((aq_model)o->model));
    (*nerr)++;
  }
}

/* --check blocks re-runs the four-hinge model's marked runs under the
 * block model: not a check of the block model itself. */
void aq_opth_check_not_blocks(aq_opts *o, int *nerr)
{
  if (o->check_blocks >= 0 && o->model == AQ_MODEL_BLOCKS) {
    fprintf(stderr, "archquake: --check: expected a four-hinge --model with --check blocks "
                    "(workpath, ode, paper, workpath-quad), got --model blocks\n");
    (*nerr)++;
  }
}

/* --cor and --impact are the four-hinge models' impact rules; the block
 * model's impacts follow each contact's restitution ([contact] e_n). */
void aq_opth_cor_not_blocks(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_COR] && o->model == AQ_MODEL_BLOCKS) {
    fprintf(stderr, "archquake: --cor: expected a four-hinge model with it, got --model "
                    "blocks (its impacts follow [contact] e_n)\n");
    (*nerr)++;
  }
}

void aq_opth_momentum_takes_no_cor(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_IMPACT] && o->model == AQ_MODEL_BLOCKS) {
    fprintf(stderr, "archquake: --impact: expected a four-hinge model with it, got --model "
                    "blocks (its impacts follow [contact] e_n)\n");
    (*nerr)++;
  }
  if (o->impact == AQ_IMPACT_MOMENTUM && !isnan(o->cor)) {
    fprintf(stderr, "archquake: --cor: expected --impact cor with it, got --impact "
                    "momentum (a cor would have no effect)\n");
    (*nerr)++;
  }
}

void aq_opth_orientation(aq_opts *o, int *nerr)
{
  aq_opt_orient_check(&o->orient, nerr);
}

/* Why the cache directory dir cannot be used (made if missing, beside an
 * existing parent, as the cache makes it; written; its records/ and
 * arches/ directories), into why[n]; "" if it can. */
static void cache_dir_unusable(const char *dir, char *why, size_t n)
{
  struct stat sb;
  why[0] = '\0';
  if (!dir[0]) {
    snprintf(why, n, "an empty name");
  } else if (stat(dir, &sb) == 0) {
    if (!S_ISDIR(sb.st_mode))
      snprintf(why, n, "a file that is not a directory");
    else if (access(dir, W_OK | X_OK) != 0)
      snprintf(why, n, "a directory that cannot be written (%s)", strerror(errno));
    for (int k = 0; k < 2 && !why[0]; k++) {
      char sub[PATH_MAX];
      snprintf(sub, sizeof sub, "%s/%s", dir, k ? "arches" : "records");
      if (stat(sub, &sb) == 0 && !S_ISDIR(sb.st_mode))
        snprintf(why, n, "a directory whose %s is a file, not a directory", k ? "arches"
                                                                               : "records");
    }
  } else if (errno != ENOENT) {
    snprintf(why, n, "a path that cannot be looked at (%s)", strerror(errno));
  } else {
    char parent[PATH_MAX];
    snprintf(parent, sizeof parent, "%s", dir);
    char *slash = strrchr(parent, '/');
    while (slash && slash > parent && slash[1] == '\0') { /* "dir/" */
      *slash = '\0';
      slash = strrchr(parent, '/');
    }
    if (!slash)
      snprintf(parent, sizeof parent, ".");
    else if (slash == parent)
      parent[1] = '\0';
    else
      *slash = '\0';
    if (stat(parent, &sb) != 0)
      snprintf(why, n, "its parent %s cannot be used (%s)", parent, strerror(errno));
    else if (!S_ISDIR(sb.st_mode))
      snprintf(why, n, "its parent %s is not a directory", parent);
    else if (access(parent, W_OK | X_OK) != 0)
      snprintf(why, n, "its parent %s cannot be written (%s)", parent, strerror(errno));
  }
}

/* --cache-dir names where --no-cache would not look: refused together.  A
 * directory the user names must be usable, or nothing runs (without
 * --cache-dir, a default directory that cannot be written is a note and
 * the run goes on). */
void aq_opth_cache_dir_needs_cache(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_CACHE_DIR] && o->given[AQ_OPT_NO_CACHE]) {
    fprintf(stderr, "archquake: --cache-dir: expected no --no-cache with it (--no-cache "
                    "uses no cache directory), got both\n");
    (*nerr)++;
    return;
  }
  char why[PATH_MAX + 128];
  if (o->given[AQ_OPT_CACHE_DIR] && o->cache_dir &&
      (cache_dir_unusable(o->cache_dir, why, sizeof why), why[0])) {
    fprintf(stderr, "archquake: --cache-dir: expected a directory that can be written, or "
                    "made in an existing one, got \"%s\": %s\n", o->cache_dir, why);
    (*nerr)++;
  }
}

/* --cache-max SIZE: digits (a decimal point allowed), then K, M, G or T
 * for a binary multiple (1K = 1024 bytes) or none for bytes; a whole
 * number of bytes, at least 1, below 2^62. */
void aq_opth_cache_max(char *arg, aq_opts *o, int *nerr)
{
  static const char units[] = "KMGT";
  size_t whole = strspn(arg, "0123456789"), frac = 0;
  if (whole && arg[whole] == '.')
    frac = 1 + strspn(arg + whole + 1, "0123456789");
  const char *end = arg + whole + frac, *u = *end ? strchr(units, *end) : NULL;
  double v = whole ? strtod(arg, NULL) : 0;
  if (u)
    v = ldexp(v, 10 * (int)(u - units + 1));
  if (!whole || (*end && (!u || end[1] != '\0')) || !(v >= 1) || !(v < 0x1p62) ||
      v != floor(v)) {
    fprintf(stderr, "archquake: --cache-max: expected a size above 0, in bytes or with K, M, "
                    "G or T (1K = 1024 bytes), e.g. 512M, got \"%s\"\n", arg);
    (*nerr)++;
    return;
  }
  o->cache_max = (unsigned long long)v;
}

/* After --highpass's value: an explicit corner is checked as given. */
void aq_opth_highpass_given(char *arg, aq_opts *o, int *nerr)
{
  (void)arg;
  (void)nerr;
  o->proc.highpass_auto = 0;
}

