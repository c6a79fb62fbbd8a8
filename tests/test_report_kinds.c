/* test_report_kinds.c: the report of every kind of results file, its
 * options in words, and the fragility's rank with what it orders.
 *   - a spectrum file alone: its spectra, a figure and a table whose PSA
 *     are `archquake spectrum`'s (its TSV, read here);
 *   - a capacity file alone: its section and its run (records, arches);
 *   - files in any order, each in its section; two results files refused;
 *   - the options table: no "nan", a word for each value that does not
 *     apply;
 *   - --fragility, capacity/fragility and the report: the quantity the
 *     rank orders, beta over the power of the scale its IM grows with
 *     (Arias intensity: beta / 2; the others beta), the ranks in its
 *     order;
 *   - the records of capacity and spectrum files identified by their
 *     SHA-256 (sha256sum's). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/"
#define PAIR REC "RSN6_IMPVALL.I_I-ELC180-hor1.AT2," REC "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"

static char big[1 << 20];

static int run(const char *args, char *out, size_t cap)
{
  char err[2048];
  int rc = aq_test_run(args, out, cap, err, sizeof err);
  return aq_check(rc == 0, "%s: exit %d %s", args, rc, err);
}

/* The number in the data-v of the td after the n-th occurrence of marker
 * in html, or NAN. */
static double cell_after(const char *html, const char *marker, int skip)
{
  const char *p = strstr(html, marker);
  for (int i = 0; p && i <= skip; i++)
    p = strstr(p + 1, "data-v=\"");
  return p ? strtod(p + 8, NULL) : NAN;
}

AQ_TEST(report_kinds_spectrum_alone)
{
  char dir[512], a[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a, "spectrum " REC "ARL360.at2 --components " PAIR " -o %s/s.h5", dir);
  if (!run(a, big, sizeof big))
    return;
  /* the spectrum's TSV: ARL360.at2's PSA at 1 s (5 % damping) */
  double want = NAN;
  for (const char *l = big; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
    char rec[512];
    double d, t, psa;
    if (sscanf(l, "%511s %*s %lf %lf %lf", rec, &d, &t, &psa) == 4 &&
        strstr(rec, "ARL360.at2") && !strchr(rec, ',') && d == 0.05 && t == 1)
      want = psa;
  }
  snprintf(a, sizeof a, "report %s/s.h5 -o %s/s.html", dir, dir);
  if (!run(a, NULL, 0))
    return;
  snprintf(a, sizeof a, "%s/s.html", dir);
  char *h = aq_test_read_file(a, NULL);
  aq_check(h && strstr(h, "<h2 id=\"spectrum-0\">Spectra: s.h5</h2>") &&
               strstr(h, "aria-label=\"response spectra of s.h5\"") &&
               strstr(h, "<b>3</b> records") && !strstr(h, "<b>0</b> runs"),
           "a spectrum file alone: its section, its figure, its 3 records, no empty run count");
  /* the table: the curve of ARL360.at2 (its channel 360), PSA at 1 s */
  int col = -1, k = 0;
  const char *head = h ? strstr(h, "<th>peak PSA (g)</th>") : NULL;
  for (const char *th = head; th && strncmp(th, "</tr>", 5); th = strstr(th + 1, "<th>"), k++)
    if (!strncmp(th, "<th>PSA at 1 s (g)</th>", 22))
      col = k;
  double got = h && col >= 0 ? cell_after(h, "<td>360</td>", 1 + col) : NAN;
  aq_check(col >= 0 && got == want, "ARL360.at2's PSA at 1 s in the table %.17g, the TSV's %.17g",
           got, want);
  aq_check(h && strstr(h, "<td>RotD50</td>") && strstr(h, "<td>GeoMean</td>"),
           "the pair's RotD50 and GeoMean curves in the table");
  free(h);
}

