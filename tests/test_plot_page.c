/* test_plot_page.c: the figures as a reader sees them, measured by other
 * programs: poppler's pdfinfo (the page size) and pdftotext -bbox (every
 * word drawn and its box, as the glyphs are laid out), the SVG's text
 * read as XML text, and the --data CSVs.
 *   - a PDF page is A4 (the C locale's paper) or Letter (--paper), and
 *     every word lies within the page's 10 mm margins;
 *   - a record name too long for the suite's margin is drawn shortened by
 *     an ellipsis in the middle (its start and end kept), within the page,
 *     and is whole in the data; the SVG keeps its text as text;
 *   - a tall suite map (26 records, 5 arches): each cell's label fits its
 *     cell, no two words overlap, the arches' names are whole;
 *   - history at small rotations: the tick labels of the rotation axis
 *     stay clear of its title, and the note of a missing ground is drawn;
 *   - capacity: a strip per record and polarity, each with its first
 *     collapse scale as `archquake capacity` prints it;
 *   - domain --data: the axis titles in plain text, no PLplot escapes.
 * Skipped, and said so, where poppler-utils is not installed (and the
 * SVG's part where librsvg2-bin's rsvg-convert is not). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define ARCHES "arches/"
enum { OUT_CAP = 1 << 20 };

/* stdout of a shell command into out[cap]; its exit status. */
static int sh(const char *cmd, char *out, size_t cap)
{
  FILE *p = popen(cmd, "r");
  if (!p)
    return -1;
  size_t n = fread(out, 1, cap - 1, p);
  out[n] = '\0';
  return pclose(p);
}

static int have_poppler(void)
{
  static int have = -1;
  char out[256];
  if (have < 0)
    have = sh("command -v pdftotext >/dev/null && command -v pdfinfo >/dev/null && echo y",
              out, sizeof out) == 0 &&
           out[0] == 'y';
  if (!have)
    fprintf(stderr, "test_plot_page: pdftotext/pdfinfo not installed (poppler-utils): "
                    "PDF checks skipped\n");
  return have;
}

typedef struct {
  double x0, y0, x1, y1;
  char text[256];
} word;

/* The words of page 1 of pdf (pdftotext -bbox) into w[cap]; the page's
 * size into *pw, *ph (points).  Returns the count, or -1. */
static long pdf_words(const char *pdf, word *w, size_t cap, double *pw, double *ph)
{
  char cmd[1200];
  char *out = malloc(OUT_CAP);
  if (!out)
    return -1;
  snprintf(cmd, sizeof cmd, "pdftotext -f 1 -l 1 -bbox '%s' - 2>/dev/null", pdf);
  if (sh(cmd, out, OUT_CAP) != 0) {
    free(out);
    return -1;
  }
  const char *pg = strstr(out, "<page width=\"");
  *pw = pg ? strtod(pg + 13, NULL) : NAN;
  pg = pg ? strstr(pg, "height=\"") : NULL;
  *ph = pg ? strtod(pg + 8, NULL) : NAN;
  long n = 0;
  for (const char *p = strstr(out, "<word "); p && (size_t)n < cap; p = strstr(p + 1, "<word ")) {
    word *q = &w[n];
    const char *a = strstr(p, "xMin=\""), *b = strstr(p, "yMin=\""), *c = strstr(p, "xMax=\""),
               *d = strstr(p, "yMax=\""), *t = strchr(p, '>'), *e = t ? strstr(t, "</word>") : NULL;
    if (!a || !b || !c || !d || !e)
      break;
    q->x0 = strtod(a + 6, NULL);
    q->y0 = strtod(b + 6, NULL);
    q->x1 = strtod(c + 6, NULL);
    q->y1 = strtod(d + 6, NULL);
    snprintf(q->text, sizeof q->text, "%.*s", (int)(e - t - 1), t + 1);
    n++;
  }
  free(out);
  return n;
}

/* A4 or Letter in either orientation; every word within 10 mm margins
 * (less 1 pt). */
