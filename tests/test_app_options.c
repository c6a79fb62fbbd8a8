/* test_app_options.c: every numeric option's range, through the CLI: a value
 * outside it (or with trailing text) is refused with exit 2 and one line
 * naming the option and the value given, nothing is run and no output file
 * is left; and --scale-to-pga scales each record to that PGA. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

#define REC "records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
#define RUN REC " --arch arches/thin.cfg"
#define PULSE "pulse --arch arches/thin.cfg --accel-g 0.5 --duration 0.2"

static int nlines(const char *s)
{
  int k = 0;
  for (; *s; s++)
    k += *s == '\n';
  return k;
}

AQ_TEST(app_options_out_of_range_refused)
{
  static const struct {
    const char *cmd, *opt, *value;
  } cs[] = {
      {RUN, "--scale-to-pga", "-0.3"},  {RUN, "--scale-to-pga", "0"},
      {RUN, "--scale-to-pga", "100.5"}, {RUN, "--scale-to-pga", "0.3g"},
      {RUN, "--scale-to-lambda0", "0"}, {RUN, "--scale-to-lambda0", "-2.5"},
      {RUN, "--scale-to-lambda0", "nan"}, {RUN, "--scale-to-lambda0", "100.5"},
      {RUN, "--scale", "-1"},           {RUN, "--scale", "0"},
      {RUN, "--scale", "1,x"},          {RUN, "--cor", "-0.1"},
      {RUN, "--cor", "1.01"},           {RUN, "--cor", "0.5x"},
      {RUN, "-j", "0"},                 {RUN, "-j", "2.5"},
      {RUN, "--taper", "0.51"},         {RUN, "--taper", "-0.01"},
      {RUN, "--highpass", "0"},         {RUN, "--highpass", "-1"},
      {RUN, "--order", "0"},            {RUN, "--lowpass", "0"},
      {RUN, "--merge-tol", "-0.001"},   {RUN, "--merge-tol", "10.5"},
      {RUN, "--dt", "0"},               {RUN, "--column", "0"},
      {RUN, "--column", "65"},          {PULSE, "--accel-g", "100.5"},
      {PULSE, "--duration", "0"},       {PULSE, "--end", "-1"},
      {PULSE, "--dt", "0"},             {PULSE, "--cor", "1.5"},
      {PULSE " --model ode", "--ode-rtol", "0.2"},
      {PULSE " --model ode", "--ode-rtol", "0"},
      {PULSE, "--max-end", "0"},        {"domain --arch arches/thin.cfg", "--ratios", "0.5"},
      {"domain --arch arches/thin.cfg", "--cor", "-1"},
      {"domain --arch arches/thin.cfg", "--tol", "0"},
      {"domain --arch arches/thin.cfg", "--tol", "1e-300"}, /* would bisect for ever */
      {"domain --arch arches/thin.cfg", "--max-duration", "0"},
      {"mechanism --arch arches/thin.cfg --table", "--points", "1"},
      {"compare records/a.h5 records/b.h5", "--rtol", "1.5"},
      {"compare records/a.h5 records/b.h5", "--atol", "-1"},
  };
  char d[512], args[2048], out[8192], err[8192], h5[700], txt[700];
  aq_test_tmpdir(d, sizeof d);
  snprintf(h5, sizeof h5, "%s/out.h5", d);
  snprintf(txt, sizeof txt, "%s/out.tsv", d);
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    int main_job = strcmp(cs[k].cmd, RUN) == 0;
    snprintf(args, sizeof args, "%s %s '%s'%s%s%s%s", cs[k].cmd, cs[k].opt, cs[k].value,
             main_job ? " -o " : "", main_job ? h5 : "", main_job ? " --text " : "",
             main_job ? txt : "");
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    char got[128];
    snprintf(got, sizeof got, "got \"%s\"", cs[k].value);
    aq_check(rc == 2, "%s %s: exit 2, got %d", cs[k].opt, cs[k].value, rc);
    aq_check(nlines(err) == 1 && strstr(err, cs[k].opt) && strstr(err, got) &&
                 strstr(err, "expected"),
             "%s %s: one line naming the option, what was expected and the value: %s",
             cs[k].opt, cs[k].value, err);
    aq_check(out[0] == '\0', "%s %s: nothing on stdout: %s", cs[k].opt, cs[k].value, out);
    if (main_job)
      aq_check(access(h5, F_OK) != 0 && access(txt, F_OK) != 0,
               "%s %s: no output file left", cs[k].opt, cs[k].value);
  }
}

