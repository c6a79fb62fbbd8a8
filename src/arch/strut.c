/* strut.c: the straight strut of an arch (see model.h, aq_strut): the line
 * that fits inside every joint with the largest margin, and the refusal of
 * an arch too flat for its thickness to open into four hinges.
 */
#include <math.h>
#include <stdio.h>

#include "../units.h"
#include "model.h"

/* ---- the straight strut -------------------------------------------------- */

#define STRUT_SLOPE_MAX 1e4    /* slopes searched, m/m: lines within 0.006 deg of vertical */
#define STRUT_BISECTIONS 200   /* halvings of the slope's bracket (to round-off) */
#define STRUT_MARGIN_REL 1e-9  /* a margin above this (relative to the arch's size) fits */

/* For slope b: the best offset *a and the margin (half the gap between the
 * lowest extrados end and the highest intrados end, each measured from the
 * line y = b x); *dgap the gap's slope in b (a supergradient); *ti, *te
 * the joints of those two ends. */
static double strut_at(const aq_geom *g, double b, double *a, double *dgap, size_t *ti,
                       size_t *te)
{
  size_t n = g->p.voussoirs;
  double lo_e = HUGE_VAL, hi_i = -HUGE_VAL;
  *ti = *te = 0;
  for (size_t j = 0; j <= n; j++) {
    double e = g->je[j].y - b * g->je[j].x, i = g->ji[j].y - b * g->ji[j].x;
    if (e < lo_e)
      lo_e = e, *te = j;
    if (i > hi_i)
      hi_i = i, *ti = j;
  }
  *a = 0.5 * (lo_e + hi_i);
  *dgap = -g->je[*te].x + g->ji[*ti].x;
  return 0.5 * (lo_e - hi_i);
}

/* Where the line y = a + b x meets the segment from p to q (clamped to it). */
static aq_vec2 strut_meets(double a, double b, aq_vec2 p, aq_vec2 q)
{
  double den = (q.y - p.y) - b * (q.x - p.x);
  double t = den != 0 ? (a + b * p.x - p.y) / den : 0.5;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  aq_vec2 r = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
  return r;
}

void aq_geom_strut(const aq_geom *g, aq_strut *s)
{
  /* the margin is concave in the slope b (a minimum of lines minus a
   * maximum of lines): bisection on the sign of its supergradient */
  double lo = -STRUT_SLOPE_MAX, hi = STRUT_SLOPE_MAX, a, d;
  size_t ti, te;
  for (int k = 0; k < STRUT_BISECTIONS && hi - lo > 0; k++) {
    double mid = 0.5 * (lo + hi);
    strut_at(g, mid, &a, &d, &ti, &te);
    if (d > 0)
      lo = mid;
    else if (d < 0)
      hi = mid;
    else
      lo = hi = mid;
  }
  double b = 0.5 * (lo + hi);
  s->margin_m = strut_at(g, b, &a, &d, &s->tight_i, &s->tight_e);
  s->a = a;
  s->b = b;
  size_t n = g->p.voussoirs;
  s->p0 = strut_meets(a, b, g->ji[0], g->je[0]);
  s->pn = strut_meets(a, b, g->ji[n], g->je[n]);
}

aq_status aq_geom_check_strut(const aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  double size = 0;
  for (size_t j = 0; j <= n; j++)
    size = fmax(size, fmax(fmax(fabs(g->ji[j].x), fabs(g->ji[j].y)),
                           fmax(fabs(g->je[j].x), fabs(g->je[j].y))));
  aq_strut s;
  aq_geom_strut(g, &s);
  if (!(s.margin_m > STRUT_MARGIN_REL * size))
    return AQ_OK;
  int joints = g->p.shape == AQ_SHAPE_JOINTS;
  char rule[400] = "";
  if (!joints) {
    /* joints normal to the centre line: the intrados end rises to the
     * crown, the extrados end is lowest at a springing, so with a joint at
     * the crown a strut fits while f - t/2 <= (t/2) cos(phi): the rise f
     * at most (t/2)(1 + cos phi), phi the centre line's slope at the
     * springings (docs/arch-model.md) */
    double t = g->p.thickness_m;
    double f = g->p.shape == AQ_SHAPE_CIRCULAR
                   ? g->p.radius_m * (1 - cos(0.5 * g->p.embrace_rad))
                   : g->p.rise_m;
    double ux = g->je[0].x - g->ji[0].x, uy = g->je[0].y - g->ji[0].y;
    double cphi = uy / hypot(ux, uy), phi_deg = acos(fmin(1, fmax(-1, cphi))) / AQ_DEG_RAD;
    snprintf(rule, sizeof rule,
             "; a mechanism needs a rise above (t/2)(1 + cos %.3g deg) = %.4g m (here %.4g; "
             "%.3g deg: the springings' slope) or t below %.4g m (here %.4g)",
             phi_deg, 0.5 * t * (1 + cphi), f, phi_deg, 2 * f / (1 + cphi), t);
  }
  return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, joints ? "joints_file" : "thickness_m",
                      "expected an arch a horizontal load can open into four hinges, got one "
                      "too flat for its thickness: a straight strut from joint 0 at (%.4g, "
                      "%.4g) m to joint %zu at (%.4g, %.4g) m passes %.4g m inside every joint "
                      "(nearest: joint %zu's intrados, joint %zu's extrados) and carries any "
                      "horizontal load%s",
                      s.p0.x, s.p0.y, n, s.pn.x, s.pn.y, s.margin_m, s.tight_i, s.tight_e,
                      rule);
}
