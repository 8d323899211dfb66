/* Linked cells and Verlet lists (docs/theory.md §3): particles are sorted by cell,
 * each pair is found once through a half shell of 13 neighbour cells, the
 * list holds every pair closer than R_i + R_j + skin (+ the longest liquid
 * bridge) and is rebuilt when a particle has moved more than skin/2.  The
 * contact history travels from the old list to the new one.  Building is
 * deterministic for given positions and particle order, so results do not
 * depend on the thread count. */
#include <config.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"

typedef struct cell_grid {
    int n[3];
    size_t stride[3];         /* cell index = sum c[d] stride[d]; the longest axis slowest */
    double lo[3], edge[3];
    size_t *start;            /* ncells + 1, into the sorted particle order */
    size_t *cell;             /* per particle (sorted order) */
} cell_grid;

/* the 13 cells of the half shell: (dz > 0) or (dz == 0 and dy > 0) or (dz == dy == 0, dx > 0) */
static const int half_shell[13][3] = {
    {1, 0, 0},   {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},  {-1, -1, 1}, {0, -1, 1}, {1, -1, 1},
    {-1, 0, 1},  {0, 0, 1},  {1, 0, 1},  {-1, 1, 1}, {0, 1, 1},   {1, 1, 1}};

static void wrap_periodic(dem_system *s)
{
    for (int d = 0; d < 3; d++) {
        if (!s->periodic[d])
            continue;
        double L = s->hi[d] - s->lo[d];
        for (size_t k = 0; k < s->n; k++) {
            double q = floor((s->x[k][d] - s->lo[d]) / L);
            if (q != 0) {
                s->x[k][d] -= q * L;
                if (s->x[k][d] >= s->hi[d])   /* rounding */
                    s->x[k][d] = s->lo[d];
                s->image[k][d] += (int32_t)q;
                if (s->glued[k] >= 0)
                    s->anchor[k][d] -= q * L;
            }
        }
    }
}

static int make_grid(const dem_system *s, double cutoff, cell_grid *g, mimas_error *err)
{
    double lo[3], hi[3];
    for (int d = 0; d < 3; d++) {
        if (s->periodic[d]) {
            lo[d] = s->lo[d];
            hi[d] = s->hi[d];
        } else {
            lo[d] = INFINITY;
            hi[d] = -INFINITY;
            for (size_t k = 0; k < s->n; k++) {
                if (s->x[k][d] < lo[d])
                    lo[d] = s->x[k][d];
                if (s->x[k][d] > hi[d])
                    hi[d] = s->x[k][d];
            }
            if (!isfinite(lo[d]) || !isfinite(hi[d]))
                return mimas_error_set(err, MIMAS_EDATA, "a particle position is not finite "
                                       "(the simulation blew up; lower dt)");
        }
    }
    double edge = cutoff;
    for (;;) {
        double total = 1;
        for (int d = 0; d < 3; d++) {
            double ext = hi[d] - lo[d];
            g->n[d] = ext > edge ? (int)fmin(floor(ext / edge), 1 << 20) : 1;
            g->lo[d] = lo[d];
            g->edge[d] = ext > 0 ? ext / g->n[d] : 1;
            if (s->periodic[d] && g->n[d] < 3)
                return mimas_error_set(err, MIMAS_EDATA, "the periodic box is too small: "
                                       "it must be at least 3 x (largest diameter + skin) "
                                       "= %g m wide", 3 * cutoff);
            total *= g->n[d];
        }
        /* at most a few cells per particle (a particle far away would make the
         * grid of the bounding box huge) */
        if (total <= 4.0 * (double)s->n + 64)
            break;
        edge *= 1.26;
    }
    /* memory order of the cells: x fastest, z slowest (sorting the axes by
     * their cell counts was measured slower on the ring shear cell) */
    const int order[3] = {0, 1, 2};
    size_t stride = 1;
    for (int a = 0; a < 3; a++) {
        g->stride[order[a]] = stride;
        stride *= (size_t)g->n[order[a]];
    }
    return MIMAS_OK;
}

