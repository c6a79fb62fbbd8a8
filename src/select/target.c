/* target.c: the target spectra of a selection (target.h).
 *
 * Eurocode 8: CEN, EN 1998-1:2004, Eurocode 8: Design of structures for
 * earthquake resistance, Part 1, section 3.2.2.2, the horizontal elastic
 * response spectrum, eqs. (3.2)-(3.5), with the damping correction eq.
 * (3.6) and the recommended parameters of Table 3.2 (type 1) and Table 3.3
 * (type 2).  ASCE/SEI 7-22, Minimum Design Loads and Associated Criteria
 * for Buildings and Other Structures, the two-period design response
 * spectrum (Fig. 11.4-1: T_0 = 0.2 S_D1/S_DS, T_S = S_D1/S_DS, T_L) and the
 * MCE_R spectrum, 1.5 times it.  docs/select.md restates both. */
#define _POSIX_C_SOURCE 200809L
#include "target.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/number.h"
#include "../units.h"

/* EN 1998-1:2004 Tables 3.2 and 3.3: S, T_B, T_C, T_D (s) of grounds A..E. */
static const double ec8_table[2][5][4] = {
    {{1.0, 0.15, 0.4, 2.0},   /* type 1, Table 3.2 */
     {1.2, 0.15, 0.5, 2.0},
     {1.15, 0.20, 0.6, 2.0},
     {1.35, 0.20, 0.8, 2.0},
     {1.4, 0.15, 0.5, 2.0}},
    {{1.0, 0.05, 0.25, 1.2},  /* type 2, Table 3.3 */
     {1.35, 0.05, 0.25, 1.2},
     {1.5, 0.10, 0.25, 1.2},
     {1.8, 0.10, 0.30, 1.2},
     {1.6, 0.05, 0.25, 1.2}},
};

#define ETA_MIN 0.55  /* eq. (3.6) */
#define MCER_FACTOR 1.5 /* the MCE_R spectrum over the design spectrum */
#define TARGET_CSV_MAX (1u << 20) /* rows of a CSV target */

/* A SPEC's parameters: key=value pairs, comma-separated, and bare words. */
#define MAX_PARAMS 16
typedef struct {
  char key[32], value[64];
  int bare, used;
} param;

static aq_status bad(aq_error *err, const char *code, const char *key, const char *fmt,
                     const char *got)
{
  char field[96];
  snprintf(field, sizeof field, "%s: %s", code, key);
  return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, field, "expected %s, got \"%s\"",
                      fmt, got);
}

static aq_status split(const char *code, const char *s, param *p, size_t *np, aq_error *err)
{
  *np = 0;
  while (*s) {
    size_t len = strcspn(s, ",");
    const char *eq = memchr(s, '=', len);
    if (*np == MAX_PARAMS || len == 0)
      return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, code,
                          "expected KEY=VALUE pairs separated by commas, got \"%s\"", s);
    param *q = &p[(*np)++];
    memset(q, 0, sizeof *q);
    size_t klen = eq ? (size_t)(eq - s) : len;
    size_t vlen = eq ? len - klen - 1 : 0;
    if (klen == 0 || klen >= sizeof q->key || vlen >= sizeof q->value)
      return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, code,
                          "expected KEY=VALUE pairs separated by commas, got \"%.*s\"",
                          (int)len, s);
    memcpy(q->key, s, klen);
    if (eq)
      memcpy(q->value, eq + 1, vlen);
    q->bare = !eq;
    for (size_t i = 0; i + 1 < *np; i++)
      if (!strcmp(p[i].key, q->key))
        return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, code,
                            "expected each parameter once, got %s twice", q->key);
    s += len + (s[len] == ',');
  }
  return AQ_OK;
}

/* The parameter key (a value), or NULL; marks it used. */
static param *find(param *p, size_t np, const char *key)
{
  for (size_t i = 0; i < np; i++)
    if (!strcmp(p[i].key, key)) {
      p[i].used = 1;
      return &p[i];
    }
  return NULL;
}

/* A number in (lo, hi] from parameter key; required: an error if absent. */
static aq_status number(const char *code, param *p, size_t np, const char *key, int required,
                        double lo, double hi, const char *what, double *out, aq_error *err)
{
  param *q = find(p, np, key);
  if (!q) {
    if (!required)
      return AQ_OK;
    char field[96];
    snprintf(field, sizeof field, "%s: %s", code, key);
    return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, field, "expected %s=%s, got none",
                        key, what);
  }
  double x;
  size_t len = strlen(q->value);
  if (q->bare || len == 0 || aq_number_parse_finite(q->value, len, 0, &x) != len ||
      !(x > lo && x <= hi))
    return bad(err, code, key, what, q->bare ? "" : q->value);
  *out = x;
  return AQ_OK;
}

