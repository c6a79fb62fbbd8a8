/* A capacity result as bytes and back (archquake-mpi's messages): every
 * field equal bit for bit, and a message cut short or out of range refused
 * with the field named, never read past its end. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "capacity/capacity.h"
#include "check.h"

static int same_bits(double a, double b)
{
  return memcmp(&a, &b, sizeof a) == 0;
}

/* A result with intervals (one open), points of the scan, odd values and
 * an error record. */
static void sample(aq_capacity *c, aq_scan_interval *iv, aq_capacity_point *pt)
{
  memset(c, 0, sizeof *c);
  c->status = AQ_CAPACITY_FAILED;
  c->run_status = AQ_ENUMERIC;
  aq_error_set(&c->err, AQ_ENUMERIC, "records/x.AT2", 17, -1, "t",
               "expected a finite angle at t = 12.340 s, got nan");
  c->lambda0 = 0.17341927361;
  c->move_scale = 1.3373892266954797;
  c->scale_max = INFINITY;
  c->first_collapse_scale = 9.9193993489725258;
  c->resurrection = 1;
  c->marks = AQ_MARK_SLIDES | AQ_MARK_BEYOND;
  c->first_mark_scale = 1.3507631189624345;
  iv[0] = (aq_scan_interval){9.9193993489725258, 10.344043128593729};
  iv[1] = (aq_scan_interval){11.113704981458142, INFINITY};
  c->scan = (aq_scan_result){2, iv, 313, 290, 23};
  pt[0] = (aq_capacity_point){1.3373892266954797, 0.0071828182845, 0.031415926535, NAN, 0,
                              0};
  pt[1] = (aq_capacity_point){9.9193993489725258, 0.43429448190325, 1.0000000000000002,
                              12.340000000000001, 1, AQ_MARK_SLIDES};
  pt[2] = (aq_capacity_point){10.5, 0.0, 0.0, NAN, 0, AQ_MARK_SLIDES | AQ_MARK_BEYOND};
  c->npoint = 3;
  c->point = pt;
}

AQ_TEST(capacity_message_round_trip_is_bit_exact)
{
  aq_scan_interval iv[2];
  aq_capacity_point pt[3];
  aq_capacity c, d;
  sample(&c, iv, pt);
  aq_bytes_out w = {0};
  aq_capacity_encode(&c, &w);
  /* 5 words, 3 strings with their lengths, 4 doubles, 4 counters, the
     marks and the first marked scale, the interval count and 2 intervals,
     the point count and 3 points of 6 words */
  size_t n = 5 * 8 + 3 * 8 + strlen("records/x.AT2") + strlen("t") + strlen(c.err.message) +
             4 * 8 + 4 * 8 + 2 * 8 + 8 + 2 * 16 + 8 + 3 * 48;
  aq_check(!w.oom && w.n == n, "encode writes the layout's %zu bytes: %zu", n, w.n);
  unsigned char *b = malloc(n + 8);
  aq_check(b != NULL, "buffer");
  if (!b || w.n != n) {
    free(b);
    free(w.data);
    return;
  }
  memcpy(b, w.data, n);
  memset(b + n, 0xa5, 8);
  free(w.data);
  aq_error e;
  aq_bytes_in r = {b, n + 8, 0, NULL, 0};
  aq_check(aq_capacity_decode(&r, &d, &e) == AQ_OK, "decode");
  aq_check(r.at == n, "decode reads one result: %zu of %zu bytes", r.at, n);
  aq_check(d.status == c.status && d.run_status == c.run_status, "status");
  aq_check(d.err.status == AQ_ENUMERIC && d.err.line == 17 && d.err.byte_offset == -1,
           "error codes");
  aq_check(strcmp(d.err.input, "records/x.AT2") == 0 && strcmp(d.err.field, "t") == 0 &&
               strcmp(d.err.message, c.err.message) == 0,
           "error texts: \"%s\" \"%s\" \"%s\"", d.err.input, d.err.field, d.err.message);
  aq_check(same_bits(d.lambda0, c.lambda0) && same_bits(d.move_scale, c.move_scale) &&
               same_bits(d.scale_max, c.scale_max) &&
               same_bits(d.first_collapse_scale, c.first_collapse_scale),
           "scales bit for bit (move %.17g, first collapse %.17g)", d.move_scale,
           d.first_collapse_scale);
  aq_check(d.marks == c.marks && same_bits(d.first_mark_scale, c.first_mark_scale),
           "marks %d, first marked scale %.17g", d.marks, d.first_mark_scale);
  aq_check(d.resurrection == 1 && d.scan.runs == 313 && d.scan.grid_runs == 290 &&
               d.scan.bisect_runs == 23,
           "counters");
  aq_check(d.scan.ninterval == 2, "intervals: %zu", d.scan.ninterval);
  for (size_t k = 0; k < d.scan.ninterval && k < 2; k++)
    aq_check(same_bits(d.scan.interval[k].lo, iv[k].lo) &&
                 same_bits(d.scan.interval[k].hi, iv[k].hi),
             "interval %zu bit for bit", k);
  aq_check(d.npoint == 3, "points: %zu", d.npoint);
  for (size_t k = 0; k < d.npoint && k < 3; k++)
    aq_check(same_bits(d.point[k].scale, pt[k].scale) &&
                 same_bits(d.point[k].peak_rotation_rad, pt[k].peak_rotation_rad) &&
                 same_bits(d.point[k].peak_rotation_over_qc, pt[k].peak_rotation_over_qc) &&
                 same_bits(d.point[k].collapse_time_s, pt[k].collapse_time_s) &&
                 d.point[k].collapsed == pt[k].collapsed && d.point[k].marks == pt[k].marks,
             "point %zu bit for bit (scale %.17g)", k, d.point[k].scale);
  aq_capacity_free(&d);

  /* no intervals or points, not failed: two results back to back */
  aq_capacity z;
  memset(&z, 0, sizeof z);
  z.status = AQ_CAPACITY_NEVER_MOVES;
  z.first_collapse_scale = NAN;
  aq_bytes_out two = {0};
  aq_capacity_encode(&z, &two);
  size_t nz = two.n;
  aq_capacity_encode(&c, &two);
  if (!two.oom) {
    aq_bytes_in r2 = {two.data, two.n, 0, NULL, 0};
    aq_check(aq_capacity_decode(&r2, &d, &e) == AQ_OK && r2.at == nz &&
                 d.status == AQ_CAPACITY_NEVER_MOVES && d.scan.ninterval == 0 &&
                 d.scan.interval == NULL && d.npoint == 0 && d.point == NULL &&
                 isnan(d.first_collapse_scale),
             "first of two");
    aq_capacity_free(&d);
    aq_status s2 = aq_capacity_decode(&r2, &d, &e);
    aq_check(s2 == AQ_OK && r2.at == n + nz && d.scan.ninterval == 2 && d.npoint == 3,
             "second of two (%zu + %zu bytes)", nz, r2.at - nz);
    aq_capacity_free(&d);
  }
  free(two.data);
  free(b);
}