static size_t cell_of(const cell_grid *g, const double *x)
{
    int c[3];
    for (int d = 0; d < 3; d++) {
        double q = floor((x[d] - g->lo[d]) / g->edge[d]);
        c[d] = q < 0 ? 0 : q >= g->n[d] ? g->n[d] - 1 : (int)q;
    }
    return (size_t)c[0] * g->stride[0] + (size_t)c[1] * g->stride[1] + (size_t)c[2] * g->stride[2];
}

static void permute(void *arr, size_t elem, const size_t *old_of, size_t n, void *tmp)
{
    char *a = arr, *t = tmp;
    for (size_t k = 0; k < n; k++)
        memcpy(t + k * elem, a + old_of[k] * elem, elem);
    memcpy(a, t, n * elem);
}

/* Sorts the particles by cell (stable), so neighbours are close in memory. */
static int sort_by_cell(dem_system *s, cell_grid *g, size_t *old_of, mimas_error *err)
{
    size_t ncells = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2], n = s->n;
    g->start = calloc(ncells + 1, sizeof *g->start);
    g->cell = malloc((n ? n : 1) * sizeof *g->cell);
    size_t *c = malloc((n ? n : 1) * sizeof *c);
    void *tmp = malloc((n ? n : 1) * sizeof(double) * 3 * DEM_MAX_WALLS);
    if (!g->start || !g->cell || !c || !tmp) {
        free(c);
        free(tmp);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the neighbour cells");
    }
    for (size_t k = 0; k < n; k++) {
        c[k] = cell_of(g, s->x[k]);
        g->start[c[k] + 1]++;
    }
    for (size_t q = 0; q < ncells; q++)
        g->start[q + 1] += g->start[q];
    {
        size_t *cursor = malloc((ncells ? ncells : 1) * sizeof *cursor);
        if (!cursor) {
            free(c);
            free(tmp);
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the neighbour cells");
        }
        memcpy(cursor, g->start, ncells * sizeof *cursor);
        for (size_t k = 0; k < n; k++)
            old_of[cursor[c[k]]++] = k;
        free(cursor);
    }
    for (size_t k = 0; k < n; k++)
        g->cell[k] = c[old_of[k]];
#define PERMUTE(a) permute(s->a, sizeof *s->a, old_of, n, tmp);
    PERMUTE(id) PERMUTE(type) PERMUTE(radius) PERMUTE(mass) PERMUTE(inertia) PERMUTE(liquid)
    PERMUTE(x) PERMUTE(v) PERMUTE(w) PERMUTE(f) PERMUTE(t) PERMUTE(image) PERMUTE(glued)
    PERMUTE(anchor) PERMUTE(bridges) PERMUTE(wall_near)
#undef PERMUTE
    permute(s->wall_xi, sizeof *s->wall_xi * DEM_MAX_WALLS, old_of, n, tmp);
    permute(s->wall_f, sizeof *s->wall_f * DEM_MAX_WALLS, old_of, n, tmp);
    permute(s->wall_delta, sizeof *s->wall_delta * DEM_MAX_WALLS, old_of, n, tmp);
    free(c);
    free(tmp);
    return MIMAS_OK;
}

/* The history of pair (oi, oj) (old indices) in the old list, oriented as i
 * relative to j, into *h and *bv; zero if the pair was not listed. */
static void old_history(const size_t *ostart, size_t on, const dem_entry *oe, const double *obv,
                        size_t oi, size_t oj, dem_entry *h, double *bv)
{
    *h = (dem_entry){0};
    *bv = 0;
    if (!ostart || oi >= on || oj >= on)   /* no list, or a particle added since */
        return;
    for (size_t k = ostart[oi]; k < ostart[oi + 1]; k++)
        if ((size_t)oe[k].j == oj) {
            *h = oe[k];
            *bv = obv[k];
            return;
        }
    for (size_t k = ostart[oj]; k < ostart[oj + 1]; k++)
        if ((size_t)oe[k].j == oi) {
            *h = oe[k];
            *bv = obv[k];
            for (int d = 0; d < 3; d++)
                h->xi[d] = -h->xi[d];
            return;
        }
}

