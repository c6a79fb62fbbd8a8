/* raw.c: the raw file a reader fills (reader.h): allocation, channels
 * appended one by one, and the walk over the channels of a multi-channel
 * text file (COSMOS, CSMIP). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

void aq_raw_file_free(aq_raw_file *raw)
{
  if (!raw)
    return;
  for (size_t i = 0; raw->chan && i < raw->nchan; i++)
    free(raw->chan[i].values);
  free(raw->chan);
  memset(raw, 0, sizeof *raw);
}

aq_status aq_raw_file_alloc(aq_raw_file *raw, size_t nchan, const char *name,
                            aq_error *err)
{
  raw->chan = calloc(nchan ? nchan : 1, sizeof *raw->chan);
  if (!raw->chan)
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory");
  raw->nchan = nchan;
  for (size_t i = 0; i < nchan; i++)
    aq_raw_channel_init(&raw->chan[i]);
  return AQ_OK;
}

aq_raw_channel *aq_raw_add_channel(aq_raw_file *raw, const char *name, aq_error *err)
{
  aq_raw_channel *c = realloc(raw->chan, (raw->nchan + 1) * sizeof *c);
  if (!c) {
    aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL, "out of memory for channel %zu",
                 raw->nchan + 1);
    return NULL;
  }
  raw->chan = c;
  c += raw->nchan++;
  aq_raw_channel_init(c);
  return c;
}

aq_status aq_raw_append_channel(aq_raw_file *raw, aq_raw_channel *c, const char *name,
                                 aq_error *err)
{
  aq_raw_channel *ch = aq_raw_add_channel(raw, name, err);
  if (!ch) {
    free(c->values);
    c->values = NULL;
    return AQ_ENOMEM;
  }
  *ch = *c;
  return AQ_OK;
}

void aq_raw_set_extra(aq_raw_channel *c, const aq_extra_rows *x, size_t per,
                      const char *count_from)
{
  c->extra_rows = x->rows;
  c->extra_values = per > 1 ? x->values / per : x->values;
  c->extra_line = x->line;
  c->extra_repeat = x->repeat;
  snprintf(c->count_from, sizeof c->count_from, "%s", count_from);
}

aq_status aq_raw_rows_end(aq_lines *c, const aq_line *last, aq_row_fn *row, const void *ctx,
                          size_t rows, const char *count_from, aq_raw_file *raw,
                          const char *name, aq_error *err)
{
  aq_extra_rows x;
  aq_extra_rows_scan(c, last, row, ctx, &x);
  aq_line ln;
  if (aq_lines_next(c, &ln)) {
    char got[48];
    aq_copy_trim(got, sizeof got, ln.p, ln.len);
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "data",
                        "expected the end of the data after %zu rows (%s), got \"%s\"",
                        rows + x.rows, count_from, got);
  }
  for (size_t j = 0; j < raw->nchan; j++)
    aq_raw_set_extra(&raw->chan[j], &x, 1, count_from);
  return AQ_OK;
}

void aq_raw_channel_init(aq_raw_channel *c)
{
  memset(c, 0, sizeof *c);
  c->azimuth_deg = NAN;
  c->dip_deg = NAN;
  c->vertical = -1;
  c->units_line = -1;
}

aq_status aq_raw_parse_channels(const unsigned char *buf, size_t n, const char *name,
                             const char *format, int (*starts)(const aq_line *),
                             const char *expected, aq_raw_channel_parser parse, aq_raw_file *raw,
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
