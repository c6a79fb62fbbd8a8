/* record_impl.h: the helpers record.c (options, the decision) shares with
 * the readers of record files (record_read.c: one file; record_set.c:
 * files and their channels expanded into a set); internal to src/io.
 * Nothing here allocates but aq_record_read_bytes (*buf, freed by the
 * caller).
 */
#ifndef AQ_IO_RECORD_IMPL_H
#define AQ_IO_RECORD_IMPL_H

#include <stddef.h>

#include "record.h"

/* A record's label: its path (at most PATH_MAX, 4096 bytes, or no file
 * could be opened by it), '#' and the channel's name (under 16). */
#define RECORD_LABEL_MAX (4096 + 32)

void aq_record_label(const aq_raw_file *raw, size_t ichan, const char *path,
                     char *out, size_t cap);

/* aq_record_decide; with in_place (the channel's own values, which the
 * caller gives up on success), the samples are scaled there instead of in a
 * new array. */
aq_status aq_record_decide_in_place(const aq_raw_file *raw, size_t ichan, const char *path,
                                    const aq_read_opts *opts, aq_record *rec, aq_error *err,
                                    double *in_place);

/* Why rec is vertical, for messages: "by its dip, 90 deg", ... */
void aq_record_vertical_why(const aq_record *rec, char *why, size_t cap);

/* What a parser may be told of opts (NULL for NULL), in *ro. */
const aq_reader_opts *aq_record_reader_opts(const aq_read_opts *opts, aq_reader_opts *ro);

/* The channel of raw that want names (exact, then case-insensitive, then a
 * 1-based number), or that a --component rule matching path names, or the
 * only one.  Returns AQ_OK with *ichan, or an error naming the channels. */
aq_status aq_record_select_channel(const aq_raw_file *raw, const char *want,
                                   const char *path, const aq_read_opts *opts,
                                   size_t *ichan, aq_error *err);

/* The bytes of the regular file at path (*buf malloc'd, caller frees). */
aq_status aq_record_read_bytes(const char *path, unsigned char **buf, size_t *size,
                               aq_error *err);

/* FILE#CHANNEL names one channel of a file when no file has the whole name:
 * file (cap bytes) gets FILE and *want CHANNEL; otherwise *want is NULL and
 * file is path. */
void aq_record_split_channel(const char *path, char *file, size_t cap, const char **want);

#endif
