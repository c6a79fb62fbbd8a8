/* version.c: what a results file says of the build and the run that made
 * it (see app.h).  build/describe.h is written by the Makefile from `git
 * describe --always --dirty` (AQ_BUILD_SUFFIX is " (DESCRIPTION)", or ""
 * outside a git checkout) and rewritten only when that changes, so that
 * only this file is rebuilt. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app.h"
#include "describe.h"

const char *aq_build_string(void) { return AQ_VERSION AQ_BUILD_SUFFIX; }

char *aq_app_command_line(int argc, char **argv)
{
  size_t len = 1;
  for (int i = 0; i < argc; i++)
    len += 4 * strlen(argv[i]) + 3;
  char *s = malloc(len), *p = s;
  if (!s)
    return NULL;
  for (int i = 0; i < argc; i++) {
    const char *w = argv[i];
    int plain = *w != '\0';
    for (const char *q = w; *q; q++)
      if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                  "0123456789-_./=,:+@%", *q))
        plain = 0;
    if (i)
      *p++ = ' ';
    if (plain) {
      strcpy(p, w);
      p += strlen(w);
    } else {
      *p++ = '\'';
      for (const char *q = w; *q; q++) {
        if (*q == '\'') {
          memcpy(p, "'\\''", 4);
          p += 4;
        } else
          *p++ = *q;
      }
      *p++ = '\'';
    }
  }
  *p = '\0';
  return s;
}

void aq_app_now_utc(char *buf, size_t n)
{
  time_t t = time(NULL);
  struct tm tm;
  if (!gmtime_r(&t, &tm) || !strftime(buf, n, "%Y-%m-%dT%H:%M:%SZ", &tm))
    snprintf(buf, n, "unknown");
}
