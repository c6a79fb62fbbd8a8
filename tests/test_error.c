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
