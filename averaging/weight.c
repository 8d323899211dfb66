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
    if (strncmp(spec, "gauss:", 6) == 0) {
        wt->kind = MIMAS_WEIGHT_GAUSS;
        wt->cutoff = 3.0;
        char *text = strdup(spec + 6), *save = NULL;
        if (!text)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
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
            rc = mimas_error_set(err, MIMAS_EUSAGE, "gauss needs its width: gauss:w=W");
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
                           "gauss:w=W[,cutoff=C])", spec);
}

double mimas_weight_reach(const mimas_weight *wt)
{
    return wt->kind == MIMAS_WEIGHT_GAUSS ? wt->cutoff * wt->w : 0.0;
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
