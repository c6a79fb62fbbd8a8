/* chain.c: the contact problem of a guessed contact state, solved directly
 * along the chain of bodies (model.h).
 *
 * With the state of every joint guessed (which corners are closed, which
 * stick, which slide and which way), the contact conditions are equations:
 * a closed corner's normal velocity and a sticking joint's tangential
 * velocity take given values, and a sliding joint's friction impulse is
 * -slide mu P_n.  Their multipliers x solve W x = rhs with the Delassus
 * matrix W = G M^-1 C^T (G the rows, C the impulses' directions).  Joint k
 * touches only bodies k-1 and k, so W is block tridiagonal with blocks of
 * at most 3 rows, and block elimination from joint 0 (the ground) factors
 * it in O(nj) operations: the part of the chain eliminated so far is held
 * by the ground at one end, so each diagonal block is regular unless the
 * rows of the last joint, which closes the chain on the other support,
 * are redundant (the arch statically indeterminate in that state: fewer
 * than three open hinges).  Then the contact forces are not determined by
 * the equations and the caller solves the inequality problem instead. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

/* A pivot below this fraction of the largest entry of its diagonal block
 * is taken as zero: the rows are dependent (a 1-degree-of-freedom
 * mechanism of 20 voussoirs has its smallest pivot near 1e-3 of the
 * block; redundant rows leave 1e-14 or less). */
static const double PIVOT_REL = 1e-9;

typedef struct {
  double a[3], b[3];
} gen;

typedef struct {
  int d;              /* rows */
  int kind[3];        /* AQ_CHAIN_ROW_* */
  gen G[3], C[3];     /* rows and impulse directions */
  double c[3];        /* constant parts of the rows */
  double D[3][3];     /* Schur complement, LU in place */
  int piv[3];
  unsigned char drop[3];
  double X[3][3];     /* D'_{k-1}^{-1} W_{k-1,k}: d_{k-1} x d_k */
  double L[3][3];     /* W_{k,k-1}: d_k x d_{k-1} */
  size_t off;         /* first row */
} jblock;

struct aq_chain {
  const aq_bodies *s;
  size_t nj, nrows;
  jblock *J;
  size_t *rjoint;     /* each row's joint */
  int *rkind;         /* and kind */
  double *minv;       /* 3 nb: 1/m, 1/m, 1/I */
};

aq_chain *aq_chain_alloc(const aq_bodies *s)
{
  aq_chain *c = calloc(1, sizeof *c);
  if (!c)
    return NULL;
  c->s = s;
  c->nj = s->nj;
  c->J = calloc(s->nj, sizeof *c->J);
  c->minv = malloc(3 * s->nb * sizeof *c->minv);
  c->rjoint = malloc(3 * s->nj * sizeof *c->rjoint);
  c->rkind = malloc(3 * s->nj * sizeof *c->rkind);
  if (!c->J || !c->minv || !c->rjoint || !c->rkind) {
    aq_chain_free(c);
    return NULL;
  }
  for (size_t b = 0; b < s->nb; b++) {
    c->minv[3 * b] = c->minv[3 * b + 1] = 1 / s->body[b].mass_kg;
    c->minv[3 * b + 2] = 1 / s->body[b].inertia_kgm2;
  }
  return c;
}

void aq_chain_free(aq_chain *c)
{
  if (!c)
    return;
  free(c->J);
  free(c->minv);
  free(c->rjoint);
  free(c->rkind);
  free(c);
}

size_t aq_chain_nrows(const aq_chain *c) { return c->nrows; }

void aq_chain_row(const aq_chain *c, size_t r, size_t *joint, int *kind)
{
  *joint = c->rjoint[r];
  *kind = c->rkind[r];
}

/* x M^-1 y over body b's three velocities. */
static inline double mdot(const double *minv, int b, const double *x, const double *y)
{
  const double *m = minv + 3 * b;
  return x[0] * m[0] * y[0] + x[1] * m[1] * y[1] + x[2] * m[2] * y[2];
}

/* LU with partial pivoting of the d x d block A; a column whose largest
 * remaining entry is at most tol is dropped (its unknown 0, its equation
 * left out).  Returns the number dropped. */
