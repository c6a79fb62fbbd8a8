/* bench_h5.c: the histories and waveforms of a results file, stored as
 * they are or deflated: the size per run and the time to write them.
 *
 * The histories are those of a real suite: the twelve acceleration records
 * of tests/data/records (AT2) against three shipped arches (bridge,
 * oppenheim, thin) at scales 1 and 2, both polarities (144 runs), run once
 * by ./archquake with --history --store-records.  They are read back into
 * memory, then written again through the results writer (aq_h5_open ...
 * aq_h5_finish, the file synced and renamed as the main job does) at each
 * deflate level (aq_h5_set_deflate: 0 stored as they are, then 1, 4, 6, 9,
 * each with the byte shuffle), the levels in turn within each of REPS
 * repetitions.  Printed per level: the file's size per run (MB), the median
 * write time per run (ms) and its ratio to the stored-as-is file's in the
 * same repetition (median [min, max]); and that every value reads back
 * the same (the writer's own reader is not used: HDF5's H5Dread). */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "report/h5.h"

#define REPS 7
#define DIR "build/tmp/bench_h5"

static const int LEVELS[] = {0, 1, 4, 6, 9};
enum { NLEVEL = sizeof LEVELS / sizeof LEVELS[0] };

typedef struct {
  char key[64];
  aq_result res;
} run;

static run *runs;
static size_t nrun;
static double *wave[64];
static size_t nwave[64], nrec;

static double *read_doubles(hid_t g, const char *name, size_t *n)
{
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT), s = H5Dget_space(d);
  *n = (size_t)H5Sget_simple_extent_npoints(s);
  double *v = malloc((*n + 1) * sizeof *v);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

static herr_t one_run(hid_t g, const char *name, const H5L_info_t *info, void *data)
{
  (void)info;
  (void)data;
  hid_t r = H5Gopen2(g, name, H5P_DEFAULT);
  run *u = &runs[nrun++];
  memset(u, 0, sizeof *u);
  snprintf(u->key, sizeof u->key, "%s", name);
  aq_history *h = &u->res.history;
  size_t n;
  h->time_s = read_doubles(r, "time_s", &n);
  h->rotation_rad = read_doubles(r, "rotation_rad", &n);
  h->displacement_m = read_doubles(r, "displacement_m", &n);
  h->kinetic_energy_j = read_doubles(r, "kinetic_energy_j", &n);
  h->potential_energy_j = read_doubles(r, "potential_energy_j", &n);
  h->set = malloc((n + 1) * sizeof *h->set);
  hid_t d = H5Dopen2(r, "hinge_set", H5P_DEFAULT);
  H5Dread(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, h->set);
  H5Dclose(d);
  h->n = h->cap = n;
  H5Gclose(r);
  return 0;
}

/* The suite's file written again at level into path: wall time, s. */
static double write_at(int level, const char *path)
{
  aq_h5_writer *w;
  aq_error err;
  double t0 = aq_bench_now_s();
  if (aq_h5_open(path, &w, &err) != AQ_OK)
    return NAN;
  aq_h5_set_deflate(w, level);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  aq_h5_root root = {.version = "bench", .command_line = "bench_h5", .created = "now",
                     .proc = &so, .units = "file", .model = "workpath", .cor = NAN,
                     .scale_to_pga_g = NAN, .scale_to_lambda0 = NAN, .history = 1,
                     .store_records = 1};
  aq_status st = aq_h5_write_root(w, &root, &err);
  for (size_t k = 0; st == AQ_OK && k < nrec; k++) {
    aq_processed p;
    memset(&p, 0, sizeof p);
    p.acc_mps2 = wave[k];
    p.n = nwave[k];
    p.dt_s = 0.01;
    p.used = so;
    aq_h5_record hr = {.source_file = "r.AT2", .proc = &p, .status = "ok"};
    st = aq_h5_write_record(w, k, &hr, &err);
  }
  for (size_t k = 0; st == AQ_OK && k < nrun; k++) {
    aq_summary s;
    aq_summary_fill(&s, "r.AT2", "a", "workpath", 1, 0.1, "ok", &runs[k].res);
    unsigned ri = 0, ai = 0, si = 0;
    sscanf(runs[k].key, "%5u_%3u_%3u", &ri, &ai, &si);
    aq_summary_normalise(&s, strchr(runs[k].key, 'r') ? "reversed" : "normal", &runs[k].res,
                         NULL, NULL);
    st = aq_h5_write_run(w, ri, ai, si, &s, &runs[k].res, NULL, 0, &err);
  }
  if (st != AQ_OK) {
    aq_h5_abort(w);
    return NAN;
  }
  if (aq_h5_finish(w, NULL, &err) != AQ_OK)
    return NAN;
  return aq_bench_now_s() - t0;
}

