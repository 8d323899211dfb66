/* Fuzz target: a per-atom LAMMPS/LIGGGHTS dump. */
#include <config.h>

#include <unistd.h>

#include "fuzz_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, "dump", 0);
    if (!path)
        return 0;
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.format = "lammps";
    o.density = 2500; /* exercise the mass path too */
    fuzz_read_all(&path, 1, &o);
    unlink(path);
    return 0;
}
