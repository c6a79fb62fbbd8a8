/* search.c: the arch's minimum-lambda0 four-hinge mechanism, over every
 * joint and every face, by the static (lower-bound) side of limit analysis.
 *
 * A hinge set is admissible when each of its four hinges opens as the
 * mechanism moves (docs/method.md sec. 8) and every hinge reaction is
 * compressive; its multiplier lambda0 comes from virtual work at s = 0
 * (docs/method.md sec. 5).  Enumerating the sets costs 16 C(n+1, 4) for n
 * voussoirs (4e11 at 1000).  The minimum is found instead with a linear
 * program whose dual is that enumeration:
 *
 *   unknowns  the force (R0x, R0y) and its moment m0 about a reference
 *             point that the ground exerts across joint 0, and lambda, the
 *             horizontal body force per unit mass s lambda g (s = +1 or
 *             -1: one program per direction);
 *   maximize  lambda,
 *   such that across every joint j the resultant of the ground's force and
 *             the loads of voussoirs 0..j-1 (gravity and the horizontal
 *             force, at each voussoir's centroid, fill and attached masses
 *             included) is a compression between the joint's ends: its
 *             moment about the intrados end Pi_j is >= 0 and about the
 *             extrados end Pe_j is <= 0 (joint direction u = Pe - Pi,
 *             normal J u into voussoir j: a compressive force b at Pe has
 *             moment |Pe - Pi| b about Pi).
 *
 * The moment across joint j about a point P is linear in the unknowns:
 *   M_j(P) = m0 + P_y R0x - P_x R0y + s lambda g (P_y m_j - S^y_j)
 *                                   + g (P_x m_j - S^x_j)
 * with m_j, S^x_j, S^y_j the mass and first moments of voussoirs 0..j-1
 * (prefix sums).  The dual variables of the two rows of joint j are the
 * rotations of an intrados or an extrados hinge there, so the dual is the
 * minimum over mechanisms of any hinge count of their kinematic
 * multiplier (static and kinematic theorems); the program has four
 * unknowns, so an optimal vertex has four tight rows.  When they are four
 * hinges on four joints, they are the minimum-lambda0 four-hinge set: its
 * line of thrust passes through them and lies inside the arch elsewhere,
 * so its hinge reactions are compressive.  GLPK solves each program
 * through its dual (a basis of four rows, whatever the number of joints),
 * in floating point and, when the vertex leaves a row violated by more
 * than OPT_TOL (recomputed here in long double), again in rational
 * arithmetic (glp_exact) from that basis.
 *
 * The vertex can also hold both ends of one joint: a mechanism in which
 * that joint lifts off (flat or thick arches under large lambda, about 6
 * and more in the tests), which no four-hinge set can do and archquake
 * does not model.  A branch and bound then finds the four-hinge minimum:
 * a branch excludes rows (no hinge there: the row's dual fixed at 0, the
 * row dropped from the program), so its optimum bounds every set in it
 * from below; a vertex lifting joint j off branches into "no hinge at
 * Pe_j" and "no hinge at Pi_j"; a vertex of four joints whose set is not
 * admissible (with rows dropped its reactions need not be compressive)
 * branches four ways, each without one of its hinges; a branch whose
 * optimum is above the best set found is dropped.  The lift-off's lambda
 * is reported (aq_search_info), for the warning that the four-hinge
 * minimum is then above the arch's collapse multiplier.
 *
 * When a lift-off governs, no four-hinge set is statically admissible: one
 * whose line of thrust stayed inside the arch would be a feasible point of
 * the program with lambda = its lambda0 (static theorem: <= the optimum)
 * and a mechanism (kinematic theorem: >= the optimum), so it would tie the
 * optimum and be among the vertex's tight rows.  The four-hinge minimum is
 * then the lowest load at which a four-hinge mechanism can form, an upper
 * bound above the lift-off's; its line of thrust leaves the section.
 *
 * The branch and bound is exact but can need many programs on flat arches
 * (every four-hinge set there has its thrust outside the arch, so the
 * bound, the line of thrust kept inside, is loose): a direction's branch
 * and bound has a budget of programs, about the time of enumerating every
 * set (budget()), and when it runs out every set of that direction is
 * enumerated instead (enumerate(): lambda0_fast for each of the 16 C(n+1,
 * 4), a screen by the program's rows, the 9x9 for the lowest in increasing
 * order), up to ENUM_MAX sets (74 voussoirs).  Beyond that the search gives
 * up in one line naming the lift-off that governs (the enumeration is in
 * search_enum.c).
 *
 * The set read from a vertex has its lambda0 computed again by virtual
 * work (lambda0_fast: the same formula and prefix sums for every set) and
 * checked with the 9x9 (eq. (3): every hinge reaction compressive).  Of
 * the two directions the lower lambda0 wins; ties (within TIE_REL, e.g.
 * the mirror images of a symmetric arch) go to the lower face pattern
 * (faces read as binary digits, e 0 and i 1, so e i e i before i e i e),
 * then to the lower joints.
 *
 * One direction alone (aq_search_direction, for an arch whose hinges are
 * free: each direction of ground acceleration drives its own minimum):
 * only that direction's program, and only sets that the direction drives
 * (act_sign, from the horizontal work of the set's bodies) are read from
 * its vertices.
 *
 * An arch that cannot stand: when the optimum of a direction is <= 0 the
 * set read from it has lambda0 <= 0 (gravity alone, or gravity with a load
 * the other way, drives it).  When no lambda at all lets a line of thrust
 * fit (both programs infeasible), a third program at lambda = 0 relaxes
 * every row by sigma times the joint's half length (in units of the
 * arch's weight times a length) and minimizes sigma: its tight rows are
 * the mechanism whose hinges gain the most work from gravity, a set with
 * lambda0 < 0, reported as the arch's minimum (not necessarily the lowest
 * such set).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "search_impl.h"

#define TIGHT_REL 1e-9    /* a row within this of its bound (in the scaled moments, units of
                             the arch's weight times its size) counts as tight */
