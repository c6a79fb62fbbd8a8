/* test_io_expand_names.c: aq_record_expand names records without reading
 * text records whole; the names must be those a full parse gives: every
 * file of tests/data/records, its agency/ and records/, with and without a
 * --component rule, against the names made here from aq_raw_parse of the
 * whole file (FILE#CHANNEL, or FILE#N for an unnamed channel, for each
 * channel of a file of several; the name as given otherwise, and for a file
 * that does not parse); and generated multi-column files, good and bad,
 * against the column names written. */
#include <dirent.h>
#include <fnmatch.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "io/record.h"

/* The names a full parse gives path (want, *nwant; each want[i] 4200 bytes). */
static size_t full_parse_names(const char *path, const aq_read_opts *ro, char (*want)[4200],
                               size_t max)
{
  size_t n = 0;
  char *b = aq_test_read_file(path, &n);
  aq_raw_file raw;
  aq_error e;
  memset(&raw, 0, sizeof raw);
  int rule = 0;
  for (size_t r = 0; ro && r < ro->ncomponents; r++)
    rule |= fnmatch(ro->components[r].glob, path, 0) == 0;
  size_t k = 0;
  if (b) {
    aq_format fmt = aq_sniff_format((const unsigned char *)b, n);
    if (fmt != AQ_FMT_SAC && fmt != AQ_FMT_AT2 && fmt != AQ_FMT_KNET &&
        aq_raw_parse((const unsigned char *)b, n, path, ro, &raw, &e) != AQ_OK)
      memset(&raw, 0, sizeof raw);
  }
  if (raw.nchan > 1 && rule) {
    snprintf(want[k++], 4200, "%s#%s", path, ro->components[ro->ncomponents - 1].channel);
  } else if (raw.nchan > 1) {
    for (size_t c = 0; c < raw.nchan && k < max; c++)
      if (raw.chan[c].channel[0])
        snprintf(want[k++], 4200, "%s#%s", path, raw.chan[c].channel);
      else
        snprintf(want[k++], 4200, "%s#%zu", path, c + 1);
  } else {
    snprintf(want[k++], 4200, "%s", path);
  }
  aq_raw_file_free(&raw);
  free(b);
  return k;
}

static size_t compare_dir(const char *dir, const aq_read_opts *ro, size_t *multi)
{
  static char want[64][4200];
  DIR *d = opendir(dir);
  size_t files = 0;
  if (!aq_check(d != NULL, "open %s", dir))
    return 0;
  struct dirent *de;
  while ((de = readdir(d))) {
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
      continue;
    files++;
    size_t nw = full_parse_names(path, ro, want, 64);
    char *paths[1] = {path}, **names = NULL;
    size_t nn = 0;
    aq_error e;
    if (!aq_check(aq_record_expand(paths, 1, ro, &names, &nn, &e) == AQ_OK, "%s: %s", path,
                  e.message))
      continue;
    *multi += nn > 1;
    if (aq_check(nn == nw, "%s: %zu names, a full parse gives %zu", path, nn, nw))
      for (size_t i = 0; i < nn; i++)
        aq_check(strcmp(names[i], want[i]) == 0, "%s: name %zu \"%s\", want \"%s\"", path, i,
                 names[i], want[i]);
    aq_record_names_free(names, nn);
  }
  closedir(d);
  return files;
}

AQ_TEST(io_expand_names_as_a_full_parse)
{
  static const char *const dirs[] = {"tests/data/records", "tests/data/records/agency",
                                     "records"};
  aq_read_opts rule = {0};
  snprintf(rule.components[0].glob, sizeof rule.components[0].glob, "*");
  snprintf(rule.components[0].channel, sizeof rule.components[0].channel, "EW");
  rule.ncomponents = 1;
  for (int way = 0; way < 2; way++) {
    size_t files = 0, multi = 0;
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++)
      files += compare_dir(dirs[i], way ? &rule : NULL, &multi);
    aq_check(files >= 60, "%zu files", files);
    if (!way) /* Q4149CF2.csv (3), the COSMOS and ESM files of several */
      aq_check(multi >= 2, "%zu files of several channels", multi);
    if (getenv("AQ_TEST_VERBOSE"))
      printf("  %s: %zu files, %zu named per channel\n", way ? "rule *=EW" : "no rule", files,
             multi);
  }
}

/* Generated text of three columns NS,EW,UD: named per column when all rows
 * read, by its name alone when a row does not. */
AQ_TEST(io_expand_text_of_several_columns)
{
  char dir[512], path[600], text[4096];
  aq_test_tmpdir(dir, sizeof dir);
  static const struct {
    const char *tail; /* after the good rows */
    int rule, column;
    const char *want[3];
  } c[] = {
      {"", 0, 0, {"#NS", "#EW", "#UD"}},
      {"0.1,0.2,x\n", 0, 0, {""}},     /* a bad value: the name as given */
      {"0.1,0.2\n", 0, 0, {""}},       /* a short row */
      {"", 1, 0, {"#EW"}},             /* --component '*=EW' */
      {"1e999,0,0\n", 1, 0, {""}},      /* rule, bad row */
      {"", 0, 2, {""}},                /* --column 2: one channel */
      {"0.1,0.2,0.3,0.4\n", 0, 2, {""}}, /* one channel, a bad row */
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    snprintf(path, sizeof path, "%s/three%zu.csv", dir, i);
    size_t p = (size_t)snprintf(text, sizeof text, "SAMPLING RATE= 100Hz\nNS,EW,UD\n");
    for (int k = 0; k < 50; k++)
      p += (size_t)snprintf(text + p, sizeof text - p, "%.4f,%.4f,%.4f\n", 0.01 * k,
                            -0.02 * k, 0.005 * k);
    snprintf(text + p, sizeof text - p, "%s", c[i].tail);
    FILE *f = fopen(path, "wb");
    if (!aq_check(f && fputs(text, f) >= 0 && fclose(f) == 0, "write %s", path))
      continue;
    aq_read_opts ro = {0};
    if (c[i].rule) {
      snprintf(ro.components[0].glob, sizeof ro.components[0].glob, "*three*");
      snprintf(ro.components[0].channel, sizeof ro.components[0].channel, "EW");
      ro.ncomponents = 1;
    }
    ro.column = (size_t)c[i].column;
    char *paths[1] = {path}, **names = NULL;
    size_t nn = 0, nw = 0;
    while (nw < 3 && c[i].want[nw])
      nw++;
    aq_error e;
    if (!aq_check(aq_record_expand(paths, 1, &ro, &names, &nn, &e) == AQ_OK, "case %zu: %s",
                  i, e.message))
      continue;
    if (aq_check(nn == nw, "case %zu: %zu names, want %zu", i, nn, nw))
      for (size_t k = 0; k < nn; k++) {
        char w[700];
        snprintf(w, sizeof w, "%s%s", path, c[i].want[k]);
        aq_check(strcmp(names[k], w) == 0, "case %zu: \"%s\", want \"%s\"", i, names[k], w);
      }
    aq_record_names_free(names, nn);
  }
}
