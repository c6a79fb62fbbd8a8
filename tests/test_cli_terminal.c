/* test_cli_terminal.c: the command line as a user meets it: the progress
 * line on a real terminal (a pseudo-terminal), the usage without arguments,
 * -h and help, unknown options named as typed, files named "-...", and the
 * TSV's nan read back by pandas (or Python's csv and float). */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"

/* Run the CLI with stdout and stderr on a new pseudo-terminal (stdin
 * /dev/null); the bytes the terminal received go to buf.  Returns the exit
 * status, or -1. */
static int run_on_pty(char *const *args, char *buf, size_t cap)
{
  buf[0] = '\0';
  int m = posix_openpt(O_RDWR | O_NOCTTY);
  if (m < 0 || grantpt(m) != 0 || unlockpt(m) != 0) {
    if (m >= 0)
      close(m);
    return -1;
  }
  char sname[256];
  const char *sn = ptsname(m);
  snprintf(sname, sizeof sname, "%s", sn ? sn : "");
  pid_t pid = fork();
  if (pid < 0) {
    close(m);
    return -1;
  }
  if (pid == 0) {
    setsid();
    int s = open(sname, O_RDWR);
    int dn = open("/dev/null", O_RDONLY);
    if (s < 0 || dn < 0)
      _exit(127);
    dup2(dn, 0);
    dup2(s, 1);
    dup2(s, 2);
    close(m);
    execv(args[0], args);
    _exit(127);
  }
  size_t len = 0;
  for (;;) {
    ssize_t k = read(m, buf + len, cap - 1 - len);
    if (k > 0) {
      len += (size_t)k;
      if (len + 1 >= cap)
        break;
    } else if (k < 0 && errno == EINTR) {
      continue;
    } else {
      break; /* EIO: the child closed the terminal */
    }
  }
  buf[len] = '\0';
  close(m);
  int st;
  if (waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
    return -1;
  return WEXITSTATUS(st);
}

/* What a terminal shows for bytes: \r moves to column 0, ESC [ K erases to
 * the end of the line, other ESC [ ... sequences are ignored, \n ends a
 * line.  Lines are written into out, separated by \n. */
static void screen(const char *in, char *out, size_t cap)
{
  char line[4096];
  size_t col = 0, llen = 0, o = 0;
  out[0] = '\0';
  for (const char *p = in;; p++) {
    if (*p == '\0' || *p == '\n') {
      if (o + llen + 2 < cap) {
        memcpy(out + o, line, llen);
        o += llen;
        out[o++] = '\n';
        out[o] = '\0';
      }
      if (*p == '\0')
        break;
      col = llen = 0;
    } else if (*p == '\r') {
      col = 0;
    } else if (*p == '\033' && p[1] == '[') {
      p += 2;
      while (*p && (*p < '@' || *p > '~'))
        p++;
      if (*p == 'K')
        llen = col;
      if (!*p)
        p--;
    } else if (col < sizeof line) {
      line[col++] = *p;
      if (col > llen)
        llen = col;
    }
  }
}

static size_t count_str(const char *s, const char *what)
{
  size_t n = 0;
  for (const char *p = strstr(s, what); p; p = strstr(p + 1, what))
    n++;
  return n;
}

AQ_TEST(cli_progress_line_never_mixes_with_rows)
{
  static const char *const recs[] = {
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
  enum { NREC = sizeof recs / sizeof recs[0], NSCALE = 4, NARCH = 2 };
  char bin[PATH_MAX];
  if (!aq_check(realpath(aq_test_bin(), bin) != NULL, "binary %s",
                aq_test_bin()))
    return;
  char *args[64];
  int k = 0;
  args[k++] = bin;
  args[k++] = "-j";
  args[k++] = "1";
  args[k++] = "--model"; /* the slow reference: the progress line shows */
  args[k++] = "ode";
  args[k++] = "--scale";
  args[k++] = "1,2,3,4";
  args[k++] = "--polarity";
  args[k++] = "normal";
  for (int i = 0; i < NREC; i++)
    args[k++] = (char *)recs[i];
  args[k++] = "--arch";
  args[k++] = "arches/oppenheim.cfg";
  args[k++] = "--arch";
  args[k++] = "arches/thin.cfg";
  args[k] = NULL;
  size_t cap = 1 << 20;
  char *raw = malloc(cap), *shown = malloc(cap);
  if (!aq_check(raw && shown, "alloc")) {
    free(raw);
    free(shown);
    return;
  }
  int rc = run_on_pty(args, raw, cap);
  screen(raw, shown, cap);
  aq_check(rc == 0, "exit %d", rc);
  /* the line was drawn (else this proves nothing) ... */
  aq_check(count_str(raw, " runs, ") >= 1, "progress lines drawn: %zu",
           count_str(raw, " runs, "));
  /* ... and the screen holds the header and whole rows only */
  size_t rows = 0, other = 0;
  char *save = NULL;
  for (char *l = strtok_r(shown, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) {
    if (strncmp(l, "tests/data/records/", 19) == 0 && !strstr(l, " runs, "))
      rows++;
    else if (strncmp(l, "record ", 7) != 0)
      aq_check(++other == 0, "a line that is neither header nor row: \"%.120s\"", l);
  }
  aq_check(rows == NREC * NSCALE * NARCH, "rows on the screen: %zu", rows);
  free(raw);
  free(shown);
}

AQ_TEST(cli_usage_without_arguments_h_and_help)
{
  char out[16384], err[4096];
  static const struct {
    const char *args;
    int status;
  } cases[] = {{"", 2}, {"-h", 0}, {"help", 0}, {"--help", 0}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    int rc = aq_test_run(cases[i].args, out, sizeof out, err, sizeof err);
    aq_check(rc == cases[i].status && strstr(out, "usage: archquake [OPTIONS]") &&
                 strstr(out, "archquake compare") && strstr(out, "--arch FILE"),
             "\"archquake %s\": exit %d, stdout %.80s, stderr %.200s",
             cases[i].args, rc, out, err);
  }
  int rc = aq_test_run("help info", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "usage: archquake info"), "help info: %d %.80s",
           rc, out);
  rc = aq_test_run("help nonsense", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "help: expected a command") &&
               strstr(err, "\"nonsense\""),
           "help nonsense: %d %s", rc, err);
}

AQ_TEST(cli_unknown_option_named_as_typed)
{
  char out[4096], err[4096];
  /* the record before the cluster: getopt moves it, and the old message
   * named it ("IELC180.AT2: unknown option") */
  int rc = aq_test_run("tests/data/records/IELC180.AT2 -ab --arch arches/thin.cfg",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "archquake: -a: unknown option") &&
               strstr(err, "archquake: -b: unknown option") &&
               !strstr(err, "IELC180.AT2: unknown") &&
               !strstr(err, "archquake: archquake") && !strstr(err, "-ab: unknown"),
           "-ab: exit %d, %s", rc, err);
  rc = aq_test_run("info -zq tests/data/records/IELC180.AT2", out, sizeof out, err,
                   sizeof err);
  /* -q is the main job's: named as an option of another command */
  aq_check(rc == 2 && strstr(err, "-z: unknown") &&
               strstr(err, "info: -q: not an option of this command (only of the main job)") &&
               !strstr(err, "IELC180.AT2: unknown"),
           "info -zq: exit %d, %s", rc, err);
  rc = aq_test_run("info --bogus tests/data/records/IELC180.AT2", out, sizeof out,
                   err, sizeof err);
  aq_check(rc == 2 && strstr(err, "archquake: --bogus: unknown"),
           "--bogus: exit %d, %s", rc, err);
  /* every command points to its own help, a command that works as typed */
  static const char *const cmds[] = {"",       "capacity ", "compare ", "domain ",
                                     "info ",  "mechanism ", "pulse "};
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    char args[64], want[80];
    snprintf(args, sizeof args, "%s--bogus", cmds[k]);
    snprintf(want, sizeof want, "(see 'archquake %s--help')", cmds[k]);
    rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && strstr(err, want), "%s: exit %d, %s", args, rc, err);
    snprintf(args, sizeof args, "%s--help", cmds[k]);
    aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0, "%s", args);
  }
}