AQ_TEST(report_kinds_capacity_alone_and_any_order)
{
  char dir[512], a[4096], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a,
           "capacity " REC "ARL360.at2 " REC "RSN77_SFERN_PUL164-hor1.AT2 --arch arches/thin.cfg "
           "--scale-max 3 -o %s/c.h5",
           dir);
  if (!run(a, big, sizeof big))
    return;
  snprintf(a, sizeof a, REC "ARL360.at2 --arch arches/thin.cfg -q -o %s/m.h5", dir);
  if (!run(a, big, sizeof big))
    return;
  snprintf(a, sizeof a, "spectrum " REC "ARL360.at2 -o %s/s.h5", dir);
  if (!run(a, big, sizeof big))
    return;
  snprintf(a, sizeof a, "report %s/c.h5 -o %s/c.html", dir, dir);
  if (run(a, NULL, 0)) {
    snprintf(a, sizeof a, "%s/c.html", dir);
    char *h = aq_test_read_file(a, NULL);
    aq_check(h && strstr(h, "<h2 id=\"capacity-0\">Capacity: c.h5</h2>") &&
                 strstr(h, "<h3 id=\"records\">Records (2)</h3>") &&
                 strstr(h, "<h3 id=\"arches\">Arches (1)</h3>") && !strstr(h, "Overview"),
             "a capacity file alone: its section, its records and arch, no verdict map");
    free(h);
  }
  /* in any order: the results file's sections first */
  snprintf(a, sizeof a, "report %s/s.h5 %s/c.h5 %s/m.h5 -o %s/all.html", dir, dir, dir, dir);
  if (run(a, NULL, 0)) {
    snprintf(a, sizeof a, "%s/all.html", dir);
    char *h = aq_test_read_file(a, NULL);
    const char *o = h ? strstr(h, "id=\"overview\"") : NULL, *s = h ? strstr(h, "id=\"spectrum-0\"") : NULL,
               *c = h ? strstr(h, "id=\"capacity-1\"") : NULL;
    aq_check(o && s && c && o < s && s < c, "the results, then the others as given");
    free(h);
  }
  snprintf(a, sizeof a, "report %s/m.h5 %s/c.h5 %s/m.h5 -o %s/two.html", dir, dir, dir, dir);
  int rc = aq_test_run(a, NULL, 0, err, sizeof err);
  snprintf(a, sizeof a, "%s/two.html", dir);
  FILE *f = fopen(a, "r");
  aq_check(rc == 1 && strstr(err, "m.h5: expected at most one results file") && !f,
           "two results files: exit %d, no page: %s", rc, err);
  if (f)
    fclose(f);
}

/* The options that do not apply, in words: a results file of the
 * defaults (no --cor, no low-pass, no --dt, --scale); the flags (filter,
 * history, store_records) as yes or no, not 1 or 0. */
AQ_TEST(report_kinds_options_in_words)
{
  char dir[512], a[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a, REC "ARL360.at2 --arch arches/thin.cfg -q -o %s/m.h5", dir);
  if (!run(a, big, sizeof big))
    return;
  snprintf(a, sizeof a, "report %s/m.h5 -o %s/m.html", dir, dir);
  if (!run(a, NULL, 0))
    return;
  snprintf(a, sizeof a, "%s/m.html", dir);
  char *h = aq_test_read_file(a, NULL);
  const char *o = h ? strstr(h, "Processing and run options") : NULL;
  const char *e = o ? strstr(o, "</table>") : NULL;
  char opts[8192] = "";
  if (o && e)
    snprintf(opts, sizeof opts, "%.*s", (int)(e - o), o);
  aq_check(opts[0] && !strstr(opts, ">nan<"), "no nan in the options: %.2000s", opts);
  static const char *const want[][2] = {
      {"cor", "per arch (each arch's own [dynamics] cor)"},
      {"lowpass_hz", "off"},
      {"dt_override_s", "none (each file's own interval)"},
      {"scale_to_pga_g", "none"},
      {"scale_to_lambda0", "none"},
      {"filter", "yes"},
      {"history", "no"},
      {"store_records", "no"}};
  for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
    char row[256];
    snprintf(row, sizeof row, "<td class=\"mono\">%s</td><td>%s</td>", want[k][0], want[k][1]);
    /* the page escapes the apostrophe */
    char esc[300];
    size_t n = 0;
    for (const char *p = row; *p && n + 6 < sizeof esc; p++)
      n += (size_t)(*p == '\'' ? snprintf(esc + n, sizeof esc - n, "&#39;")
                               : snprintf(esc + n, sizeof esc - n, "%c", *p));
    aq_check(strstr(opts, row) || strstr(opts, esc), "%s: \"%s\"", want[k][0], want[k][1]);
  }
  free(h);
}

/* --fragility's beta_per_power and rank; capacity/fragility's; the
 * report's table in rank order with both. */
