#include <config.h>

#include "deposit_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gauss_legendre.h"
#include "ring_edges.h"
#include "overlap.h"

void mimas_weights_free(mimas_weights *ws)
{
    free(ws->cell);
    free(ws->w);
    free(ws->grad);
    free(ws->scratch);
    memset(ws, 0, sizeof *ws);
}

int mimas_weights_reserve(mimas_weights *ws, size_t k)
{
    if (ws->n + k <= ws->cap)
        return MIMAS_OK;
    size_t cap = ws->cap ? ws->cap : 256;
    while (cap < ws->n + k)
        cap *= 2;
    size_t *c = realloc(ws->cell, cap * sizeof *c);
    if (c)
        ws->cell = c;
    double *w = realloc(ws->w, cap * sizeof *w);
    if (w)
        ws->w = w;
    if (!c || !w)
        return MIMAS_EIO;
    double *g = realloc(ws->grad, 3 * cap * sizeof *g);
    if (!g)
        return MIMAS_EIO;
    /* the gradients' planes to their new places, the last first (it moves furthest) */
    if (ws->cap) {
        memmove(g + 2 * cap, g + 2 * ws->cap, ws->n * sizeof *g);
        memmove(g + cap, g + ws->cap, ws->n * sizeof *g);
    }
    ws->grad = g;
    ws->cap = cap;
    return MIMAS_OK;
}

double *mimas_weights_scratch(mimas_weights *ws, size_t n)
{
    if (n > ws->scratch_cap) {
        double *p = realloc(ws->scratch, n * sizeof *p);
        if (!p)
            return NULL;
        ws->scratch = p;
        ws->scratch_cap = n;
    }
    return ws->scratch;
}

/* Whether shift u projects onto the directions a kernel is resolved in like shift v does
 * (an image shifted by u has the same marginal there as one shifted by v). */
static int same_projection(const mimas_deposit *dp, const mimas_grid *g, const double u[3],
                           const double v[3])
{
    double a[3], b[3];
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        for (int k = 0; k < dp->dims; k++) {
            double x = u[dp->gdir[k]], y = v[dp->gdir[k]];
            if (fabs(x - y) > 1e-12 * (fabs(x) + fabs(y)))
                return 0;
        }
        return 1;
    }
    double o[3] = {0, 0, 0};
    mimas_grid_to_axis(g, u, a);
    mimas_grid_to_axis(g, v, b);
    mimas_grid_to_axis(g, o, o);
    for (int k = 0; k < (g->gridded[2] ? 3 : 2); k++) {
        double x = a[k] - o[k], y = b[k] - o[k];
        if (fabs(x - y) > 1e-12 * (fabs(x) + fabs(y)))
            return 0;
    }
    return 1;
}

/* The image of a box B shifted by s misses the grid G if along some direction the
 * shift is longer than G's extent less the box's clearance from G's faces there: a
 * box whose clearance exceeds m = max over shifts of min over directions of
 * (G_d - |s_d|) on every side meets no image (for a grid spanning a periodic
 * orthogonal box, m = 0: every object inside the grid).  Directions a kernel is
 * integrated over do not count (image_reaches ignores them). */
static double image_margin(const mimas_deposit *dp)
{
    const mimas_grid *g = dp->grid;
    if (g->kind != MIMAS_GRID_CARTESIAN)
        return INFINITY;
    double m = -INFINITY;
    for (int s = 1; s < dp->nshift; s++) {
        double best = INFINITY;
        for (int d = 0; d < 3; d++) {
            if (dp->kernel && !g->gridded[d])
                continue;
            best = fmin(best, (g->hi[d] - g->lo[d]) - fabs(dp->shift[s][d]));
        }
        m = fmax(m, best);
    }
    return m;
}

/* A kernel integrated along directions I (its marginal, with the images that differ in the
 * resolved directions) averages the field over one period of the box along I only when
 * the box's periods along I lie in I: in a tilted box each periodic edge along an integrated
 * direction must have no part along a resolved one (the edges e_0, e_1, e_2 of a box are
 * lower triangular: e_1 = (xy, L_y, 0), e_2 = (xz, yz, L_z)); on a cylindrical grid without
 * z, some periodic edge must lie along the axis if any has a part along it.  Otherwise the
 * average would count images of one particle as others (a profile along x in a box tilted by
 * xy held three times its mass): refused. */
