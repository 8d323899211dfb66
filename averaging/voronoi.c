#include <config.h>

#include "voronoi.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "cell_list.h"
#include "contact_point.h"
#include "weight.h"

struct mimas_voronoi {
    mimas_voronoi_options opt;
    mimas_weight shepard;     /* the Gaussian of velocity_width (its norm cancels) */
    mimas_cell_list cl;
    size_t cap;
    double *volume;
    int *faces;
    unsigned char *surface, *use;
    double (*mean_v)[3];      /* V at each particle */
    double (*sum)[9];         /* V_cell sigma of each particle */
};

int mimas_voronoi_create(mimas_voronoi **out, const mimas_voronoi_options *o, mimas_error *err)
{
    *out = NULL;
    mimas_voronoi *v = calloc(1, sizeof *v);
    if (!v)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the Voronoi cells");
    v->opt = *o;
    mimas_cell_list_init(&v->cl);
    if (o->velocity_width > 0) {
        char spec[64];
        snprintf(spec, sizeof spec, "gauss:w=%.17g", o->velocity_width);
        int rc = mimas_weight_parse(&v->shepard, spec, err);
        if (rc) {
            free(v);
            return rc;
        }
    }
    *out = v;
    return MIMAS_OK;
}

void mimas_voronoi_free(mimas_voronoi *v)
{
    if (!v)
        return;
    mimas_cell_list_free(&v->cl);
    free(v->volume);
    free(v->faces);
    free(v->surface);
    free(v->use);
    free(v->mean_v);
    free(v->sum);
    free(v);
}

int mimas_voronoi_reported(const mimas_voronoi *v, const mimas_particles *p, size_t k)
{
    if (!(p->present & MIMAS_P_TYPE))
        return 1;
    for (size_t m = 0; m < v->opt.nexclude; m++)
        if (p->type[k] == v->opt.exclude[m])
            return 0;
    return 1;
}

#define GROW(ptr, n)                                              \
    do {                                                          \
        void *g_ = realloc((ptr), (n) * sizeof *(ptr));           \
        if (!g_)                                                  \
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the Voronoi cells"); \
        (ptr) = g_;                                               \
    } while (0)

static int reserve(mimas_voronoi *v, size_t n, mimas_error *err)
{
    if (n <= v->cap)
        return MIMAS_OK;
    GROW(v->volume, n);
    GROW(v->faces, n);
    GROW(v->surface, n);
    GROW(v->use, n);
    GROW(v->mean_v, n);
    GROW(v->sum, n);
    v->cap = n;
    return MIMAS_OK;
}

/* ---- the mean velocity V: Shepard's ratio of Gaussian sums (002 eq. 2.27) ---- */

typedef struct shepard_ctx {
    const mimas_weight *wt;
    const double (*vel)[3];
    double g, gv[3];
} shepard_ctx;

static void add_neighbour(void *user, size_t j, const double d[3], double d2)
{
    (void)d2;
    shepard_ctx *s = user;
    double g = mimas_gauss_phi(s->wt, d);
    s->g += g;
    for (int m = 0; m < 3; m++)
        s->gv[m] += g * s->vel[j][m];
}

static int mean_velocity(mimas_voronoi *v, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    if (!(v->opt.velocity_width > 0)) {
        memset(v->mean_v, 0, p->n * sizeof *v->mean_v);
        return MIMAS_OK;
    }
    int rc = mimas_cell_list_build(&v->cl, &f->box, p->n, (const double (*)[3])p->pos, v->use,
                                   mimas_weight_reach(&v->shepard), err);
    if (rc)
        return mimas_error_prefix(err, "--velocity-width %g", v->opt.velocity_width);
    long n = (long)p->n;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 256) num_threads(v->opt.threads > 0 ? v->opt.threads : omp_get_max_threads())
#endif
    for (long k = 0; k < n; k++) {
        shepard_ctx s = {&v->shepard, (const double (*)[3])p->vel, 0.0, {0, 0, 0}};
        mimas_cell_list_query(&v->cl, p->pos[k], (const double (*)[3])p->pos, add_neighbour, &s);
        for (int m = 0; m < 3; m++)
            v->mean_v[k][m] = s.g > 0 ? s.gv[m] / s.g : 0.0;
    }
    return MIMAS_OK;
}

/* ---- the stress sums V_cell sigma_k (PHYSICS 1, 6) ---- */

/* sum[k] += f (x) b, force first */
static void add_outer(double sum[9], const double f[3], const double b[3], double sign)
{
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
            sum[3 * a + c] += sign * f[a] * b[c];
}

static int stress_sums(mimas_voronoi *v, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mean_velocity(v, f, err);
    if (rc)
        return rc;
    for (size_t k = 0; k < p->n; k++) {
        double dv[3];
        for (int m = 0; m < 3; m++)
            dv[m] = p->vel[k][m] - v->mean_v[k][m];
        memset(v->sum[k], 0, sizeof v->sum[k]);
        add_outer(v->sum[k], dv, dv, p->mass[k]);
    }
    /* each particle of a contact: its force with its own branch to the
     * contact point */
    const mimas_contacts *c = &f->contacts;
    for (size_t k = 0; k < c->n; k++) {
        size_t i = c->i[k], j = c->j[k];
        double cp[3], b[3];
        mimas_contact_point(f, k, i, cp);
        mimas_branch(&f->box, p->pos[i], cp, b);
        add_outer(v->sum[i], c->force[k], b, 1.0);
        mimas_branch(&f->box, p->pos[j], cp, b);
        add_outer(v->sum[j], c->force[k], b, -1.0);
    }
    const mimas_wall_contacts *w = &f->walls;
    for (size_t k = 0; f->has_walls && k < w->n; k++) {
        double b[3];
        mimas_branch(&f->box, p->pos[w->particle[k]], w->point[k], b);
        add_outer(v->sum[w->particle[k]], w->force[k], b, 1.0);
    }
    return MIMAS_OK;
}

