/* infile.c: the arch's input files read whole, and their numbers
 * (infile.h). */
#include "infile.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

char *aq_infile_read(const char *path, size_t max_bytes, const char *what, size_t *len,
                     aq_status *st, aq_error *err)
{
  FILE *f = fopen(path, "rb");
  if (!f) {
    *st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "expected a readable %s, got %s", what,
                       strerror(errno));
    return NULL;
  }
  struct stat sb;
  if (fstat(fileno(f), &sb) == 0 && S_ISDIR(sb.st_mode)) {
    fclose(f);
    *st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "expected a readable %s, got a directory",
                       what);
    return NULL;
  }
  char *buf = malloc(max_bytes + 2);
  size_t n = buf ? fread(buf, 1, max_bytes + 1, f) : 0;
  int bad = buf && ferror(f);
  fclose(f);
  if (!buf) {
    *st = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    return NULL;
  }
  if (bad) {
    free(buf);
    *st = aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "expected a readable %s, got a read "
                       "error", what);
    return NULL;
  }
  buf[n] = '\0';
  *len = n;
  return buf;
}

int aq_infile_number(const char *s, double *x)
{
  char *end;
  errno = 0;
  double d = strtod(s, &end);
  if (end == s || *end || errno == ERANGE || !isfinite(d))
    return 0;
  *x = d;
  return 1;
}