static int marginal_defined(const mimas_deposit *dp, const mimas_box *box, const double e[3][3],
                            mimas_error *err)
{
    const mimas_grid *g = dp->grid;
    static const char *tilt[3][3] = {{"", "", ""}, {"xy", "", ""}, {"xz", "yz", ""}};
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        for (int d = 0; d < 3; d++)
            for (int r = 0; r < d; r++)
                if (box->periodic[d] && !g->gridded[d] && g->gridded[r] && e[d][r] != 0.0)
                    return mimas_error_set(err, MIMAS_EUSAGE,
                                           "a kernel averaged along %c (not in --grid) needs "
                                           "the box's periodic edge along %c without a part "
                                           "along %c, but it is tilted (%s = %g): grid %c too",
                                           "xyz"[d], "xyz"[d], "xyz"[r], tilt[d][r], e[d][r],
                                           "xyz"[d]);
        return MIMAS_OK;
    }
    int along = 0, parallel = 0;
    for (int d = 0; d < 3; d++) {
        if (!box->periodic[d])
            continue;
        double u = e[d][0] * g->ez[0] + e[d][1] * g->ez[1] + e[d][2] * g->ez[2], p2 = 0.0;
        for (int k = 0; k < 3; k++)
            p2 += (e[d][k] - u * g->ez[k]) * (e[d][k] - u * g->ez[k]);
        double n = sqrt(e[d][0] * e[d][0] + e[d][1] * e[d][1] + e[d][2] * e[d][2]);
        along |= fabs(u) > 1e-12 * n;
        parallel |= fabs(u) > 1e-12 * n && sqrt(p2) <= 1e-12 * n;
    }
    if (along && !parallel)
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "a kernel averaged along the axis (no z in --grid) needs a "
                               "periodic edge of the box along the axis, but the box repeats "
                               "along it only with a sideways shift (tilted): grid z too");
    return MIMAS_OK;
}

/* The Cartesian bounding box of a grid (a cylindrical one: of its outer cylinder) */
static void grid_bounds(const mimas_grid *g, double lo[3], double hi[3])
{
    for (int d = 0; d < 3; d++) {
        if (g->kind == MIMAS_GRID_CARTESIAN) {
            lo[d] = g->lo[d];
            hi[d] = g->hi[d];
            continue;
        }
        double p0 = g->origin[d] + g->lo[2] * g->ez[d], p1 = g->origin[d] + g->hi[2] * g->ez[d];
        double spread = g->hi[0] * sqrt(fmax(0.0, 1.0 - g->ez[d] * g->ez[d]));
        lo[d] = fmin(p0, p1) - spread;
        hi[d] = fmax(p0, p1) + spread;
    }
}

/* The periodic images an object may need along each edge d of the box, range[d] box
 * widths either way.  In fractional coordinates s_d along the edges (0 <= s_d < 1 inside
 * the box) a particle's centre lies inside the box and a contact's branch reaches out of it
 * by at most h_d (by the minimum image from a centre: 1/2, and the tilt's share in a
 * triclinic box), the grid reaches e_d = ext_d / W_d beyond it (from the corners of its
 * bounding box), W_d the width between the faces across edge d, and a kernel R / W_d
 * further: the images k with |k| <= 1 + floor(h_d + (R + ext_d) / W_d). */
static int image_range(const mimas_deposit *dp, const mimas_box *box, const double e[3][3],
                       int marginal, int range[3], mimas_error *err)
{
    double glo[3], ghi[3], R = dp->kernel ? mimas_weight_reach(dp->wt) : 0.0;
    grid_bounds(dp->grid, glo, ghi);
    double smin[3] = {0, 0, 0}, smax[3] = {1, 1, 1};
    for (int c = 0; c < 8; c++) {
        double x[3] = {c & 1 ? ghi[0] : glo[0], c & 2 ? ghi[1] : glo[1], c & 4 ? ghi[2] : glo[2]};
        double s[3];
        mimas_box_fractional(box, e, x, s);
        for (int d = 0; d < 3; d++) {
            smin[d] = fmin(smin[d], s[d]);
            smax[d] = fmax(smax[d], s[d]);
        }
    }
    double vol = e[0][0] * e[1][1] * e[2][2], h[3];
    /* mimas_box_min_image: |s_2| <= 1/2, then |d_y| <= L_y / 2 with s_2 yz, then x */
    h[2] = 0.5;
    h[1] = 0.5 + 0.5 * fabs(box->yz) / e[1][1];
    h[0] = 0.5 + (0.5 * fabs(box->xz) + h[1] * fabs(box->xy)) / e[0][0];
    for (int d = 0; d < 3; d++) {
        range[d] = box->periodic[d];
        if (!box->periodic[d])
            continue;
        /* a kernel integrated along the edge takes in all of its images there: the
         * shifts along it have the same projection as the zero one */
        static const double zero[3] = {0, 0, 0};
        if (marginal && same_projection(dp, dp->grid, e[d], zero))
            continue;
        /* the width across edge d: the volume over the area of the face of the other two */
        const double *u = e[(d + 1) % 3], *v = e[(d + 2) % 3];
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                       u[0] * v[1] - u[1] * v[0]};
        double W = fabs(vol) / sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double over = fmax(-smin[d], smax[d] - 1.0), ext = over > 0 ? W * over : 0.0;
        double k = 1.0 + floor(h[d] + (R + ext) / W);
        if (!(k <= MIMAS_IMAGE_RANGE))
            return mimas_error_set(err, MIMAS_EUSAGE,
                                   "the kernel's reach (%g) and the grid's overhang beyond the "
                                   "periodic box (%g) span %g of its widths along %c (%g) or "
                                   "more: use a narrower kernel or a grid within the box",
                                   R, ext, MIMAS_IMAGE_RANGE - h[d], "xyz"[d], W);
        range[d] = (int)k;
    }
    return MIMAS_OK;
}

