/* bench_capacity.c: the cost of `archquake capacity` (make bench; never in
 * make check).
 *
 * 1. Runs and time per (record, arch, polarity) for three pairs with
 *    resurrection or a plain collapse, side by side in one process:
 *    - capacity: scan at ratio 1 + r (r = 0.01) and bisection to tol 1e-6;
 *    - the brute force the tests use: scan at r / 10, then bisection;
 *    - a brute-force scan that reaches tol without bisection (a step of tol:
 *      its runs are counted, its time is runs x capacity's time per run);
 *    - the share of capacity's runs spent on the scan (what the guarantee
 *      at resolution r costs) and on the bisections;
 *    - a hunt by doubling then fill (resolution 1: Vamvatsikos & Cornell's
 *      steps of a factor 2), its runs and the first collapse it finds.
 *    Times are medians of REPS repetitions, and the first of them (first_s:
 *    the pair's first search in the process).
 * 2. The suite: the 11 AT2 records of tests/data/records x the 5 shipped
 *    arches x both polarities with the binary at -j 2 (wall time of one
 *    process, so cold: start, FFTW plans and arches included), the
 *    pairs with resurrection, runs per pair, and the fragility table.
 * 3. The models: the same suite under the default model and under
 *    --model ode, one process each, one after the other: wall and CPU time
 *    (user + system of the child processes), the ratio ode / default, and
 *    how far the two agree (rows with the same status, first collapse
 *    scales equal as printed or within 1e-5 relative, the largest relative
 *    difference, runs of each).  `bench_capacity models` runs it alone.
 * 5. The marks (docs/capacity.md, "Marks"): the suite of section 3 without
 *    a friction and with --friction 0.6, in turn, MARK_REPS times each: CPU
 *    medians, their ratio, and the rows of each status (search has free
 *    hinges, so its runs are followed in both).  `bench_capacity marks`
 *    runs it alone.
 * 4. `bench_capacity ab BIN_A BIN_B [N]` (alone, not in make bench): the
 *    suite of 3 under the default model with two programs, e.g. main's and
 *    a branch's, N times each (default 3) in turn: CPU medians, their ratio,
 *    and whether the tables are byte-identical. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* getloadavg */
#include <sys/resource.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "bench.h"
#include "capacity/capacity.h"
#include "io/record.h"
#include "job/job.h"
#include "signal/signal.h"

#define REPS 3

typedef struct {
  const char *record, *arch;
  double cor; /* NAN: the arch's own */
} pair;

static const pair pairs[] = {
    {"tests/data/records/RSN77_SFERN_PUL164-hor1.AT2", "arches/oppenheim.cfg", 0.5},
    {"tests/data/records/RSN77_SFERN_PUL164-hor1.AT2", "arches/oppenheim.cfg", NAN},
    {"tests/data/records/IELC180.AT2", "arches/thin.cfg", NAN},
};

/* The pair's record as the capacity command prepares it (job/subject.h):
 * read, processed, viewed at factor 1. */
static int load(const pair *p, aq_subject *subj, aq_view *view, aq_arch **arch)
{
  aq_error e;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  aq_signal_ws *ws = aq_signal_ws_alloc();
  aq_subject_src src = {{p->record, NULL, NULL}, {NAN, NAN}, p->record};
  aq_subject_opts o = {.read = &ro, .proc = &so}; /* the rest 0 or NULL: no cache */
  int ok = ws && aq_subject_prepare(subj, &src, &o, ws, &e) == AQ_OK &&
           aq_view_make(view, subj, 0, &e) == AQ_OK &&
           aq_arch_load(p->arch, arch, &e) == AQ_OK;
  aq_signal_ws_free(ws);
  if (!ok)
    aq_error_print(&e, stderr);
  return ok ? 0 : -1;
}

static double run_pair(const aq_capacity_job *job, aq_capacity *out)
{
  aq_error e;
  double t0 = aq_bench_now_s();
  if (aq_capacity_pair(job, out, &e) != AQ_OK || out->status == AQ_CAPACITY_FAILED) {
    fprintf(stderr, "bench_capacity: pair failed\n");
    return NAN;
  }
  return aq_bench_now_s() - t0;
}

static char hunt_lines[3][400];

