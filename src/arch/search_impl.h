/* search_impl.h: what the mechanism search (search.c) shares with its
 * exact enumeration (search_enum.c): the branch and bound's state and the
 * set functions both use; internal to src/arch.  Units: SI (m, kg, N);
 * lambda0 is a multiplier of g.  The bb's arrays are owned by search().
 */
#ifndef AQ_ARCH_SEARCH_IMPL_H
#define AQ_ARCH_SEARCH_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "model.h"

#define TIE_REL 1e-12     /* lambda0 within this (relative) of another is a tie */

/* The branch and bound over the programs (see search.c's comment). */
typedef struct {
  const aq_geom *g;
  double g_mps2;
  aq_lp4_row *lp;      /* the program's rows (aq_thrust_rows) */
  size_t nrows;
  unsigned char *ex;   /* rows excluded in the current branch */
  uint64_t ex_key;     /* the excluded rows' key: XOR of row_key(r) over them */
  uint64_t *seen;      /* keys of the branches solved (open addressing, 0 = empty) */
  int act;             /* 0: sets of either direction; -1, +1: only sets of that act_sign */
  int have;            /* best: the lowest admissible set so far */
  aq_hinge_set hs;
  double lambda0;
  int failed;          /* a program failed, or too many */
  size_t dir_programs; /* programs solved in this direction */
  size_t max_programs; /* at most (budget()) */
  int ran_out;         /* this direction used its budget without settling */
  aq_search_info info;
} bb;

/* First-order lambda0 from the hinge points P[k] and the joints; *act (if
 * not NULL): the sign of the ground acceleration that drives the set
 * (path.h act_sign), from the horizontal work rate of gravity's bodies. */
int aq_search_lambda0_fast(const aq_geom *g, const size_t j[4], const aq_vec2 P[4],
                           int open1, const int open[4], double *lambda0, int *act);

/* Faces as binary digits (e 0, i 1, the first hinge's the highest): the
 * order of ties. */
int aq_search_pattern(const aq_hinge_set *hs);

/* 1 if (la, a) comes before (lb, b): a lower lambda0 by more than a tie,
 * else on a tie the lower face pattern, then the lower joints. */
int aq_search_before(double la, const aq_hinge_set *a, double lb, const aq_hinge_set *b);

/* 1 if every hinge reaction of hs is compressive at s = 0 by the 9x9. */
int aq_search_compressive(const aq_geom *g, const aq_hinge_set *hs, double g_mps2);

/* The sets enumerated: 16 C(n + 1, 4). */
double aq_search_enum_count(size_t n);

/* Every set of direction act, by lambda0_fast, in batches of the lowest
 * that pass the screen, each checked by the 9x9 in increasing order, into
 * B's best (see search_enum.c); 0, or -1 when out of memory. */
int aq_search_enumerate(bb *B, int act);

#endif
