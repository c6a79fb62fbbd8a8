/* bench_select.c: the speed of `archquake select` and the heuristic's
 * distance from the optimum, in one run.
 *
 * Speed: 7 records from a synthetic pool of 1,000 (SAC files of 20,000
 * samples at dt = 0.005 s, each a sum of 40 sines from 0.1 to 20 Hz with
 * its own tilt, level, phases and event), matched at 100 periods (0.05 to
 * 3 s, log-spaced; --period-grid) to an EC8 target, on two threads (-j 2):
 * once with an empty cache directory (read, process, spectra, search) and
 * then with the pool's spectra cached (hash the files, read the entries,
 * search), medians of the runs, wall and CPU time (the machine is shared:
 * CPU time says what the work costs).  The pool is written once under
 * build/tmp/bench_select/pool and kept.
 *
 * Distance: the 43 real records of tests/test_select_search.c (their
 * spectra from `archquake select -o`), N = 7 of 43: the heuristic's misfit
 * against the exhaustive optimum over all C(43, 7) = 32,224,114 suites, and
 * N = 3 to 6 likewise.  AQ_BENCH_SELECT_POOL=N (default 1000) makes a
 * smaller pool for a quick look; AQ_BENCH_SELECT_BEFORE=PATH names another
 * archquake (an earlier commit's build) whose cold runs alternate with
 * ./archquake's (and then its runs with the spectra cached), medians and
 * ratios printed side by side; AQ_BENCH_SELECT_SPEED_ONLY=1 skips the
 * distance. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "select/search.h"

#define DIR "build/tmp/bench_select"
#define NPTS 20000
#define DT 0.005
#define NSINES 40
#define NGRID 100
#define TWO_PI 6.283185307179586

static double children_cpu_s(void)
{
  struct rusage ru;
  getrusage(RUSAGE_CHILDREN, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static uint32_t next(uint32_t *s)
{
  *s = *s * 1103515245u + 12345u;
  return *s >> 8;
}

/* One SAC file (little-endian, NVHDR 6): acceleration in nm/s^2 (IDEP
 * IACC), its event in KEVNM, horizontal (CMPINC 90). */
static int write_sac(const char *path, const float *v, const char *event, const char *station)
{
  float f[70];
  int32_t n[40];
  char k[192];
  for (int i = 0; i < 70; i++)
    f[i] = -12345.0f;
  for (int i = 0; i < 40; i++)
    n[i] = -12345;
  for (int i = 0; i < 24; i++)
    memcpy(k + 8 * i, "-12345  ", 8);
  f[0] = (float)DT;         /* DELTA */
  f[5] = 0.0f;              /* B */
  f[6] = (float)(DT * (NPTS - 1)); /* E */
  f[57] = 90.0f;            /* CMPAZ */
  f[58] = 90.0f;            /* CMPINC: horizontal */
  n[6] = 6;                 /* NVHDR */
  n[9] = NPTS;              /* NPTS */
  n[15] = 1;                /* IFTYPE: ITIME */
  n[16] = 8;                /* IDEP: IACC, nm/s^2 */
  n[35] = 1;                /* LEVEN */
  char s8[9], s16[17];
  snprintf(s8, sizeof s8, "%-8.8s", station);
  snprintf(s16, sizeof s16, "%-16.16s", event);
  memcpy(k, s8, 8);        /* KSTNM */
  memcpy(k + 8, s16, 16);  /* KEVNM */
  memcpy(k + 160, "HNE     ", 8); /* KCMPNM */
  FILE *fp = fopen(path, "wb");
  if (!fp)
    return -1;
  fwrite(f, 4, 70, fp);
  fwrite(n, 4, 40, fp);
  fwrite(k, 1, 192, fp);
  fwrite(v, 4, NPTS, fp);
  return fclose(fp);
}