static void check_page(const char *pdf, int letter, const char *what)
{
  const double MARGIN_PT = 28.35 - 1;
  enum { MAXW = 4000 };
  word *w = malloc(MAXW * sizeof *w);
  double pw = NAN, ph = NAN;
  long n = w ? pdf_words(pdf, w, MAXW, &pw, &ph) : -1;
  double a = fmin(pw, ph), b = fmax(pw, ph);
  double wa = letter ? 612 : 595.276, wb = letter ? 792 : 841.89;
  aq_check(n > 5 && fabs(a - wa) < 1 && fabs(b - wb) < 1, "%s: %s page, %.1f x %.1f pt, %ld words",
           what, letter ? "Letter" : "A4", pw, ph, n);
  long out = 0;
  for (long i = 0; i < n; i++)
    if (w[i].x0 < MARGIN_PT || w[i].y0 < MARGIN_PT || w[i].x1 > pw - MARGIN_PT ||
        w[i].y1 > ph - MARGIN_PT) {
      if (out++ < 3)
        aq_check(0, "%s: \"%s\" at x %.1f-%.1f, y %.1f-%.1f: outside the margins of the "
                    "%.0f x %.0f page", what, w[i].text, w[i].x0, w[i].x1, w[i].y0, w[i].y1,
                 pw, ph);
    }
  aq_check(out == 0, "%s: %ld of %ld words outside the margins", what, out, n);
  free(w);
}

static int run_ok(const char *args)
{
  char err[2048];
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  return aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
}

AQ_TEST(plot_page_suite_long_names)
{
  static const char LONG[] = "A_record_from_a_station_archive_with_a_long_name_ARL360_0123456789.at2";
  char dir[512], rec[1024], h5[600], args[4096], pdf[600], svg[600], csv[600], cmd[2400];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(rec, sizeof rec, "%s/%s", dir, LONG);
  snprintf(cmd, sizeof cmd, "cp tests/data/records/ARL360.at2 '%s'", rec);
  char out[256];
  if (!aq_check(sh(cmd, out, sizeof out) == 0, "copy the record"))
    return;
  snprintf(h5, sizeof h5, "%s/s.h5", dir);
  snprintf(args, sizeof args,
           "'%s' tests/data/records/IELC180.AT2 --arch " ARCHES "oppenheim.cfg --arch " ARCHES
           "thin.cfg --scale 1,3 -q -o %s",
           rec, h5);
  if (!run_ok(args))
    return;
  snprintf(pdf, sizeof pdf, "%s/s.pdf", dir);
  snprintf(svg, sizeof svg, "%s/s.svg", dir);
  snprintf(csv, sizeof csv, "%s/s.csv", dir);
  snprintf(args, sizeof args, "plot suite %s -o %s --data %s", h5, svg, csv);
  run_ok(args);
  /* the data: the whole name */
  char *data = aq_test_read_file(csv, NULL);
  aq_check(data && strstr(data, LONG), "--data holds the whole name");
  free(data);
  /* the SVG: its labels are text, the record's shortened in the middle */
  char *text = aq_test_read_file(svg, NULL);
  const char *lab = text ? strstr(text, "A_record") : NULL;
  const char *ell = lab ? strstr(lab, "…") : NULL, *end = lab ? strstr(lab, "0123456789.at2") : NULL;
  aq_check(text && strstr(text, "<text") && strstr(text, "oppenheim") && strstr(text, "thin") &&
               strstr(text, "IELC180.AT2") && !strstr(text, LONG),
           "SVG: the names are text, the long one not whole");
  aq_check(lab && ell && end && ell < end && end - lab < 60 && !memchr(lab, '<', (size_t)(end - lab)),
           "SVG: the long name as its start, an ellipsis and its end, in one text");
  free(text);
  if (!have_poppler())
    return;
  snprintf(cmd, sizeof cmd, "LC_ALL=C %s plot suite %s -o %s 2>&1", aq_test_bin(), h5, pdf);
  if (!aq_check(sh(cmd, out, sizeof out) == 0, "%s: %s", cmd, out))
    return;
  check_page(pdf, 0, "suite, A4 by default (LC_ALL=C)");
  enum { MAXW = 400 };
  word w[MAXW];
  double pw = NAN, ph = NAN;
  long n = pdf_words(pdf, w, MAXW, &pw, &ph), found = 0;
  for (long i = 0; i < n; i++)
    if (strncmp(w[i].text, "A_record", 8) == 0) {
      size_t len = strlen(w[i].text);
      found += strstr(w[i].text, "…") && len > 14 &&
               strcmp(w[i].text + len - 14, "0123456789.at2") == 0;
    }
  aq_check(found == 1, "PDF: the long name drawn once, start … end (%ld)", found);
  snprintf(args, sizeof args, "plot suite %s -o %s --paper letter", h5, pdf);
  if (run_ok(args))
    check_page(pdf, 1, "suite, --paper letter");
}

/* Is s a cell's label of the suite map: collapse, failed or a number
 * with three decimals? */
