/* select_fixture.h: what the tests of `archquake select` share: the
 * target of most of them, EN 1998-1:2004 (Eurocode 8, Part 1) section
 * 3.2.2.2's horizontal elastic spectrum, type 1, ground B (Table 3.2: S
 * 1.2, T_B 0.15 s, T_C 0.5 s, T_D 2 s), a_g = 0.25 g, 5 % (eta = 1), by
 * eqs. (3.2)-(3.5), written here from the standard. */
#ifndef AQ_TESTS_SELECT_FIXTURE_H
#define AQ_TESTS_SELECT_FIXTURE_H

#define AQ_TEST_EC8B "ec8:type=1,ground=B,ag=0.25"

/* S_e(T) of that target, g. */
static inline double aq_test_ec8_b(double T)
{
  double ag = 0.25, S = 1.2, TB = 0.15, TC = 0.5, TD = 2.0;
  if (T <= TB)
    return ag * S * (1 + T / TB * 1.5);
  if (T <= TC)
    return ag * S * 2.5;
  if (T <= TD)
    return ag * S * 2.5 * TC / T;
  return ag * S * 2.5 * TC * TD / (T * T);
}

#endif
