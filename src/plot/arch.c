/* arch.c: the arch to scale (m), its voussoirs and the hinges of both sets,
 * extrados and intrados hinges told apart; with a rotation, the four-bar
 * deformed by the arch stage's exact kinematics (aq_mech_eval: body 1 turns
 * about H1, body 3 about H4, body 2 rides between on H2', H3') drawn over
 * the undeformed outline. */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <string.h>

#include "../arch/model.h"
#include "plot.h"

enum { ARC_PTS = 16 };
static const char *const AX_X = "x from the arch's centre (m)",
                         *const AX_Y = "y from the arch's centre (m)"; /* points per voussoir face arc */

typedef struct {
  const aq_arch *arch;
  const aq_geom *g;
  int set;             /* deformed set, -1: none */
  double s_rad;        /* its rotation, rad (>= 0) */
  aq_mech_state st;    /* deformed four-bar */
  const aq_mech *m;
} fig;

static aq_vec2 rot_about(aq_vec2 p, aq_vec2 from, aq_vec2 to, double a)
{
  double c = cos(a), s = sin(a), x = p.x - from.x, y = p.y - from.y;
  aq_vec2 v = {to.x + c * x - s * y, to.y + s * x + c * y};
  return v;
}

/* Point p of voussoir k, moved with its body when the set is deformed. */
static aq_vec2 moved(const fig *f, size_t k, aq_vec2 p)
{
  if (f->set < 0)
    return p;
  const aq_mech *m = f->m;
  const size_t *j = m->hs.joint;
  if (k < j[0] || k >= j[3])
    return p;                                       /* fixed voussoir */
  if (k < j[1])
    return rot_about(p, m->h[0], m->h[0], f->st.phi[0][0]); /* body 1 about H1 */
  if (k < j[2])
    return rot_about(p, m->h[1], f->st.h2, f->st.phi[1][0]); /* body 2 on H2' */
  return rot_about(p, m->h[3], m->h[3], f->st.phi[2][0]);    /* body 3 about H4 */
}

/* Outline of voussoir k: extrados arc then intrados arc back (2 ARC_PTS). */
static void outline(const fig *f, size_t k, int deformed, PLFLT *x, PLFLT *y)
{
  const aq_geom *g = f->g;
  double a0 = g->theta_rad[k], a1 = g->theta_rad[k + 1];
  for (int i = 0; i < ARC_PTS; i++) {
    double t = a0 + (a1 - a0) * i / (ARC_PTS - 1);
    aq_vec2 pe = {g->r_e_m * cos(t), g->r_e_m * sin(t)};
    double u = a1 - (a1 - a0) * i / (ARC_PTS - 1);
    aq_vec2 pi = {g->r_i_m * cos(u), g->r_i_m * sin(u)};
    if (deformed) {
      pe = moved(f, k, pe);
      pi = moved(f, k, pi);
    }
    x[i] = pe.x;
    y[i] = pe.y;
    x[ARC_PTS + i] = pi.x;
    y[ARC_PTS + i] = pi.y;
  }
}

static const char *const sym_e[2] = {"●", "▲"}, *const sym_i[2] = {"○", "△"};

/* Hinge k of set s, deformed when s is the deformed set. */
static aq_vec2 hinge(const fig *f, int s, int k)
{
  const aq_mech *m = aq_workpath_mech(aq_arch_workpath(f->arch, s));
  if (s != f->set || k == 0 || k == 3)
    return m->h[k];
  return k == 1 ? f->st.h2 : f->st.h3;
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const fig *f = ctx;
  const aq_geom *g = f->g;
  size_t n = g->p.voussoirs;
  PLFLT x[2 * ARC_PTS + 1], y[2 * ARC_PTS + 1];
  double re = g->r_e_m, span = 2 * re;
  /* from just below the arch's lowest point (its springings); the legend
   * goes below the frame */
  double ybot = fmin(g->r_i_m, g->r_e_m) * cos(0.5 * g->p.embrace_rad);
  double ylo = ybot - 0.08 * (re - ybot);
  pladv(0);
  plschr(0, 0.9);
  double xlo = -0.6 * span, xhi = 0.6 * span, yhi = re * 1.1;
  plvpas(0.1, 0.95, 0.33, 0.92, (yhi - ylo) / (xhi - xlo)); /* equal scales: to scale */
  plwind(xlo, xhi, ylo, yhi);
  plcol0(AQ_PC_LIGHT);
  plbox("g", 0, 0, "g", 0, 0);
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bcnstv", 0, 0);
  char title[256];
  if (f->set >= 0)
    snprintf(title, sizeof title, "arch %s: %s set deformed at %.4g rad",
             aq_arch_name(f->arch), f->set ? "reverse" : "primary", f->s_rad);
  else
    snprintf(title, sizeof title, "arch %s: %zu voussoirs, span %.3g m",
             aq_arch_name(f->arch), n,
             2 * g->r_e_m * sin(0.5 * g->p.embrace_rad));
  pllab(AX_X, AX_Y, title);
  for (size_t k = 0; k < n; k++) {
    outline(f, k, 0, x, y);
    x[2 * ARC_PTS] = x[0];
    y[2 * ARC_PTS] = y[0];
    if (f->set < 0) {
      plcol0(AQ_PC_LIGHT);
      plfill(2 * ARC_PTS, x, y);
      plcol0(AQ_PC_FG);
      plline(2 * ARC_PTS + 1, x, y);
    } else {
      plcol0(AQ_PC_GREY);
      pllsty(2);
      plline(2 * ARC_PTS + 1, x, y);
      pllsty(1);
      outline(f, k, 1, x, y);
      x[2 * ARC_PTS] = x[0];
      y[2 * ARC_PTS] = y[0];
      plcol0(AQ_PC_LIGHT);
      plfill(2 * ARC_PTS, x, y);
      plcol0(AQ_PC_FG);
      plline(2 * ARC_PTS + 1, x, y);
    }
  }
  static const int color[2] = {AQ_PC_BLUE, AQ_PC_ORANGE};
  plschr(0, 1.3);
  for (int s = 0; s < 2; s++) {
    const aq_mech *m = aq_workpath_mech(aq_arch_workpath(f->arch, s));
    plcol0(color[s]);
    for (int k = 0; k < 4; k++) {
      aq_vec2 h = hinge(f, s, k);
      PLFLT hx = h.x, hy = h.y;
      plstring(1, &hx, &hy, m->hs.face[k] == 'e' ? sym_e[s] : sym_i[s]);
    }
  }
  plschr(0, 0.9);
  char txt[4][128];
  const char *t[6];
  int c[6], st[6];
  const char *sy[6];
  for (int s = 0; s < 2; s++) {
    const aq_path *p = aq_arch_path(f->arch, s);
    snprintf(txt[2 * s], sizeof txt[0], "%s, extrados hinge: #gl#d0#u = %.4g, q#dc#u = %.4g rad",
             s ? "reverse" : "primary", p->lambda0, p->s_c_rad);
    snprintf(txt[2 * s + 1], sizeof txt[0], "%s, intrados hinge%s", s ? "reverse" : "primary",
             p->admissible ? "" : " (set not admissible)");
    t[2 * s] = txt[2 * s];
    t[2 * s + 1] = txt[2 * s + 1];
    c[2 * s] = c[2 * s + 1] = color[s];
    st[2 * s] = st[2 * s + 1] = 0;
    sy[2 * s] = sym_e[s];
    sy[2 * s + 1] = sym_i[s];
  }
  size_t nl = 4;
  if (f->set >= 0) {
    t[4] = "undeformed";
    c[4] = AQ_PC_GREY;
    st[4] = 2;
    sy[4] = "";
    nl = 5;
  }
  plvpor(0.1, 0.95, 0.01, 0.21);
  aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP, nl, t, c, st, sy);
  return 0;
}