static int lu(double A[3][3], int d, int piv[3], unsigned char drop[3], double tol)
{
  int nd = 0;
  for (int i = 0; i < d; i++) {
    int p = i;
    for (int r = i + 1; r < d; r++)
      if (fabs(A[r][i]) > fabs(A[p][i]))
        p = r;
    piv[i] = p;
    if (p != i)
      for (int k = 0; k < d; k++) {
        double t = A[i][k];
        A[i][k] = A[p][k];
        A[p][k] = t;
      }
    drop[i] = !(fabs(A[i][i]) > tol);
    if (drop[i]) {
      nd++;
      A[i][i] = 1;
      for (int k = i + 1; k < d; k++)
        A[i][k] = 0;
      for (int r = i + 1; r < d; r++)
        A[r][i] = 0;
      continue;
    }
    for (int r = i + 1; r < d; r++) {
      double f = A[r][i] / A[i][i];
      A[r][i] = f;
      for (int k = i + 1; k < d; k++)
        A[r][k] -= f * A[i][k];
    }
  }
  return nd;
}

static void lu_solve(double A[3][3], int d, const int piv[3], const unsigned char drop[3],
                     double *x)
{
  for (int i = 0; i < d; i++) {
    if (piv[i] != i) {
      double t = x[i];
      x[i] = x[piv[i]];
      x[piv[i]] = t;
    }
  }
  for (int i = 0; i < d; i++)
    for (int k = 0; k < i; k++)
      x[i] -= A[i][k] * x[k];
  for (int i = d - 1; i >= 0; i--) {
    if (drop[i]) {
      x[i] = 0;
      continue;
    }
    for (int k = i + 1; k < d; k++)
      x[i] -= A[i][k] * x[k];
    x[i] /= A[i][i];
  }
}

/* The rows of joint k in state st. */
static void set_rows(jblock *B, const aq_corner *cr, aq_jstate st, double mu, int sym)
{
  B->d = 0;
  int first = -1;
  for (int k = 0; k < 2; k++) {
    if (!aq_jstate_closed(st, k))
      continue;
    if (first < 0)
      first = k;
    const aq_crow *n = &cr[k].n, *t = &cr[k].t;
    int r = B->d++;
    B->kind[r] = k ? AQ_CHAIN_ROW_N1 : AQ_CHAIN_ROW_N0;
    memcpy(B->G[r].a, n->ga, sizeof n->ga);
    memcpy(B->G[r].b, n->gb, sizeof n->gb);
    B->c[r] = n->c;
    double f = sym ? 0 : -(double)st.slide * mu;
    for (int i = 0; i < 3; i++) {
      B->C[r].a[i] = n->ga[i] + f * t->ga[i];
      B->C[r].b[i] = n->gb[i] + f * t->gb[i];
    }
  }
  if (first >= 0 && st.slide == 0) {
    const aq_crow *t = &cr[first].t;
    int r = B->d++;
    B->kind[r] = AQ_CHAIN_ROW_T;
    memcpy(B->G[r].a, t->ga, sizeof t->ga);
    memcpy(B->G[r].b, t->gb, sizeof t->gb);
    B->c[r] = t->c;
    B->C[r] = B->G[r];
  }
}

