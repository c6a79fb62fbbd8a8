/* arch_fixture.h: loading a shipped arch in a test.  A failure is a failed
 * check naming the file and the loader's message; the test then returns. */
#ifndef AQ_TESTS_ARCH_FIXTURE_H
#define AQ_TESTS_ARCH_FIXTURE_H

#include <gsl/gsl_errno.h>

#include "arch/arch.h"
#include "check.h"

static inline aq_arch *aq_test_arch_load(const char *path)
{
  gsl_set_error_handler_off(); /* as main does: GSL's default handler aborts */
  aq_arch *a = NULL;
  aq_error e;
  aq_error_clear(&e);
  if (!aq_check(aq_arch_load(path, &a, &e) == AQ_OK, "load %s: %s", path,
                e.message))
    return NULL;
  return a;
}

#endif
