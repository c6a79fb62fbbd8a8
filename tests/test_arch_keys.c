/* test_arch_keys.c: the arch file's keys as documented, as parsed and as
 * printed.
 *   - docs/arch-file.md's table of keys names every key of the parser's
 *     table (src/arch/cfg_keys.c) and no other, each number's range as the
 *     parser states it; and the parser holds to the documented range: a
 *     value at a closed bound passes the range rule, one at an open bound
 *     or just beyond a bound is refused in one line naming the file, the
 *     key's line, the key and the range (probed from the documented
 *     numbers, not from the table);
 *   - each choice key takes every documented word and refuses another;
 *   - point masses and the joints and faces files hold to the documented
 *     coordinate and mass bounds;
 *   - `archquake help arch-file` names every section, key, range and shape,
 *     and the manual page has it as ARCH FILE, with ENVIRONMENT, FILES and
 *     SEE ALSO;
 *   - every environment variable the sources read (getenv) is in the
 *     Environment table of --help, but the test hooks named here. */
#include <dirent.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/opt_table.h"
#include "arch/arch.h"
#include "arch/cfg_keys.h"
#include "check.h"

#define OUT_CAP (1 << 18)

/* A documented row: its section, key, unit and range cells (backticks
 * dropped). */
typedef struct {
  char section[32], key[64], range[160];
} doc_row;

static void strip_ticks(const char *in, size_t len, char *out, size_t n)
{
  size_t k = 0;
  while (len > 0 && (*in == ' ')) /* leading blanks */
    in++, len--;
  while (len > 0 && in[len - 1] == ' ')
    len--;
  for (size_t i = 0; i < len && k + 1 < n; i++)
    if (in[i] != '`')
      out[k++] = in[i];
  out[k] = '\0';
}

/* The rows of docs/arch-file.md's table of keys (| section | key | unit |
 * range | default | meaning |), a cell of several keys ("`a`, `b`") one row
 * each. */
static size_t doc_rows(doc_row *rows, size_t cap)
{
  char *md = aq_test_read_file("docs/arch-file.md", NULL);
  size_t n = 0;
  if (!aq_check(md != NULL, "docs/arch-file.md"))
    return 0;
  const char *t = strstr(md, "| section | key | unit | range | default | meaning |");
  if (!aq_check(t != NULL, "docs/arch-file.md has the table of keys"))
    goto done;
  t = strchr(t, '\n') + 1;
  t = strchr(t, '\n') + 1; /* |---| */
  while (*t == '|' && n < cap) {
    const char *cell[7];
    int c = 0;
    for (const char *p = t; *p && *p != '\n' && c < 7; p++)
      if (*p == '|')
        cell[c++] = p + 1;
    if (c < 7)
      break;
    char keys[160];
    doc_row r;
    strip_ticks(cell[0], (size_t)(cell[1] - cell[0] - 1), r.section, sizeof r.section);
    strip_ticks(cell[1], (size_t)(cell[2] - cell[1] - 1), keys, sizeof keys);
    strip_ticks(cell[3], (size_t)(cell[4] - cell[3] - 1), r.range, sizeof r.range);
    /* "[arch]" -> "arch" */
    memmove(r.section, r.section + 1, strlen(r.section));
    r.section[strcspn(r.section, "]")] = '\0';
    for (char *k = strtok(keys, ", "); k && n < cap; k = strtok(NULL, ", ")) {
      rows[n] = r;
      snprintf(rows[n].key, sizeof rows[n].key, "%s", k);
      n++;
    }
    t = strchr(t, '\n');
    if (!t)
      break;
    t++;
  }
done:
  free(md);
  return n;
}

/* A documented numeric range "[0.001, 1000] m", "(0, 180] deg" or
 * "4..1000": 1 and its bounds. */
static int parse_range(const char *s, double *lo, double *hi, int *lo_open, int *hi_open)
{
  char a, b;
  long l, h;
  int used = 0;
  if (sscanf(s, "%ld..%ld%n", &l, &h, &used) == 2 && s[used] == '\0') {
    *lo = (double)l;
    *hi = (double)h;
    *lo_open = *hi_open = 0;
    return 1;
  }
  if (sscanf(s, "%c%lf, %lf%c", &a, lo, hi, &b) == 4 && (a == '[' || a == '(') &&
      (b == ']' || b == ')')) {
    *lo_open = a == '(';
    *hi_open = b == ')';
    return 1;
  }
  return 0;
}

