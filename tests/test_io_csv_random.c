/* test_io_csv_random.c: the CSV reader on generated files: random number
 * layouts and widths, separators, LF, CRLF and CR ends, blanks around
 * fields, blank and comment lines, a bad character at each position, empty
 * fields and cut files.  Expected samples: strtod of the tokens written
 * (the C library, not the reader's parser); expected lines: counted in the
 * text here, a line ending at LF, at CR LF or at a run of CRs (and an LF
 * after it), as docs/agency-formats.md states for text records.  Files of
 * fixed layouts (the columns' shapes, number.h) are read with every byte of
 * them replaced in turn and cut at every byte.  Each buffer is a heap block
 * of exactly its size, so a read past its end is caught by the address
 * sanitizer. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define RND_FILES 300  /* random files of the value test */
#define RND_ROWS_MAX 90 /* rows of one such file */
#define RND_COLS_MAX 4  /* columns: time and up to three channels */
#define RND_TOK 40     /* characters of one token */

typedef struct {
  unsigned long long s;
} rng;

static unsigned rnd(rng *r, unsigned n)
{
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (unsigned)((r->s >> 33) % n);
}

/* A value token in one of the layouts machines write. */
static void value_token(rng *r, int layout, char *out, size_t cap)
{
  double v = (rnd(r, 2000001) - 1000000.0) / 1000000.0 * pow(10.0, (int)rnd(r, 9) - 6);
  switch (layout) {
  case 0: snprintf(out, cap, "%.7E", v); break;
  case 1: snprintf(out, cap, "%.6f", v); break;
  case 2: snprintf(out, cap, "%.9g", v); break;
  case 3: snprintf(out, cap, "%+.3e", v); break;
  case 4: snprintf(out, cap, "%.15e", v); break;
  default: snprintf(out, cap, "%.17g", v); break; /* 17 digits: strtod's slow cases */
  }
}

typedef struct {
  char *text;
  size_t len, cap;
  size_t rows, ncols;
  char tok[RND_ROWS_MAX][RND_COLS_MAX][RND_TOK];
} gen;

static void put(gen *g, const char *s)
{
  size_t l = strlen(s);
  if (g->len + l + 1 > g->cap) {
    g->cap = 2 * (g->len + l + 1);
    g->text = realloc(g->text, g->cap);
  }
  memcpy(g->text + g->len, s, l + 1);
  g->len += l;
}

/* A file of rows (time, channels): sep, line end, layouts random; blanks,
 * blank lines and comments when extras. */
static void generate(gen *g, rng *r, int extras)
{
  static const char seps[] = {',', ';', '\t', ' '};
  static const char *const ends[] = {"\n", "\r\n", "\r"};
  g->len = 0;
  g->ncols = 2 + rnd(r, RND_COLS_MAX - 1);
  g->rows = 2 + rnd(r, RND_ROWS_MAX - 1);
  char sep = seps[rnd(r, 4)];
  const char *end = ends[rnd(r, 3)];
  int cr = end[0] == '\r' && !end[1];
  int layout[RND_COLS_MAX];
  for (size_t i = 0; i < g->ncols; i++)
    layout[i] = (int)rnd(r, 6);
  const char *tfmt = rnd(r, 2) ? "%.3f" : "%.4f";
  char sp[2] = {sep, 0};
  put(g, "t");
  for (size_t i = 1; i < g->ncols; i++)
    put(g, sep == ' ' ? " a" : sep == '\t' ? "\ta" : sep == ';' ? ";a" : ",a");
  put(g, end);
  for (size_t k = 0; k < g->rows; k++) {
    if (extras && !cr && rnd(r, 10) == 0)
      put(g, rnd(r, 2) ? end : "# a comment, 1;2\n");
    snprintf(g->tok[k][0], RND_TOK, tfmt, (double)k * 0.005);
    for (size_t i = 1; i < g->ncols; i++)
      value_token(r, layout[i], g->tok[k][i], RND_TOK);
    for (size_t i = 0; i < g->ncols; i++) {
      if (i)
        put(g, sp);
      if (extras && rnd(r, 12) == 0)
        put(g, " ");
      put(g, g->tok[k][i]);
      if (extras && sep != ' ' && rnd(r, 12) == 0)
        put(g, " ");
    }
    if (k + 1 < g->rows || rnd(r, 4))
      put(g, end);
  }
}

