/* geometry.c: the voussoirs of an arch, their joints and their mass
 * properties (see model.h).
 *
 * Geometry conventions as in the KCLC (Stockdale et al. 2018, SoftwareX;
 * docs/method.md sec. 10).
 *
 * The mass properties of each voussoir and of its fill come from region.c
 * (annular sectors in closed form, other regions as loops of pieces by
 * Green's theorem); the point masses are added by masses.c, and the
 * straight strut of a flat arch is in strut.c.
 */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "model.h"
#include "region.h"

#define MAX_PIECES 8         /* pieces of a voussoir's or fill's loop before cutting */

const char *const aq_shape_names[AQ_SHAPE_COUNT + 1] = {
    "circular", "pointed", "elliptical", "parabolic", "catenary", "joints", NULL};

/* ---- the voussoirs ------------------------------------------------------ */

void aq_geom_free(aq_geom *g)
{
  if (!g)
    return;
  free(g->theta_rad);
  free(g->ji);
  free(g->je);
  free(g->jo);
  free(g->ju);
  free(g->jmid);
  free(g->jhalf);
  free(g->vous);
  free(g->outline);
  free(g->outline_start);
  free(g->fill);
  free(g->fill_start);
  free(g->mass);
  free(g->vcurve);
  free(g->vu);
  for (int f = 0; f < 2; f++) {
    free(g->face_pt[f]);
    free(g->face_start[f]);
  }
  free(g->cum_m);
  free(g->cum_mx);
  free(g->cum_my);
  memset(g, 0, sizeof *g);
}

/* The loop of voussoir k: joint k up, the extrados, joint k+1 down, the
 * intrados back.  Returns the number of pieces (at most MAX_PIECES, or
 * 4 plus the face points for a joints arch: out must hold that many). */
static size_t voussoir_loop(const aq_geom *g, size_t k, piece *out)
{
  size_t n = 0;
  out[n++] = aq_region_seg(g->ji[k], g->je[k]);
  if (g->p.shape == AQ_SHAPE_JOINTS) {
    aq_vec2 prev = g->je[k];
    if (g->face_start[1])
      for (size_t i = g->face_start[1][k]; i < g->face_start[1][k + 1]; i++) {
        out[n++] = aq_region_seg(prev, g->face_pt[1][i]);
        prev = g->face_pt[1][i];
      }
    out[n++] = aq_region_seg(prev, g->je[k + 1]);
    out[n++] = aq_region_seg(g->je[k + 1], g->ji[k + 1]);
    prev = g->ji[k + 1];
    if (g->face_start[0])
      for (size_t i = g->face_start[0][k + 1]; i-- > g->face_start[0][k];) {
        out[n++] = aq_region_seg(prev, g->face_pt[0][i]);
        prev = g->face_pt[0][i];
      }
    out[n++] = aq_region_seg(prev, g->ji[k]);
    return n;
  }
  const double *u = g->vu + 4 * k; /* intrados u0 u1, extrados u0 u1 */
  double h = 0.5 * g->p.thickness_m;
  piece e = aq_region_curve(&g->centre, g->vcurve[k], h, u[2], u[3]);
  piece i = aq_region_curve(&g->centre, g->vcurve[k], -h, u[1], u[0]);
  e.p0 = g->je[k]; /* the joints' ends exactly (the pointed crown's are set) */
  e.p1 = g->je[k + 1];
  i.p0 = g->ji[k + 1];
  i.p1 = g->ji[k];
  out[n++] = e;
  out[n++] = aq_region_seg(g->je[k + 1], g->ji[k + 1]);
  out[n++] = i;
  return n;
}

/* The loop of voussoir k's fill before it is cut at the level: up from
 * the extrados end of joint k to the level, along it to above the extrados
 * end of joint k+1, down to it, and back along the extrados. */
