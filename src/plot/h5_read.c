/* h5_read.c: one run of a results file as the history figure needs it.
 * This is the only code that knows where a run's histories live
 * (docs/hdf5-layout.md: /runs/KEY attributes and datasets, the record's
 * /records/NNNNN/acceleration_m_s2, the arch's /arches/NNN attributes). */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

/* Scalar attribute name of loc as mtype into out; 0 or -1. */
static int attr_num(hid_t loc, const char *name, hid_t mtype, void *out)
{
  if (H5Aexists(loc, name) <= 0)
    return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, mtype, out) >= 0 ? 0 : -1;
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

/* Fixed-length string attribute into buf[n]; 0 or -1. */
static int attr_text(hid_t loc, const char *name, char *buf, size_t n)
{
  if (H5Aexists(loc, name) <= 0)
    return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT), t = a >= 0 ? H5Aget_type(a) : -1;
  int ok = -1;
  if (t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0) {
    size_t sz = H5Tget_size(t);
    char *tmp = calloc(sz + 1, 1);
    if (tmp && H5Aread(a, t, tmp) >= 0) {
      snprintf(buf, n, "%s", tmp);
      ok = 0;
    }
    free(tmp);
  }
  if (t >= 0)
    H5Tclose(t);
  if (a >= 0)
    H5Aclose(a);
  return ok;
}

/* 1-D double dataset name of loc, malloc'd into *v, length *n; 0 or -1. */
static int dataset(hid_t loc, const char *name, double **v, size_t *n)
{
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT), s = d >= 0 ? H5Dget_space(d) : -1;
  int ok = -1;
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
  if (np >= 0) {
    *v = malloc((np ? (size_t)np : 1) * sizeof **v);
    if (*v && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *v) >= 0) {
      *n = (size_t)np;
      ok = 0;
    } else {
      free(*v);
      *v = NULL;
    }
  }
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
  return ok;
}

/* The first few run keys of /runs, for the message naming them. */
static void list_keys(hid_t runs, char *buf, size_t cap)
{
  H5G_info_t info;
  buf[0] = '\0';
  if (H5Gget_info(runs, &info) < 0)
    return;
  size_t len = 0;
  for (hsize_t k = 0; k < info.nlinks && k < 4; k++) {
    char name[64];
    if (H5Lget_name_by_idx(runs, ".", H5_INDEX_NAME, H5_ITER_INC, k, name,
                           sizeof name, H5P_DEFAULT) < 0)
      return;
    len += (size_t)snprintf(buf + len, len < cap ? cap - len : 0, "%s%s",
                            k ? ", " : "", name);
  }
  if (info.nlinks > 4 && len < cap)
    snprintf(buf + len, cap - len, ", ... (%llu runs)",
             (unsigned long long)info.nlinks);
}

void aq_plot_run_free(aq_plot_run *r)
{
  if (!r)
    return;
  free(r->t_s);
  free(r->q_rad);
  free(r->x_m);
  free(r->ke_j);
  free(r->pe_j);
  free(r->ag_mps2);
  memset(r, 0, sizeof *r);
}

