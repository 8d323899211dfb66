/* Radial profiles by probe spheres (radial.h). */
#include <config.h>

#include "radial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "axial_profile.h"
#include "contact_point.h"
#include "overlap.h"
#include "sample_mean.h"

static const mimas_radial_field_desc fields[MIMAS_RAD_NFIELDS] = {
    {"porosity", "1", "1 - solid volume in the probes of the radius / their volume"},
    {"nu", "1", "solid fraction: solid volume in the probes of the radius / their volume"},
    {"v_r", "m s-1", "radial velocity (mass-weighted over the probes, + away from the axis)"},
    {"v_phi", "m s-1", "azimuthal velocity (mass-weighted, counterclockwise about +s)"},
    {"v_s", "m s-1", "axial velocity (mass-weighted, + towards the outlet)"},
    {"T", "J", "granular temperature: sum m_i f_i (v_c - V_c)^2 / (k sum f_i) over the k "
               "chosen components"},
    {"E_rot", "J", "rotational energy per particle: sum f_i I_i |w_i|^2 / 2 / sum f_i, "
                   "I = (2/5) m a^2 (undefined without angular velocities)"},
};

const mimas_radial_field_desc *mimas_radial_field(int k)
{
    return k >= 0 && k < MIMAS_RAD_NFIELDS ? &fields[k] : NULL;
}

/* per radius and sample */
enum { R_VOL, R_N, R_MASS, R_P, R_K = R_P + 3, R_EROT = R_K + 3, R_NSUMS };

struct mimas_radial {
    mimas_radial_options o;
    size_t nr;
    size_t *nprobe;
    double *sum;               /* nr x R_NSUMS, the current sample */
    double *last;              /* nr x fields */
    mimas_sample_mean *mean;   /* nr x fields */
    size_t samples;
};

int mimas_radial_create(mimas_radial **rp, const mimas_radial_options *o, mimas_error *err)
{
    double rho = 0.5 * o->probe, R = o->geom.radius;
    if (!(o->probe > 0) || !(rho < R))
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "the probe diameter %g m must be positive and below the tube "
                               "diameter %g m", o->probe, 2 * R);
    if (!(o->dr > 0) || (R - rho) / o->dr > 1e6)
        return mimas_error_set(err, MIMAS_EUSAGE, "the radial step must be positive, not %g",
                               o->dr);
    mimas_radial *r = calloc(1, sizeof *r);
    if (!r)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    r->o = *o;
    if (!r->o.temperature)
        r->o.temperature = MIMAS_TEMP_S | MIMAS_TEMP_R | MIMAS_TEMP_PHI;
    r->nr = (size_t)floor((R - rho) / o->dr * (1 + 1e-12)) + 1;
    r->nprobe = malloc(r->nr * sizeof *r->nprobe);
    r->sum = malloc(r->nr * R_NSUMS * sizeof *r->sum);
    r->last = malloc(r->nr * MIMAS_RAD_NFIELDS * sizeof *r->last);
    r->mean = calloc(r->nr * MIMAS_RAD_NFIELDS, sizeof *r->mean);
    if (!r->nprobe || !r->sum || !r->last || !r->mean) {
        mimas_radial_free(r);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    for (size_t k = 0; k < r->nr; k++) {
        double n = ceil(2.0 * M_PI * mimas_radial_radius(r, k) / o->probe - 1e-9);
        r->nprobe[k] = n < 1 ? 1 : (size_t)n;
    }
    *rp = r;
    return MIMAS_OK;
}

void mimas_radial_free(mimas_radial *r)
{
    if (!r)
        return;
    free(r->nprobe);
    free(r->sum);
    free(r->last);
    free(r->mean);
    free(r);
}

size_t mimas_radial_nradii(const mimas_radial *r)
{
    return r->nr;
}

double mimas_radial_radius(const mimas_radial *r, size_t k)
{
    return (double)k * r->o.dr;
}

size_t mimas_radial_probes(const mimas_radial *r, size_t k)
{
    return r->nprobe[k];
}

size_t mimas_radial_samples(const mimas_radial *r)
{
    return r->samples;
}

/* Particle i (axis-frame position l, radius a, mass m, velocity v in (s, r,
 * phi), rotational energy er) against the probes of the plane at sp. */
