/* workpath_piece.c: the Taylor leg's pieces of a work path
 * (workpath_impl.h): Chebyshev fits of its slopes, M and the
 * acceleration's terms over [0, s_c] (path.h aq_path_piece).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "workpath_impl.h"

/* ---- The Taylor leg's pieces ----
 * Away from a toggle the kinematics are analytic in s, so dx/ds, dy/ds and
 * M are fitted on intervals as wide as their Chebyshev series allow, by
 * interpolation of degree PIECE_DEG at the Chebyshev points of the first
 * kind from the exact evaluation (aq_workpath_exact_f; the Hermite tables above are not
 * used, so the ode and workpath-quad references stay as they are).  An
 * interval is accepted when the last three Chebyshev coefficients of each
 * function are below PIECE_TAIL_TOL relative to its scale (dx/ds and dy/ds
 * together, and M: their largest magnitude on the interval), or when
 * halving stopped halving a tail already at round-off; else it is halved.
 * Each fit is converted to the power basis in t = (s - s_lo) / (s_hi - s_lo)
 * in [0, 1] (the monomial coefficients of a fast-decaying Chebyshev series
 * stay of the size of the function), its constant term set to the exact
 * value at s_lo (a change of the fit's own error): near the threshold the
 * start from rest at s = 0 depends on a dx + g dy at s = 0, which nearly
 * cancel, so those values are exact there.  x and y are the integrals of the
 * fitted slopes from their exact values at s_lo (degree PIECE_DEG + 1), so
 * that the potential energy m_T g y(s) is that of the work integral the leg
 * uses (the energy balance holds to round-off of y, not of the arch's
 * coordinates, even for tiny rocking near s = 0).  The acceleration's
 * pieces gc = R', ga = (xr R)', gb = (yr R)' (path.h; R = 1/M, xr, yr the
 * displacements from s_lo) are fitted alike from the exact M, M', x, y and
 * slopes, with their constant terms exact at s_lo, and share the test of
 * the tails (gc alone, ga and gb together), so that the leg needs no
 * division by M.
 *
 * At a toggle end the path has a branch point at s_c (dx/ds grows as
 * (s_c - s)^-1/2, M as (s_c - s)^-1), and the exact evaluation loses digits
 * as s nears it: measured on a 120-degree circle, t/R 0.4, 8 voussoirs, a
 * relative round-off of about 9e-16 / (s_c - s), 3e-10 at 3e-6 rad from the
 * end, which no halving takes below PIECE_ROUNDOFF.  There, an interval is
 * also accepted when halving no longer halves its tail and the branch point
 * alone would leave a tail below PIECE_TAIL_TOL: for an interval of
 * half-width h whose middle is d from s_c, Chebyshev coefficients decay as
 * rho^-k, rho = d/h + sqrt((d/h)^2 - 1) (the Bernstein ellipse through
 * s_c), so what is left of the tail is the evaluation's own round-off. */
#define PIECE_DEG 14            /* of the fits; x, y one more (< AQ_PIECE_MAX_DEG) */
#define PIECE_ROUNDOFF 1e-10    /* a tail that halving no longer halves and is below this: round-off
                                   (flat arches: 1e-11 near their end) */
#define PIECE_MAX_DEPTH 40      /* halvings of [0, s_c] at most */
enum { PC_DX = 0, PC_DY, PC_M, PC_GC, PC_GA, PC_GB, NPC_F, PN = PIECE_DEG + 1 };
_Static_assert(PIECE_DEG < AQ_PIECE_MAX_DEG, "x, y need degree PIECE_DEG + 1");

typedef struct {
  aq_workpath *w;
  double cosk[PN][PN]; /* cos(pi k (j + 1/2) / PN) */
  double tnode[PN];    /* Chebyshev points of the first kind on [-1, 1] */
  int failed, too_many;
} piece_ctx;

/* The fitted functions at one s from the exact values f there and fa at
 * the piece's start (path.h aq_path_piece: gc, ga, gb). */
