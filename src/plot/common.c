/* common.c: rendering a figure with PLplot without letting it exit, and the
 * CSV of the plotted data; both written to a temporary beside the target
 * and renamed onto it only when complete (util/outfile.h, see plot.h). */
#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "labels.h"
#include "plot.h"

/* SVG by PLplot's own svg driver, which writes text as <text> elements
 * (selectable and searchable); svgcairo would write glyph outlines. */
static const struct {
  const char *ext, *device;
} formats[] = {{".png", "pngcairo"}, {".svg", "svg"}, {".pdf", "pdfcairo"}};

/* The PDF page (--paper), points at 72/in, and the printing margin. */
static aq_plot_paper paper = AQ_PAPER_A4;
static const double PAPER_PT[2][2] = {{595.276, 841.89}, {612, 792}}; /* A4, Letter */
static const double PAPER_MARGIN_PT = 28.35;                           /* 10 mm */
static double figure_w_mm, figure_h_mm; /* the figure being drawn, on the page, mm */
static double page_k = 1;               /* the figure's scale onto the page (PDF) */

/* PLplot calls these instead of printing and exiting (plexit) or printing
 * (plabort); only one figure is drawn at a time (plot.h). */
static jmp_buf pl_jump;
static char pl_message[256];
static int pl_failed;
static char pl_errmsg[256]; /* plsError: PLplot's abort messages land here, unprinted */
static PLINT pl_errcode;

static int on_exit_(const char *msg)
{
  snprintf(pl_message, sizeof pl_message, "%s", msg ? msg : "");
  pl_failed = 1;
  longjmp(pl_jump, 1);
  return 1; /* not reached */
}

static void on_abort(const char *msg)
{
  if (!pl_failed)
    snprintf(pl_message, sizeof pl_message, "%s", msg ? msg : "");
  pl_failed = 1;
}

static int device_exists(const char *device)
{
  enum { MAX_DEV = 128 };
  const char *menu[MAX_DEV], *name[MAX_DEV];
  const char **pm = menu, **pn = name;
  int n = MAX_DEV;
  plgDevs(&pm, &pn, &n); /* every device: PLplot files its svg driver as interactive */
  for (int i = 0; i < n; i++)
    if (name[i] && strcmp(name[i], device) == 0)
      return 1;
  return 0;
}

aq_status aq_plot_device(const char *target, const char **device, aq_error *err)
{
  aq_status loaded = aq_plot_load(err); /* PLplot is opened on first use */
  if (loaded != AQ_OK)
    return loaded;
  const char *dot = strrchr(target, '.'), *slash = strrchr(target, '/');
  if (dot && (!slash || dot > slash))
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
      if (strcasecmp(dot, formats[i].ext) == 0) {
        if (device)
          *device = formats[i].device;
        pl_failed = 0;
        plsError(&pl_errcode, pl_errmsg); /* a missing drivers directory, unprinted */
        plsabort(on_abort);
        int ok = device_exists(formats[i].device);
        plsabort(NULL);
        if (!ok)
          return aq_error_set(err, AQ_EUNSUPPORTED, target, -1, -1, "driver",
                              "PLplot has no \"%s\" device (install "
                              "plplot-driver-cairo)", formats[i].device);
        return AQ_OK;
      }
  return aq_error_set(err, AQ_EOPTION, target, -1, -1, "extension",
                      "expected .png, .svg or .pdf, got \"%s\"",
                      dot && (!slash || dot > slash) ? dot : "");
}

void aq_plot_set_paper(aq_plot_paper p)
{
  paper = p == AQ_PAPER_LETTER ? AQ_PAPER_LETTER : AQ_PAPER_A4;
}

aq_plot_paper aq_plot_paper_of_size(double width_mm, double height_mm)
{
  /* Letter is 215.9 x 279.4 mm; A4 210 x 297 mm */
  return fabs(width_mm - 215.9) < 3 && fabs(height_mm - 279.4) < 3 ? AQ_PAPER_LETTER
                                                                    : AQ_PAPER_A4;
}

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Colour map 0: white background, black text, then the lines' colours. */
static void palette(void)
{
  static const int rgb[][3] = {
      {255, 255, 255}, {0, 0, 0},     {31, 91, 180},  {200, 30, 30},  {30, 140, 60},
      {230, 120, 0},   {120, 120, 120}, {255, 205, 205}, {130, 50, 160}, {225, 225, 225},
      {0, 150, 150},   {140, 80, 30},  {215, 70, 160},  {120, 120, 0},  {20, 30, 110}};
  int n = (int)(sizeof rgb / sizeof rgb[0]);
  plscmap0n(16);
  for (int i = 0; i < n; i++)
    plscol0(i, rgb[i][0], rgb[i][1], rgb[i][2]);
}

