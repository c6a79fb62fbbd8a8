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
 * `capacity` farms out its (subject, arch) tasks (capacity_tasks.h): rank
 * 0 hands each follower at most one task per thread of its (-j), a follower
 * runs them on its threads and sends each result back as bytes, and rank
 * 0 runs tasks on its own threads between messages.  The main thread of
 * every rank does all the MPI calls (MPI_THREAD_FUNNELED) and sleeps
 * between polls with a growing pause, so waiting costs no core.
 *
 * Followers write nothing: their stdout and stderr go to /dev/null (rank 0
 * reports every record's problems); only this file's own messages about
 * the follower itself reach the original stderr.  The other commands run
 * on rank 0 alone.
 */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <mpi.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "capacity_tasks.h"
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
  /* capacity */
  int farmed;          /* the command reached the farm */
  int stopped_all;     /* leader: the followers were told to stop */
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

static int stop_followers(mpi_ctx *C, aq_error *err);

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
  if (ok && stop_followers(C, &err) != 0) {
    aq_error_print(&err, stderr);
    ok = 0;
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

/* ---- the farm: capacity's (subject, arch) tasks (capacity_tasks.h) ---- */

/* A rank with nothing to do sleeps between polls, AQ_MPI_POLL_MIN_NS at
 * first, doubling to AQ_MPI_POLL_MAX_NS while nothing comes: an idle rank
 * costs its core almost nothing, and a task (tens of runs) outlasts the
 * longest pause many times. */
#define AQ_MPI_POLL_MIN_NS 20000L
#define AQ_MPI_POLL_MAX_NS 2000000L

typedef struct done_msg {
  size_t t;
  unsigned char *msg; /* task t's result, with 8 bytes ahead for its number */
  size_t n;           /* bytes of the result after them */
  struct done_msg *next;
} done_msg;

typedef struct {
  const aq_farm_tasks *T;
  int follower;
  pthread_mutex_t lock; /* guards everything below */
  pthread_cond_t cond;
  const size_t *todo;   /* leader: the tasks, handed out in order */
  size_t ntodo, next;
  size_t *ring;         /* follower: tasks received, not started (at most threads) */
  size_t nring, head, count;
  int stop;             /* no more tasks will come */
  int oom;              /* a task could not run (out of memory) */
  done_msg *done, **done_tail; /* results of this rank's threads, in order */
} farm_state;

static void pause_ns(long *ns, int active)
{
  if (active) {
    *ns = AQ_MPI_POLL_MIN_NS;
    return;
  }
  struct timespec ts = {0, *ns};
  nanosleep(&ts, NULL);
  *ns = *ns * 2 > AQ_MPI_POLL_MAX_NS ? AQ_MPI_POLL_MAX_NS : *ns * 2;
}

/* A worker thread: runs this rank's tasks, one at a time (no MPI here). */
static void *farm_worker(void *arg)
{
  farm_state *F = arg;
  pthread_mutex_lock(&F->lock);
  for (;;) {
    size_t t;
    if (F->follower) {
      while (F->count == 0 && !F->stop)
        pthread_cond_wait(&F->cond, &F->lock);
      if (F->count == 0)
        break;
      t = F->ring[F->head];
      F->head = (F->head + 1) % F->nring;
      F->count--;
    } else {
      if (F->stop || F->next >= F->ntodo)
        break;
      t = F->todo[F->next++];
    }
    pthread_mutex_unlock(&F->lock);
    done_msg *d = calloc(1, sizeof *d);
    unsigned char *m = NULL;
    size_t n = 0;
    int ok = d && F->T->run(F->T->ctx, t, &m, &n) == 0;
    unsigned char *w = ok ? malloc(n + sizeof(uint64_t)) : NULL;
    if (w) {
      uint64_t t64 = t;
      memcpy(w, &t64, sizeof t64);
      memcpy(w + sizeof t64, m, n);
    }
    free(m);
    pthread_mutex_lock(&F->lock);
    if (!w) {
      free(d);
      F->oom = 1;
      continue;
    }
    *d = (done_msg){t, w, n, NULL};
    *F->done_tail = d;
    F->done_tail = &d->next;
  }
  pthread_mutex_unlock(&F->lock);
  return NULL;
}

/* The results finished so far (lock taken here); *oom set if a task failed. */
static done_msg *farm_take_done(farm_state *F, int *oom)
{
  pthread_mutex_lock(&F->lock);
  done_msg *d = F->done;
  F->done = NULL;
  F->done_tail = &F->done;
  *oom = F->oom;
  pthread_mutex_unlock(&F->lock);
  return d;
}

static void farm_free_done(done_msg *d)
{
  while (d) {
    done_msg *x = d->next;
    free(d->msg);
    free(d);
    d = x;
  }
}

/* Start nt worker threads; returns how many started (the caller joins). */
static size_t farm_start(farm_state *F, pthread_t *tid, size_t nt)
{
  size_t k = 0;
  while (k < nt && pthread_create(&tid[k], NULL, farm_worker, F) == 0)
    k++;
  return k;
}

static void farm_join(farm_state *F, pthread_t *tid, size_t k)
{
  pthread_mutex_lock(&F->lock);
  F->stop = 1;
  pthread_cond_broadcast(&F->cond);
  pthread_mutex_unlock(&F->lock);
  for (size_t i = 0; i < k; i++)
    pthread_join(tid[i], NULL);
  int oom;
  farm_free_done(farm_take_done(F, &oom));
}

/* Leader: hand tasks to the followers, at most threads each (one per
 * thread of theirs), run tasks on its own threads between, and take every
 * result. */
static int farm_lead(mpi_ctx *C, farm_state *F, size_t threads, pthread_t *tid,
                     aq_error *err)
{
  const aq_farm_tasks *T = F->T;
  int *owner = malloc((T->ntask ? T->ntask : 1) * sizeof *owner); /* rank holding task t */
  size_t *queued = calloc((size_t)C->size, sizeof *queued);
  if (!owner || !queued) {
    free(owner);
    free(queued);
    return aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory"), -1;
  }
  for (size_t t = 0; t < T->ntask; t++)
    owner[t] = -1;
  size_t nt = farm_start(F, tid, threads), ndone = 0;
  int rc = 0;
  if (nt == 0)
    rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "cannot start a thread"), -1);
  long ns = AQ_MPI_POLL_MIN_NS;
  while (rc == 0 && ndone < F->ntodo) {
    int active = 0, e, oom;
    for (int r = 1; rc == 0 && r < C->size; r++)
      while (rc == 0 && queued[r] < threads) {
        pthread_mutex_lock(&F->lock);
        size_t k = F->next < F->ntodo ? F->next++ : F->ntodo;
        pthread_mutex_unlock(&F->lock);
        if (k >= F->ntodo)
          break;
        uint64_t t64 = F->todo[k];
        if ((e = MPI_Send(&t64, 1, MPI_UINT64_T, r, TAG_TASK, MPI_COMM_WORLD)) != MPI_SUCCESS)
          rc = mpi_fail(C, err, e, "cannot hand a task to", r);
        owner[F->todo[k]] = r;
        queued[r]++;
        active = 1;
      }
    done_msg *d = farm_take_done(F, &oom);
    for (done_msg *x = d; rc == 0 && x; x = x->next, active = 1, ndone++)
      rc = T->take(T->ctx, x->t, x->msg + sizeof(uint64_t), x->n, err);
    farm_free_done(d);
    if (rc == 0 && oom)
      rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "rank 0: out of memory"), -1);
    for (int flag = 1; rc == 0 && flag;) {
      MPI_Status st;
      if ((e = MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st)) !=
          MPI_SUCCESS) {
        rc = mpi_fail(C, err, e, "cannot hear from", -1);
        break;
      }
      if (!flag)
        break;
      int n = 0, src = st.MPI_SOURCE;
      unsigned char *m = NULL;
      if ((e = MPI_Get_count(&st, MPI_BYTE, &n)) != MPI_SUCCESS)
        rc = mpi_fail(C, err, e, "cannot size a message of", src);
      else if (!(m = malloc(n > 0 ? (size_t)n : 1)))
        rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory"), -1);
      else if ((e = MPI_Recv(m, n, MPI_BYTE, src, TAG_RESULT, MPI_COMM_WORLD,
                             MPI_STATUS_IGNORE)) != MPI_SUCCESS)
        rc = mpi_fail(C, err, e, "cannot receive a result from", src);
      uint64_t t = UINT64_MAX; /* a result starts with its task */
      if (rc == 0 && n >= (int)sizeof t)
        memcpy(&t, m, sizeof t);
      if (rc == 0 && (t >= T->ntask || owner[t] != src)) {
        C->broken = 1;
        rc = (aq_error_set(err, AQ_EFORMAT, "MPI", -1, -1, NULL,
                          "rank %d: expected the result of a task handed to it, got a "
                          "message of %d bytes for task %llu", src, n,
                          (unsigned long long)t), -1);
      }
      if (rc == 0)
        rc = T->take(T->ctx, (size_t)t, m + sizeof t, (size_t)n - sizeof t, err);
      if (rc == 0) {
        owner[t] = -1;
        queued[src]--;
        ndone++;
        active = 1;
      }
      free(m);
    }
    pause_ns(&ns, active);
  }
  farm_join(F, tid, nt);
  free(owner);
  free(queued);
  if (rc != 0)
    C->broken = 1;
  return rc;
}

