/* h5_sync.c: the background sync of the results writer's temporary
 * (h5_writer.h).
 *
 * The temporary is fdatasync'ed by a thread of the writer's own while the
 * suite runs, every AQ_H5_SYNC_BYTES of datasets, so that the fsync that
 * aq_h5_finish must do before the rename finds almost everything already on
 * disk (for a 36 MB file: 3 ms instead of 30 ms at the end of the suite,
 * when nothing else is left to run).  The thread only syncs a descriptor: it
 * never enters the HDF5 library.  It starts at the first request, so a
 * file with less than AQ_H5_SYNC_BYTES of datasets (the main job's file for
 * a few hundred runs) never starts one.  The final fsync is unchanged; a
 * failed background sync fails aq_h5_finish (its error is reported to that
 * descriptor only once). */
#include <errno.h>
#include <unistd.h>

#include "h5_writer.h"

static void *sync_main(void *arg)
{
  aq_h5_writer *w = arg;
  pthread_mutex_lock(&w->sync_lock);
  for (;;) {
    while (!w->sync_request && !w->sync_quit)
      pthread_cond_wait(&w->sync_cond, &w->sync_lock);
    if (w->sync_quit)
      break;
    w->sync_request = 0;
    pthread_mutex_unlock(&w->sync_lock);
    int e = fdatasync(w->sync_fd) != 0 ? errno : 0;
    pthread_mutex_lock(&w->sync_lock);
    if (e && !w->sync_errno)
      w->sync_errno = e;
  }
  pthread_mutex_unlock(&w->sync_lock);
  return NULL;
}

/* Start the syncing thread (nothing happens if it cannot be started: the
 * final fsync does all the work then). */
static void sync_start(aq_h5_writer *w)
{
  if (w->sync_fd < 0)
    return;
  if (pthread_mutex_init(&w->sync_lock, NULL) != 0)
    return;
  if (pthread_cond_init(&w->sync_cond, NULL) != 0) {
    pthread_mutex_destroy(&w->sync_lock);
    return;
  }
  if (pthread_create(&w->sync_thread, NULL, sync_main, w) != 0) {
    pthread_cond_destroy(&w->sync_cond);
    pthread_mutex_destroy(&w->sync_lock);
    return;
  }
  w->sync_thread_on = 1;
}

void aq_h5w_sync_stop(aq_h5_writer *w)
{
  if (!w->sync_thread_on)
    return;
  pthread_mutex_lock(&w->sync_lock);
  w->sync_quit = 1;
  pthread_cond_signal(&w->sync_cond);
  pthread_mutex_unlock(&w->sync_lock);
  pthread_join(w->sync_thread, NULL);
  pthread_cond_destroy(&w->sync_cond);
  pthread_mutex_destroy(&w->sync_lock);
  w->sync_thread_on = 0;
}

/* (starts the thread at the first request) */
void aq_h5w_sync_hint(aq_h5_writer *w, size_t bytes)
{
  w->sync_pending += bytes;
  if (w->sync_pending < AQ_H5_SYNC_BYTES)
    return;
  w->sync_pending = 0;
  if (!w->sync_tried) {
    w->sync_tried = 1;
    sync_start(w);
  }
  if (!w->sync_thread_on)
    return;
  pthread_mutex_lock(&w->sync_lock);
  w->sync_request = 1;
  pthread_cond_signal(&w->sync_cond);
  pthread_mutex_unlock(&w->sync_lock);
}