static int per_pair(void)
{
  printf("Runs and time per (record, arch, polarity normal), resolution 0.01, tol 1e-6\n"
         "(times: medians of %d; brute@tol: runs counted, time = runs x capacity's "
         "time per run)\n", REPS);
  printf("%-26s %-9s %4s %6s %6s %6s %9s %9s %9s %9s %9s %11s %9s %9s\n", "record",
         "arch", "cor", "runs", "grid", "bisect", "time_s", "first_s", "bf10_runs", "bf10_s",
         "ratio_runs", "bftol_runs", "ratio", "intervals");
  for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
    aq_subject subj;
    aq_view view;
    aq_arch *arch = NULL;
    memset(&view, 0, sizeof view);
    if (load(&pairs[k], &subj, &view, &arch) != 0)
      return -1;
    aq_capacity_job job = {.view = &view,
                           .reversed = 0,
                           .arch = arch,
                           .model = AQ_MODEL_WORKPATH,
                           .cor = pairs[k].cor,
                           .merge_tol_mps2 = 0,
                           .scale_max = NAN,
                           .scan = {0.01, 1e-6}};
    aq_capacity_job fine = job, hunt = job;
    fine.scan.resolution = 0.001;
    hunt.scan.resolution = 1.0;
    double t[REPS], tf[REPS];
    aq_capacity c, f;
    memset(&c, 0, sizeof c);
    memset(&f, 0, sizeof f);
    for (int r = 0; r < REPS; r++) { /* alternate, side by side */
      aq_capacity_free(&c);
      aq_capacity_free(&f);
      t[r] = run_pair(&job, &c);
      tf[r] = r == 0 ? run_pair(&fine, &f) : tf[0];
    }
    aq_capacity h;
    memset(&h, 0, sizeof h);
    run_pair(&hunt, &h);
    double first = t[0]; /* the pair's first run in the process */
    double tm = aq_bench_median(t, REPS), tfm = aq_bench_median(tf, REPS);
    double bftol = ceil(log(c.scale_max / c.move_scale) / log1p(1e-6));
    const char *base = strrchr(pairs[k].record, '/');
    printf("%-26.26s %-9s %4.1f %6zu %6zu %6zu %9.3f %9.3f %9zu %9.3f %9.1f %11.0f %9.0f "
           "%9zu\n",
           base ? base + 1 : pairs[k].record, aq_arch_name(arch),
           isnan(pairs[k].cor) ? 0.0 : pairs[k].cor, c.scan.runs, c.scan.grid_runs,
           c.scan.bisect_runs, tm, first, f.scan.runs, tfm,
           (double)f.scan.runs / (double)c.scan.runs, bftol, bftol / (double)c.scan.runs,
           c.scan.ninterval);
    hunt_lines[k][0] = '\0';
    snprintf(hunt_lines[k], sizeof hunt_lines[k],
             "  %-26.26s %-9s cor %.1f: hunt x2 + fill %3zu runs, first collapse %.7g, "
             "%zu interval(s); scan at 0.01: first collapse %.7g, %zu interval(s)",
             base ? base + 1 : pairs[k].record, aq_arch_name(arch),
             isnan(pairs[k].cor) ? 0.0 : pairs[k].cor, h.scan.runs,
             h.first_collapse_scale, h.scan.ninterval, c.first_collapse_scale,
             c.scan.ninterval);
    aq_capacity_free(&h);
    aq_capacity_free(&c);
    aq_capacity_free(&f);
    aq_arch_free(arch);
    aq_view_free(&view);
    aq_subject_free(&subj);
  }
  printf("Hunt (steps of x2) and fill, against the scan:\n");
  for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++)
    printf("%s\n", hunt_lines[k]);
  return 0;
}

