/* Coarse-graining kernels: normalisation, gradients, line integrals,
 * marginals and azimuthal averages against independent numerical
 * integration (GSL's adaptive quadrature of the 3-D kernel written out
 * here, not the library's). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "deposit.h"
#include "ring_branch_ref.h"
#include "weight.h"

/* ---- the 3-D kernels, written out independently ---- */

static double C_W, C_CUT, C_COEF, C_SHIFT;
static int C_LUCY;

/* Sets the reference kernel: the Gaussian e^{-r^2/2w^2} (minus its value at the cutoff
 * when shifted), normalised here by GSL quadrature of 4 pi r^2 phi, or Lucy's. */
static double ref_raw(double r)
{
    if (C_LUCY) {
        double q = r / C_W;
        return q < 1 ? (1 + 3 * q) * pow(1 - q, 3) : 0.0;
    }
    return r < C_CUT * C_W ? exp(-r * r / (2 * C_W * C_W)) - C_SHIFT : 0.0;
}

static double shell(double r, void *p)
{
    (void)p;
    return 4 * M_PI * r * r * ref_raw(r);
}

static double integrate(gsl_function *F, double a, double b)
{
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    double v, e;
    gsl_integration_qag(F, a, b, 1e-15, 1e-13, 1000, 6, ws, &v, &e);
    gsl_integration_workspace_free(ws);
    return v;
}

static void ref_set(const mimas_weight *wt)
{
    C_W = wt->w;
    C_LUCY = wt->kind == MIMAS_WEIGHT_LUCY;
    C_CUT = C_LUCY ? 1.0 : wt->cutoff;
    C_SHIFT = (!C_LUCY && wt->shifted) ? exp(-0.5 * C_CUT * C_CUT) : 0.0;
    C_COEF = 1.0;
    gsl_function F = {shell, NULL};
    C_COEF = 1.0 / integrate(&F, 0, C_CUT * C_W);
}

static double ref_phi(double r)
{
    return C_COEF * ref_raw(r);
}

static double R_REACH(void)
{
    return C_CUT * C_W;
}

static mimas_weight parse(const char *spec)
{
    mimas_weight wt;
    mimas_error err;
    assert_int_equal(mimas_weight_parse(&wt, spec, &err), MIMAS_OK);
    ref_set(&wt);
    return wt;
}

/* ---- the 3-D kernel and its line integral ---- */

typedef struct line_ctx {
    double d[3], b[3];
} line_ctx;

static double along(double s, void *p)
{
    line_ctx *c = p;
    double r2 = 0;
    for (int k = 0; k < 3; k++)
        r2 += (c->d[k] - s * c->b[k]) * (c->d[k] - s * c->b[k]);
    return ref_phi(sqrt(r2));
}

/* int_0^1 of f(s) with breakpoints where |d - s b| = R (the test's own quadratic) */
static double integrate_segment(double (*f)(double, void *), void *ctx, const double *d,
                                const double *b, int n)
{
    double a = 0, c = 0, e = 0, R = R_REACH();
    for (int k = 0; k < n; k++) {
        a += b[k] * b[k];
        c += d[k] * b[k];
        e += d[k] * d[k];
    }
    double pts[4] = {0, 0, 0, 1};
    int np = 1;
    double disc = c * c - a * (e - R * R);
    if (disc > 0) {
        double s1 = (c - sqrt(disc)) / a, s2 = (c + sqrt(disc)) / a;
        if (s1 > 0 && s1 < 1)
            pts[np++] = s1;
        if (s2 > 0 && s2 < 1)
            pts[np++] = s2;
    }
    pts[np++] = 1;
    gsl_function F = {f, ctx};
    double total = 0;
    for (int k = 0; k + 1 < np; k++)
        total += integrate(&F, pts[k], pts[k + 1]);
    return total;
}

static void check_kernel(const char *spec)
{
    mimas_weight wt = parse(spec);
    double w = wt.w;
    /* the library's kernel is the one written out here, normalised to 1 */
    const double rs[4] = {0.0, 0.37, 1.1, 2.6};
    for (int k = 0; k < 4; k++) {
        double d[3] = {rs[k] * C_W * 0.6, rs[k] * C_W * 0.8, 0}, g[3];
        assert_close(mimas_kernel_phi_grad(&wt, d, g), ref_phi(rs[k] * C_W),
                     1e-13 * ref_phi(0));
    }
    /* gradient = central differences of phi (inside the support) */
    double d[3] = {0.31 * w, -0.22 * w, 0.5 * w}, g[3], gp[3], h = 1e-6 * w;
    mimas_kernel_phi_grad(&wt, d, g);
    for (int k = 0; k < 3; k++) {
        double dp[3] = {d[0], d[1], d[2]}, dm[3] = {d[0], d[1], d[2]};
        dp[k] += h;
        dm[k] -= h;
        double fd = (mimas_kernel_phi_grad(&wt, dp, gp) - mimas_kernel_phi_grad(&wt, dm, gp)) /
                    (2 * h);
        assert_close(g[k], fd, 1e-6 * fabs(fd) + 1e-9 * wt.coef / w);
    }
    /* line integral = adaptive quadrature along the segment, for segments crossing
     * the support, ending inside it, passing through the point, and short ones */
    const double segs[5][6] = {{-2, 0.3, 0.1, 2.5, -0.2, 0.4},
                               {0.1, 0.2, 0.3, 0.9, 0.1, -0.4},
                               {-0.5, 0, 0, 0.5, 0, 0},
                               {2.2, 1.1, 0.4, 2.25, 1.08, 0.41},
                               {-1.4, 2.5, 0.2, 1.4, 2.6, -0.1}};
    for (int s = 0; s < 5; s++) {
        line_ctx c;
        for (int k = 0; k < 3; k++) {
            double a = segs[s][k] * C_W, b = segs[s][3 + k] * C_W;
            c.b[k] = b - a;
            c.d[k] = -a; /* field point at the origin: d = r - r_j */
        }
        double psi = mimas_kernel_line(&wt, c.d, c.b);
        double ref = integrate_segment(along, &c, c.d, c.b, 3);
        assert_close(psi, ref, 1e-12 * ref_phi(0));
    }
}

