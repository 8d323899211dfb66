/* Temporary output files: every writer of mimas writes NAME under the
 * temporary name NAME.tmpPID and renames it into place when complete, so no
 * partial output appears under the final name.  The names being written are
 * kept in one small registry that a signal handler can empty: on SIGINT,
 * SIGTERM, SIGHUP or SIGPIPE the program removes them before it dies
 * (cli_cleanup_on_signals).  SIGKILL cannot be caught: it can leave a
 * NAME.tmpPID behind, which is safe to delete.
 *
 * The registry is the one piece of process-wide state of the library; its
 * slots are claimed with atomic operations, so writers on several threads
 * may use it. */
#ifndef MIMAS_TMPFILES_H
#define MIMAS_TMPFILES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The temporary name of path for this process ("PATH.tmpPID") into buf;
 * 0, or -1 if it does not fit. */
int mimas_tmpfile_name(char *buf, size_t cap, const char *path);
/* Registers a file to remove on a signal; returns its slot (>= 0), or -1 if
 * the registry is full or the name too long (the file is then only removed
 * by the writer itself). */
int mimas_tmpfile_add(const char *path);
/* Forgets slot (after the file was renamed or removed); -1 is ignored. */
void mimas_tmpfile_forget(int slot);
/* Removes every registered file; async-signal-safe. */
void mimas_tmpfile_remove_all(void);

#ifdef __cplusplus
}
#endif
#endif