static int suite(void)
{
  const char *cmd =
      "./archquake capacity tests/data/records/*.AT2 --arch arches/oppenheim.cfg "
      "--arch arches/thin.cfg --arch arches/thick.cfg --arch arches/segmental.cfg "
      "--arch arches/search.cfg -j 2 --text build/bench/capacity.tsv "
      "--fragility build/bench/capacity_fragility.tsv 2>build/bench/capacity.err";
  double t0 = aq_bench_now_s();
  int rc = system(cmd);
  double wall = aq_bench_now_s() - t0;
  FILE *f = fopen("build/bench/capacity.tsv", "r");
  if (!f) {
    fprintf(stderr, "bench_capacity: the suite wrote no table (exit %d)\n", rc);
    return -1;
  }
  char line[1 << 16];
  size_t n = 0, res = 0, failed = 0, runs = 0;
  double *rv = malloc(1024 * sizeof *rv);
  /* pairs (record, arch) with resurrection in either polarity */
  char last[1024] = "";
  int last_res = 0;
  size_t res_pairs = 0;
  while (rv && fgets(line, sizeof line, f)) {
    if (strncmp(line, "record\t", 7) == 0)
      continue;
    char *c[12];
    size_t k = 0;
    for (char *p = strtok(line, "\t\n"); p && k < 12; p = strtok(NULL, "\t\n"))
      c[k++] = p;
    if (k < 12)
      continue;
    char key[1024];
    snprintf(key, sizeof key, "%s|%s", c[0], c[1]);
    if (strcmp(key, last) != 0) {
      res_pairs += last_res;
      last_res = 0;
      snprintf(last, sizeof last, "%s", key);
    }
    int r = atoi(c[9]);
    last_res |= r;
    res += r;
    failed += strchr(c[3], ':') != NULL; /* stage:code; the marks are verdicts */
    if (n < 1024)
      rv[n] = atof(c[10]);
    runs += (size_t)atol(c[10]);
    n++;
  }
  res_pairs += last_res;
  fclose(f);
  double med = rv && n ? aq_bench_median(rv, n < 1024 ? n : 1024) : NAN;
  free(rv);
  printf("\nSuite: 11 AT2 records x 5 shipped arches x both polarities, -j 2, one cold\n"
         "process (./archquake capacity): exit %d\n",
         rc);
  printf("  wall %.1f s for %zu (record, arch, polarity) rows, %zu runs (%.2f ms per run, "
         "%.2f s per pair)\n", wall, n, runs, 1e3 * wall / (double)runs,
         wall / (double)n);
  printf("  runs per pair: median %.0f; rows with resurrection %zu; (record, arch) pairs "
         "with resurrection in either polarity %zu of %zu; failed rows %zu "
         "(build/bench/capacity.err)\n", med, res, res_pairs, n / 2, failed);
  printf("\nFragility (build/bench/capacity_fragility.tsv):\n");
  f = fopen("build/bench/capacity_fragility.tsv", "r");
  while (f && fgets(line, sizeof line, f))
    fputs(line, stdout);
  if (f)
    fclose(f);
  return 0;
}

/* CPU time (user + system, s) of the waited-for children so far. */
static double children_cpu_s(void)
{
  struct rusage ru;
  if (getrusage(RUSAGE_CHILDREN, &ru) != 0)
    return NAN;
  return (double)ru.ru_utime.tv_sec + (double)ru.ru_stime.tv_sec +
         1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

typedef struct {
  char key[512], status[32];
  double fcs;
  long runs;
} cap_row;

/* The rows of a capacity table (at most max); their number, or -1. */
static long read_rows(const char *path, cap_row *rows, long max)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return -1;
  char line[1 << 16];
  long n = 0;
  while (n < max && fgets(line, sizeof line, f)) {
    if (strncmp(line, "record\t", 7) == 0)
      continue;
    char *c[12];
    size_t k = 0;
    for (char *p = strtok(line, "\t\n"); p && k < 12; p = strtok(NULL, "\t\n"))
      c[k++] = p;
    if (k < 12)
      continue;
    snprintf(rows[n].key, sizeof rows[n].key, "%s|%s|%s", c[0], c[1], c[2]);
    snprintf(rows[n].status, sizeof rows[n].status, "%s", c[3]);
    rows[n].fcs = strtod(c[5], NULL);
    rows[n].runs = atol(c[10]);
    n++;
  }
  fclose(f);
  return n;
}

