/* bench_io.c: median time to read a 20 000-sample record with
 * aq_record_read (AT2, SAC and CSV), beside the floor; then each agency-format
 * reader (COSMOS, CSMIP, SMC, ESM, miniSEED) parsing a shipped file from its
 * bytes, against the same floor.
 *
 * The floor is the I/O every reader does before it parses: stat the file,
 * open it, malloc a buffer of its size, read the whole file into it with one
 * fread, close, free (record.c's read_bytes, step for step), on a file in
 * the page cache.  ratio = reader median / floor median; ns_per_value =
 * (reader - floor) / values, the parsing and deciding alone.  Floor and
 * reader alternate (floor, reader, floor) and the smaller floor median is
 * used.  faults_per_read: minor page faults per read, pages the allocator
 * took anew from the kernel (after giving its heap back on a free); each
 * costs the reader time that the floor, whose one buffer stays, does not.
 * Both run under archquake's allocator policy (aq_app_heap_policy, which
 * main() sets before any command), as every record archquake reads is read:
 * a record's arrays stay in the heap between reads.
 *
 * The records are made here from real data:
 * CHY028-N.AT2 (18 000 values, Chi-Chi 1999) extended to 20 000 values by
 * repeating its first 2 000 value tokens, and a little-endian SAC file
 * holding the same samples (float32, g), and a CSV "t,acc_g" of them. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "app/app.h"
#include "bench.h"
#include "io/record.h"

#define NPTS 20000
#define REPS 301
#define SRC "tests/data/records/CHY028-N.AT2"

static unsigned char *slurp(const char *path, size_t *n)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  struct stat st;
  if (fstat(fileno(f), &st) != 0) {
    fclose(f);
    return NULL;
  }
  unsigned char *b = malloc((size_t)st.st_size + 1);
  size_t got = b ? fread(b, 1, (size_t)st.st_size, f) : 0;
  fclose(f);
  if (!b || got != (size_t)st.st_size) {
    free(b);
    return NULL;
  }
  *n = got;
  return b;
}

static int make_at2(const char *out)
{
  size_t n;
  unsigned char *t = slurp(SRC, &n);
  if (!t)
    return 0;
  char *s = (char *)t;
  s[n] = '\0';
  /* skip the 4 header lines */
  char *p = s;
  for (int l = 0; l < 4 && p; l++) {
    p = strchr(p, '\n');
    if (p)
      p++;
  }
  FILE *f = fopen(out, "wb");
  if (!f || !p) {
    free(t);
    return 0;
  }
  fprintf(f, "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
             "CHI-CHI 09/20/99, CHY028, N (CWB), extended to 20000 values for a bench\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G.\n"
             "NPTS= %d, DT= .00500 SEC\n",
          NPTS);
  char *save = NULL, *copy = strdup(p);
  size_t k = 0;
  for (int pass = 0; pass < 2 && k < NPTS; pass++) {
    strcpy(copy, p);
    for (char *tok = strtok_r(copy, " \r\n", &save); tok && k < NPTS;
         tok = strtok_r(NULL, " \r\n", &save)) {
      fprintf(f, "%15s", tok);
      if (++k % 5 == 0)
        fputc('\n', f);
    }
  }
  free(copy);
  free(t);
  return fclose(f) == 0 && k == NPTS;
}

static void put_le32(unsigned char *b, uint32_t u)
{
  for (int i = 0; i < 4; i++)
    b[i] = (unsigned char)(u >> (8 * i));
}

static void put_f(unsigned char *h, int word, float x)
{
  uint32_t u;
  memcpy(&u, &x, 4);
  put_le32(h + 4 * word, u);
}

