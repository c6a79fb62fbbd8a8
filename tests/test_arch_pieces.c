/* test_arch_pieces.c: the Taylor leg's polynomial pieces (path.h
 * aq_path_piece, Chebyshev fits in workpath_piece.c) against the exact
 * kinematics (eval_exact, closed-form linkage solution, an independent
 * path) at pseudo-random s, the acceleration's pieces (gc, ga, gb) against
 * their definitions from the exact M, M', x, y and slopes, and the pieces'
 * tiling of [0, s_c]. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "arch/arch.h"
#include "arch_fixture.h"
#include "check.h"

/* Stated accuracy: Chebyshev tails of the slopes and of M below 2e-15 of
 * their scale (workpath_impl.h PIECE_TAIL_TOL), x and y their integrals; the
 * power basis and the exact evaluation's own round-off add a few units.
 * Errors are relative to: x and y, the centroid's largest displacement
 * over the path (the exact x, y are differences of coordinates of the
 * arch's size); dx/ds and dy/ds, the larger of the two at s; M, M at s.
 * Measured: at most ~2e-14 (AQ_TEST_VERBOSE prints it). */
static const double PIECE_REL_TOL = 1e-13; /* error / scale */
enum { PIECE_SAMPLES = 400 };

/* Coefficients c (degree n) of piece pc at s. */
static double piece_at(const aq_path_piece *pc, const double *c, int n, double s)
{
  double t = (s - pc->s_ref) * pc->iscale, r = c[n];
  for (int k = n - 1; k >= 0; k--)
    r = r * t + c[k];
  return r;
}

AQ_TEST(arch_pieces_match_exact_kinematics)
{
  static const char *ARCHES[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                 "arches/thick.cfg", "arches/segmental.cfg"};
  unsigned long long rng = 0x2385a1c3ULL;
  for (size_t ai = 0; ai < sizeof ARCHES / sizeof ARCHES[0]; ai++) {
    aq_arch *a = aq_test_arch_load(ARCHES[ai]);
    if (!a)
      return;
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(a, set);
      if (!p->admissible || !p->piece)
        continue;
      /* the centroid's largest displacement over the path */
      double xys = 0;
      for (int i = 0; i <= 64; i++) {
        aq_path_point q;
        if (p->eval_exact(p->ctx, p->s_c_rad * i / 64.0, &q) == 0) {
          xys = fmax(xys, fmax(fabs(q.x_m), fabs(q.y_m)));
        }
      }
      double worst = 0, worst_g = 0;
      int bad = 0, ng = 0;
      for (int i = 0; i < PIECE_SAMPLES; i++) {
        rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
        double s = p->s_c_rad * (double)(rng >> 11) / 9007199254740992.0;
        int dir = i % 2 ? 1 : -1;
        aq_path_piece pc;
        aq_path_point q;
        if (p->piece(p->ctx, s, dir, &pc) != 0 || p->eval_exact(p->ctx, s, &q) != 0 ||
            !(s >= pc.s_lo && s <= pc.s_hi)) {
          bad++;
          continue;
        }
        double sd = fmax(fabs(q.dx_m), fabs(q.dy_m));
        /* the acceleration's pieces (path.h gc, ga, gb) from the exact M,
         * M', x, y and slopes here and at the piece's start; scales: the
         * slopes over M, and M' (at least M / s_c) over M^2 */
        aq_path_point q0;
        if (pc.has_g && p->eval_exact(p->ctx, pc.s_lo, &q0) == 0) {
          double m = q.mgen_kgm2, gc = -q.dmgen_kgm2 / (m * m);
          double ga = q.dx_m / m + (q.x_m - q0.x_m) * gc;
          double gb = q.dy_m / m + (q.y_m - q0.y_m) * gc;
          double sg = sd / m, sc = fmax(fabs(q.dmgen_kgm2), m / p->s_c_rad) / (m * m);
          double eg[3] = {fabs(piece_at(&pc, pc.gc, pc.deg, s) - gc) / sc,
                          fabs(piece_at(&pc, pc.ga, pc.deg, s) - ga) / sg,
                          fabs(piece_at(&pc, pc.gb, pc.deg, s) - gb) / sg};
          for (int k = 0; k < 3; k++)
            worst_g = fmax(worst_g, isnan(eg[k]) ? HUGE_VAL : eg[k]);
          ng++;
        }
        double e[5] = {fabs(piece_at(&pc, pc.x, pc.deg + 1, s) - q.x_m) / xys,
                       fabs(piece_at(&pc, pc.y, pc.deg + 1, s) - q.y_m) / xys,
                       fabs(piece_at(&pc, pc.dx, pc.deg, s) - q.dx_m) / sd,
                       fabs(piece_at(&pc, pc.dy, pc.deg, s) - q.dy_m) / sd,
                       fabs(piece_at(&pc, pc.m, pc.deg, s) - q.mgen_kgm2) / q.mgen_kgm2};
        for (int k = 0; k < 5; k++)
          worst = fmax(worst, isnan(e[k]) ? HUGE_VAL : e[k]);
      }
      aq_check(bad == 0, "%s %s: %d samples without a piece holding s",
               ARCHES[ai], p->name, bad);
      aq_check(worst <= PIECE_REL_TOL, "%s %s: pieces vs exact, largest error %.3g of "
               "scale (tolerance %.1g)", ARCHES[ai], p->name, worst, PIECE_REL_TOL);
      aq_check(ng == PIECE_SAMPLES && worst_g <= PIECE_REL_TOL,
               "%s %s: acceleration pieces vs exact at %d samples, largest error "
               "%.3g of scale (tolerance %.1g)", ARCHES[ai], p->name, ng, worst_g,
               PIECE_REL_TOL);
      /* the pieces tile [0, s_c]: each starts where the last ended */
      double s = 0;
      int n = 0, gap = 0;
      while (s < p->s_c_rad && n < 100000) {
        aq_path_piece pc;
        if (p->piece(p->ctx, s, 1, &pc) != 0 || pc.s_lo != s || !(pc.s_hi > s)) {
          gap = 1;
          break;
        }
        s = pc.s_hi;
        n++;
      }
      aq_check(!gap && s == p->s_c_rad, "%s %s: %d pieces tile [0, %.6g] (reached %.6g)",
               ARCHES[ai], p->name, n, p->s_c_rad, s);
    }
    aq_arch_free(a);
  }
}