AQ_TEST(report_kinds_rank_follows_what_it_orders)
{
  char dir[512], a[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a,
           "capacity " REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "IELC180.AT2 " REC "ARL360.at2 " REC
           "RSN763_LOMAP_GIL067.AT2 --arch arches/oppenheim.cfg --scale-max 30 --fragility "
           "%s/f.tsv -o %s/c.h5",
           dir, dir);
  if (!run(a, big, sizeof big))
    return;
  snprintf(a, sizeof a, "%s/f.tsv", dir);
  char *t = aq_test_read_file(a, NULL);
  char buf[64];
  aq_check(t && !strcmp(aq_test_tsv_field(t, 0, 9, buf, sizeof buf), "beta_per_power"),
           "--fragility's last column: %s", buf);
  double ranked[16];
  int rank[16], n = 0, ok = 1;
  for (int row = 1; t && row < 17; row++) {
    char im[64], b[64], r[64], q[64];
    aq_test_tsv_field(t, row, 1, im, sizeof im);
    if (!im[0])
      break;
    double beta = strtod(aq_test_tsv_field(t, row, 5, b, sizeof b), NULL);
    rank[n] = atoi(aq_test_tsv_field(t, row, 8, r, sizeof r));
    ranked[n] = strtod(aq_test_tsv_field(t, row, 9, q, sizeof q), NULL);
    double want = strcmp(im, "arias_m_s") == 0 ? beta / 2 : beta; /* its power of the scale */
    ok &= aq_check(ranked[n] == want, "%s: beta_per_power %.17g, beta %.17g", im, ranked[n], beta);
    n++;
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      if (rank[i] < rank[j])
        ok &= aq_check(ranked[i] <= ranked[j], "rank %d (%.6g) before rank %d (%.6g)", rank[i],
                       ranked[i], rank[j], ranked[j]);
  aq_check(n == 10 && ok, "%d measures ranked by beta_per_power", n);
  free(t);
  /* the file: capacity/fragility/beta_per_power */
  snprintf(a, sizeof a,
           "/usr/bin/python3 -c \"import h5py, sys\n"
           "g = h5py.File(sys.argv[1], 'r')['capacity/fragility']\n"
           "for im, b, q in zip(g['im'][:], g['beta'][:], g['beta_per_power'][:]):\n"
           "    assert q == (b / 2 if im in (b'arias_m_s', 'arias_m_s') else b), (im, b, q)\n"
           "assert g['beta_per_power'].attrs['units'] == b'1'\n"
           "\" %s/c.h5",
           dir);
  aq_check(system(a) == 0, "capacity/fragility/beta_per_power read with h5py");
  /* the report: the table in rank order, both columns */
  snprintf(a, sizeof a, "report %s/c.h5 -o %s/c.html", dir, dir);
  if (!run(a, NULL, 0))
    return;
  snprintf(a, sizeof a, "%s/c.html", dir);
  char *h = aq_test_read_file(a, NULL);
  const char *tab = h ? strstr(h, "<th>ranked by: β per power of the scale</th>") : NULL;
  int last = 0, rows = 0, inorder = 1;
  for (const char *p = tab ? strstr(tab, "<tr><td class=\"n\">") : NULL; p && rows < 10;
       p = strstr(p + 1, "<tr><td class=\"n\">")) {
    int r = atoi(p + 18);
    inorder &= r == last + 1;
    last = r;
    rows++;
  }
  aq_check(tab && rows == 10 && inorder, "the report's ranking: %d rows in rank order (%d)",
           rows, inorder);
  free(h);
}

/* capacity and spectrum files identify their records by SHA-256 too. */
AQ_TEST(report_kinds_records_hashed)
{
  char dir[512], a[2048], sum[256];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a,
           "capacity " REC "ARL360.at2 --arch arches/thin.cfg --scale-max 2 -o %s/c.h5 > "
           "/dev/null && %s spectrum " REC "ARL360.at2 -o %s/s.h5",
           dir, aq_test_bin(), dir);
  if (!run(a, big, sizeof big))
    return;
  aq_test_sh("sha256sum " REC "ARL360.at2", sum, sizeof sum);
  for (int k = 0; k < 2; k++) {
    snprintf(a, sizeof a,
             "/usr/bin/python3 -c \"import h5py, sys\n"
             "print(h5py.File(sys.argv[1], 'r')['records'][0]['sha256'].decode())\n"
             "\" %s/%s.h5",
             dir, k ? "s" : "c");
    char got[128] = "";
    aq_test_sh(a, got, sizeof got);
    aq_check(strlen(got) >= 64 && strlen(sum) >= 64 && !strncmp(got, sum, 64), "%s file: sha256 %.64s, sha256sum %s",
             k ? "spectrum" : "capacity", got, sum);
  }
}
