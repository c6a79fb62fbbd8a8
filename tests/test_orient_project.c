/* test_orient_project.c: the in-plane projection of two horizontal
 * components (src/signal/project.c, aq_steps_project) and the choice of the
 * worst azimuth (aq_summary_worst). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "report/report.h"
#include "signal/project.h"
#include "signal/steps.h"

#define PI_TEST 3.14159265358979323846

/* cos(theta - phi) against the plain libm formula, and the half turn exact. */
AQ_TEST(orient_cos_deg_against_libm_and_half_turn)
{
  double worst = 0;
  int exact = 1;
  for (double th = -725.5; th <= 725.5; th += 2.385) {
    double got = aq_project_cos_deg(th), want = cos(th * PI_TEST / 180.0);
    worst = fmax(worst, fabs(got - want));
  }
  for (double th = -725.25; th <= 725.25; th += 0.25) /* th + 180 exact */
    exact &= aq_project_cos_deg(th + 180.0) == -aq_project_cos_deg(th);
  aq_check(worst <= 1e-13, "|cos_deg - cos| <= 1e-13 over -725..725 deg: %.3g", worst);
  aq_check(exact, "cos(d + 180) = -cos(d) bit for bit");
  double c[2], phi[2] = {180, 270};
  aq_project_coefs(30, phi, c); /* ELC180/ELC270 at 30 deg: -cos 30, cos 120 */
  aq_check_abs(c[0], -sqrt(3.0) / 2, 1e-15, "c1 = cos(30 - 180) = %.17g", c[0]);
  aq_check_abs(c[1], -0.5, 1e-15, "c2 = cos(30 - 270) = %.17g", c[1]);
}

AQ_TEST(orient_pair_checks)
{
  aq_error e;
  double ok[2] = {67, 337}, skew[2] = {0, 88.5}, near[2] = {10, 100.9}, none[2] = {0, NAN};
  aq_check(aq_project_check_pair("GIL", ok, &e) == AQ_OK, "67/337 orthogonal");
  aq_check(aq_project_check_pair("x", near, &e) == AQ_OK, "90.9 deg apart: within 1 deg");
  aq_check(aq_project_check_pair("x", skew, &e) == AQ_EVALUE &&
               strstr(e.message, "orthogonal") && strstr(e.message, "88.5"),
           "88.5 deg apart refused: %s", e.message);
  aq_check(aq_project_check_pair("x", none, &e) == AQ_EVALUE && strstr(e.message, "--azimuths"),
           "no azimuth: %s", e.message);
  static const struct { const char *name; double az; } names[] = {
      {"RSN6_IMPVALL.I_I-ELC180-hor1.AT2", 180}, {"RSN6_IMPVALL.I_I-ELC270-hor2.AT2", 270},
      {"RSN763_LOMAP_GIL067.AT2", 67},         {"RSN763_LOMAP_GIL337.AT2", 337},
      {"RSN77_SFERN_PUL164-hor1.AT2", 164},    {"kocaeli.csv", NAN},
      {"RSN4013_SANSIMEO_36258021.AT2", NAN},  {"ABC999.AT2", NAN},
      {"run090.csv", NAN}};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    aq_record r;
    memset(&r, 0, sizeof r);
    r.name = (char *)names[i].name;
    r.azimuth_deg = NAN;
    snprintf(r.format, sizeof r.format, "%s", strstr(names[i].name, ".csv") ? "csv" : "at2");
    double az = aq_project_azimuth_of(&r);
    aq_check((isnan(az) && isnan(names[i].az)) || az == names[i].az, "%s: %g deg",
             names[i].name, az);
  }
  aq_record hdr;
  memset(&hdr, 0, sizeof hdr);
  hdr.name = "RSN6_IMPVALL.I_I-ELC180-hor1.AT2";
  snprintf(hdr.format, sizeof hdr.format, "at2");
  hdr.azimuth_deg = 90; /* the header wins over the name */
  aq_check(aq_project_azimuth_of(&hdr) == 90, "header azimuth first");
  aq_record a, b;
  memset(&a, 0, sizeof a);
  memset(&b, 0, sizeof b);
  a.path = "a";
  b.path = "b";
  a.dt_s = 0.01;
  b.dt_s = 0.02;
  const aq_record *ab[2] = {&a, &b};
  aq_check(aq_project_check_aligned(ab, 2, &e) == AQ_EVALUE && strcmp(e.field, "dt") == 0,
           "dt 0.01 and 0.02 refused: %s", e.message);
  b.dt_s = 0.01;
  b.begin_s = 0.5;
  aq_check(aq_project_check_aligned(ab, 2, &e) == AQ_EVALUE &&
               strcmp(e.field, "start time") == 0,
           "start 0 and 0.5 s refused: %s", e.message);
  b.begin_s = 0;
  aq_check(aq_project_check_aligned(ab, 2, &e) == AQ_OK, "aligned");
}

