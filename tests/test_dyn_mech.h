/* test_dyn_mech.h: test-local mechanisms implementing aq_path, independent
 * of the arch model, for the dynamics tests.
 *
 * 1. A rigid rectangular rocking block (half-width b, half-height h, mass
 *    m), rotating about a base corner.  R = sqrt(b^2 + h^2), alpha =
 *    atan(b/h).  Primary set: rotation s about the +x corner, centroid
 *    displacement x = b - R sin(alpha - s), y = R cos(alpha - s) - h;
 *    M = m R^2 + m R^2 / 3 = 4/3 m R^2 (exact); collapse at s = alpha; it
 *    opens for a_g < -g tan(alpha) (act_sign = -1).  The reverse set is the
 *    mirror image.  Housner's impact rule: sdot ratio 1 - 1.5 sin^2 alpha.
 *    Its pieces (for the work path's Taylor leg) are the closed forms'
 *    Taylor polynomials of degree 5 on TB_BLOCK_PIECES equal pieces
 *    (remainder (alpha / TB_BLOCK_PIECES)^6 / 720 of R: below 1e-16 m).
 * 2. A synthetic two-set mechanism with smooth, non-constant M(s) and
 *    curved x, y (no physics beyond the contract), asymmetric sets.
 */
#ifndef AQ_TEST_DYN_MECH_H
#define AQ_TEST_DYN_MECH_H

#include <math.h>
#include <string.h>

#include "arch/path.h"

typedef struct {
  double b, h, m, R, alpha;
  int side; /* +1: corner at +b (primary), -1: mirror */
} tb_block;

static int tb_block_eval(const void *ctx, double s, aq_path_point *p)
{
  const tb_block *k = ctx;
  if (!(s >= 0) || s > k->alpha)
    return 1;
  double R = k->R, u = k->alpha - s, sd = k->side;
  memset(p, 0, sizeof *p);
  /* b - R sin(alpha - s) and R cos(alpha - s) - h without cancellation */
  double sh = sin(0.5 * s), hv = 2 * sh * sh; /* 1 - cos s */
  p->x_m = sd * (k->b * hv + k->h * sin(s));
  p->y_m = k->b * sin(s) - k->h * hv;
  p->dx_m = sd * R * cos(u);
  p->dy_m = R * sin(u);
  p->d2x_m = sd * R * sin(u);
  p->d2y_m = -R * cos(u);
  p->mgen_kgm2 = 4.0 / 3.0 * k->m * R * R;
  p->dmgen_kgm2 = 0;
  p->lambda = tan(u);
  p->nbody = 1;
  p->body[0].mass_kg = k->m;
  p->body[0].inertia_kgm2 = k->m * R * R / 3.0;
  p->body[0].x_m = p->x_m;
  p->body[0].y_m = k->h + p->y_m;
  p->body[0].phi_rad = -sd * s;
  p->body[0].dx_m = p->dx_m;
  p->body[0].dy_m = p->dy_m;
  p->body[0].dphi = -sd;
  return 0;
}

enum { TB_BLOCK_PIECES = 256 };

/* d^k/ds^k of sin(alpha - s) and cos(alpha - s) (k >= 0). */
static double tb_dsin(double u, int k)
{
  static const double sg[4] = {1, -1, -1, 1};
  return sg[k % 4] * (k % 2 ? cos(u) : sin(u));
}
static double tb_dcos(double u, int k)
{
  static const double sg[4] = {1, 1, -1, -1};
  return sg[k % 4] * (k % 2 ? sin(u) : cos(u));
}

static int tb_block_piece(const void *ctx, double s, int dir, aq_path_piece *pc)
{
  const tb_block *k = ctx;
  if (!(s >= 0) || s > k->alpha)
    return 1;
  double w = k->alpha / TB_BLOCK_PIECES;
  double fi = dir > 0 ? floor(s / w) : ceil(s / w) - 1;
  if (dir > 0 && (fi + 1) * w <= s) /* s / w rounded down across a join */
    fi++;
  if (dir <= 0 && fi * w >= s)
    fi--;
  int i = fi < 0 ? 0 : (fi > TB_BLOCK_PIECES - 1 ? TB_BLOCK_PIECES - 1 : (int)fi);
  double R = k->R, sd = k->side, u = k->alpha - i * w, fact = 1;
  pc->s_lo = i * w;
  pc->s_hi = i + 1 == TB_BLOCK_PIECES ? k->alpha : (i + 1) * w;
  pc->s_ref = pc->s_lo;
  pc->iscale = 1;
  pc->deg = 5;
  for (int j = 0; j < 6; j++) {
    if (j > 0)
      fact *= j;
    pc->x[j] = -sd * R * tb_dsin(u, j) / fact;
    pc->y[j] = R * tb_dcos(u, j) / fact;
    pc->dx[j] = -sd * R * tb_dsin(u, j + 1) / fact;
    pc->dy[j] = R * tb_dcos(u, j + 1) / fact;
    pc->m[j] = j == 0 ? 4.0 / 3.0 * k->m * R * R : 0;
  }
  pc->x[6] = pc->y[6] = 0; /* x, y: degree deg + 1 */
  pc->x[0] += sd * k->b;
  pc->y[0] -= k->h;
  return 0;
}

