/* kinematics.c: the exact four-bar H1-H2-H3-H4 and the paper's eq. (3).
 *
 * Closure (docs/method.md sec. 1, replacing the paper's eq. (6)): H2' is H2 rotated
 * about H1 by q; H3' is the intersection of the circle of radius l23 about
 * H2' and the circle of radius l34 about H4, on the branch continuous from
 * q = 0 (the side of the line H2'H4 on which H3 lies; the branch can only
 * change at the toggle, where H2', H3', H4 are collinear).
 *
 * Derivatives (implicit differentiation of the loop): with the current link
 * vectors v1 = H2'-H1, v2 = H3'-H2', v3 = H4-H3' (v1+v2+v3 constant),
 * dv_k/dq = phi_k' J v_k (J: rotation by +90 deg, phi_1' = 1) and a = phi_2',
 * b = phi_3':
 *   a  v2 + b  v3 = -v1
 *   a' v2 + b' v3 = -J (v1 + a^2 v2 + b^2 v3)
 *   a'' v2 + b'' v3 = v1 + a^3 v2 + b^3 v3 - 3 J (a a' v2 + b b' v3)
 * each a 2x2 system with determinant v2 x v3 (zero at the toggle).
 * A body point r from its pivot P (H1, H2', H4) turning with phi:
 *   r' = phi' J r,  r'' = phi'' J r - phi'^2 r,
 *   r''' = phi''' J r - 3 phi' phi'' r - phi'^3 J r,
 * plus, for body 2, the motion of H2' (J v1, -v1, -J v1).
 *
 * Hinge opening: at a hinge on the extrados point of joint j, the block on
 * the counter-clockwise side turning by w relative to the block on the
 * clockwise side moves its intrados corner by -w t (tangential, clockwise),
 * into the other block, for w > 0: an extrados hinge opens for w < 0, an
 * intrados hinge for w > 0 (tested in tests/test_arch_kinematics.c).
 *
 * Equilibrium: eq. (3) of G. L. Stockdale, V. Sarhosis, G. Milani,
 * "Work-path approach seismic modelling of hinge-controlled masonry arches",
 * written here as force and moment balances of each body (moments about its
 * first hinge, as the paper), unknowns (h1 v1 h2 v2 h3 v3 h4 v4 lambda), the
 * reaction (h_k, v_k) being the force on the body on the counter-clockwise
 * side of hinge k, in the deformed geometry.
 */
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model.h"

static aq_vec2 v2(double x, double y)
{
  aq_vec2 v = {x, y};
  return v;
}
static aq_vec2 add(aq_vec2 a, aq_vec2 b) { return v2(a.x + b.x, a.y + b.y); }
static aq_vec2 sub(aq_vec2 a, aq_vec2 b) { return v2(a.x - b.x, a.y - b.y); }
static aq_vec2 scl(double s, aq_vec2 a) { return v2(s * a.x, s * a.y); }
static aq_vec2 perp(aq_vec2 a) { return v2(-a.y, a.x); } /* J a */
static double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }
static double dot(aq_vec2 a, aq_vec2 b) { return a.x * b.x + a.y * b.y; }
static double norm(aq_vec2 a) { return hypot(a.x, a.y); }
static aq_vec2 rot(double t, aq_vec2 a)
{
  double c = cos(t), s = sin(t);
  return v2(c * a.x - s * a.y, s * a.x + c * a.y);
}

void aq_hinge_set_format(const aq_hinge_set *hs, char *joints, size_t nj,
                         char *faces, size_t nf)
{
  if (joints)
    snprintf(joints, nj, "%zu,%zu,%zu,%zu", hs->joint[0], hs->joint[1],
             hs->joint[2], hs->joint[3]);
  if (faces)
    snprintf(faces, nf, "%c%c%c%c", hs->face[0], hs->face[1], hs->face[2],
             hs->face[3]);
}

void aq_hinge_set_text(const aq_hinge_set *hs, char *buf, size_t n)
{
  snprintf(buf, n, "%zu%c %zu%c %zu%c %zu%c", hs->joint[0], hs->face[0], hs->joint[1],
           hs->face[1], hs->joint[2], hs->face[2], hs->joint[3], hs->face[3]);
}

