/* opt.c: checked option values (see opt.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt.h"

#include "../arch/arch.h"
#include "../blocks/blocks.h"
#include "../io/number.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int parse_double(const char *s, double *x)
{
  if (!s || !*s)
    return 0;
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end || errno == ERANGE || !isfinite(v))
    return 0;
  *x = v;
  return 1;
}

void aq_opt_double(const char *opt, const char *arg, double lo, double hi,
                   double *out, int *nerr)
{
  double v;
  if (!parse_double(arg, &v) || v < lo || v > hi) {
    fprintf(stderr, "archquake: %s: expected a number in [%g, %g], got \"%s\"\n",
            opt, lo, hi, arg ? arg : "");
    (*nerr)++;
    return;
  }
  *out = v;
}

void aq_opt_double_gt(const char *opt, const char *arg, double lo, double hi,
                      double *out, int *nerr)
{
  double v;
  if (!parse_double(arg, &v) || !(v > lo) || v > hi) {
    fprintf(stderr, "archquake: %s: expected a number in (%g, %g], got \"%s\"\n",
            opt, lo, hi, arg ? arg : "");
    (*nerr)++;
    return;
  }
  *out = v;
}

void aq_opt_long(const char *opt, const char *arg, long lo, long hi, long *out,
                 int *nerr)
{
  char *end;
  errno = 0;
  long v = arg && *arg ? strtol(arg, &end, 10) : 0;
  if (!arg || !*arg || *end || errno == ERANGE || v < lo || v > hi) {
    fprintf(stderr, "archquake: %s: expected an integer in [%ld, %ld], got \"%s\"\n",
            opt, lo, hi, arg ? arg : "");
    (*nerr)++;
    return;
  }
  *out = v;
}

void aq_opt_list(const char *opt, const char *arg, double lo, double hi, double **out,
                 size_t *n, int *nerr)
{
  aq_opt_list_range(opt, arg, lo, hi, 0, out, n, nerr);
}

void aq_opt_list_range(const char *opt, const char *arg, double lo, double hi, int hi_open,
                       double **out, size_t *n, int *nerr)
{
  size_t cap = 1;
  for (const char *p = arg ? arg : ""; *p; p++)
    cap += *p == ',';
  double *v = malloc(cap * sizeof *v);
  char *copy = arg ? strdup(arg) : NULL;
  size_t k = 0;
  int bad = !v || !copy || !*arg;
  if (!bad) {
    char *save = NULL;
    for (char *tok = strtok_r(copy, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
      double x;
      if (!parse_double(tok, &x) || !(x > lo) || x > hi || (hi_open && x == hi)) {
        bad = 1;
        break;
      }
      v[k++] = x;
    }
    bad = bad || k == 0 || k != cap; /* no empty items ("1,,2", "1,") */
  }
  free(copy);
  if (bad) {
    free(v);
    if (isinf(hi))
      fprintf(stderr,
              "archquake: %s: expected a comma-separated list of numbers > %g, "
              "got \"%s\"\n",
              opt, lo, arg ? arg : "");
    else
      fprintf(stderr,
              "archquake: %s: expected a comma-separated list of numbers in (%g, %g%c, "
              "got \"%s\"\n",
              opt, lo, hi, hi_open ? ')' : ']', arg ? arg : "");
    (*nerr)++;
    return;
  }
  /* one value, one run: a repeated value would give two rows alike */
  for (size_t i = 0; i < k; i++)
    for (size_t j = i + 1; j < k; j++)
      if (v[i] == v[j]) {
        fprintf(stderr, "archquake: %s: expected distinct values, got %g twice in \"%s\"\n",
                opt, v[i], arg);
        (*nerr)++;
        free(v);
        return;
      }
  free(*out);
  *out = v;
  *n = k;
}

const char *const aq_opt_polarity_names[] = {"normal", "reversed", "both", NULL};

/* 1 if each of the n azimuths has its opposite (plus 180 deg, to 1e-9 deg)
 * among them. */
static int half_turns_present(const double *az, size_t n)
{
  for (size_t i = 0; i < n; i++) {
    int found = 0;
    for (size_t j = 0; j < n && !found; j++) {
      double d = fmod(az[j] - az[i] - 180, 360);
      found = fabs(d) < 1e-9 || fabs(fabs(d) - 360) < 1e-9;
    }
    if (!found)
      return 0;
  }
  return n > 0;
}

int aq_opt_polarity_resolve(int pol, aq_arch *const *arches, size_t n, int all_motions,
                            const double *az, size_t naz)
{
  if (pol != AQ_POLARITY_AUTO)
    return pol;
  if (all_motions && half_turns_present(az, naz))
    return AQ_POLARITY_NORMAL;
  for (size_t a = 0; a < n; a++)
    if (!arches[a] || !aq_arch_one_polarity(arches[a]))
      return AQ_POLARITY_BOTH;
  return AQ_POLARITY_NORMAL;
}

