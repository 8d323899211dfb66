/* Axial slice profiles of one frame (axial_profile.h, docs/plugs.md;
 * Strauß 2005, Sec. 4.1; docs/theory.md §7.3). */
#include <config.h>

#include "axial_profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_point.h"
#include "overlap.h"

static const mimas_axial_field_desc fields[MIMAS_AX_NFIELDS] = {
    {"porosity", "1", "1 - solid volume in the slice / (pi R^2 W)"},
    {"nu", "1", "solid fraction: solid volume in the slice / (pi R^2 W)"},
    {"n", "1", "particles in the slice: the sum of the fractions of their volumes inside it"},
    {"v_s", "m s-1", "axial velocity (mass-weighted mean, + towards the outlet)"},
    {"v_r", "m s-1", "radial velocity (mass-weighted mean, + away from the axis)"},
    {"v_phi", "m s-1", "azimuthal velocity (mass-weighted mean, counterclockwise about +s)"},
    {"T", "J", "granular temperature: sum m_i f_i (v_c - V_c)^2 / (k sum f_i) over the k "
               "chosen components c (default s, r, phi)"},
    {"stress_ss", "Pa", "axial normal stress, kinetic + contact (compression positive)"},
    {"stress_rr", "Pa", "radial normal stress, kinetic + contact (compression positive)"},
    {"wall_pressure", "Pa", "normal force of the particles on the tube wall / (2 pi R W)"},
    {"wall_shear", "Pa", "axial force of the particles on the tube wall / (2 pi R W), + "
                         "towards the outlet"},
    {"wall_friction", "1", "wall_shear / wall_pressure (undefined where wall_pressure = 0)"},
    {"gas_pressure", "Pa", "gas pressure: the gas cells' pressure weighted by the length they "
                           "share with the slice (undefined without gas fields)"},
    {"kstress_ss", "Pa", "kinetic part of stress_ss: sum m_i f_i (v_s - V_s)^2 / (pi R^2 W)"},
    {"kstress_rr", "Pa", "kinetic part of stress_rr: sum m_i f_i (v_r - V_r)^2 / (pi R^2 W)"},
    {"cstress_ss", "Pa", "contact part of stress_ss: sum f_s b_s (branch fraction) / (pi R^2 W)"},
    {"cstress_rr", "Pa", "contact part of stress_rr: sum f_r b_r (branch fraction) / (pi R^2 W)"},
};

const mimas_axial_field_desc *mimas_axial_field(int k)
{
    return k >= 0 && k < MIMAS_AX_NFIELDS ? &fields[k] : NULL;
}

struct mimas_axial {
    mimas_axial_options o;
    double *sum;     /* n x MIMAS_AS_NSUMS */
    double *field;   /* n x MIMAS_AX_NFIELDS */
    unsigned char *keep;
    size_t keep_cap;
    mimas_axial_totals totals;
};

int mimas_axial_create(mimas_axial **ax, const mimas_axial_options *o, mimas_error *err)
{
    mimas_axial *a = calloc(1, sizeof *a);
    size_t n = o->slices.n;
    if (a) {
        a->o = *o;
        a->sum = malloc(n * MIMAS_AS_NSUMS * sizeof *a->sum);
        a->field = malloc(n * MIMAS_AX_NFIELDS * sizeof *a->field);
    }
    if (!a || !a->sum || !a->field) {
        mimas_axial_free(a);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for %zu slices", n);
    }
    if (!a->o.temperature)
        a->o.temperature = MIMAS_TEMP_S | MIMAS_TEMP_R | MIMAS_TEMP_PHI;
    *ax = a;
    return MIMAS_OK;
}

void mimas_axial_free(mimas_axial *a)
{
    if (!a)
        return;
    free(a->sum);
    free(a->field);
    free(a->keep);
    free(a);
}

const mimas_axial_options *mimas_axial_opts(const mimas_axial *a)
{
    return &a->o;
}

double mimas_axial_sum(const mimas_axial *a, size_t k, int which)
{
    return a->sum[k * MIMAS_AS_NSUMS + (size_t)which];
}

double mimas_axial_value(const mimas_axial *a, size_t k, int field)
{
    return a->field[k * MIMAS_AX_NFIELDS + (size_t)field];
}

const double *mimas_axial_row(const mimas_axial *a, size_t k)
{
    return &a->field[k * MIMAS_AX_NFIELDS];
}

