/* bench_friction.c: the statics with friction (src/arch/friction.c).
 * `archquake mechanism --arch FILE --friction 0.6` as a process against
 * the same without --friction, side by side (alternated), for semicircles
 * of 20, 100 and 300 voussoirs; then in the process: building the arch
 * with and without a friction (the program for each direction, the
 * friction at rest), one program of the largest load with friction, one
 * least friction at a load, mu_required of a set (9x9), and the table of
 * the least friction over the load that the main job and capacity build
 * (its nodes per direction).  Medians of REPS. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>

#include "arch/arch.h"
#include "arch/model.h"
#include "bench.h"
#include "units.h"

#define REPS 11

extern char **environ;

/* A semicircle of nv voussoirs (R 5 m, t 1.25 m) written to path. */
static int write_cfg(const char *path, size_t nv)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return 0;
  fprintf(f, "[arch]\nname = semicircle%zu\nradius_m = 5.0\nthickness_m = 1.25\n"
             "embrace_deg = 180\nvoussoirs = %zu\ndensity_kg_m3 = 2000\ndepth_m = 1.0\n"
             "[hinges]\ncontrol = fixed\n",
          nv, nv);
  return fclose(f) == 0;
}

/* Wall time of one `archquake mechanism` process, s (stdout to /dev/null). */
static double run_mechanism(const char *cfg, const char *friction)
{
  char *argv[] = {"./archquake", "mechanism", "--arch", (char *)cfg, "--friction",
                  (char *)friction, NULL};
  if (!friction)
    argv[4] = NULL;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", 1, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", 1, 0);
  pid_t pid;
  double t0 = aq_bench_now_s();
  int rc = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
  int st = 0;
  if (rc == 0)
    waitpid(pid, &st, 0);
  double t = aq_bench_now_s() - t0;
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 && WIFEXITED(st) && WEXITSTATUS(st) == 0 ? t : NAN;
}

static double build_ms(size_t nv, double mu, int table)
{
  double t[REPS];
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
  p.friction = mu;
  p.friction_table = table;
  for (int r = 0; r < REPS; r++) {
    aq_arch *a = NULL;
    aq_error e;
    double t0 = aq_bench_now_s();
    if (aq_arch_build(&p, NULL, NULL, NULL, "bench", &a, &e) != AQ_OK) {
      fprintf(stderr, "bench_friction: %s\n", e.message);
      return NAN;
    }
    t[r] = aq_bench_now_s() - t0;
    aq_arch_free(a);
  }
  return 1e3 * aq_bench_median(t, REPS);
}

int main(void)
{
  gsl_set_error_handler_off();
  static const size_t sizes[] = {20, 100, 300};
  printf("== archquake mechanism --arch semicircle (R 5 m, t 1.25 m), process wall time, "
         "median of %d, alternated\n", REPS);
  printf("voussoirs\twithout_ms\twith_friction_0.6_ms\tratio\n");
  for (size_t i = 0; i < 3; i++) {
    char cfg[128];
    snprintf(cfg, sizeof cfg, "build/tmp/bench_friction_%zu.cfg", sizes[i]);
    if (!write_cfg(cfg, sizes[i])) {
      fprintf(stderr, "bench_friction: cannot write %s\n", cfg);
      return 1;
    }
    double a[REPS], b[REPS];
    for (int r = 0; r < REPS; r++) {
      a[r] = run_mechanism(cfg, NULL);
      b[r] = run_mechanism(cfg, "0.6");
    }
    double ma = 1e3 * aq_bench_median(a, REPS), mb = 1e3 * aq_bench_median(b, REPS);
    printf("%zu\t%.2f\t%.2f\t%.2f\n", sizes[i], ma, mb, mb / ma);
  }
  printf("\n== in the process, medians of %d (ms)\n", REPS);
  printf("voussoirs\tbuild_no_friction\tbuild_friction_0.6\tbuild_with_table\t"
         "lambda_friction_lp\tleast_at_half\tmu_required_9x9\ttable_nodes\n");
  for (size_t i = 0; i < 3; i++) {
    size_t nv = sizes[i];
    double b0 = build_ms(nv, 0, 0), b1 = build_ms(nv, 0.6, 0), b2 = build_ms(nv, 0.6, 1);
    aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
    p.friction_table = 1;
    aq_arch *a = NULL;
    aq_error e;
    if (aq_arch_build(&p, NULL, NULL, NULL, "bench", &a, &e) != AQ_OK) {
      fprintf(stderr, "bench_friction: %s\n", e.message);
      return 1;
    }
    const aq_geom *g = aq_arch_geom(a);
    double top = aq_arch_lambda_static(a, -1), tl[REPS], tm[REPS], tr[REPS];
    for (int r = 0; r < REPS; r++) {
      double l, mu;
      double t0 = aq_bench_now_s();
      aq_friction_lambda(g, -1, 0.6, &l, NULL, &e);
      tl[r] = aq_bench_now_s() - t0;
      t0 = aq_bench_now_s();
      aq_friction_least(g, -1, 0.5 * top, &mu, NULL, &e);
      tm[r] = aq_bench_now_s() - t0;
      t0 = aq_bench_now_s();
      aq_arch_joint_friction(a, 0, NULL, NULL);
      tr[r] = aq_bench_now_s() - t0;
    }
    int nodes = aq_statics_nodes(aq_arch_statics(a), -1);
    printf("%zu\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.4f\t%d\n", nv, b0, b1, b2,
           1e3 * aq_bench_median(tl, REPS), 1e3 * aq_bench_median(tm, REPS),
           1e3 * aq_bench_median(tr, REPS), nodes);
    aq_arch_free(a);
  }
  return 0;
}
