/* filter.c: acausal (zero-phase) Butterworth filtering in the frequency
 * domain with FFTW, and the plan cache behind aq_signal_ws.
 *
 * The filter multiplies the spectrum once by the real magnitude response
 * |H(f)| of a Butterworth filter of order n (no phase: acausal), as Boore
 * (2005, BSSA 95(2) 745-750) and PEER's processing do with time-domain
 * forward+backward passes, except that |H| is applied exactly here, not |H|^2.
 *
 * Threads: FFTW's planner is not thread-safe, so every planner call (create
 * and destroy) holds one process-wide mutex.  Plans are made with
 * FFTW_ESTIMATE (no timing measurements: the same plan, hence bit-identical
 * results, on every run) and executed in place with fftw_execute_dft_r2c/c2r
 * (the thread-safe part of FFTW's API) on the caller's per-record array,
 * aligned to 64 bytes by posix_memalign (aq_filter_alloc): no buffer is
 * shared between threads, and free() releases the array.
 *
 * Wisdom: planning costs tens of ms per transform length even with
 * FFTW_ESTIMATE, which dominated small suites.  The plans' wisdom is kept
 * between runs in $XDG_CACHE_HOME/archquake/fftw-wisdom (or
 * ~/.cache/archquake/fftw-wisdom), loaded before the first plan of the
 * process and written back, when it grew, by aq_signal_ws_free: under a
 * temporary name, then renamed, so a reader never sees half a file.  The
 * file starts with a line "archquake-fftw-wisdom 1 sha256=HEX" over the rest;
 * a file that does not (foreign, truncated, corrupt) is ignored and, at the
 * end, replaced; FFTW itself rejects wisdom of another FFTW build and
 * restores its own when an import fails.  Only ESTIMATE wisdom is ever
 * written there, and an ESTIMATE plan made from it is the plan that
 * ESTIMATE would choose anyway: results are bit-identical with or without
 * the cache (the suite tests check it).  The cache is optional: when it
 * cannot be read or written nothing is reported and planning happens as
 * before.  It serves only the lengths the built-in wisdom (below) lacks: it
 * is read before the first such plan and written only after one, so a
 * process whose lengths are all built in neither reads nor rewrites it
 * (reading and rewriting it cost about 1.5 ms of a 12-record suite's CPU
 * time, for plans the built-in wisdom gives anyway).
 */
#include "filter.h"

#include <fcntl.h>
#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../io/sha256.h"
#include "../util/diskcache.h"
#include "../util/outfile.h"
#include "../util/cpu.h"
#include "fftw_wisdom.h" /* build/: aq_fftw_wisdom[], made by tools/fftw_wisdom.c */

/* FFTW's planner is global to the process: one lock for every workspace. */
static pthread_mutex_t aq_fftw_planner_lock = PTHREAD_MUTEX_INITIALIZER;

/* ---- wisdom cache (all under aq_fftw_planner_lock) ---------------------- */

#define AQ_WISDOM_MAGIC "archquake-fftw-wisdom 1 sha256="
#define AQ_WISDOM_MAX_BYTES ((size_t)4 << 20) /* a larger file is not ours */

static int wisdom_loaded;  /* the cache was looked at (once per process) */
static int wisdom_planned; /* a plan was made since it was loaded or saved */
static char *wisdom_text;  /* the wisdom as loaded or last saved, or NULL */

/* The cache file's directory and name into dir[n], file[n]; 0 if there is
 * no home for it. */
static int wisdom_path(char *dir, char *file, size_t n)
{
  if (!aq_diskcache_default_dir(dir, n) || strlen(dir) + 20 >= n)
    return 0;
  snprintf(file, n, "%s/fftw-wisdom", dir);
  return 1;
}

