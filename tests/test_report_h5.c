/* test_report_h5.c: the HDF5 writer on synthetic records, arches and runs,
 * read back with the HDF5 C API directly (not through archquake's reader)
 * and with h5dump; failure paths: unwritable directory, a write that fails
 * for lack of space (RLIMIT_FSIZE in a child), an existing target left
 * untouched, no temporary left behind. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "report/h5.h"
#include "report/report.h"

enum { NACC = 1237, NHIST = 311 };

typedef struct {
  aq_record rec;
  aq_processed proc;
  aq_im im;
  double acc[NACC];
  aq_path path[2];
  aq_arch_dynamics dyn;
  aq_summary sum[4];
  aq_result res[4];
  double t[NHIST], q[NHIST], x[NHIST], ke[NHIST], pe[NHIST];
  int set[NHIST];
} fixture;

static void make_fixture(fixture *fx, size_t nhist)
{
  memset(fx, 0, sizeof *fx);
  fx->rec.path = "records/synthetic.AT2";
  fx->rec.name = "synthetic.AT2";
  snprintf(fx->rec.format, sizeof fx->rec.format, "at2");
  fx->rec.npts = 1000;
  fx->rec.dt_s = 0.005;
  fx->rec.begin_s = -0.25;
  snprintf(fx->rec.units_orig, sizeof fx->rec.units_orig, "g");
  fx->rec.to_mps2 = 9.80665;
  snprintf(fx->rec.station, sizeof fx->rec.station, "ELC");
  for (size_t i = 0; i < NACC; i++)
    fx->acc[i] = 0.731 * sin(0.0173 * (double)i * (double)i) * exp(-1e-3 * (double)i);
  fx->proc.n = NACC;
  fx->proc.dt_s = 0.005;
  fx->proc.pad_front = 118;
  fx->proc.pad_back = 119;
  fx->proc.n_orig = 1000;
  fx->proc.acc_mps2 = fx->acc;
  fx->proc.used.detrend = AQ_DETREND_LINEAR;
  fx->proc.used.taper_frac = 0.0375;
  fx->proc.used.filter = 1;
  fx->proc.used.highpass_hz = 0.0625;
  fx->proc.used.order = 6;
  fx->proc.used.lowpass_hz = 0;
  fx->proc.used.scale = 1;
  fx->im = (aq_im){.pga_g = 0.2816, .pgv_mps = 0.3317, .pgd_m = 0.0912, .arias_mps = 1.7436,
                   .d5_95_s = 24.125, .cav_mps = 8.9125, .v_end_mps = 1.5e-4, .d_end_m = -2.5e-3};
  fx->path[0] = (aq_path){.name = "primary", .mass_kg = 19634.954, .g_mps2 = 9.80665,
                          .lambda0 = 0.1743219, .s_c_rad = 0.3491237,
                          .act_sign = 1, .q_sign = -1, .admissible = 1};
  fx->path[1] = fx->path[0];
  fx->path[1].name = "reverse";
  fx->path[1].lambda0 = 0.1811;
  fx->path[1].s_c_rad = 0.2977;
  fx->path[1].admissible = 0;
  fx->dyn = (aq_arch_dynamics){.cor = 0.55, .impact = AQ_IMPACT_MOMENTUM, .g_mps2 = 9.80665};
  for (size_t i = 0; i < nhist; i++) {
    fx->t[i] = -0.59 + 0.005 * (double)i;
    fx->q[i] = 1e-3 * sin(0.1 * (double)i);
    fx->x[i] = 2.3e-3 * cos(0.07 * (double)i);
    fx->ke[i] = 17.5 * (double)i;
    fx->pe[i] = 4.25 * (double)(i % 7);
    fx->set[i] = (int)(i % 3) - 1;
  }
  for (int k = 0; k < 4; k++) {
    aq_result *r = &fx->res[k];
    r->collapsed = k == 1;
    r->collapse_time_s = k == 1 ? 3.8724110395 : NAN;
    r->peak_rotation_rad = 0.0123 * (k + 1.37);
    r->peak_displacement_m = 0.00421 * (k + 2.11);
    r->max_kinetic_energy_j = 123.4567 * (k + 0.5);
    r->impacts = (size_t)(3 * k + 2);
    r->energy_in_j = 991.25 * (k + 1);
    r->energy_dissipated_j = 11.125 * k;
    r->reversals = (size_t)k;
    r->steps_total = 1237;
    r->steps_moving = (size_t)(100 + k);
    r->evals = (size_t)(5000 + 17 * k);
    if (k == 0 && nhist) {
      r->history.n = nhist;
      r->history.time_s = fx->t;
      r->history.rotation_rad = fx->q;
      r->history.displacement_m = fx->x;
      r->history.kinetic_energy_j = fx->ke;
      r->history.potential_energy_j = fx->pe;
      r->history.set = fx->set;
    }
  }
  static const double scale[4] = {0.5, 1.25, 0.5, 1.25};
  static const char *const arch[4] = {"oppenheim", "oppenheim", "thin", "thin"};
  for (int k = 0; k < 4; k++)
    aq_summary_fill(&fx->sum[k], "records/synthetic.AT2", arch[k], "workpath",
                    scale[k], 0.2816 * scale[k], "ok", &fx->res[k]);
}

static aq_status write_fixture_to(aq_h5_writer *w, fixture *fx, aq_error *err);

/* Write the fixture to target; returns the status of the first failing call. */
static aq_status write_fixture(const char *target, fixture *fx, aq_error *err)
{
  aq_h5_writer *w;
  aq_status st = aq_h5_open(target, &w, err);
  if (st != AQ_OK)
    return st;
  st = write_fixture_to(w, fx, err);
  if (st != AQ_OK) {
    aq_h5_abort(w);
    return st;
  }
  aq_h5_timing tm = {1, 0.1, 0.2, 0.6, 0.1};
  return aq_h5_finish(w, &tm, err); /* frees w whatever happens */
}