void mimas_axial_load(mimas_axial *ax, const double *values, const mimas_axial_totals *t)
{
    memcpy(ax->field, values, ax->o.slices.n * MIMAS_AX_NFIELDS * sizeof *ax->field);
    ax->totals = *t;
}

mimas_axial_totals mimas_axial_frame_totals(const mimas_axial *a)
{
    return a->totals;
}

/* A particle at s with velocity v (s, r, phi): its volume, mass, moment and
 * momentum per slice it cuts. */
static void add_particle(mimas_axial *a, const mimas_particles *p, size_t i, double s,
                         const double v[3])
{
    const mimas_slices *sl = &a->o.slices;
    double R = p->radius[i], V = 4.0 / 3.0 * M_PI * R * R * R, m = p->mass[i];
    size_t k0, k1;
    if (!mimas_slices_range(sl, s - R, s + R, &k0, &k1))
        return;
    for (size_t k = k0; k <= k1; k++) {
        double lo = sl->s0 + (double)k * sl->w, hi = lo + sl->w;
        double vol = mimas_tube_slab_volume(s, R, lo, hi);
        if (!(vol > 0))
            continue;
        double f = vol / V, *S = &a->sum[k * MIMAS_AS_NSUMS];
        S[MIMAS_AS_VOLUME] += vol;
        S[MIMAS_AS_MOMENT] += m / V * mimas_tube_slab_moment(s, R, lo, hi, vol);
        S[MIMAS_AS_N] += f;
        S[MIMAS_AS_MASS] += m * f;
        for (int c = 0; c < 3; c++) {
            S[MIMAS_AS_P + c] += m * f * v[c];
            S[MIMAS_AS_K + c] += m * f * v[c] * v[c];
        }
    }
}

/* The branch from a to b (the contact's segment) with force f (on the
 * particle at b): f_s b_s and f_r b_r (e_r at the segment's midpoint), each
 * slice taking the fraction of the segment inside it. */
static void add_branch(mimas_axial *a, const double from[3], const double b[3],
                       const double f[3])
{
    const mimas_tube_geom *g = &a->o.geom;
    const mimas_slices *sl = &a->o.slices;
    double to[3], mid[3], la[3], lb[3];
    for (int d = 0; d < 3; d++) {
        to[d] = from[d] + b[d];
        mid[d] = from[d] + 0.5 * b[d];
    }
    double fc[3], bc[3];
    mimas_tube_vector(g, mid, f, fc);
    mimas_tube_vector(g, mid, b, bc);
    mimas_axis_to_local(&g->axis, from, la);
    mimas_axis_to_local(&g->axis, to, lb);
    size_t k0, k1;
    if (!mimas_slices_range(sl, fmin(la[2], lb[2]), fmax(la[2], lb[2]), &k0, &k1))
        return;
    for (size_t k = k0; k <= k1; k++) {
        double lo[3] = {-INFINITY, -INFINITY, sl->s0 + (double)k * sl->w};
        double hi[3] = {INFINITY, INFINITY, lo[2] + sl->w};
        double frac = segment_fraction_box(la, lb, lo, hi);
        double *S = &a->sum[k * MIMAS_AS_NSUMS];
        S[MIMAS_AS_CSS] += frac * fc[0] * bc[0];
        S[MIMAS_AS_CRR] += frac * fc[1] * bc[1];
    }
}

/* A contact of particle i (at r, radius R) with a wall at the point c, force
 * f on the particle: the stress along the segment from c to r, and, when c
 * lies on the tube's surface (within R/2 of it), the force on the wall in
 * the slice that holds c. */
static void add_wall_contact(mimas_axial *a, const mimas_box *box, const double r[3], double R,
                             const double c[3], const double f[3])
{
    double b[3];
    mimas_branch(box, r, c, b);
    double from[3] = {r[0] - b[0], r[1] - b[1], r[2] - b[2]};
    add_branch(a, from, b, f);
    double s, rc, phi, fc[3];
    mimas_tube_coords(&a->o.geom, from, &s, &rc, &phi);
    if (!(fabs(rc - a->o.geom.radius) <= 0.5 * R))
        return;
    size_t k0, k1;
    if (!mimas_slices_range(&a->o.slices, s, s, &k0, &k1))
        return;
    mimas_tube_vector(&a->o.geom, from, f, fc);
    double *S = &a->sum[k0 * MIMAS_AS_NSUMS];
    S[MIMAS_AS_WALL_N] -= fc[1]; /* the wall pushes the particle inwards */
    S[MIMAS_AS_WALL_T] -= fc[0];
}

