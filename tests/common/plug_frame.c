#include <config.h>

#include "plug_frame.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>

void tube_spec_default(tube_spec *t)
{
    memset(t, 0, sizeof *t);
    mimas_axis_parse(&t->axis, NULL, NULL);
    t->radius = 3.5e-3;
    t->d = 1.4e-3;
    t->density = 937;
    t->length = 0.2;
    t->seed = 1;
}

/* Time at which plug k reaches plug k + 1 (INFINITY: never). */
static double contact_time(const tube_spec *t, size_t k)
{
    if (k + 1 >= t->nplugs)
        return INFINITY;
    const plug_spec *a = &t->plugs[k], *b = &t->plugs[k + 1];
    double gap = b->back - (a->back + a->length);
    if (!(a->v > b->v))
        return INFINITY;
    return gap / (a->v - b->v);
}

void plug_motion(const tube_spec *t, size_t k, int lower, double time, double *shift, double *v)
{
    const plug_spec *p = &t->plugs[k];
    double tm = contact_time(t, k);
    if (time >= tm) {
        double s2, v2;
        plug_motion(t, k + 1, 1, time, &s2, &v2);
        /* moves with the plug ahead from the contact on */
        double at;
        plug_motion(t, k + 1, 1, tm, &at, &v2);
        plug_motion(t, k + 1, 1, time, &s2, &v2);
        *shift = p->v * tm + (s2 - at);
        *v = v2;
        return;
    }
    if (lower && p->t_split > 0 && time >= p->t_split) {
        *shift = p->v * p->t_split + p->v_split * (time - p->t_split);
        *v = p->v_split;
        return;
    }
    *shift = p->v * time;
    *v = p->v;
}

static int add(mimas_frame *f, const tube_spec *t, size_t *n, double x, double y, double s,
               double vs, int32_t type)
{
    mimas_particles *p = &f->particles;
    if (*n >= p->n) {
        mimas_error err;
        if (mimas_table_resize(p, &mimas_particles_desc, p->n ? 2 * p->n : 1024, &err))
            return -1;
    }
    size_t i = (*n)++;
    double a = 0.5 * t->d;
    p->id[i] = (int64_t)i + 1;
    p->type[i] = type;
    p->radius[i] = a;
    p->mass[i] = t->density * 4.0 / 3.0 * M_PI * a * a * a;
    for (int c = 0; c < 3; c++) {
        p->pos[i][c] =
            t->axis.origin[c] + x * t->axis.ex[c] + y * t->axis.ey[c] + s * t->axis.ez[c];
        p->vel[i][c] = vs * t->axis.ez[c];
        p->omega[i][c] = 0;
    }
    return 0;
}

/* Spheres at solid fraction nu in the cylinder part [s0, s1]: centres
 * evenly spaced along s in [s0, s1] (so every slice holds nearly the same
 * volume, and two parts that touch make one without a seam), spread over
 * the cross-section r <= R - a by two low-discrepancy sequences (the
 * golden ratio and sqrt 2, shifted by the rng). */
static int fill(mimas_frame *f, const tube_spec *t, gsl_rng *rng, size_t *n, double s0, double s1,
                double nu, double (*shift)(const tube_spec *, size_t, double, double, double *),
                size_t k, double time, int32_t type)
{
    double a = 0.5 * t->d, V = 4.0 / 3.0 * M_PI * a * a * a;
    size_t count = (size_t)llround(nu * M_PI * t->radius * t->radius * (s1 - s0) / V);
    double rmax = t->radius - a, u0 = gsl_rng_uniform(rng), w0 = gsl_rng_uniform(rng);
    for (size_t m = 0; m < count; m++) {
        double u = fmod(u0 + 0.6180339887498949 * (double)m, 1.0);
        double w = fmod(w0 + 0.4142135623730950 * (double)m, 1.0);
        double r = rmax * sqrt(u), ph = 2 * M_PI * w;
        double s = s0 + (s1 - s0) * ((double)m + 0.5) / (double)count, v = 0;
        if (shift)
            s += shift(t, k, (s - s0) / (s1 - s0), time, &v);
        if (add(f, t, n, r * cos(ph), r * sin(ph), s, v, type))
            return -1;
    }
    return 0;
}

static double plug_shift(const tube_spec *t, size_t k, double frac, double time, double *v)
{
    const plug_spec *p = &t->plugs[k];
    int lower = p->t_split > 0 && frac < p->split_at;
    double sh;
    plug_motion(t, k, lower, time, &sh, v);
    return sh;
}

int plug_frame(mimas_frame *f, const tube_spec *t, double time, int64_t step)
{
    mimas_frame_clear(f);
    mimas_error err;
    mimas_particles *p = &f->particles;
    if (mimas_table_set_present(p, &mimas_particles_desc,
                                MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_MASS |
                                    MIMAS_P_POS | MIMAS_P_VEL | MIMAS_P_OMEGA,
                                &err))
        return -1;
    f->step = step;
    f->time = time;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t n = 0;
    int rc = 0;
    for (size_t k = 0; !rc && k < t->nplugs; k++) {
        gsl_rng_set(rng, t->seed * 1000 + k);
        const plug_spec *q = &t->plugs[k];
        rc = fill(f, t, rng, &n, q->back, q->back + q->length, q->nu, plug_shift, k, time, 1);
    }
    if (!rc && t->dilute > 0) {
        gsl_rng_set(rng, t->seed * 1000 + 999);
        rc = fill(f, t, rng, &n, 0.0, t->length, t->dilute, NULL, 0, time, 2);
    }
    gsl_rng_free(rng);
    if (rc || mimas_table_resize(p, &mimas_particles_desc, n, &err))
        return -1;
    /* the box: the tube's bounding box, generously */
    double ext = t->length + 1.0, lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
        lo[c] = t->axis.origin[c] - ext;
        hi[c] = t->axis.origin[c] + ext;
    }
    memcpy(f->box.lo, lo, sizeof lo);
    memcpy(f->box.hi, hi, sizeof hi);
    f->tube.present = 1;
    memcpy(f->tube.origin, t->axis.origin, sizeof lo);
    memcpy(f->tube.direction, t->axis.ez, sizeof lo);
    f->tube.radius = t->radius;
    f->tube.length = t->length;
    return 0;
}
