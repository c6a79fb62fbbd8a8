/* test_plot_cli.c: `archquake plot`: every figure in every format is a
 * valid PNG (signature, IHDR), SVG (parsed as XML by python3) or PDF
 * (header, %%EOF); the axis titles carry units; the plotted data (--data)
 * equal the values in the results file, read here with the HDF5 library,
 * or outside references (the arch file's radii, rigid-body motion, the
 * `domain` command, the main job's TSV); bad input is one line and leaves
 * no file. */
#include <dirent.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "report/h5_spectrum.h"

#define RECORD "tests/data/records/ARL360.at2"
#define ARCH "arches/oppenheim.cfg"

/* The results file of ARL360 x oppenheim at scales 5 (survives, 29
 * impacts) and 10 (collapses after 13), with histories and the processed
 * record; made once per runner. */
static const char *results(void)
{
  static char path[600];
  if (path[0])
    return path;
  char dir[512], args[1400], err[2048];
  aq_test_shared_dir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/hist.h5", dir);
  snprintf(args, sizeof args,
           RECORD " --arch " ARCH " --scale 5,10 --polarity normal --history --store-records -o %s",
           path);
  if (aq_test_run(args, NULL, 0, err, sizeof err) != 0)
    fprintf(stderr, "test_plot_cli: cannot make %s: %s\n", path, err);
  return path;
}

/* Values of series name (first column) of a history CSV, the time column
 * into t (may be NULL); returns the count (at most cap). */
static size_t series(const char *csv, const char *name, double *t, double *v, size_t cap)
{
  size_t n = 0, len = strlen(name);
  for (const char *p = csv; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
    if (strncmp(p, name, len) == 0 && p[len] == ',' && n < cap) {
      char *e;
      double a = strtod(p + len + 1, &e);
      double b = strtod(e + 1, NULL);
      if (t)
        t[n] = a;
      v[n++] = b;
    }
  return n;
}

static double *dataset(hid_t f, const char *name, size_t *n)
{
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  hid_t s = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : 0;
  double *v = np > 0 ? malloc((size_t)np * sizeof *v) : NULL;
  if (v && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    free(v);
    v = NULL;
  }
  *n = v ? (size_t)np : 0;
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  return v;
}

/* Column name (a number) of row `row` of the compound table obj. */
static double table_value(hid_t f, const char *obj, size_t row, const char *name)
{
  double v = NAN, *all = NULL;
  hid_t d = H5Dopen2(f, obj, H5P_DEFAULT), s = d >= 0 ? H5Dget_space(d) : -1;
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(double));
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : 0;
  if (np > (hssize_t)row && H5Tinsert(t, name, 0, H5T_NATIVE_DOUBLE) >= 0 &&
      (all = malloc((size_t)np * sizeof *all)) &&
      H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, all) >= 0)
    v = all[row];
  free(all);
  H5Tclose(t);
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  return v;
}

/* Column name (a number) of row `row` of /summary. */
static double summary(hid_t f, size_t row, const char *name)
{
  return table_value(f, "/summary", row, name);
}

static double attr(hid_t f, const char *obj, const char *name)
{
  double v = NAN;
  hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
  }
  return v;
}

static unsigned long be32(const unsigned char *p)
{
  return (unsigned long)p[0] << 24 | (unsigned long)p[1] << 16 | (unsigned long)p[2] << 8 | p[3];
}

/* 1 if path is a valid file of its extension's format. */
static int valid(const char *path)
{
  size_t n = 0;
  unsigned char *b = (unsigned char *)aq_test_read_file(path, &n);
  int ok = 0;
  const char *ext = strrchr(path, '.');
  if (b && !strcmp(ext, ".png")) {
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned long w = n >= 24 ? be32(b + 16) : 0, h = n >= 24 ? be32(b + 20) : 0;
    ok = n > 33 && !memcmp(b, sig, 8) && be32(b + 8) == 13 && !memcmp(b + 12, "IHDR", 4) &&
         w >= 400 && w <= 4000 && h >= 300 && h <= 4000;
    aq_check(ok, "%s: PNG signature and IHDR (%lu x %lu px)", path, w, h);
  } else if (b && !strcmp(ext, ".svg")) {
    char cmd[800];
    snprintf(cmd, sizeof cmd,
             "python3 -c 'import sys, xml.etree.ElementTree as E; "
             "r = E.parse(sys.argv[1]).getroot(); sys.exit(not r.tag.endswith(\"svg\"))' '%s'",
             path);
    ok = system(cmd) == 0;
    aq_check(ok, "%s: parses as XML with an <svg> root (%zu bytes)", path, n);
  } else if (b && !strcmp(ext, ".pdf")) {
    size_t tail = n > 64 ? n - 64 : 0;
    int eof = 0;
    for (size_t i = tail; i + 5 <= n; i++)
      eof |= !memcmp(b + i, "%%EOF", 5);
    ok = n > 100 && !memcmp(b, "%PDF-", 5) && eof;
    aq_check(ok, "%s: %%PDF- header and %%%%EOF trailer (%zu bytes)", path, n);
  } else
    aq_check(0, "%s: not written", path);
  free(b);
  return ok;
}

/* Files in dir other than the test's stdout/stderr. */
static size_t files_in(const char *dir)
{
  size_t n = 0;
  DIR *d = opendir(dir);
  struct dirent *e;
  while (d && (e = readdir(d)))
    n += e->d_name[0] != '.' && strcmp(e->d_name, "stdout") && strcmp(e->d_name, "stderr");
  if (d)
    closedir(d);
  return n;
}

AQ_TEST(plot_every_figure_every_format)
{
  const char *h5 = results();
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const fmt[] = {"png", "svg", "pdf"};
  char figs[4][700];
  snprintf(figs[0], sizeof figs[0], "plot history %s --run 00000_000_001", h5);
  snprintf(figs[1], sizeof figs[1], "plot arch --arch " ARCH " --rotation 0.1");
  snprintf(figs[2], sizeof figs[2], "plot domain --arch " ARCH " --ratios 1.5,3");
  snprintf(figs[3], sizeof figs[3], "plot suite %s", h5);
  size_t made = 0;
  for (size_t i = 0; i < 4; i++)
    for (size_t k = 0; k < 3; k++) {
      char out[600], args[3500], err[1024];
      snprintf(out, sizeof out, "%s/fig%zu.%s", dir, i, fmt[k]);
      snprintf(args, sizeof args, "%s -o %s", figs[i], out);
      int rc = aq_test_run(args, NULL, 0, err, sizeof err);
      aq_check(rc == 0 && err[0] == '\0', "%s: exit %d, stderr \"%s\"", args, rc, err);
      made += valid(out);
    }
  aq_check(made == 12 && files_in(dir) == 12, "12 figures, no other file (%zu valid, %zu files)",
           made, files_in(dir));
}

