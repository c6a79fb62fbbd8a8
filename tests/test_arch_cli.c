/* test_arch_cli.c: `archquake mechanism` on good and bad arch files: one
 * clear line per problem (FILE:LINE: KEY: expected ..., got ...), a non-zero
 * exit status and nothing on stdout. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "check.h"

static const char base[] =
    "; test arch\n"                    /* 1 */
    "[arch]\n"                         /* 2 */
    "name = probe\n"                   /* 3 */
    "radius_m = 4.37\n"                /* 4 */
    "thickness_m = 1.13\n"             /* 5 */
    "embrace_deg = 171\n"              /* 6 */
    "voussoirs = 17\n"                 /* 7 */
    "density_kg_m3 = 2213\n"           /* 8 */
    "depth_m = 0.93\n"                 /* 9 */
    "[hinges]\n"                       /* 10 */
    "primary = 0e 5i 10e 16i\n"        /* 11 */
    "[dynamics]\n"                     /* 12 */
    "cor = 0.25\n"                     /* 13 */
    "impact = momentum\n"              /* 14 */
    "g_mps2 = 9.81\n";                 /* 15 */

/* base with line `line` replaced by repl ("" deletes it; NULL: unchanged) */
static void write_cfg(const char *path, int line, const char *repl, const char *append)
{
  FILE *f = fopen(path, "w");
  const char *p = base;
  for (int l = 1; *p; l++) {
    const char *nl = strchr(p, '\n');
    size_t len = (size_t)(nl - p) + 1;
    if (l == line && repl) {
      if (repl[0])
        fprintf(f, "%s\n", repl);
    } else {
      fwrite(p, 1, len, f);
    }
    p += len;
  }
  if (append)
    fputs(append, f);
  fclose(f);
}

static void expect_error_in(const char *what, const char *path, const char *want);

static void expect_error(const char *what, int line, const char *repl, const char *append,
                         const char *want)
{
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/a.cfg", dir);
  write_cfg(path, line, repl, append);
  expect_error_in(what, path, want);
}

/* three lines replaced */
static void expect_error_lines(const char *what, int l1, const char *r1, int l2, const char *r2,
                               int l3, const char *r3, const char *want)
{
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/a.cfg", dir);
  FILE *f = fopen(path, "w");
  const char *p = base;
  for (int l = 1; *p; l++) {
    const char *nl = strchr(p, '\n');
    size_t len = (size_t)(nl - p) + 1;
    const char *r = l == l1 ? r1 : l == l2 ? r2 : l == l3 ? r3 : NULL;
    if (r)
      fprintf(f, "%s\n", r);
    else
      fwrite(p, 1, len, f);
    p += len;
  }
  fclose(f);
  expect_error_in(what, path, want);
}

static void expect_error_in(const char *what, const char *path, const char *want)
{
  char args[700], out[4096], err[4096];
  snprintf(args, sizeof args, "mechanism --arch %s", path);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "%s: exit status %d", what, rc);
  aq_check(out[0] == '\0', "%s: no output, got \"%s\"", what, out);
  char *nl = strchr(err, '\n');
  aq_check(nl && nl[1] == '\0', "%s: one line, got \"%s\"", what, err);
  char prefix[800];
  snprintf(prefix, sizeof prefix, "archquake: %s", want);
  if (strstr(want, "%s")) {
    char tmp[700];
    snprintf(tmp, sizeof tmp, want, path);
    snprintf(prefix, sizeof prefix, "archquake: %s", tmp);
  }
  aq_check(strncmp(err, prefix, strlen(prefix)) == 0, "%s: want \"%s...\", got \"%s\"", what,
           prefix, err);
  aq_check(strstr(err, "expected") != NULL, "%s: says what was expected", what);
}

