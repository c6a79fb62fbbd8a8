/* runner.c: runs every registered test (or those whose names contain
 * argv[1]); last line "N passed, N failed"; exit 1 if any failed.
 * AQ_TEST_STOP_FIRST set: stop after the first failed test (make mutate).
 * A test's folders under build/tmp are removed when it passes, so that a
 * whole run needs little disk; a failed test's stay, to be looked at, and
 * AQ_TEST_KEEP set keeps every one.  The folders of fixtures that several
 * tests use (aq_test_shared_dir) stay to the end of the run, and go then
 * if every test passed. */
#define _XOPEN_SOURCE 700 /* nftw */
#include "check.h"

#include <dirent.h>
#include <ftw.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define AQ_MAX_TESTS 1024

static struct {
  const char *name;
  aq_test_fn fn;
} tests[AQ_MAX_TESTS];
static size_t ntests;
static size_t checks_failed_in_test;
static int verbose;
static const char *current;
static unsigned tmp_made;    /* folders made by aq_test_tmpdir so far */
static unsigned shared_made; /* and by aq_test_shared_dir */

void aq_test_register(const char *name, aq_test_fn fn)
{
  if (ntests < AQ_MAX_TESTS) {
    tests[ntests].name = name;
    tests[ntests].fn = fn;
    ntests++;
  }
}

static void report(int ok, const char *file, int line, const char *what,
                   const char *fmt, va_list ap)
{
  if (ok && !verbose)
    return;
  fprintf(stderr, "%s %s:%d [%s] ", ok ? "  ok" : "FAIL", file, line,
          current ? current : "?");
  vfprintf(stderr, fmt, ap);
  if (what[0])
    fprintf(stderr, " (%s)", what);
  fputc('\n', stderr);
}

int aq_check_(int ok, const char *file, int line, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  report(ok, file, line, "", fmt, ap);
  va_end(ap);
  if (!ok)
    checks_failed_in_test++;
  return ok;
}

int aq_check_rel_(double got, double want, double rel, const char *file,
                  int line, const char *fmt, ...)
{
  double d = fabs(got - want);
  int ok = d <= rel * fabs(want) && !isnan(got) && !isnan(want);
  char what[200];
  snprintf(what, sizeof what, "got %.17g, want %.17g, rel err %.3g > %.3g",
           got, want, want != 0 ? d / fabs(want) : d, rel);
  if (ok)
    snprintf(what, sizeof what, "got %.17g, want %.17g, rel err %.3g <= %.3g", got,
             want, want != 0 ? d / fabs(want) : d, rel);
  va_list ap;
  va_start(ap, fmt);
  report(ok, file, line, what, fmt, ap);
  va_end(ap);
  if (!ok)
    checks_failed_in_test++;
  return ok;
}

int aq_check_abs_(double got, double want, double tol, const char *file,
                  int line, const char *fmt, ...)
{
  double d = fabs(got - want);
  int ok = d <= tol && !isnan(got) && !isnan(want);
  char what[200];
  snprintf(what, sizeof what, "got %.17g, want %.17g, abs err %.3g%s%.3g",
           got, want, d, ok ? " <= " : " > ", tol);
  va_list ap;
  va_start(ap, fmt);
  report(ok, file, line, what, fmt, ap);
  va_end(ap);
  if (!ok)
    checks_failed_in_test++;
  return ok;
}

const char *aq_test_bin(void)
{
  const char *b = getenv("AQ_BIN");
  return b && *b ? b : "build/san/archquake";
}

