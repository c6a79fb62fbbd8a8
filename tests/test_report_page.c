/* test_report_page.c: `archquake report`.
 *   - the page of a suite with histories and a capacity file: one verdict
 *     row per run of the main job's TSV (written by the same command, read
 *     here), the collapses marked in words, a figure per arch, the verdict
 *     map, a history per collapsed run and one for the strongest survivor,
 *     the capacity file's rows and fits; nothing that a browser would fetch;
 *     the figures' text is text;
 *   - bad input (a text file, an HDF5 file not archquake's, a capacity file
 *     given as the results and the reverse, an older format_version): one
 *     line naming the file, exit 1, no file;
 *   - in a browser (Debian's chromium, headless, from disk; skipped and
 *     said so where it is not installed): the page's first screen and its
 *     second arch's verdict table are screenshots that are not blank and
 *     show the table's COLLAPSE cells; the page prints to PDF on A4 and on
 *     Letter, every page that size and every word within its margins; its net log
 *     holds no request but the page's own file; the script ran (the DOM
 *     has the filter it adds).  The screenshots are kept in build/check/. */
#define _XOPEN_SOURCE 700 /* realpath(3) */
#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "check.h"

#define ARCHES "arches/"
#define REC "tests/data/records/"
enum { BIG = 1 << 22 };

static int sh(const char *cmd, char *out, size_t cap)
{
  FILE *p = popen(cmd, "r");
  if (!p)
    return -1;
  size_t n = out ? fread(out, 1, cap - 1, p) : 0;
  if (out)
    out[n] = '\0';
  else {
    char sink[4096];
    while (fread(sink, 1, sizeof sink, p) > 0)
      ;
  }
  return pclose(p);
}

static size_t count(const char *s, const char *what)
{
  size_t n = 0;
  for (const char *p = s ? strstr(s, what) : NULL; p; p = strstr(p + 1, what))
    n++;
  return n;
}

static int exists(const char *path)
{
  struct stat st;
  return stat(path, &st) == 0;
}

/* The suite of the page tests: two records against two arches at two
 * scales, with histories and the processed records; made once. */
static const char *suite_h5(char *tsv, size_t cap)
{
  static char path[600];
  static char rows[1 << 16];
  if (!path[0]) {
    char dir[512], args[2048], err[2048];
    aq_test_shared_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/suite.h5", dir);
    snprintf(args, sizeof args,
             REC "ARL360.at2 " REC "IELC180.AT2 --arch " ARCHES "oppenheim.cfg --arch " ARCHES
                 "thin.cfg --scale 0.5,5 --history --store-records -o %s",
             path);
    if (aq_test_run(args, rows, sizeof rows, err, sizeof err) != 0)
      fprintf(stderr, "test_report_page: cannot make %s: %s\n", path, err);
  }
  if (tsv)
    snprintf(tsv, cap, "%s", rows);
  return path;
}

static const char *capacity_h5(void)
{
  static char path[600];
  if (!path[0]) {
    char dir[512], args[2048], err[2048];
    aq_test_shared_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/cap.h5", dir);
    snprintf(args, sizeof args,
             "capacity " REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "IELC180.AT2 --arch " ARCHES
             "oppenheim.cfg --scale-max 4 -o %s",
             path);
    if (aq_test_run(args, NULL, 0, err, sizeof err) != 0)
      fprintf(stderr, "test_report_page: cannot make %s: %s\n", path, err);
  }
  return path;
}