static int make_pool(size_t npool, char *pooldir, size_t cap)
{
  snprintf(pooldir, cap, DIR "/pool%zu", npool);
  char stamp[512];
  snprintf(stamp, sizeof stamp, "%s/.complete", pooldir);
  if (access(stamp, F_OK) == 0)
    return 0;
  mkdir("build", 0777);
  mkdir("build/tmp", 0777);
  mkdir(DIR, 0777);
  mkdir(pooldir, 0777);
  float *v = malloc(NPTS * sizeof *v);
  double f[NSINES], ph[NSINES], w[NSINES];
  for (size_t r = 0; r < npool; r++) {
    uint32_t seed = (uint32_t)(2654435761u * (r + 1));
    double tilt = (double)next(&seed) / 16777216.0 - 0.5;         /* -0.5 .. 0.5 */
    double pga_g = 0.05 + 0.55 * (double)next(&seed) / 16777216.0; /* 0.05 .. 0.6 g */
    double t_rise = 2 + 8 * (double)next(&seed) / 16777216.0;
    for (int j = 0; j < NSINES; j++) {
      f[j] = 0.1 * pow(200.0, (double)j / (NSINES - 1));
      ph[j] = TWO_PI * (double)next(&seed) / 16777216.0;
      w[j] = pow(1 + f[j], -0.5 + tilt) * (0.5 + (double)next(&seed) / 16777216.0);
    }
    double peak = 0;
    for (size_t i = 0; i < NPTS; i++) {
      double t = (double)i * DT, s = 0;
      for (int j = 0; j < NSINES; j++)
        s += w[j] * sin(TWO_PI * f[j] * t + ph[j]);
      s *= t < t_rise ? t / t_rise : exp(-(t - t_rise) / 20);
      v[i] = (float)s;
      peak = fmax(peak, fabs(s));
    }
    for (size_t i = 0; i < NPTS; i++)
      v[i] = (float)(v[i] / peak * pga_g * 9.80665e9);
    char path[600], event[32], station[16];
    snprintf(path, sizeof path, "%s/syn%04zu.sac", pooldir, r);
    snprintf(event, sizeof event, "SYN-%03zu", r / 5); /* five stations an event */
    snprintf(station, sizeof station, "S%04u", (unsigned)(r % 10000));
    if (write_sac(path, v, event, station) != 0) {
      free(v);
      return -1;
    }
  }
  free(v);
  FILE *fp = fopen(stamp, "w");
  return fp && fclose(fp) == 0 ? 0 : -1;
}

/* One select run: wall and CPU seconds; its exit status. */
static int run(const char *cmd, double *wall, double *cpu)
{
  double c0 = children_cpu_s(), t0 = aq_bench_now_s();
  int rc = system(cmd);
  *wall = aq_bench_now_s() - t0;
  *cpu = children_cpu_s() - c0;
  return rc;
}

/* The select command of binary bin into cmd. */
static void select_cmd(char *cmd, size_t cap, const char *bin, const char *pooldir,
                       const char *grid)
{
  snprintf(cmd, cap, "%s select %s --target ec8:type=1,ground=B,ag=0.25 "
           "--count 7 --periods 0.05,3 --period-grid %s --scale-range 0.2,5 -j 2 "
           "--cache-dir " DIR "/cache --text " DIR "/suite.tsv 2>" DIR "/stderr.txt",
           bin, pooldir, grid);
}

static double loadavg1(void)
{
  double l = -1;
  FILE *fp = fopen("/proc/loadavg", "r");
  if (fp) {
    if (fscanf(fp, "%lf", &l) != 1)
      l = -1;
    fclose(fp);
  }
  return l;
}

/* before: NULL, or another archquake (an earlier build) whose cold runs
 * alternate with ./archquake's, the medians and ratios side by side. */
