/* test_select_same.c: which members of a pool are one recording
 * (src/select/same.h), and `archquake select` never choosing two of one.
 *
 * - The trace (the mean over windows of AQ_SAME_STEP_S): closed forms for a
 *   constant and a ramp, at steps that divide the window and one that does
 *   not.
 * - rho against a second method written here: the correlation summed over
 *   every lag in the time domain, O(n^2), on sequences of a random
 *   generator; 1 for a trace against itself shifted and negated.
 * - The classes, on real records (tests/data/records/PROVENANCE.md and
 *   agency/PROVENANCE.md say what each is): one recording in two
 *   processings (PEER's 1990s IELC180.AT2, HP 0.2 Hz LP 15 Hz, and
 *   NGA-West2's RSN6 ELC180) reaches AQ_SAME_RHO_MIN; two components of one
 *   station and two stations of one event stay below it.
 * - The CLI: the pool of every AT2 file with the El Centro pair: never both
 *   in the suite, one note on stderr naming them, the suite file's comment
 *   line; the pool without IELC180.AT2: no note.
 * - The traces kept in select's cache entries, spoilt: never used. */
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "check.h"
#include "io/record.h"
#include "select/same.h"
#include "select_fixture.h"
#include "signal/signal.h"

#define R "tests/data/records/"
#define BIG (1 << 20)

AQ_TEST(select_same_trace_closed_forms)
{
  const double dts[3] = {0.005, 0.01, 0.03};
  const double h = AQ_SAME_STEP_S;
  for (int d = 0; d < 3; d++) {
    double dt = dts[d];
    size_t n = (size_t)(20.0 / dt) + 1; /* 20 s */
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    for (size_t k = 0; k < n; k++) {
      a[k] = 1.7;
      b[k] = 0.3 * (double)k * dt; /* a ramp: the window's mean is its middle's value */
    }
    aq_same_trace ta, tb;
    aq_error e;
    aq_check(aq_same_trace_make(a, n, dt, &ta, &e) == AQ_OK, "trace");
    aq_check(aq_same_trace_make(b, n, dt, &tb, &e) == AQ_OK, "trace");
    size_t want = (size_t)floor((double)(n - 1) * dt / h + 1e-9);
    aq_check(ta.n == want, "dt %g: %zu windows, want %zu", dt, ta.n, want);
    double ea = 0, eb = 0;
    for (size_t k = 0; k < ta.n; k++) {
      ea = fmax(ea, fabs(ta.x[k] - 1.7));
      eb = fmax(eb, fabs(tb.x[k] - 0.3 * ((double)k + 0.5) * h));
    }
    aq_check(ea < 1e-10, "dt %g: constant, error %g", dt, ea);
    /* the ramp is linear between samples, so the running integral is
     * exact at the samples and its linear interpolation between them errs
     * by at most c dt^2 / 8 over a window h */
    aq_check(eb <= 0.3 * dt * dt / 8 / h * 2 + 1e-12, "dt %g: ramp, error %g", dt, eb);
    aq_same_trace_free(&ta);
    aq_same_trace_free(&tb);
    free(a);
    free(b);
  }
}

static uint64_t rng = 0x9E3779B97F4A7C15ULL;
static double gauss(void)
{
  double s = 0;
  for (int i = 0; i < 12; i++) {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    s += (double)(rng >> 11) / 9007199254740992.0;
  }
  return s - 6;
}

/* rho over every lag, in the time domain. */
static double rho_direct(const double *x, size_t nx, const double *y, size_t ny)
{
  double ex = 0, ey = 0, best = 0;
  for (size_t k = 0; k < nx; k++)
    ex += x[k] * x[k];
  for (size_t k = 0; k < ny; k++)
    ey += y[k] * y[k];
  for (long tau = -(long)nx + 1; tau < (long)ny; tau++) {
    double s = 0;
    for (long t = 0; t < (long)nx; t++)
      if (t + tau >= 0 && t + tau < (long)ny)
        s += x[t] * y[t + tau];
    best = fmax(best, fabs(s));
  }
  return best / sqrt(ex * ey);
}