/* series,index,x_m,y_m: voussoir corners (ext k, ext k+1, int k+1, int k),
 * hinges of both sets, and the deformed corners and hinges. */
static aq_status write_data(const fig *f, const char *data, aq_error *err)
{
  char tmp[1024];
  FILE *o = aq_plot_csv_open(data, tmp, sizeof tmp, err);
  if (!o)
    return err->status;
  aq_plot_csv_axes(o, 2, (const char *[]){AX_X, AX_Y});
  fprintf(o, "series,index,x_m,y_m\n");
  for (int d = 0; d <= (f->set >= 0); d++)
    for (size_t k = 0; k < f->g->p.voussoirs; k++) {
      aq_vec2 p[4] = {aq_geom_joint_point(f->g, k, 'e'), aq_geom_joint_point(f->g, k + 1, 'e'),
                      aq_geom_joint_point(f->g, k + 1, 'i'), aq_geom_joint_point(f->g, k, 'i')};
      for (int i = 0; i < 4; i++) {
        aq_vec2 q = d ? moved(f, k, p[i]) : p[i];
        fprintf(o, "%s,%zu,%.17g,%.17g\n", d ? "deformed_corner" : "corner", k, q.x, q.y);
      }
    }
  for (int s = 0; s < 2; s++) {
    const aq_mech *m = aq_workpath_mech(aq_arch_workpath(f->arch, s));
    for (int k = 0; k < 4; k++) {
      fprintf(o, "%s_hinge_%c,%zu,%.17g,%.17g\n", s ? "reverse" : "primary",
              m->hs.face[k], m->hs.joint[k], m->h[k].x, m->h[k].y);
      if (s == f->set) {
        aq_vec2 h = hinge(f, s, k);
        fprintf(o, "deformed_hinge_%c,%zu,%.17g,%.17g\n", m->hs.face[k],
                m->hs.joint[k], h.x, h.y);
      }
    }
  }
  return aq_plot_csv_close(o, tmp, data, 1, err);
}

aq_status aq_plot_arch(const aq_arch *arch, double rotation_rad, const char *target,
                       const char *data, double *draw_s, aq_error *err)
{
  fig f;
  memset(&f, 0, sizeof f);
  f.arch = arch;
  f.g = aq_arch_geom(arch);
  f.set = -1;
  if (rotation_rad != 0) {
    f.set = rotation_rad > 0 ? 0 : 1;
    f.s_rad = fabs(rotation_rad);
    const aq_path *p = aq_arch_path(arch, f.set);
    f.m = aq_workpath_mech(aq_arch_workpath(arch, f.set));
    if (!(f.s_rad <= p->s_c_rad))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--rotation",
                          "expected |rotation| <= q_c of the %s set (%.6g rad), got %g",
                          p->name, p->s_c_rad, rotation_rad);
    if (aq_mech_eval(f.m, p->q_sign * f.s_rad, &f.st) != 0)
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--rotation",
                          "the %s set does not close at %g rad", p->name, rotation_rad);
  }
  aq_status rc = aq_plot_render(target, 1000, 760, draw, &f, draw_s, err);
  if (rc == AQ_OK && data)
    rc = write_data(&f, data, err);
  return rc;
}
