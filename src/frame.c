#include <config.h>

#include "frame.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define COL(st, field, nm, ty, nc, b, u, m) \
    { nm, ty, nc, offsetof(st, field), b, u, m }

static const mimas_column_desc particle_columns[] = {
    COL(mimas_particles, id, "id", MIMAS_T_I64, 1, MIMAS_P_ID, "1", "particle identifier"),
    COL(mimas_particles, type, "species", MIMAS_T_I32, 1, MIMAS_P_TYPE, "1", "particle type"),
    COL(mimas_particles, radius, "radius", MIMAS_T_F64, 1, MIMAS_P_RADIUS, "m", "particle radius"),
    COL(mimas_particles, mass, "mass", MIMAS_T_F64, 1, MIMAS_P_MASS, "kg", "particle mass"),
    COL(mimas_particles, pos, "position", MIMAS_T_F64, 3, MIMAS_P_POS, "m", "centre position"),
    COL(mimas_particles, vel, "velocity", MIMAS_T_F64, 3, MIMAS_P_VEL, "m s-1", "centre velocity"),
    COL(mimas_particles, omega, "angular_velocity", MIMAS_T_F64, 3, MIMAS_P_OMEGA, "s-1",
        "angular velocity"),
    COL(mimas_particles, force, "force", MIMAS_T_F64, 3, MIMAS_P_FORCE, "N",
        "total force on the particle"),
    COL(mimas_particles, image, "image", MIMAS_T_I32, 3, MIMAS_P_IMAGE, "1",
        "periodic image flags"),
    COL(mimas_particles, cg, "coarse_grain_factor", MIMAS_T_F64, 1, MIMAS_P_CG, "1",
        "coarse-grain scale factor alpha = R_cg/R"),
    COL(mimas_particles, liquid, "liquid_volume", MIMAS_T_F64, 1, MIMAS_P_LIQUID, "m3",
        "volume of liquid carried by the particle"),
};

static const mimas_column_desc contact_columns[] = {
    COL(mimas_contacts, i, "i", MIMAS_T_INDEX, 1, MIMAS_C_I, "1", "first particle"),
    COL(mimas_contacts, j, "j", MIMAS_T_INDEX, 1, MIMAS_C_J, "1", "second particle"),
    COL(mimas_contacts, point, "contact_point", MIMAS_T_F64, 3, MIMAS_C_POINT, "m",
        "contact point"),
    COL(mimas_contacts, force, "force", MIMAS_T_F64, 3, MIMAS_C_FORCE, "N",
        "force on i exerted by j"),
    COL(mimas_contacts, force_n, "force_normal", MIMAS_T_F64, 3, MIMAS_C_FORCE_N, "N",
        "normal part of the force on i"),
    COL(mimas_contacts, force_t, "force_tangential", MIMAS_T_F64, 3, MIMAS_C_FORCE_T, "N",
        "tangential part of the force on i"),
    COL(mimas_contacts, overlap, "overlap", MIMAS_T_F64, 1, MIMAS_C_OVERLAP, "m",
        "overlap R_i + R_j - |r_i - r_j|"),
};

static const mimas_column_desc wall_columns[] = {
    COL(mimas_wall_contacts, particle, "particle", MIMAS_T_INDEX, 1, MIMAS_W_PARTICLE, "1",
        "particle in contact"),
    COL(mimas_wall_contacts, wall, "wall", MIMAS_T_I32, 1, MIMAS_W_WALL, "1", "wall identifier"),
    COL(mimas_wall_contacts, point, "contact_point", MIMAS_T_F64, 3, MIMAS_W_POINT, "m",
        "contact point"),
    COL(mimas_wall_contacts, force, "force", MIMAS_T_F64, 3, MIMAS_W_FORCE, "N",
        "force on the particle exerted by the wall"),
    COL(mimas_wall_contacts, force_n, "force_normal", MIMAS_T_F64, 3, MIMAS_W_FORCE_N, "N",
        "normal part of the force"),
    COL(mimas_wall_contacts, force_t, "force_tangential", MIMAS_T_F64, 3, MIMAS_W_FORCE_T, "N",
        "tangential part of the force"),
    COL(mimas_wall_contacts, overlap, "overlap", MIMAS_T_F64, 1, MIMAS_W_OVERLAP, "m",
        "overlap with the wall"),
};

