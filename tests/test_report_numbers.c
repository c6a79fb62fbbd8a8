/* test_report_numbers.c: every double archquake prints is the shortest
 * decimal that reads back to the same double (docs/tsv.md, "Numbers").
 *
 * The reference is Python's repr() of a float, the shortest string that
 * round-trips (Python 3.1+, David Gay's algorithm), not archquake's
 * formatter: a printed number passes when it has no more significant
 * digits than repr() of the double it reads as.  The main job's TSV is
 * also read against its results file through h5py: each number reads
 * back to the double the file holds.  Checked: the main job's TSV,
 * capacity's TSV and --fragility, spectrum's TSV, mechanism, domain,
 * pulse and info, select's suite file, every figure's --data CSV (the
 * suite's figure included), the report (its options table
 * and the data-v of its number cells), and compare's rows of the files'
 * settings (HDF5 attributes as text); `compare --rtol 0 --atol 0` of two
 * runs of one job still finds nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/"
#define ARCHES "arches/"

/* The checker: python3 shortest_check.py MODE FILE [MODE FILE ...]; MODE tsv
 * (tab-separated, header first), csv (comma-separated, '#' lines and
 * blank lines skipped), html (the report), h5tsv:H5 (a main-job TSV and
 * its results file), info:H5 (info's TSV and the /records table of a main
 * job on the same records), mech:H5 (mechanism's TSV and the first arch of
 * a main job on the same arch).  Prints one line per offending number (at most 5 a
 * file) and exits 1 if any. */