AQ_TEST(report_page_holds_the_suite)
{
  char *tsv = malloc(1 << 16);
  const char *h5 = suite_h5(tsv, 1 << 16), *cap = capacity_h5();
  char dir[512], page[600], args[2048], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(page, sizeof page, "%s/r.html", dir);
  snprintf(args, sizeof args, "report %s %s -o %s", h5, cap, page);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "%s: exit %d \"%s\"", args, rc, err);
  char *html = aq_test_read_file(page, NULL);
  if (!aq_check(html != NULL, "%s written", page)) {
    free(tsv);
    return;
  }
  /* the TSV's runs: rows, collapses (column 7, collapsed); each record and
     scale ran both ways (fixed arches), the worse governing: a group
     survives when neither of its runs collapsed (none fails here) */
  size_t runs = aq_test_count_lines(tsv) - 1, coll[2] = {0, 0}, gsurv[2] = {0, 0},
         gcoll[2] = {0, 0};
  for (int row = 1; row <= (int)runs; row += 2) {
    char arch[64], rec[2][300], sc[2][64], pol[2][16], c[2][8];
    aq_test_tsv_field(tsv, row, 1, arch, sizeof arch);
    for (int k = 0; k < 2; k++) {
      aq_test_tsv_field(tsv, row + k, 0, rec[k], sizeof rec[k]);
      aq_test_tsv_field(tsv, row + k, 3, sc[k], sizeof sc[k]);
      aq_test_tsv_field(tsv, row + k, 14, pol[k], sizeof pol[k]);
      aq_test_tsv_field(tsv, row + k, 6, c[k], sizeof c[k]);
    }
    aq_check(!strcmp(rec[0], rec[1]) && !strcmp(sc[0], sc[1]) && !strcmp(pol[0], "normal") &&
                 !strcmp(pol[1], "reversed"),
             "rows %d and %d: one record and scale, normal then reversed", row, row + 1);
    int a = strcmp(arch, "thin") == 0, n = (c[0][0] == '1') + (c[1][0] == '1');
    coll[a] += (size_t)n;
    gcoll[a] += n > 0;
    gsurv[a] += n == 0;
  }
  aq_check(runs == 16 && coll[1] > 0, "TSV: %zu runs, %zu collapses on thin", runs, coll[1]);
  aq_check(count(html, "<tr data-verdict=") == runs, "one verdict row per run (%zu of %zu)",
           count(html, "<tr data-verdict="), runs);
  aq_check(count(html, "<tr data-verdict=\"collapse\">") == coll[0] + coll[1] &&
               count(html, "✖ COLLAPSE") == coll[0] + coll[1],
           "collapses marked in words: %zu of %zu", count(html, "✖ COLLAPSE"),
           coll[0] + coll[1]);
  for (int a = 0; a < 2; a++) {
    char want_text[200];
    snprintf(want_text, sizeof want_text,
             "the worse governs: <b>%zu collapse%s</b>, %zu survived, 0 failed, of 4.", gcoll[a],
             gcoll[a] == 1 ? "" : "s", gsurv[a]);
    aq_check(strstr(html, want_text) != NULL, "arch %d: %s", a, want_text);
  }
  /* figures: the map, an arch each, a history per collapse and per arch
     whose worse polarity survived somewhere one more, a capacity figure */
  size_t want = 1 + 2 + coll[0] + coll[1] + (gsurv[0] > 0) + (gsurv[1] > 0) + 1;
  aq_check(count(html, "<svg class=\"fig\"") == want, "%zu figures, want %zu",
           count(html, "<svg class=\"fig\""), want);
  /* the figures' text is text, the page fetches nothing */
  aq_check(strstr(html, "<tspan") && strstr(html, ">IELC180.AT2<") &&
               strstr(html, "thin: 24 voussoirs") != NULL,
           "figure text as text");
  aq_check(!strstr(html, "<link") && !strstr(html, " src=") && !strstr(html, "@import") &&
               !strstr(html, "url(http") && !strstr(html, "href=\"http") &&
               !strstr(html, "<!DOCTYPE svg"),
           "no external resource");
  /* the run and the capacity file */
  aq_check(strstr(html, "ARL360.at2") && strstr(html, "sha256") && strstr(html, "format_version") == NULL,
           "the run: records, hashes; bookkeeping left out");
  /* the record's hash as sha256sum gives it, on one line of the files table */
  char sum[128] = "", cell[200];
  sh("sha256sum " REC "ARL360.at2", sum, sizeof sum);
  snprintf(cell, sizeof cell, "<td class=\"hash\">%.64s</td>", sum);
  aq_check(strlen(sum) > 64 && strstr(html, cell), "the files table: %s", cell);
  aq_check(count(html, "RSN77_SFERN_PUL164-hor1.AT2") >= 2 && strstr(html, "pga_g") &&
               strstr(html, "ranked by the dispersion"),
           "capacity: its rows and the ranking of the measures");
  aq_check(strstr(html, "sa_avg_0.1_1s_g") && strstr(html, "their peaks taken by the rule "
                                                         "<i>peer: each peak at the samples"),
           "the rule of the spectral measures' peaks (the default, peer)");
  aq_check(strstr(html, "<td>peaks</td>") || strstr(html, ">peaks<"),
           "the run's options list peaks");
  aq_check(count(html, "How to read this") >= 6, "a note on how to read each section (%zu)",
           count(html, "How to read this"));
  free(html);
  free(tsv);
}