/* Follower: take tasks from rank 0 onto this rank's threads and send each
 * result back, until rank 0 says stop. */
static int farm_follow(mpi_ctx *C, farm_state *F, size_t threads, pthread_t *tid)
{
  F->nring = threads;
  if (!(F->ring = calloc(threads, sizeof *F->ring)))
    follower_abort(C, MPI_SUCCESS, "out of memory");
  size_t nt = farm_start(F, tid, threads);
  if (nt == 0)
    follower_abort(C, MPI_SUCCESS, "cannot start a thread");
  long ns = AQ_MPI_POLL_MIN_NS;
  while (!C->stopped) {
    int active = 0, flag = 0, e, oom;
    MPI_Status st;
    if ((e = MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st)) != MPI_SUCCESS)
      follower_abort(C, e, "cannot hear from rank 0");
    if (flag) {
      uint64_t t = 0;
      if ((e = MPI_Recv(&t, 1, MPI_UINT64_T, 0, st.MPI_TAG, MPI_COMM_WORLD,
                        MPI_STATUS_IGNORE)) != MPI_SUCCESS)
        follower_abort(C, e, "cannot hear from rank 0");
      pthread_mutex_lock(&F->lock);
      if (st.MPI_TAG == TAG_STOP) {
        C->stopped = 1;
      } else if (F->count < F->nring) {
        F->ring[(F->head + F->count++) % F->nring] = (size_t)t;
        pthread_cond_signal(&F->cond);
      } else {
        pthread_mutex_unlock(&F->lock);
        follower_abort(C, MPI_SUCCESS, "rank 0 handed out more tasks than threads");
      }
      pthread_mutex_unlock(&F->lock);
      active = 1;
    }
    done_msg *d = farm_take_done(F, &oom);
    for (done_msg *x = d; x; x = x->next, active = 1)
      send_result(C, x->msg, x->n + sizeof(uint64_t));
    farm_free_done(d);
    if (oom)
      follower_abort(C, MPI_SUCCESS, "out of memory");
    pause_ns(&ns, active);
  }
  farm_join(F, tid, nt);
  free(F->ring);
  return 0;
}

