/* bench_cli.c: the commands as a user starts them, each run a fresh process
 * (make bench; never in make check).
 *
 * 1. Start-up: /bin/true, `archquake --version`, `archquake info` (no
 *    record: the usage error) and `archquake info RECORD` (one AT2 record
 *    read, processed and measured), interleaved, START_REPS each; medians
 *    of the wall time and of the CPU time (user + system, from wait4), and
 *    each one's ratio to /bin/true.
 * 2. The main job from a cold process: the 12 shared PEER records (the AT2
 *    files of tests/data/records) against oppenheim and thick, each scaled
 *    to 2.5 lambda0 g of the arch, -o, -j 1, the default model and --model
 *    ode, interleaved, JOB_REPS each (a process per run; the FFTW wisdom
 *    cache as the first run left it), then the first run with an empty
 *    cache; medians.  The cache of prepared records (docs/cache.md) off
 *    (--no-cache), emptied before each run (untimed: the run fills it) and
 *    filled, side by side.  Beside them the floor of that work, measured here in
 *    one process: the files' bytes read (open, fread, close), one FFT pair
 *    (r2c + c2r, planned beforehand) per record at its padded length, and
 *    the default model's stepping of the 24 runs (steps made beforehand);
 *    each the median of FLOOR_REPS.  Printed: the floor, each command's
 *    ratio to it, and ode / default.
 * 3. Where the main job's time goes beyond the floor, stage by stage, cold
 *    and warm: this program run again as `bench_cli stages` (a fresh
 *    process, as archquake is) does the job's work with the library's own
 *    calls, in the job's order, twice: the two arches loaded (their
 *    mechanism search and work-path tables), then per record its file read
 *    and parsed, its bytes hashed (sha256, as -o does), processed (detrend,
 *    pads, filter: the FFTW plans of each new length come in the first
 *    pass), its intensity measures and its step list at factor 1; the 24
 *    runs of the default model; the HDF5 file created with its tables (and
 *    removed); the FFTW workspace freed; then, apart, each record prepared
 *    through the disk cache of prepared records instead (docs/cache.md:
 *    the file hashed for the key, the entry read, checked and decoded;
 *    the first process fills it), and the two arches loaded through the
 *    disk cache of built arches (docs/cache.md; first in each pass, so
 *    that the cold pass is a process that never loads GLPK, as the job
 *    with the cache warm).  The first pass is cold (first
 *    calls in the process: plans, page faults of a new heap, caches), the
 *    second warm.  Medians of STAGE_REPS processes, CPU time of the
 *    thread, each stage's cold - warm beside them.
 * AQ_BIN_BEFORE=path adds the same commands of another build (e.g. the
 * previous one) to the same interleaved runs, for a before/after on equal
 * terms.  The load average is printed before and after. */
#define _GNU_SOURCE /* wait4 */
#include <fcntl.h>
#include <fftw3.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "bench.h"
#include "io/record.h"
#include "io/sha256.h"
#include "job/arch_cache.h"
#include "job/subject.h"
#include "report/h5.h"
#include "signal/signal.h"
#include "units.h"

#define START_REPS 201
#define JOB_REPS 15
#define FLOOR_REPS 21
#define STAGE_REPS 11
#define MAXARG 64

static const char *const shared[] = {
    "tests/data/records/ARL360.at2",
    "tests/data/records/CHY028-N.AT2",
    "tests/data/records/IELC180.AT2",
    "tests/data/records/RSN1616_DUZCE_362-E.AT2",
    "tests/data/records/RSN4013_SANSIMEO_36258021.AT2",
    "tests/data/records/RSN4843_CHUETSU_65006NS.AT2",
    "tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2",
    "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
    "tests/data/records/RSN763_LOMAP_GIL067.AT2",
    "tests/data/records/RSN763_LOMAP_GIL337.AT2",
    "tests/data/records/RSN77_SFERN_PUL164-hor1.AT2",
    "tests/data/records/TCU052-N.AT2"};
enum { NSHARED = sizeof shared / sizeof shared[0] };
static const char *const job_arches[] = {"arches/oppenheim.cfg", "arches/thick.cfg"};
enum { NARCH = 2 };
#define JOB_K 2.5 /* --scale-to-lambda0 */