typedef struct build_ctx {
    const dem_system *s;
    const cell_grid *g;
    double extra;             /* skin + bridge range */
    const size_t *ostart, *old_of;
    size_t on;                /* particles of the old list (those added since have no history) */
    const dem_entry *oe;
    const double *obv;
} build_ctx;

static int pair_listed(const build_ctx *b, size_t i, size_t j)
{
    const dem_system *s = b->s;
    if (s->glued[i] >= 0 && s->glued[j] >= 0 && !s->glued_interact)
        return 0;   /* two wall particles never interact */
    double d[3];
    dem_separation(s, s->x[i], s->x[j], d);
    double cut = s->radius[i] + s->radius[j] + b->extra;
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut;
}

/* Visits the partners of i: counts them (out == NULL) or writes the entries
 * and their bridge volumes. */
static size_t visit(const build_ctx *b, size_t i, dem_entry *out, double *bv)
{
    const cell_grid *g = b->g;
    size_t c = g->cell[i], found = 0;
    int ci[3];
    for (int d = 0; d < 3; d++)
        ci[d] = (int)(c / g->stride[d] % (size_t)g->n[d]);
    for (int h = -1; h < 13; h++) {
        int q[3];
        int skip = 0;
        for (int d = 0; d < 3; d++) {
            q[d] = ci[d] + (h < 0 ? 0 : half_shell[h][d]);
            if (q[d] < 0 || q[d] >= g->n[d]) {
                if (!b->s->periodic[d])
                    skip = 1;
                q[d] = (q[d] + g->n[d]) % g->n[d];
            }
        }
        if (skip)
            continue;
        size_t cc = (size_t)q[0] * g->stride[0] + (size_t)q[1] * g->stride[1] +
                    (size_t)q[2] * g->stride[2];
        size_t j0 = h < 0 ? i + 1 : g->start[cc];
        for (size_t j = j0; j < g->start[cc + 1]; j++) {
            if (!pair_listed(b, i, j))
                continue;
            if (out) {
                old_history(b->ostart, b->on, b->oe, b->obv, b->old_of[i], b->old_of[j],
                            &out[found], &bv[found]);
                out[found].j = (int32_t)j;
            }
            found++;
        }
    }
    return found;
}

/* The walls each particle can reach before the next build (it moves less than skin/2). */
static void mark_walls_near(dem_system *s)
{
#pragma omp parallel for schedule(static) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t k = 0; k < s->n; k++) {
        uint8_t near = 0;
        for (int w = 0; w < s->nwalls; w++) {
            double nrm[3], c[3];
            if (dem_wall_geometry(&s->walls[w], s->x[k], s->radius[k] + s->skin, nrm, c) > 0)
                near |= (uint8_t)(1u << w);
        }
        s->wall_near[k] = near;
    }
}

