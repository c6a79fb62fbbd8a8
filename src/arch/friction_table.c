/* friction_table.c: the arch's statics with friction (aq_statics, model.h).
 * Built once with the arch: the least friction at rest, the largest load
 * of each direction without and with the arch's friction, and for each
 * direction a table of the least friction over the load from 0 to the
 * largest: its exact value and slope (aq_friction_least_from, friction.c)
 * at the nodes, a cubic Hermite between them.  The least friction is smooth where one joint
 * governs and has a kink where the joint that governs changes (catenary:
 * from a springing to the crown at 0.68 of the largest load), so the table
 * starts with STATICS_START equal intervals and halves every interval at
 * whose middle the cubic is off the exact value by more than STATICS_TOL
 * times the table's largest value, until none is or the table holds
 * STATICS_MAX nodes: near a
 * kink the halving goes on until the interval is so narrow that the slope
 * that changes inside it no longer matters.
 *
 * Where the line of thrust of the largest load is a lift-off mechanism's
 * (a joint whose resultant's normal force falls to 0 at that load), the
 * least friction grows without bound towards the top, as c / (lambda_top -
 * lambda) (the flat parabola of docs/arch-model.md: c = 0.54, 6.2 at 0.99
 * of the top, 6.5e4 at 1 - 1e-6), and at the top itself no friction
 * holds.  Such a table ends at lambda_end, the load (bisection on the
 * least friction) where the least friction reaches STATICS_MU_CAP, the largest friction
 * an arch may be given: beyond it no line of thrust stands with any
 * friction an arch may have, and aq_statics_mu_least gives INFINITY there,
 * never a value extrapolated towards the pole.  The cubic of such a
 * table is held to STATICS_TOL of the exact value at each middle (relative
 * to that value, not to the table's largest, which is the cap). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cfg_keys.h"
#include "friction.h"
#include "model.h"

#define STATICS_MU_CAP AQ_CFG_FRICTION_MAX /* the least friction where a table ends below
                                              its top (cfg_keys.h: 1e3, the largest friction
                                              --friction and [contact] friction accept) */
#define STATICS_NU_FROM 1.0   /* a capped table's intervals whose nodes need at least this
                                  are interpolated in 1/mu */
#define STATICS_END_REL 1e-10  /* lambda_end's bisection stops this close (relative) */
#define STATICS_START 8        /* intervals of the first table, per direction */
#define STATICS_MAX 256        /* nodes at most, per direction */
#define STATICS_TOL 1e-6       /* the cubic against the exact value at the middle of each
                                  interval, relative to the table's largest value */
#define STATICS_TOP_REL 1e-12  /* the table's last load: the largest, less this (relative),
                                  where the line of thrust is unique and round-off may
                                  leave the program none */

struct aq_statics {
  double friction;             /* the arch's, 0: none */
  double mu_rest;              /* the least friction at rest (lambda 0) */
  size_t mu_rest_joint;
  double lambda_top[2];        /* act_sign -1, +1: the largest lambda without friction */
  double lambda_fr[2];         /* ... with the arch's friction (NAN: none) */
  size_t joint_fr[2];          /* where it slides (SIZE_MAX: nowhere) */
  double lam[2][STATICS_MAX], mu[2][STATICS_MAX], dmu[2][STATICS_MAX];
  size_t joint[2][STATICS_MAX];
  int ntab[2];                 /* nodes in the table (0: none) */
  int resolved[2];             /* 1: every interval within STATICS_TOL at its middle */
};

void aq_statics_free(aq_statics *s) { free(s); }

/* The cubic Hermite of table k on its interval i at lambda: of the least
 * friction mu, or, on an interval of a capped table whose nodes both need
 * at least STATICS_NU_FROM, of its inverse 1/mu (which falls linearly to
 * 0 at a pole c / (lambda_top - lambda), where a cubic in mu needs many
 * nodes), the value given as mu. */
static int capped(const aq_statics *s, int k);
static double hermite(const aq_statics *s, int k, int i, double lambda)
{
  double h = s->lam[k][i + 1] - s->lam[k][i], t = (lambda - s->lam[k][i]) / h;
  double t2 = t * t, t3 = t2 * t;
  double y0 = s->mu[k][i], y1 = s->mu[k][i + 1], d0 = s->dmu[k][i], d1 = s->dmu[k][i + 1];
  int inv = y0 >= STATICS_NU_FROM && y1 >= STATICS_NU_FROM && capped(s, k);
  if (inv) { /* d(1/mu)/dlambda = -mu' / mu^2 */
    d0 = -d0 / (y0 * y0), d1 = -d1 / (y1 * y1);
    y0 = 1 / y0, y1 = 1 / y1;
  }
  double y = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0 + (-2 * t3 + 3 * t2) * y1 +
             (t3 - t2) * h * d1;
  return inv ? (y > 0 ? 1 / y : INFINITY) : y;
}

