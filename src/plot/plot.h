/* src/plot: figures (PNG, SVG, PDF) drawn with PLplot from a results file.
 *
 * plot.h: figures from archquake's results, drawn with PLplot (devices
 * pngcairo, svg (text kept as text), pdfcairo (A4 or Letter pages); the
 * format is the target's extension).  One figure per file:
 *   history.c   one run's ground acceleration, rotation and energies
 *   arch.c      the arch to scale, its hinge sets, a deformed mechanism
 *   domain.c    the half-cycle collapse domain
 *   suite.c     a record x arch map of the verdicts
 *   capacity.c  the collapse intervals and fragility of `archquake capacity`
 *   spectrum.c  the response spectra of `archquake spectrum`
 *   select.c    a suite's spectra against its target (`archquake select`)
 * common.c renders (driver check, exit/abort handlers) and writes the
 * plotted data (--data FILE.csv), each through a temporary renamed when
 * complete (util/outfile.h: removed on a signal too); labels.c measures
 * and shortens the figures' texts, keys.c lays out their keys and legends;
 * h5_read.c reads a run's histories (the verdicts come from
 * aq_h5_read_suite).
 *
 * PLplot keeps global state: call these from one thread, after the inputs
 * are read.  Nothing here prints: failures fill aq_error and return a
 * status, and leave no file under the target's name.  SI units inside;
 * g and degrees only in axis titles and CSV columns named so. */
#ifndef AQ_PLOT_PLOT_H
#define AQ_PLOT_PLOT_H

#include <stddef.h>
#include <stdio.h>

#include "../arch/arch.h"
#include "../error.h"
#include "../report/h5.h"
#include "../report/h5_capacity.h"
#include "../report/h5_select.h"
#include "../report/h5_spectrum.h"
#include "../report/text.h"
#include "../select/target.h"
#include "../util/outfile.h"

/* ---- h5_read.c: what the figures take from a results file ------------ */

/* One run with its histories (sample times in record time, s). */
typedef struct {
  char key[64];          /* run key: "00000_000_000", "r" appended when reversed */
  char record[AQ_SUMMARY_RECORD_MAX]; /* record file as given (whole) */
  char arch[128];        /* arch name */
  double scale;          /* factor applied to the processed record */
  int reversed;          /* 1: the record negated (polarity reversed) */
  int collapsed;         /* 1, 0, -1 (failed run) */
  double collapse_time_s;/* NaN if it survived */
  long impacts;          /* the run's impact count */
  double energy_in_j;    /* the run's work done by the ground, J */
  double lambda0[2];     /* primary, reverse: static collapse multipliers */
  double q_c_rad[2];     /* collapse rotations, rad */
  double mass_kg;        /* whole arch */
  double g_mps2;         /* the arch's gravity */
  size_t n;              /* history samples */
  double *t_s, *q_rad, *x_m, *ke_j, *pe_j; /* rotation (global sign), COM x, energies */
  int *set;              /* n: the hinge set moving (0 primary, 1 reverse, -1 at rest);
                            NULL when the file holds none (format 1) */
  int q_sign[2];         /* primary, reverse: the sign of q while that set moves (0:
                            unknown) */
  size_t na;             /* ground samples (processed record, scaled, signed);
                            0 when the file does not hold it (format 2
                            written without --store-records) */
  double *ag_mps2;       /* ground acceleration, m/s^2, zero-order hold */
  double ag_dt_s, ag_t0_s; /* sample interval and time of sample 0, s */
  long n_orig;           /* samples of the record without its pads (0: unknown) */
  double rec_dt_s;       /* the record's sample interval, s (0: unknown) */
  long arch_index;       /* the run's arch: /arches/NNN, /geometry/NNN */
  /* --model blocks: every voussoir's centroid (m, m) and rotation (rad) at
   * sample i, voussoir k at [i * nvous + k]; nvous 0 and NULL otherwise */
  size_t nvous;
  double *vx_m, *vy_m, *vrot_rad;
} aq_plot_run;

/* Read run `key` (NULL: the first run with histories) of results file
 * path (format 1 or 2).  Errors: no such run (the message lists the first
 * keys), a file or run without histories (written without --history).
 * Free with aq_plot_run_free. */
