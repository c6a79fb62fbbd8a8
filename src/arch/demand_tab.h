/* demand_tab.h: the layout of a hinge set's demand tables, shared by the
 * files of the demand (demand.c builds them, demand_grid.c bounds them,
 * demand_track.c reads them along a run).  Private to src/arch. */
#ifndef AQ_ARCH_DEMAND_TAB_H
#define AQ_ARCH_DEMAND_TAB_H

#include <stddef.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <math.h>
#include <string.h>

#include "demand.h"

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
  aq_joint_form *entry; /* joint and hinge of each entry (forms unused) */
  double s_c;       /* rad */
  double mass_kg;   /* m_T, the forms' divisor */
  double err;       /* largest error measured against the exact forms, / tol scale */
  double scale;     /* the force scale of the tolerance (m/s^2 per m/s^2) */
  double w_ref;     /* sdot^2 / g of the reference energy, 1/m... rad^2/m */
  double lambda0;   /* the set's collapse multiplier (the grid's scale of a/g) */
  double ke_ref;    /* KE / g of the energy of collapse, m_T y(s_c), kg m */
  struct aq_demand_grid *grid; /* bounds over cells of states (demand_grid.c) */
};

static inline double aq_dt_cubic(const double c[4], double u)
{
  return c[0] + u * (c[1] + u * (c[2] + u * c[3]));
}

/* ---- the grid (demand_grid.c) ----
 * The states of a set, (s, a/g, KE/g), fall in cells: NS equal ranges of
 * s, NA equal ranges of a/g about 0 (each lambda0 / 8 wide) and NK ranges
 * of KE/g (0 to k0, then two per octave).  Per cell, an upper bound on
 * each quantity (|T|/N, |e|/N at a joint that is not a hinge) over every
 * entry and every state inside it, and the entries that may be the
 * largest there (the candidates: every other entry is below some
 * candidate's lower bound over the cell, so strictly below the state's
 * largest).  A state outside the grid (|a/g| >= 4 lambda0, KE/g >= k0
 * 2^DG_OCT) has no cell. */
enum { DG_NS = 64, DG_NA = 64, DG_OCT = 14, DG_KB = 1, DG_NK = 1 + (DG_OCT << DG_KB) };
#define DG_ALL 255 /* a count meaning: every entry */
#define DG_UNMADE 0xffff /* the bounds of a cell whose block is not made: above every key */

enum { DG_INLINE = 5, DG_WS = 16 };
/* The cells are made a block at a time: DG_AB a/g bins of a row (the
 * entries below the block's largest lower bound are left out of its
 * cells), the first time a state falls in one of them. */
enum { DG_AB = 4, DG_NB = DG_NA / DG_AB, DG_NBLK = DG_NS * DG_NK * DG_NB };
/* A candidate: its entry in the low 16 bits, the code of its own upper
 * bound over the cell (as the cell's, aq_dg_bound) in the high 16. */
typedef uint32_t aq_dg_cand;
typedef struct {
  aq_dg_cand c[DG_INLINE]; /* the candidates, those of |T|/N then those of |e|/N, when
                              there are at most DG_INLINE; else c[0] is their offset
                              in the block's pool */
  uint8_t n[2];            /* their counts (DG_ALL: every entry) */
} aq_dg_cell;

