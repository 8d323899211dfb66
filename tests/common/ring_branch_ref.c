/* The edge-split integral along a branch (ring_branch_ref.h). */
#include <stdlib.h>

#include <gsl/gsl_integration.h>

#include "ring_branch_ref.h"

typedef struct along {
    double (*average)(double, void *);
    void *ctx;
} along;

static double along_at(double s, void *p)
{
    const along *a = p;
    return a->average(s, a->ctx);
}

static int ascending(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

double ring_branch_integral(double (*average)(double s, void *ctx),
                            double (*edge)(double s, double sign, void *ctx), void *ctx,
                            int intervals, double abs_tol, int *edges)
{
    double *cut = malloc((2 * (size_t)intervals + 2) * sizeof *cut);
    if (!cut)
        abort();
    int n = 0;
    cut[n++] = 0.0;
    for (int e = 0; e < 2; e++) {
        double sign = e ? 1.0 : -1.0, prev = edge(0.0, sign, ctx);
        for (int k = 1; k <= intervals; k++) {
            double lo = (k - 1) / (double)intervals, hi = k / (double)intervals;
            double v = edge(hi, sign, ctx);
            if ((v < 0) != (prev < 0)) {
                for (int it = 0; it < 60; it++) {
                    double mid = 0.5 * (lo + hi);
                    if ((edge(mid, sign, ctx) < 0) == (prev < 0))
                        lo = mid;
                    else
                        hi = mid;
                }
                cut[n++] = 0.5 * (lo + hi);
            }
            prev = v;
        }
    }
    if (edges)
        *edges = n - 1;
    cut[n++] = 1.0;
    qsort(cut, (size_t)n, sizeof *cut, ascending);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    along a = {average, ctx};
    gsl_function F = {along_at, &a};
    double sum = 0.0;
    for (int k = 0; k + 1 < n; k++) {
        double v, err;
        gsl_integration_qags(&F, cut[k], cut[k + 1], abs_tol, 1e-13, 1000, ws, &v, &err);
        sum += v;
    }
    gsl_integration_workspace_free(ws);
    free(cut);
    return sum;
}
