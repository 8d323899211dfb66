#include <config.h>

#include "deposit.h"

#include <math.h>
#include <string.h>

#include "overlap.h"

void mimas_deposit_init(mimas_deposit *dp, const mimas_grid *g, const mimas_weight *wt,
                        const mimas_box *box, int grid_none)
{
    memset(dp, 0, sizeof *dp);
    dp->grid = g;
    dp->wt = wt;
    dp->none = grid_none;
    dp->box_volume = mimas_box_volume(box);
    for (int d = 0; d < 3; d++)
        dp->h[d] = (g->hi[d] - g->lo[d]) / g->n[d];
    dp->cart_volume = dp->h[0] * dp->h[1] * dp->h[2];
    /* images along the periodic edge vectors: shifts k_a a + k_b b + k_c c */
    double e[3][3];
    mimas_box_edges(box, e);
    int range[3];
    for (int d = 0; d < 3; d++)
        range[d] = box->periodic[d] ? 1 : 0;
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
                    dp->nshift++;
                }
}

/* Cell index range [i0, i1] of direction d overlapping [lo, hi] (grid
 * coordinates); 0 if none. */
static int index_range(const mimas_grid *g, const double *h, int d, double lo, double hi,
                       int *i0, int *i1)
{
    if (hi < g->lo[d] || lo > g->hi[d])
        return 0;
    double a = floor((lo - g->lo[d]) / h[d]), b = floor((hi - g->lo[d]) / h[d]);
    *i0 = a < 0 ? 0 : (int)a;
    *i1 = b >= g->n[d] ? g->n[d] - 1 : (int)b;
    return *i0 <= *i1;
}

/* Gauss-Legendre nodes and weights on [-1, 1] (16 points, symmetric). */
static const double gl_x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                               0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                               0.9445750230732326, 0.9894009349916499};
static const double gl_w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                               0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                               0.0622535239386479, 0.0271524594117541};

/* Gauss-Legendre 4 and 8 points on [-1, 1] (half of each symmetric set). */
static const double gl4_x[2] = {0.3399810435848563, 0.8611363115940526};
static const double gl4_w[2] = {0.6521451548625461, 0.3478548451374538};
static const double gl8_x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                0.9602898564975363};
static const double gl8_w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                0.1012285362903763};

/* The kernel averaged over the azimuth (docs/theory.md §6, cylindrical grids without
 * phi cells): at the ring of radius r, height z about the axis, for a
 * particle at axis-frame position x, (1/pi) int_0^tm phi(D(t)) dt with
 * D^2 = r^2 + rho^2 - 2 r rho cos t + (z - x_z)^2 and tm where D reaches the
 * kernel's support (the kernels vanish there, so the limit adds nothing to
 * the gradient); 2 x 16-point Gauss-Legendre over [0, tm].  grad gets
 * (d/dr, 0, d/dz). */
static double ring_kernel(const mimas_weight *wt, double r, double z, const double x[3],
                          double grad[3])
{
    double rho = hypot(x[0], x[1]), dz = z - x[2], R = mimas_weight_reach(wt);
    double base = r * r + rho * rho + dz * dz;
    grad[0] = grad[1] = grad[2] = 0.0;
    double tm;
    if (r * rho <= 0.0)
        tm = base < R * R ? M_PI : 0.0;
    else {
        double k = (base - R * R) / (2.0 * r * rho);
        tm = k <= -1.0 ? M_PI : (k >= 1.0 ? 0.0 : acos(k));
    }
    if (!(tm > 0.0))
        return 0.0;
    double sum = 0.0;
    for (int half = 0; half < 2; half++) {
        double lo = half ? 0.5 * tm : 0.0, h = 0.25 * tm; /* [lo, lo + tm/2] */
        for (int k = 0; k < 8; k++)
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double t = lo + h * (1.0 + sgn * gl_x[k]);
                /* field point (r, 0, z), particle (rho cos t, rho sin t, x_z) */
                double d[3] = {r - rho * cos(t), -rho * sin(t), dz}, g[3];
                double f = mimas_kernel_phi_grad(wt, d, g);
                sum += h * gl_w[k] * f;
                grad[0] += h * gl_w[k] * g[0];
                grad[2] += h * gl_w[k] * g[2];
            }
    }
    grad[0] /= M_PI;
    grad[2] /= M_PI;
    return sum / M_PI;
}

