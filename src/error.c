/* error.c: status texts and the error record (see error.h). */
#include "error.h"

#include <stdarg.h>
#include <string.h>

const char *aq_strerror(aq_status s)
{
  switch (s) {
#define AQ_X_CASE(name, code, text) \
  case name:                        \
    return text;
    AQ_STATUS_LIST(AQ_X_CASE)
#undef AQ_X_CASE
  }
  return "unknown status";
}

void aq_error_clear(aq_error *e)
{
  if (!e)
    return;
  memset(e, 0, sizeof *e);
  e->status = AQ_OK;
  e->line = -1;
  e->byte_offset = -1;
}

aq_status aq_error_set(aq_error *e, aq_status s, const char *input, long line,
                       long byte_offset, const char *field, const char *fmt,
                       ...)
{
  if (!e)
    return s;
  e->status = s;
  snprintf(e->input, sizeof e->input, "%s", input ? input : "");
  e->line = line;
  e->byte_offset = byte_offset;
  snprintf(e->field, sizeof e->field, "%s", field ? field : "");
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(e->message, sizeof e->message, fmt, ap);
  va_end(ap);
  /* keep it one line */
  for (char *p = e->message; *p; p++)
    if (*p == '\n' || *p == '\r')
      *p = ' ';
  return s;
}

void aq_error_format(const aq_error *e, char *buf, size_t n)
{
  if (!buf || n == 0)
    return;
  buf[0] = '\0';
  if (!e)
    return;
  size_t k = 0;
#define AQ_PUT(...)                                            \
  do {                                                         \
    if (k < n) {                                               \
      int w_ = snprintf(buf + k, n - k, __VA_ARGS__);          \
      if (w_ > 0)                                              \
        k += (size_t)w_;                                       \
    }                                                          \
  } while (0)
  if (e->input[0]) {
    AQ_PUT("%s", e->input);
    if (e->line > 0)
      AQ_PUT(":%ld", e->line);
    AQ_PUT(": ");
  }
  if (e->field[0]) {
    AQ_PUT("%s", e->field);
    if (e->byte_offset >= 0)
      AQ_PUT(" (byte %ld)", e->byte_offset);
    AQ_PUT(": ");
  } else if (e->byte_offset >= 0) {
    AQ_PUT("byte %ld: ", e->byte_offset);
  }
  AQ_PUT("%s", e->message[0] ? e->message : aq_strerror(e->status));
#undef AQ_PUT
  /* one line, whatever the input's name or the text quoted holds */
  for (char *p = buf; *p; p++)
    if (*p == '\n' || *p == '\r')
      *p = ' ';
}

void aq_error_print(const aq_error *e, FILE *f)
{
  char buf[1400];
  aq_error_format(e, buf, sizeof buf);
  fprintf(f, "archquake: %s\n", buf);
}
