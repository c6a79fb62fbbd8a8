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

/* Mark a cut text: buf (n > 3 bytes) was filled to its end, so its last
 * three bytes become "...", never leaving half a UTF-8 character before
 * them. */
static void mark_cut(char *buf, size_t n)
{
  if (n < 4)
    return;
  size_t k = n - 4;
  while (k > 0 && ((unsigned char)buf[k] & 0xC0) == 0x80) /* a continuation byte */
    k--;
  memcpy(buf + k, "...", 4);
}

const char *aq_path_fit(const char *path, size_t max, char *buf, size_t n)
{
  if (!buf || n == 0)
    return "";
  if (!path)
    path = "";
  if (max >= n)
    max = n - 1;
  size_t len = strlen(path);
  if (len <= max) {
    memcpy(buf, path, len + 1);
    return buf;
  }
  if (max < 4) {
    buf[0] = '\0';
    return buf;
  }
  /* "..." and the last max - 3 bytes, from a character's first byte */
  const char *tail = path + len - (max - 3);
  while (*tail && ((unsigned char)*tail & 0xC0) == 0x80)
    tail++;
  memcpy(buf, "...", 3);
  memcpy(buf + 3, tail, strlen(tail) + 1);
  return buf;
}

int aq_text_fit(char *buf, size_t n, const char *fmt, ...)
{
  if (!buf || n == 0)
    return 0;
  va_list ap;
  va_start(ap, fmt);
  int w = vsnprintf(buf, n, fmt, ap);
  va_end(ap);
  if (w < 0) {
    buf[0] = '\0';
    return 0;
  }
  if ((size_t)w < n)
    return 0;
  mark_cut(buf, n);
  return 1;
}

/* Copy a file name into dst[n], keeping its end (the file itself) when it
 * is longer: "..." and its last bytes. */
static void copy_name(char *dst, size_t n, const char *src)
{
  aq_path_fit(src, n - 1, dst, n);
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
  copy_name(e->input, sizeof e->input, input ? input : "");
  e->line = line;
  e->byte_offset = byte_offset;
  if (snprintf(e->field, sizeof e->field, "%s", field ? field : "") >= (int)sizeof e->field)
    mark_cut(e->field, sizeof e->field);
  va_list ap;
  va_start(ap, fmt);
  int w = vsnprintf(e->message, sizeof e->message, fmt, ap);
  va_end(ap);
  if (w >= (int)sizeof e->message)
    mark_cut(e->message, sizeof e->message);
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
  /* k >= n after a put: the line was cut (marked below) */
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
  if (k >= n)
    mark_cut(buf, n);
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