static void test_gauss(void **state)
{
    (void)state;
    check_kernel("gauss:w=0.002");
    check_kernel("gauss:w=0.5,cutoff=2");
    check_kernel("gauss:w=0.002,shift");
    check_kernel("gauss:w=0.5,cutoff=2.5,shift");
}

static void test_lucy(void **state)
{
    (void)state;
    check_kernel("lucy:c=0.003");
}

/* The plain cut's jump carries kappa = phi(R) 4/3 pi R^3 of a linear gradient:
 * int_ball x_b d_a phi dV (inside the support only) = -(1 - kappa) delta_ab,
 * checked by quadrature of the radial integrand (the shifted kernel: kappa = 0). */
static double moment(double r, void *p)
{
    mimas_weight *wt = p;
    double d[3] = {r, 0, 0}, g[3];
    mimas_kernel_phi_grad(wt, d, g);
    /* int x_a d_a phi over the ball, one component a: int 4 pi r^2 (r/3) dphi/dr dr */
    return 4 * M_PI * r * r * r / 3.0 * g[0];
}

static void test_kappa(void **state)
{
    (void)state;
    const char *specs[2] = {"gauss:w=0.002", "gauss:w=0.002,shift"};
    for (int k = 0; k < 2; k++) {
        mimas_weight wt = parse(specs[k]);
        gsl_function F = {moment, &wt};
        double m = integrate(&F, 0, R_REACH());
        assert_close(m, -(1.0 - wt.kappa), 1e-12);
        if (k == 1)
            assert_close(wt.kappa, 0.0, 0.0);
        else
            assert_true(wt.kappa > 0.08 && wt.kappa < 0.083); /* 8.2 % at C = 3 */
    }
}

/* ---- marginals ---- */

static double MZ, MRHO;

static double disc_integrand(double rho, void *p)
{
    (void)p;
    return 2 * M_PI * rho * ref_phi(sqrt(MZ * MZ + rho * rho));
}

static double chord_integrand(double y, void *p)
{
    (void)p;
    return 2 * ref_phi(sqrt(MRHO * MRHO + y * y));
}

/* the reference marginals: the 3-D kernel integrated by GSL */
static double ref_marginal(int dims, const double *d)
{
    double R = R_REACH();
    if (dims == 1) {
        MZ = d[0];
        if (fabs(MZ) >= R)
            return 0.0;
        gsl_function F = {disc_integrand, NULL};
        return integrate(&F, 0, sqrt(R * R - MZ * MZ));
    }
    MRHO = hypot(d[0], d[1]);
    if (MRHO >= R)
        return 0.0;
    gsl_function F = {chord_integrand, NULL};
    return integrate(&F, 0, sqrt(R * R - MRHO * MRHO));
}

typedef struct mline_ctx {
    int dims;
    double d[2], b[2];
} mline_ctx;

static double along_marginal(double s, void *p)
{
    mline_ctx *c = p;
    double q[2];
    for (int k = 0; k < c->dims; k++)
        q[k] = c->d[k] - s * c->b[k];
    return ref_marginal(c->dims, q);
}

static void check_marginals(const char *spec)
{
    mimas_weight wt = parse(spec);
    double w = wt.w, peak = ref_phi(0) * w * w;
    const double pts[6][2] = {{0, 0}, {0.3, 0.1}, {1.2, -0.7}, {-2.1, 1.5}, {2.95, 0.2},
                              {0.05, 2.9}};
    for (int dims = 1; dims <= 2; dims++)
        for (int k = 0; k < 6; k++) {
            double d[2] = {pts[k][0] * C_W, pts[k][1] * C_W}, g[2];
            if (dims == 1 && fabs(d[0]) >= R_REACH())
                continue;
            double v = mimas_kernel_marginal(&wt, dims, d, g);
            assert_close(v, ref_marginal(dims, d), 1e-12 * peak / (dims == 1 ? 1 : w));
            /* gradient by central differences */
            for (int m = 0; m < dims; m++) {
                double h = 1e-6 * C_W, dp[2] = {d[0], d[1]}, dm[2] = {d[0], d[1]}, gg[2];
                dp[m] += h;
                dm[m] -= h;
                double fd = (mimas_kernel_marginal(&wt, dims, dp, gg) -
                             mimas_kernel_marginal(&wt, dims, dm, gg)) / (2 * h);
                assert_close(g[m], fd, 1e-5 * fabs(fd) + 1e-8 * peak / (w * w));
            }
        }
    /* the marginals integrate to 1 */
    for (int dims = 1; dims <= 2; dims++) {
        /* 1-D: int over z; 2-D: int 2 pi rho drho */
        double total = 0;
        const int n = 20000;
        for (int k = 0; k < n; k++) {
            double x = (k + 0.5) / n * R_REACH(), d[2] = {x, 0};
            double v = mimas_kernel_marginal(&wt, dims, d, NULL);
            total += (dims == 1 ? 2.0 : 2 * M_PI * x) * v * R_REACH() / n;
        }
        assert_close(total, 1.0, 2e-6);
    }
    /* marginal line integrals = adaptive quadrature of the reference marginal */
    const double segs[4][4] = {{-2, 0.3, 2.5, -0.2}, {0.1, 0.2, 0.9, 0.1}, {-0.5, 0, 0.5, 0},
                               {2.2, 1.1, 2.25, 1.08}};
    for (int dims = 1; dims <= 2; dims++)
        for (int s = 0; s < 4; s++) {
            mline_ctx c = {dims, {0, 0}, {0, 0}};
            for (int k = 0; k < dims; k++) {
                double a = segs[s][k] * C_W, b = segs[s][2 + k] * C_W;
                c.b[k] = b - a;
                c.d[k] = -a;
            }
            double psi = mimas_kernel_marginal_line(&wt, dims, c.d, c.b);
            double ref = integrate_segment(along_marginal, &c, c.d, c.b, dims);
            /* Lucy: its marginal's rho^4 log rho centre limits the rule (see test_ring) */
            assert_close(psi, ref, (C_LUCY ? 1e-9 : 1e-11) * peak / (dims == 1 ? 1 : w));
        }
}

