/* demand_track.c: what a run asks of the joints, followed state by state
 * (demand.h, docs/demand.md).
 *
 * The tracker is told every state of a run (each leg's start, its end and
 * the walls it turned at) and keeps the running maximum of each quantity
 * (|T|/N at every entry, |e|/N at the joints that are not hinges), the
 * entry and time where it occurred and the first time it passed its limit.
 * It evaluates what can change them, and nothing else: a state falls in a
 * cell of its set's grid (demand_grid.c), which bounds both quantities
 * over every entry and every state inside it; when the bound does not
 * exceed the running maximum the state cannot raise it (nor pass a limit
 * that the maximum has not passed already), and it is left there.
 * Otherwise the cell's candidates are evaluated, in the order of the
 * entries: every other entry is below one of them at every state of the
 * cell, so the state's largest value, the entry that has it first and
 * every time noted are those of evaluating every entry, to the bit.  A
 * state outside the grid, or in a cell with too many candidates, has every
 * entry evaluated.
 *
 * The stepper queues its legs; a full queue is looked at in two passes
 * (flush_legs): every state's cell first, then, after evaluating ahead the
 * state with the largest bound (a value the maximum will reach there), the
 * states that may still change a result, in order. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "demand.h"
#include "demand_impl.h"
#include "demand_tab.h"


aq_demand *aq_demand_alloc(const aq_demand_table *(*get)(void *ctx, int set), void *ctx,
                           aq_error *err)
{
  aq_demand *d = calloc(1, sizeof *d);
  if (!d) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    return NULL;
  }
  d->q.rec = d->qbuf;
  d->q.cap = DM_QUEUE;
  d->get = get;
  d->get_ctx = ctx;
  d->mu_limit = NAN;
  aq_demand_begin(d);
  return d;
}

void aq_demand_free(aq_demand *d) { free(d); }

void aq_demand_set_every(aq_demand *d, int on) { d->every = on != 0; }

void aq_demand_set_limit(aq_demand *d, double mu)
{
  d->mu_limit = isfinite(mu) && mu > 0 ? mu : NAN;
}

void aq_demand_set_marks_only(aq_demand *d, int slide, int ecc)
{
  d->marks_only = 1;
  d->want[0] = slide != 0;
  d->want[1] = ecc != 0;
  aq_demand_begin(d);
}

/* Marks only: quantity q is no longer looked at (not asked for, or its
 * limit passed). */
static inline int left(const aq_demand *d, int q)
{
  return d->marks_only && (!d->want[q] || !isnan(d->over_s[q]));
}

void aq_demand_begin(aq_demand *d)
{
  d->q.n = 0;
  d->q.closed = 0;
  for (int k = 0; k < 2; k++) {
    d->iv[k] = 0;
    d->max[k] = 0;
    d->key[k] = 0;
    d->pre[k] = 0;
    d->eff[k] = 0;
    d->joint[k] = 0;
    d->when[k] = NAN;
    d->over_s[k] = NAN;
  }
  d->g = d->ig = NAN;
  d->moved = d->failed = d->done = 0;
  d->samples = d->full = d->looks = 0;
  d->still = 0;
  for (int k = 0; k < 2; k++)
    if (left(d, k))
      d->eff[k] = 0xffff;
  d->done = left(d, 0) && left(d, 1);
}

/* The table of set k (asked for once per tracker), or NULL. */
static const aq_demand_table *table(aq_demand *d, int k)
{
  if (!d->asked[k]) {
    d->asked[k] = 1;
    d->tab[k] = d->get(d->get_ctx, k);
  }
  return d->tab[k];
}

/* The interval of s in t, from the last one i. */
static size_t locate(const aq_demand_table *t, size_t i, double s)
{
  if (i >= t->nint)
    i = 0;
  while (i > 0 && s < t->bp[i])
    i--;
  while (i + 1 < t->nint && s > t->bp[i + 1])
    i++;
  return i;
}

