/* h5_arches.c: /arches (each arch's file, hinge sets and dynamics) and
 * /geometry (its generated drawing, so that a result can be drawn again
 * without its .cfg) of the results writer (h5.h, h5_writer.h). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "../arch/model.h"
#include "h5_writer.h"

static const char *impact_name(aq_impact i)
{
  return i == AQ_IMPACT_MOMENTUM ? "momentum" : "cor";
}

/* A rows x cols table of doubles with its columns' names and units, one
 * string per column (attributes columns and units, as in /capacity). */
static herr_t dataset_2d(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                         size_t rows, size_t cols, const char *const *units,
                         const char *const *columns)
{
  hsize_t dim[2] = {rows, cols};
  hid_t s = H5Screate_simple(cols > 1 ? 2 : 1, dim, NULL);
  if (s < 0)
    return -1;
  hid_t d = H5Dcreate2(loc, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = d < 0 ? -1 : 0;
  if (rc == 0 && rows > 0)
    rc = H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    aq_h5w_sync_hint(w, rows * cols * sizeof(double));
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "columns", columns, cols);
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "units", units, cols);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

/* /geometry/NNN: arch NNN's generated geometry (docs/hdf5-layout.md), so
 * that a result can be drawn again without its .cfg. */
static aq_status write_geometry(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                                aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  snprintf(obj, sizeof obj, "/geometry/%03zu", index);
  aq_arch_drawing d;
  aq_arch_drawing_of(a->arch, &d);
  size_t n = d.voussoirs;
  /* the point masses as a table: the voussoir an integer, as every index */
  typedef struct {
    int64_t voussoir;
    double x_m, y_m, mass_kg;
  } mass_row;
  static const aq_h5_col mass_cols[] = {
      AQ_H5_COL(mass_row, voussoir, AQ_H5_INT, "1"), AQ_H5_COL(mass_row, x_m, AQ_H5_DOUBLE, "m"),
      AQ_H5_COL(mass_row, y_m, AQ_H5_DOUBLE, "m"),
      AQ_H5_COL(mass_row, mass_kg, AQ_H5_DOUBLE, "kg")};
  mass_row *masses = malloc((d.nmass ? d.nmass : 1) * sizeof *masses);
  hid_t lcpl = H5Pcreate(H5P_LINK_CREATE), g = -1;
  if (!masses) {
    st = aq_error_set(err, AQ_ENOMEM, w->target, -1, -1, obj, "out of memory");
    goto fail;
  }
  for (size_t i = 0; i < d.nmass; i++)
    masses[i] = (mass_row){(int64_t)d.mass[4 * i], d.mass[4 * i + 1], d.mass[4 * i + 2],
                           d.mass[4 * i + 3]};
  CK(lcpl, "H5Pcreate");
  CK(H5Pset_create_intermediate_group(lcpl, 1), "H5Pset_create_intermediate_group");
  g = H5Gcreate2(w->file, obj, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(aq_h5w_attr_str(w, g, "name", a->name), "geometry attributes");
  CK(aq_h5w_attr_str(w, g, "shape", d.shape), "geometry attributes");
  CK(aq_h5w_attr_int(w, g, "voussoirs", (int64_t)n), "geometry attributes");
  CK(aq_h5w_attr_double(w, g, "masonry_kg", d.stone_kg), "geometry attributes");
  CK(aq_h5w_attr_double(w, g, "fill_kg", d.fill_kg), "geometry attributes");
  CK(aq_h5w_attr_double(w, g, "point_masses_kg", d.point_kg), "geometry attributes");
  static const char *const m4[4] = {"m", "m", "m", "m"}, *const xy[2] = {"x_m", "y_m"},
                           *const jc[4] = {"xi_m", "yi_m", "xe_m", "ye_m"},
                           *const vc[4] = {"mass_kg", "x_m", "y_m", "inertia_kgm2"},
                           *const vu[4] = {"kg", "m", "m", "kg m^2"};
  CK(dataset_2d(w, g, "joints", d.joints, n + 1, 4, m4, jc), "joints");
  CK(dataset_2d(w, g, "voussoirs", d.parts, n, 4, vu, vc), "voussoirs");
  CK(dataset_2d(w, g, "outline", d.outline, d.noutline, 2, m4, xy), "outline");
  CK(aq_h5w_dataset_1d(w, g, "outline_start", H5T_STD_I64LE, H5T_NATIVE_INT64, d.outline_start,
                       n + 1, "1", 0, NULL, NULL, 0),
     "outline_start");
  CK(dataset_2d(w, g, "fill", d.fill, d.nfill, 2, m4, xy), "fill");
  CK(aq_h5w_dataset_1d(w, g, "fill_start", H5T_STD_I64LE, H5T_NATIVE_INT64, d.fill_start,
                       n + 1, "1", 0, NULL, NULL, 0),
     "fill_start");
  CK(aq_h5_table_write(g, "masses", mass_cols, sizeof mass_cols / sizeof mass_cols[0],
                       sizeof(mass_row), masses, d.nmass, NULL),
     "masses");
fail:
  free(masses);
  if (g >= 0 && H5Gclose(g) < 0 && st == AQ_OK)
    st = aq_h5w_fail(err, w->target, obj, "H5Gclose", errno);
  if (lcpl >= 0)
    H5Pclose(lcpl);
  return st;
}

aq_status aq_h5_write_arch(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                           aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  hid_t g = -1;
  snprintf(obj, sizeof obj, "/arches/%03zu", index);
  CK(aq_h5w_lazy_group(w, &w->g_arches, "/arches"), "H5Gcreate");
  g = H5Gcreate2(w->file, obj, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(aq_h5w_attr_str(w, g, "name", a->name), "arch attributes");
  CK(aq_h5w_attr_str(w, g, "source_file", a->source_file), "arch attributes");
  CK(aq_h5w_attr_str(w, g, "sha256", a->sha256), "arch attributes");
  CK(aq_h5w_attr_str(w, g, "config", a->config_text), "arch attributes");
  static const char *const data_name[2] = {"joints_csv", "faces_csv"};
  for (int k = 0; k < 2; k++) /* a joints arch's files, as read (in sha256) */
    if (a->data_text[k])
      CK(aq_h5w_attr_str(w, g, data_name[k], a->data_text[k]), "arch attributes");
  CK(aq_h5w_attr_int(w, g, "searched", a->searched ? 1 : 0), "arch attributes");
  if (a->arch) {
    CK(aq_h5w_attr_str(w, g, "control", aq_hinge_control_names[aq_arch_control(a->arch)]),
       "arch attributes");
    CK(aq_h5w_attr_double(w, g, "friction", aq_arch_friction(a->arch)), "arch attributes");
    size_t jr;
    CK(aq_h5w_attr_double(w, g, "mu_rest", aq_arch_mu_rest(a->arch, &jr)), "arch attributes");
    CK(aq_h5w_attr_int(w, g, "mu_rest_joint", (int64_t)jr), "arch attributes");
    /* the block model's contacts and supports (defaults 0) */
    CK(aq_h5w_attr_double(w, g, "e_n", aq_arch_restitution(a->arch)), "arch attributes");
    CK(aq_h5w_attr_double(w, g, "spread_m", aq_arch_spread(a->arch)), "arch attributes");
    CK(aq_h5w_attr_double(w, g, "abutment_m", aq_arch_abutment(a->arch)), "arch attributes");
  }
  if (a->dyn) {
    CK(aq_h5w_attr_double(w, g, "cor", a->dyn->cor), "arch attributes");
    CK(aq_h5w_attr_str(w, g, "impact", impact_name(a->dyn->impact)), "arch attributes");
    CK(aq_h5w_attr_double(w, g, "g_mps2", a->dyn->g_mps2), "arch attributes");
  }
  static const char *const set_name[2] = {"primary", "reverse"};
  for (int k = 0; k < 2; k++) {
    const aq_path *p = a->set[k];
    char nm[64];
    snprintf(nm, sizeof nm, "%s_joints", set_name[k]);
    CK(aq_h5w_attr_str(w, g, nm, a->joints[k]), "arch attributes");
    snprintf(nm, sizeof nm, "%s_faces", set_name[k]);
    CK(aq_h5w_attr_str(w, g, nm, a->faces[k]), "arch attributes");
    snprintf(nm, sizeof nm, "%s_act_sign", set_name[k]);
    CK(aq_h5w_attr_int(w, g, nm, p ? p->act_sign : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_q_sign", set_name[k]);
    CK(aq_h5w_attr_int(w, g, nm, p ? p->q_sign : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_admissible", set_name[k]);
    CK(aq_h5w_attr_int(w, g, nm, p && p->admissible ? 1 : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_lambda0", set_name[k]);
    CK(aq_h5w_attr_double(w, g, nm, p ? p->lambda0 : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_q_c_rad", set_name[k]);
    CK(aq_h5w_attr_double(w, g, nm, p ? p->s_c_rad : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_mass_kg", set_name[k]);
    CK(aq_h5w_attr_double(w, g, nm, p ? p->mass_kg : NAN), "arch attributes");
    if (a->arch && p) { /* its collapse state's friction, and the load with the arch's */
      size_t mj;
      double mu = aq_arch_joint_friction(a->arch, k, NULL, &mj);
      snprintf(nm, sizeof nm, "%s_mu_required", set_name[k]);
      CK(aq_h5w_attr_double(w, g, nm, mu), "arch attributes");
      snprintf(nm, sizeof nm, "%s_mu_joint", set_name[k]);
      CK(aq_h5w_attr_int(w, g, nm, mj == SIZE_MAX ? -1 : (int64_t)mj), "arch attributes");
      snprintf(nm, sizeof nm, "%s_lambda_friction", set_name[k]);
      double lf = aq_arch_lambda_friction(a->arch, p->act_sign, aq_arch_friction(a->arch));
      CK(aq_h5w_attr_double(w, g, nm, lf),
         "arch attributes");
    }
  }
  CK(H5Gclose(g), "H5Gclose");
  g = -1;
  if (a->arch)
    return write_geometry(w, index, a, err);
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

aq_status aq_h5_write_arch_of(aq_h5_writer *w, size_t index, const aq_arch *A,
                              const char *source_file, const aq_arch_dynamics *used,
                              aq_error *err)
{
  char sha[65], joints[2][64], faces[2][8];
  aq_arch_sources src;
  aq_arch_sha256(A, sha); /* the .cfg's bytes as read, and a joints arch's files' */
  aq_arch_sources_of(A, &src);
  for (int k = 0; k < 2; k++)
    aq_hinge_set_format(aq_arch_hinge_set(A, k), joints[k], sizeof joints[k], faces[k],
                        sizeof faces[k]);
  aq_h5_arch ha = {.name = aq_arch_name(A),
                   .source_file = source_file,
                   .config_text = aq_arch_config_text(A),
                   .dyn = used ? used : aq_arch_dynamics_of(A),
                   .set = {aq_arch_path(A, 0), aq_arch_path(A, 1)},
                   .sha256 = sha,
                   .searched = aq_arch_searched(A),
                   .joints = {joints[0], joints[1]},
                   .faces = {faces[0], faces[1]},
                   .arch = A,
                   .data_text = {src.data[0], src.data[1]}};
  return aq_h5_write_arch(w, index, &ha, err);
}