static void test_marginals(void **state)
{
    (void)state;
    check_marginals("gauss:w=0.002");
    check_marginals("gauss:w=0.002,shift");
    check_marginals("gauss:w=0.5,cutoff=2");
    check_marginals("lucy:c=0.003");
}

/* ---- azimuthal averages ---- */

static double RR, RHO, RDZ;
static int RDIMS;

static double ring_integrand(double t, void *p)
{
    (void)p;
    double D2 = RR * RR + RHO * RHO - 2 * RR * RHO * cos(t);
    if (RDIMS == 3)
        return ref_phi(sqrt(D2 + RDZ * RDZ));
    double d[2] = {sqrt(D2), 0};
    return ref_marginal(2, d);
}

/* (1/pi) int_0^pi with a breakpoint where D reaches R */
static double ref_ring(int dims, double r, double rho, double dz)
{
    RR = r, RHO = rho, RDZ = dims == 3 ? dz : 0, RDIMS = dims;
    double R = R_REACH(), base = r * r + rho * rho + RDZ * RDZ;
    double k = r * rho > 0 ? (base - R * R) / (2 * r * rho) : (base < R * R ? -2 : 2);
    double tm = k <= -1 ? M_PI : (k >= 1 ? 0 : acos(k));
    gsl_function F = {ring_integrand, NULL};
    double v = tm > 0 ? integrate(&F, 0, tm) : 0.0;
    return v / M_PI;
}

static void check_ring(const char *spec)
{
    mimas_weight wt = parse(spec);
    double w = wt.w, peak = ref_phi(0);
    /* far from the axis (a short arc), near it (a long arc), the full ring, the axis */
    const double cases[7][3] = {{20, 20.4, 0.3}, {20, 18.5, -1.9}, {2.5, 1.2, 0.4},
                                {1.0, 0.9, 0.2}, {0.6, 0.5, 0.1}, {0, 1.3, 0.5},
                                {2.4, 0, 1.1}};
    for (int dims = 2; dims <= 3; dims++)
        for (int k = 0; k < 7; k++) {
            double r = cases[k][0] * C_W, rho = cases[k][1] * C_W, dz = cases[k][2] * C_W;
            double g[2];
            double v = mimas_kernel_ring(&wt, dims, r, rho, dz, g);
            double scale = dims == 3 ? peak : peak * w;
            /* Lucy's kernel has an r^3 term (its marginal rho^4 log rho) at the
             * centre: where the ring passes near it the rule converges more slowly
             * (2e-10 at worst here) */
            double tol = C_LUCY ? 1e-9 : 1e-12;
            assert_close(v, ref_ring(dims, r, rho, dz), tol * scale);
            if (!(r > 0))
                continue;
            double h = 1e-6 * C_W, gg[2];
            double fr = (mimas_kernel_ring(&wt, dims, r + h, rho, dz, gg) -
                         mimas_kernel_ring(&wt, dims, r - h, rho, dz, gg)) / (2 * h);
            assert_close(g[0], fr, 1e-5 * fabs(fr) + 1e-7 * scale / w);
            if (dims == 3) {
                double fz = (mimas_kernel_ring(&wt, dims, r, rho, dz + h, gg) -
                             mimas_kernel_ring(&wt, dims, r, rho, dz - h, gg)) / (2 * h);
                assert_close(g[1], fz, 1e-5 * fabs(fz) + 1e-7 * scale / w);
            }
        }
}

static void test_ring(void **state)
{
    (void)state;
    check_ring("gauss:w=0.002");
    check_ring("gauss:w=0.002,shift");
    check_ring("lucy:c=0.004");
}

/* d/dr and d/ddz of the 3-D kernel's value on the ring (Gaussian): -phi_raw (r - rho cos t)/w^2
 * and -phi_raw dz/w^2, phi_raw the unshifted part */
static int RGRAD;
static double ring_grad_integrand(double t, void *p)
{
    (void)p;
    double D2 = RR * RR + RHO * RHO - 2 * RR * RHO * cos(t) + RDZ * RDZ;
    double e = C_COEF * exp(-D2 / (2 * C_W * C_W)) / (C_W * C_W);
    return -e * (RGRAD == 0 ? RR - RHO * cos(t) : RDZ);
}

/* The cut ring's gradient written out: the integral of the derivative up to
 * tm = acos(k), k = (r^2 + rho^2 + dz^2 - R^2)/(2 r rho), plus phi(R) dtm/dr (dtm/ddz),
 * dtm = -dk / sqrt(1 - k^2), dk/dr = 1/rho - k/r, dk/ddz = dz/(r rho); over pi. */
