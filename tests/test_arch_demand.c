/* test_arch_demand.c: what a hinge set in motion asks of its joints
 * (src/arch/demand.c) against computations of the test's own:
 *   - every piece's dynamic balance (d'Alembert) with accelerations by
 *     central differences of the four-bar's positions along the motion,
 *     summed over the voussoirs on the other side of each joint;
 *   - sddot against the equation of motion (eom.c);
 *   - at rest at lambda0, the static 9x9 balance (kinematics.c) and the
 *     line of thrust of aq_mech_thrust_line;
 *   - the tables against the exact forms;
 *   - the tracker against every joint evaluated at every state;
 *   - a run that barely passes lambda0 against the static demand. */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "arch/demand.h"
#include "arch/demand_tab.h"
#include "arch/eom.h"
#include "arch/model.h"
#include "arch/stepper.h"
#include "check.h"
#include "test_dyn_steps.h"

static const char *const shipped[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                      "arches/thick.cfg",     "arches/segmental.cfg",
                                      "arches/search.cfg",    "arches/gothic.cfg",
                                      "arches/bridge.cfg",    "arches/catenary.cfg",
                                      "arches/vertical.cfg"};
#define NSHIPPED (sizeof shipped / sizeof shipped[0])

static aq_vec2 vec(double x, double y)
{
  aq_vec2 v = {x, y};
  return v;
}

/* Where voussoir v's centroid and its joint j's ends are at q, and the
 * rotation of the part that carries them (body index b, -1 fixed). */
static void carried(const aq_mech *m, const aq_mech_state *st, int b, aq_vec2 p0, aq_vec2 *p)
{
  if (b < 0) {
    *p = p0;
    return;
  }
  aq_vec2 piv0[3] = {m->h[0], m->h[1], m->h[3]}, piv[3] = {m->h[0], st->h2, m->h[3]};
  double c = cos(st->phi[b][0]), s = sin(st->phi[b][0]);
  double dx = p0.x - piv0[b].x, dy = p0.y - piv0[b].y;
  *p = vec(piv[b].x + c * dx - s * dy, piv[b].y + s * dx + c * dy);
}

static int part_of(const aq_mech *m, size_t v)
{
  const size_t *J = m->hs.joint;
  return v < J[0] ? -1 : v < J[1] ? 0 : v < J[2] ? 1 : v < J[3] ? 2 : -1;
}

static double phi_of(const aq_mech_state *st, int b) { return b < 0 ? 0 : st->phi[b][0]; }

/* The force (x, y) and moment about the origin of joint entry f at z,
 * acting on the part on the joint's clockwise side from its
 * counter-clockwise side (N, T in the frame of the joint turned with the
 * part that carries the forms: its clockwise part, or its counter-clockwise
 * one at a joint of the +x fixed part). */
typedef struct {
  double fx, fy, m0;
} wrench;

/* Voussoir v's loads at the state: gravity g, ground a, d'Alembert from
 * the centroid's acceleration acc and the part's angular acceleration al. */
static wrench loads(const aq_mass *vm, aq_vec2 c, double g, double a, aq_vec2 acc, double al)
{
  wrench w;
  w.fx = -vm->mass_kg * (a + acc.x);
  w.fy = -vm->mass_kg * (g + acc.y);
  w.m0 = c.x * w.fy - c.y * w.fx - vm->inertia_kgm2 * al;
  return w;
}

