/* paper.c: the work-path method as printed (see paper.h), so that its error
 * can be measured against the exact models.  Never the default.
 *
 *   G. L. Stockdale, V. Sarhosis, G. Milani, "Work-path approach seismic
 *   modelling of hinge-controlled masonry arches", sections 2.4-3.
 *
 * What is reproduced as printed: sampling of alpha1 at 0.1 deg from 0 to the
 * collapse; polynomial fits y(x) (quadratic, eq. 10), lever-arm angles
 * theta_i(x) (quadratic, eq. 12), W_min(x) (quartic, eq. 16) of the work of
 * eq. (14) including the torque terms; kinetic energy of eq. (19); the
 * "mass" of eq. (23) with (1 + dy/dx)^2 and fixed lever arms, without the
 * elements' own rotational inertia; time by eq. (24) as a trapezoid sum
 * over the sampled x, using only points with KE > 0; and the position at
 * the end of a step from a quartic fit x(t) of those samples (eq. 25).
 * At a turning point ("pivot point") the motion reverses where the quartic
 * fit x(t) of eq. (25) over the sampled points with KE > 0 stops (section
 * 4.2: positive KE "reduces the number of available data points for curve
 * fitting in the vicinity of the motion switch"); with fewer than three
 * points, where the sampled KE (linear between the last sample with KE > 0
 * and the first without) vanishes; else at the last such point.  The KE that
 * eq. (19) gives there is dropped (section 3: "motion must be forward
 * facing").  This is where the printed method loses energy.
 *
 * Deliberate deviations, each minimal: the slopes are 2 A1 x + A2 (docs/method.md
 * sec. 2, a typesetting error); the lever arms are measured from the moving
 * bodies' centroid (the contract gives no absolute centroid for the fixed
 * voussoirs); the first trapezoid of a leg that starts from KE = 0 uses the
 * integrand at its right end only (the printed method gives no rule).
 */
#include "paper.h"

#include <gsl/gsl_multifit.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PAPER_DALPHA_RAD = 0.1 * 3.14159265358979323846 / 180.0;
enum { PAPER_MAX_SAMPLES = 20000 };

typedef struct {
  int ok;
  const aq_path *p;
  size_t n;      /* samples */
  double *s;     /* alpha1 samples, rad */
  double *u;     /* -act_sign x: centroid displacement along the motion, m */
  double A[3];   /* y(u) = A0 u^2 + A1 u + A2 */
  double C[5];   /* W_min(u) = C0 u^4 + ... + C4 */
  size_t nb;
  double mb[AQ_PATH_MAX_BODIES], lb[AQ_PATH_MAX_BODIES];
  double B[AQ_PATH_MAX_BODIES][3]; /* theta_i(u) quadratics */
} paper_set;

struct aq_paper {
  paper_set set[2];
  double *tt, *uu; /* scratch for a leg: times and positions */
};

/* Least-squares polynomial of degree deg (coefficients highest first). */
static int polyfit(const double *x, const double *y, size_t n, int deg,
                   double *c)
{
  size_t m = (size_t)deg + 1;
  if (n < m)
    return -1;
  gsl_matrix *X = gsl_matrix_alloc(n, m);
  gsl_vector *Y = gsl_vector_alloc(n), *cv = gsl_vector_alloc(m);
  gsl_matrix *cov = gsl_matrix_alloc(m, m);
  gsl_multifit_linear_workspace *w = gsl_multifit_linear_alloc(n, m);
  int rc = -1;
  if (X && Y && cv && cov && w) {
    for (size_t i = 0; i < n; i++) {
      double v = 1;
      for (size_t k = 0; k < m; k++) {
        gsl_matrix_set(X, i, m - 1 - k, v);
        v *= x[i];
      }
      gsl_vector_set(Y, i, y[i]);
    }
    double chisq;
    if (gsl_multifit_linear(X, Y, cv, cov, &chisq, w) == GSL_SUCCESS) {
      for (size_t k = 0; k < m; k++)
        c[k] = gsl_vector_get(cv, k);
      rc = 0;
    }
  }
  gsl_matrix_free(X);
  gsl_vector_free(Y);
  gsl_vector_free(cv);
  gsl_matrix_free(cov);
  if (w)
    gsl_multifit_linear_free(w);
  return rc;
}

