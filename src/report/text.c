/* text.c: the TSV summary writer (see text.h). */
#include "text.h"

#include <inttypes.h>
#include <math.h>
#include <string.h>

void aq_text_double(char *buf, size_t n, double x)
{
  if (isnan(x))
    snprintf(buf, n, "nan"); /* glibc would print "-nan" for a negative NaN */
  else if (isinf(x))
    snprintf(buf, n, "%s", x > 0 ? "inf" : "-inf");
  else
    snprintf(buf, n, "%.17g", x);
}

static int put_str(FILE *f, const char *s)
{
  for (; *s; s++) {
    int c = (unsigned char)*s;
    if (c == '\t' || c == '\n' || c == '\r')
      c = ' ';
    if (putc(c, f) == EOF)
      return -1;
  }
  return 0;
}

int aq_text_header(FILE *f)
{
  for (size_t i = 0; i < aq_summary_nfields; i++)
    if (fputs(aq_summary_fields[i].name, f) == EOF ||
        putc(i + 1 < aq_summary_nfields ? '\t' : '\n', f) == EOF)
      return -1;
  return ferror(f) ? -1 : 0;
}

int aq_text_row(FILE *f, const aq_summary *s)
{
  char num[64];
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *fl = &aq_summary_fields[i];
    int rc = 0;
    switch (fl->kind) {
    case AQ_SF_STR:
      rc = put_str(f, aq_summary_get_str(s, fl));
      break;
    case AQ_SF_DOUBLE:
      aq_text_double(num, sizeof num, aq_summary_get_double(s, fl));
      rc = fputs(num, f) == EOF ? -1 : 0;
      break;
    case AQ_SF_INT:
      rc = fprintf(f, "%" PRId64, aq_summary_get_int(s, fl)) < 0 ? -1 : 0;
      break;
    }
    if (rc || putc(i + 1 < aq_summary_nfields ? '\t' : '\n', f) == EOF)
      return -1;
  }
  return ferror(f) ? -1 : 0;
}
