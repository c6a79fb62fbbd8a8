/* h5_read.c: one run of a results file as the history figure needs it.
 * This is the only code that knows where a run's histories and ground
 * motion live (docs/hdf5-layout.md).  The run's summary comes from
 * aq_h5_read_suite (either format); then:
 *   format 2: /histories/KEY datasets, /waveforms/NNNNN (only with
 *             --store-records), n_orig from the /records table;
 *   format 1: /runs/KEY datasets, /records/NNNNN/acceleration_m_s2 and its
 *             group's n_orig attribute;
 * and the arch's /arches/NNN attributes (both). */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../report/h5.h"
#include "plot.h"

/* 1-D double dataset path of f, malloc'd into *v, length *n; 0 or -1. */
static int dataset(hid_t f, const char *path, double **v, size_t *n)
{
  hid_t d = H5Dopen2(f, path, H5P_DEFAULT), s = d >= 0 ? H5Dget_space(d) : -1;
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

/* n_orig and dt_s of row `row` of the /records table (format 2); left
 * as they are if unreadable. */
static void table_record(hid_t f, long long row, long *n_orig, double *dt_s)
{
  typedef struct {
    long long n_orig;
    double dt_s;
  } cols;
  cols *v = NULL;
  hid_t d = H5Dopen2(f, "/records", H5P_DEFAULT);
  hid_t s = d >= 0 ? H5Dget_space(d) : -1;
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(cols));
  hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
  if (t >= 0 && H5Tinsert(t, "n_orig", HOFFSET(cols, n_orig), H5T_NATIVE_LLONG) >= 0 &&
      H5Tinsert(t, "dt_s", HOFFSET(cols, dt_s), H5T_NATIVE_DOUBLE) >= 0 && np > row &&
      row >= 0 && (v = malloc((size_t)np * sizeof *v)) &&
      H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0) {
    *n_orig = (long)v[row].n_orig;
    *dt_s = v[row].dt_s;
  }
  free(v);
  if (t >= 0)
    H5Tclose(t);
  if (s >= 0)
    H5Sclose(s);
  if (d >= 0)
    H5Dclose(d);
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
  free(r->set);
  free(r->ag_mps2);
  free(r->vx_m);
  free(r->vy_m);
  free(r->vrot_rad);
  memset(r, 0, sizeof *r);
}

/* The block model's voussoir histories of run r->key under hist, if the
 * file has them (--model blocks): 0 (read, or none there), -1 (there but
 * not n x k doubles with n = r->n). */
static int voussoirs(hid_t f, const char *hist, aq_plot_run *r)
{
  static const char *const names[3] = {"voussoir_x_m", "voussoir_y_m", "voussoir_rotation_rad"};
  double **dst[3] = {&r->vx_m, &r->vy_m, &r->vrot_rad};
  char obj[160];
  size_t nv = 0;
  for (int i = 0; i < 3; i++) {
    snprintf(obj, sizeof obj, "%s/%s/%s", hist, r->key, names[i]);
    if (H5Oexists_by_name(f, obj, H5P_DEFAULT) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      if (i == 0)
        return 0;
      return -1;
    }
    hid_t d = H5Dopen2(f, obj, H5P_DEFAULT), s = d >= 0 ? H5Dget_space(d) : -1;
    hsize_t dim[2] = {0, 0};
    int ok = s >= 0 && H5Sget_simple_extent_ndims(s) == 2 &&
             H5Sget_simple_extent_dims(s, dim, NULL) == 2 && dim[0] == r->n && dim[1] > 0 &&
             (i == 0 || dim[1] == nv);
    if (s >= 0)
      H5Sclose(s);
    if (d >= 0)
      H5Dclose(d);
    size_t cnt = 0;
    if (!ok || dataset(f, obj, dst[i], &cnt) < 0 || cnt != r->n * dim[1])
      return -1;
    nv = dim[1];
  }
  r->nvous = nv;
  return 0;
}

static void run_key(const aq_h5_run *u, char *buf, size_t n)
{
  snprintf(buf, n, "%05lld_%03lld_%03lld%s", (long long)u->record_index,
           (long long)u->arch_index, (long long)u->scale_index,
           strcmp(u->s.polarity, "reversed") == 0 ? "r" : "");
}

