/* Output files are written under a temporary name and renamed into place
 * when complete (no partial output).  That only makes sense for regular
 * files: renaming over /dev/null, /dev/stdout or a named pipe would replace
 * the device or pipe with a file. */
#ifndef MIMAS_OUTFILE_H
#define MIMAS_OUTFILE_H

/* 1 if path names something that exists and is not a regular file (a
 * device, a pipe, a directory; links followed), else 0. */
int mimas_path_is_special(const char *path);

#endif