/* Every history value of path equal to the one in memory. */
static int same_values(const char *path)
{
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  int ok = f >= 0;
  for (size_t k = 0; ok && k < nrun; k++) {
    char name[96];
    snprintf(name, sizeof name, "/histories/%s", runs[k].key);
    hid_t g = H5Gopen2(f, name, H5P_DEFAULT);
    size_t n;
    double *t = read_doubles(g, "time_s", &n), *q = read_doubles(g, "rotation_rad", &n);
    const aq_history *h = &runs[k].res.history;
    ok = n == h->n && !memcmp(t, h->time_s, n * sizeof *t) &&
         !memcmp(q, h->rotation_rad, n * sizeof *q);
    free(t);
    free(q);
    H5Gclose(g);
  }
  if (f >= 0)
    H5Fclose(f);
  return ok;
}

int main(void)
{
  char cmd[4096];
  mkdir("build/tmp", 0777);
  mkdir(DIR, 0777);
  snprintf(cmd, sizeof cmd,
           "XDG_CACHE_HOME=%s/xdg ./archquake tests/data/records/*.AT2 --arch arches/bridge.cfg "
           "--arch arches/oppenheim.cfg --arch arches/thin.cfg --scale 1,2 --polarity both "
           "--history --store-records -q -o %s/suite.h5 > /dev/null 2>&1",
           DIR, DIR);
  if (system(cmd) != 0 && access(DIR "/suite.h5", R_OK) != 0) {
    fprintf(stderr, "bench_h5: the suite failed: %s\n", cmd);
    return 1;
  }
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(DIR "/suite.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t g = H5Gopen2(f, "/histories", H5P_DEFAULT);
  H5G_info_t info;
  H5Gget_info(g, &info);
  runs = calloc(info.nlinks, sizeof *runs);
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, NULL, one_run, NULL);
  H5Gclose(g);
  g = H5Gopen2(f, "/waveforms", H5P_DEFAULT);
  H5Gget_info(g, &info);
  for (hsize_t k = 0; k < info.nlinks && nrec < 64; k++) {
    char name[32];
    snprintf(name, sizeof name, "%05llu", (unsigned long long)k);
    wave[nrec] = read_doubles(g, name, &nwave[nrec]);
    nrec++;
  }
  H5Gclose(g);
  H5Fclose(f);
  size_t samples = 0, wsamples = 0;
  for (size_t k = 0; k < nrun; k++)
    samples += runs[k].res.history.n;
  for (size_t k = 0; k < nrec; k++)
    wsamples += nwave[k];
  printf("bench_h5: %zu runs (%.0f history samples each on average), %zu waveforms "
         "(%zu samples), %d repetitions\n",
         nrun, (double)samples / (double)nrun, nrec, wsamples, REPS);
  double t[NLEVEL][REPS], ratio[NLEVEL][REPS], size[NLEVEL];
  int same[NLEVEL];
  write_at(0, DIR "/warm.h5"); /* untimed */
  for (int r = 0; r < REPS; r++)
    for (int l = 0; l < NLEVEL; l++) {
      char path[128];
      snprintf(path, sizeof path, DIR "/level%d.h5", LEVELS[l]);
      t[l][r] = write_at(LEVELS[l], path);
      struct stat sb;
      size[l] = stat(path, &sb) == 0 ? (double)sb.st_size : NAN;
      if (r == 0)
        same[l] = same_values(path);
    }
  for (int r = 0; r < REPS; r++)
    for (int l = 0; l < NLEVEL; l++)
      ratio[l][r] = t[l][r] / t[0][r];
  printf("%-10s %10s %12s %14s %22s %s\n", "level", "MB/run", "size ratio", "ms/run",
         "time ratio [min, max]", "values");
  for (int l = 0; l < NLEVEL; l++) {
    double med = aq_bench_median(t[l], REPS), rmed = aq_bench_median(ratio[l], REPS);
    char label[16];
    snprintf(label, sizeof label, LEVELS[l] ? "deflate %d" : "stored", LEVELS[l]);
    printf("%-10s %10.4f %12.4f %14.3f %8.2f [%.2f, %.2f] %s\n", label,
           size[l] / (double)nrun / 1e6, size[l] / size[0], 1e3 * med / (double)nrun, rmed,
           ratio[l][0], ratio[l][REPS - 1], same[l] ? "same" : "DIFFER");
  }
  return 0;
}