static int map_label(const char *s)
{
  if (strcmp(s, "collapse") == 0 || strcmp(s, "failed") == 0)
    return 1;
  size_t n = strlen(s);
  return n == 5 && s[0] >= '0' && s[0] <= '9' && s[1] == '.' && strspn(s + 2, "0123456789") == 3;
}

/* The words of the tall map of plot_page_suite_tall_map_cells in pdf. */
static void map_words(const char *pdf, const char *what)
{
  enum { MAXW = 1000 };
  word *w = malloc(MAXW * sizeof *w);
  double pw = NAN, ph = NAN;
  long nw = w ? pdf_words(pdf, w, MAXW, &pw, &ph) : -1;
  long labels = 0, overlaps = 0, arches = 0;
  static const char *const names[] = {"thin", "thick", "oppenheim", "segmental", "search"};
  for (long i = 0; i < nw; i++) {
    labels += map_label(w[i].text);
    for (size_t k = 0; k < 5; k++)
      arches += strcmp(w[i].text, names[k]) == 0;
    for (long j = i + 1; j < nw; j++) {
      double dy = fmin(w[i].y1, w[j].y1) - fmax(w[i].y0, w[j].y0);
      double dx = fmin(w[i].x1, w[j].x1) - fmax(w[i].x0, w[j].x0);
      if (dy > 0.5 * (w[i].y1 - w[i].y0) && dx > 0 && overlaps++ < 3)
        aq_check(0, "%s: \"%s\" and \"%s\" overlap", what, w[i].text, w[j].text);
    }
  }
  /* and the caption's "red: collapse" */
  aq_check(labels == 26 * 5 + 1, "%s: one word per cell, a label (%ld of %d)", what, labels,
           26 * 5 + 1);
  aq_check(overlaps == 0, "%s: no two words overlap (%ld)", what, overlaps);
  aq_check(arches == 5, "%s: the arches' names whole (%ld of 5)", what, arches);
  free(w);
}

/* A tall map (26 records) of the five shipped arches: PLplot's text grows
 * with the figure's height, and it outgrew the cells ("collapse" over its
 * neighbours, "0.0020.000" read as one word).  Each cell's label is one
 * word, no two words of a line overlap, and the arches' names are whole. */
AQ_TEST(plot_page_suite_tall_map_cells)
{
  char dir[512], args[8192], pdf[600], h5[600], cmd[2400], out[256];
  aq_test_tmpdir(dir, sizeof dir);
  int n = snprintf(args, sizeof args, "-q -o %s/m.h5", dir);
  for (int i = 0; i < 24; i++) {
    snprintf(cmd, sizeof cmd, "cp tests/data/records/ARL360.at2 '%s/r%02d_from_a_station_archive_ARL360.at2'", dir, i);
    if (!aq_check(sh(cmd, out, sizeof out) == 0, "copy the record"))
      return;
    n += snprintf(args + n, sizeof args - (size_t)n, " %s/r%02d_from_a_station_archive_ARL360.at2", dir, i);
  }
  snprintf(cmd, sizeof cmd, "echo not a record >'%s/broken.at2'", dir);
  sh(cmd, out, sizeof out);
  snprintf(args + n, sizeof args - (size_t)n,
           " tests/data/records/IELC180.AT2 %s/broken.at2 --arch " ARCHES "thin.cfg --arch " ARCHES
           "thick.cfg --arch " ARCHES "oppenheim.cfg --arch " ARCHES "segmental.cfg --arch " ARCHES
           "search.cfg",
           dir);
  char err[2048];
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1, "the suite: exit %d (one record unreadable) %s", rc, err);
  if (!have_poppler())
    return;
  snprintf(h5, sizeof h5, "%s/m.h5", dir);
  snprintf(pdf, sizeof pdf, "%s/m.pdf", dir);
  snprintf(args, sizeof args, "plot suite %s -o %s", h5, pdf);
  if (!run_ok(args))
    return;
  check_page(pdf, 0, "tall suite map, PDF");
  map_words(pdf, "PDF");
  /* the SVG (the report's figures), as librsvg lays it out */
  if (sh("command -v rsvg-convert >/dev/null && echo y", out, sizeof out) != 0 || out[0] != 'y') {
    fprintf(stderr, "test_plot_page: rsvg-convert not installed (librsvg2-bin): the SVG map "
                    "not checked\n");
    return;
  }
  snprintf(args, sizeof args, "plot suite %s -o %s/m.svg", h5, dir);
  snprintf(cmd, sizeof cmd, "rsvg-convert -f pdf -o '%s/svg.pdf' '%s/m.svg' 2>&1", dir, dir);
  if (run_ok(args) && aq_check(sh(cmd, out, sizeof out) == 0, "%s: %s", cmd, out)) {
    snprintf(pdf, sizeof pdf, "%s/svg.pdf", dir);
    map_words(pdf, "SVG");
  }
}