/* The interval of table k that holds lambda (lam[0] <= lambda <= lam[n-1]). */
static int interval(const aq_statics *s, int k, double lambda)
{
  int lo = 0, hi = s->ntab[k] - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (s->lam[k][mid] <= lambda)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/* Node i of table k at lambda (x: its line, for the next node's start). */
static aq_status node_at(aq_statics *s, const aq_geom *g, int k, int i, double lambda,
                         const double *x0, double mu0, double x[3], aq_error *err)
{
  int iters;
  s->lam[k][i] = lambda;
  return aq_friction_least_from(g, k ? 1 : -1, lambda, mu0, x0, &s->mu[k][i], &s->joint[k][i],
                                x, &s->dmu[k][i], &iters, err);
}

/* 1 if node i of table k needs less than the cap and has a slope. */
static int below_cap(const aq_statics *s, int k, int i)
{
  return s->mu[k][i] < STATICS_MU_CAP && isfinite(s->dmu[k][i]);
}

/* 1 if table k ends below its top, where the least friction passes the cap. */
static int capped(const aq_statics *s, int k)
{
  return s->ntab[k] > 0 && !(s->mu[k][s->ntab[k] - 1] < STATICS_MU_CAP);
}

/* Nodes 0..STATICS_START-1 of table k: equal steps from 0 towards end,
 * each line the start of the next node's. */
static aq_status first_nodes(aq_statics *s, const aq_geom *g, int k, double end,
                             double x[][3], aq_error *err)
{
  aq_status st = AQ_OK;
  for (int i = 0; i < STATICS_START && st == AQ_OK; i++)
    st = node_at(s, g, k, i, end * i / STATICS_START, i ? x[i - 1] : NULL,
                 i ? s->mu[k][i - 1] : 0, x[i], err);
  return st;
}

/* Node STATICS_START of table k at lambda_end: the least load whose least
 * friction is at least the cap (with a slope), by bisection between node
 * lo's load (below the cap) and top, to STATICS_END_REL of top. */
static aq_status table_end(aq_statics *s, const aq_geom *g, int k, int lo, double top,
                           double x[][3], aq_error *err)
{
  const int e = STATICS_START;
  double a = s->lam[k][lo], b = top, mu_a = s->mu[k][lo], xa[3], xb[3];
  double end[3] = {NAN, NAN, NAN}; /* lambda, mu, slope of the best b */
  size_t joint = 0;
  memcpy(xa, x[lo], sizeof xa);
  aq_status st = AQ_OK;
  while (st == AQ_OK && b - a > STATICS_END_REL * top) {
    double mid = 0.5 * (a + b);
    st = node_at(s, g, k, e, mid, xa, mu_a, x[e], err);
    if (st != AQ_OK)
      break;
    if (below_cap(s, k, e)) {
      a = mid;
      mu_a = s->mu[k][e];
      memcpy(xa, x[e], sizeof xa);
    } else {
      b = mid;
      if (isfinite(s->mu[k][e]) && isfinite(s->dmu[k][e])) {
        end[0] = mid, end[1] = s->mu[k][e], end[2] = s->dmu[k][e];
        joint = s->joint[k][e];
        memcpy(xb, x[e], sizeof xb);
      }
    }
  }
  if (st == AQ_OK && isnan(end[0]))
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                        "expected a line of thrust that needs %g friction below the largest "
                        "load %.9g, got none", STATICS_MU_CAP, top);
  if (st == AQ_OK) {
    s->lam[k][e] = end[0];
    s->mu[k][e] = end[1];
    s->dmu[k][e] = end[2];
    s->joint[k][e] = joint;
    memcpy(x[e], xb, sizeof xb);
  }
  return st;
}

/* Table k (direction act) of s over [0, top], or over [0, lambda_end]
 * where the least friction passes the cap below the top: the nodes,
 * refined. */
