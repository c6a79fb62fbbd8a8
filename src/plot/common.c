/* common.c: rendering a figure with PLplot without letting it exit, and the
 * CSV of the plotted data; both written to a temporary beside the target
 * and renamed onto it only when complete (see plot.h). */
#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "plot.h"

static const struct {
  const char *ext, *device;
} formats[] = {{".png", "pngcairo"}, {".svg", "svgcairo"}, {".pdf", "pdfcairo"}};

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
  plgFileDevs(&pm, &pn, &n);
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

void aq_plot_temp_name(const char *target, char *tmp, size_t cap)
{
  snprintf(tmp, cap, "%s.tmp.%ld", target, (long)getpid());
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

aq_status aq_plot_render(const char *target, int width, int height,
                         aq_plot_draw_fn draw, void *ctx, double *draw_s,
                         aq_error *err)
{
  const char *device;
  aq_status rc = aq_plot_device(target, &device, err);
  if (rc != AQ_OK)
    return rc;
  char tmp[1024];
  aq_plot_temp_name(target, tmp, sizeof tmp);
  FILE *probe = fopen(tmp, "wb"); /* the target's directory must be writable */
  if (!probe)
    return aq_error_set(err, AQ_EIO, target, -1, -1, NULL,
                        "cannot write beside the target: %s", strerror(errno));
  fclose(probe);

  volatile int started = 0;
  volatile double t0 = now_s();
  pl_failed = 0;
  pl_message[0] = '\0';
  plsexit(on_exit_);
  plsabort(on_abort);
  plsError(&pl_errcode, pl_errmsg);
  if (setjmp(pl_jump) == 0) {
    plsdev(device);
    plsfnam(tmp);
    char geom[64];
    snprintf(geom, sizeof geom, "%dx%d", width, height);
    plsetopt("geometry", geom);
    palette();
    started = 1;
    plinit();
    plfontld(1);
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
    remove(tmp);
    if (pl_failed == 2)
      return err ? err->status : AQ_EIO;
    return aq_error_set(err, AQ_EIO, target, -1, -1, "PLplot", "%s",
                        pl_message[0] ? pl_message : "drawing failed");
  }
  FILE *f = fopen(tmp, "rb");
  long size = -1;
  if (f) {
    if (fseek(f, 0, SEEK_END) == 0)
      size = ftell(f);
    fclose(f);
  }
  if (size <= 0) {
    remove(tmp);
    return aq_error_set(err, AQ_EIO, target, -1, -1, "PLplot",
                        "the %s device wrote nothing", device);
  }
  if (rename(tmp, target) != 0) {
    int e = errno;
    remove(tmp);
    return aq_error_set(err, AQ_EIO, target, -1, -1, NULL, "cannot rename %s: %s",
                        tmp, strerror(e));
  }
  return AQ_OK;
}

FILE *aq_plot_csv_open(const char *target, char *tmp, size_t cap, aq_error *err)
{
  aq_plot_temp_name(target, tmp, cap);
  FILE *f = fopen(tmp, "w");
  if (!f)
    aq_error_set(err, AQ_EIO, target, -1, -1, NULL, "cannot write: %s",
                 strerror(errno));
  return f;
}

aq_status aq_plot_csv_close(FILE *f, const char *tmp, const char *target, int ok,
                            aq_error *err)
{
  int bad = ferror(f);
  bad |= fclose(f) != 0;
  if (!ok || bad || rename(tmp, target) != 0) {
    int e = errno;
    remove(tmp);
    if (!ok)
      return err ? err->status : AQ_EIO;
    return aq_error_set(err, AQ_EIO, target, -1, -1, NULL, "cannot write: %s",
                        strerror(e));
  }
  return AQ_OK;
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
  for (size_t i = 0; i < n; i++)
    fprintf(f, "# axis: %s\n", titles[i]);
}

void aq_plot_legend(int position, size_t n, const char *const *text,
                    const int *color, const int *style, const char *const *sym)
{
  aq_plot_legend_at(position, 0.01, 0.02, 1, n, text, color, style, sym);
}

void aq_plot_legend_at(int position, double x, double y, int ncolumn, size_t n,
                       const char *const *text, const int *color, const int *style,
                       const char *const *sym)
{
  enum { MAX_ENTRIES = AQ_PLOT_LEGEND_MAX };
  PLINT opt[MAX_ENTRIES], col[MAX_ENTRIES], sty[MAX_ENTRIES], box[MAX_ENTRIES] = {0};
  PLINT pat[MAX_ENTRIES] = {0}, tcol[MAX_ENTRIES], symn[MAX_ENTRIES];
  PLFLT w[MAX_ENTRIES], bs[MAX_ENTRIES] = {0}, blw[MAX_ENTRIES] = {0},
        ss[MAX_ENTRIES];
  const char *sy[MAX_ENTRIES];
  if (n > MAX_ENTRIES)
    n = MAX_ENTRIES;
  for (size_t i = 0; i < n; i++) {
    opt[i] = 0;
    if (style[i] > 0)
      opt[i] |= PL_LEGEND_LINE;
    if (sym && sym[i] && sym[i][0])
      opt[i] |= PL_LEGEND_SYMBOL;
    if (style[i] < 0)
      opt[i] = PL_LEGEND_COLOR_BOX;
    col[i] = color[i];
    tcol[i] = AQ_PC_FG;
    sty[i] = style[i] > 0 ? style[i] : 1;
    w[i] = 1.5;
    ss[i] = 1.0;
    symn[i] = 1;
    sy[i] = sym && sym[i] ? sym[i] : "";
    box[i] = color[i];
    bs[i] = 0.8;
  }
  PLFLT lw, lh;
  PLINT ncol = ncolumn > 1 ? ncolumn : 1, nrow = ((PLINT)n + ncol - 1) / ncol;
  pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX |
                         (ncol > 1 ? PL_LEGEND_ROW_MAJOR : 0),
           position, x, y, 0.06, AQ_PC_BG, AQ_PC_FG, 1, nrow, ncol, (PLINT)n, opt, 0.6, 0.7,
           1.7, 0.0, tcol, text, box, pat, bs,
           blw, col, sty, w, col, ss, symn, sy);
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
