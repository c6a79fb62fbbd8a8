/* arch.c: the arch object: built from parameters (aq_arch_build; cfg.c
 * reads them from a .cfg) or from the drawing stored in a results file,
 * its geometry, the search's minimum, the work paths of its primary and
 * reverse hinge sets and the arrays of its drawing.  What it is asked
 * afterwards (its parts, statics, content digest, demand tables, mirror
 * symmetry) is arch_query.c's.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/sha256.h"
#include "../units.h"
#include "arch.h"
#include "demand.h"
#include "model.h"
#include "arch_impl.h"

void aq_arch_free(aq_arch *a)
{
  if (!a)
    return;
  for (int s = 0; s < 2; s++) {
    aq_workpath_free(a->wp[s]);
    aq_demand_table_free(a->demand[s]);
  }
  aq_statics_free(a->statics);
  aq_geom_free(&a->geom);
  free(a->name);
  free(a->text);
  free(a->data[0]);
  free(a->data[1]);
  free(a->d_joints);
  free(a->d_parts);
  free(a->d_outline);
  free(a->d_fill);
  free(a->d_mass);
  free(a->d_ostart);
  free(a->d_fstart);
  free(a);
}

/* aq_arch_drawing's arrays from the geometry: 0, or -1 out of memory. */
static int drawing_make(aq_arch *a)
{
  const aq_geom *g = &a->geom;
  size_t n = g->p.voussoirs, no = g->outline_start[n], nf = g->fill_start[n], nm = g->p.nmass;
  a->d_joints = malloc(4 * (n + 1) * sizeof *a->d_joints);
  a->d_parts = malloc(4 * n * sizeof *a->d_parts);
  a->d_outline = malloc((2 * no + 1) * sizeof *a->d_outline);
  a->d_fill = malloc((2 * nf + 1) * sizeof *a->d_fill);
  a->d_mass = malloc((4 * nm + 1) * sizeof *a->d_mass);
  a->d_ostart = malloc((n + 1) * sizeof *a->d_ostart);
  a->d_fstart = malloc((n + 1) * sizeof *a->d_fstart);
  if (!a->d_joints || !a->d_parts || !a->d_outline || !a->d_fill || !a->d_mass ||
      !a->d_ostart || !a->d_fstart)
    return -1;
  for (size_t j = 0; j <= n; j++) {
    double *r = a->d_joints + 4 * j;
    r[0] = g->ji[j].x, r[1] = g->ji[j].y, r[2] = g->je[j].x, r[3] = g->je[j].y;
    a->d_ostart[j] = (int64_t)g->outline_start[j];
    a->d_fstart[j] = (int64_t)g->fill_start[j];
  }
  for (size_t k = 0; k < n; k++) {
    double *r = a->d_parts + 4 * k;
    r[0] = g->vous[k].mass_kg, r[1] = g->vous[k].c.x, r[2] = g->vous[k].c.y;
    r[3] = g->vous[k].inertia_kgm2;
  }
  for (size_t i = 0; i < no; i++)
    a->d_outline[2 * i] = g->outline[i].x, a->d_outline[2 * i + 1] = g->outline[i].y;
  for (size_t i = 0; i < nf; i++)
    a->d_fill[2 * i] = g->fill[i].x, a->d_fill[2 * i + 1] = g->fill[i].y;
  for (size_t i = 0; i < nm; i++) {
    double *r = a->d_mass + 4 * i;
    r[0] = (double)g->mass[i].voussoir, r[1] = g->mass[i].p.x, r[2] = g->mass[i].p.y;
    r[3] = g->mass[i].mass_kg;
  }
  return 0;
}

void aq_arch_drawing_of(const aq_arch *a, aq_arch_drawing *d)
{
  const aq_geom *g = &a->geom;
  size_t n = g->p.voussoirs;
  d->shape = aq_shape_names[g->p.shape];
  d->voussoirs = n;
  d->joints = a->d_joints;
  d->parts = a->d_parts;
  d->noutline = g->outline_start[n];
  d->nfill = g->fill_start[n];
  d->outline = a->d_outline;
  d->outline_start = a->d_ostart;
  d->fill = a->d_fill;
  d->fill_start = a->d_fstart;
  d->nmass = g->p.nmass;
  d->mass = a->d_mass;
  d->stone_kg = g->stone_kg;
  d->fill_kg = g->fill_kg;
  d->point_kg = g->point_kg;
}

static aq_hinge_set swap_faces(const aq_hinge_set *hs)
{
  aq_hinge_set r = *hs;
  for (int k = 0; k < 4; k++)
    r.face[k] = hs->face[k] == 'e' ? 'i' : 'e';
  return r;
}

