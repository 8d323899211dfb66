#include <config.h>

#include "weight.h"

#include <gsl/gsl_sf_bessel.h>
#include <pthread.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gauss_legendre.h"
#include "ring_tables.h"

/* ---- parsing ---------------------------------------------------------------- */

/* The Gaussian's normalisation: coef = 1 / int (e^{-r^2/2w^2} - shift) over the ball
 * r < C w, with int_ball e^{-r^2/2w^2} = (2 pi w^2)^{3/2} (erf(C/sqrt 2) - sqrt(2/pi) C e^{-C^2/2})
 * and the shift's integral shift (4/3) pi (C w)^3. */
static void gauss_setup(mimas_weight *wt)
{
    double C = wt->cutoff, w = wt->w, tail = exp(-0.5 * C * C), R = C * w;
    wt->tail = tail;
    wt->shift = wt->shifted ? tail : 0.0;
    double ball = pow(2.0 * M_PI * w * w, 1.5) * (erf(C / M_SQRT2) - sqrt(2.0 / M_PI) * C * tail);
    wt->coef = 1.0 / (ball - wt->shift * 4.0 / 3.0 * M_PI * R * R * R);
    wt->inv2w2 = 0.5 / (w * w);
    wt->reach2 = R * R;
    /* the plain cut jumps from coef tail to 0 at R: the first moment of that jump,
     * oint x_b phi(R) n_a dA = phi(R) V_ball delta_ab, is what a gradient taken inside
     * the support misses for a linear field */
    wt->kappa = wt->coef * (tail - wt->shift) * 4.0 / 3.0 * M_PI * R * R * R;
}

static int parse_gauss(mimas_weight *wt, const char *params, const char *name,
                       mimas_error *err)
{
    wt->cutoff = 3.0;
    char *text = strdup(params), *save = NULL;
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    int rc = MIMAS_OK;
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        if (!strcmp(tok, "shift")) {
            wt->shifted = 1;
            continue;
        }
        char *end;
        double *dst = !strncmp(tok, "w=", 2) ? &wt->w
                      : !strncmp(tok, "cutoff=", 7) ? &wt->cutoff : NULL;
        const char *num = dst == &wt->w ? tok + 2 : tok + 7;
        if (!dst)
            rc = mimas_error_set(err, MIMAS_EUSAGE, "unknown %s parameter '%s' (w=W, cutoff=C, "
                                 "shift)", name, tok);
        else {
            *dst = strtod(num, &end);
            if (end == num || *end || !(*dst > 0) || !isfinite(*dst))
                rc = mimas_error_set(err, MIMAS_EUSAGE, "'%s' needs a positive number", tok);
        }
    }
    free(text);
    if (!rc && !(wt->w > 0))
        rc = mimas_error_set(err, MIMAS_EUSAGE, "%s needs its width: %s:w=W", name, name);
    if (!rc)
        gauss_setup(wt);
    return rc;
}

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
        wt->kind = MIMAS_WEIGHT_GAUSS;
        wt->voronoi = 1;
        return parse_gauss(wt, spec + 8, "voronoi", err);
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
    if (strncmp(spec, "gauss:", 6) == 0) {
        wt->kind = MIMAS_WEIGHT_GAUSS;
        return parse_gauss(wt, spec + 6, "gauss", err);
    }
    if (strncmp(spec, "shepard:", 8) == 0) {
        wt->kind = MIMAS_WEIGHT_SHEPARD;
        return parse_gauss(wt, spec + 8, "shepard", err);
    }
    return mimas_error_set(err, MIMAS_EUSAGE, "unknown weight '%s' (bins, bins:center, "
                           "gauss:w=W[,cutoff=C][,shift], lucy:c=C, shepard:w=W[,cutoff=C], "
                           "voronoi, voronoi:w=W[,cutoff=C])", spec);
}

double mimas_weight_reach(const mimas_weight *wt)
{
    return wt->kind >= MIMAS_WEIGHT_GAUSS ? wt->cutoff * wt->w : 0.0;
}