/* Each record and scale run both ways, the worse governs: San Fernando at
 * 3 on oppenheim survives as recorded and collapses negated (the TSV says
 * so), so the arch's governed count is one collapse of one, and no
 * surviving run is drawn (the survivor is not the governing run). */
AQ_TEST(report_page_worse_polarity_governs)
{
  char dir[512], h5[600], page[600], args[2048], err[2048];
  static char tsv[8192];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/w.h5", dir);
  snprintf(page, sizeof page, "%s/w.html", dir);
  snprintf(args, sizeof args,
           REC "RSN77_SFERN_PUL164-hor1.AT2 --arch " ARCHES "oppenheim.cfg --scale 3 --history "
               "-o %s",
           h5);
  int rc = aq_test_run(args, tsv, sizeof tsv, err, sizeof err);
  char c[2][8], pol[2][16];
  for (int r = 0; r < 2; r++) {
    aq_test_tsv_field(tsv, r + 1, 6, c[r], sizeof c[r]);
    aq_test_tsv_field(tsv, r + 1, 14, pol[r], sizeof pol[r]);
  }
  if (!aq_check(rc == 0 && aq_test_count_lines(tsv) == 3 && !strcmp(c[0], "0") &&
                    !strcmp(c[1], "1") && !strcmp(pol[1], "reversed"),
                "the suite: normal survives (%s), reversed collapses (%s): %s", c[0], c[1], err))
    return;
  snprintf(args, sizeof args, "report %s -o %s", h5, page);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  char *html = aq_test_read_file(page, NULL);
  if (!aq_check(rc == 0 && html, "report: exit %d %s", rc, err)) {
    free(html);
    return;
  }
  aq_check(strstr(html, "<b>1 collapse</b>, 1 survived, 0 failed, of 2 runs.") &&
               strstr(html, "the worse governs: <b>1 collapse</b>, 0 survived, 0 failed, of 1."),
           "two runs, one governing collapse");
  aq_check(count(html, "<svg class=\"fig\"") == 3 && !strstr(html, "strongest surviving run)"),
           "the map, the arch and the collapse's history; no survivor drawn (%zu figures)",
           count(html, "<svg class=\"fig\""));
  free(html);
}

/* The records table's row of the record named name ("" if none). */
static void record_row(const char *html, const char *name, char *row, size_t cap)
{
  row[0] = '\0';
  const char *t = strstr(html, "id=\"records\"");
  const char *end = t ? strstr(t, "</table>") : NULL;
  char cell[300];
  snprintf(cell, sizeof cell, ">%s<", name);
  const char *c = t ? strstr(t, cell) : NULL;
  if (!c || c > end)
    return;
  const char *a = c, *z = strstr(c, "</tr>");
  while (a > t && strncmp(a, "<tr>", 4) != 0)
    a--;
  snprintf(row, cap, "%.*s", z ? (int)(z - a) : 0, a);
}

/* Where each record's units came from and whether it is vertical, as the
 * command line and the files themselves say: the AT2 header states g; the
 * miniSEED's counts take the sensitivity of the StationXML given; the CSN
 * SAC states nm/s2 (IDEP IACC) and a --units rule reads it as g; the
 * synthetic SAC states none and takes --units; the JMA CSV states gal, its
 * UD channel is vertical by its name and its NS channel is not. */