int aq_chain_factor(aq_chain *c, const aq_corner *cr, const aq_jstate *st, double mu,
                    int sym, int allow_singular)
{
  const aq_bodies *s = c->s;
  size_t off = 0;
  for (size_t k = 0; k < c->nj; k++) {
    set_rows(&c->J[k], cr + 2 * k, st[k], mu, sym);
    c->J[k].off = off;
    for (int r = 0; r < c->J[k].d; r++) {
      c->rjoint[off + (size_t)r] = k;
      c->rkind[off + (size_t)r] = c->J[k].kind[r];
    }
    off += (size_t)c->J[k].d;
  }
  c->nrows = off;
  int singular = 0;
  for (size_t k = 0; k < c->nj; k++) {
    jblock *B = &c->J[k];
    int a = s->joint[k].a, b = s->joint[k].b, d = B->d;
    double scale = 0;
    for (int i = 0; i < d; i++)
      for (int j = 0; j < d; j++) {
        double w = 0;
        if (a >= 0)
          w += mdot(c->minv, a, B->G[i].a, B->C[j].a);
        if (b >= 0)
          w += mdot(c->minv, b, B->G[i].b, B->C[j].b);
        B->D[i][j] = w;
        scale = fmax(scale, fabs(w));
      }
    if (k > 0 && d > 0 && c->J[k - 1].d > 0) {
      int dp = c->J[k - 1].d;
      for (int i = 0; i < d; i++)
        for (int j = 0; j < d; j++) {
          double w = 0;
          for (int m = 0; m < dp; m++)
            w += B->L[i][m] * B->X[m][j];
          B->D[i][j] -= w;
        }
    }
    if (d > 0 && lu(B->D, d, B->piv, B->drop, PIVOT_REL * scale) > 0) {
      singular = 1;
      if (!allow_singular)
        return 1;
    }
    if (k + 1 < c->nj) {
      jblock *N = &c->J[k + 1];
      /* the shared body: B's side of joint k, A's side of joint k+1 */
      int sb = s->joint[k].b;
      /* N->L = W_{k+1,k}: rows of k+1 on sb against impulses of k */
      for (int i = 0; i < N->d; i++)
        for (int j = 0; j < d; j++)
          N->L[i][j] = sb >= 0 ? mdot(c->minv, sb, N->G[i].a, B->C[j].b) : 0;
      /* X = D'_k^{-1} W_{k,k+1}, column by column */
      for (int j = 0; j < N->d; j++) {
        double col[3];
        for (int i = 0; i < d; i++)
          col[i] = sb >= 0 ? mdot(c->minv, sb, B->G[i].b, N->C[j].a) : 0;
        if (d > 0)
          lu_solve(B->D, d, B->piv, B->drop, col);
        for (int i = 0; i < d; i++)
          N->X[i][j] = col[i];
      }
    }
  }
  return singular;
}

void aq_chain_solve(const aq_chain *c, const double *rhs, double *x)
{
  double z[3];
  /* forward: z_k = D'_k^{-1} (rhs_k - W_{k,k-1} z_{k-1}), kept in x */
  for (size_t k = 0; k < c->nj; k++) {
    const jblock *B = &c->J[k];
    if (B->d == 0)
      continue;
    for (int i = 0; i < B->d; i++)
      z[i] = rhs[B->off + (size_t)i];
    if (k > 0) {
      const jblock *P = &c->J[k - 1];
      for (int i = 0; i < B->d; i++)
        for (int m = 0; m < P->d; m++)
          z[i] -= B->L[i][m] * x[P->off + (size_t)m];
    }
    lu_solve((double(*)[3])B->D, B->d, B->piv, B->drop, z);
    for (int i = 0; i < B->d; i++)
      x[B->off + (size_t)i] = z[i];
  }
  /* backward: x_k = z_k - X_{k+1} x_{k+1} */
  for (size_t k = c->nj - 1; k-- > 0;) {
    const jblock *B = &c->J[k], *N = &c->J[k + 1];
    for (int i = 0; i < B->d; i++)
      for (int j = 0; j < N->d; j++)
        x[B->off + (size_t)i] -= N->X[i][j] * x[N->off + (size_t)j];
  }
}

void aq_chain_apply(const aq_chain *c, const double *x, double *dv)
{
  const aq_bodies *s = c->s;
  memset(dv, 0, 3 * s->nb * sizeof *dv);
  for (size_t k = 0; k < c->nj; k++) {
    const jblock *B = &c->J[k];
    int a = s->joint[k].a, b = s->joint[k].b;
    for (int r = 0; r < B->d; r++) {
      double xr = x[B->off + (size_t)r];
      for (int i = 0; i < 3; i++) {
        if (a >= 0)
          dv[3 * a + i] += c->minv[3 * a + i] * B->C[r].a[i] * xr;
        if (b >= 0)
          dv[3 * b + i] += c->minv[3 * b + i] * B->C[r].b[i] * xr;
      }
    }
  }
}

void aq_chain_rows_dot(const aq_chain *c, const double *v, double *u)
{
  const aq_bodies *s = c->s;
  for (size_t k = 0; k < c->nj; k++) {
    const jblock *B = &c->J[k];
    int a = s->joint[k].a, b = s->joint[k].b;
    for (int r = 0; r < B->d; r++) {
      double w = B->c[r];
      for (int i = 0; i < 3; i++) {
        if (a >= 0)
          w += B->G[r].a[i] * v[3 * a + i];
        if (b >= 0)
          w += B->G[r].b[i] * v[3 * b + i];
      }
      u[B->off + (size_t)r] = w;
    }
  }
}