aq_status aq_mech_init(aq_mech *m, const aq_geom *g, const aq_hinge_set *hs,
                       aq_error *err)
{
  memset(m, 0, sizeof *m);
  size_t n = g->p.voussoirs;
  for (int k = 0; k < 4; k++) {
    if (hs->joint[k] > n)
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "hinges",
                          "expected joints in 0..%zu, got %zu", n, hs->joint[k]);
    if (hs->face[k] != 'e' && hs->face[k] != 'i')
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "hinges",
                          "expected face e or i, got '%c'", hs->face[k]);
    if (k > 0 && hs->joint[k] == hs->joint[k - 1])
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "hinges",
                          "expected one hinge per joint, got two on joint %zu",
                          hs->joint[k]);
    if (k > 0 && hs->joint[k] < hs->joint[k - 1])
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "hinges",
                          "expected joints in increasing order, got %zu after %zu",
                          hs->joint[k], hs->joint[k - 1]);
  }
  m->g = g;
  m->hs = *hs;
  for (int k = 0; k < 4; k++) {
    m->h[k] = aq_geom_joint_point(g, hs->joint[k], hs->face[k]);
    m->open[k] = hs->face[k] == 'i' ? 1 : -1;
  }
  for (int b = 0; b < 3; b++) {
    m->body[b] = aq_geom_body(g, hs->joint[b], hs->joint[b + 1]);
    m->l[b] = norm(sub(m->h[b + 1], m->h[b]));
  }
  /* branch: side of the line H2 -> H4 on which H3 lies */
  double side = cross(sub(m->h[3], m->h[1]), sub(m->h[2], m->h[1]));
  if (side == 0 || m->l[1] == 0 || m->l[2] == 0 || m->l[0] == 0)
    return aq_error_set(err, AQ_EGEOMETRY, NULL, -1, -1, "hinges",
                        "expected a four-bar with H2, H3, H4 not collinear, got "
                        "a linkage at its toggle");
  m->branch = side > 0 ? 1 : -1;
  return AQ_OK;
}

/* Solve a v2 + b v3 = w. */
static void solve2(aq_vec2 a2, aq_vec2 a3, double det, aq_vec2 w, double *a,
                   double *b)
{
  *a = cross(w, a3) / det;
  *b = cross(a2, w) / det;
}

int aq_mech_eval(const aq_mech *m, double q, aq_mech_state *st)
{
  const aq_vec2 *H = m->h;
  aq_vec2 h2 = add(H[0], rot(q, sub(H[1], H[0])));
  aq_vec2 d = sub(H[3], h2);
  double dd = norm(d);
  double l23 = m->l[1], l34 = m->l[2];
  if (!(dd > 0))
    return -1;
  double along = (l23 * l23 - l34 * l34 + dd * dd) / (2.0 * dd);
  double hh = l23 * l23 - along * along;
  if (!(hh > 0))
    return -1;
  aq_vec2 u = scl(1.0 / dd, d);
  /* H3' - H2' = along u + sigma sqrt(hh) J u, and cross(H4-H2', H3'-H2')
   * = dd sigma sqrt(hh): sigma = branch keeps the side of q = 0 */
  aq_vec2 h3 = add(h2, add(scl(along, u), scl((double)m->branch * sqrt(hh), perp(u))));
  st->q = q;
  st->h2 = h2;
  st->h3 = h3;
  aq_vec2 v1 = sub(h2, H[0]), vv2 = sub(h3, h2), v3 = sub(H[3], h3);
  double det = cross(vv2, v3);
  st->toggle = det / (l23 * l34);
  if (det == 0)
    return -1;
  /* rotations from the link directions */
  double p2 = atan2(cross(sub(H[2], H[1]), vv2), dot(sub(H[2], H[1]), vv2));
  double p3 = atan2(cross(sub(H[2], H[3]), sub(h3, H[3])),
                    dot(sub(H[2], H[3]), sub(h3, H[3])));
  double a, b, a1, b1, a2, b2;
  solve2(vv2, v3, det, scl(-1.0, v1), &a, &b);
  aq_vec2 w2 = scl(-1.0, perp(add(v1, add(scl(a * a, vv2), scl(b * b, v3)))));
  solve2(vv2, v3, det, w2, &a1, &b1);
  aq_vec2 w3 = sub(add(v1, add(scl(a * a * a, vv2), scl(b * b * b, v3))),
                   scl(3.0, perp(add(scl(a * a1, vv2), scl(b * b1, v3)))));
  solve2(vv2, v3, det, w3, &a2, &b2);
  double ph[3][4] = {{q, 1, 0, 0}, {p2, a, a1, a2}, {p3, b, b1, b2}};
  memcpy(st->phi, ph, sizeof ph);
  aq_vec2 piv[3] = {H[0], h2, H[3]};
  aq_vec2 piv0[3] = {H[0], H[1], H[3]};
  for (int k = 0; k < 3; k++) {
    double f = ph[k][0], f1 = ph[k][1], f2 = ph[k][2], f3 = ph[k][3];
    aq_vec2 r = rot(f, sub(m->body[k].c, piv0[k]));
    aq_vec2 jr = perp(r);
    st->c[k][0] = add(piv[k], r);
    st->c[k][1] = scl(f1, jr);
    st->c[k][2] = sub(scl(f2, jr), scl(f1 * f1, r));
    st->c[k][3] = sub(scl(f3 - f1 * f1 * f1, jr), scl(3.0 * f1 * f2, r));
  }
  /* body 2 rides on H2' */
  st->c[1][1] = add(st->c[1][1], perp(v1));
  st->c[1][2] = sub(st->c[1][2], v1);
  st->c[1][3] = sub(st->c[1][3], perp(v1));
  return 0;
}