static size_t fill_loop(const aq_geom *g, size_t k, piece *out)
{
  double L = g->p.fill_level_m;
  aq_vec2 a = g->je[k], b = g->je[k + 1];
  aq_vec2 at = {a.x, L}, bt = {b.x, L};
  size_t n = 0;
  out[n++] = aq_region_seg(a, at);
  out[n++] = aq_region_seg(at, bt);
  out[n++] = aq_region_seg(bt, b);
  if (g->p.shape == AQ_SHAPE_JOINTS) {
    aq_vec2 prev = b;
    if (g->face_start[1])
      for (size_t i = g->face_start[1][k + 1]; i-- > g->face_start[1][k];) {
        out[n++] = aq_region_seg(prev, g->face_pt[1][i]);
        prev = g->face_pt[1][i];
      }
    out[n++] = aq_region_seg(prev, a);
    return n;
  }
  piece loop[MAX_PIECES];
  voussoir_loop(g, k, loop);
  piece e = loop[1]; /* the extrados, reversed */
  piece r = e;
  r.u0 = e.u1, r.u1 = e.u0, r.p0 = e.p1, r.p1 = e.p0;
  out[n++] = r;
  return n;
}

/* Joints of a circular arch (the closed forms), of an analytic shape (normal
 * to the centre line at equal arc length; a pointed arch's crown joint
 * vertical, between the points where the two halves' faces meet), or as
 * given. */
static aq_status place_joints(aq_geom *g, aq_error *err)
{
  const aq_arch_params *p = &g->p;
  size_t n = p->voussoirs;
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    double th_start = 0.5 * AQ_PI - 0.5 * p->embrace_rad;
    for (size_t j = 0; j <= n; j++) {
      double th = th_start + p->embrace_rad * (double)j / (double)n;
      g->theta_rad[j] = th;
      g->ji[j] = (aq_vec2){g->r_i_m * cos(th), g->r_i_m * sin(th)};
      g->je[j] = (aq_vec2){g->r_e_m * cos(th), g->r_e_m * sin(th)};
      g->jo[j] = (aq_vec2){0, 0};
      g->ju[j] = (aq_vec2){cos(th), sin(th)};
      g->jmid[j] = p->radius_m;
      g->jhalf[j] = 0.5 * p->thickness_m;
    }
    for (size_t k = 0; k < n; k++) {
      g->vcurve[k] = 0;
      g->vu[4 * k] = g->vu[4 * k + 2] = g->theta_rad[k];
      g->vu[4 * k + 1] = g->vu[4 * k + 3] = g->theta_rad[k + 1];
    }
    return AQ_OK;
  }
  if (p->shape == AQ_SHAPE_JOINTS) {
    memcpy(g->ji, p->joint_i, (n + 1) * sizeof *g->ji);
    memcpy(g->je, p->joint_e, (n + 1) * sizeof *g->je);
  } else {
    double *u = malloc((n + 1) * sizeof *u);
    int *c = malloc((n + 1) * sizeof *c);
    if (!u || !c) {
      free(u);
      free(c);
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    }
    aq_status st = aq_centre_joints(&g->centre, n, u, c, err);
    if (st != AQ_OK) {
      free(u);
      free(c);
      return st;
    }
    double h = 0.5 * p->thickness_m;
    for (size_t j = 0; j <= n; j++) {
      aq_centre_offset(&g->centre, c[j], u[j], -h, &g->ji[j], NULL);
      aq_centre_offset(&g->centre, c[j], u[j], h, &g->je[j], NULL);
    }
    for (size_t k = 0; k < n; k++) {
      g->vcurve[k] = c[k];
      g->vu[4 * k] = g->vu[4 * k + 2] = u[k];
      g->vu[4 * k + 1] = g->vu[4 * k + 3] = c[k + 1] == c[k] ? u[k + 1] : g->centre.u1[c[k]];
    }
    if (g->centre.ncurve == 2) {
      /* the crown joint: vertical, from where the halves' intrados meet to
       * where their extrados meet (curve 0 about (cx, 0), curve 1 about
       * (-cx, 0): x = cx + (r -+ h) cos u = 0) */
      size_t m = n / 2;
      double r = g->centre.r, cx = g->centre.cx;
      double ui = acos(-cx / (r - h)), ue = acos(-cx / (r + h));
      if (!(g->vu[4 * (m - 1)] < ui)) {
        /* the radial joint beside the crown reaches past x = 0 at the
         * intrados: at most uc / (uc - ui) voussoirs a half */
        double uc = g->centre.u1[0];
        size_t most = 2 * (size_t)floor(uc / (uc - ui) * (1 - 1e-12));
        free(u);
        free(c);
        return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "voussoirs",
                            "expected at most %zu voussoirs for a pointed arch this thick "
                            "(more put the joints beside the crown past the crown joint at "
                            "the intrados), got %zu",
                            most, n);
      }
      g->vu[4 * (m - 1) + 1] = ui;
      g->vu[4 * (m - 1) + 3] = ue;
      g->vu[4 * m] = AQ_PI - ui;
      g->vu[4 * m + 2] = AQ_PI - ue;
      g->vcurve[m] = 1;
      g->ji[m] = (aq_vec2){0, sqrt((r - h) * (r - h) - cx * cx)};
      g->je[m] = (aq_vec2){0, sqrt((r + h) * (r + h) - cx * cx)};
    }
    free(u);
    free(c);
  }
  for (size_t j = 0; j <= n; j++) {
    double dx = g->je[j].x - g->ji[j].x, dy = g->je[j].y - g->ji[j].y, l = hypot(dx, dy);
    if (!(l > 0))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "joints_file",
                          "expected joints of length > 0, got joint %zu of length 0", j);
    g->jo[j] = g->ji[j];
    g->ju[j] = (aq_vec2){dx / l, dy / l};
    g->jmid[j] = g->jhalf[j] = 0.5 * l;
  }
  return AQ_OK;
}