/* eff[q]: above the maximum's key, and, before the state holding a value
 * found ahead (pre[q]), at least that value or, until the limit is first
 * passed, above the limit. */
static void refresh(aq_demand *d, int q)
{
  if (left(d, q)) { /* no code exceeds it: nothing of q is looked at */
    d->eff[q] = 0xffff;
    return;
  }
  uint16_t e = d->pre[q];
  if (e && isnan(d->over_s[q])) {
    double lim = q == 0 ? d->mu_limit : 1.0;
    uint16_t lk = isnan(lim) ? 0xffff : aq_dg_floor16(lim);
    e = lk < e ? lk : e;
  }
  d->eff[q] = e > d->key[q] ? e : d->key[q];
}

/* A state's value v of quantity q at entry j: the running maximum and the
 * first time over the limit. */
static void note(aq_demand *d, int q, double v, const aq_demand_table *t, size_t j, double t_s)
{
  if (v > d->max[q]) {
    d->max[q] = v;
    d->key[q] = aq_dg_floor16(v);
    d->joint[q] = t->entry[j].joint;
    d->when[q] = t_s;
    refresh(d, q);
  }
  double lim = q == 0 ? d->mu_limit : 1.0;
  if (v > lim && isnan(d->over_s[q])) {
    d->over_s[q] = t_s;
    refresh(d, q);
  }
}

/* The row of states (s, kg) of t (aq_dg_row), -1: none (every entry is
 * evaluated there). */
static inline long row_of(const aq_demand *d, const aq_demand_table *t, double s, double kg)
{
  return d->every || !t->grid ? -1 : aq_dg_row(t->grid, s, kg);
}

/* An entry's N and |T| (q 0) or |e| (q 1) at u, al, w, from its cubics c. */
static inline void forms(const double *c, int q, double u, double al, double w, double *N,
                         double *X)
{
  const double *x = c + (3 + 3 * (size_t)q) * DT_NC;
  *N = aq_dt_cubic(c, u) + al * aq_dt_cubic(c + DT_NC, u) + w * aq_dt_cubic(c + 2 * DT_NC, u);
  *X = fabs(aq_dt_cubic(x, u) + al * aq_dt_cubic(x + DT_NC, u) + w * aq_dt_cubic(x + 2 * DT_NC, u));
}

/* Look at one state of set k at (s, al = a/g, kg = KE/g), record time t_s,
 * in cell ic (-1: none): its candidates, or every entry. */
static void look_at(aq_demand *d, const aq_demand_table *t, int k, long ic, double s, double al,
                    double kg, double t_s)
{
  const aq_dg_cell *cl = ic >= 0 ? aq_dg_cell_at(t->grid, ic) : NULL;
  if (cl && (cl->n[0] == DG_ALL || cl->n[1] == DG_ALL))
    cl = NULL;
  int need[2] = {!cl || aq_dg_code(t->grid, ic, 0) > d->eff[0],
                 !cl || aq_dg_code(t->grid, ic, 1) > d->eff[1]};
  size_t i = d->iv[k] = locate(t, d->iv[k], s);
  double u = (s - t->bp[i]) * t->ih[i];
  const double *C = t->c + i * t->stride;
  double w = 2.0 * kg * aq_dt_cubic(C + (t->nf * DT_NV + 3) * DT_NC, u);
  if (!cl) { /* every entry */
    d->full++;
    for (size_t j = 0; j < t->nf; j++) {
      const double *c = C + j * DT_NV * DT_NC;
      double v[DT_NV];
      for (int q = 0; q < DT_NV; q++)
        v[q] = aq_dt_cubic(c + q * DT_NC, u);
      double N = v[0] + al * v[1] + w * v[2];
      double T = fabs(v[3] + al * v[4] + w * v[5]);
      double E = fabs(v[6] + al * v[7] + w * v[8]);
      note(d, 0, N > 0 ? T / N : INFINITY, t, j, t_s);
      if (t->entry[j].hinge < 0)
        note(d, 1, N > 0 ? E / N : INFINITY, t, j, t_s);
    }
  } else {
    const aq_dg_cand *p = aq_dg_cands(t->grid, ic);
    for (int q = 0; q < 2; q++) {
      for (size_t m = 0; m < cl->n[q] && need[q]; m++) {
          /* a candidate whose own bound does not exceed the maximum cannot
           * raise it (nor pass a limit the maximum has not passed); nor one
           * below a value found ahead (refresh) */
          if ((p[m] >> 16) <= d->eff[q])
            continue;
          d->looks++;
          size_t j = p[m] & 0xffff;
          double N, X;
          forms(C + j * DT_NV * DT_NC, q, u, al, w, &N, &X);
          /* X / N below the maximum by more than its rounding changes
           * nothing (nor passes a limit: one not passed yet is above the
           * maximum); the division is left out */
          if (N > 0 && X < d->max[q] * N * (1 - 1e-12))
            continue;
          note(d, q, N > 0 ? X / N : INFINITY, t, j, t_s);
        }
      p += cl->n[q];
    }
  }
  d->done = (isinf(d->max[0]) && isinf(d->max[1])) || (left(d, 0) && left(d, 1));
}

