/* test_arch_cache.c: built arches kept on disk (src/job/arch_cache.h,
 * arch.h aq_arch_load_stored, docs/cache.md).  Every shipped arch read
 * back from the cache is the arch built without it: each path's constants,
 * its tables and pieces evaluated along the path, the search's minimum,
 * the drawing, bit for bit.  An entry is used only for its own sources
 * (another .cfg's entry, or that of the same .cfg with another joints
 * file, put under this one's name is a miss); a corrupt or truncated entry
 * is a miss with one note, and the arch is built and stored again.  The
 * main job's TSV and results file are identical with --no-cache, with the
 * cache filling and with it warm, on every shipped arch. */
#define _POSIX_C_SOURCE 200809L
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../src/arch/arch.h"
#include "../src/arch/model.h"
#include "../src/job/arch_cache.h"
#include "../src/util/diskcache.h"
#include "check.h"


/* Field by field (the structs have padding). */
static int same_set(const aq_hinge_set *a, const aq_hinge_set *b)
{
  return memcmp(a->joint, b->joint, sizeof a->joint) == 0 &&
         memcmp(a->face, b->face, sizeof a->face) == 0;
}

static int same_piece(const aq_path_piece *a, const aq_path_piece *b)
{
  size_t n = (AQ_PIECE_MAX_DEG + 1) * sizeof(double);
  return a->s_lo == b->s_lo && a->s_hi == b->s_hi && a->s_ref == b->s_ref &&
         a->iscale == b->iscale && a->deg == b->deg && a->has_g == b->has_g &&
         !memcmp(a->x, b->x, n) && !memcmp(a->y, b->y, n) && !memcmp(a->dx, b->dx, n) &&
         !memcmp(a->dy, b->dy, n) && !memcmp(a->m, b->m, n) && !memcmp(a->gc, b->gc, n) &&
         !memcmp(a->ga, b->ga, n) && !memcmp(a->gb, b->gb, n);
}

/* Points along each path where both arches are evaluated. */
enum { NPOINTS = 257 };

/* 1 if paths p and q give the same bits: constants, the tables at NPOINTS
 * points, the exact evaluation, the pieces in both directions. */
static int same_path(const aq_path *p, const aq_path *q, const char *what)
{
  int ok = aq_check(p->mass_kg == q->mass_kg && p->g_mps2 == q->g_mps2 &&
                        p->lambda0 == q->lambda0 && p->s_c_rad == q->s_c_rad &&
                        p->act_sign == q->act_sign && p->q_sign == q->q_sign &&
                        p->admissible == q->admissible &&
                        p->impact_vel_ratio == q->impact_vel_ratio &&
                        p->x_mono_rad == q->x_mono_rad && strcmp(p->name, q->name) == 0 &&
                        (p->piece == NULL) == (q->piece == NULL),
                    "%s: the path's constants (lambda0 %.17g, %.17g; s_c %.17g, %.17g; impact "
                    "%.17g, %.17g)",
                    what, p->lambda0, q->lambda0, p->s_c_rad, q->s_c_rad, p->impact_vel_ratio,
                    q->impact_vel_ratio);
  if (!p->admissible || !q->admissible)
    return ok;
  int pts = 1, pcs = 1;
  for (int i = 0; i < NPOINTS; i++) {
    double s = p->s_c_rad * i / (NPOINTS - 1);
    aq_path_point a, b, ea, eb;
    memset(&a, 0, sizeof a), memset(&b, 0, sizeof b);
    memset(&ea, 0, sizeof ea), memset(&eb, 0, sizeof eb);
    pts &= p->eval(p->ctx, s, &a) == 0 && q->eval(q->ctx, s, &b) == 0 &&
           memcmp(&a, &b, sizeof a) == 0;
    pts &= p->eval_exact(p->ctx, s, &ea) == 0 && q->eval_exact(q->ctx, s, &eb) == 0 &&
           memcmp(&ea, &eb, sizeof ea) == 0;
    for (int dir = -1; dir <= 1 && p->piece; dir += 2) {
      aq_path_piece x, y;
      memset(&x, 0, sizeof x), memset(&y, 0, sizeof y);
      pcs &= p->piece(p->ctx, s, dir, &x) == 0 && q->piece(q->ctx, s, dir, &y) == 0 &&
             same_piece(&x, &y);
    }
  }
  ok &= aq_check(pts, "%s: the tables and the exact path at %d points", what, NPOINTS);
  ok &= aq_check(pcs, "%s: the Taylor pieces at %d points", what, NPOINTS);
  return ok;
}

