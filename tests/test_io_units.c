/* test_io_units.c: unit conversions against literal numbers (never the
 * code's own constants): standard gravity 9.80665 m/s^2 (CGPM 1901), 1 gal =
 * 0.01 m/s^2, 1 nm/s^2 = 1e-9 m/s^2 (SAC's IACC against gmprocess's peak:
 * io_units_sac_iacc_is_nm_per_s2 in test_io_sac.c). */
#include <stdio.h>

#include "check.h"
#include "io/record.h"

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
