/* cfg_load.c: an arch file read (from disk, a store or a string) with
 * cfg.c's handler, what the keys cannot say checked once all are read,
 * and the arch built (aq_arch_build; docs/arch-file.md). */
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
  int rc = ini_parse_stream(aq_cfg_reader, &c, aq_cfg_handler, &c);
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
