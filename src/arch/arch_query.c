/* arch_query.c: what a built arch is asked (arch.h): its name, sets,
 * paths and statics, the sources and their digest, the joints' demand
 * tables (built on first use) and trackers, and its mirror symmetry. */
#include <math.h>
#include <pthread.h>
#include <string.h>

#include "../io/sha256.h"
#include "arch_impl.h"

/* Guards every arch's demand tables while one is built (rarely). */
static pthread_mutex_t demand_lock = PTHREAD_MUTEX_INITIALIZER;

const char *aq_arch_name(const aq_arch *a) { return a->name; }
const char *aq_arch_config_text(const aq_arch *a) { return a->text; }
const aq_arch_dynamics *aq_arch_dynamics_of(const aq_arch *a) { return &a->dyn; }
const aq_path *aq_arch_path(const aq_arch *a, int set)
{
  return set == 0 || set == 1 ? aq_workpath_path(a->wp[set]) : NULL;
}
const aq_geom *aq_arch_geom(const aq_arch *a) { return &a->geom; }
const aq_workpath *aq_arch_workpath(const aq_arch *a, int set)
{
  return set == 0 || set == 1 ? a->wp[set] : NULL;
}
int aq_arch_searched(const aq_arch *a) { return a->searched; }
aq_hinge_control aq_arch_control(const aq_arch *a) { return a->control; }
double aq_arch_friction(const aq_arch *a) { return a->friction > 0 ? a->friction : NAN; }
const aq_statics *aq_arch_statics(const aq_arch *a) { return a->statics; }

double aq_arch_mu_rest(const aq_arch *a, size_t *joint)
{
  return aq_statics_mu_rest(a->statics, joint);
}
double aq_arch_mu_least(const aq_arch *a, int act_sign, double lambda, size_t *joint)
{
  return aq_statics_mu_least(a->statics, act_sign, lambda, joint);
}
double aq_arch_lambda_friction(const aq_arch *a, int act_sign, double mu)
{
  return mu == a->friction ? aq_statics_lambda_friction(a->statics, act_sign, NULL)
                           : aq_statics_lambda_at(a->statics, act_sign, mu);
}
double aq_arch_lambda_static(const aq_arch *a, int act_sign)
{
  return aq_statics_lambda_top(a->statics, act_sign);
}

double aq_arch_joint_friction(const aq_arch *a, int set, double *ratio, size_t *joint)
{
  const aq_workpath *w = aq_arch_workpath(a, set);
  if (w)
    return aq_workpath_friction(w, ratio, joint);
  if (joint)
    *joint = SIZE_MAX;
  return NAN;
}
double aq_arch_restitution(const aq_arch *a) { return a->e_n; }
double aq_arch_spread(const aq_arch *a) { return a->spread_m; }
double aq_arch_abutment(const aq_arch *a) { return a->abutment_m; }
const aq_hinge_set *aq_arch_hinge_set(const aq_arch *a, int set) { return &a->hs[set ? 1 : 0]; }
int aq_arch_minimum(const aq_arch *a, aq_hinge_set *hs, double *lambda0)
{
  if (!a->min_known)
    return 0;
  if (hs)
    *hs = a->min_hs;
  if (lambda0)
    *lambda0 = a->min_lambda0;
  return 1;
}
int aq_arch_liftoff(const aq_arch *a, size_t *joint, double *lambda)
{
  if (!a->min_known || !a->min_info.liftoff)
    return 0;
  if (joint)
    *joint = a->min_info.liftoff_joint;
  if (lambda)
    *lambda = a->min_info.liftoff_lambda;
  return 1;
}

void aq_arch_sources_of(const aq_arch *a, aq_arch_sources *src)
{
  src->text = a->text;
  src->ntext = a->text ? strlen(a->text) : 0;
  for (int f = 0; f < 2; f++) {
    src->data[f] = a->data[f];
    src->ndata[f] = a->ndata[f];
  }
}

void aq_arch_sha256(const aq_arch *a, char hex[65])
{
  aq_sha256_ctx c;
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_init(&c);
  aq_sha256_update(&c, a->text, strlen(a->text));
  for (int f = 0; f < 2; f++)
    if (a->data[f])
      aq_sha256_update(&c, a->data[f], a->ndata[f]);
  aq_sha256_final(&c, d);
  aq_sha256_hexify_(d, hex);
}

