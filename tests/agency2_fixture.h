/* agency2_fixture.h: reading a shipped record the way the program does
 * (content detection, the reader, aq_record_decide) and comparing it with
 * the npts, dt and PGA that tests/data/records/agency2/PROVENANCE.md gives,
 * computed there independently of archquake.  Paths are relative to the
 * repository root. */
#ifndef AQ_TESTS_AGENCY2_FIXTURE_H
#define AQ_TESTS_AGENCY2_FIXTURE_H

#include <math.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define AGENCY2_DIR "tests/data/records/agency2/"
#define AQ_TEST_G0_MPS2 9.80665 /* literal: the g of the provenance's PGA */

/* What the provenance states for one channel.  pga_g is compared to the
 * digits given: within half a unit of its last printed digit (pga_tol_g). */
typedef struct {
  const char *name; /* FILE or FILE#CHANNEL, as a user gives it */
  size_t npts;
  double dt_s;
  double pga_g, pga_tol_g;
  const char *units_stated; /* canonical name, "" for none */
} aq_test_expect;

/* Read e->name with opts (NULL: none) and check npts, dt (relative 1e-12),
 * PGA as stored (max |a| / g0) and the units stated.  On success the record
 * is left in *rec for further checks (caller frees); returns 1, else 0 (a
 * failed check, *rec empty). */
static inline int aq_test_expect_read(const aq_test_expect *e, const aq_read_opts *opts,
                                      aq_record *rec)
{
  aq_error err;
  aq_error_clear(&err);
  aq_read_opts none;
  memset(&none, 0, sizeof none);
  aq_status s = aq_record_read(e->name, opts ? opts : &none, rec, &err);
  if (!aq_check(s == AQ_OK, "%s: %s", e->name, err.message))
    return 0;
  aq_check(rec->npts == e->npts, "%s: npts %zu, want %zu", e->name, rec->npts, e->npts);
  aq_check_rel(rec->dt_s, e->dt_s, 1e-12, "%s: dt", e->name);
  double pk = 0;
  for (size_t k = 0; k < rec->npts; k++)
    pk = fmax(pk, fabs(rec->acc_mps2[k]));
  aq_check_abs(pk / AQ_TEST_G0_MPS2, e->pga_g, e->pga_tol_g, "%s: PGA (g)", e->name);
  aq_check(strcmp(rec->units_stated, e->units_stated) == 0, "%s: units stated \"%s\", want \"%s\"",
           e->name, rec->units_stated, e->units_stated);
  return 1;
}

#endif
