/* test_report_long_names.c: no record name is cut.  A record path of 300
 * bytes (deep directories in the test's tmp dir) goes through the main job
 * (-o and --text), capacity -o and spectrum -o: the TSV's record column and
 * the HDF5 files' record columns (read here with the HDF5 library itself,
 * by member name, whatever the string type) equal the whole path, and the
 * files read back (compare, plot spectrum --data) whole too. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* Row 0 of string member (or, member NULL, of the 1-D string dataset) of
 * dataset dset of file f, into buf[cap] ("" when unreadable); fixed or
 * variable length. */
static const char *h5_string(const char *f, const char *dset, const char *member, char *buf,
                             size_t cap)
{
  buf[0] = '\0';
  hid_t h = H5Fopen(f, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (h < 0)
    return buf;
  hid_t d = H5Dopen2(h, dset, H5P_DEFAULT), ft = d >= 0 ? H5Dget_type(d) : -1;
  hid_t st = -1;
  if (ft >= 0 && member) {
    int i = H5Tget_member_index(ft, member);
    st = i >= 0 ? H5Tget_member_type(ft, (unsigned)i) : -1;
  } else if (ft >= 0) {
    st = H5Tcopy(ft);
  }
  if (st >= 0 && H5Tget_class(st) == H5T_STRING) {
    int vlen = H5Tis_variable_str(st) > 0;
    size_t sz = vlen ? sizeof(char *) : H5Tget_size(st);
    hid_t ms = H5Tcopy(H5T_C_S1);
    H5Tset_size(ms, vlen ? H5T_VARIABLE : sz);
    hid_t mt = ms;
    if (member) {
      mt = H5Tcreate(H5T_COMPOUND, sz);
      H5Tinsert(mt, member, 0, ms);
    }
    hid_t fs = H5Dget_space(d);
    hsize_t n = (hsize_t)H5Sget_simple_extent_npoints(fs);
    char *v = calloc(n ? n : 1, sz + 1);
    if (v && n && H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0) {
      if (vlen) {
        snprintf(buf, cap, "%s", ((char **)(void *)v)[0] ? ((char **)(void *)v)[0] : "");
        H5Dvlen_reclaim(mt, fs, H5P_DEFAULT, v);
      } else {
        snprintf(buf, cap, "%.*s", (int)sz, v);
      }
    }
    free(v);
    H5Sclose(fs);
    if (member)
      H5Tclose(mt);
    H5Tclose(ms);
  }
  if (st >= 0)
    H5Tclose(st);
  if (ft >= 0)
    H5Tclose(ft);
  if (d >= 0)
    H5Dclose(d);
  H5Fclose(h);
  return buf;
}

AQ_TEST(report_long_record_path_whole_everywhere)
{
  enum { LEN = 300 };
  char d[512], dir[1200], p[1400], cmd[6000], out[65536], err[8192], f[1600], got[2048];
  aq_test_tmpdir(d, sizeof d);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  /* d/000.../x.../ARL360.at2, LEN bytes in all */
  size_t nb = LEN - (strlen(d) + 1 + 150 + 1 + strlen("/ARL360.at2"));
  if (!aq_check(nb > 10 && nb < 250, "tmp dir of %zu bytes", strlen(d)))
    return;
  snprintf(dir, sizeof dir, "%s/%0150d/x%0*d", d, 0, (int)nb - 1, 0);
  snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
  if (!aq_check(system(cmd) == 0, "mkdir"))
    return;
  snprintf(p, sizeof p, "%s/ARL360.at2", dir);
  aq_test_copy_prefix("tests/data/records/ARL360.at2", p, 1, 1);
  aq_check(strlen(p) == LEN, "path of %zu bytes", strlen(p));
  H5open();
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);

  /* the main job: TSV and HDF5, then compare reads it back */
  snprintf(f, sizeof f, "%s/main.h5", d);
  snprintf(cmd, sizeof cmd, "'%s' --arch arches/thin.cfg --scale 1 -o '%s'", p, f);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (aq_check(rc == 0, "main: exit %d: %s", rc, err)) {
    aq_check(!strcmp(aq_test_tsv_field(out, 1, 0, got, sizeof got), p), "main TSV record: %s",
             got);
    aq_check(!strcmp(h5_string(f, "/summary", "record", got, sizeof got), p),
             "main /summary record: %zu bytes", strlen(got));
    aq_check(!strcmp(h5_string(f, "/records", "source_file", got, sizeof got), p),
             "main /records source_file: %zu bytes", strlen(got));
    aq_check(!strcmp(h5_string(f, "/records", "name", got, sizeof got), "ARL360.at2"),
             "main /records name: %s", got);
    snprintf(cmd, sizeof cmd, "compare '%s' '%s'", f, f);
    rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 0, "compare reads it: exit %d: %s", rc, err);
  }

  /* capacity */
  snprintf(f, sizeof f, "%s/cap.h5", d);
  snprintf(cmd, sizeof cmd, "capacity '%s' --arch arches/thin.cfg -o '%s'", p, f);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (aq_check(rc == 0, "capacity: exit %d: %s", rc, err)) {
    aq_check(!strcmp(aq_test_tsv_field(out, 1, 0, got, sizeof got), p),
             "capacity TSV record: %s", got);
    aq_check(!strcmp(h5_string(f, "/capacity/record", NULL, got, sizeof got), p),
             "/capacity/record: %zu bytes", strlen(got));
    aq_check(!strcmp(h5_string(f, "/records", "source_file", got, sizeof got), p),
             "capacity /records source_file: %zu bytes", strlen(got));
    snprintf(cmd, sizeof cmd, "compare '%s' '%s'", f, f);
    rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 0, "compare reads the capacity file: exit %d: %s", rc, err);
  }

  /* spectrum */
  snprintf(f, sizeof f, "%s/sp.h5", d);
  snprintf(cmd, sizeof cmd, "spectrum '%s' -o '%s'", p, f);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  if (aq_check(rc == 0, "spectrum: exit %d: %s", rc, err)) {
    aq_check(!strcmp(aq_test_tsv_field(out, 1, 0, got, sizeof got), p),
             "spectrum TSV record: %s", got);
    aq_check(!strcmp(h5_string(f, "/spectra", "record", got, sizeof got), p),
             "/spectra record: %zu bytes", strlen(got));
    aq_check(!strcmp(h5_string(f, "/records", "source_file", got, sizeof got), p),
             "spectrum /records source_file: %zu bytes", strlen(got));
  }
}