static void slurp(const char *path, char *buf, size_t cap)
{
  if (!buf || cap == 0)
    return;
  buf[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (!f)
    return;
  size_t n = fread(buf, 1, cap - 1, f);
  buf[n] = '\0';
  fclose(f);
}

int aq_test_run(const char *args, char *out, size_t out_cap, char *errbuf,
                size_t err_cap)
{
  char dir[512], o[600], e[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(o, sizeof o, "%s/stdout", dir);
  snprintf(e, sizeof e, "%s/stderr", dir);
  size_t len = strlen(args) + strlen(aq_test_bin()) + 2 * sizeof o + 64;
  char *cmd = malloc(len);
  if (!cmd)
    return -1;
  snprintf(cmd, len, "%s %s </dev/null >%s 2>%s", aq_test_bin(), args, o, e);
  int rc = system(cmd);
  free(cmd);
  slurp(o, out, out_cap);
  slurp(e, errbuf, err_cap);
  if (rc == -1 || !WIFEXITED(rc))
    return -1;
  return WEXITSTATUS(rc);
}

int aq_test_sh(const char *cmd, char *out, size_t cap)
{
  size_t len = strlen(cmd) + 16;
  char *full = malloc(len);
  if (!full)
    return -1;
  snprintf(full, len, "(%s) 2>&1", cmd);
  FILE *p = popen(full, "r");
  free(full);
  if (!p)
    return -1;
  char sink[4096];
  size_t n = 0, got;
  while ((got = fread(out && n + 1 < cap ? out + n : sink, 1,
                      out && n + 1 < cap ? cap - 1 - n : sizeof sink, p)) > 0)
    if (out && n + 1 < cap)
      n += got;
  if (out && cap)
    out[n] = '\0';
  int rc = pclose(p);
  return rc == -1 || !WIFEXITED(rc) ? -1 : WEXITSTATUS(rc);
}

char *aq_test_read_file(const char *path, size_t *n)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  long len = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
  char *b = len >= 0 && fseek(f, 0, SEEK_SET) == 0 ? malloc((size_t)len + 1) : NULL;
  if (b && fread(b, 1, (size_t)len, f) != (size_t)len) {
    free(b);
    b = NULL;
  }
  fclose(f);
  if (b) {
    b[len] = '\0';
    if (n)
      *n = (size_t)len;
  }
  return b;
}

size_t aq_test_count_lines(const char *s)
{
  size_t n = 0;
  for (; *s; s++)
    n += *s == '\n';
  return n;
}

const char *aq_test_tsv_field(const char *tsv, int row, int k, char *buf, size_t n)
{
  const char *p = tsv;
  while (p && *p == '#') { /* comment lines before the header */
    p = strchr(p, '\n');
    if (p)
      p++;
  }
  for (int r = 0; r < row && p; r++) {
    p = strchr(p, '\n');
    if (p)
      p++;
  }
  for (int i = 0; i < k && p; i++) {
    p = strpbrk(p, "\t\n");
    p = p && *p == '\t' ? p + 1 : NULL;
  }
  buf[0] = '\0';
  if (!p)
    return buf;
  size_t m = strcspn(p, "\t\n");
  snprintf(buf, n, "%.*s", (int)(m < n ? m : n - 1), p);
  return buf;
}

int aq_test_copy_prefix(const char *from, const char *to, size_t num, size_t den)
{
  size_t n = 0;
  char *b = aq_test_read_file(from, &n);
  FILE *f = b ? fopen(to, "wb") : NULL;
  size_t len = den ? n / den * num + n % den * num / den : 0;
  int ok = f && fwrite(b, 1, len, f) == len;
  if (f)
    ok &= fclose(f) == 0;
  free(b);
  return ok;
}

int aq_test_edited_copy(const char *from, const char *a, const char *b, const char *dir,
                        const char *name, char *out, size_t cap)
{
  size_t n;
  char *buf = aq_test_read_file(from, &n);
  if (!aq_check(buf != NULL, "read %s", from))
    return 0;
  snprintf(out, cap, "%s/%s", dir, name);
  char *at = a ? strstr(buf, a) : NULL;
  int ok = !a || aq_check(at != NULL, "%s holds \"%s\"", from, a);
  FILE *f = ok ? fopen(out, "wb") : NULL;
  ok = f != NULL;
  if (ok && at) {
    size_t pre = (size_t)(at - buf), la = strlen(a);
    ok = fwrite(buf, 1, pre, f) == pre && fputs(b, f) >= 0 &&
         fwrite(at + la, 1, n - pre - la, f) == n - pre - la;
  } else if (ok) {
    ok = fwrite(buf, 1, n, f) == n;
  }
  if (f && fclose(f) != 0)
    ok = 0;
  free(buf);
  return ok;
}

int aq_test_count_names(const char *dir, const char *part)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strstr(e->d_name, part) != NULL;
  if (d)
    closedir(d);
  return n;
}

