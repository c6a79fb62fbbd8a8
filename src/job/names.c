/* names.c: the records a suite's operands name (names.h). */
#include "names.h"

#include <stdlib.h>
#include <string.h>

#include "../util/pool.h"

/* Naming the records reads every file of the suite (and parses those that
 * may hold several channels): 6 ms for the 200 files of the quiet bench
 * suite, before any record ran.  With several threads, each names a
 * contiguous part of at least this many operands. */
#define AQ_JOB_NAMES_MIN_PER_THREAD 8

typedef struct {
  char *const *paths;
  size_t n;
  const aq_read_opts *opts;
  char **names, **notes;
  size_t nnames, nnotes;
  aq_status st;
  aq_error err;
} expand_part;

static void expand_part_run(void *ctx, size_t k)
{
  expand_part *p = &((expand_part *)ctx)[k];
  p->st = aq_record_expand_horizontal(p->paths, p->n, p->opts, &p->names, &p->nnames, &p->notes,
                                      &p->nnotes, &p->err);
}

aq_status aq_job_names(char *const *paths, size_t n, const aq_read_opts *opts, long nthreads,
                       char ***out, size_t *nout, char ***notes, size_t *nnotes, aq_error *err)
{
  size_t T = nthreads > 1 ? (size_t)nthreads : 1;
  if (T > n / AQ_JOB_NAMES_MIN_PER_THREAD)
    T = n / AQ_JOB_NAMES_MIN_PER_THREAD;
  expand_part *p = T > 1 ? calloc(T, sizeof *p) : NULL;
  if (!p)
    return aq_record_expand_horizontal(paths, n, opts, out, nout, notes, nnotes, err);
  for (size_t k = 0; k < T; k++)
    p[k] = (expand_part){paths + n * k / T, n * (k + 1) / T - n * k / T, opts, NULL, NULL, 0,
                         0, AQ_OK, {0}};
  aq_status st = aq_pool_for(T, (long)T, expand_part_run, p, err);
  size_t total = 0;
  for (size_t k = 0; st == AQ_OK && k < T; k++) {
    if (p[k].st != AQ_OK) {
      st = p[k].st;
      *err = p[k].err;
    }
  }
  for (size_t k = 0; k < T; k++)
    total += p[k].nnames;
  char **names = st == AQ_OK ? malloc((total ? total : 1) * sizeof *names) : NULL;
  if (st == AQ_OK && !names)
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  size_t m = 0;
  for (size_t k = 0; k < T; k++) {
    if (names) { /* the names move; their array goes */
      memcpy(names + m, p[k].names, p[k].nnames * sizeof *names);
      free(p[k].names);
    } else {
      aq_record_names_free(p[k].names, p[k].nnames);
    }
    m += p[k].nnames;
  }
  /* the notes, in operand order */
  size_t nn = 0, mn = 0;
  for (size_t k = 0; k < T; k++)
    nn += p[k].nnotes;
  char **nt = st == AQ_OK && nn ? malloc(nn * sizeof *nt) : NULL;
  if (st == AQ_OK && nn && !nt) {
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
    aq_record_names_free(names, total);
    names = NULL;
  }
  for (size_t k = 0; k < T; k++) {
    if (nt)
      memcpy(nt + mn, p[k].notes, p[k].nnotes * sizeof *nt);
    else
      aq_record_names_free(p[k].notes, p[k].nnotes);
    if (nt)
      free(p[k].notes);
    mn += p[k].nnotes;
  }
  free(p);
  *out = names;
  *nout = names ? total : 0;
  *notes = nt;
  *nnotes = nt ? nn : 0;
  return st;
}
