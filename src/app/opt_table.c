/* opt_table.c: the table of every option and every command (see
 * opt_table.h for how to add one), and the options' defaults. */
#define _POSIX_C_SOURCE 200809L
#include "opt_table.h"

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

/* The commands an option applies to. */
#define C(x) (1u << AQ_CMD_##x)
#define PLOT_ALL (C(PLOT_HISTORY) | C(PLOT_ARCH) | C(PLOT_DOMAIN) | C(PLOT_SUITE) | C(PLOT_CAPACITY) | \
                  C(PLOT_SPECTRUM))
#define ALL_CMDS ((1u << AQ_CMD_N) - 1)
#define RECORDS (C(RUN) | C(INFO) | C(CAPACITY) | C(SPECTRUM)) /* the commands that read records */
#define SUITES (C(RUN) | C(CAPACITY))            /* ... and run them against arches */
#define READS (RECORDS | C(SELECT)) /* reading and processing: select's pool too */
#define DYNAMICS (SUITES | C(PULSE) | C(DOMAIN))  /* the commands that run the stepper */

/* Where a value goes. */
#define DEST(f) .dest = offsetof(aq_opts, f)
#define DEST_LIST(f, n) .dest = offsetof(aq_opts, f), .dest_n = offsetof(aq_opts, n)
/* A list of options for a rule (.requires, .conflicts, .not_below, .not_above). */
#define OPTS(...) ((const int[]){__VA_ARGS__, -1})

#define AQ_MAX_THREADS 1024
#define AQ_OPT_FREQ_MAX_HZ 1e6
#define AQ_OPT_ORDER_MAX 20 /* Butterworth orders used in practice are 1-8 */
/* Smallest domain --tol, s: a finer bisection of durations of 0.01-100 s
 * would reach the spacing of doubles, where hi - lo stops shrinking. */
#define AQ_DOMAIN_TOL_MIN_S 1e-12
/* compare's defaults: a nightly rerun of the same build reproduces every
 * value exactly; 1e-9 leaves room only for a different compiler or libm. */
#define AQ_COMPARE_RTOL_DEFAULT 1e-9
#define AQ_COMPARE_ATOL_DEFAULT 0.0

_Static_assert(sizeof(aq_detrend) == sizeof(int), "--detrend is stored as an int");
_Static_assert(sizeof(aq_spectrum_peaks) == sizeof(int), "--peaks is stored as an int");

static const char *const detrends[] = {"mean", "linear", "none", NULL}; /* aq_detrend */
static const char *const impacts[] = {"cor", "momentum", NULL};
static const char *const x_axes[] = {"qc", "rad", NULL};
static const char *const y_axes[] = {"scale", "pga", NULL};
static const char *const papers[] = {"a4", "letter", NULL}; /* aq_plot_paper */
static const char *const checks[] = {"blocks", NULL}; /* --check */

/* The handlers of the options that are more than a value. */
static void add_arch(char *arg, aq_opts *o, int *nerr)
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

static void one_arch(char *arg, aq_opts *o, int *nerr)
{
  o->arch = aq_opt_arch(arg, nerr);
}

static void ignore(char *arg, aq_opts *o, int *nerr)
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

static void units(char *arg, aq_opts *o, int *nerr)
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
static void im_periods(char *arg, aq_opts *o, int *nerr)
{
  char what[64];
  snprintf(what, sizeof what, "at most %d periods in s, or none", AQ_IM_SA_MAX);
  o->proc.im_nsa = periods("--im-periods", arg, 1, AQ_IM_SA_MAX, 0, what,
                           o->proc.im_period_s, nerr);
}

/* --sa-avg T1,T2: the range of Sa_avg, 0 < T1 < T2; "none": no Sa_avg. */
static void sa_avg(char *arg, aq_opts *o, int *nerr)
{
  double v[2] = {0, 0};
  periods("--sa-avg", arg, 2, 2, 1, "two periods T1,T2 in s with T1 < T2, or none", v, nerr);
  o->proc.sa_avg_lo_s = v[0];
  o->proc.sa_avg_hi_s = v[1];
}

/* select --periods T1,T2: the period range, 0 < T1 < T2. */
static void select_periods(char *arg, aq_opts *o, int *nerr)
{
  double v[2] = {NAN, NAN};
  if (periods("--periods", arg, 2, 2, 1, "two periods T1,T2 in s with 0 < T1 < T2", v,
              nerr) == 2) {
    o->range_s[0] = v[0];
    o->range_s[1] = v[1];
  }
}

/* --scale-range LO,HI: 0 < LO <= HI (equal: one scale for every record). */
static void scale_range(char *arg, aq_opts *o, int *nerr)
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
static void sampled_peaks_alias(aq_opts *o, int *nerr)
{
  (void)nerr;
  if (o->sampled_peaks)
    o->proc.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
}

/* Checks that need the record (the Nyquist frequency, the record length)
 * are made by aq_signal_process. */
static void lowpass_above_highpass(aq_opts *o, int *nerr)
{
  const aq_signal_opts *p = &o->proc;
  if (p->filter && p->lowpass_hz > 0 && !(p->lowpass_hz > p->highpass_hz)) {
    fprintf(stderr, "archquake: --lowpass: expected a corner above --highpass %g Hz, "
                    "got %g Hz\n", p->highpass_hz, p->lowpass_hz);
    (*nerr)++;
  }
}

static void ode_rtol_needs_ode(aq_opts *o, int *nerr)
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

static void output_names_hdf5(aq_opts *o, int *nerr)
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
static void text_names_text(aq_opts *o, int *nerr) { text_name(o, "--text", o->text, nerr); }
static void fragility_names_text(aq_opts *o, int *nerr)
{
  text_name(o, "--fragility", o->fragility, nerr);
}

/* The block model runs in pulse, the main job and capacity
 * (src/blocks/blocks.h); domain's half-cycles are the four-hinge model's. */
static void blocks_model_applies(aq_opts *o, int *nerr)
{
  if (o->model == AQ_MODEL_BLOCKS && o->cmd == AQ_CMD_DOMAIN) {
    fprintf(stderr, "archquake: --model: expected workpath, ode, paper or workpath-quad here "
                    "(domain's half-cycles are the four-hinge model's), got blocks\n");
    (*nerr)++;
  }
}

static void blocks_dt_needs_blocks(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_BLOCKS_DT] && o->model != AQ_MODEL_BLOCKS && o->check_blocks < 0) {
    fprintf(stderr, "archquake: --blocks-dt: expected --model blocks or --check blocks with "
                    "it, got --model %s\n", aq_model_name((aq_model)o->model));
    (*nerr)++;
  }
}

/* --check blocks re-runs the four-hinge model's marked runs under the
 * block model: not a check of the block model itself. */
static void check_not_blocks(aq_opts *o, int *nerr)
{
  if (o->check_blocks >= 0 && o->model == AQ_MODEL_BLOCKS) {
    fprintf(stderr, "archquake: --check: expected a four-hinge --model with --check blocks "
                    "(workpath, ode, paper, workpath-quad), got --model blocks\n");
    (*nerr)++;
  }
}

/* --cor and --impact are the four-hinge models' impact rules; the block
 * model's impacts follow each contact's restitution ([contact] e_n). */
static void cor_not_blocks(aq_opts *o, int *nerr)
{
  if (o->given[AQ_OPT_COR] && o->model == AQ_MODEL_BLOCKS) {
    fprintf(stderr, "archquake: --cor: expected a four-hinge model with it, got --model "
                    "blocks (its impacts follow [contact] e_n)\n");
    (*nerr)++;
  }
}

static void momentum_takes_no_cor(aq_opts *o, int *nerr)
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

static void orientation(aq_opts *o, int *nerr)
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
static void cache_dir_needs_cache(aq_opts *o, int *nerr)
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
static void cache_max(char *arg, aq_opts *o, int *nerr)
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
static void highpass_given(char *arg, aq_opts *o, int *nerr)
{
  (void)arg;
  (void)nerr;
  o->proc.highpass_auto = 0;
}

