/* test_error_long_paths.c: texts of a fixed size never cut a path unseen.
 * aq_path_fit and aq_text_fit (src/error.c) against texts built here; then
 * the notes and warnings that name files, with names and paths longer than
 * their old fixed rooms: the vertical left out of a motion (its 300-byte
 * warning), a StationXML's name in the polarity note (cut at 40 bytes),
 * a joints file's path in the arch file's message (cut at 300), the other
 * component's path in a pair's refusal. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "error.h"

static int ends_with(const char *s, const char *t)
{
  size_t a = strlen(s), b = strlen(t);
  return a >= b && strcmp(s + a - b, t) == 0;
}

/* n copies of c, then tail, into buf. */
static char *repeat(char *buf, char c, size_t n, const char *tail)
{
  memset(buf, c, n);
  strcpy(buf + n, tail);
  return buf;
}

AQ_TEST(error_path_fit)
{
  char path[1400], name[300], dirs[1000], buf[600];
  repeat(name, 'n', 250, ".AT2");          /* a file name of 254 bytes */
  snprintf(path, sizeof path, "/%s/%s", repeat(dirs, 'd', 900, ""), name);
  const char *p = aq_path_fit(path, 300, buf, sizeof buf);
  aq_check(strlen(p) == 300 && strncmp(p, "...", 3) == 0, "300 bytes behind \"...\": %zu",
           strlen(p));
  aq_check(ends_with(p, name) && p[strlen(p) - strlen(name) - 1] == '/',
           "the file's name whole, after its '/'");
  aq_check(!strcmp(aq_path_fit("records/x.AT2", 300, buf, sizeof buf), "records/x.AT2"),
           "a path that fits is itself");
  /* never half a UTF-8 character after the mark: "é" is 2 bytes */
  char u[64] = "/";
  for (int i = 0; i < 10; i++)
    strcat(u, "\xc3\xa9");
  p = aq_path_fit(u, 8, buf, sizeof buf); /* "..." + 5 bytes: 2 whole, not 2.5 */
  aq_check(!strcmp(p, "...\xc3\xa9\xc3\xa9"), "whole characters after the mark: %s", p);
  /* aq_text_fit: a cut is marked, a text that fits is not */
  char small[16];
  aq_check(aq_text_fit(small, sizeof small, "%s", "short") == 0 && !strcmp(small, "short"),
           "fits: %s", small);
  aq_check(aq_text_fit(small, sizeof small, "%s-%d", "a longer text", 12345) == 1 &&
               ends_with(small, "...") && strlen(small) == sizeof small - 1,
           "cut and marked: %s", small);
  aq_check(aq_text_fit(small, 8, "%s", "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9") == 1 &&
               !strcmp(small, "\xc3\xa9\xc3\xa9..."),
           "no half character before the mark: %s", small);
}

/* dir/.../name with each directory of 200 bytes, path >= len bytes; the
 * copy of src made there.  Returns 1. */
static int long_copy(const char *root, const char *src, const char *name, size_t len,
                     char *out, size_t cap)
{
  char dir[4096], seg[256], cmd[4200];
  snprintf(dir, sizeof dir, "%s", root);
  while (strlen(dir) + 1 + strlen(name) < len) {
    size_t k = strlen(dir);
    snprintf(dir + k, sizeof dir - k, "/%s", repeat(seg, 'd', 200, ""));
  }
  snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
  if (!aq_check(system(cmd) == 0, "mkdir"))
    return 0;
  snprintf(out, cap, "%s/%s", dir, name);
  return aq_test_copy_prefix(src, out, 1, 1);
}

AQ_TEST(error_long_paths_in_notes)
{
  char root[512], v[4096], name[300], xml[4096], cmd[16384], err[16384], out[65536];
  aq_test_tmpdir(root, sizeof root);
  /* the vertical of a motion, not run: its warning names it, 900 bytes of
     path, the file's name (210 bytes) whole */
  repeat(name, 'u', 207, ".UD");
  if (long_copy(root, "tests/data/records/AOM0170806140843.UD", name, 900, v, sizeof v)) {
    snprintf(cmd, sizeof cmd,
             "--components tests/data/records/AOM0170806140843.NS,"
             "tests/data/records/AOM0170806140843.EW,'%s' --arch arches/thin.cfg --scale 1 "
             "--no-cache",
             v);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    const char *w = strstr(err, "warning: vertical component ");
    aq_check(rc == 0 && w && strstr(w, "...") && strstr(w, name) &&
                 strstr(w, " ignored (--vertical runs it)"),
             "the vertical's warning keeps its file's name and its end: exit %d, %s", rc, err);
  }
  /* a StationXML whose name is 220 bytes: named whole in the polarity note */
  repeat(name, 'x', 216, ".xml");
  if (long_copy(root, "tests/data/records/evidence/BK.KCC.xml", name, 300, xml, sizeof xml)) {
    snprintf(cmd, sizeof cmd,
             "info --units counts --accept-vertical --response '%s' "
             "tests/data/records/evidence/BK.KCC.00.HNZ.mseed",
             xml);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    char want[400];
    snprintf(want, sizeof want, "(%s: InstrumentSensitivity), and its sign is applied", name);
    aq_check(rc == 0 && strstr(err, "polarity: reversed") && strstr(err, want),
             "the StationXML's whole name in the note: exit %d, %s", rc, err);
  }
  /* a pair whose first component's path is 700 bytes, the second of
     another dt: the refusal names the first by its end, its name whole */
  repeat(name, 'a', 200, ".at2");
  if (long_copy(root, "tests/data/records/ARL360.at2", name, 700, v, sizeof v)) {
    snprintf(cmd, sizeof cmd,
             "spectrum --components '%s',tests/data/records/IELC180.AT2 --azimuths 0,90", v);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    char want[400];
    snprintf(want, sizeof want, "%s (0.02 s)", name);
    aq_check(rc == 1 && strstr(err, "expected the sample interval of ...") && strstr(err, want),
             "the other component named by its end: exit %d, %s", rc, err);
  }
}