aq_status aq_plot_run_read(const char *path, const char *key, aq_plot_run *run,
                           aq_error *err);
void aq_plot_run_free(aq_plot_run *run);

/* ---- plplot_lazy.c ---------------------------------------------------- */

/* Open PLplot (once; archquake does not load it at start): AQ_OK, or
 * AQ_EUNSUPPORTED (err names the library and why).  aq_plot_device calls
 * it, so every figure drawn through aq_plot_render has it. */
aq_status aq_plot_load(aq_error *err);

/* ---- common.c, labels.c, keys.c ------------------------------------ */

/* Draws one figure between plinit and plend; returns 0, or non-zero after
 * filling err (the render then fails). */
typedef int (*aq_plot_draw_fn)(void *ctx, aq_error *err);

/* The cairo device for target's extension (.png .svg .pdf, any case):
 * AQ_EOPTION naming the extension if it is none of these, AQ_EUNSUPPORTED
 * if PLplot has no such device.  device may be NULL. */
aq_status aq_plot_device(const char *target, const char **device, aq_error *err);

/* Render draw(ctx) to target, width x height (pixels for PNG; points at
 * 72/in for SVG; a PDF is the paper of aq_plot_set_paper with the figure
 * scaled onto it): the device is checked
 * to exist first; the figure is written to a temporary beside the target
 * and renamed onto it when PLplot finished without error.  PLplot's exit
 * and abort handlers are replaced for the duration, so a PLplot error
 * returns AQ_EIO with its message instead of exiting.  *draw_s (if not
 * NULL): wall time of plinit to plend, s. */
aq_status aq_plot_render(const char *target, int width, int height,
                         aq_plot_draw_fn draw, void *ctx, double *draw_s,
                         aq_error *err);

/* Hold the next figure aq_plot_render makes (on = 1): complete under its
 * temporary, not renamed until aq_plot_held_finish, so that a command
 * writing a figure and its data (--data) leaves neither when the data
 * fail.  aq_plot_held_finish renames the held figure onto its target (ok =
 * 1; AQ_EIO, err, when that fails) or removes it (ok = 0), and stops
 * holding.  Returns AQ_OK when nothing is held. */
void aq_plot_hold(int on);
aq_status aq_plot_held_finish(int ok, aq_error *err);

/* The PDF page: A4 (the default) or Letter, portrait or landscape as the
 * figure is tall or wide, 10 mm margins; the figure scaled to fit, its
 * text with it.  PNG and SVG keep the figure's own size.  Applies to the
 * figures rendered after the call (PLplot's state is global anyway). */
typedef enum { AQ_PAPER_A4 = 0, AQ_PAPER_LETTER = 1 } aq_plot_paper;
void aq_plot_set_paper(aq_plot_paper p);
/* The paper of a locale's page size (LC_PAPER, mm): Letter if it is
 * 215.9 x 279.4 mm, else A4. */
aq_plot_paper aq_plot_paper_of_size(double width_mm, double height_mm);

/* CSV of the plotted data: open its temporary beside target (util/outfile.h,
 * *o; the stream returned, or NULL with err filled), then close, check and
 * rename it onto target (aq_plot_csv_close), or aq_outfile_abort(o).
 * Columns carry their units (`time_s`, `accel_g`). */
FILE *aq_plot_csv_open(const char *target, aq_outfile *o, aq_error *err);
aq_status aq_plot_csv_close(aq_outfile *o, aq_error *err);

/* A text field of a --data CSV and its comma, quoted (RFC 4180: inner
 * quotes doubled) when it holds a comma, a quote or a line break. */
void aq_plot_csv_text(FILE *f, const char *s);

/* "# axis: TITLE" for each of the figure's n axis titles, before the
 * CSV's header, in plain text (aq_plot_plain); readers skip them (pandas:
 * comment='#'). */
void aq_plot_csv_axes(FILE *f, size_t n, const char *const *titles);

/* A title as drawn (PLplot escapes: #gl for lambda, #d and #u to lower and
 * raise) in plain UTF-8 text, into out[cap]: "#gl#d0#u g" -> "λ0 g". */
