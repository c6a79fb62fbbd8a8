/* workpath.c: the work path of one hinge set (path.h) with its tables.
 *
 * s = q_sign * q >= 0, where q_sign is the sign of q that opens H1 (and, for
 * an admissible set, every hinge).  Along s:
 *   x(s), y(s) = sum_b m_b (c_b(s) - c_b(0)) / m_T        (whole arch, m_T
 *                includes the fixed voussoirs, which do not move)
 *   M(s) = sum_b m_b |dc_b/ds|^2 + I_b (dphi_b/ds)^2        (docs/method.md sec. 4)
 *   lambda(s) = -act_sign (dy/ds) / (dx/ds)                  (virtual work,
 *                docs/method.md sec. 5: sum m_i lambda g dx_i = g sum m_i dy_i)
 *   act_sign = -sign(dx/ds at 0): the inertial force -m a_g pushes along +s
 *                when a_g has the sign act_sign.
 *   s_c: the first s > 0 where dy/ds = 0 (lambda = 0: the unloaded potential
 *        energy peaks, docs/method.md sec. 9), where the four-bar reaches its toggle,
 *        or where a hinge would close again, whichever comes first (located
 *        by bisection to round-off after a scan in steps of SCAN_STEP_RAD).
 *
 * The Hermite tables the path is evaluated from are built in
 * workpath_table.c, the Taylor leg's pieces in workpath_piece.c; both
 * share the path's inside through workpath_impl.h.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "workpath_impl.h"

#define SCAN_STEP_RAD 5e-4     /* scan for the end of the path */
#define SCAN_MAX_RAD 3.0       /* no mechanism rotates body 1 further than this */
#define TABLE_MAX_INTERVALS 20000 /* at most this many intervals (shipped arches need < 200): a
                                     path that needs more is refused, never tabulated for minutes */
#define S_SLACK_REL 1e-12      /* s within this (relative to s_c) outside [0, s_c] is clamped */

/* Exact values f[k][0..2] (value, d/ds, d2/ds2) of every tabled function. */
int aq_workpath_exact_f(const aq_workpath *w, double s, double f[NF][3],
                        aq_mech_state *stout)
{
  aq_mech_state st;
  int qs = w->path.q_sign;
  if (aq_mech_eval(&w->mech, (double)qs * s, &st) != 0)
    return -1;
  double mt = w->path.mass_kg;
  double X[4] = {0, 0, 0, 0}, Y[4] = {0, 0, 0, 0}, M[3] = {0, 0, 0};
  for (int b = 0; b < 3; b++) {
    double mb = w->mech.body[b].mass_kg, ib = w->mech.body[b].inertia_kgm2;
    aq_vec2 *c = st.c[b];
    double *p = st.phi[b];
    X[0] += mb * (c[0].x - w->c0[b].x);
    Y[0] += mb * (c[0].y - w->c0[b].y);
    X[1] += mb * c[1].x;
    Y[1] += mb * c[1].y;
    X[2] += mb * c[2].x;
    Y[2] += mb * c[2].y;
    X[3] += mb * c[3].x;
    Y[3] += mb * c[3].y;
    M[0] += mb * (c[1].x * c[1].x + c[1].y * c[1].y) + ib * p[1] * p[1];
    M[1] += 2.0 * (mb * (c[1].x * c[2].x + c[1].y * c[2].y) + ib * p[1] * p[2]);
    M[2] += 2.0 * (mb * (c[2].x * c[2].x + c[2].y * c[2].y + c[1].x * c[3].x +
                         c[1].y * c[3].y) +
                   ib * (p[2] * p[2] + p[1] * p[3]));
    double *bx = f[F_B0 + 3 * b], *by = f[F_B0 + 3 * b + 1], *bp = f[F_B0 + 3 * b + 2];
    bx[0] = c[0].x, bx[1] = qs * c[1].x, bx[2] = c[2].x;
    by[0] = c[0].y, by[1] = qs * c[1].y, by[2] = c[2].y;
    bp[0] = p[0], bp[1] = qs * p[1], bp[2] = p[2];
  }
  f[F_X][0] = X[0] / mt, f[F_X][1] = qs * X[1] / mt, f[F_X][2] = X[2] / mt;
  f[F_Y][0] = Y[0] / mt, f[F_Y][1] = qs * Y[1] / mt, f[F_Y][2] = Y[2] / mt;
  f[F_DX][0] = f[F_X][1], f[F_DX][1] = X[2] / mt, f[F_DX][2] = qs * X[3] / mt;
  f[F_DY][0] = f[F_Y][1], f[F_DY][1] = Y[2] / mt, f[F_DY][2] = qs * Y[3] / mt;
  f[F_M][0] = M[0], f[F_M][1] = qs * M[1], f[F_M][2] = M[2];
  if (stout)
    *stout = st;
  return 0;
}

