/* arch_h5.c: the arch figure drawn again from a results file (see plot.h,
 * arch_fig.h): the geometry and hinge sets /geometry keeps, read with the
 * HDF5 library into an arch without its .cfg (aq_plot_arch_h5), and a
 * block-model run's voussoirs where its history has them at given times
 * (aq_plot_arch_run).
 */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/model.h"
#include "arch_fig.h"
#include "plot.h"

/* ---- an arch drawn again from a results file ---------------------------- */

/* String attribute name of loc into buf[n] ("" if none). */
static int attr_text(hid_t loc, const char *name, char *buf, size_t n)
{
  buf[0] = '\0';
  hid_t a = -1, t = -1;
  int ok = 0;
  H5E_BEGIN_TRY
  {
    a = H5Aopen(loc, name, H5P_DEFAULT);
    if (a >= 0 && (t = H5Tcopy(H5T_C_S1)) >= 0 && H5Tset_size(t, n) >= 0 &&
        H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0)
      ok = H5Aread(a, t, buf) >= 0;
  }
  H5E_END_TRY;
  if (t >= 0)
    H5Tclose(t);
  if (a >= 0)
    H5Aclose(a);
  buf[n - 1] = '\0';
  return ok;
}

static int attr_double(hid_t loc, const char *name, double *v)
{
  hid_t a = -1;
  int ok = 0;
  H5E_BEGIN_TRY
  {
    a = H5Aopen(loc, name, H5P_DEFAULT);
    ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, v) >= 0;
  }
  H5E_END_TRY;
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

/* Dataset name of group g, rows x cols doubles (cols as stored), into a new
 * array *v; -1 if missing or of other columns. */
static long dataset(hid_t g, const char *name, int cols, double **v)
{
  hid_t d = -1, s = -1;
  long rows = -1;
  *v = NULL;
  H5E_BEGIN_TRY
  {
    d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d >= 0 && (s = H5Dget_space(d)) >= 0) {
      hsize_t dim[2] = {0, 1};
      int nd = H5Sget_simple_extent_ndims(s);
      if (nd == (cols > 1 ? 2 : 1) && H5Sget_simple_extent_dims(s, dim, NULL) == nd &&
          (cols == 1 || dim[1] == (hsize_t)cols)) {
        *v = malloc((dim[0] * (hsize_t)cols + 1) * sizeof **v);
        if (*v && (dim[0] == 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                          *v) >= 0))
          rows = (long)dim[0];
      }
    }
  }
  H5E_END_TRY;
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  if (rows < 0) {
    free(*v);
    *v = NULL;
  }
  return rows;
}

/* The point masses of geometry group g into a new nmass x 4 array *v
 * (voussoir, x_m, y_m, mass_kg): the table `masses` (its voussoir an
 * integer), or the nmass x 4 doubles of a file written before; -1 if
 * missing or neither. */
static long masses(hid_t g, double **v)
{
  static const char *const col[4] = {"voussoir", "x_m", "y_m", "mass_kg"};
  hid_t d = -1, t = -1, s = -1, m = -1;
  long rows = -1;
  *v = NULL;
  H5E_BEGIN_TRY
  {
    d = H5Dopen2(g, "masses", H5P_DEFAULT);
    t = d >= 0 ? H5Dget_type(d) : -1;
    if (t >= 0 && H5Tget_class(t) == H5T_COMPOUND && (s = H5Dget_space(d)) >= 0) {
      hssize_t n = H5Sget_simple_extent_npoints(s);
      m = H5Tcreate(H5T_COMPOUND, 4 * sizeof(double)); /* the integer converted */
      int ok = n >= 0 && m >= 0;
      for (int k = 0; ok && k < 4; k++)
        ok = H5Tinsert(m, col[k], (size_t)k * sizeof(double), H5T_NATIVE_DOUBLE) >= 0;
      *v = ok ? malloc(((size_t)n * 4 + 1) * sizeof **v) : NULL;
      if (*v && (n == 0 || H5Dread(d, m, H5S_ALL, H5S_ALL, H5P_DEFAULT, *v) >= 0))
        rows = (long)n;
    }
  }
  H5E_END_TRY;
  if (m >= 0)
    H5Tclose(m);
  if (s >= 0)
    H5Sclose(s);
  int compound = t >= 0 && H5Tget_class(t) == H5T_COMPOUND;
  if (t >= 0)
    H5Tclose(t);
  if (d >= 0)
    H5Dclose(d);
  if (rows < 0) {
    free(*v);
    *v = NULL;
    if (!compound)
      return dataset(g, "masses", 4, v);
  }
  return rows;
}

