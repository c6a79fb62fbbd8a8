/* raw_fixture.h: running an agency-format parser (io/reader.h) on a shipped
 * file, whole or altered, and the numbers the tests compare (peak, mean).
 * Paths are relative to the repository root. */
#ifndef AQ_TESTS_RAW_FIXTURE_H
#define AQ_TESTS_RAW_FIXTURE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define AGENCY_DIR "tests/data/records/agency/"

typedef aq_reader_fn *aq_test_raw_parser;

/* Parse buf[0..n) as name; the one-line message goes to msg.  Checks that a
 * failure leaves raw empty.  Returns the status. */
static inline aq_status aq_test_raw_parse_buf(aq_test_raw_parser parse, const char *buf,
                                              size_t n, const char *name, aq_raw_file *raw,
                                              char *msg, size_t cap)
{
  aq_error e;
  aq_error_clear(&e);
  aq_status s = parse((const unsigned char *)buf, n, name, NULL, raw, &e);
  aq_error_format(&e, msg, cap);
  if (s != AQ_OK)
    aq_check(raw->nchan == 0 && raw->chan == NULL, "failed parse leaves raw empty (%s)", msg);
  return s;
}

/* Parse the file at path; 1 on success (a failure is a failed check). */
static inline int aq_test_raw_load(aq_test_raw_parser parse, const char *path, aq_raw_file *raw)
{
  size_t n;
  char *buf = aq_test_read_file(path, &n);
  memset(raw, 0, sizeof *raw);
  if (!aq_check(buf != NULL, "read %s", path))
    return 0;
  char msg[1400];
  aq_status s = aq_test_raw_parse_buf(parse, buf, n, path, raw, msg, sizeof msg);
  free(buf);
  return aq_check(s == AQ_OK, "parse %s: %s", path, msg);
}

/* Parse the file at path with bytes [cut, n) removed (cut = (size_t)-1: the
 * whole file) and text `from` replaced once by `to` (from NULL: no change).
 * Returns the status; the message in msg; raw freed. */
static inline aq_status aq_test_raw_altered(aq_test_raw_parser parse, const char *path,
                                            size_t cut, const char *from, const char *to,
                                            char *msg, size_t cap)
{
  size_t n;
  char *buf = aq_test_read_file(path, &n);
  snprintf(msg, cap, "cannot read %s", path);
  if (!buf)
    return AQ_EIO;
  char *work = buf;
  if (from) {
    char *at = strstr(buf, from);
    if (!aq_check(at != NULL, "%s holds \"%s\"", path, from)) {
      free(buf);
      return AQ_EIO;
    }
    size_t lf = strlen(from), lt = strlen(to);
    work = malloc(n - lf + lt + 1);
    memcpy(work, buf, (size_t)(at - buf));
    memcpy(work + (at - buf), to, lt);
    memcpy(work + (at - buf) + lt, at + lf, n - (size_t)(at - buf) - lf + 1);
    n = n - lf + lt;
    free(buf);
  }
  if (cut < n)
    n = cut;
  aq_raw_file raw;
  aq_status s = aq_test_raw_parse_buf(parse, work, n, path, &raw, msg, cap);
  aq_raw_file_free(&raw);
  free(work);
  return s;
}

static inline double aq_test_peak_abs(const aq_raw_channel *c)
{
  double m = 0;
  for (size_t k = 0; k < c->npts; k++)
    if (fabs(c->values[k]) > m)
      m = fabs(c->values[k]);
  return m;
}

static inline double aq_test_mean(const aq_raw_channel *c)
{
  double s = 0;
  for (size_t k = 0; k < c->npts; k++)
    s += c->values[k];
  return c->npts ? s / (double)c->npts : 0;
}

static inline double aq_test_peak_demeaned(const aq_raw_channel *c)
{
  double mu = aq_test_mean(c), m = 0;
  for (size_t k = 0; k < c->npts; k++)
    if (fabs(c->values[k] - mu) > m)
      m = fabs(c->values[k] - mu);
  return m;
}

/* 1 if msg is one line naming the file and containing word (NULL: any). */
static inline int aq_test_msg_names(const char *msg, const char *path, const char *word)
{
  return strstr(msg, path) != NULL && (!word || strstr(msg, word) != NULL) &&
         strchr(msg, '\n') == NULL;
}

#endif
