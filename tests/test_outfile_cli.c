/* Outputs that fail part way leave nothing: `plot` and `report` write
 * through util/outfile.h, so a figure whose data file (--data) cannot be
 * written is not left behind, a target that is a directory is refused in
 * one line, and no temporary ("<target>.tmp.<pid>", a report's figure
 * "<target>.fig.<pid>.svg") stays beside the target.  The directory is
 * listed here after each command: it must hold what the test put there
 * and nothing more. */
#include <dirent.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"

#define RECORD "tests/data/records/ARL360.at2"
#define ARCH "arches/oppenheim.cfg"

/* Entries of dir other than "." and ".."; the first one not in keep[nkeep]
 * into odd[cap] ("" if none). */
static int entries(const char *dir, const char *const *keep, size_t nkeep, char *odd,
                   size_t cap)
{
  int n = 0;
  odd[0] = '\0';
  DIR *d = opendir(dir);
  if (!d)
    return -1;
  for (struct dirent *e; (e = readdir(d));) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
      continue;
    n++;
    int known = 0;
    for (size_t k = 0; k < nkeep; k++)
      known |= !strcmp(e->d_name, keep[k]);
    if (!known && !odd[0])
      snprintf(odd, cap, "%s", e->d_name);
  }
  closedir(d);
  return n;
}

static void sub(char *out, size_t cap, const char *dir, const char *name)
{
  if (snprintf(out, cap, "%s/%s", dir, name) >= (int)cap)
    out[0] = '\0';
}

AQ_TEST(outfile_plot_data_failing_leaves_no_figure)
{
  char dir[512], data[600], fig[600], args[2048], err[2048], odd[256];
  aq_test_tmpdir(dir, sizeof dir);
  sub(data, sizeof data, dir, "d.csv");
  sub(fig, sizeof fig, dir, "fig.png");
  mkdir(data, 0755); /* the data's target is a directory: the data cannot be written */
  snprintf(args, sizeof args, "plot arch --arch " ARCH " -o %s --data %s", fig, data);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, "d.csv") &&
               strstr(err, "directory"),
           "exit %d (want 3), one line naming d.csv: %s", rc, err);
  const char *keep[] = {"d.csv"};
  int n = entries(dir, keep, 1, odd, sizeof odd);
  aq_check(n == 1, "the directory holds only d.csv, got %d entries (e.g. %s)", n, odd);
  /* the same with the data's directory fine: both written */
  sub(data, sizeof data, dir, "ok.csv");
  snprintf(args, sizeof args, "plot arch --arch " ARCH " -o %s --data %s", fig, data);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  struct stat sf, sd;
  aq_check(rc == 0 && stat(fig, &sf) == 0 && sf.st_size > 0 && stat(data, &sd) == 0 &&
               sd.st_size > 0,
           "exit %d, figure and data written: %s", rc, err);
  const char *keep2[] = {"d.csv", "ok.csv", "fig.png"};
  n = entries(dir, keep2, 3, odd, sizeof odd);
  aq_check(n == 3 && !odd[0], "no temporary beside them: %d entries (e.g. %s)", n, odd);
}

AQ_TEST(outfile_plot_figure_target_a_directory)
{
  char dir[512], data[600], fig[600], args[2048], err[2048], odd[256];
  aq_test_tmpdir(dir, sizeof dir);
  sub(data, sizeof data, dir, "d.csv");
  sub(fig, sizeof fig, dir, "fig.svg");
  mkdir(fig, 0755);
  snprintf(args, sizeof args, "plot arch --arch " ARCH " -o %s --data %s", fig, data);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, "fig.svg") &&
               strstr(err, "got a directory"),
           "exit %d (want 3), one line: %s", rc, err);
  const char *keep[] = {"fig.svg"};
  int n = entries(dir, keep, 1, odd, sizeof odd);
  aq_check(n == 1, "no data file, no temporary: %d entries (e.g. %s)", n, odd);
}

AQ_TEST(outfile_report_failing_at_the_end_leaves_nothing)
{
  char dir[512], out[600], h5[600], page[700], args[2048], err[2048], odd[256];
  aq_test_tmpdir(dir, sizeof dir);
  sub(h5, sizeof h5, dir, "r.h5");
  snprintf(args, sizeof args, RECORD " --arch " ARCH " --scale 5 -o %s", h5);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "results: %s", err);
  sub(out, sizeof out, dir, "out");
  mkdir(out, 0755);
  sub(page, sizeof page, out, "page.html");
  mkdir(page, 0755); /* the page's figures are drawn beside it, then it cannot be written */
  snprintf(args, sizeof args, "report %s -o %s", h5, page);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, "page.html") &&
               strstr(err, "directory"),
           "exit %d (want 3), one line naming page.html: %s", rc, err);
  const char *keep[] = {"page.html"};
  int n = entries(out, keep, 1, odd, sizeof odd);
  aq_check(n == 1, "no file, no temporary, no figure beside it: %d entries (e.g. %s)", n,
           odd);
  aq_check(entries(page, NULL, 0, odd, sizeof odd) == 0, "the directory untouched (%s)", odd);
}