const aq_demand_table *aq_arch_demand_table(const aq_arch *a, int set)
{
  if (set < 0 || set > 1 || !a->wp[set])
    return NULL;
  aq_arch *w = (aq_arch *)a; /* a cache of what the arch is: built once */
  pthread_mutex_lock(&demand_lock);
  if (!w->demand_tried[set]) {
    aq_error e;
    aq_error_clear(&e);
    const aq_path *p = aq_workpath_path(w->wp[set]);
    if (p->admissible)
      aq_demand_table_build(aq_workpath_mech(w->wp[set]), p, &w->demand[set], &e);
    w->demand_tried[set] = 1;
  }
  const aq_demand_table *t = w->demand[set];
  pthread_mutex_unlock(&demand_lock);
  return t;
}

static const aq_demand_table *demand_get(void *ctx, int set)
{
  return aq_arch_demand_table(ctx, set);
}

/* A run that never moves: the statics' least friction (aq_arch_mu_least,
 * NAN without the arch's table). */
static double demand_least(void *ctx, int act_sign, double lambda, size_t *joint)
{
  return aq_arch_mu_least(ctx, act_sign, lambda, joint);
}

aq_demand *aq_arch_demand_tracker(const aq_arch *a, double mu_limit, aq_error *err)
{
  aq_demand *d = aq_demand_alloc(demand_get, (void *)a, err);
  if (d) {
    aq_demand_set_limit(d, mu_limit);
    aq_demand_set_least(d, demand_least, (void *)a);
  }
  return d;
}

/* Mirror symmetry: to this fraction of the arch's size in position, and of
 * each mass and inertia.  The shipped shapes' joints come from closed forms
 * and are mirror images to round-off (1e-15); a joints file symmetric only
 * to its printed digits is taken as asymmetric (its runs go both ways). */
#define MIRROR_REL_TOL 1e-9

int aq_arch_mirror_symmetric(const aq_arch *a)
{
  const aq_geom *g = &a->geom;
  size_t n = g->p.voussoirs;
  /* the axis: midway between the springings' intrados ends */
  double xc = 0.5 * (g->ji[0].x + g->ji[n].x), size = 0;
  for (size_t j = 0; j <= n; j++)
    size = fmax(size, fmax(hypot(g->ji[j].x - xc, g->ji[j].y), hypot(g->je[j].x - xc, g->je[j].y)));
  double tol = MIRROR_REL_TOL * size;
  for (size_t j = 0; j <= n; j++) {
    const aq_vec2 *p[2] = {&g->ji[j], &g->je[j]}, *q[2] = {&g->ji[n - j], &g->je[n - j]};
    for (int f = 0; f < 2; f++)
      if (!(fabs(p[f]->x - (2 * xc - q[f]->x)) <= tol && fabs(p[f]->y - q[f]->y) <= tol))
        return 0;
  }
  for (size_t k = 0; k < n; k++) {
    const aq_mass *u = &g->vous[k], *v = &g->vous[n - 1 - k];
    if (!(fabs(u->mass_kg - v->mass_kg) <= MIRROR_REL_TOL * u->mass_kg &&
          fabs(u->inertia_kgm2 - v->inertia_kgm2) <= MIRROR_REL_TOL * u->inertia_kgm2 &&
          fabs(u->c.x - (2 * xc - v->c.x)) <= tol && fabs(u->c.y - v->c.y) <= tol))
      return 0;
  }
  return 1;
}

int aq_arch_one_polarity(const aq_arch *a)
{
  if (a->control != AQ_CONTROL_FREE || !aq_arch_mirror_symmetric(a))
    return 0;
  size_t n = a->geom.p.voussoirs;
  const aq_hinge_set *s0 = &a->hs[0], *s1 = &a->hs[1];
  for (int k = 0; k < 4; k++) /* set 1 is set 0 seen in the mirror */
    if (s1->joint[k] != n - s0->joint[3 - k] || s1->face[k] != s0->face[3 - k])
      return 0;
  const aq_path *p0 = aq_workpath_path(a->wp[0]), *p1 = aq_workpath_path(a->wp[1]);
  return p0->admissible && p1->admissible;
}