/* Import the cache file's wisdom if the file is whole and ours. */
static void wisdom_load(void)
{
  if (wisdom_loaded)
    return;
  wisdom_loaded = 1;
  char dir[PATH_MAX], file[PATH_MAX];
  if (!wisdom_path(dir, file, sizeof dir))
    return;
  FILE *f = fopen(file, "rb");
  if (!f)
    return;
  char *buf = malloc(AQ_WISDOM_MAX_BYTES + 1);
  size_t n = buf ? fread(buf, 1, AQ_WISDOM_MAX_BYTES + 1, f) : 0;
  fclose(f);
  size_t head = strlen(AQ_WISDOM_MAGIC) + 64 + 1; /* magic, digest, newline */
  if (!buf || n > AQ_WISDOM_MAX_BYTES || n <= head ||
      memcmp(buf, AQ_WISDOM_MAGIC, strlen(AQ_WISDOM_MAGIC)) != 0 || buf[head - 1] != '\n') {
    free(buf);
    return;
  }
  buf[n] = '\0';
  char hex[AQ_SHA256_HEX];
  aq_sha256_hex(buf + head, n - head, hex);
  if (memcmp(hex, buf + strlen(AQ_WISDOM_MAGIC), 64) != 0 ||
      strlen(buf + head) != n - head || !fftw_import_wisdom_from_string(buf + head)) {
    free(buf);
    return;
  }
  wisdom_text = strdup(buf + head);
  free(buf);
}

/* Write the process's wisdom to the cache if it differs from the file's. */
static void wisdom_save(void)
{
  if (!wisdom_planned)
    return;
  wisdom_planned = 0;
  char dir[PATH_MAX], file[PATH_MAX];
  char *w = fftw_export_wisdom_to_string();
  if (!w || !wisdom_path(dir, file, sizeof dir) ||
      (wisdom_text && strcmp(w, wisdom_text) == 0)) {
    fftw_free(w);
    return;
  }
  char *slash = strrchr(dir, '/');
  if (slash && slash != dir) { /* ~/.cache or $XDG_CACHE_HOME, then ours */
    *slash = '\0';
    mkdir(dir, 0700);
    *slash = '/';
  }
  mkdir(dir, 0700);
  char hex[AQ_SHA256_HEX];
  size_t len = strlen(w);
  aq_sha256_hex(w, len, hex);
  aq_outfile o;
  if (aq_outfile_open(&o, file, NULL) == AQ_OK) {
    if (fprintf(o.f, "%s%s\n", AQ_WISDOM_MAGIC, hex) > 0 && fwrite(w, 1, len, o.f) == len) {
      if (aq_outfile_commit(&o, NULL) == AQ_OK) {
        free(wisdom_text);
        wisdom_text = strdup(w); /* NULL: the next save compares with nothing */
      }
    } else {
      aq_outfile_abort(&o);
    }
  }
  fftw_free(w);
}

/* ---- built-in wisdom (under aq_fftw_planner_lock) -------------------------
 * FFTW_ESTIMATE's first plan of a length costs 5-25 ms of planner search
 * (a cold 5-record suite spent 60 % of its time there), although the plan
 * it chooses is fixed for a given FFTW build.  The build plans every
 * length aq_signal_fft_size can give between 2^10 and 2^22 once, in
 * tools/fftw_wisdom.c, and keeps each length's wisdom apart; before
 * planning a length, its wisdom is imported (a few hundred bytes, about
 * 0.1 ms) and FFTW rebuilds the plan ESTIMATE chose without searching: the
 * same plan, so the same bits.  Wisdom of another FFTW build is skipped
 * (version check here, configuration hash in FFTW), and the length is
 * planned as before.  AQ_FFTW_NO_BUILTIN_WISDOM (set, non-empty) turns it
 * off, so that tests can compare the results with and without it.
 * Returns 1 if length n's wisdom was imported. */