#define OPT_TOL 1e-13     /* a row's slack (scaled moment) this far below 0 is a violation */
#define MAX_PROGRAMS 4096 /* programs solved at most in a direction's branch and bound */
#define MIN_PROGRAMS 16   /* ... and at least, before it gives way to the enumeration */
#define SETS_PER_PROGRAM 2500.0 /* sets enumerated in the time of one program (measured 20 ns
                                   a set, 50-150 us a program at 20-74 voussoirs) */
#define ENUM_MAX 2e7      /* sets enumerated at most when it runs out: 16 C(n + 1, 4),
                             n <= 74 voussoirs */
#define MAX_TIGHT AQ_LP4_MAX_TIGHT /* tight rows examined at most (C(12, 4) = 495 subsets) */

static double cross(aq_vec2 a, aq_vec2 b) { return a.x * b.y - a.y * b.x; }

/* First-order lambda0 from the hinge points P[k] and the joints; *act (if
 * not NULL): the sign of the ground acceleration that drives the set
 * (path.h act_sign), from the horizontal work rate of gravity's bodies. */
int aq_search_lambda0_fast(const aq_geom *g, const size_t j[4], const aq_vec2 P[4],
                           int open1, const int open[4], double *lambda0, int *act)
{
  aq_vec2 v1 = {P[1].x - P[0].x, P[1].y - P[0].y};
  aq_vec2 v2 = {P[2].x - P[1].x, P[2].y - P[1].y};
  aq_vec2 v3 = {P[3].x - P[2].x, P[3].y - P[2].y};
  double det = cross(v2, v3);
  if (det == 0)
    return 0;
  aq_vec2 w = {-v1.x, -v1.y};
  double a = cross(w, v3) / det, b = cross(v2, w) / det;
  double rate[4] = {1.0, a - 1.0, b - a, -b};
  for (int k = 0; k < 4; k++)
    if (!(open[k] * open1 * rate[k] > 0))
      return 0;
  double m[3], sx[3], sy[3];
  for (int k = 0; k < 3; k++) {
    m[k] = g->cum_m[j[k + 1]] - g->cum_m[j[k]];
    sx[k] = g->cum_mx[j[k + 1]] - g->cum_mx[j[k]];
    sy[k] = g->cum_my[j[k + 1]] - g->cum_my[j[k]];
  }
  /* sum_b m_b dc_b/dq: J(S1 - m1 H1) + m2 J v1 + a J(S2 - m2 H2) + b J(S3 - m3 H4) */
  double gx = -(sy[0] - m[0] * P[0].y) - m[1] * v1.y - a * (sy[1] - m[1] * P[1].y) -
              b * (sy[2] - m[2] * P[3].y);
  double gy = (sx[0] - m[0] * P[0].x) + m[1] * v1.x + a * (sx[1] - m[1] * P[1].x) +
              b * (sx[2] - m[2] * P[3].x);
  if (gx == 0)
    return 0;
  *lambda0 = (double)open1 * gy / fabs(gx);
  if (act) /* a horizontal body force along -act_sign x does positive work (aq_search_compressive()) */
    *act = (double)open1 * gx > 0 ? -1 : 1;
  return 1;
}

