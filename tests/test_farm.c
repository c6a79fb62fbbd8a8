/* The main job's and capacity's tasks through a farm (farm.h), as
 * archquake-mpi runs them, but here in one process so the sanitizers see
 * the merging: a leader that runs every task last to first and takes each
 * result as it comes must write what the plain command writes, byte for
 * byte (the MPI tests, tests/mpi.sh, check the ranks themselves). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "app/farm.h"
#include "check.h"

static size_t fake_tasks; /* tasks the fake farm ran */

/* A leader alone: every task run here, last to first (the order a farm may
 * finish them in), its result taken at once. */
static int fake_farm(void *ctx, const aq_farm_tasks *T, const size_t *todo, size_t ntodo,
                     aq_error *err)
{
  (void)ctx;
  for (size_t k = ntodo; k-- > 0;) {
    unsigned char *msg = NULL;
    size_t n = 0;
    if (T->run(T->ctx, todo[k], &msg, &n) != 0)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory"), -1;
    int rc = T->take(T->ctx, todo[k], msg, n, err);
    free(msg);
    fake_tasks++;
    if (rc != 0)
      return -1;
  }
  return 0;
}

/* Run argv (NULL-terminated) through cmd with the fake farm or none. */
static int run_cmd(int (*cmd)(int, char **), const char *const *args, int farmed)
{
  char *argv[32];
  int argc = 0;
  while (args[argc] && argc < 31) {
    argv[argc] = (char *)args[argc];
    argc++;
  }
  argv[argc] = NULL;
  aq_farm f = {NULL, 0, fake_farm};
  aq_farm_set(farmed ? &f : NULL);
  int rc = cmd(argc, argv);
  aq_farm_set(NULL);
  return rc;
}

static int same_file(const char *a, const char *b)
{
  size_t na = 0, nb = 0;
  char *x = aq_test_read_file(a, &na), *y = aq_test_read_file(b, &nb);
  int same = x && y && na == nb && na > 0 && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

/* A temporary directory with the paths of both runs' outputs: p[0] and
 * p[1] the TSVs (plain, farmed), p[2] and p[3] the second output (ext). */
typedef struct {
  char dir[32];
  char p[4][64];
} outs;

static int outs_make(outs *o, const char *ext)
{
  char dir[] = "/tmp/aq_farm_XXXXXX";
  if (!aq_check(mkdtemp(dir) != NULL, "temporary directory"))
    return -1;
  snprintf(o->dir, sizeof o->dir, "%s", dir);
  for (int k = 0; k < 4; k++)
    snprintf(o->p[k], sizeof o->p[k], "%s/%c.%s", dir, "abab"[k], k < 2 ? "tsv" : ext);
  return 0;
}

static void outs_remove(const outs *o)
{
  for (int k = 0; k < 4; k++)
    unlink(o->p[k]);
  rmdir(o->dir);
}

/* cmd on args (n of them) then --text p[k] opt p[k + 2], plain (k = 0)
 * and farmed (k = 1); both exit statuses must be 0, with 6 tasks farmed. */
static void run_both(int (*cmd)(int, char **), const char *const *args, size_t n,
                     const char *opt, const outs *o)
{
  int rc[2];
  fake_tasks = 0;
  for (int k = 0; k < 2; k++) {
    const char *a[32];
    for (size_t i = 0; i < n && i < 27; i++)
      a[i] = args[i];
    size_t m = n < 27 ? n : 27;
    a[m] = "--text";
    a[m + 1] = o->p[k];
    a[m + 2] = opt;
    a[m + 3] = o->p[k + 2];
    a[m + 4] = NULL;
    rc[k] = run_cmd(cmd, a, k);
  }
  aq_check(rc[0] == 0 && rc[1] == 0, "exit status: %d plain, %d farmed", rc[0], rc[1]);
  aq_check(fake_tasks == 6, "tasks: one per (record, arch): %zu", fake_tasks);
  aq_check(same_file(o->p[0], o->p[1]), "TSV byte-identical");
}

AQ_TEST(farm_main_job_equals_the_suite)
{
  outs o;
  if (outs_make(&o, "h5") != 0)
    return;
  const char *args[] = {"archquake", "tests/data/records/ARL360.at2",
                        "tests/data/records/CHY028-N.AT2", "tests/data/records/IELC180.AT2",
                        "--arch", "arches/oppenheim.cfg", "--arch", "arches/thin.cfg",
                        "--scale", "0.5,2.385", "--polarity", "both", "-j", "2", "-q"};
  run_both(aq_cmd_run, args, sizeof args / sizeof args[0], "-o", &o);
  char cmp[200], out[4096], err[4096];
  snprintf(cmp, sizeof cmp, "compare %s %s", o.p[2], o.p[3]);
  int rc = aq_test_run(cmp, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "compare finds the results files equal (%d): %s", rc, err);
  outs_remove(&o);
}

AQ_TEST(farm_capacity_equals_the_command)
{
  outs o;
  if (outs_make(&o, "frag") != 0)
    return;
  const char *args[] = {"capacity", "tests/data/records/ARL360.at2",
                        "tests/data/records/CHY028-N.AT2", "tests/data/records/IELC180.AT2",
                        "--arch", "arches/oppenheim.cfg", "--arch", "arches/thin.cfg",
                        "--resolution", "0.1", "-j", "2"};
  run_both(aq_cmd_capacity, args, sizeof args / sizeof args[0], "--fragility", &o);
  aq_check(same_file(o.p[2], o.p[3]), "fragility byte-identical");
  outs_remove(&o);
}
