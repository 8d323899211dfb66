#include <config.h>

#include "grid.h"

#include "axis.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const cart_names[3] = {"x", "y", "z"};
static const char *const cyl_names[3] = {"r", "phi", "z"};

const char *mimas_grid_coord_name(const mimas_grid *g, int d)
{
    return g->kind == MIMAS_GRID_CYLINDRICAL ? cyl_names[d] : cart_names[d];
}

static int parse_axis(mimas_grid *g, const char *spec, mimas_error *err)
{
    mimas_axis a;
    int rc = mimas_axis_parse(&a, spec, err);
    if (rc)
        return rc;
    for (int d = 0; d < 3; d++)
        g->origin[d] = a.origin[d], g->ez[d] = a.ez[d], g->ex[d] = a.ex[d], g->ey[d] = a.ey[d];
    return MIMAS_OK;
}

int mimas_grid_parse(mimas_grid *g, const char *spec, const char *axis, mimas_error *err)
{
    memset(g, 0, sizeof *g);
    for (int d = 0; d < 3; d++)
        g->n[d] = 1;
    g->kind = MIMAS_GRID_CARTESIAN;
    int rc = parse_axis(g, axis, err);
    if (rc)
        return rc;
    if (!strcmp(spec, "none"))
        return MIMAS_OK;
    g->kind = strncmp(spec, "r=", 2) == 0 ? MIMAS_GRID_CYLINDRICAL : MIMAS_GRID_CARTESIAN;
    if (axis && g->kind != MIMAS_GRID_CYLINDRICAL)
        return mimas_error_set(err, MIMAS_EUSAGE, "--axis applies to cylindrical grids (r=...)");
    char *text = strdup(spec), *save = NULL;
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the grid");
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        char name[8];
        double lo, hi;
        int n, used = 0;
        int d = -1;
        if (sscanf(tok, "%7[a-z]=%lf:%lf:%d%n", name, &lo, &hi, &n, &used) == 4 &&
            tok[used] == '\0') {
            for (int k = 0; k < 3; k++)
                if (!strcmp(name, mimas_grid_coord_name(g, k)))
                    d = k;
        }
        if (d < 0)
            rc = mimas_error_set(err, MIMAS_EUSAGE,
                                 "grid direction '%s' is not NAME=LO:HI:N with NAME one of %s",
                                 tok, g->kind == MIMAS_GRID_CYLINDRICAL ? "r phi z" : "x y z");
        else if (g->gridded[d])
            rc = mimas_error_set(err, MIMAS_EUSAGE, "grid direction %s given twice", name);
        else if (!(hi > lo) || !isfinite(lo) || !isfinite(hi) || n < 1 || n > 100000000)
            rc = mimas_error_set(err, MIMAS_EUSAGE, "grid direction '%s' needs LO < HI and N >= 1",
                                 tok);
        else if (g->kind == MIMAS_GRID_CYLINDRICAL && d == 0 && lo < 0)
            rc = mimas_error_set(err, MIMAS_EUSAGE, "r must not be negative ('%s')", tok);
        else if (g->kind == MIMAS_GRID_CYLINDRICAL && d == 1 && hi - lo > 2 * M_PI * (1 + 1e-12))
            rc = mimas_error_set(err, MIMAS_EUSAGE, "phi spans more than 2 pi ('%s')", tok);
        if (rc)
            break;
        g->gridded[d] = 1;
        g->lo[d] = lo;
        g->hi[d] = hi;
        g->n[d] = n;
    }
    free(text);
    if (!rc && g->kind == MIMAS_GRID_CYLINDRICAL && !g->gridded[1]) {
        g->lo[1] = -M_PI;
        g->hi[1] = M_PI;
    }
    size_t cells = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
    if (!rc && cells > ((size_t)1 << 31))
        rc = mimas_error_set(err, MIMAS_EUSAGE, "the grid has %zu cells, too many", cells);
    return rc;
}