static aq_status unknown_left(const char *code, const param *p, size_t np, const char *known,
                              aq_error *err)
{
  for (size_t i = 0; i < np; i++)
    if (!p[i].used)
      return aq_error_set(err, AQ_EVALUE, "--target", -1, -1, code,
                          "expected parameters %s, got unknown \"%s\"", known, p[i].key);
  return AQ_OK;
}

static aq_status parse_ec8(const char *s, aq_target *t, aq_error *err)
{
  param p[MAX_PARAMS];
  size_t np;
  aq_status st = split("ec8", s, p, &np, err);
  double type = NAN, ag_g = NAN;
  t->importance = 1;
  t->damping = 0.05;
  if (st == AQ_OK)
    st = number("ec8", p, np, "type", 1, 0, 2, "1 or 2", &type, err);
  if (st == AQ_OK && type != 1 && type != 2)
    st = bad(err, "ec8", "type", "1 or 2", find(p, np, "type")->value);
  param *g = st == AQ_OK ? find(p, np, "ground") : NULL;
  if (st == AQ_OK && !g)
    st = aq_error_set(err, AQ_EVALUE, "--target", -1, -1, "ec8: ground",
                      "expected ground=A|B|C|D|E, got none");
  if (st == AQ_OK && (g->bare || strlen(g->value) != 1 ||
                      !strchr("ABCDE", toupper((unsigned char)g->value[0]))))
    st = bad(err, "ec8", "ground", "one of A, B, C, D, E (Table 3.1; S1 and S2 need a study "
             "of the site)", g->value);
  if (st == AQ_OK)
    st = number("ec8", p, np, "ag", 1, 0, 10, "a_gR in g, 0 < ag <= 10", &ag_g, err);
  if (st == AQ_OK)
    st = number("ec8", p, np, "importance", 0, 0, 10, "gamma_I > 0", &t->importance, err);
  if (st == AQ_OK)
    st = number("ec8", p, np, "damping", 0, 0, 0.99, "a ratio in (0, 1), e.g. 0.05",
                &t->damping, err);
  if (st == AQ_OK)
    st = unknown_left("ec8", p, np, "type, ground, ag, importance, damping", err);
  if (st != AQ_OK)
    return st;
  t->kind = AQ_TARGET_EC8;
  t->ec8_type = (int)type;
  t->ground = (char)toupper((unsigned char)g->value[0]);
  const double *row = ec8_table[t->ec8_type - 1][t->ground - 'A'];
  t->soil = row[0];
  t->tb_s = row[1];
  t->tc_s = row[2];
  t->td_s = row[3];
  t->agr_mps2 = ag_g * AQ_G0_MPS2;
  t->ag_mps2 = t->importance * t->agr_mps2;
  t->eta = sqrt(10.0 / (5.0 + 100.0 * t->damping)); /* eq. (3.6), xi in percent */
  if (t->eta < ETA_MIN)
    t->eta = ETA_MIN;
  return AQ_OK;
}

static aq_status parse_asce7(const char *s, aq_target *t, aq_error *err)
{
  param p[MAX_PARAMS];
  size_t np;
  double sds = NAN, sd1 = NAN;
  aq_status st = split("asce7", s, p, &np, err);
  if (st == AQ_OK)
    st = number("asce7", p, np, "sds", 1, 0, 10, "S_DS in g, 0 < sds <= 10", &sds, err);
  if (st == AQ_OK)
    st = number("asce7", p, np, "sd1", 1, 0, 10, "S_D1 in g, 0 < sd1 <= 10", &sd1, err);
  if (st == AQ_OK)
    st = number("asce7", p, np, "tl", 1, 0, 100, "T_L in s, 0 < tl <= 100", &t->tl_s, err);
  param *m = st == AQ_OK ? find(p, np, "mcer") : NULL;
  if (m && !m->bare)
    st = bad(err, "asce7", "mcer", "the word mcer alone (the MCE_R spectrum)", m->value);
  if (st == AQ_OK)
    st = unknown_left("asce7", p, np, "sds, sd1, tl, mcer", err);
  if (st == AQ_OK && !(sd1 / sds < t->tl_s))
    st = aq_error_set(err, AQ_EVALUE, "--target", -1, -1, "asce7: tl",
                      "expected T_L above T_S = sd1/sds = %g s, got %g s", sd1 / sds, t->tl_s);
  if (st != AQ_OK)
    return st;
  t->kind = AQ_TARGET_ASCE7;
  t->sds_mps2 = sds * AQ_G0_MPS2;
  t->sd1_mps2 = sd1 * AQ_G0_MPS2;
  t->mcer = m != NULL;
  t->damping = 0.05;
  return AQ_OK;
}

