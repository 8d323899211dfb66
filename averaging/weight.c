#include <config.h>

#include "weight.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mimas_weight_parse(mimas_weight *wt, const char *spec, mimas_error *err)
{
    memset(wt, 0, sizeof *wt);
    if (!strcmp(spec, "bins")) {
        wt->kind = MIMAS_WEIGHT_BINS;
        return MIMAS_OK;
    }
    if (!strcmp(spec, "bins:center")) {
        wt->kind = MIMAS_WEIGHT_BINS_CENTER;
        return MIMAS_OK;
    }
    if (!strcmp(spec, "voronoi")) {
        wt->kind = MIMAS_WEIGHT_BINS_CENTER;
        wt->voronoi = 1;
        return MIMAS_OK;
    }
    if (!strncmp(spec, "voronoi:", 8)) {
        char gauss[256];
        snprintf(gauss, sizeof gauss, "gauss:%s", spec + 8);
        int rc = mimas_weight_parse(wt, gauss, err);
        if (rc)
            return rc;
        wt->voronoi = 1;
        return MIMAS_OK;
    }
    if (strncmp(spec, "lucy:c=", 7) == 0) {
        char *end;
        wt->kind = MIMAS_WEIGHT_LUCY;
        wt->w = strtod(spec + 7, &end);
        if (end == spec + 7 || *end || !(wt->w > 0) || !isfinite(wt->w))
            return mimas_error_set(err, MIMAS_EUSAGE, "'%s' needs a positive range: lucy:c=C",
                                   spec);
        /* 3-D Lucy: 105/(16 pi c^3) (1 + 3q)(1 - q)^3, q = r/c < 1; integral 1 */
        wt->coef = 105.0 / (16.0 * M_PI * pow(wt->w, 3));
        wt->reach2 = wt->w * wt->w;
        wt->cutoff = 1.0;
        return MIMAS_OK;
    }
    int shepard = strncmp(spec, "shepard:", 8) == 0;
    if (strncmp(spec, "gauss:", 6) == 0 || shepard) {
        wt->kind = shepard ? MIMAS_WEIGHT_SHEPARD : MIMAS_WEIGHT_GAUSS;
        wt->cutoff = 3.0;
        char *text = strdup(spec + (shepard ? 8 : 6)), *save = NULL;
        if (!text)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the weight");
        int rc = MIMAS_OK;
        for (char *tok = strtok_r(text, ",", &save); tok && !rc;
             tok = strtok_r(NULL, ",", &save)) {
            char *end;
            double *dst = !strncmp(tok, "w=", 2) ? &wt->w
                          : !strncmp(tok, "cutoff=", 7) ? &wt->cutoff : NULL;
            const char *num = dst == &wt->w ? tok + 2 : tok + 7;
            if (!dst)
                rc = mimas_error_set(err, MIMAS_EUSAGE, "unknown gauss parameter '%s' "
                                     "(w=W, cutoff=C)", tok);
            else {
                *dst = strtod(num, &end);
                if (end == num || *end || !(*dst > 0) || !isfinite(*dst))
                    rc = mimas_error_set(err, MIMAS_EUSAGE, "'%s' needs a positive number", tok);
            }
        }
        free(text);
        if (!rc && !(wt->w > 0))
            rc = mimas_error_set(err, MIMAS_EUSAGE, "%s needs its width: %s:w=W",
                                 shepard ? "shepard" : "gauss", shepard ? "shepard" : "gauss");
        if (rc)
            return rc;
        /* The kernel is the Gaussian shifted down by its value at the cutoff,
         * g(r) = exp(-r^2/2w^2) - exp(-C^2/2) for r < C w, so that it is
         * continuous there and its analytic gradient is the whole gradient
         * (a plain cut would add a surface term).  Its integral over space,
         * in units of (2 pi w^2)^{3/2}:
         *   erf(C/sqrt 2) - sqrt(2/pi) C e^{-C^2/2} - e^{-C^2/2} (4/3) pi C^3 / (2 pi)^{3/2} */
        double C = wt->cutoff, tail = exp(-0.5 * C * C);
        wt->shift = tail;
        wt->norm = 1.0 / (erf(C / M_SQRT2) - sqrt(2.0 / M_PI) * C * tail -
                          tail * 4.0 / 3.0 * M_PI * C * C * C / pow(2.0 * M_PI, 1.5));
        wt->coef = wt->norm / pow(2.0 * M_PI * wt->w * wt->w, 1.5);
        wt->inv2w2 = 0.5 / (wt->w * wt->w);
        wt->reach2 = C * C * wt->w * wt->w;
        return MIMAS_OK;
    }
    return mimas_error_set(err, MIMAS_EUSAGE, "unknown weight '%s' (bins, bins:center, "
                           "gauss:w=W[,cutoff=C], lucy:c=C, shepard:w=W[,cutoff=C], voronoi, "
                           "voronoi:w=W[,cutoff=C])", spec);
}

double mimas_weight_reach(const mimas_weight *wt)
{
    return wt->kind >= MIMAS_WEIGHT_GAUSS ? wt->cutoff * wt->w : 0.0;
}

/* Lucy's kernel and its gradient: d/dr of (1 + 3q)(1 - q)^3 is -12 q (1 - q)^2 / c. */
static double lucy_phi_grad(const mimas_weight *wt, const double d[3], double g[3])
{
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 >= wt->reach2) {
        if (g)
            g[0] = g[1] = g[2] = 0.0;
        return 0.0;
    }
    double r = sqrt(r2), q = r / wt->w, m = 1.0 - q;
    if (g) {
        /* dphi/dr / r = -12 (1 - q)^2 / c^2 (finite at r = 0) */
        double k = -12.0 * wt->coef * m * m / (wt->w * wt->w);
        for (int i = 0; i < 3; i++)
            g[i] = k * d[i];
    }
    return wt->coef * (1.0 + 3.0 * q) * m * m * m;
}