static void speed(size_t npool, const char *before)
{
  char pooldir[256], grid[NGRID * 24], cmd[NGRID * 24 + 1024];
  double t0 = aq_bench_now_s();
  if (make_pool(npool, pooldir, sizeof pooldir) != 0) {
    printf("speed: cannot write the pool under " DIR "\n");
    return;
  }
  double made = aq_bench_now_s() - t0;
  size_t w = 0;
  for (int k = 0; k < NGRID; k++)
    w += (size_t)snprintf(grid + w, sizeof grid - w, "%s%.6g", k ? "," : "",
                          0.05 * pow(60.0, (double)k / (NGRID - 1)));
  printf("select 7 of %zu synthetic SAC records (%d samples at %g s), %d periods 0.05-3 s, "
         "-j 2 (pool written in %.1f s), load average %.2f\n", npool, NPTS, DT, NGRID, made,
         loadavg1());
  printf("%-34s %5s %10s %10s\n", "case", "runs", "wall_s", "cpu_s");
  enum { COLD = 2, WARM = 7 };
  double wall[2][WARM], cpu[2][WARM];
  for (int i = 0; i < COLD; i++)
    for (int b = before ? 1 : 0; b >= 0; b--) {
      select_cmd(cmd, sizeof cmd, b ? before : "./archquake", pooldir, grid);
      if (system("rm -rf " DIR "/cache") != 0)
        return;
      if (run(cmd, &wall[b][i], &cpu[b][i]) != 0) {
        printf("select failed: see " DIR "/stderr.txt\n");
        return;
      }
    }
  double wa = aq_bench_median(wall[0], COLD), ca = aq_bench_median(cpu[0], COLD);
  if (before) {
    double wb = aq_bench_median(wall[1], COLD), cb = aq_bench_median(cpu[1], COLD);
    printf("%-34s %5d %10.3f %10.3f\n", "cold, before (the other build)", COLD, wb, cb);
    printf("%-34s %5d %10.3f %10.3f\n", "cold, after (./archquake)", COLD, wa, ca);
    printf("%-34s %5s %9.2fx %9.2fx\n", "cold: before / after", "", wb / wa, cb / ca);
  } else {
    printf("%-34s %5d %10.3f %10.3f\n", "cold: read, process, spectra", COLD, wa, ca);
  }
  if (before) { /* its entries (another build's) into the cache beside ours */
    double w0, c0;
    select_cmd(cmd, sizeof cmd, before, pooldir, grid);
    if (run(cmd, &w0, &c0) != 0) {
      printf("select failed: see " DIR "/stderr.txt\n");
      return;
    }
  }
  for (int i = 0; i < WARM; i++)
    for (int b = before ? 1 : 0; b >= 0; b--) {
      select_cmd(cmd, sizeof cmd, b ? before : "./archquake", pooldir, grid);
      if (run(cmd, &wall[b][i], &cpu[b][i]) != 0) {
        printf("select failed: see " DIR "/stderr.txt\n");
        return;
      }
    }
  if (before)
    printf("%-34s %5d %10.3f %10.3f\n", "warm, before (the other build)", WARM,
           aq_bench_median(wall[1], WARM), aq_bench_median(cpu[1], WARM));
  printf("%-34s %5d %10.3f %10.3f\n", "warm: the pool's spectra cached", WARM,
         aq_bench_median(wall[0], WARM), aq_bench_median(cpu[0], WARM));
  printf("load average after: %.2f\n", loadavg1());
}

/* ---- the heuristic against the optimum, 43 real records ------------------ */

#define R "tests/data/records/"
static const char *const pool43 =
    R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 " R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 "
    R "RSN763_LOMAP_GIL067.AT2 " R "RSN763_LOMAP_GIL337.AT2 " R "ARL360.at2 "
    R "RSN77_SFERN_PUL164-hor1.AT2 " R "CHY028-N.AT2 " R "TCU052-N.AT2 "
    R "RSN1616_DUZCE_362-E.AT2 " R "RSN4843_CHUETSU_65006NS.AT2 "
    R "RSN4013_SANSIMEO_36258021.AT2 " R "kocaeli.csv " R "Q4149CF2.csv#NS "
    R "Q4149CF2.csv#EW " R "AOM0081801241951.NS " R "20190706031952.CJ.T001230.HNE.sac "
    R "CI.CLC..HNE.mseed " R "CI.CLC.xml "
    R "BK.CMB.00.HNE__20140824T102014Z__20140824T102244Z.mseed " R "BK.CMB.xml "
    R "HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC " R "AOM0170806140843.NS "
    R "AOM0170806140843.EW " R "NGNH351106302345.NS1 " R "NGNH351106302345.EW2 "
    R "2-ECU.dat#N " R "2-ECU.dat#E " R "20161113_110259_WTMC_20.V2A#N28W "
    R "20161113_110259_WTMC_20.V2A#S62W " R "copiapo1002271.v1#EW "
    R "copiapo1002271.v1#NZ " R "agency/CE.58360..HNE__20191015T053312Z__20191015T054042Z.mseed "
    R "agency/CE.58360..HNN__20191015T053312Z__20191015T054042Z.mseed " R "agency/CE.58360.xml "
    R "agency/CE89146.V1#360 " R "agency/CE89146.V1#90 "
    R "agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC "
    R "agency/HL.DLFA..HNN.D.20190728.160908.C.ACC.ASC " R "agency/ce36456p_CE36456.V2#90 "
    R "agency/ce36456p_CE36456.V2#0 " R "agency2/5522-1.V1#L1 " R "agency2/5522-1.V1#T3 "
    R "agency2/CUP50401.012#N90E " R "agency2/CUP50401.012#N00E "
    R "agency2/Ex20230206011732_0131_ap_Acc_N.asc "
    R "agency2/20201030115124_3519_mp_RawAcc_N.asc";