/* The page of a figure drawn width x height (points at 72/in, as for a
 * PNG's pixels): the same for PNG and SVG; for PDF the paper, turned to
 * the figure's orientation, with the figure scaled by k to fit within the
 * margins, centred. */
typedef struct {
  int page_w, page_h; /* points */
  double k;           /* figure to page */
  double margin;      /* fraction of the page's width (and height) */
} page_layout;

static page_layout layout(const char *device, int width, int height)
{
  page_layout pl = {width, height, 1, 0};
  if (strcmp(device, "pdfcairo") != 0)
    return pl;
  double pw = PAPER_PT[paper][0], ph = PAPER_PT[paper][1];
  pl.margin = PAPER_MARGIN_PT / pw;
  double fw = (1 - 2 * pl.margin) * pw, fh = (1 - 2 * pl.margin) * ph;
  if (fmin(fh / width, fw / height) > fmin(fw / width, fh / height)) { /* landscape */
    double t = pw;
    pw = ph;
    ph = t;
  }
  pl.k = fmin((1 - 2 * pl.margin) * pw / width, (1 - 2 * pl.margin) * ph / height);
  pl.page_w = (int)lround(pw);
  pl.page_h = (int)lround(ph);
  return pl;
}

/* After plinit: the figure in its window of the page, and PLplot's default
 * sizes (characters, symbols, ticks: proportional to the page, 4 mm times
 * the mean of its sides over 400 mm) those of the figure's own page times
 * k, so that a PDF is the PNG made smaller. */
static void scale_text(const page_layout *pl, int width, int height)
{
  if (pl->k == 1)
    return;
  const double mm_per_pt = 25.4 / 72;
  double s = 0.5 * (width + height) * mm_per_pt / 200 * pl->k;
  plschr(4.0 * s, 1.0);
  plssym(1.5 * s, 1.0);
  plsmaj(3.0 * s, 1.0);
  plsmin(1.5 * s, 1.0);
}

/* UTF-8 of code point u into out (at most 4 bytes); its length. */
static size_t utf8_put(unsigned long u, char *out)
{
  if (u < 0x80) {
    out[0] = (char)u;
    return 1;
  }
  if (u < 0x800) {
    out[0] = (char)(0xc0 | u >> 6);
    out[1] = (char)(0x80 | (u & 0x3f));
    return 2;
  }
  if (u < 0x10000) {
    out[0] = (char)(0xe0 | u >> 12);
    out[1] = (char)(0x80 | (u >> 6 & 0x3f));
    out[2] = (char)(0x80 | (u & 0x3f));
    return 3;
  }
  out[0] = (char)(0xf0 | u >> 18);
  out[1] = (char)(0x80 | (u >> 12 & 0x3f));
  out[2] = (char)(0x80 | (u >> 6 & 0x3f));
  out[3] = (char)(0x80 | (u & 0x3f));
  return 4;
}

/* The svg driver writes every character of a text as a numeric reference
 * (&#x41;) and indents each element: its file rewritten with the
 * characters as UTF-8 (those that XML needs escaped stay references) and
 * without the indentation, so that the text can be searched in the file
 * too and the file is about a third smaller.  0, or -1 on a read or write
 * error. */
static int svg_tidy(const char *path)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return -1;
  size_t cap = 1 << 16, n = 0;
  char *in = malloc(cap);
  for (size_t got; in && (got = fread(in + n, 1, cap - n, f)) > 0;) {
    n += got;
    if (n == cap) {
      char *m = realloc(in, cap *= 2);
      if (!m) {
        free(in);
        in = NULL;
      } else
        in = m;
    }
  }
  int bad = ferror(f);
  fclose(f);
  char *out = in ? malloc(n + 1) : NULL;
  if (!in || !out || bad) {
    free(in);
    free(out);
    return -1;
  }
  size_t m = 0;
  int line_start = 1;
  for (size_t i = 0; i < n;) {
    if (line_start && (in[i] == ' ' || in[i] == '\t')) {
      i++;
      continue;
    }
    line_start = in[i] == '\n';
    char *end;
    if (in[i] == '&' && i + 3 < n && in[i + 1] == '#' && in[i + 2] == 'x') {
      unsigned long u = strtoul(in + i + 3, &end, 16);
      if (end > in + i + 3 && end < in + n && *end == ';' && u >= 0x20 && u <= 0x10ffff &&
          u != '<' && u != '>' && u != '&' && u != '"' && u != '\'' &&
          !(u >= 0xd800 && u <= 0xdfff)) {
        m += utf8_put(u, out + m); /* never longer than the reference */
        i = (size_t)(end + 1 - in);
        continue;
      }
    }
    out[m++] = in[i++];
  }
  free(in);
  f = fopen(path, "wb");
  bad = !f;
  if (f) {
    bad |= fwrite(out, 1, m, f) != m;
    bad |= fclose(f) != 0;
  }
  free(out);
  return bad ? -1 : 0;
}