/* An arch file that loads, of the shape and sections key k needs, with k
 * on line 3 set to value (its text). */
static void probe_file(const aq_cfg_key *k, const char *value, char *buf, size_t n)
{
  const char *circ = "radius_m = 5\nembrace_deg = 180\nthickness_m = 0.6\nvoussoirs = 24\n"
                     "density_kg_m3 = 2000\ndepth_m = 1\n";
  const char *par = "shape = parabolic\nspan_m = 10\nrise_m = 4\nthickness_m = 0.6\n"
                    "voussoirs = 24\ndensity_kg_m3 = 2000\ndepth_m = 1\n";
  int curve = !strcmp(k->name, "span_m") || !strcmp(k->name, "rise_m");
  const char *geom = curve ? par : circ;
  /* the base without k's own line */
  char base[512] = "";
  for (const char *p = geom; *p;) {
    size_t len = strcspn(p, "\n") + 1;
    if (strncmp(p, k->name, strlen(k->name)) || p[strlen(k->name)] != ' ' ||
        strcmp(k->section, "arch"))
      strncat(base, p, len);
    p += len;
  }
  if (!strcmp(k->section, "arch"))
    snprintf(buf, n, "[arch]\n%s = %s\n%s", k->name, value, base);
  else if (!strcmp(k->section, "fill"))
    snprintf(buf, n, "[fill]\n%s = %s\n%s = %s\n[arch]\n%s", k->name, value,
             !strcmp(k->name, "level_m") ? "density_kg_m3" : "level_m",
             !strcmp(k->name, "level_m") ? "1800" : "6", base);
  else
    snprintf(buf, n, "[%s]\n%s = %s\n[arch]\n%s", k->section, k->name, value, base);
}

/* Load text; 1 if it was refused on line 2 (the key's) by key's range rule:
 * "KEY: expected WHAT in RANGE". */
static int refused_by_range(const aq_cfg_key *k, const char *text, const char *range,
                            char *why, size_t n)
{
  aq_arch *a = NULL;
  aq_error e;
  aq_error_clear(&e);
  aq_status st = aq_arch_load_string(text, strlen(text), "probe.cfg", &a, &e);
  aq_arch_free(a);
  snprintf(why, n, "%s", st == AQ_OK ? "loaded" : e.message);
  if (st == AQ_OK)
    return 0;
  char want[256];
  snprintf(want, sizeof want, "expected %s in %s, got", k->what, range);
  return e.line == 2 && !strcmp(e.field, k->name) && !strncmp(e.message, want, strlen(want));
}