/* The table of set k, and 1/g for g; NULL when there is nothing to do. */
static const aq_demand_table *ready(aq_demand *d, int k, double g)
{
  d->moved = 1;
  if (d->failed || d->done)
    return NULL;
  const aq_demand_table *t = table(d, k);
  if (!t) {
    d->failed = 1;
    return NULL;
  }
  if (g != d->g) {
    d->g = g;
    d->ig = 1.0 / g;
  }
  return t;
}

/* A state in cell ic (-1: none) is looked at: no cell, a block not made,
 * or bounds above the maxima. */
static inline int exceeds(const aq_demand *d, const aq_demand_table *t, long ic)
{
  if (ic < 0)
    return 1;
  uint32_t c = aq_dg_codes(t->grid, ic);
  return (c & 0xffff) > d->eff[0] || c >> 16 > d->eff[1];
}

/* Cell ic (-1: none) once its block is made; -1 when it cannot be. */
static inline long made(const aq_demand_table *t, long ic)
{
  return ic >= 0 && aq_dg_ready(t->grid, ic) ? ic : -1;
}

/* Visit state (s, al, kg) of set k in row r (row_of): look at it unless
 * its cell's bounds do not exceed the running maxima. */
static inline void visit(aq_demand *d, const aq_demand_table *t, int k, long r, double s,
                         double al, double kg, double t_s)
{
  long ic = r >= 0 ? aq_dg_cell_in(t->grid, r, al) : -1;
  if (!exceeds(d, t, ic))
    return;
  look_at(d, t, k, made(t, ic), s, al, kg, t_s);
}

void aq_demand_at(aq_demand *d, int k, double s, double ke_j, double a_mps2, double g_mps2,
                  double t_s)
{
  const aq_demand_table *t = ready(d, k, g_mps2);
  if (!t)
    return;
  d->samples++;
  double kg = ke_j * d->ig;
  visit(d, t, k, row_of(d, t, s, kg), s, a_mps2 * d->ig, kg, t_s);
}

/* The walls a leg of set k that ended at (s, kg) moving in direction dir
 * turned at (rev of them, one behind the end, then the other), under
 * al = a/g. */