void aq_opt_ode_rtol(int given, const char *model, int *nerr)
{
  if (given && strcmp(model, "ode") != 0) {
    fprintf(stderr, "archquake: --ode-rtol: expected --model ode as well (the tolerance "
                    "has no effect on other models), got --model %s\n", model);
    (*nerr)++;
  }
}

int aq_opt_cor_momentum(const char *arch_path, int cor_given, int momentum)
{
  if (!cor_given || !momentum)
    return 0;
  fprintf(stderr, "archquake: %s: --cor: expected an arch whose impacts follow a cor, "
                  "got impact = momentum (its velocity ratio comes from the geometry, a "
                  "cor would have no effect)\n", arch_path);
  return 1;
}

int aq_opt_blocks_friction(const char *arch_path, int blocks, double friction)
{
  if (!blocks || !isnan(friction))
    return 0;
  fprintf(stderr, "archquake: %s: friction: expected a Coulomb coefficient for the block "
                  "model (--model blocks, --check blocks: [contact] friction or --friction), "
                  "got none\n", arch_path);
  return 1;
}

int aq_opt_blocks_spread(const char *arch_path, int blocks, const aq_arch *arch)
{
  aq_error e;
  aq_error_clear(&e);
  if (!blocks || aq_blocks_check_spread(arch, aq_arch_spread(arch), &e) == AQ_OK)
    return 0;
  snprintf(e.input, sizeof e.input, "%s", arch_path);
  aq_error_print(&e, stderr);
  return 1;
}

int aq_opt_spread_four_hinge(const char *arch_path, int four_hinge, double spread_m)
{
  if (!four_hinge || !(spread_m > 0))
    return 0;
  char num[64];
  aq_number_format(num, sizeof num, spread_m);
  fprintf(stderr, "archquake: %s: warning: spread_m: the supports' spread of %s m is the block "
                  "model's (--model blocks); the four-hinge model runs the arch with its "
                  "supports where the file draws them\n", arch_path, num);
  return 1;
}

int aq_opt_friction_paper(const char *arch_path, int paper, double friction, int still_runs)
{
  if (!paper || isnan(friction))
    return 0;
  char num[64];
  aq_number_format(num, sizeof num, friction);
  fprintf(stderr, "archquake: %s: warning: friction: %s marks %s under --model paper (its fits "
                  "carry no joint forces: mu_demand is nan once the arch moves); --model "
                  "workpath marks every run\n",
          arch_path, num,
          still_runs ? "only the runs in which the arch never moves" : "no run");
  return 1;
}