/* Leader: stop every follower.  Returns 0, or -1 with err filled. */
static int stop_followers(mpi_ctx *C, aq_error *err)
{
  uint64_t zero = 0;
  for (int r = 1; r < C->size; r++) {
    int e = MPI_Send(&zero, 1, MPI_UINT64_T, r, TAG_STOP, MPI_COMM_WORLD);
    if (e != MPI_SUCCESS)
      return mpi_fail(C, err, e, "cannot stop", r);
  }
  return 0;
}

static int farm(void *ctx, const aq_farm_tasks *T, const size_t *todo, size_t ntodo,
                aq_error *err)
{
  mpi_ctx *C = ctx;
  size_t threads = T->threads > 0 ? (size_t)T->threads : 1;
  farm_state F;
  memset(&F, 0, sizeof F);
  F.T = T;
  F.follower = C->rank != 0;
  F.todo = todo;
  F.ntodo = ntodo;
  F.done_tail = &F.done;
  pthread_mutex_init(&F.lock, NULL);
  pthread_cond_init(&F.cond, NULL);
  pthread_t *tid = calloc(threads, sizeof *tid);
  int rc;
  if (!tid)
    rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory"), -1);
  else if (F.follower)
    rc = farm_follow(C, &F, threads, tid);
  else
    rc = farm_lead(C, &F, threads, tid, err);
  C->farmed = 1;
  if (rc == 0 && !F.follower) { /* the results are all in: stop the followers */
    rc = stop_followers(C, err);
    C->stopped_all = rc == 0;
  }
  free(tid);
  pthread_mutex_destroy(&F.lock);
  pthread_cond_destroy(&F.cond);
  return rc;
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
  /* capacity farms its tasks out when there are followers */
  int cap = C.size > 1 && !main_job && argc >= 2 && strcmp(argv[1], "capacity") == 0;
  int remote = C.size > 1 && (main_job || cap); /* the followers take part */
  aq_suite_remote R = {&C, C.rank != 0, fetch, next, send_result};
  aq_farm F = {&C, C.rank != 0, farm};
  if (cap)
    aq_farm_set(&F);
  int rc = AQ_EXIT_OK;

  if (C.rank == 0) {
    if (C.size > 1 && main_job && !(C.queued = calloc((size_t)C.size, sizeof *C.queued))) {
      fprintf(stderr, "archquake-mpi: out of memory\n");
      MPI_Abort(MPI_COMM_WORLD, AQ_EXIT_FAIL);
    }
    aq_suite_remote here = {&C, 0, NULL, NULL, NULL}; /* one rank: the suite runs here */
    aq_suite_set_remote(C.size > 1 && main_job ? &R : &here);
    rc = aq_main_serial(argc, argv);
    fflush(stdout);
    if (C.size > 1 && main_job && lead_finish(&C) != 0) {
      fflush(NULL);
      MPI_Abort(MPI_COMM_WORLD, rc != AQ_EXIT_OK ? rc : AQ_EXIT_FAIL);
    }
    aq_error err;
    if (cap && !C.broken && !C.stopped_all && stop_followers(&C, &err) != 0)
      aq_error_print(&err, stderr); /* the command ended before its tasks */
    if (C.broken) { /* the command failed the output already; stop the others */
      fflush(NULL);
      MPI_Abort(MPI_COMM_WORLD, rc != AQ_EXIT_OK ? rc : AQ_EXIT_FAIL);
    }
  } else if (remote) {
    int fd = dup(STDERR_FILENO);
    FILE *diag = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (diag)
      C.diag = diag;
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
      follower_abort(&C, MPI_SUCCESS, "cannot silence its output");
    aq_suite_set_remote(&R);
    rc = aq_main_serial(argc, argv);
    size_t i;
    while (!C.stopped) /* the command failed here but not on rank 0 */
      if (recv_task(&C, &i) == 0)
        follower_abort(&C, MPI_SUCCESS, main_job ? "cannot run records: the command fails on "
                                                   "this rank (run it alone there to see why)"
                                                 : "cannot run tasks: the command fails on "
                                                   "this rank (run it alone there to see why)");
    if (diag)
      fclose(diag);
    rc = AQ_EXIT_OK; /* rank 0's status is the run's */
  }
  MPI_Finalize();
  return rc;
}
