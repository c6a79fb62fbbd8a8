/* src/util (util.h): what every stage may use and none owns: threads (pool.h), values
 * as bytes and back (bytes.h), and output files written under a temporary
 * name and renamed onto their target when complete, removed on a signal
 * (outfile.h, cleanup.h), shared libraries opened on first use rather
 * than at start (lazylib.h), and keyed values kept on disk between
 * processes (diskcache.h).
 *
 * Nothing here knows records, arches or results; nothing here prints.
 * Every folder of src/ may include these headers (and error.h, units.h);
 * they include nothing of archquake's but error.h. */
#ifndef AQ_UTIL_H
#define AQ_UTIL_H

#include "bytes.h"
#include "cleanup.h"
#include "diskcache.h"
#include "lazylib.h"
#include "outfile.h"
#include "pool.h"

#endif