static void walls(aq_demand *d, const aq_demand_table *t, int k, double s, double kg, int dir,
                  size_t rev, double al, double t_s)
{
  /* no state at rest under al exceeds the maxima: the walls need not be found */
  if (!d->every && t->grid && kg > 0 && rev > 0 && aq_dg_wall_below(t->grid, al, d->max))
    return;
  /* sdot^2 / g falls at 2 sddot / g per unit of s (d(sdot^2)/ds = 2 sddot),
   * so from the end the wall is at s - w / (2 sddot / g), to second order
   * in the distance, which is within the leg's travel */
  for (size_t r = 0; r < rev && r < 2 && kg > 0 && !d->done; r++) {
    int toward = r == 0 ? -dir : dir;
    size_t i = d->iv[k] = locate(t, d->iv[k], s);
    double u = (s - t->bp[i]) * t->ih[i];
    const double *c = t->c + i * t->stride + t->nf * DT_NV * DT_NC;
    double w = 2.0 * kg * aq_dt_cubic(c + 3 * DT_NC, u);
    double sg = aq_dt_cubic(c, u) + al * aq_dt_cubic(c + DT_NC, u) + w * aq_dt_cubic(c + 2 * DT_NC, u);
    double sw = s - w / (2 * sg);
    if (!((sw - s) * toward > 0))
      continue;
    sw = sw < 0 ? 0 : sw > t->s_c ? t->s_c : sw;
    visit(d, t, k, row_of(d, t, sw, 0), sw, al, 0, t_s);
  }
}

void aq_demand_leg(aq_demand *d, int k, double s, double ke_j, int dir, size_t rev,
                   double a_mps2, double g_mps2, double t_s)
{
  const aq_demand_table *t = ready(d, k, g_mps2);
  if (!t)
    return;
  double kg = ke_j * d->ig, al = a_mps2 * d->ig;
  d->samples += 1 + (rev < 2 ? rev : 2);
  walls(d, t, k, s, kg, dir, rev, al, t_s);
  if (!d->done)
    visit(d, t, k, row_of(d, t, s, kg), s, al, kg, t_s);
}

/* The largest value of quantity q at state (s, al, kg) of set k in cell
 * ic over the candidates that may exceed the maximum (0 when none does,
 * or the cell is not known). */
static __attribute__((noinline)) double value_at(aq_demand *d, const aq_demand_table *t,
                                                 int k, long ic, double s, double al, double kg,
                                                 int q)
{
  const aq_dg_cell *cl = ic >= 0 ? aq_dg_cell_at(t->grid, ic) : NULL;
  if (!cl || cl->n[0] == DG_ALL || cl->n[1] == DG_ALL)
    return 0;
  size_t i = d->iv[k] = locate(t, d->iv[k], s);
  double u = (s - t->bp[i]) * t->ih[i], best = 0;
  const double *C = t->c + i * t->stride;
  double w = 2.0 * kg * aq_dt_cubic(C + (t->nf * DT_NV + 3) * DT_NC, u);
  const aq_dg_cand *p = aq_dg_cands(t->grid, ic) + (q ? cl->n[0] : 0);
  for (size_t m = 0; m < cl->n[q]; m++) {
    if ((p[m] >> 16) <= d->key[q])
      continue;
    d->looks++;
    double N, X;
    forms(C + (p[m] & 0xffff) * DT_NV * DT_NC, q, u, al, w, &N, &X);
    double v = N > 0 ? X / N : INFINITY;
    best = v > best ? v : best;
  }
  return best;
}

/* The state 2 n + e (0: start, 1: end of leg n) has been looked at: no
 * value found ahead holds past it. */
static void passed(aq_demand *d, size_t at[2], size_t st)
{
  for (int q = 0; q < 2; q++)
    if (at[q] <= st) {
      at[q] = SIZE_MAX;
      d->pre[q] = 0;
      refresh(d, q);
    }
}

/* The queued legs [n0, n1) (at most 64) of sets whose tables are known:
 * first every state's cell, and which legs have a state whose cell's
 * bounds exceed the maxima or walls to find (a state at rest under their
 * a/g that may exceed them, aq_dg_wall_below); then those legs in order,
 * each state looked at when its cell's bounds exceed the maxima of that
 * moment (they only grow, so a leg left out has nothing to look at). */
