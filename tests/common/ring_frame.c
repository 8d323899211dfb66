#include <config.h>

#include "ring_frame.h"

#include <gsl/gsl_randist.h>
#include <math.h>

void ring_spec_default(ring_spec *s)
{
    /* Uhlig (2012): r_in 0.0147 m, r_out 0.11 m, fill height 0.038 m, d = 2 mm,
     * rho = 2000 kg/m3, Omega = 2 pi 0.01 rad/s; Table 4.8 dry: Rc 0.0777 m,
     * W 0.0246 m (at the surface) */
    s->r_in = 0.0147;
    s->r_out = 0.11;
    s->height = 0.038;
    s->diameter = 0.002;
    s->density = 2000;
    s->omega = 2 * M_PI * 0.01;
    s->rc = 0.0777;
    s->rc_slope = 0;
    s->w = 0.0246;
    s->noise = 0;
    s->particles = 1000;
}

double ring_profile(const ring_spec *s, double r, double z)
{
    return 0.5 + 0.5 * erf((r - (s->rc + s->rc_slope * z)) / s->w);
}

int ring_frame(mimas_frame *f, gsl_rng *rng, const ring_spec *s, int64_t step)
{
    mimas_frame_clear(f);
    f->step = step;
    f->time = (double)step * 1e-3;
    for (int d = 0; d < 2; d++) {
        f->box.lo[d] = -s->r_out;
        f->box.hi[d] = s->r_out;
    }
    f->box.lo[2] = 0;
    f->box.hi[2] = s->height;
    mimas_error err;
    mimas_particles *p = &f->particles;
    unsigned bits = MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_POS |
                    MIMAS_P_VEL;
    if (mimas_table_set_present(p, &mimas_particles_desc, bits, &err) ||
        mimas_table_resize(p, &mimas_particles_desc, s->particles, &err))
        return -1;
    double a = 0.5 * s->diameter;
    double r2lo = (s->r_in + a) * (s->r_in + a), r2hi = (s->r_out - a) * (s->r_out - a);
    for (size_t k = 0; k < s->particles; k++) {
        /* uniform over the annulus: r^2 uniform */
        double r = sqrt(r2lo + (r2hi - r2lo) * gsl_rng_uniform(rng));
        double phi = 2 * M_PI * gsl_rng_uniform(rng);
        double z = a + (s->height - 2 * a) * gsl_rng_uniform(rng);
        double vphi = s->omega * r * ring_profile(s, r, z) + gsl_ran_gaussian(rng, s->noise);
        double vr = gsl_ran_gaussian(rng, s->noise), vz = gsl_ran_gaussian(rng, s->noise);
        double c = cos(phi), sn = sin(phi);
        p->id[k] = (int64_t)k + 1;
        p->type[k] = 1;
        p->radius[k] = a;
        p->mass[k] = s->density * 4.0 / 3.0 * M_PI * a * a * a;
        p->pos[k][0] = r * c;
        p->pos[k][1] = r * sn;
        p->pos[k][2] = z;
        p->vel[k][0] = vr * c - vphi * sn;
        p->vel[k][1] = vr * sn + vphi * c;
        p->vel[k][2] = vz;
    }
    return 0;
}