static aq_status statics_table(aq_statics *s, const aq_geom *g, int k, aq_error *err)
{
  const int e = STATICS_START;
  double top = s->lambda_top[k], x[STATICS_MAX][3];
  unsigned char ok[STATICS_MAX] = {0}; /* interval i checked at its middle */
  aq_status st = first_nodes(s, g, k, top, x, err);
  double lam = top * (1 - STATICS_TOP_REL);
  for (int back = 0; back < 4 && st == AQ_OK; back++) {
    st = node_at(s, g, k, e, lam, x[e - 1], s->mu[k][e - 1], x[e], err);
    if (isfinite(s->mu[k][e]))
      break;
    lam = top * (1 - STATICS_TOP_REL * pow(10, back + 1)); /* the rows' round-off */
  }
  if (st == AQ_OK && !below_cap(s, k, e)) {
    /* the least friction passes the cap below the top: end there */
    int lo = e - 1;
    while (lo >= 0 && !below_cap(s, k, lo))
      lo--;
    if (lo < 0) { /* the cap already at rest: a table of one node */
      s->ntab[k] = 1;
      s->resolved[k] = 1;
      return AQ_OK;
    }
    st = table_end(s, g, k, lo, top, x, err);
    if (st == AQ_OK)
      st = first_nodes(s, g, k, s->lam[k][e], x, err);
  }
  int n = e + 1;
  double end = s->lam[k][e];
  /* the slope at rest from the right: at 0 a symmetric arch's two
   * springings tie, and the program's multipliers may be the other's */
  double xr[3], mur;
  size_t jr;
  int iters;
  if (st == AQ_OK)
    st = aq_friction_least_from(g, k ? 1 : -1, (end < lam ? end : top) * STATICS_TOP_REL,
                                s->mu[k][0], x[0], &mur, &jr, xr, &s->dmu[k][0], &iters, err);
  s->ntab[k] = n;
  int cap = capped(s, k);
  double scale = s->mu[k][n - 1]; /* the largest least friction: the tolerance's unit */
  for (int i = 0; i < n && st == AQ_OK; i++)
    if (!isfinite(s->mu[k][i]) || !isfinite(s->dmu[k][i]))
      st = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                        "expected a line of thrust at lambda = %.9g, below the largest "
                        "%.9g, got none", s->lam[k][i], top);
  for (int added = 1; added && st == AQ_OK && n < STATICS_MAX;) {
    added = 0;
    for (int i = 0; i + 1 < n && n < STATICS_MAX && st == AQ_OK; i++) {
      if (ok[i])
        continue;
      double lam = 0.5 * (s->lam[k][i] + s->lam[k][i + 1]), cubic = hermite(s, k, i, lam);
      /* make room for the middle as node i + 1 */
      size_t tail = (size_t)(n - i - 1);
      memmove(&s->lam[k][i + 2], &s->lam[k][i + 1], tail * sizeof(double));
      memmove(&s->mu[k][i + 2], &s->mu[k][i + 1], tail * sizeof(double));
      memmove(&s->dmu[k][i + 2], &s->dmu[k][i + 1], tail * sizeof(double));
      memmove(&s->joint[k][i + 2], &s->joint[k][i + 1], tail * sizeof(size_t));
      memmove(&x[i + 2], &x[i + 1], tail * sizeof x[0]);
      memmove(&ok[i + 2], &ok[i + 1], tail);
      st = node_at(s, g, k, i + 1, lam, x[i], s->mu[k][i], x[i + 1], err);
      double mu = s->mu[k][i + 1];
      if (st == AQ_OK && !(isfinite(mu) && isfinite(s->dmu[k][i + 1])))
        st = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "friction",
                          "expected a line of thrust at lambda = %.9g, below the largest "
                          "%.9g, got none", lam, top);
      s->ntab[k] = ++n; /* hermite() reads the table's end */
      if (st == AQ_OK && fabs(cubic - mu) <= STATICS_TOL * (cap ? fmax(fabs(mu), 1) : scale)) {
        /* within: the middle stays (it costs nothing more), both halves pass */
        ok[i] = ok[i + 1] = 1;
      } else {
        ok[i] = ok[i + 1] = 0;
        added = 1;
      }
      i++; /* the right half: checked on the next pass if it must be */
    }
  }
  s->ntab[k] = n;
  s->resolved[k] = st == AQ_OK;
  for (int i = 0; i + 1 < n; i++)
    s->resolved[k] &= ok[i];
  return st;
}

/* 1 if g is its own mirror image in x = 0 (joint j's ends mirror joint n -
 * j's, voussoir k's mass and centroid voussoir n-1-k's) to MIRROR_REL of
 * its size: then each direction's statics are the other's mirrored. */
