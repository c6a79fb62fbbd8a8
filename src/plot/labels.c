/* labels.c: the texts of a figure (see plot.h, labels.h): PLplot's escapes
 * as plain text and back, names ellipsized to a count of characters or
 * to a width (alone, or a figure's names together so that they stay
 * apart), and the width of a text from the advance widths of DejaVu
 * Sans, the font the cairo drivers and librsvg draw "sans" with.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "labels.h"
#include "plot.h"

/* PLplot's Greek escapes (#g + the Latin key) as the Unicode letters. */
static const char GREEK_KEY[] = "ABGDEZYHIKLMNCOPRSTUFXQWabgdezyhiklmncoprstufxqw";
static const char *const GREEK[] = {
    "Α", "Β", "Γ", "Δ", "Ε", "Ζ", "Η", "Θ", "Ι", "Κ", "Λ", "Μ", "Ν", "Ξ", "Ο", "Π",
    "Ρ", "Σ", "Τ", "Υ", "Φ", "Χ", "Ψ", "Ω", "α", "β", "γ", "δ", "ε", "ζ", "η", "θ",
    "ι", "κ", "λ", "μ", "ν", "ξ", "ο", "π", "ρ", "σ", "τ", "υ", "φ", "χ", "ψ", "ω"};

void aq_plot_plain(const char *s, char *out, size_t cap)
{
  size_t n = 0;
  if (cap == 0)
    return;
  for (; *s && n + 1 < cap; s++) {
    const char *put = NULL;
    char one[2] = {*s, 0};
    if (s[0] == '#' && s[1] == 'g' && s[2] && strchr(GREEK_KEY, s[2])) {
      put = GREEK[strchr(GREEK_KEY, s[2]) - GREEK_KEY];
      s += 2;
    } else if (s[0] == '#' && s[1] && strchr("udbf", s[1])) {
      s += 1; /* raise, lower, backspace: the text stays on the line */
      continue;
    } else if (s[0] == '#' && s[1] == '#') {
      put = "#";
      s += 1;
    } else
      put = one;
    size_t len = strlen(put);
    if (n + len + 1 > cap)
      break;
    memcpy(out + n, put, len);
    n += len;
  }
  out[n] = '\0';
}

/* Bytes of the UTF-8 character that starts at s (1 for a stray byte). */
static size_t utf8_len(const char *s)
{
  unsigned char c = (unsigned char)*s;
  size_t n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 1;
  for (size_t i = 1; i < n; i++)
    if (((unsigned char)s[i] & 0xc0) != 0x80)
      return 1;
  return n;
}

size_t aq_plot_utf8_chars(const char *s)
{
  size_t n = 0;
  for (; *s; s += utf8_len(s))
    n++;
  return n;
}

void aq_plot_escape(const char *s, char *out, size_t cap)
{
  size_t n = 0;
  if (cap == 0)
    return;
  for (; *s && n + 2 < cap; s++) {
    if (*s == '#')
      out[n++] = '#'; /* PLplot's escape character, doubled: itself */
    out[n++] = *s;
  }
  out[n] = '\0';
  if (*s && cap >= 4) { /* cut: its end marked "…", never half a character */
    size_t k = cap - 4 < n ? cap - 4 : n;
    while (k > 0 && ((unsigned char)out[k] & 0xC0) == 0x80)
      k--;
    if (k > 0 && out[k - 1] == '#' && (k < 2 || out[k - 2] != '#'))
      k--; /* not half an escape */
    memcpy(out + k, "\xe2\x80\xa6", 4);
  }
}

void aq_plot_ellipsize(const char *s, size_t max_chars, char *out, size_t cap)
{
  size_t n = aq_plot_utf8_chars(s);
  char plain[1024];
  if (cap == 0)
    return;
  if (n <= max_chars || max_chars < 3)
    snprintf(plain, sizeof plain, "%s", s);
  else {
    size_t keep = max_chars - 1, head = (keep + 1) / 2, tail = keep - head;
    const char *p = s, *q = s;
    for (size_t i = 0; i < head; i++)
      p += utf8_len(p);
    for (size_t i = 0; i < n - tail; i++)
      q += utf8_len(q);
    snprintf(plain, sizeof plain, "%.*s…%s", (int)(p - s), s, q);
  }
  aq_plot_escape(plain, out, cap);
}

