/* cleanup.h: temporary files removed when SIGINT, SIGTERM, SIGHUP or
 * SIGPIPE (stdout closed early, as by `| head`) ends the process, so that an
 * interrupted run leaves no partial output.  The handler unlinks every
 * registered path, then re-raises the signal with its default action (the
 * exit status says which signal).  Paths are copied
 * into static slots; the handler only reads them (async-signal-safe). */
#ifndef AQ_UTIL_CLEANUP_H
#define AQ_UTIL_CLEANUP_H

/* Install the handlers (idempotent). */
void aq_cleanup_install(void);

/* Register path; returns a slot number, or -1 if all slots are taken or the
 * path is too long (then it is not removed on a signal). */
int aq_cleanup_add(const char *path);

/* Forget slot (after the file was renamed or removed); -1 is ignored. */
void aq_cleanup_remove(int slot);

/* Remove the temporaries "<target>.tmp.<pid>" that a process killed
 * outright (kill -9, a crash) left beside target: those whose pid no longer
 * exists.  Returns how many were removed. */
int aq_cleanup_stale(const char *target);

#endif