#define MIRROR_REL 1e-12
static int mirror_symmetric(const aq_geom *g)
{
  size_t n = g->p.voussoirs;
  double size = 0;
  for (size_t j = 0; j <= n; j++)
    size = fmax(size, fmax(hypot(g->ji[j].x, g->ji[j].y), hypot(g->je[j].x, g->je[j].y)));
  double tol = MIRROR_REL * size;
  for (size_t j = 0; j <= n; j++) {
    const aq_vec2 *a[2] = {&g->ji[j], &g->je[j]}, *b[2] = {&g->ji[n - j], &g->je[n - j]};
    for (int f = 0; f < 2; f++)
      if (!(fabs(a[f]->x + b[f]->x) <= tol && fabs(a[f]->y - b[f]->y) <= tol))
        return 0;
  }
  for (size_t k = 0; k < n; k++) {
    const aq_mass *a = &g->vous[k], *b = &g->vous[n - 1 - k];
    if (!(fabs(a->mass_kg - b->mass_kg) <= MIRROR_REL * a->mass_kg &&
          fabs(a->c.x + b->c.x) <= tol && fabs(a->c.y - b->c.y) <= tol))
      return 0;
  }
  return 1;
}

/* Direction 1's statics as direction 0's mirrored (joint j -> n - j). */
static void mirror_table(aq_statics *s, size_t n)
{
  s->lambda_top[1] = s->lambda_top[0];
  s->lambda_fr[1] = s->lambda_fr[0];
  s->joint_fr[1] = s->joint_fr[0] == SIZE_MAX ? SIZE_MAX : n - s->joint_fr[0];
  s->ntab[1] = s->ntab[0];
  s->resolved[1] = s->resolved[0];
  for (int i = 0; i < s->ntab[0]; i++) {
    s->lam[1][i] = s->lam[0][i];
    s->mu[1][i] = s->mu[0][i];
    s->dmu[1][i] = s->dmu[0][i];
    s->joint[1][i] = n - s->joint[0][i];
  }
}

aq_status aq_statics_build(const aq_geom *g, double friction, int table, aq_statics **out,
                           aq_error *err)
{
  *out = NULL;
  aq_statics *s = calloc(1, sizeof *s);
  if (!s)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  s->friction = friction > 0 ? friction : 0;
  aq_status st = aq_friction_least(g, -1, 0.0, &s->mu_rest, &s->mu_rest_joint, err);
  if (st == AQ_OK && s->friction > 0 && s->friction < s->mu_rest)
    st = aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "friction",
                      "expected an arch that stands with friction %g, got one that cannot: "
                      "it needs %.3g at rest, joint %zu",
                      s->friction, s->mu_rest, s->mu_rest_joint);
  int mirror = mirror_symmetric(g);
  for (int k = 0; k < 2 && st == AQ_OK; k++) {
    int act = k ? 1 : -1;
    if (k == 1 && mirror) {
      mirror_table(s, g->p.voussoirs);
      break;
    }
    s->lambda_fr[k] = NAN;
    s->joint_fr[k] = SIZE_MAX;
    st = aq_friction_lambda(g, act, INFINITY, &s->lambda_top[k], NULL, err);
    if (st == AQ_OK && s->friction > 0)
      st = aq_friction_lambda(g, act, s->friction, &s->lambda_fr[k], &s->joint_fr[k], err);
    if (st == AQ_OK && table && s->lambda_top[k] > 0 && isfinite(s->lambda_top[k]))
      st = statics_table(s, g, k, err);
    /* else no table: no line stands under any load of that direction, or every
       load of it stands (no mechanism of that direction at all), or none asked */
  }
  if (st != AQ_OK) {
    aq_statics_free(s);
    return st;
  }
  *out = s;
  return AQ_OK;
}

void aq_statics_put(const aq_statics *s, aq_bytes_out *b)
{
  aq_bytes_put_f64(b, s->friction);
  aq_bytes_put_f64(b, s->mu_rest);
  aq_bytes_put_i64(b, (int64_t)s->mu_rest_joint);
  for (int k = 0; k < 2; k++) {
    aq_bytes_put_f64(b, s->lambda_top[k]);
    aq_bytes_put_f64(b, s->lambda_fr[k]);
    aq_bytes_put_i64(b, s->joint_fr[k] == SIZE_MAX ? -1 : (int64_t)s->joint_fr[k]);
    aq_bytes_put_i64(b, s->ntab[k]);
    aq_bytes_put_i64(b, s->resolved[k]);
    for (int i = 0; i < s->ntab[k]; i++) {
      aq_bytes_put_f64(b, s->lam[k][i]);
      aq_bytes_put_f64(b, s->mu[k][i]);
      aq_bytes_put_f64(b, s->dmu[k][i]);
      aq_bytes_put_i64(b, (int64_t)s->joint[k][i]);
    }
  }
}

