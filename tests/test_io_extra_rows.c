/* test_io_extra_rows.c: rows past the count a file states, the rule every
 * reader of a stated count follows (readers report, src/io/record.c
 * decides): rows that copy the last row are said in one note naming both
 * counts and are not read; rows that do not are refused, naming both
 * counts and the line.
 *
 * The real case: CUP50401.012 (ASA 2.0, UNAM) states 17500 samples per
 * channel (NUM. TOTAL DE MUESTRAS) and holds 17502 rows, the last three
 * alike (tests/data/records/agency2/PROVENANCE.md).  Then, for a file of
 * every reader that reads a stated count, its last data row is written
 * twice (the copy must be noted, the values read unchanged) or followed by
 * a row of other digits (refused).  How many values a row holds is written
 * in the table from each format's layout, not taken from the reader. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "check.h"
#include "io/record.h"

#define R "tests/data/records/"

AQ_TEST(io_extra_rows_asa_unam)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  static const char *const ch[3] = {"V", "N90E", "N00E"};
  char name[256], *txt = aq_test_read_file(R "agency2/CUP50401.012", NULL);
  if (!aq_check(txt != NULL, "read the file"))
    return;
  /* the data start after the line "DATOS DE ACELERACION:" and the lines of
     names and units the provenance describes: the last row, read here, is
     the 17500th row after the first numeric row */
  char *save = NULL, *line, *rows[17503];
  int nrow = 0;
  for (line = strtok_r(txt, "\r\n", &save); line; line = strtok_r(NULL, "\r\n", &save)) {
    double a, b, c;
    char tail;
    if (sscanf(line, "%lf %lf %lf %c", &a, &b, &c, &tail) == 3 && nrow < 17503)
      rows[nrow++] = line;
  }
  aq_check(nrow == 17502, "17502 data rows in the file (counted here): %d", nrow);
  for (int j = 0; j < 3; j++) {
    snprintf(name, sizeof name, R "agency2/CUP50401.012#%s", ch[j]);
    aq_record r;
    aq_error e;
    if (!aq_check(aq_record_read(name, &ro, &r, &e) == AQ_OK, "%s: %s", name, e.message))
      continue;
    double v[3];
    sscanf(rows[17499], "%lf %lf %lf", &v[0], &v[1], &v[2]);
    aq_check(r.npts == 17500 && r.acc_mps2[17499] == v[j] * 0.01, "%s: 17500 values, the "
             "last that of row 17500 (%g gal)", name, v[j]);
    aq_check(strstr(r.count_note, "17502 values") && strstr(r.count_note, "states 17500") &&
                 strstr(r.count_note, "NUM. TOTAL DE MUESTRAS") &&
                 strstr(r.count_note, "the 2 rows from line"),
             "%s: the note names both counts: %s", name, r.count_note);
    const char *topic = NULL;
    aq_check(aq_record_note(&r, 0, &topic) == r.count_note && strcmp(topic, "data") == 0,
             "the note is listed, topic data");
    aq_record_free(&r);
  }
  free(txt);
}

typedef struct {
  const char *file;   /* under tests/data/records */
  const char *record; /* as read: FILE or FILE#CHANNEL */
  const char *marker; /* the data end before which a row goes in (its last
                         line holding it, any case); NULL: the end of the file */
  size_t npts;        /* the count the file states */
  size_t row_values;  /* the values of that channel its last data row holds */
  aq_units units;     /* for files that state none */
} extra_case;

static const extra_case cases[] = {
    {"ARL360.at2", "ARL360.at2", NULL, 2000, 5, AQ_UNITS_FILE},         /* AT2: 5 a line */
    {"agency/0165b_a.smc", "0165b_a.smc", NULL, 6014, 6, AQ_UNITS_FILE}, /* SMC: 8E10 */
    {"agency2/PRUE1004.041", "PRUE1004.041#N00W", NULL, 240, 1, AQ_UNITS_FILE}, /* ASA */
    {"agency2/TK9999-20110305.txt", "TK9999-20110305.txt#N-S", NULL, 300, 1,
     AQ_UNITS_FILE}, /* NSMN: rows of three */
    {"agency/HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC",
     "HL.DLFA..HNE.D.20190728.160908.C.ACC.ASC", NULL, 13876, 1, AQ_UNITS_FILE}, /* ESM */
    {"AOM0170806140843.NS", "AOM0170806140843.NS", NULL, 11500, 4, AQ_UNITS_FILE}, /* K-NET */
    {"agency2/5522-1.V1", "5522-1.V1#T3", "/&", 9984, 4, AQ_UNITS_FILE}, /* BHRC 10E13.6 */
    {"copiapo1002271.v1", "copiapo1002271.v1#Z", "END OF DATA", 7000, 5,
     AQ_UNITS_FILE}, /* RENADIC: 5 pairs a line */
    {"agency/Cosmos12TimeSeriesTest.v1", "Cosmos12TimeSeriesTest.v1", "End of data", 7000, 8,
     AQ_UNITS_FILE}, /* COSMOS 8F10 */
    {"agency2/CIWLT-ch1-320pts.V1", "CIWLT-ch1-320pts.V1", NULL, 320, 8,
     AQ_UNITS_FILE}, /* CSMIP V1: 8 a line */
    {"agency2/npts-dt-values.txt", "npts-dt-values.txt", NULL, 403, 3, AQ_UNITS_G},
    {"agency2/npts-dt-pairs.txt", "npts-dt-pairs.txt", NULL, 350, 1, AQ_UNITS_G},
};

