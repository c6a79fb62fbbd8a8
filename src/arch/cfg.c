/* cfg.c: the arch file (.cfg, INI read with libinih): its sections and keys
 * checked, each message naming the file, the line and the key; the arch
 * then built by arch.c (aq_arch_build).  The format, with units, defaults
 * and an example per arch type, is documented in docs/arch-file.md.
 *
 * The sections and keys, their kinds, ranges, defaults and the shapes that
 * take and need each, are the table of cfg_keys.c: every other section or
 * key is an error, as is a key given twice or a value outside its range
 * (read from the table: the message names it).  What the table cannot say
 * is here: [fill] with both keys or none, [hinges] with a primary or a
 * control (the control's default: fixed with a primary, free without; a
 * reverse needs a primary and fixed control), a key
 * the shape does not take, the joints and faces files read by joints.c
 * (paths relative to the .cfg).  A new key or section is a row of that
 * table (how: cfg_keys.h) and, for what it sets, a case in handler() below;
 * `archquake help arch-file` and the manual page then document it.
 * libinih calls the handler for each key as it reads the line; the reader
 * below feeds it line by line and counts lines, so every message names the
 * line of its key.  Reading the file, the checks once every key is read
 * and the build are cfg_load.c's.
 */
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "arch.h"
#include "cfg_keys.h"
#include "infile.h"
#include "joints.h"
#include "model.h"

#include "cfg_impl.h"

static int fail(parse_ctx *c, aq_status s, const char *field, const char *fmt,
                const char *got)
{
  if (!c->failed) {
    aq_error_set(c->err, s, c->file, c->line, -1, field, fmt, got);
    c->failed = 1;
  }
  return 0;
}

/* "[arch], [fill], ... or [dynamics]" from the table, between pre and post. */
static void section_list(char *buf, size_t n, const char *pre, const char *post)
{
  size_t len = (size_t)snprintf(buf, n, "%s", pre);
  for (size_t k = 0; k < aq_cfg_nsections && len < n; k++)
    len += (size_t)snprintf(buf + len, n - len, "%s[%s]",
                            k == 0 ? "" : k + 1 < aq_cfg_nsections ? ", " : " or ",
                            aq_cfg_sections[k].name);
  if (len < n)
    snprintf(buf + len, n - len, "%s", post);
}

char *aq_cfg_reader(char *str, int num, void *stream)
{
  parse_ctx *c = stream;
  if (c->failed || !*c->text)
    return NULL;
  const char *nl = strchr(c->text, '\n');
  size_t len = nl ? (size_t)(nl - c->text) + 1 : strlen(c->text);
  c->line++;
  if (len > MAX_LINE_CHARS || (int)len >= num) {
    if (!c->failed)
      aq_error_set(c->err, AQ_EFORMAT, c->file, c->line, -1, NULL,
                   "expected a line of at most %d characters, got %zu", MAX_LINE_CHARS, len);
    c->failed = 1;
    return NULL;
  }
  memcpy(str, c->text, len);
  str[len] = '\0';
  c->text += len;
  /* sections: libinih does not report them, so check them here */
  const char *p = str;
  if (c->line == 1 && !strncmp(p, "\xEF\xBB\xBF", 3))
    p += 3; /* a UTF-8 byte-order mark, which libinih skips too */
  while (*p == ' ' || *p == '\t')
    p++;
  if (*p == '[') {
    const char *e = strchr(p, ']');
    size_t n = e ? (size_t)(e - p - 1) : 0;
    char sec[64];
    snprintf(sec, sizeof sec, "%.*s", (int)(n < 63 ? n : 63), p + 1);
    size_t k = 0;
    while (e && k < aq_cfg_nsections && strcmp(sec, aq_cfg_sections[k].name))
      k++;
    if (!e || k == aq_cfg_nsections) {
      char got[80], fmt[256];
      snprintf(got, sizeof got, "[%s]", e ? sec : "...");
      section_list(fmt, sizeof fmt, "expected ", ", got %s");
      fail(c, AQ_EFORMAT, "section", fmt, got);
      return NULL;
    }
    if (!strcmp(sec, "hinges") && !c->hinges_section)
      c->hinges_section = (int)c->line;
    if (!strcmp(sec, "fill") && !c->fill_section)
      c->fill_section = (int)c->line;
  }
  return str;
}

