/* test_util.c: src/util: the thread pool runs every task once, whatever
 * the threads; values as bytes come back bit for bit and a cut or
 * out-of-range input is refused where it goes wrong; an output exists under
 * its target's name only once complete, and a signal removes its
 * temporary (the pulse command's used to escape it). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "util/util.h"

enum { NTASK = 1000 };

typedef struct {
  int count[NTASK];
  pthread_mutex_t lock;
  pthread_t who[NTASK];
} tally;

static void count_task(void *ctx, size_t k)
{
  tally *t = ctx;
  pthread_mutex_lock(&t->lock);
  t->count[k]++;
  t->who[k] = pthread_self();
  pthread_mutex_unlock(&t->lock);
}

AQ_TEST(util_pool_for_runs_every_task_once)
{
  for (long threads = 1; threads <= 5; threads++) {
    static tally t;
    memset(t.count, 0, sizeof t.count);
    pthread_mutex_init(&t.lock, NULL);
    aq_error e;
    aq_status s = aq_pool_for(NTASK, threads, count_task, &t, &e);
    size_t once = 0, here = 0;
    for (size_t k = 0; k < NTASK; k++) {
      once += t.count[k] == 1;
      here += pthread_equal(t.who[k], pthread_self()) != 0;
    }
    aq_check(s == AQ_OK && once == NTASK, "-j %ld: %zu of %d tasks run exactly once", threads,
             once, NTASK);
    if (threads == 1)
      aq_check(here == NTASK, "one thread: the calling one ran all (%zu)", here);
    pthread_mutex_destroy(&t.lock);
  }
  static tally none;
  aq_check(aq_pool_for(0, 4, count_task, &none, NULL) == AQ_OK && none.count[0] == 0,
           "no task: nothing runs");
}

static void mark_worker(void *ctx, size_t k)
{
  count_task(ctx, k);
}

AQ_TEST(util_pool_start_runs_each_worker_with_its_number)
{
  static tally t;
  memset(t.count, 0, sizeof t.count);
  pthread_mutex_init(&t.lock, NULL);
  size_t started = 0;
  aq_pool *p = aq_pool_start(7, mark_worker, &t, &started);
  aq_pool_join(p);
  size_t once = 0;
  for (size_t k = 0; k < 7; k++)
    once += t.count[k] == 1;
  aq_check(p != NULL && started == 7 && once == 7 && t.count[7] == 0,
           "7 workers numbered 0..6, each once: %zu started, %zu once", started, once);
  pthread_mutex_destroy(&t.lock);
  aq_pool_join(NULL);
}

AQ_TEST(util_bytes_round_trip_and_refusals)
{
  aq_bytes_out w = {0};
  double x = -0.1234567890123456789, inf = INFINITY;
  aq_bytes_put_i64(&w, -7);
  aq_bytes_put_f64(&w, x);
  aq_bytes_put_f64(&w, inf);
  aq_bytes_put_str(&w, "records/ARL360.at2", 0);
  aq_bytes_put_str(&w, "truncated here", 10); /* what a char[10] holds: 9 bytes */
  aq_bytes_put_str(&w, NULL, 0);
  for (int k = 0; k < 300; k++) /* past the first 1024-byte block */
    aq_bytes_put_i64(&w, k);
  aq_check(!w.oom && w.n == 8 + 8 + 8 + (8 + 18) + (8 + 9) + 8 + 300 * 8,
           "the layout: %zu bytes", w.n);
  aq_bytes_in r = {w.data, w.n, 0, NULL, 0};
  char s1[64], s2[10], *s3 = NULL;
  int64_t i = aq_bytes_get_int(&r, -10, 10, "i");
  double y = aq_bytes_get_f64(&r, "x"), z = aq_bytes_get_f64(&r, "inf");
  aq_bytes_get_str(&r, s1, sizeof s1, NULL, "s1");
  aq_bytes_get_str(&r, s2, sizeof s2, NULL, "s2");
  aq_bytes_get_str(&r, NULL, 0, &s3, "s3");
  int64_t sum = 0;
  for (int k = 0; k < 300; k++)
    sum += aq_bytes_get_i64(&r, "k");
  aq_check(!r.bad && r.at == w.n && i == -7 && memcmp(&y, &x, sizeof x) == 0 && z == inf &&
               strcmp(s1, "records/ARL360.at2") == 0 && strcmp(s2, "truncate") != 0 &&
               strcmp(s2, "truncated") == 0 && s3 && s3[0] == '\0' && sum == 299 * 300 / 2,
           "read back: %lld %.17g \"%s\" \"%s\" sum %lld", (long long)i, y, s1, s2,
           (long long)sum);
  free(s3);
  /* out of range: named, at the value's offset; later reads fail too */
  r = (aq_bytes_in){w.data, w.n, 0, NULL, 0};
  aq_bytes_get_int(&r, 0, 10, "status");
  double after = aq_bytes_get_f64(&r, "x");
  aq_check(r.bad && strcmp(r.bad, "status") == 0 && r.bad_at == 0 && after == 0,
           "-7 out of 0..10 refused as \"%s\" at %zu", r.bad ? r.bad : "", r.bad_at);
  /* a string longer than its array */
  r = (aq_bytes_in){w.data, w.n, 24, NULL, 0};
  char small[8];
  aq_check(aq_bytes_get_str(&r, small, sizeof small, NULL, "name") != 0 && r.bad_at == 24 &&
               small[0] == '\0',
           "an 18-byte string refused for char[8] at byte %zu", r.bad_at);
  /* every cut of the first 50 bytes fails where the input ends */
  size_t refused = 0;
  for (size_t k = 0; k < 50; k++) {
    aq_bytes_in c = {w.data, k, 0, NULL, 0};
    aq_bytes_get_i64(&c, "a");
    aq_bytes_get_f64(&c, "b");
    aq_bytes_get_f64(&c, "c");
    aq_bytes_get_str(&c, s1, sizeof s1, NULL, "d");
    refused += c.bad != NULL && c.at <= k;
  }
  aq_check(refused == 50, "every cut refused, never read past its end: %zu of 50", refused);
  /* a count larger than what is left */
  aq_bytes_out h = {0};
  aq_bytes_put_i64(&h, INT64_MAX / 2);
  r = (aq_bytes_in){h.data, h.n, 0, NULL, 0};
  aq_check(aq_bytes_get_count(&r, 8, "n") == 0 && r.bad && strcmp(r.bad, "n") == 0,
           "a huge count refused");
  free(h.data);
  free(w.data);
}

