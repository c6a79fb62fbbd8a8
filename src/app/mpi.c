/* mpi.c: archquake-mpi, the main job and capacity over Open MPI ranks
 * (docs/cluster.md).
 *
 * `mpirun -n N archquake-mpi ARGS...` takes archquake's arguments.  Every
 * rank parses them the same way and runs the command up to its tasks
 * (farm.h): a (record, arch) of the main job, a (subject, arch) of
 * capacity, every factor, polarity and azimuth of it.  Rank 0 leads: it
 * keeps one task per thread of each follower (-j, the same on every rank)
 * and AQ_MPI_QUEUED_EXTRA more at it, giving a rank the next task of the
 * record it last had when it can (pick), runs tasks on its own -j threads
 * between messages, and
 * takes every result on its main thread; the command then writes them as
 * archquake does (the main job in record order as records complete, with
 * its journal and --resume; capacity at the end), so the outputs are those
 * of `archquake -j 1`.  A follower runs the tasks it is given on its
 * threads, reading and processing each record itself (it keeps the last
 * few for the record's other arches), and sends each result back as bytes.
 * With one rank the command runs here, threads and all.
 *
 * Only the main thread of a rank calls MPI (MPI_THREAD_FUNNELED).  It
 * polls (MPI_Iprobe, MPI_Test) and sleeps between polls, from
 * AQ_MPI_POLL_MIN_NS doubling to AQ_MPI_POLL_MAX_NS while nothing comes:
 * Open MPI's blocking calls spin, and a spinning leader would take a core
 * from the ranks that compute.
 *
 * Every MPI call's status is checked (MPI_ERRORS_RETURN): a failed exchange
 * fails the outputs (no partial file) and aborts the job.  A rank that
 * dies makes mpirun end the others with SIGTERM, which removes rank 0's
 * temporaries (cleanup.h); the main job's journal stays for --resume.
 * (Rank 0 itself killed with SIGKILL leaves its temporaries, as archquake
 * does; --resume removes them.)
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

#include "../util/pool.h"
#include "app.h"
#include "farm.h"


/* A rank with nothing to do sleeps between polls, AQ_MPI_POLL_MIN_NS at
 * first, doubling to AQ_MPI_POLL_MAX_NS while nothing comes: an idle rank
 * costs its core almost nothing, and a task (a record's runs of an arch,
 * or a capacity scan) outlasts the longest pause many times. */
#define AQ_MPI_POLL_MIN_NS 20000L
#define AQ_MPI_POLL_MAX_NS 2000000L
/* Tasks waiting at each follower beyond one per thread: a thread that
 * finishes finds the next at once, not a message round trip later (ranks
 * that share cores wake late). */
#define AQ_MPI_QUEUED_EXTRA 1

enum { TAG_TASK = 1, TAG_STOP = 2, TAG_RESULT = 3 };

typedef struct {
  int rank, size;
  int broken;      /* an MPI call failed */
  FILE *diag;      /* a follower's own messages (its stderr is /dev/null) */
  double t_init;   /* MPI_Wtime after MPI_Init (AQ_MPI_DEBUG_FIRST_TASK) */
  int stopped;     /* follower: rank 0 said stop */
  int stopped_all; /* leader: the followers were told to stop */
} mpi_ctx;

/* Sleep *ns unless something happened (active), then double it up to the
 * most; activity resets it to the least. */
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