/* A figure rendered while held (aq_plot_hold) waits here, complete, for
 * the rest of the command's outputs. */
static int hold_figure;
static aq_outfile held;

void aq_plot_hold(int on)
{
  hold_figure = on;
}

aq_status aq_plot_held_finish(int ok, aq_error *err)
{
  hold_figure = 0;
  if (!held.target)
    return AQ_OK;
  if (!ok) {
    aq_outfile_abort(&held);
    return AQ_OK;
  }
  return aq_outfile_commit(&held, err);
}

aq_status aq_plot_render(const char *target, int width, int height,
                         aq_plot_draw_fn draw, void *ctx, double *draw_s,
                         aq_error *err)
{
  const char *device;
  aq_status rc = aq_plot_device(target, &device, err);
  if (rc != AQ_OK)
    return rc;
  aq_outfile out; /* the target's directory must be writable */
  if ((rc = aq_outfile_open(&out, target, err)) != AQ_OK)
    return rc;
  fclose(out.f); /* PLplot writes it */
  out.f = NULL;

  volatile int started = 0;
  volatile double t0 = now_s();
  pl_failed = 0;
  pl_message[0] = '\0';
  plsexit(on_exit_);
  plsabort(on_abort);
  plsError(&pl_errcode, pl_errmsg);
  if (setjmp(pl_jump) == 0) {
    plsdev(device);
    plsfnam(out.tmp);
    page_layout pl = layout(device, width, height);
    page_k = pl.k;
    figure_w_mm = width * pl.k * 25.4 / 72;
    figure_h_mm = height * pl.k * 25.4 / 72;
    char geom[64];
    snprintf(geom, sizeof geom, "%dx%d", pl.page_w, pl.page_h);
    plsetopt("geometry", geom);
    palette();
    if (pl.k != 1) /* the figure's proportions, centred within the margins */
      plsdidev(pl.margin, (double)width / height, 0, 0);
    started = 1;
    plinit();
    plfontld(1);
    scale_text(&pl, width, height);
    if (!pl_failed && draw(ctx, err) != 0 && !pl_failed) {
      pl_failed = 2; /* the figure's own error, already in err */
    }
    plend();
    started = 0;
  }
  if (started) { /* PLplot's exit path: close the stream (once) */
    started = 0;
    if (setjmp(pl_jump) == 0)
      plend1();
  }
  plsexit(NULL);
  plsabort(NULL);
  if (draw_s)
    *draw_s = now_s() - t0;
  if (pl_failed) {
    aq_outfile_abort(&out);
    if (pl_failed == 2)
      return err ? err->status : AQ_EIO;
    return aq_error_set(err, AQ_EIO, target, -1, -1, "PLplot", "%s",
                        pl_message[0] ? pl_message : "drawing failed");
  }
  FILE *f = fopen(out.tmp, "rb");
  long size = -1;
  if (f) {
    if (fseek(f, 0, SEEK_END) == 0)
      size = ftell(f);
    fclose(f);
  }
  if (size <= 0) {
    aq_outfile_abort(&out);
    return aq_error_set(err, AQ_EIO, target, -1, -1, "PLplot",
                        "the %s device wrote nothing", device);
  }
  if (strcmp(device, "svg") == 0 && svg_tidy(out.tmp) != 0) {
    int e = errno;
    aq_outfile_abort(&out);
    return aq_error_set(err, AQ_EIO, target, -1, -1, NULL, "cannot write: %s", strerror(e));
  }
  if (hold_figure && !held.target) {
    held = out; /* renamed by aq_plot_held_finish */
    return AQ_OK;
  }
  return aq_outfile_commit(&out, err);
}

FILE *aq_plot_csv_open(const char *target, aq_outfile *o, aq_error *err)
{
  return aq_outfile_open(o, target, err) == AQ_OK ? o->f : NULL;
}

aq_status aq_plot_csv_close(aq_outfile *o, aq_error *err)
{
  return aq_outfile_commit(o, err);
}

void aq_plot_csv_text(FILE *f, const char *s)
{
  if (!strpbrk(s, ",\"\n\r")) {
    fprintf(f, "%s,", s);
    return;
  }
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"')
      fputc('"', f);
    fputc(*s, f);
  }
  fputs("\",", f);
}

void aq_plot_csv_axes(FILE *f, size_t n, const char *const *titles)
{
  for (size_t i = 0; i < n; i++) {
    char t[512];
    aq_plot_plain(titles[i], t, sizeof t);
    fprintf(f, "# axis: %s\n", t);
  }
}

void aq_plot_text_height(double mm)
{
  plschr(mm * page_k, 1.0);
}