AQ_TEST(report_page_records_units_and_vertical)
{
  char dir[512], h5[600], page[600], args[3000], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/u.h5", dir);
  snprintf(page, sizeof page, "%s/u.html", dir);
  snprintf(args, sizeof args,
           REC "IELC180.AT2 " REC "CI.CLC..HNE.mseed " REC "CI.CLC.xml " REC
               "20190706031952.CJ.T001230.HNE.sac " REC "test.sac " REC "Q4149CF2.csv#NS " REC
               "Q4149CF2.csv#UD --units m/s2 --units *HNE.sac=g --accept-vertical --arch " ARCHES
               "thin.cfg -j 1 -o %s",
           h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  snprintf(args, sizeof args, "report %s -o %s", h5, page);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  char *html = aq_test_read_file(page, NULL);
  if (!aq_check(rc == 0 && html, "%s: exit %d %s", args, rc, err))
    return;
  static const struct {
    const char *name, *units, *vertical;
  } want[] = {
      {"IELC180.AT2", "g <small>(stated in the file)", "<td>no</td>"},
      {"CI.CLC..HNE.mseed", "counts <small>(StationXML response)", "<td>no</td>"},
      {"20190706031952.CJ.T001230.HNE.sac", "g <small>(a --units rule; the file states nm/s2)",
       "<td>no</td>"},
      {"test.sac", "m/s2 <small>(--units)", "<td>no</td>"},
      {"Q4149CF2.csv#NS", "gal <small>(stated in the file)", "<td>no</td>"},
      {"Q4149CF2.csv#UD", "gal <small>(stated in the file)",
       "<td><b>yes</b> <small>(its channel name)</small></td>"},
  };
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
    char row[4096];
    record_row(html, want[i].name, row, sizeof row);
    aq_check(strstr(row, want[i].units) && strstr(row, want[i].vertical),
             "%s: units \"%s\", vertical \"%s\" in: %s", want[i].name, want[i].units,
             want[i].vertical, row);
  }
  free(html);
}

/* Arches of other shapes: the arches table gives each one's shape and
 * voussoirs as its .cfg states them (gothic.cfg: pointed, 24; bridge.cfg:
 * elliptical, 31), and each is drawn with its line of thrust. */
AQ_TEST(report_page_arch_shapes)
{
  char dir[512], h5[600], page[600], args[3000], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/g.h5", dir);
  snprintf(page, sizeof page, "%s/g.html", dir);
  snprintf(args, sizeof args,
           REC "IELC180.AT2 --arch " ARCHES "gothic.cfg --arch " ARCHES "bridge.cfg -j 1 -q -o %s",
           h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
  snprintf(args, sizeof args, "report %s -o %s", h5, page);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  char *html = aq_test_read_file(page, NULL);
  if (!aq_check(rc == 0 && html, "%s: exit %d %s", args, rc, err))
    return;
  char *cfg[2] = {aq_test_read_file(ARCHES "gothic.cfg", NULL),
                  aq_test_read_file(ARCHES "bridge.cfg", NULL)};
  aq_check(cfg[0] && strstr(cfg[0], "shape = pointed") && strstr(cfg[0], "voussoirs = 24") &&
               cfg[1] && strstr(cfg[1], "shape = elliptical") && strstr(cfg[1], "voussoirs = 31"),
           "the .cfg files state the shapes");
  const char *t = strstr(html, "id=\"arches\"");
  const char *end = t ? strstr(t, "</table>") : NULL;
  const char *g = t ? strstr(t, "pointed, 24 voussoirs") : NULL;
  const char *e = t ? strstr(t, "elliptical, 31 voussoirs") : NULL;
  aq_check(g && e && g < end && e < end, "the arches table: pointed and elliptical");
  aq_check(count(html, "<svg class=\"fig\"") >= 3 && count(html, "line of thrust") >= 2,
           "each arch drawn with its line of thrust (%zu figures, %zu)",
           count(html, "<svg class=\"fig\""), count(html, "line of thrust"));
  free(cfg[0]);
  free(cfg[1]);
  free(html);
}

/* exit 1, one line naming path and containing what, no page */
static void refused(const char *args, const char *path, const char *what, const char *page)
{
  char err[2048];
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, path) && strstr(err, what),
           "%s: exit %d, one line naming %s and \"%s\": %s", args, rc, path, what, err);
  aq_check(!exists(page), "%s: no page left", args);
}

