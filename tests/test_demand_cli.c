/* test_demand_cli.c: what the motion asks of the joints in the main job's
 * rows: the columns, the status marks (slides, beyond) against the row's own
 * numbers and the friction given, and no verdict marked on a failed run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

static char out[1 << 16], err[8192];

/* Column of name in the TSV's header, or -1. */
static int column(const char *tsv, const char *name)
{
  char buf[128];
  for (int k = 0; k < 64; k++) {
    aq_test_tsv_field(tsv, 0, k, buf, sizeof buf);
    if (!buf[0])
      return -1;
    if (strcmp(buf, name) == 0)
      return k;
  }
  return -1;
}

static double num(const char *tsv, int row, int k)
{
  char buf[128];
  aq_test_tsv_field(tsv, row, k, buf, sizeof buf);
  return strtod(buf, NULL);
}

static const char *str(const char *tsv, int row, int k, char *buf, size_t n)
{
  return aq_test_tsv_field(tsv, row, k, buf, n);
}

AQ_TEST(demand_cli_columns_and_marks)
{
  /* El Centro at 2 on oppenheim (fixed) and on search (free): both move */
  const char *recs = "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN1616_DUZCE_362-E.AT2";
  char cmd[1024], buf[64];
  double mu[3][2], ecc[3][2];
  static const char *const fr[3] = {"0.6", "5", "0.33"};
  size_t still = 0, still_slides = 0;
  for (int f = 0; f < 3; f++) {
    snprintf(cmd, sizeof cmd, "%s --arch arches/oppenheim.cfg --arch arches/search.cfg --scale 2 "
                              "--friction %s",
             recs, fr[f]);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    aq_check(rc == 0, "exit 0, got %d: %s", rc, err);
    int cs = column(out, "status"), cm = column(out, "mu_demand"), cj = column(out, "mu_demand_joint"),
        ce = column(out, "thrust_ecc_max"), ct = column(out, "thrust_ecc_time_s"),
        csl = column(out, "slide_time_s"), cc = column(out, "control"),
        cf = column(out, "first_set"), cl = column(out, "lambda0_first");
    (void)cf;
    aq_check(cs >= 0 && cm == cc + 1 && cj == cm + 1 && ce == cj + 1 && ct == ce + 1 && csl == ct + 1,
             "the columns after control: mu_demand mu_demand_joint thrust_ecc_max "
             "thrust_ecc_time_s slide_time_s");
    /* 2 records x 2 arches x both polarities (one arch fixed): El Centro's normal rows
       are 1 (oppenheim) and 3 (search) */
    for (int row = 1; row <= 8; row++) {
      char st[64], ctl[16];
      str(out, row, cs, st, sizeof st);
      str(out, row, cc, ctl, sizeof ctl);
      double m = num(out, row, cm), e = num(out, row, ce), ts = num(out, row, csl),
             te = num(out, row, ct), l0 = num(out, row, cl);
      double fric = strtod(fr[f], NULL);
      if (isnan(l0)) { /* never moved: the statics at the record's peak, no thrust */
        still++;
        still_slides += m > fric;
        aq_check(m > 0 && isfinite(m) && isnan(e) && isnan(te) &&
                     strcmp(st, m > fric ? "slides" : "ok") == 0 &&
                     (m > fric ? ts >= 0 : isnan(ts)),
                 "row %d never moved (friction %s): mu %g ecc %g status %s slide %g", row,
                 fr[f], m, e, st, ts);
        continue;
      }
      int slides = m > fric, beyond = strcmp(ctl, "free") == 0 && e > 1;
      const char *want = slides && beyond ? "slides+beyond" : slides ? "slides" : beyond ? "beyond" : "ok";
      aq_check(strcmp(st, want) == 0, "row %d (%s, friction %s, mu_demand %g, thrust %g): status %s, "
                                      "want %s", row, ctl, fr[f], m, e, st, want);
      aq_check(slides ? ts >= 0 : isnan(ts), "row %d: slide_time_s %g with mu_demand %g", row, ts, m);
      aq_check(e > 1 ? te >= 0 : isnan(te), "row %d: thrust_ecc_time_s %g with thrust %g", row, te, e);
      aq_check(num(out, row, cj) >= 0 && num(out, row, cj) <= 30, "row %d: a joint", row);
      if (row == 1 || row == 3) { /* El Centro: oppenheim, search */
        mu[f][row / 2] = m;
        ecc[f][row / 2] = e;
      }
    }
    aq_check(strcmp(str(out, 1, cs, buf, sizeof buf), f == 1 ? "ok" : "slides") == 0,
             "El Centro x2 on oppenheim: it slides at mu = 0.6 and 0.33, not at 5 (%s)", buf);
    aq_check(strcmp(str(out, 3, cs, buf, sizeof buf), f == 2 ? "slides+beyond" : "beyond") == 0,
             "El Centro x2 on search (free): beyond (%s)", buf);
  }
  /* the friction marks the verdict, it does not change the motion */
  for (int a = 0; a < 2; a++)
    aq_check(mu[0][a] == mu[1][a] && ecc[0][a] == ecc[1][a] && mu[2][a] == mu[1][a],
             "arch %d: the same demand at any friction", a);
  aq_check(still == 12 && still_slides >= 2, "runs that never moved: %zu, %zu of them slide",
           still, still_slides);
  /* without a friction nothing slides */
  int rc = aq_test_run("records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch arches/oppenheim.cfg "
                       "--scale 2",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit 0");
  aq_check(strcmp(str(out, 1, column(out, "status"), buf, sizeof buf), "ok") == 0 &&
               isnan(num(out, 1, column(out, "slide_time_s"))) &&
               num(out, 1, column(out, "thrust_ecc_max")) > 1,
           "no friction: ok, no slide time, though the fixed arch's thrust leaves a section (%s)",
           buf);
}

AQ_TEST(demand_cli_failed_run_unmarked)
{
  /* a record that cannot be read: its rows fail, no demand, no mark (the
   * friction is the least oppenheim stands with at rest, 0.309, and a
   * little more: any run that moved would slide) */
  char path[512], cmd[768];
  if (!aq_test_tmpfile(path, sizeof path, "demand_bad.AT2", "not an AT2 file\n"))
    return;
  snprintf(cmd, sizeof cmd, "%s --arch arches/oppenheim.cfg --friction 0.31", path);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "exit 1, got %d", rc);
  char st[64];
  str(out, 1, column(out, "status"), st, sizeof st);
  aq_check(strchr(st, ':') != NULL, "a failure's status, got %s", st);
  aq_check(isnan(num(out, 1, column(out, "mu_demand"))) &&
               isnan(num(out, 1, column(out, "thrust_ecc_max"))),
           "no demand without a run");
}

