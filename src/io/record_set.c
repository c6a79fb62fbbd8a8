/* record_set.c: record files expanded into a set of records (see
 * record.h): each file read once, every channel of a multi-channel file
 * (or the one a --component rule or FILE#CH names), the vertical ones
 * noted and skipped where asked, each decided by aq_record_decide.
 */
#include <fnmatch.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "evidence.h"
#include "record.h"
#include "record_impl.h"

void aq_record_names_free(char **names, size_t n)
{
  for (size_t i = 0; names && i < n; i++)
    free(names[i]);
  free(names);
}

void aq_record_set_free(aq_record_set *set)
{
  if (!set)
    return;
  for (size_t i = 0; set->item && i < set->n; i++) {
    free(set->item[i].name);
    aq_record_free(&set->item[i].rec);
  }
  free(set->item);
  free(set->bytes);
  memset(set, 0, sizeof *set);
}

/* The last --component rule matching path, or NULL. */
static const char *component_rule(const aq_read_opts *opts, const char *path)
{
  const char *ch = NULL;
  for (size_t r = 0; opts && r < opts->ncomponents && r < AQ_UNITS_RULES_MAX; r++)
    if (fnmatch(opts->components[r].glob, path, 0) == 0)
      ch = opts->components[r].channel;
  return ch;
}

/* Append an item named name (a copy) to set: its record from channel ichan
 * of raw (scaled in place, its values taken from raw), or the status s with
 * e when s is not AQ_OK.  AQ_OK, or AQ_ENOMEM for the set itself. */
static aq_status add_item(aq_record_set *set, const char *name, aq_raw_file *raw, size_t ichan,
                          const char *file, const aq_read_opts *opts, aq_status s,
                          const aq_error *e)
{
  aq_record_item *it = realloc(set->item, (set->n + 1) * sizeof *it);
  if (!it)
    return AQ_ENOMEM;
  set->item = it;
  it += set->n;
  memset(it, 0, sizeof *it);
  if (!(it->name = strdup(name)))
    return AQ_ENOMEM;
  set->n++;
  aq_error_clear(&it->err);
  if (s == AQ_OK) {
    s = aq_record_decide_in_place(raw, ichan, file, opts, &it->rec, &it->err, raw->chan[ichan].values);
    if (s == AQ_OK)
      raw->chan[ichan].values = NULL; /* it->rec.acc_mps2 now */
  } else {
    it->err = *e;
  }
  it->status = s;
  return AQ_OK;
}

/* aq_record_read_all of the bytes buf[0..size) of file, for the operand
 * path (want: the channel it names, or NULL). */
static aq_status read_all_bytes(const unsigned char *buf, size_t size, const char *path,
                                const char *file, const char *want,
                                const aq_read_opts *opts, aq_record_set *set)
{
  aq_raw_file raw;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_raw_parse(buf, size, file, opts, &raw, &e), st = AQ_OK;
  if (s != AQ_OK)
    return add_item(set, path, NULL, 0, file, opts, s, &e);
  const char *rule = want ? NULL : component_rule(opts, path);
  if (want || raw.nchan == 1 || rule) { /* one channel: as aq_record_read */
    size_t ichan = 0;
    char name[RECORD_LABEL_MAX];
    snprintf(name, sizeof name, "%s", path);
    if (!want && raw.nchan > 1)
      snprintf(name, sizeof name, "%s#%s", path, rule);
    s = aq_record_select_channel(&raw, want, file, opts, &ichan, &e);
    st = add_item(set, name, &raw, ichan, file, opts, s, &e);
  } else {
    for (size_t c = 0; c < raw.nchan && st == AQ_OK; c++) {
      char label[RECORD_LABEL_MAX];
      aq_record_label(&raw, c, path, label, sizeof label);
      st = add_item(set, label, &raw, c, file, opts, AQ_OK, NULL);
    }
  }
  aq_raw_file_free(&raw);
  return st;
}

aq_status aq_record_read_all(const char *path, const aq_read_opts *opts, int keep_bytes,
                             aq_record_set *set, aq_error *err)
{
  memset(set, 0, sizeof *set);
  aq_error e;
  aq_error_clear(&e);
  aq_status st;
  if (!path || !*path) {
    aq_error_set(&e, AQ_EIO, "", -1, -1, NULL,
                 "expected a record file name, got an empty string");
    st = add_item(set, path ? path : "", NULL, 0, "", opts, AQ_EIO, &e);
  } else {
    char file[4096];
    const char *want;
    aq_record_split_channel(path, file, sizeof file, &want);
    unsigned char *buf = NULL;
    size_t size = 0;
    aq_status s = aq_record_read_bytes(file, &buf, &size, &e);
    st = s == AQ_OK ? read_all_bytes(buf, size, path, file, want, opts, set)
                    : add_item(set, path, NULL, 0, file, opts, s, &e);
    if (keep_bytes && buf) {
      set->bytes = buf;
      set->nbytes = size;
    } else {
      free(buf);
    }
  }
  if (st != AQ_OK) {
    aq_record_set_free(set);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  }
  return AQ_OK;
}