AQ_TEST(cli_file_named_like_an_option_gets_a_hint)
{
  char dir[512], bin[PATH_MAX], cmd[3 * PATH_MAX], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  if (!aq_check(realpath(aq_test_bin(), bin) != NULL, "binary"))
    return;
  snprintf(path, sizeof path, "%s/-x.AT2", dir);
  snprintf(cmd, sizeof cmd, "cp tests/data/records/IELC180.AT2 '%s'", path);
  aq_check(system(cmd) == 0, "copy");
  snprintf(cmd, sizeof cmd,
           "cd '%s' && '%s' info -x.AT2 >out 2>err; echo $? >rc; "
           "'%s' info -- -x.AT2 >out2 2>err2; echo $? >rc2",
           dir, bin, bin);
  aq_check(system(cmd) == 0, "run");
  char f[800];
  snprintf(f, sizeof f, "%s/err", dir);
  char *err = aq_test_read_file(f, NULL);
  snprintf(f, sizeof f, "%s/rc", dir);
  char *rc = aq_test_read_file(f, NULL);
  snprintf(f, sizeof f, "%s/out2", dir);
  char *out2 = aq_test_read_file(f, NULL);
  snprintf(f, sizeof f, "%s/rc2", dir);
  char *rc2 = aq_test_read_file(f, NULL);
  aq_check(err && rc && atoi(rc) == 2 && strstr(err, "archquake: -x.AT2: ") &&
               strstr(err, "'--'") && strstr(err, "./-x.AT2") &&
               count_str(err, "-x.AT2: ") == 1 && !strstr(err, "-A: unknown"),
           "hint: exit %s, %s", rc ? rc : "?", err ? err : "?");
  aq_check(rc2 && atoi(rc2) == 0 && out2 && strstr(out2, "\n-x.AT2\tat2\t4000"),
           "after --: exit %s, %s", rc2 ? rc2 : "?", out2 ? out2 : "?");
  free(err);
  free(rc);
  free(out2);
  free(rc2);
}

