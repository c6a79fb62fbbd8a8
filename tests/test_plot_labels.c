/* test_plot_labels.c: every kind of figure's labels, measured by other
 * programs (tests/plot_labels.py: poppler's pdftotext -bbox for the words
 * of the PDF and of the SVG as librsvg lays it out, the SVG drawn again
 * without its text for the marks under them):
 *   - every word inside the page (the PDF's 10 mm margins);
 *   - no two words overlapping, nor a word and a data point;
 *   - no label on a line, a point or the edge of a fill;
 *   - a shortened name standing for one name only.
 * The figures: history (a collapse and a small response), arch (from a
 * .cfg, deformed, and from a results file), domain, suite, capacity (three
 * ways: --arch, --y pga --x rad, --im of a spectral measure), spectrum and
 * spectrum of a select file (a target CSV of a long name with '#' in it),
 * drawn from records whose names are long and alike (two of them differ
 * only in their middle, as the Loma Prieta pair GIL067 and GIL337) and an
 * arch of a long name.
 * Besides: the capacity figure's fragility key on none of its data and its
 * scale axis' ticks off its strips, the spectrum figures' keys shortening
 * no name that fits, and aq_plot_ellipsize_set's labels against the names
 * they shorten. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "plot/plot.h"

#define REC "tests/data/records/"
/* two names alike but for their middle, longer than any figure's margin */
#define LONG_A "Station_archive_of_the_2024_campaign_RSN763_LOMAP_GIL067_horizontal_acceleration.AT2"
#define LONG_B "Station_archive_of_the_2024_campaign_RSN763_LOMAP_GIL337_horizontal_acceleration.AT2"
#define LONG_ARCH "thin_arch_of_the_figures_test_with_a_name_of_sixty_characters"

static int have_tools(void)
{
  char out[64];
  int ok = aq_test_sh("command -v pdftotext && command -v pdftoppm && command -v rsvg-convert", out,
              sizeof out) == 0;
  if (!ok)
    fprintf(stderr, "test_plot_labels: poppler-utils or librsvg2-bin not installed: "
                    "figure labels not checked\n");
  return ok;
}