AQ_TEST(report_page_bad_input)
{
  const char *h5 = suite_h5(NULL, 0), *cap = capacity_h5();
  char dir[512], page[600], args[3000], text[600], alien[600], old[600], cmd[2000];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(page, sizeof page, "%s/r.html", dir);
  /* a text file */
  snprintf(text, sizeof text, "%s/notes.h5", dir);
  FILE *f = fopen(text, "w");
  if (f) {
    fputs("not results\n", f);
    fclose(f);
  }
  snprintf(args, sizeof args, "report %s -o %s", text, page);
  refused(args, text, "expected an archquake results file", page);
  /* an HDF5 file that archquake did not write */
  snprintf(alien, sizeof alien, "%s/alien.h5", dir);
  hid_t a = H5Fcreate(alien, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0)
    H5Fclose(a);
  snprintf(args, sizeof args, "report %s -o %s", alien, page);
  refused(args, alien, "not written by archquake", page);
  /* a capacity file alone makes a page of its own; two results files do not */
  snprintf(args, sizeof args, "report %s -o %s", cap, page);
  char out[1024];
  int crc = aq_test_run(args, NULL, 0, out, sizeof out);
  aq_check(crc == 0 && exists(page), "capacity file alone: exit %d, page %d: %s", crc,
           exists(page), out);
  remove(page);
  snprintf(args, sizeof args, "report %s %s -o %s", h5, h5, page);
  refused(args, h5, "at most one results file", page);
  /* an older format_version: says which one it reads */
  snprintf(old, sizeof old, "%s/old.h5", dir);
  snprintf(cmd, sizeof cmd, "cp '%s' '%s'", h5, old);
  sh(cmd, NULL, 0);
  hid_t o = H5Fopen(old, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t at = o >= 0 ? H5Aopen(o, "format_version", H5P_DEFAULT) : -1;
  int64_t one = 1;
  aq_check(at >= 0 && H5Awrite(at, H5T_NATIVE_INT64, &one) >= 0, "format_version set to 1");
  if (at >= 0)
    H5Aclose(at);
  if (o >= 0)
    H5Fclose(o);
  snprintf(args, sizeof args, "report %s -o %s", old, page);
  refused(args, old, "expected format_version 2, got 1", page);
  /* options: no -o, not .html */
  char err[1024];
  snprintf(args, sizeof args, "report %s -o %s/r.pdf", h5, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, ".html") && aq_test_count_lines(err) == 1, "-o x.pdf: %d %s",
           rc, err);
}

/* ---- the browser test ---------------------------------------------------- */

static const char CHROMIUM_FLAGS[] =
    "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
    "--disable-background-networking --disable-component-update --disable-sync "
    "--hide-scrollbars --no-pdf-header-footer";

static int have_chromium(void)
{
  char out[256];
  int have = sh("command -v chromium", out, sizeof out) == 0 && out[0] == '/';
  if (!have)
    fprintf(stderr, "test_report_page: chromium not installed: the browser test is skipped "
                    "(make deps-dev installs it)\n");
  return have;
}

/* A PNG's pixels as RGB: how many grey levels (blank: 1) and the share of
 * the verdict tables' COLLAPSE colour (179, 0, 27: the page's .v-c, apart
 * from the verdict map's red); -1 if it cannot be decoded (8-bit RGB or
 * RGBA, non-interlaced, as chromium writes them). */