static const char *const set_names[2] = {"primary", "reverse"};
const char *const aq_hinge_control_names[2] = {"fixed", "free"};

/* ---- The built tables as bytes (aq_arch_tables_put, tables_get) ----
 * What the search and the work paths computed, kept between processes
 * (src/job/arch_cache.h) so that a later build of the same arch reads
 * them instead: the search's result, the two hinge sets and both paths
 * (workpath.c), each double as its bits. */
#define TABLES_FORMAT "archquake arch tables 3"

static void set_put(aq_bytes_out *b, const aq_hinge_set *hs)
{
  for (int k = 0; k < 4; k++) {
    aq_bytes_put_i64(b, (int64_t)hs->joint[k]);
    aq_bytes_put_i64(b, hs->face[k]);
  }
}

static void set_get(aq_bytes_in *r, size_t voussoirs, aq_hinge_set *hs)
{
  for (int k = 0; k < 4; k++) {
    hs->joint[k] = (size_t)aq_bytes_get_int(r, 0, (int64_t)voussoirs, "joint");
    hs->face[k] = (char)aq_bytes_get_int(r, 'e', 'i', "face");
  }
}

static int same_set(const aq_hinge_set *a, const aq_hinge_set *b)
{
  for (int k = 0; k < 4; k++)
    if (a->joint[k] != b->joint[k] || a->face[k] != b->face[k])
      return 0;
  return 1;
}

void aq_arch_tables_put(const aq_arch *a, aq_bytes_out *b)
{
  aq_bytes_put_str(b, TABLES_FORMAT, 0);
  aq_bytes_put_i64(b, a->control);
  aq_bytes_put_i64(b, a->searched);
  aq_bytes_put_i64(b, a->min_known);
  aq_hinge_set none = {{0, 0, 0, 0}, {'e', 'e', 'e', 'e'}}; /* no minimum: never read */
  set_put(b, a->min_known ? &a->min_hs : &none);
  aq_bytes_put_f64(b, a->min_lambda0);
  aq_bytes_put_i64(b, (int64_t)a->min_info.programs);
  aq_bytes_put_i64(b, a->min_info.liftoff);
  aq_bytes_put_i64(b, (int64_t)a->min_info.liftoff_joint);
  aq_bytes_put_f64(b, a->min_info.liftoff_lambda);
  for (int s = 0; s < 2; s++)
    set_put(b, &a->hs[s]);
  for (int s = 0; s < 2; s++)
    aq_workpath_put(a->wp[s], b);
  aq_statics_put(a->statics, b);
}

/* The search's result, the hinge sets and the paths from kept[0..n)
 * (aq_arch_tables_put's), when they are those of this arch's [hinges]
 * (primary, reverse; NULL: searched, the primary's faces swapped; free
 * control: the primary, if given, one of the two sets): 0, or -1 with
 * nothing taken. */
static int tables_get(aq_arch *a, const unsigned char *kept, size_t n,
                      const aq_hinge_set *primary, const aq_hinge_set *reverse)
{
  aq_bytes_in r = {kept, n, 0, NULL, 0};
  size_t nv = a->geom.p.voussoirs;
  char format[sizeof TABLES_FORMAT];
  aq_bytes_get_str(&r, format, sizeof format, NULL, "format");
  int control = (int)aq_bytes_get_int(&r, AQ_CONTROL_FIXED, AQ_CONTROL_FREE, "control");
  a->searched = (int)aq_bytes_get_int(&r, 0, 1, "searched");
  a->min_known = (int)aq_bytes_get_int(&r, 0, 1, "minimum known");
  set_get(&r, nv, &a->min_hs);
  a->min_lambda0 = aq_bytes_get_f64(&r, "minimum lambda0");
  a->min_info.programs = (size_t)aq_bytes_get_int(&r, 0, INT64_MAX, "programs");
  a->min_info.liftoff = (int)aq_bytes_get_int(&r, 0, 1, "liftoff");
  a->min_info.liftoff_joint = (size_t)aq_bytes_get_int(&r, 0, (int64_t)nv, "liftoff joint");
  a->min_info.liftoff_lambda = aq_bytes_get_f64(&r, "liftoff lambda");
  for (int s = 0; s < 2; s++)
    set_get(&r, nv, &a->hs[s]);
  aq_hinge_set swapped = swap_faces(&a->hs[0]);
  int ok = !r.bad && !strcmp(format, TABLES_FORMAT) && control == (int)a->control;
  if (ok && a->control == AQ_CONTROL_FREE)
    ok = !reverse && (primary ? !a->searched && (same_set(&a->hs[0], primary) ||
                                                 same_set(&a->hs[1], primary))
                              : a->searched && a->min_known);
  else if (ok)
    ok = (primary ? !a->searched && same_set(&a->hs[0], primary)
                  : a->searched && a->min_known && same_set(&a->hs[0], &a->min_hs)) &&
         same_set(&a->hs[1], reverse ? reverse : &swapped);
  for (int s = 0; s < 2 && ok; s++)
    ok = aq_workpath_get(&a->geom, &a->hs[s], a->dyn.g_mps2, set_names[s], &r, &a->wp[s],
                         NULL) == AQ_OK;
  ok = ok && aq_statics_get(&r, nv, &a->statics) == AQ_OK;
  if (ok && r.at == r.n && aq_workpath_path(a->wp[0])->admissible)
    return 0;
  for (int s = 0; s < 2; s++) {
    aq_workpath_free(a->wp[s]);
    a->wp[s] = NULL;
  }
  aq_statics_free(a->statics);
  a->statics = NULL;
  a->searched = a->min_known = 0;
  memset(&a->min_hs, 0, sizeof a->min_hs);
  memset(&a->min_info, 0, sizeof a->min_info);
  memset(a->hs, 0, sizeof a->hs);
  a->min_lambda0 = 0;
  return -1;
}