/* "0e 6i 12e 19i" -> hs (syntax only; the model checks range and order). */
static int parse_hinges(const char *v, aq_hinge_set *hs)
{
  const char *p = v;
  for (int k = 0; k < 4; k++) {
    while (*p == ' ' || *p == '\t')
      p++;
    if (*p < '0' || *p > '9')
      return 0;
    char *end;
    errno = 0;
    unsigned long j = strtoul(p, &end, 10);
    if (errno || j > 1000000 || (*end != 'e' && *end != 'i'))
      return 0;
    hs->joint[k] = (size_t)j;
    hs->face[k] = *end;
    p = end + 1;
    if (*p && *p != ' ' && *p != '\t')
      return 0;
  }
  while (*p == ' ' || *p == '\t')
    p++;
  return *p == '\0';
}

/* A value as quoted in a message, into buf[n]: whole when it fits, else
 * "..." and its end (a file's name whole: aq_path_fit). */
static void quoted(char *buf, size_t n, const char *value)
{
  char v[256];
  size_t room = n > 3 ? n - 3 : 1;
  snprintf(buf, n, "\"%s\"", aq_path_fit(value, room < sizeof v ? room : sizeof v - 1, v,
                                          sizeof v));
}

/* A line of [masses]: NAME = VOUSSOIR X_M Y_M MASS_KG. */
static int mass_key(parse_ctx *c, const char *name, const char *value)
{
  char got[160];
  quoted(got, sizeof got, value);
  for (size_t i = 0; i < c->nmass; i++)
    if (!strcmp(c->mass[i].m.name, name)) {
      char g2[64];
      snprintf(g2, sizeof g2, "a second one (first on line %ld)", c->mass[i].line);
      return fail(c, AQ_EFORMAT, name, "expected one value per key, got %s", g2);
    }
  if (strlen(name) >= sizeof c->mass[0].m.name)
    return fail(c, AQ_EVALUE, "masses", "expected a mass name of 1..63 characters, got %s",
                got);
  if (c->nmass >= MAX_MASSES)
    return fail(c, AQ_EVALUE, name, "expected at most 1000 point masses, got %s", got);
  mass_line ml;
  memset(&ml, 0, sizeof ml);
  snprintf(ml.m.name, sizeof ml.m.name, "%s", name);
  ml.line = c->line;
  char *end;
  errno = 0;
  long k = strtol(value, &end, 10);
  int ok = end != value && !errno && k >= 0 && (*end == ' ' || *end == '\t');
  char rest[200];
  double v[3];
  int used = 0;
  if (ok) {
    snprintf(rest, sizeof rest, "%s", end);
    ok = sscanf(rest, "%lf %lf %lf %n", &v[0], &v[1], &v[2], &used) == 3 &&
         rest[used] == '\0' && fabs(v[0]) <= AQ_CFG_COORD_MAX_M &&
         fabs(v[1]) <= AQ_CFG_COORD_MAX_M && aq_cfg_in_range(&aq_cfg_keys[AQ_CFG_MASS_LINE], v[2]);
  }
  if (!ok) {
    char range[64], fmt[300];
    aq_cfg_range_text(&aq_cfg_keys[AQ_CFG_MASS_LINE], range, sizeof range);
    snprintf(fmt, sizeof fmt, "expected VOUSSOIR X_M Y_M MASS_KG (a voussoir number, the "
             "position in m, each within +-%g m, and a mass in %s, e.g. 10 0.0 6.2 450), "
             "got %%s", AQ_CFG_COORD_MAX_M, range);
    return fail(c, AQ_EVALUE, name, fmt, got);
  }
  ml.m.voussoir = (size_t)k;
  ml.m.p.x = v[0];
  ml.m.p.y = v[1];
  ml.m.mass_kg = v[2];
  mass_line *grown = realloc(c->mass, (c->nmass + 1) * sizeof *grown);
  if (!grown)
    return fail(c, AQ_ENOMEM, name, "out of memory%s", "");
  c->mass = grown;
  c->mass[c->nmass++] = ml;
  return 1;
}

/* The value of key k checked by the table's rule for its kind (cfg_keys.h):
 * a number or an integer into c->num[k], a choice's index into c->num[k];
 * 0 and the line that refuses it otherwise.  What the key sets beyond
 * c->num is the handler's. */
