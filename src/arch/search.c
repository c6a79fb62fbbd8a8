/* search.c: the upper-bound mechanism when the arch file has no [hinges].
 *
 * Every alternating four-hinge set (joints j1 < j2 < j3 < j4 in 0..n, faces
 * e i e i or i e i e) is a one-degree-of-freedom mechanism; its multiplier
 * lambda0 follows from the velocities at s = 0 alone (virtual work,
 * docs/method.md sec. 5), computed in O(1) per set from prefix sums of the voussoirs' mass
 * and first moments.  The sets whose hinges all open are ranked by lambda0,
 * whatever its sign; the lowest SEARCH_KEEP are kept and checked in order
 * with the full equilibrium (eq. (3): every hinge reaction compressive); the
 * first that passes is the arch's minimum-lambda0 set.  A set with
 * lambda0 <= 0 is kept too: gravity alone (or gravity and a load of the
 * other sign) drives it, so the arch cannot stand, and the caller must know
 * it rather than be handed the lowest positive set.  Ties
 * (lambda0 equal to TIE_REL, e.g. the mirror images of a symmetric arch) go
 * to the set enumerated first (e i e i before i e i e, then lowest joints).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

#define SEARCH_KEEP 256 /* candidates kept for the full admissibility check */
#define TIE_REL 1e-12   /* lambda0 within this (relative) of another is a tie */

/* a lower than b by more than a tie */
static int lower(double a, double b) { return a < b - TIE_REL * fabs(b); }

static double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }

/* First-order lambda0 from the hinge points P[k] and the joints. */
static int lambda0_fast(const aq_geom *g, const size_t j[4], const aq_vec2 P[4],
                        int open1, const int open[4], double *lambda0)
{
  aq_vec2 v1 = {P[1].x - P[0].x, P[1].y - P[0].y};
  aq_vec2 v2 = {P[2].x - P[1].x, P[2].y - P[1].y};
  aq_vec2 v3 = {P[3].x - P[2].x, P[3].y - P[2].y};
  double det = cross(v2, v3);
  if (det == 0)
    return 0;
  aq_vec2 w = {-v1.x, -v1.y};
  double a = cross(w, v3) / det, b = cross(v2, w) / det;
  double rate[4] = {1.0, a - 1.0, b - a, -b};
  for (int k = 0; k < 4; k++)
    if (!(open[k] * open1 * rate[k] > 0))
      return 0;
  double m[3], sx[3], sy[3];
  for (int k = 0; k < 3; k++) {
    m[k] = g->cum_m[j[k + 1]] - g->cum_m[j[k]];
    sx[k] = g->cum_mx[j[k + 1]] - g->cum_mx[j[k]];
    sy[k] = g->cum_my[j[k + 1]] - g->cum_my[j[k]];
  }
  /* sum_b m_b dc_b/dq: J(S1 - m1 H1) + m2 J v1 + a J(S2 - m2 H2) + b J(S3 - m3 H4) */
  double gx = -(sy[0] - m[0] * P[0].y) - m[1] * v1.y - a * (sy[1] - m[1] * P[1].y) -
              b * (sy[2] - m[2] * P[3].y);
  double gy = (sx[0] - m[0] * P[0].x) + m[1] * v1.x + a * (sx[1] - m[1] * P[1].x) +
              b * (sx[2] - m[2] * P[3].x);
  if (gx == 0)
    return 0;
  *lambda0 = (double)open1 * gy / fabs(gx);
  return 1;
}

int aq_search_lambda0(const aq_geom *g, const aq_hinge_set *hs, double *lambda0)
{
  aq_vec2 P[4];
  int open[4];
  for (int k = 0; k < 4; k++) {
    P[k] = aq_geom_joint_point(g, hs->joint[k], hs->face[k]);
    open[k] = hs->face[k] == 'i' ? 1 : -1;
  }
  return lambda0_fast(g, hs->joint, P, open[0], open, lambda0);
}

typedef struct {
  double lambda0;
  size_t j[4];
  int pattern; /* 0: e i e i, 1: i e i e */
} cand;