static void ref_ring_grad(double r, double rho, double dz, double g[2])
{
    RR = r, RHO = rho, RDZ = dz, RDIMS = 3;
    double R = R_REACH(), k = (r * r + rho * rho + dz * dz - R * R) / (2 * r * rho);
    double tm = acos(k), fR = C_COEF * (exp(-0.5 * C_CUT * C_CUT) - C_SHIFT);
    double dk[2] = {1 / rho - k / r, dz / (r * rho)};
    gsl_function F = {ring_grad_integrand, NULL};
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    for (RGRAD = 0; RGRAD < 2; RGRAD++) {
        /* the derivative may change sign on the arc: an absolute tolerance */
        double v, e;
        int rc = gsl_integration_qags(&F, 0, tm, 1e-14 * C_COEF / (C_W * C_W), 1e-13, 1000, ws,
                                      &v, &e);
        assert_int_equal(rc, GSL_SUCCESS);
        g[RGRAD] = (v + fR * -dk[RGRAD] / sqrt(1 - k * k)) / M_PI;
    }
    gsl_integration_workspace_free(ws);
}

/* The Gaussian's cut ring (the binomial series: short arcs, sin^2(tm/2) <= 1/2) at
 * random points against adaptive quadrature of the 3-D kernel over the arc: the
 * value within tol = 1e-14 of the kernel's peak, the gradient within 10 tol peak/w (the
 * reference's own tolerance is 1e-13 relative); both recurrences are hit (a from
 * 0.5 to 2000). */
static void check_ring_series(const char *spec, unsigned seed, double tol)
{
    mimas_weight wt = parse(spec);
    double w = wt.w, R = R_REACH(), peak = ref_phi(0), worst = 0, gworst = 0;
    srand(seed);
    int n_short = 0;
    for (int k = 0; k < 400; k++) {
        double u1 = rand() / (double)RAND_MAX, u2 = rand() / (double)RAND_MAX,
               u3 = rand() / (double)RAND_MAX, u4 = rand() / (double)RAND_MAX;
        /* r from 0.5 w to 30 w (log-uniform), the point within the support about the ring */
        double r = 0.5 * w * pow(60.0, u1), D0 = R * sqrt(u2), ang = 2 * M_PI * u3;
        double rho = r + D0 * cos(ang), dz = D0 * sin(ang);
        if (!(rho > 0))
            continue;
        double um2 = (R * R - D0 * D0) / (4 * r * rho);
        if (!(um2 <= 0.5) || u4 < 0) /* only the series' range */
            continue;
        n_short++;
        double g[2], gr[2];
        double v = mimas_kernel_ring(&wt, 3, r, rho, dz, g);
        double e = fabs(v - ref_ring(3, r, rho, dz)) / peak;
        worst = fmax(worst, e);
        if (!(e < tol))
            print_message("# value r %g rho %g dz %g: %.17g vs %.17g\n", r / w, rho / w, dz / w,
                          v, ref_ring(3, r, rho, dz));
        assert_true(e < tol);
        ref_ring_grad(r, rho, dz, gr);
        for (int m = 0; m < 2; m++) {
            /* near the support's edge the arc-end term ~ 1/sqrt(R^2 - D0^2) inherits the
             * rounding of R^2 - D0^2 (in both computations): eps R^2/(R^2 - D0^2) relative */
            double cond = 4 * DBL_EPSILON * fabs(gr[m]) * R * R / (R * R - D0 * D0);
            double ge = fmax(0.0, fabs(g[m] - gr[m]) - cond) / (peak / w);
            gworst = fmax(gworst, ge);
            if (!(ge < 10 * tol))
                print_message("# grad %d r %g rho %g dz %g: %.17g vs %.17g\n", m, r / w, rho / w,
                              dz / w, g[m], gr[m]);
            assert_true(ge < 10 * tol);
        }
    }
    assert_true(n_short > 150);
    print_message("# %s: %d short arcs, worst value %.2g peak, gradient %.2g peak/w\n", spec,
                  n_short, worst, gworst);
}

static void test_ring_series(void **state)
{
    (void)state;
    check_ring_series("gauss:w=0.002", 1, 1e-14);
    check_ring_series("gauss:w=0.002,shift", 2, 1e-14);
    check_ring_series("gauss:w=0.5,cutoff=2", 3, 1e-14);
    check_ring_series("gauss:w=0.5,cutoff=5", 4, 1e-14);
    check_ring_series("gauss:w=0.5,cutoff=7", 5, 1e-14); /* X beyond the table: erf */
}

/* The line integral along a + s (b - a), s in [0, 1], of the azimuthal average at the ring
 * (r, z) (SEG_DIMS 2: of the kernel's marginal over z, z unused): adaptive on the pieces
 * between the average's edges, where the ring's nearest or farthest point is at the reach
 * (ring_branch_ref.h, 2048 intervals). */
static double SEG_A[3], SEG_B[3], SEG_R, SEG_Z;
static int SEG_DIMS = 3;

static double seg_rho(double s)
{
    return hypot(SEG_A[0] + s * SEG_B[0], SEG_A[1] + s * SEG_B[1]);
}

static double seg_integrand(double s, void *p)
{
    (void)p;
    return ref_ring(SEG_DIMS, SEG_R, seg_rho(s), SEG_Z - SEG_A[2] - s * SEG_B[2]);
}

static double seg_edge(double s, double sign, void *p)
{
    (void)p;
    double dz = SEG_DIMS == 3 ? SEG_Z - SEG_A[2] - s * SEG_B[2] : 0.0;
    return hypot(seg_rho(s) + sign * SEG_R, dz) - R_REACH();
}

