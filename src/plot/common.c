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

/* PLplot's Greek escapes (#g + the Latin key) as the Unicode letters. */
static const char GREEK_KEY[] = "ABGDEZYHIKLMNCOPRSTUFXQWabgdezyhiklmncoprstufxqw";
static const char *const GREEK[] = {
    "Α", "Β", "Γ", "Δ", "Ε", "Ζ", "Η", "Θ", "Ι", "Κ", "Λ", "Μ", "Ν", "Ξ", "Ο", "Π",
    "Ρ", "Σ", "Τ", "Υ", "Φ", "Χ", "Ψ", "Ω", "α", "β", "γ", "δ", "ε", "ζ", "η", "θ",
    "ι", "κ", "λ", "μ", "ν", "ξ", "ο", "π", "ρ", "σ", "τ", "υ", "φ", "χ", "ψ", "ω"};

void aq_plot_plain(const char *s, char *out, size_t cap)
{
  size_t n = 0;
  if (cap == 0)
    return;
  for (; *s && n + 1 < cap; s++) {
    const char *put = NULL;
    char one[2] = {*s, 0};
    if (s[0] == '#' && s[1] == 'g' && s[2] && strchr(GREEK_KEY, s[2])) {
      put = GREEK[strchr(GREEK_KEY, s[2]) - GREEK_KEY];
      s += 2;
    } else if (s[0] == '#' && s[1] && strchr("udbf", s[1])) {
      s += 1; /* raise, lower, backspace: the text stays on the line */
      continue;
    } else if (s[0] == '#' && s[1] == '#') {
      put = "#";
      s += 1;
    } else
      put = one;
    size_t len = strlen(put);
    if (n + len + 1 > cap)
      break;
    memcpy(out + n, put, len);
    n += len;
  }
  out[n] = '\0';
}

void aq_plot_csv_axes(FILE *f, size_t n, const char *const *titles)
{
  for (size_t i = 0; i < n; i++) {
    char t[512];
    aq_plot_plain(titles[i], t, sizeof t);
    fprintf(f, "# axis: %s\n", t);
  }
}

/* Bytes of the UTF-8 character that starts at s (1 for a stray byte). */
static size_t utf8_len(const char *s)
{
  unsigned char c = (unsigned char)*s;
  size_t n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 1;
  for (size_t i = 1; i < n; i++)
    if (((unsigned char)s[i] & 0xc0) != 0x80)
      return 1;
  return n;
}

static size_t utf8_chars(const char *s)
{
  size_t n = 0;
  for (; *s; s += utf8_len(s))
    n++;
  return n;
}

void aq_plot_escape(const char *s, char *out, size_t cap)
{
  size_t n = 0;
  if (cap == 0)
    return;
  for (; *s && n + 2 < cap; s++) {
    if (*s == '#')
      out[n++] = '#'; /* PLplot's escape character, doubled: itself */
    out[n++] = *s;
  }
  out[n] = '\0';
  if (*s && cap >= 4) { /* cut: its end marked "…", never half a character */
    size_t k = cap - 4 < n ? cap - 4 : n;
    while (k > 0 && ((unsigned char)out[k] & 0xC0) == 0x80)
      k--;
    if (k > 0 && out[k - 1] == '#' && (k < 2 || out[k - 2] != '#'))
      k--; /* not half an escape */
    memcpy(out + k, "\xe2\x80\xa6", 4);
  }
}

void aq_plot_ellipsize(const char *s, size_t max_chars, char *out, size_t cap)
{
  size_t n = utf8_chars(s);
  char plain[1024];
  if (cap == 0)
    return;
  if (n <= max_chars || max_chars < 3)
    snprintf(plain, sizeof plain, "%s", s);
  else {
    size_t keep = max_chars - 1, head = (keep + 1) / 2, tail = keep - head;
    const char *p = s, *q = s;
    for (size_t i = 0; i < head; i++)
      p += utf8_len(p);
    for (size_t i = 0; i < n - tail; i++)
      q += utf8_len(q);
    snprintf(plain, sizeof plain, "%.*s…%s", (int)(p - s), s, q);
  }
  aq_plot_escape(plain, out, cap);
}

