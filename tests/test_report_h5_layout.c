/* test_report_h5_layout.c: every kind of results file held to
 * docs/hdf5-layout.md.
 *
 * tests/h5_layout.py reads the layout's tables and walks a file with h5py
 * (an independent reader): every group, dataset, attribute and compound
 * column must be documented there with its type, units and columns, and a
 * name with a unit suffix must carry that unit.  Files of each kind: the
 * main job (a circular, an elliptical arch with fill and a point mass, a
 * joints arch; both polarities, two scales, --history, --store-records,
 * and a --components motion at its azimuths), capacity (with a joints
 * arch) and spectrum (a record and a pair).  A column, dataset or
 * attribute added by anyone must be documented, or this test fails and
 * says in which table.  Besides: what a kind of file must not hold (a
 * spectrum file no /summary or /arches, a capacity file no /summary or run
 * scale options), and an arch's SHA-256 checked against its texts in the
 * file and against the files on disk (sha256sum). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/"
#define PAIR REC "RSN6_IMPVALL.I_I-ELC180-hor1.AT2," REC "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"

/* The three kinds of file in dir: m.h5 (main job), az.h5 (a --components
 * motion), c.h5 (capacity), s.h5 (spectrum).  1 if all were written. */
static int make_files(const char *dir)
{
  char a[4096], err[2048];
  const char *jobs[4] = {
      REC "ARL360.at2 " REC "IELC180.AT2 --arch arches/thin.cfg --arch arches/bridge.cfg --arch "
          "arches/vertical.cfg --polarity both --scale 0.5,2 --history --store-records -q -o "
          "%s/m.h5",
      "--components " PAIR " --arch arches/bridge.cfg --history -q -o %s/az.h5",
      "capacity " REC "ARL360.at2 " REC "IELC180.AT2 --arch arches/thin.cfg --arch "
      "arches/vertical.cfg --scale-max 3 -o %s/c.h5 > /dev/null",
      "spectrum " REC "ARL360.at2 --components " PAIR " -o %s/s.h5 > /dev/null"};
  for (int k = 0; k < 4; k++) {
    snprintf(a, sizeof a, jobs[k], dir);
    int rc = aq_test_run(a, NULL, 0, err, sizeof err);
    if (!aq_check(rc == 0, "%s: exit %d %s", a, rc, err))
      return 0;
  }
  return 1;
}

static char out[1 << 16];

AQ_TEST(report_h5_layout_every_kind_documented)
{
  char dir[512], cmd[4096];
  aq_test_tmpdir(dir, sizeof dir);
  if (!make_files(dir))
    return;
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 tests/h5_layout.py docs/hdf5-layout.md %s/m.h5 %s/az.h5 %s/c.h5 "
           "%s/s.h5",
           dir, dir, dir, dir);
  int rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0 && strstr(out, " 0 faults"),
           "every object of a results, capacity and spectrum file as docs/hdf5-layout.md "
           "documents it (exit %d):\n%s",
           rc, out);
}

/* The checker catches what the layout forbids: a results file edited with
 * h5py to hold a column named in g with units 1, a 32-bit integer history,
 * an undocumented attribute and a wrong units attribute. */
