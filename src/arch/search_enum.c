/* search_enum.c: the exact enumeration of the mechanism search (search.c,
 * search_impl.h), when a direction's branch and bound runs out of its
 * budget: every four-hinge set the direction drives, by lambda0_fast, in
 * batches of the lowest that pass a screen by the program's rows, each
 * checked by the 9x9 in increasing order.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "search_impl.h"

/* A set as one 32-bit key (n + 1 <= 128 joints): its face pattern (the
 * order of ties, pattern()), then its joints, so that the order of keys is
 * before()'s among sets of equal lambda0. */
typedef struct {
  double l0;
  uint32_t key;
} cand;

static uint32_t set_key(int pat, const size_t j[4])
{
  return (uint32_t)pat << 28 | (uint32_t)j[0] << 21 | (uint32_t)j[1] << 14 |
         (uint32_t)j[2] << 7 | (uint32_t)j[3];
}

static void key_set(uint32_t key, aq_hinge_set *hs)
{
  for (int k = 0; k < 4; k++) {
    hs->joint[k] = (key >> (7 * (3 - k))) & 127;
    hs->face[k] = (key >> (28 + 3 - k)) & 1 ? 'i' : 'e';
  }
}

/* 1 if a comes after b: a larger lambda0, or an equal one and a larger key. */
static int cand_after(const cand *a, const cand *b)
{
  return a->l0 > b->l0 || (a->l0 == b->l0 && a->key > b->key);
}

static int cand_cmp(const void *a, const void *b)
{
  return cand_after(a, b) - cand_after(b, a);
}

/* The sets enumerated: 16 C(n + 1, 4). */
double aq_search_enum_count(size_t n)
{
  double m = (double)n + 1;
  return 16 * m * (m - 1) * (m - 2) * (m - 3) / 24;
}

/* A cheap screen before the 9x9: 1 unless the line of thrust through the
 * four hinge points r[0..3] (the program's rows made tight, a 4x4 solved
 * by elimination) pulls across a hinge's joint, i.e. leaves the other end
 * of that joint's row violated by more than ENUM_SCREEN (the rows' scaled
 * units).  A singular system passes (the 9x9 decides). */
#define ENUM_SCREEN 1e-9

static int screen(const aq_lp4_row *lp, const size_t r[4])
{
  double A[4][5];
  for (int i = 0; i < 4; i++) {
    for (int k = 0; k < 4; k++)
      A[i][k] = lp[r[i]].g[k];
    A[i][4] = lp[r[i]].h;
  }
  for (int c = 0; c < 4; c++) {
    int piv = c;
    for (int i = c + 1; i < 4; i++)
      if (fabs(A[i][c]) > fabs(A[piv][c]))
        piv = i;
    if (!(fabs(A[piv][c]) > 1e-14))
      return 1;
    for (int k = 0; k < 5; k++) {
      double t = A[c][k];
      A[c][k] = A[piv][k];
      A[piv][k] = t;
    }
    for (int i = 0; i < 4; i++)
      if (i != c) {
        double f = A[i][c] / A[c][c];
        for (int k = c; k < 5; k++)
          A[i][k] -= f * A[c][k];
      }
  }
  double x[4];
  for (int k = 0; k < 4; k++)
    x[k] = A[k][4] / A[k][k];
  for (int i = 0; i < 4; i++) {
    const aq_lp4_row *o = &lp[r[i] ^ 1];
    double gx = 0;
    for (int k = 0; k < 4; k++)
      gx += o->g[k] * x[k];
    if (o->h - gx < -ENUM_SCREEN)
      return 0;
  }
  return 1;
}

/* Every set of every face pattern that ground acceleration of sign act
 * drives, by lambda0_fast, in batches of the ENUM_BATCH lowest (above the
 * previous batch, at most B's best) that pass screen(), each batch checked
 * with the 9x9 in increasing order: the lowest admissible set merges into
 * B (before()).  The rows B->lp must be those of the direction act drives
 * (s = -act).  0, or -1 out of memory. */