static int models(void)
{
  static const char *const model[2] = {"", " --model ode"};
  static const char *const out[2] = {"build/bench/capacity_default.tsv",
                                     "build/bench/capacity_ode.tsv"};
  double wall[2], cpu[2];
  double l[3] = {NAN, NAN, NAN};
  if (getloadavg(l, 3) != 3)
    l[0] = NAN;
  for (int m = 0; m < 2; m++) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "./archquake capacity tests/data/records/*.AT2 --arch arches/oppenheim.cfg "
             "--arch arches/thin.cfg --arch arches/thick.cfg --arch arches/segmental.cfg "
             "--arch arches/search.cfg -j 2%s --text %s 2>/dev/null",
             model[m], out[m]);
    double c0 = children_cpu_s(), t0 = aq_bench_now_s();
    int rc = system(cmd);
    wall[m] = aq_bench_now_s() - t0;
    cpu[m] = children_cpu_s() - c0;
    (void)rc; /* a failed row is a row (status) */
  }
  enum { MAXROWS = 1024 };
  cap_row *a = calloc(MAXROWS, sizeof *a), *b = calloc(MAXROWS, sizeof *b);
  long na = a ? read_rows(out[0], a, MAXROWS) : -1, nb = b ? read_rows(out[1], b, MAXROWS) : -1;
  if (na <= 0 || na != nb) {
    fprintf(stderr, "bench_capacity: the model tables differ in rows (%ld, %ld)\n", na, nb);
    free(a);
    free(b);
    return -1;
  }
  long same_status = 0, equal = 0, close = 0, runs_a = 0, runs_b = 0;
  double worst = 0;
  for (long i = 0; i < na; i++) {
    runs_a += a[i].runs;
    runs_b += b[i].runs;
    if (strcmp(a[i].key, b[i].key) != 0 || strcmp(a[i].status, b[i].status) != 0)
      continue;
    same_status++;
    double x = a[i].fcs, y = b[i].fcs;
    if ((isnan(x) && isnan(y)) || x == y) {
      equal++;
      close++;
      continue;
    }
    double rel = fabs(x - y) / fmax(fabs(x), fabs(y));
    close += rel <= 1e-5;
    worst = isnan(rel) ? INFINITY : fmax(worst, rel);
  }
  printf("\nModels: the suite above (-j 2, one process each, in turn; load %.2f), "
         "default against --model ode:\n", l[0]);
  printf("  default     wall %8.2f s  cpu %8.2f s  runs %ld\n", wall[0], cpu[0], runs_a);
  printf("  --model ode wall %8.2f s  cpu %8.2f s  runs %ld\n", wall[1], cpu[1], runs_b);
  printf("  ode / default: wall %.1fx, cpu %.1fx\n", wall[1] / wall[0], cpu[1] / cpu[0]);
  printf("  agreement over %ld rows: same status %ld; first collapse scale equal as printed "
         "%ld, within 1e-5 relative %ld; largest relative difference %.3g\n",
         na, same_status, equal, close, worst);
  free(a);
  free(b);
  return 0;
}

/* Section 5: the cost of the marks, and what they say. */
enum { MARK_REPS = 3 };
static int marks(void)
{
  static const char *const fr[2] = {"", " --friction 0.6"};
  double cpu[2][MARK_REPS], wall[2][MARK_REPS];
  for (int r = 0; r < MARK_REPS; r++)
    for (int k = 0; k < 2; k++) {
      char cmd[1024];
      snprintf(cmd, sizeof cmd,
               "./archquake capacity tests/data/records/*.AT2 --arch arches/oppenheim.cfg "
               "--arch arches/thin.cfg --arch arches/thick.cfg --arch arches/segmental.cfg "
               "--arch arches/search.cfg -j 2%s --text build/bench/capacity_marks%d.tsv "
               "2>/dev/null", fr[k], k);
      double c0 = children_cpu_s(), t0 = aq_bench_now_s();
      (void)system(cmd); /* a failed row is a row */
      wall[k][r] = aq_bench_now_s() - t0;
      cpu[k][r] = children_cpu_s() - c0;
    }
  double l[3] = {NAN, NAN, NAN};
  if (getloadavg(l, 3) != 3)
    l[0] = NAN;
  printf("\nMarks: the suite of the models section, default model, -j 2, without a "
         "friction and with --friction 0.6, %d runs of each in turn (load %.2f):\n",
         MARK_REPS, l[0]);
  double mc[2];
  enum { MAXROWS = 1024 };
  cap_row *rows = calloc(MAXROWS, sizeof *rows);
  for (int k = 0; k < 2; k++) {
    mc[k] = aq_bench_median(cpu[k], MARK_REPS);
    char path[64];
    snprintf(path, sizeof path, "build/bench/capacity_marks%d.tsv", k);
    long n = rows ? read_rows(path, rows, MAXROWS) : -1;
    static const char *const st[5] = {"ok", "never_moves", "slides", "beyond",
                                      "slides+beyond"};
    long count[5] = {0, 0, 0, 0, 0};
    for (long i = 0; i < n; i++)
      for (int s = 0; s < 5; s++)
        count[s] += strcmp(rows[i].status, st[s]) == 0;
    printf("  %-16s cpu median %7.2f s  wall median %7.2f s  rows %ld: ok %ld, never_moves "
           "%ld, slides %ld, beyond %ld, slides+beyond %ld\n",
           k ? "--friction 0.6" : "no friction", mc[k], aq_bench_median(wall[k], MARK_REPS),
           n, count[0], count[1], count[2], count[3], count[4]);
  }
  printf("  friction / none: cpu %.3fx\n", mc[1] / mc[0]);
  free(rows);
  return 0;
}

