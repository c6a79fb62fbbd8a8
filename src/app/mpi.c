/* mpi.c: archquake-mpi, the main job over Open MPI ranks (docs/cluster.md).
 *
 * `mpirun -n N archquake-mpi ARGS...` takes archquake's arguments.  Every
 * rank parses them the same way.  Rank 0 leads: it runs the suite exactly
 * as archquake does (results file, text rows, journal, --resume), except
 * that the records come back from the followers (aq_suite_remote in
 * suite.h): it hands out record indices, a few at a time, to whichever
 * follower returns one (dynamic load balancing), keeps results that arrive
 * ahead of the writer, and gives each record to the writer in order; so the
 * outputs are those of `archquake -j 1`.  A follower reads and processes
 * each record it is given itself, runs every arch, scale and polarity of
 * it, and sends back the record's journal payload (suite_slot.h).  With one
 * rank, rank 0 runs the suite itself, threads and all.
 *
 * Every MPI call's status is checked (MPI_ERRORS_RETURN): a failed exchange
 * fails the results file (no partial file) and aborts the job.  A rank that
 * dies makes mpirun end the others with SIGTERM, which removes rank 0's
 * temporaries (cleanup.h); the journal stays for --resume.
 *
 * Followers write nothing: their stdout and stderr go to /dev/null (rank 0
 * reports every record's problems); only this file's own messages about
 * the follower itself reach the original stderr.  The other commands run
 * on rank 0 alone.
 */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "suite.h"

int aq_main_serial(int argc, char **argv); /* src/main.c */
int aq_main_is_command(const char *name);

/* Records queued at each follower: it finds the next one waiting when it
 * sends a result back. */
#define AQ_MPI_QUEUED_PER_FOLLOWER 2
/* Records handed out ahead of the writer, per follower: bounds the results
 * kept while a long record holds the writer up. */
#define AQ_MPI_AHEAD_PER_FOLLOWER 8
/* Sleep between polls of a waiting rank, ns: it leaves its core to the
 * ranks that compute (MPI's blocking calls spin). */
#define AQ_MPI_POLL_NS 200000L

enum { TAG_TASK = 1, TAG_STOP = 2, TAG_RESULT = 3 };

typedef struct {
  int rank, size;
  int broken;          /* an MPI call failed */
  FILE *diag;          /* a follower's own messages (its stderr is /dev/null) */
  /* leader */
  int started;
  size_t nrec, next_hand, want, inflight;
  int *queued;         /* per rank: records handed out, not yet returned */
  unsigned char **got; /* per record: its payload, arrived ahead of the writer */
  size_t *got_n;
  /* follower */
  int stopped;
} mpi_ctx;

static void poll_pause(void)
{
  struct timespec ts = {0, AQ_MPI_POLL_NS};
  nanosleep(&ts, NULL);
}

static int wait_req(MPI_Request *rq, MPI_Status *st)
{
  for (;;) {
    int flag = 0, e = MPI_Test(rq, &flag, st);
    if (e != MPI_SUCCESS || flag)
      return e;
    poll_pause();
  }
}

static int mpi_fail(mpi_ctx *C, aq_error *err, int code, const char *what, int peer)
{
  char s[MPI_MAX_ERROR_STRING];
  int len = 0;
  if (MPI_Error_string(code, s, &len) != MPI_SUCCESS)
    snprintf(s, sizeof s, "error %d", code);
  C->broken = 1;
  aq_error_set(err, AQ_EIO, "MPI", -1, -1, NULL, "%s rank %d: %s", what, peer, s);
  return -1;
}

/* ---- leader ------------------------------------------------------------- */

/* Top up follower r's queue. */
static int hand(mpi_ctx *C, int r, aq_error *err)
{
  size_t ahead = (size_t)(C->size - 1) * AQ_MPI_AHEAD_PER_FOLLOWER;
  while (C->queued[r] < AQ_MPI_QUEUED_PER_FOLLOWER && C->next_hand < C->nrec &&
         C->next_hand < C->want + ahead) {
    uint64_t i = C->next_hand;
    int e = MPI_Send(&i, 1, MPI_UINT64_T, r, TAG_TASK, MPI_COMM_WORLD);
    if (e != MPI_SUCCESS)
      return mpi_fail(C, err, e, "cannot hand a record to", r);
    C->next_hand++;
    C->queued[r]++;
    C->inflight++;
  }
  return 0;
}