static int wait_req(MPI_Request *rq, MPI_Status *st)
{
  long ns = AQ_MPI_POLL_MIN_NS;
  for (;;) {
    int flag = 0, e = MPI_Test(rq, &flag, st);
    if (e != MPI_SUCCESS || flag)
      return e;
    pause_ns(&ns, 0);
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

static void send_result(mpi_ctx *C, const void *data, size_t n)
{
  if (n > (size_t)INT32_MAX)
    follower_abort(C, MPI_SUCCESS, "a task's results exceed one MPI message");
  MPI_Request rq;
  int e = MPI_Isend(data, (int)n, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD, &rq);
  if (e == MPI_SUCCESS)
    e = wait_req(&rq, MPI_STATUS_IGNORE);
  if (e != MPI_SUCCESS)
    follower_abort(C, e, "cannot send results to rank 0");
}

/* ---- the farm (farm.h) ------------------------------------------------- */

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
  const size_t *todo;   /* leader: the tasks (increasing) */
  size_t ntodo;
  size_t next;          /* leader: todo[next] is the first not handed out */
  size_t limit;         /* leader: no todo[p] with p >= limit goes out yet */
  unsigned char *given; /* leader: per place in todo: handed out */
  unsigned char *begun; /* leader: per group: some task of it handed out */
  size_t *last;         /* leader: per rank: the group of its last task */
  size_t *ring;         /* follower: tasks received, not started */
  size_t nring, head, count;
  int stop;             /* no more tasks will come */
  int sent_any;         /* leader: a task went to a follower */
  int oom;              /* a task could not run (out of memory) */
  done_msg *done, **done_tail; /* results of this rank's threads, in order */
} farm_state;

/* Leader (F->lock held): the place in todo of the next task for rank r,
 * or ntodo when none may go out now.  Tasks of a group share their input
 * (a record's arches), so a rank gets the next of its last task's group;
 * else the first of a group no rank has begun; else (the window is all
 * begun) any, so no rank idles while tasks wait. */
static size_t pick(farm_state *F, int r)
{
  size_t G = F->T->group ? F->T->group : 1, none = F->ntodo, NONE = (size_t)-1;
  while (F->next < F->ntodo && F->given[F->next])
    F->next++;
  size_t end = F->limit < F->ntodo ? F->limit : F->ntodo, mine = none, fresh = none,
         any = none, gl = F->last[r];
  for (size_t p = F->next; p < end && mine == none; p++) {
    size_t g = F->todo[p] / G;
    if (F->given[p])
      continue;
    if (g == gl)
      mine = p;
    if (any == none)
      any = p;
    if (fresh == none && !F->begun[g])
      fresh = p;
    if (fresh != none && (gl == NONE || g > gl))
      break; /* groups increase: none of gl's further on */
  }
  size_t p = mine != none ? mine : fresh != none ? fresh : any;
  if (p != none) {
    F->given[p] = 1;
    F->begun[F->todo[p] / G] = 1;
    F->last[r] = F->todo[p] / G;
  }
  return p;
}

/* A worker thread: runs this rank's tasks, one at a time (no MPI here). */
static void farm_worker(void *arg, size_t k)
{
  (void)k;
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
      size_t p = F->ntodo;
      while (!F->stop && F->next < F->ntodo && (p = pick(F, 0)) == F->ntodo)
        pthread_cond_wait(&F->cond, &F->lock); /* the window moves on */
      if (p == F->ntodo)
        break;
      t = F->todo[p];
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

/* Start nt worker threads into *pool; returns how many started (the
 * caller joins them with farm_join). */
static size_t farm_start(farm_state *F, aq_pool **pool, size_t nt)
{
  size_t k = 0;
  *pool = aq_pool_start(nt, farm_worker, F, &k);
  return k;
}

static void farm_join(farm_state *F, aq_pool *pool)
{
  pthread_mutex_lock(&F->lock);
  F->stop = 1;
  pthread_cond_broadcast(&F->cond);
  pthread_mutex_unlock(&F->lock);
  aq_pool_join(pool);
  int oom;
  farm_free_done(farm_take_done(F, &oom));
}

/* Leader: hand tasks to the followers, one per thread of theirs and
 * AQ_MPI_QUEUED_EXTRA more each, run tasks on its own threads between, and
 * take every result. */
static int farm_lead(mpi_ctx *C, farm_state *F, size_t threads, aq_error *err)
{
  const aq_farm_tasks *T = F->T;
  size_t nmax = T->ntask ? T->ntask : 1;
  int *owner = malloc(nmax * sizeof *owner);   /* per task: the rank it went to */
  size_t *pos = malloc(nmax * sizeof *pos);    /* per task: its place in todo */
  unsigned char *taken = calloc(F->ntodo ? F->ntodo : 1, 1); /* per place */
  size_t *queued = calloc((size_t)C->size, sizeof *queued);
  F->given = calloc(F->ntodo ? F->ntodo : 1, 1);
  F->begun = calloc(nmax, 1);
  F->last = malloc((size_t)C->size * sizeof *F->last);
  int rc = 0;
  if (!owner || !pos || !taken || !queued || !F->given || !F->begun || !F->last)
    rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "out of memory"), -1);
  for (int r = 0; F->last && r < C->size; r++)
    F->last[r] = (size_t)-1;
  for (size_t t = 0; rc == 0 && t < T->ntask; t++)
    owner[t] = -1;
  for (size_t k = 0; rc == 0 && k < F->ntodo; k++)
    pos[F->todo[k]] = k;
  size_t ahead = T->ahead ? T->ahead * threads * (size_t)C->size : F->ntodo, lowest = 0;
  F->limit = ahead;
  aq_pool *pool = NULL;
  size_t nt = rc == 0 ? farm_start(F, &pool, threads) : 0, ndone = 0;
  if (rc == 0 && nt == 0)
    rc = (aq_error_set(err, AQ_ENOMEM, "MPI", -1, -1, NULL, "cannot start a thread"), -1);
  long ns = AQ_MPI_POLL_MIN_NS;
  while (rc == 0 && ndone < F->ntodo) {
    int active = 0, e, oom;
    for (int r = 1; rc == 0 && r < C->size; r++)
      while (rc == 0 && queued[r] < threads + AQ_MPI_QUEUED_EXTRA) {
        pthread_mutex_lock(&F->lock);
        size_t k = pick(F, r);
        pthread_mutex_unlock(&F->lock);
        if (k >= F->ntodo)
          break;
        uint64_t t64 = F->todo[k];
        if ((e = MPI_Send(&t64, 1, MPI_UINT64_T, r, TAG_TASK, MPI_COMM_WORLD)) != MPI_SUCCESS)
          rc = mpi_fail(C, err, e, "cannot hand a task to", r);
        if (rc == 0 && !F->sent_any) { /* a debug timing, on request */
          F->sent_any = 1;
          if (getenv("AQ_MPI_DEBUG_FIRST_TASK"))
            fprintf(stderr, "archquake-mpi: first task handed out %.6f s after MPI_Init\n",
                    MPI_Wtime() - C->t_init);
        }
        owner[F->todo[k]] = r;
        queued[r]++;
        active = 1;
      }
    done_msg *d = farm_take_done(F, &oom);
    for (done_msg *x = d; rc == 0 && x; x = x->next, active = 1, ndone++) {
      rc = T->take(T->ctx, x->t, x->msg + sizeof(uint64_t), x->n, err);
      taken[pos[x->t]] = 1;
    }
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
        taken[pos[t]] = 1;
        queued[src]--;
        ndone++;
        active = 1;
      }
      free(m);
    }
    while (lowest < F->ntodo && taken[lowest]) /* move the window on */
      lowest++;
    if (lowest + ahead > F->limit) {
      pthread_mutex_lock(&F->lock);
      F->limit = lowest + ahead;
      pthread_cond_broadcast(&F->cond);
      pthread_mutex_unlock(&F->lock);
    }
    pause_ns(&ns, active);
  }
  farm_join(F, pool);
  free(owner);
  free(pos);
  free(taken);
  free(queued);
  free(F->given);
  free(F->begun);
  free(F->last);
  if (rc != 0)
    C->broken = 1;
  return rc;
}