static aq_status write_fixture_to(aq_h5_writer *w, fixture *fx, aq_error *err)
{
  aq_status st;
  aq_signal_opts req = fx->proc.used;
  static const double scales[2] = {0.5, 1.25};
  aq_h5_root root = {"9.9.9", "archquake records/synthetic.AT2 --arch a.cfg -o x.h5",
                     "2026-11-22T14:00:00Z", &req, 0.001, "file", 0, "workpath",
                     NAN, scales, 2, NAN, 1, 2, "9.9.9 (v9.9.9-3-gabcdef1)", 1, "normal", NAN};
  if ((st = aq_h5_write_root(w, &root, err)) != AQ_OK)
    return st;
  for (size_t a = 0; a < 2; a++) {
    aq_h5_arch ha = {a ? "thin" : "oppenheim", a ? "arches/thin.cfg" : "arches/oppenheim.cfg",
                     "[arch]\nname = oppenheim\nradius_m = 5.0\n", &fx->dyn,
                     {&fx->path[0], &fx->path[1]},
                     a ? "5e1a" : "0a7b", (int)a, {"0,6,12,19", "0,6,12,19"},
                     {"eiei", "ieie"}, NULL, {NULL, NULL}};
    if ((st = aq_h5_write_arch(w, a, &ha, err)) != AQ_OK)
      return st;
  }
  aq_h5_record hr = {"records/synthetic.AT2", &fx->rec, &fx->proc, &fx->im, "ok",
                     NULL, "d01117c8", 0.01, 0.02};
  if ((st = aq_h5_write_record(w, 0, &hr, err)) != AQ_OK)
    return st;
  for (int k = 0; k < 4; k++)
    if ((st = aq_h5_write_run(w, 0, (size_t)k / 2, (size_t)k % 2, &fx->sum[k],
                              &fx->res[k], NULL, 0.003, err)) != AQ_OK)
      return st;
  return AQ_OK;
}

static double read_double_attr(hid_t loc, const char *name)
{
  double v = NAN;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0 || H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0)
    v = -12345.678;
  if (a >= 0)
    H5Aclose(a);
  return v;
}

static void read_str_attr(hid_t loc, const char *name, char *buf, size_t n)
{
  buf[0] = '\0';
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0)
    return;
  hid_t t = H5Aget_type(a);
  size_t sz = H5Tget_size(t);
  char *tmp = calloc(sz + 1, 1);
  if (tmp && H5Aread(a, t, tmp) >= 0)
    snprintf(buf, n, "%s", tmp);
  free(tmp);
  H5Tclose(t);
  H5Aclose(a);
}