void aq_mech_hinge_rel(const aq_mech_state *st, double rel[4])
{
  rel[0] = st->phi[0][0];
  rel[1] = st->phi[1][0] - st->phi[0][0];
  rel[2] = st->phi[2][0] - st->phi[1][0];
  rel[3] = -st->phi[2][0];
}

double aq_mech_closure_residual(const aq_mech *m, const aq_mech_state *st)
{
  const aq_vec2 *H = m->h;
  aq_vec2 s = add(rot(st->phi[0][0], sub(H[1], H[0])),
                  add(rot(st->phi[1][0], sub(H[2], H[1])),
                      rot(st->phi[2][0], sub(H[3], H[2]))));
  return norm(sub(s, sub(H[3], H[0])));
}

aq_status aq_mech_equilibrium(const aq_mech *m, const aq_mech_state *st,
                              const aq_live *live, aq_equil *out, aq_error *err)
{
  double A[81] = {0}, rhs[9] = {0}, sol[9];
  aq_vec2 hc[4] = {m->h[0], st->h2, st->h3, m->h[3]};
  double g = live->g_mps2;
  for (int b = 0; b < 3; b++) {
    double mb = m->body[b].mass_kg;
    aq_vec2 c = st->c[b][0];
    aq_vec2 rc = sub(c, hc[b]);
    aq_vec2 d = sub(hc[b + 1], hc[b]);
    double lx = 0, ly = 0, ml = 0;
    if (live->kind == AQ_LIVE_HORIZONTAL) {
      lx = -(double)live->act_sign * mb * g;
      ml = -rc.y * lx;
    } else if (live->point_body == b) {
      aq_vec2 piv0[3] = {m->h[0], m->h[1], m->h[3]};
      aq_vec2 piv[3] = {m->h[0], st->h2, m->h[3]};
      aq_vec2 p = add(piv[b], rot(st->phi[b][0], sub(live->point, piv0[b])));
      ly = -1.0;
      ml = -(p.x - hc[b].x);
    }
    int r = 3 * b;
    /* sum Fx = 0: h_b - h_{b+1} + lambda lx = 0 */
    A[r * 9 + 2 * b] = 1;
    A[r * 9 + 2 * (b + 1)] = -1;
    A[r * 9 + 8] = lx;
    rhs[r] = 0;
    /* sum Fy = 0: v_b - v_{b+1} + lambda ly - m g = 0 */
    A[(r + 1) * 9 + 2 * b + 1] = 1;
    A[(r + 1) * 9 + 2 * (b + 1) + 1] = -1;
    A[(r + 1) * 9 + 8] = ly;
    rhs[r + 1] = mb * g;
    /* moments about H_b: d x (-(h, v)_{b+1}) + (c - H_b) x (0, -m g) + lambda ml = 0 */
    A[(r + 2) * 9 + 2 * (b + 1)] = d.y;
    A[(r + 2) * 9 + 2 * (b + 1) + 1] = -d.x;
    A[(r + 2) * 9 + 8] = ml;
    rhs[r + 2] = rc.x * mb * g;
  }
  gsl_matrix_view Av = gsl_matrix_view_array(A, 9, 9);
  gsl_vector_view bv = gsl_vector_view_array(rhs, 9);
  gsl_vector_view xv = gsl_vector_view_array(sol, 9);
  gsl_permutation *perm = gsl_permutation_alloc(9);
  if (!perm)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  int sgn;
  int rc1 = gsl_linalg_LU_decomp(&Av.matrix, perm, &sgn);
  int rc2 = rc1 ? rc1 : gsl_linalg_LU_solve(&Av.matrix, perm, &bv.vector, &xv.vector);
  gsl_permutation_free(perm);
  int finite = 1;
  for (int k = 0; k < 9; k++)
    finite &= isfinite(sol[k]) != 0;
  if (rc1 || rc2 || !finite)
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "equilibrium",
                        "expected a non-singular 9x9 balance system at q = %g rad, "
                        "got GSL status %d", st->q, rc1 ? rc1 : rc2);
  for (int k = 0; k < 4; k++) {
    out->h[k] = sol[2 * k];
    out->v[k] = sol[2 * k + 1];
    /* joint normal pointing into the counter-clockwise body, turned with
     * each of the two bodies that meet at the hinge */
    aq_vec2 n0 = perp(m->g->ju[m->hs.joint[k]]);
    double rot_ccw = k < 3 ? st->phi[k][0] : 0.0;
    double rot_cw = k > 0 ? st->phi[k - 1][0] : 0.0;
    aq_vec2 f = v2(out->h[k], out->v[k]);
    double n1 = dot(f, rot(rot_ccw, n0)), n2 = dot(f, rot(rot_cw, n0));
    out->normal[k] = n1 < n2 ? n1 : n2;
  }
  out->lambda = sol[8];
  return AQ_OK;
}

