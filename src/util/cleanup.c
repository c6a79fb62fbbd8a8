/* cleanup.c: remove registered temporaries on SIGINT/SIGTERM/SIGHUP/SIGPIPE
 * (see cleanup.h). */
#define _POSIX_C_SOURCE 200809L
#include "cleanup.h"

#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#define AQ_CLEANUP_SLOTS 8
#define AQ_CLEANUP_PATH_MAX 4096

static char slot_path[AQ_CLEANUP_SLOTS][AQ_CLEANUP_PATH_MAX];
static volatile sig_atomic_t slot_used[AQ_CLEANUP_SLOTS];
static pthread_mutex_t slot_lock = PTHREAD_MUTEX_INITIALIZER; /* between threads (not the handler) */

static void on_signal(int sig)
{
  for (int i = 0; i < AQ_CLEANUP_SLOTS; i++)
    if (slot_used[i])
      unlink(slot_path[i]);
  signal(sig, SIG_DFL);
  raise(sig);
}

void aq_cleanup_install(void)
{
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
  for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigfillset(&sa.sa_mask); /* no other of ours while cleaning up */
    sigaction(sigs[i], &sa, NULL);
  }
}

int aq_cleanup_add(const char *path)
{
  size_t n = strlen(path);
  if (n >= AQ_CLEANUP_PATH_MAX)
    return -1;
  int slot = -1;
  pthread_mutex_lock(&slot_lock);
  for (int i = 0; i < AQ_CLEANUP_SLOTS && slot < 0; i++)
    if (!slot_used[i]) {
      memcpy(slot_path[i], path, n + 1);
      atomic_signal_fence(memory_order_seq_cst);
      slot_used[i] = 1; /* armed only once the path is complete */
      slot = i;
    }
  pthread_mutex_unlock(&slot_lock);
  return slot;
}

void aq_cleanup_remove(int slot)
{
  if (slot >= 0 && slot < AQ_CLEANUP_SLOTS)
    slot_used[slot] = 0;
}

int aq_cleanup_stale(const char *target)
{
  const char *slash = strrchr(target, '/');
  const char *base = slash ? slash + 1 : target;
  char dir[AQ_CLEANUP_PATH_MAX];
  snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - target) + 1 : 1,
           slash ? target : ".");
  DIR *d = opendir(dir);
  if (!d)
    return 0;
  int removed = 0;
  size_t nb = strlen(base);
  struct dirent *de;
  while ((de = readdir(d)) != NULL) {
    const char *n = de->d_name;
    if (strncmp(n, base, nb) != 0 || strncmp(n + nb, ".tmp.", 5) != 0)
      continue;
    char *end;
    errno = 0;
    long pid = strtol(n + nb + 5, &end, 10);
    if (*end != '\0' || end == n + nb + 5 || errno || pid <= 0 || pid == (long)getpid())
      continue;
    if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
      continue; /* its writer may still be running */
    char path[2 * AQ_CLEANUP_PATH_MAX];
    snprintf(path, sizeof path, "%s%s%s", slash ? "" : "./", slash ? dir : "", n);
    removed += unlink(path) == 0;
  }
  closedir(d);
  return removed;
}