/* The projected steps equal the steps of the samples projected here, bit
 * for bit, with and without merging; the peak is that of the samples. */
AQ_TEST(orient_steps_project_equals_projected_samples)
{
  enum { N = 2000 };
  static double a1[N], a2[N], ax[N];
  double c1 = cos(37.0 * PI_TEST / 180), c2 = cos(-53.0 * PI_TEST / 180), sc = -1.7;
  double peak = 0;
  for (size_t i = 0; i < N; i++) {
    a1[i] = 2.385 * sin(0.013 * (double)i) * exp(-0.001 * (double)i);
    a2[i] = 1.17 * cos(0.029 * (double)i + 0.3);
    ax[i] = sc * (c1 * a1[i] + c2 * a2[i]);
    peak = fmax(peak, fabs(ax[i]));
  }
  for (int m = 0; m < 2; m++) {
    double tol = m ? 0.05 : 0;
    aq_steps s, t;
    aq_error e;
    double pk = -1;
    int ok = aq_steps_project(a1, c1, a2, c2, sc, N, 0.005, -0.25, tol, &s, &pk, &e) == AQ_OK &&
             aq_steps_from_samples(ax, N, 0.005, -0.25, tol, &t, &e) == AQ_OK;
    aq_check(ok && s.n == t.n, "tol %g: %zu and %zu steps", tol, s.n, t.n);
    int same = ok && s.n == t.n;
    for (size_t i = 0; same && i < s.n; i++)
      same = s.a_mps2[i] == t.a_mps2[i] && aq_steps_t(&s, i) == aq_steps_t(&t, i) &&
             aq_steps_dt(&s, i) == aq_steps_dt(&t, i);
    aq_check(same, "tol %g: the same steps bit for bit", tol);
    aq_check(pk == peak, "peak %.17g = %.17g", pk, peak);
    if (ok) {
      aq_steps_free(&s);
      aq_steps_free(&t);
    }
  }
}

static aq_summary row(const char *status, int collapsed, double t_s, double ratio)
{
  aq_summary s;
  aq_summary_fill(&s, "m", "a", "workpath", 1, 0.1, status, NULL);
  s.collapsed = collapsed;
  s.collapse_time_s = t_s;
  s.peak_rotation_over_qc = ratio;
  return s;
}

AQ_TEST(orient_worst_azimuth_rule)
{
  aq_summary r[5];
  const aq_summary *p[5];
  for (size_t i = 0; i < 5; i++)
    p[i] = &r[i];
  r[0] = row("ok", 0, NAN, 0.3);
  r[1] = row("ok", 0, NAN, 0.7);
  r[2] = row("ok", 0, NAN, 0.5);
  aq_check(aq_summary_worst(p, 3) == 1, "no collapse: the largest ratio");
  r[3] = row("ok", 1, 4.5, 1);
  r[4] = row("ok", 1, 2.25, 1);
  aq_check(aq_summary_worst(p, 5) == 4, "collapse first, the earliest");
  r[2] = row("run:enumeric", AQ_SUMMARY_INT_NONE, NAN, NAN);
  aq_check(aq_summary_worst(p, 5) == 2, "a failed run: no verdict for the motion");
  r[1] = r[0];
  r[2] = r[0];
  r[3] = r[0];
  r[4] = r[0];
  aq_check(aq_summary_worst(p, 5) == 0, "ties: the first");
}
