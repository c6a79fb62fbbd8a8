/* test_io_sac.c: the SAC reader against header values and samples that other
 * programs assert or wrote: ObsPy's tests for test.sac and seism.sac,
 * gmprocess's max|data| for the CSN files (both quoted in
 * tests/data/records/PROVENANCE.md), a big-endian copy made by a separate
 * byte swapper here, and Debian's mseed2sac converting miniSEED at test time
 * (both byte orders), checked against mseed2sac's own text (alpha) output. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "units.h"

#define REC_DIR "tests/data/records/"
/* float32 samples widened to double are exact; ObsPy prints them with 9
 * significant digits. */
#define OBSPY_SAMPLE_REL 1e-8
/* gmprocess multiplies the float32 data by 980.665 in float32: agreement to
 * float32 rounding, 2^-23 relative. */
#define GMPROCESS_REL 1.2e-7
/* PROVENANCE.md prints PGA to 4 decimals of g */
#define PROV_PGA_ABS_G 0.5e-4
/* counts / SCALE computed as counts * (1 / SCALE): two roundings */
#define COUNTS_REL 1e-15
/* B is float32 0.0003 (0.00030000001...) */
#define B_F32_ABS_S 1e-9

static int read_rec(const char *path, const aq_read_opts *ro, aq_record *r, char *msg,
                    size_t cap)
{
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_record_read(path, ro, r, &e);
  aq_error_format(&e, msg, cap);
  return s == AQ_OK;
}

AQ_TEST(io_sac_obspy_test_sac)
{
  aq_record r;
  char msg[1400];
  aq_read_opts ro = {0};
  /* IDEP undefined: refused without --units */
  aq_check(!read_rec(REC_DIR "test.sac", NULL, &r, msg, sizeof msg) &&
               strstr(msg, "IDEP") && strstr(msg, "--units"),
           "undefined IDEP refused, says how to override: %s", msg);
  ro.units = AQ_UNITS_MPS2;
  if (!aq_check(read_rec(REC_DIR "test.sac", &ro, &r, msg, sizeof msg), "%s", msg))
    return;
  /* ObsPy's test_core.py values */
  static const double first10[10] = {-8.74227766e-08, -0.309016973, -0.587785363,
                                     -0.809017122,    -0.9510566,   -1.0,
                                     -0.951056302,    -0.809016585, -0.587784529,
                                     -0.309016049};
  aq_check(r.npts == 100, "npts %zu", r.npts);
  aq_check(r.dt_s == 1.0, "delta %.17g", r.dt_s);
  aq_check(r.begin_s == 10.0, "b %.17g", r.begin_s);
  aq_check(strcmp(r.station, "STA") == 0, "station '%s'", r.station);
  aq_check(strcmp(r.channel, "Q") == 0, "channel '%s'", r.channel);
  aq_check(r.network[0] == '\0', "network undefined: '%s'", r.network);
  /* nzyear 1978 nzjday 199 08:00:00.000; starttime = reference + b = 08:00:10 */
  aq_check(strcmp(r.reference, "1978-07-18T08:00:00.000Z") == 0, "reference %s",
           r.reference);
  aq_check(strcmp(r.format, "sac-le") == 0, "format %s", r.format);
  for (int k = 0; k < 10; k++)
    aq_check_rel(r.acc_mps2[k], first10[k], OBSPY_SAMPLE_REL, "sample %d", k);
  aq_record_free(&r);
}

AQ_TEST(io_sac_obspy_seism_sac)
{
  aq_record r;
  char msg[1400];
  aq_check(!read_rec(REC_DIR "seism.sac", NULL, &r, msg, sizeof msg) &&
               strstr(msg, "IVOLTS") && strstr(msg, "--units"),
           "IVOLTS refused: %s", msg);
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_GAL;
  if (!aq_check(read_rec(REC_DIR "seism.sac", &ro, &r, msg, sizeof msg), "%s", msg))
    return;
  aq_check(r.npts == 1000, "npts %zu", r.npts);
  aq_check(r.dt_s == 0.01, "delta recovered as 0.01 exactly: %.17g", r.dt_s);
  aq_check_abs(r.begin_s, 9.4599991, 0.5e-7, "b (ObsPy: 9.4599991 to 7 d.p.)");
  aq_check(strcmp(r.station, "CDV") == 0 && strcmp(r.channel, "Q") == 0, "station %s %s",
           r.station, r.channel);
  aq_check(strcmp(r.reference, "1981-03-29T10:38:14.000Z") == 0, "reference %s",
           r.reference);
  aq_check(strcmp(r.units_orig, "gal") == 0 && r.to_mps2 == 0.01, "units %s", r.units_orig);
  aq_record_free(&r);
}