/* generate, until a file of at most max_rows rows comes */
static void generate_short(gen *g, rng *r, int extras, size_t max_rows)
{
  do
    generate(g, r, extras);
  while (g->rows > max_rows);
}

/* 1-based line of byte pos of s[0..n), lines as the header comment says. */
static long line_at(const char *s, size_t pos)
{
  long line = 1;
  for (size_t i = 0; i < pos;) {
    if (s[i] == '\r') {
      while (i < pos && s[i] == '\r')
        i++;
      if (i < pos && s[i] == '\n')
        i++;
      line++;
    } else if (s[i++] == '\n') {
      line++;
    }
  }
  return line;
}

/* bits of a and b equal */
static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Parse s[0..n) from a buffer of exactly n bytes (reads past it are
 * caught by the address sanitizer). */
static aq_status parse_exact(const char *s, size_t n, aq_raw_file *raw, aq_error *e)
{
  unsigned char *b = malloc(n ? n : 1);
  memcpy(b, s, n);
  aq_status st = aq_raw_parse(b, n, "rnd.csv", NULL, raw, e);
  free(b);
  return st;
}

static void slow_drift(int N, double bow_s);

static size_t check_values(const gen *g, const aq_raw_file *raw, size_t rows, const char *what)
{
  size_t bad = 0;
  if (!aq_check(raw->nchan == g->ncols - 1, "%s: %zu channels, want %zu", what, raw->nchan,
                g->ncols - 1))
    return 1;
  for (size_t j = 0; j < raw->nchan; j++) {
    if (!aq_check(raw->chan[j].npts >= rows, "%s: channel %zu npts %zu, want %zu", what, j,
                  raw->chan[j].npts, rows))
      return 1;
    for (size_t k = 0; k < rows; k++)
      if (!same(raw->chan[j].values[k], strtod(g->tok[k][j + 1], NULL)) && bad++ < 5)
        aq_check(0, "%s: row %zu column %zu: %.17g, strtod(\"%s\") %.17g", what, k, j + 2,
                 raw->chan[j].values[k], g->tok[k][j + 1], strtod(g->tok[k][j + 1], NULL));
  }
  return bad;
}