AQ_TEST(arch_demand_forms_dalembert)
{
  gsl_set_error_handler_off();
  double worst_f = 0, worst_m = 0, worst_acc = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    const aq_geom *g = aq_arch_geom(A);
    size_t n = g->p.voussoirs, nf = aq_demand_nforms(n);
    aq_joint_form *fm = calloc(nf, sizeof *fm);
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(A, set);
      if (!p->admissible)
        continue;
      const aq_mech *m = aq_workpath_mech(aq_arch_workpath(A, set));
      static const double at[] = {0.0123, 0.2871, 0.6413};
      for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        double s = at[i] * p->s_c_rad, sd = (i == 1 ? -0.731 : 0.4127), ga = 9.80665 + 0.613,
               a = (i == 2 ? -0.827 : 0.5531) * 9.80665;
        aq_demand_kin kin;
        if (!aq_check(aq_demand_forms(m, p->q_sign, s, fm, &kin) == 0, "forms"))
          continue;
        /* sddot against the equation of motion */
        aq_path pg = *p;
        pg.g_mps2 = ga;
        aq_path_point pt;
        p->eval_exact(p->ctx, s, &pt);
        double sdd = aq_eom_accel(&pg, &pt, sd, a);
        double sdd_f = kin.sddot[0] * ga + kin.sddot[1] * a + kin.sddot[2] * sd * sd;
        aq_check_rel(sdd_f, sdd, 1e-11, "%s set %d s %g: sddot vs the equation of motion",
                     shipped[f], set, s);
        /* accelerations by central differences along the motion s(t) = s +
         * sd t + sdd t^2/2 (second order in t at 0: the acceleration of a
         * point is c'' sd^2 + c' sdd), steps h and h/2 with Richardson's
         * extrapolation */
        double h = 1e-3 * p->s_c_rad / (fabs(sd) + 1e-3);
        aq_mech_state st[5];
        for (int k = 0; k < 5; k++) {
          double tt = (k - 2) * 0.5 * h;
          aq_mech_eval(m, p->q_sign * (s + sd * tt + 0.5 * sdd * tt * tt), &st[k]);
        }
        aq_vec2 *acc = calloc(n, sizeof *acc), *cen = calloc(n, sizeof *cen);
        double *alv = calloc(n, sizeof *alv);
        for (size_t v = 0; v < n; v++) {
          int b = part_of(m, v);
          aq_vec2 c[5];
          double ph[5];
          for (int k = 0; k < 5; k++) {
            carried(m, &st[k], b, g->vous[v].c, &c[k]);
            ph[k] = phi_of(&st[k], b);
          }
          cen[v] = c[2];
          double hh = 0.5 * h;
          double ax1 = (c[0].x - 2 * c[2].x + c[4].x) / (h * h), ax2 = (c[1].x - 2 * c[2].x + c[3].x) / (hh * hh);
          double ay1 = (c[0].y - 2 * c[2].y + c[4].y) / (h * h), ay2 = (c[1].y - 2 * c[2].y + c[3].y) / (hh * hh);
          double p1 = (ph[0] - 2 * ph[2] + ph[4]) / (h * h), p2 = (ph[1] - 2 * ph[2] + ph[3]) / (hh * hh);
          acc[v] = vec((4 * ax2 - ax1) / 3, (4 * ay2 - ay1) / 3);
          alv[v] = (4 * p2 - p1) / 3;
        }
        /* a length for the moments: the largest joint end's distance from the origin */
        double L = 0;
        for (size_t jj = 0; jj <= n; jj++)
          L = fmax(L, fmax(hypot(g->je[jj].x, g->je[jj].y), hypot(g->ji[jj].x, g->ji[jj].y)));
        /* the resultant of each non-hinge joint inside a body, from the
         * forms, against the balance of the voussoirs on its other side:
         * those up to the next hinge, with that hinge's reaction (itself
         * from the forms at the hinge) */
        double Fscale = g->mass_kg * ga;
        for (size_t j = 0; j < nf; j++) {
          const aq_joint_form *q = &fm[j];
          size_t jj = q->joint;
          int b = jj < m->hs.joint[0] ? -2 : jj > m->hs.joint[3] ? -3 : part_of(m, jj);
          if (q->hinge >= 0 || b < 0)
            continue;
          double N = q->n[0] * ga + q->n[1] * a + q->n[2] * sd * sd;
          double T = q->t[0] * ga + q->t[1] * a + q->t[2] * sd * sd;
          double E = q->e[0] * ga + q->e[1] * a + q->e[2] * sd * sd;
          /* the joint frame turned with body b */
          aq_vec2 o, ou;
          carried(m, &st[2], b, g->jo[jj], &o);
          carried(m, &st[2], b, vec(g->jo[jj].x + g->ju[jj].x, g->jo[jj].y + g->ju[jj].y), &ou);
          aq_vec2 u = vec(ou.x - o.x, ou.y - o.y), nr = vec(-u.y, u.x);
          aq_vec2 mid = vec(o.x + g->jmid[jj] * u.x, o.y + g->jmid[jj] * u.y);
          /* t: external force on the clockwise sub-body but the joint's;
           * the clockwise sub-body pushes the other side with +t */
          double tx = N * nr.x + T * u.x, ty = N * nr.y + T * u.y;
          double m0 = E * g->jhalf[jj] + (mid.x * ty - mid.y * tx);
          /* the counter-clockwise sub-body: voussoirs jj .. J_{b+1}-1 */
          size_t hj = m->hs.joint[b + 1];
          double sx = tx, sy = ty, sm = m0;
          for (size_t v = jj; v < hj; v++) {
            wrench w = loads(&g->vous[v], cen[v], ga, a, acc[v], alv[v]);
            sx += w.fx, sy += w.fy, sm += w.m0;
          }
          /* hinge b+1's reaction on body b (its clockwise side): -(h, v) */
          const aq_joint_form *hf = &fm[hj];
          int hb = b + 1 < 3 ? b + 1 : -1;
          double Nh = hf->n[0] * ga + hf->n[1] * a + hf->n[2] * sd * sd;
          double Th = hf->t[0] * ga + hf->t[1] * a + hf->t[2] * sd * sd;
          double rot = phi_of(&st[2], hb), cr = cos(rot), sr = sin(rot);
          aq_vec2 hu = vec(cr * g->ju[hj].x - sr * g->ju[hj].y, sr * g->ju[hj].x + cr * g->ju[hj].y);
          aq_vec2 hn = vec(-hu.y, hu.x);
          double hx = Nh * hn.x + Th * hu.x, hy = Nh * hn.y + Th * hu.y;
          aq_vec2 hp = b + 1 == 1 ? st[2].h2 : b + 1 == 2 ? st[2].h3 : m->h[3];
          sx -= hx, sy -= hy, sm -= hp.x * hy - hp.y * hx;
          double ef = hypot(sx, sy) / Fscale, em = fabs(sm) / (Fscale * L);
          worst_f = fmax(worst_f, ef), worst_m = fmax(worst_m, em);
          aq_check(ef < 1e-5 && em < 1e-5,
                   "%s set %d s %g joint %zu: balance of the other side %.3g (force), %.3g "
                   "(moment) of the weight",
                   shipped[f], set, s, jj, ef, em);
        }
        /* the springings against the balance of the whole arch */
        double sx = 0, sy = 0, sm = 0;
        for (size_t v = 0; v < n; v++) {
          wrench w = loads(&g->vous[v], cen[v], ga, a, acc[v], alv[v]);
          sx += w.fx, sy += w.fy, sm += w.m0;
        }
        for (int end = 0; end < 2; end++) {
          const aq_joint_form *q = &fm[end ? n : 0];
          size_t jj = q->joint;
          double N = q->n[0] * ga + q->n[1] * a + q->n[2] * sd * sd;
          double T = q->t[0] * ga + q->t[1] * a + q->t[2] * sd * sd;
          double E = q->e[0] * ga + q->e[1] * a + q->e[2] * sd * sd;
          int b = q->hinge >= 0 && !end ? 0 : -1; /* H1's entry: body 0's face; H4's: the ground's */
          double rot = phi_of(&st[2], b), cr = cos(rot), sr = sin(rot);
          aq_vec2 u = vec(cr * g->ju[jj].x - sr * g->ju[jj].y, sr * g->ju[jj].x + cr * g->ju[jj].y);
          aq_vec2 nr = vec(-u.y, u.x);
          double sg = end ? 1.0 : -1.0; /* joint 0's forms are the +x part's, on its ccw side */
          aq_vec2 o;
          carried(m, &st[2], b, g->jo[jj], &o);
          aq_vec2 mid = vec(o.x + g->jmid[jj] * u.x, o.y + g->jmid[jj] * u.y);
          double tx, ty, m0;
          if (q->hinge >= 0) { /* the hinge's reaction (h, v) on its ccw body */
            double hx = N * nr.x + T * u.x, hy = N * nr.y + T * u.y;
            aq_vec2 hp = end ? m->h[3] : m->h[0];
            /* the abutment's force on the arch: +(h, v) at H1, -(h, v) at H4 */
            tx = end ? -hx : hx, ty = end ? -hy : hy;
            m0 = hp.x * ty - hp.y * tx;
          } else { /* t of the sub-body beside the springing; the abutment gives -t */
            double Ns = sg * N;
            double ttx = Ns * nr.x + T * u.x, tty = Ns * nr.y + T * u.y;
            double tm = sg * E * g->jhalf[jj] + (mid.x * tty - mid.y * ttx);
            tx = -ttx, ty = -tty, m0 = -tm;
          }
          sx += tx, sy += ty, sm += m0;
        }
        double ef = hypot(sx, sy) / Fscale, em = fabs(sm) / (Fscale * L);
        worst_acc = fmax(worst_acc, fmax(ef, em));
        aq_check(ef < 1e-5 && em < 1e-5,
                 "%s set %d s %g: the whole arch's balance with both springings' "
                 "resultants %.3g (force), %.3g (moment)",
                 shipped[f], set, s, ef, em);
        free(acc);
        free(cen);
        free(alv);
      }
    }
    free(fm);
    aq_arch_free(A);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("demand d'Alembert: joints %.3g (force) %.3g (moment), springings %.3g\n", worst_f,
           worst_m, worst_acc);
}

AQ_TEST(arch_demand_tables_vs_forms)
{
  gsl_set_error_handler_off();
  unsigned long long rng = 0x5eed2385ULL;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    size_t n = aq_arch_geom(A)->p.voussoirs, nf = aq_demand_nforms(n);
    aq_joint_form *fe = calloc(nf, sizeof *fe), *ft = calloc(nf, sizeof *ft);
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(A, set);
      const aq_demand_table *t = aq_arch_demand_table(A, set);
      if (!p->admissible) {
        aq_check(t == NULL, "%s set %d: no tables for an inadmissible set", shipped[f], set);
        continue;
      }
      if (!aq_check(t != NULL, "%s set %d: tables", shipped[f], set))
        continue;
      const aq_mech *m = aq_workpath_mech(aq_arch_workpath(A, set));
      aq_demand_forms(m, p->q_sign, 0, fe, NULL);
      double scale = 0; /* the tables' tolerance is against the largest normal force at rest */
      for (size_t j = 0; j < nf; j++)
        scale = fmax(scale, fabs(fe[j].n[0]));
      double worst = 0;
      for (int i = 0; i < 200; i++) {
        double s = i == 0 ? 0 : i == 1 ? p->s_c_rad : p->s_c_rad * tds_rng(&rng);
        aq_demand_kin ke, kt;
        aq_demand_forms(m, p->q_sign, s, fe, &ke);
        aq_check(aq_demand_table_forms(t, s, ft, &kt) == 0, "tabled at %g", s);
        for (size_t j = 0; j < nf; j++)
          for (int k = 0; k < 2; k++) /* the g and a columns */
            worst = fmax(worst, fmax(fabs(ft[j].n[k] - fe[j].n[k]),
                                     fmax(fabs(ft[j].t[k] - fe[j].t[k]),
                                          fabs(ft[j].e[k] - fe[j].e[k]))) / scale);
        aq_check_rel(kt.mgen_kgm2, ke.mgen_kgm2, 1e-7, "M at %g", s);
        if (i == 0)
          for (size_t j = 0; j < nf; j++) /* the nodes are exact (but for / m_T * m_T) */
            aq_check(fabs(ft[j].n[0] - fe[j].n[0]) <= 4e-16 * fabs(fe[j].n[0]) &&
                         fabs(ft[j].t[1] - fe[j].t[1]) <= 4e-16 * fabs(fe[j].t[1]),
                     "exact at s = 0");
      }
      aq_check(worst <= 1e-7, "%s set %d: tables within %.3g of the largest normal force",
               shipped[f], set, worst);
    }
    free(fe);
    free(ft);
    aq_arch_free(A);
  }
}

