/* Validation of a frame's values and wrapping of positions into a periodic
 * box: what every reader applies to the frames it delivers (readers/reader.c),
 * so that no format passes a value the averaging cannot use. */
#include <config.h>

#include "frame.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

/* the largest number of box lengths a position may lie outside a periodic
 * box (image flags are int32) */
#define MAX_IMAGES 1e9

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

int mimas_box_check(const mimas_box *b, mimas_error *err)
{
    static const char axis[3] = {'x', 'y', 'z'};
    for (int d = 0; d < 3; d++)
        if (!isfinite(b->lo[d]) || !isfinite(b->hi[d]) || !(b->hi[d] > b->lo[d]))
            return mimas_error_set(err, MIMAS_EDATA, "the box bounds in %c (%g .. %g) are not "
                                   "finite or not increasing", axis[d], b->lo[d], b->hi[d]);
    if (!isfinite(b->xy) || !isfinite(b->xz) || !isfinite(b->yz))
        return mimas_error_set(err, MIMAS_EDATA, "the box tilt factors are not finite");
    return MIMAS_OK;
}

/* "particle id 17 (row 3)" into the message */
static int bad_particle(const mimas_particles *p, size_t k, mimas_error *err, const char *what,
                        double v)
{
    long long id = (p->present & MIMAS_P_ID) ? (long long)p->id[k] : (long long)k;
    return mimas_error_set(err, MIMAS_EDATA, "particle id %lld (row %zu): %s %g", id, k, what, v);
}

static int check_particles(const mimas_particles *p, mimas_error *err)
{
    static const struct {
        unsigned bit;
        const char *name;
    } vectors[] = {{MIMAS_P_POS, "position"}, {MIMAS_P_VEL, "velocity"},
                   {MIMAS_P_OMEGA, "angular velocity"}, {MIMAS_P_FORCE, "force"}};
    for (size_t v = 0; v < sizeof vectors / sizeof vectors[0]; v++) {
        if (!(p->present & vectors[v].bit))
            continue;
        const double(*a)[3] = vectors[v].bit == MIMAS_P_POS   ? (const double(*)[3])p->pos
                              : vectors[v].bit == MIMAS_P_VEL ? (const double(*)[3])p->vel
                              : vectors[v].bit == MIMAS_P_OMEGA ? (const double(*)[3])p->omega
                                                                : (const double(*)[3])p->force;
        for (size_t k = 0; k < p->n; k++)
            if (!finite3(a[k])) {
                int c = !isfinite(a[k][0]) ? 0 : !isfinite(a[k][1]) ? 1 : 2;
                char what[48];
                snprintf(what, sizeof what, "%s component %d is", vectors[v].name, c + 1);
                return bad_particle(p, k, err, what, a[k][c]);
            }
    }
    for (size_t k = 0; k < p->n; k++) {
        if ((p->present & MIMAS_P_RADIUS) && !(isfinite(p->radius[k]) && p->radius[k] > 0))
            return bad_particle(p, k, err, "radius is not positive:", p->radius[k]);
        if ((p->present & MIMAS_P_MASS) && !(isfinite(p->mass[k]) && p->mass[k] > 0))
            return bad_particle(p, k, err, "mass is not positive:", p->mass[k]);
        if ((p->present & MIMAS_P_CG) && !(isfinite(p->cg[k]) && p->cg[k] > 0))
            return bad_particle(p, k, err, "coarse-grain factor is not positive:", p->cg[k]);
        if ((p->present & MIMAS_P_LIQUID) && !(isfinite(p->liquid[k]) && p->liquid[k] >= 0))
            return bad_particle(p, k, err, "liquid volume is negative or not finite:",
                                p->liquid[k]);
    }
    return MIMAS_OK;
}

/* The index columns point into the particles; the vectors are finite. */
static int check_pairs(const void *tab, const mimas_table_desc *d, size_t np, mimas_error *err)
{
    size_t n = mimas_table_n(tab, d);
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++) {
        const mimas_column_desc *col = &d->columns[c];
        if (!(present & col->bit))
            continue;
        const void *a = mimas_table_column(tab, d, c);
        /* a column at a time, the common case (nothing wrong) a loop without exits; the
         * first bad row, if any, found again for the message */
        if (col->type == MIMAS_T_INDEX) {
            const size_t *ix = a;
            size_t worst = 0;
            for (size_t k = 0; k < n; k++)
                worst = ix[k] > worst ? ix[k] : worst;
            for (size_t k = 0; n && worst >= np && k < n; k++)
                if (ix[k] >= np)
                    return mimas_error_set(err, MIMAS_EDATA, "%s row %zu: %s refers to row "
                                           "%zu of %zu particles", d->name, k, col->name,
                                           ix[k], np);
        } else if (col->type == MIMAS_T_F64) {
            const double *v = a;
            size_t m = n * (size_t)col->ncomp;
            int bad = 0;
            for (size_t q = 0; q < m; q++)
                bad |= !isfinite(v[q]);
            for (size_t q = 0; bad && q < m; q++)
                if (!isfinite(v[q]))
                    return mimas_error_set(err, MIMAS_EDATA, "%s row %zu: %s is %g", d->name,
                                           q / (size_t)col->ncomp, col->name, v[q]);
        }
    }
    return MIMAS_OK;
}

int mimas_frame_check(const mimas_frame *f, mimas_error *err)
{
    if (!isfinite(f->time) && !isnan(f->time))
        return mimas_error_set(err, MIMAS_EDATA, "the time is %g", f->time);
    int rc = mimas_box_check(&f->box, err);
    if (!rc)
        rc = check_particles(&f->particles, err);
    if (!rc && f->has_contacts)
        rc = check_pairs(&f->contacts, &mimas_contacts_desc, f->particles.n, err);
    if (!rc && f->has_walls)
        rc = check_pairs(&f->walls, &mimas_walls_desc, f->particles.n, err);
    return rc;
}

int mimas_frame_wrap(mimas_frame *f, mimas_error *err)
{
    const mimas_box *b = &f->box;
    if (!b->periodic[0] && !b->periodic[1] && !b->periodic[2])
        return MIMAS_OK;
    mimas_particles *p = &f->particles;
    double e[3][3];
    mimas_box_edges(b, e);
    for (size_t k = 0; k < p->n; k++) {
        double *x = p->pos[k];
        /* a shift by whole edge vectors changes only the fractional coordinate
         * along that edge */
        double s[3];
        mimas_box_fractional(b, e, x, s);
        for (int d = 2; d >= 0; d--) {
            if (!b->periodic[d] || (s[d] >= 0 && s[d] < 1))
                continue;
            double q = floor(s[d]);
            if (!(fabs(q) <= MAX_IMAGES))
                return bad_particle(p, k, err, "position lies too many box lengths outside "
                                    "the periodic box, in box lengths:", q);
            for (int c = 0; c < 3; c++)
                x[c] -= q * e[d][c];
            /* orthogonal boxes: rounding may leave x on the upper face, which
             * is the lower one */
            if (!mimas_box_is_triclinic(b) && !(x[d] >= b->lo[d] && x[d] < b->hi[d]))
                x[d] = b->lo[d];
            if (p->present & MIMAS_P_IMAGE)
                p->image[k][d] += (int32_t)q;
        }
    }
    return MIMAS_OK;
}