/* A direction not in the grid spans the box's extent along it, which mimas_grid_fit_box
 * set: an unfitted grid has none (and its weights would be infinite). */
static int extent_defined(const mimas_grid *g, int d, mimas_error *err)
{
    double extent = g->hi[d] - g->lo[d];
    if (extent > 0 && isfinite(extent))
        return MIMAS_OK;
    return mimas_error_set(err, MIMAS_EUSAGE,
                           "the grid's %s (not gridded) spans %g to %g, no extent: fit the "
                           "grid to the box first (mimas_grid_fit_box)",
                           mimas_grid_coord_name(g, d), g->lo[d], g->hi[d]);
}

int mimas_deposit_init(mimas_deposit *dp, const mimas_grid *g, const mimas_weight *wt,
                       const mimas_box *box, int grid_none, mimas_error *err)
{
    if (!grid_none)
        for (int d = 0; d < 3; d++)
            if (!g->gridded[d] && (g->kind == MIMAS_GRID_CARTESIAN || d == 2) &&
                extent_defined(g, d, err))
                return MIMAS_EUSAGE;
    memset(dp, 0, sizeof *dp);
    dp->grid = g;
    dp->wt = wt;
    dp->none = grid_none;
    dp->box_volume = mimas_box_volume(box);
    for (int d = 0; d < 3; d++) {
        dp->h[d] = (g->hi[d] - g->lo[d]) / g->n[d];
        dp->inv_h[d] = 1.0 / dp->h[d];
    }
    dp->cart_volume = dp->h[0] * dp->h[1] * dp->h[2];
    dp->kernel = wt->kind >= MIMAS_WEIGHT_GAUSS;
    dp->inv_extent = 1.0;
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        for (int d = 0; d < 3; d++)
            if (g->gridded[d])
                dp->gdir[dp->dims++] = d;
            else
                dp->inv_extent /= g->hi[d] - g->lo[d];
    } else {
        dp->dims = g->gridded[2] ? 3 : 2;
        if (!g->gridded[2])
            dp->inv_extent = 1.0 / (g->hi[2] - g->lo[2]);
    }
    if (dp->kernel && wt->kind != MIMAS_WEIGHT_LUCY && g->kind == MIMAS_GRID_CARTESIAN &&
        dp->dims == 3) {
        dp->gauss_xyz = 1;
        for (int d = 0; d < 3; d++)
            dp->gq[d] = exp(-2.0 * dp->h[d] * dp->h[d] * wt->inv2w2);
        mimas_gauss_tables();
    }
    dp->gauss_rz = dp->kernel && wt->kind != MIMAS_WEIGHT_LUCY &&
                   g->kind != MIMAS_GRID_CARTESIAN && !g->gridded[1] && dp->dims == 3;
    dp->ring_terms = dp->gauss_rz ? mimas_ring_tier2_terms(wt) : 0;
    /* images along the periodic edge vectors: shifts k_a a + k_b b + k_c c */
    double e[3][3];
    mimas_box_edges(box, e);
    /* a kernel integrated over a direction takes in all of its images there:
     * only images that differ in the resolved directions are added */
    int marginal = dp->kernel && (g->kind == MIMAS_GRID_CARTESIAN ? dp->dims < 3
                                                                  : !g->gridded[2]);
    int range[3] = {0, 0, 0};
    if (!grid_none && ((marginal && marginal_defined(dp, box, e, err)) ||
                       image_range(dp, box, e, marginal, range, err)))
        return MIMAS_EUSAGE;
    dp->nshift = 0;
    for (int pass = 0; pass < 2; pass++) /* the zero shift first */
        for (int i = -range[0]; i <= range[0]; i++)
            for (int j = -range[1]; j <= range[1]; j++)
                for (int k = -range[2]; k <= range[2]; k++) {
                    int zero = !i && !j && !k;
                    if (zero != (pass == 0))
                        continue;
                    for (int d = 0; d < 3; d++)
                        dp->shift[dp->nshift][d] = i * e[0][d] + j * e[1][d] + k * e[2][d];
                    int dup = 0;
                    for (int t = 0; marginal && t < dp->nshift && !dup; t++)
                        dup = same_projection(dp, g, dp->shift[dp->nshift], dp->shift[t]);
                    if (!dup)
                        dp->nshift++;
                }
    dp->image_margin = image_margin(dp);
    return MIMAS_OK;
}

/* Bounds of cell k along d (no divisions). */
static void cell_bounds(const mimas_deposit *dp, int d, int k, double *lo, double *hi)
{
    const mimas_grid *g = dp->grid;
    *lo = g->lo[d] + dp->h[d] * k;
    *hi = k + 1 == g->n[d] ? g->hi[d] : *lo + dp->h[d];
}

/* Bounds and centre of the cell with indices idx. */
static void cell_geometry(const mimas_deposit *dp, const int idx[3], double lo[3], double hi[3],
                          double c[3])
{
    for (int d = 0; d < 3; d++) {
        cell_bounds(dp, d, idx[d], &lo[d], &hi[d]);
        c[d] = 0.5 * (lo[d] + hi[d]);
    }
}