/* ---- storing the results as extra columns ---- */

static int add_column(mimas_particles *p, const char *name, int ncomp, const char *unit,
                      size_t *index, mimas_error *err)
{
    int rc = mimas_table_add_extra(p, &mimas_particles_desc, name, ncomp, index, err);
    if (!rc)
        snprintf(p->extra[*index].unit, sizeof p->extra[*index].unit, "%s", unit);
    return rc;
}

static int store(mimas_voronoi *v, mimas_particles *p, int with_stress, mimas_error *err)
{
    size_t iv, inu, ifc, isf, ist = 0;
    int rc = add_column(p, MIMAS_VORONOI_VOLUME, 1, "m3", &iv, err);
    if (!rc)
        rc = add_column(p, MIMAS_VORONOI_NU, 1, "", &inu, err);
    if (!rc)
        rc = add_column(p, MIMAS_VORONOI_FACES, 1, "", &ifc, err);
    if (!rc)
        rc = add_column(p, MIMAS_VORONOI_SURFACE, 1, "", &isf, err);
    if (!rc && with_stress)
        rc = add_column(p, MIMAS_VORONOI_STRESS, 9, "Pa", &ist, err);
    if (rc)
        return rc;
    double *vol = p->extra[iv].data, *nu = p->extra[inu].data, *fc = p->extra[ifc].data,
           *sf = p->extra[isf].data, *st = with_stress ? p->extra[ist].data : NULL;
    for (size_t k = 0; k < p->n; k++) {
        double V = v->volume[k];
        if (!v->use[k]) {
            vol[k] = nu[k] = fc[k] = sf[k] = NAN;
            for (int m = 0; st && m < 9; m++)
                st[9 * k + (size_t)m] = NAN;
            continue;
        }
        vol[k] = V;
        nu[k] = V > 0 ? 4.0 / 3.0 * M_PI * pow(p->radius[k], 3) / V : NAN;
        fc[k] = v->faces[k];
        sf[k] = v->surface[k];
        for (int m = 0; st && m < 9; m++)
            st[9 * k + (size_t)m] = V > 0 ? v->sum[k][m] / V : NAN;
    }
    return MIMAS_OK;
}

int mimas_voronoi_frame(mimas_voronoi *v, mimas_frame *f, mimas_error *err)
{
    mimas_particles *p = &f->particles;
    int rc = mimas_table_require(p, &mimas_particles_desc, MIMAS_P_RADIUS, err);
    int with_stress = f->has_contacts;
    if (!rc && with_stress) {
        rc = mimas_table_require(p, &mimas_particles_desc, MIMAS_P_MASS | MIMAS_P_VEL, err);
        if (rc && !(p->present & MIMAS_P_MASS))
            return mimas_error_prefix(err, "%s", "give the particle density with --density");
        if (!rc)
            rc = mimas_table_require(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, err);
        if (!rc && f->has_walls)
            rc = mimas_table_require(&f->walls, &mimas_walls_desc,
                                     MIMAS_W_FORCE | MIMAS_W_POINT, err);
    }
    if (!rc)
        rc = reserve(v, p->n, err);
    if (rc)
        return rc;
    mimas_voro_options vo = {v->opt.radical ? p->radius : NULL, v->opt.walls, v->opt.nwalls,
                             v->opt.max_extent, v->opt.threads,
                             (p->present & MIMAS_P_ID) ? p->id : NULL};
    rc = mimas_voro_cells(&f->box, p->n, (const double (*)[3])p->pos, &vo, v->volume, v->faces,
                          v->surface, err);
    if (rc)
        return rc;
    for (size_t k = 0; k < p->n; k++)
        v->use[k] = (unsigned char)mimas_voronoi_reported(v, p, k);
    if (with_stress && (rc = stress_sums(v, f, err)))
        return rc;
    return store(v, p, with_stress, err);
}

void mimas_voronoi_values_of(const mimas_particles *p, mimas_voronoi_values *v)
{
    memset(v, 0, sizeof *v);
    for (size_t e = 0; e < p->n_extra; e++) {
        const mimas_extra *x = &p->extra[e];
        const double **dst = NULL;
        int ncomp = 1;
        if (!strcmp(x->name, MIMAS_VORONOI_VOLUME))
            dst = &v->volume;
        else if (!strcmp(x->name, MIMAS_VORONOI_NU))
            dst = &v->nu;
        else if (!strcmp(x->name, MIMAS_VORONOI_FACES))
            dst = &v->faces;
        else if (!strcmp(x->name, MIMAS_VORONOI_SURFACE))
            dst = &v->surface;
        else if (!strcmp(x->name, MIMAS_VORONOI_STRESS))
            dst = &v->stress, ncomp = 9;
        if (dst && x->ncomp == ncomp)
            *dst = x->data;
    }
}