static aq_status check_params(const aq_arch_params *p, aq_error *err)
{
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    if (!(p->radius_m > 0) || !isfinite(p->radius_m))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "radius_m",
                          "expected a finite length > 0 m, got %g", p->radius_m);
    if (!(p->thickness_m > 0) || !isfinite(p->thickness_m))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "thickness_m",
                          "expected a finite length > 0 m, got %g", p->thickness_m);
    if (!(p->thickness_m < 2.0 * p->radius_m))
      return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "thickness_m",
                          "expected less than the diameter 2*radius_m = %g m, got %g",
                          2.0 * p->radius_m, p->thickness_m);
    if (!(p->embrace_rad > 0) || !(p->embrace_rad <= AQ_PI * (1 + 1e-15)))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "embrace_deg",
                          "expected an angle in (0, 180] deg, got %g",
                          p->embrace_rad / AQ_DEG_RAD);
  }
  if (p->voussoirs < 4)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "voussoirs",
                        "expected an integer >= 4, got %zu", p->voussoirs);
  if (!(p->density_kg_m3 > 0) || !isfinite(p->density_kg_m3))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "density_kg_m3",
                        "expected a finite density > 0 kg/m^3, got %g",
                        p->density_kg_m3);
  if (!(p->depth_m > 0) || !isfinite(p->depth_m))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "depth_m",
                        "expected a finite length > 0 m, got %g", p->depth_m);
  if (p->shape == AQ_SHAPE_JOINTS && (!p->joint_i || !p->joint_e))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "joints_file",
                        "expected the joints, got none");
  if (p->fill_density_kg_m3 != 0 &&
      (!(p->fill_density_kg_m3 > 0) || !isfinite(p->fill_density_kg_m3)))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "density_kg_m3",
                        "expected a finite fill density > 0 kg/m^3, got %g",
                        p->fill_density_kg_m3);
  return AQ_OK;
}

static size_t at_least_one(size_t n) { return n ? n : 1; }