static void piece_g(const double f[NF][3], const double fa[NF][3], double v[NPC_F])
{
  double r = 1 / f[F_M][0], rp = -f[F_M][1] * r * r; /* R = 1/M, R' */
  v[PC_DX] = f[F_DX][0];
  v[PC_DY] = f[F_DY][0];
  v[PC_M] = f[F_M][0];
  v[PC_GC] = rp;
  v[PC_GA] = f[F_DX][0] * r + (f[F_X][0] - fa[F_X][0]) * rp;
  v[PC_GB] = f[F_DY][0] * r + (f[F_Y][0] - fa[F_Y][0]) * rp;
}

/* Chebyshev coefficients c of dx/ds, dy/ds, M and the acceleration's
 * pieces gc, ga, gb (path.h) on [a, b], and their tail relative to the
 * scales (dx/ds and dy/ds together, M, gc, ga and gb together: their
 * largest magnitudes on the interval); fa the exact values at a (for
 * piece_append); -1 when the linkage fails. */
static int piece_fit(piece_ctx *pc, double a, double b, double c[NPC_F][PN],
                     double *tail, double fa[NF][3])
{
  double v[PN][NPC_F], mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sdxy = 0, sm = 0, sgc = 0, sgab = 0;
  if (aq_workpath_exact_f(pc->w, a, fa, NULL) != 0)
    return -1;
  for (int j = 0; j < PN; j++) {
    double f[NF][3];
    if (aq_workpath_exact_f(pc->w, mid + half * pc->tnode[j], f, NULL) != 0)
      return -1;
    piece_g(f, fa, v[j]);
    sdxy = fmax(sdxy, fmax(fabs(v[j][PC_DX]), fabs(v[j][PC_DY])));
    sm = fmax(sm, fabs(v[j][PC_M]));
    sgc = fmax(sgc, fabs(v[j][PC_GC]));
    sgab = fmax(sgab, fmax(fabs(v[j][PC_GA]), fabs(v[j][PC_GB])));
  }
  const double scale[NPC_F] = {sdxy, sdxy, sm, sgc, sgab, sgab};
  *tail = 0;
  for (int f = 0; f < NPC_F; f++) {
    for (int k = 0; k < PN; k++) {
      double sum = 0;
      for (int j = 0; j < PN; j++)
        sum += v[j][f] * pc->cosk[k][j];
      c[f][k] = (k == 0 ? 1.0 : 2.0) * sum / PN;
    }
    for (int k = PN - 3; k < PN; k++) {
      double e = fabs(c[f][k]) / (scale[f] > 0 ? scale[f] : 1);
      if (!(e <= *tail)) /* NaN propagates as a failed fit */
        *tail = isnan(e) ? HUGE_VAL : e;
    }
  }
  return 0;
}

/* Append the piece [a, b] from its Chebyshev coefficients and the exact
 * values fa at a; -1 on failure. */
static int piece_append(aq_workpath *w, double a, double b, double c[NPC_F][PN],
                        const double fa[NF][3])
{
  if (w->npc == w->pcap) {
    size_t cap = w->pcap ? 2 * w->pcap : 16;
    double *bp = realloc(w->pbp, (cap + 1) * sizeof *bp);
    if (!bp)
      return -1;
    w->pbp = bp;
    aq_path_piece *pp = realloc(w->piece, cap * sizeof *pp);
    if (!pp)
      return -1;
    w->piece = pp;
    w->pcap = cap;
  }
  aq_path_piece *pc = &w->piece[w->npc];
  memset(pc, 0, sizeof *pc);
  pc->s_lo = a;
  pc->s_hi = b;
  pc->s_ref = a;
  pc->iscale = 1.0 / (b - a);
  pc->deg = PIECE_DEG;
  double *dst[NPC_F] = {pc->dx, pc->dy, pc->m, pc->gc, pc->ga, pc->gb};
  double exact_a[NPC_F];
  piece_g(fa, fa, exact_a);
  pc->has_g = 1;
  for (int f = 0; f < NPC_F; f++) {
    /* sum c_k T_k(tau) in powers of tau: T_{k+1} = 2 tau T_k - T_{k-1} */
    double tp[PN] = {1}, tc[PN] = {0, 1};
    double *d = dst[f];
    d[0] = c[f][0];
    d[1] = c[f][1];
    for (int k = 2; k < PN; k++) {
      double tn[PN];
      tn[0] = -tp[0];
      for (int i = 1; i < PN; i++)
        tn[i] = 2 * tc[i - 1] - tp[i];
      for (int i = 0; i < PN; i++) {
        tp[i] = tc[i];
        tc[i] = tn[i];
        d[i] += c[f][k] * tn[i];
      }
    }
    /* tau = 2 t - 1: shift to tau = -1, then scale by 2^k */
    for (int k = 0; k < PIECE_DEG; k++)
      for (int j = PIECE_DEG - 1; j >= k; j--)
        d[j] -= d[j + 1];
    for (int k = 1, p2 = 2; k < PN; k++, p2 *= 2)
      d[k] *= p2;
    d[0] = exact_a[f];
  }
  /* x, y: the integrals of the slopes (ds = (b - a) dt) from s_lo */
  const double *slope[2] = {pc->dx, pc->dy};
  double *val[2] = {pc->x, pc->y};
  val[0][0] = fa[F_X][0];
  val[1][0] = fa[F_Y][0];
  for (int f = 0; f < 2; f++)
    for (int k = 0; k < PN; k++)
      val[f][k + 1] = (b - a) * slope[f][k] / (k + 1);
  w->pbp[w->npc] = a;
  w->pbp[w->npc + 1] = b;
  w->npc++;
  return 0;
}