static double polyval(const double *c, int deg, double x)
{
  double v = 0;
  for (int k = 0; k <= deg; k++)
    v = v * x + c[k];
  return v;
}

static double polyder(const double *c, int deg, double x)
{
  double v = 0;
  for (int k = 0; k < deg; k++)
    v = v * x + c[k] * (deg - k);
  return v;
}

static void set_free(paper_set *ps)
{
  free(ps->s);
  free(ps->u);
  memset(ps, 0, sizeof *ps);
}

static aq_status set_build(paper_set *ps, const aq_path *p, aq_error *err)
{
  memset(ps, 0, sizeof *ps);
  ps->p = p;
  size_t n = (size_t)floor(p->s_c_rad / PAPER_DALPHA_RAD) + 1;
  if (n * PAPER_DALPHA_RAD < p->s_c_rad * (1 - 1e-12))
    n++; /* the collapse point itself */
  if (n < 6 || n > PAPER_MAX_SAMPLES)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, p->name,
                        "paper model: expected 6..%d samples at 0.1 deg up "
                        "to q_c, got %zu",
                        PAPER_MAX_SAMPLES, n);
  ps->n = n;
  ps->s = malloc(n * sizeof *ps->s);
  ps->u = malloc(n * sizeof *ps->u);
  double *y = malloc(n * sizeof *y), *w = malloc(n * sizeof *w),
         *th = malloc(n * AQ_PATH_MAX_BODIES * sizeof *th),
         *lam = malloc(n * sizeof *lam);
  double *ry = malloc(n * AQ_PATH_MAX_BODIES * sizeof *ry);
  aq_status rc = AQ_OK;
  if (!ps->s || !ps->u || !y || !w || !th || !lam || !ry) {
    rc = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, p->name, "out of memory");
    goto out;
  }
  double sgn = -p->act_sign, mt = p->mass_kg, g = p->g_mps2;
  for (size_t j = 0; j < n; j++) {
    double s = fmin(j * PAPER_DALPHA_RAD, p->s_c_rad);
    aq_path_point pt;
    if (p->eval_exact(p->ctx, s, &pt) != 0) {
      rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                        "paper model: path evaluation failed at %.9g rad", s);
      goto out;
    }
    ps->s[j] = s;
    ps->u[j] = sgn * pt.x_m;
    y[j] = pt.y_m;
    lam[j] = pt.lambda;
    ps->nb = pt.nbody;
    double mm = 0, cx = 0, cy = 0;
    for (size_t b = 0; b < pt.nbody; b++) {
      mm += pt.body[b].mass_kg;
      cx += pt.body[b].mass_kg * pt.body[b].x_m;
      cy += pt.body[b].mass_kg * pt.body[b].y_m;
    }
    if (mm > 0) {
      cx /= mm;
      cy /= mm;
    }
    for (size_t b = 0; b < pt.nbody; b++) {
      double rx = pt.body[b].x_m - cx, r_y = pt.body[b].y_m - cy;
      double a = atan2(r_y, rx);
      if (j > 0) { /* unwrap */
        double prev = th[(j - 1) * AQ_PATH_MAX_BODIES + b];
        while (a - prev > 3.14159265358979323846)
          a -= 2 * 3.14159265358979323846;
        while (a - prev < -3.14159265358979323846)
          a += 2 * 3.14159265358979323846;
      } else {
        ps->mb[b] = pt.body[b].mass_kg;
        ps->lb[b] = hypot(rx, r_y);
      }
      th[j * AQ_PATH_MAX_BODIES + b] = a;
      ry[j * AQ_PATH_MAX_BODIES + b] = r_y;
    }
    if (j > 0 && !(ps->u[j] > ps->u[j - 1])) {
      rc = aq_error_set(err, AQ_EVALUE, NULL, -1, -1, p->name,
                        "paper model: the centroid's x must advance along "
                        "the path (eqs. 10-16 are in x), got a reversal at "
                        "%.4g rad",
                        s);
      goto out;
    }
  }
  /* eq. (14): W = int F dx + sum int tau_i dtheta_i, trapezoids */
  w[0] = 0;
  for (size_t j = 1; j < n; j++) {
    double F0 = lam[j - 1] * g * mt, F1 = lam[j] * g * mt;
    double dw = 0.5 * (F0 + F1) * (ps->u[j] - ps->u[j - 1]);
    for (size_t b = 0; b < ps->nb; b++) {
      /* tau = -r_y F_x, F_x = sgn lambda g m_i (along the motion) */
      double t0 = -ry[(j - 1) * AQ_PATH_MAX_BODIES + b] * sgn * lam[j - 1] * g *
                  ps->mb[b];
      double t1 = -ry[j * AQ_PATH_MAX_BODIES + b] * sgn * lam[j] * g * ps->mb[b];
      dw += 0.5 * (t0 + t1) *
            (th[j * AQ_PATH_MAX_BODIES + b] - th[(j - 1) * AQ_PATH_MAX_BODIES + b]);
    }
    w[j] = w[j - 1] + dw;
  }
  if (polyfit(ps->u, y, n, 2, ps->A) || polyfit(ps->u, w, n, 4, ps->C)) {
    rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "paper model: polynomial fit failed");
    goto out;
  }
  for (size_t b = 0; b < ps->nb; b++) {
    double *tb = y; /* reuse */
    for (size_t j = 0; j < n; j++)
      tb[j] = th[j * AQ_PATH_MAX_BODIES + b];
    if (polyfit(ps->u, tb, n, 2, ps->B[b])) {
      rc = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                        "paper model: polynomial fit failed");
      goto out;
    }
  }
  ps->ok = 1;
