/* arch.c: the arch to scale (m) as it is built: its voussoirs (the real
 * faces, from the arch stage's outlines), its fill and its point masses,
 * the hinges of both sets (extrados and intrados told apart), and the line
 * of thrust: the funicular polygon of the resultants across the joints,
 * where the resultant crosses each joint, from the hinge reactions of the
 * 9x9 equilibrium (eq. (3), aq_mech_thrust_line) of the primary set at
 * lambda0.  With a rotation, the
 * four-bar deformed by the arch stage's exact kinematics (aq_mech_eval:
 * body 1 turns about H1, body 3 about H4, body 2 rides between on H2', H3')
 * is drawn over the undeformed outline, fill and masses moving with their
 * voussoirs, and the line of thrust is that set's at lambda(q) in the
 * deformed arch.  The frame holds the undeformed and the deformed arch
 * with a margin.  Below it, the friction each joint needs (|T|/N of the
 * resultant across it) in each set's collapse state at its lambda0 (the
 * 9x9 hinge reactions and each piece's statics, aq_arch_joint_friction),
 * with the arch's friction coefficient when it has one.  A run of the
 * block model (plot arch --run KEY --at T): every voussoir where its
 * stored history has it at each time T (linear between samples), the last
 * time filled, over the undeformed outline.  The figure drawn from a
 * results file is read in arch_h5.c. */
#include <hdf5.h>
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/model.h"
#include "plot.h"
#include "arch_fig.h"

static const char *const AX_X = "x (m)", *const AX_Y = "y (m)";
#define FRAME_MARGIN 0.06 /* of the drawing's larger extent, on every side */
#define FIG_W 1000        /* pixels */
#define PLOT_H 620        /* pixels above the legend */
#define LEGEND_ROW 32     /* pixels per legend entry (2 character heights) */
#define C_FILL 15         /* colour map 0's spare entry (plot.h uses 0..14): sand */
#define PANEL_H 320       /* pixels of the friction panel, below the arch */
#define RATIO_CAP 3.0     /* the friction panel's top at most: a larger demand (a joint
                             that pulls needs infinite friction) is drawn at the top */

static aq_vec2 rot_about(aq_vec2 p, aq_vec2 from, aq_vec2 to, double a)
{
  double c = cos(a), s = sin(a), x = p.x - from.x, y = p.y - from.y;
  aq_vec2 v = {to.x + c * x - s * y, to.y + s * x + c * y};
  return v;
}

/* Deformed layers drawn over the undeformed arch: the block model's
 * times, or the one deformed set (or none). */
static int layers(const fig *f)
{
  return f->nat ? (int)f->nat : f->set >= 0;
}

/* Point p of voussoir k in layer d (0: undeformed; 1..layers: the block
 * model's time d - 1, or the deformed set). */
