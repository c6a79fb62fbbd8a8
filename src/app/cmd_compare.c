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
#include "opt_table.h"

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
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_COMPARE);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_COMPARE, argc, argv, &o, &nerr))
    return AQ_EXIT_OK; /* --help */
  double rtol = o.rtol, atol = o.atol;
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
  aq_compare_opts co = {rtol, atol, o.ignore, o.nignore};
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