/* The largest |T|/N and |e|/N (non-hinge) over every entry at one state,
 * from the tables, with the state's first time over each limit. */
typedef struct {
  double mu, ecc, mu_over, ecc_over;
} brute;

static void brute_at(const aq_demand_table *t, aq_joint_form *f, size_t nf, double s, double ke,
                     double a, double g, double t_s, double mu_limit, brute *b)
{
  aq_demand_kin kin;
  aq_demand_table_forms(t, s, f, &kin);
  double al = a / g, w = 2 * ke / (kin.mgen_kgm2 * g);
  for (size_t j = 0; j < nf; j++) {
    double N = f[j].n[0] + al * f[j].n[1] + w * f[j].n[2];
    double T = fabs(f[j].t[0] + al * f[j].t[1] + w * f[j].t[2]);
    double E = fabs(f[j].e[0] + al * f[j].e[1] + w * f[j].e[2]);
    double mu = N > 0 ? T / N : INFINITY, ecc = N > 0 ? E / N : INFINITY;
    b->mu = fmax(b->mu, mu);
    if (mu > mu_limit && isnan(b->mu_over))
      b->mu_over = t_s;
    if (f[j].hinge < 0) {
      b->ecc = fmax(b->ecc, ecc);
      if (ecc > 1 && isnan(b->ecc_over))
        b->ecc_over = t_s;
    }
  }
}

AQ_TEST(arch_demand_tracker_vs_every_joint)
{
  /* states of a motion: s and KE move smoothly (a swing out and back),
   * the ground acceleration jumps from step to step; the tracker, told
   * each, against every joint evaluated at each */
  gsl_set_error_handler_off();
  unsigned long long rng = 0x2385a11ULL;
  size_t runs = 0, full = 0, samples = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    size_t n = aq_arch_geom(A)->p.voussoirs, nf = aq_demand_nforms(n);
    aq_joint_form *fb = calloc(nf, sizeof *fb);
    aq_demand *d = aq_arch_demand_tracker(A, 0.55, &e);
    const aq_path *p0 = aq_arch_path(A, 0);
    double g = p0->g_mps2, l0 = p0->lambda0;
    for (int r = 0; r < 6; r++) {
      double amax = (0.5 + 3 * tds_rng(&rng)) * l0;
      aq_demand_begin(d);
      brute b = {0, 0, NAN, NAN};
      int set = 0;
      double s = 0, phase = 0, t_s = 0;
      for (int i = 0; i < 400; i++) {
        const aq_path *p = aq_arch_path(A, set);
        const aq_demand_table *t = aq_arch_demand_table(A, set);
        if (!t)
          break;
        /* a swing: s = A sin(phase), KE ~ cos^2 */
        double amp = (0.05 + 0.9 * tds_rng(&rng)) * p->s_c_rad;
        phase += 0.05 + 0.3 * tds_rng(&rng);
        double sn = sin(phase);
        s = fabs(amp * sn);
        double ke = 0.5 * p->mass_kg * g * 0.01 * p->s_c_rad * (1 - sn * sn) * tds_rng(&rng);
        double a = (2 * tds_rng(&rng) - 1) * amax * g;
        t_s += 0.01;
        aq_demand_at(d, set, s, ke, a, g, t_s);
        brute_at(t, fb, nf, s, ke, a, g, t_s, 0.55, &b);
        if (tds_rng(&rng) < 0.03) {
          aq_demand_at(d, set, 0, ke, a, g, t_s); /* an impact: the other set */
          brute_at(t, fb, nf, 0, ke, a, g, t_s, 0.55, &b);
          if (aq_arch_path(A, 1 - set)->admissible)
            set = 1 - set;
        }
      }
      aq_demand_result dr;
      aq_demand_get(d, &dr);
      runs++, full += dr.full, samples += dr.samples;
      aq_check(dr.mu_max == b.mu || fabs(dr.mu_max - b.mu) <= 1e-9 * b.mu,
               "%s run %d: tracker mu %.17g, every joint %.17g", shipped[f], r, dr.mu_max, b.mu);
      aq_check(dr.ecc_max == b.ecc || fabs(dr.ecc_max - b.ecc) <= 1e-9 * b.ecc,
               "%s run %d: tracker ecc %.17g, every joint %.17g", shipped[f], r, dr.ecc_max, b.ecc);
      aq_check((isnan(dr.slide_s) && isnan(b.mu_over)) || dr.slide_s == b.mu_over,
               "%s run %d: first over the friction %g, every joint %g", shipped[f], r,
               dr.slide_s, b.mu_over);
      aq_check((isnan(dr.ecc_over_s) && isnan(b.ecc_over)) || dr.ecc_over_s == b.ecc_over,
               "%s run %d: thrust first out %g, every joint %g", shipped[f], r, dr.ecc_over_s,
               b.ecc_over);
    }
    aq_demand_free(d);
    free(fb);
    aq_arch_free(A);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("tracker: %zu runs, %zu states, %zu with every joint evaluated\n", runs, samples, full);
}

/* Two results equal to the bit (NAN equal to NAN). */
static int same(double a, double b) { return (isnan(a) && isnan(b)) || a == b; }