/* aq_search_lambda0 with the set's act_sign (*act, if not NULL). */
static int set_lambda0(const aq_geom *g, const aq_hinge_set *hs, double *lambda0, int *act)
{
  aq_vec2 P[4];
  int open[4];
  for (int k = 0; k < 4; k++) {
    if (hs->joint[k] > g->p.voussoirs || (k > 0 && hs->joint[k] <= hs->joint[k - 1]))
      return 0;
    P[k] = aq_geom_joint_point(g, hs->joint[k], hs->face[k]);
    open[k] = hs->face[k] == 'i' ? 1 : -1;
  }
  return aq_search_lambda0_fast(g, hs->joint, P, open[0], open, lambda0, act);
}

int aq_search_lambda0(const aq_geom *g, const aq_hinge_set *hs, double *lambda0)
{
  return set_lambda0(g, hs, lambda0, NULL);
}

int aq_search_act_sign(const aq_geom *g, const aq_hinge_set *hs)
{
  double l0;
  int act = 0;
  return set_lambda0(g, hs, &l0, &act) ? act : 0;
}

/* Faces as binary digits (e 0, i 1, the first hinge's the highest): the
 * order of ties. */
int aq_search_pattern(const aq_hinge_set *hs)
{
  int p = 0;
  for (int k = 0; k < 4; k++)
    p = 2 * p + (hs->face[k] == 'i');
  return p;
}

/* 1 if (la, a) comes before (lb, b): a lower lambda0 by more than a tie,
 * else on a tie the lower face pattern, then the lower joints. */
int aq_search_before(double la, const aq_hinge_set *a, double lb, const aq_hinge_set *b)
{
  if (la < lb - TIE_REL * fabs(lb))
    return 1;
  if (lb < la - TIE_REL * fabs(la))
    return 0;
  if (aq_search_pattern(a) != aq_search_pattern(b))
    return aq_search_pattern(a) < aq_search_pattern(b);
  for (int k = 0; k < 4; k++)
    if (a->joint[k] != b->joint[k])
      return a->joint[k] < b->joint[k];
  return 0;
}

/* 1 if every hinge reaction of hs is compressive at s = 0 by the 9x9. */
int aq_search_compressive(const aq_geom *g, const aq_hinge_set *hs, double g_mps2)
{
  aq_mech m;
  aq_mech_state s0;
  aq_equil eq;
  aq_error e2;
  if (aq_mech_init(&m, g, hs, &e2) != AQ_OK || aq_mech_eval(&m, 0.0, &s0) != 0)
    return 0;
  /* act_sign: the sign that drives s forward (see workpath.c) */
  double gx = 0;
  for (int b = 0; b < 3; b++)
    gx += m.body[b].mass_kg * s0.c[b][1].x;
  int act = (double)m.open[0] * gx > 0 ? -1 : 1;
  aq_live live = {AQ_LIVE_HORIZONTAL, act, {0, 0}, 0, g_mps2};
  if (aq_mech_equilibrium(&m, &s0, &live, &eq, &e2) != AQ_OK)
    return 0;
  for (int k = 0; k < 4; k++)
    if (!(eq.normal[k] > 0))
      return 0;
  return 1;
}

typedef enum { LP_OPT, LP_INFEASIBLE, LP_UNBOUNDED, LP_FAILED } lp_status;

/* One program (lp4.c): relax = 0 maximizes lambda; relax = 1 fixes
 * lambda = 0 and minimizes sigma.  Its dual's variables, one per row, are
 * the rotations of a hinge at that row's joint end; a row excluded (ex[i])
 * has its rotation fixed at 0: no hinge there.  The vertex's rows (tight[0
 * .. *nbasic-1]), then the rows within TIGHT_REL of their bound (ties);
 * *obj: the optimum (lambda, or -sigma). */
