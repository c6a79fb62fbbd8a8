/* test_error.c: the error record's one-line format and the CLI's option checks. */
#include <string.h>

#include "check.h"
#include "error.h"

AQ_TEST(error_format_text_line)
{
  aq_error e;
  aq_error_clear(&e);
  aq_error_set(&e, AQ_EFORMAT, "records/x.AT2", 4, -1, "NPTS",
               "expected a positive integer, got \"%s\"", "12a");
  char buf[512];
  aq_error_format(&e, buf, sizeof buf);
  aq_check(strcmp(buf, "records/x.AT2:4: NPTS: expected a positive integer, got \"12a\"") == 0,
           "text format: %s", buf);
}

AQ_TEST(error_format_binary_offset)
{
  aq_error e;
  aq_error_clear(&e);
  aq_error_set(&e, AQ_EVALUE, "records/y.sac", -1, 0, "header DELTA",
               "expected > 0 s, got %g", -0.01);
  char buf[512];
  aq_error_format(&e, buf, sizeof buf);
  aq_check(strcmp(buf, "records/y.sac: header DELTA (byte 0): expected > 0 s, got -0.01") == 0,
           "binary format: %s", buf);
  aq_check(strcmp(aq_strerror(AQ_EUNITS), "unknown or non-acceleration units") == 0,
           "strerror");
}

static int ends_with(const char *s, const char *end)
{
  size_t a = strlen(s), b = strlen(end);
  return a >= b && strcmp(s + a - b, end) == 0;
}

/* A text longer than its field is cut visibly: a file name keeps its end
 * (the file) behind "...", a message and a formatted line end in "...",
 * and no UTF-8 character is split. */
AQ_TEST(error_cut_is_marked)
{
  char path[1200];
  size_t k = 0;
  path[k++] = '/';
  while (k < 1000)
    path[k++] = 'd';
  strcpy(path + k, "/\xc3\xa9t\xc3\xa9.AT2"); /* "/été.AT2" */
  aq_error e;
  aq_error_clear(&e);
  char msg[700];
  memset(msg, 'm', sizeof msg - 3);
  strcpy(msg + sizeof msg - 3, "\xc3\xa9"); /* ends in a 2-byte character */
  aq_error_set(&e, AQ_EFORMAT, path, 3, -1, "NPTS", "%s", msg);
  aq_check(strncmp(e.input, "...", 3) == 0 && ends_with(e.input, "/\xc3\xa9t\xc3\xa9.AT2"),
           "a long file name keeps its end behind \"...\": %.20s...%s", e.input,
           e.input + strlen(e.input) - 12);
  aq_check(strlen(e.input) < sizeof e.input, "input within its field");
  aq_check(ends_with(e.message, "mmm..."), "a cut message ends in \"...\": %s",
           e.message + strlen(e.message) - 10);
  char buf[64];
  aq_error_format(&e, buf, sizeof buf);
  aq_check(strlen(buf) == sizeof buf - 1 && ends_with(buf, "..."),
           "a cut line ends in \"...\": %s", buf);
  /* the cut never leaves half of a UTF-8 character before the mark */
  aq_error_set(&e, AQ_EFORMAT, "x", -1, -1, NULL, "%s", "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9");
  char small[8]; /* room for 7 bytes: 4 before "...", mid-character */
  aq_error_format(&e, small, sizeof small);
  size_t n = strlen(small);
  aq_check(ends_with(small, "..."), "short cut marked: %s", small);
  for (size_t i = 0; i + 3 < n; i++)
    if (((unsigned char)small[i] & 0xE0) == 0xC0)
      aq_check(i + 1 < n - 3 && ((unsigned char)small[i + 1] & 0xC0) == 0x80,
               "whole characters only before the mark: %s", small);
  /* texts that fit are left as they are */
  aq_error_set(&e, AQ_EFORMAT, "records/x.AT2", -1, -1, NULL, "%s", "short");
  aq_check(strcmp(e.input, "records/x.AT2") == 0 && strcmp(e.message, "short") == 0,
           "no mark on texts that fit");
}

AQ_TEST(cli_version_and_unknown_option)
{
  char out[4096], err[4096];
  int rc = aq_test_run("--version", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strncmp(out, "archquake ", 10) == 0, "--version: rc %d out %s", rc, out);
  rc = aq_test_run("info --frobnicate --dt=-1 x.AT2", out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "bad options exit 2, got %d", rc);
  aq_check(strstr(err, "--frobnicate") != NULL, "names the unknown option: %s", err);
  aq_check(strstr(err, "--dt") != NULL, "reports every bad option: %s", err);
  aq_check(out[0] == '\0', "no table when options are bad: %s", out);
}