AQ_TEST(arch_keys_ranges_as_documented)
{
  gsl_set_error_handler_off(); /* as archquake's main does: GSL's default aborts */
  doc_row rows[64];
  size_t nrows = doc_rows(rows, 64);
  aq_check(nrows >= 20, "docs/arch-file.md: %zu rows of keys", nrows);
  /* both ways: every key documented, every documented key a key */
  for (size_t i = 0; i < nrows; i++) {
    int found = 0;
    for (int k = 0; k < AQ_CFG_NKEYS; k++)
      found |= !strcmp(aq_cfg_keys[k].section, rows[i].section) &&
               !strcmp(aq_cfg_keys[k].name, rows[i].key);
    aq_check(found, "docs/arch-file.md documents [%s] %s, which the parser does not take",
             rows[i].section, rows[i].key);
  }
  char text[1024], why[512], v[64];
  for (int k = 0; k < AQ_CFG_NKEYS; k++) {
    const aq_cfg_key *key = &aq_cfg_keys[k];
    const doc_row *d = NULL;
    for (size_t i = 0; i < nrows; i++)
      if (!strcmp(key->section, rows[i].section) && !strcmp(key->name, rows[i].key))
        d = &rows[i];
    if (!aq_check(d != NULL, "docs/arch-file.md documents [%s] %s", key->section, key->name))
      continue;
    if (key->kind == AQ_CFG_CHOICE) {
      /* every documented word is taken; another is refused naming them */
      char words[160];
      snprintf(words, sizeof words, "%s", d->range);
      size_t nw = 0;
      for (char *w = strtok(words, ", "); w; w = strtok(NULL, ", ")) {
        probe_file(key, w, text, sizeof text);
        aq_arch *a = NULL;
        aq_error e;
        aq_error_clear(&e);
        aq_status st = aq_arch_load_string(text, strlen(text), "probe.cfg", &a, &e);
        aq_arch_free(a);
        aq_check(st == AQ_OK || strcmp(e.field, key->name), "%s = %s taken: %s", key->name,
                 w, e.message);
        nw++;
      }
      probe_file(key, "bogus", text, sizeof text);
      aq_arch *a = NULL;
      aq_error e;
      aq_error_clear(&e);
      aq_arch_load_string(text, strlen(text), "probe.cfg", &a, &e);
      aq_arch_free(a);
      aq_check(nw >= 2 && e.line == 2 && !strcmp(e.field, key->name) &&
                   strstr(e.message, "expected") && strstr(e.message, "\"bogus\""),
               "%s = bogus refused on its line: %s", key->name, e.message);
      continue;
    }
    if (key->kind != AQ_CFG_REAL && key->kind != AQ_CFG_INT)
      continue;
    char range[64];
    aq_cfg_range_text(key, range, sizeof range);
    aq_check(!strcmp(range, d->range), "%s: the parser's range %s, documented %s", key->name,
             range, d->range);
    double lo, hi;
    int lo_open = 0, hi_open = 0;
    if (!aq_check(parse_range(d->range, &lo, &hi, &lo_open, &hi_open),
                  "%s: a range in the docs: \"%s\"", key->name, d->range))
      continue;
    int integer = key->kind == AQ_CFG_INT;
    /* the bounds, then just beyond them */
    double at[4] = {lo, hi, integer ? lo - 1 : nextafter(lo, -INFINITY),
                    integer ? hi + 1 : nextafter(hi, INFINITY)};
    int refused[4] = {lo_open, hi_open, 1, 1};
    for (int i = 0; i < 4; i++) {
      snprintf(v, sizeof v, integer ? "%.0f" : "%.17g", at[i]);
      probe_file(key, v, text, sizeof text);
      int r = refused_by_range(key, text, d->range, why, sizeof why);
      aq_check(r == refused[i], "%s = %s: %s by its range (%s): %s", key->name, v,
               refused[i] ? "refused" : "not refused", d->range, why);
    }
    /* far beyond: the slips the range is for */
    snprintf(v, sizeof v, "%g", hi > 0 ? 1e200 : -1e200);
    probe_file(key, v, text, sizeof text);
    aq_check(refused_by_range(key, text, d->range, why, sizeof why), "%s = %s refused: %s",
             key->name, v, why);
  }
}