typedef struct aq_demand_grid {
  double inv_ds;  /* NS / s_c */
  double da, inv_da; /* a/g per bin */
  double k0, inv_k0; /* KE/g of the first bin's top */
  _Atomic uint32_t *hu; /* per cell, both quantities' upper bounds (|T|/N's in the low
                           half): the top half of a float's bits, rounded up
                           (aq_dg_bound); DG_UNMADE until its block is made (written
                           once, under lock; read without); index (is * NK + ik) * NA
                           + ia */
  /* Each block of cells is made the first time a state falls in it (under
   * lock, published by built[block]); a block that cannot be made (out of
   * memory) leaves its states outside the grid.  A made block is its
   * DG_AB cells, then its pool (the candidates of its cells that have
   * more than DG_INLINE), packed one after another in chunks of memory
   * that never move, so that the pages a run touches are few. */
  aq_dg_cell *blk[DG_NBLK];  /* per block (cell index / DG_AB), once made */
  unsigned char *chunk;      /* the chunk being filled (its first bytes: the one before) */
  size_t chunk_used, chunk_cap;
  const struct aq_demand_table *t;
  pthread_mutex_t lock;
  double *rng[DG_NS];        /* per range of s, once one of its blocks is made: each
                                entry's nine forms' ranges (lo, hi), then 1/M's */
  double *scratch;           /* the making's work space (under lock) */
  atomic_int built[DG_NBLK]; /* 1: made, 2: failed */
  /* The walls (states at rest, KE 0, at any s): per a/g bin, both
   * quantities' upper bounds over them, made the first time a leg's walls
   * under that a/g are asked about (aq_dg_wall_below), from each entry's
   * forms' ranges over DG_WS equal ranges of s (wrng, made with the first
   * bin; under lock, published by wall_made). */
  float wall[DG_NA][2];
  atomic_int wall_made[DG_NA]; /* 1: made, 2: failed (out of memory) */
  double *wrng;
} aq_demand_grid;

/* The range of cubic c (aq_dt_cubic) over u in [ua, ub]: its ends and its
 * turning points inside, widened by 1e-14 of the sum of its coefficients'
 * magnitudes (for the rounding of aq_dt_cubic). */
void aq_dg_cubic_range(const double c[4], double ua, double ub, double *lo, double *hi);
/* Make block b of cells (cell index / DG_AB; demand_grid.c); 0, or -1
 * when it cannot be made. */
int aq_dg_make(aq_demand_grid *g, size_t b);

/* The grid of table t (NULL: out of memory, or a table too large). */
aq_demand_grid *aq_dg_build(const aq_demand_table *t);
void aq_dg_free(aq_demand_grid *g);

/* The row of states (s, KE/g = kg), is * DG_NK + ik, or -1 (outside the
 * grid).  Its cells may not be made yet (aq_dg_ready). */
static inline long aq_dg_row(const aq_demand_grid *g, double s, double kg)
{
  double xs = s * g->inv_ds, xk = kg * g->inv_k0;
  if (!(xs >= 0 && xs < DG_NS + 1.0 && xk >= 0 && xk < (double)(1ULL << DG_OCT)))
    return -1;
  size_t is = (size_t)xs, ik = 0;
  if (is >= DG_NS)
    is = DG_NS - 1;
  if (xk >= 1) {
    uint64_t bits;
    memcpy(&bits, &xk, sizeof bits);
    ik = 1 + ((size_t)(((bits >> 52) & 0x7ff) - 1023) << DG_KB) +
         (size_t)((bits >> (52 - DG_KB)) & ((1u << DG_KB) - 1));
  }
  return (long)(is * DG_NK + ik);
}

/* 1: cell c's block is made, made now the first time; 0: it cannot be. */
static inline int aq_dg_ready(aq_demand_grid *g, long c)
{
  size_t k = (size_t)c / DG_AB;
  int b = atomic_load_explicit(&g->built[k], memory_order_acquire);
  return b == 1 || (b == 0 && aq_dg_make(g, k) == 0);
}

/* The cell of a/g al in row r (aq_dg_row), or -1 (r < 0, or al outside). */
static inline long aq_dg_cell_in(const aq_demand_grid *g, long r, double al)
{
  double xa = al * g->inv_da + 0.5 * DG_NA;
  if (r < 0 || !(xa >= 0 && xa < DG_NA))
    return -1;
  return r * DG_NA + (long)xa;
}

/* Cell c's bound codes, |T|/N's in the low half (DG_UNMADE in both: its
 * block is not made). */