AQ_TEST(report_h5_layout_checker_finds_faults)
{
  char dir[512], cmd[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cmd, sizeof cmd,
           REC "ARL360.at2 --arch arches/thin.cfg --history -q -o %s/m.h5", dir);
  char err[2048];
  int rc = aq_test_run(cmd, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", cmd, rc, err))
    return;
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, numpy as np, sys\n"
           "with h5py.File(sys.argv[1], 'r+') as f:\n"
           "    t = f['summary'][:]\n"
           "    names = [n if n != 'pga_over_lambda0' else 'pga_over_lambda0_g' for n in t.dtype.names]\n"
           "    u = {n: f['summary'].attrs['units_' + n] for n in t.dtype.names}\n"
           "    t.dtype.names = names\n"
           "    del f['summary']\n"
           "    f['summary'] = t\n"
           "    for n, o in zip(names, u): f['summary'].attrs['units_' + n] = u[o]\n"
           "    h = f['histories'][list(f['histories'])[0]]\n"
           "    s = h['hinge_set'][:].astype(np.int32); del h['hinge_set']; h['hinge_set'] = s\n"
           "    h['hinge_set'].attrs['units'] = b'1 (0 primary, 1 reverse, -1 at rest)'\n"
           "    f['arches/000'].attrs['g_m_s2'] = 9.80665\n"
           "    h['time_s'].attrs['units'] = b'ms'\n"
           "\" %s/m.h5 && /usr/bin/python3 tests/h5_layout.py docs/hdf5-layout.md %s/m.h5",
           dir, dir);
  rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc != 0, "the edited file fails the layout (exit %d)", rc);
  static const char *const want[] = {
      "column pga_over_lambda0_g (double) is not in docs/hdf5-layout.md",
      "hinge_set: dataset is int32[n], docs/hdf5-layout.md says int64[n]",
      "attribute g_m_s2 (double) is not in docs/hdf5-layout.md: add a row",
      "time_s: units 'ms', docs/hdf5-layout.md says 's'",
      "time_s: the name says s (suffix _s), its units are 'ms'"};
  for (size_t k = 0; k < sizeof want / sizeof want[0]; k++)
    aq_check(strstr(out, want[k]) != NULL, "the checker says \"%s\":\n%s", want[k], out);
}

/* What each kind holds and does not: the root's kind; no runs table and no
 * arches in a spectrum file, no runs table and no run scales in a
 * capacity file. */
AQ_TEST(report_h5_layout_kinds_hold_their_own)
{
  char dir[512], cmd[4096];
  aq_test_tmpdir(dir, sizeof dir);
  if (!make_files(dir))
    return;
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, sys\n"
           "d = sys.argv[1]\n"
           "m, c, s = (h5py.File(d + x, 'r') for x in ('/m.h5', '/c.h5', '/s.h5'))\n"
           "print('kinds', m.attrs['kind'].decode(), c.attrs['kind'].decode(), s.attrs['kind'].decode())\n"
           "print('spectrum holds', sorted(s))\n"
           "print('capacity holds', sorted(c))\n"
           "print('capacity root', 'scale_mode' in c.attrs, 'scales' in c.attrs, 'history' in c.attrs)\n"
           "print('results holds', sorted(m))\n"
           "\" %s",
           dir);
  int rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0 && strstr(out, "kinds results capacity spectrum\n"), "root kind: %s", out);
  aq_check(strstr(out, "spectrum holds ['records', 'spectra']\n") != NULL,
           "a spectrum file holds its records and spectra only: %s", out);
  aq_check(strstr(out, "capacity holds ['arches', 'capacity', 'geometry', 'records']\n") != NULL,
           "a capacity file holds no run table: %s", out);
  aq_check(strstr(out, "capacity root False False False\n") != NULL,
           "a capacity file has no run scales or history options: %s", out);
  aq_check(strstr(out, "results holds ['arches', 'geometry', 'histories', 'records', "
                       "'summary', 'waveforms']\n") != NULL,
           "a results file: %s", out);
}

/* An arch's SHA-256: of the .cfg's bytes, then a joints arch's joints and
 * faces files', as stored in the file (config, joints_csv, faces_csv) and
 * as sha256sum reads the files on disk; in the main job's file and in
 * capacity's alike, with the hinge sets as used. */
