#include <config.h>

#include "liggghts_set.h"

#include <stdio.h>
#include <stdlib.h>

const char *liggghts_data(const char *rel)
{
    static char buf[8][512];
    static int k;
    k = (k + 1) % 8;
    const char *top = getenv("TEST_SRCDIR");
    snprintf(buf[k], sizeof buf[k], "%s/data/liggghts/%s", top ? top : "tests", rel);
    return buf[k];
}

int liggghts_open(mimas_reader **r, const char *atoms, const char *pgl, const char *wgl,
                  mimas_error *err)
{
    const char *inputs[1] = {atoms}, *contacts[1] = {pgl}, *walls[1] = {wgl};
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    if (pgl) {
        o.contacts = contacts;
        o.ncontacts = 1;
        o.contact_columns = LIGGGHTS_KEYS;
    }
    if (wgl) {
        o.walls = walls;
        o.nwalls = 1;
        o.wall_columns = LIGGGHTS_KEYS;
    }
    return mimas_reader_open(r, inputs, 1, &o, err);
}

int liggghts_last_frame(const char *atoms, const char *pgl, const char *wgl, mimas_frame *f,
                        mimas_error *err)
{
    mimas_reader *r;
    int rc = liggghts_open(&r, atoms, pgl, wgl, err);
    if (rc)
        return rc;
    size_t n = 0;
    while ((rc = mimas_reader_next(r, f, err)) == MIMAS_OK)
        n++;
    mimas_reader_close(r);
    if (rc == MIMAS_END && n == 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no frames", atoms);
    return rc == MIMAS_END ? MIMAS_OK : rc;
}