typedef struct {
  const char *label;
  char *argv[MAXARG];
  const char *env;  /* one NAME=VALUE added to the environment, or NULL */
  const char *prep; /* a shell command run (untimed) before each run, or NULL */
  double *wall, *cpu;
} command;

/* CPU time of the calling thread, s. */
static double thread_cpu_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A floor part: median wall and CPU time of FLOOR_REPS repetitions. */
typedef struct {
  double wall[FLOOR_REPS], cpu[FLOOR_REPS];
} floor_times;

static void floor_start(double *w, double *c)
{
  *w = aq_bench_now_s();
  *c = thread_cpu_s();
}

static void floor_stop(floor_times *f, int r, double w, double c)
{
  f->wall[r] = aq_bench_now_s() - w;
  f->cpu[r] = thread_cpu_s() - c;
}

static void load_average(const char *when)
{
  double l[3];
  if (getloadavg(l, 3) == 3)
    printf("  load average %s: %.2f %.2f %.2f\n", when, l[0], l[1], l[2]);
}

/* Run c once (stdout and stderr to /dev/null); wall and CPU time, s.
 * Exits the bench if the command fails. */
static void run(const command *c, double *wall, double *cpu, int want_status)
{
  if (c->prep && system(c->prep) != 0) {
    fprintf(stderr, "bench_cli: %s: %s failed\n", c->label, c->prep);
    exit(1);
  }
  double t0 = aq_bench_now_s();
  pid_t p = fork();
  if (p == 0) {
    int fd = open("/dev/null", O_WRONLY);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    if (c->env)
      putenv((char *)c->env);
    execv(c->argv[0], c->argv);
    _exit(127);
  }
  int st = 0;
  struct rusage ru;
  if (p < 0 || wait4(p, &st, 0, &ru) != p) {
    perror("bench_cli: fork");
    exit(1);
  }
  *wall = aq_bench_now_s() - t0;
  *cpu = (double)ru.ru_utime.tv_sec + (double)ru.ru_stime.tv_sec +
         1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  if (!WIFEXITED(st) || WEXITSTATUS(st) != want_status) {
    fprintf(stderr, "bench_cli: %s: exit %d, expected %d\n", c->label,
            WIFEXITED(st) ? WEXITSTATUS(st) : -1, want_status);
    exit(1);
  }
}

/* Run the n commands reps times each, interleaved; c[i].wall/cpu filled. */
static void interleave(command *c, size_t n, int reps, const int *status)
{
  for (size_t i = 0; i < n; i++) {
    c[i].wall = calloc((size_t)reps, sizeof(double));
    c[i].cpu = calloc((size_t)reps, sizeof(double));
    if (!c[i].wall || !c[i].cpu)
      exit(1);
  }
  for (int r = 0; r < reps; r++)
    for (size_t i = 0; i < n; i++)
      run(&c[i], &c[i].wall[r], &c[i].cpu[r], status ? status[i] : 0);
}

static void free_commands(command *c, size_t n)
{
  for (size_t i = 0; i < n; i++) {
    free(c[i].wall);
    free(c[i].cpu);
  }
}

/* argv from a label's words plus extra (NULL-terminated) arguments. */
static void set_argv(command *c, const char *bin, const char *const *args)
{
  size_t k = 0;
  c->argv[k++] = (char *)bin;
  for (; args && *args && k + 1 < MAXARG; args++)
    c->argv[k++] = (char *)*args;
  c->argv[k] = NULL;
}

/* ---- 1. start-up ---------------------------------------------------------- */