AQ_TEST(arch_demand_queued_legs_as_every_joint)
{
  /* the stepper's path (legs queued, then each queue looked at: its cells
   * first, the state with the largest bound found ahead, then the states
   * in order) against every joint evaluated at every state in order, on
   * legs built to try it: swings that grow through each queue (the
   * largest value late in it), states repeated exactly later (ties: the
   * first keeps the maximum), walls, impacts to the other set, a varying
   * gravity, and friction limits passed part-way; every result, the time
   * and joint of each maximum included, to the bit */
  gsl_set_error_handler_off();
  unsigned long long rng = 0x51ab3c7ULL;
  size_t runs = 0, over[2] = {0, 0}, pre = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    const aq_path *p0 = aq_arch_path(A, 0);
    double g0 = p0->g_mps2, l0 = p0->lambda0;
    for (int r = 0; r < 8; r++) {
      double mu_limit = 0.1 + 1.5 * tds_rng(&rng);
      aq_demand *d[2];
      for (int k = 0; k < 2; k++) {
        d[k] = aq_arch_demand_tracker(A, mu_limit, &e);
        aq_demand_set_every(d[k], k);
        aq_demand_begin(d[k]);
      }
      enum { NL = 400 };
      static aq_demand_leg_rec leg[NL];
      int set = 0;
      double s = 0, ke = 0, t_s = 0, amax = (0.5 + 3 * tds_rng(&rng)) * l0;
      for (size_t i = 0; i < NL; i++) {
        aq_demand_leg_rec *L = leg + i;
        if (i > 10 && tds_rng(&rng) < 0.05) { /* an earlier leg again, later */
          *L = leg[(size_t)(tds_rng(&rng) * (double)(i - 1))];
          L->t0 = t_s, L->t1 = t_s += 0.005;
          set = L->k, s = L->s1, ke = L->ke1;
          continue;
        }
        const aq_path *p = aq_arch_path(A, set);
        double grow = 0.2 + 0.8 * (double)(i % 64) / 64; /* grows through a queue */
        double amp = grow * (0.05 + 0.9 * tds_rng(&rng)) * p->s_c_rad;
        double s1 = amp * tds_rng(&rng);
        double ke1 = 0.5 * p->mass_kg * g0 * 0.02 * p->s_c_rad * grow * tds_rng(&rng);
        double g = g0 * (tds_rng(&rng) < 0.2 ? 0.8 + 0.4 * tds_rng(&rng) : 1);
        size_t rev = tds_rng(&rng) < 0.15 ? 1 + (size_t)(2 * tds_rng(&rng)) : 0;
        *L = (aq_demand_leg_rec){s, ke, t_s, s1, ke1, t_s + 0.005,
                                 (2 * tds_rng(&rng) - 1) * amax * g, g, set,
                                 tds_rng(&rng) < 0.5 ? 1 : -1, rev};
        t_s += 0.005;
        s = s1, ke = ke1;
        if (tds_rng(&rng) < 0.03 && aq_arch_path(A, 1 - set)->admissible) {
          set = 1 - set; /* an impact: the next leg starts at 0 on the other set */
          s = 0, ke *= 0.7;
        }
      }
      for (int k = 0; k < 2; k++) {
        for (size_t i = 0; i < NL; i++) {
          aq_demand_leg_rec *L = aq_demand_slot(d[k]);
          if (L)
            *L = leg[i];
        }
        aq_demand_flush(d[k]);
      }
      aq_demand_result q, ev;
      aq_demand_get(d[0], &q);
      aq_demand_get(d[1], &ev);
      runs++;
      over[0] += !isnan(ev.slide_s), over[1] += !isnan(ev.ecc_over_s);
      pre += q.samples == ev.samples && q.looks < ev.samples;
      aq_check(same(q.mu_max, ev.mu_max) && q.mu_joint == ev.mu_joint &&
                   same(q.mu_time_s, ev.mu_time_s),
               "%s run %d: |T|/N %.17g at joint %zu, %.3f s; every joint %.17g at %zu, %.3f s",
               shipped[f], r, q.mu_max, q.mu_joint, q.mu_time_s, ev.mu_max, ev.mu_joint,
               ev.mu_time_s);
      aq_check(same(q.ecc_max, ev.ecc_max) && q.ecc_joint == ev.ecc_joint &&
                   same(q.ecc_time_s, ev.ecc_time_s),
               "%s run %d: |e|/N %.17g at joint %zu, %.3f s; every joint %.17g at %zu, %.3f s",
               shipped[f], r, q.ecc_max, q.ecc_joint, q.ecc_time_s, ev.ecc_max, ev.ecc_joint,
               ev.ecc_time_s);
      aq_check(same(q.slide_s, ev.slide_s) && same(q.ecc_over_s, ev.ecc_over_s),
               "%s run %d (friction %.3f): over the friction at %.3f s, every joint %.3f; "
               "thrust out at %.3f s, every joint %.3f", shipped[f], r, mu_limit, q.slide_s,
               ev.slide_s, q.ecc_over_s, ev.ecc_over_s);
      aq_demand_free(d[0]);
      aq_demand_free(d[1]);
    }
    aq_arch_free(A);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("queued: %zu runs, %zu over the friction, %zu thrust out, %zu looked at in part\n",
           runs, over[0], over[1], pre);
  /* the cases are there: limits passed part-way, runs looked at in part */
  aq_check(over[0] >= runs / 4 && over[1] >= runs / 8 && pre >= runs / 2,
           "%zu runs: %zu over the friction, %zu thrust out, %zu looked at in part", runs,
           over[0], over[1], pre);
}

/* Both quantities' maxima over what tracker d is told (a fresh run): a
 * state (rev < 0) or a leg ending at that state that turned rev times. */
static void told(aq_demand *d, int k, double s, double ke, int dir, int rev, double a, double g,
                 double v[2])
{
  aq_demand_result r;
  aq_demand_begin(d);
  if (rev < 0)
    aq_demand_at(d, k, s, ke, a, g, 0);
  else
    aq_demand_leg(d, k, s, ke, dir, (size_t)rev, a, g, 0);
  aq_demand_get(d, &r);
  v[0] = r.mu_max, v[1] = r.ecc_max;
}

AQ_TEST(arch_demand_walls_found_past_the_maxima)
{
  /* A queued leg is left out when neither end's cell can exceed the
   * maxima and no state at rest under its a/g can: its walls (the states
   * at rest where it turned) then need not be found.  Legs whose wall
   * exceeds the bound of their end's cell, found by search, told after
   * two states that raise the maxima past that bound but not past the
   * wall: the queued tracker must find the wall, as every joint at every
   * state does (the time and joint of each maximum included). */
  unsigned long long rng = 0x3a11e7ULL;
  size_t cases = 0, tried = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    aq_demand *q = aq_arch_demand_tracker(A, NAN, &e), *ev = aq_arch_demand_tracker(A, NAN, &e);
    aq_demand_set_every(ev, 1);
    for (int k = 0; k < 2 && q && ev; k++) {
      const aq_path *p = aq_arch_path(A, k);
      const aq_demand_table *t = aq_arch_demand_table(A, k);
      if (!p || !p->admissible || !t || !t->grid)
        continue;
      double g = p->g_mps2, sc = p->s_c_rad, ke_top = 0.01 * p->mass_kg * g * sc;
      enum { NP = 400 };
      static double pool[NP][5]; /* s, KE, a, both quantities there */
      for (size_t i = 0; i < NP; i++) {
        pool[i][0] = sc * tds_rng(&rng), pool[i][1] = ke_top * tds_rng(&rng);
        pool[i][2] = (2 * tds_rng(&rng) - 1) * 1.5 * p->lambda0 * g;
        told(ev, k, pool[i][0], pool[i][1], 0, -1, pool[i][2], g, pool[i] + 3);
      }
      size_t found = 0;
      for (int trial = 0; trial < 3000 && found < 2; trial++) {
        double s = 0.9 * sc * tds_rng(&rng), ke = ke_top * tds_rng(&rng);
        double a = (2 * tds_rng(&rng) - 1) * 1.5 * p->lambda0 * g, vw[2], v0[2], u[2];
        int dir = tds_rng(&rng) < 0.5 ? 1 : -1, x = -1;
        size_t nc[2], cand[1024];
        told(ev, k, s, ke, dir, 1, a, g, vw);
        told(ev, k, s, ke, dir, 0, a, g, v0);
        if (aq_demand_grid_cell(t, s, a / g, ke / g, u, cand, 1024, nc) != 1)
          continue;
        for (int m = 0; m < 2; m++) /* the wall exceeds the end and its cell's bound */
          if (vw[m] > v0[m] && vw[m] > u[m] && isfinite(vw[m]))
            x = m;
        if (x < 0)
          continue;
        tried++;
        /* states that raise quantity x into [u, wall) and the other past its bound */
        long sa = -1, sb = -1;
        for (long i = 0; i < NP; i++) {
          const double *v = pool[i] + 3;
          if (sa < 0 && v[x] >= u[x] && v[x] < vw[x])
            sa = i;
          if (sb < 0 && v[1 - x] >= u[1 - x] && !(v[x] >= vw[x]))
            sb = i;
        }
        if (sa < 0 || sb < 0)
          continue;
        aq_demand_result r[2];
        for (int m = 0; m < 2; m++) {
          aq_demand *d = m ? ev : q;
          aq_demand_begin(d);
          aq_demand_at(d, k, pool[sa][0], pool[sa][1], pool[sa][2], g, 0);
          aq_demand_at(d, k, pool[sb][0], pool[sb][1], pool[sb][2], g, 0.005);
          aq_demand_leg_rec *L = aq_demand_slot(d);
          if (L)
            *L = (aq_demand_leg_rec){s, ke, 0.01, s, ke, 0.015, a, g, k, dir, 1};
          aq_demand_flush(d);
          aq_demand_get(d, &r[m]);
        }
        aq_check(r[1].mu_max >= u[0] && r[1].ecc_max >= u[1] &&
                     (x ? r[1].ecc_time_s : r[1].mu_time_s) == 0.015,
                 "%s set %d: the case is not one (a wall past maxima above the end's bounds)",
                 shipped[f], k);
        aq_check(same(r[0].mu_max, r[1].mu_max) && r[0].mu_joint == r[1].mu_joint &&
                     same(r[0].mu_time_s, r[1].mu_time_s) && same(r[0].ecc_max, r[1].ecc_max) &&
                     r[0].ecc_joint == r[1].ecc_joint && same(r[0].ecc_time_s, r[1].ecc_time_s),
                 "%s set %d: s %.6g KE %.6g J a %.6g: |T|/N %.17g (%.3f s), |e|/N %.17g (%.3f "
                 "s); every joint %.17g (%.3f s), %.17g (%.3f s)", shipped[f], k, s, ke, a,
                 r[0].mu_max, r[0].mu_time_s, r[0].ecc_max, r[0].ecc_time_s, r[1].mu_max,
                 r[1].mu_time_s, r[1].ecc_max, r[1].ecc_time_s);
        found++, cases++;
      }
    }
    aq_demand_free(q);
    aq_demand_free(ev);
    aq_arch_free(A);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("walls past the maxima: %zu cases of %zu legs whose wall exceeds its end's bound\n",
           cases, tried);
  aq_check(cases >= 8, "%zu cases of a wall past the maxima", cases);
}