const aq_opt_row aq_opt_rows[AQ_OPT_N] = {
    [AQ_OPT_ARCHES] = {.name = "arch", .kind = AQ_ARG_CUSTOM, .meta = "FILE", .fn = add_arch,
                       .cmds = SUITES,
                       .help = "an arch (.cfg), or an installed arch by name (oppenheim); "
                               "repeatable",
                       .required = SUITES},
    [AQ_OPT_ARCH] = {.name = "arch", .kind = AQ_ARG_CUSTOM, .meta = "FILE", .fn = one_arch,
                     .cmds = C(MECHANISM) | C(PULSE) | C(DOMAIN) | C(PLOT_DOMAIN),
                     .help = "the arch file (.cfg), or an installed arch by name (oppenheim)",
                     .required = C(MECHANISM) | C(PULSE) | C(DOMAIN) | C(PLOT_DOMAIN)},
    [AQ_OPT_ARCH_NAME] = {.name = "arch", .kind = AQ_ARG_STRING, .meta = "NAME", DEST(arch),
                          .cmds = C(PLOT_CAPACITY),
                          .help = "the arch of the capacity file to draw, by its name "
                                  "(default: the file's first)"},
    [AQ_OPT_ARCH_DRAWN] = {.name = "arch", .kind = AQ_ARG_STRING, .meta = "ARCH", DEST(arch),
                           .cmds = C(PLOT_ARCH),
                           .help = "the arch file (.cfg), or an installed arch by name; with "
                                   "a results file (RESULTS.h5 before the options), the name "
                                   "of its arch to draw (default: its first)"},
    [AQ_OPT_ACCEL_G] = {.name = "accel-g", .kind = AQ_ARG_DOUBLE, .lo = -100, .hi = 100,
                        .meta = "A", DEST(accel_g), .cmds = C(PULSE),
                        .help = "pulse amplitude, g (signed, |A| <= 100: its sign is the "
                                "polarity, so pulse takes no --polarity)",
                        .required = C(PULSE)},
    [AQ_OPT_DURATION] = {.name = "duration", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                         .meta = "S", DEST(duration_s), .cmds = C(PULSE),
                         .help = "pulse duration, s (0 < S <= 3600)",
                         .required = C(PULSE)},
    [AQ_OPT_END] = {.name = "end", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 86400, .meta = "S",
                    DEST(end_s), .cmds = C(PULSE),
                    .help = "stop at t = S (>= duration).  Default: run until rest or "
                            "collapse: end_s is the first duration + k s (k = 0, 1, 2, ...) "
                            "at which the arch has collapsed or is at rest (s = 0, no "
                            "kinetic energy, by the stepper's rest criterion); the row "
                            "equals that of --end end_s.  Motion that never rests (COR 1) "
                            "stops at the cap, --max-end, with a note on stderr (exit 0)",
                    .not_below = OPTS(AQ_OPT_DURATION)},
    [AQ_OPT_MAX_END] = {.name = "max-end", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 86400,
                        .meta = "S", DEST(max_end_s), .cmds = C(PULSE),
                        .help = "the cap of the default end, s (default duration + 3600 s, "
                                "and at most 5e6 steps of --dt)",
                        .conflicts = OPTS(AQ_OPT_END), .not_below = OPTS(AQ_OPT_DURATION),
                        .why = "it caps the default end"},
    [AQ_OPT_PULSE_DT] = {.name = "dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                         .meta = "S", DEST(pulse_dt_s), .cmds = C(PULSE),
                         .help = "constant steps of at most S seconds (default 0.01)"},
    [AQ_OPT_RATIOS] = {.name = "ratios", .kind = AQ_ARG_LIST, .lo = 1, .hi = 1000,
                       .meta = "LIST", DEST_LIST(ratios, nratios),
                       .cmds = C(DOMAIN) | C(PLOT_DOMAIN),
                       .help = "comma-separated ratios r > 1 (at most 1000) of the "
                               "pulse to lambda0 g (default 1.05,1.1,1.2,1.5,2,3,4; plot domain: "
                               "1.02,1.05,1.1,1.2,1.35,1.5,1.75,2,2.5,3,4,5)"},
    [AQ_OPT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                       .meta = "FILE.h5", DEST(output),
                       .cmds = SUITES | C(SPECTRUM) | C(SELECT), .check = output_names_hdf5,
                       .help = "write the HDF5 results file (docs/hdf5-layout.md; capacity: "
                               "its results in a `capacity` group; spectrum: the spectra "
                               "in a `spectra` group; select: a `select` group)"},
    [AQ_OPT_PLOT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                            .meta = "FILE", DEST(output), .cmds = PLOT_ALL,
                            .help = "the figure (.png .svg .pdf)",
                            .required = PLOT_ALL},
    [AQ_OPT_REPORT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                              .meta = "FILE.html", DEST(output), .cmds = C(REPORT),
                              .help = "the page",
                              .required = C(REPORT)},
    [AQ_OPT_TEXT] = {.name = "text", .kind = AQ_ARG_STRING, .meta = "FILE", DEST(text),
                     .cmds = SUITES | C(SELECT), .check = text_names_text,
                     .help = "write the TSV to FILE instead of stdout"},
    [AQ_OPT_FRAGILITY] = {.name = "fragility", .kind = AQ_ARG_STRING, .meta = "FILE",
                          DEST(fragility), .cmds = C(CAPACITY), .check = fragility_names_text,
                          .help = "lognormal fragility fits, one row per (arch, IM)"},
    [AQ_OPT_DATA] = {.name = "data", .kind = AQ_ARG_STRING, .meta = "FILE.csv", DEST(data),
                     .cmds = PLOT_ALL,
                     .help = "also write the plotted data (columns carry units)"},
    [AQ_OPT_PAPER] = {.name = "paper", .kind = AQ_ARG_CHOICE, .choices = papers,
                      .meta = "a4|letter", DEST(paper), .cmds = PLOT_ALL,
                      .help = "the page of a PDF (default: the locale's paper, LC_PAPER, else "
                              "A4); the figure is scaled to fit"},
    [AQ_OPT_RUN] = {.name = "run", .kind = AQ_ARG_STRING, .meta = "KEY", DEST(run),
                    .cmds = C(PLOT_HISTORY) | C(PLOT_ARCH),
                    .help = "the run to draw: a group under /histories, e.g. "
                            "00000_000_000 (default: the first run with histories; plot "
                            "arch: a run of --model blocks, every voussoir as its history "
                            "has it, at --at)"},
    [AQ_OPT_RECORD] = {.name = "record", .kind = AQ_ARG_STRING, .meta = "NAME", DEST(record),
                       .cmds = C(PLOT_SPECTRUM),
                       .help = "the record (or --components pair) of a spectrum file to draw, "
                               "as its record column says or by file name (default: all)"},
    [AQ_OPT_ROTATION] = {.name = "rotation", .kind = AQ_ARG_DOUBLE, .lo = -10, .hi = 10,
                         .meta = "RAD", DEST(rotation_rad), .cmds = C(PLOT_ARCH),
                         .conflicts = OPTS(AQ_OPT_RUN),
                         .help = "draw the mechanism deformed at that rotation of body 1: "
                                 "the primary set if RAD > 0, the reverse set if RAD < 0, "
                                 "|RAD| <= q_c"},
    [AQ_OPT_AT] = {.name = "at", .kind = AQ_ARG_LIST, .lo = -1e3, .hi = 1e5, .meta = "LIST",
                   DEST_LIST(at_s, nat), .cmds = C(PLOT_ARCH), .requires = OPTS(AQ_OPT_RUN),
                   .help = "with --run: the record times (s) to draw the voussoirs at, at "
                           "most 6, e.g. 1.2,1.5 (within the run's history; default: the "
                           "time of voussoir 0's largest |rotation|); the last is filled"},
    [AQ_OPT_IM] = {.name = "im", .kind = AQ_ARG_STRING, .meta = "IM", DEST(im),
                   .cmds = C(PLOT_CAPACITY),
                   .help = "the intensity measure of the fragility: pga_g (default), "
                           "pgv_m_s, pgd_m, arias_m_s, cav_m_s, pga_lambda0, or a spectral "
                           "measure the file's fits hold (capacity's --im-periods and "
                           "--sa-avg: sa_0.2s_g, sa_avg_0.1_1s_g)"},
    [AQ_OPT_X] = {.name = "x", .kind = AQ_ARG_CHOICE, .choices = x_axes, .meta = "qc|rad",
                  DEST(x_rad), .cmds = C(PLOT_CAPACITY),
                  .help = "the peak rotation over q_c (qc, the default) or in rad (rad)"},
    [AQ_OPT_Y] = {.name = "y", .kind = AQ_ARG_CHOICE, .choices = y_axes, .meta = "scale|pga",
                  DEST(y_pga), .cmds = C(PLOT_CAPACITY),
                  .help = "the scale factor (scale, the default) or the PGA in g (pga)"},
    [AQ_OPT_SCALE] = {.name = "scale", .kind = AQ_ARG_LIST, .lo = 0, .hi = INFINITY,
                      .meta = "LIST", DEST_LIST(scales, nscale), .cmds = C(RUN),
                      .help = "run each record scaled by each factor, e.g. 0.5,1,2 "
                              "(default 1)"},
    [AQ_OPT_SCALE_TO_PGA] = {.name = "scale-to-pga", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 100,
                             .meta = "G", DEST(scale_to_pga_g), .cmds = C(RUN),
                             .help = "scale each processed record to a PGA of G g instead",
                             .conflicts = OPTS(AQ_OPT_SCALE),
                             .why = "one scaling rule per run"},
    [AQ_OPT_SCALE_TO_LAMBDA0] = {.name = "scale-to-lambda0", .kind = AQ_ARG_DOUBLE_GT,
                                 .lo = 0, .hi = 100, .meta = "K", DEST(scale_to_lambda0),
                                 .cmds = C(RUN),
                                 .help = "scale each processed record, for each arch, to a "
                                         "PGA of K lambda0 g, lambda0 the arch's static "
                                         "collapse multiplier (the smaller of its two hinge "
                                         "sets'), so that one suite shakes arches of unlike "
                                         "strength alike",
                                 .conflicts = OPTS(AQ_OPT_SCALE, AQ_OPT_SCALE_TO_PGA),
                                 .why = "one scaling rule per run"},
    [AQ_OPT_SCALE_MAX] = {.name = "scale-max", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 1e6,
                          .meta = "S", DEST(scale_max), .cmds = C(CAPACITY),
                          .help = "highest scale (default: PGA = 20 lambda0 g)"},
    [AQ_OPT_RESOLUTION] = {.name = "resolution", .kind = AQ_ARG_DOUBLE,
                           .lo = AQ_SCAN_RESOLUTION_MIN, .hi = AQ_SCAN_RESOLUTION_MAX,
                           .meta = "R", DEST(resolution), .cmds = C(CAPACITY),
                           .help = "relative scan step: no window of either verdict wider "
                                   "than R is missed (default 0.01; 1e-4 to 1)"},
    [AQ_OPT_SCAN_TOL] = {.name = "tol", .kind = AQ_ARG_DOUBLE, .lo = AQ_SCAN_TOL_MIN, .hi = 1,
                         .meta = "T", DEST(scan_tol), .cmds = C(CAPACITY),
                         .help = "relative tolerance of each change (default 1e-6; 1e-12 "
                                 "to R)",
                         .not_above = OPTS(AQ_OPT_RESOLUTION)},
    [AQ_OPT_DOMAIN_TOL] = {.name = "tol", .kind = AQ_ARG_DOUBLE, .lo = AQ_DOMAIN_TOL_MIN_S,
                           .hi = 1, .meta = "S", DEST(domain_tol_s), .cmds = C(DOMAIN),
                           .help = "bisection tolerance on the duration, s, 1e-12..1 "
                                   "(default 1e-9; at most --max-duration)",
                           .not_above = OPTS(AQ_OPT_MAX_DURATION)},
    [AQ_OPT_MAX_DURATION] = {.name = "max-duration", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                             .hi = 3600, .meta = "S", DEST(max_duration_s), .cmds = C(DOMAIN),
                             .help = "give up above this duration, s (default 100)"},
    [AQ_OPT_JOBS] = {.name = "jobs", .short_name = 'j', .kind = AQ_ARG_LONG, .lo = 1,
                     .hi = AQ_MAX_THREADS, .meta = "N", DEST(threads),
                     .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                     .help = "worker threads (default: the number of cores); the results "
                             "are the same for every N"},
    [AQ_OPT_MODEL] = {.name = "model", .kind = AQ_ARG_CHOICE, .choices = aq_model_names,
                      .meta = "M", DEST(model), .cmds = DYNAMICS,
                      .help = "workpath (default), ode (reference), paper, workpath-quad, "
                              "blocks (rigid voussoirs in frictional contact; docs/blocks.md)",
                      .check = blocks_model_applies},
    [AQ_OPT_COR] = {.name = "cor", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 1, .meta = "C",
                    DEST(cor), .cmds = DYNAMICS | C(PLOT_DOMAIN), .check = cor_not_blocks,
                    .help = "kinetic-energy ratio kept at an impact, 0..1 (default: each "
                            "arch's [dynamics] cor; refused for an arch whose impact is "
                            "momentum, which uses none)"},
    [AQ_OPT_FRICTION] = {.name = "friction", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 1e3,
                         .meta = "MU", DEST(friction),
                         .cmds = DYNAMICS | C(MECHANISM) | C(PLOT_ARCH),
                         .help = "the Coulomb friction coefficient of every joint, springings "
                                 "included, 0 < MU <= 1000 (default: each arch's [contact] "
                                 "friction; none if it has none)"},
    [AQ_OPT_BLOCKS_DT] = {.name = "blocks-dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 0.1,
                          .meta = "S", DEST(blocks_dt_s), .cmds = C(PULSE) | SUITES,
                          .help = "the block model's time step, s (default 0.002; only with "
                                  "--model blocks or --check blocks)",
                          .check = blocks_dt_needs_blocks},
    [AQ_OPT_CHECK] = {.name = "check", .kind = AQ_ARG_CHOICE, .choices = checks,
                      .meta = "blocks", DEST(check_blocks), .cmds = C(RUN),
                      .check = check_not_blocks,
                      .help = "re-run under --model blocks every run whose status the "
                              "four-hinge model marks (slides, beyond): the block model's "
                              "verdict in the columns check_blocks (agrees, differs, failed; "
                              "- for a run not checked), check_collapsed, "
                              "check_collapse_time_s, check_peak_rotation_rad, and what it "
                              "saw in max_slip_m, hinges_observed, hinges_first_s, "
                              "mechanism_changed_s (docs/blocks.md)"},
    [AQ_OPT_IMPACT] = {.name = "impact", .kind = AQ_ARG_CHOICE, .choices = impacts,
                       .meta = "RULE", DEST(impact), .cmds = C(PULSE),
                       .help = "cor | momentum (default: the arch file's)",
                       .check = momentum_takes_no_cor},
    [AQ_OPT_ODE_RTOL] = {.name = "ode-rtol", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 0.1,
                         .meta = "R", DEST(ode_rtol), .cmds = C(PULSE) | C(DOMAIN),
                         .help = "ode model tolerance (default 1e-10; only with --model ode)",
                         .check = ode_rtol_needs_ode},
    [AQ_OPT_HISTORY] = {.name = "history", .kind = AQ_ARG_FLAG, DEST(history), .cmds = C(RUN),
                        .help = "write histories (step ends, turning points, impacts) to the "
                                "HDF5 file (with -o), with each record's processed ground "
                                "motion (as --store-records), which plot history draws",
                        .requires = OPTS(AQ_OPT_OUTPUT),
                        .why = "histories are written only to the results file"},
    [AQ_OPT_HISTORY_FILE] = {.name = "history", .kind = AQ_ARG_STRING, .meta = "FILE",
                             DEST(history_file), .cmds = C(PULSE),
                             .help = "write the history as CSV (step ends, turning points, "
                                     "impacts)"},
    [AQ_OPT_STORE_RECORDS] = {.name = "store-records", .kind = AQ_ARG_FLAG, DEST(store_records),
                              .cmds = C(RUN),
                              .help = "write the processed records to the HDF5 file (with -o)",
                              .requires = OPTS(AQ_OPT_OUTPUT),
                              .why = "processed records are written only to the results file"},
    [AQ_OPT_RESUME] = {.name = "resume", .kind = AQ_ARG_FLAG, DEST(resume), .cmds = C(RUN),
                       .help = "continue an interrupted run of this same command (with -o): "
                               "every record done is kept in FILE.h5.journal until the "
                               "results file is complete; the outputs equal an "
                               "uninterrupted run's (not with --history or --store-records)",
                       .requires = OPTS(AQ_OPT_OUTPUT),
                       .conflicts = OPTS(AQ_OPT_HISTORY, AQ_OPT_STORE_RECORDS),
                       .why = "the journal beside the results file holds rows and record "
                              "metadata, not datasets"},
    [AQ_OPT_POLARITY] = {.name = "polarity", .kind = AQ_ARG_CHOICE,
                         .choices = aq_opt_polarity_names, .meta = "P", DEST(polarity),
                         .cmds = SUITES,
                         .help = "normal (the record as read), reversed (negated) or both "
                                 "(each record both ways; the polarity column says which: a "
                                 "hinge-controlled arch's response depends on the sign); "
                                 "default both, the worse governing every summary, or normal "
                                 "alone when every arch has free hinges and is its own mirror "
                                 "image (it answers a record and its negation alike) or every "
                                 "subject is a ground motion at azimuths in opposite pairs "
                                 "(--azimuth all)"},
    [AQ_OPT_TABLE] = {.name = "table", .kind = AQ_ARG_FLAG, DEST(table), .cmds = C(MECHANISM),
                      .help = "add, after a blank line, the work path of each admissible set "
                              "at N points over [0, q_c] (the data of the paper's Figs 4-7)"},
    [AQ_OPT_POINTS] = {.name = "points", .kind = AQ_ARG_LONG, .lo = 2, .hi = 100000,
                       .meta = "N", DEST(points), .cmds = C(MECHANISM),
                       .help = "rows per set in --table (2..100000, default 101)",
                       .requires = OPTS(AQ_OPT_TABLE),
                       .why = "the number of rows of the table"},
    [AQ_OPT_RTOL] = {.name = "rtol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 1, .meta = "R",
                     DEST(rtol), .cmds = C(COMPARE), .help = "relative tolerance (default 1e-9)"},
    [AQ_OPT_ATOL] = {.name = "atol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = HUGE_VAL,
                     .meta = "A", DEST(atol), .cmds = C(COMPARE),
                     .help = "absolute tolerance in each field's units (default 0)"},
    [AQ_OPT_IGNORE] = {.name = "ignore", .kind = AQ_ARG_CUSTOM, .meta = "NAME", .fn = ignore,
                       .cmds = C(COMPARE),
                       .help = "leave out a setting or a field (repeatable, or a comma "
                               "list), e.g. --ignore model to compare two models' numbers; "
                               "record_sha256 / arch_sha256 match records by file name / "
                               "arches by name alone"},
    [AQ_OPT_QUIET] = {.name = "quiet", .short_name = 'q', .kind = AQ_ARG_FLAG, DEST(quiet),
                      .cmds = C(RUN),
                      .help = "no progress line (it is shown only on a terminal)"},
    [AQ_OPT_PERIODS] = {.name = "periods", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1e4,
                        .meta = "LIST", DEST_LIST(periods, nperiods), .cmds = C(SPECTRUM),
                        .help = "oscillator periods, s, comma-separated, each > 0 (default: "
                                "PEER's 111 periods of the NGA-West2 flatfile, 0.01-20 s)"},
    /* each in (0, 1): critical damping (1) leaves no oscillation for a spectrum */
    [AQ_OPT_DAMPING] = {.name = "damping", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1, .hi_open = 1,
                        .meta = "LIST", DEST_LIST(dampings, ndampings),
                        .cmds = C(SPECTRUM),
                        .help = "damping ratios, comma-separated, each in (0, 1) (default "
                                "0.05)"},
    [AQ_OPT_TARGET] = {.name = "target", .kind = AQ_ARG_STRING, .meta = "SPEC", DEST(target),
                       .cmds = C(SELECT) | C(PLOT_SPECTRUM),
                       .help = "the target spectrum: ec8:KEY=VALUE,... with type=1|2, "
                               "ground=A..E, ag=G (a_gR in g) and optionally importance=GAMMA, "
                               "damping=ZETA (EN 1998-1:2004 3.2.2.2); asce7:sds=G,sd1=G,tl=S "
                               "and optionally ,mcer (ASCE/SEI 7-22, the design or MCE_R "
                               "spectrum); or a CSV file period_s,psa_g of your own "
                               "(docs/select.md)",
                       .required = C(SELECT)},
    [AQ_OPT_COUNT] = {.name = "count", .kind = AQ_ARG_SIZE, .lo = 1, .hi = 1000, .meta = "N",
                      DEST(count), .cmds = C(SELECT),
                      .help = "records (or --components pairs) in the suite, 1..1000",
                      .required = C(SELECT)},
    [AQ_OPT_SELECT_PERIODS] = {.name = "periods", .kind = AQ_ARG_CUSTOM, .meta = "T1,T2",
                               .fn = select_periods, .cmds = C(SELECT),
                               .help = "the period range, s, 0 < T1 < T2 (default: the range "
                                       "of the best-ranked spectral measure of --fragility, "
                                       "else 0.1,1; docs/select.md)"},
    [AQ_OPT_PERIOD_GRID] = {.name = "period-grid", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1e4,
                            .meta = "LIST", DEST_LIST(period_grid, nperiod_grid),
                            .cmds = C(SELECT),
                            .help = "the periods, s, at which the suite is matched and checked "
                                    "(those within the range; default: PEER's 111 periods "
                                    "within the range, and T1 and T2)"},
    [AQ_OPT_SCALE_RANGE] = {.name = "scale-range", .kind = AQ_ARG_CUSTOM, .meta = "LO,HI",
                            .fn = scale_range, .cmds = C(SELECT),
                            .help = "each record's scale factor within LO..HI, 0 < LO <= HI "
                                    "(default 0.25,4)"},
    [AQ_OPT_MAX_PER_EVENT] = {.name = "max-per-event", .kind = AQ_ARG_SIZE, .lo = 1,
                              .hi = 1000, .meta = "K", DEST(max_per_event), .cmds = C(SELECT),
                              .help = "at most K records of one event, where the files name "
                                      "their event (default: no limit)"},
    [AQ_OPT_BEST_EFFORT] = {.name = "best-effort", .kind = AQ_ARG_FLAG, DEST(best_effort),
                            .cmds = C(SELECT),
                            .help = "when no suite meets the conditions within the scale "
                                    "range, write the one closest to them anyway (its file "
                                    "says which fail; exit status 1)"},
    [AQ_OPT_FRAGILITY_IN] = {.name = "fragility", .kind = AQ_ARG_STRING, .meta = "FILE",
                             DEST(fragility_in), .cmds = C(SELECT),
                             .help = "capacity's --fragility fits: the period range is that of "
                                     "the arch's best-ranked spectral measure (Sa_avg T1..T2, "
                                     "or 0.2T..2T of Sa(T))",
                             .conflicts = OPTS(AQ_OPT_SELECT_PERIODS),
                             .why = "both give the period range"},
    [AQ_OPT_ARCH_FRAGILITY] = {.name = "fragility-arch", .kind = AQ_ARG_STRING, .meta = "NAME",
                               DEST(arch), .cmds = C(SELECT),
                               .help = "the arch of the --fragility file, by name (default: "
                                       "its only arch)",
                               .requires = OPTS(AQ_OPT_FRAGILITY_IN),
                               .why = "it names an arch of that file"},
    [AQ_OPT_SUITE] = {.name = "suite", .kind = AQ_ARG_STRING, .meta = "FILE", DEST(suite),
                      .cmds = SUITES,
                      .help = "the records of a suite file of select, each at its scale "
                              "(capacity: its scale 1)",
                      .conflicts = OPTS(AQ_OPT_SCALE_TO_PGA, AQ_OPT_SCALE_TO_LAMBDA0),
                      .why = "the suite gives each record its scale"},
    [AQ_OPT_HELP] = {.name = "help", .short_name = 'h', .kind = AQ_ARG_FLAG, .cmds = ALL_CMDS,
                     .help = "this text"},
    [AQ_OPT_VERSION] = {.name = "version", .kind = AQ_ARG_FLAG, .cmds = C(RUN),
                        .help = "the version, and nothing else"},

    [AQ_OPT_UNITS] = {.name = "units", .kind = AQ_ARG_CUSTOM, .meta = "U", .fn = units,
                      .cmds = READS, .group = AQ_GROUP_READING,
                      .help = "values of records that state no units are U: g, g/10, gal, "
                              "cm/s2, mm/s2, m/s2, nm/s2 or counts (divided by the "
                              "sensitivity the file states, e.g. SAC SCALE)",
                      .meta2 = "GLOB=U",
                      .help2 = "records whose path matches GLOB are read as U, even over "
                               "units the file states (reported), e.g. '*.SAC=counts' "
                               "(repeatable; the last matching rule wins)"},
    [AQ_OPT_READ_DT] = {.name = "dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                        .meta = "S", DEST(read.dt_s), .cmds = READS,
                        .group = AQ_GROUP_READING,
                        .help = "sample interval (s) of text records without time column"},
    [AQ_OPT_COLUMN] = {.name = "column", .kind = AQ_ARG_SIZE, .lo = 1, .hi = 64, .meta = "N",
                       DEST(read.column), .cmds = READS, .group = AQ_GROUP_READING,
                       .help = "column N (1-based) of a text record is the acceleration"},
    [AQ_OPT_COMPONENT] = {.name = "component", .kind = AQ_ARG_CUSTOM, .meta = "GLOB=CH",
                          .read_fn = aq_opt_component, .cmds = READS, .group = AQ_GROUP_READING,
                          .help = "channel CH of multi-channel files matching GLOB (or name "
                                  "one record as FILE#CH)"},
    [AQ_OPT_ACCEPT_IMPLAUSIBLE] = {.name = "accept-implausible", .kind = AQ_ARG_FLAG,
                                   DEST(read.accept_implausible), .cmds = READS,
                                   .group = AQ_GROUP_READING,
                                   .help = "keep records whose PGA is outside 1e-5..10 g"},
    [AQ_OPT_ACCEPT_VERTICAL] = {.name = "accept-vertical", .kind = AQ_ARG_FLAG,
                                DEST(read.accept_vertical), .cmds = READS,
                                .group = AQ_GROUP_READING,
                                .help = "run channels the file identifies as vertical"},
    [AQ_OPT_RESPONSE] = {.name = "response", .kind = AQ_ARG_CUSTOM, .meta = "FILE.xml",
                         .read_fn = aq_opt_response, .cmds = READS, .group = AQ_GROUP_READING,
                         .help = "StationXML giving the sensitivity of miniSEED records (a "
                                 "StationXML given as a RECORD does the same)"},

    [AQ_OPT_COMPONENTS] = {.name = "components", .kind = AQ_ARG_CUSTOM, .meta = "H1,H2[,V]",
                           .orient_fn = aq_opt_components,
                           .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                           .group = AQ_GROUP_ORIENTATION,
                           .help = "one ground motion from two orthogonal horizontal "
                                   "component records (and the vertical V); repeatable.  The "
                                   "arch feels a_x = a1 cos(theta - phi1) + a2 cos(theta - "
                                   "phi2).  The components must share dt and start time; the "
                                   "samples they share are run (spectrum: their RotD50, "
                                   "RotD100 and GeoMean)",
                           .check = orientation},
    [AQ_OPT_AZIMUTHS] = {.name = "azimuths", .kind = AQ_ARG_CUSTOM, .meta = "A1,A2",
                         .orient_fn = aq_opt_azimuths,
                         .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                         .group = AQ_GROUP_ORIENTATION,
                         .help = "azimuths phi1, phi2 (deg from north) of the preceding "
                                 "--components (default: from the files, e.g. PEER's GIL067 "
                                 "is 67 deg)"},
    [AQ_OPT_AZIMUTH] = {.name = "azimuth", .kind = AQ_ARG_CUSTOM, .meta = "DEG",
                        .orient_fn = aq_opt_azimuth,
                        .cmds = SUITES, .group = AQ_GROUP_ORIENTATION,
                        .help = "the arch's +x azimuth theta, deg from north (default 0)",
                        .requires = OPTS(AQ_OPT_COMPONENTS),
                        .why = "a plain RECORD is already the arch's in-plane component",
                        .meta2 = "all[:STEP]",
                        .help2 = "every theta 0, STEP, ... < 360 (default STEP 5); the TSV "
                                 "shows the worst azimuth per (motion, arch, scale): a failed "
                                 "run, else a collapse (the earliest), else the largest "
                                 "peak_rotation_over_qc; the HDF5 file has all"},
    [AQ_OPT_ALL_AZIMUTHS] = {.name = "all-azimuths", .kind = AQ_ARG_FLAG,
                             DEST(orient.all_azimuths), .cmds = C(RUN),
                             .group = AQ_GROUP_ORIENTATION,
                             .help = "with --azimuth all: every azimuth's row in the TSV"},
    [AQ_OPT_VERTICAL] = {.name = "vertical", .kind = AQ_ARG_FLAG, DEST(orient.vertical),
                         .cmds = SUITES, .group = AQ_GROUP_ORIENTATION,
                         .help = "run the vertical component V too (without it a V is "
                                 "ignored, with a warning); a step with g + a_v <= 0 stops "
                                 "the run: status run:eliftoff"},

    [AQ_OPT_DETREND] = {.name = "detrend", .kind = AQ_ARG_CHOICE, .choices = detrends,
                        .meta = "D", DEST(proc.detrend), .cmds = READS,
                        .group = AQ_GROUP_PROCESSING,
                        .help = "remove the least-squares line (linear, default), the mean "
                                "(mean) or nothing (none)"},
    [AQ_OPT_TAPER] = {.name = "taper", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 0.5,
                      .zero_is_off = 1, /* --taper 0: no taper, as --no-filter gives */
                      .meta = "FRAC", DEST(proc.taper_frac), .cmds = READS,
                      .group = AQ_GROUP_PROCESSING,
                      .help = "Hann taper over FRAC of the record at each end, 0-0.5 "
                              "(default 0: only the zero pads' junctions are tapered)"},
    [AQ_OPT_HIGHPASS] = {.name = "highpass", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                         .hi = AQ_OPT_FREQ_MAX_HZ, .meta = "HZ", DEST(proc.highpass_hz),
                         .fn = highpass_given, .cmds = READS, .group = AQ_GROUP_PROCESSING,
                         .help = "acausal Butterworth high-pass corner (default 0.03 Hz, or "
                                 "1/duration for a record shorter than 33.3 s)"},
    [AQ_OPT_ORDER] = {.name = "order", .kind = AQ_ARG_INT, .lo = 1, .hi = AQ_OPT_ORDER_MAX,
                      .meta = "N", DEST(proc.order), .cmds = READS,
                      .group = AQ_GROUP_PROCESSING,
                      .help = "Butterworth order, 1-20 (default 4)"},
    [AQ_OPT_LOWPASS] = {.name = "lowpass", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                        .hi = AQ_OPT_FREQ_MAX_HZ, .meta = "HZ", DEST(proc.lowpass_hz),
                        .cmds = READS, .group = AQ_GROUP_PROCESSING,
                        .help = "acausal Butterworth low-pass corner (default off)",
                        .check = lowpass_above_highpass},
    [AQ_OPT_IM_PERIODS] = {.name = "im-periods", .kind = AQ_ARG_CUSTOM, .meta = "LIST",
                           .fn = im_periods, .cmds = RECORDS, .group = AQ_GROUP_PROCESSING,
                           .help = "intensity measures Sa(T), 5 % damping, at these periods, "
                                   "s, comma-separated, at most 8, or none (default "
                                   "0.2,0.5,1 in info and capacity, none in the main job)"},
    [AQ_OPT_SA_AVG] = {.name = "sa-avg", .kind = AQ_ARG_CUSTOM, .meta = "T1,T2",
                       .fn = sa_avg, .cmds = RECORDS, .group = AQ_GROUP_PROCESSING,
                       .help = "intensity measure Sa_avg: the geometric mean of Sa at 10 "
                               "periods evenly spaced from T1 to T2 s (Eads et al. 2015), "
                               "or none (default 0.1,1 in info and capacity, none in the main job)"},
    [AQ_OPT_PEAKS] = {.name = "peaks", .kind = AQ_ARG_CHOICE,
                      .choices = aq_spectrum_peaks_names, .meta = "RULE", DEST(proc.peaks),
                      .cmds = READS, .group = AQ_GROUP_PROCESSING,
                      .help = "where each oscillator's peak is taken, for the spectra and "
                              "the spectral measures: peer (default: at the samples and at "
                              "N - 1 points between each two, N = ceil(10 dt / T), as PEER "
                              "computes the NGA-West2 spectra), exact (over continuous time, "
                              "the record linear between samples) or samples (at the samples "
                              "only); docs/spectrum.md"},
    [AQ_OPT_SAMPLED_PEAKS] = {.name = "sampled-peaks", .kind = AQ_ARG_FLAG,
                              DEST(sampled_peaks), .cmds = READS,
                              .group = AQ_GROUP_PROCESSING,
                              .help = "the same as --peaks samples",
                              .conflicts = OPTS(AQ_OPT_PEAKS),
                              .why = "it is --peaks samples",
                              .check = sampled_peaks_alias},
    [AQ_OPT_NO_FILTER] = {.name = "no-filter", .kind = AQ_ARG_FLAG_OFF, DEST(proc.filter),
                          .cmds = READS, .group = AQ_GROUP_PROCESSING,
                          .help = "no taper, pads or filter (detrend still applies; "
                                  "--taper 0, no taper, may be given with it)",
                          /* an option that sets one of them would be ignored: refused,
                           * even at its default, unless it asks for none (--taper 0:
                           * .zero_is_off) */
                          .conflicts = OPTS(AQ_OPT_TAPER, AQ_OPT_HIGHPASS, AQ_OPT_ORDER,
                                            AQ_OPT_LOWPASS),
                          .why = "it applies no taper, pads or filter"},
    [AQ_OPT_MERGE_TOL] = {.name = "merge-tol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 10,
                          .meta = "G", DEST(merge_tol_g), .cmds = SUITES,
                          .group = AQ_GROUP_PROCESSING,
                          .help = "merge consecutive samples differing by less than G (g) "
                                  "into one constant-acceleration step (default 0: none)"},
    [AQ_OPT_NO_CACHE] = {.name = "no-cache", .kind = AQ_ARG_FLAG, DEST(no_cache),
                         .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                         .help = "neither read nor store processed records, built arches "
                                 "and spectra in the cache (results are the same either way; "
                                 "docs/cache.md)"},
    [AQ_OPT_CACHE_DIR] = {.name = "cache-dir", .kind = AQ_ARG_STRING, .meta = "DIR",
                          DEST(cache_dir), .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                          .help = "keep processed records, built arches and spectra in DIR (made "
                                  "if its parent exists; one that cannot be used stops the "
                                  "command before anything runs; default "
                                  "$XDG_CACHE_HOME/archquake, else ~/.cache/archquake, "
                                  "which, if it cannot be used, is a note and the run goes "
                                  "on)",
                          .check = cache_dir_needs_cache},
    [AQ_OPT_CACHE_MAX] = {.name = "cache-max", .kind = AQ_ARG_CUSTOM, .meta = "SIZE",
                          .fn = cache_max, .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                          .help = "keep the cache directory under SIZE bytes, or K, M, G, T "
                                  "(1K = 1024), e.g. 2G (default 512M): a write that passes "
                                  "it removes other builds' entries, then the least "
                                  "recently used",
                          .conflicts = OPTS(AQ_OPT_NO_CACHE),
                          .why = "--no-cache uses no cache directory"},
};