static void flush_legs(aq_demand *d, size_t n0, size_t n1)
{
  const aq_demand_leg_rec *rec = d->q.rec;
  double al[DM_QUEUE], kg[DM_QUEUE][2];
  long cell[DM_QUEUE][2];
  uint16_t wsum[DM_QUEUE + 1]; /* the walls of the legs before each, of those left out */
  uint64_t mark = 0;
  long prow = -1;
  uint16_t best[2] = {0, 0};
  size_t at[2] = {SIZE_MAX, SIZE_MAX}; /* 2 n + (0: start, 1: end) of the largest */
  wsum[0] = 0;
  for (size_t n = n0; n < n1; n++) {
    const aq_demand_leg_rec *r = rec + n;
    const aq_demand_table *t = d->tab[r->k];
    if (r->g_mps2 != d->g) {
      d->g = r->g_mps2;
      d->ig = 1.0 / r->g_mps2;
    }
    double a = r->a_mps2 * d->ig, k0 = r->ke0 * d->ig, k1 = r->ke1 * d->ig;
    al[n] = a, kg[n][0] = k0, kg[n][1] = k1;
    long c0 = -1, c1 = -1;
    aq_demand_grid *g = d->every ? NULL : t->grid;
    if (g) {
      double xa = a * g->inv_da + 0.5 * DG_NA;
      /* a leg starts where the one before ended (the same set, s, KE and
       * g): in the row of that end, under the new a/g */
      const aq_demand_leg_rec *p = r - 1;
      long r0 = n > n0 && p->k == r->k && p->s1 == r->s0 && p->ke1 == r->ke0 &&
                        p->g_mps2 == r->g_mps2
                    ? prow
                    : aq_dg_row(g, r->s0, k0);
      long r1 = prow = aq_dg_row(g, r->s1, k1);
      if (xa >= 0 && xa < DG_NA) {
        long ia = (long)xa;
        c0 = r0 >= 0 ? r0 * DG_NA + ia : -1;
        c1 = r1 >= 0 ? r1 * DG_NA + ia : -1;
      }
    } else {
      prow = -1;
    }
    cell[n][0] = c0, cell[n][1] = c1;
    /* its walls are looked for unless no state at rest under its a/g can
     * exceed the maxima (they only grow) */
    int walls_in = r->rev > 0 && k1 > 0 && !(g && aq_dg_wall_below(g, a, d->max));
    size_t w = r->rev < 2 ? r->rev : 2;
    if (walls_in || exceeds(d, t, c0) || exceeds(d, t, c1))
      mark |= (uint64_t)1 << (n - n0), w = 0;
    wsum[n - n0 + 1] = (uint16_t)(wsum[n - n0] + w);
  }
  /* of the states to look at, the one whose bound is the largest, of each
   * quantity: its value, when above the maximum, is one the maximum will
   * reach at that state (worth finding when other states come before) */
  for (uint64_t mk = mark & (mark - 1) ? mark : 0; mk; mk &= mk - 1) {
    size_t n = n0 + (size_t)__builtin_ctzll(mk);
    const aq_demand_table *t = d->tab[rec[n].k];
    for (int e = 0; e < 2; e++)
      for (int q = 0; q < 2 && cell[n][e] >= 0; q++) {
        uint16_t code = aq_dg_code(t->grid, cell[n][e], q);
        if (code > best[q] && code != DG_UNMADE)
          best[q] = code, at[q] = 2 * n + (size_t)e;
      }
  }
  for (int q = 0; q < 2; q++) {
    if (best[q] <= d->key[q]) {
      at[q] = SIZE_MAX;
      continue;
    }
    size_t n = at[q] / 2;
    int e = (int)(at[q] % 2);
    const aq_demand_leg_rec *r = rec + n;
    const aq_demand_table *t = d->tab[r->k];
    double v = value_at(d, t, r->k, made(t, cell[n][e]), e ? r->s1 : r->s0, al[n], kg[n][e], q);
    if (v > d->max[q] && v < 3e38) {
      d->pre[q] = aq_dg_floor16(nextafter(v, 0));
      refresh(d, q);
    } else {
      at[q] = SIZE_MAX;
    }
  }
  /* each leg is two states (its start, its end) and the walls it turned at */
  size_t next = n0, until = at[0] < at[1] ? at[0] : at[1];
  while (mark && !d->done) {
    size_t n = n0 + (size_t)__builtin_ctzll(mark);
    mark &= mark - 1;
    const aq_demand_leg_rec *r = rec + n;
    const aq_demand_table *t = d->tab[r->k];
    d->samples += 2 * (n - next) + wsum[n - n0] - wsum[next - n0] + 1;
    next = n + 1;
    if (exceeds(d, t, cell[n][0]))
      look_at(d, t, r->k, made(t, cell[n][0]), r->s0, al[n], kg[n][0], r->t0);
    if (2 * n >= until)
      passed(d, at, 2 * n), until = at[0] < at[1] ? at[0] : at[1];
    if (d->done)
      break;
    size_t rev = r->rev;
    d->samples += 1 + (rev < 2 ? rev : 2);
    if (rev > 0)
      walls(d, t, r->k, r->s1, kg[n][1], r->dir, rev, al[n], r->t1);
    if (!d->done && exceeds(d, t, cell[n][1]))
      look_at(d, t, r->k, made(t, cell[n][1]), r->s1, al[n], kg[n][1], r->t1);
    if (2 * n + 1 >= until)
      passed(d, at, 2 * n + 1), until = at[0] < at[1] ? at[0] : at[1];
  }
  passed(d, at, SIZE_MAX - 1);
  if (!d->done)
    d->samples += 2 * (n1 - next) + wsum[n1 - n0] - wsum[next - n0];
}

