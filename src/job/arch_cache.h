/* arch_cache.h: built arches kept on disk between processes
 * (src/util/diskcache.h, kind "arches"), so that a later run loading the
 * same arch with the same build reads what its build computed instead of
 * computing it again: the mechanism search's result (GLPK's linear
 * programs), the work paths' tables and the Taylor leg's pieces
 * (arch.h aq_arch_load_stored; the bytes are arch.c's and workpath.c's).
 * The .cfg is still read and parsed and the geometry made, so the arch's
 * name, text, digest and drawing are as ever.
 *
 * The key is everything the built arch depends on: its sources (the
 * .cfg's bytes and a joints arch's joints and faces files, each by its
 * length and SHA-256: what aq_arch_sha256 covers), the libraries and CPU
 * (cache_key.h), and, through the store, the archquake version and build.
 * No command-line option changes a built arch (--cor and --impact act on
 * the stepper), so none is in the key.  Only arches built without error
 * are stored.  Nothing prints; the store keeps the notes. */
#ifndef AQ_JOB_ARCH_CACHE_H
#define AQ_JOB_ARCH_CACHE_H

#include "../arch/arch.h"
#include "../util/bytes.h"
#include "../util/diskcache.h"

/* The key of the arch of src into *key (free key->data; oom set when out
 * of memory). */
void aq_arch_cache_key(const aq_arch_sources *src, aq_bytes_out *key);

/* aq_arch_load_opts (opt NULL: none) through the store c (NULL: built, no
 * cache); *hit (if not NULL) 1 when the arch's tables were read from c. */
aq_status aq_arch_cache_load(aq_diskcache *c, const char *path, const aq_arch_options *opt,
                             int *hit, aq_arch **out, aq_error *err);

#endif