static double cell_volume(const mimas_deposit *dp, const double lo[3], const double hi[3])
{
    if (dp->grid->kind == MIMAS_GRID_CARTESIAN)
        return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    return 0.5 * (hi[0] * hi[0] - lo[0] * lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}

/* The cell holding a point (grid coordinates q), or 0 if it is off the grid. */
static int cell_of(const mimas_grid *g, const double *h, const double q[3], size_t *cell)
{
    int idx[3];
    for (int d = 0; d < 3; d++) {
        if (!(q[d] >= g->lo[d] && q[d] <= g->hi[d]))
            return 0;
        int k = (int)floor((q[d] - g->lo[d]) / h[d]);
        idx[d] = k >= g->n[d] ? g->n[d] - 1 : k;
    }
    *cell = mimas_grid_index(g, idx);
    return 1;
}

/* Grid coordinates (x y z, or r phi z with phi mapped into the grid's range
 * where possible; without phi cells phi is the grid's lower bound) of an axis-frame
 * point. */
static void grid_coords(const mimas_grid *g, const double a[3], double q[3])
{
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        memcpy(q, a, 3 * sizeof *q);
        return;
    }
    q[0] = hypot(a[0], a[1]);
    if (!g->gridded[1]) { /* one phi cell: the angle does not matter */
        q[1] = g->lo[1];
        q[2] = a[2];
        return;
    }
    double phi = atan2(a[1], a[0]);
    while (phi < g->lo[1])
        phi += 2 * M_PI;
    while (phi > g->hi[1] && phi - 2 * M_PI >= g->lo[1])
        phi -= 2 * M_PI;
    q[1] = phi;
    q[2] = a[2];
}

/* The index box of the cells that may meet the ball of radius reach about the
 * axis-frame point a (all phi cells when the ball holds the axis or the phi
 * range wraps); 0 if there are none. */
int dep_candidate_box(const mimas_deposit *dp, const double a[3], double reach, int lo[3],
                      int hi[3])
{
    const mimas_grid *g = dp->grid;
    double q[3];
    grid_coords(g, a, q);
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        for (int d = 0; d < 3; d++)
            if (!dep_index_range(dp, d, q[d] - reach, q[d] + reach, &lo[d], &hi[d]))
                return 0;
        return 1;
    }
    if (!dep_index_range(dp, 0, q[0] - reach, q[0] + reach, &lo[0], &hi[0]) ||
        !dep_index_range(dp, 2, q[2] - reach, q[2] + reach, &lo[2], &hi[2]))
        return 0;
    double half = q[0] > reach ? asin(reach / q[0]) : M_PI;
    lo[1] = 0;
    hi[1] = g->n[1] - 1;
    if (half < M_PI && q[1] - half >= g->lo[1] && q[1] + half <= g->hi[1])
        dep_index_range(dp, 1, q[1] - half, q[1] + half, &lo[1], &hi[1]);
    return 1;
}

/* Whether an image of an object with Cartesian bounding box [lo, hi], shifted
 * by shift s, can reach a Cartesian grid (a quick test before the cell
 * search; cylindrical grids are searched for every image). */
static int image_reaches(const mimas_deposit *dp, int s, const double lo[3], const double hi[3])
{
    const mimas_grid *g = dp->grid;
    if (g->kind != MIMAS_GRID_CARTESIAN)
        return 1;
    for (int d = 0; d < 3; d++) {
        if (dp->kernel && !g->gridded[d])
            continue;
        if (hi[d] + dp->shift[s][d] < g->lo[d] || lo[d] + dp->shift[s][d] > g->hi[d])
            return 0;
    }
    return 1;
}

/* How many of the image shifts to try for an object with bounding box [lo, hi]: only
 * the first (zero) one when the box is clear of the grid's faces by more than the
 * image margin, else all of them. */
static int images_to_try(const mimas_deposit *dp, const double lo[3], const double hi[3])
{
    const mimas_grid *g = dp->grid;
    double m = dp->image_margin;
    if (dp->nshift == 1 || !(m < INFINITY))
        return dp->nshift;
    for (int d = 0; d < 3; d++) {
        if (dp->kernel && !g->gridded[d])
            continue;
        if (!(lo[d] > g->lo[d] + m && hi[d] < g->hi[d] - m))
            return dp->nshift;
    }
    return 1;
}

/* Whether the ball of radius reach about an axis-frame point can meet a cylindrical
 * grid's r and z ranges (always on Cartesian grids): dep_candidate_box's test of them,
 * without its square root (r^2 against the bounds squared, widened by 1e-9, so that it
 * never refuses what that test would take), to pass over the periodic images that miss
 * the grid before their cells are sought. */
static int ring_reaches(const mimas_deposit *dp, const double a[3], double reach)
{
    const mimas_grid *g = dp->grid;
    if (g->kind == MIMAS_GRID_CARTESIAN)
        return 1;
    if (!(dp->kernel && !g->gridded[2]) && (a[2] + reach < g->lo[2] || a[2] - reach > g->hi[2]))
        return 0;
    double r2 = a[0] * a[0] + a[1] * a[1], out = g->hi[0] + reach, in = g->lo[0] - reach;
    if (r2 > out * out * (1.0 + 1e-9))
        return 0;
    return !(in > 0 && r2 < in * in * (1.0 - 1e-9));
}