AQ_TEST(select_same_rho_against_direct_sum)
{
  const size_t lens[4][2] = {{50, 50}, {37, 101}, {128, 9}, {300, 257}};
  for (int c = 0; c < 4; c++) {
    size_t na = lens[c][0], nb = lens[c][1];
    aq_same_trace a = {malloc(na * sizeof(double)), na}, b = {malloc(nb * sizeof(double)), nb};
    for (size_t k = 0; k < na; k++)
      a.x[k] = gauss();
    for (size_t k = 0; k < nb; k++) /* partly a's, shifted and negated, partly noise */
      b.x[k] = (k >= 5 && k - 5 < na ? -0.7 * a.x[k - 5] : 0) + 0.8 * gauss();
    double got = aq_same_rho(&a, &b, NULL), want = rho_direct(a.x, na, b.x, nb);
    aq_check_rel(got, want, 1e-10, "lengths %zu, %zu", na, nb);
    free(a.x);
    free(b.x);
  }
  /* a trace against itself delayed by 13 steps and negated: 1, at +13 steps */
  size_t n = 400;
  aq_same_trace a = {malloc(n * sizeof(double)), n}, b = {calloc(n + 13, sizeof(double)), n + 13};
  for (size_t k = 0; k < n; k++) {
    a.x[k] = gauss();
    b.x[k + 13] = -2.5 * a.x[k];
  }
  double lag;
  aq_check_abs(aq_same_rho(&a, &b, &lag), 1.0, 1e-12, "itself, shifted and negated");
  aq_check_abs(lag, 13 * AQ_SAME_STEP_S, 1e-12, "the lag of the peak");
  free(a.x);
  free(b.x);
}

/* The trace of a record as select makes it: read, processed with the
 * default options, the record's own span. */
static int trace_of(const char *path, aq_same_trace *t)
{
  aq_record rec;
  aq_error e;
  aq_read_opts ro = {0};
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  aq_processed p;
  if (!aq_check(aq_record_read(path, &ro, &rec, &e) == AQ_OK, "%s: %s", path, e.message))
    return 0;
  int ok = aq_check(aq_signal_process(&rec, &so, NULL, &p, &e) == AQ_OK, "%s: %s", path,
                    e.message);
  if (ok)
    ok = aq_check(aq_same_trace_make(p.acc_mps2 + p.pad_front, p.n_orig, p.dt_s, t, &e) ==
                      AQ_OK,
                  "%s: trace", path);
  if (ok)
    aq_processed_free(&p);
  aq_record_free(&rec);
  return ok;
}

static double rho_of(const char *a, const char *b)
{
  aq_same_trace ta = {0}, tb = {0};
  double r = -1;
  if (trace_of(a, &ta) && trace_of(b, &tb))
    r = aq_same_rho(&ta, &tb, NULL);
  aq_same_trace_free(&ta);
  aq_same_trace_free(&tb);
  return r;
}

