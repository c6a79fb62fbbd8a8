/* test_arch_control.c: [hinges] control and [contact] friction: their
 * defaults and refusals, --friction over the file's, and the free arch's
 * two sets, each its direction's minimum mechanism, against a brute force
 * over every four-hinge set by the 9x9 equilibrium (another way to get
 * lambda0 and the direction than the search's linear programs). */
#include <gsl/gsl_errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"
#include "units.h"

#define TIE_TOL 5e-14 /* relative: lambda0 by two methods agree to round-off */

static const char probe[] =
    "[arch]\n"                /* 1 */
    "name = probe\n"          /* 2 */
    "radius_m = 4.37\n"       /* 3 */
    "thickness_m = 1.13\n"    /* 4 */
    "embrace_deg = 171\n"     /* 5 */
    "voussoirs = 17\n"        /* 6 */
    "density_kg_m3 = 2213\n"  /* 7 */
    "depth_m = 0.93\n";       /* 8 */

/* probe with more lines after it, written to dir/name.cfg (path in out). */
static void write_probe(const char *dir, const char *name, const char *more, char *out,
                        size_t cap)
{
  snprintf(out, cap, "%s/%s.cfg", dir, name);
  FILE *f = fopen(out, "w");
  if (f) {
    fputs(probe, f);
    fputs(more, f);
    fclose(f);
  }
}

static aq_arch *load(const char *path, double friction)
{
  aq_arch *a = NULL;
  aq_error e;
  aq_error_clear(&e);
  aq_arch_options o = {.friction = friction};
  aq_check(aq_arch_load_opts(path, &o, &a, &e) == AQ_OK, "%s loads: %s", path, e.message);
  return a;
}

AQ_TEST(arch_control_defaults)
{
  gsl_set_error_handler_off();
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  /* a primary: fixed, the reverse its face swap; no friction */
  write_probe(dir, "named", "[hinges]\nprimary = 0e 5i 10e 16i\n", path, sizeof path);
  aq_arch *a = load(path, NAN);
  if (a) {
    aq_check(aq_arch_control(a) == AQ_CONTROL_FIXED, "a primary: fixed");
    const aq_hinge_set *r = aq_arch_hinge_set(a, 1);
    aq_check(r->joint[0] == 0 && r->joint[3] == 16 && r->face[0] == 'i' && r->face[1] == 'e',
             "reverse: the face swap");
    aq_check(isnan(aq_arch_friction(a)), "no friction: NAN, got %g", aq_arch_friction(a));
    aq_arch_free(a);
  }
  /* no primary: free */
  write_probe(dir, "searched", "", path, sizeof path);
  if ((a = load(path, NAN))) {
    aq_check(aq_arch_control(a) == AQ_CONTROL_FREE, "no primary: free");
    aq_check(aq_arch_path(a, 0)->act_sign == -1 && aq_arch_path(a, 1)->act_sign == 1,
             "free: set 0 act_sign -1, set 1 +1 (%d %d)", aq_arch_path(a, 0)->act_sign,
             aq_arch_path(a, 1)->act_sign);
    aq_arch_free(a);
  }
  /* control = fixed without a primary: the searched primary, face-swapped */
  write_probe(dir, "fixedsearch", "[hinges]\ncontrol = fixed\n[contact]\nfriction = 0.637\n",
              path, sizeof path);
  if ((a = load(path, NAN))) {
    aq_check(aq_arch_control(a) == AQ_CONTROL_FIXED && aq_arch_searched(a), "fixed, searched");
    const aq_hinge_set *p = aq_arch_hinge_set(a, 0), *r = aq_arch_hinge_set(a, 1);
    int swapped = 1;
    for (int k = 0; k < 4; k++)
      swapped &= p->joint[k] == r->joint[k] && p->face[k] != r->face[k];
    aq_check(swapped, "fixed: the reverse is the primary's face swap");
    aq_check(aq_arch_friction(a) == 0.637, "the file's friction, got %g", aq_arch_friction(a));
    aq_arch_free(a);
  }
  /* --friction over the file's */
  if ((a = load(path, 0.4123))) {
    aq_check(aq_arch_friction(a) == 0.4123, "--friction wins, got %g", aq_arch_friction(a));
    aq_arch_free(a);
  }
  /* control = free with a primary: the primary in its direction's place */
  write_probe(dir, "freeprimary", "[hinges]\nprimary = 0e 5i 10e 16i\ncontrol = free\n", path,
              sizeof path);
  if ((a = load(path, NAN))) {
    const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
    const aq_hinge_set *hs = aq_arch_hinge_set(a, p0->act_sign == -1 ? 0 : 1);
    aq_check(aq_arch_control(a) == AQ_CONTROL_FREE && !aq_arch_searched(a), "free, named");
    aq_check(p0->act_sign == -1 && p1->act_sign == 1, "act_signs -1, +1");
    aq_check(hs->joint[0] == 0 && hs->joint[1] == 5 && hs->joint[2] == 10 &&
                 hs->joint[3] == 16 && hs->face[0] == 'e',
             "the primary is set 0 (it is driven by act_sign -1)");
    aq_arch_free(a);
  }
}

