#include <config.h>

#include "mimas.h"

const char *mimas_version(void)
{
    return PACKAGE_VERSION;
}