out:
  free(y);
  free(w);
  free(th);
  free(lam);
  free(ry);
  if (rc != AQ_OK)
    set_free(ps);
  return rc;
}

aq_paper *aq_paper_alloc(const aq_path *primary, const aq_path *reverse,
                         aq_error *err)
{
  aq_paper *w = calloc(1, sizeof *w);
  if (!w) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "paper", "out of memory");
    return NULL;
  }
  if (set_build(&w->set[0], primary, err) != AQ_OK ||
      (reverse && reverse->admissible &&
       set_build(&w->set[1], reverse, err) != AQ_OK)) {
    aq_paper_free(w);
    return NULL;
  }
  size_t nmax = w->set[0].n > w->set[1].n ? w->set[0].n : w->set[1].n;
  w->tt = malloc((nmax + 2) * sizeof *w->tt);
  w->uu = malloc((nmax + 2) * sizeof *w->uu);
  if (!w->tt || !w->uu) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "paper", "out of memory");
    aq_paper_free(w);
    return NULL;
  }
  return w;
}

void aq_paper_free(aq_paper *w)
{
  if (!w)
    return;
  set_free(&w->set[0]);
  set_free(&w->set[1]);
  free(w->tt);
  free(w->uu);
  free(w);
}

/* u <-> s by linear interpolation on the samples (exact inverses). */
static double u_of_s(const paper_set *ps, double s)
{
  if (s <= 0)
    return ps->u[0];
  size_t n = ps->n;
  if (s >= ps->s[n - 1])
    return ps->u[n - 1];
  size_t j = (size_t)(s / PAPER_DALPHA_RAD);
  if (j >= n - 1)
    j = n - 2;
  while (j > 0 && ps->s[j] > s)
    j--;
  while (j + 2 < n && ps->s[j + 1] < s)
    j++;
  double f = (s - ps->s[j]) / (ps->s[j + 1] - ps->s[j]);
  return ps->u[j] + f * (ps->u[j + 1] - ps->u[j]);
}

static double s_of_u(const paper_set *ps, double u)
{
  size_t n = ps->n, lo = 0, hi = n - 1;
  if (u <= ps->u[0])
    return 0;
  if (u >= ps->u[n - 1])
    return ps->s[n - 1];
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (ps->u[mid] <= u)
      lo = mid;
    else
      hi = mid;
  }
  double f = (u - ps->u[lo]) / (ps->u[hi] - ps->u[lo]);
  return ps->s[lo] + f * (ps->s[hi] - ps->s[lo]);
}

double aq_paper_wmin(const aq_paper *w, int set, double s)
{
  const paper_set *ps = &w->set[set ? 1 : 0];
  if (!ps->ok)
    return NAN;
  return polyval(ps->C, 4, u_of_s(ps, s)) - polyval(ps->C, 4, 0);
}

/* eq. (23): the printed "mass" along u. */
static double paper_mass(const paper_set *ps, double u)
{
  double dy = polyder(ps->A, 2, u);
  double m = ps->p->mass_kg * (1 + dy) * (1 + dy);
  for (size_t b = 0; b < ps->nb; b++) {
    double dth = polyder(ps->B[b], 2, u);
    m += ps->mb[b] * ps->lb[b] * ps->lb[b] * dth * dth;
  }
  return m;
}