/* What a cell-by-cell deposit needs: the object (Cartesian and axis-frame
 * positions, radius) and, per cell, its weight and (kernels) gradient. */
typedef struct cell_object {
    const double *x, *a;   /* a point or a segment's start: Cartesian, axis frame */
    const double *b, *ab;  /* a segment's end (NULL for points and spheres) */
    double R, vol;         /* bins: the sphere */
} cell_object;
typedef double (*cell_weight_fn)(const mimas_deposit *dp, const int idx[3], const double lo[3],
                                 const double hi[3], const double c[3], const cell_object *o,
                                 double *grad);

/* Calls weight for every cell of the index box [lo, hi] and keeps the nonzero
 * ones, times scale (with their gradients when with_grad). */
static int each_cell(const mimas_deposit *dp, const int lo[3], const int hi[3],
                     cell_weight_fn weight, const cell_object *o, int with_grad, double scale,
                     mimas_weights *ws)
{
    const mimas_grid *g = dp->grid;
    if (mimas_weights_reserve(ws, (size_t)(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1)))
        return MIMAS_EIO;
    int idx[3];
    for (idx[2] = lo[2]; idx[2] <= hi[2]; idx[2]++)
        for (idx[1] = lo[1]; idx[1] <= hi[1]; idx[1]++)
            for (idx[0] = lo[0]; idx[0] <= hi[0]; idx[0]++) {
                double clo[3], chi[3], c[3], gr[3] = {0, 0, 0};
                cell_geometry(dp, idx, clo, chi, c);
                double v = weight(dp, idx, clo, chi, c, o, with_grad ? gr : NULL);
                if (v == 0.0 && gr[0] == 0.0 && gr[1] == 0.0 && gr[2] == 0.0)
                    continue;
                size_t cell = mimas_grid_index(g, idx);
                if (with_grad)
                    dep_put_grad(ws, cell, v * scale, gr[0] * scale, gr[1] * scale, gr[2] * scale);
                else
                    dep_put(ws, cell, v * scale);
            }
    ws->has_grad = with_grad;
    return MIMAS_OK;
}

/* ---- kernels: particles ---------------------------------------------------------- */

/* A kernel on any grid, cell by cell: the kernel at the cell centre, its
 * marginal over the directions not gridded, or its azimuthal average. */
static double kernel_cell(const mimas_deposit *dp, const int idx[3], const double lo[3],
                          const double hi[3], const double c[3], const cell_object *o,
                          double *gr)
{
    (void)idx, (void)lo, (void)hi;
    const mimas_grid *g = dp->grid;
    const mimas_weight *wt = dp->wt;
    const double *x = o->x, *a = o->a;
    double v;
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        double d[3], gm[3];
        for (int k = 0; k < dp->dims; k++)
            d[k] = c[dp->gdir[k]] - x[dp->gdir[k]];
        v = mimas_kernel_marginal(wt, dp->dims, d, gr ? gm : NULL);
        for (int k = 0; gr && k < dp->dims; k++)
            gr[dp->gdir[k]] = gm[k];
    } else if (!g->gridded[1]) {
        double gg[2];
        v = mimas_kernel_ring(wt, dp->dims, c[0], hypot(a[0], a[1]), c[2] - a[2],
                              gr ? gg : NULL);
        if (gr) {
            gr[0] = gg[0];
            gr[2] = dp->dims == 3 ? gg[1] : 0.0;
        }
    } else {
        /* phi cells: at the cell centre, the gradient in the centre's
         * (r, phi, z) components */
        double cs = cos(c[1]), sn = sin(c[1]), gc[3] = {0, 0, 0};
        double d[3] = {c[0] * cs - a[0], c[0] * sn - a[1], c[2] - a[2]};
        v = mimas_kernel_marginal(wt, dp->dims, d, gr ? gc : NULL);
        if (gr) {
            gr[0] = cs * gc[0] + sn * gc[1];
            gr[1] = -sn * gc[0] + cs * gc[1];
            gr[2] = dp->dims == 3 ? gc[2] : 0.0;
        }
    }
    return v;
}

/* A kernel on any grid, cell by cell: the kernel at the cell centre, its
 * marginal over the directions not gridded, or its azimuthal average. */
static int kernel_sphere(const mimas_deposit *dp, const double x[3], const double a[3],
                         int with_grad, mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    if (dp->gauss_xyz)
        return mimas_gauss_sphere_xyz(dp, x, with_grad, ws);
    if (dp->gauss_rz)
        return mimas_gauss_sphere_rz(dp, a, with_grad, dp->inv_extent, ws);
    int lo[3], hi[3];
    if (!dep_candidate_box(dp, a, mimas_weight_reach(wt), lo, hi))
        return MIMAS_OK;
    cell_object o = {x, a, NULL, NULL, 0, 0};
    return each_cell(dp, lo, hi, kernel_cell, &o, with_grad, dp->inv_extent, ws);
}

/* ---- bins: particles ---------------------------------------------------------------- */