static lp_status lp_solve(const aq_lp4_row *lp, size_t nrows, int relax,
                          const unsigned char *ex, size_t *tight, size_t *ntight,
                          size_t *nbasic, double *obj)
{
  static const double c_max[4] = {0, 0, 0, 1}, c_relax[4] = {0, 0, 0, -1};
  const aq_lp4_opts o = {OPT_TOL, TIGHT_REL, MAX_TIGHT, 0};
  aq_lp4_result r = {.y = NULL};
  aq_lp4_status s = aq_lp4_solve(lp, nrows, relax ? c_relax : c_max, ex, &o, &r);
  *ntight = r.ntight;
  *nbasic = r.nbasic;
  for (size_t k = 0; k < r.ntight; k++)
    tight[k] = r.tight[k];
  if (s == AQ_LP4_OPT)
    *obj = r.obj;
  return s == AQ_LP4_OPT ? LP_OPT : s == AQ_LP4_INFEASIBLE ? LP_INFEASIBLE
         : s == AQ_LP4_UNBOUNDED ? LP_UNBOUNDED : LP_FAILED;
}

/* The set of four rows r (joint 2r/2, face e for odd r), if they are on
 * distinct joints and make an admissible set: every hinge opens, and
 * unless relax compressive hinge reactions, or when relax lambda0 <= 0.
 * 1 and *hs, *l0; else 0. */
static int admissible(const bb *B, const size_t rows[4], int relax, aq_hinge_set *hs,
                      double *l0)
{
  size_t r[4] = {rows[0], rows[1], rows[2], rows[3]};
  for (int i = 1; i < 4; i++) /* by joint */
    for (int k = i; k > 0 && r[k] < r[k - 1]; k--) {
      size_t t = r[k];
      r[k] = r[k - 1];
      r[k - 1] = t;
    }
  for (int k = 0; k < 4; k++) {
    hs->joint[k] = r[k] / 2;
    hs->face[k] = r[k] % 2 ? 'e' : 'i';
    if (k > 0 && hs->joint[k] == hs->joint[k - 1])
      return 0;
  }
  int act = 0;
  if (!set_lambda0(B->g, hs, l0, &act) || !isfinite(*l0) || (B->act && act != B->act))
    return 0;
  return relax ? *l0 <= 0 : aq_search_compressive(B->g, hs, B->g_mps2);
}

/* Every four of the tight rows that make an admissible set: the best
 * (before()) into B.  Returns 1 if the vertex's own four (the first four,
 * nbasic == 4) do. */
static int from_tight(bb *B, const size_t *tight, size_t nt, size_t nbasic, int relax)
{
  int vertex = 0;
  for (size_t a = 0; a < nt; a++)
    for (size_t c = a + 1; c < nt; c++)
      for (size_t d = c + 1; d < nt; d++)
        for (size_t e = d + 1; e < nt; e++) {
          size_t r[4] = {tight[a], tight[c], tight[d], tight[e]};
          aq_hinge_set hs;
          double l0;
          if (!admissible(B, r, relax, &hs, &l0))
            continue;
          vertex |= nbasic == 4 && e == 3;
          if (B->have && !aq_search_before(l0, &hs, B->lambda0, &B->hs))
            continue;
          B->have = 1;
          B->hs = hs;
          B->lambda0 = l0;
        }
  return vertex;
}

/* A branch is its set of excluded rows, whatever the order in which they
 * were excluded: the four-way branching reaches the same set by many paths
 * (excluding a then b, or b then a), and a branch solved once has had its
 * sets read and its subtree searched (the bound only tightens after), so a
 * second visit is skipped.  A set of rows is keyed by the XOR of a 64-bit
 * key per row (Zobrist hashing; splitmix64 of the row): two different sets
 * share a key with probability about 2^-64 per pair. */
#define SEEN_SLOTS 16384 /* a power of two above 2 MAX_PROGRAMS */
static uint64_t row_key(size_t r)
{
  uint64_t z = (uint64_t)r + 0x9e3779b97f4a7c15u;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
  return (z ^ (z >> 31)) | 1; /* never 0: 0 marks an empty slot */
}