static const char run_tail[] =
    "Output: TSV, one row per run (on a terminal: an aligned table with 6\n"
    "significant digits; pipe or redirect it, or use --text, for the TSV).\n"
    "Columns: record arch model scale pga_g status collapsed collapse_time_s\n"
    "  peak_rotation_rad peak_displacement_m max_kinetic_energy_j impacts\n"
    "  energy_in_j energy_dissipated_j  (status: ok, slides, beyond,\n"
    "  slides+beyond (below), or read:CODE, process:CODE,\n"
    "  arch:CODE, run:CODE; collapse_time_s is nan for an arch that survives;\n"
    "  then polarity (normal | reversed) lambda0_first (lambda0 of the set the\n"
    "  record drove first; nan if it never moved) peak_rotation_over_qc (the\n"
    "  largest |q| / q_c over both sets; 1 at collapse) pga_over_lambda0 (pga_g over\n"
    "  lambda0_first, or over the lower lambda0 if it never moved);\n"
    "  a run whose status is not ok has every result column nan, collapsed\n"
    "  included: no verdict; then azimuth_deg: the arch's azimuth for a\n"
    "  --components motion, nan for a RECORD; control: fixed or free, the\n"
    "  arch's hinge control, which its verdicts assume; then mu_demand (the\n"
    "  largest |T|/N at any joint over the run) mu_demand_joint (where)\n"
    "  thrust_ecc_max (the largest eccentricity of the thrust at a joint that\n"
    "  is not a hinge) thrust_ecc_time_s (when it first passed 1)\n"
    "  slide_time_s (when mu_demand first passed the friction given); when\n"
    "  the arch never moved, mu_demand is the least friction with which a\n"
    "  line of thrust stands at the record's peak and the thrust columns are\n"
    "  nan; status slides: a friction was given and\n"
    "  mu_demand passed it; beyond: free control, the thrust left a joint's\n"
    "  section; slides+beyond: both: the verdict holds for the four-hinge\n"
    "  model only up to that time, follow such a run with --model blocks);\n"
    "  last, with --model blocks: max_slip_m hinges_observed (the joints and\n"
    "  faces that opened, 0e,6i,...) hinges_first_s (when) mechanism_changed_s\n"
    "  (when the open joints left the arch's sets); nan and - otherwise;\n"
    "  then check_blocks check_collapsed check_collapse_time_s\n"
    "  check_peak_rotation_rad: with --check blocks, a marked run's verdict\n"
    "  under the block model (agrees, differs, failed) and its collapse and\n"
    "  peak, the block columns filled from it; - and nan for a run not checked;\n"
    "  last friction_work_j: the work the block model's joint friction took, J\n"
    "Exit status (the main job's; each command's --help gives its own):\n"
    "  0  every record read and every run done\n"
    "  1  some record or run failed, or a --check blocks re-run did (each\n"
    "     reported on stderr; the others ran)\n"
    "  2  bad or missing options, or an arch file that cannot be loaded:\n"
    "     nothing was run\n"
    "  3  an output file could not be written (no partial file is left; an\n"
    "     existing file of that name is untouched)\n"
    "  A run ended by SIGINT, SIGTERM, SIGHUP or SIGPIPE removes its\n"
    "  temporaries and ends with that signal.\n";

