/* plplot_lazy.c: PLplot opened when a figure is drawn, not when archquake
 * starts (src/util/lazylib.h): linked directly, PLplot and the libraries
 * it needs (freetype, shapelib, csiro, qsastime, ltdl) were mapped and
 * relocated by every command, `--version` included.
 *
 * The PLplot functions the figures call are defined here, each as a
 * trampoline through a pointer that aq_plot_load sets from the library;
 * their prototypes come from plplot.h, so a definition that does not match
 * the library's declaration does not compile.  A PLplot function not
 * listed below fails to link ("undefined reference to c_plxxx"): add it to
 * AQ_PLPLOT_FUNCS with plplot.h's parameter list.  Every figure is drawn
 * through aq_plot_device, which calls aq_plot_load first. */
#include <plplot.h>
#include <stdlib.h>

#include "../util/lazylib.h"
#include "lazylib_sonames.h" /* build/: AQ_PLPLOT_SONAME, from the build's libplplot.so */
#include "plot.h"

/* V(name, parameters, arguments): a function returning void;
 * R(type, name, parameters, arguments): one returning type. */
#define AQ_PLPLOT_FUNCS(V, R) \
  V(c_pladv, (PLINT page), (page))                                                       \
  V(c_plbox, (PLCHAR_VECTOR xopt, PLFLT xtick, PLINT nxsub, PLCHAR_VECTOR yopt, PLFLT    \
    ytick, PLINT nysub), (xopt, xtick, nxsub, yopt, ytick, nysub))                       \
  V(c_plcol0, (PLINT icol0), (icol0))                                                    \
  V(c_plcol1, (PLFLT col1), (col1))                                                      \
  V(c_plcolorbar, (PLFLT_NC_SCALAR p_colorbar_width, PLFLT_NC_SCALAR                     \
    p_colorbar_height, PLINT opt, PLINT position, PLFLT x, PLFLT y, PLFLT x_length,      \
    PLFLT y_length, PLINT bg_color, PLINT bb_color, PLINT bb_style, PLFLT                \
    low_cap_color, PLFLT high_cap_color, PLINT cont_color, PLFLT cont_width, PLINT       \
    n_labels, PLINT_VECTOR label_opts, PLCHAR_MATRIX labels, PLINT n_axes,               \
    PLCHAR_MATRIX axis_opts, PLFLT_VECTOR ticks, PLINT_VECTOR sub_ticks,                 \
    PLINT_VECTOR n_values, PLFLT_MATRIX values), (p_colorbar_width,                      \
    p_colorbar_height, opt, position, x, y, x_length, y_length, bg_color, bb_color,      \
    bb_style, low_cap_color, high_cap_color, cont_color, cont_width, n_labels,           \
    label_opts, labels, n_axes, axis_opts, ticks, sub_ticks, n_values, values))          \
  V(c_plend, (void), ())                                                                 \
  V(c_plend1, (void), ())                                                                \
  V(c_plfill, (PLINT n, PLFLT_VECTOR x, PLFLT_VECTOR y), (n, x, y))                      \
  V(c_plfontld, (PLINT fnt), (fnt))                                                      \
  V(c_plgchr, (PLFLT_NC_SCALAR p_def, PLFLT_NC_SCALAR p_ht), (p_def, p_ht))              \
  V(c_plgvpd, (PLFLT_NC_SCALAR p_xmin, PLFLT_NC_SCALAR p_xmax, PLFLT_NC_SCALAR p_ymin,   \
    PLFLT_NC_SCALAR p_ymax), (p_xmin, p_xmax, p_ymin, p_ymax))                           \
  V(c_plgvpw, (PLFLT_NC_SCALAR p_xmin, PLFLT_NC_SCALAR p_xmax, PLFLT_NC_SCALAR p_ymin,   \
    PLFLT_NC_SCALAR p_ymax), (p_xmin, p_xmax, p_ymin, p_ymax))                           \
  V(c_plinit, (void), ())                                                                \
  V(c_pllab, (PLCHAR_VECTOR xlabel, PLCHAR_VECTOR ylabel, PLCHAR_VECTOR tlabel),         \
    (xlabel, ylabel, tlabel))                                                            \
  V(c_pllegend, (PLFLT_NC_SCALAR p_legend_width, PLFLT_NC_SCALAR p_legend_height,        \
    PLINT opt, PLINT position, PLFLT x, PLFLT y, PLFLT plot_width, PLINT bg_color,       \
    PLINT bb_color, PLINT bb_style, PLINT nrow, PLINT ncolumn, PLINT nlegend,            \
    PLINT_VECTOR opt_array, PLFLT text_offset, PLFLT text_scale, PLFLT text_spacing,     \
    PLFLT text_justification, PLINT_VECTOR text_colors, PLCHAR_MATRIX text,              \
    PLINT_VECTOR box_colors, PLINT_VECTOR box_patterns, PLFLT_VECTOR box_scales,         \
    PLFLT_VECTOR box_line_widths, PLINT_VECTOR line_colors, PLINT_VECTOR                 \
    line_styles, PLFLT_VECTOR line_widths, PLINT_VECTOR symbol_colors, PLFLT_VECTOR      \
    symbol_scales, PLINT_VECTOR symbol_numbers, PLCHAR_MATRIX symbols),                  \
    (p_legend_width, p_legend_height, opt, position, x, y, plot_width, bg_color,         \
    bb_color, bb_style, nrow, ncolumn, nlegend, opt_array, text_offset, text_scale,      \
    text_spacing, text_justification, text_colors, text, box_colors, box_patterns,       \
    box_scales, box_line_widths, line_colors, line_styles, line_widths,                  \
    symbol_colors, symbol_scales, symbol_numbers, symbols))                              \
  V(c_plline, (PLINT n, PLFLT_VECTOR x, PLFLT_VECTOR y), (n, x, y))                      \
  V(c_pllsty, (PLINT lin), (lin))                                                        \
  V(c_plmtex, (PLCHAR_VECTOR side, PLFLT disp, PLFLT pos, PLFLT just, PLCHAR_VECTOR      \
    text), (side, disp, pos, just, text))                                                \
  V(c_plpsty, (PLINT patt), (patt))                                                      \
  V(c_plptex, (PLFLT x, PLFLT y, PLFLT dx, PLFLT dy, PLFLT just, PLCHAR_VECTOR text),    \
    (x, y, dx, dy, just, text))                                                          \
  V(plsabort, (void ( *handler )( PLCHAR_VECTOR )), (handler))                           \
  V(c_plschr, (PLFLT def, PLFLT scale), (def, scale))                                    \
  V(c_plscmap0n, (PLINT ncol0), (ncol0))                                                 \
  V(c_plscmap1l, (PLBOOL itype, PLINT npts, PLFLT_VECTOR intensity, PLFLT_VECTOR         \
    coord1, PLFLT_VECTOR coord2, PLFLT_VECTOR coord3, PLBOOL_VECTOR alt_hue_path),       \
    (itype, npts, intensity, coord1, coord2, coord3, alt_hue_path))                      \
  V(c_plscol0, (PLINT icol0, PLINT r, PLINT g, PLINT b), (icol0, r, g, b))               \
  V(c_plsdev, (PLCHAR_VECTOR devname), (devname))                                        \
  V(c_plsdidev, (PLFLT mar, PLFLT aspect, PLFLT jx, PLFLT jy), (mar, aspect, jx, jy))    \
  R(PLINT, c_plsetopt, (PLCHAR_VECTOR opt, PLCHAR_VECTOR optarg), (opt, optarg))         \
  V(plsexit, (int ( *handler )( PLCHAR_VECTOR )), (handler))                             \
  V(c_plsfnam, (PLCHAR_VECTOR fnam), (fnam))                                             \
  V(c_plsmaj, (PLFLT def, PLFLT scale), (def, scale))                                    \
  V(c_plsmin, (PLFLT def, PLFLT scale), (def, scale))                                    \
  V(c_plssym, (PLFLT def, PLFLT scale), (def, scale))                                    \
  V(c_plstring, (PLINT n, PLFLT_VECTOR x, PLFLT_VECTOR y, PLCHAR_VECTOR string), (n,     \
    x, y, string))                                                                       \
  V(c_plsyax, (PLINT digmax, PLINT digits), (digmax, digits))                            \
  V(c_plvpas, (PLFLT xmin, PLFLT xmax, PLFLT ymin, PLFLT ymax, PLFLT aspect), (xmin,     \
    xmax, ymin, ymax, aspect))                                                           \
  V(c_plvpor, (PLFLT xmin, PLFLT xmax, PLFLT ymin, PLFLT ymax), (xmin, xmax, ymin,       \
    ymax))                                                                               \
  V(c_plwidth, (PLFLT width), (width))                                                   \
  V(c_plwind, (PLFLT xmin, PLFLT xmax, PLFLT ymin, PLFLT ymax), (xmin, xmax, ymin,       \
    ymax))                                                                               \
  V(plgDevs, (PLCHAR_VECTOR **p_menustr, PLCHAR_VECTOR **p_devname, int *p_ndev),        \
    (p_menustr, p_devname, p_ndev))                                                      \
  V(plgFileDevs, (PLCHAR_VECTOR **p_menustr, PLCHAR_VECTOR **p_devname, int *p_ndev),    \
    (p_menustr, p_devname, p_ndev))                                                      \
  V(plsError, (PLINT_NC_SCALAR errcode, PLCHAR_NC_VECTOR errmsg), (errcode, errmsg))     \
/* end of AQ_PLPLOT_FUNCS */

AQ_PLPLOT_FUNCS(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)
static const aq_lazylib_sym plplot_syms[] = {
    AQ_PLPLOT_FUNCS(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R)};

static aq_lazylib plplot = {AQ_PLPLOT_SONAME, "PLplot", plplot_syms,
                            sizeof plplot_syms / sizeof plplot_syms[0], 0, ""};

aq_status aq_plot_load(aq_error *err)
{
  return aq_lazylib_load(&plplot, err);
}

/* A PLplot call before aq_plot_load: load now; a failure here is a
 * figure drawn without aq_plot_device, a bug, so it stops the program. */
static void need(int resolved)
{
  if (!resolved && aq_lazylib_load(&plplot, NULL) != AQ_OK)
    abort();
}

AQ_PLPLOT_FUNCS(AQ_LAZYLIB_TRAMPOLINE_V, AQ_LAZYLIB_TRAMPOLINE_R)