static double max_abs(const aq_record *r)
{
  double m = 0;
  for (size_t k = 0; k < r->npts; k++)
    m = fmax(m, fabs(r->acc_mps2[k]));
  return m;
}

AQ_TEST(io_sac_csn_in_g_against_gmprocess)
{
  aq_record r;
  char msg[1400];
  /* IACC but values in g: refused as implausible nm/s2 */
  aq_check(!read_rec(REC_DIR "20190706031952.CJ.T001230.HNE.sac", NULL, &r, msg,
                     sizeof msg) &&
               strstr(msg, "--units"),
           "CSN without --units refused: %s", msg);
  aq_read_opts ro = {0};
  snprintf(ro.rules[0].glob, sizeof ro.rules[0].glob, "*CJ.T001230*");
  ro.rules[0].units = AQ_UNITS_G;
  ro.nrules = 1;
  static const struct {
    const char *file;
    double max_cm_s2;
  } want[] = {{"20190706031952.CJ.T001230.HNE.sac", 42.54516983},
              {"20190706031952.CJ.T001230.HNZ.sac", 992.60430908}};
  for (int i = 0; i < 2; i++) {
    char path[300];
    snprintf(path, sizeof path, REC_DIR "%s", want[i].file);
    if (!aq_check(read_rec(path, &ro, &r, msg, sizeof msg), "%s", msg))
      continue;
    /* gmprocess: max|data| * 980.665 (data in g) */
    aq_check_rel(max_abs(&r) / AQ_G0_MPS2 * 980.665, want[i].max_cm_s2, GMPROCESS_REL,
                 "%s max|a| cm/s2", want[i].file);
    aq_check(r.npts == 15001 && r.dt_s == 0.02, "%s npts %zu dt %.17g", want[i].file,
             r.npts, r.dt_s);
    aq_check(strcmp(r.station, "T001230") == 0 && strcmp(r.network, "CJ") == 0,
             "NUL-padded strings: '%s' '%s'", r.network, r.station);
    aq_record_free(&r);
  }
}

/* Swap a little-endian SAC file to big-endian: the 110 numeric header words
 * and the data words; the strings (bytes 440..631) stay. */
static int swap_sac(const char *in, const char *out)
{
  FILE *f = fopen(in, "rb");
  if (!f)
    return 0;
  unsigned char *b = malloc(1 << 20);
  size_t n = fread(b, 1, 1 << 20, f);
  fclose(f);
  for (size_t w = 0; w * 4 + 4 <= n; w++) {
    if (w * 4 >= 440 && w * 4 < 632)
      continue;
    unsigned char *p = b + 4 * w, t;
    t = p[0], p[0] = p[3], p[3] = t;
    t = p[1], p[1] = p[2], p[2] = t;
  }
  f = fopen(out, "wb");
  int ok = f && fwrite(b, 1, n, f) == n;
  if (f)
    ok &= fclose(f) == 0;
  free(b);
  return ok;
}