/* Deformed position of body-fixed point p0 of part `b` (-1: fixed). */
static aq_vec2 carry(const aq_mech *m, const aq_mech_state *st, int b, aq_vec2 p0)
{
  if (b < 0)
    return p0;
  aq_vec2 piv0[3] = {m->h[0], m->h[1], m->h[3]};
  aq_vec2 piv[3] = {m->h[0], st->h2, m->h[3]};
  return add(piv[b], rot(st->phi[b][0], sub(p0, piv0[b])));
}

double aq_mech_thrust(const aq_mech *m, const aq_mech_state *st,
                      const aq_live *live, const aq_equil *eq, double *ecc,
                      int *tension)
{
  return aq_mech_thrust_line(m, st, live, eq, ecc, tension, NULL, NULL);
}

/* aq_mech_thrust_line, and (ratio not NULL) each joint's |T|/N (see
 * aq_mech_friction). */
static double thrust_core(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                          const aq_equil *eq, double *ecc, int *tension, aq_vec2 *pt,
                          aq_vec2 *dir, double *ratio);

double aq_mech_thrust_line(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                           const aq_equil *eq, double *ecc, int *tension, aq_vec2 *pt,
                           aq_vec2 *dir)
{
  return thrust_core(m, st, live, eq, ecc, tension, pt, dir, NULL);
}

/* |T|/N of the force f across a joint of unit direction u (intrados to
 * extrados), f pushing into the side that perp(u) points to when sign = 1
 * (-1: the other side): INFINITY when it does not push. */
static double slip_ratio(aq_vec2 f, aq_vec2 u, double sign)
{
  double nf = sign * dot(f, perp(u)), tf = fabs(dot(f, u));
  return nf > 0 ? tf / nf : INFINITY;
}

double aq_mech_friction(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                        const aq_equil *eq, double *ecc, double *ratio, size_t *joint)
{
  size_t n = m->g->p.voussoirs;
  thrust_core(m, st, live, eq, ecc, NULL, NULL, NULL, ratio);
  double worst = -1;
  for (size_t j = 0; j <= n; j++)
    if (!(ratio[j] <= worst)) {
      worst = ratio[j];
      if (joint)
        *joint = j;
    }
  return worst;
}

