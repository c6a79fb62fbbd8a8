/* test_blocks_plot.c: a block model's run stored with --history (every
 * voussoir's centroid and rotation, /histories/KEY/voussoir_*) and drawn
 * by `plot arch RESULTS --run KEY --at TIMES`: the figure's data against
 * the stored history, read here with the HDF5 library (each corner is its
 * voussoir's rest corner moved rigidly with the centroid and rotation the
 * history holds at that time, linear between samples); its default time
 * the peak of voussoir 0's |rotation|; the refusals of bad input. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

#define RECORD "records/elcentro_chopra.csv"
#define ARCH "arches/oppenheim.cfg"
#define KEY "00000_000_000"

static char out[1 << 16], err[8192];

/* The main job's block model on ARCH through RECORD at scale 3 (hinges
 * open at 2.0-2.3 s: docs/blocks.md) with --history, into dir/name; 1 if
 * written. */
static int blocks_run(const char *dir, const char *name, const char *model)
{
  char cmd[1024];
  snprintf(cmd, sizeof cmd, RECORD " --arch " ARCH " --scale 3 --model %s --friction 10 "
           "--history -o %s/%s", model, dir, name);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  return aq_check(rc == 0, "%s: exit 0 (%d): %s", cmd, rc, err);
}

/* Dataset name of group g (n x cols doubles, cols 1 for 1-D) malloc'd;
 * *n and *cols its shape; NULL if absent. */
static double *read2d(hid_t g, const char *name, size_t *n, size_t *cols)
{
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  if (d < 0)
    return NULL;
  hid_t s = H5Dget_space(d);
  hsize_t dim[2] = {0, 1};
  int nd = H5Sget_simple_extent_dims(s, dim, NULL);
  double *v = nd >= 1 ? malloc(dim[0] * (nd == 2 ? dim[1] : 1) * sizeof *v + 1) : NULL;
  if (v && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    free(v);
    v = NULL;
  }
  *n = dim[0];
  *cols = nd == 2 ? dim[1] : 1;
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

typedef struct {
  size_t n, nv;
  double *t, *q, *x, *y, *r; /* time_s, rotation_rad, voussoir_x_m, _y_m, _rotation_rad */
} hist;

static int hist_read(const char *h5, hist *h)
{
  memset(h, 0, sizeof *h);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t g = f >= 0 ? H5Gopen2(f, "/histories/" KEY, H5P_DEFAULT) : -1;
  size_t n[5] = {0}, c[5] = {0};
  if (g >= 0) {
    h->t = read2d(g, "time_s", &n[0], &c[0]);
    h->q = read2d(g, "rotation_rad", &n[1], &c[1]);
    h->x = read2d(g, "voussoir_x_m", &n[2], &c[2]);
    h->y = read2d(g, "voussoir_y_m", &n[3], &c[3]);
    h->r = read2d(g, "voussoir_rotation_rad", &n[4], &c[4]);
    H5Gclose(g);
  }
  if (f >= 0)
    H5Fclose(f);
  h->n = n[0];
  h->nv = c[2];
  int ok = h->t && h->q && h->x && h->y && h->r && h->n > 2;
  for (int i = 1; i < 5; i++)
    ok = ok && n[i] == h->n && c[i] == (i < 2 ? 1 : h->nv);
  return aq_check(ok, "%s: time_s, rotation_rad and voussoir_* n x k (n %zu, k %zu)", h5, h->n,
                  h->nv);
}

static void hist_free(hist *h)
{
  free(h->t);
  free(h->q);
  free(h->x);
  free(h->y);
  free(h->r);
}

/* Rows "PREFIXcorner,k,x,y" of a plot arch --data file: the corners of
 * voussoir k (4 each) of the layer named prefix ("" the undeformed) into
 * c[4 * k + j]; the count read. */
static size_t corners(const char *csv, const char *prefix, double (*c)[2], size_t cap)
{
  char want[96];
  snprintf(want, sizeof want, "\n%scorner,", prefix);
  size_t cnt = 0, seen[64] = {0};
  for (const char *p = strstr(csv, want); p; p = strstr(p + 1, want)) {
    size_t k;
    double x, y;
    if (sscanf(p + strlen(want), "%zu,%lf,%lf", &k, &x, &y) != 3 || k >= 64 ||
        4 * k + seen[k] >= cap || seen[k] >= 4)
      return 0;
    c[4 * k + seen[k]][0] = x;
    c[4 * k + seen[k]][1] = y;
    seen[k]++;
    cnt++;
  }
  return cnt;
}

/* Where the rest point p of voussoir k is at time t of h: the centroid
 * and rotation of the samples about t, linear between them, the point
 * carried rigidly from its rest place (sample 0: the arch at rest). */
static void moved(const hist *h, size_t k, double t, const double p[2], double o[2])
{
  size_t i = 0;
  while (i + 2 < h->n && h->t[i + 1] <= t)
    i++;
  double w = h->t[i + 1] > h->t[i] ? (t - h->t[i]) / (h->t[i + 1] - h->t[i]) : 1;
  size_t a = i * h->nv + k, b = (i + 1) * h->nv + k;
  double cx = h->x[a] + w * (h->x[b] - h->x[a]), cy = h->y[a] + w * (h->y[b] - h->y[a]);
  double th = h->r[a] + w * (h->r[b] - h->r[a]);
  double dx = p[0] - h->x[k], dy = p[1] - h->y[k];
  o[0] = cx + cos(th) * dx - sin(th) * dy;
  o[1] = cy + sin(th) * dx + cos(th) * dy;
}

/* Occurrences of needle in s. */
static size_t count(const char *s, const char *needle)
{
  size_t n = 0;
  for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle))
    n++;
  return n;
}