/* int phi(|d - s b|) ds over [0, 1] for Lucy's kernel: 20-point Gauss-Legendre
 * on the part inside the support, split at the point of the segment nearest
 * to the field point (where |d - s b| has its kink); the pieces are smooth,
 * so the rule is exact to rounding for the polynomial-in-sqrt integrand's
 * smooth pieces (error ~1e-13). */
static double lucy_line(const mimas_weight *wt, const double d[3], const double b[3])
{
    double a = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    if (!(a > 0))
        return lucy_phi_grad(wt, d, NULL);
    double c = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
    double e = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double s_star = c / a, h2 = fmax(0.0, e - c * c / a);
    if (h2 >= wt->reach2)
        return 0.0;
    double half = sqrt((wt->reach2 - h2) / a);
    double lim[3] = {fmax(0.0, s_star - half), fmin(1.0, fmax(0.0, s_star)),
                     fmin(1.0, s_star + half)};
    if (lim[1] < lim[0])
        lim[1] = lim[0];
    if (lim[2] < lim[1])
        lim[2] = lim[1];
    static const double x[10] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                                 0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                                 0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                                 0.9931285991850949};
    static const double wgt[10] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                                   0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                                   0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                   0.0176140071391521};
    double sum = 0.0;
    for (int piece = 0; piece < 2; piece++) {
        double lo = lim[piece], hi = lim[piece + 1];
        if (!(hi > lo))
            continue;
        double mid = 0.5 * (lo + hi), rad = 0.5 * (hi - lo);
        for (int k = 0; k < 10; k++)
            for (int sign = -1; sign <= 1; sign += 2) {
                double s = mid + sign * rad * x[k];
                double p[3] = {d[0] - s * b[0], d[1] - s * b[1], d[2] - s * b[2]};
                sum += rad * wgt[k] * lucy_phi_grad(wt, p, NULL);
            }
    }
    return sum;
}

double mimas_kernel_phi_grad(const mimas_weight *wt, const double d[3], double g[3])
{
    return wt->kind == MIMAS_WEIGHT_LUCY ? lucy_phi_grad(wt, d, g)
                                         : mimas_gauss_phi_grad(wt, d, g);
}

double mimas_kernel_line(const mimas_weight *wt, const double d[3], const double b[3])
{
    return wt->kind == MIMAS_WEIGHT_LUCY ? lucy_line(wt, d, b) : mimas_gauss_line(wt, d, b);
}

double mimas_gauss_phi(const mimas_weight *wt, const double d[3])
{
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 >= wt->reach2)
        return 0.0;
    return wt->coef * (exp(-r2 * wt->inv2w2) - wt->shift);
}

double mimas_gauss_phi_grad(const mimas_weight *wt, const double d[3], double g[3])
{
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 >= wt->reach2) {
        g[0] = g[1] = g[2] = 0.0;
        return 0.0;
    }
    double e = wt->coef * exp(-r2 * wt->inv2w2);
    double k = -2.0 * e * wt->inv2w2; /* d/dd of exp(-d^2/2w^2) */
    for (int m = 0; m < 3; m++)
        g[m] = k * d[m];
    return e - wt->coef * wt->shift;
}

/* psi = int_0^1 phi(|d - s b|) ds.  With |d - s b|^2 = a s^2 - 2 c s + e
 * (a = b.b, c = d.b, e = d.d) and s* = c/a:
 *   a s^2 - 2 c s + e = a (s - s*)^2 + (e - c^2/a),
 * so int exp(-(...)/(2 w^2)) ds over [s0, s1] is
 *   exp(-(e - c^2/a)/(2 w^2)) sqrt(pi/2) w/sqrt(a) [erf(u1) - erf(u0)],
 *   u = sqrt(a)(s - s*)/(sqrt 2 w).
 * [s0, s1] is [0, 1] clipped to where |d - s b| < cutoff w. */
double mimas_gauss_line(const mimas_weight *wt, const double d[3], const double b[3])
{
    double a = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    if (!(a > 0))
        return mimas_gauss_phi(wt, d);
    double c = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
    double e = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double w = wt->w, R = wt->cutoff * w;
    double s_star = c / a;
    double h2 = fmax(0.0, e - c * c / a); /* squared distance of the line from the point */
    if (h2 >= R * R)
        return 0.0;
    double half = sqrt((R * R - h2) / a);
    double s0 = fmax(0.0, s_star - half), s1 = fmin(1.0, s_star + half);
    if (!(s1 > s0))
        return 0.0;
    double k = sqrt(a) / (M_SQRT2 * w);
    double u0 = k * (s0 - s_star), u1 = k * (s1 - s_star);
    /* erf(u1) - erf(u0) without cancellation when both lie in one tail */
    double diff = u0 > 0 ? erfc(u0) - erfc(u1) : (u1 < 0 ? erfc(-u1) - erfc(-u0) : erf(u1) - erf(u0));
    double integral = exp(-0.5 * h2 / (w * w)) * sqrt(M_PI / 2.0) * w / sqrt(a) * diff;
    /* minus the shift over the part of the segment inside the cutoff */
    integral -= wt->shift * (s1 - s0);
    return wt->coef * integral;
}