/* Receive one result (kept in got[]) and top up its sender. */
static int receive(mpi_ctx *C, aq_error *err)
{
  MPI_Status st;
  int flag = 0, e;
  while ((e = MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st)) ==
             MPI_SUCCESS &&
         !flag)
    poll_pause();
  if (e != MPI_SUCCESS)
    return mpi_fail(C, err, e, "cannot hear from", -1);
  int n = 0, src = st.MPI_SOURCE;
  if ((e = MPI_Get_count(&st, MPI_BYTE, &n)) != MPI_SUCCESS)
    return mpi_fail(C, err, e, "cannot size a message of", src);
  unsigned char *d = malloc(n > 0 ? (size_t)n : 1);
  if (!d) {
    aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory");
    return -1;
  }
  if ((e = MPI_Recv(d, n, MPI_BYTE, src, TAG_RESULT, MPI_COMM_WORLD, MPI_STATUS_IGNORE)) !=
      MPI_SUCCESS) {
    free(d);
    return mpi_fail(C, err, e, "cannot receive a result from", src);
  }
  uint64_t idx = UINT64_MAX; /* a payload starts with its record index */
  if (n >= (int)sizeof idx)
    memcpy(&idx, d, sizeof idx);
  if (idx >= C->nrec || idx < C->want || C->got[idx] || C->queued[src] == 0) {
    free(d);
    C->broken = 1;
    aq_error_set(err, AQ_EFORMAT, "MPI", -1, -1, NULL,
                 "rank %d: expected the results of a record handed to it, got a message "
                 "of %d bytes for record %llu", src, n, (unsigned long long)idx);
    return -1;
  }
  C->got[idx] = d;
  C->got_n[idx] = (size_t)n;
  C->queued[src]--;
  C->inflight--;
  return hand(C, src, err);
}

static int fetch(void *ctx, size_t i, size_t nrec, unsigned char **data, size_t *n,
                 aq_error *err)
{
  mpi_ctx *C = ctx;
  if (!C->started) {
    C->got = calloc(nrec ? nrec : 1, sizeof *C->got);
    C->got_n = calloc(nrec ? nrec : 1, sizeof *C->got_n);
    if (!C->got || !C->got_n) {
      aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory");
      return -1;
    }
    C->started = 1;
    C->nrec = nrec;
    C->next_hand = i;
  }
  C->want = i;
  for (int r = 1; r < C->size; r++)
    if (hand(C, r, err) != 0)
      return -1;
  while (!C->got[i])
    if (receive(C, err) != 0)
      return -1;
  *data = C->got[i];
  *n = C->got_n[i];
  C->got[i] = NULL;
  return 0;
}

/* After the suite: collect what is still out (the suite may have stopped
 * early), then stop every follower.  Returns 0, or -1 (message printed). */
static int lead_finish(mpi_ctx *C)
{
  aq_error err;
  aq_error_clear(&err);
  int ok = !C->broken;
  C->nrec = C->next_hand; /* hand out nothing more */
  while (ok && C->started && C->inflight > 0) {
    C->want = 0;
    if (receive(C, &err) != 0) {
      aq_error_print(&err, stderr);
      ok = 0;
    }
  }
  for (size_t i = 0; C->got && i < C->nrec; i++)
    free(C->got[i]);
  free(C->got);
  free(C->got_n);
  free(C->queued);
  uint64_t zero = 0;
  for (int r = 1; ok && r < C->size; r++) {
    int e = MPI_Send(&zero, 1, MPI_UINT64_T, r, TAG_STOP, MPI_COMM_WORLD);
    if (e != MPI_SUCCESS) {
      mpi_fail(C, &err, e, "cannot stop", r);
      aq_error_print(&err, stderr);
      ok = 0;
    }
  }
  return ok ? 0 : -1;
}

/* ---- follower ----------------------------------------------------------- */

static void follower_abort(mpi_ctx *C, int code, const char *what)
{
  char s[MPI_MAX_ERROR_STRING] = "";
  int len = 0;
  if (code != MPI_SUCCESS)
    MPI_Error_string(code, s, &len);
  fprintf(C->diag, "archquake-mpi: rank %d: %s%s%s\n", C->rank, what, s[0] ? ": " : "", s);
  fflush(C->diag);
  MPI_Abort(MPI_COMM_WORLD, AQ_EXIT_FAIL);
}