static int builtin_wisdom(size_t n)
{
  static int off = -1;
  if (off < 0) {
    const char *e = getenv("AQ_FFTW_NO_BUILTIN_WISDOM");
    off = (e && e[0]) || strcmp(fftw_version, AQ_FFTW_WISDOM_VERSION) != 0;
  }
  size_t lo = 0, hi = sizeof aq_fftw_wisdom / sizeof aq_fftw_wisdom[0];
  while (!off && lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if ((size_t)aq_fftw_wisdom[mid].n == n) /* 0: refused, planned as before */
      return fftw_import_wisdom_from_string(aq_fftw_wisdom[mid].wisdom) != 0;
    if ((size_t)aq_fftw_wisdom[mid].n < n)
      lo = mid + 1;
    else
      hi = mid;
  }
  return 0;
}

typedef struct {
  size_t n;       /* transform length */
  fftw_plan r2c;  /* n reals -> n/2+1 complex */
  fftw_plan c2r;  /* n/2+1 complex -> n reals (destroys its input) */
} plan_pair;

/* The plans of the process, one pair per length, kept from the first
 * record of that length to the end of the process (under
 * aq_fftw_planner_lock): re-planning a length even from in-memory wisdom
 * costs 0.5-1 ms, which every suite of a process (a capacity search, the
 * bench) paid again per length when each workspace had plans of its own.
 * Blocks of AQ_PLAN_BLOCK pairs that never move, so that a pair found
 * under the lock stays valid after it is released.  They are reachable
 * until exit, as FFTW's own planner state is. */
#define AQ_PLAN_BLOCK 64
typedef struct plan_block {
  plan_pair pair[AQ_PLAN_BLOCK];
  size_t n;                 /* pairs used */
  struct plan_block *next;
} plan_block;
static plan_block *aq_plans;

/* A workspace is a handle on the process's plan cache (see signal.h). */
struct aq_signal_ws {
  int unused;
};

aq_signal_ws *aq_signal_ws_alloc(void)
{
  return calloc(1, sizeof(aq_signal_ws));
}

void aq_signal_ws_free(aq_signal_ws *ws)
{
  if (!ws)
    return;
  pthread_mutex_lock(&aq_fftw_planner_lock);
  wisdom_save();
  pthread_mutex_unlock(&aq_fftw_planner_lock);
  free(ws);
}

/* Find or make the in-place plans for length n.  Caller holds the planner
 * lock. */
static const plan_pair *plans_for(aq_signal_ws *ws, size_t n)
{
  (void)ws;
  for (plan_block *b = aq_plans; b; b = b->next)
    for (size_t i = 0; i < b->n; i++)
      if (b->pair[i].n == n)
        return &b->pair[i];
  if (!aq_plans || aq_plans->n == AQ_PLAN_BLOCK) {
    plan_block *b = calloc(1, sizeof *b);
    if (!b)
      return NULL;
    b->next = aq_plans;
    aq_plans = b;
  }
  /* plan in place on a scratch array aligned as fftw_malloc aligns: every
   * array later passed to the new-array execute calls is aligned alike
   * (aq_filter_alloc) and also in place */
  if (!builtin_wisdom(n)) { /* the cache, for a length not built in */
    wisdom_load();
    wisdom_planned = 1;
  }
  double *x = fftw_malloc(2 * (n / 2 + 1) * sizeof *x);
  fftw_plan r2c = NULL, c2r = NULL;
  if (x) {
    r2c = fftw_plan_dft_r2c_1d((int)n, x, (fftw_complex *)x, FFTW_ESTIMATE);
    c2r = fftw_plan_dft_c2r_1d((int)n, (fftw_complex *)x, x, FFTW_ESTIMATE);
  }
  fftw_free(x);
  if (!r2c || !c2r) {
    if (r2c)
      fftw_destroy_plan(r2c);
    if (c2r)
      fftw_destroy_plan(c2r);
    return NULL;
  }
  plan_pair *pp = &aq_plans->pair[aq_plans->n++];
  pp->n = n;
  pp->r2c = r2c;
  pp->c2r = c2r;
  return pp;
}

