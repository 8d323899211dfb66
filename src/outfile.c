#include <config.h>

#include "outfile.h"

#include <sys/stat.h>

int mimas_path_is_special(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && !S_ISREG(st.st_mode);
}