/* ---- the 3-D kernels ---------------------------------------------------------- */

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
 * so the rule is exact to rounding (error ~1e-13). */
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
        if (g)
            g[0] = g[1] = g[2] = 0.0;
        return 0.0;
    }
    double e = wt->coef * exp(-r2 * wt->inv2w2);
    if (g) {
        double k = -2.0 * e * wt->inv2w2; /* d/dd of exp(-d^2/2w^2) */
        for (int m = 0; m < 3; m++)
            g[m] = k * d[m];
    }
    return e - wt->coef * wt->shift;
}

/* int_lo^hi e^{-u^2/2w^2} du without cancellation: 8-point Gauss-Legendre for
 * intervals up to w/4 (exact to rounding there), erf / erfc differences beyond
 * (the tails by erfc; at most ~10 ulp lost in the difference). */
static double gauss_interval(double w, double lo, double hi)
{
    if (!(hi > lo))
        return 0.0;
    if (hi - lo <= 0.25 * w) {
        double sum = 0.0, k = 0.5 / (w * w);
        for (int n = 0; n < 8; n++) {
            double u, wgt;
            gl_node(gl8_x, gl8_w, 8, n, lo, hi, &u, &wgt);
            sum += wgt * exp(-k * u * u);
        }
        return sum;
    }
    double u0 = lo / (M_SQRT2 * w), u1 = hi / (M_SQRT2 * w);
    double diff = u0 > 0 ? erfc(u0) - erfc(u1) : (u1 < 0 ? erfc(-u1) - erfc(-u0) : erf(u1) - erf(u0));
    return sqrt(M_PI / 2.0) * w * diff;
}

/* psi = int_0^1 phi(|d - s b|) ds.  With |d - s b|^2 = a s^2 - 2 c s + e
 * (a = b.b, c = d.b, e = d.d) and s* = c/a:
 *   a s^2 - 2 c s + e = a (s - s*)^2 + (e - c^2/a),
 * so int e^{-(...)/(2 w^2)} ds over [s0, s1] is e^{-(e - c^2/a)/(2 w^2)} times the
 * Gaussian's integral over u = sqrt(a) (s - s*) from u0 to u1, divided by sqrt(a);
 * [s0, s1] is [0, 1] clipped to where |d - s b| < cutoff w. */
double mimas_gauss_line(const mimas_weight *wt, const double d[3], const double b[3])
{
    double a = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    if (!(a > 0))
        return mimas_gauss_phi(wt, d);
    double c = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
    double e = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double s_star = c / a;
    double h2 = fmax(0.0, e - c * c / a); /* squared distance of the line from the point */
    if (h2 >= wt->reach2)
        return 0.0;
    double half = sqrt((wt->reach2 - h2) / a);
    double s0 = fmax(0.0, s_star - half), s1 = fmin(1.0, s_star + half);
    if (!(s1 > s0))
        return 0.0;
    double ra = sqrt(a);
    double integral = exp(-h2 * wt->inv2w2) * gauss_interval(wt->w, ra * (s0 - s_star),
                                                             ra * (s1 - s_star)) / ra;
    /* minus the shift over the part of the segment inside the cutoff */
    integral -= wt->shift * (s1 - s0);
    return wt->coef * integral;
}

/* ---- marginals ------------------------------------------------------------------ */

/* Lucy's kernel integrated along one direction through a point at distance rho
 * from the centre, in units of c (Y = sqrt(1 - rho^2)):
 *   int_{-Y}^{Y} f(sqrt(rho^2 + y^2)) dy = 6 (1 - Y^2)^2 atanh Y - 6 Y + 10 Y^3 - 16/5 Y^5
 *                                        = sum_{m>=3} 48 Y^{2m+1} / ((2m+1)(2m-1)(2m-3)),
 * f(q) = (1 + 3q)(1 - q)^3, and the derivative's factor
 *   int_{-Y}^{Y} f'(r)/r dy = -12 [2 (1 - Y^2)(Y - atanh Y) + 2/3 Y^3]
 *                           = -12 sum_{m>=2} 4 Y^{2m+1} / ((2m-1)(2m+1));
 * the series where the closed forms cancel (Y <= 0.6). */