static aq_status alloc_all(aq_geom *g, aq_error *err)
{
  size_t n = g->p.voussoirs;
  int ok = 1;
#define ALLOC(f, count) ok &= (g->f = calloc(at_least_one(count), sizeof *g->f)) != NULL
  ALLOC(theta_rad, n + 1);
  ALLOC(ji, n + 1);
  ALLOC(je, n + 1);
  ALLOC(jo, n + 1);
  ALLOC(ju, n + 1);
  ALLOC(jmid, n + 1);
  ALLOC(jhalf, n + 1);
  ALLOC(vous, n);
  ALLOC(outline_start, n + 1);
  ALLOC(fill_start, n + 1);
  ALLOC(mass, g->p.nmass);
  ALLOC(vcurve, n);
  ALLOC(vu, 4 * n);
  ALLOC(cum_m, n + 1);
  ALLOC(cum_mx, n + 1);
  ALLOC(cum_my, n + 1);
#undef ALLOC
  if (!ok)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  if (g->p.shape == AQ_SHAPE_JOINTS)
    for (int f = 0; f < 2; f++)
      if (g->p.face_start[f]) {
        size_t np = g->p.face_start[f][n];
        g->face_start[f] = malloc((n + 1) * sizeof *g->face_start[f]);
        g->face_pt[f] = malloc((np ? np : 1) * sizeof *g->face_pt[f]);
        if (!g->face_start[f] || !g->face_pt[f])
          return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        memcpy(g->face_start[f], g->p.face_start[f], (n + 1) * sizeof *g->face_start[f]);
        if (np)
          memcpy(g->face_pt[f], g->p.face_pt[f], np * sizeof *g->face_pt[f]);
      }
  return AQ_OK;
}

/* The most pieces a voussoir's loop or its fill's has (before cutting). */
static size_t max_loop(const aq_geom *g)
{
  size_t most = MAX_PIECES, n = g->p.voussoirs;
  if (g->p.shape == AQ_SHAPE_JOINTS)
    for (size_t k = 0; k < n; k++) {
      size_t m = 5;
      for (int f = 0; f < 2; f++)
        if (g->face_start[f])
          m += g->face_start[f][k + 1] - g->face_start[f][k];
      if (m > most)
        most = m;
    }
  return most;
}

/* Voussoirs, fills and outlines. */
static aq_status build_parts(aq_geom *g, aq_error *err)
{
  const aq_arch_params *p = &g->p;
  size_t n = p->voussoirs, cap = max_loop(g);
  piece *loop = malloc(cap * sizeof *loop);
  piece *cut = malloc(2 * cap * (CROSS_SAMPLES + 2) * sizeof *cut);
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(GL_POINTS);
  size_t nout = 0, nfill = 0, ocap = 0, fcap = 0;
  aq_status st = AQ_OK;
  int fill = p->fill_density_kg_m3 > 0;
  double rho_d = p->density_kg_m3 * p->depth_m, fill_d = p->fill_density_kg_m3 * p->depth_m;
  if (!loop || !cut || !gl) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (size_t k = 0; k < n; k++) {
    size_t nl = voussoir_loop(g, k, loop), ns = aq_region_sample_count(loop, nl);
    double area = 0;
    if (p->shape == AQ_SHAPE_CIRCULAR) {
      g->vous[k] = aq_sector_mass(g->r_i_m, g->r_e_m, g->theta_rad[k], g->theta_rad[k + 1],
                                  p->density_kg_m3, p->depth_m);
    } else {
      g->vous[k] = aq_region_mass(&g->centre, gl, loop, nl, rho_d, &area);
      if (!(area > 0)) {
        st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "joints_file",
                          "expected voussoirs of positive area (counter-clockwise from the "
                          "springing on the +x side), got voussoir %zu of area %.6g m^2",
                          k, area);
        goto done;
      }
    }
    g->stone_kg += g->vous[k].mass_kg;
    if (nout + ns > ocap) {
      ocap = 2 * (nout + ns) + 64;
      aq_vec2 *o = realloc(g->outline, ocap * sizeof *o);
      if (!o) {
        st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        goto done;
      }
      g->outline = o;
    }
    g->outline_start[k] = nout;
    nout += aq_region_sample(&g->centre, loop, nl, g->outline + nout);
    g->fill_start[k] = nfill;
    if (fill) {
      size_t nf = fill_loop(g, k, loop);
      nf = aq_region_cut_below(&g->centre, loop, nf, p->fill_level_m, cut);
      aq_mass fm = aq_region_mass(&g->centre, gl, cut, nf, fill_d, &area);
      if (area < -1e-12 * p->thickness_m * p->thickness_m) {
        st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "level_m",
                          "expected an extrados the fill lies on (its x decreasing from "
                          "joint %zu to %zu), got voussoir %zu's turning back (fill area "
                          "%.6g m^2)",
                          k, k + 1, k, area);
        goto done;
      }
      if (area > 0 && fm.mass_kg > 0) {
        g->vous[k] = aq_mass_add(g->vous[k], fm);
        g->fill_kg += fm.mass_kg;
        size_t nsf = aq_region_sample_count(cut, nf);
        if (nfill + nsf > fcap) {
          fcap = 2 * (nfill + nsf) + 64;
          aq_vec2 *f = realloc(g->fill, fcap * sizeof *f);
          if (!f) {
            st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
            goto done;
          }
          g->fill = f;
        }
        nfill += aq_region_sample(&g->centre, cut, nf, g->fill + nfill);
      }
    }
  }
  g->outline_start[n] = nout;
  g->fill_start[n] = nfill;
