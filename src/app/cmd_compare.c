/* cmd_compare.c: `archquake compare A.h5 B.h5 [--rtol R] [--atol A]
 * [--ignore NAME]...`: compare two results files, configuration first, then
 * run by run, matched by identity (report/compare.h).  Differences go to
 * stdout as TSV (record arch scale polarity field a b rel_diff), one row
 * each, and a one-line count to stderr. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../report/compare.h"
#include "../report/h5_capacity.h"
#include "../report/h5.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"

/* Defaults: a nightly rerun of the same build reproduces every value
 * exactly; 1e-9 leaves room only for a different compiler or libm. */
#define AQ_COMPARE_RTOL_DEFAULT 1e-9
#define AQ_COMPARE_ATOL_DEFAULT 0.0

static const char usage[] =
    "usage: archquake compare A.h5 B.h5 [--rtol R] [--atol A] [--ignore NAME]...\n"
    "Compare two results files (archquake ... -o FILE.h5).  First their\n"
    "configuration: processing options, model, cor, version (shown only), and\n"
    "the content (sha256) of records and arches of one name.  Then run by run,\n"
    "matched by identity: the record's content, the arch's name and .cfg\n"
    "content, the scale and the polarity (however the files were spelt on the\n"
    "command line).  Numbers agree when |a-b| <= A + R*max(|a|,|b|) (NaN equals\n"
    "NaN); collapsed, impacts, model and status must be equal.\n"
    "  --rtol R       relative tolerance (default 1e-9)\n"
    "  --atol A       absolute tolerance in each field's units (default 0)\n"
    "  --ignore NAME  leave out a setting or a field (repeatable, or a comma\n"
    "                 list), e.g. --ignore model to compare two models' numbers;\n"
    "                 record_sha256 / arch_sha256 match records by file name /\n"
    "                 arches by name alone\n"
    "  --help         this text\n"
    "Each difference is a TSV row on stdout: record arch scale polarity field a b\n"
    "rel_diff.  Configuration rows come first, with * for what they are not\n"
    "about (field = the setting, record_sha256 or arch_sha256); field \"present\"\n"
    "marks a run found in only one file.  Records are named by file name.  A file\n"
    "of the first format (no hashes) is read too: records and arches then match\n"
    "by name.\n"
    "Exit status: 0 all runs and settings agree (a different version alone is\n"
    "shown but agrees), 1 some differ, 2 bad options or a file that cannot be\n"
    "read as a results file.\n";

#define AQ_COMPARE_IGNORE_MAX 32

typedef struct {
  FILE *out;
} sink;

/* A text cell as the main job's TSV writes it: tab, CR and LF (possible in
 * a record's file name) become spaces, so that a row stays one line of the
 * header's columns. */
static void put_cell(FILE *f, const char *s)
{
  for (; *s; s++)
    fputc(*s == '\t' || *s == '\n' || *s == '\r' ? ' ' : *s, f);
}

static void put_value(FILE *f, const aq_summary *s, const aq_summary_field *fl)
{
  char num[64];
  switch (fl->kind) {
  case AQ_SF_STR:
    put_cell(f, aq_summary_get_str(s, fl));
    break;
  case AQ_SF_DOUBLE:
    aq_text_double(num, sizeof num, aq_summary_get_double(s, fl));
    fputs(num, f);
    break;
  case AQ_SF_INT:
    aq_text_int(num, sizeof num, aq_summary_get_int(s, fl));
    fputs(num, f);
    break;
  }
}

static void on_diff(void *ctx, const aq_diff *d)
{
  FILE *f = ((sink *)ctx)->out;
  if (d->kind == AQ_DIFF_CONFIG) {
    put_cell(f, d->record ? d->record : "*");
    fputc('\t', f);
    put_cell(f, d->arch ? d->arch : "*");
    fprintf(f, "\t*\t*\t%s\t", d->name);
    put_cell(f, d->va);
    fputc('\t', f);
    put_cell(f, d->vb);
    fputs("\tnan\n", f);
    return;
  }
  const aq_summary *r = d->a ? d->a : d->b;
  char num[64], rel[64];
  aq_text_double(num, sizeof num, r->scale);
  put_cell(f, d->record);
  fputc('\t', f);
  put_cell(f, d->arch);
  fprintf(f, "\t%s\t%s\t", num, r->polarity);
  if (d->kind == AQ_DIFF_VALUE) {
    fprintf(f, "%s\t", d->field->name);
    put_value(f, d->a, d->field);
    fputc('\t', f);
    put_value(f, d->b, d->field);
    aq_text_double(rel, sizeof rel, d->rel);
    fprintf(f, "\t%s\n", rel);
  } else {
    fprintf(f, "present\t%s\t%s\tnan\n", d->a ? "yes" : "no",
            d->b ? "yes" : "no");
  }
}

/* A capacity difference as a row: scale nan (a capacity row is about every
 * scale), the field prefixed "capacity/". */
static void on_capacity_diff(void *ctx, const aq_h5_capacity_diff *d)
{
  FILE *f = ctx;
  const aq_h5_capacity_row *r = d->a ? d->a : d->b;
  char rel[64];
  put_cell(f, r->record);
  fputc('\t', f);
  put_cell(f, r->arch);
  fprintf(f, "\tnan\t%s\t", r->polarity);
  if (d->field) {
    aq_text_double(rel, sizeof rel, d->rel);
    fprintf(f, "capacity/%s\t%s\t%s\t%s\n", d->field, d->a_text, d->b_text, rel);
  } else {
    fprintf(f, "capacity/present\t%s\t%s\tnan\n", d->a ? "yes" : "no",
            d->b ? "yes" : "no");
  }
}

