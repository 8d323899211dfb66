/* Line-by-line reading of text files, plain or gzip-compressed (zlib reads
 * both), in large blocks, with line numbers for error messages. */
#ifndef MIMAS_TEXT_INPUT_H
#define MIMAS_TEXT_INPUT_H

#include <stddef.h>
#include <zlib.h>

#include "error.h"

typedef struct text_input {
    gzFile gz;
    char *path;
    char *buf;
    size_t cap, len, pos;  /* buffer, bytes in it, start of the next line */
    long line;             /* number of the line last returned (1-based) */
    int eof;
} text_input;

enum { TEXT_LINE_PAD = 8 };

int text_open(text_input *t, const char *path, mimas_error *err);
/* The next line without its newline, NUL-terminated and writable, valid until
 * the next call; *len its length.  TEXT_LINE_PAD bytes after its NUL can be
 * read (what follows in the buffer, or zeros): word-wise parsing may look past
 * the end (parse_double_in_line).  Returns NULL at the end of the file (rc
 * MIMAS_OK) or on an error (rc set, err filled: unreadable, binary, corrupt
 * gzip data). */
char *text_line(text_input *t, size_t *len, int *rc, mimas_error *err);
/* Error "PATH:LINE: message" for the line last returned. */
int text_error(const text_input *t, mimas_error *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void text_close(text_input *t);

#endif
