/* suite_journal.c: the main job's journal, for --resume (suite_slot.h,
 * report/journal.h): a finished record as a journal entry, the identity
 * of a suite, starting a journal (checking one read back) and appending to
 * it (suite_write.c replays one).
 *
 * Structs are stored as their bytes: the identity names the exact build, so
 * a journal is read back only by the build that wrote it. */
#define _POSIX_C_SOURCE 200809L
#include "suite_slot.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../util/bytes.h"
#include "app.h"
#include "opt.h"

enum { F_FAILED = 1, F_REC = 2, F_PROC = 4, F_IM = 8, F_RUNS = 16 };
enum { R_RES = 1, R_FAILED = 2, R_CHECK_FAILED = 4 };

/* A run's summary: its record as a string (up to AQ_SUMMARY_RECORD_MAX bytes,
 * mostly unused), the other fields as they are. */
static void sum_put(aq_bytes_out *b, const aq_summary *s)
{
  const size_t at = offsetof(aq_summary, record), end = at + sizeof s->record;
  aq_bytes_put(b, s, at);
  aq_bytes_put_str(b, s->record, sizeof s->record);
  aq_bytes_put(b, (const char *)s + end, sizeof *s - end);
}

static void sum_get(aq_bytes_in *c, aq_summary *s)
{
  const size_t at = offsetof(aq_summary, record), end = at + sizeof s->record;
  aq_bytes_get(c, s, at, NULL);
  aq_bytes_get_str(c, s->record, sizeof s->record, NULL, NULL);
  aq_bytes_get(c, (char *)s + end, sizeof *s - end, NULL);
}

void aq_suite_slot_encode(const rec_slot *r, size_t nruns, aq_bytes_out *b)
{
  uint64_t index = r->index;
  unsigned char f = (unsigned char)((r->failed ? F_FAILED : 0) | (r->subj.have_rec[0] ? F_REC : 0) |
                                    (r->subj.have_proc[0] ? F_PROC : 0) |
                                    (r->subj.have_im ? F_IM : 0) |
                                    (r->runs ? F_RUNS : 0));
  aq_bytes_put(b, &index, sizeof index);
  aq_bytes_put(b, &f, 1);
  if (r->failed)
    aq_bytes_put(b, &r->err, sizeof r->err);
  aq_bytes_put_str(b, r->status, sizeof r->status);
  aq_bytes_put_str(b, r->subj.warning, sizeof r->subj.warning);
  aq_bytes_put_str(b, r->sha256, sizeof r->sha256);
  aq_bytes_put(b, &r->subj.read_s, sizeof r->subj.read_s);
  aq_bytes_put(b, &r->subj.process_s, sizeof r->subj.process_s);
  if (r->subj.have_rec[0]) {
    aq_record m = r->subj.rec[0]; /* metadata: the strings follow, no samples */
    m.path = m.name = NULL;
    m.acc_mps2 = NULL;
    aq_bytes_put(b, &m, sizeof m);
    aq_bytes_put_str(b, r->subj.rec[0].path, 0);
    aq_bytes_put_str(b, r->subj.rec[0].name, 0);
  }
  if (r->subj.have_proc[0]) {
    aq_processed p = r->subj.proc[0];
    p.acc_mps2 = NULL;
    aq_bytes_put(b, &p, sizeof p);
  }
  if (r->subj.have_im)
    aq_bytes_put(b, &r->subj.im, sizeof r->subj.im);
  for (size_t i = 0; r->runs && i < nruns; i++) {
    const run_slot *u = &r->runs[i];
    unsigned char g = (unsigned char)((u->have_res ? R_RES : 0) | (u->failed ? R_FAILED : 0) |
                                      (u->check_failed ? R_CHECK_FAILED : 0));
    sum_put(b, &u->sum);
    aq_bytes_put(b, &g, 1);
    if (u->have_res) {
      aq_result res = u->res;
      memset(&res.history, 0, sizeof res.history);
      res.bodies = NULL; /* the summary keeps its columns */
      aq_bytes_put(b, &res, sizeof res);
    }
    if (u->failed)
      aq_bytes_put(b, &u->err, sizeof u->err);
    if (u->check_failed)
      aq_bytes_put(b, &u->check_err, sizeof u->check_err);
    aq_bytes_put(b, &u->run_s, sizeof u->run_s);
  }
}

