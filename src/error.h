/* mimas error reporting: the library never prints or exits; it fills a
 * mimas_error and returns its code.  The front end prints the message and
 * maps the code to an exit status (exit status 0, 1 for bad usage, 2 for bad data). */
#ifndef MIMAS_ERROR_H
#define MIMAS_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

enum mimas_status {
    MIMAS_OK = 0,
    MIMAS_EUSAGE = 1,   /* bad arguments: exit status 1 */
    MIMAS_EDATA = 2,    /* bad or unreadable input data: exit status 2 */
    MIMAS_EIO = 3,      /* the system refused (cannot write, no memory): exit status 2 */
    MIMAS_EMISSING = 4, /* a quantity the computation needs is absent: exit status 2 */
    MIMAS_END = 5       /* not an error: a stream has no more frames */
};

/* room for two file names of PATH_MAX and the problem: a message is never cut */
#define MIMAS_ERROR_MSG_MAX 9216

typedef struct mimas_error {
    int code;                        /* enum mimas_status */
    char msg[MIMAS_ERROR_MSG_MAX];   /* one line, no trailing newline */
} mimas_error;

/* Sets err (if not NULL) and returns code.  The message is printf-formatted. */
int mimas_error_set(mimas_error *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prefixes an existing message with "prefix: " (e.g. the file name). */
int mimas_error_prefix(mimas_error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

void mimas_error_clear(mimas_error *err);

/* Exit status for a code: 0 (also for MIMAS_END), 1 (usage) or 2 (everything else). */
int mimas_exit_status(int code);

#ifdef __cplusplus
}
#endif
#endif