static double *read_ds(hid_t g, const char *name, size_t *rows, size_t *cols)
{
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT), sp = d >= 0 ? H5Dget_space(d) : -1;
  hsize_t dims[2] = {0, 1};
  int nd = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
  *rows = nd >= 1 ? dims[0] : 0;
  *cols = nd == 2 ? dims[1] : 1;
  double *v = malloc(*rows * *cols * sizeof *v + 1);
  if (v && d >= 0)
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  return v;
}

static void distance(void)
{
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "./archquake select %s --target ec8:type=1,ground=B,ag=0.25 "
           "--count 7 --scale-range 0.01,100 --no-filter --units '*T001230.HNE.sac=g' -o " DIR
           "/p43.h5 "
           "--text " DIR "/p43.tsv 2>" DIR "/stderr43.txt", pool43);
  mkdir(DIR, 0777);
  if (system(cmd) != 0) {
    printf("distance: select failed (" DIR "/stderr43.txt)\n");
    return;
  }
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(DIR "/p43.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t g = f >= 0 ? H5Gopen2(f, "select", H5P_DEFAULT) : -1;
  size_t K, M, c, r;
  double *psa = read_ds(g, "pool_psa_g", &M, &K), *target = read_ds(g, "target_g", &r, &c);
  /* the zero-period values: the pool table's psa0_g */
  double *pga = malloc(M * sizeof *pga + 1);
  hid_t d = H5Dopen2(g, "pool", H5P_DEFAULT), mt = H5Tcreate(H5T_COMPOUND, sizeof(double));
  H5Tinsert(mt, "psa0_g", 0, H5T_NATIVE_DOUBLE);
  H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, pga);
  H5Tclose(mt);
  H5Dclose(d);
  H5Gclose(g);
  H5Fclose(f);
  printf("\nthe heuristic (greedy, then swaps) against every suite: %zu real records "
         "(detrended, not filtered), %zu periods 0.1-1 s, EC8 type 1 ground B a_g 0.25 g, scale "
         "range 0.01-100\n", M, K);
  printf("%3s %12s %12s %12s %8s %7s %12s %10s %10s\n", "N", "suites", "optimum", "heuristic",
         "ratio", "starts", "evaluated", "exh_s", "heur_s");
  for (size_t N = 3; N <= 7; N++) {
    aq_select_problem p = {.nrec = M, .nper = K, .psa_mps2 = psa, .pga_mps2 = pga,
                           .target_mps2 = target, .target0_mps2 = 0.3, .band = 0.9,
                           .scale_lo = 0.01, .scale_hi = 100, .count = N};
    aq_select_prepared q;
    aq_error e;
    aq_select_result ex, h;
    if (aq_select_prepare(&p, &q, &e) != AQ_OK)
      return;
    double t0 = aq_bench_now_s();
    aq_select_exhaustive(&q, 2, &ex, &e);
    double t1 = aq_bench_now_s();
    aq_select_heuristic(&q, AQ_SELECT_STARTS, AQ_SELECT_HEURISTIC_BUDGET, &h, &e);
    double t2 = aq_bench_now_s();
    printf("%3zu %12.0f %12.6g %12.6g %8.4f %7zu %12.0f %10.3f %10.3f\n", N, ex.combinations,
           ex.eval.misfit, h.eval.misfit, h.eval.misfit / ex.eval.misfit, h.starts,
           h.evaluated, t1 - t0, t2 - t1);
    aq_select_result_free(&ex);
    aq_select_result_free(&h);
    aq_select_prepared_free(&q);
  }
  free(psa);
  free(target);
  free(pga);
}

int main(void)
{
  gsl_set_error_handler_off();
  const char *env = getenv("AQ_BENCH_SELECT_POOL");
  size_t npool = env ? (size_t)strtoul(env, NULL, 10) : 1000;
  speed(npool ? npool : 1000, getenv("AQ_BENCH_SELECT_BEFORE"));
  if (!getenv("AQ_BENCH_SELECT_SPEED_ONLY"))
    distance();
  return 0;
}