/* "0,6,12,19" and "eiei" into hs. */
static int hinges(const char *joints, const char *faces, aq_hinge_set *hs)
{
  unsigned long j[4];
  if (sscanf(joints, "%lu,%lu,%lu,%lu", &j[0], &j[1], &j[2], &j[3]) != 4 || strlen(faces) != 4)
    return 0;
  for (int k = 0; k < 4; k++) {
    hs->joint[k] = j[k];
    hs->face[k] = faces[k];
  }
  return 1;
}

/* Arch `name` of open results file f (NULL: the first; want >= 0: the
 * arch of that index, name then checked against it) into *arch, built from
 * its stored geometry and hinge sets. */
static aq_status file_arch(hid_t f, const char *path, const char *name, long want,
                           aq_arch **out, aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64], got[128], first[128] = "", names[512] = "";
  long index = -1;
  *out = NULL;
  for (long k = 0; k < 1000; k++) {
    snprintf(obj, sizeof obj, "/arches/%03ld", k);
    htri_t there = H5Lexists(f, "/arches", H5P_DEFAULT) > 0 ? H5Lexists(f, obj, H5P_DEFAULT) : 0;
    if (there <= 0)
      break;
    hid_t g = H5Gopen2(f, obj, H5P_DEFAULT);
    attr_text(g, "name", got, sizeof got);
    H5Gclose(g);
    if (!first[0])
      snprintf(first, sizeof first, "%s", got);
    snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", k ? ", " : "", got);
    if (want >= 0 ? k == want : !name || !strcmp(name, got)) {
      index = k;
      break;
    }
  }
  double *joints = NULL, *parts = NULL, *outline = NULL, *ostart = NULL, *fill = NULL,
         *fstart = NULL, *mass = NULL;
  int64_t *os = NULL, *fs = NULL;
  aq_arch *arch = NULL;
  if (index < 0) {
    st = want >= 0 ? aq_error_set(err, AQ_EFORMAT, path, -1, -1, "--run",
                                  "expected arch %ld of the run in the file's arches (%s), "
                                  "got none", want, names[0] ? names : "none")
                   : aq_error_set(err, AQ_EVALUE, path, -1, -1, "--arch",
                                  "expected the name of one of the file's arches (%s), got "
                                  "\"%s\"",
                                  names[0] ? names : "none", name ? name : "");
    goto done;
  }
  if (want >= 0 && name && strcmp(name, got) != 0) {
    st = aq_error_set(err, AQ_EVALUE, path, -1, -1, "--arch",
                      "expected the run's arch, %s, or no --arch, got \"%s\"", got, name);
    goto done;
  }
  char gname[64], pj[64], pf[8], rj[64], rf[8], shape[32];
  snprintf(gname, sizeof gname, "/geometry/%03ld", index);
  hid_t ga = H5Gopen2(f, obj, H5P_DEFAULT);
  aq_arch_dynamics dyn = {0, AQ_IMPACT_COR, 9.80665};
  aq_hinge_set hs[2];
  int ok = ga >= 0 && attr_text(ga, "name", got, sizeof got) &&
           attr_text(ga, "primary_joints", pj, sizeof pj) &&
           attr_text(ga, "primary_faces", pf, sizeof pf) &&
           attr_text(ga, "reverse_joints", rj, sizeof rj) &&
           attr_text(ga, "reverse_faces", rf, sizeof rf) && hinges(pj, pf, &hs[0]) &&
           hinges(rj, rf, &hs[1]);
  if (!attr_double(ga, "g_mps2", &dyn.g_mps2))
    attr_double(ga, "g_m_s2", &dyn.g_mps2); /* its name before it became the .cfg key's */
  double mu = NAN; /* the runs' friction (files written before it have none) */
  attr_double(ga, "friction", &mu);
  if (ga >= 0)
    H5Gclose(ga);
  hid_t gg = ok && H5Lexists(f, "/geometry", H5P_DEFAULT) > 0 &&
                     H5Lexists(f, gname, H5P_DEFAULT) > 0
                 ? H5Gopen2(f, gname, H5P_DEFAULT)
                 : -1;
  if (!ok || gg < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, gname,
                      "expected arch %s's hinge sets in %s and its geometry in %s, got %s "
                      "(a file written before the geometry was stored: draw it from its .cfg)",
                      got, obj, gname, ok ? "no geometry" : "no hinge sets");
    goto done;
  }
  attr_text(gg, "shape", shape, sizeof shape);
  long nj = dataset(gg, "joints", 4, &joints), nv = dataset(gg, "voussoirs", 4, &parts);
  long no = dataset(gg, "outline", 2, &outline), nos = dataset(gg, "outline_start", 1, &ostart);
  long nf = dataset(gg, "fill", 2, &fill), nfs = dataset(gg, "fill_start", 1, &fstart);
  long nm = masses(gg, &mass);
  double kg[3] = {NAN, 0, 0};
  attr_double(gg, "masonry_kg", &kg[0]);
  attr_double(gg, "fill_kg", &kg[1]);
  attr_double(gg, "point_masses_kg", &kg[2]);
  H5Gclose(gg);
  if (nv < 4 || nj != nv + 1 || nos != nv + 1 || nfs != nv + 1 || no < 0 || nf < 0 || nm < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, gname,
                      "expected joints, voussoirs, outline, fill and masses of matching sizes, "
                      "got %ld joints for %ld voussoirs", nj, nv);
    goto done;
  }
  os = malloc((size_t)(nv + 1) * sizeof *os);
  fs = malloc((size_t)(nv + 1) * sizeof *fs);
  if (!os || !fs) {
    st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (long k = 0; k <= nv; k++) {
    os[k] = (int64_t)ostart[k];
    fs[k] = (int64_t)fstart[k];
  }
  aq_arch_drawing d = {shape, (size_t)nv, joints, parts, (size_t)no, (size_t)nf, outline, os,
                       fill, fs, (size_t)nm, mass, kg[0], kg[1], kg[2]};
  st = aq_arch_from_drawing(&d, &hs[0], &hs[1], &dyn, mu, got, &arch, err);
  if (st != AQ_OK) {
    snprintf(err->input, sizeof err->input, "%s", path);
    goto done;
  }
  *out = arch;
  arch = NULL;
done:
  aq_arch_free(arch);
  free(joints);
  free(parts);
  free(outline);
  free(ostart);
  free(fill);
  free(fstart);
  free(mass);
  free(os);
  free(fs);
  return st;
}

