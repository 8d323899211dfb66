/* The registry of temporary output files (see tmpfiles.h). */
#include <config.h>

#include "tmpfiles.h"

#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define SLOTS 32
#define NAME_MAX_LEN 4352

enum { FREE = 0, CLAIMED = 1, LIVE = 2 };

static atomic_int state[SLOTS];
static char names[SLOTS][NAME_MAX_LEN];

int mimas_tmpfile_name(char *buf, size_t cap, const char *path)
{
    int w = snprintf(buf, cap, "%s.tmp%ld", path, (long)getpid());
    return w < 0 || (size_t)w >= cap ? -1 : 0;
}

int mimas_tmpfile_add(const char *path)
{
    size_t len = strlen(path);
    if (len >= NAME_MAX_LEN)
        return -1;
    for (int k = 0; k < SLOTS; k++) {
        int expected = FREE;
        if (atomic_compare_exchange_strong(&state[k], &expected, CLAIMED)) {
            memcpy(names[k], path, len + 1);
            atomic_store(&state[k], LIVE);
            return k;
        }
    }
    return -1;
}

void mimas_tmpfile_forget(int slot)
{
    if (slot >= 0 && slot < SLOTS)
        atomic_store(&state[slot], FREE);
}

void mimas_tmpfile_remove_all(void)
{
    for (int k = 0; k < SLOTS; k++)
        if (atomic_load(&state[k]) == LIVE)
            unlink(names[k]);
}