/* The lowest lambda0 of each direction (best[0]: act_sign -1, best[1]:
 * +1) over every set of four joints with alternating faces. */
static void brute_minima(const aq_geom *g, double best[2])
{
  size_t n = g->p.voussoirs;
  best[0] = best[1] = HUGE_VAL;
  for (int pat = 0; pat < 2; pat++)
    for (size_t a = 0; a <= n; a++)
      for (size_t b = a + 1; b <= n; b++)
        for (size_t c = b + 1; c <= n; c++)
          for (size_t d = c + 1; d <= n; d++) {
            aq_hinge_set hs = {{a, b, c, d}, {'e', 'i', 'e', 'i'}};
            if (pat)
              hs = (aq_hinge_set){{a, b, c, d}, {'i', 'e', 'i', 'e'}};
            double l0;
            int act;
            if (aq_test_lambda0_eq_act(g, &hs, &l0, &act) && l0 > 0 && l0 < best[act > 0])
              best[act > 0] = l0;
          }
}

/* An asymmetric arch (a point mass off the crown on one side): the free
 * arch's sets are its two directions' minima, unlike each other. */
AQ_TEST(arch_control_free_sets_are_direction_minima)
{
  gsl_set_error_handler_off();
  aq_point_mass pm = {"bell", 2, {0, 0}, 812.0};
  aq_arch_params pp = aq_arch_circular(2.73, 0.517, 151.0 * AQ_DEG_RAD, 11, 1711.0, 0.63);
  aq_geom g0;
  aq_error e;
  if (!aq_check(aq_geom_init(&g0, &pp, &e) == AQ_OK, "geometry"))
    return;
  pm.p = g0.vous[2].c; /* on voussoir 2's centroid, +x side */
  aq_geom_free(&g0);
  pp.nmass = 1;
  pp.mass = &pm;
  pp.control = AQ_CONTROL_FREE;
  aq_arch *a = NULL;
  if (!aq_check(aq_arch_build(&pp, NULL, NULL, NULL, "bell", &a, &e) == AQ_OK, "build: %s",
                e.message))
    return;
  double best[2];
  brute_minima(aq_arch_geom(a), best);
  for (int k = 0; k < 2; k++) {
    const aq_path *p = aq_arch_path(a, k);
    double l0;
    int act;
    aq_check(p->admissible && p->act_sign == (k ? 1 : -1), "set %d: act_sign %d", k,
             p->act_sign);
    aq_check(aq_test_lambda0_eq_act(aq_arch_geom(a), aq_arch_hinge_set(a, k), &l0, &act) &&
                 l0 > 0 && act == p->act_sign,
             "set %d admissible by the 9x9, same direction", k);
    aq_check_rel(p->lambda0, best[k], TIE_TOL, "set %d: lambda0 = brute force's minimum of "
                 "act_sign %+d", k, k ? 1 : -1);
  }
  aq_check(fabs(best[0] - best[1]) > 1e-3 * best[0], "the directions differ (%.6g %.6g)",
           best[0], best[1]);
  aq_arch_free(a);
}

/* A mirror-symmetric arch: set 1 is set 0 mirrored (joint j -> n - j, the
 * order reversed, each hinge on the same face), with the same lambda0. */
AQ_TEST(arch_control_free_symmetric_mirror)
{
  gsl_set_error_handler_off();
  static const char *const files[] = {"arches/gothic.cfg", "arches/bridge.cfg",
                                      "arches/catenary.cfg", "arches/search.cfg"};
  for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
    aq_arch *a = load(files[f], NAN);
    if (!a)
      continue;
    size_t n = aq_arch_geom(a)->p.voussoirs;
    const aq_hinge_set *s0 = aq_arch_hinge_set(a, 0), *s1 = aq_arch_hinge_set(a, 1);
    int mirror = aq_arch_control(a) == AQ_CONTROL_FREE;
    for (int k = 0; k < 4; k++)
      mirror &= s1->joint[k] == n - s0->joint[3 - k] && s1->face[k] == s0->face[3 - k];
    aq_check(mirror, "%s: set 1 is set 0's mirror", files[f]);
    aq_check_rel(aq_arch_path(a, 1)->lambda0, aq_arch_path(a, 0)->lambda0, 1e-12,
                 "%s: the same lambda0", files[f]);
    aq_arch_free(a);
  }
}

/* The control and the friction in the results file (/arches/NNN), with
 * the block model's contacts and supports (the arch file's, or 0). */