AQ_TEST(io_sac_big_endian_swapped_copy)
{
  char dir[512], be[600], msg[1400];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(be, sizeof be, "%s/clc-be.sac", dir);
  aq_check(swap_sac(REC_DIR "CI.CLC..HNE.D.2019.187.031923.SAC", be), "swapped");
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_COUNTS;
  aq_record a, b;
  int ok = aq_check(read_rec(REC_DIR "CI.CLC..HNE.D.2019.187.031923.SAC", &ro, &a, msg,
                             sizeof msg),
                    "%s", msg);
  ok &= aq_check(read_rec(be, &ro, &b, msg, sizeof msg), "%s", msg);
  if (ok) {
    aq_check(strcmp(a.format, "sac-le") == 0 && strcmp(b.format, "sac-be") == 0,
             "formats %s %s", a.format, b.format);
    aq_check(a.npts == 39001 && b.npts == a.npts, "npts %zu %zu", a.npts, b.npts);
    size_t diff = 0;
    for (size_t k = 0; k < a.npts && k < b.npts; k++)
      diff += a.acc_mps2[k] != b.acc_mps2[k];
    aq_check(diff == 0, "%zu samples differ", diff);
    aq_check(b.dt_s == 0.01 && b.begin_s == a.begin_s, "dt %.17g b %.17g", b.dt_s,
             b.begin_s);
    aq_check(strcmp(b.reference, a.reference) == 0 && strcmp(b.station, "CLC") == 0,
             "reference %s station %s", b.reference, b.station);
    /* PROVENANCE: 0.3433 g after mean removal, SCALE 213945 counts/(m/s2) */
    double mean = 0, m = 0;
    for (size_t k = 0; k < b.npts; k++)
      mean += b.acc_mps2[k] / (double)b.npts;
    for (size_t k = 0; k < b.npts; k++)
      m = fmax(m, fabs(b.acc_mps2[k] - mean));
    aq_check_abs(m / AQ_G0_MPS2, 0.3433, PROV_PGA_ABS_G, "mean-removed PGA (g)");
  }
  aq_record_free(&a);
  aq_record_free(&b);
}

/* ---- mseed2sac: SAC files written by another program at test time ---- */

/* The samples of a SAC alpha file written by mseed2sac -f 1: 14 lines of 5
 * floats, 8 lines of 5 integers and 8 lines of strings form the header; the
 * data follow, 5 per line.  Returns a malloc'd array (count in *n). */
static double *read_alpha(const char *path, size_t *n)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return NULL;
  char line[512];
  for (int i = 0; i < 30 && fgets(line, sizeof line, f); i++)
    ;
  size_t cap = 1024, k = 0;
  double *v = malloc(cap * sizeof *v);
  while (v && fgets(line, sizeof line, f)) {
    char *p = line, *end;
    for (;;) {
      double x = strtod(p, &end);
      if (end == p)
        break;
      if (k == cap) {
        double *w = realloc(v, 2 * cap * sizeof *v);
        if (!w) {
          free(v);
          v = NULL;
          break;
        }
        v = w, cap *= 2;
      }
      v[k++] = x;
      p = end;
    }
  }
  fclose(f);
  *n = k;
  return v;
}

/* Run mseed2sac in dir on tests/data/records/<mseed> with args; the output
 * file path goes to out. */
static int run_mseed2sac(const char *dir, const char *args, const char *mseed,
                         const char *outname, char *out, size_t cap)
{
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "cd '%s' && mseed2sac %s '../../../" REC_DIR "%s' >/dev/null 2>&1",
           dir, args, mseed);
  int rc = system(cmd);
  snprintf(out, cap, "%s/%s", dir, outname);
  FILE *f = fopen(out, "rb");
  if (f)
    fclose(f);
  return rc == 0 && f != NULL;
}

#define CLC_META "'CI,CLC,--,HNE,35.81574,-117.59751,775,0,90,90,,213945,0.03,M/S**2,100'"
#define CLC_OUT "CI.CLC..HNE.D.2019.187.031923"
#define CLC_SCALE 213945.0 /* counts per m/s2, CI.CLC.xml InstrumentSensitivity */

