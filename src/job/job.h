/* src/job (job.h): the path from a file name to a result: a subject (a record or a
 * ground motion) read and processed once, its step list built once as a
 * view, and runs (factor, polarity, azimuth, arch) giving an aq_result.
 *
 *   subject.h  reading, checking and processing a record or motion; views
 *   subject_cache.h  prepared subjects kept on disk (util/diskcache.h)
 *   arch_cache.h  built arches kept on disk (the search, the tables)
 *   cache_key.h  the libraries and CPU in those caches' keys
 *   scale.h    the scaling rule (--scale, --scale-to-pga,
 *              --scale-to-lambda0), the polarity, lambda0
 *   run.h      the arch's stepper, and the runs of a subject
 *   names.h    the records a suite's operands name (FILE#CH), on threads
 *   cache.h    prepared subjects kept for a process's next tasks (farmed)
 *
 * The main job (src/app/suite*.c), capacity (src/capacity), archquake-mpi
 * and the benches all take this path.  It comes after arch (its steppers)
 * and before capacity and report; nothing here prints. */
#ifndef AQ_JOB_H
#define AQ_JOB_H

#include "arch_cache.h"
#include "cache.h"
#include "names.h"
#include "run.h"
#include "scale.h"
#include "subject.h"
#include "subject_cache.h"

#endif