/* DejaVu Sans (Book, version 2.37), the font the cairo drivers and
 * librsvg find for "sans" on Debian (fc-match sans): the advance widths
 * of U+0020 .. U+007E in 1/2048 em, from the font's hmtx table. */
static const unsigned short ADVANCE[95] = {
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690,  690,  1716, 1716, 1716, 1087,
    2048, 1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612,
    1235, 1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799,  690,  799,  1716, 1024,
    1024, 1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186, 569,  1995, 1298, 1253,
    1300, 1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075, 1303, 690,  1303, 1716};
/* and of the other characters the figures write (the rest: 1 em) */
static const struct {
  unsigned long u;
  unsigned short adv;
} ADVANCE_MORE[] = {{0x2026, 2048}, {0x3bb, 1212}, {0x3b2, 1307}, {0x3bc, 1303}, {0xb1, 1716},
                    {0x25cf, 1787}, {0x25cb, 1787}, {0x25c6, 1575}, {0xd7, 1716}, {0x2212, 1716},
                    {0xb2, 821},    {0xb3, 821},    {0x2013, 1024}, {0xb7, 651},  {0x3b8, 1253},
                    {0x3b6, 1114},  {0x2002, 1024}, {0x207b, 1081}, {0x2070, 821},
                    {0xb9, 821},    {0x2074, 821},  {0x2075, 821},  {0x2076, 821},
                    {0x2077, 821},  {0x2078, 821},  {0x2079, 821},  {0x3b3, 1212},
                    {0x3b4, 1253},  {0x3b5, 1107},  {0x3a6, 1612},  {0x3c6, 1351},
                    {0x394, 1401}};
/* The cairo drivers draw text at a font size of 1.33 times PLplot's
 * character height (measured: 1.336 in a PDF through pdftotext's boxes,
 * 1.325 in an SVG's font-size); a line of text is the font's ascent and
 * descent, 1.164 em (2384/2048). */
static const double FONT_PER_HEIGHT = 1.33, LINE_EM = 1.164;

/* The code point at s (and its bytes in *n). */
static unsigned long utf8_code(const char *s, size_t *n)
{
  const unsigned char *u = (const unsigned char *)s;
  *n = 1;
  if (u[0] < 0x80)
    return u[0];
  size_t len = u[0] >= 0xf0 ? 4 : u[0] >= 0xe0 ? 3 : u[0] >= 0xc0 ? 2 : 1;
  unsigned long c = u[0] & (0x3f >> (len - 1));
  for (size_t i = 1; i < len; i++) {
    if ((u[i] & 0xc0) != 0x80)
      return u[0];
    c = c << 6 | (u[i] & 0x3f);
  }
  *n = len;
  return c;
}

static double advance_em(unsigned long u)
{
  if (u >= 0x20 && u <= 0x7e)
    return ADVANCE[u - 0x20] / 2048.0;
  for (size_t k = 0; k < sizeof ADVANCE_MORE / sizeof ADVANCE_MORE[0]; k++)
    if (ADVANCE_MORE[k].u == u)
      return ADVANCE_MORE[k].adv / 2048.0;
  return 1.0;
}