void mimas_grid_fit_box(mimas_grid *g, const mimas_box *b)
{
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        /* a periodic direction spans lo..hi: with the tilts, the orthogonal
         * box lo..hi is still a fundamental domain of the periodic lattice
         * (subtract multiples of c, then b, then a), so periodic images fill
         * it exactly once; a non-periodic direction spans the tilted box's
         * bounding box */
        double e[3][3];
        mimas_box_edges(b, e);
        for (int d = 0; d < 3; d++) {
            if (g->gridded[d])
                continue;
            if (b->periodic[d]) {
                g->lo[d] = b->lo[d];
                g->hi[d] = b->hi[d];
                continue;
            }
            double lo = b->lo[d], hi = b->lo[d];
            for (int k = 1; k < 8; k++) {
                double x = b->lo[d];
                for (int m = 0; m < 3; m++)
                    if (k & (1 << m))
                        x += e[m][d];
                lo = fmin(lo, x);
                hi = fmax(hi, x);
            }
            g->lo[d] = lo;
            g->hi[d] = hi;
        }
        return;
    }
    if (g->gridded[2])
        return;
    /* z: the box's extent along the axis (over its eight corners) */
    double e[3][3];
    mimas_box_edges(b, e);
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < 8; k++) {
        double x[3] = {b->lo[0], b->lo[1], b->lo[2]};
        for (int m = 0; m < 3; m++)
            if (k & (1 << m))
                for (int d = 0; d < 3; d++)
                    x[d] += e[m][d];
        double a[3];
        mimas_grid_to_axis(g, x, a);
        lo = fmin(lo, a[2]);
        hi = fmax(hi, a[2]);
    }
    g->lo[2] = lo;
    g->hi[2] = hi;
}

size_t mimas_grid_cells(const mimas_grid *g)
{
    return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
}

size_t mimas_grid_index(const mimas_grid *g, const int idx[3])
{
    return (size_t)idx[0] + (size_t)g->n[0] * ((size_t)idx[1] + (size_t)g->n[1] * (size_t)idx[2]);
}

void mimas_grid_unindex(const mimas_grid *g, size_t cell, int idx[3])
{
    idx[0] = (int)(cell % (size_t)g->n[0]);
    cell /= (size_t)g->n[0];
    idx[1] = (int)(cell % (size_t)g->n[1]);
    idx[2] = (int)(cell / (size_t)g->n[1]);
}

void mimas_grid_cell_bounds(const mimas_grid *g, size_t cell, double lo[3], double hi[3])
{
    int idx[3];
    mimas_grid_unindex(g, cell, idx);
    for (int d = 0; d < 3; d++) {
        double h = (g->hi[d] - g->lo[d]) / g->n[d];
        lo[d] = g->lo[d] + h * idx[d];
        hi[d] = idx[d] + 1 == g->n[d] ? g->hi[d] : g->lo[d] + h * (idx[d] + 1);
    }
}

void mimas_grid_cell_centre(const mimas_grid *g, size_t cell, double c[3])
{
    double lo[3], hi[3];
    mimas_grid_cell_bounds(g, cell, lo, hi);
    for (int d = 0; d < 3; d++)
        c[d] = 0.5 * (lo[d] + hi[d]);
}

double mimas_grid_cell_volume(const mimas_grid *g, size_t cell)
{
    double lo[3], hi[3];
    mimas_grid_cell_bounds(g, cell, lo, hi);
    if (g->kind == MIMAS_GRID_CYLINDRICAL)
        /* annular sector: (r1^2 - r0^2)/2 * dphi * dz */
        return 0.5 * (hi[0] * hi[0] - lo[0] * lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}

void mimas_grid_to_axis(const mimas_grid *g, const double x[3], double out[3])
{
    if (g->kind == MIMAS_GRID_CARTESIAN) {
        memcpy(out, x, 3 * sizeof *out);
        return;
    }
    double d[3] = {x[0] - g->origin[0], x[1] - g->origin[1], x[2] - g->origin[2]};
    out[0] = d[0] * g->ex[0] + d[1] * g->ex[1] + d[2] * g->ex[2];
    out[1] = d[0] * g->ey[0] + d[1] * g->ey[1] + d[2] * g->ey[2];
    out[2] = d[0] * g->ez[0] + d[1] * g->ez[1] + d[2] * g->ez[2];
}