/* mu of the static collapse state at lambda0 on set p, by the 9x9 balance
 * and the line of thrust of kinematics.c: the largest |T|/N over every
 * joint (both faces of a hinge coincide at rest), infinite when a joint's
 * resultant pulls (gothic's face-swapped set at its joint 10). */
static double static_mu(const aq_workpath *w)
{
  const aq_path *p = aq_workpath_path(w);
  const aq_mech *m = aq_workpath_mech(w);
  const aq_geom *g = m->g;
  size_t n = g->p.voussoirs;
  aq_mech_state st;
  aq_mech_eval(m, 0, &st);
  aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, p->g_mps2};
  aq_equil eq;
  aq_error e;
  aq_mech_equilibrium(m, &st, &live, &eq, &e);
  double *ecc = calloc(n + 1, sizeof *ecc);
  aq_vec2 *pt = calloc(n + 1, sizeof *pt), *dir = calloc(n + 1, sizeof *dir);
  int tension = 0;
  aq_mech_thrust_line(m, &st, &live, &eq, ecc, &tension, pt, dir);
  double mu = tension ? INFINITY : 0; /* a joint pulled apart holds by no friction */
  for (size_t j = 0; j <= n; j++) {
    aq_vec2 u = g->ju[j];
    double T = u.x * dir[j].x + u.y * dir[j].y, N = -u.y * dir[j].x + u.x * dir[j].y;
    mu = fmax(mu, fabs(T) / fabs(N));
  }
  free(ecc);
  free(pt);
  free(dir);
  return mu;
}

AQ_TEST(arch_demand_barely_past_lambda0_is_the_static_demand)
{
  gsl_set_error_handler_off();
  static const aq_model models[] = {AQ_MODEL_WORKPATH, AQ_MODEL_ODE, AQ_MODEL_WORKPATH_QUAD};
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(A, set);
      if (!p->admissible)
        continue;
      double want = static_mu(aq_arch_workpath(A, set));
      for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        aq_stepper *st = aq_stepper_alloc(aq_arch_path(A, 0), aq_arch_path(A, 1), models[k], &e);
        if (!aq_check(st != NULL, "stepper"))
          continue;
        aq_stepper_set_demand(st, aq_arch_demand_tracker(A, NAN, &e));
        aq_steps steps;
        /* 1e-9 above the set's threshold for the whole record (0.4 s) */
        double acc[40];
        for (int i = 0; i < 40; i++)
          acc[i] = p->act_sign * p->lambda0 * p->g_mps2 * (1 + 1e-9);
        if (!aq_check(aq_steps_from_samples(acc, 40, 0.01, 0, 0, &steps, &e) == AQ_OK, "steps"))
          continue;
        aq_result res;
        aq_check(aq_stepper_run(st, &steps, &res, &e) == AQ_OK, "runs");
        aq_check(res.first_set == set, "%s: set %d moved", shipped[f], set);
        if (isinf(want))
          aq_check(isinf(res.mu_demand), "%s set %d: a joint in tension at rest, got %g", shipped[f],
                   set, res.mu_demand);
        else
          aq_check_rel(res.mu_demand, want, 1e-7,
                     "%s set %d %s: mu_demand against the static collapse state at lambda0",
                     shipped[f], set, aq_model_name(models[k]));
        aq_result_free(&res);
        aq_steps_free(&steps);
        aq_stepper_free(st);
      }
    }
    aq_arch_free(A);
  }
}

AQ_TEST(arch_demand_runs_as_with_every_joint_at_every_state)
{
  /* real motions (pseudo-random records about lambda0 on every shipped
   * arch, three models): the tracker's results equal those of every joint
   * evaluated at every state the run passed through */
  gsl_set_error_handler_off();
  static const aq_model models[] = {AQ_MODEL_WORKPATH, AQ_MODEL_ODE, AQ_MODEL_WORKPATH_QUAD};
  unsigned long long rng = 0xd3a1d23ULL;
  size_t runs = 0, moved = 0, states = 0, full = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    const aq_path *p0 = aq_arch_path(A, 0), *p1 = aq_arch_path(A, 1);
    double lneg = p0->act_sign < 0 ? p0->lambda0 : p1->admissible ? p1->lambda0 : p0->lambda0;
    double lpos = p0->act_sign > 0 ? p0->lambda0 : p1->admissible ? p1->lambda0 : p0->lambda0;
    for (int r = 0; r < 3; r++) {
      enum { N = 300 };
      double t[N], dt[N], acc[N];
      tds_random(&rng, lneg * p0->g_mps2, lpos * p0->g_mps2, t, dt, acc, N);
      aq_steps steps;
      if (!aq_check(aq_steps_from_list(t, dt, acc, N, &steps, &e) == AQ_OK, "steps"))
        continue;
      aq_model model = models[r % 3];
      aq_result res[2];
      for (int k = 0; k < 2; k++) {
        aq_stepper *st = aq_stepper_alloc(p0, p1, model, &e);
        aq_demand *d = aq_arch_demand_tracker(A, 0.45, &e);
        aq_demand_set_every(d, k);
        aq_stepper_set_demand(st, d);
        aq_check(aq_stepper_run(st, &steps, &res[k], &e) == AQ_OK, "runs");
        aq_stepper_free(st);
      }
      runs++;
      moved += res[0].first_set >= 0;
      states += res[0].demand_samples, full += res[0].demand_full;
      int never = res[0].first_set < 0;
      aq_check(never ? isnan(res[0].mu_demand) && isnan(res[1].mu_demand)
                     : res[0].mu_demand == res[1].mu_demand &&
                           res[0].thrust_ecc_max == res[1].thrust_ecc_max,
               "%s %s run %d: mu %.17g ecc %.17g, every joint %.17g %.17g", shipped[f],
               aq_model_name(model), r, res[0].mu_demand, res[0].thrust_ecc_max,
               res[1].mu_demand, res[1].thrust_ecc_max);
      aq_check(res[0].mu_demand_joint == res[1].mu_demand_joint, "joint");
      aq_check((isnan(res[0].slide_time_s) && isnan(res[1].slide_time_s)) ||
                   res[0].slide_time_s == res[1].slide_time_s,
               "%s: slides at %g, every joint %g", shipped[f], res[0].slide_time_s,
               res[1].slide_time_s);
      aq_check((isnan(res[0].thrust_ecc_time_s) && isnan(res[1].thrust_ecc_time_s)) ||
                   res[0].thrust_ecc_time_s == res[1].thrust_ecc_time_s,
               "%s: thrust out at %g, every joint %g", shipped[f], res[0].thrust_ecc_time_s,
               res[1].thrust_ecc_time_s);
      aq_check(res[1].demand_full == res[1].demand_samples, "the reference evaluates every state");
      aq_result_free(&res[0]);
      aq_result_free(&res[1]);
      aq_steps_free(&steps);
    }
    aq_arch_free(A);
  }
  aq_check(moved >= runs / 2, "most runs move (%zu of %zu)", moved, runs);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("runs %zu (moved %zu): %zu states, %zu with every joint evaluated\n", runs, moved,
           states, full);
}