/* 1 if the current branch was solved before; else records it and 0. */
static int seen_before(bb *B)
{
  uint64_t k = B->ex_key ? B->ex_key : 1; /* the root: nothing excluded */
  for (size_t i = (size_t)(k >> 7) & (SEEN_SLOTS - 1);; i = (i + 1) & (SEEN_SLOTS - 1)) {
    if (B->seen[i] == k)
      return 1;
    if (!B->seen[i]) {
      B->seen[i] = k;
      return 0;
    }
  }
}

/* Solve the program with row r excluded as well, then restore it. */
static lp_status node(bb *B, int relax, int depth);
static void child(bb *B, size_t r, int relax, int depth)
{
  B->ex[r] = 1;
  B->ex_key ^= row_key(r);
  if (!seen_before(B))
    node(B, relax, depth + 1);
  B->ex_key ^= row_key(r);
  B->ex[r] = 0;
}

/* One node of the branch and bound: solve, bound, then
 *  - a joint with both ends tight (lifting off, which no four-hinge set
 *    does): branch without a hinge at its extrados end, then without one
 *    at its intrados end (every four-hinge set lies in one of the two);
 *  - else the vertex's four hinges: the set, if admissible, is the
 *    branch's minimum; if not (with rows excluded its reactions need not
 *    be compressive), every admissible set in the branch lacks one of its
 *    hinges: branch four ways, each without one of them.
 * In the relaxed program (relax) the first set with lambda0 <= 0 ends the
 * search.  Returns the node's status. */
static lp_status node(bb *B, int relax, int depth)
{
  size_t tight[MAX_TIGHT], nt, nb;
  double obj = 0;
  if (B->failed || (relax && B->have))
    return LP_FAILED;
  B->info.programs++;
  if (++B->dir_programs > B->max_programs) {
    B->failed = B->ran_out = 1;
    return LP_FAILED;
  }
  lp_status st = lp_solve(B->lp, B->nrows, relax, B->ex, tight, &nt, &nb, &obj);
  if (st == LP_FAILED)
    B->failed = 1;
  if (st != LP_OPT)
    return st;
  if (relax ? !(obj < 0) : B->have && obj > B->lambda0 + TIE_REL * fabs(B->lambda0))
    return st; /* relax: gravity drives nothing here; else: no lower set here */
  size_t lift = SIZE_MAX;
  for (size_t a = 0; a < nb; a++)
    for (size_t b = a + 1; b < nb; b++)
      if (tight[a] / 2 == tight[b] / 2)
        lift = tight[a] / 2;
  if (lift != SIZE_MAX) {
    if (depth == 0 && !relax && (!B->info.liftoff || obj < B->info.liftoff_lambda)) {
      B->info.liftoff = 1;
      B->info.liftoff_joint = lift;
      B->info.liftoff_lambda = obj;
    }
    child(B, 2 * lift + 1, relax, depth);
    child(B, 2 * lift, relax, depth);
  } else if (!from_tight(B, tight, nt, nb, relax) && nb == 4) {
    for (size_t k = 0; k < 4; k++)
      child(B, tight[k], relax, depth);
  }
  return st;
}

/* The programs a direction's branch and bound may solve: about the time
 * the enumeration would take (so that an arch the branch and bound does not
 * settle costs at most twice the enumeration), within [MIN_PROGRAMS,
 * MAX_PROGRAMS]; MAX_PROGRAMS when the enumeration is out of reach. */
static size_t budget(size_t n)
{
  double e = aq_search_enum_count(n);
  if (e > ENUM_MAX)
    return MAX_PROGRAMS;
  double p = e / SETS_PER_PROGRAM;
  return p < MIN_PROGRAMS ? MIN_PROGRAMS : p > MAX_PROGRAMS ? MAX_PROGRAMS : (size_t)p;
}

