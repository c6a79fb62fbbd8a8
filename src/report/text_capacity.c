/* text_capacity.c: the TSV tables of `archquake capacity` (text_capacity.h). */
#include "text_capacity.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

void aq_text_capacity_intervals(const aq_scan_result *s, char *buf, size_t n)
{
  size_t k = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < s->ninterval && k + 80 < n; i++) {
    char a[40], b[40];
    aq_text_double(a, sizeof a, s->interval[i].lo);
    aq_text_double(b, sizeof b, s->interval[i].hi);
    k += (size_t)snprintf(buf + k, n - k, "%s%s-%s", i ? ";" : "", a, b);
  }
  if (!s->ninterval)
    snprintf(buf, n, "-");
}

int aq_text_capacity(FILE *f, const aq_capacity_row *rows, size_t n)
{
  size_t cap = 1 << 16;
  char *iv = malloc(cap);
  if (!iv)
    return -1;
  fputs("record\tarch\tpolarity\tstatus\tmove_scale\tfirst_collapse_scale\t"
        "first_collapse_pga_g\tfirst_collapse_pgv_m_s\tcollapse_intervals\t"
        "resurrection\truns\tscale_max\tfirst_mark_scale", f);
  int ori = n && rows[0].oriented;
  fputs(ori ? "\tazimuth_deg\tfirst_collapse_scale_min\tfirst_collapse_scale_max\n"
            : "\n", f);
  for (size_t i = 0; i < n; i++) {
    const aq_capacity_row *r = &rows[i];
    const aq_capacity *c = r->cap;
    double fc = c ? c->first_collapse_scale : NAN;
    char v[6][40];
    aq_text_double(v[0], sizeof v[0], c ? c->move_scale : NAN);
    aq_text_double(v[1], sizeof v[1], fc);
    aq_text_double(v[2], sizeof v[2], fc * r->pga_g);
    aq_text_double(v[3], sizeof v[3], fc * r->pgv_mps);
    aq_text_double(v[4], sizeof v[4], c ? c->scale_max : NAN);
    aq_text_double(v[5], sizeof v[5], c ? c->first_mark_scale : NAN);
    if (c)
      aq_text_capacity_intervals(&c->scan, iv, cap);
    else
      snprintf(iv, cap, "-");
    fprintf(f, "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%d\t%zu\t%s\t%s", r->record, r->arch,
            r->polarity, r->status, v[0], v[1], v[2], v[3], iv, c ? c->resurrection : 0,
            c ? c->scan.runs : 0, v[4], v[5]);
    if (ori) {
      char w[3][40];
      aq_text_double(w[0], sizeof w[0], r->azimuth_deg);
      aq_text_double(w[1], sizeof w[1], r->fcs_min);
      aq_text_double(w[2], sizeof w[2], r->fcs_max);
      fprintf(f, "\t%s\t%s\t%s", w[0], w[1], w[2]);
    }
    fputc('\n', f);
  }
  free(iv);
  return ferror(f) ? -1 : 0;
}

double aq_fragility_row_ranked(const char *im, double beta)
{
  int which = AQ_FRAGILITY_NIM; /* a spectral measure */
  for (int m = 0; m < AQ_FRAGILITY_NIM; m++)
    if (im && strcmp(im, aq_fragility_im_names[m]) == 0)
      which = m;
  return beta / aq_fragility_im_power(which);
}

int aq_text_fragility(FILE *f, const aq_fragility_row *rows, size_t n)
{
  fputs("arch\tim\trecords\tcensored\tmedian\tbeta\tmedian_lo\tmedian_hi\trank\t"
        "beta_per_power\tmarked\n", f);
  for (size_t i = 0; i < n; i++) {
    const aq_fragility *fit = rows[i].fit;
    char v[4][40];
    aq_text_double(v[0], sizeof v[0], fit->median);
    aq_text_double(v[1], sizeof v[1], fit->beta);
    aq_text_double(v[2], sizeof v[2], fit->median_lo);
    aq_text_double(v[3], sizeof v[3], fit->median_hi);
    fprintf(f, "%s\t%s\t%zu\t%zu\t%s\t%s\t%s\t%s\t", rows[i].arch, rows[i].im, fit->n,
            fit->ncensored, v[0], v[1], v[2], v[3]);
    if (fit->rank > 0)
      fprintf(f, "%d\t", fit->rank);
    else
      fputs("nan\t", f);
    fprintf(f, "%s\t%zu\n", AQ_TEXT_NUM(aq_fragility_row_ranked(rows[i].im, fit->beta)),
            fit->nmarked);
  }
  return ferror(f) ? -1 : 0;
}