AQ_TEST(demand_cli_paper_still_runs)
{
  /* --model paper: a run in which the arch never moves has the statics'
   * demand, which no model changes (the work path's, to the digit), and
   * is marked over the friction; once the arch moves the demand is nan
   * (paper's fits carry no joint forces) and the run is not marked.  A
   * friction under paper is named in one warning line per arch. */
  const char *base = "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 records/RSN1616_DUZCE_362-E.AT2 "
                     "--arch arches/oppenheim.cfg --arch arches/search.cfg --scale 0.5,2 "
                     "--polarity both --friction 0.33";
  static char ref[1 << 16];
  char cmd[1024], a[64], b[64], e2[8192];
  snprintf(cmd, sizeof cmd, "%s --model workpath", base);
  int rc = aq_test_run(cmd, ref, sizeof ref, e2, sizeof e2);
  aq_check(rc == 0 && !strstr(e2, "warning: friction"), "workpath: exit 0 (%d), no warning: %s",
           rc, e2);
  snprintf(cmd, sizeof cmd, "%s --model paper", base);
  rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  const char *w = strstr(err, "warning: friction: 0.33 marks only the runs in which the arch "
                              "never moves under --model paper");
  const char *w2 = w ? strstr(w + 1, "warning: friction") : NULL;
  aq_check(rc == 0 && w && w2 && !strstr(w2 + 1, "warning: friction"),
           "paper: exit 0 (%d), one warning per arch: %s", rc, err);
  int cl = column(out, "lambda0_first"), cs = column(out, "status");
  static const char *const same[] = {"mu_demand", "mu_demand_joint", "slide_time_s",
                                     "thrust_ecc_max", "thrust_ecc_time_s", "status"};
  size_t still = 0, slides = 0, moved = 0;
  for (int row = 1; row <= 16; row++) {
    char l0[64];
    str(ref, row, column(ref, "lambda0_first"), l0, sizeof l0);
    aq_check(strcmp(str(out, row, cl, a, sizeof a), l0) == 0,
             "row %d: the same runs move under both models (%s, %s)", row, a, l0);
    if (strcmp(l0, "nan") == 0) { /* never moved */
      still++;
      slides += strcmp(str(out, row, cs, a, sizeof a), "slides") == 0;
      for (size_t k = 0; k < sizeof same / sizeof same[0]; k++)
        aq_check(strcmp(str(out, row, column(out, same[k]), a, sizeof a),
                        str(ref, row, column(ref, same[k]), b, sizeof b)) == 0,
                 "row %d never moved: %s %s under paper, %s under the work path", row, same[k],
                 a, b);
      aq_check(num(out, row, column(out, "mu_demand")) > 0, "row %d: a demand", row);
    } else {
      moved++;
      char st[64];
      str(out, row, cs, st, sizeof st);
      aq_check(isnan(num(out, row, column(out, "mu_demand"))) &&
                   isnan(num(out, row, column(out, "slide_time_s"))) && !strstr(st, "slides"),
               "row %d moved under paper: mu_demand %g, status %s", row,
               num(out, row, column(out, "mu_demand")), st);
    }
  }
  aq_check(still >= 4 && moved >= 4 && slides >= 1,
           "runs that never moved %zu (%zu slide), that moved %zu", still, slides, moved);
}