aq_status aq_search_minimum(const aq_geom *g, double g_mps2, aq_hinge_set *best,
                            double *lambda0, size_t *nsets, aq_error *err)
{
  size_t n = g->p.voussoirs, count = 0, nk = 0;
  if (n > AQ_SEARCH_MAX_VOUSSOIRS)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "voussoirs",
                        "expected at most %d voussoirs without [hinges] (the search "
                        "grows as voussoirs^4), got %zu",
                        AQ_SEARCH_MAX_VOUSSOIRS, n);
  aq_vec2 *pt = malloc(2 * (n + 1) * sizeof *pt); /* [face][joint] */
  cand *keep = malloc(SEARCH_KEEP * sizeof *keep);
  if (!pt || !keep) {
    free(pt);
    free(keep);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  for (size_t j = 0; j <= n; j++) {
    pt[j] = aq_geom_joint_point(g, j, 'e');
    pt[n + 1 + j] = aq_geom_joint_point(g, j, 'i');
  }
  static const char faces[2][4] = {{'e', 'i', 'e', 'i'}, {'i', 'e', 'i', 'e'}};
  for (int pat = 0; pat < 2; pat++) {
    int open[4];
    for (int k = 0; k < 4; k++)
      open[k] = faces[pat][k] == 'i' ? 1 : -1;
    size_t j[4];
    for (j[0] = 0; j[0] + 3 <= n; j[0]++)
      for (j[1] = j[0] + 1; j[1] + 2 <= n; j[1]++)
        for (j[2] = j[1] + 1; j[2] + 1 <= n; j[2]++)
          for (j[3] = j[2] + 1; j[3] <= n; j[3]++) {
            aq_vec2 P[4];
            for (int k = 0; k < 4; k++)
              P[k] = pt[(faces[pat][k] == 'i' ? n + 1 : 0) + j[k]];
            count++;
            double l0;
            if (!lambda0_fast(g, j, P, open[0], open, &l0) || !isfinite(l0))
              continue;
            if (nk == SEARCH_KEEP && !lower(l0, keep[nk - 1].lambda0))
              continue;
            size_t pos = nk < SEARCH_KEEP ? nk++ : nk - 1;
            while (pos > 0 && lower(l0, keep[pos - 1].lambda0)) {
              keep[pos] = keep[pos - 1];
              pos--;
            }
            keep[pos].lambda0 = l0;
            memcpy(keep[pos].j, j, sizeof j);
            keep[pos].pattern = pat;
          }
  }
  if (nsets)
    *nsets = count;
  free(pt);
  aq_status st = AQ_EINADMISSIBLE;
  for (size_t c = 0; c < nk; c++) {
    aq_hinge_set hs;
    for (int k = 0; k < 4; k++) {
      hs.joint[k] = keep[c].j[k];
      hs.face[k] = faces[keep[c].pattern][k];
    }
    aq_mech m;
    aq_mech_state s0;
    aq_equil eq;
    aq_error e2;
    if (aq_mech_init(&m, g, &hs, &e2) != AQ_OK || aq_mech_eval(&m, 0.0, &s0) != 0)
      continue;
    /* act_sign: the sign that drives s forward (see workpath.c) */
    double gx = 0;
    for (int b = 0; b < 3; b++)
      gx += m.body[b].mass_kg * s0.c[b][1].x;
    int act = (double)m.open[0] * gx > 0 ? -1 : 1;
    aq_live live = {AQ_LIVE_HORIZONTAL, act, {0, 0}, 0, g_mps2};
    if (aq_mech_equilibrium(&m, &s0, &live, &eq, &e2) != AQ_OK)
      continue;
    int ok = 1;
    for (int k = 0; k < 4; k++)
      ok &= eq.normal[k] > 0;
    if (ok) {
      *best = hs;
      if (lambda0)
        *lambda0 = keep[c].lambda0;
      st = AQ_OK;
      break;
    }
  }
  free(keep);
  if (st != AQ_OK)
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "hinges",
                        "expected an admissible four-hinge mechanism among the %d "
                        "with the lowest lambda0, got none",
                        SEARCH_KEEP);
  return AQ_OK;
}

aq_status aq_search_mechanism(const aq_geom *g, double g_mps2,
                              aq_hinge_set *best, size_t *nsets, aq_error *err)
{
  double l0;
  aq_status st = aq_search_minimum(g, g_mps2, best, &l0, nsets, err);
  if (st == AQ_OK && !(l0 > 0)) {
    char set[64];
    aq_hinge_set_text(best, set, sizeof set);
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "hinges",
                        "expected an arch that stands under its own weight, got "
                        "one that cannot: the admissible hinge set %s has "
                        "lambda0 = %.4g <= 0",
                        set, l0);
  }
  return st;
}
