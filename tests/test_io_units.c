/* test_io_units.c: unit conversions against literal numbers (never the
 * code's own constants): standard gravity 9.80665 m/s^2 (CGPM 1901), 1 gal =
 * 0.01 m/s^2, and SAC's IACC = nm/s^2 (1e-9 m/s^2) on a record whose peak
 * gmprocess states. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define CSN_HNE "tests/data/records/20190706031952.CJ.T001230.HNE.sac"
/* gmprocess's test_sac_csn: max|data| * 980.665 = 42.54516983 cm/s^2, the
 * data in g (tests/data/records/PROVENANCE.md) */
static const double CSN_HNE_MAX_CM_S2 = 42.54516983;
/* The copy stores each sample * 9.80665e9 as float32: 2^-24 relative, plus
 * the reference's 10 digits */
static const double NM_COPY_REL = 2e-7;

AQ_TEST(io_units_factors_are_literal)
{
  aq_check(aq_units_to_mps2(AQ_UNITS_G) == 9.80665, "g = 9.80665 m/s2, got %.17g",
           aq_units_to_mps2(AQ_UNITS_G));
  aq_check(aq_units_to_mps2(AQ_UNITS_GAL) == 0.01, "gal = 0.01 m/s2, got %.17g",
           aq_units_to_mps2(AQ_UNITS_GAL));
  aq_check(aq_units_to_mps2(AQ_UNITS_MPS2) == 1.0, "m/s2 = 1");
  aq_check(aq_units_to_mps2(AQ_UNITS_NMPS2) == 1e-9, "nm/s2 = 1e-9 m/s2, got %.17g",
           aq_units_to_mps2(AQ_UNITS_NMPS2));
}

static double max_abs(const aq_record *r)
{
  double m = 0;
  for (size_t k = 0; k < r->npts; k++)
    m = fmax(m, fabs(r->acc_mps2[k]));
  return m;
}

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