void aq_plot_plain(const char *s, char *out, size_t cap);

/* A name to draw (a file name, an arch's name) with PLplot's escape
 * character '#' doubled, into out[cap]: drawn as it is ("x.csv#NS"); one
 * that does not fit ends in "…". */
void aq_plot_escape(const char *s, char *out, size_t cap);
/* s shortened to at most max_chars characters (UTF-8) by an ellipsis in
 * the middle, keeping its start and its end ("RSN6_IMP…hor1.AT2"), into
 * out[cap], escaped (aq_plot_escape); s itself if it fits. */
void aq_plot_ellipsize(const char *s, size_t max_chars, char *out, size_t cap);
/* The same for n names at once, into out (n strings of cap bytes): each
 * at most max_chars characters, and distinct where the names are: the
 * ellipsis placed alike for all where that keeps them apart (even, then
 * more of the end, then more of the start), else each showing where it
 * first differs from the others ("…LOMAP_GIL067…"). */
void aq_plot_ellipsize_set(const char *const *names, size_t n, size_t max_chars, char *out,
                           size_t cap);
/* The same measured: names[n] shortened alike (aq_plot_ellipsize_set) to
 * the most characters at which each, escaped, is at most room_mm[i] wide
 * at the current character height: every name whole when all fit. */
void aq_plot_shorten_set_to(const char *const *names, size_t n, const double *room_mm,
                            char *out, size_t cap);
/* A key below a figure's plot: entry i a line (color, style, width) and
 * the text pre + name + post (pre and post drawn as written, with PLplot's
 * escapes; name escaped, and shortened only when it must be, the names
 * kept distinct), in one or two columns filled down, then across.
 * aq_plot_key_columns (before plinit) chooses them for a figure width_px
 * wide, the key in x0 .. x1 of the width, its text text_mm high
 * (aq_plot_text_height): one column up to
 * AQ_PLOT_KEY_ONE_COLUMN entries; beyond, two when their whole texts fit
 * side by side, else one up to AQ_PLOT_KEY_ROWS_MAX entries, else two.
 * aq_plot_key_below (between plinit and plend, the character height as
 * set) draws it in the viewport x0 .. x1, y0 .. y1 (fractions of the
 * figure): the second column past the first's widest text, names whole
 * where they fit; else each column a share of the width in proportion to
 * its whole texts, their names shortened alike to fit it, measured. */
enum { AQ_PLOT_KEY_ONE_COLUMN = 8, AQ_PLOT_KEY_ROWS_MAX = 20 };
typedef struct {
  int color, style;
  double width;
  const char *pre, *name, *post;
} aq_plot_key;
size_t aq_plot_key_columns(const aq_plot_key *key, size_t n, double x0, double x1, int width_px,
                           double text_mm);
size_t aq_plot_key_rows(size_t n, size_t ncol);
void aq_plot_key_below(const aq_plot_key *key, size_t n, size_t ncol, double x0, double x1,
                       double y0, double y1);
/* Between plinit and plend: how many characters of a file name fit in
 * width_frac of the page's width at the current character height. */
size_t aq_plot_chars_fit(double width_frac);

/* Text measured as the figures draw it (DejaVu Sans, the cairo drivers'
 * and librsvg's "sans"): the width of s in em (PLplot's escapes resolved:
 * #gX a Greek letter, #u and #d a smaller sub- or superscript, ## a #).
 * Needs no PLplot. */
double aq_plot_text_em(const char *s);
/* The font size (mm) of text of PLplot character height height_mm. */
double aq_plot_font_mm(double height_mm);
/* Between plinit and plend, in mm of the figure's own size (72 points an
 * inch, whatever the page it is scaled onto): set the character height;
 * the width of s and the height of a line (the font's ascent and descent)
 * at the current height. */
void aq_plot_text_height(double mm);
double aq_plot_text_mm(const char *s);
double aq_plot_line_mm(void);
/* The figure's width, and s (a name, not escaped) shortened by an ellipsis
 * in its middle until it is at most width_mm wide at the current
 * character height, escaped, into out[cap] (s itself if it fits). */
