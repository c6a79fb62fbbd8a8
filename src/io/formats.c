/* formats.c: small helpers shared by the agency-format parsers (formats.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fixed.h"
#include "formats.h"

aq_raw_channel *aq_raw_add_channel_(aq_raw_file *raw, const char *name, aq_error *err)
{
  aq_raw_channel *c = realloc(raw->chan, (raw->nchan + 1) * sizeof *c);
  if (!c) {
    aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory for channel %zu",
                 raw->nchan + 1);
    return NULL;
  }
  raw->chan = c;
  c += raw->nchan++;
  aq_raw_channel_init_(c);
  return c;
}

aq_status aq_raw_append_channel_(aq_raw_file *raw, aq_raw_channel *c, const char *name,
                                 aq_error *err)
{
  aq_raw_channel *ch = aq_raw_add_channel_(raw, name, err);
  if (!ch) {
    free(c->values);
    c->values = NULL;
    return AQ_ENOMEM;
  }
  *ch = *c;
  return AQ_OK;
}

int aq_line_names_accelerogram_(const aq_line *ln)
{
  return aq_find_ci(ln->p, ln->len, "accelerogram") != NULL;
}

void aq_raw_channel_init_(aq_raw_channel *c)
{
  memset(c, 0, sizeof *c);
  c->azimuth_deg = NAN;
  c->dip_deg = NAN;
  c->vertical = -1;
}

int aq_zone_offset_(const char *s, size_t n, int *hours_east)
{
  static const struct {
    const char *word;
    int east_h;
  } zones[] = {{"UTC", 0},  {"GMT", 0},  {"UT", 0},  {"PDT", -7}, {"PST", -8},
               {"MDT", -6}, {"MST", -7}, {"CDT", -5}, {"CST", -6}, {"EDT", -4},
               {"EST", -5}, {"JST", 9}};
  for (size_t i = 0; i < sizeof zones / sizeof zones[0]; i++)
    if (strlen(zones[i].word) == n && strncasecmp(s, zones[i].word, n) == 0) {
      *hours_east = zones[i].east_h;
      return 1;
    }
  return 0;
}

aq_status aq_parse_channels_(const unsigned char *buf, size_t n, const char *name,
                             const char *format, int (*starts)(const aq_line *),
                             const char *expected, aq_channel_parser_ parse, aq_raw_file *raw,
                             aq_error *err)
{
  memset(raw, 0, sizeof *raw);
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  aq_status s = AQ_OK;
  while (s == AQ_OK && aq_lines_next(&c, &ln)) {
    if (aq_line_blank(&ln))
      continue;
    if (!starts(&ln)) {
      char got[64];
      aq_copy_trim(got, sizeof got, ln.p, ln.len);
      s = aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "text header",
                       "expected %s%s, got \"%s\"", raw->nchan ? "the next channel's " : "",
                       expected, got);
      break;
    }
    s = parse(&c, &ln, name, raw, err);
  }
  if (s == AQ_OK && raw->nchan == 0)
    s = aq_error_set(err, AQ_EFORMAT, name, 1, -1, "text header",
                     "expected %s, got an empty file", expected);
  if (s != AQ_OK) {
    aq_raw_file_free(raw);
    return s;
  }
  snprintf(raw->format, sizeof raw->format, "%s", format);
  return AQ_OK;
}