static double bins_cell(const mimas_deposit *dp, const int idx[3], const double lo[3],
                        const double hi[3], const double c[3], const cell_object *o,
                        double *gr)
{
    (void)idx, (void)c, (void)gr;
    double ov = dp->grid->kind == MIMAS_GRID_CARTESIAN
                    ? overlap_sphere_box(o->x, o->R, lo, hi)
                    : overlap_sphere_cylcell(o->a, o->R, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    return ov / (o->vol * cell_volume(dp, lo, hi));
}

/* Bins on a Cartesian grid: the sphere's volumes in the block of cells it may meet, all at
 * once (overlap_sphere_cells), kept as each_cell() with bins_cell() would keep them. */
enum { BLOCK_AXIS = 8 };
static int bins_sphere_block(const mimas_deposit *dp, const double x[3], const int lo[3],
                             const int hi[3], double vol_sphere, double R, mimas_weights *ws)
{
    int n[3];
    double blo[3][BLOCK_AXIS], bhi[3][BLOCK_AXIS], width[3][BLOCK_AXIS];
    for (int d = 0; d < 3; d++) {
        n[d] = hi[d] - lo[d] + 1;
        for (int k = 0; k < n[d]; k++) {
            cell_bounds(dp, d, lo[d] + k, &blo[d][k], &bhi[d][k]);
            width[d][k] = bhi[d][k] - blo[d][k];
        }
    }
    double vol[BLOCK_AXIS * BLOCK_AXIS * BLOCK_AXIS];
    const double *pl[3] = {blo[0], blo[1], blo[2]}, *ph[3] = {bhi[0], bhi[1], bhi[2]};
    overlap_sphere_cells(x, R, n, pl, ph, vol);
    if (mimas_weights_reserve(ws, (size_t)n[0] * n[1] * n[2]))
        return MIMAS_EIO;
    const mimas_grid *g = dp->grid;
    size_t q = 0, sy = (size_t)g->n[0], sz = sy * (size_t)g->n[1];
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++, q++) {
                /* bins_cell()'s weight: the cell's volume as cell_volume() forms it */
                double v = vol[q] / (vol_sphere * (width[0][i] * width[1][j] * width[2][k]));
                if (v != 0.0)
                    dep_put(ws, (size_t)(lo[0] + i) + sy * (size_t)(lo[1] + j) +
                                    sz * (size_t)(lo[2] + k), v);
            }
    return MIMAS_OK;
}

/* Bins on a cylindrical grid of full rings (no phi cells): the sphere's volumes in the
 * block of cells it may meet, ring by ring in each slab (overlap_sphere_rings), the rings'
 * bounds those of the cells (each ring's outer bound the next one's inner bound, so that
 * the rings meet) and the weights as bins_cell() would form them. */
static int bins_sphere_rings(const mimas_deposit *dp, const double a[3], const int lo[3],
                             const int hi[3], double vol_sphere, double R, mimas_weights *ws)
{
    int nr = hi[0] - lo[0] + 1;
    double rp[BLOCK_AXIS + 1], vol[BLOCK_AXIS], top = 0.0;
    for (int k = 0; k < nr; k++)
        cell_bounds(dp, 0, lo[0] + k, &rp[k], &top);
    rp[nr] = top;
    if (mimas_weights_reserve(ws, (size_t)nr * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1)))
        return MIMAS_EIO;
    int idx[3];
    for (idx[2] = lo[2]; idx[2] <= hi[2]; idx[2]++)
        for (idx[1] = lo[1]; idx[1] <= hi[1]; idx[1]++) {
            double clo[3], chi[3], c[3];
            idx[0] = lo[0];
            cell_geometry(dp, idx, clo, chi, c);
            overlap_sphere_rings(a, R, nr, rp, clo[2], chi[2], vol);
            for (int k = 0; k < nr; k++) {
                idx[0] = lo[0] + k;
                cell_geometry(dp, idx, clo, chi, c);
                double v = vol[k] / (vol_sphere * cell_volume(dp, clo, chi));
                if (v != 0.0)
                    dep_put(ws, mimas_grid_index(dp->grid, idx), v);
            }
        }
    return MIMAS_OK;
}

static int bins_sphere(const mimas_deposit *dp, const double x[3], const double a[3], double R,
                       mimas_weights *ws)
{
    int lo[3], hi[3];
    if (!dep_candidate_box(dp, a, R, lo, hi))
        return MIMAS_OK;
    cell_object o = {x, a, NULL, NULL, R, 4.0 / 3.0 * M_PI * R * R * R};
    if (dp->grid->kind == MIMAS_GRID_CARTESIAN && hi[0] - lo[0] < BLOCK_AXIS &&
        hi[1] - lo[1] < BLOCK_AXIS && hi[2] - lo[2] < BLOCK_AXIS)
        return bins_sphere_block(dp, x, lo, hi, o.vol, R, ws);
    if (dp->grid->kind == MIMAS_GRID_CYLINDRICAL && !dp->grid->gridded[1] &&
        hi[0] - lo[0] < BLOCK_AXIS)
        return bins_sphere_rings(dp, a, lo, hi, o.vol, R, ws);
    return each_cell(dp, lo, hi, bins_cell, &o, 0, 1.0, ws);
}