void aq_workpath_fill_point(const aq_workpath *w, double f[NF][3], aq_path_point *p)
{
  p->x_m = f[F_X][0], p->dx_m = f[F_DX][0], p->d2x_m = f[F_DX][1];
  p->y_m = f[F_Y][0], p->dy_m = f[F_DY][0], p->d2y_m = f[F_DY][1];
  p->mgen_kgm2 = f[F_M][0];
  p->dmgen_kgm2 = f[F_M][1];
  p->lambda = -(double)w->path.act_sign * p->dy_m / p->dx_m;
  p->nbody = 3;
  for (int b = 0; b < 3; b++) {
    p->body[b].mass_kg = w->mech.body[b].mass_kg;
    p->body[b].inertia_kgm2 = w->mech.body[b].inertia_kgm2;
    p->body[b].x_m = f[F_B0 + 3 * b][0];
    p->body[b].dx_m = f[F_B0 + 3 * b][1];
    p->body[b].y_m = f[F_B0 + 3 * b + 1][0];
    p->body[b].dy_m = f[F_B0 + 3 * b + 1][1];
    p->body[b].phi_rad = f[F_B0 + 3 * b + 2][0];
    p->body[b].dphi = f[F_B0 + 3 * b + 2][1];
  }
}

/* s checked and clamped into [0, s_c]; -1 outside. */
int aq_workpath_clamp_s(const aq_workpath *w, double *s)
{
  double sc = w->path.s_c_rad, slack = S_SLACK_REL * sc;
  if (!w->path.admissible || !(*s >= -slack) || !(*s <= sc + slack))
    return -1;
  if (*s < 0)
    *s = 0;
  if (*s > sc)
    *s = sc;
  return 0;
}

static int eval_exact(const void *ctx, double s, aq_path_point *p)
{
  const aq_workpath *w = ctx;
  double f[NF][3];
  if (aq_workpath_clamp_s(w, &s) != 0 || aq_workpath_exact_f(w, s, f, NULL) != 0)
    return -1;
  aq_workpath_fill_point(w, f, p);
  return 0;
}

static int hinges_open(const aq_workpath *w, const aq_mech_state *st)
{
  double rel[4];
  aq_mech_hinge_rel(st, rel);
  for (int k = 0; k < 4; k++)
    if (!(w->mech.open[k] * rel[k] > 0))
      return 0;
  return 1;
}

/* 0: fine at s; else the reason it is past the end. */
static aq_end past_end(const aq_workpath *w, double s)
{
  double f[NF][3];
  aq_mech_state st;
  if (aq_workpath_exact_f(w, s, f, &st) != 0)
    return AQ_END_TOGGLE;
  if (!(f[F_Y][1] > 0))
    return AQ_END_PEAK;
  if (!hinges_open(w, &st))
    return AQ_END_HINGE;
  return AQ_END_NONE;
}

static void find_end(aq_workpath *w)
{
  double lo = 0, hi = 0;
  aq_end why = AQ_END_NONE;
  for (double s = SCAN_STEP_RAD; s <= SCAN_MAX_RAD; s += SCAN_STEP_RAD) {
    why = past_end(w, s);
    if (why != AQ_END_NONE) {
      hi = s;
      break;
    }
    lo = s;
  }
  if (why == AQ_END_NONE) {
    w->path.s_c_rad = lo;
    w->end = AQ_END_NONE;
    return;
  }
  for (int it = 0; it < 200 && hi - lo > 2 * __DBL_EPSILON__ * hi; it++) {
    double mid = 0.5 * (lo + hi);
    aq_end e = past_end(w, mid);
    if (e == AQ_END_NONE)
      lo = mid;
    else {
      hi = mid;
      why = e;
    }
  }
  w->path.s_c_rad = lo;
  w->end = why;
}

void aq_workpath_free(aq_workpath *w)
{
  if (!w)
    return;
  free(w->coef);
  free(w->piece);
  free(w->pbp);
  free(w->bp);
  free(w);
}

static const char *face_name(char f) { return f == 'e' ? "extrados" : "intrados"; }

/* A path of hs on g with its four-bar set up and its functions (tables,
 * exact, pieces) in place, nothing else computed, into *out. */
