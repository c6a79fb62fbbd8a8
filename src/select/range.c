/* range.c: the period range of a selection for an arch (range.h). */
#define _POSIX_C_SOURCE 200809L
#include "range.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/number.h"

#define FRAGILITY_HEADER "arch\tim\trecords\tcensored\tmedian\tbeta\tmedian_lo\tmedian_hi\trank"
#define SA_SPAN_LO 0.2 /* Sa(T): 0.2 T to 2 T */
#define SA_SPAN_HI 2.0

/* A number at s that ends at a character of stop; the characters taken. */
static size_t num(const char *s, const char *stop, double *x)
{
  size_t len = strcspn(s, stop);
  return len && aq_number_parse_finite(s, len, 0, x) == len ? len : 0;
}

int aq_select_range_of_im(const char *im, double *t1_s, double *t2_s)
{
  double a, b;
  size_t k;
  if (!strncmp(im, "sa_avg_", 7)) {
    const char *p = im + 7;
    if (!(k = num(p, "_", &a)) || p[k] != '_')
      return 0;
    p += k + 1;
    if (!(k = num(p, "s", &b)) || strcmp(p + k, "s_g") != 0 || !(a > 0 && a < b))
      return 0;
    *t1_s = a;
    *t2_s = b;
    return 1;
  }
  if (!strncmp(im, "sa_", 3)) {
    const char *p = im + 3;
    if (!(k = num(p, "s", &a)) || strcmp(p + k, "s_g") != 0 || !(a > 0))
      return 0;
    *t1_s = SA_SPAN_LO * a;
    *t2_s = SA_SPAN_HI * a;
    return 1;
  }
  return 0;
}

aq_status aq_select_range_from_fragility(const char *path, const char *arch, double *t1_s,
                                         double *t2_s, char *im, size_t nim, aq_error *err)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, "--fragility",
                        "expected a fragility file of archquake capacity, got a file that "
                        "cannot be read");
  char line[1024], first_arch[256] = "", best_im[128] = "";
  long ln = 0, best_rank = 0;
  int several = 0, seen = 0;
  aq_status st = AQ_OK;
  while (st == AQ_OK && fgets(line, sizeof line, f)) {
    ln++;
    line[strcspn(line, "\r\n")] = '\0';
    if (ln == 1) {
      if (strcmp(line, FRAGILITY_HEADER) != 0)
        st = aq_error_set(err, AQ_EFORMAT, path, 1, -1, "--fragility",
                          "expected the header of capacity --fragility (arch im records "
                          "censored median beta median_lo median_hi rank), got \"%.60s\"",
                          line);
      continue;
    }
    char *fld[9];
    size_t nf = 0;
    for (char *p = line; nf < 9; p++) {
      fld[nf++] = p;
      p += strcspn(p, "\t");
      if (!*p)
        break;
      *p = '\0';
    }
    if (nf != 9) {
      st = aq_error_set(err, AQ_EFORMAT, path, ln, -1, NULL,
                        "expected 9 tab-separated fields, got %zu", nf);
      break;
    }
    if (!first_arch[0])
      snprintf(first_arch, sizeof first_arch, "%s", fld[0]);
    else if (strcmp(first_arch, fld[0]) != 0)
      several = 1;
    if (arch ? strcmp(arch, fld[0]) != 0 : strcmp(first_arch, fld[0]) != 0)
      continue;
    seen = 1;
    double a, b;
    char *end;
    long rank = strtol(fld[8], &end, 10);
    if (*end || rank <= 0 || !aq_select_range_of_im(fld[1], &a, &b))
      continue; /* not fitted, or not spectral */
    if (!best_rank || rank < best_rank) {
      best_rank = rank;
      snprintf(best_im, sizeof best_im, "%s", fld[1]);
      *t1_s = a;
      *t2_s = b;
    }
  }
  if (st == AQ_OK && ferror(f))
    st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "read error");
  fclose(f);
  if (st != AQ_OK)
    return st;
  if (ln < 1)
    return aq_error_set(err, AQ_EFORMAT, path, -1, -1, "--fragility",
                        "expected a fragility file of archquake capacity, got an empty file");
  if (!arch && several)
    return aq_error_set(err, AQ_EVALUE, path, -1, -1, "--fragility-arch",
                        "expected --fragility-arch NAME: the file holds several arches (\"%s\" "
                        "first)",
                        first_arch);
  if (!seen)
    return aq_error_set(err, AQ_EVALUE, path, -1, -1, "--fragility-arch",
                        "expected an arch of the file, got \"%s\"", arch ? arch : "");
  if (!best_rank)
    return aq_error_set(err, AQ_EVALUE, path, -1, -1, "--fragility",
                        "expected a fitted spectral measure (sa_... with a rank) of arch "
                        "\"%s\", got none (run capacity with --im-periods or --sa-avg)",
                        arch ? arch : first_arch);
  snprintf(im, nim, "%s", best_im);
  return AQ_OK;
}