#define TABLE(st, nm, cols, req)                                                        \
    {                                                                                   \
        nm, cols, sizeof cols / sizeof cols[0], req, offsetof(st, n), offsetof(st, cap), \
            offsetof(st, present), offsetof(st, n_extra), offsetof(st, extra)           \
    }

const mimas_table_desc mimas_particles_desc =
    TABLE(mimas_particles, "particles", particle_columns, MIMAS_P_ID | MIMAS_P_POS);
const mimas_table_desc mimas_contacts_desc =
    TABLE(mimas_contacts, "contacts", contact_columns, MIMAS_C_I | MIMAS_C_J);
const mimas_table_desc mimas_walls_desc =
    TABLE(mimas_wall_contacts, "wall contacts", wall_columns, MIMAS_W_PARTICLE | MIMAS_W_WALL);

/* ---- member access through the descriptor offsets ---- */
#define MEMBER(tab, off, T) ((T *)((char *)(tab) + (off)))

size_t mimas_elem_size(mimas_elem_type t)
{
    switch (t) {
    case MIMAS_T_F64: return sizeof(double);
    case MIMAS_T_I64: return sizeof(int64_t);
    case MIMAS_T_I32: return sizeof(int32_t);
    case MIMAS_T_INDEX: return sizeof(size_t);
    }
    return 0;
}

size_t mimas_table_n(const void *tab, const mimas_table_desc *d)
{
    return *MEMBER(tab, d->off_n, const size_t);
}

unsigned mimas_table_present(const void *tab, const mimas_table_desc *d)
{
    return *MEMBER(tab, d->off_present, const unsigned);
}

void *mimas_table_column(const void *tab, const mimas_table_desc *d, size_t col)
{
    return *MEMBER(tab, d->columns[col].offset, void *const);
}

const mimas_column_desc *mimas_table_find(const mimas_table_desc *d, const char *name)
{
    for (size_t c = 0; c < d->ncolumns; c++)
        if (strcmp(d->columns[c].name, name) == 0)
            return &d->columns[c];
    return NULL;
}

static size_t row_bytes(const mimas_column_desc *c)
{
    return mimas_elem_size(c->type) * (size_t)c->ncomp;
}

static int grow(void **p, size_t bytes, mimas_error *err)
{
    void *q = realloc(*p, bytes ? bytes : 1);
    if (!q)
        return mimas_error_set(err, MIMAS_EIO, "out of memory (%zu bytes)", bytes);
    *p = q;
    return MIMAS_OK;
}

int mimas_table_set_present(void *tab, const mimas_table_desc *d, unsigned bits,
                            mimas_error *err)
{
    unsigned *present = MEMBER(tab, d->off_present, unsigned);
    size_t cap = *MEMBER(tab, d->off_cap, size_t);
    for (size_t c = 0; c < d->ncolumns; c++) {
        const mimas_column_desc *col = &d->columns[c];
        if (!(bits & col->bit) || (*present & col->bit))
            continue;
        void **arr = MEMBER(tab, col->offset, void *);
        int rc = grow(arr, cap * row_bytes(col), err);
        if (rc)
            return rc;
        *present |= col->bit;
    }
    return MIMAS_OK;
}

