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

AQ_TEST(farm_main_job_equals_the_suite)
{
  char dir[] = "/tmp/aq_farm_XXXXXX", t1[64], t2[64], h1[64], h2[64];
  if (!aq_check(mkdtemp(dir) != NULL, "temporary directory"))
    return;
  snprintf(t1, sizeof t1, "%s/a.tsv", dir);
  snprintf(t2, sizeof t2, "%s/b.tsv", dir);
  snprintf(h1, sizeof h1, "%s/a.h5", dir);
  snprintf(h2, sizeof h2, "%s/b.h5", dir);
  const char *common[] = {"tests/data/records/ARL360.at2", "tests/data/records/CHY028-N.AT2",
                          "tests/data/records/IELC180.AT2", "--arch", "arches/oppenheim.cfg",
                          "--arch", "arches/thin.cfg", "--scale", "0.5,2.385",
                          "--polarity", "both", "-j", "2", "-q"};
  const char *a1[24] = {"archquake"}, *a2[24] = {"archquake"};
  size_t nc = sizeof common / sizeof common[0];
  for (size_t i = 0; i < nc; i++)
    a1[i + 1] = a2[i + 1] = common[i];
  const char *o1[] = {"--text", t1, "-o", h1}, *o2[] = {"--text", t2, "-o", h2};
  for (size_t i = 0; i < 4; i++) {
    a1[nc + 1 + i] = o1[i];
    a2[nc + 1 + i] = o2[i];
  }
  fake_tasks = 0;
  int r1 = run_cmd(aq_cmd_run, a1, 0), r2 = run_cmd(aq_cmd_run, a2, 1);
  aq_check(r1 == 0 && r2 == 0, "exit status: %d plain, %d farmed", r1, r2);
  aq_check(fake_tasks == 6, "tasks: one per (record, arch): %zu", fake_tasks);
  aq_check(same_file(t1, t2), "TSV byte-identical");
  char cmp[200], out[4096], err[4096];
  snprintf(cmp, sizeof cmp, "compare %s %s", h1, h2);
  int rc = aq_test_run(cmp, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "compare finds the results files equal (%d): %s", rc, err);
  unlink(t1);
  unlink(t2);
  unlink(h1);
  unlink(h2);
  rmdir(dir);
}

AQ_TEST(farm_capacity_equals_the_command)
{
  char dir[] = "/tmp/aq_farm_XXXXXX", t1[64], t2[64], f1[64], f2[64];
  if (!aq_check(mkdtemp(dir) != NULL, "temporary directory"))
    return;
  snprintf(t1, sizeof t1, "%s/a.tsv", dir);
  snprintf(t2, sizeof t2, "%s/b.tsv", dir);
  snprintf(f1, sizeof f1, "%s/a.frag", dir);
  snprintf(f2, sizeof f2, "%s/b.frag", dir);
  const char *a1[] = {"capacity", "tests/data/records/ARL360.at2",
                      "tests/data/records/CHY028-N.AT2", "tests/data/records/IELC180.AT2",
                      "--arch", "arches/oppenheim.cfg", "--arch", "arches/thin.cfg",
                      "--resolution", "0.1", "-j", "2", "--text", t1, "--fragility", f1,
                      NULL};
  const char *a2[] = {"capacity", "tests/data/records/ARL360.at2",
                      "tests/data/records/CHY028-N.AT2", "tests/data/records/IELC180.AT2",
                      "--arch", "arches/oppenheim.cfg", "--arch", "arches/thin.cfg",
                      "--resolution", "0.1", "-j", "2", "--text", t2, "--fragility", f2,
                      NULL};
  fake_tasks = 0;
  int r1 = run_cmd(aq_cmd_capacity, a1, 0), r2 = run_cmd(aq_cmd_capacity, a2, 1);
  aq_check(r1 == 0 && r2 == 0, "exit status: %d plain, %d farmed", r1, r2);
  aq_check(fake_tasks == 6, "tasks: one per (record, arch): %zu", fake_tasks);
  aq_check(same_file(t1, t2), "TSV byte-identical");
  aq_check(same_file(f1, f2), "fragility byte-identical");
  unlink(t1);
  unlink(t2);
  unlink(f1);
  unlink(f2);
  rmdir(dir);
}