/* Bounds and centre of the cell with indices idx (no divisions). */
static void cell_geometry(const mimas_deposit *dp, const int idx[3], double lo[3], double hi[3],
                          double c[3])
{
    const mimas_grid *g = dp->grid;
    for (int d = 0; d < 3; d++) {
        lo[d] = g->lo[d] + dp->h[d] * idx[d];
        hi[d] = idx[d] + 1 == g->n[d] ? g->hi[d] : lo[d] + dp->h[d];
        c[d] = 0.5 * (lo[d] + hi[d]);
    }
}

static double cell_volume(const mimas_deposit *dp, const double lo[3], const double hi[3])
{
    if (dp->grid->kind == MIMAS_GRID_CARTESIAN)
        return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    return 0.5 * (hi[0] * hi[0] - lo[0] * lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}

/* The weight of a sphere (or point, R = 0) in one cell; for the Gaussian on
 * a Cartesian grid also its gradient (grad set, *has_grad = 1). */
static double cell_weight_sphere(const mimas_deposit *dp, const int idx[3], const double x[3],
                                 const double a[3], double R, double grad[3], int *has_grad)
{
    const mimas_grid *g = dp->grid;
    double lo[3], hi[3], c[3];
    cell_geometry(dp, idx, lo, hi, c);
    *has_grad = 0;
    if (dp->wt->kind >= MIMAS_WEIGHT_GAUSS) {
        if (g->kind == MIMAS_GRID_CARTESIAN) {
            double d[3] = {c[0] - x[0], c[1] - x[1], c[2] - x[2]};
            *has_grad = 1;
            return mimas_kernel_phi_grad(dp->wt, d, grad);
        }
        *has_grad = 1;
        if (!g->gridded[1])
            return ring_kernel(dp->wt, c[0], c[2], a, grad);
        /* phi cells: the kernel at the cell centre, its gradient in the
         * centre's (r, phi, z) components */
        double cs = cos(c[1]), sn = sin(c[1]), gc[3];
        double d[3] = {c[0] * cs - a[0], c[0] * sn - a[1], c[2] - a[2]};
        double f = mimas_kernel_phi_grad(dp->wt, d, gc);
        grad[0] = cs * gc[0] + sn * gc[1];
        grad[1] = -sn * gc[0] + cs * gc[1];
        grad[2] = gc[2];
        return f;
    }
    double vol_p = 4.0 / 3.0 * M_PI * R * R * R;
    double ov = g->kind == MIMAS_GRID_CARTESIAN
                    ? overlap_sphere_box(x, R, lo, hi)
                    : overlap_sphere_cylcell(a, R, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    return ov / (vol_p * cell_volume(dp, lo, hi));
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
 * where possible) of an axis-frame point. */
static void grid_coords(const mimas_grid *g, const double a[3], double q[3])
{
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        memcpy(q, a, 3 * sizeof *q);
        return;
    }
    q[0] = hypot(a[0], a[1]);
    double phi = atan2(a[1], a[0]);
    while (phi < g->lo[1])
        phi += 2 * M_PI;
    while (phi > g->hi[1] && phi - 2 * M_PI >= g->lo[1])
        phi -= 2 * M_PI;
    q[1] = phi;
    q[2] = a[2];
}

/* Calls visit for every cell that may meet the ball of radius reach about
 * the axis-frame point a (all phi cells when the ball holds the axis or the
 * phi range wraps). */
typedef void (*cell_visit)(const mimas_deposit *dp, size_t cell, const int idx[3], void *ctx);
static void candidate_cells(const mimas_deposit *dp, const double a[3], double reach,
                            cell_visit visit, void *ctx)
{
    const mimas_grid *g = dp->grid;
    double q[3];
    grid_coords(g, a, q);
    int lo[3], hi[3];
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        for (int d = 0; d < 3; d++)
            if (!index_range(g, dp->h, d, q[d] - reach, q[d] + reach, &lo[d], &hi[d]))
                return;
    } else {
        if (!index_range(g, dp->h, 0, q[0] - reach, q[0] + reach, &lo[0], &hi[0]) ||
            !index_range(g, dp->h, 2, q[2] - reach, q[2] + reach, &lo[2], &hi[2]))
            return;
        double half = q[0] > reach ? asin(reach / q[0]) : M_PI;
        lo[1] = 0;
        hi[1] = g->n[1] - 1;
        if (half < M_PI && q[1] - half >= g->lo[1] && q[1] + half <= g->hi[1])
            index_range(g, dp->h, 1, q[1] - half, q[1] + half, &lo[1], &hi[1]);
    }
    int idx[3];
    for (idx[2] = lo[2]; idx[2] <= hi[2]; idx[2]++)
        for (idx[1] = lo[1]; idx[1] <= hi[1]; idx[1]++)
            for (idx[0] = lo[0]; idx[0] <= hi[0]; idx[0]++)
                visit(dp, mimas_grid_index(g, idx), idx, ctx);
}

