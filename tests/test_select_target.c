/* test_select_target.c: the target spectra of `archquake select`
 * (src/select/target.h) against values computed here from the codes:
 *
 * EN 1998-1:2004 (CEN, Eurocode 8: Design of structures for earthquake
 * resistance, Part 1) section 3.2.2.2, eqs. (3.2)-(3.6), with the
 * recommended S, T_B, T_C, T_D of its Table 3.2 (type 1) and Table 3.3 (type
 * 2), written out below as the standard prints them (the same values are
 * tabulated in ROB-Seismology/rshalib, refspec/en1998.py, and by CSI's
 * ETABS documentation of the "2004 Eurocode 8" spectrum function).
 *
 * ASCE/SEI 7-22 two-period design response spectrum (Fig. 11.4-1): S_DS
 * (0.4 + 0.6 T/T_0) below T_0 = 0.2 S_D1/S_DS, S_DS up to T_S = S_D1/S_DS,
 * S_D1/T up to T_L, S_D1 T_L/T^2 beyond; the MCE_R spectrum 1.5 times it.
 *
 * And a CSV target's interpolation (log-log between rows), and bad SPECs:
 * one error naming the parameter. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "select/target.h"

#define G0 9.80665 /* m/s^2 per g (literal) */
#define REL 1e-13  /* the formulas are a few operations */

/* Table 3.2 and Table 3.3: S, T_B, T_C, T_D of grounds A..E. */
static const double table[2][5][4] = {
    {{1.0, 0.15, 0.4, 2.0}, {1.2, 0.15, 0.5, 2.0}, {1.15, 0.20, 0.6, 2.0},
     {1.35, 0.20, 0.8, 2.0}, {1.4, 0.15, 0.5, 2.0}},
    {{1.0, 0.05, 0.25, 1.2}, {1.35, 0.05, 0.25, 1.2}, {1.5, 0.10, 0.25, 1.2},
     {1.8, 0.10, 0.30, 1.2}, {1.6, 0.05, 0.25, 1.2}}};

/* The EC8 spectrum at T, written here from eqs. (3.2)-(3.5). */
static double ec8(double ag, double S, double TB, double TC, double TD, double eta, double T)
{
  if (T <= TB)
    return ag * S * (1 + T / TB * (eta * 2.5 - 1));
  if (T <= TC)
    return ag * S * eta * 2.5;
  if (T <= TD)
    return ag * S * eta * 2.5 * TC / T;
  return ag * S * eta * 2.5 * TC * TD / (T * T);
}

AQ_TEST(select_target_ec8_tables)
{
  static const double damping[] = {0.05, 0.07};
  char spec[160];
  for (int type = 1; type <= 2; type++)
    for (int g = 0; g < 5; g++)
      for (int d = 0; d < 2; d++) {
        const double *row = table[type - 1][g];
        double agr = 0.2385, gamma = 1.2, ag = gamma * agr * G0;
        double eta = sqrt(10.0 / (5 + 100 * damping[d])); /* eq. (3.6), >= 0.55 */
        snprintf(spec, sizeof spec, "ec8:type=%d,ground=%c,ag=%g,importance=%g,damping=%g",
                 type, 'A' + g, agr, gamma, damping[d]);
        aq_target t;
        aq_error e;
        if (!aq_check(aq_target_parse(spec, &t, &e) == AQ_OK, "%s: %s", spec, e.message))
          continue;
        /* the corners, the plateau and points on every branch */
        const double T[] = {0,          row[1] / 2, row[1],     (row[1] + row[2]) / 2,
                            row[2],     1.37 * row[2], row[3],  (row[3] + 4) / 2,
                            4.0};
        for (size_t i = 0; i < sizeof T / sizeof T[0]; i++) {
          double want = ec8(ag, row[0], row[1], row[2], row[3], eta, T[i]);
          aq_check_rel(aq_target_psa(&t, T[i]), want, REL, "%s at %g s", spec, T[i]);
        }
        aq_check_rel(aq_target_psa(&t, 0), ag * row[0], REL, "%s: Se(0) = a_g S", spec);
        aq_check_rel(aq_target_psa(&t, row[2]), ag * row[0] * eta * 2.5, REL,
                     "%s: the plateau 2.5 eta a_g S", spec);
        aq_check(isnan(aq_target_psa(&t, 4.01)), "%s: not defined beyond 4 s", spec);
        aq_target_free(&t);
      }
}

