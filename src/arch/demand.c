/* demand.c: the forces across every joint of a hinge set in motion (demand.h).
 *
 * Each body b of the four-bar (kinematics.c) turns by phi_b(q), q = q_sign s,
 * so a point fixed in it at r from its pivot P_b has the acceleration
 *     acc = P_b'' qd^2 + P_b' qdd + phi_b'' qd^2 J r - phi_b'^2 qd^2 r + phi_b' qdd J r
 * (' = d/dq, qd = dq/dt, qdd = d2q/dt2, J the +90 degree rotation; only
 * body 2's pivot H2' moves: P' = J v1, P'' = -v1, v1 = H2' - H1).  With the
 * ground accelerating by a along +x, every mass m carries the loads
 * (-m a, -m g) and the inertia force -m acc, every body the couple
 * -I (phi' qdd + phi'' qd^2) (d'Alembert).  The balance of the three bodies
 * (forces, and moments about each body's first hinge, as the paper's eq. (3)
 * in kinematics.c) is nine equations for the eight hinge reactions and qdd:
 * solved for the three load cases g = 1, a = 1 and qd^2 = 1, it gives the
 * reactions and qdd as linear forms in z = (g, a, qd^2) (sdot^2 = qd^2,
 * sddot = q_sign qdd).  qdd so found is the equation of motion's
 * (eom.h): the ninth equation is the balance of virtual powers.
 *
 * The force across a joint inside a body (or inside the fixed parts beyond
 * H1 and H4) is then the balance of the voussoirs between it and the
 * nearest hinge on one side, as aq_mech_thrust_line does for the static
 * load, with the inertia forces added; one sweep per part accumulates them.
 */
#include "demand.h"
#include "demand_tab.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static aq_vec2 v2(double x, double y)
{
  aq_vec2 v = {x, y};
  return v;
}
static aq_vec2 add(aq_vec2 a, aq_vec2 b) { return v2(a.x + b.x, a.y + b.y); }
static aq_vec2 sub(aq_vec2 a, aq_vec2 b) { return v2(a.x - b.x, a.y - b.y); }
static aq_vec2 scl(double s, aq_vec2 a) { return v2(s * a.x, s * a.y); }
static aq_vec2 perp(aq_vec2 a) { return v2(-a.y, a.x); }
static double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }
static aq_vec2 rot(double c, double s, aq_vec2 a) { return v2(c * a.x - s * a.y, s * a.x + c * a.y); }

/* Solve A X = B (9 unknowns, 3 right-hand sides) by Gaussian elimination
 * with partial pivoting; A and B are overwritten, X in B.  -1 if singular. */
static int solve9(double A[9][9], double B[9][3])
{
  for (int c = 0; c < 9; c++) {
    int p = c;
    for (int r = c + 1; r < 9; r++)
      if (fabs(A[r][c]) > fabs(A[p][c]))
        p = r;
    if (!(fabs(A[p][c]) > 0))
      return -1;
    if (p != c) {
      for (int k = 0; k < 9; k++) {
        double t = A[c][k];
        A[c][k] = A[p][k], A[p][k] = t;
      }
      for (int k = 0; k < 3; k++) {
        double t = B[c][k];
        B[c][k] = B[p][k], B[p][k] = t;
      }
    }
    for (int r = c + 1; r < 9; r++) {
      double f = A[r][c] / A[c][c];
      if (f == 0)
        continue;
      for (int k = c; k < 9; k++)
        A[r][k] -= f * A[c][k];
      for (int k = 0; k < 3; k++)
        B[r][k] -= f * B[c][k];
    }
  }
  for (int c = 8; c >= 0; c--)
    for (int k = 0; k < 3; k++) {
      double s = B[c][k];
      for (int j = c + 1; j < 9; j++)
        s -= A[c][j] * B[j][k];
      B[c][k] = s / A[c][c];
    }
  for (int c = 0; c < 9; c++)
    for (int k = 0; k < 3; k++)
      if (!isfinite(B[c][k]))
        return -1;
  return 0;
}

/* The running balance of a sub-body: force (tx, ty) and moment about the
 * origin m0, each a form in z. */
typedef struct {
  double tx[3], ty[3], m0[3];
} sums;

/* One part of the arch as its voussoirs move: rotation (cos, sin) from the
 * undeformed shape, pivot then and now, the pivot's derivatives and the
 * rotation's, per dq; fixed parts have none. */
typedef struct {
  int moving;
  double c, s;
  aq_vec2 piv0, piv, pv1, pv2;
  double p1, p2;
} part;