AQ_TEST(io_csv_random_files_equal_strtod)
{
  rng r = {20261123};
  gen g = {0};
  size_t bad = 0, values = 0;
  for (int f = 0; f < RND_FILES; f++) {
    generate(&g, &r, f % 2);
    aq_raw_file raw;
    aq_error e;
    char what[64];
    snprintf(what, sizeof what, "file %d", f);
    if (!aq_check(parse_exact(g.text, g.len, &raw, &e) == AQ_OK, "%s: %s", what, e.message))
      continue;
    aq_check(raw.chan[0].npts == g.rows, "%s: %zu rows, want %zu", what, raw.chan[0].npts,
             g.rows);
    bad += check_values(&g, &raw, g.rows, what);
    values += g.rows * (g.ncols - 1);
    aq_check(raw.chan[0].dt_s == 0.005, "%s: dt %.17g", what, raw.chan[0].dt_s);
    aq_raw_file_free(&raw);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %d random files, %zu values, %zu differ from strtod\n", RND_FILES, values, bad);
  free(g.text);
}

/* A bad character at each position of the rows: refused at its line. */
AQ_TEST(io_csv_bad_character_at_each_position)
{
  rng r = {7};
  gen g = {0};
  size_t tried = 0, wrong = 0;
  for (int f = 0; f < 24; f++) {
    generate_short(&g, &r, 0, 12);
    /* from the second row on (a first row that is not numbers would be
     * taken for a line of the preamble) */
    size_t first = 0;
    for (int l = 0; l < 2; l++) {
      first += strcspn(g.text + first, "\r\n");
      first += g.text[first] == '\r' && g.text[first + 1] == '\n' ? 2 : 1;
    }
    for (size_t pos = first; pos < g.len; pos++) {
      char *t = malloc(g.len);
      memcpy(t, g.text, g.len);
      t[pos] = 'x';
      long want = line_at(t, pos);
      aq_raw_file raw;
      aq_error e;
      aq_status st = parse_exact(t, g.len, &raw, &e);
      tried++;
      if (st == AQ_OK) {
        aq_raw_file_free(&raw);
        if (wrong++ < 5)
          aq_check(0, "file %d: 'x' at byte %zu accepted:\n%.*s", f, pos, (int)g.len, t);
      } else if (e.line != want && wrong++ < 5) {
        aq_check(0, "file %d: 'x' at byte %zu: line %ld, want %ld (%s)", f, pos, e.line, want,
                 e.message);
      }
      free(t);
    }
  }
  aq_check(wrong == 0, "%zu of %zu bad characters misreported", wrong, tried);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu bad characters, %zu misreported\n", tried, wrong);
  free(g.text);
}

/* An empty field in any row and column: refused at its line, naming the
 * column. */
AQ_TEST(io_csv_missing_value_named)
{
  rng r = {99};
  gen g = {0};
  for (int f = 0; f < 40; f++) {
    do
      generate(&g, &r, 0);
    while (g.text[1] == ' ' || g.text[1] == '\t'); /* blanks and tabs around a line are cut */
    /* not the first row: one that is not numbers would be preamble */
    size_t k = 1 + rnd(&r, (unsigned)g.rows - 1), col = rnd(&r, (unsigned)g.ncols);
    /* the token of row k, column col: blank it out of the text */
    size_t p = strcspn(g.text, "\r\n");
    p += strspn(g.text + p, "\r\n");
    for (size_t i = 0; i < k; i++) {
      p += strcspn(g.text + p, "\r\n");
      p += g.text[p] == '\r' && g.text[p + 1] == '\n' ? 2 : 1;
    }
    for (size_t i = 0; i < col; i++)
      p += strcspn(g.text + p, ",;\t") + 1;
    size_t l = strlen(g.tok[k][col]);
    if (!aq_check(strncmp(g.text + p, g.tok[k][col], l) == 0, "file %d: token found", f))
      continue;
    memmove(g.text + p, g.text + p + l, g.len - p - l);
    g.len -= l;
    aq_raw_file raw;
    aq_error e;
    char want[32];
    snprintf(want, sizeof want, "column %zu", col + 1);
    if (aq_check(parse_exact(g.text, g.len, &raw, &e) != AQ_OK, "file %d: empty field refused",
                 f)) {
      aq_check(e.line == (long)k + 2, "file %d: line %ld, want %zu", f, e.line, k + 2);
      aq_check(strstr(e.field, want) && strstr(e.message, "got \"\""),
               "file %d: field \"%s\" message \"%s\"", f, e.field, e.message);
    } else {
      aq_raw_file_free(&raw);
    }
  }
  free(g.text);
}

/* Every cut of a file: no read past the end; what is read is the rows
 * before the cut, as strtod reads them. */
AQ_TEST(io_csv_cut_files)
{
  rng r = {31};
  gen g = {0};
  size_t cuts = 0, ok = 0;
  for (int f = 0; f < 12; f++) {
    generate_short(&g, &r, 1, 20);
    for (size_t n = 0; n < g.len; n++) {
      aq_raw_file raw;
      aq_error e;
      cuts++;
      if (parse_exact(g.text, n, &raw, &e) != AQ_OK)
        continue;
      ok++;
      size_t rows = raw.chan[0].npts;
      char what[64];
      snprintf(what, sizeof what, "file %d cut at %zu", f, n);
      /* the last row read may be cut short: the ones before are whole */
      aq_check(rows >= 2 && rows <= g.rows, "%s: %zu rows", what, rows);
      if (rows >= 2)
        check_values(&g, &raw, rows - 1, what);
      aq_raw_file_free(&raw);
    }
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu cuts, %zu read\n", cuts, ok);
  free(g.text);
}

/* Times whose every step is within 1 % of the median but that drift from
 * t_0 + k dt by more than 1 % of dt: refused at the first row that does
 * (the rule of csv.c's header comment, evaluated here on strtod's times). */
AQ_TEST(io_csv_slow_drift_of_times_named)
{
  /* weaker bows drift past 1 % later: the first such row in each lane of
   * four (rows 2, 3, 4, 5, 6, ...) */
  for (int m = 2; m <= 16; m++)
    slow_drift(200, 8e-7 / m);
}

/* t_k = 0.01 k + bow_s k (N - 1 - k) */
static void slow_drift(int N, double bow_s)
{
  char *text = malloc((size_t)N * 40 + 16);
  double *t = malloc((size_t)N * sizeof *t);
  size_t p = (size_t)sprintf(text, "t,acc\n");
  for (int k = 0; k < N; k++) {
    char tok[32];
    snprintf(tok, sizeof tok, "%.9f", 0.01 * k + bow_s * k * (N - 1 - k));
    t[k] = strtod(tok, NULL);
    p += (size_t)sprintf(text + p, "%s,%.4f\r\n", tok, 0.001 * (k % 17));
  }
  double est = (t[N - 1] - t[0]) / (N - 1);
  long want = -1;
  for (int k = 1; k < N && want < 0; k++)
    if (fabs(t[k] - (t[0] + k * est)) > 0.01 * est)
      want = k + 2;
  aq_raw_file raw;
  aq_error e;
  aq_check(want > 0, "the drift exceeds 1 %% of dt somewhere");
  if (aq_check(parse_exact(text, p, &raw, &e) != AQ_OK, "drift refused")) {
    aq_check(e.line == want, "line %ld, want %ld (%s)", e.line, want, e.message);
    aq_check(strstr(e.message, "for sample") != NULL, "message %s", e.message);
  } else {
    aq_raw_file_free(&raw);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %d rows: the drift named at line %ld\n", N, e.line);
  free(t);
  free(text);
}

/* ---- rows four at a time (csv_fields.c) ------------------------------
 * Files of fixed layouts, so the AVX2 kernel takes their rows: "%.3f"
 * times whose width grows past 10, 100 and 1000 s, channels "%.7E", "%.6f",
 * "%+.3e", "%.4f" with random signs and now and then an exponent too large
 * for the exact path or about its edges (10^22 and 10^23 either way),
 * separators ',', ';', tab, LF and CR LF ends, the header padded by pad
 * bytes (rows starting at every offset of a 32-byte block); rows rows. */
static void generate_fixed(gen *g, rng *r, size_t pad, size_t rows)
{
  static const char seps[] = {',', ';', '\t'};
  static const char *const fmts[] = {"%.7E", "%.6f", "%+.3e", "%.4f"};
  static const double t0s[] = {0.0, 9.9, 99.85, 999.9};
  g->len = 0;
  g->ncols = 2 + rnd(r, RND_COLS_MAX - 1);
  g->rows = rows;
  char sep[2] = {seps[rnd(r, 3)], 0};
  const char *end = rnd(r, 2) ? "\n" : "\r\n";
  int fmt[RND_COLS_MAX];
  for (size_t i = 1; i < g->ncols; i++)
    fmt[i] = (int)rnd(r, 4);
  double t0 = t0s[rnd(r, 4)];
  put(g, "t");
  for (size_t i = 1; i < g->ncols; i++) {
    put(g, sep);
    put(g, "a");
    if (i == 1)
      for (size_t j = 0; j < pad; j++)
        put(g, "x");
  }
  put(g, end);
  for (size_t k = 0; k < rows; k++) {
    snprintf(g->tok[k][0], RND_TOK, "%.3f", t0 + (double)k * 0.005);
    for (size_t i = 1; i < g->ncols; i++) {
      double v = (rnd(r, 2000001) - 1000000.0) / 1000000.0 * pow(10.0, (int)rnd(r, 7) - 5);
      if (rnd(r, 40) == 0)
        v *= 1e-25; /* 10^e not exact: strtod's */
      else if ((fmt[i] == 0 || fmt[i] == 2) && rnd(r, 8) == 0)
        /* exponents about the exact path's edges, e = exponent less the
         * digits after the point: +-22 and +-23 */
        v = (1 + rnd(r, 1000000) / 1e6) * pow(10.0, (int)rnd(r, 14) + (rnd(r, 2) ? 18 : -23));
      snprintf(g->tok[k][i], RND_TOK, fmts[fmt[i]], v);
    }
    for (size_t i = 0; i < g->ncols; i++) {
      if (i)
        put(g, sep);
      put(g, g->tok[k][i]);
    }
    if (k + 1 < rows || rnd(r, 2))
      put(g, end);
  }
}

/* s[0..n) read from a heap block of exactly n bytes. */
static aq_status parse_heap(const char *s, size_t n, aq_raw_file *raw, aq_error *e)
{
  unsigned char *b = malloc(n ? n : 1);
  memcpy(b, s, n);
  aq_status st = aq_raw_parse(b, n, "fixed.csv", NULL, raw, e);
  free(b);
  return st;
}

/* Every alignment: the values strtod gives. */
AQ_TEST(io_csv_rows_fixed_layouts_equal_strtod)
{
  rng r = {424242};
  gen g = {0};
  size_t bad = 0, values = 0;
  for (size_t pad = 0; pad < 32; pad++)
      for (int f = 0; f < 4; f++) {
        generate_fixed(&g, &r, pad, 40 + rnd(&r, RND_ROWS_MAX - 40));
        aq_raw_file raw;
        aq_error e;
        if (!aq_check(parse_heap(g.text, g.len, &raw, &e) == AQ_OK, "pad %zu: %s", pad,
                      e.message))
          continue;
        aq_check(raw.nchan == g.ncols - 1, "pad %zu: %zu channels", pad, raw.nchan);
        for (size_t j = 0; j < raw.nchan; j++) {
          aq_check(raw.chan[j].npts == g.rows, "pad %zu: %zu rows, want %zu", pad,
                   raw.chan[j].npts, g.rows);
          for (size_t k = 0; k < g.rows && k < raw.chan[j].npts; k++, values++)
            if (!same(raw.chan[j].values[k], strtod(g.tok[k][j + 1], NULL)) && bad++ < 5)
              aq_check(0, "pad %zu row %zu column %zu: %.17g, strtod(\"%s\") %.17g",
                       pad, k, j + 2, raw.chan[j].values[k], g.tok[k][j + 1],
                       strtod(g.tok[k][j + 1], NULL));
        }
        aq_check(raw.chan[0].dt_s == 0.005, "pad %zu: dt %.17g", pad, raw.chan[0].dt_s);
        aq_raw_file_free(&raw);
      }
  aq_check(bad == 0, "%zu of %zu values differ from strtod", bad, values);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu values, %zu differ from strtod\n", values, bad);
  free(g.text);
}

/* Each byte of the rows replaced in turn: read within the buffer (the
 * address sanitizer watches), and a letter is refused at its line. */
AQ_TEST(io_csv_rows_bad_byte_each_position)
{
  static const char bytes[] = {'x', '.', '7', '-', 'e', '\n'};
  rng r = {1123};
  gen g = {0};
  size_t tried = 0, wrong = 0;
  for (int f = 0; f < 6; f++) {
    generate_fixed(&g, &r, (size_t)f * 5, 24);
    /* from the second row on (a first row that is not numbers would be
     * taken for a line of the preamble) */
    size_t first = 0;
    for (int l = 0; l < 2; l++)
      first += strcspn(g.text + first, "\n") + 1;
    char *t = malloc(g.len);
    for (size_t pos = first; pos < g.len; pos++)
      for (size_t b = 0; b < sizeof bytes; b++) {
        if (g.text[pos] == bytes[b])
          continue;
        memcpy(t, g.text, g.len);
        t[pos] = bytes[b];
        aq_raw_file raw;
        aq_error e;
        tried++;
        aq_status st = parse_heap(t, g.len, &raw, &e);
        if (st == AQ_OK)
          aq_raw_file_free(&raw);
        if (bytes[b] == 'x' && (st == AQ_OK || e.line != line_at(t, pos)) && wrong++ < 5)
          aq_check(0, "file %d: 'x' at byte %zu: status %d line %ld, want line %ld", f, pos,
                   (int)st, st == AQ_OK ? -1 : e.line, line_at(t, pos));
      }
    free(t);
  }
  aq_check(wrong == 0, "%zu of %zu letters misreported", wrong, tried);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu changed bytes, %zu misreported\n", tried, wrong);
  free(g.text);
}

/* Every cut of such files: no read past the end (the address sanitizer
 * watches), and every row left whole reads as strtod reads its fields. */
AQ_TEST(io_csv_rows_cut_anywhere)
{
  rng r = {77};
  gen g = {0};
  size_t cuts = 0, bad = 0;
  for (int f = 0; f < 6; f++) {
    generate_fixed(&g, &r, (size_t)f * 3, 30);
    for (size_t n = 0; n <= g.len; n++) {
      aq_raw_file raw;
      aq_error e;
      cuts++;
      if (parse_heap(g.text, n, &raw, &e) != AQ_OK)
        continue;
      /* rows whose line end lies inside the cut are whole */
      size_t whole = 0, pos = strcspn(g.text, "\n") + 1;
      while (pos < n) {
        size_t len = strcspn(g.text + pos, "\n");
        if (pos + len >= n)
          break;
        whole++;
        pos += len + 1;
      }
      for (size_t j = 0; j < raw.nchan; j++)
        for (size_t k = 0; k < whole && k < raw.chan[j].npts; k++)
          if (!same(raw.chan[j].values[k], strtod(g.tok[k][j + 1], NULL)) && bad++ < 5)
            aq_check(0, "file %d cut at %zu: row %zu column %zu: %.17g, strtod(\"%s\") %.17g",
                     f, n, k, j + 2, raw.chan[j].values[k], g.tok[k][j + 1],
                     strtod(g.tok[k][j + 1], NULL));
      aq_raw_file_free(&raw);
    }
  }
  aq_check(bad == 0, "%zu values of whole rows differ from strtod over %zu cuts", bad, cuts);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  %zu cuts, %zu values differ\n", cuts, bad);
  free(g.text);
}

/* One row's time moved by 30 % of the step, at each row in turn: refused
 * at that row's line (its step is 1.3 dt, the first uneven one). */
AQ_TEST(io_csv_rows_uneven_step_each_row)
{
  enum { N = 41 };
  size_t wrong = 0;
  for (int j = 1; j < N; j++) {
    char *text = malloc(N * 32 + 16);
    size_t p = (size_t)sprintf(text, "t,acc\n");
    for (int k = 0; k < N; k++)
      p += (size_t)sprintf(text + p, "%.3f,%.4f\n", 0.01 * k + (k == j ? 0.003 : 0.0),
                           0.001 * (k % 7));
    aq_raw_file raw;
    aq_error e;
    aq_status st = parse_heap(text, p, &raw, &e);
    if (st == AQ_OK) {
      aq_raw_file_free(&raw);
      if (wrong++ < 5)
        aq_check(0, "row %d moved: accepted", j);
    } else if ((e.line != j + 2 || !strstr(e.message, "evenly spaced")) && wrong++ < 5) {
      aq_check(0, "row %d moved: line %ld, want %d (%s)", j, e.line, j + 2, e.message);
    }
    free(text);
  }
  aq_check(wrong == 0, "%zu of %d moved rows misreported", wrong, N - 1);
}