static aq_vec2 moved(const fig *f, int d, size_t k, aq_vec2 p)
{
  if (d == 0)
    return p;
  if (f->nat) {
    size_t i = (size_t)(d - 1) * f->g->p.voussoirs + k;
    return rot_about(p, f->g->vous[k].c, (aq_vec2){f->bx[i], f->by[i]}, f->br[i]);
  }
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

static const char *const sym_e[2] = {"●", "▲"}, *const sym_i[2] = {"○", "△"};
#define SYM_MASS "■"

/* Hinge k of set s, deformed when s is the deformed set. */
static aq_vec2 hinge(const fig *f, int s, int k)
{
  const aq_mech *m = aq_workpath_mech(aq_arch_workpath(f->arch, s));
  if (s != f->set || k == 0 || k == 3)
    return m->h[k];
  return k == 1 ? f->st.h2 : f->st.h3;
}

/* The line of thrust of set s at state st: where the resultant crosses
 * each joint (the hinge at a hinge joint), joined joint to joint. */
static int thrust_line(fig *f, int s, const aq_mech_state *st, aq_error *err)
{
  const aq_workpath *w = aq_arch_workpath(f->arch, s);
  const aq_path *p = aq_workpath_path(w);
  const aq_mech *m = aq_workpath_mech(w);
  size_t n = f->g->p.voussoirs;
  aq_equil eq;
  aq_live live = {AQ_LIVE_HORIZONTAL, p->act_sign, {0, 0}, 0, p->g_mps2};
  if (aq_mech_equilibrium(m, st, &live, &eq, err) != AQ_OK)
    return -1;
  double *ecc = malloc((n + 1) * sizeof *ecc);
  aq_vec2 *pt = malloc((n + 1) * sizeof *pt), *dir = malloc((n + 1) * sizeof *dir);
  f->thrust = malloc((n + 1) * sizeof *f->thrust);
  if (!ecc || !pt || !dir || !f->thrust) {
    free(ecc);
    free(pt);
    free(dir);
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    return -1;
  }
  aq_mech_thrust_line(m, st, &live, &eq, ecc, NULL, pt, dir);
  size_t k = 0;
  for (size_t j = 0; j <= n; j++)
    f->thrust[k++] = pt[j];
  f->nthrust = k;
  f->thrust_set = s;
  f->thrust_lambda = eq.lambda;
  free(ecc);
  free(pt);
  free(dir);
  return 0;
}

/* A closed polygon of pts[0..n), voussoir k's, moved to layer d. */
static void polygon(const fig *f, size_t k, const aq_vec2 *pts, size_t n, int d,
                    int fill_color, int line_color, int style)
{
  if (n < 2)
    return;
  PLFLT *x = malloc((n + 1) * sizeof *x), *y = malloc((n + 1) * sizeof *y);
  if (!x || !y) {
    free(x);
    free(y);
    return;
  }
  for (size_t i = 0; i <= n; i++) {
    aq_vec2 p = moved(f, d, k, pts[i % n]);
    x[i] = p.x;
    y[i] = p.y;
  }
  if (fill_color >= 0) {
    plcol0(fill_color);
    plfill((PLINT)n, x, y);
  }
  if (line_color >= 0) {
    plcol0(line_color);
    pllsty(style);
    plline((PLINT)n + 1, x, y);
    pllsty(1);
  }
  free(x);
  free(y);
}

/* The extent of everything drawn: outlines, fill, masses, deformed too. */
static void extent(const fig *f, double *xlo, double *xhi, double *ylo, double *yhi)
{
  const aq_geom *g = f->g;
  size_t n = g->p.voussoirs;
  *xlo = *ylo = HUGE_VAL;
  *xhi = *yhi = -HUGE_VAL;
  for (int d = 0; d <= layers(f); d++)
    for (size_t k = 0; k < n; k++) {
      for (size_t i = g->outline_start[k]; i < g->outline_start[k + 1]; i++) {
        aq_vec2 p = moved(f, d, k, g->outline[i]);
        *xlo = fmin(*xlo, p.x), *xhi = fmax(*xhi, p.x);
        *ylo = fmin(*ylo, p.y), *yhi = fmax(*yhi, p.y);
      }
      for (size_t i = g->fill_start[k]; i < g->fill_start[k + 1]; i++) {
        aq_vec2 p = moved(f, d, k, g->fill[i]);
        *xlo = fmin(*xlo, p.x), *xhi = fmax(*xhi, p.x);
        *ylo = fmin(*ylo, p.y), *yhi = fmax(*yhi, p.y);
      }
    }
  for (size_t i = 0; i < g->p.nmass; i++)
    for (int d = 0; d <= layers(f); d++) {
      aq_vec2 p = moved(f, d, g->mass[i].voussoir, g->mass[i].p);
      *xlo = fmin(*xlo, p.x), *xhi = fmax(*xhi, p.x);
      *ylo = fmin(*ylo, p.y), *yhi = fmax(*yhi, p.y);
    }
}

/* The friction panel in the viewport's rows [y0, y1]: each set's |T|/N per
 * joint at lambda0, the arch's friction coefficient dashed. */
static void draw_friction(const fig *f, double y0, double y1)
{
  static const int color[2] = {AQ_PC_BLUE, AQ_PC_ORANGE};
  size_t n = f->g->p.voussoirs;
  double mu = aq_arch_friction(f->arch);
  plvpor(0.13, 0.95, y0, y1);
  plwind(-0.5, (double)n + 0.5, 0, f->ratio_max);
  plcol0(AQ_PC_LIGHT);
  plbox("g", 0, 0, "g", 0, 0);
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bcnstv", 0, 0);
  char title[200];
  if (mu > 0)
    snprintf(title, sizeof title, "friction needed at #gl#d0#u: primary blue, reverse orange; "
                                  "#gm = %.3g dashed", mu);
  else
    snprintf(title, sizeof title, "friction needed at #gl#d0#u: primary blue, reverse orange");
  pllab("joint", "|T| / N", title);
  for (int s = 0; s < 2; s++) {
    if (!f->ratio[s])
      continue;
    PLFLT *x = malloc((n + 1) * sizeof *x), *y = malloc((n + 1) * sizeof *y);
    if (x && y) {
      for (size_t j = 0; j <= n; j++)
        x[j] = (PLFLT)j, y[j] = fmin(f->ratio[s][j], f->ratio_max);
      plcol0(color[s]);
      plwidth(2);
      plline((PLINT)(n + 1), x, y);
      plwidth(1);
      plstring((PLINT)(n + 1), x, y, s ? "#(840)" : "#(841)");
    }
    free(x);
    free(y);
  }
  if (mu > 0 && mu <= f->ratio_max) {
    PLFLT x[2] = {-0.5, (double)n + 0.5}, y[2] = {mu, mu};
    plcol0(AQ_PC_RED);
    pllsty(2);
    plline(2, x, y);
    pllsty(1);
  }
}
/* The colours of the block model's times. */
static const int at_color[] = {AQ_PC_TEAL, AQ_PC_BROWN, AQ_PC_NAVY, AQ_PC_PINK, AQ_PC_OLIVE,
                               AQ_PC_FG};
#define N_AT_COLOR (sizeof at_color / sizeof at_color[0])
_Static_assert(N_AT_COLOR >= AQ_PLOT_ARCH_AT_MAX, "a colour per time");

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const fig *f = ctx;
  const aq_geom *g = f->g;
  size_t n = g->p.voussoirs;
  double xlo, xhi, ylo, yhi;
  extent(f, &xlo, &xhi, &ylo, &yhi);
  double size = fmax(xhi - xlo, yhi - ylo), pad = FRAME_MARGIN * size;
  xlo -= pad, xhi += pad, ylo -= pad, yhi += pad;
  pladv(0);
  plscol0(C_FILL, 232, 214, 170);
  plschr(0, 0.9);
  double legend = (double)(LEGEND_ROW * f->nlegend + 40) / f->height;
  double panel = f->ratio_max > 0 ? (double)PANEL_H / f->height : 0;
  plvpas(0.1, 0.95, legend + panel + 0.11, 0.93, (yhi - ylo) / (xhi - xlo)); /* equal scales */
  plwind(xlo, xhi, ylo, yhi);
  plcol0(AQ_PC_LIGHT);
  plbox("g", 0, 0, "g", 0, 0);
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bcnstv", 0, 0);
  char title[700], name[300], rest[300];
  /* the centre line's span, between the springing joints' midpoints (the
   * centre line passes through every joint's midpoint; so also for an arch
   * read back from a results file); a joints arch: its intrados span */
  int centre = g->p.shape != AQ_SHAPE_JOINTS;
  double span = centre ? fabs(0.5 * (g->ji[0].x + g->je[0].x) - 0.5 * (g->ji[n].x + g->je[n].x))
                       : fabs(g->ji[0].x - g->ji[n].x);
  const char *what = centre ? "span" : "intrados span";
  if (f->nat == 1)
    snprintf(rest, sizeof rest, "run %s, block model at %.6g s", f->run, f->at_s[0]);
  else if (f->nat)
    snprintf(rest, sizeof rest, "run %s, block model at %zu times", f->run, f->nat);
  else if (f->set >= 0)
    snprintf(rest, sizeof rest, "%s set deformed at %.4g rad", f->set ? "reverse" : "primary",
             f->s_rad);
  else
    snprintf(rest, sizeof rest, "%zu voussoirs, %s, %s %.4g m", n, aq_shape_names[g->p.shape],
             what, span);
  /* on one line, or the name on a line of its own */
  double room = 0.94 * aq_plot_page_w_mm();
  aq_plot_escape(aq_arch_name(f->arch), name, sizeof name);
  snprintf(title, sizeof title, "arch %s: %s", name, rest);
  pllab(AX_X, AX_Y, "");
  if (aq_plot_text_mm(title) <= room) {
    plmtex("t", 2.0, 0.5, 0.5, title);
  } else {
    aq_plot_shorten_to(aq_arch_name(f->arch), room - aq_plot_text_mm("arch :"), name,
                       sizeof name);
    snprintf(title, sizeof title, "arch %s:", name);
    plmtex("t", 3.0, 0.5, 0.5, title);
    plmtex("t", 1.6, 0.5, 0.5, rest);
  }
  /* fill, then the voussoirs: undeformed (dashed when deformed), deformed
   * (the block model's last time filled, then its earlier times over it as
   * outlines in their colours) */
  int nd = layers(f);
  for (int j = 0; j <= nd; j++) {
    int d = j <= 1 ? j * nd : j - 1; /* 0, nd, 1, ..., nd - 1 */
    int ghost = nd > 0 && d == 0, bare = f->nat && d > 0 && d < nd;
    int line = ghost ? AQ_PC_GREY : f->nat > 1 ? at_color[(d - 1) % N_AT_COLOR] : AQ_PC_FG;
    for (size_t k = 0; k < n; k++) {
      size_t a = g->fill_start[k], b = g->fill_start[k + 1];
      polygon(f, k, g->fill + a, b - a, d, ghost || bare ? -1 : C_FILL,
              ghost ? AQ_PC_GREY : -1, 2);
    }
    for (size_t k = 0; k < n; k++) {
      size_t a = g->outline_start[k], b = g->outline_start[k + 1];
      polygon(f, k, g->outline + a, b - a, d, ghost || bare ? -1 : AQ_PC_LIGHT, line,
              ghost ? 2 : 1);
    }
  }
  /* the line of thrust */
  if (f->nthrust > 1) {
    PLFLT *x = malloc(f->nthrust * sizeof *x), *y = malloc(f->nthrust * sizeof *y);
    if (x && y) {
      for (size_t i = 0; i < f->nthrust; i++)
        x[i] = f->thrust[i].x, y[i] = f->thrust[i].y;
      plcol0(AQ_PC_RED);
      plwidth(2);
      plline((PLINT)f->nthrust, x, y);
      plwidth(1);
    }
    free(x);
    free(y);
  }
  /* point masses, moved with their voussoirs */
  plschr(0, 1.1);
  for (size_t i = 0; i < g->p.nmass; i++) {
    aq_vec2 p = moved(f, nd, g->mass[i].voussoir, g->mass[i].p);
    PLFLT px = p.x, py = p.y;
    plcol0(AQ_PC_PURPLE);
    plstring(1, &px, &py, SYM_MASS);
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
  char txt[8 + AQ_PLOT_ARCH_AT_MAX][160];
  const char *t[8 + AQ_PLOT_ARCH_AT_MAX];
  int c[8 + AQ_PLOT_ARCH_AT_MAX], st[8 + AQ_PLOT_ARCH_AT_MAX];
  const char *sy[8 + AQ_PLOT_ARCH_AT_MAX];
  size_t nl = 0;
  for (int s = 0; s < 2; s++) {
    const aq_path *p = aq_arch_path(f->arch, s);
    snprintf(txt[nl], sizeof txt[0], "%s, extrados hinge: #gl#d0#u = %.4g, q#dc#u = %.4g rad",
             s ? "reverse" : "primary", p->lambda0, p->s_c_rad);
    t[nl] = txt[nl], c[nl] = color[s], st[nl] = 0, sy[nl] = sym_e[s];
    nl++;
    snprintf(txt[nl], sizeof txt[0], "%s, intrados hinge%s", s ? "reverse" : "primary",
             p->admissible ? "" : " (set not admissible)");
    t[nl] = txt[nl], c[nl] = color[s], st[nl] = 0, sy[nl] = sym_i[s];
    nl++;
  }
  if (f->nthrust > 1) {
    if (f->set >= 0)
      snprintf(txt[nl], sizeof txt[0], "line of thrust, %s set at #gl = %.4g",
               f->thrust_set ? "reverse" : "primary", f->thrust_lambda);
    else
      snprintf(txt[nl], sizeof txt[0], "line of thrust at #gl#d0#u (9×9 equilibrium)");
    t[nl] = txt[nl], c[nl] = AQ_PC_RED, st[nl] = 1, sy[nl] = "";
    nl++;
  }
  if (g->fill_kg > 0) {
    snprintf(txt[nl], sizeof txt[0], "fill: %.4g kg, carried by the voussoirs (masonry %.4g kg)",
             g->fill_kg, g->stone_kg);
    t[nl] = txt[nl], c[nl] = C_FILL, st[nl] = 0, sy[nl] = SYM_MASS;
    nl++;
  }
  if (g->p.nmass > 0) {
    snprintf(txt[nl], sizeof txt[0], "%zu point mass%s, %.4g kg", g->p.nmass,
             g->p.nmass > 1 ? "es" : "", g->point_kg);
    t[nl] = txt[nl], c[nl] = AQ_PC_PURPLE, st[nl] = 0, sy[nl] = SYM_MASS;
    nl++;
  }
  if (nd > 0) {
    t[nl] = "undeformed", c[nl] = AQ_PC_GREY, st[nl] = 2, sy[nl] = "";
    nl++;
  }
  for (size_t i = 0; i < f->nat; i++) {
    snprintf(txt[nl], sizeof txt[0], "t = %.6g s%s", f->at_s[i],
             f->nat > 1 && i + 1 == f->nat ? " (filled)" : "");
    t[nl] = txt[nl], c[nl] = f->nat > 1 ? at_color[i % N_AT_COLOR] : AQ_PC_FG, st[nl] = 1,
    sy[nl] = "";
    nl++;
  }
  plvpor(0.1, 0.95, 0.01, legend);
  aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP, nl, t, c, st, sy);
  if (panel > 0)
    draw_friction(f, legend + 0.08, legend + panel);
  return 0;
}