/* [masses] and the joints and faces files: the documented bounds. */
AQ_TEST(arch_keys_masses_and_joints_bounds)
{
  gsl_set_error_handler_off();
  static const char arch[] = "[arch]\nradius_m = 5\nembrace_deg = 180\nthickness_m = 0.6\n"
                             "voussoirs = 24\ndensity_kg_m3 = 2000\ndepth_m = 1\n[masses]\n";
  static const struct {
    const char *line;
    int refused;
  } cases[] = {
      {"m = 12 0 5.3 1e9", 0},         {"m = 12 0 5.3 1.0000000000000002e9", 1},
      {"m = 12 0 5.3 0", 1},           {"m = 12 0 5.3 -3", 1},
      {"m = 12 1000 5.3 450", 0},      {"m = 12 1000.0000000000001 5.3 450", 1},
      {"m = 12 0 -1000.0000000000001 450", 1}, {"m = 12 0 1e300 450", 1},
      {"m = 12 0 nan 450", 1},
  };
  char text[1024];
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(text, sizeof text, "%s%s\n", arch, cases[i].line);
    aq_arch *a = NULL;
    aq_error e;
    aq_error_clear(&e);
    aq_status st = aq_arch_load_string(text, strlen(text), "m.cfg", &a, &e);
    aq_arch_free(a);
    int by_rule = st != AQ_OK && e.line == 9 && !strcmp(e.field, "m") &&
                  strstr(e.message, "within +-1000 m, and a mass in (0, 1e9] kg");
    aq_check(by_rule == cases[i].refused, "%s: %s by the bounds: %s", cases[i].line,
             cases[i].refused ? "refused" : "not refused", st == AQ_OK ? "loaded" : e.message);
  }
  /* a joints file's coordinate beyond 1000 m, a joint shorter than 1 mm */
  char dir[512], path[700], cfg[900], out[4096], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const joints[] = {
      "joint,xi_m,yi_m,xe_m,ye_m\n0,4.5,0,5.5,0\n1,3.2,3.2,3.9,3.9\n2,0,4.5,0,5.5\n"
      "3,-3.2,3.2,-3.9,3.9\n4,-4.5,0,-1000.5,0\n",
      "joint,xi_m,yi_m,xe_m,ye_m\n0,4.5,0,5.5,0\n1,3.2,3.2,3.2005,3.2005\n2,0,4.5,0,5.5\n"
      "3,-3.2,3.2,-3.9,3.9\n4,-4.5,0,-5.5,0\n"};
  static const char *const want[] = {"j.csv:6: xe_m: expected a coordinate within +-1000 m",
                                     "j.csv:3: xe_m: expected a joint 0.001 to 1000 m long"};
  for (int i = 0; i < 2; i++) {
    snprintf(path, sizeof path, "%s/j.csv", dir);
    FILE *f = fopen(path, "w");
    fputs(joints[i], f);
    fclose(f);
    snprintf(path, sizeof path, "%s/j.cfg", dir);
    f = fopen(path, "w");
    fputs("[arch]\nshape = joints\njoints_file = j.csv\ndensity_kg_m3 = 2000\ndepth_m = 1\n",
          f);
    fclose(f);
    snprintf(cfg, sizeof cfg, "mechanism --arch %s", path);
    int rc = aq_test_run(cfg, out, sizeof out, err, sizeof err);
    aq_check(rc == 1 && strstr(err, want[i]) && aq_test_count_lines(err) == 1,
             "joints file %d: want \"%s\", got %d \"%s\"", i, want[i], rc, err);
  }
}