static inline uint32_t aq_dg_codes(const aq_demand_grid *g, long c)
{
  return atomic_load_explicit(&g->hu[c], memory_order_relaxed);
}

/* Cell c's bound code of quantity q (DG_UNMADE: its block is not made). */
static inline uint16_t aq_dg_code(const aq_demand_grid *g, long c, int q)
{
  return (uint16_t)(aq_dg_codes(g, c) >> (16 * q));
}

/* The cell of a state, or -1 (outside the grid, or in a block that
 * cannot be made).  Makes the state's block the first time. */
static inline long aq_dg_index(aq_demand_grid *g, double s, double al, double kg)
{
  long c = aq_dg_cell_in(g, aq_dg_row(g, s, kg), al);
  return c >= 0 && aq_dg_ready(g, c) ? c : -1;
}

/* Cell ic, of a made block (aq_dg_ready). */
static inline const aq_dg_cell *aq_dg_cell_at(const aq_demand_grid *g, long ic)
{
  return g->blk[(size_t)ic / DG_AB] + (size_t)ic % DG_AB;
}

/* The candidates of cell ic, of a made block. */
static inline const aq_dg_cand *aq_dg_cands(const aq_demand_grid *g, long ic)
{
  const aq_dg_cell *c = aq_dg_cell_at(g, ic);
  size_t n = (c->n[0] == DG_ALL ? 0 : c->n[0]) + (c->n[1] == DG_ALL ? 0 : c->n[1]);
  return n <= DG_INLINE ? c->c
                        : (const aq_dg_cand *)(const void *)(g->blk[(size_t)ic / DG_AB] + DG_AB) +
                              c->c[0];
}

/* Make the walls' bounds of a/g bin ia (demand_grid.c): 1, or 2 when they
 * cannot be. */
int aq_dg_make_wall(aq_demand_grid *g, size_t ia);

/* 1: no state at rest (KE 0) under a/g al exceeds the maxima m[2] (its
 * a/g bin's bounds made the first time). */
static inline int aq_dg_wall_below(aq_demand_grid *g, double al, const double m[2])
{
  double xa = al * g->inv_da + 0.5 * DG_NA;
  if (!(xa >= 0 && xa < DG_NA))
    return 0;
  size_t ia = (size_t)xa;
  int b = atomic_load_explicit(&g->wall_made[ia], memory_order_acquire);
  if (b == 0)
    b = aq_dg_make_wall(g, ia);
  const float *w = g->wall[ia];
  return b == 1 && !(w[0] > m[0]) && !(w[1] > m[1]);
}

/* The code of a bound at least u (u >= 0): the top half of the bits of a
 * float at least u, rounded up (8 significant bits; aq_dg_bound). */
static inline uint16_t aq_dg_upper16(double u)
{
  if (!(u < 3e38))
    return 0x7f80; /* INFINITY (and NAN: no bound) */
  float f = (float)u;
  uint32_t b;
  memcpy(&b, &f, sizeof b);
  b += (double)f < u; /* the next float up (f >= 0) */
  return (uint16_t)((b + 0xffffu) >> 16);
}

/* The largest code whose bound is at most m (m >= 0): a cell's bound
 * exceeds m exactly when its code exceeds this one. */
static inline uint16_t aq_dg_floor16(double m)
{
  if (!(m < 3e38))
    return 0x7f80;
  float f = (float)m;
  if ((double)f > m)
    f = nextafterf(f, 0);
  uint32_t b;
  memcpy(&b, &f, sizeof b);
  return (uint16_t)(b >> 16);
}

/* Cell c's upper bound of quantity q. */
static inline double aq_dg_bound(const aq_demand_grid *g, long c, int q)
{
  uint32_t b = (uint32_t)aq_dg_code(g, c, q) << 16;
  float f;
  memcpy(&f, &b, sizeof f);
  return f;
}

#endif