AQ_TEST(plot_page_history_small_rotation)
{
  char dir[512], h5[600], args[2048], pdf[600], csv[600], tsv[4096], err[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/h.h5", dir);
  /* thin under ARL360 at 0.3: a peak of 1.5e-4 rad, far below q_c */
  snprintf(args, sizeof args,
           "tests/data/records/ARL360.at2 --arch " ARCHES "thin.cfg --scale 0.3 --history -o %s",
           h5);
  int rc = aq_test_run(args, tsv, sizeof tsv, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  /* the run's peak rotation from the TSV (column peak_rotation_rad) */
  const char *row = strchr(tsv, '\n');
  double peak = NAN;
  if (row) {
    const char *f = row + 1;
    for (int k = 0; k < 8 && f; k++) {
      f = strchr(f, '\t');
      f = f ? f + 1 : NULL;
    }
    peak = f ? strtod(f, NULL) : NAN;
  }
  aq_check(peak > 1e-5 && peak < 1e-3, "peak rotation %g rad, between 0.01 and 1 mrad", peak);
  snprintf(pdf, sizeof pdf, "%s/h.pdf", dir);
  snprintf(csv, sizeof csv, "%s/h.csv", dir);
  snprintf(args, sizeof args, "plot history %s -o %s --data %s", h5, pdf, csv);
  if (!run_ok(args))
    return;
  char *data = aq_test_read_file(csv, NULL);
  /* over q_c (thin's primary set's 0.0208 rad, q_c_rad of the file): a
     ratio of some thousandths, drawn in thousandths */
  aq_check(data && strstr(data, "# axis: rotation / qc of its set (10⁻³)\n"),
           "a peak of %g rad, %g of q_c, drawn in thousandths of q_c (axis title in the "
           "data)", peak, peak / 0.020813);
  free(data);
  if (!have_poppler())
    return;
  check_page(pdf, 0, "history");
  enum { MAXW = 600 };
  word *w = malloc(MAXW * sizeof *w);
  double pw = NAN, ph = NAN;
  long n = w ? pdf_words(pdf, w, MAXW, &pw, &ph) : 0;
  /* the title's words "rotation / qc of its set (10⁻³)", drawn upwards
     left of the axis */
  const word *title = NULL;
  for (long i = 0; i < n; i++)
    if (strcmp(w[i].text, "(10⁻³)") == 0)
      title = &w[i];
  long labels = 0, overlap = 0, longest = 0, note = 0, missing = 0;
  for (long i = 0; i < n && title; i++) {
    const word *q = &w[i];
    note += strcmp(q->text, "ground") == 0; /* the axis' and the legend's */
    missing += strcmp(q->text, "before") == 0; /* the note of a file without it */
    char *e;
    strtod(q->text, &e);
    /* a number beside the title's band of the page, in the panel's height */
    if (*e != '\0' || e == q->text || q->x0 > title->x1 + 60 || q->x1 < title->x0 - 5 ||
        q->y1 < title->y0 - 80 || q->y0 > title->y1 + 80)
      continue;
    labels++;
    longest = (long)strlen(q->text) > longest ? (long)strlen(q->text) : longest;
    overlap += q->x0 < title->x1;
  }
  aq_check(title && labels >= 3 && overlap == 0 && longest <= 5,
           "rotation axis: %ld tick labels, at most %ld characters, %ld over the title", labels,
           longest, overlap);
  aq_check(note == 2 && missing == 0,
           "the ground (stored with --history) on its axis and in the legend, no note of it "
           "missing (%ld words \"ground\", %ld \"before\")", note, missing);
  free(w);
}

AQ_TEST(plot_page_capacity_strips)
{
  char dir[512], h5[600], args[2048], pdf[600], err[1024];
  char *tsv = malloc(OUT_CAP);
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/c.h5", dir);
  snprintf(args, sizeof args,
           "capacity tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 --arch " ARCHES
           "oppenheim.cfg --scale-max 4 -o %s",
           h5);
  int rc = tsv ? aq_test_run(args, tsv, OUT_CAP, err, sizeof err) : -1;
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err)) {
    free(tsv);
    return;
  }
  /* first_collapse_scale of each polarity (column 6), as %.3g */
  char want[2][32] = {"", ""};
  int nrow = 0;
  for (const char *l = strchr(tsv, '\n'); l && l[1] && nrow < 2; l = strchr(l + 1, '\n')) {
    const char *f = l + 1;
    for (int k = 0; k < 5 && f; k++) {
      f = strchr(f, '\t');
      f = f ? f + 1 : NULL;
    }
    double v = f ? strtod(f, NULL) : NAN;
    snprintf(want[nrow++], sizeof want[0], isfinite(v) ? "%.3g" : "none", v);
  }
  free(tsv);
  aq_check(nrow == 2, "two rows (normal, reversed)");
  if (!have_poppler())
    return;
  snprintf(pdf, sizeof pdf, "%s/c.pdf", dir);
  snprintf(args, sizeof args, "plot capacity %s -o %s", h5, pdf);
  if (!run_ok(args))
    return;
  check_page(pdf, 0, "capacity");
  enum { MAXW = 600 };
  word *w = malloc(MAXW * sizeof *w);
  double pw = NAN, ph = NAN;
  long n = w ? pdf_words(pdf, w, MAXW, &pw, &ph) : 0;
  /* each strip's label (normal, reversed) and, on its line to the right,
     its first collapse */
  int ok[2] = {0, 0};
  for (long i = 0; i < n; i++)
    for (int k = 0; k < 2; k++)
      if (strcmp(w[i].text, k ? "reversed" : "normal") == 0)
        for (long j = 0; j < n; j++)
          ok[k] |= strcmp(w[j].text, want[k]) == 0 && w[j].x0 > w[i].x1 + 100 &&
                   fabs(0.5 * (w[j].y0 + w[j].y1) - 0.5 * (w[i].y0 + w[i].y1)) < 3;
  aq_check(ok[0] && ok[1], "strips: normal beside %s (%d), reversed beside %s (%d)", want[0],
           ok[0], want[1], ok[1]);
  free(w);
}