aq_status aq_plot_arch_h5(const char *path, const char *name, double rotation_rad,
                          const char *target, const char *data, double *draw_s, aq_error *err)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "expected an archquake results file (HDF5), got one that cannot be "
                        "opened as such");
  aq_arch *arch = NULL;
  aq_status st = file_arch(f, path, name, -1, &arch, err);
  H5Fclose(f);
  if (st == AQ_OK)
    st = aq_plot_arch(arch, rotation_rad, target, data, draw_s, err);
  aq_arch_free(arch);
  return st;
}

/* Sample value of v (n samples x nv columns, column k) at time t between
 * the samples of t_s (ascending; t within [t_s[0], t_s[n-1]]), linear. */
static double at_time(const double *t_s, size_t n, const double *v, size_t nv, size_t k, double t)
{
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) { /* t_s[lo] <= t <= t_s[hi] */
    size_t mid = lo + (hi - lo) / 2;
    if (t_s[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  double a = v[lo * nv + k], b = v[hi * nv + k], dt = t_s[hi] - t_s[lo];
  return dt > 0 ? a + (b - a) * (t - t_s[lo]) / dt : b;
}

aq_status aq_plot_arch_run(const char *path, const char *name, const char *key,
                           const double *at_s, size_t nat, const char *target,
                           const char *data, double *draw_s, aq_error *err)
{
  if (nat > AQ_PLOT_ARCH_AT_MAX)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--at",
                        "expected at most %d times, got %zu", AQ_PLOT_ARCH_AT_MAX, nat);
  aq_plot_run r;
  aq_status st = aq_plot_run_read(path, key, &r, err);
  if (st != AQ_OK)
    return st;
  aq_arch *arch = NULL;
  double *buf = NULL, peak_s = 0;
  if (r.nvous == 0 || r.n == 0) {
    st = aq_error_set(err, AQ_EVALUE, path, -1, -1, "--run",
                      "expected a run of --model blocks (its voussoirs' histories), got run "
                      "%s without them (a four-hinge run: plot arch --rotation draws its "
                      "mechanism)",
                      r.key);
    goto done;
  }
  double t0 = r.t_s[0], t1 = r.t_s[r.n - 1];
  for (size_t i = 0; i < nat; i++)
    if (!(at_s[i] >= t0 && at_s[i] <= t1)) {
      st = aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--at",
                        "expected times within run %s's history, [%.6g, %.6g] s, got %g",
                        r.key, t0, t1, at_s[i]);
      goto done;
    }
  if (nat == 0) { /* the peak of voussoir 0's |rotation| */
    double peak = -1;
    for (size_t i = 0; i < r.n; i++)
      if (fabs(r.vrot_rad[i * r.nvous]) > peak)
        peak = fabs(r.vrot_rad[i * r.nvous]), peak_s = r.t_s[i];
    at_s = &peak_s;
    nat = 1;
  }
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) {
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
    goto done;
  }
  st = file_arch(f, path, name, r.arch_index, &arch, err);
  H5Fclose(f);
  if (st != AQ_OK)
    goto done;
  size_t nv = aq_arch_geom(arch)->p.voussoirs;
  if (nv != r.nvous) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "--run",
                      "expected run %s's history of the arch's %zu voussoirs, got %zu", r.key,
                      nv, r.nvous);
    goto done;
  }
  buf = malloc(3 * nat * nv * sizeof *buf);
  if (!buf) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    goto done;
  }
  fig fg;
  memset(&fg, 0, sizeof fg);
  fg.arch = arch;
  fg.g = aq_arch_geom(arch);
  fg.set = fg.thrust_set = -1;
  fg.nat = nat;
  fg.at_s = at_s;
  fg.bx = buf, fg.by = buf + nat * nv, fg.br = buf + 2 * nat * nv;
  fg.run = r.key;
  for (size_t i = 0; i < nat; i++)
    for (size_t k = 0; k < nv; k++) {
      buf[i * nv + k] = at_time(r.t_s, r.n, r.vx_m, nv, k, at_s[i]);
      buf[(nat + i) * nv + k] = at_time(r.t_s, r.n, r.vy_m, nv, k, at_s[i]);
      buf[(2 * nat + i) * nv + k] = at_time(r.t_s, r.n, r.vrot_rad, nv, k, at_s[i]);
    }
  st = aq_plot_arch_render(&fg, target, data, draw_s, err);
done:
  free(buf);
  aq_arch_free(arch);
  aq_plot_run_free(&r);
  return st;
}