/* Gas cells on a grid aligned with the axis: each slice takes the cells'
 * pressure weighted by the length the cell shares with it along the axis.
 * 0, or MIMAS_EDATA when the grid is not aligned with the axis. */
static int add_gas(mimas_axial *a, const mimas_gas *gas, mimas_error *err)
{
    const double *ez = a->o.geom.axis.ez;
    int dir = -1;
    for (int d = 0; d < 3; d++)
        if (fabs(ez[d]) > 1.0 - 1e-9)
            dir = d;
    if (dir < 0)
        return mimas_error_set(err, MIMAS_EDATA,
                               "the gas grid is not aligned with the tube axis");
    const mimas_slices *sl = &a->o.slices;
    double sign = ez[dir] > 0 ? 1.0 : -1.0;
    /* s of a point whose coordinate dir is x (the other components do not
     * matter: e_z has none) */
    double o = a->o.geom.axis.origin[dir];
    size_t nx = gas->cells[0], ny = gas->cells[1], nz = gas->cells[2];
    for (size_t l = 0; l < nz; l++)
        for (size_t j = 0; j < ny; j++)
            for (size_t i = 0; i < nx; i++) {
                size_t idx[3] = {i, j, l}, cell = i + nx * (j + ny * l);
                double x0 = gas->origin[dir] + (double)idx[dir] * gas->spacing[dir];
                double x1 = x0 + gas->spacing[dir];
                double s0 = sign * (x0 - o), s1 = sign * (x1 - o);
                double lo = fmin(s0, s1), hi = fmax(s0, s1);
                size_t k0, k1;
                if (!isfinite(gas->pressure[cell]) || !mimas_slices_range(sl, lo, hi, &k0, &k1))
                    continue;
                for (size_t k = k0; k <= k1; k++) {
                    double a0 = sl->s0 + (double)k * sl->w;
                    double w = fmin(hi, a0 + sl->w) - fmax(lo, a0);
                    if (!(w > 0))
                        continue;
                    double *S = &a->sum[k * MIMAS_AS_NSUMS];
                    S[MIMAS_AS_GAS_PW] += w * gas->pressure[cell];
                    S[MIMAS_AS_GAS_W] += w;
                }
            }
    return MIMAS_OK;
}

static double ratio(double a, double b)
{
    return b != 0 ? a / b : NAN;
}

static void derive(mimas_axial *a, int gas)
{
    const mimas_slices *sl = &a->o.slices;
    double R = a->o.geom.radius, V = M_PI * R * R * sl->w, A = 2.0 * M_PI * R * sl->w;
    int ncomp = 0;
    for (int c = 0; c < 3; c++)
        ncomp += (a->o.temperature >> c) & 1;
    for (size_t k = 0; k < sl->n; k++) {
        const double *S = &a->sum[k * MIMAS_AS_NSUMS];
        double *F = &a->field[k * MIMAS_AX_NFIELDS];
        double M = S[MIMAS_AS_MASS], kin[3];
        F[MIMAS_AX_NU] = S[MIMAS_AS_VOLUME] / V;
        F[MIMAS_AX_POROSITY] = 1.0 - F[MIMAS_AX_NU];
        F[MIMAS_AX_N] = S[MIMAS_AS_N];
        double tsum = 0;
        for (int c = 0; c < 3; c++) {
            F[MIMAS_AX_VS + c] = ratio(S[MIMAS_AS_P + c], M);
            /* sum m f (v - V)^2 = sum m f v^2 - P^2/M, never below zero */
            double P = S[MIMAS_AS_P + c];
            kin[c] = M > 0 ? fmax(0.0, S[MIMAS_AS_K + c] - P * P / M) : 0.0;
            if ((a->o.temperature >> c) & 1)
                tsum += kin[c];
        }
        F[MIMAS_AX_T] = ratio(tsum, ncomp * S[MIMAS_AS_N]);
        F[MIMAS_AX_KSTRESS_SS] = kin[0] / V;
        F[MIMAS_AX_KSTRESS_RR] = kin[1] / V;
        F[MIMAS_AX_CSTRESS_SS] = S[MIMAS_AS_CSS] / V;
        F[MIMAS_AX_CSTRESS_RR] = S[MIMAS_AS_CRR] / V;
        F[MIMAS_AX_STRESS_SS] = F[MIMAS_AX_KSTRESS_SS] + F[MIMAS_AX_CSTRESS_SS];
        F[MIMAS_AX_STRESS_RR] = F[MIMAS_AX_KSTRESS_RR] + F[MIMAS_AX_CSTRESS_RR];
        F[MIMAS_AX_WALL_P] = S[MIMAS_AS_WALL_N] / A;
        F[MIMAS_AX_WALL_SHEAR] = S[MIMAS_AS_WALL_T] / A;
        F[MIMAS_AX_WALL_FRICTION] = ratio(S[MIMAS_AS_WALL_T], S[MIMAS_AS_WALL_N]);
        F[MIMAS_AX_GAS_P] = gas ? ratio(S[MIMAS_AS_GAS_PW], S[MIMAS_AS_GAS_W]) : NAN;
    }
}