/* `archquake help arch-file` and the manual page. */
AQ_TEST(arch_keys_help_and_man)
{
  char *out = malloc(OUT_CAP), *page = NULL;
  if (!aq_check(out != NULL, "memory"))
    return;
  int rc = aq_test_run("help arch-file", out, OUT_CAP, NULL, 0);
  aq_check(rc == 0, "help arch-file: exit %d", rc);
  for (size_t s = 0; s < aq_cfg_nsections; s++) {
    char sec[64];
    snprintf(sec, sizeof sec, "\n[%s]  ", aq_cfg_sections[s].name);
    aq_check(strstr(out, sec) != NULL, "help arch-file shows [%s]", aq_cfg_sections[s].name);
  }
  for (int k = 0; k < AQ_CFG_NKEYS; k++) {
    const aq_cfg_key *key = &aq_cfg_keys[k];
    char lab[96], range[64];
    snprintf(lab, sizeof lab, "\n  %s = ", key->name);
    const char *at = strstr(out, lab);
    if (!aq_check(at != NULL, "help arch-file shows %s", key->name))
      continue;
    aq_cfg_range_text(key, range, sizeof range);
    /* the range within the key's entry (up to the next line that is not a
     * continuation), words wrapped: compared without line breaks */
    char entry[2048];
    size_t n = 0;
    for (const char *p = at + 1; *p && n + 1 < sizeof entry; p++) {
      if (*p == '\n' && strncmp(p + 1, "      ", 6))
        break;
      if (*p == '\n' || (*p == ' ' && n && entry[n - 1] == ' '))
        entry[n] = ' ', n += !(n && entry[n - 1] == ' ');
      else
        entry[n++] = *p;
    }
    entry[n] = '\0';
    aq_check(!range[0] || strstr(entry, range), "help arch-file: %s with its range %s: %s",
             key->name, range, entry);
    aq_check(!key->deflt || strstr(entry, "default:"), "help arch-file: %s with its default",
             key->name);
  }
  for (size_t s = 0; s < aq_cfg_nshapes; s++) {
    char sh[64];
    snprintf(sh, sizeof sh, "\n  %s ", aq_cfg_shape_names[s]);
    aq_check(strstr(out, sh) != NULL, "help arch-file: shape %s", aq_cfg_shape_names[s]);
  }
  aq_check(strstr(out, aq_cfg_joints_header) && strstr(out, aq_cfg_faces_header),
           "help arch-file: the joints and faces files' headers");
  /* the man page */
  char dir[512], cmd[1200], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/archquake.1", dir);
  snprintf(cmd, sizeof cmd, "sh tools/man.sh %s > %s", aq_test_bin(), path);
  rc = system(cmd);
  page = aq_test_read_file(path, NULL);
  if (aq_check(rc == 0 && page, "tools/man.sh: exit %d", rc)) {
    static const char *const sections[] = {".SH \"ARCH FILE\"\n", ".SH ENVIRONMENT\n",
                                           ".SH FILES\n", ".SH \"SEE ALSO\"\n"};
    for (int s = 0; s < 4; s++)
      aq_check(strstr(page, sections[s]) != NULL, "the man page has %s", sections[s]);
    const char *arch = strstr(page, ".SH \"ARCH FILE\"");
    for (int k = 0; arch && k < AQ_CFG_NKEYS; k++) { /* roff: '-' as \- */
      char roff[96] = "", *r = roff;
      for (const char *p = aq_cfg_keys[k].name; *p; p++)
        r += *p == '-' ? sprintf(r, "\\-") : sprintf(r, "%c", *p);
      char lab[128];
      snprintf(lab, sizeof lab, "\n  %s = ", roff);
      aq_check(strstr(arch, lab) != NULL, "the man page's ARCH FILE has %s",
               aq_cfg_keys[k].name);
    }
    const char *env = strstr(page, ".SH ENVIRONMENT");
    for (const aq_opt_note *e = aq_opt_environment; env && e->name; e++) {
      char lab[96];
      snprintf(lab, sizeof lab, "\n  %s ", e->name);
      aq_check(strstr(env, lab) != NULL, "the man page's ENVIRONMENT has %s", e->name);
    }
  }
  free(page);
  free(out);
}

/* The getenv("NAME") calls of the .c files under dir into names[]. */
static void getenv_names(const char *dir, char names[][64], size_t *n, size_t cap)
{
  DIR *d = opendir(dir);
  if (!d)
    return;
  struct dirent *de;
  while ((de = readdir(d))) {
    char path[1024];
    if (de->d_name[0] == '.')
      continue;
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    size_t len = strlen(de->d_name);
    if (len > 2 && !strcmp(de->d_name + len - 2, ".c")) {
      char *src = aq_test_read_file(path, NULL);
      for (const char *p = src; p && (p = strstr(p, "getenv(\"")); p++) {
        const char *q = p + 8;
        size_t l = strcspn(q, "\"");
        if (l > 0 && l < 64 && *n < cap)
          snprintf(names[(*n)++], 64, "%.*s", (int)l, q);
      }
      free(src);
    } else if (!strchr(de->d_name, '.')) {
      getenv_names(path, names, n, cap);
    }
  }
  closedir(d);
}

AQ_TEST(arch_keys_environment_documented)
{
  /* hooks for tests and debugging, not for users */
  static const char *const hooks[] = {"AQ_FFTW_NO_BUILTIN_WISDOM", "AQ_MPI_DEBUG_FIRST_TASK"};
  char names[64][64];
  size_t n = 0;
  getenv_names("src", names, &n, 64);
  aq_check(n >= 4, "getenv in src: %zu", n);
  for (size_t i = 0; i < n; i++) {
    int ok = 0;
    for (const aq_opt_note *e = aq_opt_environment; e->name; e++)
      ok |= !strcmp(e->name, names[i]);
    for (size_t h = 0; h < sizeof hooks / sizeof hooks[0]; h++)
      ok |= !strcmp(hooks[h], names[i]);
    aq_check(ok, "%s is read (getenv) but not in --help's Environment", names[i]);
  }
}