double aq_plot_text_em(const char *s)
{
  double em = 0, size = 1;
  while (*s) {
    if (s[0] == '#' && s[1] == 'g' && s[2] && strchr(GREEK_KEY, s[2])) {
      size_t n;
      em += size * advance_em(utf8_code(GREEK[strchr(GREEK_KEY, s[2]) - GREEK_KEY], &n));
      s += 3;
    } else if (s[0] == '#' && (s[1] == 'u' || s[1] == 'd')) {
      size = size < 1 ? 1 : 0.75; /* a sub- or superscript, and back */
      s += 2;
    } else if (s[0] == '#' && s[1] == '#') {
      em += size * advance_em('#');
      s += 2;
    } else {
      size_t n;
      em += size * advance_em(utf8_code(s, &n));
      s += n;
    }
  }
  return em;
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

void aq_plot_shorten_to(const char *s, double width_mm, char *out, size_t cap)
{
  size_t n = utf8_chars(s);
  for (size_t keep = n; keep >= 5; keep--) {
    aq_plot_ellipsize(s, keep, out, cap);
    if (aq_plot_text_mm(out) <= width_mm)
      return;
  }
  aq_plot_ellipsize(s, 5, out, cap);
}

double aq_plot_font_mm(double height_mm)
{
  return FONT_PER_HEIGHT * height_mm;
}

/* The first head and the last keep - 1 - head characters of s (n
 * characters) with an ellipsis between, into out[cap]; s if n <= keep. */
static void cut(const char *s, size_t n, size_t keep, size_t head, char *out, size_t cap)
{
  if (n <= keep || keep < 3) {
    snprintf(out, cap, "%s", s);
    return;
  }
  size_t tail = keep - 1 - head;
  const char *p = s, *q = s;
  for (size_t i = 0; i < head; i++)
    p += utf8_len(p);
  for (size_t i = 0; i < n - tail; i++)
    q += utf8_len(q);
  snprintf(out, cap, "%.*s…%s", (int)(p - s), s, q);
}

/* The characters of s from character `from`, count of them, with an
 * ellipsis where s goes on, before and after, into out[cap]. */
static void window(const char *s, size_t n, size_t from, size_t count, char *out, size_t cap)
{
  const char *p = s;
  for (size_t i = 0; i < from; i++)
    p += utf8_len(p);
  const char *q = p;
  for (size_t i = 0; i < count && *q; i++)
    q += utf8_len(q);
  snprintf(out, cap, "%s%.*s%s", from > 0 ? "…" : "", (int)(q - p), p,
           from + count < n ? "…" : "");
}

/* Characters s and t have in common from their start. */
static size_t common_start(const char *s, const char *t)
{
  size_t n = 0;
  while (*s && *s == *t) {
    size_t k = utf8_len(s);
    if (strncmp(s, t, k) != 0)
      break;
    s += k;
    t += k;
    n++;
  }
  return n;
}

void aq_plot_ellipsize_set(const char *const *names, size_t n, size_t max_chars, char *out,
                           size_t cap)
{
  enum { PLAIN = 1024 };
  char(*plain)[PLAIN] = malloc((n ? n : 1) * sizeof *plain);
  if (!plain) { /* each on its own */
    for (size_t i = 0; i < n; i++)
      aq_plot_ellipsize(names[i], max_chars, out + i * cap, cap);
    return;
  }
  /* the share of the kept characters taken from the start: even first,
     then more of the end (where file names differ most: a station, a
     component), then more of the start */
  static const double head_share[] = {0.5, 0.35, 0.2, 0.65, 0.8, 0.1, 0.9, 0, 1};
  int distinct = 0;
  for (size_t r = 0; r < sizeof head_share / sizeof head_share[0] && !distinct; r++) {
    size_t keep = max_chars, head = (size_t)lround(head_share[r] * (double)(keep - 1));
    for (size_t i = 0; i < n; i++)
      cut(names[i], utf8_chars(names[i]), keep, keep >= 3 ? head : 0, plain[i], PLAIN);
    distinct = 1;
    for (size_t i = 0; i < n && distinct; i++)
      for (size_t j = i + 1; j < n && distinct; j++)
        distinct = strcmp(plain[i], plain[j]) != 0 || strcmp(names[i], names[j]) == 0;
  }
  /* names alike at both ends: each shortened name shows where it first
     differs from the others */
  for (size_t i = 0; i < n && !distinct; i++) {
    size_t len = utf8_chars(names[i]), at = 0;
    if (len <= max_chars || max_chars < 5)
      continue;
    for (size_t j = 0; j < n; j++)
      if (j != i && strcmp(names[i], names[j]) != 0) {
        size_t c = common_start(names[i], names[j]);
        at = c > at ? c : at;
      }
    size_t count = max_chars - 2, from = at > count / 4 ? at - count / 4 : 0;
    if (from + count > len)
      from = len - count;
    window(names[i], len, from, count, plain[i], PLAIN);
  }
  for (size_t i = 0; i < n; i++)
    aq_plot_escape(plain[i], out + i * cap, cap);
  free(plain);
}

void aq_plot_shorten_set_to(const char *const *names, size_t n, const double *room_mm,
                            char *out, size_t cap)
{
  size_t longest = 0;
  for (size_t i = 0; i < n; i++) {
    size_t c = utf8_chars(names[i]);
    longest = c > longest ? c : longest;
  }
  for (size_t keep = longest; keep >= 5; keep--) {
    aq_plot_ellipsize_set(names, n, keep, out, cap);
    size_t i = 0;
    while (i < n && aq_plot_text_mm(out + i * cap) <= room_mm[i] + 1e-9)
      i++;
    if (i == n)
      return;
  }
  aq_plot_ellipsize_set(names, n, 5, out, cap);
}

/* In fractions of a key's width: a column's line, where its text starts,
 * and the room between two columns. */
static const double KEY_LINE0 = 0.01, KEY_LINE1 = 0.07, KEY_LEAD = 0.085, KEY_GAP = 0.03;

/* The widest whole text of each column of a key in nrow rows, in
 * fractions of its width: measured by measure (mm, or em) over unit (the
 * key's width in the same unit). */
static void key_widest(const aq_plot_key *key, size_t n, size_t nrow, double (*measure)(const char *),
                       double unit, double widest[2])
{
  char esc[1024];
  widest[0] = widest[1] = 0;
  for (size_t k = 0; k < n; k++) {
    aq_plot_escape(key[k].name ? key[k].name : "", esc, sizeof esc);
    double w = (measure(key[k].pre ? key[k].pre : "") + measure(esc) +
                measure(key[k].post ? key[k].post : "")) / unit;
    size_t c = k >= nrow;
    widest[c] = w > widest[c] ? w : widest[c];
  }
}

static int key_side_by_side(const double widest[2])
{
  return KEY_LEAD + widest[0] + KEY_GAP + KEY_LEAD + widest[1] <= 1;
}

size_t aq_plot_key_columns(const aq_plot_key *key, size_t n, double x0, double x1, int width_px,
                           double text_mm)
{
  if (n <= AQ_PLOT_KEY_ONE_COLUMN)
    return 1;
  /* the key's width in em of its font (72 points an inch) */
  double widest[2];
  key_widest(key, n, (n + 1) / 2, aq_plot_text_em,
             (x1 - x0) * (double)width_px * 25.4 / 72 / (FONT_PER_HEIGHT * text_mm), widest);
  return key_side_by_side(widest) || n > AQ_PLOT_KEY_ROWS_MAX ? 2 : 1;
}

size_t aq_plot_key_rows(size_t n, size_t ncol)
{
  return ncol > 1 ? (n + 1) / 2 : n;
}

void aq_plot_key_below(const aq_plot_key *key, size_t n, size_t ncol, double x0, double x1,
                       double y0, double y1)
{
  enum { NM = 1024 };
  if (n == 0)
    return;
  ncol = ncol > 1 ? 2 : 1;
  size_t nrow = aq_plot_key_rows(n, ncol);
  char *nm = malloc(n * NM);
  const char **name = malloc(n * sizeof *name);
  double *room = malloc(n * sizeof *room);
  if (!nm || !name || !room) {
    free(nm);
    free(name);
    free(room);
    return;
  }
  double wmm = (x1 - x0) * aq_plot_page_w_mm(), widest[2];
  key_widest(key, n, ncol > 1 ? nrow : n, aq_plot_text_mm, wmm, widest);
  /* where the second column starts: at the middle when both columns fit
     whole beside it, else past the first's widest text; when the two do
     not fit side by side, each a share in proportion to its texts */
  double x2 = 1;
  if (ncol > 1) {
    double need1 = KEY_LEAD + widest[0] + KEY_GAP, need2 = KEY_LEAD + widest[1];
    if (key_side_by_side(widest))
      x2 = need1 <= 0.5 && 0.5 + need2 <= 1 ? 0.5 : need1;
    else
      x2 = need1 / (need1 + need2);
  }
  for (size_t k = 0; k < n; k++) {
    int second = ncol > 1 && k >= nrow;
    double end = ncol > 1 && !second ? x2 - KEY_GAP : 1, start = second ? x2 : 0;
    name[k] = key[k].name ? key[k].name : "";
    room[k] = (end - start - KEY_LEAD) * wmm - aq_plot_text_mm(key[k].pre ? key[k].pre : "") -
              aq_plot_text_mm(key[k].post ? key[k].post : "");
  }
  aq_plot_shorten_set_to(name, n, room, nm, NM);
  plvpor(x0, x1, y0, y1);
  plwind(0, 1, (double)nrow, 0);
  for (size_t k = 0; k < n; k++) {
    double x = ncol > 1 && k >= nrow ? x2 : 0.0, y = (double)(k % nrow) + 0.5;
    PLFLT lx[2] = {x + KEY_LINE0, x + KEY_LINE1}, ly[2] = {y, y};
    plcol0(key[k].color);
    pllsty(key[k].style);
    plwidth(key[k].width);
    plline(2, lx, ly);
    pllsty(1);
    plwidth(1);
    plcol0(AQ_PC_FG);
    char text[3 * NM];
    snprintf(text, sizeof text, "%s%s%s", key[k].pre ? key[k].pre : "", nm + k * NM,
             key[k].post ? key[k].post : "");
    plptex(x + KEY_LEAD, y, 1, 0, 0, text);
  }
  free(nm);
  free(name);
  free(room);
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
  double hw = 0.5 * (0.62 * ht * (double)utf8_chars(text) + ht) / ((vx1 - vx0) * figure_w_mm) *
              (wx1 - wx0);
  double hh = 0.9 * ht / ((vy1 - vy0) * figure_h_mm) * (wy1 - wy0);
  PLFLT bx[4] = {x - hw, x + hw, x + hw, x - hw}, by[4] = {y - hh, y - hh, y + hh, y + hh};
  plcol0(AQ_PC_BG);
  plfill(4, bx, by);
  plcol0(AQ_PC_FG);
  plptex(x, y - 0.35 * hh, 1, 0, 0.5, text);
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
  const char *sy[MAX_ENTRIES], *ptext[MAX_ENTRIES];
  char padded[MAX_ENTRIES][160];
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
    /* a space's room after each text: on a PDF page scaled onto the paper
       PLplot measures the text a little narrower than cairo draws it */
    snprintf(padded[i], sizeof padded[i], "%s\u2002", text[i]); /* an en space */
    ptext[i] = padded[i];
    box[i] = color[i];
    bs[i] = 0.8;
  }
  PLFLT lw, lh;
  PLINT ncol = ncolumn > 1 ? ncolumn : 1, nrow = ((PLINT)n + ncol - 1) / ncol;
  pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX |
                         (ncol > 1 ? PL_LEGEND_ROW_MAJOR : 0),
           position, x, y, 0.06, AQ_PC_BG, AQ_PC_FG, 1, nrow, ncol, (PLINT)n, opt, 0.6, 0.7,
           2.0, 0.0, tcol, ptext, box, pat, bs,
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