static int make_sac(const char *out, const aq_record *r)
{
  unsigned char h[632];
  for (int w = 0; w < 70; w++)
    put_f(h, w, -12345.0f);
  for (int w = 70; w < 110; w++)
    put_le32(h + 4 * w, (uint32_t)-12345);
  for (int i = 440; i < 632; i += 8)
    memcpy(h + i, "-12345  ", 8);
  put_f(h, 0, (float)r->dt_s); /* DELTA */
  put_f(h, 5, 0.0f);           /* B */
  put_le32(h + 4 * 76, 6);     /* NVHDR */
  put_le32(h + 4 * 79, (uint32_t)r->npts);
  put_le32(h + 4 * 85, 1); /* IFTYPE = ITIME */
  put_le32(h + 4 * 105, 1); /* LEVEN */
  memcpy(h + 440, "CHY028  ", 8);
  FILE *f = fopen(out, "wb");
  if (!f)
    return 0;
  int ok = fwrite(h, 1, sizeof h, f) == sizeof h;
  for (size_t k = 0; k < r->npts && ok; k++) {
    unsigned char b[4];
    float x = (float)(r->acc_mps2[k] / r->to_mps2);
    uint32_t u;
    memcpy(&u, &x, 4);
    put_le32(b, u);
    ok = fwrite(b, 1, 4, f) == 4;
  }
  return (fclose(f) == 0) && ok;
}

/* The same samples as CSV: "t,acc_g" and one row per sample. */
static int make_csv(const char *out, const aq_record *r)
{
  FILE *f = fopen(out, "wb");
  if (!f)
    return 0;
  fprintf(f, "t,acc_g\n");
  for (size_t k = 0; k < r->npts; k++)
    fprintf(f, "%.3f,%.7E\n", (double)k * r->dt_s, r->acc_mps2[k] / r->to_mps2);
  return fclose(f) == 0;
}

/* Median seconds of REPS runs of fn(path). */
static double time_median(int (*fn)(const char *, const aq_read_opts *), const char *path,
                          const aq_read_opts *ro)
{
  static double t[REPS];
  for (int i = 0; i < REPS; i++) {
    double t0 = aq_bench_now_s();
    if (!fn(path, ro)) {
      fprintf(stderr, "bench_io: %s failed\n", path);
      exit(1);
    }
    t[i] = aq_bench_now_s() - t0;
  }
  return aq_bench_median(t, REPS);
}

/* Minor page faults of the process so far. */
static long minor_faults(void)
{
  struct rusage u;
  return getrusage(RUSAGE_SELF, &u) == 0 ? u.ru_minflt : 0;
}

/* The floor: the reader's I/O (record.c read_bytes) and nothing else. */
static int floor_read(const char *path, const aq_read_opts *ro)
{
  (void)ro;
  struct stat st;
  if (stat(path, &st) != 0)
    return 0;
  FILE *f = fopen(path, "rb");
  if (!f)
    return 0;
  size_t n = (size_t)st.st_size;
  unsigned char *b = malloc(n ? n : 1);
  size_t got = b ? fread(b, 1, n, f) : 0;
  int ok = b && got == n && !ferror(f);
  fclose(f);
  free(b);
  return ok;
}

static int reader(const char *path, const aq_read_opts *ro)
{
  aq_record r;
  aq_error e;
  int ok = aq_record_read(path, ro, &r, &e) == AQ_OK && r.npts == NPTS;
  aq_record_free(&r);
  return ok;
}

/* An agency-format file parsed from its bytes by the dispatcher (what the
 * reader states, before the units decision). */
static int raw_reader(const char *path, const aq_read_opts *ro)
{
  size_t n;
  unsigned char *b = slurp(path, &n);
  if (!b)
    return 0;
  aq_raw_file raw;
  aq_error e;
  int ok = aq_raw_parse(b, n, path, ro, &raw, &e) == AQ_OK;
  aq_raw_file_free(&raw);
  free(b);
  return ok;
}

