/* src/select: suites of records chosen and scaled to a target spectrum.
 *
 * target.h: the target spectrum of a selection, from its SPEC:
 *   ec8:type=1|2,ground=A..E,ag=G[,importance=GAMMA][,damping=ZETA]
 *       the horizontal elastic response spectrum of EN 1998-1:2004
 *       section 3.2.2.2 (eqs. 3.2-3.6), S, T_B, T_C and T_D from its Table
 *       3.2 (type 1) or 3.3 (type 2); a_g = GAMMA a_gR, ag the reference
 *       peak ground acceleration a_gR on ground A, in g; defined up to 4 s;
 *   asce7:sds=G,sd1=G,tl=S[,mcer]
 *       the ASCE/SEI 7-22 two-period design response spectrum (T_0 = 0.2
 *       S_D1/S_DS, T_S = S_D1/S_DS, T_L), and with mcer the risk-targeted
 *       maximum considered earthquake spectrum, 1.5 times it; 5 % damping;
 *   FILE (anything else): a CSV of the user's own, a header row
 *       "period_s,psa_g" then one row per period (s, increasing; the first
 *       may be 0, the PGA) with PSA > 0 in g, at 5 % damping, interpolated
 *       linearly in log T and log PSA (linearly in T between 0 and the
 *       first period above it).
 *
 * Units: periods in s, spectral accelerations in m/s^2 (g only in SPEC and
 * the CSV).  The target owns its arrays (aq_target_free; a zeroed target is
 * fine).  Nothing prints: a bad SPEC fills the aq_error with one line naming
 * the parameter (or the file and line) and what was expected. */
#ifndef AQ_SELECT_TARGET_H
#define AQ_SELECT_TARGET_H

#include <stddef.h>

#include "../error.h"

typedef enum { AQ_TARGET_EC8 = 0, AQ_TARGET_ASCE7, AQ_TARGET_CSV } aq_target_kind;

typedef struct {
  aq_target_kind kind;
  char spec[256];    /* the SPEC as given (cut to fit) */
  double damping;    /* ratio of critical damping of the spectrum (0.05 unless ec8's damping=) */
  /* ec8 */
  int ec8_type;      /* 1 or 2 */
  char ground;       /* 'A'..'E' */
  double agr_mps2;   /* reference peak ground acceleration a_gR on ground A, m/s^2 */
  double importance; /* gamma_I (default 1) */
  double ag_mps2;    /* design ground acceleration a_g = gamma_I a_gR, m/s^2 */
  double soil;       /* S */
  double tb_s, tc_s, td_s; /* corner periods, s */
  double eta;        /* damping correction, sqrt(10 / (5 + 100 zeta)) >= 0.55 (eq. 3.6) */
  /* asce7 */
  double sds_mps2, sd1_mps2; /* S_DS, S_D1, m/s^2 */
  double tl_s;       /* T_L, s */
  int mcer;          /* 1: the MCE_R spectrum (1.5 times the design spectrum) */
  /* csv */
  size_t n;
  double *period_s;  /* n periods, s, increasing (the first may be 0) */
  double *psa_mps2;  /* n values, m/s^2, > 0 */
} aq_target;

/* The longest period of the EC8 elastic spectrum, s (EN 1998-1 eq. 3.5
 * holds for T_D <= T <= 4 s). */
#define AQ_TARGET_EC8_TMAX_S 4.0

/* Parse spec into *t (zeroed first).  Returns AQ_OK; AQ_EVALUE with err
 * naming the parameter ("--target: ec8: ground: expected one of A, B, C, D,
 * E, got \"F\"") for a missing, unknown or out-of-range parameter; for a CSV
 * AQ_EIO (cannot be read) or AQ_EFORMAT (err names the file and line);
 * AQ_ENOMEM. */
aq_status aq_target_parse(const char *spec, aq_target *t, aq_error *err);

void aq_target_free(aq_target *t);

/* The target's PSA at period_s (s, >= 0), m/s^2; NAN outside its periods
 * (aq_target_periods). */
double aq_target_psa(const aq_target *t, double period_s);

/* The periods over which the target is defined, s: *lo_s (0, or a CSV's
 * first) to *hi_s (4 s for ec8, INFINITY for asce7, a CSV's last). */
void aq_target_periods(const aq_target *t, double *lo_s, double *hi_s);

/* One line describing the target with every value it uses, into buf[n]
 * ("EN 1998-1:2004 3.2.2.2 type 1, ground B: a_g = 0.25 g, S = 1.2, T_B =
 * 0.15 s, T_C = 0.5 s, T_D = 2 s, eta = 1"). */
void aq_target_describe(const aq_target *t, char *buf, size_t n);

/* The code whose conditions apply: "ec8", "asce7" or "none" (a CSV). */
const char *aq_target_code(const aq_target *t);

#endif
