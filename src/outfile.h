/* Outputs written under a temporary name and renamed into place (no partial
 * output) must not replace what is not a regular file: renamed onto
 * /dev/null or a named pipe, a finished file would take its place (and, as
 * root, that is the system's /dev/null). */
#ifndef MIMAS_OUTFILE_H
#define MIMAS_OUTFILE_H

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 if path exists and is not a regular file (a device, a pipe, a folder). */
int mimas_output_is_special(const char *path);
/* MIMAS_OK if a finished file may be renamed onto path (absent or a regular
 * file); else MIMAS_EUSAGE "PATH: not a regular file (a device or a pipe
 * cannot take this output)". */
int mimas_output_check(const char *path, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