static size_t read_dataset(hid_t loc, const char *name, double *v, size_t cap,
                           char *units, size_t ucap)
{
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  if (d < 0)
    return (size_t)-1;
  hid_t s = H5Dget_space(d);
  hssize_t n = H5Sget_simple_extent_npoints(s);
  size_t got = (size_t)-1;
  if (n >= 0 && (size_t)n <= cap && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                            H5P_DEFAULT, v) >= 0)
    got = (size_t)n;
  read_str_attr(d, "units", units, ucap);
  H5Sclose(s);
  H5Dclose(d);
  return got;
}

AQ_TEST(report_h5_layout_read_back)
{
  static fixture fx;
  make_fixture(&fx, NHIST);
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/suite.h5", dir);
  aq_error err;
  aq_error_clear(&err);
  aq_status st = write_fixture(path, &fx, &err);
  aq_check(st == AQ_OK, "write: %s", err.message);
  if (st != AQ_OK)
    return;

  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0, "reopen");
  char s[512];
  read_str_attr(f, "archquake_version", s, sizeof s);
  aq_check(strcmp(s, "9.9.9") == 0, "version %s", s);
  read_str_attr(f, "command_line", s, sizeof s);
  aq_check(strstr(s, "--arch a.cfg") != NULL, "command line %s", s);
  read_str_attr(f, "created", s, sizeof s);
  aq_check(strcmp(s, "2026-11-22T14:00:00Z") == 0, "created %s", s);
  read_str_attr(f, "detrend", s, sizeof s);
  aq_check(strcmp(s, "linear") == 0, "root detrend %s", s);
  aq_check(read_double_attr(f, "highpass_hz") == 0.0625, "root highpass");

  H5Fclose(f);

  /* Everything else through h5py (Debian python3-h5py), an independent
   * reader: the record table, the arch group, the run table with its units
   * attributes, the stored waveform and the one history. */
  char py[700], cmd[1400];
  snprintf(py, sizeof py, "%s/check.py", dir);
  FILE *pf = fopen(py, "w");
  aq_check(pf != NULL, "write %s", py);
  if (!pf)
    return;
  fprintf(pf,
          "import h5py, math, sys\n"
          "f = h5py.File(sys.argv[1], 'r')\n"
          "assert f.attrs['format_version'] == 2\n"
          "assert f.attrs['archquake_build'] == b'9.9.9 (v9.9.9-3-gabcdef1)'\n"
          "assert f.attrs['store_records'] == 1\n"
          "r = f['records'][:]\n"
          "assert len(r) == 1\n"
          "assert r['source_file'][0] == b'records/synthetic.AT2'\n"
          "assert r['name'][0] == b'synthetic.AT2' and r['format'][0] == b'at2'\n"
          "assert r['sha256'][0] == b'd01117c8' and r['station'][0] == b'ELC'\n"
          "assert r['dt_s'][0] == 0.005 and r['taper_frac'][0] == 0.0375\n"
          "assert r['highpass_hz'][0] == 0.0625 and r['highpass_order'][0] == 6\n"
          "assert math.isnan(r['lowpass_hz'][0])\n"
          "assert r['pad_front'][0] == 118 and r['pad_back'][0] == 119\n"
          "assert r['arias_m_s'][0] == 1.7436 and r['d5_95_s'][0] == 24.125\n"
          "assert f['records'].attrs['units_d5_95_s'] == b's'\n"
          "w = f[r['waveform'][0].decode()]\n"
          "assert w.shape == (%d,) and w.attrs['units'] == b'm/s^2'\n"
          "assert w.attrs['t0_s'] == -118 * 0.005\n"
          "a = f['arches/001'].attrs\n"
          "assert a['name'] == b'thin' and a['sha256'] == b'5e1a' and a['searched'] == 1\n"
          "assert a['config'] == b'[arch]\\nname = oppenheim\\nradius_m = 5.0\\n'\n"
          "assert a['primary_joints'] == b'0,6,12,19' and a['reverse_faces'] == b'ieie'\n"
          "assert a['primary_act_sign'] == 1 and a['primary_q_sign'] == -1\n"
          "assert a['primary_lambda0'] == 0.1743219 and a['reverse_q_c_rad'] == 0.2977\n"
          "assert a['primary_admissible'] == 1 and a['reverse_admissible'] == 0\n"
          "t = f['summary'][:]\n"
          "assert len(t) == 4\n"
          "assert list(t['impacts']) == [2, 5, 8, 11]\n"
          "assert list(t['arch_index']) == [0, 0, 1, 1] and list(t['scale_index']) == [0, 1, 0, 1]\n"
          "assert list(t['record_index']) == [0, 0, 0, 0]\n"
          "assert list(t['scale']) == [0.5, 1.25, 0.5, 1.25]\n"
          "assert math.isnan(t['collapse_time_s'][0]) and t['collapse_time_s'][1] == 3.8724110395\n"
          "assert list(t['path_evaluations']) == [5000, 5017, 5034, 5051]\n"
          "u = f['summary'].attrs\n"
          "assert u['units_peak_rotation_rad'] == b'rad' and u['units_pga_g'] == b'g'\n"
          "assert u['units_max_kinetic_energy_j'] == b'J' and u['units_scale'] == b'1'\n"
          "assert u['units_collapse_time_s'] == b's' and u['units_record'] == b''\n"
          "assert list(f['histories']) == ['00000_000_000']\n"
          "h = f['histories/00000_000_000']\n"
          "assert h['time_s'].shape == (%d,) and h['time_s'].attrs['units'] == b's'\n"
          "assert h['potential_energy_j'][5] == 4.25 * 5\n"
          "assert 'runs' not in f\n",
          NACC, NHIST);
  fclose(pf);
  snprintf(cmd, sizeof cmd, "/usr/bin/python3 '%s' '%s' 2>&1", py, path);
  aq_check(system(cmd) == 0, "h5py reads the file back as written (%s)", py);
  /* h5dump reads it too */
  snprintf(cmd, sizeof cmd, "h5dump -d /summary '%s' > /dev/null 2>&1", path);
  aq_check(system(cmd) == 0, "h5dump reads /summary");

  /* the waveform and the history are bit-identical (C API) */
  f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  static double acc[NACC + 1];
  char units[64];
  size_t n = read_dataset(f, "/waveforms/00000", acc, NACC + 1, units, sizeof units);
  aq_check(n == NACC && memcmp(acc, fx.acc, sizeof fx.acc) == 0,
           "waveform bit-identical (%zu values)", n);
  n = read_dataset(f, "/histories/00000_000_000/rotation_rad", acc, NACC, units,
                   sizeof units);
  aq_check(n == NHIST && memcmp(acc, fx.q, sizeof fx.q) == 0 && strcmp(units, "rad") == 0,
           "rotation history bit-identical");
  H5Fclose(f);

  /* archquake's own reader gives back exactly the summaries and inputs */
  aq_h5_suite back;
  aq_check(aq_h5_read_suite(path, &back, &err) == AQ_OK, "read suite: %s", err.message);
  aq_check(back.nruns == 4 && back.nrecords == 1 && back.narches == 2,
           "4 runs, 1 record, 2 arches read (%zu %zu %zu)", back.nruns, back.nrecords,
           back.narches);
  for (size_t k = 0; k < back.nruns && k < 4; k++)
    aq_check(memcmp(&back.runs[k].s.scale, &fx.sum[k].scale, sizeof(double)) == 0 &&
                 strcmp(back.runs[k].s.arch, fx.sum[k].arch) == 0 &&
                 back.runs[k].s.impacts == fx.sum[k].impacts &&
                 back.runs[k].s.peak_rotation_rad == fx.sum[k].peak_rotation_rad &&
                 back.runs[k].arch_index == (int64_t)k / 2,
             "run %zu read back", k);
  aq_check(back.nrecords == 1 && strcmp(back.records[0].sha256, "d01117c8") == 0 &&
               strcmp(back.records[0].name, "synthetic.AT2") == 0,
           "record identity read back");
  aq_check(back.narches == 2 && strcmp(back.arches[1].sha256, "5e1a") == 0 &&
               strcmp(back.arches[1].name, "thin") == 0,
           "arch identity read back");
  aq_h5_suite_free(&back);
  /* no temporary left beside it */
  DIR *dd = opendir(dir);
  int extra = 0;
  for (struct dirent *e; dd && (e = readdir(dd));)
    extra += strstr(e->d_name, ".tmp") != NULL;
  if (dd)
    closedir(dd);
  aq_check(extra == 0, "no temporary file left");
}