void aq_demand_flush(aq_demand *d)
{
  size_t n0 = 0, nq = d->q.n;
  if (nq)
    d->moved = 1;
  /* in runs of legs whose sets' tables are known; a set's table is asked
   * for when its first leg comes, unless nothing is left to do */
  while (n0 < nq && !d->failed && !d->done) {
    size_t n1 = n0;
    while (n1 < nq && (n1 == n0 || d->asked[d->q.rec[n1].k]) && n1 - n0 < 64)
      n1++;
    if (!table(d, d->q.rec[n0].k)) {
      d->failed = 1;
      break;
    }
    flush_legs(d, n0, n1);
    n0 = n1;
  }
  d->q.n = 0;
  d->q.closed = d->failed || d->done;
}

int aq_demand_grid_cell(const aq_demand_table *t, double s, double al, double kg, double u[2],
                        size_t *cand, size_t cap, size_t n[2])
{
  long ic = t->grid ? aq_dg_index(t->grid, s, al, kg) : -1;
  if (ic < 0)
    return 0;
  const aq_dg_cell *cl = aq_dg_cell_at(t->grid, ic);
  const aq_dg_cand *p = aq_dg_cands(t->grid, ic);
  size_t m = 0;
  for (int q = 0; q < 2; q++) {
    int all = cl->n[q] == DG_ALL;
    u[q] = aq_dg_bound(t->grid, ic, q);
    n[q] = all ? t->nf : cl->n[q];
    if (m + n[q] > cap)
      return -1;
    for (size_t k = 0; k < n[q]; k++)
      cand[m++] = all ? k : *p++ & 0xffff;
  }
  return 1;
}

void aq_demand_get(const aq_demand *d, aq_demand_result *r)
{
  r->mu_max = r->ecc_max = NAN;
  r->mu_joint = r->ecc_joint = 0;
  r->mu_time_s = r->ecc_time_s = r->ecc_over_s = r->slide_s = NAN;
  r->samples = d->samples;
  r->full = d->full;
  r->looks = d->looks;
  if (d->still) {
    r->mu_max = d->still_mu;
    r->mu_joint = d->still_joint;
    r->mu_time_s = d->still_s;
    r->slide_s = d->still_slide;
    return;
  }
  if (!d->moved || d->failed)
    return;
  r->mu_max = d->max[0];
  r->mu_joint = d->joint[0];
  r->mu_time_s = d->when[0];
  r->ecc_max = d->max[1];
  r->ecc_joint = d->joint[1];
  r->ecc_time_s = d->when[1];
  r->ecc_over_s = d->over_s[1];
  r->slide_s = d->over_s[0];
}