AQ_TEST(arch_cli_bad_files)
{
  expect_error("negative radius", 4, "radius_m = -4.37", NULL, "%s:4: radius_m: expected");
  expect_error("zero thickness", 5, "thickness_m = 0", NULL, "%s:5: thickness_m: expected");
  expect_error("thickness >= diameter", 5, "thickness_m = 8.74", NULL,
               "%s:5: thickness_m: expected less than the diameter");
  expect_error("zero depth", 9, "depth_m = 0.0", NULL, "%s:9: depth_m: expected");
  expect_error("negative density", 8, "density_kg_m3 = -1", NULL, "%s:8: density_kg_m3: expected");
  expect_error("embrace > 180", 6, "embrace_deg = 180.5", NULL, "%s:6: embrace_deg: expected");
  expect_error("embrace 0", 6, "embrace_deg = 0", NULL, "%s:6: embrace_deg: expected");
  expect_error("3 voussoirs", 7, "voussoirs = 3", NULL, "%s:7: voussoirs: expected");
  expect_error("voussoirs not an integer", 7, "voussoirs = 17.5", NULL,
               "%s:7: voussoirs: expected");
  expect_error("bad number", 4, "radius_m = 4.37x", NULL, "%s:4: radius_m: expected");
  expect_error("joints out of order", 11, "primary = 0e 10i 5e 16i", NULL,
               "%s:11: primary: expected joints in increasing order");
  expect_error("joint out of range", 11, "primary = 0e 5i 10e 18i", NULL,
               "%s:11: primary: expected joints in 0..17");
  expect_error("two hinges on one joint", 11, "primary = 0e 5i 5e 16i", NULL,
               "%s:11: primary: expected one hinge per joint");
  expect_error("faces not alternating", 11, "primary = 0e 5e 10i 16i", NULL,
               "%s:11: primary: expected an admissible mechanism");
  expect_error("three hinges", 11, "primary = 0e 5i 10e", NULL, "%s:11: primary: expected four hinges");
  expect_error("bad face", 11, "primary = 0e 5x 10e 16i", NULL, "%s:11: primary: expected four hinges");
  expect_error("unknown key", 9, "depth = 0.93", NULL, "%s:9: depth: expected a key of [arch]");
  expect_error("unknown section", 12, "[dynamic]", NULL, "%s:12: section: expected [arch], [fill], [masses], [hinges], [contact], [supports] or [dynamics]");
  expect_error("duplicate key", 0, NULL, "[arch]\nradius_m = 5\n", "%s:17: radius_m: expected one value per key");
  expect_error("missing key", 8, "", NULL, "%s: density_kg_m3: expected a value in [arch], got none");
  expect_error("hinges without primary", 11, "", NULL, "%s:10: primary: expected a primary hinge set");
  expect_error("control neither fixed nor free", 11, "primary = 0e 5i 10e 16i\ncontrol = loose",
               NULL, "%s:12: control: expected fixed or free, got \"loose\"");
  expect_error("control free with a reverse", 11,
               "primary = 0e 5i 10e 16i\nreverse = 0i 5e 10i 16e\ncontrol = free", NULL,
               "%s:12: reverse: expected no reverse with control = free (line 13");
  expect_error("reverse without primary", 11, "reverse = 0i 5e 10i 16e", NULL,
               "%s:11: primary: expected a primary hinge set in [hinges] with the reverse");
  static const char *const bad_mu[] = {"0", "-0.41", "nan", "inf", "0.6x", ""};
  for (size_t k = 0; k < sizeof bad_mu / sizeof bad_mu[0]; k++) {
    char line[64], what[64];
    snprintf(line, sizeof line, "[contact]\nfriction = %s", bad_mu[k]);
    snprintf(what, sizeof what, "friction \"%s\"", bad_mu[k]);
    expect_error(what, 12, line, NULL,
                 "%s:13: friction: expected a Coulomb coefficient in (0, 1000], got");
  }
  /* too many voussoirs, with no [hinges] (lines 10-11 become comments) */
  expect_error_lines("too many voussoirs", 7, "voussoirs = 1001", 10, "; no hinges", 11, "; none",
                     "%s:7: voussoirs: expected an integer in 4..1000");
  expect_error("cor > 1", 13, "cor = 1.2", NULL, "%s:13: cor: expected");
  expect_error("impact", 14, "impact = newton", NULL, "%s:14: impact: expected cor or momentum");
  expect_error("not INI", 3, "name probe", NULL, "%s:3: expected KEY = VALUE");
  /* a missing file */
  char out[1024], err[1024];
  int rc = aq_test_run("mechanism --arch build/tmp/no-such-arch.cfg", out, sizeof out, err,
                       sizeof err);
  aq_check(rc == 1 && out[0] == '\0', "missing file: status %d", rc);
  aq_check(strncmp(err, "archquake: build/tmp/no-such-arch.cfg: expected a readable arch file",
                   strlen("archquake: build/tmp/no-such-arch.cfg: expected a readable arch file")) == 0,
           "missing file message: %s", err);
  rc = aq_test_run("mechanism", out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "no --arch: usage status %d", rc);
}

AQ_TEST(arch_cli_mechanism_output)
{
  char out[65536], err[4096];
  int rc = aq_test_run("mechanism --arch arches/oppenheim.cfg --table --points 7", out,
                       sizeof out, err, sizeof err);
  /* oppenheim's reverse is above its direction's minimum: one warning */
  aq_check(rc == 0 && aq_test_count_lines(err) == 1 &&
               !strncmp(err, "archquake: arches/oppenheim.cfg: warning: the reverse set", 57),
           "runs: %d %s", rc, err);
  aq_check(strncmp(out, "set\tjoints\tfaces\tlambda0\tq_c_rad\t", 32) == 0, "header");
  aq_check(strstr(out, "\nprimary\t0,6,12,19\teiei\t") != NULL, "primary row");
  aq_check(strstr(out, "\nreverse\t0,6,12,19\tieie\t") != NULL, "reverse row");
  int rows = 0;
  for (const char *p = out; (p = strstr(p, "\nprimary\t")); p++)
    rows++;
  aq_check(rows == 1 + 7, "summary row and 7 table rows: %d", rows);
  rc = aq_test_run("mechanism --help", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "usage: archquake mechanism"), "help");
  rc = aq_test_run("mechanism --arch arches/oppenheim.cfg --points 1", out, sizeof out, err,
                   sizeof err);
  aq_check(rc == 2 && strstr(err, "--points"), "bad --points");
}

AQ_TEST(arch_load_keeps_text_and_options)
{
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/probe.cfg", dir);
  write_cfg(path, 0, NULL, NULL);
  aq_arch *a = NULL;
  aq_error e;
  aq_error_clear(&e);
  if (!aq_check(aq_arch_load(path, &a, &e) == AQ_OK, "loads: %s", e.message))
    return;
  aq_check(strcmp(aq_arch_config_text(a), base) == 0, "text as read");
  aq_check(strcmp(aq_arch_name(a), "probe") == 0, "name");
  const aq_arch_dynamics *d = aq_arch_dynamics_of(a);
  aq_check(d->cor == 0.25 && d->impact == AQ_IMPACT_MOMENTUM && d->g_mps2 == 9.81, "dynamics");
  const aq_path *p = aq_arch_path(a, 0);
  aq_check(p->g_mps2 == 9.81 && p->admissible && aq_arch_path(a, 2) == NULL, "paths");
  aq_arch_free(a);
  /* name defaults to the file name */
  write_cfg(path, 3, "", NULL);
  aq_check(aq_arch_load(path, &a, &e) == AQ_OK && strcmp(aq_arch_name(a), "probe") == 0,
           "default name");
  aq_arch_free(a);
  aq_arch_free(NULL);
}