/* Every entry's |T|/N and |e|/N (0 at a hinge) at the state (s, a/g al,
 * KE/g kg) of t, from the tables, into r[2 nf]. */
static void entry_ratios(const aq_demand_table *t, aq_joint_form *fb, size_t nf, double s,
                         double al, double kg, double *r)
{
  aq_demand_kin kin;
  aq_demand_table_forms(t, s, fb, &kin);
  double w = 2 * kg / kin.mgen_kgm2;
  for (size_t j = 0; j < nf; j++) {
    double N = fb[j].n[0] + al * fb[j].n[1] + w * fb[j].n[2];
    double T = fabs(fb[j].t[0] + al * fb[j].t[1] + w * fb[j].t[2]);
    double E = fabs(fb[j].e[0] + al * fb[j].e[1] + w * fb[j].e[2]);
    r[2 * j] = N > 0 ? T / N : INFINITY;
    r[2 * j + 1] = fb[j].hinge < 0 ? (N > 0 ? E / N : INFINITY) : 0;
  }
}

AQ_TEST(arch_demand_grid_bounds_every_entry)
{
  /* the claim the tracker rests on: in the cell of the grid that holds a
   * state, no entry exceeds the cell's bound, and every entry that is not
   * a candidate is strictly below the largest candidate.  Random states of
   * every set of every shipped arch, over the grid's range of a/g (and
   * beyond it) and of KE/g, every entry evaluated from the tables. */
  gsl_set_error_handler_off();
  unsigned long long rng = 0xb0c5e5ULL;
  size_t points = 0, outside = 0, cands = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    size_t n = aq_arch_geom(A)->p.voussoirs, nf = aq_demand_nforms(n);
    aq_joint_form *fb = calloc(nf, sizeof *fb);
    size_t *cand = calloc(2 * nf, sizeof *cand);
    double *r = calloc(2 * nf, sizeof *r);
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(A, set);
      const aq_demand_table *t = aq_arch_demand_table(A, set);
      if (!t)
        continue;
      aq_path_point pc;
      aq_check(p->eval_exact(p->ctx, p->s_c_rad, &pc) == 0, "the path at s_c");
      double ke_ref = p->mass_kg * pc.y_m; /* KE/g of the energy of collapse */
      for (int i = 0; i < 2000; i++) {
        double s = tds_rng(&rng) * p->s_c_rad;
        double al = (2 * tds_rng(&rng) - 1) * 4.5 * p->lambda0;
        double kg = i % 10 == 0 ? 0 : ke_ref * pow(2.0, 16 * tds_rng(&rng) - 12);
        double u[2];
        size_t nc[2];
        int in = aq_demand_grid_cell(t, s, al, kg, u, cand, 2 * nf, nc);
        aq_check(in >= 0, "cap");
        if (in == 0) {
          outside++;
          continue;
        }
        double best[2] = {0, 0};
        entry_ratios(t, fb, nf, s, al, kg, r);
        for (size_t j = 0; j < nf; j++) {
          for (int q = 0; q < 2; q++)
            aq_check(r[2 * j + q] <= u[q], "%s set %d: s %.9g a/g %.6g KE/g %.6g: entry %zu "
                     "quantity %d %.17g above the cell's bound %.17g", shipped[f], set, s, al,
                     kg, j, q, r[2 * j + q], u[q]);
        }
        for (int q = 0; q < 2; q++)
          for (size_t m = 0; m < nc[q]; m++)
            best[q] = fmax(best[q], r[2 * cand[(q ? nc[0] : 0) + m] + (size_t)q]);
        for (size_t j = 0; j < nf; j++)
          for (int q = 0; q < 2; q++) {
            int is = 0;
            for (size_t m = 0; m < nc[q]; m++)
              is |= cand[(q ? nc[0] : 0) + m] == j;
            if (!is && (q == 0 || fb[j].hinge < 0))
              aq_check(r[2 * j + q] < best[q], "%s set %d: s %.9g a/g %.6g KE/g %.6g: entry "
                       "%zu (not a candidate) quantity %d %.17g, the candidates' largest %.17g",
                       shipped[f], set, s, al, kg, j, q, r[2 * j + q], best[q]);
          }
        points++;
        cands += nc[0] + nc[1];
      }
    }
    free(fb);
    free(cand);
    free(r);
    aq_arch_free(A);
  }
  aq_check(points > 20000 && outside > 1000, "states in cells %zu, outside %zu", points, outside);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("grid: %zu states in cells (%.2f candidates each), %zu outside\n", points,
           (double)cands / (double)points, outside);
}

AQ_TEST(arch_demand_grid_code_bounds)
{
  /* a cell's code is a bound: the value it stands for (aq_dg_bound's
   * float) is at least the bound it was made from, and within 1/128 of
   * it; at floats whose low 16 bits are zero and just above them, at
   * random values of every scale, 0 and the infinite */
  unsigned long long rng = 0xb0b16ULL;
  for (int i = 0; i < 20000; i++) {
    double u;
    if (i < 2000) { /* a float with 8 significant bits, then the next double or float up */
      uint32_t b = (uint32_t)(0x00800000u + (tds_rng(&rng) * 0x7e000000u)) & 0xffff0000u;
      float f;
      memcpy(&f, &b, sizeof f);
      u = i % 2 ? nextafter((double)f, INFINITY) : (double)nextafterf(f, INFINITY);
    } else {
      u = ldexp(0.5 + 0.5 * tds_rng(&rng), (int)(tds_rng(&rng) * 200) - 100); /* normal floats */
    }
    uint32_t b = (uint32_t)aq_dg_upper16(u) << 16;
    float f;
    memcpy(&f, &b, sizeof f);
    aq_check((double)f >= u && (double)f <= u * (1 + 1.0 / 128),
             "u %.17g: code %#x stands for %.17g", u, (unsigned)(b >> 16), (double)f);
  }
  aq_check(aq_dg_upper16(0) == 0 && aq_dg_upper16(INFINITY) == 0x7f80 &&
               aq_dg_upper16(NAN) == 0x7f80,
           "0, INFINITY, NAN: %#x %#x %#x", aq_dg_upper16(0), aq_dg_upper16(INFINITY),
           aq_dg_upper16(NAN));
}

