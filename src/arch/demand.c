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

/* Per entry and interval: the nine forms' cubics (n0 n1 n2 t0 t1 t2 e0 e1
 * e2), 4 power coefficients each; per interval besides: sddot's three,
 * 1/M and the moving bodies' centroid x, y (per m_T, absolute). */
enum { DT_NV = 9, DT_NX = 6, DT_NC = 4 };

struct aq_demand_table {
  size_t n;         /* voussoirs */
  size_t nf;        /* entries (aq_demand_nforms(n)) */
  size_t nint;      /* intervals */
  size_t stride;    /* doubles per interval: (nf DT_NV + DT_NX) DT_NC */
  double *bp;       /* nint + 1 breakpoints, rad */
  double *ih;       /* 1 / width of each interval, 1/rad */
  double *c;        /* nint * stride cubic coefficients in u = (s - bp[i]) ih[i] */
  double *bound;    /* nint * DT_BOUNDS (below) */
  aq_joint_form *entry; /* joint and hinge of each entry (forms unused) */
  double s_c;       /* rad */
  double mass_kg;   /* m_T, the forms' divisor */
  double err;       /* largest error measured against the exact forms, / tol scale */
  double scale;     /* the force scale of the tolerance (m/s^2 per m/s^2) */
  double w_ref;     /* sdot^2 / g of the reference energy, 1/m... rad^2/m */
};

/* Per interval, for the tracker's boxes: for each of the nine forms the
 * largest |coefficient function| over the interval and over every entry,
 * then the largest |d/ds| likewise, then the largest |d(1/M)/ds|. */
enum { DT_BOUNDS = 2 * DT_NV + 1 };

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

static double cubic_at(const double c[4], double u) { return c[0] + u * (c[1] + u * (c[2] + u * c[3])); }

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
      double e = fabs(cubic_at(c, us[q]) - B->v[q][k]) / B->tol[k];
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
  free(t->bound);
  free(t->entry);
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
  t->bound = malloc(t->nint * DT_BOUNDS * sizeof *t->bound);
  if (!t->bound) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    goto done;
  }
  for (size_t i = 0; i < t->nint; i++) {
    double *bd = t->bound + i * DT_BOUNDS;
    for (int q = 0; q < DT_BOUNDS; q++)
      bd[q] = 0;
    for (size_t j = 0; j < nf; j++)
      for (int q = 0; q < DT_NV; q++) {
        const double *c = t->c + i * t->stride + (j * DT_NV + q) * DT_NC;
        double val = fabs(c[0]) + fabs(c[1]) + fabs(c[2]) + fabs(c[3]);
        double der = (fabs(c[1]) + 2 * fabs(c[2]) + 3 * fabs(c[3])) * t->ih[i];
        bd[q] = fmax(bd[q], val);
        bd[DT_NV + q] = fmax(bd[DT_NV + q], der);
      }
    const double *c = t->c + i * t->stride + (nf * DT_NV + 3) * DT_NC;
    bd[2 * DT_NV] = (fabs(c[1]) + 2 * fabs(c[2]) + 3 * fabs(c[3])) * t->ih[i];
  }
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
      f[j].n[k] = cubic_at(c + k * DT_NC, u) * t->mass_kg;
      f[j].t[k] = cubic_at(c + (3 + k) * DT_NC, u) * t->mass_kg;
      f[j].e[k] = cubic_at(c + (6 + k) * DT_NC, u) * t->mass_kg;
    }
  }
  if (kin) {
    const double *c = C + t->nf * DT_NV * DT_NC;
    for (int k = 0; k < 3; k++)
      kin->sddot[k] = cubic_at(c + k * DT_NC, u);
    kin->mgen_kgm2 = 1.0 / cubic_at(c + 3 * DT_NC, u);
    kin->x_m = cubic_at(c + 4 * DT_NC, u);
    kin->y_m = cubic_at(c + 5 * DT_NC, u);
  }
  return 0;
}
double aq_demand_table_error(const aq_demand_table *t) { return t->err * DT_TOL; }

/* ---- the tracker ------------------------------------------------------- */