static void add_particle(mimas_radial *r, const double l[3], double a, double m,
                         const double v[3], double er, double sp)
{
    double rho = 0.5 * r->o.probe, reach = a + rho, ds = l[2] - sp;
    if (fabs(ds) >= reach)
        return;
    double ri = hypot(l[0], l[1]), phi = atan2(l[1], l[0]);
    double V = 4.0 / 3.0 * M_PI * a * a * a;
    for (size_t k = 0; k < r->nr; k++) {
        double rk = mimas_radial_radius(r, k);
        if (fabs(ri - rk) >= reach)
            continue;
        size_t np = r->nprobe[k];
        double step = 2.0 * M_PI / (double)np;
        /* the probes within reach: |x_i - x_probe|^2 = ri^2 + rk^2 - 2 ri rk
         * cos(dphi) + ds^2 < reach^2 */
        size_t j0 = 0, j1 = np - 1;
        long lo = 0, hi = (long)np - 1;
        int all = 1;
        if (ri * rk > 0) {
            double c = (ri * ri + rk * rk + ds * ds - reach * reach) / (2.0 * ri * rk);
            if (c > -1.0) {
                double dphi = acos(fmin(1.0, c));
                lo = (long)ceil((phi - dphi) / step);
                hi = (long)floor((phi + dphi) / step);
                all = hi - lo + 1 >= (long)np;
            }
        }
        double *S = &r->sum[k * R_NSUMS];
        for (long jj = all ? (long)j0 : lo; jj <= (all ? (long)j1 : hi); jj++) {
            double pa = (double)jj * step;
            double dx = l[0] - rk * cos(pa), dy = l[1] - rk * sin(pa);
            double vol = overlap_sphere_sphere(sqrt(dx * dx + dy * dy + ds * ds), a, rho);
            if (!(vol > 0))
                continue;
            double f = vol / V;
            S[R_VOL] += vol;
            S[R_N] += f;
            S[R_MASS] += m * f;
            for (int c = 0; c < 3; c++) {
                S[R_P + c] += m * f * v[c];
                S[R_K + c] += m * f * v[c] * v[c];
            }
            S[R_EROT] += f * er;
        }
    }
}

int mimas_radial_probe(mimas_radial *r, const mimas_frame *f, const double *planes, size_t n,
                       mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_frame_require_dynamics(f, err);
    if (rc)
        return rc;
    memset(r->sum, 0, r->nr * R_NSUMS * sizeof *r->sum);
    int omega = (p->present & MIMAS_P_OMEGA) != 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!mimas_particle_selected(p, i, r->o.types, r->o.ntypes, r->o.exclude))
            continue;
        if (r->o.check_inside && (rc = mimas_tube_check_particle(&r->o.geom, f, i, err)))
            return rc;
        double l[3], v[3], a = p->radius[i], m = p->mass[i], er = NAN;
        mimas_axis_to_local(&r->o.geom.axis, p->pos[i], l);
        mimas_tube_vector(&r->o.geom, p->pos[i], p->vel[i], v); /* components at the particle */
        if (omega) {
            const double *w = p->omega[i];
            er = 0.5 * 0.4 * m * a * a * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        }
        for (size_t q = 0; q < n; q++)
            add_particle(r, l, a, m, v, er, planes[q]);
    }
    double Vp = M_PI / 6.0 * r->o.probe * r->o.probe * r->o.probe;
    int ncomp = 0;
    for (int c = 0; c < 3; c++)
        ncomp += (r->o.temperature >> c) & 1;
    /* the output order of velocities is r, phi, s */
    static const int order[3] = {1, 2, 0};
    for (size_t k = 0; k < r->nr; k++) {
        const double *S = &r->sum[k * R_NSUMS];
        double *L = &r->last[k * MIMAS_RAD_NFIELDS];
        double M = S[R_MASS], tsum = 0;
        L[MIMAS_RAD_NU] = S[R_VOL] / ((double)(r->nprobe[k] * n) * Vp);
        L[MIMAS_RAD_POROSITY] = 1.0 - L[MIMAS_RAD_NU];
        for (int c = 0; c < 3; c++) {
            L[MIMAS_RAD_VR + c] = M > 0 ? S[R_P + order[c]] / M : NAN;
            double kin = M > 0 ? fmax(0.0, S[R_K + c] - S[R_P + c] * S[R_P + c] / M) : 0.0;
            if ((r->o.temperature >> c) & 1)
                tsum += kin;
        }
        L[MIMAS_RAD_T] = S[R_N] > 0 ? tsum / (ncomp * S[R_N]) : NAN;
        L[MIMAS_RAD_EROT] = S[R_N] > 0 && omega ? S[R_EROT] / S[R_N] : NAN;
    }
    return MIMAS_OK;
}

const double *mimas_radial_values(const mimas_radial *r)
{
    return r->last;
}

void mimas_radial_add(mimas_radial *r, const double *values)
{
    for (size_t k = 0; k < r->nr * MIMAS_RAD_NFIELDS; k++)
        if (!isnan(values[k]))
            mimas_sample_mean_add(&r->mean[k], values[k]);
    r->samples++;
}

int mimas_radial_sample(mimas_radial *r, const mimas_frame *f, const double *planes, size_t n,
                        mimas_error *err)
{
    int rc = mimas_radial_probe(r, f, planes, n, err);
    if (!rc)
        mimas_radial_add(r, r->last);
    return rc;
}

double mimas_radial_last(const mimas_radial *r, size_t k, int field)
{
    return r->last[k * MIMAS_RAD_NFIELDS + (size_t)field];
}

void mimas_radial_result(const mimas_radial *r, size_t k, int field, double *mean, double *sem,
                         size_t *n)
{
    mimas_sample_mean_get(&r->mean[k * MIMAS_RAD_NFIELDS + (size_t)field], mean, sem, n);
}