/* The next message from the leader: 0 and a record in *i, or 1 to stop. */
static int recv_task(mpi_ctx *C, size_t *i)
{
  uint64_t v = 0;
  MPI_Request rq;
  MPI_Status st;
  int e = MPI_Irecv(&v, 1, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &rq);
  if (e == MPI_SUCCESS)
    e = wait_req(&rq, &st);
  if (e != MPI_SUCCESS)
    follower_abort(C, e, "cannot hear from rank 0");
  if (st.MPI_TAG == TAG_STOP) {
    C->stopped = 1;
    return 1;
  }
  *i = (size_t)v;
  return 0;
}

static int next(void *ctx, size_t *i)
{
  return recv_task(ctx, i);
}

static int send_result(void *ctx, const void *data, size_t n)
{
  mpi_ctx *C = ctx;
  if (n > (size_t)INT32_MAX)
    follower_abort(C, MPI_SUCCESS, "a record's results exceed one MPI message");
  MPI_Request rq;
  int e = MPI_Isend(data, (int)n, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD, &rq);
  if (e == MPI_SUCCESS)
    e = wait_req(&rq, MPI_STATUS_IGNORE);
  if (e != MPI_SUCCESS)
    follower_abort(C, e, "cannot send results to rank 0");
  return 0;
}

/* ---- entry -------------------------------------------------------------- */

/* 1 if argv is the main job (not a command, help or the version). */
static int is_main_job(int argc, char **argv)
{
  static const char *const other[] = {"help", "-h", "--help", "--version"};
  if (argc < 2 || aq_main_is_command(argv[1]))
    return 0;
  for (size_t k = 0; k < sizeof other / sizeof other[0]; k++)
    if (strcmp(argv[1], other[k]) == 0)
      return 0;
  return 1;
}

int main(int argc, char **argv)
{
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    fprintf(stderr, "archquake-mpi: cannot start MPI\n");
    return AQ_EXIT_FAIL;
  }
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  mpi_ctx C;
  memset(&C, 0, sizeof C);
  C.diag = stderr;
  MPI_Comm_rank(MPI_COMM_WORLD, &C.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &C.size);
  int main_job = is_main_job(argc, argv);
  aq_suite_remote R = {&C, C.rank != 0, fetch, next, send_result};
  int rc = AQ_EXIT_OK;

  if (C.rank == 0) {
    if (C.size > 1 && main_job && !(C.queued = calloc((size_t)C.size, sizeof *C.queued))) {
      fprintf(stderr, "archquake-mpi: out of memory\n");
      MPI_Abort(MPI_COMM_WORLD, AQ_EXIT_FAIL);
    }
    aq_suite_remote here = {&C, 0, NULL, NULL, NULL}; /* one rank: the suite runs here */
    aq_suite_set_remote(C.size > 1 && main_job ? &R : &here);
    if (C.size > 1 && !main_job && argc >= 2 && strcmp(argv[1], "capacity") == 0)
      fprintf(stderr, "archquake-mpi: capacity runs on rank 0 alone (%d ranks idle)\n",
              C.size - 1);
    rc = aq_main_serial(argc, argv);
    fflush(stdout);
    if (C.size > 1 && main_job && lead_finish(&C) != 0) {
      fflush(NULL);
      MPI_Abort(MPI_COMM_WORLD, rc != AQ_EXIT_OK ? rc : AQ_EXIT_FAIL);
    }
    if (C.broken) { /* the suite failed the output already; stop the others */
      fflush(NULL);
      MPI_Abort(MPI_COMM_WORLD, rc != AQ_EXIT_OK ? rc : AQ_EXIT_FAIL);
    }
  } else if (main_job) {
    int fd = dup(STDERR_FILENO);
    FILE *diag = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (diag)
      C.diag = diag;
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
      follower_abort(&C, MPI_SUCCESS, "cannot silence its output");
    aq_suite_set_remote(&R);
    rc = aq_main_serial(argc, argv);
    size_t i;
    while (!C.stopped) /* the suite failed here but not on rank 0 */
      if (recv_task(&C, &i) == 0)
        follower_abort(&C, MPI_SUCCESS, "cannot run records: the command fails on this "
                                         "rank (run it alone there to see why)");
    if (diag)
      fclose(diag);
    rc = AQ_EXIT_OK; /* rank 0's status is the run's */
  }
  MPI_Finalize();
  return rc;
}