AQ_TEST(select_same_recording_classes)
{
  /* one recording, two processings (PROVENANCE.md: El Centro Array #9,
   * 180, PEER's older file and NGA-West2's) */
  double r = rho_of(R "IELC180.AT2", R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2");
  aq_check(r >= AQ_SAME_RHO_MIN && r <= 1, "El Centro 180 twice: rho %.3f, want >= %g", r,
           AQ_SAME_RHO_MIN);
  static const char *const apart[][2] = {
      /* two components of one station */
      {R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"},
      {R "IELC180.AT2", R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"},
      {R "RSN763_LOMAP_GIL067.AT2", R "RSN763_LOMAP_GIL337.AT2"},
      {R "agency/ce36456p_CE36456.V2#90", R "agency/ce36456p_CE36456.V2#0"},
      {R "Q4149CF2.csv#NS", R "Q4149CF2.csv#EW"},
      {R "AOM0170806140843.NS", R "AOM0170806140843.EW"},
      /* two stations of one event */
      {R "CHY028-N.AT2", R "TCU052-N.AT2"},
      {R "HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC",
       R "agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC"},
  };
  for (size_t i = 0; i < sizeof apart / sizeof apart[0]; i++) {
    r = rho_of(apart[i][0], apart[i][1]);
    aq_check(r >= 0 && r < AQ_SAME_RHO_MIN, "%s and %s: rho %.3f, want < %g", apart[i][0],
             apart[i][1], r, AQ_SAME_RHO_MIN);
  }
}

/* The groups of a pool (every pass: the coarse one included, the spectra's
 * left out: NULL): El Centro 180 twice and once more as the second
 * component of a pair, beside another component and another event. */
AQ_TEST(select_same_groups_of_a_pool)
{
  static const char *const path[5] = {
      R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", R "IELC180.AT2", R "RSN763_LOMAP_GIL067.AT2",
      R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", R "RSN763_LOMAP_GIL337.AT2"};
  aq_same_trace tr[8] = {{0}};
  /* members: 0 ELC270; 1 IELC180; 2 GIL067; 3 the pair (GIL337, RSN6 ELC180) */
  int ok = trace_of(path[0], &tr[0]) && trace_of(path[1], &tr[2]) &&
           trace_of(path[2], &tr[4]) && trace_of(path[4], &tr[6]) &&
           trace_of(path[3], &tr[7]);
  int group[4];
  size_t ng = 0, np = 0, nc = 0;
  aq_same_pair *pairs = NULL;
  aq_error e;
  if (ok && aq_check(aq_same_groups(tr, 4, NULL, 0, NULL, AQ_SAME_RHO_MIN, 2, group, &ng,
                                    &pairs, &np, &nc, &e) == AQ_OK,
                     "groups")) {
    aq_check(group[0] == -1 && group[1] == 0 && group[2] == -1 && group[3] == 0 && ng == 1,
             "groups %d %d %d %d (%zu), want -1 0 -1 0", group[0], group[1], group[2],
             group[3], ng);
    aq_check(np == 1 && pairs[0].i == 1 && pairs[0].j == 3 && nc == 6, "%zu pairs, %zu "
             "compared", np, nc);
    if (np == 1)
      aq_check_abs(pairs[0].rho, aq_same_rho(&tr[2], &tr[7], NULL), 1e-12, "its rho");
  }
  free(pairs);
  for (int i = 0; i < 8; i++)
    aq_same_trace_free(&tr[i]);
}

/* The suite file's records (field 0 of its rows) as one string. */
static void suite_records(const char *out, char *buf, size_t n)
{
  char f[512];
  buf[0] = '\0';
  for (int row = 1; aq_test_tsv_field(out, row, 0, f, sizeof f)[0]; row++)
    snprintf(buf + strlen(buf), n - strlen(buf), "%s|", f);
}

AQ_TEST(select_same_recording_never_both)
{
  char *out = malloc(BIG), err[8192], rows[4096];
  for (int count = 3; count <= 9; count += 2) {
    char cmd[512];
    snprintf(cmd, sizeof cmd, "select " R "*.AT2 --target " AQ_TEST_EC8B " --count %d "
             "--no-cache", count);
    int rc = aq_test_run(cmd, out, BIG, err, sizeof err);
    aq_check(rc == 0, "--count %d: exit %d: %s", count, rc, err);
    suite_records(out, rows, sizeof rows);
    int both = strstr(rows, "IELC180.AT2") && strstr(rows, "RSN6_IMPVALL.I_I-ELC180");
    aq_check(!both, "--count %d: the suite holds El Centro 180 twice: %s", count, rows);
    aq_check(aq_test_count_lines(err) == 1 && strstr(err, "note: same recording") &&
                 strstr(err, "IELC180.AT2 and " R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2"),
             "--count %d: one note naming the pair: %s", count, err);
    aq_check(strstr(out, "# same recording: 1 pair") != NULL, "--count %d: the comment line",
             count);
  }
  /* without the older file: nothing to say */
  int rc = aq_test_run("select " R "RSN*.AT2 " R "CHY028-N.AT2 " R "TCU052-N.AT2 --target "
                       AQ_TEST_EC8B " --count 3 --no-cache", out, BIG, err, sizeof err);
  aq_check(rc == 0 && !strstr(err, "same recording") && !strstr(out, "same recording"),
           "no pair, no note: exit %d: %s", rc, err);
  free(out);
}

/* Spoil the traces of every entry of select's spectra cache in dir (each
 * member a single record: its value ends with trace 0's samples, then
 * trace 1's count, 0): nan_whole 0 flips one bit of trace 0's last sample
 * (the checksum no longer matches); 1 writes NaN over its last four
 * samples and makes the checksum again (XXH3-64 of all before it, as the
 * store does: docs/cache.md), an entry whole yet not what select writes.
 * Returns the entries spoilt. */
static int spoil_traces(const char *dir, int nan_whole)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));) {
    if (!strstr(e->d_name, ".aqc"))
      continue;
    char p[1200];
    snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
    size_t len = 0;
    unsigned char *b = (unsigned char *)aq_test_read_file(p, &len);
    uint64_t last_count = 1;
    if (b && len > 24 + 8 + 8 + 32)
      memcpy(&last_count, b + len - 16, sizeof last_count);
    if (!b || last_count != 0) { /* not a single record's entry */
      free(b);
      continue;
    }
    if (nan_whole) {
      for (int k = 0; k < 4; k++) {
        double v = NAN;
        memcpy(b + len - 16 - 8 * (size_t)(k + 1), &v, sizeof v);
      }
      uint64_t sum = XXH3_64bits(b, len - 8);
      memcpy(b + len - 8, &sum, sizeof sum);
    } else {
      b[len - 16 - 3] ^= 1;
    }
    FILE *f = fopen(p, "wb");
    n += f && fwrite(b, 1, len, f) == len && fclose(f) == 0;
    free(b);
  }
  if (d)
    closedir(d);
  return n;
}

/* The traces that select's cache keeps for its duplicate check (its
 * newest field) spoilt: a damaged entry is never used (docs/cache.md).
 * With a bit of a trace flipped each entry is named in one note (checksum
 * mismatch) and computed again; with traces of NaN under a checksum made
 * again (whole by its checksum, yet not what select writes) each is
 * computed again too, and read whole on the next run.  Every run exits 0
 * with the suite of --no-cache and its note naming the El Centro pair:
 * never a crash, never a duplicate missed or invented. */
AQ_TEST(select_same_cache_traces_spoilt)
{
  char dir[512], cdir[700], kdir[800], cmd[1200], err[8192];
  char *ref = malloc(BIG), *out = malloc(BIG);
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cdir, sizeof cdir, "%s/cache", dir);
  snprintf(kdir, sizeof kdir, "%s/spectra", cdir);
  static const char *const pool = "select " R "*.AT2 --target " AQ_TEST_EC8B " --count 3";
  snprintf(cmd, sizeof cmd, "%s --no-cache", pool);
  int rc = aq_test_run(cmd, ref, BIG, err, sizeof err);
  if (!aq_check(ref && out && rc == 0 && strstr(err, "note: same recording"),
                "--no-cache: exit %d: %s", rc, err)) {
    free(ref);
    free(out);
    return;
  }
  snprintf(cmd, sizeof cmd, "%s --cache-dir %s", pool, cdir);
  static const char *const step[] = {"cache cold", "cache warm", "a bit of the traces flipped",
                                     "written again", "traces of NaN, checksum made again",
                                     "written again"};
  int entries = 0;
  for (int i = 0; i < 6; i++) {
    int spoilt = -1;
    if (i == 2 || i == 4) {
      spoilt = spoil_traces(kdir, i == 4);
      aq_check(spoilt == entries && entries >= 10, "%s: %d entries of %d spoilt", step[i],
               spoilt, entries);
    }
    rc = aq_test_run(cmd, out, BIG, err, sizeof err);
    if (i == 0)
      entries = aq_test_count_names(kdir, ".aqc");
    int notes = 0;
    for (const char *p = err; (p = strstr(p, "note: cache entry ")); p++)
      notes++;
    int want_notes = i == 2 ? entries : 0;
    aq_check(rc == 0 && !strcmp(out, ref) && strstr(err, "note: same recording") &&
                 strstr(err, "IELC180.AT2 and " R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2") &&
                 notes == want_notes &&
                 (i != 2 || strstr(err, "is corrupt (checksum mismatch)")),
             "%s: exit %d (want 0), the suite of --no-cache (%s), the pair's note, %d notes of "
             "the cache (want %d): %s", step[i], rc, strcmp(out, ref) ? "differs" : "same",
             notes, want_notes, err);
  }
  aq_check(aq_test_count_names(kdir, ".tmp.") == 0, "no temporary left");
  free(ref);
  free(out);
}