int mimas_deposit_sphere(const mimas_deposit *dp, const double x[3], double R, int with_grad,
                         mimas_weights *ws)
{
    const mimas_grid *g = dp->grid;
    ws->has_grad = 0;
    if (dp->none) {
        if (mimas_weights_reserve(ws, 1))
            return MIMAS_EIO;
        dep_put(ws, 0, 1.0 / dp->box_volume);
        return MIMAS_OK;
    }
    int point = dp->wt->kind == MIMAS_WEIGHT_BINS_CENTER ||
                (dp->wt->kind == MIMAS_WEIGHT_BINS && !(R > 0));
    double reach = dp->kernel ? mimas_weight_reach(dp->wt) : R;
    double blo[3] = {x[0] - reach, x[1] - reach, x[2] - reach};
    double bhi[3] = {x[0] + reach, x[1] + reach, x[2] + reach};
    int rc = MIMAS_OK, nimg = images_to_try(dp, blo, bhi);
    for (int s = 0; s < nimg && !rc; s++) {
        if (!image_reaches(dp, s, blo, bhi))
            continue;
        double xs[3] = {x[0] + dp->shift[s][0], x[1] + dp->shift[s][1], x[2] + dp->shift[s][2]};
        double a[3];
        mimas_grid_to_axis(g, xs, a);
        if (point) {
            double q[3];
            size_t cell;
            grid_coords(g, a, q);
            if (cell_of(g, dp->h, q, &cell)) {
                if (mimas_weights_reserve(ws, 1))
                    return MIMAS_EIO;
                dep_put(ws, cell, 1.0 / (g->kind == MIMAS_GRID_CARTESIAN
                                         ? dp->cart_volume
                                         : mimas_grid_cell_volume(g, cell)));
            }
            continue;
        }
        if (!ring_reaches(dp, a, reach))
            continue;
        rc = dp->kernel ? kernel_sphere(dp, xs, a, with_grad, ws) : bins_sphere(dp, xs, a, R, ws);
    }
    return rc;
}

/* ---- segments ------------------------------------------------------------------------ */

double dep_ring_longest(const mimas_weight *wt, int n)
{
    double scale = wt->kind == MIMAS_WEIGHT_LUCY ? wt->w / 3.0 : wt->w;
    return n == 4 ? 0.5 * scale : (n == 8 ? 2.0 * scale : INFINITY);
}

int dep_ring_rule(const mimas_weight *wt, double len, const double **x, const double **w)
{
    int n = len <= dep_ring_longest(wt, 4) ? 4 : (len <= dep_ring_longest(wt, 8) ? 8 : 16);
    *x = n == 4 ? gl4_x : (n == 8 ? gl8_x : gl16_x);
    *w = n == 4 ? gl4_w : (n == 8 ? gl8_w : gl16_w);
    return n;
}

/* The azimuthal average along the segment from a to b (axis frame) at the ring
 * (r, z) by Gauss-Legendre (dep_ring_rule), split at the average's singular points where
 * one is near (ring_edges.h; a kernel averaged over z has its edges at |rho -+ r| = R). */
static double ring_segment(const mimas_deposit *dp, double r, double z, const double a[3],
                           const double b[3])
{
    const mimas_weight *wt = dp->wt;
    double a2[3] = {a[0], a[1], dp->dims == 3 ? a[2] : 0.0};
    double b2[3] = {b[0], b[1], dp->dims == 3 ? b[2] : 0.0};
    mimas_ring_branch br;
    mimas_ring_nodes nd;
    mimas_ring_branch_init(&br, wt, a2, b2);
    int ne = mimas_ring_edge_nodes(&br, wt, r, dp->dims == 3 ? z : 0.0, &nd);
    double sum = 0.0;
    for (int k = 0; k < ne; k++)
        sum += nd.w[k] * mimas_kernel_ring(wt, dp->dims, r, nd.rho[k], nd.dz[k], NULL);
    if (ne >= 0)
        return sum;
    /* no singular point near: the rule along the whole branch, the one whose reach the
     * split's test assumed (for a kernel averaged over z, that of the branch's projection,
     * along which the marginal varies) */
    const double *xs, *wsg, *d = br.b;
    int n = dep_ring_rule(wt, br.len, &xs, &wsg);
    for (int k = 0; k < n; k++) {
        double t, wgt;
        gl_node(xs, wsg, n, k, 0.0, 1.0, &t, &wgt);
        double p0 = a[0] + t * d[0], p1 = a[1] + t * d[1], p2 = a[2] + t * d[2];
        sum += wgt * mimas_kernel_ring(wt, dp->dims, r, hypot(p0, p1), z - p2, NULL);
    }
    return sum;
}

/* A kernel's line integral at a cell: the object's Cartesian x -> b and axis-frame
 * a -> ab. */
