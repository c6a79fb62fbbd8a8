/* csv_names.c: what the words of a CSV / plain-text record say (csv.c,
 * csv_impl.h): units and quantities in column names and preamble lines,
 * time columns, "KEY = value" lines, the start times JMA and CWB state,
 * and a column's name as its channel's.
 */
#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "csv_impl.h"
#include "fixed.h"

/* Units named in a piece of text: 1 acceleration (*u set), -1 units that are
 * not acceleration (velocity, displacement, time), 0 none recognised. */
int aq_csv_units_in(const char *text, aq_units *u)
{
  static const char *const not_acc[] = {"cm/s", "m/s", "cm", "m", "mm", "in",
                                         "in/s", "mm/s", "s", "sec", NULL};
  char t[CSV_NAME_MAX];
  snprintf(t, sizeof t, "%s", text);
  /* inside () or [] */
  char *o = strpbrk(t, "([");
  if (o) {
    char *cl = strpbrk(o + 1, ")]");
    if (cl) {
      *cl = '\0';
      char *in = o + 1;
      while (*in == ' ')
        in++;
      if (aq_units_parse(in, u))
        return *u == AQ_UNITS_COUNTS ? 0 : 1;
      for (int i = 0; not_acc[i]; i++)
        if (strcasecmp(in, not_acc[i]) == 0)
          return -1;
    }
    *o = '\0'; /* "gal(cm/s/s)" -> "gal" */
  }
  size_t l = strlen(t);
  while (l > 0 && t[l - 1] == ' ')
    t[--l] = '\0';
  if (aq_units_parse(t, u) && *u != AQ_UNITS_COUNTS)
    return 1;
  char *sfx = strrchr(t, '_');
  if (!sfx)
    sfx = strrchr(t, ' ');
  if (sfx && aq_units_parse(sfx + 1, u) && *u != AQ_UNITS_COUNTS)
    return 1;
  return 0;
}

/* The quantity the units in text measure ("vel (cm/s)", "disp_cm",
 * "cm/s"): the word in () or [], after the last '_' or blank, or the whole
 * text (aq_units_quantity). */
aq_quantity aq_csv_quantity_in(const char *text)
{
  char t[CSV_NAME_MAX];
  snprintf(t, sizeof t, "%s", text);
  char *o = strpbrk(t, "([");
  if (o) {
    char *cl = strpbrk(o + 1, ")]");
    if (cl)
      *cl = '\0';
    char *in = o + 1;
    while (*in == ' ')
      in++;
    return aq_units_quantity(in);
  }
  size_t l = strlen(t);
  while (l > 0 && t[l - 1] == ' ')
    t[--l] = '\0';
  aq_quantity q = aq_units_quantity(t);
  char *sfx = strrchr(t, '_');
  if (!sfx)
    sfx = strrchr(t, ' ');
  return q != AQ_QUANTITY_UNSTATED || !sfx ? q : aq_units_quantity(sfx + 1);
}

int aq_csv_is_time_name(const char *name)
{
  char base[CSV_NAME_MAX];
  size_t k = 0;
  for (const char *p = name; *p && k + 1 < sizeof base; p++) {
    if (*p == '(' || *p == '[' || *p == '_' || *p == ' ')
      break;
    base[k++] = (char)tolower((unsigned char)*p);
  }
  base[k] = '\0';
  return strcmp(base, "t") == 0 || strcmp(base, "time") == 0 ||
         strcmp(base, "sec") == 0 || strcmp(base, "seconds") == 0 ||
         strcmp(base, "zeit") == 0 || strcmp(base, "tiempo") == 0 ||
         strcmp(base, "temps") == 0;
}

#define CSV_JST_OFFSET_H 9 /* JMA's times: Japan Standard Time, UTC+9 h */

/* JMA: "INITIAL TIME = YYYY MM DD hh mm ss" (JST) in [v, e). */
int aq_csv_jma_start(const char *v, const char *e, char *out, size_t cap)
{
  char tmp[64];
  size_t l = (size_t)(e - v) < sizeof tmp - 1 ? (size_t)(e - v) : sizeof tmp - 1;
  memcpy(tmp, v, l);
  tmp[l] = '\0';
  int y, mo, d, h, mi, sec, used = 0;
  if (sscanf(tmp, "%d %d %d %d %d %d%n", &y, &mo, &d, &h, &mi, &sec, &used) != 6 ||
      tmp[used + strspn(tmp + used, " \t")] != '\0')
    return 0;
  return aq_iso_time_local(out, cap, y, mo, d, h, mi, sec, CSV_JST_OFFSET_H);
}

/* CWB: "#StartTime(GMT+08): YYYY/MM/DD-hh:mm:ss.sss" in s[b..e) (after '#'). */
int aq_csv_cwb_start(const char *s, size_t b, size_t e, char *out, size_t cap)
{
  static const char key[] = "StartTime(GMT";
  size_t m = sizeof key - 1;
  if (e - b < m || strncasecmp(s + b, key, m) != 0)
    return 0;
  char tmp[80];
  size_t l = e - b - m < sizeof tmp - 1 ? e - b - m : sizeof tmp - 1;
  memcpy(tmp, s + b + m, l);
  tmp[l] = '\0';
  char sign;
  int oh, y, mo, d, h, mi, used = 0;
  double sec;
  if (sscanf(tmp, "%c%d): %d/%d/%d-%d:%d:%lf%n", &sign, &oh, &y, &mo, &d, &h, &mi, &sec,
             &used) != 8 ||
      (sign != '+' && sign != '-') || tmp[used + strspn(tmp + used, " \t")] != '\0')
    return 0;
  return aq_iso_time_local(out, cap, y, mo, d, h, mi, sec, sign == '-' ? -oh : oh);
}

/* "KEY = value" or "KEY: value" in a preamble line: returns the value's
 * start (in s) if the line's key starts with key (case-insensitive). */
const char *aq_csv_kv(const char *s, size_t b, size_t e, const char *key)
{
  size_t m = strlen(key);
  if (e - b < m || strncasecmp(s + b, key, m) != 0)
    return NULL;
  size_t i = b + m;
  while (i < e && s[i] != '=' && s[i] != ':')
    if (!isalpha((unsigned char)s[i]) && s[i] != ' ' && s[i] != '_' && s[i] != '.')
      return NULL;
    else
      i++;
  if (i >= e)
    return NULL;
  i++;
  while (i < e && s[i] == ' ')
    i++;
  return s + i;
}

/* A column's name as the channel's: as written when it fits; else without
 * its units in parentheses or brackets ("Acceleration (g)" ->
 * "Acceleration"); else none, never a cut phrase. */
void aq_csv_channel_name(const char *col, char *out, size_t cap)
{
  size_t n = strlen(col);
  if (n >= cap) {
    const char *u = strpbrk(col, "([");
    n = u ? (size_t)(u - col) : n;
    while (n > 0 && aq_csv_is_space(col[n - 1]))
      n--;
  }
  if (n >= cap)
    n = 0;
  memcpy(out, col, n);
  out[n] = '\0';
}
