#include <config.h>

#include "fuzz_input.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix, int slot)
{
    static char path[4][256];
    snprintf(path[slot], sizeof path[slot], "%s/mimas-fuzz-%ld-%d.%s",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (long)getpid(), slot, suffix);
    FILE *fp = fopen(path[slot], "wb");
    if (!fp)
        return NULL;
    if (size && fwrite(data, 1, size, fp) != size) {
        fclose(fp);
        return NULL;
    }
    fclose(fp);
    return path[slot];
}

void fuzz_read_all(const char *const *inputs, size_t n, const mimas_reader_options *o)
{
    mimas_reader *r;
    mimas_error err;
    if (mimas_reader_open(&r, inputs, n, o, &err) != MIMAS_OK)
        return;
    mimas_frame f;
    mimas_frame_init(&f);
    for (int k = 0; k < 1000 && mimas_reader_next(r, &f, &err) == MIMAS_OK; k++)
        ;
    mimas_frame_free(&f);
    mimas_reader_close(r);
}