/* Add voussoir v of part P to S, qdd being the form qdd[3]. */
static void add_vous(const aq_geom *g, const part *P, size_t v, const double qdd[3], sums *S)
{
  double mv = g->vous[v].mass_kg, iv = g->vous[v].inertia_kgm2;
  aq_vec2 c = g->vous[v].c;
  double fx[3] = {0, -mv, 0}, fy[3] = {-mv, 0, 0}, cpl[3] = {0, 0, 0};
  if (P->moving) {
    aq_vec2 r = rot(P->c, P->s, sub(c, P->piv0));
    c = add(P->piv, r);
    aq_vec2 c1 = add(P->pv1, scl(P->p1, perp(r)));                            /* dc/dq */
    aq_vec2 c2 = sub(add(P->pv2, scl(P->p2, perp(r))), scl(P->p1 * P->p1, r)); /* d2c/dq2 */
    for (int k = 0; k < 3; k++) {
      double ax = c1.x * qdd[k] + (k == 2 ? c2.x : 0);
      double ay = c1.y * qdd[k] + (k == 2 ? c2.y : 0);
      fx[k] -= mv * ax;
      fy[k] -= mv * ay;
      cpl[k] = -iv * (P->p1 * qdd[k] + (k == 2 ? P->p2 : 0));
    }
  }
  for (int k = 0; k < 3; k++) {
    S->tx[k] += fx[k];
    S->ty[k] += fy[k];
    S->m0[k] += c.x * fy[k] - c.y * fx[k] + cpl[k];
  }
}

/* Start S with the force sign * H (forms hx, hy) acting at point p. */
static void start_sums(sums *S, double sign, const double hx[3], const double hy[3], aq_vec2 p)
{
  for (int k = 0; k < 3; k++) {
    S->tx[k] = sign * hx[k];
    S->ty[k] = sign * hy[k];
    S->m0[k] = p.x * S->ty[k] - p.y * S->tx[k];
  }
}

/* The forms of joint j of part P from the balance S of the sub-body on its
 * clockwise side (sigma = 1) or counter-clockwise side (sigma = -1). */
static void joint_forms(const aq_geom *g, const part *P, size_t j, double sigma, const sums *S,
                        aq_joint_form *f)
{
  aq_vec2 o = g->jo[j], u = g->ju[j];
  if (P->moving) {
    o = add(P->piv, rot(P->c, P->s, sub(o, P->piv0)));
    u = rot(P->c, P->s, u);
  }
  aq_vec2 nrm = perp(u), mid = add(o, scl(g->jmid[j], u));
  f->joint = j;
  f->hinge = -1;
  for (int k = 0; k < 3; k++) {
    aq_vec2 t = v2(S->tx[k], S->ty[k]);
    f->n[k] = sigma * (nrm.x * t.x + nrm.y * t.y);
    f->t[k] = u.x * t.x + u.y * t.y;
    f->e[k] = sigma * (S->m0[k] - cross(mid, t)) / g->jhalf[j];
  }
}

/* The forms of hinge k's reaction hx, hy (on the counter-clockwise body)
 * on the face of joint j turned by (c, s). */
static void hinge_forms(const aq_geom *g, size_t j, int k, double c, double s, const double hx[3],
                        const double hy[3], aq_joint_form *f)
{
  aq_vec2 u = rot(c, s, g->ju[j]), nrm = perp(u);
  f->joint = j;
  f->hinge = k;
  for (int i = 0; i < 3; i++) {
    f->n[i] = nrm.x * hx[i] + nrm.y * hy[i];
    f->t[i] = u.x * hx[i] + u.y * hy[i];
    f->e[i] = 0;
  }
}