/* eq. (3.6): eta = sqrt(10 / (5 + xi)) but never below 0.55: at 30 % and
 * 40 % damping (sqrt(10/35) = 0.535, sqrt(10/45) = 0.471) the floor; at
 * 25 % (sqrt(10/30) = 0.577) not. */
AQ_TEST(select_target_ec8_eta_floor)
{
  static const double damping[] = {0.25, 0.3, 0.4}, eta[] = {0.5773502691896258, 0.55, 0.55};
  for (int i = 0; i < 3; i++) {
    char spec[96];
    snprintf(spec, sizeof spec, "ec8:type=1,ground=C,ag=0.3,damping=%g", damping[i]);
    aq_target t;
    aq_error e;
    if (!aq_check(aq_target_parse(spec, &t, &e) == AQ_OK, "%s", e.message))
      continue;
    double want = 0.3 * G0 * 1.15 * eta[i] * 2.5;
    aq_check_rel(aq_target_psa(&t, 0.4), want, REL, "%s: plateau with eta %g", spec, eta[i]);
    aq_target_free(&t);
  }
}

AQ_TEST(select_target_asce7)
{
  const double sds = 1.137, sd1 = 0.583, tl = 6; /* g, g, s */
  const double t0 = 0.2 * sd1 / sds, ts = sd1 / sds;
  for (int m = 0; m < 2; m++) {
    aq_target t;
    aq_error e;
    const char *spec = m ? "asce7:sds=1.137,sd1=0.583,tl=6,mcer" : "asce7:sds=1.137,sd1=0.583,tl=6";
    if (!aq_check(aq_target_parse(spec, &t, &e) == AQ_OK, "%s: %s", spec, e.message))
      continue;
    double f = m ? 1.5 : 1.0;
    const double T[] = {0, t0 / 2, t0, (t0 + ts) / 2, ts, 1.0, 3.3, tl, 2 * tl};
    const double want[] = {0.4 * sds,
                           sds * (0.4 + 0.6 * 0.5),
                           sds,
                           sds,
                           sds,
                           sd1 / 1.0,
                           sd1 / 3.3,
                           sd1 / tl,
                           sd1 * tl / (4 * tl * tl)};
    for (size_t i = 0; i < sizeof T / sizeof T[0]; i++)
      aq_check_rel(aq_target_psa(&t, T[i]), f * want[i] * G0, REL, "%s at %g s", spec, T[i]);
    aq_target_free(&t);
  }
}

