/* workpath_impl.h: the inside of a work path (struct aq_workpath), shared
 * by workpath.c (the exact path, its end, the build, the bytes),
 * workpath_table.c (the Hermite tables) and workpath_piece.c (the Taylor
 * leg's pieces); internal to src/arch.  Units: SI (m, kg, rad).  The
 * arrays of struct aq_workpath are owned by it (aq_workpath_free).
 */
#ifndef AQ_ARCH_WORKPATH_IMPL_H
#define AQ_ARCH_WORKPATH_IMPL_H

#include <stddef.h>

#include "model.h"

#define TABLE_REL_TOL 4e-12    /* target relative error of the tables (round-off floor ~1e-12) */
#define TABLE_STALL 0.5        /* a split must at least halve the error ... */
#define PIECE_TAIL_TOL 2e-15    /* Chebyshev tail / scale (about ten unit round-offs) */

/* Tabled functions, each from its value, first and second derivative at the
 * nodes.  F_DX, F_DY are dx/ds, dy/ds (from the second and third
 * derivatives), so that d2x/ds2, d2y/ds2 come from a first derivative of an
 * interpolant (round-off eps/h rather than eps/h^2). */
enum { F_X = 0, F_Y, F_DX, F_DY, F_M, F_B0 /* then 3 per body: x, y, phi */, NF = F_B0 + 9 };

struct aq_workpath {
  aq_path path;
  aq_mech mech;
  const aq_geom *g;
  double g_mps2;
  aq_vec2 c0[3];      /* body centroids at s = 0 as evaluated */
  aq_end end;
  char reason[200];
  char name[16];
  size_t n;           /* table intervals */
  double *bp;         /* n+1 breakpoints, rad */
  double *coef;       /* n * NF * 6 power-basis coefficients in t = (s - bp[i]) / h_i */
  size_t npc;         /* the Taylor leg's pieces (Chebyshev fits) */
  double *pbp;        /* npc+1 breakpoints, rad */
  aq_path_piece *piece; /* npc pieces for path.h */
  size_t pcap;        /* allocated pieces */
  size_t cap;         /* allocated intervals */
  double tab_err;
  double thrust0;     /* max |eccentricity| of the thrust at s = 0 */
  size_t max_n;       /* table intervals and pieces at most (TABLE_MAX_INTERVALS) */
  /* where the tables or the pieces ran out of intervals (build_tables -2):
   * the start of the interval that found none left, rad, and the finest
   * interval so far (its halvings of the first grid, its start, rad) */
  double out_s, fine_s;
  int fine_depth;
};

/* ---- workpath.c */

/* Exact values f[k][0..2] (value, d/ds, d2/ds2) of every tabled function. */
int aq_workpath_exact_f(const aq_workpath *w, double s, double f[NF][3],
                        aq_mech_state *stout);

/* The path point p (path.h) from the values f of every tabled function. */
void aq_workpath_fill_point(const aq_workpath *w, double f[NF][3], aq_path_point *p);

/* s checked and clamped into [0, s_c]; -1 outside. */
int aq_workpath_clamp_s(const aq_workpath *w, double *s);

/* ---- workpath_table.c */

/* path.h eval: the point at s from the tables; -1 outside [0, s_c]. */
int aq_workpath_eval_table(const void *ctx, double s, aq_path_point *p);

/* x_mono_rad (path.h): the first s where the tabled slope dx/ds, sampled
 * at X_MONO_SAMPLES points per interval, leaves the sign it has at s = 0. */
double aq_workpath_x_mono(const aq_workpath *w);

/* Tables over [0, s_c]: TABLE_N0 equal intervals, each refined by halving
 * where needed (refine), so that the grid is fine only where the path
 * varies fast (near a toggle); then the Taylor leg's pieces.  -1 on failure
 * (memory, or the linkage), -2 when the tables would need more than
 * w->max_n intervals, -3 when the pieces would (w->out_s, fine_s and
 * fine_depth say where). */
int aq_workpath_build_tables(aq_workpath *w);

/* ---- workpath_piece.c */

/* The pieces over [0, s_c]; 0, -1 on failure, -2 when too many. */
int aq_workpath_build_pieces(aq_workpath *w);

/* path.h piece: the piece holding s for direction dir; -1 outside [0, s_c]. */
int aq_workpath_eval_piece(const void *ctx, double s, int dir, aq_path_piece *pc);

#endif