/* The records, arch and results files of the figures into dir; 1 if made. */
static int make_inputs(const char *dir)
{
  char cmd[8192], out[4096], err[2048];
  snprintf(cmd, sizeof cmd,
           "cp " REC "RSN763_LOMAP_GIL067.AT2 '%s/" LONG_A "' && cp " REC
           "RSN763_LOMAP_GIL337.AT2 '%s/" LONG_B "' && sed 's/^name = thin/name = " LONG_ARCH
           "/' arches/thin.cfg > '%s/long.cfg'",
           dir, dir, dir);
  if (!aq_check(aq_test_sh(cmd, out, sizeof out) == 0, "%s: %s", cmd, out))
    return 0;
  const char *jobs[4] = {
      "'%s/" LONG_A "' '%s/" LONG_B "' " REC "IELC180.AT2 --arch arches/thin.cfg --arch "
      "arches/bridge.cfg --arch '%s/long.cfg' --scale 1,2 --history -q -o '%s/m.h5'",
      "capacity '%s/" LONG_A "' '%s/" LONG_B "' " REC "IELC180.AT2 --arch arches/thin.cfg "
      "--arch '%s/long.cfg' --scale-max 3 -o '%s/c.h5' > /dev/null",
      "spectrum '%s/" LONG_A "' '%s/" LONG_B "' --components " REC
      "RSN6_IMPVALL.I_I-ELC180-hor1.AT2," REC "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 -o '%s/s.h5%s' "
      "> /dev/null",
      "select '%s/" LONG_A "' '%s/" LONG_B "' " REC "IELC180.AT2 " REC "ARL360.at2 " REC
      "CHY028-N.AT2 " REC "RSN4843_CHUETSU_65006NS.AT2 --target '%s/target#A.csv' "
      "--count 6 --scale-range 0.1,10 -o '%s/sel.h5' > /dev/null"};
  /* a target of a long name with a '#' in it (drawn as it is) */
  snprintf(cmd, sizeof cmd,
           "printf 'period_s,psa_g\\n0.01,0.3\\n0.15,0.75\\n0.5,0.75\\n2,0.19\\n4,0.05\\n' "
           "> '%s/target#A.csv'", dir);
  if (!aq_check(aq_test_sh(cmd, out, sizeof out) == 0, "%s: %s", cmd, out))
    return 0;
  for (int k = 0; k < 4; k++) {
    snprintf(cmd, sizeof cmd, jobs[k], dir, dir, dir, k == 2 ? "" : dir);
    int rc = aq_test_run(cmd, NULL, 0, err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit %d %s", cmd, rc, err))
      return 0;
  }
  /* every whole name the figures may shorten */
  snprintf(cmd, sizeof cmd,
           "printf '%%s\\n' '" LONG_A "' '" LONG_B "' IELC180.AT2 thin bridge '" LONG_ARCH
           "' RSN6_IMPVALL.I_I-ELC180-hor1.AT2 RSN6_IMPVALL.I_I-ELC270-hor2.AT2 "
           "'RSN6_IMPVALL.I_I-ELC{180-hor1,270-hor2}.AT2' ARL360.at2 CHY028-N.AT2 "
           "RSN4843_CHUETSU_65006NS.AT2 '%s/target#A.csv' > '%s/names.txt'",
           dir, dir);
  return aq_check(aq_test_sh(cmd, out, sizeof out) == 0, "names: %s", out);
}

AQ_TEST(plot_labels_every_figure)
{
  if (!have_tools())
    return;
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  if (!make_inputs(dir))
    return;
  /* name, then the plot command's arguments (%1$s the directory) */
  static const char *const fig[][2] = {
      {"history-collapse", "history %1$s/m.h5 --run 00000_000_000"},
      {"history-small", "history %1$s/m.h5 --run 00002_001_000"},
      {"arch", "arch --arch arches/bridge.cfg"},
      {"arch-deformed", "arch --arch arches/bridge.cfg --rotation 0.05"},
      {"arch-file", "arch %1$s/m.h5 --arch " LONG_ARCH},
      {"domain", "domain --arch arches/thin.cfg"},
      {"suite", "suite %1$s/m.h5"},
      {"capacity", "capacity %1$s/c.h5"},
      {"capacity-pga", "capacity %1$s/c.h5 --arch " LONG_ARCH " --y pga --x rad"},
      {"capacity-sa", "capacity %1$s/c.h5 --im sa_avg_0.1_1s_g"},
      {"spectrum", "spectrum %1$s/s.h5"},
      {"spectrum-select", "spectrum %1$s/sel.h5"}};
  enum { NFIG = sizeof fig / sizeof fig[0] };
  char list[8192], args[2048], a[1024], err[2048];
  size_t n = (size_t)snprintf(list, sizeof list, "--names '%s/names.txt'", dir);
  for (size_t i = 0; i < NFIG; i++) {
    snprintf(a, sizeof a, fig[i][1], dir);
    for (int k = 0; k < 2; k++) {
      snprintf(args, sizeof args, "plot %s -o '%s/%s.%s'", a, dir, fig[i][0], k ? "svg" : "pdf");
      int rc = aq_test_run(args, NULL, 0, err, sizeof err);
      aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
    }
    n += (size_t)snprintf(list + n, sizeof list - n, " '%s/%s.pdf' '%s/%s.svg'", dir, fig[i][0],
                          dir, fig[i][0]);
  }
  char cmd[9000];
  static char out[1 << 16];
  snprintf(cmd, sizeof cmd, "LC_ALL=C.UTF-8 /usr/bin/python3 tests/plot_labels.py %s", list);
  int rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0, "every figure's labels inside the page, apart, on no mark, each shortened "
                    "name one name's (exit %d):\n%s", rc, out);
  /* the suite's margin shortened the two names alike but for their middle
     (and told them apart, above) */
  const char *suite = strstr(out, "\nsuite: ");
  int npw = 0, nsw = 0, nshort = 0;
  if (suite)
    sscanf(suite, "\nsuite: %d words (PDF), %d words (SVG), %d shortened", &npw, &nsw, &nshort);
  aq_check(nshort >= 2, "the suite's names shortened: %d (%d words)", nshort, npw);
  /* a name with '#' drawn as it is, not "##" */
  snprintf(cmd, sizeof cmd, "pdftotext -raw '%s/spectrum-select.pdf' -", dir);
  rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0 && strstr(out, "#A.csv") && !strstr(out, "##"),
           "the target's name with its '#' once:\n%s", out);
}

/* The fragility's key is below its axis, on none of its data: every word
 * of it lies outside the band of the frame's y axis (from the tick label
 * 1.0 to the tick label 0.0 at its left), where the data are. */