static double kernel_segment_cell(const mimas_deposit *dp, const int idx[3], const double lo[3],
                                  const double hi[3], const double c[3], const cell_object *o,
                                  double *gr)
{
    (void)idx, (void)lo, (void)hi, (void)gr;
    const mimas_grid *g = dp->grid;
    const double *a = o->x, *b = o->b, *aa = o->a, *ab = o->ab;
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        double d[3], br[3];
        for (int k = 0; k < dp->dims; k++) {
            int m = dp->gdir[k];
            d[k] = c[m] - a[m];
            br[k] = b[m] - a[m];
        }
        return mimas_kernel_marginal_line(dp->wt, dp->dims, d, br);
    }
    if (!g->gridded[1])
        return ring_segment(dp, c[0], c[2], aa, ab);
    double p[3] = {c[0] * cos(c[1]), c[0] * sin(c[1]), c[2]};
    double d[3] = {p[0] - aa[0], p[1] - aa[1], p[2] - aa[2]};
    double br[3] = {ab[0] - aa[0], ab[1] - aa[1], ab[2] - aa[2]};
    return mimas_kernel_marginal_line(dp->wt, dp->dims, d, br);
}

static double bins_segment_cell(const mimas_deposit *dp, const int idx[3], const double lo[3],
                                const double hi[3], const double c[3], const cell_object *o,
                                double *gr)
{
    (void)idx, (void)c, (void)gr; /* cylindrical grids (Cartesian ones: dep_walk_segment) */
    double f = segment_fraction_cylcell(o->a, o->ab, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    return f / cell_volume(dp, lo, hi);
}

/* The cells of a segment by the cell search: within reach of the midpoint am. */
static int segment_cells(const mimas_deposit *dp, const double a[3], const double b[3],
                         const double aa[3], const double ab[3], const double am[3],
                         double reach, mimas_weights *ws)
{
    if (dp->gauss_xyz) {
        int rc = mimas_gauss_segment_xyz(dp, a, b, ws);
        if (rc >= 0)
            return rc;
    }
    if (dp->gauss_rz)
        return mimas_gauss_segment_rz(dp, aa, ab, am, reach, dp->inv_extent, ws);
    int lo[3], hi[3];
    if (!dep_candidate_box(dp, am, reach, lo, hi))
        return MIMAS_OK;
    cell_object o = {a, aa, b, ab, 0, 0};
    return dp->kernel ? each_cell(dp, lo, hi, kernel_segment_cell, &o, 0, dp->inv_extent, ws)
                      : each_cell(dp, lo, hi, bins_segment_cell, &o, 0, 1.0, ws);
}

int mimas_deposit_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                          mimas_weights *ws)
{
    const mimas_grid *g = dp->grid;
    ws->has_grad = 0;
    if (dp->none) {
        if (mimas_weights_reserve(ws, 1))
            return MIMAS_EIO;
        dep_put(ws, 0, 1.0 / dp->box_volume);
        return MIMAS_OK;
    }
    if (dp->wt->kind == MIMAS_WEIGHT_BINS_CENTER) {
        /* the cell of the segment's midpoint */
        double m[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
        return mimas_deposit_sphere(dp, m, 0.0, 0, ws);
    }
    if (!dp->kernel && g->kind == MIMAS_GRID_CARTESIAN) {
        /* bins: each image whose bounding box meets the grid walked through the cells */
        double blo[3], bhi[3];
        for (int d = 0; d < 3; d++) {
            blo[d] = a[d] < b[d] ? a[d] : b[d];
            bhi[d] = a[d] < b[d] ? b[d] : a[d];
        }
        int nimg = images_to_try(dp, blo, bhi);
        for (int s = 0; s < nimg; s++) {
            if (!image_reaches(dp, s, blo, bhi))
                continue;
            const double *sh = dp->shift[s];
            double as[3] = {a[0] + sh[0], a[1] + sh[1], a[2] + sh[2]};
            double bs[3] = {b[0] + sh[0], b[1] + sh[1], b[2] + sh[2]};
            if (dep_walk_segment(dp, as, bs, ws))
                return MIMAS_EIO;
        }
        return MIMAS_OK;
    }
    double half = 0.5 * sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                             (b[2] - a[2]) * (b[2] - a[2]));
    double reach = half + mimas_weight_reach(dp->wt);
    double blo[3], bhi[3];
    for (int d = 0; d < 3; d++) {
        double m = 0.5 * (a[d] + b[d]);
        blo[d] = m - reach;
        bhi[d] = m + reach;
    }
    int rc = MIMAS_OK, nimg = images_to_try(dp, blo, bhi);
    for (int s = 0; s < nimg && !rc; s++) {
        if (!image_reaches(dp, s, blo, bhi))
            continue;
        double as[3], bs[3], aa[3], ab[3], mid[3], am[3];
        for (int d = 0; d < 3; d++) {
            as[d] = a[d] + dp->shift[s][d];
            bs[d] = b[d] + dp->shift[s][d];
            mid[d] = 0.5 * (as[d] + bs[d]);
        }
        mimas_grid_to_axis(g, mid, am);
        if (!ring_reaches(dp, am, reach))
            continue;
        mimas_grid_to_axis(g, as, aa);
        mimas_grid_to_axis(g, bs, ab);
        rc = segment_cells(dp, as, bs, aa, ab, am, reach, ws);
    }
    return rc;
}