static int file_equals(const char *path, const char *want)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return 0;
  char buf[256];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  return strcmp(buf, want) == 0;
}

static int count_entries(const char *dir)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += e->d_name[0] != '.' || (e->d_name[1] && strcmp(e->d_name, "..") != 0);
  if (d)
    closedir(d);
  return n;
}

AQ_TEST(report_h5_unwritable_directory)
{
  static fixture fx;
  make_fixture(&fx, 0);
  aq_error err;
  aq_error_clear(&err);
  /* /proc refuses new files even to root; a missing directory likewise */
  aq_status st = write_fixture("/proc/archquake-test.h5", &fx, &err);
  aq_check(st == AQ_EIO, "unwritable: status %d", st);
  aq_check(strstr(err.input, "/proc/archquake-test.h5") != NULL, "names target");
  aq_check(strstr(err.message, "cannot create") != NULL, "clear message: %s",
           err.message);
  aq_check(access("/proc/archquake-test.h5", F_OK) != 0, "no file");
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/no/such/dir/x.h5", dir);
  aq_error_clear(&err);
  st = write_fixture(path, &fx, &err);
  aq_check(st == AQ_EIO, "missing dir: status %d", st);
  aq_check(strstr(err.message, "No such file") != NULL, "errno text: %s",
           err.message);
  aq_check(count_entries(dir) == 0, "nothing created in %s", dir);
}

