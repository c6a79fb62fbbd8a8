/* input.c: a capacity subject read and processed once (capacity.h): a plain
 * record, or a ground motion whose components are read, checked (azimuths
 * orthogonal, dt and start shared), cut to their common samples, processed
 * each once, and projected at every arch azimuth asked (src/signal/project.h;
 * docs/dynamics.md, "Orientation and vertical acceleration"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../signal/project.h"
#include "capacity.h"

size_t aq_capacity_input_n(const aq_capacity_input *in)
{
  return in->have_proc[0] ? in->proc[0].n : 0;
}

void aq_capacity_input_free(aq_capacity_input *in)
{
  for (int j = 0; j < 3; j++) {
    if (in->have_rec[j])
      aq_record_free(&in->rec[j]);
    if (in->have_proc[j])
      aq_processed_free(&in->proc[j]);
  }
  free(in->acc);
  free(in->neg);
  free(in->im);
  memset(in, 0, sizeof *in);
}

static aq_status oom(aq_error *err)
{
  return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "capacity", "out of memory");
}

/* Read the components: azimuths, orthogonality, alignment, common samples. */
static aq_status read_all(aq_capacity_input *in, const char *const path[3], int nc,
                          const double phi_given[2], const aq_read_opts *ro,
                          aq_error *err)
{
  for (int j = 0; j < nc; j++) {
    aq_status s = aq_record_read(path[j], ro, &in->rec[j], err);
    if (s != AQ_OK)
      return s;
    in->have_rec[j] = 1;
    if (in->motion && j < 2 &&
        (s = aq_record_check_horizontal(&in->rec[j], ro, err)) != AQ_OK)
      return s;
  }
  if (!in->motion)
    return AQ_OK;
  const aq_record *all[3] = {&in->rec[0], &in->rec[1], &in->rec[2]};
  for (int j = 0; j < 2; j++)
    in->phi_deg[j] = isfinite(phi_given[j]) ? phi_given[j] : aq_project_azimuth_of(all[j]);
  aq_status s = aq_project_check_pair(path[0], in->phi_deg, err);
  if (s == AQ_OK)
    s = aq_project_check_aligned(all, (size_t)nc, err);
  if (s != AQ_OK)
    return s;
  size_t npts = aq_project_common_npts(all, (size_t)nc);
  for (int j = 0; j < nc; j++)
    in->rec[j].npts = npts;
  return AQ_OK;
}

aq_status aq_capacity_input_prepare(aq_capacity_input *in, const char *const path[3],
                                    int vertical, const double phi_given[2],
                                    const aq_read_opts *ro, const aq_signal_opts *po,
                                    aq_signal_ws *ws, const double *azimuths_deg,
                                    size_t naz, int want_neg, aq_error *err)
{
  memset(in, 0, sizeof *in);
  in->motion = path[1] != NULL;
  in->run_v = in->motion && path[2] && vertical;
  in->naz = in->motion ? naz : 1;
  int nc = in->motion ? 2 + in->run_v : 1;
  in->stage = "read";
  aq_status s = read_all(in, path, nc, phi_given, ro, err);
  if (s != AQ_OK)
    return s;
  in->stage = "process";
  aq_signal_opts o = *po;
  o.scale = 1.0;
  for (int j = 0; j < nc; j++) {
    if ((s = aq_signal_process(&in->rec[j], &o, ws, &in->proc[j], err)) != AQ_OK)
      return s;
    in->have_proc[j] = 1;
    if (in->proc[j].n != in->proc[0].n)
      return aq_error_set(err, AQ_EINTERNAL, path[j], -1, -1, NULL,
                          "processed to %zu samples, expected %zu as %s", in->proc[j].n,
                          in->proc[0].n, path[0]);
  }
  size_t n = in->proc[0].n, m = n ? n : 1;
  in->acc = malloc(in->naz * m * sizeof *in->acc);
  in->neg = want_neg ? malloc(in->naz * m * sizeof *in->neg) : NULL;
  in->im = calloc(in->naz, sizeof *in->im);
  if (!in->acc || (want_neg && !in->neg) || !in->im)
    return oom(err);
  for (size_t z = 0; z < in->naz; z++) {
    double *a = in->acc + z * m, c[2] = {1.0, 0.0};
    if (in->motion)
      aq_project_coefs(azimuths_deg[z], in->phi_deg, c);
    for (size_t i = 0; i < n; i++) /* a_x = a1 cos(theta - phi1) + a2 cos(theta - phi2) */
      a[i] = in->motion ? c[0] * in->proc[0].acc_mps2[i] + c[1] * in->proc[1].acc_mps2[i]
                        : in->proc[0].acc_mps2[i];
    for (size_t i = 0; want_neg && i < n; i++)
      in->neg[z * m + i] = -a[i];
    aq_processed view = in->proc[0];
    view.acc_mps2 = a;
    if ((s = aq_im_compute(&view, &in->im[z], err)) != AQ_OK)
      return s;
  }
  return AQ_OK;
}
