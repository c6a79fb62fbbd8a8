/* test_repo_standalone.c: the repository stands alone.  No tracked file
 * (README, docs, sources, tests, bench, fuzz, Makefile, arches, data) may
 * send a user to a file outside it: the paper's list of corrections, a shared
 * folder beside the checkout, or the development machine's paths.  The
 * method and its departures from the paper are in docs/method.md. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* Case-insensitive search of n bytes of s for w. */
static const char *find_ci(const char *s, size_t n, const char *w)
{
  size_t m = strlen(w);
  for (size_t i = 0; m <= n && i <= n - m; i++) {
    size_t k = 0;
    while (k < m && tolower((unsigned char)s[i + k]) == tolower((unsigned char)w[k]))
      k++;
    if (k == m)
      return s + i;
  }
  return NULL;
}

AQ_TEST(repo_mentions_no_outside_path)
{
  /* built from pieces so that this file does not name them itself */
  char w_corr[16], w_shared[16], w_work[16], w_paper[24], w_recs[24];
  snprintf(w_corr, sizeof w_corr, "%s%s", "ERR", "ATA");
  snprintf(w_shared, sizeof w_shared, "%s%s", "../sha", "red");
  snprintf(w_work, sizeof w_work, "%s%s", "/wo", "rk/");
  snprintf(w_paper, sizeof w_paper, "%s%s", "shared/pa", "per");
  snprintf(w_recs, sizeof w_recs, "%s%s", "shared/rec", "ords");
  const char *const words[] = {w_corr, w_shared, w_work, w_paper, w_recs};
  /* the tracked files; outside a git checkout (a source tarball), every
   * file but the build tree */
  FILE *p = popen("git ls-files 2>/dev/null || find . -type f ! -path './build/*' "
                  "! -path './.git/*' | sed 's|^\\./||'",
                  "r");
  if (!aq_check(p != NULL, "cannot list the files"))
    return;
  char path[4096];
  size_t nfiles = 0, hits = 0;
  while (fgets(path, sizeof path, p)) {
    path[strcspn(path, "\n")] = '\0';
    if (!path[0])
      continue;
    size_t n = 0;
    char *text = aq_test_read_file(path, &n);
    if (!text)
      continue; /* a tracked file deleted in the work tree */
    nfiles++;
    for (size_t w = 0; w < sizeof words / sizeof words[0]; w++) {
      const char *at = find_ci(text, n, words[w]);
      if (at) {
        size_t line = 1;
        for (const char *q = text; q < at; q++)
          line += *q == '\n';
        hits++;
        aq_check(0, "%s:%zu mentions \"%s\" (a path or file outside the "
                    "repository; cite docs/ instead)",
                 path, line, words[w]);
      }
    }
    free(text);
  }
  pclose(p);
  aq_check(nfiles >= 50, "files scanned: %zu", nfiles);
  aq_check(hits == 0, "%zu mentions of outside paths", hits);
}
