/* test_io_fixed.c: the fixed-width field reader (io/fixed.h) against the C
 * library's strtod, bit for bit, on the number shapes agencies write and on
 * a stream of pseudo-random decimals; and its refusals. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/fixed.h"

static int same_as_strtod(const char *t)
{
  double a = 0, b = strtod(t, NULL);
  if (!aq_field_double(t, strlen(t), &a))
    return 0;
  return memcmp(&a, &b, sizeof a) == 0;
}

AQ_TEST(io_fixed_numbers_match_strtod)
{
  static const char *const shapes[] = {
      "-94.84213", "-120.18770", ".000010",   "-.045290",      "5.0000000",  "-999.00000",
      "-2.7715E+0", "-1.1578E-1", "0.1700000E+39", "-0.000000", "985881",     "-2378638",
      "0.3",        "152378.61058", "1.5237861058e-4", "123.4500000", "9007199254740993",
      "1e-30",      "+7.25",      "0.1234567890123456789"};
  for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++)
    aq_check(same_as_strtod(shapes[i]), "\"%s\" as strtod reads it", shapes[i]);
  /* pseudo-random decimals: sign, 1-17 digits, a point, an exponent */
  unsigned x = 2385u;
  int bad = 0;
  for (int k = 0; k < 20000; k++) {
    char t[48];
    size_t n = 0;
    x = x * 1103515245u + 12345u;
    if (x & 0x10000u)
      t[n++] = '-';
    int nd = 1 + (int)((x >> 17) % 17), point = (int)((x >> 22) % (unsigned)(nd + 1));
    for (int d = 0; d < nd; d++) {
      if (d == point)
        t[n++] = '.';
      x = x * 1103515245u + 12345u;
      t[n++] = (char)('0' + (x >> 16) % 10);
    }
    x = x * 1103515245u + 12345u;
    if (x & 0x40000u)
      n += (size_t)snprintf(t + n, sizeof t - n, "E%+d", (int)((x >> 19) % 61) - 30);
    t[n] = '\0';
    bad += !same_as_strtod(t);
  }
  aq_check(bad == 0, "%d of 20000 random decimals differ from strtod", bad);
}

AQ_TEST(io_fixed_refusals)
{
  static const char *const bad[] = {"", "  ", "-", ".", "1e", "1.5x", "0x10", "inf", "nan",
                                    "1e999", "--1", "1 2"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    double v;
    aq_check(!aq_field_double(bad[i], strlen(bad[i]), &v), "\"%s\" refused", bad[i]);
  }
  double v;
  aq_check(aq_field_double("  -1.5  ", 8, &v) && v == -1.5, "blanks around");
}

/* Local times to UTC (aq_iso_time_local): zones east and west of UTC, day,
 * month and year rolled back and over; the expected UTC written out by hand. */
AQ_TEST(io_fixed_local_time_to_utc)
{
  static const struct {
    int y, mo, d, h, mi;
    double s;
    int east;
    const char *want; /* NULL: refused */
  } c[] = {
      {2016, 4, 14, 21, 26, 20, 9, "2016-04-14T12:26:20.000Z"},   /* JST */
      {2021, 1, 1, 3, 0, 0, 8, "2020-12-31T19:00:00.000Z"},       /* back a year */
      {2020, 12, 31, 22, 15, 1.25, -5, "2021-01-01T03:15:01.250Z"}, /* over a year */
      {2016, 3, 1, 2, 0, 0, 9, "2016-02-29T17:00:00.000Z"},       /* leap day */
      {1994, 1, 17, 4, 30, 55.39, -8, "1994-01-17T12:30:55.390Z"}, /* PST */
      {2016, 4, 14, 25, 0, 0, 9, NULL},
      {2016, 4, 14, 21, 0, 0, 15, NULL},
      {2016, 4, 14, -1, 0, 0, 0, NULL}};
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    char out[40] = "";
    int ok = aq_iso_time_local(out, sizeof out, c[i].y, c[i].mo, c[i].d, c[i].h, c[i].mi,
                               c[i].s, c[i].east);
    aq_check(c[i].want ? ok && strcmp(out, c[i].want) == 0 : !ok, "%zu: %d \"%s\"", i, ok,
             out);
  }
}

/* The calendar (timegm(3) and gmtime_r(3) underneath): day of the year to
 * month and day across leap rules, ISO times to seconds since 1970 and
 * back; the expected values written out by hand (and by GNU date: `date -u
 * -d 2019-07-06T03:19:53 +%s` is 1562383193). */
AQ_TEST(io_fixed_calendar)
{
  static const struct {
    int y, jd, mo, d; /* mo 0: refused */
  } md[] = {{2000, 60, 2, 29},  {1900, 60, 3, 1},  {2100, 60, 3, 1},  {2016, 366, 12, 31},
            {2019, 187, 7, 6},  {2019, 366, 0, 0}, {2019, 0, 0, 0},   {1799, 1, 0, 0},
            {2201, 1, 0, 0},    {1983, 122, 5, 2}};
  for (size_t i = 0; i < sizeof md / sizeof md[0]; i++) {
    int mo = 0, d = 0;
    int ok = aq_month_day(md[i].y, md[i].jd, &mo, &d);
    aq_check(md[i].mo ? ok && mo == md[i].mo && d == md[i].d : !ok,
             "day %d of %d: %d -> %d-%d", md[i].jd, md[i].y, ok, mo, d);
  }
  double t;
  aq_check(aq_iso_parse("2019-07-06T03:19:53Z", &t) && t == 1562383193.0, "parse: %.17g", t);
  aq_check(aq_iso_parse("1969-12-31T23:59:59.5", &t) && t == -0.5, "before 1970: %.17g", t);
  aq_check(aq_iso_parse("2016-02-29", &t) && t == 1456704000.0, "date only: %.17g", t);
  aq_check(!aq_iso_parse("2016-13-01", &t), "month 13 refused");
  char out[40];
  aq_check(aq_iso_from_ms(out, sizeof out, 1562383193040LL) &&
               strcmp(out, "2019-07-06T03:19:53.040Z") == 0,
           "from ms: %s", out);
  aq_check(aq_iso_from_ms(out, sizeof out, -1LL) && strcmp(out, "1969-12-31T23:59:59.999Z") == 0,
           "from -1 ms: %s", out);
  aq_check(aq_iso_time(out, sizeof out, 2012, 2, 13, 45, 6, 45.25) &&
               strcmp(out, "2012-02-14T21:06:45.250Z") == 0,
           "hours past the day roll it over: %s", out);
}