int dem_neighbours_build(dem_system *s, mimas_error *err)
{
    dem_nlist *nl = &s->nl;
    size_t n = s->n, ne = 0;
    double dmax = 0;
    for (size_t k = 0; k < n; k++)
        if (2 * s->radius[k] > dmax)
            dmax = 2 * s->radius[k];
    double extra = s->skin + (s->bridges_on ? s->bridge_range : 0);
    /* a state that blew up stops here, before its huge numbers reach the
     * cells and image flags */
    int bad = dem_check_state(s, err);
    if (bad)
        return bad;
    wrap_periodic(s);
    cell_grid g = {0};
    size_t *old_of = malloc((n ? n : 1) * sizeof *old_of);
    size_t *start = malloc((n + 1) * sizeof *start);
    dem_entry *e = NULL;
    double *bv = NULL;
    int rc = !old_of || !start ? mimas_error_set(err, MIMAS_EIO, "out of memory for the "
                                                 "neighbour list")
                               : make_grid(s, dmax + extra, &g, err);
    if (!rc)
        rc = sort_by_cell(s, &g, old_of, err);
    if (!rc) {
        /* the old list (in old indices) stays until the history has moved over;
         * particles appended since it was built (indices >= nl->n) have none */
        build_ctx b = {s, &g, extra, nl->n <= n ? nl->start : NULL, old_of, nl->n, nl->e, nl->bv};
        start[0] = 0;
#pragma omp parallel for schedule(dynamic, 256) if (s->n >= DEM_PARALLEL_MIN)
        for (size_t i = 0; i < n; i++)
            start[i + 1] = visit(&b, i, NULL, NULL);
        for (size_t i = 0; i < n; i++)
            start[i + 1] += start[i];
        ne = start[n];
        e = malloc((ne ? ne : 1) * sizeof *e);
        bv = malloc((ne ? ne : 1) * sizeof *bv);
        if (!e || !bv)
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory for %zu neighbour pairs", ne);
        else {
#pragma omp parallel for schedule(dynamic, 256) if (s->n >= DEM_PARALLEL_MIN)
            for (size_t i = 0; i < n; i++)
                visit(&b, i, e + start[i], bv + start[i]);
        }
    }
    free(old_of);
    free(g.start);
    free(g.cell);
    if (rc) {
        free(start);
        free(e);
        free(bv);
        return rc;
    }
    free(nl->start);
    free(nl->e);
    free(nl->bv);
    nl->n = n;
    nl->start = start;
    nl->e = e;
    nl->bv = bv;
    nl->ne = ne;
    nl->builds++;
    memcpy(s->x_ref, s->x, n * sizeof *s->x);
    mark_walls_near(s);
    return dem_neighbours_transpose(nl, err);
}

/* The transposed index: entries in which a particle is the second one, in
 * entry order (a fixed summation order when forces are gathered). */
int dem_neighbours_transpose(dem_nlist *nl, mimas_error *err)
{
    size_t n = nl->n, ne = nl->ne;
    size_t *tstart = calloc(n + 1, sizeof *tstart), *tk = malloc((ne ? ne : 1) * sizeof *tk);
    size_t *tpos = malloc((ne ? ne : 1) * sizeof *tpos);
    size_t *cur = malloc((n ? n : 1) * sizeof *cur);
    dem_entry_force *eft = calloc(ne ? ne : 1, sizeof *eft);
    if (!tstart || !tk || !tpos || !cur || !eft) {
        free(tstart);
        free(tk);
        free(tpos);
        free(cur);
        free(eft);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the neighbour list");
    }
    const dem_entry *e = nl->e;
    for (size_t k = 0; k < ne; k++)
        tstart[e[k].j + 1]++;
    for (size_t i = 0; i < n; i++)
        tstart[i + 1] += tstart[i];
    memcpy(cur, tstart, n * sizeof *cur);
    for (size_t k = 0; k < ne; k++) {
        tpos[k] = cur[e[k].j]++;
        tk[tpos[k]] = k;
    }
    free(cur);
    free(nl->tstart);
    free(nl->tk);
    free(nl->tpos);
    free(nl->eft);
    nl->tstart = tstart;
    nl->tk = tk;
    nl->tpos = tpos;
    nl->eft = eft;
    return MIMAS_OK;
}
/* A build decided on here first lets the scenario add and remove particles. */
static int rebuild(dem_system *s, mimas_error *err)
{
    if (s->hooks.edit && s->hooks.edit(s->hooks.ctx, s, err))
        return -1;
    return dem_neighbours_build(s, err) ? -1 : 1;
}

int dem_neighbours_update(dem_system *s, mimas_error *err)
{
    if (s->nl.n != s->n || !s->nl.start)
        return rebuild(s, err);
    double limit = 0.25 * s->skin * s->skin, worst = 0;
#pragma omp parallel for reduction(max : worst) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t k = 0; k < s->n; k++) {
        double d2 = 0;
        for (int d = 0; d < 3; d++) {
            double q = s->x[k][d] - s->x_ref[k][d];
            d2 += q * q;
        }
        if (d2 > worst)
            worst = d2;
    }
    if (worst <= limit)
        return 0;
    return rebuild(s, err);
}