/* Follower: take tasks from rank 0 onto this rank's threads and send each
 * result back, until rank 0 says stop. */
static int farm_follow(mpi_ctx *C, farm_state *F, size_t threads)
{
  F->nring = threads + AQ_MPI_QUEUED_EXTRA;
  if (!(F->ring = calloc(F->nring, sizeof *F->ring)))
    follower_abort(C, MPI_SUCCESS, "out of memory");
  aq_pool *pool = NULL;
  size_t nt = farm_start(F, &pool, threads);
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
        follower_abort(C, MPI_SUCCESS, "rank 0 handed out more tasks than it may");
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
  farm_join(F, pool);
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
  int rc;
  if (F.follower)
    rc = farm_follow(C, &F, threads);
  else
    rc = farm_lead(C, &F, threads, err);
  if (rc == 0 && !F.follower) { /* the results are all in: stop the followers */
    rc = stop_followers(C, err);
    C->stopped_all = rc == 0;
  }
  pthread_mutex_destroy(&F.lock);
  pthread_cond_destroy(&F.cond);
  return rc;
}

/* ---- entry -------------------------------------------------------------- */

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
  C.t_init = MPI_Wtime();
  MPI_Comm_rank(MPI_COMM_WORLD, &C.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &C.size);
  /* the commands the table marks (the main job and capacity) farm their
   * tasks out when there are followers */
  int farmed = C.size > 1 && aq_app_farms(argc, argv);
  aq_farm F = {&C, C.rank != 0, farmed ? farm : NULL};
  aq_farm_set(&F); /* with one rank, or another command: runs here */
  int rc = AQ_EXIT_OK;

  if (C.rank == 0) {
    rc = aq_app_main(argc, argv);
    fflush(stdout);
    aq_error err;
    if (farmed && !C.broken && !C.stopped_all && stop_followers(&C, &err) != 0)
      aq_error_print(&err, stderr); /* the command ended before its tasks */
    if (C.broken) { /* the command failed the output already; stop the others */
      fflush(NULL);
      MPI_Abort(MPI_COMM_WORLD, rc != AQ_EXIT_OK ? rc : AQ_EXIT_FAIL);
    }
  } else if (farmed) {
    int fd = dup(STDERR_FILENO);
    FILE *diag = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (diag)
      C.diag = diag;
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
      follower_abort(&C, MPI_SUCCESS, "cannot silence its output");
    rc = aq_app_main(argc, argv);
    size_t i;
    while (!C.stopped) /* the command failed here but not on rank 0 */
      if (recv_task(&C, &i) == 0)
        follower_abort(&C, MPI_SUCCESS, "cannot run tasks: the command fails on this rank "
                                        "(run it alone there to see why)");
    if (diag)
      fclose(diag);
    rc = AQ_EXIT_OK; /* rank 0's status is the run's */
  }
  MPI_Finalize();
  return rc;
}
