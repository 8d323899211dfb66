#include <config.h>

#include "particle_frame.h"

#include <math.h>

int particle_frame(mimas_frame *f, size_t n, unsigned bits, double time, mimas_error *err)
{
    mimas_frame_clear(f);
    f->time = time;
    f->step = (int64_t)lround(time * 1000);
    int rc = mimas_table_set_present(&f->particles, &mimas_particles_desc,
                                     MIMAS_P_ID | MIMAS_P_POS | bits, err);
    return rc ? rc : mimas_table_resize(&f->particles, &mimas_particles_desc, n, err);
}