static int prepare(mimas_axial *a, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_frame_require_dynamics(f, err);
    if (rc)
        return rc;
    if (p->n > a->keep_cap) {
        unsigned char *k = realloc(a->keep, p->n);
        if (!k)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        a->keep = k;
        a->keep_cap = p->n;
    }
    for (size_t k = 0; k < p->n; k++)
        a->keep[k] = (unsigned char)mimas_particle_selected(p, k, a->o.types, a->o.ntypes,
                                                            a->o.exclude);
    return MIMAS_OK;
}

/* Every particle once: inside the tube, its slices, the frame's totals. */
static int add_particles(mimas_axial *a, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    const mimas_tube_geom *g = &a->o.geom;
    const mimas_slices *sl = &a->o.slices;
    double lo = isfinite(g->length) ? 0.0 : sl->s0;
    double hi = isfinite(g->length) ? g->length : sl->s0 + (double)sl->n * sl->w;
    double fl = a->o.flow_at - 0.5 * sl->w, fh = a->o.flow_at + 0.5 * sl->w;
    mimas_axial_totals t = {0, 0, isnan(a->o.flow_at) ? NAN : 0.0, 0, NAN};
    for (size_t i = 0; i < p->n; i++) {
        if (!a->keep[i])
            continue;
        double s, r, v[3], R = p->radius[i];
        mimas_tube_point(g, p->pos[i], p->vel[i], &s, &r, v);
        if (a->o.check_inside && r > g->radius) /* mimas_tube_check_particle's test */
            return mimas_tube_check_particle(g, f, i, err);
        add_particle(a, p, i, s, v);
        if (s >= lo && s <= hi) {
            t.particles += 1;
            t.mass += p->mass[i];
        }
        if (!isnan(a->o.flow_at)) {
            double vol = mimas_tube_slab_volume(s, R, fl, fh);
            if (vol > 0)
                t.flow_rate += p->mass[i] * vol / (4.0 / 3.0 * M_PI * R * R * R) * v[0] / sl->w;
        }
    }
    a->totals = t;
    return MIMAS_OK;
}

typedef struct contact_visit {
    mimas_axial *a;
    const mimas_frame *f;
} contact_visit;

static void visit_pair(void *user, size_t k, const double b[3], const double at[3])
{
    contact_visit *v = user;
    (void)at;
    add_branch(v->a, v->f->particles.pos[v->f->contacts.j[k]], b, v->f->contacts.force[k]);
}

static void visit_wall(void *user, size_t i, const double c[3], const double force[3])
{
    contact_visit *v = user;
    const mimas_particles *p = &v->f->particles;
    add_wall_contact(v->a, &v->f->box, p->pos[i], p->radius[i], c, force);
}

int mimas_axial_compute(mimas_axial *a, const mimas_frame *f, mimas_error *err)
{
    int rc = prepare(a, f, err);
    if (rc)
        return rc;
    memset(a->sum, 0, a->o.slices.n * MIMAS_AS_NSUMS * sizeof *a->sum);
    if ((rc = add_particles(a, f, err)))
        return rc;
    contact_visit v = {a, f};
    mimas_contacts_visit(f, a->keep, 0, 1, visit_pair, visit_wall, &v);
    int gas = f->gas.present && f->gas.pressure;
    if (gas && (rc = add_gas(a, &f->gas, err)))
        return rc;
    derive(a, gas);
    a->totals.gas = gas;
    double first = NAN, last = NAN;
    for (size_t k = 0; gas && k < a->o.slices.n; k++) {
        double p = a->field[k * MIMAS_AX_NFIELDS + MIMAS_AX_GAS_P];
        if (!isnan(p)) {
            if (isnan(first))
                first = p;
            last = p;
        }
    }
    a->totals.pressure_drop = first - last;
    return MIMAS_OK;
}