/* aq_search_minimum (act 0) and aq_search_direction (act -1 or +1). */
static aq_status search(const aq_geom *g, double g_mps2, int act, aq_hinge_set *best,
                        double *lambda0, aq_search_info *info, aq_error *err)
{
  if (aq_glpk_load(err) != AQ_OK)
    return AQ_EUNSUPPORTED;
  size_t n = g->p.voussoirs, nrows = 2 * (n + 1);
  bb B;
  memset(&B, 0, sizeof B);
  B.g = g;
  B.g_mps2 = g_mps2;
  B.act = act;
  B.nrows = nrows;
  B.lp = malloc(nrows * sizeof *B.lp);
  B.ex = calloc(nrows, 1);
  B.seen = malloc(SEEN_SLOTS * sizeof *B.seen);
  if (!B.lp || !B.ex || !B.seen) {
    free(B.lp);
    free(B.ex);
    free(B.seen);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  int infeasible = 0;
  for (int s = 1; s >= -1; s -= 2) { /* the body force s lambda g drives act_sign -s */
    if (act && s != -act)
      continue;
    aq_thrust_rows(g, s, 0, B.lp);
    memset(B.seen, 0, SEEN_SLOTS * sizeof *B.seen); /* each direction its own program */
    B.dir_programs = 0;
    B.ran_out = 0;
    B.max_programs = budget(n);
    infeasible += node(&B, 0, 0) == LP_INFEASIBLE;
    if (B.ran_out) {
      if (aq_search_enum_count(n) > ENUM_MAX)
        break; /* B.failed: no set settled */
      B.failed = 0; /* the enumeration settles this direction exactly */
      if (aq_search_enumerate(&B, -s) != 0) {
        free(B.lp);
        free(B.ex);
        free(B.seen);
        return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
      }
    }
  }
  if (!act && !B.have && infeasible == 2 && !B.failed) {
    /* no line of thrust fits for any lambda: a set gravity drives */
    aq_thrust_rows(g, 1, 1, B.lp);
    memset(B.seen, 0, SEEN_SLOTS * sizeof *B.seen);
    node(&B, 1, 0);
  }
  free(B.lp);
  free(B.ex);
  free(B.seen);
  if (B.info.liftoff && B.have &&
      !(B.info.liftoff_lambda < B.lambda0 - TIE_REL * fabs(B.lambda0)))
    B.info.liftoff = 0; /* no lower than the four-hinge minimum */
  if (info)
    *info = B.info;
  if (B.failed && B.ran_out)
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "hinges",
                        "expected the minimum four-hinge mechanism, got none settled: %d "
                        "linear programs left it open and the %.4g sets of %zu voussoirs are "
                        "more than the %.4g enumerated at most (74 voussoirs); a mechanism "
                        "with joint %zu lifting off has lambda = %.6g, below every four-hinge "
                        "set: the four-hinge models do not describe it",
                        MAX_PROGRAMS, aq_search_enum_count(n), n, ENUM_MAX, B.info.liftoff_joint,
                        B.info.liftoff_lambda);
  if (B.failed && !B.ran_out) /* a program without its optimum: no set is settled */
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "hinges",
                        "expected the minimum four-hinge mechanism, got a linear program of "
                        "%zu rows that GLPK left unsolved (its limit: %d simplex iterations)",
                        2 * (n + 1), aq_lp4_iteration_limit(2 * (n + 1)));
  if (!B.have) {
    char dir[48] = "";
    if (act)
      snprintf(dir, sizeof dir, " driven by act_sign %+d", act);
    if (B.info.liftoff)
      return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "hinges",
                          "expected an admissible four-hinge mechanism%s, got none: a "
                          "mechanism with joint %zu lifting off governs (lambda = %.6g), which "
                          "archquake does not model",
                          dir, B.info.liftoff_joint, B.info.liftoff_lambda);
    return aq_error_set(err, AQ_EINADMISSIBLE, NULL, -1, -1, "hinges",
                        "expected an admissible four-hinge mechanism%s, got none (%s)", dir,
                        B.failed ? "the linear program failed" : "no set read from its optimum");
  }
  *best = B.hs;
  if (lambda0)
    *lambda0 = B.lambda0;
  return AQ_OK;
}

aq_status aq_search_minimum(const aq_geom *g, double g_mps2, aq_hinge_set *best,
                            double *lambda0, aq_search_info *info, aq_error *err)
{
  return search(g, g_mps2, 0, best, lambda0, info, err);
}

aq_status aq_search_direction(const aq_geom *g, double g_mps2, int act_sign,
                              aq_hinge_set *best, double *lambda0, aq_search_info *info,
                              aq_error *err)
{
  return search(g, g_mps2, act_sign < 0 ? -1 : 1, best, lambda0, info, err);
}