static void lucy_chord(double rho2, double *val, double *dfac)
{
    double Y = sqrt(fmax(0.0, 1.0 - rho2));
    if (Y > 0.6) {
        /* rho^2 atanh Y = rho^2 log((1 + Y)/rho), 0 at rho = 0 */
        double y2 = Y * Y, rho = sqrt(rho2);
        double at2 = rho > 0 ? rho2 * log((1.0 + Y) / rho) : 0.0;
        *val = 6.0 * rho2 * at2 - 6.0 * Y + 10.0 * Y * y2 - 3.2 * Y * y2 * y2;
        *dfac = -12.0 * (2.0 * (rho2 * Y - at2) + 2.0 / 3.0 * Y * y2);
        return;
    }
    double y2 = Y * Y, p = Y * y2 * y2; /* Y^5 */
    double v = 0.0, g = 0.0;
    for (int m = 2; m < 60; m++) {
        g += 4.0 * p / ((2.0 * m - 1) * (2.0 * m + 1));
        if (m >= 3)
            v += 48.0 * p / ((2.0 * m + 1) * (2.0 * m - 1) * (2.0 * m - 3));
        p *= y2;
        if (p < 1e-18 * (g + 1e-300))
            break;
    }
    *val = v;
    *dfac = -12.0 * g;
}

/* The marginal at offset d of length^2 r2 (dims components); gfac gets
 * (d marginal/d r)/r, so the gradient is gfac * d. */
static double marginal_radial(const mimas_weight *wt, int dims, double r2, double *gfac)
{
    *gfac = 0.0;
    if (r2 >= wt->reach2)
        return 0.0;
    double R2 = wt->reach2;
    if (wt->kind == MIMAS_WEIGHT_LUCY) {
        double c = wt->w, u2 = r2 / R2;
        if (dims == 1) {
            /* 2 pi c^2 int_u^1 f(q) q dq = 2 pi c^2 (1 - u)^4 (1 + 4u + 5u^2)/10 */
            double u = sqrt(u2), m = 1.0 - u;
            *gfac = -2.0 * M_PI * wt->coef * (1.0 + 3.0 * u) * m * m * m;
            return wt->coef * 2.0 * M_PI * c * c * m * m * m * m * (1.0 + 4.0 * u + 5.0 * u2) /
                   10.0;
        }
        double val, dfac;
        lucy_chord(u2, &val, &dfac);
        *gfac = wt->coef * dfac / c;
        return wt->coef * c * val;
    }
    double e = exp(-r2 * wt->inv2w2), sh = wt->shift, tail = wt->tail, w = wt->w;
    if (dims == 1) {
        /* int over the disc of radius P = sqrt(R^2 - z^2):
         * 2 pi w^2 (e^{-z^2/2w^2} - e^{-C^2/2}) - shift pi P^2 */
        *gfac = wt->coef * 2.0 * M_PI * (sh - e);
        return wt->coef * (2.0 * M_PI * w * w * (e - tail) - sh * M_PI * (R2 - r2));
    }
    /* int over the chord |y| < Y = sqrt(R^2 - rho^2):
     * sqrt(2 pi) w e^{-rho^2/2w^2} erf(Y / sqrt(2) w) - 2 shift Y; its d/drho is
     * -(rho/w^2) sqrt(2 pi) w e^{..} erf(..) - 2 rho (e^{-C^2/2} - shift)/Y */
    double Y = sqrt(R2 - r2), er = erf(Y / (M_SQRT2 * w));
    *gfac = wt->coef * (-sqrt(2.0 * M_PI) / w * e * er - 2.0 * (tail - sh) / Y);
    return wt->coef * (sqrt(2.0 * M_PI) * w * e * er - 2.0 * sh * Y);
}