static const char plot_head[] =
    "usage: archquake plot FIGURE [INPUT] [OPTIONS] -o FILE\n"
    "Draw a figure with PLplot; the format is FILE's extension: .png, .svg or\n"
    ".pdf (cairo drivers).  No partial file is ever left under FILE.\n"
    "Figures:\n"
    "  history RESULTS.h5 [--run KEY]   one run of a results file written with\n"
    "        --history: ground acceleration (g) with +-lambda0 g, rotation (rad)\n"
    "        with +-q_c, kinetic and potential energy and the work put in (J);\n"
    "        impacts and collapse marked\n"
    "  arch --arch ARCH [--rotation RAD]   the arch to scale, its voussoirs and\n"
    "        both hinge sets; with --rotation the mechanism deformed at that\n"
    "        rotation of body 1\n"
    "  arch RESULTS.h5 --run KEY [--at LIST]   a run of --model blocks stored\n"
    "        with --history: every voussoir at those times over the arch\n"
    "  domain --arch ARCH [--ratios LIST] [--cor C]   the half-cycle collapse\n"
    "        domain: shortest collapsing pulse against a/(lambda0 g)\n"
    "  suite RESULTS.h5   record x arch map of the verdict (worst over scales\n"
    "        and polarities: collapse, or peak rotation / q_c)\n"
    "  capacity CAPACITY.h5 [--arch NAME] [--x qc|rad] [--y scale|pga] [--im IM]\n"
    "        a file of archquake capacity -o, one arch (default: the file's\n"
    "        first): a strip per record and polarity with the verdict at every\n"
    "        scanned scale (--y scale: the scale factor, the default; --y pga:\n"
    "        the PGA in g), shaded by the survived runs' peak rotation (--x qc:\n"
    "        over q_c, the default; --x rad), red and hatched where it\n"
    "        collapses, a tick at each change, its first collapse beside it\n"
    "        (R: it survives again above a collapse); below, the lognormal\n"
    "        fragility of IM (pga_g, pgv_m_s, pgd_m, arias_m_s, cav_m_s,\n"
    "        pga_lambda0, or a spectral measure the file's fits hold:\n"
    "        sa_0.2s_g, sa_avg_0.1_1s_g; default pga_g) over the empirical\n"
    "        fraction of first collapses, censored records at their cap, and\n"
    "        the band of the median's interval\n"
    "  spectrum SPECTRA.h5 [--record NAME]   a file of archquake spectrum -o:\n"
    "        pseudo-spectral acceleration (g) against period (s, log axis), one\n"
    "        curve per record, component and damping\n"
    "ARCH: an arch file (.cfg), or an installed arch by name (oppenheim).\n";