/* 1 if arch b (read through the cache) is arch a (built), bit for bit in
 * everything the arch gives. */
static int same_arch(const aq_arch *a, const aq_arch *b, const char *file)
{
  char ha[65], hb[65], what[300];
  aq_arch_sha256(a, ha);
  aq_arch_sha256(b, hb);
  int ok = aq_check(strcmp(aq_arch_name(a), aq_arch_name(b)) == 0 && strcmp(ha, hb) == 0 &&
                        strcmp(aq_arch_config_text(a), aq_arch_config_text(b)) == 0 &&
                        aq_arch_dynamics_of(a)->cor == aq_arch_dynamics_of(b)->cor &&
                        aq_arch_dynamics_of(a)->impact == aq_arch_dynamics_of(b)->impact &&
                        aq_arch_dynamics_of(a)->g_mps2 == aq_arch_dynamics_of(b)->g_mps2,
                    "%s: name, text, digest, dynamics", file);
  for (int s = 0; s < 2; s++) {
    const aq_workpath *wa = aq_arch_workpath(a, s), *wb = aq_arch_workpath(b, s);
    snprintf(what, sizeof what, "%s set %d", file, s);
    ok &= aq_check(same_set(aq_arch_hinge_set(a, s), aq_arch_hinge_set(b, s)) &&
                       aq_workpath_end(wa) == aq_workpath_end(wb) &&
                       aq_workpath_table_size(wa) == aq_workpath_table_size(wb) &&
                       aq_workpath_table_error(wa) == aq_workpath_table_error(wb) &&
                       aq_workpath_piece_count(wa) == aq_workpath_piece_count(wb) &&
                       aq_workpath_thrust0(wa) == aq_workpath_thrust0(wb) &&
                       strcmp(aq_workpath_reason(wa), aq_workpath_reason(wb)) == 0 &&
                       same_set(&aq_workpath_mech(wa)->hs, &aq_workpath_mech(wb)->hs),
                   "%s: set, end, table size %zu/%zu, error, pieces %zu/%zu, thrust", what,
                   aq_workpath_table_size(wa), aq_workpath_table_size(wb),
                   aq_workpath_piece_count(wa), aq_workpath_piece_count(wb));
    ok &= same_path(aq_arch_path(a, s), aq_arch_path(b, s), what);
  }
  aq_hinge_set ma, mb;
  double la = 0, lb = 0, lla = 0, llb = 0;
  size_t ja = 0, jb = 0;
  int ka = aq_arch_minimum(a, &ma, &la), kb = aq_arch_minimum(b, &mb, &lb);
  int fa = aq_arch_liftoff(a, &ja, &lla), fb = aq_arch_liftoff(b, &jb, &llb);
  ok &= aq_check(ka == kb && (!ka || (same_set(&ma, &mb) && la == lb)) &&
                     fa == fb && ja == jb && lla == llb &&
                     aq_arch_searched(a) == aq_arch_searched(b),
                 "%s: the search's minimum (%.17g, %.17g), lift-off, searched", file, la, lb);
  aq_arch_drawing da, db;
  aq_arch_drawing_of(a, &da);
  aq_arch_drawing_of(b, &db);
  size_t n = da.voussoirs;
  ok &= aq_check(n == db.voussoirs && da.noutline == db.noutline && da.nfill == db.nfill &&
                     da.nmass == db.nmass &&
                     memcmp(da.joints, db.joints, 4 * (n + 1) * sizeof(double)) == 0 &&
                     memcmp(da.parts, db.parts, 4 * n * sizeof(double)) == 0 &&
                     memcmp(da.outline, db.outline, 2 * da.noutline * sizeof(double)) == 0 &&
                     (!da.nfill || memcmp(da.fill, db.fill, 2 * da.nfill * sizeof(double)) == 0),
                 "%s: the drawing", file);
  return ok;
}