double mimas_kernel_marginal(const mimas_weight *wt, int dims, const double *d, double *g)
{
    if (dims == 3)
        return mimas_kernel_phi_grad(wt, d, g);
    double r2 = 0.0, gfac;
    for (int m = 0; m < dims; m++)
        r2 += d[m] * d[m];
    double v = marginal_radial(wt, dims, r2, &gfac);
    if (g)
        for (int m = 0; m < dims; m++)
            g[m] = gfac * d[m];
    return v;
}

/* int_lo^hi of the 1-D marginal (lo < hi within [-R, R]) */
static double marginal1_interval(const mimas_weight *wt, double lo, double hi)
{
    if (!(hi > lo))
        return 0.0;
    if (wt->kind == MIMAS_WEIGHT_LUCY) {
        /* a polynomial of degree 6 in |z| on each side of 0: 4-point Gauss-Legendre is exact */
        double cut[3] = {lo, fmin(hi, fmax(lo, 0.0)), hi}, sum = 0.0;
        for (int piece = 0; piece < 2; piece++)
            for (int n = 0; n < 4; n++) {
                double z, wgt, gf;
                if (!(cut[piece + 1] > cut[piece]))
                    continue;
                gl_node(gl4_x, gl4_w, 4, n, cut[piece], cut[piece + 1], &z, &wgt);
                sum += wgt * marginal_radial(wt, 1, z * z, &gf);
            }
        return sum;
    }
    double w = wt->w, R2 = wt->reach2;
    double g = 2.0 * M_PI * w * w * (gauss_interval(w, lo, hi) - wt->tail * (hi - lo));
    if (wt->shift > 0)
        g -= wt->shift * M_PI * (R2 * (hi - lo) - (hi - lo) * (hi * hi + hi * lo + lo * lo) / 3.0);
    return wt->coef * g;
}

/* The 2-D marginal's line integral over the chord of the disc of radius R about
 * the field point: with s = s* + H sin(theta), s* the foot of the perpendicular
 * and H the chord's half-length, the marginal's square-root edge
 * Y = sqrt(R^2 - rho^2) = sqrt(a) H cos(theta) is smooth in theta, and so is the
 * integrand: 16-point Gauss-Legendre in theta on each side of the foot
 * (2e-16 relative for cutoffs 1.5 to 5). */
static double marginal2_line(const mimas_weight *wt, const double *d, const double *b)
{
    double a = b[0] * b[0] + b[1] * b[1];
    if (!(a > 0))
        return mimas_kernel_marginal(wt, 2, d, NULL);
    double c = d[0] * b[0] + d[1] * b[1], e = d[0] * d[0] + d[1] * d[1];
    double s_star = c / a, h2 = fmax(0.0, e - c * c / a), R2 = wt->reach2;
    if (h2 >= R2)
        return 0.0;
    double H = sqrt((R2 - h2) / a);
    double s0 = fmax(0.0, s_star - H), s1 = fmin(1.0, s_star + H);
    if (!(s1 > s0))
        return 0.0;
    double t0 = asin(fmax(-1.0, fmin(1.0, (s0 - s_star) / H)));
    double t1 = asin(fmax(-1.0, fmin(1.0, (s1 - s_star) / H)));
    double cut[3] = {t0, fmin(t1, fmax(t0, 0.0)), t1}, sum = 0.0;
    for (int piece = 0; piece < 2; piece++) {
        if (!(cut[piece + 1] > cut[piece]))
            continue;
        for (int n = 0; n < 16; n++) {
            double th, wgt, gf;
            gl_node(gl16_x, gl16_w, 16, n, cut[piece], cut[piece + 1], &th, &wgt);
            double sn = sin(th), cs = cos(th);
            double rho2 = fmin(R2, h2 + a * H * H * sn * sn);
            sum += wgt * H * cs * marginal_radial(wt, 2, rho2, &gf);
        }
    }
    return sum;
}