/* The tracker is told every state of a run (each leg's start, its end and
 * the walls it turned at) but evaluates an entry only when the state
 * leaves a region in which that entry cannot exceed the running maximum m
 * it was given (m only grows, so a region stays valid).
 *
 * At a fixed s the forms are linear in a = a_g/g and w = sdot^2/g, so
 * |X| <= m N (X: T or e) holds exactly on the intersection of two half
 * planes of (a, w).  Over a range of s about the anchor, each form moves
 * by at most ds (D0 + D1 |a| + D2 w), D the tables' bounds on the slopes
 * d/ds of its coefficients over the intervals the range spans; taking that
 * off m N - |X| leaves, for each sign of a, two half planes that hold over
 * the whole range: exact in the ground acceleration, which jumps from step
 * to step, and in the speed, bounded in s only, which moves smoothly.
 * w = 2 KE/(M g) is turned into KE/g with the bounds of 1/M over the range,
 * so that states are tested in the stepper's own terms (s, a/g, KE/g).
 *
 * The DM_WATCH entries nearest to m (at the last evaluation of every
 * entry) are watched one by one with their half planes over a few of the
 * last moves in s.  The others get one box: a wider range of s, a band of
 * KE/g, and the range of a/g in which all their half planes hold over the
 * band (a convex region's: the intersection of its ranges at the band's
 * two edges).  Leaving it evaluates every entry.  Each state is first
 * tried against one box inside every region of the set, both quantities:
 * six comparisons; the box is made again about the state when it leaves
 * it but stays inside the regions. */
#define DM_WATCH 3         /* entries watched one by one, per set and quantity */
#define DM_AMAX_PAD 2.0    /* the a/g range considered when none is given */
#define DM_MOVES 4.0       /* a watched entry's range spans this many of the last moves in s */
#define DM_REST_MOVES 8.0  /* the others' range and band span this many moves in s and KE/g */

/* a*A + k*B <= C, a = a_g/g, k = KE/g */
typedef struct {
  double A, B, C;
} hp;

typedef struct {
  double s0, s1; /* rad */
  double a0, a1; /* a/g */
  double k0, k1; /* KE/g */
} box;

typedef struct {
  int j;            /* entry */
  double s0, s1;    /* the range of s of its half planes */
  hp h[2][2];       /* [a >= 0, a < 0][+X, -X] */
} watch;

typedef struct {
  int valid;        /* 0: every entry is evaluated at the next state */
  int nw;
  watch w[DM_WATCH];
  box rest;         /* where none of the others exceeds the maximum */
} tier;

struct aq_demand {
  const aq_demand_table *tab[2];
  const aq_demand_table *(*get)(void *ctx, int set);
  void *get_ctx;
  int asked[2];     /* the table of set k was asked for */
  double mu_limit;  /* the friction coefficient, NAN: none */
  size_t iv[2];     /* the interval of each set's last evaluated state */
  tier tr[2][2];    /* [set][quantity: 0 |T|/N, 1 |e|/N at non-hinge joints] */
  box fast[2];      /* inside every region of the set */
  double g, ig;     /* the last gravity and its inverse */
  double amax;      /* the largest |a|/g of the run's steps */
  double max[2];
  size_t joint[2];
  double when[2];
  double over_s[2]; /* first time over the limit (mu_limit, 1), NAN: never */
  double mv_s, mv_k, prev_s, prev_k; /* moves in s and KE/g between slow states, smoothed */
  int moved, failed, done;
  int every;        /* 1: every entry at every state (the reference) */
  size_t samples, full, looks;
  size_t cap;       /* scratch entries */
  double *sv;       /* cap * 9 values of the forms at a state */
  double *sr;       /* cap * 2: each entry's range of a/g */
  aq_demand_least_fn least; /* the statics' least friction, NULL: none */
  void *least_ctx;
  int still;        /* a run at rest throughout: the statics' demand below */
  double still_mu, still_s, still_slide;
  size_t still_joint;
};

static const box no_box = {NAN, NAN, NAN, NAN, NAN, NAN};

aq_demand *aq_demand_alloc(const aq_demand_table *(*get)(void *ctx, int set), void *ctx,
                           aq_error *err)
{
  aq_demand *d = calloc(1, sizeof *d);
  if (!d) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    return NULL;
  }
  d->get = get;
  d->get_ctx = ctx;
  d->mu_limit = NAN;
  aq_demand_begin(d, NAN);
  return d;
}

void aq_demand_free(aq_demand *d)
{
  if (!d)
    return;
  free(d->sv);
  free(d->sr);
  free(d);
}

void aq_demand_set_every(aq_demand *d, int on) { d->every = on != 0; }

void aq_demand_set_limit(aq_demand *d, double mu)
{
  d->mu_limit = isfinite(mu) && mu > 0 ? mu : NAN;
}