AQ_TEST(blocks_plot_arch_run_is_the_history)
{
  char dir[512], h5[700], png[700], csvp[700], cmd[4096];
  aq_test_tmpdir(dir, sizeof dir);
  if (!blocks_run(dir, "r.h5", "blocks"))
    return;
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  hist h;
  if (!hist_read(h5, &h))
    return;
  aq_check(h.nv == 20, "20 voussoirs (%zu)", h.nv);
  /* rotation_rad is voussoir 0's; the first sample is the arch at rest */
  size_t peak = 0, bad = 0;
  for (size_t i = 0; i < h.n; i++) {
    bad += h.q[i] != h.r[i * h.nv];
    if (fabs(h.r[i * h.nv]) > fabs(h.r[peak * h.nv]))
      peak = i;
  }
  aq_check(bad == 0, "rotation_rad is voussoir_rotation_rad's column 0 (%zu differ)", bad);
  for (size_t k = 0; k < h.nv; k++)
    bad += h.r[k] != 0;
  aq_check(bad == 0, "at rest at the first sample (%zu voussoirs turned)", bad);
  aq_check(fabs(h.r[peak * h.nv]) > 1e-3 && peak > 1 && peak + 1 < h.n,
           "the arch moved: peak %g rad at %g s", h.r[peak * h.nv], h.t[peak]);
  /* a sample time and a time between two samples in motion */
  double at[2] = {h.t[peak], 0.3 * h.t[peak - 1] + 0.7 * h.t[peak]};
  snprintf(png, sizeof png, "%s/a.png", dir);
  snprintf(csvp, sizeof csvp, "%s/a.csv", dir);
  snprintf(cmd, sizeof cmd, "plot arch %s --run " KEY " --at %.17g,%.17g -o %s --data %s", h5,
           at[0], at[1], png, csvp);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  char *csv = aq_check(rc == 0, "%s: exit 0 (%d): %s", cmd, rc, err)
                  ? aq_test_read_file(csvp, NULL)
                  : NULL;
  aq_check(access(png, F_OK) == 0, "the figure written");
  if (!aq_check(csv != NULL, "the data written")) {
    hist_free(&h);
    return;
  }
  static double c0[80][2], c1[80][2];
  size_t n0 = corners(csv, "", c0, 80);
  aq_check(n0 == 80, "the undeformed corners (%zu)", n0);
  /* the rest centroids are the voussoirs': ARCH is a semicircle about the
   * origin without fill or masses, so voussoir k is an annular sector,
   * its centroid on the bisector at (2/3)(R^3 - r^3)/(R^2 - r^2) sin(a)/a
   * from the centre (a: its half-angle; the corners extrados, extrados,
   * intrados, intrados) */
  double worst = 0;
  for (size_t k = 0; k < h.nv; k++) {
    const double *e0 = c0[4 * k], *e1 = c0[4 * k + 1], *i1 = c0[4 * k + 2];
    double R = hypot(e0[0], e0[1]), r = hypot(i1[0], i1[1]);
    double t0 = atan2(e0[1], e0[0]), t1 = atan2(e1[1], e1[0]), a = fabs(t1 - t0) / 2;
    double d = 2.0 / 3.0 * (R * R * R - r * r * r) / (R * R - r * r) * sin(a) / a;
    double tm = (t0 + t1) / 2;
    worst = fmax(worst, hypot(d * cos(tm) - h.x[k], d * sin(tm) - h.y[k]));
  }
  aq_check(worst < 1e-9, "rest centroids: the annular sectors' (%.3g m)", worst);
  /* each time's layer, in the order given: every corner moved rigidly */
  char pre[2][64];
  const char *p = csv;
  for (int l = 0; l < 2; l++) { /* the layers' own prefixes, "at_...s_" */
    p = strstr(p, "\nat_");
    pre[l][0] = 0;
    if (p)
      snprintf(pre[l], sizeof pre[l], "%.*s", (int)strcspn(p + 1, "c"), p + 1);
    while (p && !strncmp(p + 1, pre[l], strlen(pre[l])))
      p = strchr(p + 1, '\n');
  }
  for (int l = 0; l < 2; l++) {
    size_t n1 = corners(csv, pre[l], c1, 80);
    double dev = 0;
    for (size_t k = 0; k < h.nv && n1 == 80; k++)
      for (int j = 0; j < 4; j++) {
        double o[2];
        moved(&h, k, at[l], c0[4 * k + j], o);
        dev = fmax(dev, hypot(o[0] - c1[4 * k + j][0], o[1] - c1[4 * k + j][1]));
      }
    aq_check(n1 == 80 && dev < 1e-9, "layer %s (t %.17g s): 80 corners (%zu) as the history "
             "moves them (%.3g m)", pre[l], at[l], n1, dev);
  }
  free(csv);
  /* no --at: the time of voussoir 0's largest |rotation| */
  snprintf(cmd, sizeof cmd, "plot arch %s --run " KEY " -o %s --data %s", h5, png, csvp);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  csv = rc == 0 ? aq_test_read_file(csvp, NULL) : NULL;
  char want[64];
  snprintf(want, sizeof want, "\nat_%.6gs_corner,0,", h.t[peak]);
  want[strlen(want) - strlen("corner,0,")] = 0; /* the layer's prefix */
  aq_check(csv && count(csv, want) > 0 && count(csv, want) == count(csv, "\nat_"),
           "default: one layer, at the peak, %g s (exit %d)", h.t[peak], rc);
  free(csv);
  hist_free(&h);
}