static aq_status path_alloc(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                            const char *name, aq_workpath **out, aq_error *err)
{
  *out = NULL;
  aq_workpath *w = calloc(1, sizeof *w);
  if (!w)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  aq_status st = aq_mech_init(&w->mech, g, hs, err);
  if (st != AQ_OK) {
    free(w);
    return st;
  }
  w->g = g;
  w->g_mps2 = g_mps2;
  snprintf(w->name, sizeof w->name, "%s", name ? name : "");
  aq_path *p = &w->path;
  p->name = w->name;
  p->eval = aq_workpath_eval_table;
  p->eval_exact = eval_exact;
  p->piece = aq_workpath_eval_piece;
  p->ctx = w;
  p->mass_kg = g->mass_kg;
  p->g_mps2 = g_mps2;
  p->q_sign = w->mech.open[0];
  *out = w;
  return AQ_OK;
}

aq_status aq_workpath_build(const aq_geom *g, const aq_hinge_set *hs,
                            double g_mps2, const char *name, aq_workpath **out,
                            aq_error *err)
{
  return aq_workpath_build_max(g, hs, g_mps2, name, TABLE_MAX_INTERVALS, out, err);
}

aq_status aq_workpath_build_max(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                                const char *name, size_t max_intervals, aq_workpath **out,
                                aq_error *err)
{
  aq_status st = path_alloc(g, hs, g_mps2, name, out, err);
  if (st != AQ_OK)
    return st;
  aq_workpath *w = *out;
  *out = NULL;
  w->max_n = max_intervals;
  aq_path *p = &w->path;
  p->act_sign = 1;
  p->admissible = 0;
  aq_mech_state s0;
  if (aq_mech_eval(&w->mech, 0.0, &s0) != 0) {
    snprintf(w->reason, sizeof w->reason, "the linkage does not close at s = 0");
    *out = w;
    return AQ_OK;
  }
  for (int b = 0; b < 3; b++)
    w->c0[b] = s0.c[b][0];
  double f[NF][3];
  aq_workpath_exact_f(w, 0.0, f, NULL);
  p->act_sign = f[F_X][1] > 0 ? -1 : 1;
  p->lambda0 = f[F_X][1] != 0 ? -(double)p->act_sign * f[F_Y][1] / f[F_X][1] : 0;
  /* first-order opening of every hinge: rates of the relative rotations */
  double rate[4] = {1.0, s0.phi[1][1] - 1.0, s0.phi[2][1] - s0.phi[1][1], -s0.phi[2][1]};
  for (int k = 0; k < 4; k++)
    if (!(w->mech.open[k] * p->q_sign * rate[k] > 0)) {
      snprintf(w->reason, sizeof w->reason,
               "hinge %d (joint %zu, %s) does not open when H1 opens", k + 1,
               hs->joint[k], face_name(hs->face[k]));
      *out = w;
      return AQ_OK;
    }
  if (!(p->lambda0 > 0) || !isfinite(p->lambda0)) {
    snprintf(w->reason, sizeof w->reason,
             "lambda0 = %.6g: the mechanism does not lift the arch's centroid",
             p->lambda0);
    *out = w;
    return AQ_OK;
  }
  aq_equil eq;
  aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, g_mps2};
  aq_error e2;
  aq_error_clear(&e2);
  if (aq_mech_equilibrium(&w->mech, &s0, &live, &eq, &e2) != AQ_OK) {
    snprintf(w->reason, sizeof w->reason, "singular equilibrium at s = 0");
    *out = w;
    return AQ_OK;
  }
  for (int k = 0; k < 4; k++)
    if (!(eq.normal[k] > 0)) {
      snprintf(w->reason, sizeof w->reason,
               "hinge %d (joint %zu, %s) in tension at s = 0 (normal force %.6g N)",
               k + 1, hs->joint[k], face_name(hs->face[k]), eq.normal[k]);
      *out = w;
      return AQ_OK;
    }
  double *ecc = malloc((g->p.voussoirs + 1) * sizeof *ecc);
  if (!ecc) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  w->thrust0 = aq_mech_thrust(&w->mech, &s0, &live, &eq, ecc, NULL);
  free(ecc);
  find_end(w);
  if (!(p->s_c_rad > 0) || w->end == AQ_END_NONE) {
    snprintf(w->reason, sizeof w->reason, "no end of the path found in (0, %g] rad",
             SCAN_MAX_RAD);
    *out = w;
    return AQ_OK;
  }
  p->admissible = 1;
  int tab = aq_workpath_build_tables(w);
  if (tab == -2 || tab == -3) {
    /* what ran out and where: the tables (or the pieces) halve an interval
     * until it meets its tolerance, so the count runs out where the path
     * varies fastest or where round-off keeps an error from halving */
    int pieces = tab == -3;
    double lambda0 = p->lambda0, s_c = p->s_c_rad, out_s = w->out_s, fine_s = w->fine_s;
    int depth = w->fine_depth;
    size_t max_n = w->max_n;
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "hinges",
                        "expected a work path that %s of at most %zu intervals resolve to "
                        "%g, got one that needs more: they ran out at s = %.6g rad of q_c = "
                        "%.6g rad; the finest, %d halvings of %s, is at s = %.6g rad "
                        "(lambda0 = %.6g)",
                        pieces ? "the Taylor leg's pieces (Chebyshev tails)"
                               : "the Hermite tables",
                        max_n, pieces ? PIECE_TAIL_TOL : TABLE_REL_TOL, out_s, s_c, depth,
                        pieces ? "[0, q_c]" : "one of the first 16", fine_s, lambda0);
  }
  if (tab != 0) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL,
                        "out of memory (or the linkage failed) building tables");
  }
  p->x_mono_rad = aq_workpath_x_mono(w);
  p->table_err = w->tab_err;
  *out = w;
  return AQ_OK;
}