void aq_demand_begin(aq_demand *d, double amax)
{
  d->amax = isfinite(amax) && amax >= 0 ? amax : DM_AMAX_PAD;
  for (int k = 0; k < 2; k++) {
    d->iv[k] = 0;
    d->max[k] = 0;
    d->joint[k] = 0;
    d->when[k] = NAN;
    d->over_s[k] = NAN;
    d->fast[k] = no_box;
    for (int q = 0; q < 2; q++)
      d->tr[k][q].valid = 0;
  }
  d->g = d->ig = NAN;
  d->mv_s = d->mv_k = 0;
  d->prev_s = d->prev_k = NAN;
  d->moved = d->failed = d->done = 0;
  d->samples = d->full = d->looks = 0;
  d->still = 0;
}

/* The table of set k (asked for once per tracker), or NULL. */
static const aq_demand_table *table(aq_demand *d, int k)
{
  if (!d->asked[k]) {
    d->asked[k] = 1;
    d->tab[k] = d->get(d->get_ctx, k);
    size_t nf = d->tab[k] ? d->tab[k]->nf : 0;
    if (nf > d->cap) {
      double *a = realloc(d->sv, nf * DT_NV * sizeof *a);
      if (a)
        d->sv = a;
      double *b = a ? realloc(d->sr, 2 * nf * sizeof *b) : NULL;
      if (!b) {
        d->tab[k] = NULL;
        return NULL;
      }
      d->sr = b;
      d->cap = nf;
    }
  }
  return d->tab[k];
}

/* The interval of s in t, from the last one i. */
static size_t locate(const aq_demand_table *t, size_t i, double s)
{
  if (i >= t->nint)
    i = 0;
  while (i > 0 && s < t->bp[i])
    i--;
  while (i + 1 < t->nint && s > t->bp[i + 1])
    i++;
  return i;
}

static double dmax(double a, double b) { return a > b ? a : b; }
static double dmin(double a, double b) { return a < b ? a : b; }

/* A state's value v of quantity q at entry j: the running maximum and the
 * first time over the limit. */
static void note(aq_demand *d, int q, double v, const aq_demand_table *t, size_t j, double t_s)
{
  if (v > d->max[q]) {
    d->max[q] = v;
    d->joint[q] = t->entry[j].joint;
    d->when[q] = t_s;
  }
  double lim = q == 0 ? d->mu_limit : 1.0;
  if (v > lim && isnan(d->over_s[q]))
    d->over_s[q] = t_s;
}

/* One state of a set: its interval and place in it, s, a/g, KE/g, w. */
typedef struct {
  size_t i;
  double u, s, al, kg, w, t_s;
} state;

static int inside(const box *b, double s, double al, double kg)
{
  return al >= b->a0 && al <= b->a1 && s >= b->s0 && s <= b->s1 && kg >= b->k0 && kg <= b->k1;
}

/* A range of s about a state: what the forms' coefficients may move by
 * per unit of |s - s0| (dn, dx, three columns each), and 1/M's range. */
typedef struct {
  double s0, s1, ds, rm0, rm1;
  double dn[3], dx[3];
} span;

static span make_span(const aq_demand_table *t, int q, const state *x, double rm, double ds)
{
  span p;
  size_t lo = x->i > 0 ? x->i - 1 : 0, hi = x->i + 1 < t->nint ? x->i + 1 : x->i;
  p.s0 = dmax(x->s - ds, t->bp[lo]);
  p.s1 = dmin(x->s + ds, t->bp[hi + 1]);
  p.ds = dmax(x->s - p.s0, p.s1 - x->s);
  double drm = 0;
  int xo = q == 0 ? 3 : 6;
  for (int c = 0; c < 3; c++)
    p.dn[c] = p.dx[c] = 0;
  for (size_t k = lo; k <= hi; k++) {
    const double *b = t->bound + k * DT_BOUNDS + DT_NV;
    for (int c = 0; c < 3; c++) {
      p.dn[c] = dmax(p.dn[c], b[c]);
      p.dx[c] = dmax(p.dx[c], b[xo + c]);
    }
    drm = dmax(drm, b[DT_NV]);
  }
  p.rm0 = rm - drm * p.ds, p.rm1 = rm + drm * p.ds;
  return p;
}

/* The half plane, for sign g of a (0: a >= 0, 1: a < 0) and sign sx of X,
 * in which an entry of forms n[3], x[3] at the anchor stays below m over
 * span p. */