/* 1 when s_c is a toggle and [a, b] is far enough from it that the branch
 * point there would leave a tail (degree PN - 3) below PIECE_TAIL_TOL. */
static int piece_clear_of_toggle(const aq_workpath *w, double a, double b)
{
  double h = 0.5 * (b - a), d = w->path.s_c_rad - (a + h);
  if (w->end != AQ_END_TOGGLE || !(d > h))
    return 0;
  double r = d / h, rho = r + sqrt(r * r - 1);
  return pow(rho, -(PN - 3)) <= PIECE_TAIL_TOL;
}

static void piece_refine(piece_ctx *pc, double a, double b, int depth,
                         double parent_tail)
{
  if (pc->failed)
    return;
  if (pc->w->npc >= pc->w->max_n) {
    pc->failed = pc->too_many = 1;
    pc->w->out_s = a;
    return;
  }
  if (depth > pc->w->fine_depth) {
    pc->w->fine_depth = depth;
    pc->w->fine_s = a;
  }
  double c[NPC_F][PN], tail, fa[NF][3];
  if (piece_fit(pc, a, b, c, &tail, fa) != 0) {
    pc->failed = 1;
    return;
  }
  const int stalled = tail > TABLE_STALL * parent_tail;
  if (tail <= PIECE_TAIL_TOL || depth >= PIECE_MAX_DEPTH || (stalled && tail < PIECE_ROUNDOFF) ||
      (stalled && piece_clear_of_toggle(pc->w, a, b))) {
    if (piece_append(pc->w, a, b, c, fa) != 0)
      pc->failed = 1;
    return;
  }
  double m = a + 0.5 * (b - a);
  piece_refine(pc, a, m, depth + 1, tail);
  piece_refine(pc, m, b, depth + 1, tail);
}

/* The pieces over [0, s_c]; 0, -1 on failure, -2 when too many. */
int aq_workpath_build_pieces(aq_workpath *w)
{
  piece_ctx pc;
  const double pi = acos(-1.0);
  memset(&pc, 0, sizeof pc);
  pc.w = w;
  for (int j = 0; j < PN; j++) {
    pc.tnode[j] = cos(pi * (j + 0.5) / PN);
    for (int k = 0; k < PN; k++)
      pc.cosk[k][j] = cos(pi * k * (j + 0.5) / PN);
  }
  piece_refine(&pc, 0.0, w->path.s_c_rad, 0, HUGE_VAL);
  return pc.too_many ? -2 : pc.failed ? -1 : 0;
}

int aq_workpath_eval_piece(const void *ctx, double s, int dir, aq_path_piece *pc)
{
  const aq_workpath *w = ctx;
  if (aq_workpath_clamp_s(w, &s) != 0)
    return -1;
  size_t lo = 0, hi = w->npc; /* the piece holding s for dir (binary search) */
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (dir > 0 ? s < w->pbp[mid] : s <= w->pbp[mid])
      hi = mid;
    else
      lo = mid;
  }
  *pc = w->piece[lo];
  return 0;
}