AQ_TEST(select_target_csv)
{
  char dir[256], path[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/uhs.csv", dir);
  FILE *f = fopen(path, "w");
  fprintf(f, "period_s,psa_g\n0,0.31\n0.1,0.62\n0.3,0.815\n1.2,0.2743\n\n4,0.0511\n");
  fclose(f);
  aq_target t;
  aq_error e;
  if (!aq_check(aq_target_parse(path, &t, &e) == AQ_OK, "%s", e.message))
    return;
  aq_check_rel(aq_target_psa(&t, 0.3), 0.815 * G0, 1e-15, "a row");
  /* log-log: at the geometric mean of two periods, the geometric mean */
  aq_check_rel(aq_target_psa(&t, sqrt(0.3 * 1.2)), sqrt(0.815 * 0.2743) * G0, 1e-13,
               "log-log between 0.3 and 1.2 s");
  aq_check_rel(aq_target_psa(&t, 0.025), (0.31 + 0.25 * (0.62 - 0.31)) * G0, 1e-13,
               "linear in T from the PGA row");
  aq_check(isnan(aq_target_psa(&t, 4.5)), "nothing beyond the last row");
  double lo, hi;
  aq_target_periods(&t, &lo, &hi);
  aq_check(lo == 0 && hi == 4, "periods %g to %g", lo, hi);
  aq_target_free(&t);
}

/* A SPEC with a missing, unknown, repeated or out-of-range parameter, and
 * bad CSVs: AQ_EVALUE or AQ_EFORMAT naming the parameter or the line. */
AQ_TEST(select_target_bad)
{
  static const struct {
    const char *spec, *field, *says;
  } bad[] = {
      {"ec8:type=1,ground=B", "ec8: ag", "got none"},
      {"ec8:type=3,ground=B,ag=0.2", "ec8: type", "1 or 2"},
      {"ec8:type=1,ground=S1,ag=0.2", "ec8: ground", "A, B, C, D, E"},
      {"ec8:type=1,ground=B,ag=-0.2", "ec8: ag", "-0.2"},
      {"ec8:type=1,ground=B,ag=0.2,soil=1.2", "ec8", "unknown \"soil\""},
      {"ec8:type=1,ground=B,ag=0.2,ag=0.3", "ec8", "twice"},
      {"ec8:type=1,ground=B,ag=0.2,damping=1.5", "ec8: damping", "(0, 1)"},
      {"ec8", "ec8", "no parameters"},
      {"asce7:sds=1,sd1=0.6", "asce7: tl", "got none"},
      {"asce7:sds=1,sd1=-0.6,tl=8", "asce7: sd1", "-0.6"},
      {"asce7:sds=1,sd1=0.6,tl=0.4", "asce7: tl", "T_S"},
      {"asce7:sds=1,sd1=0.6,tl=8,mcer=2", "asce7: mcer", "alone"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    aq_target t;
    aq_error e;
    aq_status s = aq_target_parse(bad[i].spec, &t, &e);
    aq_check(s == AQ_EVALUE, "%s: status %d", bad[i].spec, (int)s);
    aq_check(!strcmp(e.field, bad[i].field), "%s: field \"%s\"", bad[i].spec, e.field);
    aq_check(strstr(e.message, bad[i].says) != NULL, "%s: \"%s\"", bad[i].spec, e.message);
  }
  char dir[256], path[512];
  aq_test_tmpdir(dir, sizeof dir);
  static const struct {
    const char *text;
    long line;
    const char *says;
  } csv[] = {
      {"T,Sa\n0.1,0.5\n", 1, "period_s,psa_g"},
      {"period_s,psa_g\n0.1,0.5\n0.2,x\n", 3, "two numbers"},
      {"period_s,psa_g\n0.2,0.5\n0.1,0.4\n", 3, "increasing"},
      {"period_s,psa_g\n0.1,0.5\n0.2,-0.4\n", 3, "0 < psa_g"},
      {"period_s,psa_g\n0.1,0.5\n", 2, "at least two rows"},
  };
  for (size_t i = 0; i < sizeof csv / sizeof csv[0]; i++) {
    snprintf(path, sizeof path, "%s/bad%zu.csv", dir, i);
    FILE *f = fopen(path, "w");
    fputs(csv[i].text, f);
    fclose(f);
    aq_target t;
    aq_error e;
    aq_status s = aq_target_parse(path, &t, &e);
    aq_check(s == AQ_EFORMAT && e.line == csv[i].line && strstr(e.message, csv[i].says),
             "csv %zu: status %d line %ld \"%s\"", i, (int)s, e.line, e.message);
  }
  aq_target t;
  aq_error e;
  aq_check(aq_target_parse("no/such/target.csv", &t, &e) == AQ_EIO, "a missing file");
}