static hp half_plane(const span *p, const double *n, const double *x, double m, int g, double sx)
{
  double sa = g ? -1.0 : 1.0, ds = p->ds;
  hp h;
  h.A = sx * x[1] + sa * ds * (p->dx[1] + m * p->dn[1]) - m * n[1];
  double bw = sx * x[2] + ds * (p->dx[2] + m * p->dn[2]) - m * n[2];
  h.B = 2 * (bw > 0 ? bw * p->rm1 : bw * p->rm0); /* w = 2 (KE/g) / M */
  h.C = m * n[0] - sx * x[0] - ds * (p->dx[0] + m * p->dn[0]);
  if (!(p->rm0 > 0))
    h.A = h.B = 0, h.C = -1; /* nowhere */
  return h;
}

/* Narrow [*lo, *hi] (a/g, for sign g of a) to where h holds at both k0
 * and k1 (so between them: a convex region). */
static void a_cut_c(double A, double c, double *lo, double *hi)
{
  /* most half planes do not cut the range: two products tell */
  if (A * *hi <= c && A * *lo <= c)
    return;
  if (A > 0)
    *hi = dmin(*hi, c / A);
  else if (A < 0)
    *lo = dmax(*lo, c / A);
  else
    *lo = INFINITY; /* A = 0 and C - B k < 0: nowhere */
}

static void a_cut(const hp *h, double k0, double k1, double *lo, double *hi)
{
  double c0 = h->C - h->B * k0, c1 = h->C - h->B * k1;
  a_cut_c(h->A, c0 < c1 ? c0 : c1, lo, hi);
}

/* The a/g range, about al, over the band [k0, k1] in which every half
 * plane h[g][i] (i < nh, per sign g of a) holds; NAN when al is not in it. */
static void a_range(hp *const h[2], int nh, double al, double k0, double k1, double amax,
                    double *a0, double *a1)
{
  double lo[2] = {0, -amax}, hi[2] = {amax, 0};
  for (int g = 0; g < 2; g++)
    for (int i = 0; i < nh; i++)
      a_cut(&h[g][i], k0, k1, &lo[g], &hi[g]);
  int g = al < 0;
  *a0 = lo[g], *a1 = hi[g];
  if (!(al >= lo[g] && al <= hi[g])) {
    *a0 = *a1 = NAN;
    return;
  }
  if (g == 0 && lo[0] == 0 && lo[1] <= hi[1] && hi[1] == 0) /* reaches across 0 */
    *a0 = lo[1];
  if (g == 1 && hi[1] == 0 && lo[0] <= hi[0] && lo[0] == 0)
    *a1 = hi[0];
}

static int in_watch(const watch *W, double s, double al, double kg)
{
  if (!(s >= W->s0 && s <= W->s1))
    return 0;
  const hp *h = W->h[al < 0];
  return h[0].A * al + h[0].B * kg <= h[0].C && h[1].A * al + h[1].B * kg <= h[1].C;
}

/* The moves in s and KE/g between slow states, smoothed. */
static void moves(aq_demand *d, double s, double kg)
{
  if (d->prev_s == d->prev_s && (s != d->prev_s || kg != d->prev_k)) {
    d->mv_s = 0.5 * (d->mv_s + fabs(s - d->prev_s));
    d->mv_k = 0.5 * (d->mv_k + fabs(kg - d->prev_k));
  }
  d->prev_s = s, d->prev_k = kg;
}

/* Watched entry W of quantity q's half planes at x over its range. */
static void watch_at(aq_demand *d, const aq_demand_table *t, int q, watch *W, const state *x,
                     double rm, const double *n, const double *xv)
{
  span p = make_span(t, q, x, rm, DM_MOVES * d->mv_s);
  W->s0 = p.s0, W->s1 = p.s1;
  for (int g = 0; g < 2; g++)
    for (int e = 0; e < 2; e++)
      W->h[g][e] = half_plane(&p, n, xv, d->max[q], g, e ? -1.0 : 1.0);
}

/* Evaluate watched entry W of quantity q at x, note it and give it new
 * half planes. */
static void look(aq_demand *d, const aq_demand_table *t, int q, watch *W, const state *x,
                 double rm)
{
  d->looks++;
  const double *c = t->c + x->i * t->stride + (size_t)W->j * DT_NV * DT_NC;
  int xo = q == 0 ? 3 : 6;
  double n[3], xv[3];
  for (int k = 0; k < 3; k++) {
    n[k] = cubic_at(c + k * DT_NC, x->u);
    xv[k] = cubic_at(c + (xo + k) * DT_NC, x->u);
  }
  double N = n[0] + x->al * n[1] + x->w * n[2];
  double X = fabs(xv[0] + x->al * xv[1] + x->w * xv[2]);
  note(d, q, N > 0 ? X / N : INFINITY, t, (size_t)W->j, x->t_s);
  if (!isinf(d->max[q]))
    watch_at(d, t, q, W, x, rm, n, xv);
}