/* --scale-to-pga 0.3: the run's pga_g column is 0.3, and its scale is 0.3
 * over the record's processed PGA that `info` reports. */
AQ_TEST(app_scale_to_pga_reaches_the_pga)
{
  char out[8192], err[8192];
  int rc = aq_test_run(RUN " --scale-to-pga 0.3 -j 1", out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "run: exit %d %s", rc, err);
  char *row = strchr(out, '\n');
  double scale = NAN, pga = NAN;
  if (row)
    sscanf(row + 1, "%*s\t%*s\t%*s\t%lf\t%lf", &scale, &pga);
  aq_check_rel(pga, 0.3, 1e-15, "pga_g column");
  rc = aq_test_run("info " REC, out, sizeof out, err, sizeof err);
  row = strchr(out, '\n');
  double pga_rec = NAN;
  if (row)
    sscanf(row + 1, "%*s\t%*s\t%*s\t%*s\t%*s\t%*s\t%lf", &pga_rec);
  /* info prints 6 significant digits */
  aq_check_rel(scale * pga_rec, 0.3, 5e-6, "scale x the record's PGA (%.17g x %g)", scale,
               pga_rec);
}

/* An output named as another kind of file is refused before anything runs:
 * -o writes HDF5 (a results file named out.tsv would be HDF5 under a text
 * name), --text and --fragility write TSV.  Exit 2, one line naming the
 * option, what was expected and the name, no file left; the names that
 * fit (and names without an extension) run. */
AQ_TEST(app_output_names_of_another_kind_refused)
{
  static const struct {
    const char *cmd, *opt, *name;
  } cs[] = {
      {RUN, "-o", "out.tsv"},
      {RUN, "-o", "out.CSV"},
      {RUN, "-o", "out.html"},
      {RUN, "--text", "out.h5"},
      {RUN, "--text", "out.hdf5"},
      {"spectrum " REC, "-o", "out.txt"},
      {"select " REC " --target ec8:type=1,ground=B,ag=0.25 --count 1", "-o", "out.tsv"},
      {"select " REC " --target ec8:type=1,ground=B,ag=0.25 --count 1", "--text", "out.h5"},
      {"capacity " RUN, "--fragility", "out.h5"},
      {"capacity " RUN, "-o", "out.png"},
  };
  char d[512], args[2048], out[8192], err[8192], path[700];
  aq_test_tmpdir(d, sizeof d);
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", d, cs[k].name);
    snprintf(args, sizeof args, "%s %s %s", cs[k].cmd, cs[k].opt, path);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2, "%s %s: exit 2, got %d", cs[k].opt, cs[k].name, rc);
    aq_check(nlines(err) == 1 && strstr(err, cs[k].opt) && strstr(err, cs[k].name) &&
                 strstr(err, "expected"),
             "%s %s: one line naming the option, what was expected and the name: %s",
             cs[k].opt, cs[k].name, err);
    aq_check(access(path, F_OK) != 0, "%s %s: no file left", cs[k].opt, cs[k].name);
  }
  /* the names that fit run */
  char h5[700], txt[700];
  snprintf(h5, sizeof h5, "%s/results", d);
  snprintf(txt, sizeof txt, "%s/rows.txt", d);
  snprintf(args, sizeof args, RUN " -j 1 -o %s --text %s", h5, txt);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "-o without an extension, --text .txt: exit 0, got %d: %s", rc, err);
  aq_check(access(h5, F_OK) == 0 && access(txt, F_OK) == 0, "both files written");
}