int aq_suite_slot_decode(const aq_journal_entry *e, size_t nruns, rec_slot *r)
{
  memset(r, 0, sizeof *r);
  aq_bytes_in c = {e->data, e->n, 0, NULL, 0};
  uint64_t index = 0;
  unsigned char f = 0;
  aq_bytes_get(&c, &index, sizeof index, NULL);
  aq_bytes_get(&c, &f, 1, NULL);
  r->index = (size_t)index;
  r->failed = (f & F_FAILED) != 0;
  if (r->failed)
    aq_bytes_get(&c, &r->err, sizeof r->err, NULL);
  aq_bytes_get_str(&c, r->status, sizeof r->status, NULL, NULL);
  aq_bytes_get_str(&c, r->subj.warning, sizeof r->subj.warning, NULL, NULL);
  aq_bytes_get_str(&c, r->sha256, sizeof r->sha256, NULL, NULL);
  aq_bytes_get(&c, &r->subj.read_s, sizeof r->subj.read_s, NULL);
  aq_bytes_get(&c, &r->subj.process_s, sizeof r->subj.process_s, NULL);
  aq_record *rec = &r->subj.rec[0];
  if ((f & F_REC) && aq_bytes_get(&c, rec, sizeof *rec, NULL) == 0) {
    rec->path = rec->name = NULL;
    rec->acc_mps2 = NULL;
    r->subj.have_rec[0] = 1; /* aq_record_free frees what was read */
    aq_bytes_get_str(&c, NULL, 0, &rec->path, NULL);
    aq_bytes_get_str(&c, NULL, 0, &rec->name, NULL);
  }
  if ((f & F_PROC) && aq_bytes_get(&c, &r->subj.proc[0], sizeof r->subj.proc[0], NULL) == 0) {
    r->subj.proc[0].acc_mps2 = NULL;
    r->subj.have_proc[0] = 1;
  }
  if (f & F_IM)
    r->subj.have_im = aq_bytes_get(&c, &r->subj.im, sizeof r->subj.im, NULL) == 0;
  if ((f & F_RUNS) && !c.bad && !(r->runs = calloc(nruns ? nruns : 1, sizeof *r->runs)))
    return -1;
  for (size_t i = 0; r->runs && i < nruns && !c.bad; i++) {
    run_slot *u = &r->runs[i];
    unsigned char g = 0;
    sum_get(&c, &u->sum);
    aq_bytes_get(&c, &g, 1, NULL);
    if ((g & R_RES) && aq_bytes_get(&c, &u->res, sizeof u->res, NULL) == 0) {
      memset(&u->res.history, 0, sizeof u->res.history);
      u->res.bodies = NULL;
      u->have_res = 1;
    }
    u->failed = (g & R_FAILED) != 0;
    if (u->failed)
      aq_bytes_get(&c, &u->err, sizeof u->err, NULL);
    u->check_failed = (g & R_CHECK_FAILED) != 0;
    if (u->check_failed)
      aq_bytes_get(&c, &u->check_err, sizeof u->check_err, NULL);
    aq_bytes_get(&c, &u->run_s, sizeof u->run_s, NULL);
  }
  r->runs_done = r->runs ? nruns : 0;
  r->state = SLOT_DONE;
  return c.bad || c.at != c.n ? -1 : 0;
}