/* Every entry of set k at x: maxima, then the watched entries and the box
 * of the others, for both quantities. */
static void full(aq_demand *d, const aq_demand_table *t, int k, const state *x, double rm)
{
  const double *C = t->c + x->i * t->stride;
  size_t nf = t->nf;
  d->full++;
  for (size_t j = 0; j < nf; j++) {
    const double *c = C + j * DT_NV * DT_NC;
    double *v = d->sv + j * DT_NV;
    for (int q = 0; q < DT_NV; q++)
      v[q] = cubic_at(c + q * DT_NC, x->u);
    double N = v[0] + x->al * v[1] + x->w * v[2];
    double T = fabs(v[3] + x->al * v[4] + x->w * v[5]);
    double E = fabs(v[6] + x->al * v[7] + x->w * v[8]);
    note(d, 0, N > 0 ? T / N : INFINITY, t, j, x->t_s);
    if (t->entry[j].hinge < 0)
      note(d, 1, N > 0 ? E / N : INFINITY, t, j, x->t_s);
  }
  double kb = DM_REST_MOVES * d->mv_k;
  double k0 = dmax(0, x->kg - kb), k1 = x->kg + kb;
  for (int q = 0; q < 2; q++) {
    tier *R = &d->tr[k][q];
    R->valid = 0;
    double m = d->max[q];
    if (isinf(m))
      continue;
    int xo = q == 0 ? 3 : 6;
    /* each entry's range of a/g about the state (or, for an entry already
     * over m at the state, an empty one) over the others' range of s and
     * band of KE/g */
    span p = make_span(t, q, x, rm, DM_REST_MOVES * d->mv_s);
    int g = x->al < 0;
    double *lo = d->sr, *hi = d->sr + nf;
    /* w over the band, and the span's slope terms */
    double wl = 2 * k0 * p.rm0, wh = 2 * k1 * p.rm1, am = d->amax;
    double e0 = p.ds * (p.dx[0] + m * p.dn[0]), e1 = p.ds * (p.dx[1] + m * p.dn[1]) * am,
           e2 = p.ds * (p.dx[2] + m * p.dn[2]) * wh;
    for (size_t j = 0; j < nf; j++) {
      lo[j] = -INFINITY, hi[j] = INFINITY;
      if (q == 1 && t->entry[j].hinge >= 0)
        continue;
      const double *v = d->sv + j * DT_NV;
      /* m N - |X| over the whole band and range, bounded below: most
       * entries stay under m everywhere there */
      double nlo = v[0] - fabs(v[1]) * am + dmin(v[2] * wl, v[2] * wh);
      double xhi = fabs(v[xo]) + fabs(v[xo + 1]) * am + fabs(v[xo + 2]) * wh;
      if (m * nlo - xhi - e0 - e1 - e2 >= 0 && p.rm0 > 0)
        continue;
      double l[2] = {0, -d->amax}, h[2] = {d->amax, 0};
      for (int e = 0; e < 2; e++) { /* both signs of a share B and C */
        double sx = e ? -1.0 : 1.0;
        hp h0 = half_plane(&p, v, v + xo, m, 0, sx);
        double A1 = p.rm0 > 0 ? sx * v[xo + 1] - p.ds * (p.dx[1] + m * p.dn[1]) - m * v[1] : 0;
        double c0 = h0.C - h0.B * k0, c1 = h0.C - h0.B * k1, c = c0 < c1 ? c0 : c1;
        a_cut_c(h0.A, c, &l[0], &h[0]);
        a_cut_c(A1, c, &l[1], &h[1]);
      }
      lo[j] = l[g], hi[j] = h[g];
      if (g == 0 && l[0] == 0 && l[1] <= h[1] && h[1] == 0) /* reaches across 0 */
        lo[j] = l[1];
      if (g == 1 && h[1] == 0 && l[0] <= h[0] && l[0] == 0)
        hi[j] = h[0];
      if (!(x->al >= lo[j] && x->al <= hi[j]))
        lo[j] = hi[j] = NAN;
    }
    /* watched: those whose ranges bind the others' nearest to the state
     * (an empty range first), the DM_WATCH smallest rooms in one pass, the
     * first entry first among equal rooms; a room of 2 amax or more binds
     * nothing */
    int np = 0, bj[DM_WATCH];
    double br[DM_WATCH];
    for (size_t j = 0; j < nf; j++) {
      if (q == 1 && t->entry[j].hinge >= 0)
        continue;
      double r = lo[j] == lo[j] ? dmin(x->al - lo[j], hi[j] - x->al) : -INFINITY;
      if (!(r < 2 * d->amax) || (np == DM_WATCH && !(r < br[np - 1])))
        continue;
      int w = np < DM_WATCH ? np++ : np - 1;
      for (; w > 0 && r < br[w - 1]; w--)
        br[w] = br[w - 1], bj[w] = bj[w - 1];
      br[w] = r, bj[w] = (int)j;
    }
    for (int w = 0; w < np; w++) { /* the watched leave the others' range free */
      R->w[w].j = bj[w];
      lo[bj[w]] = -INFINITY, hi[bj[w]] = INFINITY;
    }
    R->nw = np;
    box *b = &R->rest;
    b->s0 = p.s0, b->s1 = p.s1, b->k0 = k0, b->k1 = k1;
    b->a0 = -d->amax, b->a1 = d->amax;
    for (size_t j = 0; j < nf; j++) {
      if (q == 1 && t->entry[j].hinge >= 0)
        continue;
      if (!(lo[j] <= hi[j])) { /* one of the others is over m here: no box */
        *b = no_box;
        break;
      }
      b->a0 = dmax(b->a0, lo[j]), b->a1 = dmin(b->a1, hi[j]);
    }
    for (int w = 0; w < np; w++) {
      const double *v = d->sv + (size_t)R->w[w].j * DT_NV;
      watch_at(d, t, q, &R->w[w], x, rm, v, v + xo);
    }
    R->valid = 1;
  }
}