const aq_path *aq_workpath_path(const aq_workpath *w) { return &w->path; }
const aq_mech *aq_workpath_mech(const aq_workpath *w) { return &w->mech; }
const char *aq_workpath_reason(const aq_workpath *w) { return w->reason; }
aq_end aq_workpath_end(const aq_workpath *w) { return w->end; }
size_t aq_workpath_table_size(const aq_workpath *w) { return w->n; }
size_t aq_workpath_piece_count(const aq_workpath *w) { return w->npc; }
double aq_workpath_table_error(const aq_workpath *w) { return w->tab_err; }
double aq_workpath_thrust0(const aq_workpath *w) { return w->thrust0; }

aq_status aq_workpath_equilibrium(const aq_workpath *w, double s, aq_equil *out,
                                  aq_error *err)
{
  aq_mech_state st;
  if (w->path.admissible && aq_workpath_clamp_s(w, &s) != 0)
    s = -1;
  if (!(s >= 0) || aq_mech_eval(&w->mech, (double)w->path.q_sign * s, &st) != 0)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "s",
                        "expected a position in [0, %g] rad, got %g",
                        w->path.s_c_rad, s);
  aq_live live = {AQ_LIVE_HORIZONTAL, w->path.act_sign, {0, 0}, 0, w->g_mps2};
  return aq_mech_equilibrium(&w->mech, &st, &live, out, err);
}

void aq_workpath_set_impact(aq_workpath *b, const aq_workpath *a)
{
  b->path.impact_vel_ratio = 0;
  if (!b->path.admissible)
    return; /* never entered */
  size_t n = b->g->p.voussoirs;
  aq_vec2 *ua = malloc(2 * n * sizeof *ua);
  double *wa = malloc(2 * n * sizeof *wa);
  double f[NF][3];
  if (ua && wa && aq_workpath_exact_f(b, 0.0, f, NULL) == 0 && f[F_M][0] > 0) {
    aq_mech_field0(&a->mech, a->path.q_sign, ua, wa);
    aq_mech_field0(&b->mech, b->path.q_sign, ua + n, wa + n);
    double d = aq_field_dot(b->g->vous, n, ua, wa, ua + n, wa + n);
    b->path.impact_vel_ratio = -d / f[F_M][0];
  }
  free(ua);
  free(wa);
}

/* ---- The built path as bytes (arch.c's aq_arch_tables_put and _get) ----
 * Everything aq_workpath_build computed past the four-bar, each double as
 * its bits: a path read back is the path built, bit for bit.  The four-bar
 * itself (aq_mech_init: closed forms from the geometry) is set up again. */