double mimas_kernel_marginal_line(const mimas_weight *wt, int dims, const double *d,
                                  const double *b)
{
    if (dims == 3)
        return mimas_kernel_line(wt, d, b);
    if (dims == 2)
        return marginal2_line(wt, d, b);
    /* 1-D: (1/|b|) int over [d - b, d] (or [d, d - b]) of the marginal, clipped to the support */
    double R = sqrt(wt->reach2), L = fabs(b[0]);
    if (!(L > 1e-12 * R)) {
        double z = d[0] - 0.5 * b[0], gf;
        return marginal_radial(wt, 1, z * z, &gf);
    }
    double lo = fmax(-R, fmin(d[0], d[0] - b[0])), hi = fmin(R, fmax(d[0], d[0] - b[0]));
    return marginal1_interval(wt, lo, hi) / L;
}

/* ---- azimuthal averages ------------------------------------------------------------ */

/* The Gauss-Legendre rule in theta on [0, pi/2] for an arc's quadrature (mimas_kernel_ring):
 * 32 points (gauss_legendre.h), with sin and cos of each node, made once.  Its error for
 * the Gaussian's long arcs is below 1e-15 of the peak at cutoffs 2 to 5 (tests/unit/
 * test_deposit_random.c, test_ring_points); 16 points left 5e-12 at cutoff 3 and 7.8e-9 at 5. */
enum { ARC_NODES = 32 };
typedef struct arc_node {
    double w, sin, cos;
} arc_node;
static arc_node arc_nodes[ARC_NODES];
static pthread_once_t arc_once = PTHREAD_ONCE_INIT;

static void arc_setup(void)
{
    for (int n = 0; n < ARC_NODES; n++) {
        double th, w;
        gl_node(gl32_x, gl32_w, ARC_NODES, n, 0.0, 0.5 * M_PI, &th, &w);
        arc_nodes[n] = (arc_node){w, sin(th), cos(th)};
    }
}

static const arc_node *arc_rule(void)
{
    pthread_once(&arc_once, arc_setup);
    return arc_nodes;
}

/* The kernel (dims 3) or its 2-D marginal (dims 2) at distance^2 D2, and its
 * radial derivative divided by D. */
static double radial_kernel(const mimas_weight *wt, int dims, double D2, double *gfac)
{
    if (dims == 2)
        return marginal_radial(wt, 2, D2, gfac);
    *gfac = 0.0;
    if (D2 >= wt->reach2)
        return 0.0;
    if (wt->kind == MIMAS_WEIGHT_LUCY) {
        double d[3] = {sqrt(D2), 0, 0}, g[3];
        double v = lucy_phi_grad(wt, d, g);
        *gfac = d[0] > 0 ? g[0] / d[0] : -12.0 * wt->coef / (wt->w * wt->w);
        return v;
    }
    double e = wt->coef * exp(-D2 * wt->inv2w2);
    *gfac = -2.0 * wt->inv2w2 * e;
    return e - wt->coef * wt->shift;
}

/* The cut ring of the plain or shifted Gaussian by the binomial series (docs/fields.md,
 * "Cylindrical grids without phi cells"): with u = sin(t/2), u_m = sin(t_m/2), y = u_m^2,
 * a = 2 r rho/w^2 and X = (R^2 - D0^2)/2w^2 = a y, (1 - u^2)^{-1/2} = sum_n c_n u^{2n} gives
 *   I_m = int_0^tm e^{-D^2/2w^2} u^{2m} dt = u_m y^m sum_n c_n y^n T_{n+m},
 *   T_n = 2 E int_0^1 e^{-X s^2} s^{2n} ds = tail M_{n+1/2}(X),
 * E = e^{-D0^2/2w^2} = tail e^X, M_s(X) = e^X X^{-s} gamma(s, X) = sum_k X^k/(s (s+1)..(s+k)).
 * The terms fall like c_n y^n (T_n <= T_0): N + 1 of them leave < 1e-17 relative.
 * Upwards, T_{n+1} = ((n + 1/2) T_n - tail)/X loses (n + 1/2)/X per step, but each term
 * has a factor y = X/a: while a >= 4 (n + 2) the loss stays below a few ulp of the sum
 * (in U_n = X^n T_n there is no division); T_0 = tail M_{1/2}(X) from its table (beyond
 * it E sqrt(pi) erf(sqrt X)/sqrt X).
 * Nearer the axis, T_{N+1} by its series and T_n = (tail + X T_{n+1})/(n + 1/2)
 * downwards (stable).  Returns 0 where it does not apply (y > 1/2, or a series for
 * T_{N+1} longer than the table of 1/(j + 1/2), X > ~100).  I_1 (for the gradient) only
 * with_grad: I_0 is the same either way. */