/* A figure of plot: its --help is plot's. */
#define FIGURE(n) {.name = "plot " n, .title = "plot " n, .help_cmd = "plot"}

const aq_opt_command aq_opt_commands[AQ_CMD_N] = {
    [AQ_CMD_RUN] =
        {.name = "",
         .farmed = 1,
         .title = "the main job",
         .help_cmd = "",
         .synopsis = "[OPTIONS] RECORD... --arch FILE",
         .summary = "run records against arches",
         .head = "usage: archquake [OPTIONS] RECORD... --arch FILE [--arch FILE ...]\n"
                 "       archquake [OPTIONS] --components H1,H2[,V] ... --arch FILE ...\n"
                 "Run every record against every arch (and every scale factor): each record\n"
                 "is read and processed once.  One TSV row per run on stdout.\n",
         .tail = run_tail},
    [AQ_CMD_INFO] =
        {.name = "info",
         .title = "info",
         .help_cmd = "info",
         .synopsis = "info [OPTIONS] RECORD...",
         .summary = "describe records",
         .head = "usage: archquake info [OPTIONS] RECORD...\n"
                 "Describe accelerograms: one TSV row per record on stdout.\n",
         .tail = "Columns: file format npts dt_s duration_s units pga_g pgv_m_s pgd_m\n"
                 "  arias_m_s d5_95_s cav_m_s channel vertical pgv_pga_s, then one column\n"
                 "  per --im-periods T, sa_Ts_g, and sa_avg_T1_T2s_g (--sa-avg) (npts,\n"
                 "  duration_s: the record as read; the measures: the processed record,\n"
                 "  pads included; --no-filter --detrend none gives the record as read)\n"
                 "Exit status: 0 all records read, 1 some record failed, 2 bad options.\n",
         .heading = {[AQ_GROUP_PROCESSING] = "Processing (intensity measures are computed "
                                             "on the processed record):"}},
    [AQ_CMD_MECHANISM] =
        {.name = "mechanism",
         .title = "mechanism",
         .help_cmd = "mechanism",
         .synopsis = "mechanism --arch FILE",
         .summary = "static analysis of an arch",
         .head = "usage: archquake mechanism --arch FILE [--table] [--points N]\n"
                 "The hinge sets of an arch: one TSV row per set: primary, reverse, and\n"
                 "minimum, the admissible set of lowest lambda0 over every joint (the\n"
                 "primary itself without [hinges]; with [hinges] a lower one is warned of\n"
                 "on stderr: it governs unless its joints are restrained).  An arch whose\n"
                 "minimum lambda0 is <= 0 cannot stand and is refused (exit 1), naming the set.\n",
         .tail = "Columns: set joints faces lambda0 q_c_rad admissible act_sign q_sign mass_kg\n"
                 "  impact_vel_ratio end table_n table_err thrust_ecc searched reason\n"
                 "  control mu_required mu_joint lambda_friction\n"
                 "  q_c_rad is the rotation of body 1 about H1 at collapse (magnitude;\n"
                 "  q = q_sign * s); act_sign is the sign of the ground acceleration along +x\n"
                 "  that drives the set; end is why the path ends (peak: lambda = 0, toggle,\n"
                 "  hinge: a hinge closes); table_err is the measured relative error of the\n"
                 "  interpolation tables against the exact kinematics; thrust_ecc is the\n"
                 "  largest eccentricity |r - R|/(t/2) of the line of thrust over the joints\n"
                 "  at q = 0 (<= 1: the thrust stays inside, lambda0 is also a lower bound).\n"
                 "  impact_vel_ratio is the set's velocity after an impact arriving from the\n"
                 "  other set over the velocity before (momentum rule); <= 0: the arch stops.\n"
                 "  control is the arch's hinges, fixed or free ([hinges] control).\n"
                 "  mu_required is the largest |T|/N (shear over normal force) over every\n"
                 "  joint in the set's collapse state at lambda0 (inf: the resultant pulls\n"
                 "  on some joint; nan: no collapse state), mu_joint that joint.\n"
                 "  lambda_friction, with a friction (--friction or [contact] friction;\n"
                 "  else nan), is the largest lambda of the set's direction at which a line\n"
                 "  of thrust lies inside the arch with |T| <= mu N at every joint: lambda0\n"
                 "  of that direction's minimum when mu >= its mu_required, less below.  An\n"
                 "  arch that needs more friction than given even at rest is refused (exit\n"
                 "  1), naming the joint.\n"
                 "Table columns: set s_rad q_rad lambda lambda_eq x_m y_m pe_j mgen_kgm2\n"
                 "  min_normal_n (lambda by virtual work and by the 9x9 equilibrium; pe_j =\n"
                 "  m_T g y; min_normal_n the smallest compressive hinge force; thrust_ecc\n"
                 "  as above, in the deformed arch at lambda(q)).\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded (the arch\n"
                 "is mechanism's input, as a record is info's), 2 bad options.\n"},
    [AQ_CMD_PULSE] =
        {.name = "pulse",
         .title = "pulse",
         .help_cmd = "pulse",
         .synopsis = "pulse --arch FILE --accel-g A --duration S",
         .summary = "one pulse",
         .head = "usage: archquake pulse --arch FILE --accel-g A --duration S [OPTIONS]\n"
                 "A rectangular ground-acceleration pulse of A g (signed along +x) from\n"
                 "t = 0 for S seconds, then zero; prints one TSV row (header + row).\n",
         .tail = "Columns: model accel_g duration_s end_s collapsed collapse_time_s\n"
                 "  peak_rotation_rad peak_displacement_m max_kinetic_energy_j impacts\n"
                 "  reversals energy_in_j energy_dissipated_j steps_moving evals\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded, or the run\n"
                 "failed, 2 bad options (or an option the arch makes ineffective, as --cor\n"
                 "with impact momentum), 3 the history could not be written.\n"},
    [AQ_CMD_DOMAIN] =
        {.name = "domain",
         .title = "domain",
         .help_cmd = "domain",
         .synopsis = "domain --arch FILE",
         .summary = "half-cycle collapse domain",
         .head = "usage: archquake domain --arch FILE [OPTIONS]\n"
                 "Half-cycle collapse domain: for each ratio r, the shortest rectangular\n"
                 "pulse of r lambda0 g (direction opening the primary set) that collapses\n"
                 "the arch, by bisection (the direction is the set's own, so domain takes no\n"
                 "--polarity).\n",
         .tail = "Columns: ratio accel_g min_duration_s (inf: no collapse up to\n"
                 "  --max-duration)\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded, or a run\n"
                 "failed, 2 bad options (or an option the arch makes ineffective, as --cor\n"
                 "with impact momentum).\n"},
    [AQ_CMD_COMPARE] =
        {.name = "compare",
         .title = "compare",
         .help_cmd = "compare",
         .synopsis = "compare A.h5 B.h5",
         .summary = "regression check",
         .head = "usage: archquake compare A.h5 B.h5 [--rtol R] [--atol A] [--ignore NAME]...\n"
                 "Compare two results files (archquake ... -o FILE.h5).  First their\n"
                 "configuration: processing options, model, cor, version (shown only), and\n"
                 "the content (sha256) of records and arches of one name.  Then run by run,\n"
                 "matched by identity: the record's content, the arch's name and .cfg\n"
                 "content, the scale and the polarity (however the files were spelt on the\n"
                 "command line).  Numbers agree when |a-b| <= A + R*max(|a|,|b|) (NaN equals\n"
                 "NaN); collapsed, impacts, model and status must be equal.\n",
         .tail = "Each difference is a TSV row on stdout: record arch scale polarity field a b\n"
                 "rel_diff.  Configuration rows come first, with * for what they are not\n"
                 "about (field = the setting, record_sha256 or arch_sha256); field \"present\"\n"
                 "marks a run found in only one file.  Records are named by file name.  A file\n"
                 "of the first format (no hashes) is read too: records and arches then match\n"
                 "by name.\n"
                 "Exit status: 0 all runs and settings agree (a different version alone is\n"
                 "shown but agrees), 1 some differ, 2 bad options or a file that cannot be\n"
                 "read as a results file.\n"},
    [AQ_CMD_CAPACITY] =
        {.name = "capacity",
         .farmed = 1,
         .title = "capacity",
         .help_cmd = "capacity",
         .synopsis = "capacity RECORD... --arch FILE",
         .summary = "collapse scales, fragility",
         .head = "usage: archquake capacity RECORD|--components H1,H2[,V]... --arch FILE "
                 "[--arch FILE ...] [OPTIONS]\n"
                 "For each record, arch and polarity, every scale factor at which the arch's\n"
                 "verdict (collapse or not) changes, from the scale at which it first moves\n"
                 "to --scale-max (docs/capacity.md).  One TSV row per (record, arch,\n"
                 "polarity) on stdout.\n",
         .tail = "Columns: record arch polarity status move_scale first_collapse_scale\n"
                 "  first_collapse_pga_g first_collapse_pgv_m_s collapse_intervals\n"
                 "  resurrection runs scale_max, with --components also azimuth_deg\n"
                 "  first_collapse_scale_min first_collapse_scale_max (the range over the\n"
                 "  azimuths where it collapses)  (status: ok, never_moves, read:CODE,\n"
                 "  process:CODE, arch:CODE, run:CODE; intervals lo-hi;lo-hi, hi inf when\n"
                 "  collapse holds at the cap)\n"
                 "Exit status: 0 all done, 1 some record or run failed (reported; the others\n"
                 "ran), 2 bad options or an arch file that cannot be loaded (nothing ran),\n"
                 "3 an output could not be written.\n",
         .heading = {[AQ_GROUP_ORIENTATION] =
                         "Orientation (--azimuth all: each row is the worst azimuth, lowest\n"
                         "first_collapse_scale, no collapse last, with the range over the\n"
                         "azimuths; --azimuth DEG gives one azimuth's; -o and --fragility\n"
                         "take plain RECORDs only):"}},
    [AQ_CMD_SPECTRUM] =
        {.name = "spectrum",
         .title = "spectrum",
         .help_cmd = "spectrum",
         .synopsis = "spectrum RECORD...",
         .summary = "response spectra, RotD50/RotD100",
         .head = "usage: archquake spectrum RECORD|--components H1,H2 ... [--periods LIST]\n"
                 "       [--damping LIST] [-o FILE.h5] [OPTIONS]\n"
                 "Elastic response spectra (pseudo-spectral acceleration, 5 % damping by\n"
                 "default) of processed records: for a RECORD its own, for two horizontal\n"
                 "components their RotD50, RotD100 (Boore 2010, 180 angles) and geometric\n"
                 "mean (docs/spectrum.md).  --no-filter --detrend none: the records as\n"
                 "read.  One TSV row per (record, component, damping, period) on stdout.\n",
         .tail = "Columns: record component damping period_s psa_g sd_m psv_m_s\n"
                 "  (component: the record's channel, or RotD50, RotD100, GeoMean for a\n"
                 "  pair; sd_m = PSA / omega^2, psv_m_s = PSA / omega).  Periods below 2 dt\n"
                 "  lie above a record's Nyquist frequency: they are computed for the\n"
                 "  record as linear between samples (PSA -> PGA as T -> 0), with a warning.\n"
                 "Exit status: 0 success; 1 a record could not be read or processed, or a\n"
                 "pair does not fit (each said in one line; nothing is written); 2 bad\n"
                 "options; 3 the output file could not be written.\n"},
    [AQ_CMD_SELECT] =
        {.name = "select",
         .title = "select",
         .help_cmd = "select",
         .synopsis = "select POOL... --target SPEC --count N",
         .summary = "choose and scale a suite to a target spectrum",
         .head = "usage: archquake select POOL... --target SPEC --count N [--periods T1,T2]\n"
                 "       [--scale-range LO,HI] [--max-per-event K] [--components H1,H2 ...]\n"
                 "       [--text SUITE.tsv] [-o SUITE.h5] [OPTIONS]\n"
                 "Choose N records of the pool (records, directories of records, or quoted\n"
                 "globs; or pairs with --components), each scaled to bring its spectrum\n"
                 "closest to the target in the log over the period range, whose mean\n"
                 "spectrum has the least misfit to the target and meets the code's\n"
                 "conditions: the mean nowhere below 90 % of the target over the range, for\n"
                 "Eurocode 8 the mean PGA at least a_g S, at most K records of one event.  A\n"
                 "suite that falls short is raised by one common factor within the scale\n"
                 "range.  Every suite is tried when the combinations are at most 2e6, else\n"
                 "greedy selection then swaps (Jayaram, Lin & Baker 2011) (docs/select.md).\n"
                 "The suite file (TSV: comment lines, then record channel scale misfit\n"
                 "event) goes to stdout or --text; the main job and capacity run it with\n"
                 "--suite.\n",
         .tail = "Exit status: 0 a suite that meets every condition was written; 1 some\n"
                 "pool member could not be used (each named; the suite is chosen from the\n"
                 "others), fewer than N usable, or no suite meets the conditions (how far\n"
                 "the best falls short, and where, is said; nothing is written unless\n"
                 "--best-effort); 2 bad options, target or range, or a pool of fewer than N\n"
                 "records; 3 an output could not be written (no partial file is left).\n",
         .heading = {[AQ_GROUP_PROCESSING] = "Processing (the pool is processed as the main "
                                             "job processes records):"}},
    [AQ_CMD_PLOT] = {.name = "plot",
                     .title = "plot",
                     .help_cmd = "plot",
         .synopsis = "plot FIGURE ... -o FILE",
         .summary = "figures (history arch domain suite capacity spectrum)",
                     .head = plot_head,
                     .tail = "Exit status: 0 drawn, 1 an input could not be read or drawn (a\n"
                             "results file, or an arch file that cannot be loaded), 2 bad\n"
                             "options, 3 the figure or the data could not be written.\n",
                     .heading = {[AQ_GROUP_MAIN] = "Options:"}},
    [AQ_CMD_HELP] =
        {.name = "help",
         .title = "help",
         .help_cmd = "help",
         .synopsis = "help [COMMAND|arch-file]",
         .summary = "a command's --help; the arch file's keys",
         .head = "usage: archquake help [COMMAND|arch-file]\n"
                 "Print COMMAND's --help (archquake COMMAND --help); without a COMMAND,\n"
                 "archquake --help; with arch-file, the arch file's sections and keys\n"
                 "(units, ranges, defaults), shapes, joints and faces files.\n",
         .tail = "Exit status: 0 printed, 2 an unknown COMMAND or bad options.\n",
         .heading = {[AQ_GROUP_MAIN] = "Options:"}},
    [AQ_CMD_PLOT_HISTORY] = FIGURE("history"),
    [AQ_CMD_PLOT_ARCH] = FIGURE("arch"),
    [AQ_CMD_PLOT_DOMAIN] = FIGURE("domain"),
    [AQ_CMD_PLOT_SUITE] = FIGURE("suite"),
    [AQ_CMD_PLOT_CAPACITY] = FIGURE("capacity"),
    [AQ_CMD_PLOT_SPECTRUM] = FIGURE("spectrum"),
    [AQ_CMD_REPORT] =
        {.name = "report",
         .title = "report",
         .help_cmd = "report",
         .synopsis = "report FILE.h5 ... -o F.html",
         .summary = "one HTML page to hand on",
         .head = "usage: archquake report FILE.h5 ... -o REPORT.html\n"
                 "One self-contained HTML page of a screening, to hand on: per arch its\n"
                 "verdict table (sortable, filterable by verdict) and figures (the arch\n"
                 "and its hinge sets, the suite's verdict map, the history of each\n"
                 "collapsed run and of the strongest surviving one when the results hold\n"
                 "histories), the capacity files' first collapses, collapse intervals,\n"
                 "fragility curves and the ranking of the intensity measures, the failed\n"
                 "records with their reasons, and the run: command line, build, date,\n"
                 "options, every record and every arch.  Figures are inline SVG, text as\n"
                 "text; nothing is fetched; it prints on A4 and Letter (docs/report.md).\n"
                 "Each FILE.h5 in its section, whatever their order: at most one\n"
                 "results file of the main job (archquake ... -o), and any files of\n"
                 "archquake capacity -o, select -o (its suite: the target, checks,\n"
                 "spectra, records) and spectrum -o (its spectra: a figure and a table);\n"
                 "without a results file, the run is the first file's.\n",
         .tail = "Exit status: 0 written, 1 an input could not be read, 2 bad options,\n"
                 "3 the page could not be written.  No partial file is left under FILE.\n",
         .heading = {[AQ_GROUP_MAIN] = "Options:"}},
};