/* The shipped arches (arches, every .cfg), into g (globfree). */
static size_t shipped(glob_t *g)
{
  if (glob("arches/*.cfg", 0, NULL, g) != 0)
    return 0;
  return g->gl_pathc;
}

AQ_TEST(arch_cache_round_trip_bit_for_bit)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "arches", "test 1");
  glob_t g;
  size_t n = shipped(&g);
  aq_check(c && n >= 9, "store opened, %zu shipped arches", n);
  for (size_t i = 0; c && i < n; i++) {
    const char *file = g.gl_pathv[i];
    aq_arch *ref = NULL, *got[2] = {NULL, NULL};
    aq_error e;
    int hit[2] = {-1, -1};
    aq_check(aq_arch_load(file, &ref, &e) == AQ_OK, "%s built: %s", file, e.message);
    for (int k = 0; k < 2; k++) /* 0 fills the cache, 1 reads it */
      aq_check(aq_arch_cache_load(c, file, NULL, &hit[k], &got[k], &e) == AQ_OK, "%s (%d): %s", file,
               k, e.message);
    aq_check(hit[0] == 0 && hit[1] == 1, "%s: built and stored, then read (%d, %d)", file,
             hit[0], hit[1]);
    for (int k = 0; k < 2 && ref && got[k]; k++)
      same_arch(ref, got[k], file);
    aq_arch_free(ref);
    aq_arch_free(got[0]);
    aq_arch_free(got[1]);
  }
  aq_diskcache_counts k = aq_diskcache_count(c);
  aq_check(k.hits == n && k.misses == n && k.writes == n && k.corrupt == 0,
           "one entry per arch: hits %zu misses %zu writes %zu", k.hits, k.misses, k.writes);
  char *notes = aq_diskcache_notes(c);
  aq_check(notes == NULL, "no note: %s", notes ? notes : "");
  free(notes);
  globfree(&g);
  aq_diskcache_close(c);
}

/* Load file through c: 1 if it loaded, *hit whether it was read. */
static int load_via(aq_diskcache *c, const char *file, int *hit, aq_arch **a)
{
  aq_error e;
  *a = NULL;
  return aq_check(aq_arch_cache_load(c, file, NULL, hit, a, &e) == AQ_OK, "%s: %s", file, e.message);
}

/* The sources of file (as aq_arch_load_stored gives them to the store)
 * caught by a store that keeps nothing. */
static aq_arch_sources caught;
static char *caught_text, *caught_data[2];
static int catch_get(void *ctx, const aq_arch_sources *src, const unsigned char **bytes,
                     size_t *n, void **handle)
{
  (void)ctx, (void)bytes, (void)n, (void)handle;
  caught = *src;
  caught_text = strndup(src->text, src->ntext);
  caught.text = caught_text;
  for (int f = 0; f < 2; f++)
    caught.data[f] = caught_data[f] = src->data[f] ? strndup(src->data[f], src->ndata[f]) : NULL;
  return 0;
}
static void catch_release(void *ctx, void *handle) { (void)ctx, (void)handle; }
static void catch_put(void *ctx, const aq_arch_sources *src, const unsigned char *bytes,
                      size_t n)
{
  (void)ctx, (void)src, (void)bytes, (void)n;
}

/* The entry file of file's arch in c into path[cap]. */
static void entry_of(aq_diskcache *c, const char *file, char *path, size_t cap)
{
  aq_arch_store s = {NULL, catch_get, catch_release, catch_put};
  aq_arch *a = NULL;
  aq_error e;
  aq_arch_load_stored(file, &s, NULL, &a, &e);
  aq_arch_free(a);
  aq_bytes_out key = {0};
  aq_arch_cache_key(&caught, &key);
  aq_diskcache_entry_path(c, key.data, key.n, path, cap);
  free(key.data);
  free(caught_text);
  free(caught_data[0]);
  free(caught_data[1]);
}

/* Arch b's entry name made to hold arch a's entry: b read through the
 * cache must be a miss and b itself, not a. */