/* b (n bytes) copied into b2 with the word at byte at set to v: refused,
 * naming field at that byte. */
static void word_refused(const unsigned char *b, unsigned char *b2, size_t n, size_t at,
                         int64_t v, const char *field)
{
  aq_capacity d;
  aq_error e;
  memcpy(b2, b, n);
  memcpy(b2 + at, &v, sizeof v);
  aq_bytes_in r = {b2, n, 0, NULL, 0};
  aq_status s = aq_capacity_decode(&r, &d, &e);
  aq_check(s == AQ_EFORMAT && strcmp(e.field, field) == 0 && e.byte_offset == (long)at,
           "%s of %lld refused: field \"%s\" at byte %ld", field, (long long)v, e.field,
           e.byte_offset);
  aq_capacity_free(&d);
}

AQ_TEST(capacity_message_cut_or_corrupt_is_refused)
{
  aq_scan_interval iv[2];
  aq_capacity_point pt[3];
  aq_capacity c, d;
  sample(&c, iv, pt);
  aq_bytes_out w = {0};
  aq_capacity_encode(&c, &w);
  size_t n = w.n;
  unsigned char *b = w.data;
  if (!aq_check(b != NULL && !w.oom, "buffer"))
    return;
  aq_error e;
  size_t refused = 0;
  for (size_t k = 0; k < n; k++) { /* every cut: an exact-size copy for ASan */
    unsigned char *cut = malloc(k ? k : 1);
    memcpy(cut, b, k);
    aq_bytes_in r = {cut, k, 0, NULL, 0};
    aq_status s = aq_capacity_decode(&r, &d, &e);
    refused += s == AQ_EFORMAT && e.field[0] != '\0' && d.scan.interval == NULL &&
               d.point == NULL;
    aq_capacity_free(&d);
    free(cut);
  }
  aq_check(refused == n, "every cut short of %zu bytes refused, with a field: %zu", n,
           refused);
  /* the interval count (after 18 words and 3 strings) made huge */
  size_t at = 5 * 8 + 3 * 8 + strlen("records/x.AT2") + strlen("t") +
              strlen(c.err.message) + 4 * 8 + 4 * 8 + 2 * 8;
  int64_t huge = INT64_MAX / 4, two = 2, four = 4;
  /* the point count, after the 2 intervals, made huge; the last point's
     collapse flag made 2, its marks 4 */
  unsigned char *b2 = malloc(n);
  if (b2) {
    memcpy(b2, b, n);
    memcpy(b2 + at + 8 + 2 * 16, &huge, sizeof huge);
    aq_bytes_in r = {b2, n, 0, NULL, 0};
    aq_status s = aq_capacity_decode(&r, &d, &e);
    aq_check(s == AQ_EFORMAT && strcmp(e.field, "npoint") == 0 && d.point == NULL,
             "a huge point count refused: field \"%s\"", e.field);
    aq_capacity_free(&d);
    word_refused(b, b2, n, n - 16, two, "point collapsed");
    word_refused(b, b2, n, n - 8, four, "point marks");
    free(b2);
  }
  memcpy(b + at, &huge, sizeof huge);
  aq_bytes_in r = {b, n, 0, NULL, 0};
  aq_status s = aq_capacity_decode(&r, &d, &e);
  aq_check(s == AQ_EFORMAT && strcmp(e.field, "ninterval") == 0,
           "a huge interval count refused: field \"%s\"", e.field);
  aq_capacity_free(&d);
  /* a status out of range */
  int64_t bad = 7;
  memcpy(b, &bad, sizeof bad);
  r = (aq_bytes_in){b, n, 0, NULL, 0};
  s = aq_capacity_decode(&r, &d, &e);
  aq_check(s == AQ_EFORMAT && strcmp(e.field, "status") == 0 && e.byte_offset == 0,
           "a status of 7 refused: field \"%s\" at byte %ld", e.field, e.byte_offset);
  aq_capacity_free(&d);
  free(b);
}