/* A box about x inside every region of set k: the band of KE/g a few of
 * the last moves about x, the others' boxes, and the range of a/g in which
 * the watched entries' half planes hold over that band. */
static void make_fast(aq_demand *d, int k, const state *x)
{
  double kb = DM_MOVES * d->mv_k;
  box f = {-INFINITY, INFINITY, -INFINITY, INFINITY, dmax(0, x->kg - kb), x->kg + kb};
  for (int q = 0; q < 2; q++) {
    const tier *R = &d->tr[k][q];
    if (isinf(d->max[q]))
      continue;
    const box *b = &R->rest;
    f.s0 = dmax(f.s0, b->s0), f.s1 = dmin(f.s1, b->s1);
    f.a0 = dmax(f.a0, b->a0), f.a1 = dmin(f.a1, b->a1);
    f.k0 = dmax(f.k0, b->k0), f.k1 = dmin(f.k1, b->k1);
    for (int w = 0; w < R->nw; w++) {
      const watch *W = &R->w[w];
      hp h0[2] = {W->h[0][0], W->h[0][1]}, h1[2] = {W->h[1][0], W->h[1][1]};
      hp *hs[2] = {h0, h1};
      double a0, a1;
      a_range(hs, 2, x->al, f.k0, f.k1, d->amax, &a0, &a1);
      if (!(a0 <= a1)) { /* the state is not inside: no box */
        d->fast[k] = no_box;
        return;
      }
      f.s0 = dmax(f.s0, W->s0), f.s1 = dmin(f.s1, W->s1);
      f.a0 = dmax(f.a0, a0), f.a1 = dmin(f.a1, a1);
    }
  }
  if (!inside(&f, x->s, x->al, x->kg))
    f = no_box;
  d->fast[k] = f;
}

/* State (s, al, kg) of set k outside its fast box. */
static void slow(aq_demand *d, const aq_demand_table *t, int k, double s, double al, double kg,
                 double t_s)
{
  state x;
  x.i = d->iv[k] = locate(t, d->iv[k], s);
  x.u = (s - t->bp[x.i]) * t->ih[x.i];
  x.s = s, x.al = al, x.kg = kg, x.t_s = t_s;
  double rm = cubic_at(t->c + x.i * t->stride + (t->nf * DT_NV + 3) * DT_NC, x.u);
  x.w = 2.0 * kg * rm;
  moves(d, s, kg);
  int all = d->every;
  for (int q = 0; q < 2 && !all; q++) {
    all = !isinf(d->max[q]) && (!d->tr[k][q].valid || !inside(&d->tr[k][q].rest, s, al, kg));
  }
  if (all) {
    full(d, t, k, &x, rm);
  } else {
    for (int q = 0; q < 2; q++) {
      tier *R = &d->tr[k][q];
      for (int w = 0; w < R->nw && !isinf(d->max[q]); w++)
        if (!in_watch(&R->w[w], s, al, kg))
          look(d, t, q, &R->w[w], &x, rm);
    }
  }
  d->done = isinf(d->max[0]) && isinf(d->max[1]);
  make_fast(d, k, &x);
}