double *aq_filter_alloc(size_t n)
{
  void *p = NULL;
  size_t m = 2 * (n / 2 + 1);
  if (m > SIZE_MAX / sizeof(double) ||
      posix_memalign(&p, AQ_FILTER_ALIGN, m * sizeof(double)) != 0)
    return NULL;
  return p;
}

/* x^k for integer k >= 1 by repeated squaring (cheaper than pow per bin). */
static double ipow(double x, int k)
{
  double r = 1.0;
  while (k > 0) {
    if (k & 1)
      r *= x;
    x *= x;
    k >>= 1;
  }
  return r;
}

double aq_filter_gain(double f_hz, const aq_signal_opts *o)
{
  if (!(f_hz > 0))
    return 0.0;
  double r = o->highpass_hz / f_hz;
  double g = 1.0 / sqrt(1.0 + ipow(r * r, o->order));
  if (o->lowpass_hz > 0) {
    double q = f_hz / o->lowpass_hz;
    g /= sqrt(1.0 + ipow(q * q, o->order));
  }
  return g;
}

aq_status aq_filter_apply(aq_signal_ws *ws, double *x, size_t n, double dt_s,
                          const aq_signal_opts *o, double factor,
                          const char *input, aq_error *err)
{
  if (n < 2 || n > (size_t)INT_MAX)
    return aq_error_set(err, AQ_EVALUE, input, -1, -1, "--highpass",
                        "expected a padded length in [2, %d] samples for the "
                        "FFT, got %zu",
                        INT_MAX, n);
  aq_signal_ws *own = NULL;
  if (!ws && !(ws = own = aq_signal_ws_alloc()))
    return aq_error_set(err, AQ_ENOMEM, input, -1, -1, "fft",
                        "cannot allocate the FFT workspace");
  pthread_mutex_lock(&aq_fftw_planner_lock);
  const plan_pair *pp = plans_for(ws, n);
  fftw_plan r2c = pp ? pp->r2c : NULL, c2r = pp ? pp->c2r : NULL;
  pthread_mutex_unlock(&aq_fftw_planner_lock);
  if (!pp) {
    aq_signal_ws_free(own);
    return aq_error_set(err, AQ_EINTERNAL, input, -1, -1, "fft",
                        "cannot make FFTW plans for %zu points", n);
  }

  fftw_complex *spec = (fftw_complex *)x; /* in place: n/2+1 bins */
  fftw_execute_dft_r2c(r2c, x, spec);
  /* bin k is frequency k / (n dt); factor/n undoes FFTW's unnormalised pair.
   * Without a low-pass the computed gain rises monotonically to exactly 1.0
   * ((fc/f)^(2n) below half an ulp of 1) and stays there: the bins above
   * are only scaled, bit-identically to multiplying by the gain. */
  size_t nc = n / 2 + 1, k = 0;
  double df_hz = 1.0 / ((double)n * dt_s), s = factor / (double)n;
  for (; k < nc; k++) {
    double g = aq_filter_gain((double)k * df_hz, o);
    if (g == 1.0 && o->lowpass_hz <= 0)
      break;
    spec[k][0] *= g * s;
    spec[k][1] *= g * s;
  }
  for (; k < nc; k++) {
    spec[k][0] *= s;
    spec[k][1] *= s;
  }
  fftw_execute_dft_c2r(c2r, spec, x);
  aq_signal_ws_free(own);
  return AQ_OK;
}

void aq_signal_fingerprint(char *buf, size_t n)
{
  /* FFTW_ESTIMATE picks codelets by the SIMD sets the CPU (and OS) offer */
  char cpu[96];
  aq_cpu_simd(cpu, sizeof cpu);
  const char *e = getenv("AQ_FFTW_NO_BUILTIN_WISDOM");
  snprintf(buf, n, "%s; %s; builtin wisdom %d", fftw_version, cpu, !(e && e[0]));
}