/* The TSV read back by pandas (docs/tsv.md): every nan cell is a float NaN,
 * the numeric columns are float64.  Without pandas, Python's csv and float
 * (which also read "nan").  The counts come from the TSV text here. */
AQ_TEST(cli_tsv_nan_reads_back_in_pandas)
{
  char dir[512], tsv[700], out[4096], err[4096], cmd[3000];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(tsv, sizeof tsv, "%s/r.tsv", dir);
  snprintf(cmd, sizeof cmd,
           "tests/data/records/IELC180.AT2 tests/data/records/TCU052-N.AT2 "
           "--arch arches/thick.cfg --arch arches/thin.cfg --scale 0.5,2 --text %s",
           tsv);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  char *text = aq_test_read_file(tsv, NULL);
  if (!aq_check(rc == 0 && text, "run: exit %d, %s", rc, err)) {
    free(text);
    return;
  }
  size_t nan_cells = count_str(text, "\tnan\t") + count_str(text, "\tnan\n");
  size_t lines = count_str(text, "\n");
  /* 2 records x 2 arches x 2 scales x both polarities (fixed arches), and the header */
  aq_check(nan_cells >= 1 && lines == 17, "the TSV has %zu nan cells, %zu lines",
           nan_cells, lines);
  free(text);
  static const char pandas_py[] =
      "import sys, pandas as pd\n"
      "d = pd.read_csv(sys.argv[1], sep='\\t')\n"
      "print(len(d), int(d.isna().sum().sum()), d['collapse_time_s'].dtype,"
      " d['peak_rotation_rad'].dtype)\n";
  static const char csv_py[] =
      "import sys, csv, math\n"
      "rows = list(csv.reader(open(sys.argv[1]), delimiter='\\t'))\n"
      "def num(x):\n"
      "    try:\n"
      "        return float(x)\n"
      "    except ValueError:\n"
      "        return None\n"
      "n = sum(1 for r in rows[1:] for x in r if num(x) is not None and math.isnan(num(x)))\n"
      "print(len(rows) - 1, n, 'float64', 'float64')\n";
  char py[800];
  snprintf(py, sizeof py, "%s/check.py", dir);
  const char *found = NULL;
  static const char *const pythons[] = {"python3", "/usr/bin/python3"};
  for (size_t i = 0; i < 2 && !found; i++) {
    snprintf(cmd, sizeof cmd, "%s -c 'import pandas' >/dev/null 2>&1", pythons[i]);
    if (system(cmd) == 0)
      found = pythons[i];
  }
  FILE *f = fopen(py, "w");
  if (!aq_check(f != NULL, "write %s", py))
    return;
  fputs(found ? pandas_py : csv_py, f);
  fclose(f);
  if (!found)
    fprintf(stderr, "note: cli_tsv_nan_reads_back_in_pandas: no pandas; "
                    "Python's csv and float instead\n");
  snprintf(cmd, sizeof cmd, "%s %s %s", found ? found : "python3", py, tsv);
  FILE *p = popen(cmd, "r");
  char line[256] = "";
  if (!aq_check(p != NULL, "popen %s", cmd))
    return;
  if (!fgets(line, sizeof line, p))
    line[0] = '\0';
  int pst = pclose(p);
  size_t nrow = 0, nnan = 0;
  char t1[32] = "", t2[32] = "";
  int got = sscanf(line, "%zu %zu %31s %31s", &nrow, &nnan, t1, t2);
  aq_check(pst == 0 && got == 4 && nrow == 16 && nnan == nan_cells &&
               strcmp(t1, "float64") == 0 && strcmp(t2, "float64") == 0,
           "%s: \"%s\" (want 16 rows, %zu NaN)", found ? "pandas" : "csv", line,
           nan_cells);
}
