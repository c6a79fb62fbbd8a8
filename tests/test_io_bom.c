/* test_io_bom.c: a UTF-8 byte-order mark before a text record, as Excel
 * and other spreadsheets write one, is skipped by every text reader: each
 * text record shipped under records/ and tests/data/records/ (every format
 * archquake reads as text), with a byte-order mark put before it, parses
 * to the same channels, counts, intervals, units and samples, bit for bit,
 * and sniffs as the same format.  A byte-order mark before binary data is
 * not stripped. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "io/reader.h"
#include "io/record.h"
#include "io/sniff.h"

static int same_channels(const aq_raw_file *a, const aq_raw_file *b)
{
  if (a->nchan != b->nchan || strcmp(a->format, b->format))
    return 0;
  for (size_t c = 0; c < a->nchan; c++) {
    const aq_raw_channel *x = &a->chan[c], *y = &b->chan[c];
    if (x->npts != y->npts || x->dt_s != y->dt_s || strcmp(x->units, y->units) ||
        strcmp(x->channel, y->channel) ||
        (x->npts && memcmp(x->values, y->values, x->npts * sizeof *x->values)))
      return 0;
  }
  return 1;
}

/* Every regular file under dir: the text records read alike with a BOM. */
static void walk(const char *dir, int *ntext, int *nsame)
{
  DIR *d = opendir(dir);
  if (!d)
    return;
  struct dirent *de;
  while ((de = readdir(d))) {
    char path[1024];
    struct stat sb;
    if (de->d_name[0] == '.')
      continue;
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    if (stat(path, &sb) != 0)
      continue;
    if (S_ISDIR(sb.st_mode)) {
      walk(path, ntext, nsame);
      continue;
    }
    size_t n = 0;
    unsigned char *buf = (unsigned char *)aq_test_read_file(path, &n);
    aq_format f = buf ? aq_sniff_format(buf, n) : AQ_FMT_EMPTY;
    if (!buf || !aq_sniff_is_text(f) || f == AQ_FMT_XML ||
        (n >= 3 && !memcmp(buf, "\xEF\xBB\xBF", 3))) {
      free(buf);
      continue;
    }
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.dt_s = 0.01; /* for text that states no interval */
    aq_raw_file a, b;
    aq_error e;
    aq_error_clear(&e);
    if (aq_raw_parse(buf, n, path, &ro, &a, &e) != AQ_OK) { /* not a record as read */
      free(buf);
      continue;
    }
    unsigned char *bom = malloc(n + 3);
    memcpy(bom, "\xEF\xBB\xBF", 3);
    memcpy(bom + 3, buf, n);
    aq_status st = aq_raw_parse(bom, n + 3, path, &ro, &b, &e);
    (*ntext)++;
    int same = st == AQ_OK && same_channels(&a, &b);
    *nsame += same;
    aq_check(same && aq_sniff_format(bom, n + 3) == f,
             "%s with a byte-order mark: %s", path, st == AQ_OK ? "read otherwise" : e.message);
    aq_raw_file_free(&a);
    if (st == AQ_OK)
      aq_raw_file_free(&b);
    free(bom);
    free(buf);
  }
  closedir(d);
}

AQ_TEST(io_bom_skipped_by_every_text_reader)
{
  int ntext = 0, nsame = 0;
  walk("records", &ntext, &nsame);
  walk("tests/data/records", &ntext, &nsame);
  aq_check(ntext >= 40 && nsame == ntext, "%d of %d text records read alike with a BOM", nsame,
           ntext);
  /* a BOM before SAC's binary header: not taken for text, not stripped */
  size_t n = 0;
  unsigned char *sac = (unsigned char *)aq_test_read_file(
      "records/CI.CLC..HNE.D.2019.187.031923.SAC", &n);
  if (aq_check(sac != NULL, "the SAC record")) {
    unsigned char *bom = malloc(n + 3);
    memcpy(bom, "\xEF\xBB\xBF", 3);
    memcpy(bom + 3, sac, n);
    aq_check(aq_sniff_bom(bom, n + 3) == 0, "a BOM before binary data is not stripped");
    free(bom);
    free(sac);
  }
}