AQ_TEST(io_sac_mseed2sac_both_byte_orders)
{
  char d1[512], d3[512], d4[512], alpha[700], le[700], be[700], msg[1400];
  aq_test_tmpdir(d1, sizeof d1);
  aq_test_tmpdir(d3, sizeof d3);
  aq_test_tmpdir(d4, sizeof d4);
  int ok = aq_check(run_mseed2sac(d1, "-f 1 -M " CLC_META, "CI.CLC..HNE.mseed",
                                  CLC_OUT ".SACA", alpha, sizeof alpha),
                    "mseed2sac -f 1 (alpha) ran");
  ok &= aq_check(run_mseed2sac(d3, "-f 3 -M " CLC_META, "CI.CLC..HNE.mseed",
                               CLC_OUT ".SAC", le, sizeof le),
                 "mseed2sac -f 3 (little-endian) ran");
  ok &= aq_check(run_mseed2sac(d4, "-f 4 -M " CLC_META, "CI.CLC..HNE.mseed",
                               CLC_OUT ".SAC", be, sizeof be),
                 "mseed2sac -f 4 (big-endian) ran");
  if (!ok)
    return;
  size_t na = 0;
  double *counts = read_alpha(alpha, &na);
  aq_check(counts && na == 39001, "39001 samples in the alpha file, got %zu", na);
  if (!counts)
    return;
  const char *files[2] = {le, be}, *fmts[2] = {"sac-le", "sac-be"};
  for (int i = 0; i < 2; i++) {
    aq_record raw, cnt;
    aq_read_opts ro = {0};
    /* m/s2 = the raw values as stored: the miniSEED counts themselves */
    ro.units = AQ_UNITS_MPS2;
    ro.accept_implausible = 1; /* counts read as m/s2 are ~7e4 g */
    if (!aq_check(read_rec(files[i], &ro, &raw, msg, sizeof msg), "%s", msg))
      continue;
    ro.units = AQ_UNITS_COUNTS;
    if (!aq_check(read_rec(files[i], &ro, &cnt, msg, sizeof msg), "%s", msg)) {
      aq_record_free(&raw);
      continue;
    }
    aq_check(strcmp(raw.format, fmts[i]) == 0, "format %s, want %s", raw.format, fmts[i]);
    aq_check(raw.npts == na && cnt.npts == na, "npts %zu", raw.npts);
    size_t bad_raw = 0, bad_cnt = 0;
    for (size_t k = 0; k < na && k < raw.npts; k++) {
      bad_raw += raw.acc_mps2[k] != counts[k];
      bad_cnt += fabs(cnt.acc_mps2[k] - counts[k] / CLC_SCALE) >
                 COUNTS_REL * fabs(counts[k] / CLC_SCALE);
    }
    aq_check(bad_raw == 0, "%s: %zu samples differ from the miniSEED counts", fmts[i],
             bad_raw);
    aq_check(bad_cnt == 0, "%s: %zu samples differ from counts / SCALE", fmts[i], bad_cnt);
    aq_check(cnt.dt_s == 0.01, "dt %.17g", cnt.dt_s);
    aq_check_abs(cnt.begin_s, 0.0003, B_F32_ABS_S, "B (mseed2sac: 0.0003 s)");
    /* miniSEED start 2019-187 03:19:23.038 */
    aq_check(strcmp(cnt.reference, "2019-07-06T03:19:23.038Z") == 0, "reference %s",
             cnt.reference);
    aq_check(strcmp(cnt.network, "CI") == 0 && strcmp(cnt.station, "CLC") == 0 &&
                 strcmp(cnt.channel, "HNE") == 0 && cnt.location[0] == '\0',
             "codes '%s' '%s' '%s' '%s'", cnt.network, cnt.station, cnt.location,
             cnt.channel);
    aq_check(strcmp(cnt.units_orig, "counts") == 0, "units %s", cnt.units_orig);
    aq_record_free(&raw);
    aq_record_free(&cnt);
  }
  free(counts);
}

AQ_TEST(io_sac_mseed2sac_counts_need_scale)
{
  /* without -M mseed2sac leaves SCALE undefined: --units counts is refused */
  char d[512], out[700], msg[1400];
  aq_test_tmpdir(d, sizeof d);
  if (!aq_check(run_mseed2sac(d, "-f 4", "BK.CMB.00.HNE__20140824T102014Z__20140824T102244Z.mseed",
                              "BK.CMB.00.HNE.M.2014.236.102014.SAC", out, sizeof out),
                "mseed2sac ran"))
    return;
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_COUNTS;
  aq_record r;
  aq_check(!read_rec(out, &ro, &r, msg, sizeof msg) && strstr(msg, "SCALE") &&
               strstr(msg, "found none"),
           "counts without SCALE refused: %s", msg);
  ro.units = AQ_UNITS_MPS2;
  ro.accept_implausible = 1; /* the counts as m/s2 */
  if (aq_check(read_rec(out, &ro, &r, msg, sizeof msg), "%s", msg)) {
    aq_check(r.npts == 15000 && strcmp(r.format, "sac-be") == 0 &&
                 strcmp(r.location, "00") == 0,
             "npts %zu format %s location '%s'", r.npts, r.format, r.location);
    aq_record_free(&r);
  }
}