/* Two programs (before and after a change), the default model: the suite
 * of section 3 run by each in turn, reps times, alternating; CPU medians,
 * their ratio, and whether the tables are byte-identical. */
static int ab(const char *bin[2], int reps)
{
  enum { MAXREP = 15 };
  double cpu[2][MAXREP], wall[2][MAXREP];
  int same = 1;
  if (reps < 1 || reps > MAXREP)
    reps = 3;
  for (int r = 0; r < reps; r++) {
    for (int k = 0; k < 2; k++) {
      char cmd[2048];
      snprintf(cmd, sizeof cmd,
               "%s capacity tests/data/records/*.AT2 --arch arches/oppenheim.cfg "
               "--arch arches/thin.cfg --arch arches/thick.cfg --arch arches/segmental.cfg "
               "--arch arches/search.cfg -j 2 --text build/bench/capacity_ab%d.tsv 2>/dev/null",
               bin[k], k);
      double c0 = children_cpu_s(), t0 = aq_bench_now_s();
      int rc = system(cmd);
      wall[k][r] = aq_bench_now_s() - t0;
      cpu[k][r] = children_cpu_s() - c0;
      if (rc != 0)
        fprintf(stderr, "bench_capacity: %s exited with %d\n", bin[k], rc);
    }
    same = same && system("cmp -s build/bench/capacity_ab0.tsv build/bench/capacity_ab1.tsv") == 0;
  }
  double l[3] = {NAN, NAN, NAN};
  if (getloadavg(l, 3) != 3)
    l[0] = NAN;
  printf("\nBefore / after: the suite of the models section, default model, -j 2, %d runs "
         "of each program in turn (load %.2f):\n", reps, l[0]);
  double mc[2];
  for (int k = 0; k < 2; k++) {
    mc[k] = aq_bench_median(cpu[k], (size_t)reps);
    printf("  %-40s cpu median %7.2f s  wall median %7.2f s\n", bin[k], mc[k],
           aq_bench_median(wall[k], (size_t)reps));
  }
  printf("  first / second: cpu %.3fx; tables byte-identical in every run: %s\n",
         mc[0] / mc[1], same ? "yes" : "NO");
  return 0;
}

int main(int argc, char **argv)
{
  gsl_set_error_handler_off();
  if (argc == 2 && strcmp(argv[1], "models") == 0) /* section 3 alone */
    return models() == 0 ? 0 : 1;
  if (argc == 2 && strcmp(argv[1], "marks") == 0) /* section 5 alone */
    return marks() == 0 ? 0 : 1;
  if ((argc == 4 || argc == 5) && strcmp(argv[1], "ab") == 0) {
    const char *bin[2] = {argv[2], argv[3]};
    return ab(bin, argc == 5 ? atoi(argv[4]) : 3) == 0 ? 0 : 1;
  }
  if (per_pair() != 0)
    return 1;
  if (suite() != 0)
    return 1;
  if (models() != 0)
    return 1;
  return marks() == 0 ? 0 : 1;
}