int mimas_table_resize(void *tab, const mimas_table_desc *d, size_t n, mimas_error *err)
{
    size_t *cap = MEMBER(tab, d->off_cap, size_t);
    if (n > *cap) {
        size_t newcap = *cap ? *cap : 16;
        while (newcap < n)
            newcap += newcap / 2;
        unsigned present = *MEMBER(tab, d->off_present, unsigned);
        for (size_t c = 0; c < d->ncolumns; c++) {
            const mimas_column_desc *col = &d->columns[c];
            if (!(present & col->bit))
                continue;
            int rc = grow(MEMBER(tab, col->offset, void *), newcap * row_bytes(col), err);
            if (rc)
                return rc;
        }
        size_t n_extra = *MEMBER(tab, d->off_n_extra, size_t);
        mimas_extra *extra = *MEMBER(tab, d->off_extra, mimas_extra *);
        for (size_t e = 0; e < n_extra; e++) {
            int rc = grow((void **)&extra[e].data,
                          newcap * (size_t)extra[e].ncomp * sizeof(double), err);
            if (rc)
                return rc;
        }
        *cap = newcap;
    }
    *MEMBER(tab, d->off_n, size_t) = n;
    return MIMAS_OK;
}

static int append_extra(void *tab, const mimas_table_desc *d, const char *name, int ncomp,
                        size_t *index, mimas_error *err);

int mimas_table_add_extra(void *tab, const mimas_table_desc *d, const char *name, int ncomp,
                          size_t *index, mimas_error *err)
{
    size_t *n_extra = MEMBER(tab, d->off_n_extra, size_t);
    mimas_extra **extra = MEMBER(tab, d->off_extra, mimas_extra *);
    for (size_t e = 0; e < *n_extra; e++) {
        if (strcmp((*extra)[e].name, name) == 0) {
            if ((*extra)[e].ncomp != ncomp)
                return mimas_error_set(err, MIMAS_EDATA,
                                       "%s column '%s' has %d components, not %d", d->name,
                                       name, (*extra)[e].ncomp, ncomp);
            if (index)
                *index = e;
            return MIMAS_OK;
        }
    }
    return append_extra(tab, d, name, ncomp, index, err);
}

int mimas_table_add_new_extra(void *tab, const mimas_table_desc *d, const char *name, int ncomp,
                              mimas_error *err)
{
    return append_extra(tab, d, name, ncomp, NULL, err);
}

static int append_extra(void *tab, const mimas_table_desc *d, const char *name, int ncomp,
                        size_t *index, mimas_error *err)
{
    size_t *n_extra = MEMBER(tab, d->off_n_extra, size_t);
    mimas_extra **extra = MEMBER(tab, d->off_extra, mimas_extra *);
    if (mimas_table_find(d, name))
        return mimas_error_set(err, MIMAS_EDATA, "'%s' is a standard %s quantity, not an extra",
                               name, d->name);
    if (ncomp < 1)
        return mimas_error_set(err, MIMAS_EUSAGE, "extra column '%s' needs components", name);
    /* the array doubles at 4, 8, 16, ... columns (its capacity is not stored:
     * it follows from the count), so many columns take linear time */
    size_t n = *n_extra;
    if (n == 0 || (n >= 4 && (n & (n - 1)) == 0)) {
        int rc = grow((void **)extra, (n ? 2 * n : 4) * sizeof **extra, err);
        if (rc)
            return rc;
    }
    mimas_extra *x = &(*extra)[*n_extra];
    x->name = strdup(name);
    x->ncomp = ncomp;
    x->data = NULL;
    x->unit[0] = '\0';
    size_t cap = *MEMBER(tab, d->off_cap, size_t);
    if (!x->name || grow((void **)&x->data, cap * (size_t)ncomp * sizeof(double), err)) {
        free(x->name);
        free(x->data);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for a frame column");
    }
    if (index)
        *index = *n_extra;
    (*n_extra)++;
    return MIMAS_OK;
}

void mimas_table_free(void *tab, const mimas_table_desc *d)
{
    for (size_t c = 0; c < d->ncolumns; c++) {
        void **arr = MEMBER(tab, d->columns[c].offset, void *);
        free(*arr);
        *arr = NULL;
    }
    size_t *n_extra = MEMBER(tab, d->off_n_extra, size_t);
    mimas_extra **extra = MEMBER(tab, d->off_extra, mimas_extra *);
    for (size_t e = 0; e < *n_extra; e++) {
        free((*extra)[e].name);
        free((*extra)[e].data);
    }
    free(*extra);
    *extra = NULL;
    *n_extra = 0;
    *MEMBER(tab, d->off_n, size_t) = 0;
    *MEMBER(tab, d->off_cap, size_t) = 0;
    *MEMBER(tab, d->off_present, unsigned) = 0;
}