/* The table of set k, and 1/g for g; NULL when there is nothing to do. */
static const aq_demand_table *ready(aq_demand *d, int k, double g)
{
  d->moved = 1;
  if (d->failed || d->done)
    return NULL;
  const aq_demand_table *t = table(d, k);
  if (!t) {
    d->failed = 1;
    return NULL;
  }
  if (g != d->g) {
    d->g = g;
    d->ig = 1.0 / g;
  }
  return t;
}

void aq_demand_at(aq_demand *d, int k, double s, double ke_j, double a_mps2, double g_mps2,
                  double t_s)
{
  const aq_demand_table *t = ready(d, k, g_mps2);
  if (!t)
    return;
  d->samples++;
  double al = a_mps2 * d->ig, kg = ke_j * d->ig;
  if (d->every || !inside(&d->fast[k], s, al, kg))
    slow(d, t, k, s, al, kg, t_s);
}

void aq_demand_leg(aq_demand *d, int k, double s, double ke_j, int dir, size_t rev,
                   double a_mps2, double g_mps2, double t_s)
{
  const aq_demand_table *t = ready(d, k, g_mps2);
  if (!t)
    return;
  double al = a_mps2 * d->ig, kg = ke_j * d->ig;
  /* the walls the leg turned at (one behind the end, then the other):
   * sdot^2 / g falls at 2 sddot / g per unit of s (d(sdot^2)/ds = 2 sddot),
   * so from the end the wall is at s - w / (2 sddot / g), to second order
   * in the distance, which is within the leg's travel */
  for (size_t r = 0; r < rev && r < 2 && kg > 0 && !d->done; r++) {
    int toward = r == 0 ? -dir : dir;
    size_t i = d->iv[k] = locate(t, d->iv[k], s);
    double u = (s - t->bp[i]) * t->ih[i];
    const double *c = t->c + i * t->stride + t->nf * DT_NV * DT_NC;
    double w = 2.0 * kg * cubic_at(c + 3 * DT_NC, u);
    double sg = cubic_at(c, u) + al * cubic_at(c + DT_NC, u) + w * cubic_at(c + 2 * DT_NC, u);
    double sw = s - w / (2 * sg);
    if (!((sw - s) * toward > 0))
      continue;
    sw = sw < 0 ? 0 : sw > t->s_c ? t->s_c : sw;
    d->samples++;
    if (d->every || !inside(&d->fast[k], sw, al, 0))
      slow(d, t, k, sw, al, 0, t_s);
  }
  d->samples++;
  if (!d->done && (d->every || !inside(&d->fast[k], s, al, kg)))
    slow(d, t, k, s, al, kg, t_s);
}

int aq_demand_fast_box(const aq_demand *d, int k, double out[6])
{
  const box *f = &d->fast[k];
  out[0] = f->s0, out[1] = f->s1, out[2] = f->a0, out[3] = f->a1, out[4] = f->k0, out[5] = f->k1;
  return f->s0 <= f->s1 && f->a0 <= f->a1 && f->k0 <= f->k1;
}

double aq_demand_max(const aq_demand *d, int q) { return d->max[q ? 1 : 0]; }

/* ---- a run in which the arch never moves (docs/demand.md) ---- */

void aq_demand_set_least(aq_demand *d, aq_demand_least_fn least, void *ctx)
{
  d->least = least;
  d->least_ctx = ctx;
}

/* Step i's load of direction sgn: sgn a / (g + a_v), a and a_v scaled. */
static double still_load(const aq_steps *st, size_t i, double scale, double vscale,
                         double g, int sgn)
{
  double gv = st->av_mps2 ? g + vscale * st->av_mps2[i] : g;
  return sgn * scale * st->a_mps2[i] / gv;
}

/* The first step i < n_end whose load of direction sgn is at least lam
 * (n_end: none).  Without a vertical acceleration the quiet index skips
 * the steps below a bound loosened by 1e-12 (relative) and the exact load
 * decides. */
