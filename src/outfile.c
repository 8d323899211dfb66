#include <config.h>

#include "outfile.h"

#include <sys/stat.h>

int mimas_output_is_special(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && !S_ISREG(st.st_mode);
}

int mimas_output_check(const char *path, mimas_error *err)
{
    if (mimas_output_is_special(path))
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: not a regular file (a device or a pipe "
                               "cannot take this output)", path);
    return MIMAS_OK;
}