AQ_TEST(arch_demand_grid_cubic_range)
{
  /* the range of a cubic over a part of [0, 1], on which every bound of
   * the grid rests: it holds the cubic's values at 2001 points (and it is
   * tight: within 1e-7 (the points' spacing) of the extremes they find, the widening
   * aside), for random cubics, most with a turning point inside */
  unsigned long long rng = 0xc0b1cULL;
  int inside = 0;
  for (int i = 0; i < 2000; i++) {
    double c[4], ua = 0.6 * tds_rng(&rng), ub = ua + 0.05 + 0.35 * tds_rng(&rng);
    for (int k = 0; k < 4; k++)
      c[k] = (2 * tds_rng(&rng) - 1) * (k == 3 && i % 7 == 0 ? 0 : 1);
    double lo, hi, slo = INFINITY, shi = -INFINITY;
    aq_dg_cubic_range(c, ua, ub, &lo, &hi);
    for (int m = 0; m <= 2000; m++) {
      double u = ua + (ub - ua) * m / 2000, v = aq_dt_cubic(c, u);
      slo = fmin(slo, v), shi = fmax(shi, v);
    }
    double e0 = aq_dt_cubic(c, ua), e1 = aq_dt_cubic(c, ub);
    inside += slo < fmin(e0, e1) - 1e-6 || shi > fmax(e0, e1) + 1e-6;
    double w = 1e-14 * (fabs(c[0]) + fabs(c[1]) + fabs(c[2]) + fabs(c[3]));
    aq_check(lo <= slo && hi >= shi, "cubic %d: range [%.17g, %.17g], values [%.17g, %.17g]", i,
             lo, hi, slo, shi);
    aq_check(lo >= slo - w - 1e-7 && hi <= shi + w + 1e-7, "cubic %d: range [%.17g, %.17g] "
             "looser than the values [%.17g, %.17g]", i, lo, hi, slo, shi);
  }
  aq_check(inside > 200, "cubics with an extreme inside: %d", inside);
}

/* fn on each set with a grid of every shipped arch; the states it counts. */
typedef size_t (*grid_case)(const char *arch, int set, const aq_demand_table *t,
                            aq_joint_form *fb, size_t nf, double *r);
static size_t each_grid(grid_case fn)
{
  gsl_set_error_handler_off();
  size_t states = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(shipped[f], &A, &e) == AQ_OK, "load %s", shipped[f]))
      continue;
    size_t nf = aq_demand_nforms(aq_arch_geom(A)->p.voussoirs);
    aq_joint_form *fb = calloc(nf, sizeof *fb);
    double *r = calloc(2 * nf, sizeof *r);
    for (int set = 0; set < 2; set++) {
      const aq_demand_table *t = aq_arch_demand_table(A, set);
      if (t && t->grid)
        states += fn(shipped[f], set, t, fb, nf, r);
    }
    free(fb);
    free(r);
    aq_arch_free(A);
  }
  return states;
}

static size_t corners(const char *arch, int set, const aq_demand_table *t, aq_joint_form *fb,
                      size_t nf, double *r)
{
  const aq_demand_grid *G = t->grid;
  static const int abin[] = {DG_NA / 2 + 7, DG_NA / 2 - 9}, kbin[] = {0, 9};
  size_t states = 0;
  for (int c = 0; c < 16; c++) { /* two bins of each, four corners */
    int ai = c & 1, ki = c >> 1 & 1, corner = c >> 2;
    double a0 = ((double)abin[ai] - 0.5 * DG_NA) * G->da, a1 = a0 + G->da;
    double al = corner & 1 ? nextafter(a1, a0) : a0;
    double k0 = kbin[ki] ? G->k0 * ldexp(1.0, (kbin[ki] - 1) >> DG_KB) : 0;
    double k1 = kbin[ki] ? k0 * (1 + 1.0 / (1 << DG_KB)) : G->k0;
    double kg = corner & 2 ? nextafter(k1, k0) : k0;
    for (size_t is = 0; is < DG_NS; is++)
      for (int m = 0; m < 7; m++) {
        double s = t->s_c * ((double)is + (m + 0.5) / 7) / DG_NS, u[2];
        size_t nc[2], cand[1024];
        if (aq_demand_grid_cell(t, s, al, kg, u, cand, 1024, nc) != 1)
          continue;
        entry_ratios(t, fb, nf, s, al, kg, r);
        for (size_t j = 0; j < nf; j++)
          aq_check(r[2 * j] <= u[0] && r[2 * j + 1] <= u[1],
                   "%s set %d: s %.9g a/g %.6g KE/g %.6g: entry %zu: %.17g %.17g, the cell's "
                   "bounds %.17g %.17g", arch, set, s, al, kg, j, r[2 * j], r[2 * j + 1], u[0],
                   u[1]);
        states++;
      }
  }
  return states;
}

AQ_TEST(arch_demand_grid_bounds_at_cell_corners)
{
  /* where a cell's bound is tightest: at the corners of its ranges of a/g
   * and KE/g (the forms are linear in both there), over s sampled densely
   * through every range of s (a coefficient's turning point inside a range
   * is where leaving it out would show), every entry evaluated */
  size_t states = each_grid(corners);
  aq_check(states > 50000, "states %zu", states);
}

static size_t walls_near, walls_seen;
static size_t walls(const char *arch, int set, const aq_demand_table *t, aq_joint_form *fb,
                    size_t nf, double *r)
{
  aq_demand_grid *G = t->grid;
  size_t states = 0;
  for (size_t ia = DG_NA / 2 - 12; ia < DG_NA / 2 + 12; ia += 3) {
    double a0 = ((double)ia - 0.5 * DG_NA) * G->da, al[2] = {a0, nextafter(a0 + G->da, a0)};
    double m[2] = {0, 0};
    for (int c = 0; c < 2; c++)
      for (int k = 0; k < 6 * DG_NS; k++, states++) {
        entry_ratios(t, fb, nf, t->s_c * (k + 0.5) / (6 * DG_NS), al[c], 0, r);
        for (size_t j = 0; j < 2 * nf; j++)
          m[j % 2] = fmax(m[j % 2], r[j]);
      }
    /* the bounds say no state at rest exceeds a little less than the
     * entries reach: wrong (an infinite demand: the bound must be too) */
    /* and it is near what they reach (a bound far above would leave every
     * wall to be found) */
    for (int q = 0; q < 2; q++)
      if (isfinite(m[q]) && m[q] > 0) {
        double above[2] = {INFINITY, INFINITY};
        above[q] = 1.25 * m[q];
        walls_near += aq_dg_wall_below(G, al[0], above);
        walls_seen++;
      }
    for (int q = 0; q < 2; q++) {
      double below[2] = {INFINITY, INFINITY};
      below[q] = isinf(m[q]) ? DBL_MAX : m[q] * (1 - 1e-9);
      aq_check(!aq_dg_wall_below(G, al[0], below), "%s set %d: a/g bin %zu: at rest "
               "quantity %d reaches %.9g, the walls' bound says less", arch, set, ia, q, m[q]);
    }
  }
  return states;
}

AQ_TEST(arch_demand_grid_walls_bound_states_at_rest)
{
  /* a leg's walls are found only when some state at rest under its a/g
   * could exceed the maxima: each a/g bin's bound must hold at rest (KE 0)
   * at every s.  States at rest sampled densely in s (six to each range of
   * s of the grid's rows) at both edges of each a/g bin, every entry
   * evaluated. */
  size_t states = each_grid(walls);
  aq_check(states > 50000, "states %zu", states);
  aq_check(walls_seen > 100 && walls_near >= walls_seen * 8 / 10,
           "the walls' bound within 1.25 of the states at rest in %zu of %zu a/g bins",
           walls_near, walls_seen);
}

