/* version.c: the exact build (see app.h).  build/describe.h is written by
 * the Makefile from `git describe --always --dirty` (AQ_BUILD_SUFFIX is
 * " (DESCRIPTION)", or "" outside a git checkout) and rewritten only when
 * that changes, so that only this file is rebuilt. */
#include "app.h"
#include "describe.h"

const char *aq_build_string(void) { return AQ_VERSION AQ_BUILD_SUFFIX; }