aq_status aq_plot_run_read(const char *path, const char *key, aq_plot_run *r,
                           aq_error *err)
{
  memset(r, 0, sizeof *r);
  aq_h5_suite S;
  aq_status st = aq_h5_read_suite(path, &S, err);
  if (st != AQ_OK)
    return st;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT), arc = -1;
  char obj[160], keys[256] = "", k[64];
  const aq_h5_run *u = NULL;
  if (f < 0) {
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "HDF5: cannot open");
    goto done;
  }
  int v2 = H5Lexists(f, "/runs", H5P_DEFAULT) <= 0; /* format 1: a group per run */
  const char *hist = v2 ? "/histories" : "/runs";
  size_t with = 0, len = 0; /* runs with histories; the first few keys */
  for (size_t i = 0; i < S.nruns; i++) {
    run_key(&S.runs[i], k, sizeof k);
    snprintf(obj, sizeof obj, "%s/%s/time_s", hist, k);
    int has = H5Lexists(f, hist, H5P_DEFAULT) > 0 && H5Oexists_by_name(f, obj, H5P_DEFAULT) > 0;
    H5Eclear2(H5E_DEFAULT);
    if (has && with++ < 4 && len < sizeof keys)
      len += (size_t)snprintf(keys + len, sizeof keys - len, "%s%s", len ? ", " : "", k);
    if (has && (key ? strcmp(key, k) == 0 : !u))
      u = &S.runs[i];
    if (!has && key && strcmp(key, k) == 0) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, k,
                        "expected the run's histories (a results file written with "
                        "--history), got none");
      goto done;
    }
  }
  if (with == 0) {
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, hist,
                      "expected histories (a results file written with --history), got none");
    goto done;
  }
  if (!u) {
    st = aq_error_set(err, AQ_EVALUE, path, -1, -1, "--run",
                      "expected a run key such as %s%s, got \"%s\"", keys,
                      with > 4 ? ", ..." : "", key);
    goto done;
  }
  run_key(u, r->key, sizeof r->key);
  snprintf(r->record, sizeof r->record, "%s", u->s.record);
  snprintf(r->arch, sizeof r->arch, "%s", u->s.arch);
  r->scale = u->s.scale;
  r->reversed = strcmp(u->s.polarity, "reversed") == 0;
  r->collapsed = (int)u->s.collapsed;
  r->collapse_time_s = u->s.collapse_time_s;
  r->impacts = (long)u->s.impacts;
  r->energy_in_j = u->s.energy_in_j;
  r->arch_index = (long)u->arch_index;

  static const char *const names[5] = {"time_s", "rotation_rad", "displacement_m",
                                       "kinetic_energy_j", "potential_energy_j"};
  double **dst[5] = {&r->t_s, &r->q_rad, &r->x_m, &r->ke_j, &r->pe_j};
  for (int i = 0; i < 5; i++) {
    size_t n = 0;
    snprintf(obj, sizeof obj, "%s/%s/%s", hist, r->key, names[i]);
    if (dataset(f, obj, dst[i], &n) < 0 || (i > 0 && n != r->n)) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                        "expected a history as long as time_s, got none or another length");
      goto done;
    }
    r->n = n;
  }
  /* the hinge set at each sample, where the file keeps it (format 2) */
  snprintf(obj, sizeof obj, "%s/%s/hinge_set", hist, r->key);
  if (H5Oexists_by_name(f, obj, H5P_DEFAULT) > 0) {
    hid_t d = H5Dopen2(f, obj, H5P_DEFAULT), sp = d >= 0 ? H5Dget_space(d) : -1;
    r->set = sp >= 0 && H5Sget_simple_extent_npoints(sp) == (hssize_t)r->n
                 ? malloc((r->n ? r->n : 1) * sizeof *r->set)
                 : NULL;
    if (r->set && H5Dread(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, r->set) < 0) {
      free(r->set);
      r->set = NULL;
    }
    if (sp >= 0)
      H5Sclose(sp);
    if (d >= 0)
      H5Dclose(d);
  }
  H5Eclear2(H5E_DEFAULT);
  if (voussoirs(f, hist, r) < 0) {
    snprintf(obj, sizeof obj, "%s/%s", hist, r->key);
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                      "expected the block model's voussoir histories as n x k doubles, n "
                      "as long as time_s, got others");
    goto done;
  }

  /* the ground, as the run saw it (absent from a format-2 file written
   * without --store-records: the figure then goes without it) */
  long long ri = (long long)u->record_index;
  if (v2)
    snprintf(obj, sizeof obj, "/waveforms/%05lld", ri);
  else
    snprintf(obj, sizeof obj, "/records/%05lld/acceleration_m_s2", ri);
  if (H5Lexists(f, v2 ? "/waveforms" : "/records", H5P_DEFAULT) > 0 &&
      H5Oexists_by_name(f, obj, H5P_DEFAULT) > 0) {
    hid_t d = H5Dopen2(f, obj, H5P_DEFAULT);
    int ok = d >= 0 && aq_h5_attr_num(d, "dt_s", H5T_NATIVE_DOUBLE, &r->ag_dt_s) == 0 &&
             aq_h5_attr_num(d, "t0_s", H5T_NATIVE_DOUBLE, &r->ag_t0_s) == 0;
    if (d >= 0)
      H5Dclose(d);
    if (!ok || dataset(f, obj, &r->ag_mps2, &r->na) < 0 || !(r->ag_dt_s > 0)) {
      st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                        "expected the ground acceleration with dt_s > 0 and t0_s, got others");
      goto done;
    }
    double sign = r->reversed ? -r->scale : r->scale; /* as the run saw it */
    for (size_t i = 0; i < r->na; i++)
      r->ag_mps2[i] *= sign;
  }
  H5Eclear2(H5E_DEFAULT);
  if (v2)
    table_record(f, ri, &r->n_orig, &r->rec_dt_s);
  else {
    snprintf(obj, sizeof obj, "/records/%05lld", ri);
    hid_t g = H5Gopen2(f, obj, H5P_DEFAULT);
    if (g >= 0) {
      aq_h5_attr_num(g, "n_orig", H5T_NATIVE_LONG, &r->n_orig); /* 0 if absent */
      aq_h5_attr_num(g, "dt_s", H5T_NATIVE_DOUBLE, &r->rec_dt_s);
      H5Gclose(g);
    }
  }

  snprintf(obj, sizeof obj, "/arches/%03lld", (long long)u->arch_index);
  if ((arc = H5Gopen2(f, obj, H5P_DEFAULT)) < 0 ||
      aq_h5_attr_num(arc, "primary_lambda0", H5T_NATIVE_DOUBLE, &r->lambda0[0]) < 0 ||
      aq_h5_attr_num(arc, "reverse_lambda0", H5T_NATIVE_DOUBLE, &r->lambda0[1]) < 0 ||
      aq_h5_attr_num(arc, "primary_q_c_rad", H5T_NATIVE_DOUBLE, &r->q_c_rad[0]) < 0 ||
      aq_h5_attr_num(arc, "reverse_q_c_rad", H5T_NATIVE_DOUBLE, &r->q_c_rad[1]) < 0 ||
      aq_h5_attr_num(arc, "primary_mass_kg", H5T_NATIVE_DOUBLE, &r->mass_kg) < 0 ||
      (aq_h5_attr_num(arc, "g_mps2", H5T_NATIVE_DOUBLE, &r->g_mps2) < 0 &&
       aq_h5_attr_num(arc, "g_m_s2", H5T_NATIVE_DOUBLE, &r->g_mps2) < 0)) { /* (its former name) */
    st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, obj,
                      "expected the arch's lambda0, q_c_rad, mass_kg and g_mps2, got none");
    goto done;
  }
  /* the sign of q while each set moves (0 if the file does not say) */
  aq_h5_attr_num(arc, "primary_q_sign", H5T_NATIVE_INT, &r->q_sign[0]);
  aq_h5_attr_num(arc, "reverse_q_sign", H5T_NATIVE_INT, &r->q_sign[1]);
done:
  H5E_BEGIN_TRY
  {
    if (arc >= 0)
      H5Gclose(arc);
    if (f >= 0)
      H5Fclose(f);
  }
  H5E_END_TRY;
  aq_h5_suite_free(&S);
  if (st != AQ_OK)
    aq_plot_run_free(r);
  return st;
}