/* series,index,x_m,y_m,mu: voussoir corners (ext k, ext k+1, int k+1, int
 * k), outlines (curved faces sampled) and fills by voussoir, point masses,
 * hinges of both sets, the line of thrust, and the deformed corners,
 * outlines, fills, masses and hinges (mu nan); each set's friction demand
 * |T|/N at each joint (series friction_primary, friction_reverse: index
 * the joint, x_m, y_m its middle, mu the demand). */
static aq_status write_data(const fig *f, const char *data, aq_error *err)
{
  aq_outfile tmp;
  const aq_geom *g = f->g;
  size_t n = g->p.voussoirs;
  FILE *o = aq_plot_csv_open(data, &tmp, err);
  if (!o)
    return err->status;
  aq_plot_csv_axes(o, 2, (const char *[]){AX_X, AX_Y});
  fprintf(o, "series,index,x_m,y_m,mu\n");
  for (int d = 0; d <= layers(f); d++) {
    char pre[48] = "";
    if (f->nat && d)
      snprintf(pre, sizeof pre, "at_%.6gs_", f->at_s[d - 1]);
    else if (d)
      snprintf(pre, sizeof pre, "deformed_");
    for (size_t k = 0; k < n; k++) {
      aq_vec2 p[4] = {g->je[k], g->je[k + 1], g->ji[k + 1], g->ji[k]};
      for (int i = 0; i < 4; i++) {
        aq_vec2 q = moved(f, d, k, p[i]);
        fprintf(o, "%scorner,%zu,%s,%s,nan\n", pre, k, AQ_TEXT_NUM(q.x), AQ_TEXT_NUM(q.y));
      }
    }
    for (size_t k = 0; k < n; k++)
      for (size_t i = g->outline_start[k]; i < g->outline_start[k + 1]; i++) {
        aq_vec2 q = moved(f, d, k, g->outline[i]);
        fprintf(o, "%soutline,%zu,%s,%s,nan\n", pre, k, AQ_TEXT_NUM(q.x), AQ_TEXT_NUM(q.y));
      }
    for (size_t k = 0; k < n; k++)
      for (size_t i = g->fill_start[k]; i < g->fill_start[k + 1]; i++) {
        aq_vec2 q = moved(f, d, k, g->fill[i]);
        fprintf(o, "%sfill,%zu,%s,%s,nan\n", pre, k, AQ_TEXT_NUM(q.x), AQ_TEXT_NUM(q.y));
      }
    for (size_t i = 0; i < g->p.nmass; i++) {
      aq_vec2 q = moved(f, d, g->mass[i].voussoir, g->mass[i].p);
      fprintf(o, "%smass,%zu,%s,%s,nan\n", pre, g->mass[i].voussoir, AQ_TEXT_NUM(q.x),
              AQ_TEXT_NUM(q.y));
    }
  }
  for (int s = 0; s < 2; s++) {
    const aq_mech *m = aq_workpath_mech(aq_arch_workpath(f->arch, s));
    for (int k = 0; k < 4; k++) {
      fprintf(o, "%s_hinge_%c,%zu,%s,%s,nan\n", s ? "reverse" : "primary", m->hs.face[k],
              m->hs.joint[k], AQ_TEXT_NUM(m->h[k].x), AQ_TEXT_NUM(m->h[k].y));
      if (s == f->set) {
        aq_vec2 h = hinge(f, s, k);
        fprintf(o, "deformed_hinge_%c,%zu,%s,%s,nan\n", m->hs.face[k], m->hs.joint[k], AQ_TEXT_NUM(h.x),
                AQ_TEXT_NUM(h.y));
      }
    }
  }
  for (size_t i = 0; i < f->nthrust; i++)
    fprintf(o, "thrust,%zu,%s,%s,nan\n", i, AQ_TEXT_NUM(f->thrust[i].x), AQ_TEXT_NUM(f->thrust[i].y));
  for (int s = 0; s < 2; s++)
    for (size_t j = 0; f->ratio[s] && j <= n; j++) {
      aq_vec2 mid = {0.5 * (g->ji[j].x + g->je[j].x), 0.5 * (g->ji[j].y + g->je[j].y)};
      fprintf(o, "friction_%s,%zu,%s,%s,%s\n", s ? "reverse" : "primary", j, AQ_TEXT_NUM(mid.x),
              AQ_TEXT_NUM(mid.y), AQ_TEXT_NUM(f->ratio[s][j]));
    }
  return aq_plot_csv_close(&tmp, err);
}