/* Whether an image of an object with Cartesian bounding box [lo, hi], shifted
 * by shift s, can reach a Cartesian grid (a quick test before the cell
 * search; cylindrical grids are searched for every image). */
static int image_reaches(const mimas_deposit *dp, int s, const double lo[3], const double hi[3])
{
    const mimas_grid *g = dp->grid;
    if (g->kind != MIMAS_GRID_CARTESIAN)
        return 1;
    for (int d = 0; d < 3; d++)
        if (hi[d] + dp->shift[s][d] < g->lo[d] || lo[d] + dp->shift[s][d] > g->hi[d])
            return 0;
    return 1;
}

typedef struct sphere_ctx {
    const double *x, *a;
    double R;
    deposit_fn fn;
    void *user;
} sphere_ctx;

static void visit_sphere(const mimas_deposit *dp, size_t cell, const int idx[3], void *ctx)
{
    sphere_ctx *s = ctx;
    double grad[3];
    int has_grad;
    double w = cell_weight_sphere(dp, idx, s->x, s->a, s->R, grad, &has_grad);
    if (w != 0.0)
        s->fn(s->user, cell, w, has_grad ? grad : NULL);
}

void mimas_deposit_sphere(const mimas_deposit *dp, const double x[3], double R, deposit_fn fn,
                          void *user)
{
    const mimas_grid *g = dp->grid;
    if (dp->none) {
        fn(user, 0, 1.0 / dp->box_volume, NULL);
        return;
    }
    int point = dp->wt->kind == MIMAS_WEIGHT_BINS_CENTER ||
                (dp->wt->kind == MIMAS_WEIGHT_BINS && !(R > 0));
    double reach = dp->wt->kind >= MIMAS_WEIGHT_GAUSS ? mimas_weight_reach(dp->wt) : R;
    double blo[3] = {x[0] - reach, x[1] - reach, x[2] - reach};
    double bhi[3] = {x[0] + reach, x[1] + reach, x[2] + reach};
    for (int s = 0; s < dp->nshift; s++) {
        if (!image_reaches(dp, s, blo, bhi))
            continue;
        double xs[3] = {x[0] + dp->shift[s][0], x[1] + dp->shift[s][1], x[2] + dp->shift[s][2]};
        double a[3];
        mimas_grid_to_axis(g, xs, a);
        if (point) {
            double q[3];
            size_t cell;
            grid_coords(g, a, q);
            if (cell_of(g, dp->h, q, &cell))
                fn(user, cell,
                   1.0 / (g->kind == MIMAS_GRID_CARTESIAN ? dp->cart_volume
                                                          : mimas_grid_cell_volume(g, cell)),
                   NULL);
            continue;
        }
        sphere_ctx ctx = {xs, a, R, fn, user};
        candidate_cells(dp, a, reach, visit_sphere, &ctx);
    }
}

typedef struct segment_ctx {
    const double *a, *b;     /* Cartesian (for box cells and the Gaussian) */
    const double *aa, *ab;   /* axis frame (cylindrical cells) */
    deposit_fn fn;
    void *user;
} segment_ctx;

static void visit_segment(const mimas_deposit *dp, size_t cell, const int idx[3], void *ctx)
{
    segment_ctx *s = ctx;
    const mimas_grid *g = dp->grid;
    double lo[3], hi[3], c[3], w;
    cell_geometry(dp, idx, lo, hi, c);
    if (dp->wt->kind >= MIMAS_WEIGHT_GAUSS) {
        double p[3];
        if (g->kind == MIMAS_GRID_CARTESIAN)
            memcpy(p, c, sizeof p);
        else {
            p[0] = c[0] * cos(c[1]);
            p[1] = c[0] * sin(c[1]);
            p[2] = c[2];
        }
        const double *a = g->kind == MIMAS_GRID_CARTESIAN ? s->a : s->aa;
        const double *b = g->kind == MIMAS_GRID_CARTESIAN ? s->b : s->ab;
        if (g->kind == MIMAS_GRID_CYLINDRICAL && !g->gridded[1]) {
            /* the azimuthal average along the segment by Gauss-Legendre, with
             * 4, 8 or 16 points for segments up to w/2, 2w or longer (the
             * kernel varies on the scale w) */
            double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                              (b[2] - a[2]) * (b[2] - a[2]));
            double scale = dp->wt->kind == MIMAS_WEIGHT_LUCY ? dp->wt->w / 3.0 : dp->wt->w;
            int half = len <= 0.5 * scale ? 2 : (len <= 2.0 * scale ? 4 : 8);
            const double *xs = half == 2 ? gl4_x : (half == 4 ? gl8_x : gl_x);
            const double *ws = half == 2 ? gl4_w : (half == 4 ? gl8_w : gl_w);
            w = 0.0;
            for (int k = 0; k < half; k++)
                for (int sgn = -1; sgn <= 1; sgn += 2) {
                    double t = 0.5 * (1.0 + sgn * xs[k]), x[3], gr[3];
                    for (int m = 0; m < 3; m++)
                        x[m] = a[m] + t * (b[m] - a[m]);
                    w += 0.5 * ws[k] * ring_kernel(dp->wt, c[0], c[2], x, gr);
                }
        } else {
            double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
            double br[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            w = mimas_kernel_line(dp->wt, d, br);
        }
    } else {
        double f = g->kind == MIMAS_GRID_CARTESIAN
                       ? segment_fraction_box(s->a, s->b, lo, hi)
                       : segment_fraction_cylcell(s->aa, s->ab, lo[0], hi[0], lo[1], hi[1], lo[2],
                                                  hi[2]);
        w = f / cell_volume(dp, lo, hi);
    }
    if (w != 0.0)
        s->fn(s->user, cell, w, NULL);
}