static size_t still_first(const aq_steps *st, size_t n_end, double scale, double vscale,
                          double g, int sgn, double lam)
{
  size_t i = 0;
  int index = !st->av_mps2 && scale != 0 && lam > 0;
  double c = lam * g / (sgn * scale) * (1 - 1e-12);
  double lo = sgn * scale > 0 ? -INFINITY : c, hi = sgn * scale > 0 ? c : INFINITY;
  for (; i < n_end; i++) {
    if (index && (i = aq_steps_next_outside(st, i, lo, hi)) >= n_end)
      break;
    if (still_load(st, i, scale, vscale, g, sgn) >= lam)
      return i;
  }
  return n_end;
}

void aq_demand_still(aq_demand *d, const aq_steps *steps, size_t n_end, double scale,
                     double vscale, double g_mps2)
{
  if (d->moved || !d->least || n_end == 0 || n_end > steps->n)
    return;
  /* each direction's peak load and its first step */
  double lam[2] = {0, 0};
  if (!steps->av_mps2 && steps->nblock) { /* from the quiet index */
    double hi = -INFINITY, lo = INFINITY;
    for (size_t b = 0; b < steps->nblock; b++) {
      hi = fmax(hi, steps->block_max_mps2[b]);
      lo = fmin(lo, steps->block_min_mps2[b]);
    }
    lam[1] = fmax(scale * (scale >= 0 ? hi : lo) / g_mps2, 0);
    lam[0] = fmax(-scale * (scale >= 0 ? lo : hi) / g_mps2, 0);
  } else {
    for (size_t i = 0; i < n_end; i++)
      for (int k = 0; k < 2; k++)
        lam[k] = fmax(lam[k], still_load(steps, i, scale, vscale, g_mps2, 2 * k - 1));
  }
  double mu = NAN, t_s = NAN;
  size_t joint = 0;
  for (int k = 0; k < 2; k++) {
    size_t j = 0;
    double m = d->least(d->least_ctx, 2 * k - 1, lam[k], &j);
    if (isnan(m))
      return;
    size_t i = lam[k] > 0 ? still_first(steps, n_end, scale, vscale, g_mps2, 2 * k - 1, lam[k])
                          : 0;
    double t = aq_steps_t(steps, i < n_end ? i : 0);
    if (isnan(mu) || m > mu || (m == mu && t < t_s))
      mu = m, t_s = t, joint = j;
  }
  d->still = 1;
  d->still_mu = mu;
  d->still_joint = joint;
  d->still_s = t_s;
  d->still_slide = NAN;
  if (!(mu > d->mu_limit))
    return;
  /* the first step whose load needs more than the limit: in each direction
   * the least load that does (the least friction is nondecreasing in the
   * load), found by bisection, then the first step that reaches it */
  for (int k = 0; k < 2; k++) {
    double lo = 0, hi = lam[k];
    if (!(d->least(d->least_ctx, 2 * k - 1, hi, NULL) > d->mu_limit))
      continue;
    if (d->least(d->least_ctx, 2 * k - 1, 0, NULL) > d->mu_limit)
      hi = 0; /* at rest already */
    for (int it = 0; it < 200 && hi > 0 && lo < hi; it++) {
      double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi)
        break;
      if (d->least(d->least_ctx, 2 * k - 1, mid, NULL) > d->mu_limit)
        hi = mid;
      else
        lo = mid;
    }
    size_t i = hi > 0 ? still_first(steps, n_end, scale, vscale, g_mps2, 2 * k - 1, hi) : 0;
    if (i < n_end) {
      double t = aq_steps_t(steps, i);
      if (isnan(d->still_slide) || t < d->still_slide)
        d->still_slide = t;
    }
  }
}

void aq_demand_get(const aq_demand *d, aq_demand_result *r)
{
  r->mu_max = r->ecc_max = NAN;
  r->mu_joint = r->ecc_joint = 0;
  r->mu_time_s = r->ecc_time_s = r->ecc_over_s = r->slide_s = NAN;
  r->samples = d->samples;
  r->full = d->full;
  r->looks = d->looks;
  if (d->still) {
    r->mu_max = d->still_mu;
    r->mu_joint = d->still_joint;
    r->mu_time_s = d->still_s;
    r->slide_s = d->still_slide;
    return;
  }
  if (!d->moved || d->failed)
    return;
  r->mu_max = d->max[0];
  r->mu_joint = d->joint[0];
  r->mu_time_s = d->when[0];
  r->ecc_max = d->max[1];
  r->ecc_joint = d->joint[1];
  r->ecc_time_s = d->when[1];
  r->ecc_over_s = d->over_s[1];
  r->slide_s = d->over_s[0];
}