int aq_demand_forms(const aq_mech *m, int q_sign, double s, aq_joint_form *f, aq_demand_kin *kin)
{
  aq_mech_state st;
  if (aq_mech_eval(m, (double)q_sign * s, &st) != 0)
    return -1;
  const aq_geom *g = m->g;
  const size_t n = g->p.voussoirs, *J = m->hs.joint;
  aq_vec2 hc[4] = {m->h[0], st.h2, st.h3, m->h[3]};
  double A[9][9], B[9][3];
  memset(A, 0, sizeof A);
  memset(B, 0, sizeof B);
  for (int b = 0; b < 3; b++) {
    double mb = m->body[b].mass_kg, ib = m->body[b].inertia_kgm2;
    aq_vec2 rc = sub(st.c[b][0], hc[b]), d = sub(hc[b + 1], hc[b]);
    aq_vec2 c1 = st.c[b][1], c2 = st.c[b][2];
    double p1 = st.phi[b][1], p2 = st.phi[b][2];
    int r = 3 * b;
    /* sum Fx: h_b - h_{b+1} - mb (a + c1.x qdd + c2.x qd^2) = 0 */
    A[r][2 * b] = 1, A[r][2 * b + 2] = -1, A[r][8] = -mb * c1.x;
    B[r][0] = 0, B[r][1] = mb, B[r][2] = mb * c2.x;
    /* sum Fy: v_b - v_{b+1} - mb (g + c1.y qdd + c2.y qd^2) = 0 */
    A[r + 1][2 * b + 1] = 1, A[r + 1][2 * b + 3] = -1, A[r + 1][8] = -mb * c1.y;
    B[r + 1][0] = mb, B[r + 1][1] = 0, B[r + 1][2] = mb * c2.y;
    /* moments about H_b: d x -(h, v)_{b+1} + rc x (loads) - ib (p1 qdd + p2 qd^2) = 0 */
    A[r + 2][2 * b + 2] = d.y, A[r + 2][2 * b + 3] = -d.x;
    A[r + 2][8] = -mb * cross(rc, c1) - ib * p1;
    B[r + 2][0] = mb * rc.x, B[r + 2][1] = -mb * rc.y, B[r + 2][2] = mb * cross(rc, c2) + ib * p2;
  }
  if (kin) { /* M = sum_b m_b |dc_b/dq|^2 + I_b (dphi_b/dq)^2 (docs/method.md sec. 4) */
    double mg = 0, x = 0, y = 0;
    for (int b = 0; b < 3; b++) {
      mg += m->body[b].mass_kg * (st.c[b][1].x * st.c[b][1].x + st.c[b][1].y * st.c[b][1].y) +
            m->body[b].inertia_kgm2 * st.phi[b][1] * st.phi[b][1];
      x += m->body[b].mass_kg * st.c[b][0].x;
      y += m->body[b].mass_kg * st.c[b][0].y;
    }
    kin->mgen_kgm2 = mg;
    kin->x_m = x / g->mass_kg;
    kin->y_m = y / g->mass_kg;
  }
  if (solve9(A, B) != 0)
    return -1;
  double qdd[3] = {B[8][0], B[8][1], B[8][2]};
  if (kin)
    for (int k = 0; k < 3; k++)
      kin->sddot[k] = (double)q_sign * qdd[k];
  double hx[4][3], hy[4][3];
  for (int h = 0; h < 4; h++)
    for (int k = 0; k < 3; k++)
      hx[h][k] = B[2 * h][k], hy[h][k] = B[2 * h + 1][k];
  /* the parts: fixed (+x side), bodies 0..2, fixed (-x side) */
  part P[3], fixed = {0, 1, 0, {0, 0}, {0, 0}, {0, 0}, {0, 0}, 0, 0};
  aq_vec2 v1 = sub(st.h2, m->h[0]);
  aq_vec2 piv0[3] = {m->h[0], m->h[1], m->h[3]}, piv[3] = {m->h[0], st.h2, m->h[3]};
  for (int b = 0; b < 3; b++) {
    P[b].moving = 1;
    P[b].c = cos(st.phi[b][0]), P[b].s = sin(st.phi[b][0]);
    P[b].piv0 = piv0[b], P[b].piv = piv[b];
    P[b].pv1 = b == 1 ? perp(v1) : v2(0, 0);
    P[b].pv2 = b == 1 ? scl(-1.0, v1) : v2(0, 0);
    P[b].p1 = st.phi[b][1], P[b].p2 = st.phi[b][2];
  }
  sums S;
  /* +x fixed part: joints J0-1 down to 0, the voussoirs j..J0-1 with -H1 */
  start_sums(&S, -1.0, hx[0], hy[0], hc[0]);
  for (size_t j = J[0]; j-- > 0;) {
    add_vous(g, &fixed, j, qdd, &S);
    joint_forms(g, &fixed, j, -1.0, &S, &f[j]);
  }
  /* the bodies: joints inside body b, the voussoirs J_b..j-1 with +H_b */
  for (int b = 0; b < 3; b++) {
    start_sums(&S, 1.0, hx[b], hy[b], hc[b]);
    for (size_t j = J[b] + 1; j < J[b + 1]; j++) {
      add_vous(g, &P[b], j - 1, qdd, &S);
      joint_forms(g, &P[b], j, 1.0, &S, &f[j]);
    }
  }
  /* -x fixed part: joints J3+1..n, the voussoirs J3..j-1 with +H4 */
  start_sums(&S, 1.0, hx[3], hy[3], hc[3]);
  for (size_t j = J[3] + 1; j <= n; j++) {
    add_vous(g, &fixed, j - 1, qdd, &S);
    joint_forms(g, &fixed, j, 1.0, &S, &f[j]);
  }
  /* the hinges: the face of the counter-clockwise body at joint J_k, then
   * that of the clockwise body */
  for (int k = 0; k < 4; k++) {
    double cc = k < 3 ? P[k].c : 1, sc = k < 3 ? P[k].s : 0;
    double cw = k > 0 ? P[k - 1].c : 1, sw = k > 0 ? P[k - 1].s : 0;
    hinge_forms(g, J[k], k, cc, sc, hx[k], hy[k], &f[J[k]]);
    hinge_forms(g, J[k], k, cw, sw, hx[k], hy[k], &f[n + 1 + (size_t)k]);
  }
  return 0;
}