static double ref_ring_segment(const double a[3], const double b[3], double r, double z)
{
    for (int m = 0; m < 3; m++) {
        SEG_A[m] = a[m];
        SEG_B[m] = b[m] - a[m];
    }
    SEG_R = r, SEG_Z = z;
    return ring_branch_integral(seg_integrand, seg_edge, NULL, 2048, 1e-14 * ref_phi(0), NULL);
}

/* A contact's branch on an r-z grid: each cell's weight is the integral along the branch of
 * the azimuthal average (a Gauss-Legendre rule, split at the average's singular points,
 * docs/fields.md), here the adaptive integral above of the adaptive average at each point:
 * within 1e-8 of the kernel's peak (far from the axis, near it and across it; the plain and
 * shifted Gaussian, cutoffs 3 and 5, and Lucy). */
static void check_ring_segments(const char *spec, int dims)
{
    mimas_weight wt = parse(spec);
    mimas_grid g;
    mimas_error err;
    /* dims 2: an r-only grid, the kernel's marginal over z divided by the box's height */
    assert_int_equal(mimas_grid_parse(&g, dims == 3 ? "r=0:0.03:30,z=0:0.02:20" : "r=0:0.03:30",
                                      NULL, &err),
                     MIMAS_OK);
    SEG_DIMS = dims;
    mimas_box box = {{-0.05, -0.05, -0.01}, {0.05, 0.05, 0.03}, 0, 0, 0, {0, 0, 0}};
    mimas_deposit dp;
    if (dims == 2) { /* z over the box, as average does; refused before (no height) */
        assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_EUSAGE);
        assert_non_null(strstr(err.msg, "the grid's z (not gridded) spans 0 to 0, no extent"));
        mimas_grid_fit_box(&g, &box);
    }
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    /* from, to (mm): far, middle, near and across the axis; 0.4, 1.5 and 3 w long */
    const double seg[7][6] = {{20, 3, 9, 20.3, 3.2, 9.1},  {15, 14, 8, 16.1, 14.2, 8.7},
                              {4, 3, 10, 5.5, 4.6, 11},   {2, 0.5, 7, 2.3, 0.6, 7.2},
                              {1, 0.3, 9, -0.4, -0.5, 9.8}, {0.5, 0.1, 12, 1.9, -1.3, 13.1},
                              {25, 8, 4, 27.1, 6.2, 4.5}};
    const double origin[2] = {0, 0}, height = 0.04; /* the box's, below */
    double peak = dims == 3 ? ref_phi(0) : ref_marginal(2, origin), worst = 0, far = 0;
    size_t nc = mimas_grid_cells(&g);
    double *dense = calloc(nc, sizeof *dense);
    mimas_weights ws = {0};
    for (int k = 0; k < 7; k++) {
        double a[3], b[3];
        for (int m = 0; m < 3; m++) {
            a[m] = seg[k][m] * 1e-3;
            b[m] = seg[k][3 + m] * 1e-3;
        }
        ws.n = 0;
        assert_int_equal(mimas_deposit_segment(&dp, a, b, &ws), MIMAS_OK);
        memset(dense, 0, nc * sizeof *dense);
        for (size_t e = 0; e < ws.n; e++)
            dense[ws.cell[e]] += ws.w[e];
        double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                          (b[2] - a[2]) * (b[2] - a[2]));
        for (int i = 0; i < 30; i++)
            for (int j = 0; j < (dims == 3 ? 20 : 1); j++) {
                double r = (i + 0.5) * 1e-3, z = (j + 0.5) * 1e-3;
                int idx[3] = {i, 0, j};
                double got = dense[mimas_grid_index(&g, idx)] * (dims == 3 ? 1.0 : height);
                /* out of reach of the whole branch: nothing */
                if (hypot(hypot(a[0], a[1]) - r, dims == 3 ? a[2] - z : 0.0) > R_REACH() + len) {
                    assert_true(got == 0.0);
                    continue;
                }
                double ref = ref_ring_segment(a, b, r, z), e = fabs(got - ref) / peak;
                worst = fmax(worst, e);
                if (!(e < 1e-8))
                    print_message("# segment %d cell r %d z %d: %.17g vs %.17g\n", k, i, j, got,
                                  ref);
                assert_true(e < 1e-8);
                if (k == 0 || k == 1 || k == 6)
                    far = fmax(far, e);
            }
    }
    print_message("# %s: branches on %s, worst %.2g peak, far from the axis %.2g\n", spec,
                  dims == 3 ? "r-z" : "r", worst, far);
    mimas_weights_free(&ws);
    free(dense);
}

static void test_ring_segments(void **state)
{
    (void)state;
    gsl_set_error_handler_off(); /* the adaptive references near their rounding */
    check_ring_segments("gauss:w=0.001", 3);
    check_ring_segments("gauss:w=0.001,shift", 3);
    /* the 16-point rule's long arcs reach 4 mm out */
    check_ring_segments("gauss:w=0.001,cutoff=5", 3);
    check_ring_segments("lucy:c=0.003", 3);
    /* r-only grids: the marginal's average, whose edges are at |rho -+ r| = R */
    check_ring_segments("gauss:w=0.001", 2);
    check_ring_segments("lucy:c=0.003", 2);
}

/* ---- bins: a branch walked through the cells of a Cartesian grid ---- */

/* The fraction of the segment a-b inside the box [lo, hi] (slab clipping, written out
 * here) */