AQ_TEST(plot_labels_capacity_key_off_the_data)
{
  if (!have_tools())
    return;
  char dir[512], args[2048], err[2048], cmd[1024];
  static char out[1 << 17];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "capacity " REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "IELC180.AT2 " REC
           "ARL360.at2 " REC "RSN763_LOMAP_GIL067.AT2 --arch arches/oppenheim.cfg "
           "--scale-max 30 -o '%s/c.h5' > /dev/null && %s plot capacity '%s/c.h5' -o '%s/c.pdf'",
           dir, aq_test_bin(), dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  snprintf(cmd, sizeof cmd, "pdftotext -bbox '%s/c.pdf' -", dir);
  if (!aq_check(aq_test_sh(cmd, out, sizeof out) == 0, "%s", cmd))
    return;
  double top = NAN, bottom = NAN, key = NAN;
  long nkey = 0, inside = 0;
  static const char *const keyw[] = {"lognormal", "confidence", "interval", "collapses",
                                     "(i/n)"};
  for (const char *p = strstr(out, "<word "); p; p = strstr(p + 1, "<word ")) {
    double y0 = strtod(strstr(p, "yMin=\"") + 6, NULL), y1 = strtod(strstr(p, "yMax=\"") + 6, NULL);
    const char *t = strchr(p, '>') + 1;
    double yc = 0.5 * (y0 + y1);
    if (!strncmp(t, "1.0<", 4))
      top = yc; /* the fragility's axis: the last 1.0 and 0.0 of the page */
    if (!strncmp(t, "0.0<", 4))
      bottom = yc;
    for (size_t k = 0; k < sizeof keyw / sizeof keyw[0]; k++)
      if (!strncmp(t, keyw[k], strlen(keyw[k])) && t[strlen(keyw[k])] == '<') {
        nkey++;
        key = yc;
      }
  }
  for (const char *p = strstr(out, "<word "); p; p = strstr(p + 1, "<word ")) {
    double y0 = strtod(strstr(p, "yMin=\"") + 6, NULL), y1 = strtod(strstr(p, "yMax=\"") + 6, NULL);
    const char *t = strchr(p, '>') + 1;
    for (size_t k = 0; k < sizeof keyw / sizeof keyw[0]; k++)
      if (!strncmp(t, keyw[k], strlen(keyw[k])) && t[strlen(keyw[k])] == '<')
        inside += 0.5 * (y0 + y1) > top && 0.5 * (y0 + y1) < bottom;
  }
  aq_check(nkey == 5 && top < bottom && inside == 0,
           "the fragility's key (%ld words, the last at y %.1f) outside its frame's band "
           "(y %.1f to %.1f): %ld inside", nkey, key, top, bottom, inside);
}

/* aq_plot_ellipsize_set: labels of at most max characters, each standing
 * for its own name only (its start before the ellipsis, its end after it,
 * a middle part between two ellipses found in it in order), the
 * distinguishing digits kept where the names differ only in the middle. */
static int stands_for(const char *label, const char *name)
{
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", label);
  const char *at = name;
  char *part = buf, *e;
  int first = 1;
  while (1) {
    e = strstr(part, "…");
    if (e)
      *e = '\0';
    size_t len = strlen(part);
    if (first) {
      if (strncmp(name, part, len) != 0)
        return 0;
      at = name + len;
    } else if (!e) {
      size_t nl = strlen(at);
      return nl >= len && strcmp(at + nl - len, part) == 0;
    } else {
      const char *k = strstr(at, part);
      if (!k)
        return 0;
      at = k + len;
    }
    if (!e)
      return strcmp(label, name) == 0;
    part = e + strlen("…");
    first = 0;
  }
}

static size_t chars(const char *s)
{
  size_t n = 0;
  for (; *s; s++)
    n += ((unsigned char)*s & 0xc0) != 0x80;
  return n;
}

AQ_TEST(plot_labels_shortened_names_distinct)
{
  static const char *const sets[][4] = {
      {"RSN763_LOMAP_GIL067.AT2", "RSN763_LOMAP_GIL337.AT2", "IELC180.AT2", NULL},
      {LONG_A, LONG_B, "Station_archive_of_the_2024_campaign_IELC180.AT2", NULL},
      {"same_name_twice_and_long_enough.AT2", "same_name_twice_and_long_enough.AT2",
       "another_name_as_long_as_the_first.AT2", NULL}};
  static const size_t max[] = {11, 30, 12};
  for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
    const char *const *names = sets[s];
    size_t n = 0;
    while (n < 4 && names[n])
      n++;
    char out[3][256];
    aq_plot_ellipsize_set(names, n, max[s], out[0], sizeof out[0]);
    for (size_t i = 0; i < n; i++) {
      size_t owners = 0;
      for (size_t j = 0; j < n; j++)
        owners += (j == i || strcmp(names[j], names[i]) != 0) && stands_for(out[i], names[j]);
      aq_check(chars(out[i]) <= max[s] && stands_for(out[i], names[i]) && owners == 1,
               "set %zu: \"%s\" shortened to \"%s\" (%zu characters, at most %zu) stands for "
               "it alone (%zu names)", s, names[i], out[i], chars(out[i]), max[s], owners);
    }
  }
  char out[2][256];
  const char *pair[2] = {LONG_A, LONG_B};
  aq_plot_ellipsize_set(pair, 2, 30, out[0], sizeof out[0]);
  aq_check(strstr(out[0], "067") && strstr(out[1], "337"),
           "names alike but for their middle show it: \"%s\", \"%s\"", out[0], out[1]);
}