const aq_opt_note aq_opt_environment[] = {
    {"XDG_CACHE_HOME", "the cache of processed records and built arches, and FFTW's wisdom, "
                       "are kept in $XDG_CACHE_HOME/archquake (an absolute path; "
                       "docs/cache.md)"},
    {"HOME", "without XDG_CACHE_HOME, the cache is ~/.cache/archquake; with neither "
             "there is none"},
    {"ARCHQUAKE_DATADIR", "--arch NAME looks for NAME.cfg in $ARCHQUAKE_DATADIR/arches "
                          "first (Arches, above)"},
    {"LC_PAPER", "plot: the page of a PDF without --paper, Letter or A4 (the locale's, as "
                 "LC_ALL, LC_PAPER and LANG set it)"},
    {NULL, NULL}};

const aq_opt_note aq_opt_files[] = {
    {"~/.cache/archquake/records/, arches/",
     "the cache (or under $XDG_CACHE_HOME/archquake, or --cache-dir): one entry per "
     "processed record and per built arch, for later runs of the same build; at most "
     "--cache-max (default 512M); removing it loses nothing but time"},
    {"~/.cache/archquake/fftw-wisdom", "FFTW's plans for record lengths the built-in "
                                       "wisdom lacks"},
    {"FILE.h5.journal", "beside a results file being written with -o: the records done, "
                        "until the file is complete (--resume reads it)"},
    {NULL, NULL}};