static void startup(const char *before)
{
  static const char *const version[] = {"--version", NULL};
  static const char *const info0[] = {"info", NULL};
  static const char *const info1[] = {"info", "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", NULL};
  const char *const *what[3] = {version, info0, info1};
  static const char *const names[3] = {"--version", "info (no record: usage error)",
                                       "info RECORD (RSN6 ELC180)"};
  command c[7];
  int status[7] = {0};
  size_t n = 0;
  memset(c, 0, sizeof c);
  c[n].label = "/bin/true";
  set_argv(&c[n++], "/bin/true", NULL);
  for (int k = 0; k < 3; k++)
    for (int b = 0; b < (before ? 2 : 1); b++) {
      c[n].label = names[k];
      status[n] = k == 1 ? 2 : 0;
      set_argv(&c[n++], b ? before : "./archquake", what[k]);
    }
  printf("Start-up: %d runs of each, interleaved; medians (wall, and CPU = user +\n"
         "system); ratio to /bin/true's median:\n", START_REPS);
  load_average("before");
  interleave(c, n, START_REPS, status);
  load_average("after");
  double tw = aq_bench_median(c[0].wall, START_REPS);
  double tc = aq_bench_median(c[0].cpu, START_REPS);
  for (size_t i = 0; i < n; i++) {
    double w = aq_bench_median(c[i].wall, START_REPS), u = aq_bench_median(c[i].cpu, START_REPS);
    const char *who = i == 0 ? "" : before && (i % 2 == 0) ? "before " : before ? "after  " : "";
    printf("  %s%-32s wall %7.3f ms %5.2fx   cpu %7.3f ms %5.2fx\n", who, c[i].label, 1e3 * w,
           w / tw, 1e3 * u, u / tc);
  }
  free_commands(c, n);
}

/* ---- 2. the main job and its floor ----------------------------------------- */

/* Median time (s) to read every shared record's bytes, as a reader does
 * before it parses: open, fread of its size, close. */
static void floor_read(floor_times *ft)
{
  for (int r = 0; r < FLOOR_REPS; r++) {
    double w0, c0;
    floor_start(&w0, &c0);
    size_t sum = 0;
    for (size_t i = 0; i < NSHARED; i++) {
      FILE *f = fopen(shared[i], "rb");
      struct stat st;
      if (!f || fstat(fileno(f), &st) != 0)
        exit(1);
      unsigned char *b = malloc((size_t)st.st_size + 1);
      if (!b || fread(b, 1, (size_t)st.st_size, f) != (size_t)st.st_size)
        exit(1);
      sum += b[st.st_size / 2];
      free(b);
      fclose(f);
    }
    floor_stop(ft, r, w0 - (sum == 1 ? 1e-12 : 0), c0);
  }
}

/* Median time (s) of one r2c + c2r pair at each length n[i] (planned
 * before the timing, FFTW_ESTIMATE, in place). */
static void floor_fft(const size_t *n, size_t nrec, floor_times *ft)
{
  double **x = calloc(nrec, sizeof *x);
  fftw_plan *f = calloc(nrec, sizeof *f), *b = calloc(nrec, sizeof *b);
  if (!x || !f || !b)
    exit(1);
  for (size_t i = 0; i < nrec; i++) {
    x[i] = fftw_malloc(2 * (n[i] / 2 + 1) * sizeof(double));
    if (!x[i])
      exit(1);
    f[i] = fftw_plan_dft_r2c_1d((int)n[i], x[i], (fftw_complex *)x[i], FFTW_ESTIMATE);
    b[i] = fftw_plan_dft_c2r_1d((int)n[i], (fftw_complex *)x[i], x[i], FFTW_ESTIMATE);
    if (!f[i] || !b[i])
      exit(1);
    for (size_t k = 0; k < n[i]; k++)
      x[i][k] = sin(0.001 * (double)k);
  }
  for (int r = 0; r < FLOOR_REPS; r++) {
    double w0, c0;
    floor_start(&w0, &c0);
    for (size_t i = 0; i < nrec; i++) {
      fftw_execute(f[i]);
      fftw_execute(b[i]);
    }
    floor_stop(ft, r, w0, c0);
  }
  for (size_t i = 0; i < nrec; i++) {
    fftw_destroy_plan(f[i]);
    fftw_destroy_plan(b[i]);
    fftw_free(x[i]);
  }
  free(x);
  free(f);
  free(b);
}

/* The default model's stepper for arch a (its COR and impact rule) and
 * *l0 its smaller lambda0; NULL if it cannot be made. */
static aq_stepper *job_stepper(const aq_arch *a, double *l0, aq_error *e)
{
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), AQ_MODEL_WORKPATH, e);
  if (!st)
    return NULL;
  const aq_arch_dynamics *d = aq_arch_dynamics_of(a);
  aq_stepper_set_cor(st, d->cor);
  aq_stepper_set_impact(st, d->impact == AQ_IMPACT_MOMENTUM);
  *l0 = INFINITY;
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(a, k);
    if (p && p->admissible)
      *l0 = fmin(*l0, p->lambda0);
  }
  return st;
}