/* A negative sensitivity is the channel's polarity: Debian's mseed2sac
 * writes SCALE -214371.7 (float32) for BK.KCC HNZ given its StationXML's
 * InstrumentSensitivity -214371.7163008 (tests/data/records/evidence/
 * PROVENANCE.md: demeaned peak +4.393e-4 m/s2, up, = 4.479e-5 g).  It was
 * refused as "found none". */
AQ_TEST(io_sac_negative_scale_is_polarity)
{
  char d[512], sac[700], msg[1400];
  aq_test_tmpdir(d, sizeof d);
  if (!aq_check(run_mseed2sac(d,
                              "-f 3 -M 'BK,KCC,00,HNZ,37.32363,-119.3187,888.1,87.3,0,0,,"
                              "-214371.7163008,1.0,M/S**2,100'",
                              "evidence/BK.KCC.00.HNZ.mseed",
                              "BK.KCC.00.HNZ.Q.2019.185.173655.SAC", sac, sizeof sac),
                "mseed2sac ran"))
    return;
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_COUNTS; /* mseed2sac leaves IDEP undefined */
  aq_record r;
  if (!aq_check(read_rec(sac, &ro, &r, msg, sizeof msg), "%s", msg))
    return;
  aq_check(r.npts == 33000 && r.dt_s == 0.01, "npts %zu dt %g", r.npts, r.dt_s);
  /* SCALE as float32 */
  aq_check_rel(r.to_mps2, 1.0 / (double)(float)-214371.7163008, 1e-15, "1 / SCALE");
  double mean = 0, peak = 0;
  for (size_t k = 0; k < r.npts; k++)
    mean += r.acc_mps2[k];
  mean /= (double)r.npts;
  for (size_t k = 0; k < r.npts; k++)
    if (fabs(r.acc_mps2[k] - mean) > fabs(peak))
      peak = r.acc_mps2[k] - mean;
  aq_check_rel(peak, 4.393e-4, 1e-3, "demeaned peak +4.393e-4 m/s2 (up), got %g", peak);
  aq_check_rel(fabs(peak) / 9.80665, 4.479e-5, 5e-4, "PGA 4.479e-5 g");
  aq_check(strstr(r.polarity_note, "reversed") && strstr(r.polarity_note, "-214371.7") &&
               strstr(r.polarity_note, "header SCALE"),
           "polarity recorded: %s", r.polarity_note);
  aq_record_free(&r);
}

/* Header version 7: a copy of ObsPy's test.sac with NVHDR = 7 and the
 * 22-word float64 footer (DELTA, B, E, O, A, ...) appended. */
AQ_TEST(io_sac_version7_footer)
{
  FILE *f = fopen(REC_DIR "test.sac", "rb");
  unsigned char b[1032 + 176];
  size_t n = f ? fread(b, 1, 1032, f) : 0;
  if (f)
    fclose(f);
  if (!aq_check(n == 1032, "test.sac read"))
    return;
  b[304] = 7; /* NVHDR, little-endian */
  const double footer[22] = {1.0, 10.000000000123, 109.0};
  for (int w = 0; w < 22; w++) {
    double v = w < 3 ? footer[w] : -12345.0;
    unsigned char le[8];
    memcpy(le, &v, 8); /* the test host is little-endian, as is test.sac */
    memcpy(b + 1032 + 8 * w, le, 8);
  }
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_MPS2;
  aq_record r;
  aq_error e;
  if (aq_check(aq_record_parse(b, sizeof b, "v7.sac", &ro, &r, &e) == AQ_OK, "v7: %s",
               e.message)) {
    aq_check(r.npts == 100 && r.dt_s == 1.0, "npts %zu dt %.17g", r.npts, r.dt_s);
    aq_check(r.begin_s == 10.000000000123, "B from the float64 footer: %.17g", r.begin_s);
    aq_record_free(&r);
  }
  aq_check(aq_record_parse(b, 1032, "v7-nofooter.sac", &ro, &r, &e) == AQ_EFORMAT &&
               strstr(e.message, "version-7 footer"),
           "v7 without footer: %s", e.message);
}