/* Every "# axis:" line of the CSV ends with a unit in parentheses. */
static void check_axes(const char *csv, size_t want, const char *what)
{
  size_t n = 0, with_unit = 0;
  for (const char *p = strstr(csv, "# axis: "); p; p = strstr(p + 1, "# axis: ")) {
    const char *nl = strchr(p, '\n');
    n++;
    with_unit += nl && nl - p > 3 && nl[-1] == ')' && memchr(p, '(', (size_t)(nl - p));
  }
  aq_check(n == want && with_unit == want, "%s: %zu axis titles, %zu with a unit (want %zu)",
           what, n, with_unit, want);
}

AQ_TEST(plot_history_data_are_the_results)
{
  const char *h5 = results();
  char dir[512], out[600], data[600], args[1600], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0, "open %s", h5);
  if (f < 0)
    return;
  enum { CAP = 200000 };
  double *t = malloc(CAP * sizeof *t), *v = malloc(CAP * sizeof *v);
  for (int run = 0; run < 2; run++) {
    char obj[64], path[128];
    snprintf(obj, sizeof obj, "/histories/00000_000_00%d", run);
    snprintf(out, sizeof out, "%s/h%d.png", dir, run);
    snprintf(data, sizeof data, "%s/h%d.csv", dir, run);
    snprintf(args, sizeof args, "plot history %s --run 00000_000_00%d -o %s --data %s", h5,
             run, out, data);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "%s: exit %d, %s", args, rc, err);
    char *csv = aq_test_read_file(data, NULL);
    aq_check(csv != NULL, "%s written", data);
    if (!csv)
      continue;
    check_axes(csv, 4, "history");
    /* the histories, sample by sample */
    static const char *const names[] = {"rotation_rad", "kinetic_energy_j", "potential_energy_j"};
    size_t nt = 0;
    snprintf(path, sizeof path, "%s/time_s", obj);
    double *ts = dataset(f, path, &nt);
    for (size_t j = 0; j < 3; j++) {
      size_t nd = 0, differ = 0;
      snprintf(path, sizeof path, "%s/%s", obj, names[j]);
      double *d = dataset(f, path, &nd);
      size_t nc = series(csv, names[j], t, v, CAP);
      for (size_t i = 0; i < nc && i < nd && ts; i++)
        differ += v[i] != d[i] || t[i] != ts[i];
      aq_check(d && nc == nd && nd == nt && differ == 0,
               "%s %s: %zu plotted samples equal to the file's %zu (%zu differ)", obj, names[j],
               nc, nd, differ);
      free(d);
    }
    free(ts);
    /* the ground: its peak is the run's PGA (the suite's own measure) */
    size_t ng = series(csv, "ground_accel_g", NULL, v, CAP);
    double peak = 0;
    for (size_t i = 0; i < ng; i++)
      peak = fmax(peak, fabs(v[i]));
    aq_check_rel(peak, summary(f, (size_t)run, "pga_g"), 1e-12, "%s: peak plotted ground = pga_g", obj);
    /* work in: accumulated from the displacement, ends at the run's energy_in_j */
    size_t nw = series(csv, "work_in_j", NULL, v, CAP);
    aq_check(nw > 0, "%s: work_in_j plotted", obj);
    if (nw)
      aq_check_rel(v[nw - 1], summary(f, (size_t)run, "energy_in_j"), 1e-9,
                   "%s: last work in = energy_in_j", obj);
    double lam = attr(f, "/arches/000", "primary_lambda0");
    aq_check(series(csv, "primary_lambda0_g", NULL, v, CAP) == 1 && v[0] == lam,
             "%s: lambda0 line at the file's primary_lambda0 %.6g g", obj, lam);
    /* every impact marked: the histories sample each impact (q = 0) */
    size_t ni = series(csv, "impact", NULL, v, CAP);
    aq_check_abs((double)ni, summary(f, (size_t)run, "impacts"), 0, "%s: impact marks = impacts", obj);
    if (run == 0) {
      aq_check(series(csv, "collapse", NULL, v, CAP) == 0, "%s: no collapse mark", obj);
    } else {
      aq_check(series(csv, "collapse", t, v, CAP) == 1 &&
                   t[0] == summary(f, (size_t)run, "collapse_time_s") && summary(f, (size_t)run, "collapsed") == 1,
               "%s: collapse marked at collapse_time_s", obj);
    }
    free(csv);
  }
  free(t);
  free(v);
  H5Fclose(f);
}

/* --history stores the ground the histories answer (as --store-records):
 * the figure draws it and the work put in.  A file without it (one written
 * before, here the same with its /waveforms removed by h5py) is drawn
 * without them. */
AQ_TEST(plot_history_ground_with_history)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/h.h5", dir);
  snprintf(args, sizeof args, RECORD " --arch " ARCH " --scale 10 --history -o %s", h5);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "results: %s", err);
  snprintf(out, sizeof out, "%s/h.png", dir);
  snprintf(data, sizeof data, "%s/h.csv", dir);
  for (int old = 0; old < 2; old++) {
    if (old) {
      char cmd[1400];
      snprintf(cmd, sizeof cmd,
               "/usr/bin/python3 -c \"import h5py, sys\n"
               "with h5py.File(sys.argv[1], 'r+') as f:\n"
               "    del f['waveforms']\n"
               "\" %s", h5);
      aq_check(system(cmd) == 0, "h5py removes the waveforms");
    }
    snprintf(args, sizeof args, "plot history %s -o %s --data %s", h5, out, data);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
    valid(out);
    char *csv = aq_test_read_file(data, NULL);
    double v[4];
    size_t ng = csv ? series(csv, "ground_accel_g", NULL, v, 4) : 0;
    size_t nw = csv ? series(csv, "work_in_j", NULL, v, 4) : 0;
    size_t nq = csv ? series(csv, "rotation_rad", NULL, v, 4) : 0;
    aq_check(csv && nq == 4 && (old ? ng == 0 && nw == 0 : ng == 4 && nw == 4),
             "%s: ground %zu, work in %zu, rotation %zu samples plotted",
             old ? "a file without the ground" : "--history", ng, nw, nq);
    free(csv);
  }
}