/* A run in which the arch never moves: the least friction with which a
 * line of thrust stands at the record's peak (docs/demand.md, "A run that
 * never moves").  The test scans its own samples for each direction's peak
 * load a / (g + a_v) at the run's polarity and asks the linear program
 * (friction.c, solved here at that load, not read from the arch's table)
 * for the least friction there; the run's demand is the larger of the
 * two, within the table's error (5.4e-5 relative on the shipped arches:
 * test_arch_friction).  Over a limit between two of the record's running
 * peaks, the run slides at the first sample whose load needs more than the
 * limit (the least friction grows with the load: the first sample past it
 * is a running peak of its direction). */
#define STILL_REL 1e-4

static double still_lp(const aq_arch *A, int act, double lam, size_t *joint)
{
  double mu = NAN;
  aq_error e;
  aq_check(aq_friction_least(aq_arch_geom(A), act, lam, &mu, joint, &e) == AQ_OK,
           "the program at %g: %s", lam, e.message);
  return mu;
}

AQ_TEST(arch_demand_still_is_the_statics_at_the_peak)
{
  gsl_set_error_handler_off();
  unsigned long long rng = 0x5711ULL;
  size_t runs = 0, slides = 0, joints = 0;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *A = NULL;
    aq_error e;
    aq_arch_options o = {.friction_table = 1};
    if (!aq_check(aq_arch_load_opts(shipped[f], &o, &A, &e) == AQ_OK, "load %s: %s",
                  shipped[f], e.message))
      continue;
    const aq_path *p0 = aq_arch_path(A, 0), *p1 = aq_arch_path(A, 1);
    double g = p0->g_mps2, lmin = INFINITY;
    for (int k = 0; k < 2; k++)
      if (aq_arch_path(A, k) && aq_arch_path(A, k)->admissible)
        lmin = fmin(lmin, aq_arch_path(A, k)->lambda0);
    for (int r = 0; r < 3; r++) {
      /* below either set's threshold at either polarity; one direction
       * larger than the other; r = 2 with a vertical acceleration */
      enum { N = 600 };
      double acc[N], av[N], fpos = r == 1 ? 0.35 : 0.9, fneg = r == 1 ? 0.9 : 0.5;
      int vert = r == 2;
      for (int i = 0; i < N; i++) {
        double u = 2 * tds_rng(&rng) - 1;
        av[i] = vert ? 0.2 * g * (2 * tds_rng(&rng) - 1) : 0;
        acc[i] = u * lmin * (vert ? 0.8 : 1) * g * (u > 0 ? fpos : fneg);
      }
      aq_steps steps;
      if (!aq_check(aq_steps_from_samples(acc, N, 0.01, 0.5, 0, &steps, &e) == AQ_OK, "steps"))
        continue;
      if (vert && !aq_check(aq_steps_set_vertical(&steps, av, &e) == AQ_OK, "vertical"))
        continue;
      for (int pol = -1; pol <= 1; pol += 2) {
        /* the test's own peaks, and the running peaks in time */
        double peak[2] = {0, 0}, mu[2];
        size_t first[2] = {0, 0}, jt[2] = {0, 0};
        double run_mu[N];
        for (int i = 0; i < N; i++) {
          double load = pol * acc[i] / (g + av[i]);
          int k = load > 0;
          run_mu[i] = NAN;
          if (fabs(load) > peak[k]) {
            peak[k] = fabs(load);
            first[k] = (size_t)i;
            run_mu[i] = still_lp(A, 2 * k - 1, peak[k], NULL);
          }
        }
        for (int k = 0; k < 2; k++)
          mu[k] = still_lp(A, 2 * k - 1, peak[k], &jt[k]);
        int gk = mu[1] > mu[0] || (mu[1] == mu[0] && first[1] < first[0]);
        double want = mu[gk];
        /* a limit between the running largest demand before a sample and
         * that sample's (a jump of more than 1 %, the last one): the first
         * sample that needs more than the limit */
        double lim = NAN, prev = still_lp(A, 1, 0, NULL), want_t = NAN;
        for (int i = 0; i < N; i++) {
          if (isnan(run_mu[i]))
            continue;
          if (run_mu[i] > prev * 1.01) {
            lim = 0.5 * (prev + run_mu[i]);
            want_t = 0.5 + 0.01 * i;
          }
          prev = fmax(prev, run_mu[i]);
        }
        for (int with = 0; with < 2; with++) {
          aq_stepper *st = aq_stepper_alloc(p0, p1, AQ_MODEL_WORKPATH, &e);
          aq_stepper_set_scale(st, pol);
          aq_stepper_set_demand(st, aq_arch_demand_tracker(A, with ? lim : NAN, &e));
          aq_result res;
          if (!aq_check(aq_stepper_run(st, &steps, &res, &e) == AQ_OK, "runs: %s", e.message)) {
            aq_stepper_free(st);
            continue;
          }
          runs++;
          aq_check(res.first_set < 0, "%s r %d pol %d: never moves", shipped[f], r, pol);
          aq_check_rel(res.mu_demand, want, STILL_REL,
                       "%s r %d pol %+d: mu_demand against the program at the peaks %g (-) %g (+)",
                       shipped[f], r, pol, peak[0], peak[1]);
          joints += res.mu_demand_joint == jt[gk];
          aq_check(isnan(res.thrust_ecc_max), "no thrust eccentricity at rest");
          if (with && !isnan(lim)) {
            slides++;
            aq_check(res.slide_time_s == want_t,
                     "%s r %d pol %+d: slides over %g at %.17g, expected %.17g", shipped[f], r,
                     pol, lim, res.slide_time_s, want_t);
          } else {
            aq_check(isnan(res.slide_time_s), "no limit: no slide");
          }
          aq_result_free(&res);
          aq_stepper_free(st);
        }
      }
      aq_steps_free(&steps);
    }
    /* a run that moves is the tracker's alone: the same results, to the
     * bit, without the statics */
    for (int k = 0; k < 2; k++) {
      const aq_path *p = aq_arch_path(A, k);
      if (!p || !p->admissible)
        continue;
      aq_steps steps;
      double acc[60];
      for (int i = 0; i < 60; i++)
        acc[i] = i < 20 ? p->act_sign * 1.3 * p->lambda0 * g : 0;
      if (!aq_check(aq_steps_from_samples(acc, 60, 0.01, 0, 0, &steps, &e) == AQ_OK, "steps"))
        continue;
      aq_result res[2];
      for (int w = 0; w < 2; w++) {
        aq_stepper *st = aq_stepper_alloc(p0, p1, AQ_MODEL_WORKPATH, &e);
        aq_demand *d = aq_arch_demand_tracker(A, 0.5, &e);
        if (w)
          aq_demand_set_least(d, NULL, NULL);
        aq_stepper_set_demand(st, d);
        aq_check(aq_stepper_run(st, &steps, &res[w], &e) == AQ_OK, "runs");
        aq_stepper_free(st);
      }
      aq_check(res[0].first_set == k, "%s: set %d moves", shipped[f], k);
      aq_check(memcmp(&res[0].mu_demand, &res[1].mu_demand, sizeof(double)) == 0 &&
                   res[0].mu_demand_joint == res[1].mu_demand_joint &&
                   memcmp(&res[0].slide_time_s, &res[1].slide_time_s, sizeof(double)) == 0 &&
                   memcmp(&res[0].thrust_ecc_max, &res[1].thrust_ecc_max, sizeof(double)) == 0,
               "%s set %d: a run that moves, with and without the statics", shipped[f], k);
      aq_result_free(&res[0]);
      aq_result_free(&res[1]);
      aq_steps_free(&steps);
    }
    aq_arch_free(A);
  }
  aq_check(slides >= runs / 4, "slides checked in %zu of %zu runs", slides, runs);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("still runs %zu, slide times %zu, joints as the program's %zu\n", runs, slides,
           joints);
}