static double thrust_core(const aq_mech *m, const aq_mech_state *st, const aq_live *live,
                          const aq_equil *eq, double *ecc, int *tension, aq_vec2 *pt,
                          aq_vec2 *dir, double *ratio)
{
  const aq_geom *g = m->g;
  size_t n = g->p.voussoirs;
  const size_t *J = m->hs.joint;
  double gg = live->g_mps2, lam = eq->lambda, worst = 0;
  aq_vec2 hc[4] = {m->h[0], st->h2, st->h3, m->h[3]};
  if (tension)
    *tension = 0;
  for (size_t j = 0; j <= n; j++) {
    int k;
    for (k = 0; k < 4 && J[k] != j; k++)
      ;
    if (k < 4) {
      ecc[j] = m->hs.face[k] == 'e' ? 1.0 : -1.0;
      if (pt) {
        pt[j] = hc[k];
        dir[j] = v2(eq->h[k], eq->v[k]);
      }
      if (ratio) /* the force on the counter-clockwise body, across its face */
        ratio[j] = slip_ratio(v2(eq->h[k], eq->v[k]),
                              rot(k < 3 ? st->phi[k][0] : 0.0, g->ju[j]), 1.0);
      continue;
    }
    /* the part j lies in (body index or -1 fixed), the hinge the sub-body
     * runs to, the voussoirs [a, b) of the sub-body, the hinge force on it */
    int part, cut_ccw;
    size_t a, b;
    aq_vec2 f, pf;
    if (j < J[0]) { /* fixed, +x side: voussoirs j..J0-1, force -(h1, v1) at H1 */
      part = -1, a = j, b = J[0], cut_ccw = 0;
      f = v2(-eq->h[0], -eq->v[0]), pf = hc[0];
    } else if (j > J[3]) { /* fixed, -x side: voussoirs J3..j-1, force (h4, v4) at H4 */
      part = -1, a = J[3], b = j, cut_ccw = 1;
      f = v2(eq->h[3], eq->v[3]), pf = hc[3];
    } else {
      int bb = j < J[1] ? 0 : j < J[2] ? 1 : 2;
      part = bb, a = J[bb], b = j, cut_ccw = 1;
      f = v2(eq->h[bb], eq->v[bb]), pf = hc[bb];
    }
    aq_vec2 t = f;
    double m0 = cross(pf, f);
    for (size_t v = a; v < b; v++) {
      double mv = g->vous[v].mass_kg;
      aq_vec2 load = v2(lam * -(double)live->act_sign * mv * gg, -mv * gg);
      aq_vec2 c = carry(m, st, part, g->vous[v].c);
      t = add(t, load);
      m0 += cross(c, load);
    }
    /* joint line: P(r) = A + r u (model.h: jo, ju, jmid, jhalf) */
    aq_vec2 A = carry(m, st, part, g->jo[j]);
    aq_vec2 u = sub(carry(m, st, part, add(g->jo[j], g->ju[j])), A);
    double ut = cross(u, t);
    double r = ut != 0 ? (m0 - cross(A, t)) / ut : HUGE_VAL;
    ecc[j] = (r - g->jmid[j]) / g->jhalf[j];
    if (pt) {
      pt[j] = add(A, scl(r, u));
      dir[j] = t;
    }
    aq_vec2 nrm = perp(u); /* into the counter-clockwise side */
    double push = dot(t, nrm) * (cut_ccw ? 1.0 : -1.0);
    if (ratio)
      ratio[j] = slip_ratio(t, u, cut_ccw ? 1.0 : -1.0);
    if (tension && !(push > 0))
      *tension = 1;
    if (fabs(ecc[j]) > worst)
      worst = fabs(ecc[j]);
  }
  return worst;
}

void aq_mech_field0(const aq_mech *m, int q_sign, aq_vec2 *u, double *w)
{
  const aq_geom *g = m->g;
  aq_mech_state st;
  size_t n = g->p.voussoirs;
  for (size_t k = 0; k < n; k++) {
    u[k] = v2(0, 0);
    w[k] = 0;
  }
  if (aq_mech_eval(m, 0.0, &st) != 0)
    return;
  aq_vec2 piv[3] = {m->h[0], m->h[1], m->h[3]};
  aq_vec2 pivv[3] = {v2(0, 0), perp(sub(m->h[1], m->h[0])), v2(0, 0)};
  for (int b = 0; b < 3; b++)
    for (size_t k = m->hs.joint[b]; k < m->hs.joint[b + 1]; k++) {
      double om = st.phi[b][1];
      u[k] = scl((double)q_sign, add(pivv[b], scl(om, perp(sub(g->vous[k].c, piv[b])))));
      w[k] = (double)q_sign * om;
    }
}

double aq_field_dot(const aq_mass *parts, size_t n, const aq_vec2 *u_a,
                    const double *w_a, const aq_vec2 *u_b, const double *w_b)
{
  double s = 0;
  for (size_t k = 0; k < n; k++)
    s += parts[k].mass_kg * dot(u_a[k], u_b[k]) + parts[k].inertia_kgm2 * w_a[k] * w_b[k];
  return s;
}