double aq_plot_page_w_mm(void);
void aq_plot_shorten_to(const char *s, double width_mm, char *out, size_t cap);

/* Drawing helpers (between plinit and plend). */
enum { AQ_PC_BG = 0, AQ_PC_FG, AQ_PC_BLUE, AQ_PC_RED, AQ_PC_GREEN,
       AQ_PC_ORANGE, AQ_PC_GREY, AQ_PC_SHADE, AQ_PC_PURPLE, AQ_PC_LIGHT,
       AQ_PC_TEAL, AQ_PC_BROWN, AQ_PC_PINK, AQ_PC_OLIVE, AQ_PC_NAVY };
/* A legend in the viewport's corner position (PL_POSITION_*): n entries of
 * lines (style >= 1, 0: none) and/or symbols (sym NULL or "": none). */
void aq_plot_legend(int position, size_t n, const char *const *text,
                    const int *color, const int *style, const char *const *sym);
/* The same at offset (x, y) (fractions of the viewport) from position, in
 * ncolumn columns filled by rows; at most AQ_PLOT_LEGEND_MAX entries. */
enum { AQ_PLOT_LEGEND_MAX = 40 };
void aq_plot_legend_at(int position, double x, double y, int ncolumn, size_t n,
                       const char *const *text, const int *color, const int *style,
                       const char *const *sym);
/* plline of n points with x increasing, thinned where they are many more
 * than the panel has pixels: in each of `buckets` equal spans of x the
 * first, lowest, highest and last point, in order, so that the line looks
 * the same (its extremes kept) at a fraction of the size in SVG and PDF. */
void aq_plot_line(size_t n, const double *x, const double *y, size_t buckets);
/* text centred at (x, y) (world coordinates) on a box of the background
 * colour, so that lines drawn before do not strike through it. */
void aq_plot_note(double x, double y, const char *text);
/* Min and max of the finite values of x[n] into *lo, *hi (widened when equal). */
void aq_plot_range(const double *x, size_t n, double *lo, double *hi);

/* ---- the figures ------------------------------------------------------ */

/* history.c: panels sharing the time axis (ground acceleration in g with
 * +-lambda0 g of both sets; rotation with +-q_c; KE, PE and work in);
 * impacts and collapse marked.  Without the ground (run->na == 0) its
 * panel says so and the work put in is left out.  data: CSV target or NULL. */
aq_status aq_plot_history(const aq_plot_run *run, const char *target,
                          const char *data, double *draw_s, aq_error *err);

/* arch.c: the arch to scale, voussoirs and both hinge sets; with
 * rotation_rad != 0 the mechanism deformed at that rotation of body 1 about
 * H1 (> 0: primary set, < 0: reverse set, |rotation| <= the set's q_c). */
aq_status aq_plot_arch(const aq_arch *arch, double rotation_rad, const char *target,
                       const char *data, double *draw_s, aq_error *err);
/* The same for arch `name` (NULL: the first) of results file path, drawn
 * from its stored geometry (/geometry/NNN) and hinge sets (/arches/NNN)
 * without its .cfg.  Errors name the file (or --arch for an unknown name). */
aq_status aq_plot_arch_h5(const char *path, const char *name, double rotation_rad,
                          const char *target, const char *data, double *draw_s, aq_error *err);
/* The most times plot arch --run draws at once (--at). */
#define AQ_PLOT_ARCH_AT_MAX 6
/* Run `key` of results file path (NULL: the first with histories), a run
 * of the block model stored with --history: every voussoir where the
 * history has it at each of the nat times at_s (s, record time, within the
 * history; linear between samples), over the undeformed arch (its stored
 * geometry); nat 0: at the peak |rotation| of voussoir 0.  name: NULL, or
 * the run's arch's name (checked).  Errors name --run (no such run; not a
 * block model's run) or --at (outside the history, too many). */
aq_status aq_plot_arch_run(const char *path, const char *name, const char *key,
                           const double *at_s, size_t nat, const char *target,
                           const char *data, double *draw_s, aq_error *err);