/* A pseudo-random double in [1, 2), its 52 mantissa bits a hash of k and
 * i: samples that deflate cannot make much smaller than 8 bytes. */
static double noise(size_t k, size_t i)
{
  uint64_t x = (uint64_t)i * 0x9E3779B97F4A7C15u + (uint64_t)k * 0xD1B54A32D192ED03u + 1;
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9u;
  x ^= x >> 29;
  return 1.0 + (double)(x >> 12) * 0x1p-52;
}

/* Child: write with the file size limited to limit bytes (SIGXFSZ ignored,
 * so writes fail with EFBIG as on a full disk).  Exit 0 if the writer
 * reported AQ_EIO with a message, 10 + status otherwise. */
static int child_write_limited(const char *target, rlim_t limit)
{
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl = {limit, limit};
    setrlimit(RLIMIT_FSIZE, &rl);
    static fixture fx;
    make_fixture(&fx, NHIST);
    /* make the processed record big enough to cross the limit */
    size_t big = 400000;
    double *acc = calloc(big, sizeof *acc);
    for (size_t i = 0; acc && i < big; i++)
      acc[i] = noise(7, i); /* deflate leaves it near 8 bytes a sample */
    fx.proc.acc_mps2 = acc;
    fx.proc.n = big;
    aq_error err;
    aq_error_clear(&err);
    aq_status st = write_fixture(target, &fx, &err);
    free(acc);
    if (st == AQ_EIO && err.message[0]) {
      fprintf(stderr, "  (expected failure: %s)\n", err.message);
      _exit(0);
    }
    _exit(10 + (int)st);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid)
    return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