static void other_key_case(aq_diskcache *c, const char *fa, const char *fb, const char *what)
{
  char pa[1024], pb[1024];
  aq_arch *a = NULL, *b = NULL, *ref = NULL;
  int hit = -1;
  aq_error e;
  load_via(c, fa, &hit, &a); /* stores a */
  entry_of(c, fa, pa, sizeof pa);
  entry_of(c, fb, pb, sizeof pb);
  aq_check(strcmp(pa, pb) != 0 && aq_test_copy_prefix(pa, pb, 1, 1),
           "%s: a's entry copied to b's name", what);
  aq_check(aq_arch_load(fb, &ref, &e) == AQ_OK, "%s: b built: %s", what, e.message);
  if (a && ref)
    aq_check(aq_arch_path(a, 0)->s_c_rad != aq_arch_path(ref, 0)->s_c_rad ||
                 aq_workpath_table_size(aq_arch_workpath(a, 1)) !=
                     aq_workpath_table_size(aq_arch_workpath(ref, 1)),
             "%s: the two arches' paths differ (the case tests something)", what);
  if (load_via(c, fb, &hit, &b) && ref) {
    aq_check(hit == 0, "%s: b's name holding a's entry: a miss for b", what);
    same_arch(ref, b, what);
  }
  char *notes = aq_diskcache_notes(c);
  aq_check(notes == NULL, "%s: another key's entry is not corrupt: %s", what,
           notes ? notes : "");
  free(notes);
  aq_arch_free(a);
  aq_arch_free(b);
  aq_arch_free(ref);
}

AQ_TEST(arch_cache_other_sources_never_confused)
{
  char dir[512], cfg[800], cfg2[800], csv[800], faces[800];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "arches", "test 1");
  if (!aq_check(c != NULL, "store opened"))
    return;
  /* a .cfg that differs in one value */
  aq_test_edited_copy("arches/oppenheim.cfg", NULL, NULL, dir, "a.cfg", cfg, sizeof cfg);
  aq_test_edited_copy("arches/oppenheim.cfg", "thickness_m", "thickness_m = 0.55 ;", dir,
                      "b.cfg", cfg2, sizeof cfg2);
  other_key_case(c, cfg, cfg2, "thickness_m");
  /* the same .cfg text (same name beside it), another joints file: one
   * joint moved 2 cm */
  char d1[700], d2[700];
  snprintf(d1, sizeof d1, "%s/one", dir);
  snprintf(d2, sizeof d2, "%s/two", dir);
  char cmd[2000];
  snprintf(cmd, sizeof cmd, "mkdir -p %s %s", d1, d2);
  aq_check(system(cmd) == 0, "directories made");
  aq_test_edited_copy("arches/vertical.cfg", NULL, NULL, d1, "vertical.cfg", cfg, sizeof cfg);
  aq_test_edited_copy("arches/vertical.cfg", NULL, NULL, d2, "vertical.cfg", cfg2,
                      sizeof cfg2);
  aq_test_edited_copy("arches/vertical_faces.csv", NULL, NULL, d1, "vertical_faces.csv", faces,
                      sizeof faces);
  aq_test_edited_copy("arches/vertical_faces.csv", NULL, NULL, d2, "vertical_faces.csv", faces,
                      sizeof faces);
  aq_test_edited_copy("arches/vertical.csv", NULL, NULL, d1, "vertical.csv", csv, sizeof csv);
  aq_test_edited_copy("arches/vertical.csv", "6,0,2.15,0,2.85", "6,0.02,2.15,0.02,2.85", d2,
                      "vertical.csv", csv, sizeof csv);
  other_key_case(c, cfg, cfg2, "joints file");
  aq_diskcache_close(c);
}