/* Bins on a Cartesian grid: walk the segment through the cells.  The
 * parameters where it crosses grid planes split it into pieces that each lie
 * in one cell (the cell of the piece's midpoint), so every piece gets its
 * exact length fraction and the pieces add up to the part on the grid. */
static int walk_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                        deposit_fn fn, void *user)
{
    const mimas_grid *g = dp->grid;
    double t[64];
    int nt = 0;
    t[nt++] = 0.0;
    for (int d = 0; d < 3; d++) {
        double lo = fmin(a[d], b[d]), hi = fmax(a[d], b[d]), len = b[d] - a[d];
        if (!(hi > lo))
            continue;
        double k0 = ceil((fmax(lo, g->lo[d]) - g->lo[d]) / dp->h[d]);
        for (double k = k0;; k++) {
            double x = g->lo[d] + k * dp->h[d];
            if (x >= hi || x > g->hi[d])
                break;
            if (nt >= 62)
                return 0; /* a long segment: the cell search does it */
            if (x > lo)
                t[nt++] = (x - a[d]) / len;
        }
    }
    t[nt++] = 1.0;
    /* insertion sort: a handful of values */
    for (int i = 1; i < nt; i++)
        for (int j = i; j > 0 && t[j] < t[j - 1]; j--) {
            double x = t[j];
            t[j] = t[j - 1];
            t[j - 1] = x;
        }
    for (int i = 0; i + 1 < nt; i++) {
        double dt = t[i + 1] - t[i];
        if (!(dt > 0))
            continue;
        double tm = 0.5 * (t[i] + t[i + 1]), q[3];
        for (int d = 0; d < 3; d++)
            q[d] = a[d] + tm * (b[d] - a[d]);
        size_t cell;
        if (cell_of(g, dp->h, q, &cell))
            fn(user, cell, dt / dp->cart_volume, NULL);
    }
    return 1;
}

void mimas_deposit_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                           deposit_fn fn, void *user)
{
    const mimas_grid *g = dp->grid;
    if (dp->none) {
        fn(user, 0, 1.0 / dp->box_volume, NULL);
        return;
    }
    if (dp->wt->kind == MIMAS_WEIGHT_BINS_CENTER) {
        /* the cell of the segment's midpoint */
        double m[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
        mimas_deposit_sphere(dp, m, 0.0, fn, user);
        return;
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
    for (int s = 0; s < dp->nshift; s++) {
        if (!image_reaches(dp, s, blo, bhi))
            continue;
        double as[3], bs[3], aa[3], ab[3], mid[3], am[3];
        for (int d = 0; d < 3; d++) {
            as[d] = a[d] + dp->shift[s][d];
            bs[d] = b[d] + dp->shift[s][d];
            mid[d] = 0.5 * (as[d] + bs[d]);
        }
        mimas_grid_to_axis(g, as, aa);
        mimas_grid_to_axis(g, bs, ab);
        mimas_grid_to_axis(g, mid, am);
        if (dp->wt->kind == MIMAS_WEIGHT_BINS && g->kind == MIMAS_GRID_CARTESIAN &&
            walk_segment(dp, as, bs, fn, user))
            continue;
        segment_ctx ctx = {as, bs, aa, ab, fn, user};
        candidate_cells(dp, am, reach, visit_segment, &ctx);
    }
}
