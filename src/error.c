#include <config.h>

#include "error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int mimas_error_set(mimas_error *err, int code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return code;
}

int mimas_error_prefix(mimas_error *err, const char *fmt, ...)
{
    if (!err)
        return MIMAS_OK;
    char joined[2 * MIMAS_ERROR_MSG_MAX + 2];
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(joined, MIMAS_ERROR_MSG_MAX, fmt, ap);
    va_end(ap);
    size_t at = w < 0 ? 0 : (w >= MIMAS_ERROR_MSG_MAX ? MIMAS_ERROR_MSG_MAX - 1 : (size_t)w);
    memcpy(joined + at, ": ", 2);
    memcpy(joined + at + 2, err->msg, sizeof err->msg);
    joined[sizeof joined - 1] = '\0';
    memcpy(err->msg, joined, sizeof err->msg - 1);
    err->msg[sizeof err->msg - 1] = '\0';
    return err->code;
}

void mimas_error_clear(mimas_error *err)
{
    if (err) {
        err->code = MIMAS_OK;
        err->msg[0] = '\0';
    }
}

int mimas_exit_status(int code)
{
    if (code == MIMAS_OK || code == MIMAS_END)
        return 0;
    return code == MIMAS_EUSAGE ? 1 : 2;
}