static double clip_fraction(const double a[3], const double b[3], const double lo[3],
                            const double hi[3])
{
    double t0 = 0, t1 = 1;
    for (int d = 0; d < 3; d++) {
        double l = b[d] - a[d];
        if (l == 0) {
            if (a[d] < lo[d] || a[d] > hi[d])
                return 0;
            continue;
        }
        double u = (lo[d] - a[d]) / l, v = (hi[d] - a[d]) / l;
        t0 = fmax(t0, fmin(u, v));
        t1 = fmin(t1, fmax(u, v));
    }
    return t1 > t0 ? t1 - t0 : 0;
}

/* The weights of a segment on the 26^3 grid over [0, 26 mm]^3 (cells of 1 mm, whose planes
 * lo + k h overshoot the grid's upper bound by rounding: 26 h = 0.026000000000000002), as
 * a dense array times the cell volume */
static void walk_dense(const mimas_deposit *dp, const double a[3], const double b[3],
                       double *dense, size_t nc, mimas_weights *ws)
{
    ws->n = 0;
    assert_int_equal(mimas_deposit_segment(dp, a, b, ws), MIMAS_OK);
    memset(dense, 0, nc * sizeof *dense);
    for (size_t e = 0; e < ws->n; e++)
        dense[ws->cell[e]] += ws->w[e] * dp->cart_volume;
}

/* Each cell holds the fraction of the branch inside it (the cells' bounds from the grid's
 * definition: lo + k h, the last one ending at hi), and only the part on the grid counts:
 * random branches in and across the grid's faces, and two across the upper face, where a
 * cell of the last layer holds exactly the part below it. */
static void test_bins_walk(void **state)
{
    (void)state;
    mimas_weight wt = parse("bins");
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "x=0:0.026:26,y=0:0.026:26,z=0:0.026:26", NULL, &err),
                     MIMAS_OK);
    mimas_box box = {{-0.01, -0.01, -0.01}, {0.04, 0.04, 0.04}, 0, 0, 0, {0, 0, 0}};
    mimas_deposit dp;
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    size_t nc = mimas_grid_cells(&g);
    double *dense = calloc(nc, sizeof *dense), h = 0.026 / 26;
    mimas_weights ws = {0};
    unsigned long long state64 = 12345;
    double worst = 0;
    for (int k = 0; k < 400; k++) {
        double a[3], b[3];
        for (int m = 0; m < 3; m++) {
            state64 = state64 * 6364136223846793005ULL + 1442695040888963407ULL;
            a[m] = -0.002 + 0.030 * (double)(state64 >> 11) / 9007199254740992.0;
            state64 = state64 * 6364136223846793005ULL + 1442695040888963407ULL;
            b[m] = a[m] + (k % 2 ? 0.003 : 0.0012) * ((double)(state64 >> 11) / 9007199254740992.0 - 0.5);
        }
        if (k % 7 == 0)
            b[k % 3] = a[k % 3]; /* in a plane of constant coordinate */
        walk_dense(&dp, a, b, dense, nc, &ws);
        double glo[3] = {0, 0, 0}, ghi[3] = {0.026, 0.026, 0.026}, total = 0;
        for (size_t c = 0; c < nc; c++) {
            int idx[3];
            mimas_grid_unindex(&g, c, idx);
            double lo[3], hi[3];
            for (int m = 0; m < 3; m++) {
                lo[m] = 0 + h * idx[m];
                hi[m] = idx[m] == 25 ? 0.026 : lo[m] + h;
            }
            double f = clip_fraction(a, b, lo, hi);
            worst = fmax(worst, fabs(dense[c] - f));
            assert_true(fabs(dense[c] - f) < 1e-13);
            total += dense[c];
        }
        assert_true(fabs(total - clip_fraction(a, b, glo, ghi)) < 1e-13);
    }
    /* across the upper face z = 0.026: a quarter and 5/7 of the branch on the grid */
    const double across[2][6] = {{0.0105, 0.0105, 0.0255, 0.0105, 0.0105, 0.0275},
                                 {0.0105, 0.0105, 0.0255, 0.0105, 0.0105, 0.0262}};
    const double part[2] = {0.25, 5.0 / 7.0};
    for (int k = 0; k < 2; k++) {
        walk_dense(&dp, across[k], across[k] + 3, dense, nc, &ws);
        int idx[3] = {10, 10, 25};
        assert_close(dense[mimas_grid_index(&g, idx)], part[k], 1e-13);
    }
    /* a position that is not a number lies on no cell (and does not hang the walk) */
    const double nan3[3] = {NAN, 0.01, 0.01}, in3[3] = {0.0105, 0.0105, 0.0105};
    ws.n = 0;
    assert_int_equal(mimas_deposit_segment(&dp, nan3, in3, &ws), MIMAS_OK);
    assert_int_equal(ws.n, 0);
    print_message("# bins walk: 400 branches, worst %.2g of the branch\n", worst);
    mimas_weights_free(&ws);
    free(dense);
}

/* ---- a periodic box narrower than the kernel's reach ---- */

/* The weights of an object summed per cell (times nothing: the kernel's own units) */
static void dense_weights(const mimas_weights *ws, double *dense, size_t nc)
{
    memset(dense, 0, nc * sizeof *dense);
    for (size_t e = 0; e < ws->n; e++)
        dense[ws->cell[e]] += ws->w[e];
}

/* Every cell of a 4^3 grid over a periodic box of 2 mm (orthogonal, then tilted) against
 * the kernel summed over all of the periodic images written out here (shifts by up to 4
 * edge vectors either way: the kernel reaches 3 mm), for particles and branches (one across
 * a face), on the x-y-z grid (the Gaussian's separable deposit, Lucy's cell by cell);
 * before, the images beyond the nearest were missing (5 % of the field of the first spec).
 * A box the kernel reaches across 2.5 times is refused with a message, unless the kernel
 * is integrated along it (a profile). */