/* One CSV field: blanks trimmed, into a number; 1 if it is one. */
static int csv_number(const char *p, size_t len, double *x)
{
  while (len && isspace((unsigned char)*p))
    p++, len--;
  while (len && isspace((unsigned char)p[len - 1]))
    len--;
  return len && aq_number_parse_finite(p, len, 0, x) == len;
}

static aq_status parse_csv(const char *path, aq_target *t, aq_error *err)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, "--target",
                        "expected ec8:..., asce7:... or a CSV file period_s,psa_g, got a "
                        "name that is neither a code nor a readable file");
  char line[512];
  long ln = 0;
  aq_status st = AQ_OK;
  size_t cap = 0;
  t->kind = AQ_TARGET_CSV;
  t->damping = 0.05;
  while (st == AQ_OK && fgets(line, sizeof line, f)) {
    ln++;
    size_t len = strcspn(line, "\r\n");
    if (len == strlen(line) && !feof(f)) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL, "expected a line of at most %zu "
                        "characters", sizeof line - 2);
      break;
    }
    line[len] = '\0';
    if (ln == 1) {
      char h[64];
      size_t k = 0;
      for (size_t i = 0; i < len && k + 1 < sizeof h; i++)
        if (!isspace((unsigned char)line[i]))
          h[k++] = line[i];
      h[k] = '\0';
      if (strcmp(h, "period_s,psa_g") != 0)
        st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, "header",
                          "expected \"period_s,psa_g\" (period in s, PSA in g), got \"%.60s\"",
                          line);
      continue;
    }
    if (strspn(line, " \t") == len)
      continue; /* a blank line */
    const char *comma = strchr(line, ',');
    double T, a;
    if (!comma || strchr(comma + 1, ',') || !csv_number(line, (size_t)(comma - line), &T) ||
        !csv_number(comma + 1, strlen(comma + 1), &a)) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL,
                        "expected two numbers period_s,psa_g, got \"%.60s\"", line);
      break;
    }
    if (!(T >= 0) || (t->n && !(T > t->period_s[t->n - 1]))) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, "period_s",
                        "expected periods >= 0 s in increasing order, got %g after %g", T,
                        t->n ? t->period_s[t->n - 1] : -1.0);
      break;
    }
    if (!(a > 0) || a > 100) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, "psa_g",
                        "expected a spectral acceleration in g, 0 < psa_g <= 100, got %g", a);
      break;
    }
    if (t->n == cap) {
      cap = cap ? 2 * cap : 64;
      double *pp = cap <= TARGET_CSV_MAX ? realloc(t->period_s, cap * sizeof *pp) : NULL;
      double *pa = pp ? realloc(t->psa_mps2, cap * sizeof *pa) : NULL;
      if (pp)
        t->period_s = pp;
      if (pa)
        t->psa_mps2 = pa;
      if (!pp || !pa) {
        st = aq_error_set(err, AQ_ENOMEM, path, ln, -1, NULL, "out of memory");
        break;
      }
    }
    t->period_s[t->n] = T;
    t->psa_mps2[t->n++] = a * AQ_G0_MPS2;
  }
  if (st == AQ_OK && ferror(f))
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "read error");
  fclose(f);
  if (st == AQ_OK && t->n < 2)
    st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL,
                      "expected at least two rows period_s,psa_g, got %zu", t->n);
  return st;
}

aq_status aq_target_parse(const char *spec, aq_target *t, aq_error *err)
{
  memset(t, 0, sizeof *t);
  snprintf(t->spec, sizeof t->spec, "%s", spec);
  aq_status st;
  if (!strncmp(spec, "ec8:", 4))
    st = parse_ec8(spec + 4, t, err);
  else if (!strncmp(spec, "asce7:", 6))
    st = parse_asce7(spec + 6, t, err);
  else if (!strcmp(spec, "ec8") || !strcmp(spec, "asce7"))
    st = aq_error_set(err, AQ_EVALUE, "--target", -1, -1, spec,
                      "expected %s:KEY=VALUE,... (docs/select.md), got no parameters", spec);
  else
    st = parse_csv(spec, t, err);
  if (st != AQ_OK)
    aq_target_free(t);
  return st;
}

void aq_target_free(aq_target *t)
{
  free(t->period_s);
  free(t->psa_mps2);
  t->period_s = t->psa_mps2 = NULL;
  t->n = 0;
}