done:
  free(loop);
  free(cut);
  if (gl)
    gsl_integration_glfixed_table_free(gl);
  return st;
}

/* The springing level: the lower of the two springing joints' middles. */
static double springing_level(const aq_geom *g)
{
  size_t n = g->p.voussoirs;
  double a = 0.5 * (g->ji[0].y + g->je[0].y), b = 0.5 * (g->ji[n].y + g->je[n].y);
  return a < b ? a : b;
}

/* The geometry as stored (p->stored), copied: joints, voussoirs, outlines,
 * fill and point masses as they are. */
static aq_status from_stored(aq_geom *g, aq_error *err)
{
  const aq_arch_drawing *d = g->p.stored;
  size_t n = d->voussoirs;
  if (n < 4 || !d->joints || !d->parts || d->outline_start[0] != 0 ||
      (size_t)d->outline_start[n] != d->noutline || (size_t)d->fill_start[n] != d->nfill)
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                        "expected a stored geometry of at least 4 voussoirs with its outlines, "
                        "got %zu voussoirs", n);
  for (size_t k = 0; k < n; k++)
    if (d->outline_start[k] > d->outline_start[k + 1] || d->fill_start[k] > d->fill_start[k + 1] ||
        !(d->parts[4 * k] > 0))
      return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                          "expected voussoir %zu's mass > 0 and its outline's rows in order, "
                          "got neither", k);
  g->p.voussoirs = n;
  g->p.nmass = d->nmass;
  aq_status st = alloc_all(g, err);
  if (st != AQ_OK)
    return st;
  g->outline = malloc((d->noutline ? d->noutline : 1) * sizeof *g->outline);
  g->fill = malloc((d->nfill ? d->nfill : 1) * sizeof *g->fill);
  if (!g->outline || !g->fill)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  for (size_t j = 0; j <= n; j++) {
    const double *r = d->joints + 4 * j;
    g->ji[j] = (aq_vec2){r[0], r[1]};
    g->je[j] = (aq_vec2){r[2], r[3]};
    double dx = r[2] - r[0], dy = r[3] - r[1], l = hypot(dx, dy);
    if (!(l > 0))
      return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, "geometry",
                          "expected joints of length > 0, got joint %zu of length 0", j);
    g->jo[j] = g->ji[j];
    g->ju[j] = (aq_vec2){dx / l, dy / l};
    g->jmid[j] = g->jhalf[j] = 0.5 * l;
    g->outline_start[j] = (size_t)d->outline_start[j];
    g->fill_start[j] = (size_t)d->fill_start[j];
  }
  for (size_t k = 0; k < n; k++) {
    const double *r = d->parts + 4 * k;
    g->vous[k] = (aq_mass){r[0], {r[1], r[2]}, r[3]};
  }
  for (size_t i = 0; i < d->noutline; i++)
    g->outline[i] = (aq_vec2){d->outline[2 * i], d->outline[2 * i + 1]};
  for (size_t i = 0; i < d->nfill; i++)
    g->fill[i] = (aq_vec2){d->fill[2 * i], d->fill[2 * i + 1]};
  for (size_t i = 0; i < d->nmass; i++) {
    const double *r = d->mass + 4 * i;
    g->mass[i] = (aq_point_mass){"", (size_t)r[0], {r[1], r[2]}, r[3]};
    snprintf(g->mass[i].name, sizeof g->mass[i].name, "mass %zu", i);
  }
  g->stone_kg = d->stone_kg;
  g->fill_kg = d->fill_kg;
  g->point_kg = d->point_kg;
  free(g->theta_rad);
  g->theta_rad = NULL;
  return AQ_OK;
}