/* `pulse` reports what its run asks of the joints and marks it, as the main
 * job does.  Just above lambda0 (1.001 lambda0 g, opening oppenheim's
 * primary set), the friction demand is that of the set's collapse state
 * at rest, mechanism's mu_required (0.686 at joint 0), to the load's excess
 * (measured 9e-5); the run slides at 0.6 from its start, not at 0.7.  A
 * pulse that never moves the arch has the statics' demand at its peak, as
 * the main job's still runs.  The block model's row has its own columns,
 * not these; --model paper with a friction says, once, what it marks. */
AQ_TEST(demand_cli_pulse_marks)
{
  int rc = aq_test_run("mechanism --arch arches/oppenheim.cfg", out, sizeof out, err, sizeof err);
  double l0 = num(out, 1, column(out, "lambda0")), mu = num(out, 1, column(out, "mu_required"));
  if (!aq_check(rc == 0 && l0 > 0.4 && mu > 0.6, "mechanism: lambda0 %g, mu_required %g", l0,
                mu))
    return;
  char cmd[512], st[64], j[16];
  static const char *const fr[2] = {"0.6", "0.7"};
  for (int f = 0; f < 2; f++) {
    snprintf(cmd, sizeof cmd, "pulse --arch arches/oppenheim.cfg --accel-g %.17g --duration 0.2 "
                              "--friction %s", -1.001 * l0, fr[f]);
    rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    int cs = column(out, "status"), cm = column(out, "mu_demand");
    aq_check(rc == 0 && cs == 15 && cm == 16 && column(out, "slide_time_s") == 20,
             "%s: exit %d, the columns after evals", cmd, rc);
    double m = num(out, 1, cm), ts = num(out, 1, column(out, "slide_time_s"));
    aq_check(m >= mu && m <= mu * (1 + 2e-4) &&
                 !strcmp(str(out, 1, column(out, "mu_demand_joint"), j, sizeof j), "0"),
             "friction %s: mu_demand %.9g at joint %s, mu_required %.9g", fr[f], m, j, mu);
    str(out, 1, cs, st, sizeof st);
    aq_check(f == 0 ? !strcmp(st, "slides") && ts == 0 : !strcmp(st, "ok") && isnan(ts),
             "friction %s: status %s, slide_time_s %g", fr[f], st, ts);
  }
  /* still: the statics at the pulse's peak, marked over a friction below it */
  rc = aq_test_run("pulse --arch arches/thin.cfg --accel-g 0.01 --duration 0.5 --friction 0.385",
                   out, sizeof out, err, sizeof err);
  double m = num(out, 1, column(out, "mu_demand"));
  aq_check(rc == 0 && num(out, 1, column(out, "peak_rotation_rad")) == 0 && m > 0.385 &&
               m < 0.4 && !strcmp(str(out, 1, column(out, "status"), st, sizeof st), "slides") &&
               isnan(num(out, 1, column(out, "thrust_ecc_max"))),
           "thin at 0.01 g never moves: mu_demand %g (the statics, above its 0.381 at rest), "
           "status %s", m, st);
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.5 --duration 0.2 --model "
                   "paper --friction 0.7", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(err, "warning: friction: 0.7 marks only the runs in which the arch "
                                  "never moves under --model paper") &&
               isnan(num(out, 1, column(out, "mu_demand"))),
           "paper: one warning, no demand once it moves: %s", err);
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.5 --duration 0.2 --model "
                   "blocks --friction 0.7", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && column(out, "status") < 0 && column(out, "max_slip_m") == 15,
           "blocks: its own columns (exit %d)", rc);
  rc = aq_test_run("capacity records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2 --arch "
                   "arches/oppenheim.cfg --model paper --friction 0.7 --scale-max 2 "
                   "--resolution 0.5", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(err, "warning: friction: 0.7 marks no run under --model paper") &&
               !strcmp(str(out, 1, column(out, "status"), st, sizeof st), "ok"),
           "capacity under paper: one warning, no mark (%s): %s", st, err);
}