double aq_plot_text_mm(const char *s)
{
  PLFLT def, ht;
  plgchr(&def, &ht);
  return aq_plot_text_em(s) * FONT_PER_HEIGHT * ht / page_k;
}

double aq_plot_line_mm(void)
{
  PLFLT def, ht;
  plgchr(&def, &ht);
  return LINE_EM * FONT_PER_HEIGHT * ht / page_k;
}

double aq_plot_page_w_mm(void)
{
  return figure_w_mm / page_k;
}

size_t aq_plot_chars_fit(double width_frac)
{
  PLFLT def, ht;
  plgchr(&def, &ht);
  /* DejaVu Sans, the cairo drivers' sans: about 0.85 of the character
   * height per character of a file name, measured on the figures */
  double w = width_frac * figure_w_mm, per = 0.85 * ht;
  return per > 0 && w > per ? (size_t)(w / per) : 1;
}

void aq_plot_line(size_t n, const double *x, const double *y, size_t buckets)
{
  if (n <= 4 * buckets || buckets == 0) {
    plline((PLINT)n, x, y);
    return;
  }
  PLFLT *bx = malloc(4 * buckets * sizeof *bx), *by = malloc(4 * buckets * sizeof *by);
  if (!bx || !by) { /* drawn whole */
    free(bx);
    free(by);
    plline((PLINT)n, x, y);
    return;
  }
  double x0 = x[0], w = (x[n - 1] - x[0]) / (double)buckets;
  size_t m = 0;
  for (size_t i = 0; i < n;) {
    /* the samples of one bucket: the first, the lowest, the highest and
       the last, in their order */
    double edge = x0 + w * floor((x[i] - x0) / w + 1);
    size_t j = i, lo = i, hi = i;
    while (j < n && (x[j] < edge || j == i)) {
      if (y[j] < y[lo])
        lo = j;
      if (y[j] > y[hi])
        hi = j;
      j++;
    }
    size_t k[4] = {i, lo < hi ? lo : hi, lo < hi ? hi : lo, j - 1};
    for (int q = 0; q < 4; q++)
      if (q == 0 || k[q] != k[q - 1]) {
        bx[m] = x[k[q]];
        by[m++] = y[k[q]];
      }
    i = j;
    if (m + 4 > 4 * buckets) { /* uneven spacing: flush */
      plline((PLINT)m, bx, by);
      bx[0] = bx[m - 1];
      by[0] = by[m - 1];
      m = 1;
    }
  }
  plline((PLINT)m, bx, by);
  free(bx);
  free(by);
}

void aq_plot_note(double x, double y, const char *text)
{
  PLFLT def, ht, vx0, vx1, vy0, vy1, wx0, wx1, wy0, wy1;
  plgchr(&def, &ht);
  plgvpd(&vx0, &vx1, &vy0, &vy1);
  plgvpw(&wx0, &wx1, &wy0, &wy1);
  /* half the text's width and a line's height, in world units */
  double hw = 0.5 * (0.62 * ht * (double)aq_plot_utf8_chars(text) + ht) / ((vx1 - vx0) * figure_w_mm) *
              (wx1 - wx0);
  double hh = 0.9 * ht / ((vy1 - vy0) * figure_h_mm) * (wy1 - wy0);
  PLFLT bx[4] = {x - hw, x + hw, x + hw, x - hw}, by[4] = {y - hh, y - hh, y + hh, y + hh};
  plcol0(AQ_PC_BG);
  plfill(4, bx, by);
  plcol0(AQ_PC_FG);
  plptex(x, y - 0.35 * hh, 1, 0, 0.5, text);
}

void aq_plot_range(const double *x, size_t n, double *lo, double *hi)
{
  double a = INFINITY, b = -INFINITY;
  for (size_t i = 0; i < n; i++)
    if (isfinite(x[i])) {
      a = fmin(a, x[i]);
      b = fmax(b, x[i]);
    }
  if (!(a <= b))
    a = b = 0;
  if (b - a <= 1e-300 * (fabs(a) + fabs(b)) || a == b) {
    double d = a == 0 ? 1 : 0.1 * fabs(a);
    a -= d;
    b += d;
  }
  *lo = a;
  *hi = b;
}

#if defined(__SANITIZE_ADDRESS__)
/* The cairo driver's font machinery (fontconfig, pango, glib) and PLplot's
 * driver loader (libltdl) keep caches for the life of the process; under
 * `make check` LeakSanitizer is told that these are not archquake's. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
  return "leak:libfontconfig.so\nleak:libpango\nleak:libpangoft2\nleak:libpangocairo\n"
         "leak:libglib\nleak:libgobject\nleak:libharfbuzz\nleak:libcairo\n"
         "leak:libltdl.so\nleak:cairo.so\n";
}
const char *__lsan_default_options(void);
const char *__lsan_default_options(void) { return "print_suppressions=0"; }
#endif