static double ec8_psa(const aq_target *t, double T)
{
  double top = t->ag_mps2 * t->soil * t->eta * 2.5;
  if (T < t->tb_s) /* eq. (3.2) */
    return t->ag_mps2 * t->soil * (1.0 + T / t->tb_s * (t->eta * 2.5 - 1.0));
  if (T <= t->tc_s) /* eq. (3.3) */
    return top;
  if (T <= t->td_s) /* eq. (3.4) */
    return top * t->tc_s / T;
  return top * t->tc_s * t->td_s / (T * T); /* eq. (3.5) */
}

static double asce7_psa(const aq_target *t, double T)
{
  double t0 = 0.2 * t->sd1_mps2 / t->sds_mps2, ts = t->sd1_mps2 / t->sds_mps2, sa;
  if (T < t0)
    sa = t->sds_mps2 * (0.4 + 0.6 * T / t0);
  else if (T <= ts)
    sa = t->sds_mps2;
  else if (T <= t->tl_s)
    sa = t->sd1_mps2 / T;
  else
    sa = t->sd1_mps2 * t->tl_s / (T * T);
  return t->mcer ? MCER_FACTOR * sa : sa;
}

static double csv_psa(const aq_target *t, double T)
{
  size_t hi = 1;
  while (hi + 1 < t->n && t->period_s[hi] < T)
    hi++;
  double t0 = t->period_s[hi - 1], t1 = t->period_s[hi];
  double a0 = t->psa_mps2[hi - 1], a1 = t->psa_mps2[hi];
  if (T == t1)
    return a1;
  if (T == t0)
    return a0;
  if (t0 == 0) /* linear in T from the PGA */
    return a0 + (a1 - a0) * T / t1;
  double u = log(T / t0) / log(t1 / t0);
  return exp(log(a0) + u * log(a1 / a0));
}

double aq_target_psa(const aq_target *t, double period_s)
{
  double lo, hi;
  aq_target_periods(t, &lo, &hi);
  if (!(period_s >= lo && period_s <= hi))
    return NAN;
  switch (t->kind) {
  case AQ_TARGET_EC8:
    return ec8_psa(t, period_s);
  case AQ_TARGET_ASCE7:
    return asce7_psa(t, period_s);
  case AQ_TARGET_CSV:
    return csv_psa(t, period_s);
  }
  return NAN;
}

void aq_target_periods(const aq_target *t, double *lo_s, double *hi_s)
{
  *lo_s = t->kind == AQ_TARGET_CSV && t->n ? t->period_s[0] : 0.0;
  *hi_s = t->kind == AQ_TARGET_EC8     ? AQ_TARGET_EC8_TMAX_S
          : t->kind == AQ_TARGET_ASCE7 ? INFINITY
          : t->n                      ? t->period_s[t->n - 1]
                                      : 0.0;
}

void aq_target_describe(const aq_target *t, char *buf, size_t n)
{
  switch (t->kind) {
  case AQ_TARGET_EC8:
    snprintf(buf, n, "EN 1998-1:2004 3.2.2.2, type %d, ground %c: a_g = %g x %g g = %g g, "
             "S = %g, T_B = %g s, T_C = %g s, T_D = %g s, damping %g (eta = %.6g)",
             t->ec8_type, t->ground, t->importance, t->agr_mps2 / AQ_G0_MPS2,
             t->ag_mps2 / AQ_G0_MPS2, t->soil, t->tb_s, t->tc_s, t->td_s, t->damping, t->eta);
    break;
  case AQ_TARGET_ASCE7:
    snprintf(buf, n, "ASCE/SEI 7-22 %s: S_DS = %g g, S_D1 = %g g, T_0 = %.6g s, T_S = %.6g s, "
             "T_L = %g s, damping 0.05",
             t->mcer ? "MCE_R spectrum (1.5 x the design spectrum)" : "design response spectrum",
             t->sds_mps2 / AQ_G0_MPS2, t->sd1_mps2 / AQ_G0_MPS2,
             0.2 * t->sd1_mps2 / t->sds_mps2, t->sd1_mps2 / t->sds_mps2, t->tl_s);
    break;
  case AQ_TARGET_CSV:
    snprintf(buf, n, "the CSV %s: %zu periods, %g to %g s, damping 0.05", t->spec, t->n,
             t->n ? t->period_s[0] : 0.0, t->n ? t->period_s[t->n - 1] : 0.0);
    break;
  }
}

const char *aq_target_code(const aq_target *t)
{
  return t->kind == AQ_TARGET_EC8 ? "ec8" : t->kind == AQ_TARGET_ASCE7 ? "asce7" : "none";
}