/* eq. (19) */
static double paper_ke(const paper_set *ps, double a, double u1, double ke1,
                       double u)
{
  double fapp = a * ps->p->act_sign * ps->p->mass_kg;
  return ke1 + fapp * (u - u1) - polyval(ps->C, 4, u) + polyval(ps->C, 4, u1);
}

static void fill_motion(const paper_set *ps, double u, double ke, aq_motion *m,
                        aq_leg_stats *S)
{
  aq_path_point pt;
  m->s = s_of_u(ps, u);
  m->ke_j = ke > 0 ? ke : 0;
  if (ps->p->eval_exact(ps->p->ctx, m->s, &pt) == 0) {
    m->x_m = pt.x_m;
    m->y_m = pt.y_m;
  }
  S->evals++;
  if (m->s > S->peak_s)
    S->peak_s = m->s;
  if (m->ke_j > S->peak_ke_j)
    S->peak_ke_j = m->ke_j;
}

aq_status aq_paper_leg(aq_paper *w, int set, double a, aq_motion *m,
                       double dt_s, double *used_s, aq_leg_end *end,
                       aq_leg_stats *S, aq_error *err)
{
  const paper_set *ps = &w->set[set ? 1 : 0];
  if (!ps->ok)
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "paper",
                        "set %d has no fits", set);
  double t = 0;
  for (int guard = 0; guard < 1000000; guard++) {
    double rem = dt_s - t;
    if (rem <= 0) {
      *used_s = dt_s;
      *end = AQ_LEG_TIME;
      return AQ_OK;
    }
    double u1 = u_of_s(ps, m->s), ke1 = m->ke_j;
    if (ke1 <= 0) { /* choose the direction in which KE grows */
      double h = 1e-3 * (ps->u[1] - ps->u[0]);
      int up = paper_ke(ps, a, u1, 0, fmin(u1 + h, ps->u[ps->n - 1])) > 0;
      int dn = u1 > ps->u[0] && paper_ke(ps, a, u1, 0, u1 - h) > 0;
      if (!up && !dn) {
        if (m->s <= 0) {
          *used_s = t;
          *end = AQ_LEG_REST;
          return AQ_OK;
        }
        *used_s = dt_s; /* held in place */
        *end = AQ_LEG_TIME;
        return AQ_OK;
      }
      int nd = up ? 1 : -1;
      if (nd != m->dir && m->s > 0)
        S->reversals++;
      m->dir = nd;
    }
    int d = m->dir;
    /* the sampled x ahead, with KE > 0 (eqs. 24-25, trapezoids) */
    size_t k = 0;
    w->tt[0] = 0;
    w->uu[0] = u1;
    double hprev = ke1 > 0 ? sqrt(paper_mass(ps, u1) / (2 * ke1)) : INFINITY;
    int hit_end = 0, have_b = 0;
    double ub = 0, keb = 0;
    size_t j;
    if (d > 0) {
      for (j = 0; j < ps->n && ps->u[j] <= u1; j++)
        ;
    } else {
      for (j = ps->n; j > 0 && ps->u[j - 1] >= u1; j--)
        ;
    }
    for (;;) {
      double un;
      if (d > 0) {
        if (j >= ps->n) {
          hit_end = 1;
          break;
        }
        un = ps->u[j++];
      } else {
        if (j == 0) {
          hit_end = 1;
          break;
        }
        un = ps->u[--j];
      }
      double ke = paper_ke(ps, a, u1, ke1, un);
      if (!(ke > 0)) { /* the turning point lies before un */
        have_b = 1;
        ub = un;
        keb = ke;
        break;
      }
      double hn = sqrt(paper_mass(ps, un) / (2 * ke));
      double du = fabs(un - w->uu[k]);
      double dtk = isfinite(hprev) ? 0.5 * (hprev + hn) * du : hn * du;
      k++;
      w->tt[k] = w->tt[k - 1] + dtk;
      w->uu[k] = un;
      hprev = hn;
      if (w->tt[k] >= rem)
        break;
    }
    if (k > 0 && w->tt[k] >= rem) {
      /* eq. (25): quartic (or lower, with few points) fit u(t) */
      int deg = k >= 4 ? 4 : (int)k;
      double c[5];
      double un;
      if (deg >= 2 && polyfit(w->tt, w->uu, k + 1, deg, c) == 0)
        un = polyval(c, deg, rem);
      else /* two points: linear */
        un = w->uu[k - 1] + (w->uu[k] - w->uu[k - 1]) * (rem - w->tt[k - 1]) /
                                 (w->tt[k] - w->tt[k - 1]);
      double ulo = fmin(w->uu[0], w->uu[k]), uhi = fmax(w->uu[0], w->uu[k]);
      un = fmin(fmax(un, ulo), uhi);
      fill_motion(ps, un, paper_ke(ps, a, u1, ke1, un), m, S);
      *used_s = dt_s;
      *end = AQ_LEG_TIME;
      return AQ_OK;
    }
    /* the whole sampled stretch takes less than the step */
    double ulast = w->uu[k], tlast = w->tt[k];
    if (!hit_end && have_b && k < 2) {
      /* too few points for a fit: the switch where the sampled KE,
       * linear between the last sample with KE > 0 and the first
       * without, vanishes; time to it with the last sampled integrand */
      double ka = paper_ke(ps, a, u1, ke1, ulast);
      if (ka > 0 && ka - keb > 0 && isfinite(hprev)) {
        double ut = ulast + (ub - ulast) * ka / (ka - keb);
        double t0 = tlast;
        tlast += hprev * fabs(ut - ulast);
        if (tlast > rem) { /* the step ends before the switch */
          double un = ulast + (ut - ulast) * (rem - t0) / (tlast - t0);
          fill_motion(ps, un, paper_ke(ps, a, u1, ke1, un), m, S);
          *used_s = dt_s;
          *end = AQ_LEG_TIME;
          return AQ_OK;
        }
        ulast = ut;
      }
    }
    if (!hit_end && have_b && k >= 2) {
      /* the pivot from the curve fit of eq. (25) over the points with
       * KE > 0: where the fitted x(t) stops, between the last sample with
       * KE > 0 and the first without */
      int deg = k >= 4 ? 4 : (int)k;
      double c[5];
      if (polyfit(w->tt, w->uu, k + 1, deg, c) == 0) {
        double ta = w->tt[k], tb = ta + 4 * (w->tt[k] - w->tt[k - 1]);
        if (d * polyder(c, deg, ta) > 0 && d * polyder(c, deg, tb) <= 0) {
          for (int it = 0; it < 60; it++) {
            double tm = 0.5 * (ta + tb);
            if (d * polyder(c, deg, tm) > 0)
              ta = tm;
            else
              tb = tm;
          }
          double ut = polyval(c, deg, ta);
          if (d * (ut - ulast) > 0 && d * (ub - ut) > 0) {
            if (ta > rem) { /* the step ends before the switch */
              double un = polyval(c, deg, rem);
              un = d > 0 ? fmin(fmax(un, ulast), ut) : fmax(fmin(un, ulast), ut);
              fill_motion(ps, un, paper_ke(ps, a, u1, ke1, un), m, S);
              *used_s = dt_s;
              *end = AQ_LEG_TIME;
              return AQ_OK;
            }
            ulast = ut;
            tlast = ta;
          }
        }
      }
    }
    t += tlast;
    if (hit_end && d > 0) {
      fill_motion(ps, ps->u[ps->n - 1], paper_ke(ps, a, u1, ke1, ulast), m, S);
      m->s = ps->p->s_c_rad;
      *used_s = t;
      *end = AQ_LEG_COLLAPSE;
      return AQ_OK;
    }
    if (hit_end && d < 0) {
      fill_motion(ps, ps->u[0], paper_ke(ps, a, u1, ke1, ulast), m, S);
      m->s = 0;
      *used_s = t;
      *end = AQ_LEG_IMPACT;
      return AQ_OK;
    }
    /* turning point: the motion reverses at the last sample with KE > 0,
     * whose kinetic energy is dropped (section 3) */
    fill_motion(ps, ulast, 0, m, S);
    m->ke_j = 0;
    m->dir = -d;
    S->reversals++;
    if (k == 0 && ke1 <= 0) { /* no motion possible either way */
      *used_s = dt_s;
      *end = AQ_LEG_TIME;
      return AQ_OK;
    }
  }
  return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "paper",
                      "no progress within one step");
}