int aq_opt_same_file(const char *a, const char *b)
{
  struct stat sa, sb;
  if (strcmp(a, b) == 0)
    return 1;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

/* Each path stat'ed once (stat per pair cost 0.2 s at the start of a
 * 200-record suite); paths that cannot be stat'ed compare by name. */
void aq_opt_distinct_files(const char *what, char *const *paths, size_t n, int *nerr)
{
  struct stat *sb = malloc((n ? n : 1) * sizeof *sb);
  unsigned char *ok = malloc(n ? n : 1);
  for (size_t i = 0; sb && ok && i < n; i++)
    ok[i] = stat(paths[i], &sb[i]) == 0;
  for (size_t j = 1; j < n; j++)
    for (size_t i = 0; i < j; i++)
      if (sb && ok ? (ok[i] && ok[j] ? sb[i].st_dev == sb[j].st_dev &&
                                           sb[i].st_ino == sb[j].st_ino
                                     : strcmp(paths[i], paths[j]) == 0)
                   : aq_opt_same_file(paths[i], paths[j])) {
        if (strcmp(paths[i], paths[j]) == 0)
          fprintf(stderr, "archquake: %s: expected each %s once, got it twice\n", paths[j],
                  what);
        else
          fprintf(stderr, "archquake: %s: expected each %s once, got the same file as %s\n",
                  paths[j], what, paths[i]);
        (*nerr)++;
        break;
      }
  free(sb);
  free(ok);
}

void aq_opt_choice(const char *opt, const char *arg, const char *const *choices,
                   int *out, int *nerr)
{
  for (int i = 0; choices[i]; i++)
    if (arg && strcmp(arg, choices[i]) == 0) {
      *out = i;
      return;
    }
  char list[256] = "";
  size_t k = 0;
  for (int i = 0; choices[i] && k < sizeof list; i++) {
    int w = snprintf(list + k, sizeof list - k, "%s%s", i ? "|" : "", choices[i]);
    if (w > 0)
      k += (size_t)w;
  }
  fprintf(stderr, "archquake: %s: expected one of %s, got \"%s\"\n", opt, list,
          arg ? arg : "");
  (*nerr)++;
}

/* The word behind an unknown option, if it begins with '-' and names an
 * existing file (the user meant to read it): a short option ch comes from
 * argv[optind_after] (inside a cluster) or argv[optind_after - 1] (its last
 * character); a long one (ch 0 or an id >= 128) from argv[optind_after - 1]. */
static const char *dash_file(char **argv, int optind_after, int ch)
{
  struct stat sb;
  int shortopt = ch > 0 && ch < 128;
  for (int k = optind_after - 1; k <= optind_after && argv; k++) {
    if (k < 1 || (k == optind_after && !shortopt))
      continue;
    const char *w = argv[k];
    if (!w || w[0] != '-' || w[1] == '\0' || strcmp(w, "--") == 0)
      continue;
    if (shortopt && (w[1] == '-' || !strchr(w + 1, ch)))
      continue;
    if (stat(w, &sb) == 0 && !S_ISDIR(sb.st_mode))
      return w;
  }
  return NULL;
}

int aq_opt_dash_file(const char *cmd, char **argv, int optind_after, int optopt_,
                     int *nerr)
{
  static const char *last_file; /* one line per such word, not per letter */
  const char *sep = cmd[0] ? " " : "";
  const char *file = dash_file(argv, optind_after, optopt_);
  if (!file)
    return 0;
  if (file != last_file) {
    fprintf(stderr,
            "archquake: %s: expected an option, got a file whose name "
            "begins with '-': put it after '--' (archquake %s%s[OPTIONS] -- "
            "%s) or write it as ./%s\n",
            file, cmd, sep, file, file);
    (*nerr)++;
  }
  last_file = file;
  return 1;
}

void aq_opt_unknown(const char *cmd, char **argv, int optind_after, int optopt_,
                    int *nerr)
{
  const char *sep = cmd[0] ? " " : ""; /* "archquake --help", "archquake plot --help" */
  if (aq_opt_dash_file(cmd, argv, optind_after, optopt_, nerr))
    return;
  /* A short option (optopt_ a character) is named by itself: in a cluster
   * such as -ab, argv[optind_after - 1] may be another word (the previous
   * one, or an operand getopt has moved there).  A long option has no
   * optopt_ (or an id >= 128) and is the word getopt just passed. */
  if (optopt_ > 0 && optopt_ < 128)
    fprintf(stderr,
            "archquake: -%c: unknown option or missing value (see 'archquake %s%s--help')\n",
            optopt_, cmd, sep);
  else
    fprintf(stderr,
            "archquake: %s: unknown option or missing value (see 'archquake %s%s--help')\n",
            optind_after > 0 ? argv[optind_after - 1] : "?", cmd, sep);
  (*nerr)++;
}

void aq_opt_no_operands(const char *cmd, int argc, char **argv, int optind_,
                        int *nerr)
{
  if (optind_ < argc) {
    fprintf(stderr, "archquake: %s: expected no operands, got \"%s\"\n", cmd,
            argv[optind_]);
    (*nerr)++;
  }
}

int aq_opt_output_special(const char *opt, const char *path)
{
  struct stat sb;
  if (!path || stat(path, &sb) != 0 || S_ISREG(sb.st_mode) || S_ISDIR(sb.st_mode))
    return 0;
  fprintf(stderr, "archquake: %s: %s: expected a regular file or a new file name, "
                  "got a %s (it would be replaced)\n", path, opt,
          S_ISCHR(sb.st_mode) || S_ISBLK(sb.st_mode) ? "device"
          : S_ISFIFO(sb.st_mode)                     ? "FIFO"
                                                     : "special file");
  return 1;
}

/* An output path that names an existing input (a record or an arch file,
 * possibly under another spelling) would destroy it: report it (one line)
 * and return 1. */
int aq_opt_output_is_input(const char *opt, const char *out, char *const *records,
                           size_t nrec, char *const *arches, size_t narch)
{
  struct stat so, si;
  if (!out || stat(out, &so) != 0 || !S_ISREG(so.st_mode))
    return 0;
  for (size_t i = 0; i < nrec + narch; i++) {
    const char *in = i < nrec ? records[i] : arches[i - nrec];
    if (stat(in, &si) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino) {
      fprintf(stderr, "archquake: %s: %s: expected a file other than the inputs, "
                      "got the %s %s\n", out, opt, i < nrec ? "record" : "arch file", in);
      return 1;
    }
  }
  return 0;
}