/* The agency-format readers on shipped files (tests/data/records/agency). */
static void bench_agency(void)
{
  static const struct {
    const char *name, *path;
  } f[] = {
      {"cosmos-v2", "tests/data/records/agency/Cosmos12TimeSeriesTest.v1"},
      {"cosmos-v0", "tests/data/records/agency/NP1795-n.305.v0c"},
      {"csmip-v1", "tests/data/records/agency/CE89146.V1"},
      {"csmip-v2", "tests/data/records/agency/ce36456p_CE36456.V2"},
      {"smc", "tests/data/records/agency/0165b_a.smc"},
      {"esm", "tests/data/records/agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC"},
      {"mseed", "tests/data/records/agency/"
                "CE.58360..HNE__20191015T053312Z__20191015T054042Z.mseed"},
  };
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
    struct stat st;
    size_t n, npts = 0;
    unsigned char *b = slurp(f[i].path, &n);
    aq_raw_file raw;
    aq_error e;
    if (!b || stat(f[i].path, &st) != 0 || aq_raw_parse(b, n, f[i].path, NULL, &raw, &e)) {
      fprintf(stderr, "bench_io: cannot parse %s\n", f[i].path);
      exit(1);
    }
    for (size_t c = 0; c < raw.nchan; c++)
      npts += raw.chan[c].npts;
    aq_raw_file_free(&raw);
    free(b);
    double fl = time_median(floor_read, f[i].path, NULL);
    double rd = time_median(raw_reader, f[i].path, NULL);
    double fl2 = time_median(floor_read, f[i].path, NULL);
    double fm = fl < fl2 ? fl : fl2;
    printf("%s\t%zu\t%lld\t%.1f\t%.1f\t%.1f\t%.1f\n", f[i].name, npts,
           (long long)st.st_size, 1e6 * rd, 1e6 * fm, rd / fm, 1e9 * (rd - fm) / (double)npts);
  }
}

int main(void)
{
  aq_app_heap_policy(); /* as archquake's main() sets it */
  mkdir("build", 0777);
  mkdir("build/bench", 0777);
  const char *at2 = "build/bench/chy028-20000.AT2", *sac = "build/bench/chy028-20000.sac",
             *csv = "build/bench/chy028-20000.csv";
  aq_read_opts g = {0};
  g.units = AQ_UNITS_G;
  aq_record r;
  aq_error e;
  if (!make_at2(at2) || aq_record_read(at2, NULL, &r, &e) != AQ_OK) {
    fprintf(stderr, "bench_io: cannot make %s: %s\n", at2, e.message);
    return 1;
  }
  int ok = make_sac(sac, &r) && make_csv(csv, &r);
  aq_record_free(&r);
  if (!ok) {
    fprintf(stderr, "bench_io: cannot write %s\n", sac);
    return 1;
  }
  printf("# floor = stat + open + malloc + one fread of the whole file + close + free;\n"
         "# floor and readers under archquake's allocator policy (aq_app_heap_policy)\n");
  printf("reader\tnpts\tfile_bytes\tread_median_us\tfloor_median_us\tratio\tns_per_value\t"
         "faults_per_read\n");
  const char *paths[3] = {at2, sac, csv}, *names[3] = {"at2", "sac", "csv"};
  for (int i = 0; i < 3; i++) {
    struct stat st;
    stat(paths[i], &st);
    /* interleave: floor, reader, floor, reader ... (same cache state) */
    double fl = time_median(floor_read, paths[i], NULL);
    long f0 = minor_faults();
    double rd = time_median(reader, paths[i], &g);
    double faults = (double)(minor_faults() - f0) / REPS;
    double fl2 = time_median(floor_read, paths[i], NULL);
    double fm = fl < fl2 ? fl : fl2;
    printf("%s\t%d\t%lld\t%.1f\t%.1f\t%.1f\t%.1f\t%.0f\n", names[i], NPTS,
           (long long)st.st_size, 1e6 * rd, 1e6 * fm, rd / fm, 1e9 * (rd - fm) / NPTS, faults);
  }
  bench_agency();
  return 0;
}
