/* suite_file.c: the suite file of `archquake select` (suite_file.h). */
#define _POSIX_C_SOURCE 200809L
#include "suite_file.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../io/number.h"

#define SUITE_LINE_MAX 8192
#define SUITE_ROWS_MAX 1000000

/* s with tabs and line ends as spaces, "-" when empty. */
static void put_field(FILE *f, const char *s)
{
  if (!s[0]) {
    fputc('-', f);
    return;
  }
  for (; *s; s++)
    fputc(*s == '\t' || *s == '\n' || *s == '\r' ? ' ' : *s, f);
}

int aq_suite_file_write(FILE *f, const char *const *comment, size_t ncomment,
                        const aq_suite_row *rows, size_t n)
{
  for (size_t i = 0; i < ncomment; i++) {
    fputs("# ", f);
    for (const char *c = comment[i]; *c; c++)
      fputc(*c == '\n' || *c == '\r' ? ' ' : *c, f);
    fputc('\n', f);
  }
  fprintf(f, "%s\n", AQ_SUITE_FILE_HEADER);
  for (size_t i = 0; i < n; i++) {
    put_field(f, rows[i].record);
    fputc('\t', f);
    put_field(f, rows[i].channel);
    char scale[32], misfit[32];
    aq_number_format(scale, sizeof scale, rows[i].scale);
    aq_number_format(misfit, sizeof misfit, rows[i].misfit);
    fprintf(f, "\t%s\t%s\t", scale, misfit);
    put_field(f, rows[i].event);
    fputc('\n', f);
  }
  return ferror(f) ? -1 : 0;
}

void aq_suite_file_free(aq_suite_file *s)
{
  for (size_t i = 0; s->row && i < s->n; i++)
    free(s->row[i].record);
  free(s->row);
  s->row = NULL;
  s->n = 0;
}

/* Split line at tabs into at most max fields (pointers into line). */
static size_t fields(char *line, char **f, size_t max)
{
  size_t n = 0;
  for (char *p = line;; p++) {
    if (n < max)
      f[n] = p;
    n++;
    p += strcspn(p, "\t");
    if (*p == '\0')
      break;
    *p = '\0';
  }
  return n;
}

static aq_status row_of(const char *path, long ln, char *line, aq_suite_file *s, size_t *cap,
                        aq_error *err)
{
  char *f[5];
  size_t nf = fields(line, f, 5);
  if (nf != 5)
    return aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL,
                        "expected 5 tab-separated fields (" AQ_SUITE_FILE_HEADER "), got %zu",
                        nf);
  if (!f[0][0] || !strcmp(f[0], "-"))
    return aq_error_set(err, AQ_EFORMAT, path, ln, -1, "record", "expected a record, got none");
  double scale, misfit;
  size_t ls = strlen(f[2]), lm = strlen(f[3]);
  if (!ls || aq_number_parse_finite(f[2], ls, 0, &scale) != ls || !(scale > 0))
    return aq_error_set(err, AQ_EFORMAT, path, ln, -1, "scale",
                        "expected a factor > 0, got \"%.40s\"", f[2]);
  if (!lm || (aq_number_parse(f[3], lm, 0, &misfit) != lm && strcmp(f[3], "nan") != 0))
    return aq_error_set(err, AQ_EFORMAT, path, ln, -1, "misfit",
                        "expected a number, got \"%.40s\"", f[3]);
  if (!strcmp(f[3], "nan"))
    misfit = NAN;
  for (size_t i = 0; i < s->n; i++)
    if (!strcmp(s->row[i].record, f[0]))
      return aq_error_set(err, AQ_EFORMAT, path, ln, -1, "record",
                          "expected each record once, got \"%.200s\" twice", f[0]);
  if (s->n == *cap) {
    size_t nc = *cap ? 2 * *cap : 16;
    aq_suite_row *r = nc <= SUITE_ROWS_MAX ? realloc(s->row, nc * sizeof *r) : NULL;
    if (!r)
      return aq_error_set(err, AQ_ENOMEM, path, ln, -1, NULL, "out of memory");
    s->row = r;
    *cap = nc;
  }
  aq_suite_row *r = &s->row[s->n];
  memset(r, 0, sizeof *r);
  r->record = strdup(f[0]);
  if (!r->record)
    return aq_error_set(err, AQ_ENOMEM, path, ln, -1, NULL, "out of memory");
  s->n++;
  snprintf(r->channel, sizeof r->channel, "%s", f[1]);
  r->scale = scale;
  r->misfit = misfit;
  snprintf(r->event, sizeof r->event, "%s", strcmp(f[4], "-") ? f[4] : "");
  return AQ_OK;
}

aq_status aq_suite_file_read(const char *path, aq_suite_file *s, aq_error *err)
{
  memset(s, 0, sizeof *s);
  FILE *f = fopen(path, "r");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, "--suite",
                        "expected a suite file written by archquake select, got a file that "
                        "cannot be read");
  char *line = malloc(SUITE_LINE_MAX);
  long ln = 0;
  int header = 0;
  size_t cap = 0;
  aq_status st = line ? AQ_OK : aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  while (st == AQ_OK && fgets(line, SUITE_LINE_MAX, f)) {
    ln++;
    size_t len = strcspn(line, "\r\n");
    if (line[len] == '\0' && !feof(f)) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL,
                        "expected lines of at most %d characters", SUITE_LINE_MAX - 2);
      break;
    }
    line[len] = '\0';
    if (line[0] == '#' || (!header && len == 0))
      continue;
    if (!header) {
      if (strcmp(line, AQ_SUITE_FILE_HEADER) != 0)
        st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, "header",
                          "expected the header row \"%s\" (a suite file of archquake "
                          "select), got \"%.60s\"", "record channel scale misfit event", line);
      header = 1;
      continue;
    }
    if (len == 0)
      continue;
    st = row_of(path, ln, line, s, &cap, err);
  }
  if (st == AQ_OK && ferror(f))
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "read error");
  if (st == AQ_OK && s->n == 0)
    st = aq_error_set(err, AQ_EFORMAT, path, ln > 0 ? ln : -1, -1, NULL,
                      "expected the header row and at least one record, got %s",
                      header ? "no record" : "no header row");
  fclose(f);
  free(line);
  if (st != AQ_OK)
    aq_suite_file_free(s);
  return st;
}