/* The floor's parts: bytes read, FFT pairs, the default model's stepping
 * of every (record, arch) run at K lambda0 g; *nlen distinct FFT lengths. */
static int job_floor(floor_times *fr, floor_times *ff, floor_times *fs, size_t *nlen)
{
  aq_error e;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  so.im_nsa = 0; /* the main job's: spectral measures only when named (opt_table.c) */
  so.sa_avg_lo_s = so.sa_avg_hi_s = 0;
  aq_signal_ws *ws = aq_signal_ws_alloc();
  aq_arch *arch[NARCH] = {NULL};
  aq_stepper *st[NARCH] = {NULL};
  double l0[NARCH];
  for (int a = 0; a < NARCH; a++) {
    if (aq_arch_load(job_arches[a], &arch[a], &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      return -1;
    }
    if (!(st[a] = job_stepper(arch[a], &l0[a], &e)))
      return -1;
  }
  size_t n[NSHARED];
  aq_steps steps[NSHARED];
  double pga_mps2[NSHARED];
  for (size_t i = 0; i < NSHARED; i++) {
    aq_record rec;
    aq_processed proc;
    aq_im im;
    if (aq_record_read(shared[i], &ro, &rec, &e) != AQ_OK ||
        aq_signal_process(&rec, &so, ws, &proc, &e) != AQ_OK ||
        aq_im_compute(&proc, &im, &e) != AQ_OK ||
        aq_steps_from_processed(&proc, 0, &steps[i], &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      return -1;
    }
    n[i] = proc.n;
    pga_mps2[i] = im.pga_g * AQ_G0_MPS2;
    aq_processed_free(&proc);
    aq_record_free(&rec);
  }
  *nlen = 0;
  for (size_t i = 0; i < NSHARED; i++) {
    size_t j = 0;
    while (j < i && n[j] != n[i])
      j++;
    *nlen += j == i;
  }
  floor_read(fr);
  floor_fft(n, NSHARED, ff);
  for (int r = 0; r < FLOOR_REPS; r++) {
    double w0, c0;
    floor_start(&w0, &c0);
    for (size_t i = 0; i < NSHARED; i++)
      for (int a = 0; a < NARCH; a++) {
        aq_result res;
        aq_stepper_set_scale(st[a], JOB_K * l0[a] * AQ_G0_MPS2 / pga_mps2[i]);
        if (aq_stepper_run(st[a], &steps[i], &res, &e) != AQ_OK) {
          aq_error_print(&e, stderr);
          return -1;
        }
        aq_result_free(&res);
      }
    floor_stop(fs, r, w0, c0);
  }
  for (size_t i = 0; i < NSHARED; i++)
    aq_steps_free(&steps[i]);
  for (int a = 0; a < NARCH; a++) {
    aq_stepper_free(st[a]);
    aq_arch_free(arch[a]);
  }
  aq_signal_ws_free(ws);
  return 0;
}

/* The main job's commands: this build's default model with the disk cache
 * (prepared records, built arches) off (--no-cache), empty before each run
 * (it fills it: "cache cold") and filled ("cache warm"); --model ode off
 * and warm; the before build's two models with a cache directory of its
 * own, filled by its first run (warm, whatever it keeps there). */
enum { JC_OFF, JC_COLD, JC_WARM, JC_ODE_OFF, JC_ODE_WARM, JC_N };
static const char *const jc_label[JC_N] = {"default, no cache", "default, cache cold",
                                           "default, cache warm", "ode, no cache",
                                           "ode, cache warm"};

static void main_job(const char *before)
{
  char cache[64], env_cache[96], out[96], prep[240], bcache[80], env_bcache[112];
  snprintf(cache, sizeof cache, "/tmp/aq-bench-cli-%ld", (long)getpid());
  snprintf(env_cache, sizeof env_cache, "XDG_CACHE_HOME=%s", cache);
  snprintf(bcache, sizeof bcache, "%s-before", cache);
  snprintf(env_bcache, sizeof env_bcache, "XDG_CACHE_HOME=%s", bcache);
  snprintf(out, sizeof out, "%s/job.h5", cache);
  snprintf(prep, sizeof prep, "rm -rf %s/archquake/records %s/archquake/arches", cache, cache);
  mkdir(cache, 0700);
  mkdir(bcache, 0700);
  const char *args[JC_N + 2][MAXARG];
  size_t k = 0;
  for (size_t i = 0; i < NSHARED; i++)
    args[0][k++] = shared[i];
  for (int a = 0; a < NARCH; a++) {
    args[0][k++] = "--arch";
    args[0][k++] = job_arches[a];
  }
  args[0][k++] = "--scale-to-lambda0";
  args[0][k++] = "2.5";
  args[0][k++] = "-o";
  args[0][k++] = out;
  args[0][k++] = "-j";
  args[0][k++] = "1";
  args[0][k++] = "-q";
  size_t base = k;
  command c[JC_N + 2];
  memset(c, 0, sizeof c);
  size_t nc = before ? JC_N + 2 : JC_N;
  for (size_t i = 0; i < nc; i++) {
    int ode = i == JC_ODE_OFF || i == JC_ODE_WARM || i == JC_N + 1;
    int off = i == JC_OFF || i == JC_ODE_OFF;
    memcpy(args[i], args[0], base * sizeof args[0][0]);
    size_t m = base;
    if (ode) {
      args[i][m++] = "--model";
      args[i][m++] = "ode";
    }
    if (off)
      args[i][m++] = "--no-cache";
    args[i][m] = NULL;
    c[i].label = i < JC_N ? jc_label[i] : ode ? "before: ode" : "before: default";
    c[i].env = i < JC_N ? env_cache : env_bcache;
    c[i].prep = i == JC_COLD ? prep : NULL;
    set_argv(&c[i], i < JC_N ? "./archquake" : before, args[i]);
  }
  floor_times part[3];
  size_t nlen;
  if (job_floor(&part[0], &part[1], &part[2], &nlen) != 0) {
    fprintf(stderr, "bench_cli: the floor cannot be measured\n");
    exit(1);
  }
  double pw[3], pc[3];
  for (int j = 0; j < 3; j++) {
    pw[j] = aq_bench_median(part[j].wall, FLOOR_REPS);
    pc[j] = aq_bench_median(part[j].cpu, FLOOR_REPS);
  }
  double fl = pw[0] + pw[1] + pw[2], flc = pc[0] + pc[1] + pc[2];
  printf("\nThe main job from a cold process: %d shared AT2 records x oppenheim, thick,\n"
         "--scale-to-lambda0 2.5, -o, -j 1 (%d runs); %d runs of each command,\n"
         "interleaved, medians; the wisdom cache as the first run left it; the cache\n"
         "of prepared records (docs/cache.md) off, emptied before each run (cold:\n"
         "the run fills it) or filled (warm):\n",
         NSHARED, 2 * NSHARED, JOB_REPS);
  printf("  floor, wall %.2f ms = read %.2f + FFT pairs %.2f (%zu lengths) + default "
         "stepping %.2f\n        CPU %.2f ms = %.2f + %.2f + %.2f\n",
         1e3 * fl, 1e3 * pw[0], 1e3 * pw[1], nlen, 1e3 * pw[2], 1e3 * flc, 1e3 * pc[0],
         1e3 * pc[1], 1e3 * pc[2]);
  /* an empty cache first, once each (as a user's first run), in this
   * order, so that the warm commands find it filled */
  double empty_w[JC_N + 2];
  for (size_t i = 0; i < nc; i++) {
    char rm[160];
    snprintf(rm, sizeof rm, "rm -rf %s/archquake", i < JC_N ? cache : bcache);
    if (i != JC_WARM && i != JC_ODE_WARM && system(rm) != 0)
      exit(1);
    run(&c[i], &empty_w[i], &empty_w[i], 0);
    empty_w[i] = c[i].prep || i == JC_WARM || i == JC_ODE_WARM ? NAN : empty_w[i];
  }
  load_average("before");
  interleave(c, nc, JOB_REPS, NULL);
  load_average("after");
  double med_w[JC_N + 2], med_c[JC_N + 2];
  for (size_t i = 0; i < nc; i++) {
    med_w[i] = aq_bench_median(c[i].wall, JOB_REPS);
    med_c[i] = aq_bench_median(c[i].cpu, JOB_REPS);
  }
  for (size_t i = 0; i < nc; i++) {
    printf("  %-20s wall %8.2f ms (%5.2fx the floor)  cpu %8.2f ms (%5.2fx)", c[i].label,
           1e3 * med_w[i], med_w[i] / fl, 1e3 * med_c[i], med_c[i] / flc);
    if (!isnan(empty_w[i]))
      printf("  empty wisdom cache: wall %.2f ms", 1e3 * empty_w[i]);
    printf("\n");
  }
  printf("  ode/default (wall, CPU): no cache %.2f %.2f, cache warm %.2f %.2f",
         med_w[JC_ODE_OFF] / med_w[JC_OFF], med_c[JC_ODE_OFF] / med_c[JC_OFF],
         med_w[JC_ODE_WARM] / med_w[JC_WARM], med_c[JC_ODE_WARM] / med_c[JC_WARM]);
  if (before)
    printf(", before %.2f %.2f\n  this build's cache warm / before's (wall, CPU): default %.3f "
           "%.3f, ode %.3f %.3f",
           med_w[JC_N + 1] / med_w[JC_N], med_c[JC_N + 1] / med_c[JC_N],
           med_w[JC_WARM] / med_w[JC_N], med_c[JC_WARM] / med_c[JC_N],
           med_w[JC_ODE_WARM] / med_w[JC_N + 1], med_c[JC_ODE_WARM] / med_c[JC_N + 1]);
  printf("\n  cache warm / no cache (CPU): default %.2f, ode %.2f; cache cold / no cache: "
         "%.2f\n",
         med_c[JC_WARM] / med_c[JC_OFF], med_c[JC_ODE_WARM] / med_c[JC_ODE_OFF],
         med_c[JC_COLD] / med_c[JC_OFF]);
  free_commands(c, nc);
  char rm[160];
  snprintf(rm, sizeof rm, "rm -rf %s %s", cache, bcache);
  if (system(rm) != 0)
    fprintf(stderr, "bench_cli: cannot remove %s\n", cache);
}

/* ---- 3. the job's stages, cold and warm ----------------------------------- */

enum { ST_ARCH, ST_READ, ST_HASH, ST_PROCESS, ST_IM, ST_STEPS, ST_STEP, ST_H5, ST_WS, ST_CACHE,
       ST_ARCH_CACHE, NSTAGE };
static const char *const stage_name[NSTAGE] = {
    "arches loaded (2: mechanism search, tables)", "records read and parsed",
    "files hashed (sha256)", "processed (detrend, pads, filter; plans)",
    "intensity measures (pads included)", "step lists (factor 1)",
    "default model's 24 runs", "HDF5 file set up (tables; removed)",
    "FFTW workspace freed (wisdom)",
    "instead of read..measures: the disk cache",
    "instead of arches loaded: the disk cache"};

/* The child: the job's stages twice in this process; prints 2 x NSTAGE
 * CPU times (s), cold then warm.  Returns 0, or 1 if a stage fails. */
static int stages_child(const char *cache_dir)
{
  aq_diskcache *dc = aq_diskcache_open(cache_dir, "records", "bench");
  aq_diskcache *ac = aq_diskcache_open(cache_dir, "arches", "bench");
  if (!dc || !ac) {
    aq_diskcache_close(dc);
    aq_diskcache_close(ac);
    return 1;
  }
  aq_error e;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  so.im_nsa = 0; /* the main job's: spectral measures only when named (opt_table.c) */
  so.sa_avg_lo_s = so.sa_avg_hi_s = 0;
  char h5[96];
  snprintf(h5, sizeof h5, "/tmp/aq-bench-cli-stages-%ld.h5", (long)getpid());
  for (int pass = 0; pass < 2; pass++) {
    double t[NSTAGE] = {0}, w, c;
    aq_arch *arch[NARCH] = {NULL};
    /* the arches through the disk cache (filled by the first process),
     * first: as the job does, a process that reads them never loads GLPK */
    c = thread_cpu_s();
    for (int a = 0; a < NARCH; a++) {
      if (aq_arch_cache_load(ac, job_arches[a], NULL, NULL, &arch[a], &e) != AQ_OK)
        goto fail;
      aq_arch_free(arch[a]);
      arch[a] = NULL;
    }
    t[ST_ARCH_CACHE] = thread_cpu_s() - c;
    floor_start(&w, &c);
    for (int a = 0; a < NARCH; a++)
      if (aq_arch_load(job_arches[a], &arch[a], &e) != AQ_OK)
        goto fail;
    t[ST_ARCH] = thread_cpu_s() - c;
    aq_signal_ws *ws = aq_signal_ws_alloc();
    aq_steps steps[NSHARED];
    aq_processed procs[NSHARED]; /* the steps borrow their samples, as the job's do */
    double pga_mps2[NSHARED];
    memset(steps, 0, sizeof steps);
    memset(procs, 0, sizeof procs);
    for (size_t i = 0; i < NSHARED; i++) {
      aq_record rec;
      aq_processed *proc = &procs[i];
      aq_im im;
      char hex[AQ_SHA256_HEX];
      double c0 = thread_cpu_s();
      if (aq_record_read(shared[i], &ro, &rec, &e) != AQ_OK)
        goto fail;
      double c1 = thread_cpu_s();
      FILE *f = fopen(shared[i], "rb");
      unsigned char *b = malloc(1 << 22);
      size_t nb = f && b ? fread(b, 1, 1 << 22, f) : 0;
      if (f)
        fclose(f);
      double c2 = thread_cpu_s();
      aq_sha256_hex(b, nb, hex);
      double c3 = thread_cpu_s();
      free(b);
      if (aq_signal_process(&rec, &so, ws, proc, &e) != AQ_OK)
        goto fail;
      double c4 = thread_cpu_s();
      if (aq_im_compute(proc, &im, &e) != AQ_OK)
        goto fail;
      double c5 = thread_cpu_s();
      /* a plain record's view (job/subject.h): no copy of the samples */
      if (aq_steps_over(proc->acc_mps2, proc->n, proc->dt_s,
                        -(double)proc->pad_front * proc->dt_s, &steps[i], NULL,
                        &e) != AQ_OK)
        goto fail;
      double c6 = thread_cpu_s();
      t[ST_READ] += c1 - c0;
      t[ST_HASH] += c3 - c2;
      t[ST_PROCESS] += c4 - c3;
      t[ST_IM] += c5 - c4;
      t[ST_STEPS] += c6 - c5;
      /* the same record prepared through the disk cache (key: the file
       * read and hashed; the entry read, checked and decoded), filled by
       * the first process of the run */
      aq_subject sj;
      aq_subject_src src = {{shared[i], NULL, NULL}, {NAN, NAN}, NULL};
      aq_subject_opts sopt = {&ro, &so, 0, 0, 0, dc};
      double c7 = thread_cpu_s();
      if (aq_subject_prepare(&sj, &src, &sopt, ws, &e) != AQ_OK)
        goto fail;
      t[ST_CACHE] += thread_cpu_s() - c7;
      aq_subject_free(&sj);
      pga_mps2[i] = im.pga_g * AQ_G0_MPS2;
      aq_record_free(&rec);
    }
    c = thread_cpu_s();
    for (int a = 0; a < NARCH; a++) {
      double l0;
      aq_stepper *st = job_stepper(arch[a], &l0, &e);
      if (!st)
        goto fail;
      for (size_t i = 0; i < NSHARED; i++) {
        aq_result res;
        aq_stepper_set_scale(st, JOB_K * l0 * AQ_G0_MPS2 / pga_mps2[i]);
        aq_status rs = aq_stepper_run(st, &steps[i], &res, &e);
        aq_result_free(&res);
        if (rs != AQ_OK) {
          aq_stepper_free(st);
          goto fail;
        }
      }
      aq_stepper_free(st);
    }
    t[ST_STEP] = thread_cpu_s() - c;
    c = thread_cpu_s();
    aq_h5_writer *hw = NULL;
    if (aq_h5_open(h5, &hw, &e) != AQ_OK)
      goto fail;
    aq_h5_abort(hw);
    t[ST_H5] = thread_cpu_s() - c;
    c = thread_cpu_s();
    aq_signal_ws_free(ws);
    t[ST_WS] = thread_cpu_s() - c;
    for (size_t i = 0; i < NSHARED; i++) {
      aq_steps_free(&steps[i]);
      aq_processed_free(&procs[i]);
    }
    for (int a = 0; a < NARCH; a++)
      aq_arch_free(arch[a]);
    for (int k = 0; k < NSTAGE; k++)
      printf("%.9g%c", t[k], k + 1 < NSTAGE ? ' ' : '\n');
    (void)w;
  }
  aq_diskcache_close(dc);
  aq_diskcache_close(ac);
  return 0;
fail:
  aq_diskcache_close(dc);
  aq_diskcache_close(ac);
  aq_error_print(&e, stderr);
  return 1;
}

static void stages(void)
{
  double cold[NSTAGE][STAGE_REPS], warm[NSTAGE][STAGE_REPS];
  char dir[64], cmd[160];
  snprintf(dir, sizeof dir, "/tmp/aq-bench-cli-stages-%ld", (long)getpid());
  snprintf(cmd, sizeof cmd, "./build/bench/bench_cli stages %s", dir);
  for (int r = 0; r < STAGE_REPS; r++) {
    FILE *p = popen(cmd, "r");
    int ok = p != NULL;
    for (int pass = 0; ok && pass < 2; pass++)
      for (int k = 0; ok && k < NSTAGE; k++)
        ok = fscanf(p, "%lf", pass ? &warm[k][r] : &cold[k][r]) == 1;
    if (!p || pclose(p) != 0 || !ok) {
      fprintf(stderr, "bench_cli: bench_cli stages failed\n");
      exit(1);
    }
  }
  printf("\nThe main job's work stage by stage (library calls, the job's order), in a\n"
         "fresh process: the first pass cold, the same work again warm; CPU time,\n"
         "medians of %d processes:\n", STAGE_REPS);
  printf("  %-44s %9s %9s %9s\n", "stage", "cold_ms", "warm_ms", "cold-warm");
  double sc = 0, sw = 0;
  for (int k = 0; k < ST_CACHE; k++) {
    double mc = aq_bench_median(cold[k], STAGE_REPS), mw = aq_bench_median(warm[k], STAGE_REPS);
    sc += mc;
    sw += mw;
    printf("  %-44s %9.2f %9.2f %9.2f\n", stage_name[k], 1e3 * mc, 1e3 * mw, 1e3 * (mc - mw));
  }
  printf("  %-44s %9.2f %9.2f %9.2f\n", "sum", 1e3 * sc, 1e3 * sw, 1e3 * (sc - sw));
  double mc = aq_bench_median(cold[ST_CACHE], STAGE_REPS);
  double mw = aq_bench_median(warm[ST_CACHE], STAGE_REPS);
  printf("  %-44s %9.2f %9.2f %9.2f\n", stage_name[ST_CACHE], 1e3 * mc, 1e3 * mw,
         1e3 * (mc - mw));
  mc = aq_bench_median(cold[ST_ARCH_CACHE], STAGE_REPS);
  mw = aq_bench_median(warm[ST_ARCH_CACHE], STAGE_REPS);
  printf("  %-44s %9.2f %9.2f %9.2f\n", stage_name[ST_ARCH_CACHE], 1e3 * mc, 1e3 * mw,
         1e3 * (mc - mw));
  mc = aq_bench_median(cold[ST_CACHE], STAGE_REPS);
  printf("  (the records from the disk cache, the first process filling it: read,\n"
         "  hash, process and measures cold %.2f ms become %.2f ms)\n",
         1e3 * (aq_bench_median(cold[ST_READ], STAGE_REPS) +
                aq_bench_median(cold[ST_HASH], STAGE_REPS) +
                aq_bench_median(cold[ST_PROCESS], STAGE_REPS) +
                aq_bench_median(cold[ST_IM], STAGE_REPS)),
         1e3 * mc);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd) != 0)
    fprintf(stderr, "bench_cli: cannot remove %s\n", dir);
}

int main(int argc, char **argv)
{
  gsl_set_error_handler_off();
  if (argc == 3 && strcmp(argv[1], "stages") == 0)
    return stages_child(argv[2]);
  const char *before = getenv("AQ_BIN_BEFORE");
  if (before && !before[0])
    before = NULL;
  startup(before);
  main_job(before);
  stages();
  return 0;
}