/* Every count of files in dir. */
static size_t files_in(const char *dir)
{
  char cmd[700];
  snprintf(cmd, sizeof cmd, "ls -A %s | wc -l", dir);
  FILE *p = popen(cmd, "r");
  size_t n = 0;
  if (p) {
    if (fscanf(p, "%zu", &n) != 1)
      n = 0;
    pclose(p);
  }
  return n;
}

/* Bad input to plot arch --run: one line naming the option, exit 2,
 * nothing written. */
AQ_TEST(blocks_plot_arch_run_refusals)
{
  char dir[512], h5[700], wp[700];
  aq_test_tmpdir(dir, sizeof dir);
  if (!blocks_run(dir, "r.h5", "blocks") || !blocks_run(dir, "w.h5", "workpath"))
    return;
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(wp, sizeof wp, "%s/w.h5", dir);
  struct {
    const char *file, *args, *want;
  } cases[] = {
      {h5, "--at 2", "--run"},                              /* --at needs --run */
      {NULL, "--arch " ARCH " --run " KEY, "results file"}, /* no file to read */
      {h5, "--run " KEY " --rotation 0.01", "--rotation"},
      {h5, "--run " KEY " --at 9999", "--at"},              /* past the history */
      {h5, "--run " KEY " --at 1,2,3,4,5,6,7", "--at"},     /* more than 6 */
      {h5, "--run " KEY " --at 1,,2", "--at"},
      {h5, "--run 00042_000_000", "--run"},
      {h5, "--run " KEY " --arch thick", "--arch"},         /* not the run's arch */
      {wp, "--run " KEY, "--model blocks"},                 /* a four-hinge run */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "plot arch %s %s -o %s/x.png --data %s/x.csv",
             cases[i].file ? cases[i].file : "", cases[i].args, dir, dir);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, cases[i].want) &&
                 !strncmp(err, "archquake: ", 11),
             "%s: exit %d (want 2), \"%s\"", cmd, rc, err);
  }
  aq_check(files_in(dir) == 2, "nothing written but the two results files (%zu files)",
           files_in(dir));
}
