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
 * line of its key.
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

#define MAX_LINE_CHARS 190    /* libinih's line buffer is 200 bytes */
#define MAX_MASSES 1000       /* point masses in [masses] */
#define MAX_FILE_BYTES 1000000
#define PATH_BYTES 4096       /* a joints or faces file's path beside the .cfg */

typedef struct {
  aq_point_mass m;
  long line;
} mass_line;

typedef struct {
  const char *file;
  const char *text; /* cursor */
  long line;        /* lines read so far */
  long key_line[AQ_CFG_NKEYS];
  int hinges_section; /* line of [hinges], 0 if absent */
  int fill_section;   /* line of [fill], 0 if absent */
  aq_error *err;
  int failed;
  char name[64];
  int shape;
  char path[2][200];  /* joints_file, faces_file as given */
  double num[AQ_CFG_NKEYS];
  aq_hinge_set hs[2];
  int impact;
  int control; /* aq_hinge_control */
  mass_line *mass;
  size_t nmass;
} parse_ctx;

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

static char *reader(char *str, int num, void *stream)
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

static int handler(void *user, const char *section, const char *name,
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

static aq_status load_string(const char *data, size_t len, const char *path,
                             const aq_arch_options *opt, const aq_arch_store *store, int *hit,
                             aq_arch **out, aq_error *err);

aq_status aq_arch_load_stored(const char *path, const aq_arch_store *store, int *hit,
                              aq_arch **out, aq_error *err)
{
  return aq_arch_load_stored_opts(path, NULL, store, hit, out, err);
}

aq_status aq_arch_load_opts(const char *path, const aq_arch_options *opt, aq_arch **out,
                            aq_error *err)
{
  return aq_arch_load_stored_opts(path, opt, NULL, NULL, out, err);
}

aq_status aq_arch_load_stored_opts(const char *path, const aq_arch_options *opt,
                                   const aq_arch_store *store, int *hit, aq_arch **out,
                                   aq_error *err)
{
  *out = NULL;
  if (hit)
    *hit = 0;
  aq_status st = AQ_OK;
  size_t len = 0;
  char *buf = aq_infile_read(path, MAX_FILE_BYTES, "arch file", &len, &st, err);
  if (!buf)
    return st;
  st = load_string(buf, len, path, opt, store, hit, out, err);
  free(buf);
  return st;
}

aq_status aq_arch_load(const char *path, aq_arch **out, aq_error *err)
{
  return aq_arch_load_stored_opts(path, NULL, NULL, NULL, out, err);
}

/* The checks that need the whole file: the keys the shape takes and
 * needs, [fill] and [hinges] complete; then a joints arch's files, read
 * from beside the .cfg (joints.c names their own lines). */
static aq_status after_parse(parse_ctx *c, const char *path, aq_joints *J, aq_error *err)
{
  unsigned bit = 1u << c->shape;
  const char *shape = aq_shape_names[c->shape];
  for (int k = 0; k < AQ_CFG_NKEYS; k++)
    if (c->key_line[k] && !(aq_cfg_keys[k].shapes & bit)) {
      char takes[256] = "";
      for (int i = 0; i < AQ_CFG_NKEYS; i++)
        if (!strcmp(aq_cfg_keys[i].section, "arch") && (aq_cfg_keys[i].shapes & bit) && i != AQ_CFG_NAME &&
            i != AQ_CFG_SHAPE)
          snprintf(takes + strlen(takes), sizeof takes - strlen(takes), "%s%s",
                   takes[0] ? ", " : "", aq_cfg_keys[i].name);
      return aq_error_set(err, AQ_EFORMAT, path, c->key_line[k], -1, aq_cfg_keys[k].name,
                          "expected no %s with shape = %s (it takes %s), got one",
                          aq_cfg_keys[k].name, shape, takes);
    }
  for (int k = 0; k < AQ_CFG_NKEYS; k++)
    if ((aq_cfg_keys[k].required & bit) && !c->key_line[k]) {
      if (c->shape == AQ_SHAPE_CIRCULAR)
        return aq_error_set(err, AQ_EFORMAT, path, -1, -1, aq_cfg_keys[k].name,
                            "expected a value in [%s], got none", aq_cfg_keys[k].section);
      return aq_error_set(err, AQ_EFORMAT, path, -1, -1, aq_cfg_keys[k].name,
                          "expected a value in [%s] for shape = %s, got none", aq_cfg_keys[k].section,
                          shape);
    }
  if (c->fill_section && (!c->key_line[AQ_CFG_FILL_LEVEL] || !c->key_line[AQ_CFG_FILL_DENSITY]))
    return aq_error_set(err, AQ_EFORMAT, path, c->fill_section, -1,
                        c->key_line[AQ_CFG_FILL_LEVEL] ? "density_kg_m3" : "level_m",
                        "expected level_m and density_kg_m3 in [fill], got no %s",
                        c->key_line[AQ_CFG_FILL_LEVEL] ? "density_kg_m3" : "level_m");
  if (c->key_line[AQ_CFG_REVERSE] && !c->key_line[AQ_CFG_PRIMARY])
    return aq_error_set(err, AQ_EFORMAT, path, c->key_line[AQ_CFG_REVERSE], -1, "primary",
                        "expected a primary hinge set in [hinges] with the reverse, got none");
  if (c->hinges_section && !c->key_line[AQ_CFG_PRIMARY] && !c->key_line[AQ_CFG_CONTROL])
    return aq_error_set(err, AQ_EFORMAT, path, c->hinges_section, -1, "primary",
                        "expected a primary hinge set or a control in [hinges], got neither");
  /* control: fixed by default when the file names the primary, free when
   * the search finds it */
  if (!c->key_line[AQ_CFG_CONTROL])
    c->control = c->key_line[AQ_CFG_PRIMARY] ? AQ_CONTROL_FIXED : AQ_CONTROL_FREE;
  if (c->control == AQ_CONTROL_FREE && c->key_line[AQ_CFG_REVERSE])
    return aq_error_set(err, AQ_EVALUE, path, c->key_line[AQ_CFG_REVERSE], -1, "reverse",
                        "expected no reverse with control = free (line %ld: each direction's "
                        "set is its own minimum mechanism), got one",
                        c->key_line[AQ_CFG_CONTROL]);
  if (c->shape != AQ_SHAPE_JOINTS)
    return AQ_OK;
  /* joints_file and faces_file: relative to the .cfg's directory */
  char full[2][PATH_BYTES];
  const char *slash = strrchr(path, '/');
  for (int f = 0; f < 2; f++) {
    if (!c->path[f][0])
      continue;
    int w = c->path[f][0] == '/' || !slash
                ? snprintf(full[f], sizeof full[f], "%s", c->path[f])
                : snprintf(full[f], sizeof full[f], "%.*s/%s", (int)(slash - path), path,
                           c->path[f]);
    if (w < 0 || (size_t)w >= sizeof full[f])
      return aq_error_set(err, AQ_EVALUE, path, c->key_line[AQ_CFG_JOINTS_FILE + f], -1,
                          aq_cfg_keys[AQ_CFG_JOINTS_FILE + f].name, "expected a path of at most %d bytes, got "
                          "a longer one", PATH_BYTES - 1);
  }
  aq_status st = aq_joints_read(full[0], c->path[1][0] ? full[1] : NULL, J, err);
  if (st == AQ_EIO && err) { /* a file that cannot be read: said on its key's line */
    int f = !strcmp(err->input, full[0]) ? 0 : 1;
    char why[sizeof err->message], shown[301];
    snprintf(why, sizeof why, "%s", err->message);
    const char *r = strstr(why, "got ");
    aq_error_set(err, AQ_EIO, path, c->key_line[AQ_CFG_JOINTS_FILE + f], -1, aq_cfg_keys[AQ_CFG_JOINTS_FILE + f].name,
                 "expected a readable file, got \"%s\": %.200s",
                 aq_path_fit(full[f], 300, shown, sizeof shown), r ? r + 4 : why);
  }
  return st;
}

/* aq_arch_build_kept through store (NULL: aq_arch_build): the bytes kept
 * for src taken, or the arch's bytes put once built; *hit 1 when taken. */
static aq_status build_stored(const aq_arch_params *p, const aq_hinge_set *primary,
                              const aq_hinge_set *reverse, const aq_arch_dynamics *dyn,
                              const char *name, const aq_arch_sources *src,
                              const aq_arch_store *store, int *hit, aq_arch **out,
                              aq_error *err)
{
  const unsigned char *kept = NULL;
  size_t nkept = 0;
  void *handle = NULL;
  int got = store && store->get(store->ctx, src, &kept, &nkept, &handle);
  aq_status st = aq_arch_build_kept(p, primary, reverse, dyn, name, got ? kept : NULL, nkept,
                                    hit, out, err);
  if (got)
    store->release(store->ctx, handle);
  if (st == AQ_OK && store && !*hit) {
    aq_bytes_out b = {0};
    aq_arch_tables_put(*out, &b);
    if (!b.oom)
      store->put(store->ctx, src, b.data, b.n);
    free(b.data);
  }
  return st;
}

/* The arch from the parsed file (its sources src, through store). */
static aq_status build_parsed(parse_ctx *c, const char *path, const aq_joints *J,
                              const aq_arch_sources *src, const aq_arch_store *store, int *hit,
                              aq_arch **out, aq_error *err)
{
  aq_arch_params p;
  memset(&p, 0, sizeof p);
  p.radius_m = c->num[AQ_CFG_RADIUS];
  p.thickness_m = c->num[AQ_CFG_THICKNESS];
  p.embrace_rad = c->num[AQ_CFG_EMBRACE] * AQ_DEG_RAD;
  p.voussoirs = c->shape == AQ_SHAPE_JOINTS ? J->n : (size_t)c->num[AQ_CFG_VOUSSOIRS];
  p.density_kg_m3 = c->num[AQ_CFG_DENSITY];
  p.depth_m = c->num[AQ_CFG_DEPTH];
  p.shape = (aq_shape)c->shape;
  p.span_m = c->num[AQ_CFG_SPAN];
  p.rise_m = c->num[AQ_CFG_RISE];
  if (c->shape == AQ_SHAPE_JOINTS) {
    p.joint_i = J->ji;
    p.joint_e = J->je;
    for (int f = 0; f < 2; f++) {
      p.face_pt[f] = J->face_pt[f];
      p.face_start[f] = J->face_start[f];
    }
  }
  if (c->fill_section) {
    p.fill_level_m = c->num[AQ_CFG_FILL_LEVEL];
    p.fill_density_kg_m3 = c->num[AQ_CFG_FILL_DENSITY];
  }
  p.control = (aq_hinge_control)c->control;
  p.friction = src->friction > 0 ? src->friction : c->num[AQ_CFG_FRICTION]; /* 0: none */
  p.friction_table = src->friction_table;
  p.e_n = c->num[AQ_CFG_EN];
  p.spread_m = c->num[AQ_CFG_SPREAD];
  p.abutment_m = c->num[AQ_CFG_ABUTMENT];
  aq_point_mass *pm = c->nmass ? malloc(c->nmass * sizeof *pm) : NULL;
  if (c->nmass && !pm)
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  for (size_t i = 0; i < c->nmass; i++)
    pm[i] = c->mass[i].m;
  p.nmass = c->nmass;
  p.mass = pm;
  aq_arch_dynamics dyn = {c->num[AQ_CFG_COR], (aq_impact)c->impact, c->num[AQ_CFG_G]};
  char name[64];
  if (c->name[0]) {
    snprintf(name, sizeof name, "%s", c->name);
  } else {
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t len = strlen(b);
    if (len > 4 && !strcmp(b + len - 4, ".cfg"))
      len -= 4;
    snprintf(name, sizeof name, "%.*s", (int)(len < 63 ? len : 63), b);
  }
  aq_status st = build_stored(&p, c->key_line[AQ_CFG_PRIMARY] ? &c->hs[0] : NULL,
                              c->key_line[AQ_CFG_REVERSE] ? &c->hs[1] : NULL, &dyn, name, src, store,
                              hit, out, err);
  free(pm);
  if (st != AQ_OK && err) {
    /* name the file and the line of the key the model complained about */
    long line = -1;
    for (int k = AQ_CFG_NKEYS; k-- > 0;)
      if (!strcmp(err->field, aq_cfg_keys[k].name) && c->key_line[k])
        line = c->key_line[k];
    for (size_t i = 0; i < c->nmass; i++)
      if (!strcmp(err->field, c->mass[i].m.name))
        line = c->mass[i].line;
    if (!strcmp(err->field, "reverse") && !c->key_line[AQ_CFG_REVERSE])
      line = c->key_line[AQ_CFG_PRIMARY];
    if (!strcmp(err->field, "hinges") && !c->key_line[AQ_CFG_PRIMARY])
      line = -1;
    snprintf(err->input, sizeof err->input, "%s", path);
    err->line = line > 0 ? line : -1;
  }
  return st;
}

aq_status aq_arch_load_string(const char *data, size_t len, const char *path,
                              aq_arch **out, aq_error *err)
{
  return load_string(data, len, path, NULL, NULL, NULL, out, err);
}

aq_status aq_arch_load_string_opts(const char *data, size_t len, const char *path,
                                   const aq_arch_options *opt, aq_arch **out, aq_error *err)
{
  return load_string(data, len, path, opt, NULL, NULL, out, err);
}

static aq_status load_string(const char *data, size_t len, const char *path,
                             const aq_arch_options *opt, const aq_arch_store *store, int *hit,
                             aq_arch **out, aq_error *err)
{
  int hit_ = 0;
  *out = NULL;
  if (hit)
    *hit = 0;
  aq_status st = AQ_OK;
  if (len > MAX_FILE_BYTES)
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                        "expected an arch file of at most 1 MB, got more");
  if (len && memchr(data, '\0', len))
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL,
                        "expected a text arch file, got a NUL byte");
  char *text = malloc(len + 1);
  if (!text)
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  if (len)
    memcpy(text, data, len);
  text[len] = '\0';
  parse_ctx c;
  memset(&c, 0, sizeof c);
  c.file = path;
  c.text = text;
  c.err = err;
  c.num[AQ_CFG_G] = AQ_G0_MPS2;
  int rc = ini_parse_stream(reader, &c, handler, &c);
  if (!c.failed && rc > 0) {
    /* a line libinih could not parse: show it */
    const char *p = text;
    for (int l = 1; l < rc && p; l++) {
      p = strchr(p, '\n');
      p = p ? p + 1 : NULL;
    }
    char got[120];
    size_t len = p ? strcspn(p, "\r\n") : 0;
    snprintf(got, sizeof got, "\"%.*s\"", (int)(len < 100 ? len : 100), p ? p : "");
    aq_error_set(err, AQ_EFORMAT, path, rc, -1, NULL,
                 "expected KEY = VALUE, [section] or a comment, got %s", got);
    free(text);
    return AQ_EFORMAT;
  }
  if (c.failed || rc < 0) {
    free(text);
    if (!c.failed)
      return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    return err ? err->status : AQ_EFORMAT;
  }
  aq_arch *a = NULL;
  aq_joints J;
  memset(&J, 0, sizeof J);
  st = after_parse(&c, path, &J, err);
  double friction = opt && opt->friction > 0 && isfinite(opt->friction) ? opt->friction : 0;
  aq_arch_sources src = {text, len, {J.bytes[0], J.bytes[1]}, {J.nbytes[0], J.nbytes[1]},
                         friction, opt ? opt->friction_table : 0};
  if (st == AQ_OK)
    st = build_parsed(&c, path, &J, &src, store, &hit_, &a, err);
  free(c.mass);
  if (st != AQ_OK) {
    aq_joints_free(&J);
    free(text);
    return st;
  }
  aq_arch_keep_sources(a, text, J.bytes, J.nbytes); /* the joints arch's files: its digest */
  J.bytes[0] = J.bytes[1] = NULL;
  aq_joints_free(&J);
  if (hit)
    *hit = hit_;
  *out = a;
  return AQ_OK;
}