#define ENUM_BATCH 256

int aq_search_enumerate(bb *B, int act)
{
  const aq_geom *g = B->g;
  size_t n = g->p.voussoirs;
  aq_vec2 *pt = malloc(2 * (n + 1) * sizeof *pt);
  cand *heap = malloc(ENUM_BATCH * sizeof *heap);
  if (!pt || !heap) {
    free(pt);
    free(heap);
    return -1;
  }
  for (size_t j = 0; j <= n; j++) {
    pt[2 * j] = aq_geom_joint_point(g, j, 'i');
    pt[2 * j + 1] = aq_geom_joint_point(g, j, 'e');
  }
  cand floor = {-HUGE_VAL, 0};
  int have_floor = 0;
  B->info.enumerated = 1;
  for (;;) {
    size_t nh = 0;
    double cap = B->have ? B->lambda0 + TIE_REL * fabs(B->lambda0) : HUGE_VAL;
    for (int pat = 0; pat < 16; pat++) {
      int open[4];
      for (int k = 0; k < 4; k++)
        open[k] = (pat >> (3 - k)) & 1 ? 1 : -1; /* i opens +1 */
      size_t j[4];
      for (j[0] = 0; j[0] + 3 <= n; j[0]++)
        for (j[1] = j[0] + 1; j[1] + 2 <= n; j[1]++)
          for (j[2] = j[1] + 1; j[2] + 1 <= n; j[2]++)
            for (j[3] = j[2] + 1; j[3] <= n; j[3]++) {
              size_t r[4];
              aq_vec2 P[4];
              for (int k = 0; k < 4; k++) {
                r[k] = 2 * j[k] + (open[k] < 0);
                P[k] = pt[r[k]];
              }
              double l0;
              int a = 0;
              if (!aq_search_lambda0_fast(g, j, P, open[0], open, &l0, &a) || a != act ||
                  !isfinite(l0) || l0 > cap)
                continue;
              cand c = {l0, set_key(pat, j)};
              if ((have_floor && !cand_after(&c, &floor)) ||
                  (nh == ENUM_BATCH && !cand_after(&heap[0], &c)) || !screen(B->lp, r))
                continue;
              size_t i = nh;
              if (nh < ENUM_BATCH) { /* push, sift up */
                nh++;
                for (; i > 0 && cand_after(&c, &heap[(i - 1) / 2]); i = (i - 1) / 2)
                  heap[i] = heap[(i - 1) / 2];
              } else { /* replace the largest, sift down */
                i = 0;
                for (;;) {
                  size_t ch = 2 * i + 1;
                  if (ch >= nh)
                    break;
                  if (ch + 1 < nh && cand_after(&heap[ch + 1], &heap[ch]))
                    ch++;
                  if (!cand_after(&heap[ch], &c))
                    break;
                  heap[i] = heap[ch];
                  i = ch;
                }
              }
              heap[i] = c;
            }
    }
    if (nh == 0)
      break;
    qsort(heap, nh, sizeof *heap, cand_cmp);
    for (size_t i = 0; i < nh; i++) {
      aq_hinge_set hs;
      key_set(heap[i].key, &hs);
      if (B->have && !aq_search_before(heap[i].l0, &hs, B->lambda0, &B->hs))
        continue;
      if (!aq_search_compressive(g, &hs, B->g_mps2))
        continue;
      B->have = 1;
      B->hs = hs;
      B->lambda0 = heap[i].l0;
    }
    if (nh < ENUM_BATCH || (B->have && heap[nh - 1].l0 > B->lambda0 + TIE_REL * fabs(B->lambda0)))
      break; /* every candidate was in this batch, or the rest are above the minimum */
    floor = heap[nh - 1];
    have_floor = 1;
  }
  free(pt);
  free(heap);
  return 0;
}