void mimas_table_keep_only(void *tab, const mimas_table_desc *d, unsigned bits)
{
    unsigned *present = MEMBER(tab, d->off_present, unsigned);
    for (size_t c = 0; c < d->ncolumns; c++) {
        const mimas_column_desc *col = &d->columns[c];
        if ((*present & col->bit) && !((bits | d->required) & col->bit)) {
            void **arr = MEMBER(tab, col->offset, void *);
            free(*arr);
            *arr = NULL;
            *present &= ~col->bit;
        }
    }
}

void mimas_table_drop_extras(void *tab, const mimas_table_desc *d)
{
    size_t *n_extra = MEMBER(tab, d->off_n_extra, size_t);
    mimas_extra *extra = *MEMBER(tab, d->off_extra, mimas_extra *);
    for (size_t e = 0; e < *n_extra; e++) {
        free(extra[e].name);
        free(extra[e].data);
    }
    *n_extra = 0;
}

/* Drops rows, optional quantities and extras but keeps the memory of the
 * required arrays. */
static void table_clear(void *tab, const mimas_table_desc *d)
{
    mimas_table_keep_only(tab, d, 0);
    mimas_table_drop_extras(tab, d);
    *MEMBER(tab, d->off_n, size_t) = 0;
}

int mimas_table_require(const void *tab, const mimas_table_desc *d, unsigned bits,
                        mimas_error *err)
{
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++)
        if ((bits & d->columns[c].bit) && !(present & d->columns[c].bit))
            return mimas_error_set(err, MIMAS_EMISSING, "%s have no %s", d->name,
                                   d->columns[c].name);
    return MIMAS_OK;
}

/* ---- frame ---- */
void mimas_frame_init(mimas_frame *f)
{
    memset(f, 0, sizeof *f);
    /* the required quantities exist from the start (with zero rows) */
    mimas_table_set_present(&f->particles, &mimas_particles_desc, mimas_particles_desc.required,
                            NULL);
    mimas_table_set_present(&f->contacts, &mimas_contacts_desc, mimas_contacts_desc.required,
                            NULL);
    mimas_table_set_present(&f->walls, &mimas_walls_desc, mimas_walls_desc.required, NULL);
}

void mimas_frame_free(mimas_frame *f)
{
    mimas_table_free(&f->particles, &mimas_particles_desc);
    mimas_table_free(&f->contacts, &mimas_contacts_desc);
    mimas_table_free(&f->walls, &mimas_walls_desc);
    mimas_gas_free(&f->gas);
}

void mimas_frame_clear(mimas_frame *f)
{
    table_clear(&f->particles, &mimas_particles_desc);
    table_clear(&f->contacts, &mimas_contacts_desc);
    table_clear(&f->walls, &mimas_walls_desc);
    f->step = 0;
    f->time = 0.0;
    f->has_contacts = f->has_walls = 0;
    memset(&f->box, 0, sizeof f->box);
    memset(&f->tube, 0, sizeof f->tube);
    f->gas.present = 0;
}

/* ---- gas grid ---- */
size_t mimas_gas_cells(const mimas_gas *g)
{
    return g->present ? g->cells[0] * g->cells[1] * g->cells[2] : 0;
}

