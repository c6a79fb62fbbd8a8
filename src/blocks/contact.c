/* contact.c: the corner contacts of a joint (model.h): B's two corners
 * against A's face line.
 *
 * With d = p_B - p_A (B's corner from A's image of the joint's intrados
 * end), A's normal n_A = R(theta_A) n0 and tangent t_A = R(theta_A) t0, the
 * gap is d . n_A and the tangential coordinate d . t_A.  Their rates are
 * exactly the relative velocity of B's material point at the corner
 * against A's material point there, along n_A and t_A: the terms of the
 * turning frame, omega_A s and -omega_A s along the normal (omega_A g and
 * -omega_A g along the tangent), cancel.  So the rows below are the exact
 * Jacobians of gap and s, and the contact impulse P_n n_A + P_t t_A acts
 * on B (and its opposite on A) through the same rows. */
#include <math.h>

#include "model.h"

/* 2-D cross product a x b. */
static inline double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }

void aq_contact_eval(const aq_bodies *s, size_t j, const double *q, const double gx[2],
                     const double gvx[2], aq_corner c[2])
{
  const aq_bjoint *J = &s->joint[j];
  int a = J->a, b = J->b;
  double tha = a >= 0 ? q[3 * a + 2] : 0, cs = cos(tha), sn = sin(tha);
  aq_vec2 nA = {cs * J->n0.x - sn * J->n0.y, sn * J->n0.x + cs * J->n0.y};
  aq_vec2 tA = {cs * J->t0.x - sn * J->t0.y, sn * J->t0.x + cs * J->t0.y};
  aq_vec2 pA = aq_bodies_point(s, a, q, gx, J->p[0]);
  aq_vec2 cA = a >= 0 ? (aq_vec2){q[3 * a], q[3 * a + 1]} : (aq_vec2){0, 0};
  aq_vec2 cB = b >= 0 ? (aq_vec2){q[3 * b], q[3 * b + 1]} : (aq_vec2){0, 0};
  for (int k = 0; k < 2; k++) {
    aq_corner *C = &c[k];
    aq_vec2 pB = aq_bodies_point(s, b, q, gx, J->p[k]);
    aq_vec2 d = {pB.x - pA.x, pB.y - pA.y};
    C->gap_m = d.x * nA.x + d.y * nA.y;
    C->s_m = d.x * tA.x + d.y * tA.y;
    aq_vec2 rA = {pB.x - cA.x, pB.y - cA.y}, rB = {pB.x - cB.x, pB.y - cB.y};
    aq_vec2 dir[2] = {nA, tA};
    aq_crow *row[2] = {&C->n, &C->t};
    for (int r = 0; r < 2; r++) {
      aq_crow *R = row[r];
      aq_vec2 e = dir[r];
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