/* ---- tables ------------------------------------------------------------ */

/* Power coefficients of the cubic through f(0), f(1/4), f(3/4), f(1). */
static void cubic_fit(const double f[4], double c[4])
{
  /* Lagrange basis on 0, 1/4, 3/4, 1 expanded in powers of u */
  static const double L[4][4] = {
      /* L0 = (u - 1/4)(u - 3/4)(u - 1) / (-3/16) */
      {1.0, -19.0 / 3.0, 32.0 / 3.0, -16.0 / 3.0},
      /* L1 = u (u - 3/4)(u - 1) / (3/32) */
      {0.0, 8.0, -56.0 / 3.0, 32.0 / 3.0},
      /* L2 = u (u - 1/4)(u - 1) / (-3/32) */
      {0.0, -8.0 / 3.0, 40.0 / 3.0, -32.0 / 3.0},
      /* L3 = u (u - 1/4)(u - 3/4) / (3/16) */
      {0.0, 1.0, -16.0 / 3.0, 16.0 / 3.0},
  };
  for (int k = 0; k < 4; k++)
    c[k] = f[0] * L[0][k] + f[1] * L[1][k] + f[2] * L[2][k] + f[3] * L[3][k];
}


/* Values of every tabled function at s: nf * DT_NV forms / m_T, then
 * sddot's three, 1/M, x and y.  0, or -1 (the forms fail at s). */
static int node_values(const aq_mech *m, int q_sign, double mass_kg, double s, size_t nf,
                       aq_joint_form *f, double *v)
{
  aq_demand_kin kin;
  if (aq_demand_forms(m, q_sign, s, f, &kin) != 0 || !(kin.mgen_kgm2 > 0))
    return -1;
  for (size_t j = 0; j < nf; j++)
    for (int k = 0; k < 3; k++) {
      v[j * DT_NV + k] = f[j].n[k] / mass_kg;
      v[j * DT_NV + 3 + k] = f[j].t[k] / mass_kg;
      v[j * DT_NV + 6 + k] = f[j].e[k] / mass_kg;
    }
  for (int k = 0; k < 3; k++)
    v[nf * DT_NV + k] = kin.sddot[k];
  v[nf * DT_NV + 3] = 1.0 / kin.mgen_kgm2;
  v[nf * DT_NV + 4] = kin.x_m;
  v[nf * DT_NV + 5] = kin.y_m;
  return 0;
}

typedef struct {
  const aq_mech *m;
  int q_sign;
  double mass_kg;
  size_t nv;          /* values per position */
  aq_joint_form *f;   /* scratch */
  double *tol;        /* nv: the absolute tolerance of each value */
  double *v[5];       /* scratch values: u = 1/4, 3/4, 1/8, 1/2, 7/8 */
  aq_demand_table *t;
  size_t cap;
  int failed;         /* 1: out of memory or the forms failed */
} build_ctx;