/* Rows "series,index,x,y" of an arch CSV into x, y; returns the count. */
static size_t points(const char *csv, const char *name, double *x, double *y, size_t cap)
{
  size_t n = 0, len = strlen(name);
  for (const char *p = csv; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
    if (strncmp(p, name, len) == 0 && p[len] == ',' && n < cap) {
      char *e;
      strtol(p + len + 1, &e, 10);
      x[n] = strtod(e + 1, &e);
      y[n++] = strtod(e + 1, NULL);
    }
  return n;
}

AQ_TEST(plot_arch_to_scale_and_rigid)
{
  char dir[512], out[600], data[600], args[1400], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(out, sizeof out, "%s/a.svg", dir);
  snprintf(data, sizeof data, "%s/a.csv", dir);
  const double rot = 0.1234;
  snprintf(args, sizeof args, "plot arch --arch " ARCH " --rotation %.4f -o %s --data %s", rot,
           out, data);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d, %s", args, rc, err);
  char *csv = aq_test_read_file(data, NULL);
  if (!aq_check(csv != NULL, "%s written", data))
    return;
  check_axes(csv, 2, "arch");
  enum { CAP = 200 };
  double x[CAP], y[CAP], dx[CAP], dy[CAP];
  /* oppenheim.cfg: radius_m 5.0, thickness_m 1.25, 20 voussoirs, 180 deg */
  const double r_e = 5.0 + 0.625, r_i = 5.0 - 0.625, TOL_M = 1e-12;
  size_t n = points(csv, "corner", x, y, CAP), bad = 0;
  for (size_t i = 0; i < n; i++) {
    double r = hypot(x[i], y[i]), want = (i % 4 < 2) ? r_e : r_i;
    bad += fabs(r - want) > TOL_M;
  }
  aq_check(n == 80 && bad == 0, "80 corners on the arch file's radii (%zu, %zu off)", n, bad);
  aq_check_abs(atan2(y[0], x[0]), 0, TOL_M, "first joint at the springing, 0 rad");
  const double PI = 3.14159265358979323846;
  aq_check_abs(atan2(y[79], x[79]), 19 * PI / 20, 1e-12, "joint 19 at 19 pi/20");
  /* deformed: every voussoir moves rigidly (its corner distances kept) */
  size_t nd = points(csv, "deformed_corner", dx, dy, CAP);
  double worst = 0;
  for (size_t k = 0; k + 3 < nd && k + 3 < n; k += 4)
    for (int a = 0; a < 4; a++)
      for (int b = a + 1; b < 4; b++)
        worst = fmax(worst, fabs(hypot(dx[k + a] - dx[k + b], dy[k + a] - dy[k + b]) -
                                 hypot(x[k + a] - x[k + b], y[k + a] - y[k + b])));
  aq_check(nd == 80 && worst < TOL_M, "deformed voussoirs rigid (worst %.3g m)", worst);
  /* hinges: H1, H4 fixed; H2 turned about H1 by the rotation */
  double hx[4], hy[4], gx[4], gy[4];
  size_t nh = points(csv, "primary_hinge_e", hx, hy, 4);
  nh += points(csv, "primary_hinge_i", hx + nh, hy + nh, 4 - nh);
  size_t ng = points(csv, "deformed_hinge_e", gx, gy, 4);
  ng += points(csv, "deformed_hinge_i", gx + ng, gy + ng, 4 - ng);
  /* primary = 0e 6i 12e 19i: rows e (0, 12) then i (6, 19) */
  if (aq_check(nh == 4 && ng == 4, "4 hinges, 4 deformed")) {
    aq_check(hx[0] == gx[0] && hy[0] == gy[0] && hx[3] == gx[3] && hy[3] == gy[3],
             "H1 and H4 do not move");
    double a0 = atan2(hy[2] - hy[0], hx[2] - hx[0]), a1 = atan2(gy[2] - gy[0], gx[2] - gx[0]);
    aq_check_abs(fabs(a1 - a0), rot, 1e-12, "H2 turned about H1 by |q|");
    aq_check_abs(hypot(gx[2] - gx[0], gy[2] - gy[0]), hypot(hx[2] - hx[0], hy[2] - hy[0]),
                 TOL_M, "|H1H2| kept");
    /* the deformed voussoirs on either side of each hinge still touch at it:
     * joints 6 (i), 12 (e), 19 (i); corners ext k, ext k+1, int k+1, int k */
    static const struct { size_t joint, h; int ext; } hj[] = {{6, 2, 0}, {12, 1, 1}, {19, 3, 0}};
    double gap = 0;
    for (size_t i = 0; i < 3 && nd == 80; i++) {
      size_t before = 4 * (hj[i].joint - 1) + (hj[i].ext ? 1 : 2);
      size_t after = 4 * hj[i].joint + (hj[i].ext ? 0 : 3);
      gap = fmax(gap, hypot(dx[before] - gx[hj[i].h], dy[before] - gy[hj[i].h]));
      gap = fmax(gap, hypot(dx[after] - gx[hj[i].h], dy[after] - gy[hj[i].h]));
    }
    aq_check(gap < TOL_M, "deformed voussoirs meet at the deformed hinges (%.3g m)", gap);
  }
  free(csv);
  /* beyond q_c: refused, nothing written */
  snprintf(out, sizeof out, "%s/b.png", dir);
  snprintf(args, sizeof args, "plot arch --arch " ARCH " --rotation 0.5 -o %s", out);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--rotation") && aq_test_count_lines(err) == 1 &&
               !aq_test_read_file(out, NULL),
           "rotation beyond q_c: exit %d, \"%s\"", rc, err);
}

