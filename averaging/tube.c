/* The tube geometry shared by mimas plugs and mimas radial (tube.h). */
#include <config.h>

#include "tube.h"

#include <math.h>

#include "overlap.h"

int mimas_tube_geom_resolve(mimas_tube_geom *g, const char *axis_spec, double radius,
                            const mimas_tube *from_file, mimas_error *err)
{
    int file = from_file && from_file->present;
    int rc;
    if (axis_spec || !file)
        rc = mimas_axis_parse(&g->axis, axis_spec, err);
    else
        rc = mimas_axis_set(&g->axis, from_file->origin, from_file->direction, err);
    if (rc)
        return rc;
    if (radius != 0)
        g->radius = radius;
    else if (file)
        g->radius = from_file->radius;
    else
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "--tube-radius is required: the input does not record its tube");
    if (!(g->radius > 0) || !isfinite(g->radius))
        return mimas_error_set(err, MIMAS_EUSAGE, "the tube radius must be positive, not %g",
                               g->radius);
    g->length = file && !axis_spec && from_file->length > 0 ? from_file->length : NAN;
    return MIMAS_OK;
}

void mimas_tube_coords(const mimas_tube_geom *g, const double x[3], double *s, double *r,
                       double *phi)
{
    double l[3];
    mimas_axis_to_local(&g->axis, x, l);
    *s = l[2];
    *r = hypot(l[0], l[1]);
    *phi = atan2(l[1], l[0]);
}

void mimas_tube_point(const mimas_tube_geom *g, const double x[3], const double v[3], double *s,
                      double *r, double out[3])
{
    double l[3], w[3];
    mimas_axis_to_local(&g->axis, x, l);
    mimas_axis_vector_to_local(&g->axis, v, w);
    double rr = sqrt(l[0] * l[0] + l[1] * l[1]);
    double c = rr > 0 ? l[0] / rr : 1.0, sn = rr > 0 ? l[1] / rr : 0.0;
    out[0] = w[2];
    out[1] = c * w[0] + sn * w[1];
    out[2] = -sn * w[0] + c * w[1];
    *s = l[2];
    *r = rr;
}

void mimas_tube_vector(const mimas_tube_geom *g, const double x[3], const double v[3],
                       double out[3])
{
    double s, r;
    mimas_tube_point(g, x, v, &s, &r, out);
}

double mimas_tube_slab_volume(double c, double a, double s0, double s1)
{
    const double centre[3] = {0, 0, c}, lo[3] = {-INFINITY, -INFINITY, s0},
                 hi[3] = {INFINITY, INFINITY, s1};
    return overlap_sphere_box(centre, a, lo, hi);
}

double mimas_tube_slab_moment(double c, double a, double s0, double s1, double volume)
{
    double xa = fmax(s0 - c, -a), xb = fmin(s1 - c, a);
    if (!(a > 0) || !(xa < xb))
        return 0.0;
    /* pi int_xa^xb (c + x)(a^2 - x^2) dx */
    double a2 = a * a;
    double m1 = 0.5 * a2 * (xb * xb - xa * xa) - 0.25 * (xb * xb * xb * xb - xa * xa * xa * xa);
    return c * volume + M_PI * m1;
}

int mimas_slices_set(mimas_slices *sl, double s0, double s1, double w, mimas_error *err)
{
    if (!(s1 > s0) || !isfinite(s0) || !isfinite(s1))
        return mimas_error_set(err, MIMAS_EUSAGE, "the axial range %g:%g is empty", s0, s1);
    if (!(w > 0) || !isfinite(w))
        return mimas_error_set(err, MIMAS_EUSAGE, "the slice width must be positive, not %g", w);
    double n = round((s1 - s0) / w);
    if (n > 1e8)
        return mimas_error_set(err, MIMAS_EUSAGE, "%g:%g in slices of %g m: too many slices",
                               s0, s1, w);
    sl->n = n < 1 ? 1 : (size_t)n;
    sl->s0 = s0;
    sl->w = (s1 - s0) / (double)sl->n;
    return MIMAS_OK;
}

double mimas_slice_centre(const mimas_slices *sl, size_t k)
{
    return sl->s0 + ((double)k + 0.5) * sl->w;
}

int mimas_slices_range(const mimas_slices *sl, double lo, double hi, size_t *k0, size_t *k1)
{
    double a = floor((lo - sl->s0) / sl->w), b = floor((hi - sl->s0) / sl->w);
    if (!(b >= 0) || !(a < (double)sl->n) || !(a <= b))
        return 0;
    *k0 = a < 0 ? 0 : (size_t)a;
    *k1 = b >= (double)sl->n ? sl->n - 1 : (size_t)b;
    return 1;
}

int mimas_tube_check_particle(const mimas_tube_geom *g, const mimas_frame *f, size_t i,
                              mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    double s, r, v[3], zero[3] = {0, 0, 0};
    mimas_tube_point(g, p->pos[i], zero, &s, &r, v);
    if (r <= g->radius)
        return MIMAS_OK;
    return mimas_error_set(err, MIMAS_EDATA,
                           "particle %lld at r = %g m lies outside the tube of radius %g m "
                           "(check --axis and --tube-radius)",
                           p->id ? (long long)p->id[i] : (long long)i, r, g->radius);
}

int mimas_tube_extent(const mimas_tube_geom *g, const mimas_frame *f, const int32_t *types,
                      size_t ntypes, int exclude, double *s_min, double *s_max, double *diameter,
                      mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_table_require(p, &mimas_particles_desc, MIMAS_P_RADIUS, err);
    if (rc)
        return rc;
    double lo = INFINITY, hi = -INFINITY, dsum = 0;
    size_t n = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!mimas_particle_selected(p, i, types, ntypes, exclude))
            continue;
        double s, r, phi;
        mimas_tube_coords(g, p->pos[i], &s, &r, &phi);
        lo = fmin(lo, s - p->radius[i]);
        hi = fmax(hi, s + p->radius[i]);
        dsum += 2.0 * p->radius[i];
        n++;
    }
    if (!n || !(dsum > 0))
        return mimas_error_set(err, MIMAS_EDATA, "no particles (of the selected types) with a "
                               "positive radius in the first frame");
    *s_min = lo;
    *s_max = hi;
    *diameter = dsum / (double)n;
    return MIMAS_OK;
}

int mimas_tube_setup_from(mimas_tube_setup *s, const char *axis_spec, double radius,
                          const mimas_frame *f, const int32_t *types, size_t ntypes, int exclude,
                          mimas_error *err)
{
    int rc = mimas_tube_geom_resolve(&s->geom, axis_spec, radius, &f->tube, err);
    if (!rc)
        rc = mimas_tube_extent(&s->geom, f, types, ntypes, exclude, &s->s_min, &s->s_max,
                               &s->diameter, err);
    if (rc == MIMAS_EDATA) { /* none selected: the command may not need them */
        s->s_min = s->s_max = s->diameter = NAN;
        rc = MIMAS_OK;
    }
    return rc;
}

int mimas_tube_defaults_known(double d, double s0, double s1, mimas_error *err)
{
    if (d > 0 && isfinite(d) && isfinite(s0) && isfinite(s1))
        return MIMAS_OK;
    return mimas_error_set(err, MIMAS_EDATA, "no particles (of the selected types) with a "
                           "positive radius in the first frame: give --diameter%s, or --from a "
                           "time when there are", isfinite(s0) && isfinite(s1) ? "" : " and --range");
}