/* Fill two paths for a block of half-width b, half-height h, mass m. */
static void tb_block_paths(tb_block blk[2], aq_path path[2], double b,
                           double h, double m, double g)
{
  for (int k = 0; k < 2; k++) {
    blk[k].b = b;
    blk[k].h = h;
    blk[k].m = m;
    blk[k].R = sqrt(b * b + h * h);
    blk[k].alpha = atan(b / h);
    blk[k].side = k == 0 ? 1 : -1;
    double sa = sin(blk[k].alpha);
    path[k] = (aq_path){.name = k == 0 ? "primary" : "reverse",
                        .eval = tb_block_eval,
                        .eval_exact = tb_block_eval,
                        .piece = tb_block_piece,
                        .ctx = &blk[k],
                        .mass_kg = m,
                        .g_mps2 = g,
                        .lambda0 = b / h,
                        .s_c_rad = blk[k].alpha,
                        .act_sign = k == 0 ? -1 : 1,
                        .q_sign = k == 0 ? -1 : 1,
                        .admissible = 1,
                        .impact_vel_ratio = 1 - 1.5 * sa * sa};
  }
}

/* Synthetic set: x = sd X (sin s + 0.4 s^2), y = Y (s - s^2/(2 sc)
 * + 0.1 s^3 (sc - s)), M = M0 (1 + 0.5 s + 0.3 sin 2.7 s). */
typedef struct {
  double X, Y, sc, M0;
  int sd;
} tb_syn;

static int tb_syn_eval(const void *ctx, double s, aq_path_point *p)
{
  const tb_syn *k = ctx;
  if (!(s >= 0) || s > k->sc)
    return 1;
  double X = k->sd * k->X, Y = k->Y, sc = k->sc;
  memset(p, 0, sizeof *p);
  p->x_m = X * (sin(s) + 0.4 * s * s);
  p->dx_m = X * (cos(s) + 0.8 * s);
  p->d2x_m = X * (-sin(s) + 0.8);
  p->y_m = Y * (s - s * s / (2 * sc) + 0.1 * s * s * s * (sc - s));
  p->dy_m = Y * (1 - s / sc + 0.3 * s * s * sc - 0.4 * s * s * s);
  p->d2y_m = Y * (-1 / sc + 0.6 * s * sc - 1.2 * s * s);
  p->mgen_kgm2 = k->M0 * (1 + 0.5 * s + 0.3 * sin(2.7 * s));
  p->dmgen_kgm2 = k->M0 * (0.5 + 0.81 * cos(2.7 * s));
  p->lambda = fabs(p->dy_m / p->dx_m);
  p->nbody = 0;
  return 0;
}

static void tb_syn_paths(tb_syn syn[2], aq_path path[2])
{
  syn[0] = (tb_syn){1.3, 0.55, 0.37, 3000.0, 1};
  syn[1] = (tb_syn){1.1, 0.50, 0.33, 2600.0, -1};
  for (int k = 0; k < 2; k++)
    path[k] = (aq_path){.name = k == 0 ? "primary" : "reverse",
                        .eval = tb_syn_eval,
                        .eval_exact = tb_syn_eval,
                        .ctx = &syn[k],
                        .mass_kg = 2385.0,
                        .g_mps2 = 9.80665,
                        .lambda0 = syn[k].Y / syn[k].X,
                        .s_c_rad = syn[k].sc,
                        .act_sign = k == 0 ? -1 : 1,
                        .q_sign = k == 0 ? 1 : -1,
                        .admissible = 1,
                        .impact_vel_ratio = 0.83};
}

#endif