#define CSN_HNE REC_DIR "20190706031952.CJ.T001230.HNE.sac"
/* gmprocess's test_sac_csn: max|data| * 980.665 = 42.54516983 cm/s^2, the
 * data in g (tests/data/records/PROVENANCE.md) */
static const double CSN_HNE_MAX_CM_S2 = 42.54516983;
/* The copy stores each sample * 9.80665e9 as float32: 2^-24 relative, plus
 * the reference's 10 digits */
static const double NM_COPY_REL = 2e-7;

/* The CSN record (IDEP = IACC, values in g) rewritten in nm/s^2, as SAC's
 * IACC promises: read with the file's units and with --units nm/s2, its
 * peak is 42.54516983 cm/s^2 = 0.4254516983 m/s^2 (0.0434 g), not 1000
 * times more or less. */
AQ_TEST(io_units_sac_iacc_is_nm_per_s2)
{
  size_t n;
  unsigned char *b = (unsigned char *)aq_test_read_file(CSN_HNE, &n);
  if (!aq_check(b && n >= 632 + 4 * 15001, "read %s", CSN_HNE)) {
    free(b);
    return;
  }
  for (size_t k = 0; k < 15001; k++) { /* little-endian float32 samples */
    unsigned char *p = b + 632 + 4 * k;
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                 (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &u, 4);
    f = (float)((double)f * 9.80665e9); /* g -> nm/s^2 */
    memcpy(&u, &f, 4);
    for (int i = 0; i < 4; i++)
      p[i] = (unsigned char)(u >> (8 * i));
  }
  char d[512], path[700];
  aq_test_tmpdir(d, sizeof d);
  snprintf(path, sizeof path, "%s/csn-nm.sac", d);
  FILE *f = fopen(path, "wb");
  aq_check(f && fwrite(b, 1, n, f) == n && fclose(f) == 0, "write %s", path);
  free(b);
  for (int how = 0; how < 2; how++) {
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.units = how ? AQ_UNITS_NMPS2 : AQ_UNITS_FILE;
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    if (!aq_check(aq_record_read(path, &ro, &r, &e) == AQ_OK, "read (%s): %s",
                  how ? "--units nm/s2" : "file units", e.message))
      continue;
    aq_check_rel(max_abs(&r), CSN_HNE_MAX_CM_S2 / 100, NM_COPY_REL,
                 "%s: max|a| m/s2 = gmprocess's cm/s2 / 100", how ? "--units nm/s2" : "IACC");
    aq_check_rel(max_abs(&r) / 9.80665, CSN_HNE_MAX_CM_S2 / 980.665, NM_COPY_REL,
                 "max|a| in g");
    aq_record_free(&r);
  }
}

/* E, the last sample's time, against B + (NPTS-1) DELTA: test.sac has B
 * 10 s, DELTA 1 s, NPTS 100, E 109 s (ObsPy's values); E 0.6 s later is
 * more than half a sample off and refused naming both times, 0.4 s later
 * is not; E undefined (-12345) is not checked. */
AQ_TEST(io_sac_end_time_checked)
{
  size_t n;
  unsigned char *b = (unsigned char *)aq_test_read_file(REC_DIR "test.sac", &n);
  if (!aq_check(b && n == 1032, "read test.sac"))
    return;
  static const struct {
    float e;
    int ok;
  } c[] = {{109.0f, 1}, {109.6f, 0}, {108.4f, 0}, {109.4f, 1}, {-12345.0f, 1}};
  aq_read_opts ro = {0};
  ro.units = AQ_UNITS_MPS2;
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    memcpy(b + 4 * 6, &c[i].e, 4); /* word 6, little-endian as the file */
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    aq_status s = aq_record_parse(b, n, "e.sac", &ro, &r, &e);
    char want[64];
    snprintf(want, sizeof want, "got E = %.9g s", (double)c[i].e);
    aq_check(c[i].ok ? s == AQ_OK
                     : s == AQ_EFORMAT && strcmp(e.field, "header E") == 0 &&
                           strstr(e.message, "= 109 s") && strstr(e.message, want),
             "E %g: status %d: %s", (double)c[i].e, (int)s, e.message);
    if (s == AQ_OK)
      aq_record_free(&r);
  }
  free(b);
}
