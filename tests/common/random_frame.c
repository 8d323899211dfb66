#include <config.h>

#include "random_frame.h"

#include <gsl/gsl_randist.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void fill_column(void *arr, const mimas_column_desc *c, size_t n, size_t nparticles,
                        gsl_rng *rng)
{
    size_t m = n * (size_t)c->ncomp;
    switch (c->type) {
    case MIMAS_T_F64:
        /* two draws: mt19937 gives 32 random bits, a double has 53 */
        for (size_t k = 0; k < m; k++)
            ((double *)arr)[k] =
                (gsl_rng_uniform(rng) + 0x1p-32 * gsl_rng_uniform(rng)) * 2.0 - 1.0;
        break;
    case MIMAS_T_I32:
        for (size_t k = 0; k < m; k++)
            ((int32_t *)arr)[k] = (int32_t)gsl_rng_uniform_int(rng, 7) - 3;
        break;
    case MIMAS_T_I64:
        for (size_t k = 0; k < m; k++)
            ((int64_t *)arr)[k] = (int64_t)gsl_rng_get(rng);
        break;
    case MIMAS_T_INDEX:
        for (size_t k = 0; k < m; k++)
            ((size_t *)arr)[k] = nparticles ? gsl_rng_uniform_int(rng, nparticles) : 0;
        break;
    }
}

static int fill_table(void *tab, const mimas_table_desc *d, size_t n, unsigned bits,
                      size_t nparticles, gsl_rng *rng, const char *extra, int extra_ncomp)
{
    mimas_error err;
    if (mimas_table_set_present(tab, d, bits | d->required, &err) ||
        mimas_table_resize(tab, d, n, &err))
        return -1;
    size_t e;
    if (extra && mimas_table_add_extra(tab, d, extra, extra_ncomp, &e, &err))
        return -1;
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++)
        if (present & d->columns[c].bit)
            fill_column(mimas_table_column(tab, d, c), &d->columns[c], n, nparticles, rng);
    if (extra) {
        mimas_extra *x = &(*(mimas_extra **)((char *)tab + d->off_extra))[e];
        for (size_t k = 0; k < n * (size_t)extra_ncomp; k++)
            x->data[k] = gsl_rng_uniform(rng);
    }
    return 0;
}

int random_frame(mimas_frame *f, gsl_rng *rng, const random_frame_spec *s, int64_t step)
{
    mimas_frame_clear(f);
    f->step = step;
    f->time = (double)step * 1e-5;
    for (int d = 0; d < 3; d++) {
        f->box.lo[d] = -0.5 * gsl_rng_uniform(rng);
        f->box.hi[d] = f->box.lo[d] + 0.5 + gsl_rng_uniform(rng);
        f->box.periodic[d] = s->triclinic || d != 1; /* x and z periodic, y walls */
    }
    if (s->triclinic) {
        f->box.xy = 0.1 * gsl_rng_uniform(rng);
        f->box.xz = -0.05 * gsl_rng_uniform(rng);
        f->box.yz = 0.2 * gsl_rng_uniform(rng);
    }
    unsigned pbits = MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_VEL | MIMAS_P_OMEGA;
    if (s->optional)
        pbits |= MIMAS_P_FORCE | MIMAS_P_IMAGE | MIMAS_P_CG | MIMAS_P_LIQUID;
    size_t np = s->particles;
    if (fill_table(&f->particles, &mimas_particles_desc, np, pbits, np, rng,
                   s->optional ? "stress_atom" : NULL, 6))
        return -1;
    mimas_particles *p = &f->particles;
    /* unique ids: a shuffled sparse range, so the id map is exercised */
    for (size_t k = 0; k < np; k++)
        p->id[k] = (int64_t)(3 * k + 1);
    gsl_ran_shuffle(rng, p->id, np, sizeof *p->id);
    for (size_t k = 0; k < np; k++) {
        p->radius[k] = 1e-3 * (0.5 + gsl_rng_uniform(rng));
        p->mass[k] = 2000.0 * 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
        for (int d = 0; d < 3; d++)
            p->pos[k][d] = f->box.lo[d] + gsl_rng_uniform(rng) * (f->box.hi[d] - f->box.lo[d]);
        /* the readers refuse what no simulation has: factors and volumes < 0 */
        if (p->present & MIMAS_P_CG)
            p->cg[k] = 1.0 + fabs(p->cg[k]);
        if (p->present & MIMAS_P_LIQUID)
            p->liquid[k] = 1e-9 * fabs(p->liquid[k]);
    }
    f->has_contacts = s->with_contacts;
    f->has_walls = s->with_walls;
    unsigned cbits = MIMAS_C_POINT | MIMAS_C_FORCE | MIMAS_C_FORCE_N | MIMAS_C_FORCE_T |
                     MIMAS_C_OVERLAP;
    if (s->with_contacts &&
        fill_table(&f->contacts, &mimas_contacts_desc, np ? s->contacts : 0, cbits, np, rng,
                   s->optional ? "bridge_volume" : NULL, 1))
        return -1;
    unsigned wbits = MIMAS_W_POINT | MIMAS_W_FORCE | MIMAS_W_FORCE_N | MIMAS_W_FORCE_T |
                     MIMAS_W_OVERLAP;
    if (s->with_walls &&
        fill_table(&f->walls, &mimas_walls_desc, np ? s->walls : 0, wbits, np, rng, NULL, 0))
        return -1;
    return 0;
}