static int png_stats(const char *path, size_t *distinct_grey, double *red_share, long *w_out,
                     long *h_out)
{
  size_t n;
  unsigned char *p = (unsigned char *)aq_test_read_file(path, &n);
  if (!p || n < 33 || memcmp(p, "\x89PNG\r\n\x1a\n", 8) != 0) {
    free(p);
    return -1;
  }
  long w = 0, h = 0;
  int bpp = 0;
  size_t zcap = n, zn = 0;
  unsigned char *z = malloc(zcap);
  for (size_t i = 8; z && i + 12 <= n;) {
    size_t len = (size_t)p[i] << 24 | (size_t)p[i + 1] << 16 | (size_t)p[i + 2] << 8 | p[i + 3];
    const unsigned char *type = p + i + 4, *d = p + i + 8;
    if (i + 12 + len > n)
      break;
    if (!memcmp(type, "IHDR", 4)) {
      w = (long)d[0] << 24 | d[1] << 16 | d[2] << 8 | d[3];
      h = (long)d[4] << 24 | d[5] << 16 | d[6] << 8 | d[7];
      bpp = d[8] == 8 && d[9] == 6 ? 4 : d[8] == 8 && d[9] == 2 ? 3 : 0;
      if (d[12] != 0)
        bpp = 0;
    } else if (!memcmp(type, "IDAT", 4)) {
      memcpy(z + zn, d, len);
      zn += len;
    }
    i += 12 + len;
  }
  free(p);
  if (!z || bpp == 0 || w <= 0 || h <= 0) {
    free(z);
    return -1;
  }
  size_t stride = (size_t)w * (size_t)bpp;
  uLongf rn = (uLongf)((stride + 1) * (size_t)h);
  unsigned char *raw = malloc(rn);
  if (!raw || uncompress(raw, &rn, z, zn) != Z_OK) {
    free(z);
    free(raw);
    return -1;
  }
  free(z);
  unsigned char *prev = calloc(stride, 1);
  size_t red = 0, seen[256] = {0};
  for (long y = 0; prev && y < h; y++) {
    unsigned char *row = raw + (size_t)y * (stride + 1), ft = row[0], *cur = row + 1;
    for (size_t x = 0; x < stride; x++) { /* PNG's five filters */
      int a = x >= (size_t)bpp ? cur[x - bpp] : 0, b = prev[x], c = x >= (size_t)bpp ? prev[x - bpp] : 0;
      int pr = a + b - c, pa = abs(pr - a), pb = abs(pr - b), pc = abs(pr - c);
      int pred = ft == 1 ? a : ft == 2 ? b : ft == 3 ? (a + b) / 2
                 : ft == 4 ? (pa <= pb && pa <= pc ? a : pb <= pc ? b : c)
                           : 0;
      cur[x] = (unsigned char)(cur[x] + pred);
    }
    for (long x = 0; x < w; x++) {
      const unsigned char *px = cur + x * bpp;
      seen[(px[0] + px[1] + px[2]) / 3]++;
      red += abs(px[0] - 179) <= 3 && px[1] <= 3 && abs(px[2] - 27) <= 3;
    }
    memcpy(prev, cur, stride);
  }
  free(prev);
  free(raw);
  *distinct_grey = 0;
  for (int i = 0; i < 256; i++)
    *distinct_grey += seen[i] > 0;
  *red_share = (double)red / ((double)w * (double)h);
  *w_out = w;
  *h_out = h;
  return 0;
}

/* Requests started in a net log (URL_REQUEST_START_JOB carries an
 * initiator), and those a page started: the browser's own (update checks,
 * accounts) are "not an origin"; a page's have its origin ("null" for a
 * file). */
static void count_requests(const char *log, size_t *starts, size_t *from_page)
{
  char *net = aq_test_read_file(log, NULL);
  *starts = *from_page = 0;
  for (const char *p = net ? strstr(net, "\"initiator\":\"") : NULL; p;
       p = strstr(p + 1, "\"initiator\":\"")) {
    (*starts)++;
    *from_page += strncmp(p + 13, "not an origin\"", 14) != 0;
  }
  aq_check(net != NULL, "net log %s written", log);
  free(net);
}

/* chromium with the flags above, a fresh profile, and what; 0 on success. */
static int chromium(const char *dir, const char *what, const char *url, char *out, size_t cap)
{
  char cmd[4096], prof[700];
  static int n;
  snprintf(prof, sizeof prof, "%s/profile%d", dir, n++);
  snprintf(cmd, sizeof cmd, "chromium %s --user-data-dir='%s' %s '%s' 2>/dev/null", CHROMIUM_FLAGS,
           prof, what, url);
  return sh(cmd, out, cap);
}

