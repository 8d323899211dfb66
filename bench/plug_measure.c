/* The measurements of docs/plugconveying.md on a plugtube run (native file):
 *   plug_measure RUN.h5 [--from T0] [--slice W] [--threshold PHI] [--min-length L]
 *                [--cohort T1] [--window DT] [--fit-sigma S]
 * after T0 (the tube filled): grains in the tube, the pressure drop over the
 * tube per length (gas fields), plugs (runs of slices of porosity below PHI,
 * at least L long: Strauß 2005, Sec. 4.3), their lengths and velocities
 * (plugs of consecutive frames matched; centres in the middle half of the
 * tube), and the dispersion coefficient D of the grains released within DT
 * after T1 (variance of their axial positions about the mean, D = half the
 * slope over the frames where its square root exceeds S, up to the first
 * frame in which one of them has left: Strauß 2005, Sec. 5.7). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "native.h"
#include "plug_stats.h"

#define MAX_PLUGS 256

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(double *v, size_t n, double q)
{
    if (n == 0)
        return NAN;
    qsort(v, n, sizeof *v, cmp_double);
    double pos = q * (double)(n - 1);
    size_t i = (size_t)pos;
    return i + 1 < n ? v[i] + (pos - (double)i) * (v[i + 1] - v[i]) : v[i];
}

typedef struct growing {
    double *v;
    size_t n, cap;
} growing;

static void push(growing *g, double x)
{
    if (g->n == g->cap) {
        g->cap = g->cap ? 2 * g->cap : 1024;
        g->v = realloc(g->v, g->cap * sizeof *g->v);
        if (!g->v)
            exit(2);
    }
    g->v[g->n++] = x;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: plug_measure RUN.h5 [--from T0] [--slice W] [--threshold PHI] "
                        "[--min-length L] [--cohort T1] [--window DT] [--fit-sigma S]\n");
        return 1;
    }
    double from = 0, w = 0.0014, threshold = 0.6, min_length = 0.0028, cohort = -1, window = 0.1,
           fit_sigma = 0.03;
    for (int k = 2; k + 1 < argc; k += 2) {
        double v = atof(argv[k + 1]);
        if (!strcmp(argv[k], "--from"))
            from = v;
        else if (!strcmp(argv[k], "--slice"))
            w = v;
        else if (!strcmp(argv[k], "--threshold"))
            threshold = v;
        else if (!strcmp(argv[k], "--min-length"))
            min_length = v;
        else if (!strcmp(argv[k], "--cohort"))
            cohort = v;
        else if (!strcmp(argv[k], "--window"))
            window = v;
        else if (!strcmp(argv[k], "--fit-sigma"))
            fit_sigma = v;
        else {
            fprintf(stderr, "plug_measure: unknown option %s\n", argv[k]);
            return 1;
        }
    }
    mimas_native *r;
    mimas_error err;
    if (mimas_native_open(&r, argv[1], &err)) {
        fprintf(stderr, "plug_measure: %s\n", err.msg);
        return 2;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    size_t nf = mimas_native_frames(r), used = 0, ns = 0, nprev = 0;
    double *phi = NULL, tprev = 0;
    plug prev[MAX_PLUGS], cur[MAX_PLUGS];
    growing grains = {0}, dpl = {0}, lengths = {0}, speeds = {0}, nplugs = {0};
    growing ct = {0}, cvar = {0};
    /* cohort: by id, 1 = member */
    size_t idcap = 1 << 22;
    unsigned char *member = calloc(idcap, 1), *seen = calloc(idcap, 1);
    size_t members = 0;
    int cohort_open = cohort >= 0, cohort_done = 0;
    double R = 0, L = 0;
    for (size_t k = 0; k < nf; k++) {
        if (mimas_native_read(r, k, &f, &err)) {
            fprintf(stderr, "plug_measure: %s\n", err.msg);
            return 2;
        }
        if (!f.tube.present || !f.particles.type) {
            fprintf(stderr, "plug_measure: %s is not a plugtube run\n", argv[1]);
            return 2;
        }
        R = f.tube.radius;
        L = f.tube.length;
        const mimas_particles *p = &f.particles;
        /* the cohort: grains seen free for the first time in [cohort, cohort + window] */
        for (size_t i = 0; i < p->n; i++) {
            int64_t id = p->id[i];
            if (id < 0 || (size_t)id >= idcap || p->type[i] != 1)
                continue;
            if (!seen[id] && cohort_open && f.time >= cohort && f.time <= cohort + window) {
                member[id] = 1;
                members++;
            }
            seen[id] = 1;
        }
        if (cohort_open && f.time > cohort + window && !cohort_done && members > 1) {
            double s = 0, s2 = 0;
            size_t m = 0;
            for (size_t i = 0; i < p->n; i++)
                if (p->id[i] >= 0 && (size_t)p->id[i] < idcap && member[p->id[i]]) {
                    s += p->pos[i][2];
                    s2 += p->pos[i][2] * p->pos[i][2];
                    m++;
                }
            if (m < members)
                cohort_done = 1;   /* one has left the tube */
            else {
                push(&ct, f.time - cohort);
                push(&cvar, s2 / (double)m - (s / (double)m) * (s / (double)m));
            }
        }
        if (f.time < from)
            continue;
        used++;
        size_t n_in = 0;
        for (size_t i = 0; i < p->n; i++)
            n_in += p->type[i] == 1 && p->pos[i][2] >= 0 && p->pos[i][2] < L;
        push(&grains, (double)n_in);
        if (f.gas.present) {
            const mimas_gas *g = &f.gas;
            size_t layer = g->cells[0] * g->cells[1], last = layer * (g->cells[2] - 1);
            double pin = 0, pout = 0;
            for (size_t c = 0; c < layer; c++) {
                pin += g->pressure[c] / (double)layer;
                pout += g->pressure[last + c] / (double)layer;
            }
            push(&dpl, (pin - pout) / ((double)(g->cells[2] - 1) * g->spacing[2]));
        }
        if (!phi) {
            ns = (size_t)(L / w);
            phi = malloc(ns * sizeof *phi);
        }
        plug_porosity(&f, R, ns, w, 2, phi);
        size_t nc = plug_find(phi, ns, w, threshold, (size_t)ceil(min_length / w - 1e-9), cur,
                              MAX_PLUGS);
        push(&nplugs, (double)nc);
        for (size_t j = 0; j < nc; j++)
            push(&lengths, cur[j].hi - cur[j].lo);
        if (used > 1) {
            double v[MAX_PLUGS], dt = f.time - tprev;
            /* a plug moves less than 2 m/s x dt between frames */
            plug_match(prev, nprev, cur, nc, dt, 2 * dt, v);
            for (size_t j = 0; j < nc; j++)
                if (!isnan(v[j]) && cur[j].centre > L / 4 && cur[j].centre < 3 * L / 4)
                    push(&speeds, v[j]);
        }
        memcpy(prev, cur, nc * sizeof *cur);
        nprev = nc;
        tprev = f.time;
    }
    double mg = 0, mdp = 0, mn = 0;
    for (size_t k = 0; k < grains.n; k++)
        mg += grains.v[k] / (double)grains.n;
    for (size_t k = 0; k < dpl.n; k++)
        mdp += dpl.v[k] / (double)dpl.n;
    for (size_t k = 0; k < nplugs.n; k++)
        mn += nplugs.v[k] / (double)nplugs.n;
    printf("%s: %zu frames from t = %g s, tube R = %g m, L = %g m\n", argv[1], used, from, R, L);
    printf("grains in the tube        %.0f\n", mg);
    printf("pressure drop dP/L        %.2f hPa/m\n", mdp / 100);
    printf("plugs per frame           %.2f (porosity < %g, at least %g m)\n", mn, threshold,
           min_length);
    printf("plug length               median %.4f m, quartiles %.4f .. %.4f m (%zu plugs)\n",
           quantile(lengths.v, lengths.n, 0.5), quantile(lengths.v, lengths.n, 0.25),
           quantile(lengths.v, lengths.n, 0.75), lengths.n);
    printf("plug velocity (mid tube)  median %.3f m/s, quartiles %.3f .. %.3f m/s (%zu matches)\n",
           quantile(speeds.v, speeds.n, 0.5), quantile(speeds.v, speeds.n, 0.25),
           quantile(speeds.v, speeds.n, 0.75), speeds.n);
    if (cohort >= 0) {
        growing fx = {0}, fy = {0};
        for (size_t k = 0; k < ct.n; k++)
            if (sqrt(cvar.v[k]) >= fit_sigma) {
                push(&fx, ct.v[k]);
                push(&fy, cvar.v[k]);
            }
        double D = fx.n >= 3 ? plug_slope(fx.v, fy.v, fx.n) / 2 : NAN;
        printf("dispersion D              %.3g m^2/s (%zu grains released %g..%g s, %zu frames "
               "with sigma >= %g m of %zu)\n", D, members, cohort, cohort + window, fx.n,
               fit_sigma, ct.n);
        free(fx.v);
        free(fy.v);
    }
    free(phi);
    free(member);
    free(seen);
    mimas_frame_free(&f);
    mimas_native_close(r);
    return 0;
}