aq_status aq_geom_init(aq_geom *g, const aq_arch_params *p, aq_error *err)
{
  memset(g, 0, sizeof *g);
  if (p->stored) {
    g->p = *p;
    aq_status st = from_stored(g, err);
    if (st != AQ_OK) {
      aq_geom_free(g);
      return st;
    }
    goto sums;
  }
  aq_status st = check_params(p, err);
  if (st != AQ_OK)
    return st;
  size_t n = p->voussoirs;
  g->p = *p;
  if (p->shape == AQ_SHAPE_CIRCULAR) {
    g->r_i_m = p->radius_m - 0.5 * p->thickness_m;
    g->r_e_m = p->radius_m + 0.5 * p->thickness_m;
    double a = 0.5 * AQ_PI - 0.5 * p->embrace_rad;
    aq_centre_circle(&g->centre, p->radius_m, p->thickness_m, a, a + p->embrace_rad);
  } else if (p->shape != AQ_SHAPE_JOINTS) {
    st = aq_centre_init(&g->centre, p->shape, p->span_m, p->rise_m, p->thickness_m, err);
    if (st != AQ_OK)
      return st;
  }
  if ((st = alloc_all(g, err)) != AQ_OK || (st = place_joints(g, err)) != AQ_OK)
    goto fail;
  if (p->fill_density_kg_m3 > 0) {
    double lo = springing_level(g);
    if (!(p->fill_level_m > lo) || !isfinite(p->fill_level_m)) {
      st = aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "level_m",
                        "expected a fill level above the springings (y > %.6g m), got %g", lo,
                        p->fill_level_m);
      goto fail;
    }
  }
  if ((st = build_parts(g, err)) != AQ_OK || (st = aq_geom_add_masses(g, err)) != AQ_OK)
    goto fail;
  if (p->shape != AQ_SHAPE_CIRCULAR)
    free(g->theta_rad), g->theta_rad = NULL;
sums:
  n = g->p.voussoirs;
  g->cum_m[0] = g->cum_mx[0] = g->cum_my[0] = 0;
  for (size_t k = 0; k < n; k++) {
    g->cum_m[k + 1] = g->cum_m[k] + g->vous[k].mass_kg;
    g->cum_mx[k + 1] = g->cum_mx[k] + g->vous[k].mass_kg * g->vous[k].c.x;
    g->cum_my[k + 1] = g->cum_my[k] + g->vous[k].mass_kg * g->vous[k].c.y;
  }
  aq_mass all = aq_geom_body(g, 0, n);
  g->mass_kg = all.mass_kg;
  g->c = all.c;
  g->p.joint_i = g->p.joint_e = NULL;
  g->p.face_pt[0] = g->p.face_pt[1] = NULL;
  g->p.face_start[0] = g->p.face_start[1] = NULL;
  g->p.mass = NULL;
  g->p.stored = NULL;
  return AQ_OK;
fail:
  aq_geom_free(g);
  return st;
}

aq_vec2 aq_geom_joint_point(const aq_geom *g, size_t j, char face)
{
  return face == 'e' ? g->je[j] : g->ji[j];
}

aq_mass aq_geom_body(const aq_geom *g, size_t j0, size_t j1)
{
  aq_mass b = {0, {0, 0}, 0};
  double sx = 0, sy = 0;
  for (size_t k = j0; k < j1; k++) {
    b.mass_kg += g->vous[k].mass_kg;
    sx += g->vous[k].mass_kg * g->vous[k].c.x;
    sy += g->vous[k].mass_kg * g->vous[k].c.y;
  }
  if (b.mass_kg > 0) {
    b.c.x = sx / b.mass_kg;
    b.c.y = sy / b.mass_kg;
  }
  for (size_t k = j0; k < j1; k++) {
    double dx = g->vous[k].c.x - b.c.x, dy = g->vous[k].c.y - b.c.y;
    b.inertia_kgm2 += g->vous[k].inertia_kgm2 + g->vous[k].mass_kg * (dx * dx + dy * dy);
  }
  return b;
}