static void check_narrow_box(const char *spec, double xy, double xz, double yz)
{
    mimas_weight wt = parse(spec);
    const double L = 0.002, R = R_REACH();
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "x=0:0.002:4,y=0:0.002:4,z=0:0.002:4", NULL, &err),
                     MIMAS_OK);
    mimas_box box = {{0, 0, 0}, {L, L, L}, xy, xz, yz, {1, 1, 1}};
    const double e[3][3] = {{L, 0, 0}, {xy, L, 0}, {xz, yz, L}};
    mimas_deposit dp;
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    size_t nc = mimas_grid_cells(&g);
    double dense[64], peak = ref_phi(0), worst = 0;
    mimas_weights ws = {0};
    /* in fractional coordinates: particles, then branches from, to (one across a face) */
    const double at[4][6] = {{0.15, 0.55, 0.85}, {0.97, 0.03, 0.5},
                             {0.2, 0.3, 0.4, 0.6, 0.45, 0.25}, {0.85, 0.5, 0.55, 1.3, 0.6, 0.45}};
    for (int k = 0; k < 4; k++) {
        double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        for (int q = 0; q < 3; q++)
            for (int m = 0; m < 3; m++) {
                a[m] += at[k][q] * e[q][m];
                b[m] += (k < 2 ? at[k][q] : at[k][3 + q]) * e[q][m];
            }
        ws.n = 0;
        int rc = k < 2 ? mimas_deposit_sphere(&dp, a, 0.0, 0, &ws)
                       : mimas_deposit_segment(&dp, a, b, &ws);
        assert_int_equal(rc, MIMAS_OK);
        dense_weights(&ws, dense, nc);
        for (size_t c = 0; c < nc; c++) {
            double ctr[3], ref = 0;
            mimas_grid_cell_centre(&g, c, ctr);
            for (int i = -4; i <= 4; i++)
                for (int j = -4; j <= 4; j++)
                    for (int l = -4; l <= 4; l++) {
                        line_ctx lc;
                        double r2 = 0;
                        for (int m = 0; m < 3; m++) {
                            lc.d[m] = ctr[m] - a[m] - i * e[0][m] - j * e[1][m] - l * e[2][m];
                            lc.b[m] = b[m] - a[m];
                            r2 += lc.d[m] * lc.d[m];
                        }
                        if (k < 2)
                            ref += ref_phi(sqrt(r2));
                        else if (sqrt(r2) < R + 1e-3) /* the branch is under 1 mm long */
                            ref += integrate_segment(along, &lc, lc.d, lc.b, 3);
                    }
            double err_c = fabs(dense[c] - ref) / peak;
            worst = fmax(worst, err_c);
            if (!(err_c < 1e-12))
                print_message("# object %d cell %zu: %.17g vs %.17g\n", k, c, dense[c], ref);
            assert_true(err_c < 1e-12);
        }
    }
    print_message("# %s in a periodic box of 2/3 of its reach (tilt %g %g %g): worst %.2g of "
                  "the peak\n", spec, xy, xz, yz, worst);
    mimas_weights_free(&ws);
    /* reaching across a 1 mm box three times: refused; along a profile's z only: taken */
    mimas_box thin = {{0, 0, 0}, {0.001, 0.001, 0.01}, 0, 0, 0, {1, 1, 1}};
    assert_int_equal(mimas_grid_parse(&g, "x=0:0.001:2,y=0:0.001:2,z=0:0.01:10", NULL, &err),
                     MIMAS_OK);
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &thin, 0, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "widths along x"));
    assert_int_equal(mimas_grid_parse(&g, "z=0:0.01:10", NULL, &err), MIMAS_OK);
    mimas_grid_fit_box(&g, &thin);
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &thin, 0, &err), MIMAS_OK);
}

/* The same for particles on an r-z grid about the box's z edge that reaches 1.5 widths of
 * the periodic box (4 mm) beyond it: the ring averages of every image (ref_ring) */
static void check_narrow_ring(const char *spec, double tol)
{
    mimas_weight wt = parse(spec);
    const double L = 0.004;
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "r=0:0.006:6,z=0:0.004:4", NULL, &err), MIMAS_OK);
    mimas_box box = {{0, 0, 0}, {L, L, L}, 0, 0, 0, {1, 1, 1}};
    mimas_deposit dp;
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    size_t nc = mimas_grid_cells(&g);
    double dense[24], peak = ref_phi(0), worst = 0;
    mimas_weights ws = {0};
    const double at[2][3] = {{3.7, 0.4, 2.9}, {1.2, 3.1, 0.3}};
    for (int k = 0; k < 2; k++) {
        double a[3] = {at[k][0] * 1e-3, at[k][1] * 1e-3, at[k][2] * 1e-3};
        ws.n = 0;
        assert_int_equal(mimas_deposit_sphere(&dp, a, 0.0, 0, &ws), MIMAS_OK);
        dense_weights(&ws, dense, nc);
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 4; j++) {
                double r = (i + 0.5) * 1e-3, z = (j + 0.5) * 1e-3, ref = 0;
                for (int p = -4; p <= 4; p++)
                    for (int q = -4; q <= 4; q++)
                        for (int l = -2; l <= 2; l++)
                            ref += ref_ring(3, r, hypot(a[0] + p * L, a[1] + q * L),
                                            z - a[2] - l * L);
                int idx[3] = {i, 0, j};
                double e = fabs(dense[mimas_grid_index(&g, idx)] - ref) / peak;
                worst = fmax(worst, e);
                if (!(e < tol))
                    print_message("# particle %d cell r %d z %d: %.17g vs %.17g\n", k, i, j,
                                  dense[mimas_grid_index(&g, idx)], ref);
                assert_true(e < tol);
            }
    }
    print_message("# %s on r-z past a periodic box: worst %.2g of the peak\n", spec, worst);
    mimas_weights_free(&ws);
}

