/* bodies.c: the rigid bodies and joints of the block model (model.h), from
 * explicit data or from an arch's geometry (src/arch/model.h aq_geom: each
 * voussoir with its fill and point masses as the arch attaches them). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

void aq_bodies_free(aq_bodies *s)
{
  if (!s)
    return;
  free(s->body);
  free(s->joint);
  free(s->vous_body);
  free(s->vous_c0);
  free(s->vous_m);
  memset(s, 0, sizeof *s);
}

static aq_status set_joint(aq_bodies *s, size_t k, aq_vec2 pi, aq_vec2 pe, aq_error *err)
{
  aq_bjoint *J = &s->joint[k];
  double dx = pe.x - pi.x, dy = pe.y - pi.y, w = hypot(dx, dy);
  if (!(w > 0) || !isfinite(w))
    return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "joints",
                        "joint %zu: expected two distinct finite ends, got a length of %g m",
                        k, w);
  J->a = k == 0 ? AQ_GROUND_P : (int)k - 1;
  J->b = k == s->nb ? AQ_GROUND_M : (int)k;
  J->arch_joint = k;
  J->p[0] = pi;
  J->p[1] = pe;
  J->t0 = (aq_vec2){dx / w, dy / w};
  J->n0 = (aq_vec2){-J->t0.y, J->t0.x};
  J->width_m = w;
  J->ext_m[0] = J->ext_m[1] = 0;
  return AQ_OK;
}

/* The length scale: the largest distance between any two joint ends. */
static void set_scale(aq_bodies *s)
{
  double L = 0;
  for (size_t a = 0; a < s->nj; a++)
    for (size_t b = a; b < s->nj; b++)
      for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++)
          L = fmax(L, hypot(s->joint[a].p[i].x - s->joint[b].p[k].x,
                            s->joint[a].p[i].y - s->joint[b].p[k].y));
  s->length_m = L;
  s->mass_kg = 0;
  for (size_t b = 0; b < s->nb; b++)
    s->mass_kg += s->body[b].mass_kg;
}

aq_status aq_bodies_init(aq_bodies *s, const aq_body *body, size_t nb,
                         const aq_vec2 (*ends)[2], size_t nj, double g_mps2,
                         aq_error *err)
{
  memset(s, 0, sizeof *s);
  if (nb < 1 || (nj != nb && nj != nb + 1))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "bodies",
                        "expected nb >= 1 bodies and nb or nb + 1 joints, got %zu and %zu",
                        nb, nj);
  if (!(g_mps2 > 0) || !isfinite(g_mps2))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "g_mps2", "expected > 0, got %g",
                        g_mps2);
  s->nb = nb;
  s->nj = nj;
  s->g_mps2 = g_mps2;
  s->body = calloc(nb, sizeof *s->body);
  s->joint = calloc(nj, sizeof *s->joint);
  if (!s->body || !s->joint) {
    aq_bodies_free(s);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "bodies", "out of memory");
  }
  for (size_t b = 0; b < nb; b++) {
    if (!(body[b].mass_kg > 0) || !(body[b].inertia_kgm2 > 0) ||
        !isfinite(body[b].mass_kg + body[b].inertia_kgm2 + body[b].c0.x + body[b].c0.y)) {
      aq_bodies_free(s);
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "bodies",
                          "body %zu: expected a finite mass and inertia > 0, got %g kg, "
                          "%g kg m^2",
                          b, body[b].mass_kg, body[b].inertia_kgm2);
    }
    s->body[b] = body[b];
  }
  for (size_t k = 0; k < nj; k++) {
    aq_status st = set_joint(s, k, ends[k][0], ends[k][1], err);
    if (st != AQ_OK) {
      aq_bodies_free(s);
      return st;
    }
  }
  set_scale(s);
  /* an arch's supports bear on their springing joints; the ground under a
   * stack runs on */
  if (nj == nb)
    aq_bodies_set_support_extent(s, INFINITY);
  return AQ_OK;
}

void aq_bodies_set_support_extent(aq_bodies *s, double ext_m)
{
  for (size_t k = 0; k < s->nj; k++) {
    if (s->joint[k].a < 0)
      s->joint[k].ext_m[0] = ext_m;
    if (s->joint[k].b < 0)
      s->joint[k].ext_m[1] = ext_m;
  }
}