void aq_workpath_put(const aq_workpath *w, aq_bytes_out *b)
{
  const aq_path *p = &w->path;
  aq_bytes_put_i64(b, p->admissible);
  aq_bytes_put_i64(b, p->act_sign);
  aq_bytes_put_f64(b, p->lambda0);
  aq_bytes_put_f64(b, p->s_c_rad);
  aq_bytes_put_f64(b, p->impact_vel_ratio);
  aq_bytes_put_f64(b, p->x_mono_rad);
  for (int k = 0; k < 3; k++) {
    aq_bytes_put_f64(b, w->c0[k].x);
    aq_bytes_put_f64(b, w->c0[k].y);
  }
  aq_bytes_put_i64(b, w->end);
  aq_bytes_put_str(b, w->reason, sizeof w->reason);
  aq_bytes_put_f64(b, w->tab_err);
  aq_bytes_put_f64(b, w->thrust0);
  aq_bytes_put_i64(b, (int64_t)w->n);
  if (w->n) {
    aq_bytes_put(b, w->bp, (w->n + 1) * sizeof *w->bp);
    aq_bytes_put(b, w->coef, w->n * NF * 6 * sizeof *w->coef);
  }
  aq_bytes_put_i64(b, (int64_t)w->npc);
  if (w->npc) {
    aq_bytes_put(b, w->pbp, (w->npc + 1) * sizeof *w->pbp);
    aq_bytes_put(b, w->piece, w->npc * sizeof *w->piece);
  }
}

/* n + extra items of size bytes each from r into a new array *out
 * (NULL when n is 0; n is bounded by the caller); -1 when r cannot hold
 * them or out of memory. */
static int get_array(aq_bytes_in *r, size_t n, size_t extra, size_t size, void **out,
                     const char *what)
{
  *out = NULL;
  if (!n)
    return 0;
  size_t bytes = (n + extra) * size;
  if (r->bad || bytes > r->n - r->at ||
      !(*out = malloc(bytes))) {
    r->bad = r->bad ? r->bad : what;
    return -1;
  }
  return aq_bytes_get(r, *out, bytes, what);
}

aq_status aq_workpath_get(const aq_geom *g, const aq_hinge_set *hs, double g_mps2,
                          const char *name, aq_bytes_in *r, aq_workpath **out,
                          aq_error *err)
{
  aq_status st = path_alloc(g, hs, g_mps2, name, out, err);
  if (st != AQ_OK)
    return st;
  aq_workpath *w = *out;
  *out = NULL;
  aq_path *p = &w->path;
  p->admissible = (int)aq_bytes_get_int(r, 0, 1, "admissible");
  p->act_sign = aq_bytes_get_int(r, -1, 1, "act_sign") < 0 ? -1 : 1;
  p->lambda0 = aq_bytes_get_f64(r, "lambda0");
  p->s_c_rad = aq_bytes_get_f64(r, "s_c");
  p->impact_vel_ratio = aq_bytes_get_f64(r, "impact_vel_ratio");
  p->x_mono_rad = aq_bytes_get_f64(r, "x_mono");
  for (int k = 0; k < 3; k++) {
    w->c0[k].x = aq_bytes_get_f64(r, "c0");
    w->c0[k].y = aq_bytes_get_f64(r, "c0");
  }
  w->end = (aq_end)aq_bytes_get_int(r, AQ_END_PEAK, AQ_END_NONE, "end");
  aq_bytes_get_str(r, w->reason, sizeof w->reason, NULL, "reason");
  w->tab_err = p->table_err = aq_bytes_get_f64(r, "table_error");
  w->thrust0 = aq_bytes_get_f64(r, "thrust0");
  w->n = w->cap = (size_t)aq_bytes_get_int(r, 0, TABLE_MAX_INTERVALS, "table_n");
  void *bp, *coef, *pbp, *piece;
  get_array(r, w->n, 1, sizeof *w->bp, &bp, "breakpoints");
  w->bp = bp;
  get_array(r, w->n * NF * 6, 0, sizeof *w->coef, &coef, "coefficients");
  w->coef = coef;
  w->npc = w->pcap = (size_t)aq_bytes_get_int(r, 0, TABLE_MAX_INTERVALS, "pieces");
  get_array(r, w->npc, 1, sizeof *w->pbp, &pbp, "piece breakpoints");
  w->pbp = pbp;
  get_array(r, w->npc, 0, sizeof *w->piece, &piece, "pieces");
  w->piece = piece;
  for (size_t i = 0; i < w->npc && !r->bad; i++)
    if (w->piece[i].deg < 0 || w->piece[i].deg >= AQ_PIECE_MAX_DEG)
      r->bad = "piece degree";
  /* a path that may be integrated has its tables and pieces */
  if (!r->bad && p->admissible && (!w->n || !w->npc || !(p->s_c_rad > 0)))
    r->bad = "tables";
  if (r->bad) {
    aq_workpath_free(w);
    return aq_error_set(err, AQ_EFORMAT, NULL, -1, -1, name,
                        "expected a stored work path, got bytes that are not one (%s)",
                        r->bad);
  }
  *out = w;
  return AQ_OK;
}