static int exists(const char *p)
{
  struct stat sb;
  return stat(p, &sb) == 0;
}

AQ_TEST(util_outfile_renamed_only_when_complete)
{
  char dir[512], target[700], tmp[800];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(target, sizeof target, "%s/out.tsv", dir);
  aq_outfile_temp_name(target, tmp, sizeof tmp);
  char want[800];
  snprintf(want, sizeof want, "%s.tmp.%ld", target, (long)getpid());
  aq_check(strcmp(tmp, want) == 0, "the temporary's name: %s", tmp);
  /* an existing target stays untouched until the commit */
  FILE *f = fopen(target, "w");
  fputs("old\n", f);
  fclose(f);
  aq_outfile o;
  aq_error e;
  aq_check(aq_outfile_open(&o, target, &e) == AQ_OK && o.f && exists(tmp), "opened");
  fputs("new\n", o.f);
  char *before = aq_test_read_file(target, NULL);
  aq_check(before && strcmp(before, "old\n") == 0, "the target untouched while writing");
  free(before);
  aq_check(aq_outfile_commit(&o, &e) == AQ_OK && !exists(tmp), "committed");
  char *after = aq_test_read_file(target, NULL);
  aq_check(after && strcmp(after, "new\n") == 0, "the target replaced whole");
  free(after);
  /* aborted: nothing new, no temporary */
  aq_check(aq_outfile_open(&o, target, &e) == AQ_OK, "opened again");
  fputs("partial", o.f);
  aq_outfile_abort(&o);
  after = aq_test_read_file(target, NULL);
  aq_check(after && strcmp(after, "new\n") == 0 && !exists(tmp),
           "aborted: the target as it was, no temporary");
  free(after);
  aq_outfile_abort(&o); /* released: nothing happens */
  /* a temporary of that name is not ours: refused, and left alone */
  f = fopen(tmp, "w");
  fputs("someone's\n", f);
  fclose(f);
  aq_check(aq_outfile_open(&o, target, &e) == AQ_EIO && strstr(e.message, tmp) &&
               exists(tmp),
           "an existing temporary refused and kept: %s", e.message);
  unlink(tmp);
  /* a target that is a directory: refused before anything is written */
  char sub[800];
  snprintf(sub, sizeof sub, "%s/adir", dir);
  mkdir(sub, 0777);
  aq_outfile_temp_name(sub, tmp, sizeof tmp);
  aq_check(aq_outfile_open(&o, sub, &e) == AQ_EIO && strstr(e.message, "got a directory") &&
               !exists(tmp),
           "a directory refused, no temporary: %s", e.message);
  /* a target that became one meanwhile cannot be renamed onto: the
   * temporary goes */
  char sub2[800], subf[900];
  snprintf(sub2, sizeof sub2, "%s/bdir", dir);
  aq_outfile_temp_name(sub2, tmp, sizeof tmp);
  aq_check(aq_outfile_open(&o, sub2, &e) == AQ_OK, "opened");
  mkdir(sub2, 0777);
  snprintf(subf, sizeof subf, "%s/x", sub2);
  f = fopen(subf, "w");
  fclose(f);
  aq_check(aq_outfile_commit(&o, &e) == AQ_EIO && strstr(e.message, "rename") && !exists(tmp),
           "a failed rename: reported, no temporary: %s", e.message);
}

AQ_TEST(util_outfile_temporary_removed_on_a_signal)
{
  char dir[512], target[700], tmp[800];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(target, sizeof target, "%s/h.csv", dir);
  int fds[2];
  if (!aq_check(pipe(fds) == 0, "pipe"))
    return;
  pid_t pid = fork();
  if (pid == 0) { /* the child opens an output, says where, and waits to be killed */
    close(fds[0]);
    aq_cleanup_install();
    aq_outfile o;
    if (aq_outfile_open(&o, target, NULL) != AQ_OK)
      _exit(3);
    fputs("partial", o.f);
    fflush(o.f);
    if (write(fds[1], o.tmp, strlen(o.tmp) + 1) < 0)
      _exit(4);
    for (;;)
      pause();
  }
  close(fds[1]);
  ssize_t n = read(fds[0], tmp, sizeof tmp - 1);
  close(fds[0]);
  tmp[n > 0 ? n : 0] = '\0';
  int was = n > 0 && exists(tmp);
  kill(pid, SIGTERM);
  int st = 0;
  waitpid(pid, &st, 0);
  aq_check(was && WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM && !exists(tmp) &&
               !exists(target),
           "SIGTERM: the temporary %s (there before: %d) removed, no target, the child "
           "ended by the signal",
           tmp, was);
}