aq_status aq_bodies_from_arch(aq_bodies *s, const aq_geom *g, const size_t *fj,
                              size_t nfree, double g_mps2, aq_error *err)
{
  size_t n = g->p.voussoirs;
  if (!fj)
    nfree = n + 1;
  memset(s, 0, sizeof *s);
  if (nfree < 2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "joints",
                        "expected at least two free joints, got %zu", nfree);
  for (size_t k = 0; fj && k < nfree; k++)
    if (fj[k] > n || (k > 0 && fj[k] <= fj[k - 1]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "joints",
                          "expected free joints increasing in 0..%zu, got %zu after %zu", n,
                          fj[k], k > 0 ? fj[k - 1] : 0);
  size_t nb = nfree - 1;
  aq_body *body = calloc(nb, sizeof *body);
  aq_vec2(*ends)[2] = calloc(nfree, sizeof *ends);
  if (!body || !ends) {
    free(body);
    free(ends);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "bodies", "out of memory");
  }
  for (size_t k = 0; k < nfree; k++) {
    size_t j = fj ? fj[k] : k;
    ends[k][0] = g->ji[j];
    ends[k][1] = g->je[j];
  }
  for (size_t b = 0; b < nb; b++) {
    size_t v0 = fj ? fj[b] : b, v1 = fj ? fj[b + 1] : b + 1;
    aq_mass m = aq_geom_body(g, v0, v1);
    body[b] = (aq_body){m.mass_kg, m.inertia_kgm2, m.c, v0, v1};
  }
  aq_status st = aq_bodies_init(s, body, nb, (const aq_vec2(*)[2])ends, nfree, g_mps2, err);
  free(body);
  free(ends);
  if (st != AQ_OK)
    return st;
  for (size_t k = 0; k < nfree; k++)
    s->joint[k].arch_joint = fj ? fj[k] : k;
  s->nvous = n;
  s->vous_body = malloc(n * sizeof *s->vous_body);
  s->vous_c0 = malloc(n * sizeof *s->vous_c0);
  s->vous_m = malloc(n * sizeof *s->vous_m);
  if (!s->vous_body || !s->vous_c0 || !s->vous_m) {
    aq_bodies_free(s);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "bodies", "out of memory");
  }
  size_t first = s->joint[0].arch_joint, last = s->joint[nfree - 1].arch_joint;
  for (size_t k = 0, b = 0; k < n; k++) {
    while (b + 1 < nb && k >= s->body[b].v1)
      b++;
    s->vous_body[k] = k < first ? AQ_GROUND_P : k >= last ? AQ_GROUND_M : (int)b;
    s->vous_c0[k] = g->vous[k].c;
    s->vous_m[k] = g->vous[k].mass_kg;
  }
  return AQ_OK;
}

aq_vec2 aq_bodies_point(const aq_bodies *s, int b, const double *q, const double gx[2],
                        aq_vec2 p0)
{
  if (b < 0)
    return (aq_vec2){p0.x + gx[b == AQ_GROUND_P ? 0 : 1], p0.y};
  const double *qb = q + 3 * b;
  aq_vec2 c0 = s->body[b].c0;
  double dx = p0.x - c0.x, dy = p0.y - c0.y, cs = cos(qb[2]), sn = sin(qb[2]);
  return (aq_vec2){qb[0] + cs * dx - sn * dy, qb[1] + sn * dx + cs * dy};
}

void aq_bodies_rest(const aq_bodies *s, double *q)
{
  for (size_t b = 0; b < s->nb; b++) {
    q[3 * b] = s->body[b].c0.x;
    q[3 * b + 1] = s->body[b].c0.y;
    q[3 * b + 2] = 0;
  }
}

double aq_bodies_kinetic_j(const aq_bodies *s, const double *v)
{
  double ke = 0;
  for (size_t b = 0; b < s->nb; b++) {
    const double *w = v + 3 * b;
    ke += 0.5 * s->body[b].mass_kg * (w[0] * w[0] + w[1] * w[1]) +
          0.5 * s->body[b].inertia_kgm2 * w[2] * w[2];
  }
  return ke;
}

double aq_bodies_potential_j(const aq_bodies *s, const double *q)
{
  double pe = 0;
  for (size_t b = 0; b < s->nb; b++)
    pe += s->body[b].mass_kg * s->g_mps2 * q[3 * b + 1];
  return pe;
}