/* Profiles in a tilted periodic box (10 mm, tilts xy 3 mm, xz 2 mm, yz -1 mm): along z the
 * box repeats within the x-y planes, so the z profile is the 1-D marginal summed over the
 * images along z, divided by L_x L_y (ref_marginal), whatever the tilts; along y it is
 * defined when yz = 0 (the edge along z has no y part), checked here by its mass: the
 * profile summed over the cells holds the particle once.  Where an integrated direction's
 * edge has a part along a resolved one the profile is not one period's average (before, an
 * x profile counted three to eight times the mass): refused, and so is a cylindrical grid
 * without z whose box repeats along the axis only with a sideways shift. */
static void check_tilted_profiles(const char *spec)
{
    mimas_weight wt = parse(spec);
    const double L = 0.01;
    mimas_grid g;
    mimas_error err;
    mimas_box box = {{0, 0, 0}, {L, L, L}, 0.003, 0.002, -0.001, {1, 1, 1}};
    assert_int_equal(mimas_grid_parse(&g, "z=0:0.01:20", NULL, &err), MIMAS_OK);
    mimas_grid_fit_box(&g, &box);
    mimas_deposit dp;
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    mimas_weights ws = {0};
    double dense[20], a[3] = {0.0071, 0.0042, 0.0093}, peak = ref_marginal(1, (double[]){0});
    assert_int_equal(mimas_deposit_sphere(&dp, a, 0.0, 0, &ws), MIMAS_OK);
    dense_weights(&ws, dense, 20);
    for (int j = 0; j < 20; j++) {
        double ref = 0;
        for (int k = -2; k <= 2; k++) {
            double dz = (j + 0.5) * 5e-4 - a[2] - k * L;
            ref += ref_marginal(1, &dz) / (L * L);
        }
        assert_close(dense[j], ref, 1e-12 * peak / (L * L));
    }
    /* along y with yz = 0: the profile holds the particle's mass */
    mimas_box ybox = box;
    ybox.yz = 0.0;
    assert_int_equal(mimas_grid_parse(&g, "y=0:0.01:40", NULL, &err), MIMAS_OK);
    mimas_grid_fit_box(&g, &ybox);
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &ybox, 0, &err), MIMAS_OK);
    ws.n = 0;
    assert_int_equal(mimas_deposit_sphere(&dp, a, 0.0, 0, &ws), MIMAS_OK);
    double mass = 0;
    for (size_t e = 0; e < ws.n; e++)
        mass += ws.w[e] * L * L * L / 40;
    assert_close(mass, 1.0, 1e-3); /* the cell-centre sum of a kernel 4 cells wide */
    /* refused: x profile (the edges along y and z have x parts), x-y grid (z's has), r only */
    const char *bad[3] = {"x=0:0.01:20", "x=0:0.01:8,y=0:0.01:8", "r=0:0.004:8"};
    const char *why[3] = {"along y", "along z", "along the axis"};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(mimas_grid_parse(&g, bad[k], NULL, &err), MIMAS_OK);
        mimas_grid_fit_box(&g, &box);
        assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_EUSAGE);
        assert_non_null(strstr(err.msg, why[k]));
    }
    mimas_weights_free(&ws);
}

static void test_narrow_box(void **state)
{
    (void)state;
    check_narrow_box("gauss:w=0.001", 0, 0, 0);
    check_narrow_box("gauss:w=0.001,shift", 0, 0, 0);
    check_narrow_box("lucy:c=0.003", 0, 0, 0);
    check_narrow_box("gauss:w=0.001", 3e-4, -2e-4, 2.5e-4);
    check_narrow_box("lucy:c=0.003", 3e-4, -2e-4, 2.5e-4);
    check_narrow_ring("gauss:w=0.001", 1e-10);
    check_narrow_ring("lucy:c=0.003", 1e-7);
    check_tilted_profiles("gauss:w=0.001");
    check_tilted_profiles("lucy:c=0.003");
}

static void test_parse_errors(void **state)
{
    (void)state;
    mimas_weight wt;
    mimas_error err;
    const char *bad[] = {"gauss", "gauss:w=0", "gauss:w=1,cutoff=-1", "gauss:x=1", "lucy:c=",
                         "lucy:c=-2", "shepard:", "box", "gauss:w=1,shifted", "gauss:shift"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        if (mimas_weight_parse(&wt, bad[k], &err) != MIMAS_EUSAGE)
            fail_msg("'%s' accepted", bad[k]);
    assert_int_equal(mimas_weight_parse(&wt, "gauss:w=1,shift,cutoff=2.5", &err), MIMAS_OK);
    assert_true(wt.shifted && wt.cutoff == 2.5);
    assert_int_equal(mimas_weight_parse(&wt, "gauss:w=1", &err), MIMAS_OK);
    assert_true(!wt.shifted && wt.shift == 0.0 && wt.cutoff == 3.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gauss),
        cmocka_unit_test(test_lucy),
        cmocka_unit_test(test_kappa),
        cmocka_unit_test(test_marginals),
        cmocka_unit_test(test_ring),
        cmocka_unit_test(test_ring_series),
        cmocka_unit_test(test_ring_segments),
        cmocka_unit_test(test_bins_walk),
        cmocka_unit_test(test_narrow_box),
        cmocka_unit_test(test_parse_errors),
    };
    return cmocka_run_group_tests_name("weight", tests, NULL, NULL);
}
