/* buf.h: a growing text buffer for the page (src/page/buf.c).  Appends
 * never fail loudly: a failed allocation sets ->failed and later appends
 * do nothing, so a writer checks once at the end.  Free with
 * aq_page_buf_free. */
#ifndef AQ_PAGE_BUF_H
#define AQ_PAGE_BUF_H

#include <stddef.h>

typedef struct {
  char *s;
  size_t n, cap;
  int failed;
} aq_page_buf;

void aq_page_buf_free(aq_page_buf *b);
void aq_page_put(aq_page_buf *b, const char *s, size_t len);
void aq_page_puts(aq_page_buf *b, const char *s);
void aq_page_printf(aq_page_buf *b, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* s with & < > " ' as entities (HTML text and attribute values). */
void aq_page_esc(aq_page_buf *b, const char *s);

#endif