aq_status aq_plot_run_read(const char *path, const char *key, aq_plot_run *r,
                           aq_error *err)
{
  memset(r, 0, sizeof *r);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  aq_status st = AQ_OK;
  hid_t f = -1, runs = -1, g = -1, rec = -1, arc = -1;
  char obj[128], keys[256], recg[64] = "", archg[64] = "", pol[16] = "normal";
  if (H5Fis_hdf5(path) <= 0 || (f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                      "expected an archquake results file (HDF5), got none readable");
    goto done;
  }
  if ((runs = H5Gopen2(f, "/runs", H5P_DEFAULT)) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/runs",
                      "expected an archquake results file (group /runs), got none");
    goto done;
  }
  if (!key) {
    if (H5Lget_name_by_idx(runs, ".", H5_INDEX_NAME, H5_ITER_INC, 0, r->key,
                           sizeof r->key, H5P_DEFAULT) < 0) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, "/runs",
                        "expected at least one run, got none");
      goto done;
    }
  } else {
    snprintf(r->key, sizeof r->key, "%s", key);
    if (strlen(key) >= sizeof r->key || strchr(key, '/') ||
        H5Lexists(runs, key, H5P_DEFAULT) <= 0) {
      list_keys(runs, keys, sizeof keys);
      st = aq_error_set(err, AQ_EVALUE, path, -1, -1, "--run",
                        "expected a run key such as %s, got \"%s\"", keys, key);
      goto done;
    }
  }
  snprintf(obj, sizeof obj, "/runs/%s", r->key);
  if ((g = H5Gopen2(runs, r->key, H5P_DEFAULT)) < 0 ||
      attr_text(g, "record", r->record, sizeof r->record) < 0 ||
      attr_text(g, "arch", r->arch, sizeof r->arch) < 0 ||
      attr_text(g, "record_group", recg, sizeof recg) < 0 ||
      attr_text(g, "arch_group", archg, sizeof archg) < 0 ||
      attr_num(g, "scale", H5T_NATIVE_DOUBLE, &r->scale) < 0 ||
      attr_num(g, "collapsed", H5T_NATIVE_INT, &r->collapsed) < 0 ||
      attr_num(g, "collapse_time_s", H5T_NATIVE_DOUBLE, &r->collapse_time_s) < 0 ||
      attr_num(g, "impacts", H5T_NATIVE_LONG, &r->impacts) < 0 ||
      attr_num(g, "energy_in_j", H5T_NATIVE_DOUBLE, &r->energy_in_j) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                      "expected a run group with its attributes, got an incomplete one");
    goto done;
  }
  attr_text(g, "polarity", pol, sizeof pol); /* absent before --polarity */
  r->reversed = strcmp(pol, "reversed") == 0;
  if (H5Lexists(g, "time_s", H5P_DEFAULT) <= 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                      "expected histories (a results file written with --history), "
                      "got none");
    goto done;
  }
  size_t n[5];
  if (dataset(g, "time_s", &r->t_s, &n[0]) < 0 ||
      dataset(g, "rotation_rad", &r->q_rad, &n[1]) < 0 ||
      dataset(g, "displacement_m", &r->x_m, &n[2]) < 0 ||
      dataset(g, "kinetic_energy_j", &r->ke_j, &n[3]) < 0 ||
      dataset(g, "potential_energy_j", &r->pe_j, &n[4]) < 0 || n[1] != n[0] ||
      n[2] != n[0] || n[3] != n[0] || n[4] != n[0]) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                      "expected five histories of equal length, got others");
    goto done;
  }
  r->n = n[0];
  if ((rec = H5Gopen2(f, recg, H5P_DEFAULT)) < 0 ||
      H5Lexists(rec, "acceleration_m_s2", H5P_DEFAULT) <= 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, recg,
                      "expected the record's acceleration_m_s2, got none");
    goto done;
  }
  hid_t d = H5Dopen2(rec, "acceleration_m_s2", H5P_DEFAULT);
  int ok = d >= 0 && attr_num(d, "dt_s", H5T_NATIVE_DOUBLE, &r->ag_dt_s) == 0 &&
           attr_num(d, "t0_s", H5T_NATIVE_DOUBLE, &r->ag_t0_s) == 0;
  if (d >= 0)
    H5Dclose(d);
  if (!ok || dataset(rec, "acceleration_m_s2", &r->ag_mps2, &r->na) < 0 ||
      !(r->ag_dt_s > 0)) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, recg,
                      "expected acceleration_m_s2 with dt_s > 0 and t0_s, got others");
    goto done;
  }
  attr_num(rec, "n_orig", H5T_NATIVE_LONG, &r->n_orig); /* 0 if absent */
  double sign = r->reversed ? -r->scale : r->scale; /* as the run saw it */
  for (size_t i = 0; i < r->na; i++)
    r->ag_mps2[i] *= sign;
  if ((arc = H5Gopen2(f, archg, H5P_DEFAULT)) < 0 ||
      attr_num(arc, "primary_lambda0", H5T_NATIVE_DOUBLE, &r->lambda0[0]) < 0 ||
      attr_num(arc, "reverse_lambda0", H5T_NATIVE_DOUBLE, &r->lambda0[1]) < 0 ||
      attr_num(arc, "primary_q_c_rad", H5T_NATIVE_DOUBLE, &r->q_c_rad[0]) < 0 ||
      attr_num(arc, "reverse_q_c_rad", H5T_NATIVE_DOUBLE, &r->q_c_rad[1]) < 0 ||
      attr_num(arc, "primary_mass_kg", H5T_NATIVE_DOUBLE, &r->mass_kg) < 0 ||
      attr_num(arc, "g_m_s2", H5T_NATIVE_DOUBLE, &r->g_mps2) < 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, archg,
                      "expected the arch's lambda0, q_c_rad and mass_kg, got none");
    goto done;
  }
done:
  H5E_BEGIN_TRY
  {
    if (arc >= 0) H5Gclose(arc);
    if (rec >= 0) H5Gclose(rec);
    if (g >= 0) H5Gclose(g);
    if (runs >= 0) H5Gclose(runs);
    if (f >= 0) H5Fclose(f);
  }
  H5E_END_TRY;
  if (st != AQ_OK)
    aq_plot_run_free(r);
  return st;
}