/* DejaVu Sans (Book, version 2.37), the font the cairo drivers and
 * librsvg find for "sans" on Debian (fc-match sans): the advance widths
 * of U+0020 .. U+007E in 1/2048 em, from the font's hmtx table. */
static const unsigned short ADVANCE[95] = {
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690,  690,  1716, 1716, 1716, 1087,
    2048, 1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612,
    1235, 1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799,  690,  799,  1716, 1024,
    1024, 1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186, 569,  1995, 1298, 1253,
    1300, 1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075, 1303, 690,  1303, 1716};
/* and of the other characters the figures write (the rest: 1 em) */
static const struct {
  unsigned long u;
  unsigned short adv;
} ADVANCE_MORE[] = {{0x2026, 2048}, {0x3bb, 1212}, {0x3b2, 1307}, {0x3bc, 1303}, {0xb1, 1716},
                    {0x25cf, 1787}, {0x25cb, 1787}, {0x25c6, 1575}, {0xd7, 1716}, {0x2212, 1716},
                    {0xb2, 821},    {0xb3, 821},    {0x2013, 1024}, {0xb7, 651},  {0x3b8, 1253},
                    {0x3b6, 1114},  {0x2002, 1024}, {0x207b, 1081}, {0x2070, 821},
                    {0xb9, 821},    {0x2074, 821},  {0x2075, 821},  {0x2076, 821},
                    {0x2077, 821},  {0x2078, 821},  {0x2079, 821},  {0x3b3, 1212},
                    {0x3b4, 1253},  {0x3b5, 1107},  {0x3a6, 1612},  {0x3c6, 1351},
                    {0x394, 1401}};

/* The code point at s (and its bytes in *n). */
static unsigned long utf8_code(const char *s, size_t *n)
{
  const unsigned char *u = (const unsigned char *)s;
  *n = 1;
  if (u[0] < 0x80)
    return u[0];
  size_t len = u[0] >= 0xf0 ? 4 : u[0] >= 0xe0 ? 3 : u[0] >= 0xc0 ? 2 : 1;
  unsigned long c = u[0] & (0x3f >> (len - 1));
  for (size_t i = 1; i < len; i++) {
    if ((u[i] & 0xc0) != 0x80)
      return u[0];
    c = c << 6 | (u[i] & 0x3f);
  }
  *n = len;
  return c;
}

static double advance_em(unsigned long u)
{
  if (u >= 0x20 && u <= 0x7e)
    return ADVANCE[u - 0x20] / 2048.0;
  for (size_t k = 0; k < sizeof ADVANCE_MORE / sizeof ADVANCE_MORE[0]; k++)
    if (ADVANCE_MORE[k].u == u)
      return ADVANCE_MORE[k].adv / 2048.0;
  return 1.0;
}

double aq_plot_text_em(const char *s)
{
  double em = 0, size = 1;
  while (*s) {
    if (s[0] == '#' && s[1] == 'g' && s[2] && strchr(GREEK_KEY, s[2])) {
      size_t n;
      em += size * advance_em(utf8_code(GREEK[strchr(GREEK_KEY, s[2]) - GREEK_KEY], &n));
      s += 3;
    } else if (s[0] == '#' && (s[1] == 'u' || s[1] == 'd')) {
      size = size < 1 ? 1 : 0.75; /* a sub- or superscript, and back */
      s += 2;
    } else if (s[0] == '#' && s[1] == '#') {
      em += size * advance_em('#');
      s += 2;
    } else {
      size_t n;
      em += size * advance_em(utf8_code(s, &n));
      s += n;
    }
  }
  return em;
}

void aq_plot_shorten_to(const char *s, double width_mm, char *out, size_t cap)
{
  size_t n = aq_plot_utf8_chars(s);
  for (size_t keep = n; keep >= 5; keep--) {
    aq_plot_ellipsize(s, keep, out, cap);
    if (aq_plot_text_mm(out) <= width_mm)
      return;
  }
  aq_plot_ellipsize(s, 5, out, cap);
}

double aq_plot_font_mm(double height_mm)
{
  return FONT_PER_HEIGHT * height_mm;
}

/* The first head and the last keep - 1 - head characters of s (n
 * characters) with an ellipsis between, into out[cap]; s if n <= keep. */