static int gauss_ring_series(const mimas_weight *wt, double D02, double X, double a, double y,
                             int with_grad, double I[2])
{
    double tail = wt->tail, eps = 1e-17 * (1.0 - y), s0 = 0.0, s1 = 0.0;
    if (!(y <= 0.5) || !(X > 0))
        return 0;
    /* upwards while a >= 4 (n + 2), to the first y^n below eps, in U_n = X^n T_n:
     * U_{n+1} = (n + 1/2) U_n - tail X^n, and y^n T_n = U_n / a^n */
    double U = X <= RING_XMAX ? tail * ring_m_half_at(X)
                              : exp(-D02 * wt->inv2w2) * sqrt(M_PI) * erf(sqrt(X)) / sqrt(X);
    double ia = 1.0 / a, ian = 1.0, xn = tail, yn = 1.0;
    for (int n = 0; 4.0 * (n + 2) <= a; n++) {
        double next = (n + 0.5) * U - xn;
        s0 += ring_binom[n] * ian * U;
        ian *= ia;
        if (with_grad)
            s1 += ring_binom[n] * ian * next;
        U = next;
        xn *= X;
        yn *= y;
        if (yn <= eps) {
            I[0] = sqrt(y) * s0;
            I[1] = sqrt(y) * s1;
            return 1;
        }
    }
    s0 = s1 = 0.0;
    int N = 0;
    for (double p = y; p > eps; p *= y)
        N++;
    /* T_{N+1}: its series, to the last term below 1e-17 of the sum beyond k = X */
    double term = ring_inv_half[N + 1], T = term;
    int j = N + 2;
    for (; j < RING_NH && (term > 1e-17 * T || j < N + 1 + X); j++) {
        term *= X * ring_inv_half[j];
        T += term;
    }
    if (j == RING_NH)
        return 0;
    T *= tail;
    for (int n = N; n >= 0; n--) {
        double Tn = (tail + X * T) * ring_inv_half[n];
        if (with_grad)
            s1 = s1 * y + ring_binom[n] * T;
        s0 = s0 * y + ring_binom[n] * Tn;
        T = Tn;
    }
    I[0] = sqrt(y) * s0;
    I[1] = sqrt(y) * y * s1;
    return 1;
}

/* The plain Gaussian is coef tail (not 0) at a cut arc's end t_m (sin^2(t_m/2) = um2):
 * its average's gradient has + f(R) dt_m/dr (and d/ddz) besides the integral's. */
static void arc_end_grad(const mimas_weight *wt, int dims, double um2, double r, double rho,
                         double dz, double grad[2])
{
    double fR = dims == 3 && wt->kind != MIMAS_WEIGHT_LUCY ? wt->coef * (wt->tail - wt->shift)
                                                            : 0.0;
    double sin_tm = 2.0 * sqrt(um2 * (1.0 - um2)), cos_tm = 1.0 - 2.0 * um2;
    if (fR != 0.0 && sin_tm > 0) {
        grad[0] += fR * (-(r - rho * cos_tm) / (r * rho * sin_tm)) / M_PI;
        grad[1] += fR * (-dz / (r * rho * sin_tm)) / M_PI;
    }
}

int mimas_gauss_ring_short(const mimas_weight *wt, double r, double rho, double dz, double D02,
                           double *v, double grad[2])
{
    double rr = 4.0 * r * rho, R2 = wt->reach2, um2 = (R2 - D02) / rr, I[2];
    if (!(um2 <= 0.5) ||
        !gauss_ring_series(wt, D02, (R2 - D02) * wt->inv2w2, rr * wt->inv2w2, um2, grad != NULL,
                           I))
        return 0;
    /* (coef/pi) (I_0 - shift t_m); d/dr of D^2 is 2 (r - rho) + 4 rho u^2 */
    *v = wt->coef / M_PI * I[0];
    if (wt->shift > 0)
        *v -= wt->coef / M_PI * wt->shift * 2.0 * asin(sqrt(um2));
    if (grad) {
        double k = -wt->coef * wt->inv2w2 / M_PI;
        grad[0] = k * (2.0 * (r - rho) * I[0] + 4.0 * rho * I[1]);
        grad[1] = k * 2.0 * dz * I[0];
        arc_end_grad(wt, 3, um2, r, rho, dz, grad);
    }
    return 1;
}

