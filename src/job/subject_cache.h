/* subject_cache.h: prepared subjects (subject.h: the records read, checked,
 * processed and measured) kept on disk between processes
 * (src/util/diskcache.h), so that a later run of the same records with
 * the same options and the same build reads them instead of processing
 * them again (docs/cache.md).
 *
 * The key is everything the prepared subject depends on: each file's
 * SHA-256 (FILE of a FILE#CHANNEL name), the operands as given (records
 * are named after them, and --units rules match them), every reading
 * option, every processing option (the scale excepted: a subject is at
 * factor 1), the subject options (vertical, any channel, azimuths given),
 * FFTW's version and the CPU features its plans depend on
 * (aq_signal_fingerprint), the libraries and CPU (cache_key.h, shared with
 * arch_cache.h), and, through the store, the archquake version
 * and build.  Records whose reading takes StationXML responses are not
 * cached (their responses' files would belong in the key).
 *
 * The value is the subject after aq_subject_prepare: every component's
 * record metadata and processed samples, the intensity measures, the PGA a
 * scaling rule divides, the azimuths and the warning.  Only a subject
 * prepared without error is stored.  The bytes are this build's own
 * layout (the build is in the key).  Nothing prints; the store keeps the
 * notes. */
#ifndef AQ_JOB_SUBJECT_CACHE_H
#define AQ_JOB_SUBJECT_CACHE_H

#include <stddef.h>

#include "../io/sha256.h"
#include "../util/bytes.h"
#include "../util/diskcache.h"
#include "subject.h"

typedef struct {
  aq_bytes_out key;
  char sha256[3][AQ_SHA256_HEX]; /* each file's, "" where none */
} aq_subject_key;

/* The key of subject src prepared with o into *k (aq_subject_key_free):
 * each file read and hashed.  Returns 1, or 0 when it is not to be
 * cached (a file that cannot be read: the reader will say why; StationXML
 * responses; out of memory), *k then empty. */
int aq_subject_cache_key(const aq_subject_src *src, const aq_subject_opts *o,
                         aq_subject_key *k);

void aq_subject_key_free(aq_subject_key *k);

/* The subject stored under k into *s (zeroed first, as aq_subject_prepare
 * leaves it: stage "process", samples of every component, no bytes).
 * Returns 1 on a hit, 0 on a miss (*s zeroed). */
int aq_subject_cache_get(aq_diskcache *c, const aq_subject_key *k, aq_subject *s);

/* Store prepared subject s under k (never fails its caller: the store
 * notes a failure). */
void aq_subject_cache_put(aq_diskcache *c, const aq_subject_key *k, const aq_subject *s);

#endif