static void cut(const char *s, size_t n, size_t keep, size_t head, char *out, size_t cap)
{
  if (n <= keep || keep < 3) {
    snprintf(out, cap, "%s", s);
    return;
  }
  size_t tail = keep - 1 - head;
  const char *p = s, *q = s;
  for (size_t i = 0; i < head; i++)
    p += utf8_len(p);
  for (size_t i = 0; i < n - tail; i++)
    q += utf8_len(q);
  snprintf(out, cap, "%.*s…%s", (int)(p - s), s, q);
}

/* The characters of s from character `from`, count of them, with an
 * ellipsis where s goes on, before and after, into out[cap]. */
static void window(const char *s, size_t n, size_t from, size_t count, char *out, size_t cap)
{
  const char *p = s;
  for (size_t i = 0; i < from; i++)
    p += utf8_len(p);
  const char *q = p;
  for (size_t i = 0; i < count && *q; i++)
    q += utf8_len(q);
  snprintf(out, cap, "%s%.*s%s", from > 0 ? "…" : "", (int)(q - p), p,
           from + count < n ? "…" : "");
}

/* Characters s and t have in common from their start. */
static size_t common_start(const char *s, const char *t)
{
  size_t n = 0;
  while (*s && *s == *t) {
    size_t k = utf8_len(s);
    if (strncmp(s, t, k) != 0)
      break;
    s += k;
    t += k;
    n++;
  }
  return n;
}

void aq_plot_ellipsize_set(const char *const *names, size_t n, size_t max_chars, char *out,
                           size_t cap)
{
  enum { PLAIN = 1024 };
  char(*plain)[PLAIN] = malloc((n ? n : 1) * sizeof *plain);
  if (!plain) { /* each on its own */
    for (size_t i = 0; i < n; i++)
      aq_plot_ellipsize(names[i], max_chars, out + i * cap, cap);
    return;
  }
  /* the share of the kept characters taken from the start: even first,
     then more of the end (where file names differ most: a station, a
     component), then more of the start */
  static const double head_share[] = {0.5, 0.35, 0.2, 0.65, 0.8, 0.1, 0.9, 0, 1};
  int distinct = 0;
  for (size_t r = 0; r < sizeof head_share / sizeof head_share[0] && !distinct; r++) {
    size_t keep = max_chars, head = (size_t)lround(head_share[r] * (double)(keep - 1));
    for (size_t i = 0; i < n; i++)
      cut(names[i], aq_plot_utf8_chars(names[i]), keep, keep >= 3 ? head : 0, plain[i], PLAIN);
    distinct = 1;
    for (size_t i = 0; i < n && distinct; i++)
      for (size_t j = i + 1; j < n && distinct; j++)
        distinct = strcmp(plain[i], plain[j]) != 0 || strcmp(names[i], names[j]) == 0;
  }
  /* names alike at both ends: each shortened name shows where it first
     differs from the others */
  for (size_t i = 0; i < n && !distinct; i++) {
    size_t len = aq_plot_utf8_chars(names[i]), at = 0;
    if (len <= max_chars || max_chars < 5)
      continue;
    for (size_t j = 0; j < n; j++)
      if (j != i && strcmp(names[i], names[j]) != 0) {
        size_t c = common_start(names[i], names[j]);
        at = c > at ? c : at;
      }
    size_t count = max_chars - 2, from = at > count / 4 ? at - count / 4 : 0;
    if (from + count > len)
      from = len - count;
    window(names[i], len, from, count, plain[i], PLAIN);
  }
  for (size_t i = 0; i < n; i++)
    aq_plot_escape(plain[i], out + i * cap, cap);
  free(plain);
}

void aq_plot_shorten_set_to(const char *const *names, size_t n, const double *room_mm,
                            char *out, size_t cap)
{
  size_t longest = 0;
  for (size_t i = 0; i < n; i++) {
    size_t c = aq_plot_utf8_chars(names[i]);
    longest = c > longest ? c : longest;
  }
  for (size_t keep = longest; keep >= 5; keep--) {
    aq_plot_ellipsize_set(names, n, keep, out, cap);
    size_t i = 0;
    while (i < n && aq_plot_text_mm(out + i * cap) <= room_mm[i] + 1e-9)
      i++;
    if (i == n)
      return;
  }
  aq_plot_ellipsize_set(names, n, 5, out, cap);
}