AQ_TEST(plot_domain_is_the_domain_command)
{
  char dir[512], out[600], data[600], args[1400], err[1024], tsv[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(out, sizeof out, "%s/d.pdf", dir);
  snprintf(data, sizeof data, "%s/d.csv", dir);
  snprintf(args, sizeof args, "plot domain --arch " ARCH " --ratios 1.2,2,4 -o %s --data %s",
           out, data);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d, %s", args, rc, err);
  rc = aq_test_run("domain --arch " ARCH " --ratios 1.2,2,4", tsv, sizeof tsv, err, sizeof err);
  char *csv = aq_test_read_file(data, NULL);
  if (!aq_check(rc == 0 && csv, "domain and the plot's data"))
    return;
  check_axes(csv, 2, "domain");
  const char *p = strstr(csv, "ratio,min_duration_s\n"), *q = strchr(tsv, '\n');
  for (int i = 0; i < 3 && p && q; i++) {
    p = strchr(p, '\n') + 1;
    q++;
    double r1 = strtod(p, NULL), d1 = strtod(strchr(p, ',') + 1, NULL);
    char *e;
    double r2 = strtod(q, &e);
    strtod(e, &e);
    double d2 = strtod(e, NULL);
    /* the plot bisects to 1e-6 s, the command to 1e-9 s */
    aq_check(r1 == r2, "ratio %g", r1);
    aq_check_abs(d1, d2, 2e-6, "ratio %g: plotted shortest pulse = domain's", r1);
    q = strchr(q, '\n');
  }
  free(csv);
}

AQ_TEST(plot_suite_is_the_worst_run)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/s.h5", dir);
  enum { TSV_CAP = 1 << 16 };
  char *tsv = malloc(TSV_CAP);
  snprintf(args, sizeof args,
           RECORD " tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 --arch " ARCH
                  " --arch arches/thick.cfg --scale 2,3 --polarity both -o %s",
           h5);
  int rc = aq_test_run(args, tsv, TSV_CAP, err, sizeof err);
  aq_check(rc == 0, "suite: exit %d %s", rc, err);
  snprintf(out, sizeof out, "%s/s.png", dir);
  snprintf(data, sizeof data, "%s/s.csv", dir);
  snprintf(args, sizeof args, "plot suite %s -o %s --data %s", h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  char *csv = aq_test_read_file(data, NULL);
  if (!aq_check(csv != NULL, "%s written", data)) {
    free(tsv);
    return;
  }
  check_axes(csv, 1, "suite");
  /* from the TSV: columns record arch ... collapsed(7) ... peak_rotation_over_qc(17) */
  size_t cells = 0, agree = 0, collapses = 0;
  for (const char *c = strstr(csv, "record,arch,"); c && (c = strchr(c, '\n')) && c[1];) {
    c++;
    char rec[300], arch[64];
    int coll;
    double v;
    if (sscanf(c, "%299[^,],%63[^,],%d,%lf", rec, arch, &coll, &v) != 4)
      break;
    cells++;
    double worst = -1;
    int any = 0;
    for (const char *l = strchr(tsv, '\n'); l && l[1]; l = strchr(l + 1, '\n')) {
      char r2[300], a2[64];
      if (sscanf(l + 1, "%299[^\t]\t%63[^\t]", r2, a2) != 2 || strcmp(r2, rec) || strcmp(a2, arch))
        continue;
      const char *fld = l + 1;
      double col[18];
      for (int k = 0; k < 18 && fld; k++) {
        col[k] = strtod(fld, NULL);
        fld = strchr(fld, '\t');
        fld = fld ? fld + 1 : NULL;
      }
      any |= col[6] == 1;
      worst = fmax(worst, col[16]);
    }
    collapses += coll;
    agree += coll == any && v == worst;
  }
  aq_check(cells == 4 && agree == 4 && collapses >= 1,
           "4 cells, each the worst run of the TSV (%zu cells, %zu agree, %zu collapse)", cells,
           agree, collapses);
  free(csv);
  free(tsv);
}

/* The map's marks: a cell says slides (beyond) when some run of its record
 * and arch has the status mark slides (beyond) in the TSV, and the key
 * names --model blocks; the CSV has them as columns. */
AQ_TEST(plot_suite_marks_the_runs)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/m.h5", dir);
  enum { TSV_CAP = 1 << 16 };
  char *tsv = malloc(TSV_CAP);
  if (!tsv)
    return;
  snprintf(args, sizeof args,
           "tests/data/records/IELC180.AT2 tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 " RECORD
                  " --arch arches/oppenheim.cfg --arch arches/search.cfg --scale 2.5,1,0.3"
                  " --friction 0.6 -o %s",
           h5);
  int rc = aq_test_run(args, tsv, TSV_CAP, err, sizeof err);
  aq_check(rc == 0, "suite: exit %d %s", rc, err);
  snprintf(out, sizeof out, "%s/m.svg", dir);
  snprintf(data, sizeof data, "%s/m.csv", dir);
  snprintf(args, sizeof args, "plot suite %s -o %s --data %s", h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  char *csv = aq_test_read_file(data, NULL), *svg = aq_test_read_file(out, NULL);
  if (!aq_check(csv && svg, "%s and %s written", data, out)) {
    free(csv);
    free(svg);
    free(tsv);
    return;
  }
  aq_check(strstr(csv, "record,arch,collapsed,peak_rotation_over_qc,slides,beyond\n") != NULL,
           "the CSV's columns");
  size_t cells = 0, agree = 0, marks[2] = {0, 0}, unmarked = 0;
  for (const char *c = strstr(csv, "record,arch,"); c && (c = strchr(c, '\n')) && c[1];) {
    c++;
    char rec[300], arch[64];
    int coll, mk[2];
    double v;
    if (sscanf(c, "%299[^,],%63[^,],%d,%lf,%d,%d", rec, arch, &coll, &v, &mk[0], &mk[1]) != 6)
      break;
    cells++;
    int any[2] = {0, 0}, none = 0;
    for (int row = 1;; row++) {
      char r2[300], a2[64], st[64];
      if (!aq_test_tsv_field(tsv, row, 0, r2, sizeof r2)[0])
        break;
      aq_test_tsv_field(tsv, row, 1, a2, sizeof a2);
      aq_test_tsv_field(tsv, row, 5, st, sizeof st);
      if (strcmp(r2, rec) || strcmp(a2, arch))
        continue;
      any[0] |= strstr(st, "slides") != NULL;
      any[1] |= strstr(st, "beyond") != NULL;
      none |= strcmp(st, "ok") == 0;
    }
    agree += mk[0] == any[0] && mk[1] == any[1];
    marks[0] += (size_t)mk[0];
    marks[1] += (size_t)mk[1];
    unmarked += none && (mk[0] || mk[1]); /* a cell marked though some of its runs are not */
  }
  aq_check(cells == 6 && agree == 6 && marks[0] > 0 && marks[1] > 0 && unmarked > 0,
           "6 cells, each marked as its runs are (%zu cells, %zu agree, %zu slide, %zu beyond, "
           "%zu with unmarked runs too)",
           cells, agree, marks[0], marks[1], unmarked);
  aq_check(strstr(svg, "--model blocks") != NULL, "the key names --model blocks");
  free(csv);
  free(svg);
  free(tsv);
}

AQ_TEST(plot_bad_input_one_line)
{
  const char *h5 = results();
  char dir[512], nohist[600], args[1600], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(nohist, sizeof nohist, "%s/nohist.h5", dir);
  snprintf(args, sizeof args, RECORD " --arch " ARCH " -o %s", nohist);
  aq_check(aq_test_run(args, NULL, 0, NULL, 0) == 0, "results without histories");
  struct {
    const char *args_fmt, *arg, *want;
    int status;
  } cases[] = {
      {"plot history %s -o %s/x.png", nohist, "--history", 1},
      {"plot history %s -o %s/x.png", "tests/data/results/format1-elcentro-thin.h5",
       "/runs: expected histories", 1},
      {"plot history %s --run 00042_000_000 -o %s/x.png", h5, "00042_000_000", 2},
      {"plot history %s -o %s/x.jpg", h5, ".jpg", 2},
      {"plot history %s -o %s/no/such/dir/x.png", h5, "no/such/dir/x.png", 3},
      {"plot suite %s -o %s/x.png", "tests/data/records/ARL360.at2", "ARL360.at2", 1},
      {"plot arch %s --arch " ARCH " -o %s/x.png", "--record=1", "not an option of this figure", 2},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char a[1200];
    snprintf(a, sizeof a, cases[i].args_fmt, cases[i].arg, dir);
    int rc = aq_test_run(a, NULL, 0, err, sizeof err);
    aq_check(rc == cases[i].status && aq_test_count_lines(err) == 1 &&
                 strstr(err, cases[i].want) && !strncmp(err, "archquake: ", 11),
             "%s: exit %d (want %d), \"%s\"", a, rc, cases[i].status, err);
  }
  /* no cairo device: refused before anything is read or written */
  char cmd[2000], dev[600];
  snprintf(dev, sizeof dev, "%s/x.png", dir);
  remove(dev);
  snprintf(cmd, sizeof cmd, "PLPLOT_DRV_DIR=%s/none %s plot arch --arch " ARCH " -o %s 2>%s/e",
           dir, aq_test_bin(), dev, dir);
  int st = system(cmd);
  char epath[600];
  snprintf(epath, sizeof epath, "%s/e", dir);
  char *e = aq_test_read_file(epath, NULL);
  remove(epath);
  aq_check(st != 0 && e && aq_test_count_lines(e) == 1 && strstr(e, "pngcairo"),
           "no drivers: one line naming the device (\"%s\")", e ? e : "");
  free(e);
  aq_check(files_in(dir) == 1, "nothing left but the results file (%zu files)", files_in(dir));
}

/* A reversed run (key ending in r) plots the negated, scaled record. */
AQ_TEST(plot_history_reversed_ground)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(args, sizeof args,
           RECORD " --arch " ARCH " --scale 2.385 --polarity reversed --history --store-records -o %s",
           h5);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "results: %s", err);
  snprintf(out, sizeof out, "%s/r.pdf", dir);
  snprintf(data, sizeof data, "%s/r.csv", dir);
  snprintf(args, sizeof args, "plot history %s --run 00000_000_000r -o %s --data %s", h5, out,
           data);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  char *csv = aq_test_read_file(data, NULL);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  size_t nw = 0;
  double *w = f >= 0 ? dataset(f, "/waveforms/00000", &nw) : NULL;
  double *v = malloc((nw + 1) * sizeof *v);
  size_t ng = csv && v ? series(csv, "ground_accel_g", NULL, v, nw + 1) : 0, bad = 0;
  const double G0 = 9.80665; /* standard gravity, m/s^2 */
  for (size_t i = 0; i < ng && i < nw; i++)
    bad += fabs(v[i] - (-2.385 * w[i] / G0)) > 1e-15 * (fabs(v[i]) + 1e-300) + 1e-300;
  aq_check(ng == nw && nw > 0 && bad == 0,
           "ground = -2.385 x the stored record / g0 at every sample (%zu of %zu, %zu off)", ng,
           nw, bad);
  free(v);
  free(w);
  free(csv);
  if (f >= 0)
    H5Fclose(f);
}