static int checked_value(parse_ctx *c, int k, const char *name, const char *value)
{
  const aq_cfg_key *key = &aq_cfg_keys[k];
  char got[160], range[64], fmt[400];
  quoted(got, sizeof got, value);
  aq_cfg_range_text(key, range, sizeof range);
  double x = 0;
  switch (key->kind) {
  case AQ_CFG_REAL:
    if (aq_infile_number(value, &x) && aq_cfg_in_range(key, x))
      break;
    snprintf(fmt, sizeof fmt, "expected %s in %s, got %%s", key->what, range);
    return fail(c, AQ_EVALUE, name, fmt, got);
  case AQ_CFG_INT: {
    char *end;
    errno = 0;
    long v = strtol(value, &end, 10);
    x = (double)v;
    if (end != value && !*end && !errno && aq_cfg_in_range(key, x))
      break;
    snprintf(fmt, sizeof fmt, "expected %s in %s, got %%s", key->what, range);
    return fail(c, AQ_EVALUE, name, fmt, got);
  }
  case AQ_CFG_CHOICE: {
    size_t n = 0;
    while (key->choices[n] && strcmp(value, key->choices[n]))
      n++;
    if (key->choices[n]) {
      x = (double)n;
      break;
    }
    size_t len = (size_t)snprintf(fmt, sizeof fmt, "expected ");
    for (size_t i = 0; key->choices[i] && len < sizeof fmt; i++)
      len += (size_t)snprintf(fmt + len, sizeof fmt - len, "%s%s",
                              i == 0 ? "" : key->choices[i + 1] ? ", " : " or ",
                              key->choices[i]);
    if (len < sizeof fmt)
      snprintf(fmt + len, sizeof fmt - len, ", got %%s");
    return fail(c, AQ_EVALUE, name, fmt, got);
  }
  default:
    break;
  }
  c->num[k] = x;
  return 1;
}

int aq_cfg_handler(void *user, const char *section, const char *name,
                   const char *value)
{
  parse_ctx *c = user;
  if (c->failed)
    return 0;
  if (!strcmp(section, "masses"))
    return mass_key(c, name, value);
  int k;
  for (k = 0; k < AQ_CFG_NKEYS; k++)
    if (!strcmp(aq_cfg_keys[k].section, section) && !strcmp(aq_cfg_keys[k].name, name))
      break;
  if (k == AQ_CFG_NKEYS) {
    char got[128];
    quoted(got, sizeof got, name);
    if (!section[0]) {
      char fmt[256];
      section_list(fmt, sizeof fmt, "expected a key inside ", ", got %s before any section");
      return fail(c, AQ_EFORMAT, name, fmt, got);
    }
    char expect[512];
    expect[0] = '\0';
    for (int i = 0; i < AQ_CFG_NKEYS; i++)
      if (!strcmp(aq_cfg_keys[i].section, section))
        snprintf(expect + strlen(expect), sizeof expect - strlen(expect), "%s%s",
                 expect[0] ? ", " : "", aq_cfg_keys[i].name);
    char fmt[700];
    snprintf(fmt, sizeof fmt, "expected a key of [%s] (%s), got %%s", section, expect);
    return fail(c, AQ_EFORMAT, name, fmt, got);
  }
  if (c->key_line[k]) {
    char got[64];
    snprintf(got, sizeof got, "a second one (first on line %ld)", c->key_line[k]);
    return fail(c, AQ_EFORMAT, name, "expected one value per key, got %s", got);
  }
  c->key_line[k] = c->line;
  if (!checked_value(c, k, name, value))
    return 0;
  char got[160];
  quoted(got, sizeof got, value);
  switch (k) {
  case AQ_CFG_NAME:
    if (!value[0] || strlen(value) >= sizeof c->name || strpbrk(value, "\t\r\n"))
      return fail(c, AQ_EVALUE, name, "expected a name of 1..63 characters without tabs, got %s", got);
    snprintf(c->name, sizeof c->name, "%s", value);
    return 1;
  case AQ_CFG_SHAPE:
    c->shape = (int)c->num[k];
    return 1;
  case AQ_CFG_JOINTS_FILE:
  case AQ_CFG_FACES_FILE:
    if (!value[0] || strlen(value) >= sizeof c->path[0])
      return fail(c, AQ_EVALUE, name, "expected a file name of 1..199 characters, got %s",
                  got);
    snprintf(c->path[k - AQ_CFG_JOINTS_FILE], sizeof c->path[0], "%s", value);
    return 1;
  case AQ_CFG_PRIMARY:
  case AQ_CFG_REVERSE:
    if (!parse_hinges(value, &c->hs[k - AQ_CFG_PRIMARY]))
      return fail(c, AQ_EVALUE, name,
                  "expected four hinges JOINT FACE with FACE e or i (e.g. 0e 6i 12e 19i), got %s",
                  got);
    return 1;
  case AQ_CFG_IMPACT:
    c->impact = (int)c->num[k]; /* aq_impact, in the table's order */
    return 1;
  case AQ_CFG_CONTROL:
    c->control = (int)c->num[k]; /* aq_hinge_control, in the table's order */
    return 1;
  default:
    return 1; /* a number, kept in c->num[k] */
  }
}