/* Draw f (its state set), write its data when asked, free its line of
 * thrust and its friction demands. */
aq_status aq_plot_arch_render(fig *f, const char *target, const char *data, double *draw_s,
                              aq_error *err)
{
  const aq_geom *g = f->g;
  f->nlegend = 4 + (f->nthrust > 1) + (g->fill_kg > 0) + (g->p.nmass > 0) + (layers(f) > 0) +
               f->nat;
  f->height = PLOT_H + LEGEND_ROW * (int)f->nlegend + 40 + (f->ratio_max > 0 ? PANEL_H : 0);
  aq_status rc = aq_plot_render(target, FIG_W, f->height, draw, f, draw_s, err);
  if (rc == AQ_OK && data)
    rc = write_data(f, data, err);
  free(f->thrust);
  f->thrust = NULL;
  for (int s = 0; s < 2; s++) {
    free(f->ratio[s]);
    f->ratio[s] = NULL;
  }
  return rc;
}

aq_status aq_plot_arch(const aq_arch *arch, double rotation_rad, const char *target,
                       const char *data, double *draw_s, aq_error *err)
{
  fig f;
  memset(&f, 0, sizeof f);
  f.arch = arch;
  f.g = aq_arch_geom(arch);
  f.set = -1;
  f.thrust_set = -1;
  aq_mech_state st0;
  const aq_mech *m0 = aq_workpath_mech(aq_arch_workpath(arch, 0));
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
    if (thrust_line(&f, f.set, &f.st, err) != 0)
      return err->status;
  } else if (aq_arch_path(arch, 0)->admissible && aq_mech_eval(m0, 0.0, &st0) == 0 &&
             thrust_line(&f, 0, &st0, err) != 0) {
    return err->status;
  }
  const aq_geom *g = f.g;
  size_t n = g->p.voussoirs;
  for (int s = 0; s < 2; s++) { /* the friction each joint needs at lambda0 */
    if (!aq_arch_path(arch, s)->admissible || !(f.ratio[s] = malloc((n + 1) * sizeof(double))))
      continue;
    aq_arch_joint_friction(arch, s, f.ratio[s], NULL);
    for (size_t j = 0; j <= n; j++)
      f.ratio_max = fmax(f.ratio_max, fmin(f.ratio[s][j], RATIO_CAP));
  }
  if (aq_arch_friction(arch) > 0 && f.ratio_max > 0)
    f.ratio_max = fmax(f.ratio_max, fmin(aq_arch_friction(arch), RATIO_CAP));
  f.ratio_max *= 1.1;
  return aq_plot_arch_render(&f, target, data, draw_s, err);
}