/* The capacity figure's intervals are the capacity command's own TSV
 * column collapse_intervals ("lo-hi;lo-hi", another output path). */
AQ_TEST(plot_capacity_is_the_capacity_tsv)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/c.h5", dir);
  enum { CAP = 1 << 15 };
  char *tsv = malloc(CAP);
  snprintf(args, sizeof args,
           "capacity " RECORD " --arch " ARCH " --polarity both --resolution 0.1 -j 2 -o %s", h5);
  int rc = aq_test_run(args, tsv, CAP, err, sizeof err);
  aq_check(rc == 0, "capacity: exit %d %s", rc, err);
  snprintf(out, sizeof out, "%s/c.svg", dir);
  snprintf(data, sizeof data, "%s/c.csv", dir);
  snprintf(args, sizeof args, "plot capacity %s --arch oppenheim -o %s --data %s", h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
  valid(out);
  char *csv = aq_test_read_file(data, NULL);
  if (!aq_check(csv != NULL, "%s written", data)) {
    free(tsv);
    return;
  }
  check_axes(csv, 4, "capacity");
  /* rebuild "lo-hi;lo-hi" per polarity from the CSV's intervals and find it
     in the TSV */
  size_t found = 0;
  const char *ivs = strstr(csv, "\nrecord,polarity,move_scale,");
  aq_check(ivs != NULL, "the intervals' section");
  for (int p = 0; p < 2 && ivs; p++) {
    const char *pol = p ? ",reversed," : ",normal,";
    char want[4096] = "";
    size_t len = 0;
    for (const char *l = strstr(ivs, pol); l; l = strstr(l + 1, pol)) {
      double v[4];
      const char *q = l + strlen(pol);
      for (int k = 0; k < 4; k++) {
        char *e;
        v[k] = strtod(q, &e);
        q = e + 1;
      }
      if (isnan(v[2]))
        break;
      len += (size_t)snprintf(want + len, sizeof want - len, "%s%.17g-%.17g", len ? ";" : "",
                              v[2], v[3]);
    }
    /* the TSV prints %.17g too; inf as "inf" */
    found += len > 0 && strstr(tsv, want) != NULL;
    if (getenv("AQ_TEST_VERBOSE"))
      fprintf(stderr, "%s: %s\n", pol, want);
  }
  aq_check(found == 2, "both polarities' intervals as the capacity TSV prints them (%zu)", found);
  static const char *const other[] = {"png", "pdf"};
  for (int k = 0; k < 2; k++) {
    snprintf(out, sizeof out, "%s/c.%s", dir, other[k]);
    snprintf(args, sizeof args, "plot capacity %s -o %s", h5, out);
    rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
    valid(out);
  }
  /* an arch the file does not hold: one line, no file */
  snprintf(args, sizeof args, "plot capacity %s --arch nosuch -o %s/x.png", h5, dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "nosuch") && aq_test_count_lines(err) == 1,
           "unknown arch: exit %d \"%s\"", rc, err);
  free(csv);
  free(tsv);
}

/* Standard normal CDF from the C library's erf (not the plot's erfc form). */
static double normal_cdf(double z)
{
  return 0.5 * (1 + erf(z / sqrt(2)));
}

/* The fragility panel of the capacity figure: its CDFs are the fit stored
 * in /capacity/fragility (read here with HDF5) evaluated here; its
 * empirical fractions are i/n of the capacity TSV's first_collapse_pga_g
 * (the lower polarity of each record); the records without collapse up to
 * the cap (never_moves at --scale-max 12) are the censored ones. */
