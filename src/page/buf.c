/* buf.c: the page's text buffer (buf.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"

void aq_page_buf_free(aq_page_buf *b)
{
  free(b->s);
  memset(b, 0, sizeof *b);
}

void aq_page_put(aq_page_buf *b, const char *s, size_t len)
{
  if (b->failed)
    return;
  if (b->n + len + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 1 << 16;
    while (b->n + len + 1 > cap)
      cap *= 2;
    char *m = realloc(b->s, cap);
    if (!m) {
      b->failed = 1;
      return;
    }
    b->s = m;
    b->cap = cap;
  }
  memcpy(b->s + b->n, s, len);
  b->n += len;
  b->s[b->n] = '\0';
}

void aq_page_puts(aq_page_buf *b, const char *s)
{
  aq_page_put(b, s, strlen(s));
}

void aq_page_printf(aq_page_buf *b, const char *fmt, ...)
{
  char small[512];
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(small, sizeof small, fmt, ap);
  va_end(ap);
  if (n < 0) {
    b->failed = 1;
    return;
  }
  if ((size_t)n < sizeof small) {
    aq_page_put(b, small, (size_t)n);
    return;
  }
  char *big = malloc((size_t)n + 1);
  if (!big) {
    b->failed = 1;
    return;
  }
  va_start(ap, fmt);
  vsnprintf(big, (size_t)n + 1, fmt, ap);
  va_end(ap);
  aq_page_put(b, big, (size_t)n);
  free(big);
}

void aq_page_esc(aq_page_buf *b, const char *s)
{
  for (const char *p = s; *p;) {
    size_t run = strcspn(p, "&<>\"'");
    aq_page_put(b, p, run);
    p += run;
    if (!*p)
      break;
    static const char *const ent[] = {"&amp;", "&lt;", "&gt;", "&quot;", "&#39;"};
    aq_page_puts(b, ent[strchr("&<>\"'", *p) - "&<>\"'"]);
    p++;
  }
}