static const char CHECKER[] =
    "import csv, math, re, sys\n"
    "NUM = re.compile(r'[-+]?(?:\\d+\\.?\\d*|\\.\\d+)(?:[eE][-+]?\\d+)?|[-+]?inf|nan')\n"
    "def sig(s):\n"
    "    m = s.lstrip('+-').lower().split('e')[0].replace('.', '').lstrip('0').rstrip('0')\n"
    "    return max(len(m), 1)\n"
    "bad = 0\n"
    "def check(where, s):\n"
    "    global bad\n"
    "    x = float(s)\n"
    "    if math.isnan(x) or math.isinf(x):\n"
    "        ok = s in ('nan', 'inf', '-inf')\n"
    "    else:\n"
    "        ok = sig(s) <= sig(repr(x))\n"
    "    if not ok:\n"
    "        bad += 1\n"
    "        if bad <= 12:\n"
    "            print('%s: %r is not the shortest that reads back (%r)' % (where, s, repr(x)))\n"
    "    return ok\n"
    "def cells(where, rows):\n"
    "    n = 0\n"
    "    for i, row in enumerate(rows):\n"
    "        for j, c in enumerate(row):\n"
    "            if NUM.fullmatch(c):\n"
    "                check('%s:%d:%d' % (where, i + 1, j + 1), c); n += 1\n"
    "            elif re.fullmatch(r'[0-9.e+-]+(?:-[0-9.e+inf]+)?(?:;[0-9.e+-]+-[0-9.e+inf]+)*', c):\n"
    "                for t in re.findall(r'\\d[0-9.]*(?:e[-+]\\d+)?|inf', c):\n"
    "                    check('%s:%d:%d' % (where, i + 1, j + 1), t); n += 1\n"
    "    return n\n"
    "total = 0\n"
    "args = sys.argv[1:]\n"
    "for mode, path in zip(args[::2], args[1::2]):\n"
    "    text = open(path, encoding='utf-8').read()\n"
    "    if mode == 'tsv' or mode.startswith('h5tsv:'):\n"
    "        rows = [l.split('\\t') for l in text.splitlines()]\n"
    "        total += cells(path, rows[1:])\n"
    "        if mode.startswith('h5tsv:'):\n"
    "            import h5py\n"
    "            t = h5py.File(mode[6:], 'r')['summary'][:]\n"
    "            head = rows[0]\n"
    "            assert len(rows) - 1 == len(t), (len(rows), len(t))\n"
    "            for i, row in enumerate(rows[1:]):\n"
    "                for j, name in enumerate(head):\n"
    "                    v = t[name][i]\n"
    "                    if isinstance(v, bytes) or name in ('collapsed', 'impacts', 'mu_demand_joint',\n"
    "                                                       'check_collapsed'):\n"
    "                        continue\n"
    "                    x = float(row[j])\n"
    "                    if not (x == v or (math.isnan(x) and math.isnan(v))):\n"
    "                        bad += 1\n"
    "                        print('%s:%d: %s %r reads as %r, the file holds %r' %\n"
    "                              (path, i + 2, name, row[j], x, float(v)))\n"
    "    if mode.startswith('info:') or mode.startswith('mech:'):\n"
    "        import h5py\n"
    "        f = h5py.File(mode[5:], 'r')\n"
    "        rows = [l.split('\\t') for l in text.splitlines()]\n"
    "        total += cells(path, rows[1:])\n"
    "        head = rows[0]\n"
    "        if mode.startswith('info:'):\n"
    "            recs = f['records'][:]\n"
    "            want = {r['source_file'].decode(): r for r in recs}\n"
    "            pairs = [(row[0], n, n) for row in rows[1:] for n in\n"
    "                     ('pga_g', 'pgv_m_s', 'pgd_m', 'arias_m_s', 'd5_95_s', 'cav_m_s', 'dt_s')]\n"
    "            get = lambda key, n: float(want[key][n])\n"
    "        else:\n"
    "            a = f['arches/000'].attrs\n"
    "            pairs = [(row[0], n, row[0] + '_' + n) for row in rows[1:]\n"
    "                     if row[0] in ('primary', 'reverse') for n in ('lambda0', 'q_c_rad', 'mass_kg')]\n"
    "            get = lambda key, n: float(a[n])\n"
    "        for key, col, src in pairs:\n"
    "            row = [r for r in rows[1:] if r[0] == key][0]\n"
    "            x = float(row[head.index(col)])\n"
    "            v = get(key, src)\n"
    "            if x != v:\n"
    "                bad += 1\n"
    "                print('%s: %s %s %r reads as %r, the results file holds %r' %\n"
    "                      (path, key, col, row[head.index(col)], x, v))\n"
    "    elif mode == 'csv':\n"
    "        lines = [l for l in text.splitlines() if l and not l.startswith('#')]\n"
    "        total += cells(path, csv.reader(lines))\n"
    "    elif mode == 'html':\n"
    "        for v in re.findall(r'data-v=\"([^\"]*)\"', text):\n"
    "            if v != 'NaN':\n"
    "                check(path + ': data-v', v); total += 1\n"
    "        opts = text[text.find('Processing and run options'):]\n"
    "        opts = opts[:opts.find('</table>')]\n"
    "        for name, v in re.findall(r'<tr><td class=\"mono\">([^<]*)</td><td>([^<]*)</td>', opts):\n"
    "            for t in v.split(', '):\n"
    "                if NUM.fullmatch(t):\n"
    "                    check(path + ': option ' + name, t); total += 1\n"
    "print('%d numbers checked, %d not the shortest' % (total, bad))\n"
    "sys.exit(1 if bad or total == 0 else 0)\n";

/* Run the checker on its arguments; 1 if every number passed. */
static int numbers_ok(const char *dir, const char *args, const char *what)
{
  char py[600], cmd[8192];
  snprintf(py, sizeof py, "%s/shortest_check.py", dir);
  FILE *f = fopen(py, "w");
  if (!aq_check(f != NULL, "write %s", py))
    return 0;
  fputs(CHECKER, f);
  fclose(f);
  snprintf(cmd, sizeof cmd, "/usr/bin/python3 '%s' %s", py, args);
  char out[4096] = "";
  int rc = aq_test_sh(cmd, out, sizeof out);
  return aq_check(rc == 0, "%s: %s", what, out);
}

/* Run the CLI with args, its stdout into the file tsv; 1 if it exited 0. */
static int run_to(const char *args, const char *tsv)
{
  enum { CAP = 1 << 22 };
  char err[2048], *out = malloc(CAP);
  int rc = out ? aq_test_run(args, out, CAP, err, sizeof err) : -1;
  FILE *f = rc == 0 ? fopen(tsv, "w") : NULL;
  if (f) {
    fputs(out, f);
    fclose(f);
  }
  free(out);
  return aq_check(rc == 0 && f, "%s: exit %d %s", args, rc, rc ? err : "");
}

/* The main job at --scale 0.8 (printed 0.80000000000000004 by %.17g):
 * its TSV against Python's shortest repr and against its results file. */