AQ_TEST(plot_capacity_fragility_is_the_fit)
{
  static const char *const recs[] = {
      "ARL360.at2", "IELC180.AT2", "CHY028-N.AT2", "RSN1616_DUZCE_362-E.AT2",
      "RSN4013_SANSIMEO_36258021.AT2", "RSN4843_CHUETSU_65006NS.AT2"};
  enum { NREC = 6, CAP = 1 << 15 };
  const double TOL_P = 1e-12;  /* CDF values: a few ulps of erf/erfc */
  const double TOL_REL = 1e-12; /* IM: scale x PGA rounded two ways */
  char dir[512], h5[600], out[600], data[600], args[4000], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/f.h5", dir);
  size_t len = (size_t)snprintf(args, sizeof args, "capacity");
  for (int r = 0; r < NREC; r++)
    len += (size_t)snprintf(args + len, sizeof args - len, " tests/data/records/%s", recs[r]);
  snprintf(args + len, sizeof args - len,
           " --arch " ARCH " --polarity both --resolution 0.1 --scale-max 12 -j 2 -o %s", h5);
  char *tsv = malloc(CAP);
  int rc = aq_test_run(args, tsv, CAP, err, sizeof err);
  aq_check(rc == 0, "capacity: exit %d %s", rc, err);
  /* the TSV: per record the lowest first_collapse_pga_g (column 7) */
  double low[NREC];
  for (int r = 0; r < NREC; r++)
    low[r] = INFINITY;
  for (const char *l = strchr(tsv, '\n'); l && l[1]; l = strchr(l + 1, '\n')) {
    const char *p = l + 1;
    for (int r = 0; r < NREC; r++)
      if (strstr(p, recs[r]) && strstr(p, recs[r]) < strchr(p, '\t')) {
        const char *q = p;
        for (int c = 0; c < 6 && q; c++)
          q = strchr(q, '\t') ? strchr(q, '\t') + 1 : NULL;
        double v = q ? strtod(q, NULL) : NAN;
        if (!isnan(v))
          low[r] = fmin(low[r], v);
      }
  }
  double want[NREC];
  size_t ncol = 0;
  for (int r = 0; r < NREC; r++)
    if (isfinite(low[r]))
      want[ncol++] = low[r];
  for (size_t i = 1; i < ncol; i++) /* insertion sort */
    for (size_t j = i; j > 0 && want[j - 1] > want[j]; j--) {
      double t = want[j];
      want[j] = want[j - 1];
      want[j - 1] = t;
    }
  /* the fit (one arch: the first AQ_FRAGILITY_NIM rows, pga_g first) */
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  size_t n1 = 0, n2 = 0, n3 = 0, n4 = 0;
  double *med = f >= 0 ? dataset(f, "/capacity/fragility/median", &n1) : NULL;
  double *beta = f >= 0 ? dataset(f, "/capacity/fragility/beta", &n2) : NULL;
  double *mlo = f >= 0 ? dataset(f, "/capacity/fragility/median_lo", &n3) : NULL;
  double *mhi = f >= 0 ? dataset(f, "/capacity/fragility/median_hi", &n4) : NULL;
  if (f >= 0)
    H5Fclose(f);
  int have = med && beta && mlo && mhi && n1 > 0 && n2 > 0 && n3 > 0 && n4 > 0;
  aq_check(have && isfinite(med[0]) && beta[0] > 0, "a PGA fit in %s", h5);
  snprintf(out, sizeof out, "%s/f.png", dir);
  snprintf(data, sizeof data, "%s/f.csv", dir);
  snprintf(args, sizeof args, "plot capacity %s --arch oppenheim --im pga_g -o %s --data %s",
           h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
  valid(out);
  char *csv = aq_test_read_file(data, NULL);
  if (!aq_check(csv != NULL && have, "%s written", data)) {
    free(csv), free(tsv), free(med), free(beta), free(mlo), free(mhi);
    return;
  }
  check_axes(csv, 4, "capacity with fragility");
  aq_check(strstr(csv, "im=pga_g ") != NULL && strstr(csv, "\nseries,pga_g,probability\n"),
           "the fragility section names its IM");
  static const char *const name[3] = {"\nfit,", "\nfit_median_lo,", "\nfit_median_hi,"};
  const double m3[3] = {med[0], mlo[0], mhi[0]};
  for (int k = 0; k < 3; k++) {
    size_t n = 0, bad = 0;
    double worst = 0;
    for (const char *p = strstr(csv, name[k]); p; p = strstr(p + 1, name[k])) {
      char *e;
      double x = strtod(p + strlen(name[k]), &e), y = strtod(e + 1, NULL);
      double d = fabs(y - normal_cdf(log(x / m3[k]) / beta[0]));
      worst = fmax(worst, d);
      bad += !(d <= TOL_P);
      n++;
    }
    if (getenv("AQ_TEST_VERBOSE"))
      fprintf(stderr, "%s worst |p - Phi| %.3g over %zu points\n", name[k] + 1, worst, n);
    aq_check(n > 100 && bad == 0, "%s= Phi(ln(x/m)/beta) at %zu points (%zu off, worst %.3g)",
             name[k] + 1, n, bad, worst);
  }
  size_t ne = 0, bad = 0, ncen = 0;
  for (const char *p = strstr(csv, "\nempirical,"); p; p = strstr(p + 1, "\nempirical,")) {
    char *e;
    double x = strtod(p + 11, &e), y = strtod(e + 1, NULL);
    bad += ne >= ncol || fabs(x - want[ne]) > TOL_REL * want[ne] ||
           fabs(y - (ne + 1) / (double)NREC) > TOL_P;
    if (getenv("AQ_TEST_VERBOSE") && ne < ncol)
      fprintf(stderr, "empirical %.17g %.17g (TSV %.17g, %zu/%d)\n", x, y, want[ne], ne + 1,
              NREC);
    ne++;
  }
  for (const char *p = strstr(csv, "\ncensored,"); p; p = strstr(p + 1, "\ncensored,"))
    ncen++;
  aq_check(ne == ncol && ncol >= 2 && bad == 0,
           "empirical points = sorted first collapses of the TSV at i/%d (%zu of %zu, %zu off)",
           NREC, ne, ncol, bad);
  aq_check(ncen == NREC - ncol && ncen > 0, "censored records %zu, the TSV's %zu", ncen,
           NREC - ncol);
  static const char *const other[] = {"svg", "pdf"};
  for (int k = 0; k < 2; k++) {
    snprintf(out, sizeof out, "%s/f.%s", dir, other[k]);
    snprintf(args, sizeof args, "plot capacity %s --im pgv_m_s -o %s", h5, out);
    rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
    valid(out);
  }
  /* an IM the fit does not store: one line, no file */
  snprintf(out, sizeof out, "%s/y.png", dir);
  snprintf(args, sizeof args, "plot capacity %s --im sa_g -o %s", h5, out);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  FILE *g = fopen(out, "rb");
  aq_check(rc == 2 && strstr(err, "--im") && strstr(err, "sa_g") &&
               aq_test_count_lines(err) == 1 && g == NULL,
           "unknown IM: exit %d \"%s\"", rc, err);
  if (g)
    fclose(g);
  free(csv), free(tsv), free(med), free(beta), free(mlo), free(mhi);
}

/* ---- the capacity figure's lines -------------------------------------- */

typedef struct {
  int64_t pair, collapsed;
  double scale, peak_rad, peak_qc, t_s;
} cap_point;

/* capacity/scan_points, read with our own compound type; count or -1. */
static long cap_points(hid_t f, cap_point *p, size_t cap)
{
  hid_t d = H5Dopen2(f, "/capacity/scan_points", H5P_DEFAULT);
  hid_t s = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t n = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(cap_point));
  H5Tinsert(t, "pair", HOFFSET(cap_point, pair), H5T_NATIVE_INT64);
  H5Tinsert(t, "collapsed", HOFFSET(cap_point, collapsed), H5T_NATIVE_INT64);
  H5Tinsert(t, "scale", HOFFSET(cap_point, scale), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "peak_rotation_rad", HOFFSET(cap_point, peak_rad), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "peak_rotation_over_qc", HOFFSET(cap_point, peak_qc), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "collapse_time_s", HOFFSET(cap_point, t_s), H5T_NATIVE_DOUBLE);
  long rc = n >= 0 && (size_t)n <= cap && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, p) >= 0
                ? (long)n
                : -1;
  H5Tclose(t);
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  return rc;
}

/* Strings dataset name (variable length) of f: entry i into buf. */
static const char *cap_string(hid_t f, const char *name, size_t i, char *buf, size_t n)
{
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT), s = d >= 0 ? H5Dget_space(d) : -1;
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : 0;
  char **v = np > 0 ? calloc((size_t)np, sizeof *v) : NULL;
  buf[0] = '\0';
  if (v && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0 && i < (size_t)np) {
    snprintf(buf, n, "%s", v[i]);
    H5Dvlen_reclaim(t, s, H5P_DEFAULT, v);
  }
  free(v);
  H5Tclose(t);
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  return buf;
}

