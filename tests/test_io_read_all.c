/* test_io_read_all.c: aq_record_read_all reads every channel of a file from
 * one parse.  Against the other way of reading the same operands,
 * aq_record_expand then aq_record_read of each name: the same names in the
 * same order, the same status and message for each, and the same record
 * (format, npts, dt, start, channel, vertical, units and every sample bit
 * for bit), over every file of tests/data/records, agency/ and agency2/,
 * with and without a --component rule and as FILE#CHANNEL; and the parses
 * counted (aq_record_parses_): one per file for aq_record_read_all, one and
 * then one per channel the other way (four for three channels). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "io/record.h"

static int same_record(const aq_record *a, const aq_record *b)
{
  if (strcmp(a->path, b->path) || strcmp(a->format, b->format) || a->npts != b->npts ||
      memcmp(&a->dt_s, &b->dt_s, sizeof a->dt_s) || strcmp(a->reference, b->reference) ||
      strcmp(a->channel, b->channel) || a->vertical != b->vertical ||
      strcmp(a->units_used, b->units_used) || strcmp(a->units_conflict, b->units_conflict))
    return 0;
  return memcmp(a->acc_mps2, b->acc_mps2, a->npts * sizeof *a->acc_mps2) == 0;
}

/* Operand path both ways; returns the number of records compared. */
static size_t compare(const char *path, const aq_read_opts *ro)
{
  aq_record_set set;
  aq_error e;
  if (!aq_check(aq_record_read_all(path, ro, 0, &set, &e) == AQ_OK, "%s: %s", path, e.message))
    return 0;
  char **names = NULL;
  size_t nn = 0;
  char *one[1] = {(char *)path};
  if (!aq_check(aq_record_expand(one, 1, ro, &names, &nn, &e) == AQ_OK, "expand %s", path)) {
    aq_record_set_free(&set);
    return 0;
  }
  aq_check(nn == set.n, "%s: %zu names, read_all %zu records", path, nn, set.n);
  for (size_t i = 0; i < nn && i < set.n; i++) {
    aq_record r;
    aq_error re;
    aq_error_clear(&re);
    aq_status s = aq_record_read(names[i], ro, &r, &re);
    const aq_record_item *it = &set.item[i];
    aq_check(strcmp(names[i], it->name) == 0, "%s: name %s, read_all %s", path, names[i],
             it->name);
    aq_check(s == it->status, "%s: status %d, read_all %d", names[i], (int)s, (int)it->status);
    if (s == AQ_OK && it->status == AQ_OK)
      aq_check(same_record(&r, &it->rec), "%s: the same record", names[i]);
    else if (s != AQ_OK && it->status != AQ_OK)
      aq_check(strcmp(re.message, it->err.message) == 0 && strcmp(re.input, it->err.input) == 0,
               "%s: \"%s\", read_all \"%s\"", names[i], re.message, it->err.message);
    aq_record_free(&r);
  }
  size_t n = set.n;
  aq_record_names_free(names, nn);
  aq_record_set_free(&set);
  return n;
}

static size_t compare_dir(const char *dir, const aq_read_opts *ro)
{
  DIR *d = opendir(dir);
  size_t n = 0;
  if (!aq_check(d != NULL, "open %s", dir))
    return 0;
  struct dirent *de;
  while ((de = readdir(d))) {
    char path[1024];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    if (de->d_name[0] == '.' || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
      continue;
    n += compare(path, ro);
  }
  closedir(d);
  return n;
}

AQ_TEST(io_read_all_equals_expand_then_read)
{
  static const char *const dirs[] = {"tests/data/records", "tests/data/records/agency",
                                     "tests/data/records/agency2"};
  aq_read_opts none = {0}, rule = {0};
  rule.ncomponents = 1;
  snprintf(rule.components[0].glob, sizeof rule.components[0].glob, "*");
  snprintf(rule.components[0].channel, sizeof rule.components[0].channel, "EW");
  size_t n = 0;
  for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
    n += compare_dir(dirs[i], &none);
    n += compare_dir(dirs[i], &rule);
  }
  n += compare("tests/data/records/Q4149CF2.csv#UD", &none);
  n += compare("tests/data/records/agency/CE89146.V1#up", &none);
  n += compare("tests/data/records/no-such-file.AT2", &none);
  aq_check(n > 100, "%zu records compared", n);
}

/* Parses counted: a file of three channels, one way and the other. */
AQ_TEST(io_read_all_parses_once)
{
  static const char *const files[] = {"tests/data/records/Q4149CF2.csv",
                                      "tests/data/records/agency/CE89146.V1",
                                      "tests/data/records/agency/NP1795-n.305.v0c"};
  for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
    aq_record_set set;
    aq_error e;
    unsigned long p0 = aq_record_parses_();
    if (!aq_check(aq_record_read_all(files[f], NULL, 1, &set, &e) == AQ_OK, "%s", files[f]))
      continue;
    unsigned long p1 = aq_record_parses_();
    aq_check(p1 - p0 == 1 && set.n == 3, "%s: %zu records from %lu parses", files[f], set.n,
             p1 - p0);
    struct stat st;
    aq_check(set.bytes && stat(files[f], &st) == 0 && (size_t)st.st_size == set.nbytes,
             "%s: the file's %zu bytes kept", files[f], set.nbytes);
    aq_record_set_free(&set);
    char **names;
    size_t nn;
    char *one[1] = {(char *)files[f]};
    unsigned long q0 = aq_record_parses_();
    if (aq_record_expand(one, 1, NULL, &names, &nn, &e) != AQ_OK)
      continue;
    for (size_t i = 0; i < nn; i++) {
      aq_record r;
      if (aq_record_read(names[i], NULL, &r, &e) == AQ_OK)
        aq_record_free(&r);
    }
    aq_record_names_free(names, nn);
    unsigned long q1 = aq_record_parses_();
    aq_check(q1 - q0 == 4, "%s: expand then read: %lu parses (want 4)", files[f], q1 - q0);
  }
}