/* Case-insensitive: does line [b, e) hold s? */
static int holds(const char *b, const char *e, const char *s)
{
  size_t n = strlen(s);
  for (const char *p = b; p + n <= e; p++)
    if (strncasecmp(p, s, n) == 0)
      return 1;
  return 0;
}

/* Write dir/out: the file with its last data row (the last non-blank line
 * before the last line holding marker, or before the end) followed by a
 * copy (alter 0) or by the same row with its digits 1 and 2 made 7 and 8
 * (alter 1).  Returns the line number of the new row, 0 on failure. */
static long with_extra_row(const char *file, const char *marker, int alter, const char *out)
{
  size_t n;
  char *buf = aq_test_read_file(file, &n);
  if (!aq_check(buf != NULL, "read %s", file))
    return 0;
  size_t end = n; /* the end of the data: the start of the marker's line */
  while (end > 0 && (buf[end - 1] == '\n' || buf[end - 1] == '\r' || buf[end - 1] == ' ' ||
                     buf[end - 1] == 0x1A))
    end--;
  if (marker) {
    for (size_t b = 0, e; b < n; b = e + 1) {
      for (e = b; e < n && buf[e] != '\n'; e++)
        ;
      if (holds(buf + b, buf + e, marker))
        end = b;
    }
    while (end > 0 && (buf[end - 1] == '\n' || buf[end - 1] == '\r'))
      end--;
  }
  size_t lb = end; /* the last data row [lb, end) */
  while (lb > 0 && buf[lb - 1] != '\n')
    lb--;
  const char *nl = memchr(buf, '\r', n) ? "\r\n" : "\n";
  long line = 1;
  for (size_t i = 0; i < end; i++)
    line += buf[i] == '\n';
  FILE *f = fopen(out, "wb");
  if (!aq_check(f != NULL, "write %s", out)) {
    free(buf);
    return 0;
  }
  fwrite(buf, 1, end, f);
  fputs(nl, f);
  for (size_t i = lb; i < end; i++) {
    char c = buf[i];
    if (alter && (c == '1' || c == '2'))
      c = (char)(c + 6);
    fputc(c, f);
  }
  fwrite(buf + end, 1, n - end, f);
  free(buf);
  return fclose(f) == 0 ? line + 1 : 0;
}

AQ_TEST(io_extra_rows_every_reader)
{
  char dir[512], in[700], out[800], want[200], msg[1400];
  aq_test_tmpdir(dir, sizeof dir);
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    const extra_case *k = &cases[i];
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.units = k->units;
    ro.accept_vertical = 1;
    aq_record orig, r;
    aq_error e;
    snprintf(in, sizeof in, R "%s", k->file);
    const char *hash = strchr(k->record, '#');
    snprintf(out, sizeof out, "%s%s", in, hash ? hash : "");
    if (!aq_check(aq_record_read(out, &ro, &orig, &e) == AQ_OK, "%s: %s", out, e.message))
      continue;
    aq_check(orig.npts == k->npts && !orig.count_note[0], "%s as shipped: %zu values, no note",
             k->record, orig.npts);
    for (int alter = 0; alter < 2; alter++) {
      char src[700];
      const char *base = strrchr(k->file, '/') ? strrchr(k->file, '/') + 1 : k->file;
      snprintf(src, sizeof src, R "%s", k->file);
      snprintf(in, sizeof in, "%s/%s%s", dir, alter ? "alt_" : "rep_", base);
      long at = with_extra_row(src, k->marker, alter, in);
      if (!at)
        continue;
      char name[800];
      snprintf(name, sizeof name, "%s%s", in, hash ? hash : "");
      aq_status s = aq_record_read(name, &ro, &r, &e);
      aq_error_format(&e, msg, sizeof msg);
      if (!alter) {
        snprintf(want, sizeof want, "the file holds %zu values, ", k->npts + k->row_values);
        if (aq_check(s == AQ_OK, "%s with its last row twice: %s", k->record, msg)) {
          int same = r.npts == orig.npts;
          for (size_t j = 0; same && j < r.npts; j++)
            same = r.acc_mps2[j] == orig.acc_mps2[j];
          char line[64];
          snprintf(line, sizeof line, "the row at line %ld repeats", at);
          aq_check(same && strstr(r.count_note, want) && strstr(r.count_note, line),
                   "%s: the values as shipped, and a note: %s (want \"%s\", \"%s\")",
                   k->record, r.count_note, want, line);
          snprintf(want, sizeof want, " states %zu: ", k->npts);
          aq_check(strstr(r.count_note, want) != NULL, "%s: the stated count: %s", k->record,
                   r.count_note);
          aq_record_free(&r);
        }
      } else {
        snprintf(want, sizeof want, ":%ld: data: expected %zu values (", at, k->npts);
        char got[64];
        snprintf(got, sizeof got, "), got %zu: the row at line %ld is not a copy",
                 k->npts + k->row_values, at);
        aq_check(s == AQ_EFORMAT && strstr(msg, want) && strstr(msg, got) && !strchr(msg, '\n'),
                 "%s with another row after its last: %s (want \"%s\", \"%s\")", k->record, msg,
                 want, got);
      }
    }
    aq_record_free(&orig);
  }
}