aq_status aq_statics_get(aq_bytes_in *r, size_t voussoirs, aq_statics **out)
{
  *out = NULL;
  aq_statics *s = calloc(1, sizeof *s);
  if (!s)
    return AQ_ENOMEM;
  int64_t nj = (int64_t)voussoirs;
  s->friction = aq_bytes_get_f64(r, "friction");
  s->mu_rest = aq_bytes_get_f64(r, "mu_rest");
  s->mu_rest_joint = (size_t)aq_bytes_get_int(r, 0, nj, "mu_rest joint");
  for (int k = 0; k < 2; k++) {
    s->lambda_top[k] = aq_bytes_get_f64(r, "lambda_top");
    s->lambda_fr[k] = aq_bytes_get_f64(r, "lambda_friction");
    int64_t j = aq_bytes_get_int(r, -1, nj, "lambda_friction joint");
    s->joint_fr[k] = j < 0 ? SIZE_MAX : (size_t)j;
    s->ntab[k] = (int)aq_bytes_get_int(r, 0, STATICS_MAX, "nodes");
    s->resolved[k] = (int)aq_bytes_get_int(r, 0, 1, "resolved");
    for (int i = 0; i < s->ntab[k]; i++) {
      s->lam[k][i] = aq_bytes_get_f64(r, "node lambda");
      s->mu[k][i] = aq_bytes_get_f64(r, "node mu");
      s->dmu[k][i] = aq_bytes_get_f64(r, "node slope");
      s->joint[k][i] = (size_t)aq_bytes_get_int(r, 0, nj, "node joint");
    }
    for (int i = 1; i < s->ntab[k]; i++)
      if (!(s->lam[k][i] > s->lam[k][i - 1]) && !r->bad)
        r->bad = "node lambda";
  }
  if (r->bad) {
    aq_statics_free(s);
    return AQ_EFORMAT;
  }
  *out = s;
  return AQ_OK;
}

double aq_statics_mu_rest(const aq_statics *s, size_t *joint)
{
  if (joint)
    *joint = s->mu_rest_joint;
  return s->mu_rest;
}

double aq_statics_lambda_top(const aq_statics *s, int act_sign)
{
  return s->lambda_top[act_sign > 0];
}

double aq_statics_lambda_friction(const aq_statics *s, int act_sign, size_t *joint)
{
  if (joint)
    *joint = s->joint_fr[act_sign > 0];
  return s->lambda_fr[act_sign > 0];
}

double aq_statics_mu_least(const aq_statics *s, int act_sign, double lambda, size_t *joint)
{
  int k = act_sign > 0, n = s->ntab[k];
  if (joint)
    *joint = s->mu_rest_joint;
  if (!(lambda >= 0) || n < 1 || (n < 2 && !capped(s, k)))
    return lambda == 0 ? s->mu_rest : NAN;
  if (lambda > s->lam[k][n - 1]) {
    if (joint && n > 1)
      *joint = s->joint[k][n - 1];
    /* beyond a capped table's end more than the cap (the least friction
       grows with the load): as good as none */
    return lambda <= s->lambda_top[k] && !capped(s, k) ? s->mu[k][n - 1] : INFINITY;
  }
  if (n < 2)
    return s->mu[k][0];
  int i = interval(s, k, lambda);
  if (joint) /* the nearer node's */
    *joint = s->joint[k][lambda - s->lam[k][i] < s->lam[k][i + 1] - lambda ? i : i + 1];
  return hermite(s, k, i, lambda);
}

double aq_statics_lambda_at(const aq_statics *s, int act_sign, double mu)
{
  int k = act_sign > 0, n = s->ntab[k];
  if (n < 2 || !(mu > 0))
    return NAN;
  if (mu >= s->mu[k][n - 1]) /* beyond a capped table's end: not known from it */
    return capped(s, k) ? NAN : s->lambda_top[k];
  /* the loads at which some line stands with mu form an interval (the
   * program's feasible set is convex): its top is in the highest table
   * interval whose lower node needs no more than mu */
  int i = n - 2;
  while (i >= 0 && s->mu[k][i] > mu)
    i--;
  if (i < 0)
    return NAN; /* not even at rest */
  double lo = s->lam[k][i], hi = s->lam[k][i + 1];
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; it++) {
    double mid = 0.5 * (lo + hi);
    if (hermite(s, k, i, mid) <= mu)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

int aq_statics_nodes(const aq_statics *s, int act_sign) { return s->ntab[act_sign > 0]; }

int aq_statics_resolved(const aq_statics *s, int act_sign)
{
  int k = act_sign > 0;
  return s->ntab[k] < 2 || s->resolved[k];
}