AQ_TEST(arch_control_in_results_file)
{
  char dir[512], h5[600], args[2048], out[8192], err[4096], cfg[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  if (!aq_test_edited_copy("arches/oppenheim.cfg", "[dynamics]",
                           "[contact]\ne_n = 0.25\n[supports]\nspread_m = 0.002\n"
                           "abutment_m = 0.75\n[dynamics]",
                           dir, "o.cfg", cfg, sizeof cfg))
    return;
  snprintf(args, sizeof args,
           "records/RSN1616_DUZCE_362-E.AT2 --arch %s --arch arches/gothic.cfg "
           "--friction 0.537 --polarity normal --no-cache -j 1 -o %s", cfg, h5);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  if (!aq_check(rc == 0, "runs: %d %s", rc, err))
    return;
  char cell[64];
  aq_check(!strcmp(aq_test_tsv_field(out, 0, 19, cell, sizeof cell), "control"),
           "the control column, got \"%s\"", cell);
  aq_check(!strcmp(aq_test_tsv_field(out, 1, 19, cell, sizeof cell), "fixed"),
           "oppenheim fixed, got \"%s\"", cell);
  aq_check(!strcmp(aq_test_tsv_field(out, 2, 19, cell, sizeof cell), "free"),
           "gothic free, got \"%s\"", cell);
  hid_t file = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (!aq_check(file >= 0, "open %s", h5))
    return;
  static const char *const want[2] = {"fixed", "free"};
  for (int k = 0; k < 2; k++) {
    char g[32];
    snprintf(g, sizeof g, "/arches/%03d", k);
    hid_t grp = H5Gopen2(file, g, H5P_DEFAULT);
    hid_t at = H5Aopen(grp, "control", H5P_DEFAULT);
    hid_t t = H5Aget_type(at);
    char buf[32] = "";
    if (H5Tget_size(t) < sizeof buf)
      H5Aread(at, t, buf);
    aq_check(!strcmp(buf, want[k]), "%s control %s, got \"%s\"", g, want[k], buf);
    H5Tclose(t);
    H5Aclose(at);
    double mu = NAN;
    at = H5Aopen(grp, "friction", H5P_DEFAULT);
    H5Aread(at, H5T_NATIVE_DOUBLE, &mu);
    H5Aclose(at);
    aq_check(mu == 0.537, "%s friction 0.537, got %g", g, mu);
    static const char *const blk[3] = {"e_n", "spread_m", "abutment_m"};
    static const double bwant[2][3] = {{0.25, 0.002, 0.75}, {0, 0, 0}};
    for (int b = 0; b < 3; b++) {
      double v = NAN;
      at = H5Aopen(grp, blk[b], H5P_DEFAULT);
      if (at >= 0)
        H5Aread(at, H5T_NATIVE_DOUBLE, &v), H5Aclose(at);
      aq_check(v == bwant[k][b], "%s %s %g, got %g", g, blk[b], bwant[k][b], v);
    }
    H5Gclose(grp);
  }
  H5Fclose(file);
}

/* --friction: a value > 0 for the commands that build arches, refused
 * elsewhere; mechanism prints the minimum of each direction. */
AQ_TEST(arch_control_cli)
{
  char out[16384], err[4096];
  static const char *const bad[] = {"0", "-0.3", "nan", "abc", "inf"};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char args[200];
    snprintf(args, sizeof args, "mechanism --arch arches/oppenheim.cfg --friction %s", bad[k]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && out[0] == '\0' && strstr(err, "--friction") &&
                 aq_test_count_lines(err) == 1,
             "--friction %s refused in one line: %d \"%s\"", bad[k], rc, err);
  }
  int rc = aq_test_run("info records/RSN1616_DUZCE_362-E.AT2 --friction 0.6", out, sizeof out,
                       err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--friction"), "info takes no --friction: %d %s", rc, err);
  rc = aq_test_run("mechanism --arch arches/gothic.cfg --friction 0.6", out, sizeof out, err,
                   sizeof err);
  aq_check(rc == 0, "mechanism with --friction runs: %s", err);
  int minus = 0, plus = 0;
  for (int row = 1; row < 6; row++) {
    char set[32], act[8], ctl[16];
    aq_test_tsv_field(out, row, 0, set, sizeof set);
    aq_test_tsv_field(out, row, 6, act, sizeof act);
    aq_test_tsv_field(out, row, 16, ctl, sizeof ctl);
    if (!strcmp(set, "minimum")) {
      minus += !strcmp(act, "-1");
      plus += !strcmp(act, "+1");
      aq_check(!strcmp(ctl, "free"), "gothic's control column: free, got %s", ctl);
    }
  }
  aq_check(minus == 1 && plus == 1, "a minimum row per direction (%d %d)", minus, plus);
  /* a fixed arch: the warning names the lower minimum of the reverse's direction */
  rc = aq_test_run("mechanism --arch arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(err, "warning: the reverse set 0i 5e 12i 20e (act_sign +1)") &&
               strstr(err, "4i 12e 19i 24e"),
           "thin: the reverse above its direction's minimum 4i 12e 19i 24e: %s", err);
}