static int table_equal(const void *a, const void *b, const mimas_table_desc *d, char *why,
                       size_t len)
{
    size_t n = mimas_table_n(a, d);
    if (n != mimas_table_n(b, d)) {
        snprintf(why, len, "%s: %zu rows vs %zu", d->name, n, mimas_table_n(b, d));
        return 0;
    }
    if (mimas_table_present(a, d) != mimas_table_present(b, d)) {
        snprintf(why, len, "%s: quantities %#x vs %#x", d->name, mimas_table_present(a, d),
                 mimas_table_present(b, d));
        return 0;
    }
    unsigned present = mimas_table_present(a, d);
    for (size_t c = 0; c < d->ncolumns; c++) {
        if (!(present & d->columns[c].bit))
            continue;
        size_t bytes = n * (size_t)d->columns[c].ncomp * mimas_elem_size(d->columns[c].type);
        if (bytes && memcmp(mimas_table_column(a, d, c), mimas_table_column(b, d, c), bytes)) {
            snprintf(why, len, "%s: %s differs", d->name, d->columns[c].name);
            return 0;
        }
    }
    size_t ne = *(const size_t *)((const char *)a + d->off_n_extra);
    if (ne != *(const size_t *)((const char *)b + d->off_n_extra)) {
        snprintf(why, len, "%s: number of extra columns differs", d->name);
        return 0;
    }
    const mimas_extra *xa = *(mimas_extra *const *)((const char *)a + d->off_extra);
    const mimas_extra *xb = *(mimas_extra *const *)((const char *)b + d->off_extra);
    for (size_t e = 0; e < ne; e++) {
        if (strcmp(xa[e].name, xb[e].name) || xa[e].ncomp != xb[e].ncomp ||
            (n && memcmp(xa[e].data, xb[e].data, n * (size_t)xa[e].ncomp * sizeof(double)))) {
            snprintf(why, len, "%s: extra column %s differs", d->name, xa[e].name);
            return 0;
        }
    }
    return 1;
}

int frames_equal(const mimas_frame *a, const mimas_frame *b, char *why, size_t len)
{
    if (a->step != b->step || memcmp(&a->time, &b->time, sizeof a->time)) {
        snprintf(why, len, "step/time differ");
        return 0;
    }
    if (memcmp(&a->box, &b->box, sizeof a->box)) {
        snprintf(why, len, "box differs");
        return 0;
    }
    if (a->has_contacts != b->has_contacts || a->has_walls != b->has_walls) {
        snprintf(why, len, "contact presence differs");
        return 0;
    }
    return table_equal(&a->particles, &b->particles, &mimas_particles_desc, why, len) &&
           table_equal(&a->contacts, &b->contacts, &mimas_contacts_desc, why, len) &&
           table_equal(&a->walls, &b->walls, &mimas_walls_desc, why, len);
}