/* Append [a, b] with the cubics through va (s = a), v[0], v[1], vb (s = b). */
static void append(build_ctx *B, double a, double b, const double *va, const double *vb)
{
  aq_demand_table *t = B->t;
  if (t->nint == B->cap) {
    size_t cap = B->cap ? 2 * B->cap : 32;
    double *bp = realloc(t->bp, (cap + 1) * sizeof *bp);
    if (bp)
      t->bp = bp;
    double *ih = bp ? realloc(t->ih, cap * sizeof *ih) : NULL;
    if (ih)
      t->ih = ih;
    double *c = ih ? realloc(t->c, cap * t->stride * sizeof *c) : NULL;
    if (!c) {
      B->failed = 1;
      return;
    }
    t->c = c;
    B->cap = cap;
  }
  size_t i = t->nint++;
  t->bp[i] = a;
  t->bp[i + 1] = b;
  t->ih[i] = 1.0 / (b - a);
  double *c = t->c + i * t->stride;
  for (size_t k = 0; k < B->nv; k++) {
    double f[4] = {va[k], B->v[0][k], B->v[1][k], vb[k]};
    cubic_fit(f, c + DT_NC * k);
  }
}

#define DT_TOL 1e-8       /* target error of the tables, relative to their scale */
#define DT_N0 8            /* initial equal intervals */
#define DT_MAX_DEPTH 24    /* halvings of an initial interval at most */
#define DT_MAX_INTERVALS 2048

/* Tabulate [a, b] (values va, vb at its ends), halving until the cubics
 * are within the tolerance at u = 1/8, 1/2, 7/8. */
static void refine(build_ctx *B, double a, double b, const double *va, const double *vb, int depth)
{
  if (B->failed)
    return;
  const double us[5] = {0.25, 0.75, 0.125, 0.5, 0.875};
  double h = b - a;
  for (int q = 0; q < 5; q++)
    if (node_values(B->m, B->q_sign, B->mass_kg, a + us[q] * h, B->t->nf, B->f, B->v[q]) != 0) {
      B->failed = 1;
      return;
    }
  double worst = 0;
  for (size_t k = 0; k < B->nv; k++) {
    double f[4] = {va[k], B->v[0][k], B->v[1][k], vb[k]}, c[4];
    cubic_fit(f, c);
    for (int q = 2; q < 5; q++) {
      double e = fabs(aq_dt_cubic(c, us[q]) - B->v[q][k]) / B->tol[k];
      if (!(e <= worst))
        worst = isnan(e) ? INFINITY : e;
    }
  }
  if (worst <= 1 || depth >= DT_MAX_DEPTH || B->t->nint + 2 > DT_MAX_INTERVALS) {
    if (worst > B->t->err)
      B->t->err = worst;
    append(B, a, b, va, vb);
    return;
  }
  size_t nv = B->nv;
  double *mid = malloc(nv * sizeof *mid);
  if (!mid) {
    B->failed = 1;
    return;
  }
  memcpy(mid, B->v[3], nv * sizeof *mid);
  refine(B, a, a + 0.5 * h, va, mid, depth + 1);
  refine(B, a + 0.5 * h, b, mid, vb, depth + 1);
  free(mid);
}

void aq_demand_table_free(aq_demand_table *t)
{
  if (!t)
    return;
  free(t->bp);
  free(t->ih);
  free(t->c);
  free(t->entry);
  aq_dg_free(t->grid);
  free(t);
}