AQ_TEST(report_h5_failing_write_leaves_target_untouched)
{
  char dir[512], path[700], ref[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(ref, sizeof ref, "%s/reference.h5", dir);
  aq_check(child_write_limited(ref, RLIM_INFINITY) == 10, "unlimited write succeeds");
  struct stat sb;
  rlim_t full = stat(ref, &sb) == 0 ? (rlim_t)sb.st_size : 0;
  aq_check(full > 2400000, "file size %lu (3.2 MB of samples, deflated)", (unsigned long)full);
  unlink(ref);
  snprintf(path, sizeof path, "%s/suite.h5", dir);
  FILE *f = fopen(path, "w");
  fputs("last night's results\n", f);
  fclose(f);
  /* fails on the big dataset (64 KiB), and when only the last few hundred
   * bytes (metadata flushed at close) cross the limit */
  const rlim_t limits[] = {64 * 1024, full - 300};
  for (size_t i = 0; i < 2; i++) {
    int rc = child_write_limited(path, limits[i]);
    aq_check(rc == 0, "limit %lu: writer reported the failure (child %d)",
             (unsigned long)limits[i], rc);
    aq_check(file_equals(path, "last night's results\n"),
             "existing target untouched");
    aq_check(count_entries(dir) == 1, "no temporary left (%d entries)",
             count_entries(dir));
  }
  /* without the limit the same write succeeds and replaces the target */
  aq_check(child_write_limited(path, RLIM_INFINITY) == 10, "unlimited: no failure");
  aq_check(!file_equals(path, "last night's results\n"), "target replaced");
  aq_check(count_entries(dir) == 1, "still one file");
}

/* n runs through the writer, read back with the HDF5 library: the rows in
 * run order, each exact.  Returns the number of bad rows (n + 1: not read). */
static size_t summary_rows_read_back(size_t n)
{
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/many%zu.h5", dir, n);
  aq_h5_writer *w;
  aq_error err;
  if (aq_h5_open(path, &w, &err) != AQ_OK)
    return n + 1;
  aq_status st = AQ_OK;
  for (size_t k = 0; k < n && st == AQ_OK; k++) {
    aq_result r;
    memset(&r, 0, sizeof r);
    r.peak_rotation_rad = 1e-3 * sin(0.731 * (double)k);
    r.impacts = k * 7 % 13;
    aq_summary s;
    char rec[64];
    snprintf(rec, sizeof rec, "records/r%zu.AT2", k);
    aq_summary_fill(&s, rec, "oppenheim", "workpath", 1.5, 0.25, "ok", &r);
    st = aq_h5_write_run(w, k, 0, 0, &s, &r, NULL, 0, &err);
  }
  if (st != AQ_OK) {
    aq_h5_abort(w);
    return n + 1;
  }
  if (aq_h5_finish(w, NULL, &err) != AQ_OK)
    return n + 1;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(f, "/summary", H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  typedef struct {
    char *record; /* a variable-length string: the path whole */
    double rot;
    long long impacts;
  } row;
  hid_t mt = H5Tcreate(H5T_COMPOUND, sizeof(row));
  hid_t s32 = H5Tcopy(H5T_C_S1);
  H5Tset_size(s32, H5T_VARIABLE);
  H5Tinsert(mt, "record", HOFFSET(row, record), s32);
  H5Tinsert(mt, "peak_rotation_rad", HOFFSET(row, rot), H5T_NATIVE_DOUBLE);
  H5Tinsert(mt, "impacts", HOFFSET(row, impacts), H5T_NATIVE_LLONG);
  row *rows = calloc(n, sizeof *rows);
  size_t bad = n + 1;
  if (rows && H5Sget_simple_extent_npoints(sp) == (hssize_t)n &&
      H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0) {
    bad = 0;
    for (size_t k = 0; k < n; k++) {
      char rec[64];
      snprintf(rec, sizeof rec, "records/r%zu.AT2", k);
      bad += !rows[k].record || strcmp(rows[k].record, rec) != 0 ||
             rows[k].rot != 1e-3 * sin(0.731 * (double)k) ||
             rows[k].impacts != (long long)(k * 7 % 13);
    }
    H5Dvlen_reclaim(mt, sp, H5P_DEFAULT, rows);
  }
  free(rows);
  H5Tclose(s32);
  H5Tclose(mt);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  return bad;
}

AQ_TEST(report_h5_summary_table_many_runs)
{
  /* more rows than one chunk of the table (256 rows), in run order: a chunk
   * exactly, one row over, several chunks and a part */
  static const size_t n[] = {1, 256, 257, 613};
  for (size_t i = 0; i < sizeof n / sizeof n[0]; i++) {
    size_t bad = summary_rows_read_back(n[i]);
    aq_check(bad == 0, "%zu runs: rows in order and exact (%zu bad; %zu: not read)", n[i], bad,
             n[i] + 1);
  }
}

/* Several records whose datasets add up to more than the writer's
 * background-sync step (8 MiB): records k = 0..NBIG-1 of NBIG_N samples
 * each, sample i of record k a pseudo-random double in [1, 2) (its 52
 * mantissa bits from a hash of k and i), so that the deflated waveforms
 * (docs/hdf5-layout.md, "Compression") are not much smaller than 8 bytes
 * a sample. */
enum { NBIG = 4, NBIG_N = 450000 };

static double big_value(size_t k, size_t i)
{
  return noise(k, i);
}

static aq_status write_big(const char *target, aq_error *err)
{
  static fixture fx;
  make_fixture(&fx, 0);
  double *acc = malloc(NBIG_N * sizeof *acc);
  if (!acc)
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  aq_h5_writer *w;
  aq_status st = aq_h5_open(target, &w, err);
  if (st != AQ_OK) {
    free(acc);
    return st;
  }
  aq_h5_root root = {"9.9.9", "big", "2026-11-22T14:00:00Z", &fx.proc.used, 0, "file", 0,
                     "workpath", NAN, NULL, 1, 0.3, 0, 1, NULL, 1 /* store_records */, "normal", NAN};
  st = aq_h5_write_root(w, &root, err);
  for (size_t k = 0; k < NBIG && st == AQ_OK; k++) {
    for (size_t i = 0; i < NBIG_N; i++)
      acc[i] = big_value(k, i);
    fx.proc.acc_mps2 = acc;
    fx.proc.n = NBIG_N;
    aq_h5_record hr = {"records/synthetic.AT2", &fx.rec, &fx.proc, &fx.im, "ok",
                       NULL, NULL, 0.01, 0.02};
    st = aq_h5_write_record(w, k, &hr, err);
    if (st == AQ_OK)
      st = aq_h5_write_run(w, k, 0, 0, &fx.sum[0], &fx.res[0], NULL, 0.003, err);
  }
  free(acc);
  if (st != AQ_OK) {
    aq_h5_abort(w);
    return st;
  }
  return aq_h5_finish(w, NULL, err);
}

AQ_TEST(report_h5_large_file_reads_back_exactly)
{
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/big.h5", dir);
  aq_error err;
  aq_error_clear(&err);
  aq_check(write_big(path, &err) == AQ_OK, "written: %s", err.message);
  aq_check(count_entries(dir) == 1, "only the target (%d entries)", count_entries(dir));
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0, "opens");
  if (f < 0)
    return;
  double *v = malloc(NBIG_N * sizeof *v);
  for (size_t k = 0; v && k < NBIG; k++) {
    char g[64], units[32];
    snprintf(g, sizeof g, "/waveforms/%05zu", k);
    size_t n = read_dataset(f, g, v, NBIG_N, units, sizeof units);
    aq_check(n == NBIG_N, "%s: %zu samples", g, n);
    size_t bad = 0;
    for (size_t i = 0; n == NBIG_N && i < NBIG_N; i++)
      bad += v[i] != big_value(k, i);
    aq_check(bad == 0, "%s: every sample exact (%zu differ)", g, bad);
    aq_check(strcmp(units, "m/s^2") == 0, "units %s", units);
  }
  free(v);
  hid_t d = H5Dopen2(f, "/summary", H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  aq_check(H5Sget_simple_extent_npoints(sp) == NBIG, "%d summary rows", NBIG);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
}

AQ_TEST(report_h5_large_file_failing_late_leaves_nothing)
{
  /* the limit falls in the last record, after more than 8 MiB were
     written: halfway through it, in the file the same write makes */
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/big.h5", dir);
  aq_error e0;
  struct stat sb;
  rlim_t full = write_big(path, &e0) == AQ_OK && stat(path, &sb) == 0 ? (rlim_t)sb.st_size : 0;
  unlink(path);
  aq_check(full > (rlim_t)NBIG * NBIG_N * 6, "the whole file: %lu bytes", (unsigned long)full);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    rlim_t limit = full / (2 * NBIG) * (2 * NBIG - 1);
    struct rlimit rl = {limit, limit};
    setrlimit(RLIMIT_FSIZE, &rl);
    aq_error err;
    aq_error_clear(&err);
    aq_status st = write_big(path, &err);
    if (st == AQ_EIO && err.message[0])
      fprintf(stderr, "  (expected failure: %s)\n", err.message);
    _exit(st == AQ_EIO && err.message[0] ? 0 : 10 + (int)st);
  }
  int status = -1;
  aq_check(pid > 0 && waitpid(pid, &status, 0) == pid, "child ran");
  aq_check(WIFEXITED(status) && WEXITSTATUS(status) == 0,
           "writer reported the failure (status %d)", status);
  aq_check(count_entries(dir) == 0, "no file left (%d entries)", count_entries(dir));
}