static void line(aq_bytes_out *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* A line of the identity holds a path whole (record=PATH, up to 4095 bytes). */
#define JOURNAL_LINE_MAX 8192

static void line(aq_bytes_out *b, const char *fmt, ...)
{
  char buf[JOURNAL_LINE_MAX];
  va_list ap;
  va_start(ap, fmt);
  int k = vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (k < 0 || (size_t)k >= sizeof buf - 1) {
    b->oom = 1; /* a line that does not fit cannot identify */
    return;
  }
  buf[k] = '\n';
  aq_bytes_put(b, buf, (size_t)k + 1);
}

int aq_suite_identity(const aq_suite_cfg *c, aq_arch *const *arches, char **out)
{
  aq_bytes_out b = {0};
  const aq_signal_opts *p = &c->proc;
  /* floating-point values in %a: exact, so equal text means equal numbers */
  line(&b, "archquake journal for %s", aq_build_string());
  line(&b, "model=%d cor=%a polarity=%s", (int)c->model, c->cor,
       aq_opt_polarity_names[c->polarity]);
  if (c->model == AQ_MODEL_BLOCKS || c->check_blocks) /* the block model's step */
    line(&b, "blocks_dt=%a check_blocks=%d", c->blocks_dt_s, c->check_blocks);
  line(&b, "detrend=%d taper=%a filter=%d highpass=%a highpass_auto=%d order=%d lowpass=%a",
       (int)p->detrend, p->taper_frac, p->filter, p->highpass_hz, p->highpass_auto,
       p->order, p->lowpass_hz);
  /* the spectral measures the records table and /records carry */
  line(&b, "im_periods=%zu sa_avg=%a,%a peaks=%d", p->im_nsa, p->sa_avg_lo_s, p->sa_avg_hi_s,
       (int)p->peaks);
  for (size_t k = 0; k < p->im_nsa && k < AQ_IM_SA_MAX; k++)
    line(&b, "im_period=%a", p->im_period_s[k]);
  line(&b, "merge_tol_g=%a scale_to_pga_g=%a", c->merge_tol_g,
       c->scales ? 0.0 : c->scale_to_pga_g);
  if (!c->scales && c->scale_to_lambda0 > 0)
    line(&b, "scale_to_lambda0=%a", c->scale_to_lambda0);
  for (size_t k = 0; c->scales && k < c->nscale; k++)
    line(&b, "scale=%a", c->scales[k]);
  for (size_t i = 0; c->record_scales && i < c->nrecords; i++) /* --suite */
    line(&b, "record_scale=%a", c->record_scales[i]);
  line(&b, "units=%d dt=%a column=%zu", (int)c->read.units, c->read.dt_s, c->read.column);
  for (size_t k = 0; k < c->read.nrules; k++)
    line(&b, "units_rule=%d %s", (int)c->read.rules[k].units, c->read.rules[k].glob);
  line(&b, "history=%d store_records=%d", c->history, c->store_records);
  line(&b, "vertical=%d all_azimuths=%d", c->vertical, c->all_azimuths);
  for (size_t k = 0; c->motions && k < c->nazimuth; k++)
    line(&b, "azimuth=%a", c->azimuths_deg[k]);
  for (size_t i = 0; c->motions && i < c->nrecords; i++)
    if (c->motions[i])
      line(&b, "motion=%zu azimuths=%a,%a", i, c->motions[i]->azimuth_deg[0],
           c->motions[i]->azimuth_deg[1]);
  for (size_t a = 0; a < c->narches; a++) {
    char sha[AQ_SHA256_HEX];
    aq_arch_sha256(arches[a], sha);
    line(&b, "arch=%s sha256=%s", c->arch_paths[a], sha);
  }
  line(&b, "records=%zu", c->nrecords);
  for (size_t i = 0; i < c->nrecords; i++)
    line(&b, "record=%s", c->records[i]);
  aq_bytes_put(&b, "", 1);
  if (b.oom) {
    free(b.data);
    return -1;
  }
  *out = (char *)b.data;
  return 0;
}

/* The first line where identities a (the journal's) and b (this
 * command's) differ, into buf[n] as 'has "..." where this command has
 * "..."'. */
static void first_difference(const char *a, const char *b, char *buf, size_t n)
{
  while (*a && *b) {
    size_t la = strcspn(a, "\n"), lb = strcspn(b, "\n");
    if (la != lb || memcmp(a, b, la) != 0) {
      aq_text_fit(buf, n, "has \"%.*s\" where this command has \"%.*s\"", (int)la, a,
                  (int)lb, b);
      return;
    }
    a += la + (a[la] != '\0');
    b += lb + (b[lb] != '\0');
  }
  snprintf(buf, n, "has %s lines than this command's identity", *a ? "more" : "fewer");
}

/* Start the journal of a suite writing to c->h5_path.  With --resume and a
 * journal of the same command, its entries (identity first) are checked and
 * returned in *e (*ne of them) for aq_suite_journal_replay.  Returns AQ_EXIT_OK, or
 * the exit status after printing one line. */
int aq_suite_journal_start(suite *S, aq_journal **J, aq_journal_entry **e, size_t *ne)
{
  const aq_suite_cfg *c = S->cfg;
  *J = NULL;
  *e = NULL;
  *ne = 0;
  if (!c->h5_path || c->history || c->store_records)
    return AQ_EXIT_OK; /* datasets a journal does not hold */
  char *id = NULL, *path = malloc(strlen(c->h5_path) + 16);
  size_t dropped = 0;
  aq_error err;
  aq_error_clear(&err);
  int rc = AQ_EXIT_OK;
  if (!path || aq_suite_identity(c, S->arches, &id) != 0) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto out;
  }
  aq_journal_name(c->h5_path, path, strlen(c->h5_path) + 16);
  if (c->resume && aq_journal_open(path, J, e, ne, &dropped, &err) != AQ_OK) {
    char msg[1200];
    aq_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "archquake: %s (--resume: run without it to start over)\n", msg);
    rc = AQ_EXIT_USAGE;
    goto out;
  }
  if (!*J) {
    if (aq_journal_create(path, id, strlen(id) + 1, AQ_SUITE_JOURNAL_SYNC_S, J, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      rc = AQ_EXIT_OUTPUT;
    }
    goto out;
  }
  /* two identity lines quoted whole, or a record's path whole */
  char why[2 * JOURNAL_LINE_MAX + 256];
  why[0] = '\0';
  if ((*e)[0].n != strlen(id) + 1 || memcmp((*e)[0].data, id, (*e)[0].n) != 0) {
    char diff[2 * JOURNAL_LINE_MAX + 64];
    first_difference((const char *)(*e)[0].data, id, diff, sizeof diff);
    aq_text_fit(why, sizeof why, "the journal is another command's: it %s", diff);
  }
  /* Check every entry before writing anything: the order, and that each
   * record's file is still the one that was run. */
  for (size_t k = 1; !why[0] && k < *ne; k++) {
    rec_slot r;
    memset(&r, 0, sizeof r);
    char sha[AQ_SHA256_HEX] = "", file[4096];
    if (k - 1 < c->nrecords)
      aq_suite_slot_orient(S, k - 1, &r);
    if (k - 1 >= c->nrecords || aq_suite_slot_decode(&(*e)[k], r.nruns, &r) != 0 ||
        r.index != k - 1)
      snprintf(why, sizeof why, "entry %zu: expected record %zu of this suite, got "
                                "something else", k, k - 1);
    else if (r.sha256[0] &&
             (aq_sha256_file(aq_record_file(aq_suite_record_file(S, k - 1), file, sizeof file), sha,
                             &err) != AQ_OK ||
              strcmp(sha, r.sha256) != 0))
      aq_text_fit(why, sizeof why, "the record %s changed since the journal was written "
                                   "(sha256 %s, journal %s)", c->records[k - 1],
                  sha[0] ? sha : "unreadable", r.sha256);
    aq_suite_slot_clear(S, &r);
  }
  if (why[0]) {
    fprintf(stderr, "archquake: %s: --resume: %s; run without --resume to start over\n",
            path, why);
    aq_journal_close(*J);
    *J = NULL;
    rc = AQ_EXIT_USAGE;
    goto out;
  }
  if (dropped)
    fprintf(stderr, "archquake: %s: dropped a torn last entry (%zu bytes): its record "
                    "runs again\n", path, dropped);
  fprintf(stderr, "archquake: %s: %zu of %zu records done before, continuing\n", path,
          *ne - 1, c->nrecords);
out:
  if (*J)
    aq_journal_set_sync_period(*J, AQ_SUITE_JOURNAL_SYNC_S);
  if (rc != AQ_EXIT_OK) {
    aq_journal_entries_free(*e, *ne);
    *e = NULL;
    *ne = 0;
  }
  free(id);
  free(path);
  return rc;
}

aq_status aq_suite_journal_append(suite *S, aq_journal *J, const rec_slot *r, aq_error *err)
{
  aq_bytes_out jb = {0};
  aq_suite_slot_encode(r, r->nruns, &jb);
  aq_status s = jb.oom ? aq_error_set(err, AQ_ENOMEM, S->cfg->h5_path, -1, -1, NULL,
                                      "out of memory")
                       : aq_journal_append(J, jb.data, jb.n, err);
  free(jb.data);
  return s;
}