/* `domain` marks each ratio's shortest collapsing pulse: that run, made
 * again with `pulse` at the printed acceleration and duration, has the
 * same status; the durations do not depend on the friction. */
AQ_TEST(demand_cli_domain_marks)
{
  static char ref[4096];
  int rc = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 1.1,4", ref, sizeof ref, err,
                       sizeof err);
  aq_check(rc == 0 && column(ref, "status") == 3, "domain without a friction: exit %d", rc);
  rc = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 1.1,4 --friction 0.9", out,
                   sizeof out, err, sizeof err);
  aq_check(rc == 0, "domain with 0.9: exit %d", rc);
  static const char *const want[2] = {"ok", "slides"};
  for (int row = 1; row <= 2; row++) {
    char a[64], b[64], st[64], ps[64], cmd[512];
    aq_check(!strcmp(str(out, row, 2, a, sizeof a), str(ref, row, 2, b, sizeof b)) &&
                 !strcmp(str(ref, row, 3, st, sizeof st), "ok"),
             "row %d: the same duration (%s, %s), ok without a friction (%s)", row, a, b, st);
    str(out, row, 3, st, sizeof st);
    snprintf(cmd, sizeof cmd, "pulse --arch arches/oppenheim.cfg --accel-g %s --duration %s "
                              "--friction 0.9", str(out, row, 1, a, sizeof a),
             str(out, row, 2, b, sizeof b));
    static char p[4096];
    rc = aq_test_run(cmd, p, sizeof p, err, sizeof err);
    aq_check(rc == 0 && num(p, 1, column(p, "collapsed")) == 1 &&
                 !strcmp(str(p, 1, column(p, "status"), ps, sizeof ps), st) &&
                 !strcmp(st, want[row - 1]),
             "row %d: domain's %s, pulse's %s (want %s)", row, st, ps, want[row - 1]);
  }
}