int aq_test_same_outputs(const char *dir, const char *a, const char *b)
{
  char pa[600], pb[600], args[1400];
  size_t na = 0, nb = 0;
  snprintf(pa, sizeof pa, "%s/%s.tsv", dir, a);
  snprintf(pb, sizeof pb, "%s/%s.tsv", dir, b);
  char *x = aq_test_read_file(pa, &na), *y = aq_test_read_file(pb, &nb);
  int same = x && y && na == nb && na > 500 && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  snprintf(args, sizeof args, "compare %s/%s.h5 %s/%s.h5 --rtol 0 --atol 0", dir, a, dir, b);
  return same && aq_test_run(args, NULL, 0, NULL, 0) == 0;
}

static void tmp_name(char *buf, size_t cap, int shared, unsigned k)
{
  snprintf(buf, cap, "build/tmp/%s-%ld-%u", shared ? "shared" : current ? current : "t",
           (long)getpid(), k);
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
  (void)st, (void)flag, (void)ftw;
  remove(path);
  return 0;
}

/* Remove the folders made from the from-th to the to-th (excluded). */
static void remove_tmp(int shared, unsigned from, unsigned to)
{
  char dir[512];
  for (unsigned k = from; k < to; k++) {
    tmp_name(dir, sizeof dir, shared, k);
    nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS);
  }
}

static const char *make_dir(char *buf, size_t cap, int shared)
{
  mkdir("build", 0777);
  mkdir("build/tmp", 0777);
  tmp_name(buf, cap, shared, shared ? shared_made++ : tmp_made++);
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", buf, buf);
  if (system(cmd) != 0)
    fprintf(stderr, "runner: cannot make %s\n", buf);
  return buf;
}

const char *aq_test_tmpdir(char *buf, size_t cap)
{
  return make_dir(buf, cap, 0);
}

const char *aq_test_shared_dir(char *buf, size_t cap)
{
  return make_dir(buf, cap, 1);
}

const char *aq_test_tmpfile(char *buf, size_t cap, const char *name, const char *text)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(buf, cap, "%s/%s", dir, name);
  FILE *f = fopen(buf, "w");
  if (!aq_check(f != NULL, "write %s", buf))
    return NULL;
  fputs(text, f);
  return fclose(f) == 0 ? buf : NULL;
}

int main(int argc, char **argv)
{
  verbose = getenv("AQ_TEST_VERBOSE") != NULL;
  const int stop_first = getenv("AQ_TEST_STOP_FIRST") != NULL;
  const int keep = getenv("AQ_TEST_KEEP") != NULL;
  size_t passed = 0, failed = 0;
  for (size_t i = 0; i < ntests; i++) {
    if (argc > 1 && !strstr(tests[i].name, argv[1]))
      continue;
    current = tests[i].name;
    checks_failed_in_test = 0;
    const unsigned tmp_from = tmp_made;
    tests[i].fn();
    if (checks_failed_in_test) {
      failed++;
      fprintf(stderr, "FAIL %s (%zu checks failed)\n", tests[i].name,
              checks_failed_in_test);
      if (stop_first) {
        fflush(stderr);
        break;
      }
    } else {
      passed++;
      if (!keep)
        remove_tmp(0, tmp_from, tmp_made);
      if (verbose)
        fprintf(stderr, "PASS %s\n", tests[i].name);
    }
    fflush(stderr);
  }
  if (!failed && !keep)
    remove_tmp(1, 0, shared_made);
  printf("%zu passed, %zu failed\n", passed, failed);
  return failed ? 1 : 0;
}