aq_status aq_demand_table_build(const aq_mech *m, const aq_path *p, aq_demand_table **out,
                                aq_error *err)
{
  *out = NULL;
  if (!p->admissible || !(p->s_c_rad > 0))
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, p->name,
                        "expected an admissible hinge set, got one that is not");
  size_t n = m->g->p.voussoirs, nf = aq_demand_nforms(n), nv = nf * DT_NV + DT_NX;
  aq_demand_table *t = calloc(1, sizeof *t);
  build_ctx B = {m, p->q_sign, p->mass_kg, nv, NULL, NULL, {NULL}, t, 0, 0};
  double *v0 = NULL, *v1 = NULL;
  if (t) {
    t->n = n, t->nf = nf, t->stride = nv * DT_NC, t->s_c = p->s_c_rad, t->mass_kg = p->mass_kg;
    t->entry = malloc(nf * sizeof *t->entry);
    B.f = malloc(nf * sizeof *B.f);
    B.tol = malloc(nv * sizeof *B.tol);
    v0 = malloc(nv * sizeof *v0);
    v1 = malloc(nv * sizeof *v1);
    for (int q = 0; q < 5; q++)
      B.v[q] = malloc(nv * sizeof *B.v[q]);
  }
  int ok = t && t->entry && B.f && B.tol && v0 && v1;
  for (int q = 0; ok && q < 5; q++)
    ok = B.v[q] != NULL;
  aq_status st = AQ_OK;
  if (!ok) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    goto done;
  }
  if (node_values(m, p->q_sign, p->mass_kg, 0.0, nf, t->entry, v0) != 0) {
    st = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "expected joint forces at s = 0, got a singular balance");
    goto done;
  }
  /* the scales of the tolerance: forces per unit g of the whole arch's
   * weight at rest; the sdot^2 column against w_ref, the sdot^2 / g that
   * carries the energy of collapse m_T g y(s_c) at s = 0 */
  aq_path_point pc;
  double w_ref = 1, y_c = 0;
  if (p->eval_exact(p->ctx, p->s_c_rad, &pc) == 0)
    y_c = pc.y_m;
  if (y_c > 0)
    w_ref = 2.0 * p->mass_kg * y_c * v0[nf * DT_NV + 3];
  double scale = 0, sdd_scale = fabs(v0[nf * DT_NV]) + fabs(v0[nf * DT_NV + 1]);
  for (size_t j = 0; j < nf; j++)
    scale = fmax(scale, fabs(v0[j * DT_NV]));
  t->scale = scale;
  t->w_ref = w_ref;
  t->lambda0 = p->lambda0;
  t->ke_ref = y_c > 0 ? p->mass_kg * y_c : 0;
  /* x, y: against the centroid's rise over the path (its energy of
   * collapse per unit weight) */
  double len = y_c > 0 ? y_c : p->s_c_rad;
  for (size_t k = 0; k < nv; k++) {
    size_t col = k < nf * DT_NV ? k % 3 : k - nf * DT_NV;
    double s = k < nf * DT_NV ? scale : col < 3 ? sdd_scale : col == 3 ? v0[nf * DT_NV + 3] : len;
    B.tol[k] = DT_TOL * s * (col == 2 ? 1.0 / w_ref : 1.0);
  }
  for (int i = 0; i < DT_N0 && !B.failed; i++) {
    double a = p->s_c_rad * i / DT_N0, b = i + 1 == DT_N0 ? p->s_c_rad : p->s_c_rad * (i + 1) / DT_N0;
    if (node_values(m, p->q_sign, p->mass_kg, b, nf, B.f, v1) != 0) {
      B.failed = 1;
      break;
    }
    refine(&B, a, b, v0, v1, 0);
    double *x = v0;
    v0 = v1, v1 = x;
  }
  if (B.failed) {
    st = aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, p->name,
                      "expected joint forces along the path, got a singular balance "
                      "(or out of memory)");
    goto done;
  }
  t->grid = aq_dg_build(t);
  *out = t;
  t = NULL;
done:
  aq_demand_table_free(t);
  free(B.f);
  free(B.tol);
  free(v0);
  free(v1);
  for (int q = 0; q < 5; q++)
    free(B.v[q]);
  return st;
}

size_t aq_demand_table_intervals(const aq_demand_table *t) { return t->nint; }

int aq_demand_table_forms(const aq_demand_table *t, double s, aq_joint_form *f, aq_demand_kin *kin)
{
  if (!(s >= 0 && s <= t->s_c))
    return -1;
  size_t i = 0, lo = 0, hi = t->nint;
  while (hi - lo > 1) { /* the interval holding s */
    size_t mid = (lo + hi) / 2;
    if (s < t->bp[mid])
      hi = mid;
    else
      lo = mid;
  }
  i = lo;
  double u = (s - t->bp[i]) * t->ih[i];
  const double *C = t->c + i * t->stride;
  for (size_t j = 0; j < t->nf; j++) {
    const double *c = C + j * DT_NV * DT_NC;
    f[j] = t->entry[j];
    for (int k = 0; k < 3; k++) {
      f[j].n[k] = aq_dt_cubic(c + k * DT_NC, u) * t->mass_kg;
      f[j].t[k] = aq_dt_cubic(c + (3 + k) * DT_NC, u) * t->mass_kg;
      f[j].e[k] = aq_dt_cubic(c + (6 + k) * DT_NC, u) * t->mass_kg;
    }
  }
  if (kin) {
    const double *c = C + t->nf * DT_NV * DT_NC;
    for (int k = 0; k < 3; k++)
      kin->sddot[k] = aq_dt_cubic(c + k * DT_NC, u);
    kin->mgen_kgm2 = 1.0 / aq_dt_cubic(c + 3 * DT_NC, u);
    kin->x_m = aq_dt_cubic(c + 4 * DT_NC, u);
    kin->y_m = aq_dt_cubic(c + 5 * DT_NC, u);
  }
  return 0;
}
double aq_demand_table_error(const aq_demand_table *t) { return t->err * DT_TOL; }
