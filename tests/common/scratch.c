#include <config.h>

#include "scratch.h"

#include <stdio.h>
#include <stdlib.h>

static char dir[] = "/tmp/mimas-test-XXXXXX";

int scratch_setup(void **state)
{
    (void)state;
    return mkdtemp(dir) ? 0 : -1;
}

int scratch_teardown(void **state)
{
    (void)state;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd);
}

const char *scratch_path(const char *name)
{
    static char buf[32][256];
    static int k;
    k = (k + 1) % 32;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}