AQ_TEST(report_h5_layout_arch_texts_and_sha256)
{
  char dir[512], cmd[4096], sums[1024];
  aq_test_tmpdir(dir, sizeof dir);
  if (!make_files(dir))
    return;
  int rc = aq_test_sh("cat arches/vertical.cfg arches/vertical.csv arches/vertical_faces.csv | sha256sum "
              "&& sha256sum < arches/bridge.cfg",
              sums, sizeof sums);
  if (!aq_check(rc == 0 && strlen(sums) > 130, "sha256sum: %s", sums))
    return;
  char want_v[65], want_b[65];
  snprintf(want_v, sizeof want_v, "%.64s", sums);
  snprintf(want_b, sizeof want_b, "%.64s", strchr(sums, '\n') + 1);
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, hashlib, sys\n"
           "for fn in ('/m.h5', '/c.h5'):\n"
           "    f = h5py.File(sys.argv[1] + fn, 'r')\n"
           "    for k in sorted(f['arches']):\n"
           "        a = f['arches'][k].attrs\n"
           "        text = a['config'] + a.get('joints_csv', b'') + a.get('faces_csv', b'')\n"
           "        print(fn, a['name'].decode(), a['sha256'].decode(),\n"
           "              hashlib.sha256(text).hexdigest() == a['sha256'].decode(),\n"
           "              'joints_csv' in a, a['primary_joints'].decode(), a['g_mps2'])\n"
           "\" %s",
           dir);
  rc = aq_test_sh(cmd, out, sizeof out);
  aq_check(rc == 0, "read the arches: %s", out);
  for (int k = 0; k < 2; k++) {
    const char *fn = k ? "/c.h5" : "/m.h5";
    char line[512];
    snprintf(line, sizeof line, "%s vertical %s True True ", fn, want_v);
    aq_check(strstr(out, line) != NULL, "%s: the joints arch's sha256 is that of its .cfg, "
             "joints and faces files, which the file holds (%s):\n%s", fn, line, out);
    snprintf(line, sizeof line, "%s thin ", fn);
    const char *t = strstr(out, line);
    aq_check(t && strstr(t, " True False 0,") && strstr(t, " 9.80665\n"),
             "%s: thin: sha256 of its .cfg, no joints texts, hinge sets, g_mps2:\n%s", fn, out);
  }
  char line[512];
  snprintf(line, sizeof line, "/m.h5 bridge %s True False ", want_b);
  aq_check(strstr(out, line) != NULL, "bridge's sha256 is sha256sum's (%s)", want_b);
}

/* Histories and waveforms are stored in chunks, byte-shuffled and deflated
 * (docs/hdf5-layout.md, "Compression"): every such dataset of a suite's
 * file, as h5py reports its filters, and the space they take against
 * their values' bytes (1.36 MB of histories per run took 0.024 MB when
 * this was written: a factor of 56; at least 4 is asked here).  Their
 * values read back bit for bit: test_report_h5.c. */
AQ_TEST(report_h5_layout_series_deflated)
{
  char dir[512], cmd[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cmd, sizeof cmd,
           REC "ARL360.at2 " REC "RSN77_SFERN_PUL164-hor1.AT2 --arch arches/thin.cfg --arch "
           "arches/oppenheim.cfg --polarity both --history --store-records -q -o %s/m.h5",
           dir);
  char err[2048];
  int rc = aq_test_run(cmd, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", cmd, rc, err))
    return;
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, sys\n"
           "f = h5py.File(sys.argv[1], 'r')\n"
           "n = plain = stored = raw = 0\n"
           "for g in ('histories', 'waveforms'):\n"
           "    def v(name, d):\n"
           "        global n, plain, stored, raw\n"
           "        if not isinstance(d, h5py.Dataset): return\n"
           "        n += 1\n"
           "        plain += not (d.compression == 'gzip' and d.shuffle and d.chunks)\n"
           "        stored += d.id.get_storage_size(); raw += d.size * d.dtype.itemsize\n"
           "    f[g].visititems(v)\n"
           "print(n, 'series', plain, 'not deflated', 'ratio %%.1f' %% (raw / stored))\n"
           "\" %s/m.h5",
           dir);
  rc = aq_test_sh(cmd, out, sizeof out);
  int n = 0, plain = -1;
  double ratio = 0;
  sscanf(out, "%d series %d not deflated ratio %lf", &n, &plain, &ratio);
  aq_check(rc == 0 && n == 2 * 2 * 2 * 6 + 2 && plain == 0,
           "every history and waveform chunked, shuffled and deflated: %s", out);
  aq_check(ratio >= 4, "their values' bytes over the space they take: %g (>= 4)", ratio);
}