AQ_TEST(plot_page_domain_data_plain)
{
  char dir[512], args[2048], png[600], csv[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(png, sizeof png, "%s/d.png", dir);
  snprintf(csv, sizeof csv, "%s/d.csv", dir);
  snprintf(args, sizeof args,
           "plot domain --arch " ARCHES "oppenheim.cfg --ratios 1.5,3 -o %s --data %s", png, csv);
  if (!run_ok(args))
    return;
  char *data = aq_test_read_file(csv, NULL);
  size_t axes = 0, escaped = 0;
  for (const char *p = data ? strstr(data, "# axis: ") : NULL; p; p = strstr(p + 1, "# axis: ")) {
    axes++;
    const char *e = strchr(p, '\n');
    const char *h = strchr(p + 1, '#');
    escaped += h && (!e || h < e);
  }
  aq_check(axes == 2 && escaped == 0 && strstr(data, "# axis: amplitude ratio a / (λ0 g) (1)\n"),
           "--data axis titles in plain text (%zu, %zu with a #)", axes, escaped);
  free(data);
}

/* plot spectrum: on the PDF page within its margins, the axis titles with
 * their units and every curve's component named (the pair's RotD50,
 * RotD100, GeoMean; the record's channel) for both dampings. */
AQ_TEST(plot_page_spectrum_axes_and_curves)
{
  if (!have_poppler())
    return;
  char dir[512], h5[600], pdf[600], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/sp.h5", dir);
  snprintf(pdf, sizeof pdf, "%s/sp.pdf", dir);
  snprintf(args, sizeof args,
           "spectrum --components tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2,"
           "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2 tests/data/records/ARL360.at2 "
           "--damping 0.02,0.05 -o %s", h5);
  if (!run_ok(args))
    return;
  snprintf(args, sizeof args, "plot spectrum %s -o %s", h5, pdf);
  if (!run_ok(args))
    return;
  check_page(pdf, 0, "plot spectrum");
  enum { MAXW = 4000 };
  word *w = malloc(MAXW * sizeof *w);
  double pw, ph;
  long n = w ? pdf_words(pdf, w, MAXW, &pw, &ph) : -1;
  static const char *const want[] = {"period", "(s)", "pseudo-spectral", "PSA", "(g)",
                                     "RotD50,", "RotD100,", "GeoMean,", "360,"};
  for (size_t k = 0; k < sizeof want / sizeof *want; k++) {
    long seen = 0;
    for (long i = 0; i < n; i++)
      seen += strcmp(w[i].text, want[k]) == 0;
    long need = k >= 5 ? 2 : 1; /* each component at both dampings */
    aq_check(seen >= need, "plot spectrum: \"%s\" drawn %ld times (want %ld)", want[k], seen,
             need);
  }
  free(w);
}