double mimas_kernel_ring(const mimas_weight *wt, int dims, double r, double rho, double dz,
                         double grad[2])
{
    if (dims == 2)
        dz = 0.0;
    double R2 = wt->reach2, D02 = (r - rho) * (r - rho) + dz * dz, rr = 4.0 * r * rho;
    if (grad)
        grad[0] = grad[1] = 0.0;
    if (D02 >= R2)
        return 0.0;
    double um2 = rr > 0 ? (R2 - D02) / rr : INFINITY; /* sin^2(tm/2) */
    int full = um2 >= 1.0;
    if (full && dims == 3 && wt->kind != MIMAS_WEIGHT_LUCY) {
        /* (1/pi) int_0^pi e^{-D^2/2w^2} dt = e^{-D0^2/2w^2} I0_scaled(r rho/w^2) */
        double k = r * rho * 2.0 * wt->inv2w2, w2 = 0.5 / wt->inv2w2;
        double e = wt->coef * exp(-D02 * wt->inv2w2);
        double i0 = gsl_sf_bessel_I0_scaled(k);
        if (grad) {
            double i1 = gsl_sf_bessel_I1_scaled(k);
            grad[0] = e * (-(r - rho) / w2 * i0 + rho / w2 * (i1 - i0));
            grad[1] = e * (-dz / w2) * i0;
        }
        return e * i0 - wt->coef * wt->shift;
    }
    double v;
    if (dims == 3 && wt->kind != MIMAS_WEIGHT_LUCY && um2 <= 0.5 &&
        mimas_gauss_ring_short(wt, r, rho, dz, D02, &v, grad))
        return v;
    /* (1/pi) int_0^tm k(D(t)) dt, D^2 = D0^2 + 4 r rho sin^2(t/2): in u = sin(t/2) =
     * um sin(theta) while the arc is short (the Jacobian 2/sqrt(1 - u^2) stays smooth),
     * else in t = tm sin(theta); both make a square-root edge of the marginal smooth; the
     * rule of ARC_NODES points (arc_rule) */
    int in_u = um2 <= 0.81;
    double um = in_u ? sqrt(um2) : 0.0, tm = full ? M_PI : (in_u ? 0.0 : 2.0 * asin(sqrt(um2)));
    double sum = 0.0, gr = 0.0, gz = 0.0;
    const arc_node *nodes = arc_rule();
    for (int n = 0; n < ARC_NODES; n++) {
        double wgt = nodes[n].w, u, jac;
        if (in_u) {
            u = um * nodes[n].sin;
            jac = 2.0 * um * nodes[n].cos / sqrt(1.0 - u * u);
        } else {
            u = sin(0.5 * tm * nodes[n].sin);
            jac = tm * nodes[n].cos;
        }
        double D2 = D02 + rr * u * u, gfac;
        double f = radial_kernel(wt, dims, fmin(D2, R2 * (1 - 1e-16)), &gfac);
        sum += wgt * jac * f;
        if (grad) {
            /* dD/dr = (r - rho cos t)/D, cos t = 1 - 2 u^2; dD/ddz = dz/D (gfac = f'/D) */
            gr += wgt * jac * gfac * (r - rho + 2.0 * rho * u * u);
            gz += wgt * jac * gfac * dz;
        }
    }
    if (grad) {
        grad[0] = gr / M_PI;
        grad[1] = gz / M_PI;
        if (!full)
            arc_end_grad(wt, dims, um2, r, rho, dz, grad);
    }
    return sum / M_PI;
}