/* The capacity groups of a and b (docs/capacity.md): the number of
 * differences (a group in one file only counts one), or (size_t)-2 when a
 * group cannot be read (reported). */
static size_t compare_capacity(const char *a, const char *b, double rtol, double atol)
{
  aq_h5_capacity_table t[2];
  int present[2] = {0, 0};
  aq_error err;
  size_t nd = 0;
  for (int k = 0; k < 2; k++)
    if (aq_h5_capacity_read(k ? b : a, &t[k], &present[k], &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      if (k)
        aq_h5_capacity_table_free(&t[0]);
      return (size_t)-2;
    }
  if (present[0] != present[1]) {
    printf("capacity\t-\tnan\t-\tcapacity/present\t%s\t%s\tnan\n", present[0] ? "yes" : "no",
           present[1] ? "yes" : "no");
    nd = 1;
  } else if (present[0]) {
    nd = aq_h5_capacity_compare(&t[0], &t[1], rtol, atol, on_capacity_diff, stdout);
  }
  aq_h5_capacity_table_free(&t[0]);
  aq_h5_capacity_table_free(&t[1]);
  return nd;
}

int aq_cmd_compare(int argc, char **argv)
{
  static const struct option longopts[] = {
      {"rtol", required_argument, NULL, 'r'},
      {"atol", required_argument, NULL, 'a'},
      {"ignore", required_argument, NULL, 'i'},
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  double rtol = AQ_COMPARE_RTOL_DEFAULT, atol = AQ_COMPARE_ATOL_DEFAULT;
  int nerr = 0, c;
  char ignore_buf[AQ_COMPARE_IGNORE_MAX][64];
  const char *ignore[AQ_COMPARE_IGNORE_MAX];
  size_t nignore = 0;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
    switch (c) {
    case 'r':
      aq_opt_double("--rtol", optarg, 0, 1, &rtol, &nerr);
      break;
    case 'a':
      aq_opt_double("--atol", optarg, 0, HUGE_VAL, &atol, &nerr);
      break;
    case 'i':
      for (const char *p = optarg; *p;) {
        size_t len = strcspn(p, ",");
        if (len == 0 || len >= sizeof ignore_buf[0] || nignore == AQ_COMPARE_IGNORE_MAX) {
          fprintf(stderr, "archquake: compare: --ignore: expected up to %d names of "
                          "settings or fields, comma-separated, got \"%s\"\n",
                  AQ_COMPARE_IGNORE_MAX, optarg);
          nerr++;
          break;
        }
        snprintf(ignore_buf[nignore], sizeof ignore_buf[0], "%.*s", (int)len, p);
        ignore[nignore] = ignore_buf[nignore];
        nignore++;
        p += len + (p[len] == ',');
      }
      break;
    case 'h':
      fputs(usage, stdout);
      return AQ_EXIT_OK;
    default:
      aq_opt_unknown("compare", argv, optind, optopt, &nerr);
    }
  }
  if (argc - optind != 2) {
    fprintf(stderr,
            "archquake: compare: expected two results files A.h5 B.h5, got %d\n",
            argc - optind);
    nerr++;
  }
  if (nerr)
    return AQ_EXIT_USAGE;

  aq_h5_suite suite[2];
  memset(suite, 0, sizeof suite);
  int bad = 0;
  for (int k = 0; k < 2; k++) {
    aq_error err;
    aq_error_clear(&err);
    if (aq_h5_read_suite(argv[optind + k], &suite[k], &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      bad = 1;
    }
  }
  if (bad) {
    aq_h5_suite_free(&suite[0]);
    aq_h5_suite_free(&suite[1]);
    return AQ_EXIT_USAGE;
  }
  sink s = {stdout};
  printf("record\tarch\tscale\tpolarity\tfield\ta\tb\trel_diff\n");
  aq_compare_opts co = {rtol, atol, ignore, nignore};
  size_t nd = aq_compare_suites(&suite[0], &suite[1], &co, on_diff, &s);
  size_t n[2] = {suite[0].nruns, suite[1].nruns};
  aq_h5_suite_free(&suite[0]);
  aq_h5_suite_free(&suite[1]);
  size_t ncd = compare_capacity(argv[optind], argv[optind + 1], rtol, atol);
  if (ncd == (size_t)-2)
    return AQ_EXIT_USAGE;
  if (nd != (size_t)-1)
    nd += ncd;
  if (fflush(stdout) != 0 || ferror(stdout)) {
    fprintf(stderr, "archquake: compare: cannot write the differences\n");
    return AQ_EXIT_USAGE;
  }
  if (nd == (size_t)-1) {
    fprintf(stderr, "archquake: compare: out of memory\n");
    return AQ_EXIT_USAGE;
  }
  fprintf(stderr, "archquake: compare: %zu runs in %s, %zu in %s: %zu difference%s\n",
          n[0], argv[optind], n[1], argv[optind + 1], nd, nd == 1 ? "" : "s");
  return nd ? AQ_EXIT_FAIL : AQ_EXIT_OK;
}
