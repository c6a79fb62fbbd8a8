/* text.c: the TSV summary writer (see text.h). */
#include "text.h"

#include "../io/number.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void aq_text_double(char *buf, size_t n, double x)
{
  aq_number_format(buf, n, x);
}

char *aq_text_num(char *buf, double x)
{
  aq_text_double(buf, AQ_TEXT_NUM_MAX, x);
  return buf;
}

void aq_text_int(char *buf, size_t n, int64_t x)
{
  if (x == AQ_SUMMARY_INT_NONE)
    snprintf(buf, n, "nan"); /* a failed run: no value, as for the doubles */
  else
    snprintf(buf, n, "%" PRId64, x);
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
      aq_text_int(num, sizeof num, aq_summary_get_int(s, fl));
      rc = fputs(num, f) == EOF ? -1 : 0;
      break;
    }
    if (rc || putc(i + 1 < aq_summary_nfields ? '\t' : '\n', f) == EOF)
      return -1;
  }
  return ferror(f) ? -1 : 0;
}

/* Significant digits of numbers in the aligned table, and the widest such
 * number ("-1.23457e-308"). */
#define AQ_TEXT_ALIGNED_DIGITS 6
#define AQ_TEXT_ALIGNED_NUM_W 13
#define AQ_TEXT_ALIGNED_STATUS_W 21 /* "process:einadmissible" */

void aq_text_layout_init(aq_text_layout *L, size_t record_w, size_t arch_w)
{
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    size_t w = strlen(f->name);
    size_t want = f->kind == AQ_SF_STR ? (strcmp(f->name, "record") == 0 ? record_w
                                          : strcmp(f->name, "arch") == 0  ? arch_w
                                          : strcmp(f->name, "status") == 0
                                              ? AQ_TEXT_ALIGNED_STATUS_W
                                              : 8 /* model */)
                  : f->kind == AQ_SF_DOUBLE ? AQ_TEXT_ALIGNED_NUM_W
                                            : 6;
    if (want > w)
      w = want;
    L->width[i] = (int)(w < 512 ? w : 512);
  }
}

int aq_text_header_aligned(FILE *f, const aq_text_layout *L)
{
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *fl = &aq_summary_fields[i];
    int left = fl->kind == AQ_SF_STR;
    if (fprintf(f, left ? "%-*s%s" : "%*s%s", L->width[i], fl->name,
                i + 1 < aq_summary_nfields ? "  " : "\n") < 0)
      return -1;
  }
  return ferror(f) ? -1 : 0;
}

int aq_text_row_aligned(FILE *f, const aq_text_layout *L, const aq_summary *s)
{
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *fl = &aq_summary_fields[i];
    const char *sep = i + 1 < aq_summary_nfields ? "  " : "\n";
    char cell[600];
    int rc = 0;
    switch (fl->kind) {
    case AQ_SF_STR: {
      snprintf(cell, sizeof cell, "%s", aq_summary_get_str(s, fl));
      for (char *p = cell; *p; p++)
        if (*p == '\t' || *p == '\n' || *p == '\r')
          *p = ' ';
      rc = fprintf(f, "%-*s%s", L->width[i], cell, sep);
      break;
    }
    case AQ_SF_DOUBLE: {
      double x = aq_summary_get_double(s, fl);
      if (isnan(x))
        snprintf(cell, sizeof cell, "nan");
      else
        snprintf(cell, sizeof cell, "%.*g", AQ_TEXT_ALIGNED_DIGITS, x);
      rc = fprintf(f, "%*s%s", L->width[i], cell, sep);
      break;
    }
    case AQ_SF_INT:
      aq_text_int(cell, sizeof cell, aq_summary_get_int(s, fl));
      rc = fprintf(f, "%*s%s", L->width[i], cell, sep);
      break;
    }
    if (rc < 0)
      return -1;
  }
  return ferror(f) ? -1 : 0;
}
