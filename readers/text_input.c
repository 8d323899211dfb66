#include <config.h>

#include "text_input.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BLOCK (1u << 20)
#define MAX_LINE (64u << 20)  /* a longer line is not a dump */

int text_open(text_input *t, const char *path, mimas_error *err)
{
    memset(t, 0, sizeof *t);
    t->path = strdup(path);
    t->buf = malloc(2 * BLOCK + 1 + TEXT_LINE_PAD);
    if (!t->path || !t->buf) {
        text_close(t);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the text reader");
    }
    t->cap = 2 * BLOCK;
    errno = 0;
    t->gz = gzopen(path, "rb");
    if (!t->gz) {
        int e = errno;
        text_close(t);
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open: %s", path,
                               e ? strerror(e) : "out of memory for the text reader");
    }
    gzbuffer(t->gz, BLOCK);
    return MIMAS_OK;
}

void text_close(text_input *t)
{
    if (t->gz)
        gzclose(t->gz);
    free(t->path);
    free(t->buf);
    memset(t, 0, sizeof *t);
}

int text_error(const text_input *t, mimas_error *err, const char *fmt, ...)
{
    if (!err)
        return MIMAS_EDATA;
    char msg[MIMAS_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return mimas_error_set(err, MIMAS_EDATA, "%s:%ld: %s", t->path, t->line, msg);
}

/* Reads more data after the unconsumed part; returns bytes read, 0 at end,
 * -1 on error. */
static long refill(text_input *t, int *rc, mimas_error *err)
{
    if (t->pos > 0) {
        memmove(t->buf, t->buf + t->pos, t->len - t->pos);
        t->len -= t->pos;
        t->pos = 0;
    }
    if (t->cap - t->len < BLOCK) {
        if (t->cap >= MAX_LINE) {
            t->line++;
            *rc = text_error(t, err, "line longer than %u MB: not a text dump", MAX_LINE >> 20);
            return -1;
        }
        char *b = realloc(t->buf, 2 * t->cap + 1 + TEXT_LINE_PAD);
        if (!b) {
            *rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the text reader");
            return -1;
        }
        t->buf = b;
        t->cap *= 2;
    }
    int n = gzread(t->gz, t->buf + t->len, BLOCK);
    if (n < 0) {
        int zerr;
        const char *msg = gzerror(t->gz, &zerr);
        *rc = mimas_error_set(err, MIMAS_EDATA, "%s: %s", t->path,
                              zerr == Z_ERRNO ? strerror(errno) : msg);
        return -1;
    }
    if (n == 0) {
        /* zlib reports a gzip stream cut short only through gzerror */
        int zerr;
        const char *msg = gzerror(t->gz, &zerr);
        if (zerr != Z_OK && zerr != Z_STREAM_END) {
            *rc = mimas_error_set(err, MIMAS_EDATA, "%s: compressed data are corrupt or cut "
                                  "short (%s)", t->path, msg);
            return -1;
        }
    }
    t->len += (size_t)n;
    memset(t->buf + t->len, 0, TEXT_LINE_PAD); /* what a last line's padding reads */
    return n;
}

char *text_line(text_input *t, size_t *len, int *rc, mimas_error *err)
{
    *rc = MIMAS_OK;
    for (;;) {
        char *start = t->buf + t->pos;
        size_t avail = t->len - t->pos;
        char *nl = avail ? memchr(start, '\n', avail) : NULL;
        if (nl || (t->eof && avail)) {
            size_t n = nl ? (size_t)(nl - start) : avail;
            t->pos += nl ? n + 1 : n;
            t->line++;
            if (n && start[n - 1] == '\r')
                n--;
            start[n] = '\0';
            if (memchr(start, '\0', n)) {
                *rc = text_error(t, err, "binary data (NUL byte): not a text file");
                return NULL;
            }
            *len = n;
            return start;
        }
        if (t->eof)
            return NULL;
        long got = refill(t, rc, err);
        if (got < 0)
            return NULL;
        if (got == 0)
            t->eof = 1;
    }
}
