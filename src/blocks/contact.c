/* contact.c: the contacts of a joint (model.h): the two ends of the
 * overlap of its faces.
 *
 * Both sides of joint j carry a face along it: a body's is the joint
 * itself, from p[0] to p[1]; a support's runs on by its extent ext beyond
 * both ends (model.h aq_bjoint).  At end k (0 intrados, 1 extrados) the
 * overlap ends at the corner of either side that lies on the other's
 * face: B's corner against A's face line, or A's corner against B's.
 * Which one follows from the slip there, Delta . tbar, with Delta the
 * displacement of B's material point at the joint's end k from A's (the
 * same point undeformed) and tbar the mean of the two faces' tangents: at
 * the intrados end B's corner when B has slid along +t by at least
 * ext_B - ext_A, at the extrados end when it has slid by at most
 * ext_A - ext_B.  A mirror image of the arch exchanges A and B at the
 * mirror joint, reverses the slip and maps tbar to its mirror, so the
 * choice is mirror-symmetric (up to a tie, where the two corners meet).
 *
 * For B's corner c (undeformed) on A's face, with d = p_B(c) - p_A(c)
 * (A's material point at c lies on A's face line), A's normal
 * n_A = R(theta_A) n0 and tangent t_A = R(theta_A) t0, the gap is d . n_A
 * and the slip d . t_A.  Their rates are exactly the relative velocity of
 * B's material point at the corner against A's material point there,
 * along n_A and t_A: the terms of the turning frame, -omega_A d . t_A
 * along the normal and omega_A d . n_A along the tangent, appear in both
 * and cancel.  For A's corner c on B's face the same holds with the roles
 * exchanged: d = p_B(c) - p_A(c), gap d . n_B, slip d . t_B, rates the
 * velocity of B's material point at A's corner against A's corner along
 * n_B and t_B.  So the rows below are the exact Jacobians of gap and s,
 * and the contact impulse P_n n + P_t t acts on B (its opposite on A)
 * through the same rows. */
#include <math.h>

#include "model.h"

/* 2-D cross product a x b. */
static inline double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }

static inline aq_vec2 rot(double th, aq_vec2 v)
{
  double cs = cos(th), sn = sin(th);
  return (aq_vec2){cs * v.x - sn * v.y, sn * v.x + cs * v.y};
}

/* Rows of the velocity of B against A at point p along e. */
static void set_row(int a, int b, aq_vec2 p, aq_vec2 cA, aq_vec2 cB, aq_vec2 e,
                    const double gvx[2], aq_crow *R)
{
  aq_vec2 rA = {p.x - cA.x, p.y - cA.y}, rB = {p.x - cB.x, p.y - cB.y};
  R->c = 0;
  if (a >= 0) {
    R->ga[0] = -e.x;
    R->ga[1] = -e.y;
    R->ga[2] = -cross(rA, e);
  } else {
    R->ga[0] = R->ga[1] = R->ga[2] = 0;
    R->c -= gvx[a == AQ_GROUND_P ? 0 : 1] * e.x;
  }
  if (b >= 0) {
    R->gb[0] = e.x;
    R->gb[1] = e.y;
    R->gb[2] = cross(rB, e);
  } else {
    R->gb[0] = R->gb[1] = R->gb[2] = 0;
    R->c += gvx[b == AQ_GROUND_P ? 0 : 1] * e.x;
  }
}

double aq_contact_overlap(const aq_bodies *s, size_t j, double slip_m)
{
  const aq_bjoint *J = &s->joint[j];
  double w = J->width_m, ea = J->ext_m[0], eb = J->ext_m[1];
  return fmin(w + ea, w + eb + slip_m) - fmax(-ea, -eb + slip_m);
}

void aq_contact_eval(const aq_bodies *s, size_t j, const double *q, const double gx[2],
                     const double gvx[2], aq_corner c[2])
{
  const aq_bjoint *J = &s->joint[j];
  int a = J->a, b = J->b;
  double tha = a >= 0 ? q[3 * a + 2] : 0, thb = b >= 0 ? q[3 * b + 2] : 0;
  aq_vec2 nA = rot(tha, J->n0), tA = rot(tha, J->t0);
  aq_vec2 nB = rot(thb, J->n0), tB = rot(thb, J->t0);
  aq_vec2 tm = rot(0.5 * (tha + thb), J->t0);
  aq_vec2 cA = a >= 0 ? (aq_vec2){q[3 * a], q[3 * a + 1]} : (aq_vec2){0, 0};
  aq_vec2 cB = b >= 0 ? (aq_vec2){q[3 * b], q[3 * b + 1]} : (aq_vec2){0, 0};
  double ea = J->ext_m[0], eb = J->ext_m[1];
  for (int k = 0; k < 2; k++) {
    aq_corner *C = &c[k];
    double out = k ? 1 : -1; /* beyond end k is along out t0 */
    /* the slip at the joint's end k */
    aq_vec2 pb = aq_bodies_point(s, b, q, gx, J->p[k]);
    aq_vec2 pa = aq_bodies_point(s, a, q, gx, J->p[k]);
    double sig = (pb.x - pa.x) * tm.x + (pb.y - pa.y) * tm.y;
    int on_b; /* A's corner on B's face */
    if (isinf(ea) || isinf(eb))
      on_b = isinf(eb) && !isinf(ea);
    else
      on_b = !(out * sig <= ea - eb);
    double e = on_b ? ea : eb;
    aq_vec2 c0 = J->p[k];
    if (e != 0)
      c0 = (aq_vec2){c0.x + out * e * J->t0.x, c0.y + out * e * J->t0.y};
    if (e != 0) {
      pb = aq_bodies_point(s, b, q, gx, c0);
      pa = aq_bodies_point(s, a, q, gx, c0);
    }
    aq_vec2 d = {pb.x - pa.x, pb.y - pa.y};
    aq_vec2 n = on_b ? nB : nA, t = on_b ? tB : tA, p = on_b ? pa : pb;
    C->on_b = on_b;
    C->gap_m = d.x * n.x + d.y * n.y;
    C->s_m = d.x * t.x + d.y * t.y + (k ? J->width_m : 0);
    set_row(a, b, p, cA, cB, n, gvx, &C->n);
    set_row(a, b, p, cA, cB, t, gvx, &C->t);
  }
}

double aq_crow_dot(const aq_bodies *s, size_t j, const aq_crow *r, const double *v)
{
  int a = s->joint[j].a, b = s->joint[j].b;
  double u = r->c;
  if (a >= 0)
    u += r->ga[0] * v[3 * a] + r->ga[1] * v[3 * a + 1] + r->ga[2] * v[3 * a + 2];
  if (b >= 0)
    u += r->gb[0] * v[3 * b] + r->gb[1] * v[3 * b + 1] + r->gb[2] * v[3 * b + 2];
  return u;
}