AQ_TEST(arch_cache_corrupt_entry_noted_and_rebuilt)
{
  char dir[512], path[1024], whole[1100];
  aq_test_tmpdir(dir, sizeof dir);
  aq_diskcache *c = aq_diskcache_open(dir, "arches", "test 1");
  if (!aq_check(c != NULL, "store opened"))
    return;
  const char *file = "arches/thick.cfg";
  aq_arch *ref = NULL, *a = NULL;
  aq_error e;
  int hit = -1;
  aq_check(aq_arch_load(file, &ref, &e) == AQ_OK, "built: %s", e.message);
  load_via(c, file, &hit, &a);
  aq_arch_free(a);
  entry_of(c, file, path, sizeof path);
  snprintf(whole, sizeof whole, "%s.whole", path);
  /* one byte among the tables flipped; the entry cut to two thirds */
  for (int way = 0; way < 2; way++) {
    aq_check(aq_test_copy_prefix(path, whole, 1, 1), "(%d) entry kept", way);
    if (way == 0) {
      FILE *f = fopen(path, "r+b");
      if (f) {
        fseek(f, -2000, SEEK_END);
        int ch = fgetc(f);
        fseek(f, -2000, SEEK_END);
        fputc(ch ^ 0x04, f);
        fclose(f);
      }
    } else {
      aq_test_copy_prefix(whole, path, 2, 3);
    }
    if (load_via(c, file, &hit, &a) && ref) {
      aq_check(hit == 0, "(%d) a spoilt entry is not read", way);
      same_arch(ref, a, "rebuilt");
    }
    aq_arch_free(a);
    char *notes = aq_diskcache_notes(c);
    aq_check(notes && strstr(notes, "corrupt") && strstr(notes, path) &&
                 aq_test_count_lines(notes) == 1,
             "(%d) one note naming the entry: %s", way, notes ? notes : "(none)");
    free(notes);
    if (load_via(c, file, &hit, &a) && ref) {
      aq_check(hit == 1, "(%d) stored again whole, then read", way);
      same_arch(ref, a, "read again");
    }
    aq_arch_free(a);
  }
  aq_arch_free(ref);
  aq_diskcache_close(c);
}

/* The main job on two records and every shipped arch, TSV into
 * dir/name.tsv, results into dir/name.h5. */
static int arch_job(const char *dir, const char *name, const char *extra, char *err,
                    size_t cap)
{
  char args[4096];
  glob_t g;
  size_t n = shipped(&g), at = 0;
  at += (size_t)snprintf(args, sizeof args,
                         "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 "
                         "records/RSN1616_DUZCE_362-E.AT2 --scale 1.5 --polarity both");
  for (size_t i = 0; i < n && at < sizeof args; i++)
    at += (size_t)snprintf(args + at, sizeof args - at, " --arch %s", g.gl_pathv[i]);
  if (at < sizeof args)
    snprintf(args + at, sizeof args - at, " %s --text %s/%s.tsv -o %s/%s.h5", extra, dir, name,
             dir, name);
  globfree(&g);
  return aq_test_run(args, NULL, 0, err, cap);
}

AQ_TEST(arch_cache_main_job_identical)
{
  char dir[512], cdir[600], adir[700], opt[700];
  static char err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cdir, sizeof cdir, "%s/cache", dir);
  snprintf(adir, sizeof adir, "%s/arches", cdir);
  snprintf(opt, sizeof opt, "--cache-dir %s", cdir);
  glob_t g;
  int n = (int)shipped(&g);
  globfree(&g);
  aq_check(arch_job(dir, "off", "--no-cache", err, sizeof err) == 0, "--no-cache: %s", err);
  aq_check(aq_test_count_names(adir, ".aqc") == 0, "--no-cache stores no arch");
  aq_check(arch_job(dir, "fill", opt, err, sizeof err) == 0, "cache cold: %s", err);
  aq_check(aq_test_count_names(adir, ".aqc") == n, "one entry per arch (%d of %d)",
           aq_test_count_names(adir, ".aqc"), n);
  aq_check(arch_job(dir, "warm", opt, err, sizeof err) == 0 && !strstr(err, "note"),
           "cache warm: %s", err);
  aq_check(aq_test_same_outputs(dir, "off", "fill"),
           "filling the cache: the outputs of --no-cache");
  aq_check(aq_test_same_outputs(dir, "off", "warm"),
           "arches read from the cache: the outputs of --no-cache");
  aq_check(aq_test_count_names(adir, ".tmp.") == 0, "no temporary left");
}