/* Free control's sets: for act_sign -1 (set 0) and +1 (set 1) the
 * primary if it is that direction's, else the arch's minimum if it is,
 * else that direction's own minimum by the search. */
static aq_status free_sets(aq_arch *a, const aq_hinge_set *primary, aq_error *err)
{
  int pact = primary ? aq_search_act_sign(&a->geom, primary) : 0;
  int mact = a->min_known ? aq_search_act_sign(&a->geom, &a->min_hs) : 0;
  if (primary && !pact)
    pact = -1; /* no mechanism: set 0, where building its path says why */
  for (int k = 0; k < 2; k++) {
    int act = k ? 1 : -1;
    if (primary && pact == act) {
      a->hs[k] = *primary;
    } else if (mact == act) {
      a->hs[k] = a->min_hs;
    } else {
      aq_search_info info;
      aq_status st = aq_search_direction(&a->geom, a->dyn.g_mps2, act, &a->hs[k], NULL, &info,
                                         err);
      if (st != AQ_OK)
        return st;
    }
  }
  return AQ_OK;
}

/* Everything after the parameters: geometry, hinge sets, paths (from
 * kept[0..nkept), aq_arch_tables_put's bytes, when they are this arch's:
 * *used 1).  Errors carry the field ("primary", "reverse", a parameter
 * key) but no file. */