/* domain.c: duration (s) against ratio for the n ratios, with the shortest
 * collapsing durations dur_s[] (INFINITY: none up to the search limit)
 * already computed (aq_domain_min_duration); lambda0 for the title. */
aq_status aq_plot_domain(const char *arch_name, double lambda0, const double *ratio,
                         const double *dur_s, size_t n, double tmax_s,
                         const char *target, const char *data, double *draw_s,
                         aq_error *err);

/* suite.c: record x arch map of the worst verdict over scales and
 * polarities (collapse, or peak rotation / q_c). */
aq_status aq_plot_suite(const aq_h5_run *runs, size_t n, const char *source,
                        const char *target, const char *data, double *draw_s,
                        aq_error *err);

/* capacity.c: for arch (NULL: the file's first), one line per (record,
 * polarity) through its scanned scales ordered by scale: scale factor (or
 * PGA, g) against the run's peak rotation (over q_c, or rad), beside a
 * strip per line with its collapse intervals shaded; below, the arch's
 * lognormal fragility in IM im (NULL: pga_g) with the band of its median's
 * interval, over the empirical fraction of first collapses (the worse
 * polarity of each record) and the censored records at their cap. */
typedef struct {
  const char *arch; /* NULL: the file's first */
  const char *im;   /* fragility IM (aq_fragility_im_names); NULL: pga_g */
  int x_rad;        /* x: 1 peak rotation (rad), 0 peak rotation / q_c */
  int y_pga;        /* y: 1 PGA (g) of the scaled record, 0 the scale factor */
} aq_plot_capacity_opts;

aq_status aq_plot_capacity(const aq_h5_capacity_table *t, const aq_plot_capacity_opts *o,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err);

/* spectrum.c: PSA (g) against period (s, log axis) of the spectra of t
 * (a file of archquake spectrum -o, source its name), one curve per
 * (record, component, damping), of the record named record (its record
 * column, or that column's file name; NULL: every record).  AQ_EVALUE
 * (field --record) when none matches or the curves are more than a legend
 * holds (AQ_PLOT_LEGEND_MAX). */
aq_status aq_plot_spectrum(const aq_h5_spectra_table *t, const char *record,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err);
/* The --data CSV of a spectra figure (plot spectrum, plot select): its
 * axes (period, PSA), the header line, then rows(f, ctx), through a
 * temporary renamed onto data at the end (aq_plot_csv_open). */
aq_status aq_plot_spectra_csv(const char *data, const char *header,
                              void (*rows)(FILE *f, const void *ctx), const void *ctx,
                              aq_error *err);

/* select.c: spectra against a target: PSA (g) against period (s, log
 * axis), the target and band x target (dashed) from a third of the range's
 * start to three times its end (within the target's periods), each
 * spectrum (thin, scaled as given), their mean (thick), the range's ends;
 * --data: the target, the mean and each curve (curve, period_s, psa_g). */
typedef struct {
  size_t n, nper;
  const double *period_s;     /* the range's periods, s, ascending */
  const double *psa_g;        /* n x nper, as drawn (scaled), g */
  const char *const *label;   /* n */
  const aq_target *target;
  const char *target_name;    /* in the legend */
  double band;                /* 0.9 */
  const char *title_pre, *title_name, *title_post; /* the title: title_name (a file's name,
                                                      not escaped) shortened only to fit */
} aq_plot_target_set;

aq_status aq_plot_target(const aq_plot_target_set *s, const char *target, const char *data,
                         double *draw_s, aq_error *err);

/* The suite of a file of `archquake select -o` (each record at its scale)
 * against its target, or override (NULL: the file's). */
aq_status aq_plot_select(const aq_h5_select_file *f, const aq_target *override,
                         const char *source, const char *target, const char *data,
                         double *draw_s, aq_error *err);

/* The spectra of t (a file of `archquake spectrum -o`; record NULL: all)
 * against target tg: every one at the same periods and tg's damping. */
aq_status aq_plot_spectra_target(const aq_h5_spectra_table *t, const char *record,
                                 const aq_target *tg, const char *source, const char *target,
                                 const char *data, double *draw_s, aq_error *err);

#endif
