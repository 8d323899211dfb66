/* Fuzz target: the thermo output of a LAMMPS/LIGGGHTS log (readers/thermo_log.c).
 * The first byte picks the time step given (none or 1e-5) and whether
 * a Time column is asked for among the columns. */
#include <config.h>

#include <stdlib.h>
#include <unistd.h>

#include "fuzz_input.h"
#include "thermo_log.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    const char *path = fuzz_file(data + 1, size - 1, "log", 0);
    if (!path)
        return 0;
    const char *names[4] = {"KinEng", "rke", "Step", "Time"};
    size_t n = (data[0] & 2) ? 4 : 2;
    mimas_thermo_log *log;
    mimas_error err;
    if (mimas_thermo_log_open(&log, path, names, n, (data[0] & 1) ? 1e-5 : 0, &err) == MIMAS_OK) {
        int64_t step;
        double t, v[4];
        while (mimas_thermo_log_next(log, &step, &t, v, &err) == MIMAS_OK)
            ;
        for (size_t k = 0; k < n; k++)
            (void)mimas_thermo_log_has(log, k);
        mimas_thermo_log_close(log);
    }
    unlink(path);
    return 0;
}