/* Append to notes[0..*n) the line saying why item it, a channel the file
 * identifies as vertical, is left out of a run. */
static aq_status add_note(char ***notes, size_t *n, const aq_record_item *it)
{
  char why[sizeof it->rec.vertical_note + 32], line[5400];
  aq_record_vertical_why(&it->rec, why, sizeof why);
  aq_text_fit(line, sizeof line,
              "%s: skipped: the file identifies channel \"%s\" as vertical (%s), which is "
              "not horizontal excitation (give --accept-vertical to run it)",
              it->name, it->rec.channel, why);
  char **g = realloc(*notes, (*n + 1) * sizeof *g);
  if (!g)
    return AQ_ENOMEM;
  *notes = g;
  if (!(g[*n] = strdup(line)))
    return AQ_ENOMEM;
  (*n)++;
  return AQ_OK;
}

/* Formats that hold one channel per file (SAC, AT2, K-NET, NPTS DT) are not
 * parsed here, nor text that has one column of acceleration (only its
 * columns are read); the others are read as aq_record_read_all reads them,
 * and named as it names them. */
static aq_status expand(char *const *paths, size_t n, const aq_read_opts *opts, int skip_vertical,
                        char ***out, size_t *nout, char ***notes, size_t *nnotes, aq_error *err)
{
  size_t cap = n + 1, k = 0;
  char **names = malloc(cap * sizeof *names);
  *out = NULL;
  *nout = 0;
  size_t nn = 0;
  char **nt = NULL;
  if (!names)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  aq_status st = AQ_OK;
  for (size_t i = 0; i < n && st == AQ_OK; i++) {
    aq_record_set set;
    memset(&set, 0, sizeof set);
    char file[4096];
    const char *want;
    aq_record_split_channel(paths[i], file, sizeof file, &want);
    unsigned char *buf = NULL;
    size_t size = 0;
    aq_error ignored;
    if (!want && aq_record_read_bytes(paths[i], &buf, &size, &ignored) == AQ_OK) {
      aq_format fmt = aq_sniff_format(buf, size);
      int single = fmt == AQ_FMT_SAC || fmt == AQ_FMT_AT2 || fmt == AQ_FMT_KNET ||
                   fmt == AQ_FMT_NPTS_DT;
      size_t nch;
      aq_reader_opts ro;
      /* text of one channel, or that fails before its rows, keeps its name
       * whatever its rows hold: only its columns are read */
      if (fmt == AQ_FMT_TEXT &&
          (aq_csv_channels(buf, size, paths[i], aq_record_reader_opts(opts, &ro), &nch, &ignored) !=
               AQ_OK ||
           nch <= 1))
        single = 1;
      if (!single && read_all_bytes(buf, size, paths[i], paths[i], NULL, opts, &set) != AQ_OK)
        st = AQ_ENOMEM;
    }
    free(buf);
    size_t add = set.n > 1 ? set.n : 1;
    if (st == AQ_OK && k + add > cap) {
      size_t ncap = 2 * cap + add;
      char **g = realloc(names, ncap * sizeof *names);
      if (!g)
        st = AQ_ENOMEM;
      else {
        names = g;
        cap = ncap;
      }
    }
    for (size_t c = 0; c < add && st == AQ_OK; c++) {
      /* (a file that fails to parse is one item named as given: reported
       * when it is read) */
      const char *name = set.n ? set.item[c].name : paths[i];
      if (skip_vertical && set.n > 1 && set.item[c].status == AQ_OK &&
          set.item[c].rec.vertical && !(opts && opts->accept_vertical)) {
        st = add_note(&nt, &nn, &set.item[c]);
        continue;
      }
      if (!(names[k] = strdup(name)))
        st = AQ_ENOMEM;
      else
        k++;
    }
    aq_record_set_free(&set);
    if (st != AQ_OK)
      aq_error_set(err, AQ_ENOMEM, paths[i], -1, -1, NULL, "out of memory");
  }
  if (st != AQ_OK) {
    aq_record_names_free(names, k);
    aq_record_names_free(nt, nn);
    return st;
  }
  *out = names;
  *nout = k;
  if (notes) {
    *notes = nt;
    *nnotes = nn;
  }
  return AQ_OK;
}

aq_status aq_record_expand(char *const *paths, size_t n, const aq_read_opts *opts,
                           char ***out, size_t *nout, aq_error *err)
{
  return expand(paths, n, opts, 0, out, nout, NULL, NULL, err);
}

aq_status aq_record_expand_horizontal(char *const *paths, size_t n, const aq_read_opts *opts,
                                      char ***out, size_t *nout, char ***notes, size_t *nnotes,
                                      aq_error *err)
{
  *notes = NULL;
  *nnotes = 0;
  return expand(paths, n, opts, 1, out, nout, notes, nnotes, err);
}
