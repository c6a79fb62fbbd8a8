/* test_io_scale.c: the samples' conversion to m/s2 in aq_record_decide
 * (record.c), which reads them several at a time: every sample is its
 * value times the units factor (1 g = 9.80665 m/s2 exactly, CGPM 1901; one
 * IEEE multiply, so the product computed here is the one expected), the
 * PGA is the largest |value| wherever it sits, and a value whose product is
 * not finite is refused naming its number and the value as stored, at
 * every position of a record of every length from 1 to 13 samples: in the
 * copy aq_record_decide makes and in place, as aq_record_parse converts an
 * AT2 file's own array. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define G_MPS2 9.80665 /* standard gravity, m/s2 (CGPM 1901) */
#define MAX_N 13

/* A raw file of one channel in g holding v[0..n). */
static int raw_of(const double *v, size_t n, aq_raw_file *raw)
{
  aq_error e;
  memset(raw, 0, sizeof *raw);
  if (aq_raw_file_alloc(raw, 1, "scale.txt", &e) != AQ_OK)
    return 0;
  aq_raw_channel *ch = &raw->chan[0];
  ch->values = malloc(n * sizeof *ch->values);
  if (!ch->values)
    return 0;
  memcpy(ch->values, v, n * sizeof *v);
  ch->npts = n;
  ch->dt_s = 0.01;
  snprintf(ch->units, sizeof ch->units, "g");
  return 1;
}

/* An AT2 file of v[0..n) (in g, "%.17g", one a line) into buf. */
static size_t at2_of(const double *v, size_t n, char *buf, size_t cap)
{
  size_t k = (size_t)snprintf(buf, cap,
                              "PEER TEST\nSCALE\nACCELERATION TIME SERIES IN UNITS OF G\n"
                              "NPTS= %zu, DT= .0100 SEC\n",
                              n);
  for (size_t i = 0; i < n; i++)
    k += (size_t)snprintf(buf + k, cap - k, "%.17g\n", v[i]);
  return k;
}

/* decide (copy: in_place 0) or parse (in place: 1) v[0..n); status. */
static aq_status convert(const double *v, size_t n, int in_place, aq_record *r, aq_error *e)
{
  aq_error_clear(e);
  memset(r, 0, sizeof *r);
  if (in_place) {
    char buf[2048];
    size_t len = at2_of(v, n, buf, sizeof buf);
    return aq_record_parse((const unsigned char *)buf, len, "scale.AT2", NULL, r, e);
  }
  aq_raw_file raw;
  if (!raw_of(v, n, &raw)) {
    aq_raw_file_free(&raw);
    return AQ_ENOMEM;
  }
  aq_status s = aq_record_decide(&raw, 0, "scale.txt", NULL, r, e);
  aq_raw_file_free(&raw);
  return s;
}

static double random_g(uint64_t *x)
{
  *x ^= *x << 13, *x ^= *x >> 7, *x ^= *x << 17;
  double u = (double)(*x >> 11) / 9007199254740992.0; /* [0, 1) */
  return (*x & 1 ? -1 : 1) * (0.001 + 0.9 * u);
}

AQ_TEST(io_scale_every_sample)
{
  uint64_t x = 0x2385417ULL;
  size_t bad = 0, cases = 0;
  for (int in_place = 0; in_place < 2; in_place++)
    for (size_t n = 1; n <= MAX_N; n++) {
      double v[MAX_N];
      for (size_t i = 0; i < n; i++)
        v[i] = random_g(&x);
      if (n > 2)
        v[n / 2] = -0.0;
      aq_record r;
      aq_error e;
      aq_status s = convert(v, n, in_place, &r, &e);
      cases++;
      if (!aq_check(s == AQ_OK && r.npts == n, "n %zu: %s", n, e.message)) {
        bad++;
        continue;
      }
      for (size_t i = 0; i < n; i++) {
        double want = v[i] * G_MPS2;
        if (memcmp(&want, &r.acc_mps2[i], sizeof want) != 0) {
          bad++;
          aq_check(0, "n %zu%s: sample %zu is %.17g, expected %.17g", n,
                   in_place ? " in place" : "", i, r.acc_mps2[i], want);
        }
      }
      aq_record_free(&r);
    }
  aq_check(bad == 0, "%zu of %zu records converted wrong", bad, cases);
}

/* One value of 10.5 g (implausible: above AQ_PGA_MAX_G = 10 g) among
 * 0.001 g ones, at each position and with each sign: refused with PGA
 * 10.5 g; 9.75 g instead: accepted. */
AQ_TEST(io_scale_peak_anywhere)
{
  size_t bad = 0;
  for (int in_place = 0; in_place < 2; in_place++)
    for (size_t n = 1; n <= MAX_N; n++)
      for (size_t at = 0; at < n; at++)
        for (int sign = -1; sign <= 1; sign += 2) {
          double v[MAX_N];
          for (size_t i = 0; i < n; i++)
            v[i] = i % 2 ? 0.001 : -0.001;
          aq_record r;
          aq_error e;
          v[at] = 10.5 * sign;
          aq_status s = convert(v, n, in_place, &r, &e);
          if (s == AQ_OK)
            aq_record_free(&r);
          if (!aq_check(s == AQ_EUNITS && strstr(e.message, "PGA 10.5 g"),
                        "n %zu, %g at %zu%s: expected a refusal with PGA 10.5 g, got %s", n,
                        v[at], at, in_place ? " in place" : "", s == AQ_OK ? "none" : e.message))
            bad++;
          v[at] = 9.75 * sign;
          s = convert(v, n, in_place, &r, &e);
          if (!aq_check(s == AQ_OK, "n %zu, %g at %zu: %s", n, v[at], at, e.message))
            bad++;
          else
            aq_record_free(&r);
        }
  aq_check(bad == 0, "%zu records with the peak misread", bad);
}

/* A value whose product in m/s2 overflows (1e308 g), or, in the copy, a
 * NaN or an infinity as stored, at each position: refused naming "value
 * k" and the value as stored. */
AQ_TEST(io_scale_not_finite_anywhere)
{
  static const double odd[] = {1e308, -1.5e308, NAN, INFINITY};
  static const char *const said[] = {"got 1e+308 g", "got -1.5e+308 g", "got nan g", "got inf g"};
  size_t bad = 0;
  for (int in_place = 0; in_place < 2; in_place++)
    for (size_t n = 1; n <= MAX_N; n++)
      for (size_t at = 0; at < n; at++)
        for (size_t o = 0; o < (in_place ? 2 : 4); o++) { /* an AT2 has no NaN */
          double v[MAX_N];
          for (size_t i = 0; i < n; i++)
            v[i] = i % 2 ? 0.25 : -0.125;
          v[at] = odd[o];
          if (at + 1 < n) /* a second one after it: the first is named */
            v[at + 1] = odd[(o + 1) % 2];
          aq_record r;
          aq_error e;
          aq_status s = convert(v, n, in_place, &r, &e);
          char field[40];
          snprintf(field, sizeof field, "value %zu", at + 1);
          if (s == AQ_OK)
            aq_record_free(&r);
          if (!aq_check(s == AQ_EVALUE && strcmp(e.field, field) == 0 &&
                            strstr(e.message, said[o]) && strstr(e.message, "finite in m/s2"),
                        "n %zu, %g at %zu%s: expected \"%s\" refused (%s), got %s: %s", n,
                        odd[o], at, in_place ? " in place" : "", field, said[o],
                        s == AQ_OK ? "read" : e.field, s == AQ_OK ? "" : e.message))
            bad++;
        }
  aq_check(bad == 0, "%zu records with a value not finite misread", bad);
}