static aq_status build_core(aq_arch *a, const aq_arch_params *p,
                            const aq_hinge_set *primary, const aq_hinge_set *reverse,
                            const unsigned char *kept, size_t nkept, int *used, aq_error *err)
{
  if (p->control == AQ_CONTROL_FREE && reverse)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "reverse",
                        "expected no reverse set with control = free (each direction's set is "
                        "its own minimum mechanism), got one");
  if (!(p->friction >= 0) || !isfinite(p->friction))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "friction",
                        "expected a Coulomb coefficient > 0, got %g", p->friction);
  if (!(p->e_n >= 0 && p->e_n <= 1))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "e_n", "expected 0..1, got %g", p->e_n);
  if (!(p->spread_m >= 0) || !isfinite(p->spread_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "spread_m", "expected >= 0 m, got %g",
                        p->spread_m);
  if (!(p->abutment_m >= 0) || !isfinite(p->abutment_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "abutment_m",
                        "expected >= 0 m, got %g", p->abutment_m);
  a->control = p->control;
  a->friction = p->friction;
  a->e_n = p->e_n;
  a->spread_m = p->spread_m;
  a->abutment_m = p->abutment_m;
  aq_status st = aq_geom_init(&a->geom, p, err);
  if (st != AQ_OK || (st = aq_geom_check_strut(&a->geom, err)) != AQ_OK)
    return st; /* a strut fits: no set of any hinges is a mechanism */
  if (kept && tables_get(a, kept, nkept, primary, reverse) == 0) {
    *used = 1;
    if (drawing_make(a) != 0)
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    return AQ_OK;
  }
  /* The arch's minimum over every admissible set, whether or not [hinges]
   * names one: an arch that some set turns into a mechanism under gravity
   * alone (lambda0 <= 0) cannot stand, whichever set the file names. */
  aq_error e2;
  aq_error_clear(&e2);
  st = aq_search_minimum(&a->geom, a->dyn.g_mps2, &a->min_hs, &a->min_lambda0, &a->min_info,
                         &e2);
  /* AQ_EUNSUPPORTED: GLPK could not be opened, so nothing was searched:
   * refused even with [hinges], or whether the arch stands goes unchecked */
  if (st != AQ_OK && (!primary || st == AQ_EUNSUPPORTED)) {
    if (err)
      *err = e2;
    return st;
  }
  a->min_known = st == AQ_OK;
  if (a->min_known && !(a->min_lambda0 > 0)) {
    char set[64];
    aq_hinge_set_text(&a->min_hs, set, sizeof set);
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "arch",
                        "expected an arch that stands under its own weight, got one "
                        "that cannot: the admissible hinge set %s has lambda0 = %.4g "
                        "<= 0 (gravity alone makes it a mechanism)",
                        set, a->min_lambda0);
  }
  if (a->control == AQ_CONTROL_FREE) {
    st = free_sets(a, primary, err);
    if (st != AQ_OK)
      return st;
  } else {
    a->hs[0] = primary ? *primary : a->min_hs;
    a->hs[1] = reverse ? *reverse : swap_faces(&a->hs[0]);
  }
  a->searched = !primary;
  /* the statics with friction: an arch that cannot stand with its friction
   * is refused here, before its paths are built */
  st = aq_statics_build(&a->geom, a->friction, p->friction_table, &a->statics, err);
  if (st != AQ_OK)
    return st;
  for (int s = 0; s < 2; s++) {
    st = aq_workpath_build(&a->geom, &a->hs[s], a->dyn.g_mps2, set_names[s], &a->wp[s], err);
    if (st != AQ_OK) {
      if (err && !strcmp(err->field, "hinges"))
        snprintf(err->field, sizeof err->field, "%s", set_names[s]);
      return st;
    }
  }
  if (!aq_workpath_path(a->wp[0])->admissible)
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "primary",
                        "expected an admissible mechanism, got one where %s",
                        aq_workpath_reason(a->wp[0]));
  aq_workpath_set_impact(a->wp[0], a->wp[1]);
  aq_workpath_set_impact(a->wp[1], a->wp[0]);
  if (drawing_make(a) != 0)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  return AQ_OK;
}

aq_status aq_arch_build(const aq_arch_params *p, const aq_hinge_set *primary,
                        const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                        const char *name, aq_arch **out, aq_error *err)
{
  return aq_arch_build_kept(p, primary, reverse, dyn, name, NULL, 0, NULL, out, err);
}

aq_status aq_arch_build_kept(const aq_arch_params *p, const aq_hinge_set *primary,
                             const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                             const char *name, const unsigned char *kept, size_t nkept,
                             int *used, aq_arch **out, aq_error *err)
{
  int used_ = 0;
  *out = NULL;
  if (used)
    *used = 0;
  aq_arch *a = calloc(1, sizeof *a);
  if (!a)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  a->dyn.cor = 0;
  a->dyn.impact = AQ_IMPACT_COR;
  a->dyn.g_mps2 = AQ_G0_MPS2;
  if (dyn)
    a->dyn = *dyn;
  a->name = strdup(name ? name : "arch");
  a->text = strdup("");
  if (!a->name || !a->text) {
    aq_arch_free(a);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  aq_status st = build_core(a, p, primary, reverse, kept, nkept, &used_, err);
  if (st != AQ_OK) {
    aq_arch_free(a);
    return st;
  }
  if (used)
    *used = used_;
  *out = a;
  return AQ_OK;
}

void aq_arch_keep_sources(aq_arch *a, char *text, char *data[2], const size_t ndata[2])
{
  free(a->text);
  a->text = text;
  for (int f = 0; f < 2; f++) {
    free(a->data[f]);
    a->data[f] = data[f];
    a->ndata[f] = ndata[f];
  }
}

aq_status aq_arch_from_drawing(const aq_arch_drawing *d, const aq_hinge_set *primary,
                               const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                               double friction, const char *name, aq_arch **out,
                               aq_error *err)
{
  aq_arch_params p = aq_arch_circular(0, 0, 0, d->voussoirs, 1, 1);
  for (int s = 0; s < AQ_SHAPE_COUNT; s++)
    if (d->shape && !strcmp(d->shape, aq_shape_names[s]))
      p.shape = (aq_shape)s;
  p.stored = d;
  p.friction = friction > 0 ? friction : 0;
  return aq_arch_build(&p, primary, reverse, dyn, name, out, err);
}