AQ_TEST(report_numbers_main_tsv_shortest)
{
  char dir[512], args[2048], tsv[600], h5[600], py[1400];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(tsv, sizeof tsv, "%s/m.tsv", dir);
  snprintf(h5, sizeof h5, "%s/m.h5", dir);
  snprintf(args, sizeof args,
           REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "ARL360.at2 --arch " ARCHES "thin.cfg --arch " ARCHES
           "oppenheim.cfg --scale 0.8,1.3 --polarity both -o %s",
           h5);
  if (!run_to(args, tsv))
    return;
  char field[64], *text = aq_test_read_file(tsv, NULL);
  aq_check(text && strcmp(aq_test_tsv_field(text, 1, 3, field, sizeof field), "0.8") == 0,
           "--scale 0.8 printed \"%s\"", field);
  free(text);
  snprintf(py, sizeof py, "h5tsv:%s %s", h5, tsv);
  numbers_ok(dir, py, "main job TSV");
}

/* capacity (TSV, --fragility), spectrum, mechanism, domain, pulse, info. */
AQ_TEST(report_numbers_commands_shortest)
{
  char dir[512], a[2048], f[8][600], list[6000];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const name[8] = {"cap", "frag", "spec", "mech", "dom", "pulse", "info", "x"};
  for (int i = 0; i < 8; i++)
    snprintf(f[i], sizeof f[i], "%s/%s.tsv", dir, name[i]);
  snprintf(a, sizeof a,
           "capacity " REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "ARL360.at2 " REC
           "IELC180.AT2 --arch " ARCHES "thin.cfg --scale-max 3 --fragility %s",
           f[1]);
  int ok = run_to(a, f[0]);
  ok &= run_to("spectrum " REC "ARL360.at2 --damping 0.02,0.05 --periods 0.1,0.3,1.7", f[2]);
  ok &= run_to("mechanism --arch " ARCHES "oppenheim.cfg --table --points 7", f[3]);
  /* the same arch and records in a results file, for what info and
     mechanism print */
  char x[2048];
  snprintf(x, sizeof x, REC "ARL360.at2 " REC "IELC180.AT2 --arch " ARCHES "oppenheim.cfg -o %s/x.h5",
           dir);
  ok &= run_to(x, f[7]);
  ok &= run_to("domain --arch " ARCHES "thin.cfg --ratios 1.3,2.7", f[4]);
  ok &= run_to("pulse --arch " ARCHES "thin.cfg --accel-g 0.3 --duration 0.7", f[5]);
  ok &= run_to("info " REC "ARL360.at2 " REC "IELC180.AT2", f[6]);
  if (!ok)
    return;
  size_t n = 0;
  for (int i = 0; i < 7; i++)
    n += (size_t)snprintf(list + n, sizeof list - n, " %s%s%s '%s'",
                          i == 3 ? "mech:" : i == 6 ? "info:" : "tsv", i == 3 || i == 6 ? dir : "",
                          i == 3 || i == 6 ? "/x.h5" : "", f[i]);
  numbers_ok(dir, list, "capacity, --fragility, spectrum, mechanism, domain, pulse, info");
}

