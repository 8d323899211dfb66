/* Fuzz target: MercuryDPM input.  The first byte picks what the rest is: a
 * .data file alone, or an .fstat file beside a fixed, valid .data file
 * (3 particles at t = 0 and t = 0.1). */
#include <config.h>

#include <unistd.h>

#include "fuzz_input.h"

static const char data_text[] = "3 0 0 0 0 1 1 1\n"
                                "0.2 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n"
                                "0.38 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n"
                                "0.8 0.8 0.8 0 0 0 0.1 0 0 0 0 0 0 1\n"
                                "3 0.1 0 0 0 1 1 1\n"
                                "0.2 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n"
                                "0.38 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n"
                                "0.8 0.8 0.8 0 0 0 0.1 0 0 0 0 0 0 1\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.format = "mercury";
    o.density = 1000;
    o.allow_missing_contacts = (data[0] >> 1) & 1;
    const char *path;
    const char *fstat = NULL;
    if (data[0] & 1) {
        path = fuzz_file((const uint8_t *)data_text, sizeof data_text - 1, "data", 0);
        fstat = fuzz_file(data + 1, size - 1, "fstat", 1);
        if (!path || !fstat)
            return 0;
        o.contacts = &fstat;
        o.ncontacts = 1;
    } else {
        path = fuzz_file(data + 1, size - 1, "data", 0);
        if (!path)
            return 0;
    }
    fuzz_read_all(&path, 1, &o);
    unlink(path);
    if (fstat)
        unlink(fstat);
    return 0;
}