void aq_opts_init(aq_opts *o, aq_cmd cmd)
{
  memset(o, 0, sizeof *o);
  aq_signal_opts_default(&o->proc);
  aq_opt_orient_init(&o->orient);
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  o->threads = ncpu >= 1 ? (ncpu > AQ_MAX_THREADS ? AQ_MAX_THREADS : ncpu) : 1;
  o->model = AQ_MODEL_WORKPATH;
  o->cor = NAN;
  o->friction = NAN;
  o->blocks_dt_s = AQ_BLOCKS_DT_DEFAULT_S;
  o->cmd = (int)cmd;
  o->impact = -1;
  o->ode_rtol = 1e-10;
  o->polarity = AQ_POLARITY_AUTO; /* aq_opt_polarity_resolve, once the arches are loaded */
  if (cmd == AQ_CMD_RUN) { /* the main job: spectral measures only when named; their
                              13 periods over the padded records cost more than
                              everything else it does (docs/spectrum.md) */
    o->proc.im_nsa = 0;
    o->proc.sa_avg_lo_s = o->proc.sa_avg_hi_s = 0;
  }
  o->scale_to_pga_g = NAN;
  o->scale_max = NAN;
  o->resolution = AQ_SCAN_RESOLUTION_DEFAULT;
  o->scan_tol = AQ_SCAN_TOL_DEFAULT;
  o->points = 101;
  o->accel_g = o->duration_s = o->end_s = o->max_end_s = NAN;
  o->pulse_dt_s = 0.01;
  o->domain_tol_s = 1e-9;
  o->max_duration_s = 100;
  o->paper = -1;
  o->check_blocks = -1;
  o->rtol = AQ_COMPARE_RTOL_DEFAULT;
  o->range_s[0] = o->range_s[1] = NAN;
  o->scale_range[0] = AQ_SELECT_SCALE_LO_DEFAULT;
  o->scale_range[1] = AQ_SELECT_SCALE_HI_DEFAULT;
  o->atol = AQ_COMPARE_ATOL_DEFAULT;
}

void aq_opts_free(aq_opts *o)
{
  free(o->arches);
  free(o->scales);
  free(o->ratios);
  free(o->at_s);
  free(o->periods);
  free(o->dampings);
  free(o->period_grid);
  o->period_grid = NULL;
  o->nperiod_grid = 0;
  o->periods = o->dampings = NULL;
  o->nperiods = o->ndampings = 0;
  aq_opt_orient_free(&o->orient);
  o->arches = NULL;
  o->scales = o->ratios = NULL;
  o->narches = o->nscale = o->nratios = 0;
}

int aq_opt_applies(aq_opt_id id, aq_cmd cmd)
{
  return (unsigned)id < AQ_OPT_N && (unsigned)cmd < AQ_CMD_N &&
         (aq_opt_rows[id].cmds >> cmd & 1u);
}