/* A key shortens a name only when the names do not fit whole: plot
 * spectrum of a select file (the target, 90 %, the mean and six records:
 * two columns) and of a spectrum file of nine records (two columns), every
 * name at most 32 characters, the target "ec8:type=1,ground=B,ag=0.25":
 * each written whole in the PDF (pdftotext), no ellipsis anywhere. */
AQ_TEST(plot_labels_key_whole_where_it_fits)
{
  if (!have_tools())
    return;
  char dir[512], args[8192], err[2048], cmd[1024];
  static char out[1 << 16];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const rec[] = {
      "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
      "RSN77_SFERN_PUL164-hor1.AT2", "RSN4843_CHUETSU_65006NS.AT2",
      "RSN4013_SANSIMEO_36258021.AT2", "RSN763_LOMAP_GIL067.AT2", "RSN763_LOMAP_GIL337.AT2",
      "RSN1616_DUZCE_362-E.AT2", "ARL360.at2"};
  enum { NREC = sizeof rec / sizeof rec[0] };
  char pool[2048];
  size_t n = 0;
  for (size_t i = 0; i < NREC; i++)
    n += (size_t)snprintf(pool + n, sizeof pool - n, REC "%s ", rec[i]);
  snprintf(args, sizeof args,
           "select %s--target ec8:type=1,ground=B,ag=0.25 --count 6 --scale-range 0.1,10 "
           "-o '%s/sel.h5' > /dev/null && %s spectrum %s-o '%s/s.h5' > /dev/null",
           pool, dir, aq_test_bin(), pool, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  static const char *const file[] = {"sel", "s"};
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, "plot spectrum '%s/%s.h5' -o '%s/%s.pdf'", dir, file[k], dir,
             file[k]);
    rc = aq_test_run(args, NULL, 0, err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
      continue;
    snprintf(cmd, sizeof cmd, "pdftotext -raw '%s/%s.pdf' -", dir, file[k]);
    rc = aq_test_sh(cmd, out, sizeof out);
    size_t whole = 0;
    for (size_t i = 0; i < NREC; i++)
      whole += strstr(out, rec[i]) != NULL;
    aq_check(rc == 0 && !strstr(out, "…") && whole >= (k ? NREC : 6) &&
                 (k || strstr(out, "target ec8:type=1,ground=B,ag=0.25")),
             "plot spectrum of the %s file: every name whole (%zu of the records, no "
             "ellipsis):\n%s", k ? "spectrum" : "select", whole, out);
  }
}

/* The capacity figure's scale axis ticks outwards, off the strips: the
 * last strip ends a few points above the axis, and ticks drawn inwards
 * crossed it.  Two records far apart in strength (CHY028 and RSN1616), so
 * that each strip spans less of the axis than 40 % of the width.  The SVG
 * drawn without its text (tests/plot_labels.py): the axis the topmost
 * line dark over 40 % of the width; its tick marks the dark columns 3 and 4
 * pixels below it; at most a fifth of them also dark 3 and 4 pixels above
 * it (where a verdict's change line may reach the axis). */
AQ_TEST(plot_labels_capacity_ticks_off_the_strips)
{
  if (!have_tools())
    return;
  char dir[512], args[2048], err[2048], cmd[2048];
  static char out[1 << 12];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "capacity " REC "CHY028-N.AT2 " REC "RSN1616_DUZCE_362-E.AT2 --arch arches/thin.cfg "
           "-o '%s/c.h5' > /dev/null && %s plot capacity '%s/c.h5' -o '%s/c.svg'",
           dir, aq_test_bin(), dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import sys, tempfile\n"
           "sys.path.insert(0, 'tests')\n"
           "import plot_labels as L\n"
           "img = L.raster_without_text(sys.argv[1], tempfile.mkdtemp()).astype(int)\n"
           "h, w, _ = img.shape\n"
           "dark = img.max(axis=2) < 100\n"
           "y = min(y for y in range(h) if dark[y].sum() > 0.4 * w)\n"
           "xs = dark[y].nonzero()[0]\n"
           "s = slice(xs.min() + 3, xs.max() - 3)\n"
           "below = dark[y + 3, s] & dark[y + 4, s]\n"
           "above = dark[y - 3, s] & dark[y - 4, s]\n"
           "nb, both = int(below.sum()), int((below & above).sum())\n"
           "print('axis at y %%d: %%d tick columns below it, %%d also marked above it' %% (y, nb, both))\n"
           "sys.exit(0 if nb >= 5 and both <= 0.2 * nb else 1)\n"
           "\" '%s/c.svg'",
           dir);
  rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0, "the scale axis' ticks outwards, off the strips: %s", out);
}