AQ_TEST(report_page_in_chromium)
{
  if (!have_chromium())
    return;
  const char *h5 = suite_h5(NULL, 0), *cap = capacity_h5();
  char dir[512], page[600], args[2048], err[2048], url[1200], what[1500], shot[2][700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(page, sizeof page, "%s/report.html", dir);
  snprintf(args, sizeof args, "report %s %s -o %s", h5, cap, page);
  if (!aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "%s: %s", args, err))
    return;
  char real[4096];
  if (!aq_check(realpath(page, real) != NULL, "realpath"))
    return;
  /* the first screen, kept for a reader in build/check/; a screen as
     tall as the page's first part, down to the arch sections' verdict
     tables (a headless screenshot shows the page from its top) */
  sh("mkdir -p build/check", NULL, 0);
  snprintf(url, sizeof url, "file://%.1100s", real);
  for (int k = 0; k < 2; k++) {
    snprintf(shot[k], sizeof shot[k], "%s/shot%d.png", dir, k);
    snprintf(what, sizeof what, "--window-size=1000,%d --screenshot='%s'", k ? 16000 : 1300,
             shot[k]);
    chromium(dir, what, url, NULL, 0);
    size_t grey = 0;
    double red = 0;
    long w = 0, h = 0;
    int ok = png_stats(shot[k], &grey, &red, &w, &h) == 0;
    aq_check(ok && w == 1000 && h == (k ? 16000 : 1300) && grey > 20,
             "screenshot %d: %ldx%ld, %zu grey levels (not blank)", k, w, h, grey);
    if (k == 1)
      aq_check(red * (double)w * (double)h > 2000,
               "the verdict tables on screen: %.0f pixels of COLLAPSE cells", red * w * h);
  }
  char cmd[3000];
  snprintf(cmd, sizeof cmd, "cp '%s' build/check/report-first-page.png", shot[0]);
  sh(cmd, NULL, 0);
  /* printed to PDF on A4 and on Letter (a copy of the page whose CSS asks
     for the paper: the browser's own default is its locale's); every word,
     the figures' too, within the page's 12 mm margins; the A4 page where
     the arch thin begins kept as an image */
  static const struct {
    const char *name, *css;
    double w_pt, h_pt;
  } paper[] = {{"A4", "210mm 297mm", 595.276, 841.89}, {"Letter", "8.5in 11in", 612, 792}};
  char out[64];
  int poppler = sh("command -v pdftoppm >/dev/null && command -v pdftotext >/dev/null && "
                   "command -v pdfinfo >/dev/null && echo y",
                   out, sizeof out) == 0 &&
                out[0] == 'y';
  if (!poppler)
    fprintf(stderr, "test_report_page: poppler-utils not installed: the printed pages are "
                    "not measured\n");
  char *text = malloc(BIG);
  for (size_t k = 0; k < 2 && text; k++) {
    char copy[700], pdf[700], copy_real[4096];
    snprintf(copy, sizeof copy, "%s/report-%s.html", dir, paper[k].name);
    snprintf(cmd, sizeof cmd, "sed 's|</head>|<style>@page{size:%s}</style></head>|' '%s' >'%s'",
             paper[k].css, page, copy);
    sh(cmd, NULL, 0);
    snprintf(pdf, sizeof pdf, "%s/report-%s.pdf", dir, paper[k].name);
    snprintf(what, sizeof what, "--print-to-pdf='%s'", pdf);
    snprintf(url, sizeof url, "file://%.1100s", realpath(copy, copy_real) ? copy_real : copy);
    chromium(dir, what, url, NULL, 0);
    size_t n = 0;
    char *bytes = aq_test_read_file(pdf, &n);
    size_t pages = 0;
    for (size_t i = 0; bytes && i + 11 < n; i++)
      pages += memcmp(bytes + i, "/Type /Page", 11) == 0 && bytes[i + 11] != 's';
    aq_check(bytes && n > 1000 && memcmp(bytes, "%PDF", 4) == 0 && pages >= 3,
             "%s: printed to PDF: %zu bytes, %zu pages", paper[k].name, n, pages);
    free(bytes);
    if (!poppler)
      continue;
    /* every page of the paper's size, every word within the margins */
    snprintf(cmd, sizeof cmd, "pdftotext -bbox '%s' -", pdf);
    long words = 0, outside = 0, wrong = 0;
    if (sh(cmd, text, BIG) == 0) {
      const double margin = 12 / 25.4 * 72 - 1; /* pt, less 1 pt */
      double pw = NAN, ph = NAN;
      for (const char *q = text; (q = strchr(q, '<')) != NULL; q++) {
        if (strncmp(q, "<page width=\"", 13) == 0) {
          pw = strtod(q + 13, NULL);
          const char *hh = strstr(q, "height=\"");
          ph = hh ? strtod(hh + 8, NULL) : NAN;
          wrong += !(fabs(pw - paper[k].w_pt) < 1.5 && fabs(ph - paper[k].h_pt) < 1.5);
        } else if (strncmp(q, "<word ", 6) == 0) {
          const char *a = strstr(q, "xMin=\""), *b2 = strstr(q, "yMin=\""),
                     *c = strstr(q, "xMax=\""), *d = strstr(q, "yMax=\"");
          if (!a || !b2 || !c || !d)
            break;
          double x0 = strtod(a + 6, NULL), y0 = strtod(b2 + 6, NULL), x1 = strtod(c + 6, NULL),
                 y1 = strtod(d + 6, NULL);
          words++;
          if ((x0 < margin || y0 < margin || x1 > pw - margin || y1 > ph - margin) &&
              outside++ < 3)
            aq_check(0, "%s: a word at x %.1f-%.1f, y %.1f-%.1f outside the margins of the "
                        "%.0f x %.0f pt page",
                     paper[k].name, x0, x1, y0, y1, pw, ph);
        }
      }
    }
    aq_check(words > 200 && wrong == 0 && outside == 0,
             "%s: %zu pages of %.0f x %.0f pt (%ld others), %ld words, %ld outside the margins",
             paper[k].name, pages, paper[k].w_pt, paper[k].h_pt, wrong, words, outside);
    if (k != 0)
      continue;
    int page_no = 0;
    for (int pg = 1; pg <= (int)pages && !page_no; pg++) {
      snprintf(cmd, sizeof cmd, "pdftotext -f %d -l %d -layout '%s' -", pg, pg, pdf);
      if (sh(cmd, text, BIG) == 0 && strstr(text, "Arch thin")) /* its section's first */
        page_no = pg;
    }
    snprintf(cmd, sizeof cmd,
             "pdftoppm -f %d -l %d -r 90 -png -singlefile '%s' build/check/report-arch-thin",
             page_no, page_no, pdf);
    size_t grey = 0;
    double red = 0;
    long w = 0, h = 0;
    aq_check(page_no > 1 && sh(cmd, NULL, 0) == 0 &&
                 png_stats("build/check/report-arch-thin.png", &grey, &red, &w, &h) == 0 &&
                 grey > 20,
             "the printed page of arch thin (page %d): %zu grey levels", page_no, grey);
  }
  free(text);
  snprintf(url, sizeof url, "file://%.1100s", real);
  /* the script ran, and no request left the page */
  char log[700];
  snprintf(log, sizeof log, "%s/net.json", dir);
  snprintf(what, sizeof what, "--log-net-log='%s' --net-log-capture-mode=Everything --dump-dom",
           log);
  char *dom = malloc(BIG);
  if (dom)
    chromium(dir, what, url, dom, BIG);
  aq_check(dom && strstr(dom, "class=\"controls\"") && strstr(dom, "table class=\"verdicts"),
           "the DOM after the script: the verdict tables have their filter");
  free(dom);
  size_t starts = 0, from_page = 0;
  count_requests(log, &starts, &from_page);
  aq_check(from_page == 0, "net log: %zu requests, %zu from the page", starts, from_page);
  /* the check itself: a page that fetches an image is caught */
  char ctl[700];
  snprintf(ctl, sizeof ctl, "%s/fetch.html", dir);
  FILE *f = fopen(ctl, "w");
  if (f) {
    fputs("<!DOCTYPE html><html><body><img src=\"http://127.0.0.1:9/x.png\"></body></html>\n", f);
    fclose(f);
  }
  char ctl_real[4096];
  snprintf(url, sizeof url, "file://%.1100s", realpath(ctl, ctl_real) ? ctl_real : ctl);
  snprintf(what, sizeof what, "--log-net-log='%s' --net-log-capture-mode=Everything --dump-dom",
           log);
  chromium(dir, what, url, NULL, 0);
  size_t s2 = 0, p2 = 0;
  count_requests(log, &s2, &p2);
  aq_check(p2 >= 1, "a page fetching http://127.0.0.1:9/x.png is caught (%zu requests)", p2);
}
