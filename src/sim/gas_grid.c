/* The gas grid of the tube: cells and faces with the fraction of each that
 * lies inside the circular cross-section, and the permeability law. */
#include <config.h>

#include "gas.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* int_0^t sqrt(r^2 - u^2) du for |t| <= r */
static double half_chord_integral(double r, double t)
{
    double s = sqrt(fmax(r * r - t * t, 0));
    return 0.5 * (t * s + r * r * asin(fmax(-1, fmin(1, t / r))));
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sim_disk_rect_area(double r, double x0, double x1, double y0, double y1)
{
    double a = fmax(x0, -r), b = fmin(x1, r);
    if (!(r > 0) || a >= b || y0 >= y1)
        return 0;
    /* the chord length min(y1, s) - max(y0, -s), s = sqrt(r^2 - t^2), changes
     * its form where s = |y0| or s = |y1| */
    double t[6];
    int n = 0;
    t[n++] = a;
    const double ys[2] = {y0, y1};
    for (int k = 0; k < 2; k++)
        if (fabs(ys[k]) < r) {
            double c = sqrt(r * r - ys[k] * ys[k]);
            if (-c > a && -c < b)
                t[n++] = -c;
            if (c > a && c < b)
                t[n++] = c;
        }
    t[n++] = b;
    qsort(t + 1, (size_t)(n - 2), sizeof *t, cmp_double);
    double area = 0;
    for (int k = 0; k + 1 < n; k++) {
        double t0 = t[k], t1 = t[k + 1], dt = t1 - t0;
        if (!(dt > 0))
            continue;
        double tm = 0.5 * (t0 + t1), s = sqrt(fmax(r * r - tm * tm, 0));
        /* (a tie is a tangent point: the circle stays on its side) */
        int top_is_s = s <= y1, bottom_is_s = -s >= y0;
        double top = top_is_s ? s : y1, bottom = bottom_is_s ? -s : y0;
        if (top <= bottom)
            continue;
        double S = half_chord_integral(r, t1) - half_chord_integral(r, t0);
        area += (top_is_s ? S : y1 * dt) - (bottom_is_s ? -S : y0 * dt);
    }
    return area;
}

/* length of the segment x = xf, y0 <= y <= y1 inside the disk */
static double chord_in(double r, double xf, double y0, double y1)
{
    if (fabs(xf) >= r)
        return 0;
    double s = sqrt(r * r - xf * xf);
    return fmax(0, fmin(y1, s) - fmax(y0, -s));
}

size_t sim_gas_cells(const sim_gas *g)
{
    return g->n[0] * g->n[1] * g->n[2];
}

static size_t face_count(const sim_gas_faces *f)
{
    return f->m[0] * f->m[1] * f->m[2];
}

void sim_gas_free(sim_gas *g)
{
    free(g->fraction);
    free(g->pressure);
    free(g->porosity);
    free(g->scratch);
    free(g->solid);
    free(g->tents);
    for (int d = 0; d < 3; d++) {
        free(g->line_order[d]);
        free(g->face_below[d]);
        free(g->face_above[d]);
        sim_gas_faces *f = &g->f[d];
        free(f->fraction);
        free(f->cv_fraction);
        free(f->phi);
        free(f->u);
        free(f->kappa);
        free(f->grad);
    }
    memset(g, 0, sizeof *g);
}

/* fraction of the cross-section rectangle [x0,x1] x [y0,y1] inside the tube */
static double rect_fraction(const sim_gas *g, double x0, double x1, double y0, double y1)
{
    return sim_disk_rect_area(g->p.radius, x0, x1, y0, y1) / ((x1 - x0) * (y1 - y0));
}

static void face_geometry(sim_gas *g, int d)
{
    sim_gas_faces *f = &g->f[d];
    const double R = g->p.radius, hx = g->h[0], hy = g->h[1];
    for (size_t k = 0; k < f->m[2]; k++)
        for (size_t j = 0; j < f->m[1]; j++)
            for (size_t i = 0; i < f->m[0]; i++) {
                size_t q = i + f->m[0] * (j + f->m[1] * k);
                double x0 = g->lo[0] + (double)i * hx, y0 = g->lo[1] + (double)j * hy;
                if (d == 2) {
                    f->fraction[q] = f->cv_fraction[q] = rect_fraction(g, x0, x0 + hx, y0, y0 + hy);
                } else if (d == 0) {
                    f->fraction[q] = chord_in(R, x0, y0, y0 + hy) / hy;
                    f->cv_fraction[q] = rect_fraction(g, x0 - hx / 2, x0 + hx / 2, y0, y0 + hy);
                } else {
                    f->fraction[q] = chord_in(R, y0, x0, x0 + hx) / hx;
                    f->cv_fraction[q] = rect_fraction(g, x0, x0 + hx, y0 - hy / 2, y0 + hy / 2);
                }
            }
}

/* the order of the cells along the lines of direction d, and each cell's faces */
static void index_lines(sim_gas *g, int d)
{
    int e1 = d == 0 ? 1 : 0, e2 = d == 2 ? 1 : 2;
    const size_t *m = g->f[d].m;
    size_t t = 0;
    for (size_t b = 0; b < g->n[e2]; b++)
        for (size_t a = 0; a < g->n[e1]; a++)
            for (size_t p = 0; p < g->n[d]; p++, t++) {
                size_t idx[3];
                idx[d] = p;
                idx[e1] = a;
                idx[e2] = b;
                size_t c = sim_gas_index(g, idx[0], idx[1], idx[2]);
                g->line_order[d][t] = c;
                g->face_below[d][c] = idx[0] + m[0] * (idx[1] + m[1] * idx[2]);
                idx[d]++;
                g->face_above[d][c] = idx[0] + m[0] * (idx[1] + m[1] * idx[2]);
            }
}

int sim_gas_init(sim_gas *g, const sim_gas_params *p, mimas_error *err)
{
    memset(g, 0, sizeof *g);
    if (!(p->radius > 0 && p->length > 0 && p->across >= 1 && p->axial >= 2 && p->P0 > 0 &&
          p->eta > 0 && p->d > 0 && p->theta >= 0.5 && p->theta <= 1 && p->start <= 0 &&
          p->start > -p->length))
        return mimas_error_set(err, MIMAS_EUSAGE, "gas grid: bad parameters");
    g->p = *p;
    g->n[0] = g->n[1] = p->across;
    g->n[2] = p->axial;
    g->lo[0] = g->lo[1] = -p->radius;
    g->lo[2] = p->start;
    g->h[0] = g->h[1] = 2 * p->radius / (double)p->across;
    g->h[2] = (p->length - p->start) / (double)p->axial;
    size_t nc = sim_gas_cells(g);
    g->fraction = malloc(nc * sizeof *g->fraction);
    g->pressure = calloc(nc, sizeof *g->pressure);
    g->porosity = malloc(nc * sizeof *g->porosity);
    g->solid = malloc(nc * sizeof *g->solid);
    g->scratch = malloc(5 * nc * sizeof *g->scratch);
    int bad = !g->fraction || !g->pressure || !g->porosity || !g->solid || !g->scratch;
    for (int d = 0; d < 3 && !bad; d++) {
        sim_gas_faces *f = &g->f[d];
        for (int e = 0; e < 3; e++)
            f->m[e] = g->n[e] + (e == d);
        size_t nf = face_count(f);
        f->fraction = malloc(nf * sizeof *f->fraction);
        f->cv_fraction = malloc(nf * sizeof *f->cv_fraction);
        f->phi = malloc(nf * sizeof *f->phi);
        f->u = calloc(nf, sizeof *f->u);
        f->kappa = calloc(nf, sizeof *f->kappa);
        f->grad = calloc(nf, sizeof *f->grad);
        bad = !f->fraction || !f->cv_fraction || !f->phi || !f->u || !f->kappa || !f->grad;
        g->line_order[d] = malloc(nc * sizeof *g->line_order[d]);
        g->face_below[d] = malloc(nc * sizeof *g->face_below[d]);
        g->face_above[d] = malloc(nc * sizeof *g->face_above[d]);
        bad = bad || !g->line_order[d] || !g->face_below[d] || !g->face_above[d];
        if (!bad) {
            face_geometry(g, d);
            index_lines(g, d);
        }
    }
    if (bad) {
        sim_gas_free(g);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the gas grid");
    }
    for (size_t k = 0; k < g->n[2]; k++)
        for (size_t j = 0; j < g->n[1]; j++)
            for (size_t i = 0; i < g->n[0]; i++) {
                double x0 = g->lo[0] + (double)i * g->h[0], y0 = g->lo[1] + (double)j * g->h[1];
                size_t c = sim_gas_index(g, i, j, k);
                g->fraction[c] = rect_fraction(g, x0, x0 + g->h[0], y0, y0 + g->h[1]);
                g->porosity[c] = 1;
                if (k == 0)
                    g->layer_volume += g->fraction[c] * g->h[0] * g->h[1] * g->h[2];
            }
    for (int d = 0; d < 3; d++)
        for (size_t q = 0; q < face_count(&g->f[d]); q++)
            g->f[d].phi[q] = 1;
    sim_gas_update_permeability(g);
    return MIMAS_OK;
}

double sim_gas_permeability(const sim_gas *g, double phi)
{
    phi = fmin(1, fmax(0.2, phi));
    const double d = g->p.d, D = 2 * g->p.radius;
    /* resistances in series: the grains (Carman-Kozeny) and the tube wall */
    double r = 180 * (1 - phi) * (1 - phi) / (d * d * phi * phi * phi) + 32 / (D * D);
    return 1 / r;
}

double sim_gas_effective_viscosity(double eta0, double re)
{
    return re > 0 ? eta0 * (1 + 0.1935 * pow(re, 0.6305)) : eta0;
}

void sim_gas_update_permeability(sim_gas *g)
{
    for (int d = 0; d < 3; d++) {
        sim_gas_faces *f = &g->f[d];
        for (size_t k = 0; k < f->m[2]; k++)
            for (size_t j = 0; j < f->m[1]; j++)
                for (size_t i = 0; i < f->m[0]; i++) {
                    size_t q = i + f->m[0] * (j + f->m[1] * k), idx[3] = {i, j, k};
                    /* the faces on the tube wall and the tube ends are closed */
                    int boundary = idx[d] == 0 || idx[d] == f->m[d] - 1;
                    f->kappa[q] = boundary || f->fraction[q] <= 0
                                      ? 0
                                      : sim_gas_permeability(g, f->phi[q]);
                }
    }
}