/* Every figure's --data, the report, and compare's settings rows. */
AQ_TEST(report_numbers_data_report_compare)
{
  char dir[512], a[4096], h5[2][600], cap[600], sp[600], list[8000], out[8192], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  for (int k = 0; k < 2; k++) {
    snprintf(h5[k], sizeof h5[k], "%s/r%d.h5", dir, k);
    snprintf(a, sizeof a,
             REC "RSN77_SFERN_PUL164-hor1.AT2 --arch " ARCHES "thin.cfg --arch " ARCHES
             "oppenheim.cfg --scale 0.7,1.9 --taper %s --history --store-records -q -o %s",
             k ? "0.1" : "0.05", h5[k]);
    int rc = aq_test_run(a, NULL, 0, err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit %d %s", a, rc, err))
      return;
  }
  snprintf(cap, sizeof cap, "%s/c.h5", dir);
  snprintf(sp, sizeof sp, "%s/s.h5", dir);
  snprintf(a, sizeof a,
           "capacity " REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "ARL360.at2 --arch " ARCHES
           "thin.cfg --scale-max 3 -o %s > /dev/null && %s spectrum " REC
           "ARL360.at2 --periods 0.1,0.3,1.7 -o %s > /dev/null",
           cap, aq_test_bin(), sp);
  int rc = aq_test_run(a, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", a, rc, err))
    return;
  static const char *const fig[][2] = {
      {"history", "R"}, {"suite", "R"}, {"arch", "R"}, {"capacity", "C"}, {"spectrum", "S"},
      {"domain", "--arch " ARCHES "thin.cfg --ratios 1.3,2.7"}};
  size_t n = 0;
  for (size_t i = 0; i < sizeof fig / sizeof fig[0]; i++) {
    const char *in = fig[i][1][0] == 'R' ? h5[0] : fig[i][1][0] == 'C' ? cap
                     : fig[i][1][0] == 'S' ? sp : fig[i][1];
    snprintf(a, sizeof a, "plot %s %s -o %s/%s.svg --data %s/%s.csv", fig[i][0], in, dir,
             fig[i][0], dir, fig[i][0]);
    rc = aq_test_run(a, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "%s: exit %d %s", a, rc, err);
    n += (size_t)snprintf(list + n, sizeof list - n, " csv '%s/%s.csv'", dir, fig[i][0]);
  }
  snprintf(a, sizeof a, "report %s %s -o %s/report.html", h5[0], cap, dir);
  rc = aq_test_run(a, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "%s: exit %d %s", a, rc, err);
  snprintf(list + n, sizeof list - n, " html '%s/report.html'", dir);
  numbers_ok(dir, list, "--data of every figure, the report");
  /* the files' settings, as compare reads them from the root attributes */
  snprintf(a, sizeof a, "compare %s %s --rtol 0 --atol 0", h5[0], h5[1]);
  rc = aq_test_run(a, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "\ttaper_frac\t0.05\t0.1\t"),
           "compare: the settings' row taper_frac 0.05 0.1 (exit %d): %.600s", rc, out);
}

/* compare --rtol 0 --atol 0 of two runs of one job: no difference. */
AQ_TEST(report_numbers_compare_rtol0_identical)
{
  char dir[512], a[2048], out[4096], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  for (int k = 0; k < 2; k++) {
    snprintf(a, sizeof a,
             REC "RSN77_SFERN_PUL164-hor1.AT2 " REC "ARL360.at2 --arch " ARCHES
             "thin.cfg --scale 0.8,1.3 -q -j %d -o %s/%c.h5 > %s/%c.tsv",
             k + 1, dir, 'a' + k, dir, 'a' + k);
    int rc = aq_test_run(a, NULL, 0, err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit %d %s", a, rc, err))
      return;
  }
  snprintf(a, sizeof a, "compare %s/a.h5 %s/b.h5 --rtol 0 --atol 0", dir, dir);
  int rc = aq_test_run(a, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 1,
           "compare --rtol 0 --atol 0 of one job twice: exit %d, %zu lines: %.400s", rc,
           aq_test_count_lines(out), out);
}

/* select's suite file (--text: its scales and misfits) and the --data of
 * the suite's figure (the target, the mean, each record at its scale),
 * printed %.17g before (a misfit 0.019666248818411475 has a 16-digit
 * shortest, 0.01966624881841148 or so: about half of such doubles do). */
AQ_TEST(report_numbers_select_shortest)
{
  char dir[512], a[4096], err[2048], list[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a,
           "select " REC "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 " REC "RSN763_LOMAP_GIL067.AT2 " REC
           "ARL360.at2 " REC "CHY028-N.AT2 " REC "RSN4843_CHUETSU_65006NS.AT2 " REC
           "IELC180.AT2 --target ec8:type=1,ground=B,ag=0.25 --count 4 --scale-range 0.1,10 "
           "--text %s/suite.tsv -o %s/s.h5 > /dev/null && %s plot spectrum %s/s.h5 -o %s/s.svg "
           "--data %s/s.csv",
           dir, dir, aq_test_bin(), dir, dir, dir);
  int rc = aq_test_run(a, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", a, rc, err))
    return;
  snprintf(list, sizeof list, " tsv '%s/suite.tsv' csv '%s/s.csv'", dir, dir);
  numbers_ok(dir, list, "select's suite file, the suite figure's --data");
}