static int same_double(double a, double b)
{
  return a == b || (isnan(a) && isnan(b));
}

/* Split a CSV line at commas into f[0..n-1] (in place); the count. */
static int csv_fields(char *line, char **f, int n)
{
  int k = 0;
  for (char *p = line; p && k < n; k++) {
    f[k] = p;
    p = strchr(p, ',');
    if (p)
      *p++ = '\0';
  }
  return k;
}

/* San Fernando (RSN77) on the oppenheim arch with COR 0.5 collapses from a
 * scale of 1.94, survives from 3.67 to 3.75 and collapses again
 * (test_capacity_cli.c); IELC180 is the second record.  The figure's lines
 * are the file's scan_points, read here with HDF5, row for row; its PGA
 * axis is the scale times the /records table's pga_g; its shaded intervals
 * the file's intervals; RSN77 shows one below a survived point. */
AQ_TEST(plot_capacity_lines_are_the_scan_points)
{
  enum { MAXP = 8192, LINE = 512 };
  /* pga_g = scale x PGA at scale 1, which the figure takes as im_cap /
     scale_max: two roundings apart (measured 0) */
  const double TOL_PGA_REL = 1e-15;
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/l.h5", dir);
  snprintf(args, sizeof args,
           "capacity tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 "
           "tests/data/records/IELC180.AT2 --arch " ARCH " --cor 0.5 --detrend mean "
           "--taper 0.05 --highpass 0.05 --scale-max 4 -j 2 -o %s", h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "capacity: exit %d %s", rc, err);
  cap_point *p = malloc(MAXP * sizeof *p);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  long np = f >= 0 && p ? cap_points(f, p, MAXP) : -1;
  if (!aq_check(np > 100, "%s: %ld scan points", h5, np)) {
    if (f >= 0)
      H5Fclose(f);
    free(p);
    return;
  }
  size_t nin = 0, nint = 0;
  double *iv = dataset(f, "/capacity/intervals", &nin);
  double *ist = dataset(f, "/capacity/interval_start", &nint);
  double *icn = dataset(f, "/capacity/interval_count", &nint);
  for (int y = 0; y < 2; y++) {
    const char *ext = y ? "svg" : "png";
    snprintf(out, sizeof out, "%s/l%d.%s", dir, y, ext);
    snprintf(data, sizeof data, "%s/l%d.csv", dir, y);
    snprintf(args, sizeof args, "plot capacity %s %s -o %s --data %s", h5,
             y ? "--y pga --x rad" : "", out, data);
    rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
    valid(out);
    char *csv = aq_test_read_file(data, NULL);
    if (!aq_check(csv != NULL, "%s written", data))
      continue;
    check_axes(csv, 4, "capacity lines");
    aq_check(strstr(csv, y ? "# axis: PGA of the scaled record (g)\n"
                           : "# axis: scale factor on the processed record (1)\n") &&
                 strstr(csv, y ? "# axis: survived: peak rotation (rad)\n"
                               : "# axis: survived: peak rotation / qc (1)\n"),
             "axes as asked (--y %s)", y ? "pga" : "scale");
    /* the points' section, row for row against scan_points */
    const char *hdr = "record,polarity,legend_no,scale,pga_g,peak_rotation_rad,"
                      "peak_rotation_over_qc,collapsed,collapse_time_s\n";
    char *sec = strstr(csv, hdr), *l = sec ? sec + strlen(hdr) : NULL;
    long row = 0;
    size_t bad = 0, bad_pga = 0;
    double worst_pga = 0;
    char rec[LINE], pol[32];
    while (l && *l && *l != '\n') {
      char *nl = strchr(l, '\n'), *fl[9];
      if (nl)
        *nl = '\0';
      int nf = csv_fields(l, fl, 9);
      if (row >= np || nf != 9) {
        bad++;
        break;
      }
      const cap_point *q = &p[row];
      size_t pr = (size_t)q->pair;
      cap_string(f, "/capacity/record", pr, rec, sizeof rec);
      cap_string(f, "/capacity/polarity", pr, pol, sizeof pol);
      double pga1 = table_value(f, "/records", pr / 2, "pga_g"); /* 2 polarities */
      double pga = strtod(fl[4], NULL);
      bad += strcmp(fl[0], rec) != 0 || strcmp(fl[1], pol) != 0 ||
             strtod(fl[3], NULL) != q->scale || strtod(fl[5], NULL) != q->peak_rad ||
             strtod(fl[6], NULL) != q->peak_qc || atoi(fl[7]) != q->collapsed ||
             !same_double(strtod(fl[8], NULL), q->t_s);
      double d = fabs(pga - q->scale * pga1) / (q->scale * pga1);
      worst_pga = fmax(worst_pga, d);
      bad_pga += !(d <= TOL_PGA_REL);
      row++;
      l = nl ? nl + 1 : NULL;
    }
    aq_check(row == np && bad == 0,
             "--data rows = capacity/scan_points (%ld of %ld rows, %zu differ)", row, np, bad);
    aq_check(bad_pga == 0, "pga_g = scale x /records pga_g (worst relative %.3g)", worst_pga);
    /* the shaded intervals: the file's, and one below a survived point */
    const char *ih = "record,polarity,move_scale,scale_max,collapse_lo,collapse_hi,legend_no,"
                     "record_pga_g\n";
    char *is = l ? strstr(l, ih) : NULL;
    l = is ? is + strlen(ih) : NULL;
    size_t nshade = 0, bad_iv = 0, below_survivor = 0;
    for (size_t pr = 0; l && *l && *l != '\n' && pr < nint; pr++) {
      for (int64_t j = 0; j < (int64_t)fmax(icn[pr], 1) && l && *l != '\n'; j++) {
        char *nl = strchr(l, '\n'), *fl[8];
        if (nl)
          *nl = '\0';
        csv_fields(l, fl, 8);
        double lo = strtod(fl[4], NULL), hi = strtod(fl[5], NULL);
        if (icn[pr] > 0) {
          size_t q = (size_t)ist[pr] + (size_t)j;
          bad_iv += 2 * q + 1 >= nin || lo != iv[2 * q] || hi != iv[2 * q + 1];
          nshade++;
          for (long k = 0; isfinite(hi) && k < np; k++)
            if ((size_t)p[k].pair == pr && !p[k].collapsed && p[k].scale > hi) {
              below_survivor++;
              break;
            }
        } else
          bad_iv += !isnan(lo);
        l = nl ? nl + 1 : NULL;
      }
    }
    aq_check(nshade >= 3 && bad_iv == 0, "%zu shaded intervals = capacity/intervals (%zu "
             "differ)", nshade, bad_iv);
    aq_check(below_survivor >= 1, "%zu shaded intervals lie below a survived point",
             below_survivor);
    free(csv);
  }
  free(iv);
  free(ist);
  free(icn);
  H5Fclose(f);
  free(p);
  /* the PDF; and a bad --x: one line, no file */
  snprintf(out, sizeof out, "%s/l.pdf", dir);
  snprintf(args, sizeof args, "plot capacity %s --x deg -o %s", h5, out);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  FILE *g = fopen(out, "rb");
  aq_check(rc == 2 && strstr(err, "--x") && aq_test_count_lines(err) == 1 && !g,
           "--x deg: exit %d \"%s\"", rc, err);
  if (g)
    fclose(g);
  snprintf(args, sizeof args, "plot capacity %s --x qc --y scale -o %s", h5, out);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
  valid(out);
  snprintf(args, sizeof args, "plot suite %s --y pga -o %s/s.png", h5, dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--y") && aq_test_count_lines(err) == 1,
           "--y on another figure: exit %d \"%s\"", rc, err);
}