int mimas_gas_resize(mimas_gas *g, size_t nx, size_t ny, size_t nz, mimas_error *err)
{
    if (nx == 0 || ny == 0 || nz == 0 || nx > SIZE_MAX / ny || nx * ny > SIZE_MAX / nz ||
        nx * ny * nz > SIZE_MAX / (3 * sizeof(double)))
        return mimas_error_set(err, MIMAS_EDATA, "gas grid of %zu x %zu x %zu cells", nx, ny,
                               nz);
    size_t n = nx * ny * nz;
    if (n > g->cap) {
        double *p = realloc(g->pressure, n * sizeof *p);
        if (p)
            g->pressure = p;
        double *q = p ? realloc(g->porosity, n * sizeof *q) : NULL;
        if (q)
            g->porosity = q;
        double(*v)[3] = q ? realloc(g->velocity, n * sizeof *v) : NULL;
        if (!v)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for a gas grid of %zu cells",
                                   n);
        g->velocity = v;
        g->cap = n;
    }
    g->cells[0] = nx, g->cells[1] = ny, g->cells[2] = nz;
    g->present = 1;
    return MIMAS_OK;
}

void mimas_gas_free(mimas_gas *g)
{
    free(g->pressure);
    free(g->porosity);
    free(g->velocity);
    memset(g, 0, sizeof *g);
}

/* ---- box ---- */
int mimas_box_is_triclinic(const mimas_box *b)
{
    return b->xy != 0.0 || b->xz != 0.0 || b->yz != 0.0;
}

int mimas_box_equal(const mimas_box *a, const mimas_box *b)
{
    for (int d = 0; d < 3; d++)
        if (a->lo[d] != b->lo[d] || a->hi[d] != b->hi[d] || a->periodic[d] != b->periodic[d])
            return 0;
    return a->xy == b->xy && a->xz == b->xz && a->yz == b->yz;
}

double mimas_box_volume(const mimas_box *b)
{
    /* the tilt shears the box without changing its volume */
    return (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}

void mimas_box_edges(const mimas_box *b, double e[3][3])
{
    double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
    double m[3][3] = {{L[0], 0.0, 0.0}, {b->xy, L[1], 0.0}, {b->xz, b->yz, L[2]}};
    memcpy(e, m, sizeof m);
}

void mimas_box_fractional(const mimas_box *b, const double e[3][3], const double x[3],
                          double s[3])
{
    /* the edge vectors form a lower triangular matrix: solved from z down */
    double r[3] = {x[0] - b->lo[0], x[1] - b->lo[1], x[2] - b->lo[2]};
    s[2] = r[2] / e[2][2];
    s[1] = (r[1] - s[2] * e[2][1]) / e[1][1];
    s[0] = (r[0] - s[2] * e[2][0] - s[1] * e[1][0]) / e[0][0];
}

void mimas_box_min_image_shift(const mimas_box *b, double d[3], double k[3])
{
    double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
    k[0] = k[1] = k[2] = 0;
    /* z, then y, then x: the tilt couples each axis to the ones below it.  Within half a
     * period along an axis its shift is 0 (|d / L| <= 1/2, which rounds to 0, ties to even),
     * and d stays as it is: the division and the rounding only where it is not. */
    if (b->periodic[2] && !(fabs(d[2]) <= 0.5 * L[2])) {
        k[2] = nearbyint(d[2] / L[2]);
        d[2] -= k[2] * L[2];
        d[1] -= k[2] * b->yz;
        d[0] -= k[2] * b->xz;
    }
    if (b->periodic[1] && !(fabs(d[1]) <= 0.5 * L[1])) {
        k[1] = nearbyint(d[1] / L[1]);
        d[1] -= k[1] * L[1];
        d[0] -= k[1] * b->xy;
    }
    if (b->periodic[0] && !(fabs(d[0]) <= 0.5 * L[0])) {
        k[0] = nearbyint(d[0] / L[0]);
        d[0] -= k[0] * L[0];
    }
}

void mimas_box_min_image(const mimas_box *b, double d[3])
{
    double k[3];
    mimas_box_min_image_shift(b, d, k);
}

int mimas_particle_selected(const mimas_particles *p, size_t k, const int32_t *types,
                            size_t ntypes, int exclude)
{
    if (!ntypes)
        return 1;
    int32_t t = (p->present & MIMAS_P_TYPE) ? p->type[k] : 1;
    int listed = 0;
    for (size_t m = 0; m < ntypes; m++)
        listed |= types[m] == t;
    return exclude ? !listed : listed;
}