/* A capacity file written before scan_points: the figure is drawn (the
 * strips and the fragility) with no lines, and says so in its data. */
AQ_TEST(plot_capacity_without_scan_points)
{
  char dir[512], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/old.h5", dir);
  snprintf(args, sizeof args,
           "capacity " RECORD " --arch " ARCH " --resolution 0.1 -j 2 -o %s", h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "capacity: exit %d %s", rc, err);
  hid_t f = H5Fopen(h5, H5F_ACC_RDWR, H5P_DEFAULT);
  aq_check(f >= 0 && H5Ldelete(f, "/capacity/scan_points", H5P_DEFAULT) >= 0,
           "scan_points removed");
  if (f >= 0)
    H5Fclose(f);
  snprintf(out, sizeof out, "%s/old.png", dir);
  snprintf(data, sizeof data, "%s/old.csv", dir);
  snprintf(args, sizeof args, "plot capacity %s -o %s --data %s", h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
  valid(out);
  char *csv = aq_test_read_file(data, NULL);
  const char *hdr = "collapse_time_s\n";
  const char *after = csv ? strstr(csv, hdr) : NULL;
  aq_check(after && after[strlen(hdr)] == '\n', "no point rows");
  free(csv);
}

/* A record whose name holds a comma and a quote: its --data rows quote it
 * (RFC 4180, the inner quote doubled), so a CSV reader sees one field. */
AQ_TEST(plot_capacity_data_quotes_record_names)
{
  char dir[512], rec[600], h5[600], out[600], data[600], args[2048], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(rec, sizeof rec, "%s/north,\"south\".at2", dir);
  size_t n = 0;
  char *bytes = aq_test_read_file(RECORD, &n);
  FILE *f = bytes ? fopen(rec, "wb") : NULL;
  aq_check(f && fwrite(bytes, 1, n, f) == n, "copy %s to %s", RECORD, rec);
  if (f)
    fclose(f);
  free(bytes);
  snprintf(h5, sizeof h5, "%s/q.h5", dir);
  snprintf(args, sizeof args, "capacity '%s' --arch " ARCH " --resolution 0.1 -o %s", rec, h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "capacity: exit %d %s", rc, err);
  snprintf(out, sizeof out, "%s/q.png", dir);
  snprintf(data, sizeof data, "%s/q.csv", dir);
  snprintf(args, sizeof args, "plot capacity %s -o %s --data %s", h5, out, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  char *csv = aq_test_read_file(data, NULL), want[700];
  snprintf(want, sizeof want, "\n\"%s/north,\"\"south\"\".at2\",normal,", dir);
  size_t rows = 0;
  for (const char *p = csv ? strstr(csv, want) : NULL; p; p = strstr(p + 1, want))
    rows++;
  /* every point row and the interval rows: at least the scan's points */
  aq_check(rows >= 10, "%zu rows quote the name as %s", rows, want + 1);
  free(csv);
}

/* plot spectrum: every format; --data holds the file's spectra of the
 * record chosen, in the file's order, with the axis titles' units; bad
 * input in one line. */
AQ_TEST(plot_spectrum_formats_data_and_bad_input)
{
  char dir[512], h5[600], args[2400], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/sp.h5", dir);
  snprintf(args, sizeof args,
           "spectrum tests/data/records/ARL360.at2 tests/data/records/IELC180.AT2 "
           "--periods 0.05,0.2,1,4 --damping 0.05,0.1 -o %s", h5);
  if (!aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "%s: %s", args, err))
    return;
  static const char *const fmt[] = {"png", "svg", "pdf"};
  for (int k = 0; k < 3; k++) {
    char out[600];
    snprintf(out, sizeof out, "%s/sp.%s", dir, fmt[k]);
    snprintf(args, sizeof args, "plot spectrum %s -o %s", h5, out);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0 && err[0] == '\0', "%s: exit %d, stderr \"%s\"", args, rc, err);
    valid(out);
  }
  char png[600], csv[600];
  snprintf(png, sizeof png, "%s/one.png", dir);
  snprintf(csv, sizeof csv, "%s/one.csv", dir);
  snprintf(args, sizeof args, "plot spectrum %s --record IELC180.AT2 -o %s --data %s", h5, png,
           csv);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "%s: %s", args, err);
  char *data = aq_test_read_file(csv, NULL);
  aq_h5_spectra_table t;
  aq_error e;
  if (data && aq_check(aq_h5_spectra_read(h5, &t, &e) == AQ_OK, "read %s", h5)) {
    check_axes(data, 2, "plot spectrum --data");
    const char *p = strstr(data, "record,component,damping,period_s,psa_g\n");
    size_t rows = 0, same = 0;
    for (p = p ? strchr(p, '\n') + 1 : NULL; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
      size_t i = 8 + rows++; /* IELC180's 8 rows follow ARL360's 8 */
      char rec[512], comp[32];
      double d, T, a;
      if (sscanf(p, "%511[^,],%31[^,],%lf,%lf,%lf", rec, comp, &d, &T, &a) == 5 && i < t.n)
        same += !strcmp(rec, t.record[i]) && !strcmp(comp, t.component[i]) &&
                d == t.damping[i] && T == t.period_s[i] && a == t.psa_g[i];
    }
    aq_check(rows == 8 && same == 8, "--data: %zu rows, %zu the file's (want 8)", rows, same);
    aq_h5_spectra_table_free(&t);
  }
  free(data);
  const char *results_file = results();
  struct {
    const char *fmt, *in, *says;
    int rc;
  } bad[] = {
      {"plot spectrum %s -o %s/x.png", results_file, "spectra", 1},
      {"plot spectrum %s --record nosuch.AT2 -o %s/x.png", h5, "nosuch.AT2", 2},
      {"plot spectrum %s --run 00000_000_000 -o %s/x.png", h5, "--run", 2},
  };
  for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
    snprintf(args, sizeof args, bad[k].fmt, bad[k].in, dir);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == bad[k].rc && aq_test_count_lines(err) == 1 && strstr(err, bad[k].says),
             "%s: exit %d, one line naming %s: %s", args, rc, bad[k].says, err);
  }
  snprintf(png, sizeof png, "%s/x.png", dir);
  aq_check(access(png, F_OK) != 0, "no figure left by the bad input");
}
