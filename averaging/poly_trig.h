/* Cosine, atan2 and beta - sin(beta) on the ranges the sphere-ring overlap needs
 * (annulus_slices.c), PT_LANES values at a time in GCC's generic vectors, as polynomials
 * without branches or library calls.  Truncated Taylor series whose first omitted term is
 * below 1e-18 of the result on the stated range, evaluated by Estrin's scheme: the error is
 * that of rounding, a few ulp (tests/unit/test_overlap_parts.c compares them with libm and
 * long double).  Only IEEE operations, in the same order for any number of lanes and in
 * every build (ISO C: no fused multiply-add), so the same bits on every processor.
 *
 * A template: the includer defines PT_LANES (2, 4 or 8: vectors of 16, 32 or 64 bytes,
 * which it includes this for under a #pragma GCC target that has them in registers) and
 * PT_(name), the names to give the types PT_(vd) (doubles) and PT_(vi) (their masks, from
 * comparisons) and the functions; no include guard. */
#include <stdint.h>
#include <string.h>

typedef double PT_(vd) __attribute__((vector_size(8 * PT_LANES)));
typedef int64_t PT_(vi) __attribute__((vector_size(8 * PT_LANES)));

/* m ? a : b lane by lane (m: all bits set or none, as comparisons give) */
static inline __attribute__((always_inline)) PT_(vd) PT_(sel)(PT_(vi) m, PT_(vd) a, PT_(vd) b)
{
    return (PT_(vd))(((PT_(vi))a & m) | ((PT_(vi))b & ~m));
}

static inline __attribute__((always_inline)) PT_(vd) PT_(fabs)(PT_(vd) x)
{
    return (PT_(vd))((PT_(vi))x & INT64_MAX);
}

static inline __attribute__((always_inline)) PT_(vd) PT_(sqrt)(PT_(vd) x)
{
    PT_(vd) r;
    for (int k = 0; k < PT_LANES; k++)
        r[k] = __builtin_sqrt(x[k]);
    return r;
}

/* sum_k c[k] y^k (k < n <= 16) by Estrin's scheme: pairs c[2j] + c[2j+1] y, then pairs
 * of those with y^2, and so on; a chain of ceil(log2 n) steps instead of Horner's n - 1,
 * which is what bounds a loop of these polynomials (n is a constant after inlining). */
static inline __attribute__((always_inline)) PT_(vd) PT_(estrin)(PT_(vd) y, const double *c,
                                                                  int n)
{
    const PT_(vd) zero = {0};
    PT_(vd) p[16], x = y;
    for (int k = 0; k < n; k++)
        p[k] = zero + c[k];
    for (int m = n; m > 1; m = (m + 1) / 2, x = x * x)
        for (int j = 0; j < (m + 1) / 2; j++)
            p[j] = 2 * j + 1 < m ? p[2 * j] + p[2 * j + 1] * x : p[2 * j];
    return p[0];
}

/* cos(x) for |x| <= pi/2: the series to x^22 (the next term is below 1e-19). */
static inline __attribute__((always_inline)) PT_(vd) PT_(cos)(PT_(vd) x)
{
    static const double c[12] = {1.0, -1.0 / 2, 1.0 / 24, -1.0 / 720, 1.0 / 40320,
                                 -1.0 / 3628800, 1.0 / 479001600, -1.0 / 87178291200.0,
                                 1.0 / 20922789888000.0, -1.0 / 6402373705728000.0,
                                 1.0 / 2432902008176640000.0, -1.0 / 1124000727777607680000.0};
    return PT_(estrin)(x * x, c, 12);
}

/* beta - sin(beta) for 0 <= beta <= pi, accurate relative to its value also for small
 * beta (~beta^3/6): the series to beta^29 (the next term is below 4e-19). */
static inline __attribute__((always_inline)) PT_(vd) PT_(bms)(PT_(vd) x)
{
    static const double c[14] = {
        1.0 / 6, -1.0 / 120, 1.0 / 5040, -1.0 / 362880, 1.0 / 39916800, -1.0 / 6227020800.0,
        1.0 / 1307674368000.0, -1.0 / 355687428096000.0, 1.0 / 121645100408832000.0,
        -1.0 / 51090942171709440000.0, 1.0 / 25852016738884976640000.0,
        -1.0 / 15511210043330985984000000.0, 1.0 / 10888869450418352160768000000.0,
        -1.0 / 8841761993739701954543616000000.0};
    PT_(vd) y = x * x;
    return x * y * PT_(estrin)(y, c, 14);
}

/* atan2(y, x) for y >= 0, in [0, pi]: atan of t = s/b, s and b the smaller and the larger
 * of |x| and y (0 <= t <= 1), reduced to |u| <= tan(pi/8) by atan t = pi/4 + atan u,
 * u = (t - 1)/(t + 1) = (s - b)/(s + b), and halved, atan u = 2 atan(v), v = u / (1 +
 * sqrt(1 + u^2)), |v| <= tan(pi/16); the series of atan v to v^23 (the next term is below
 * 1e-18 of the value).  atan2(0, 0) is 0. */
static inline __attribute__((always_inline)) PT_(vd) PT_(atan2)(PT_(vd) y, PT_(vd) x)
{
    static const double c[12] = {1.0,       -1.0 / 3,  1.0 / 5,   -1.0 / 7,
                                 1.0 / 9,   -1.0 / 11, 1.0 / 13,  -1.0 / 15,
                                 1.0 / 17,  -1.0 / 19, 1.0 / 21,  -1.0 / 23};
    const double pi = 3.14159265358979323846, tan_pi8 = 0.41421356237309504880;
    const PT_(vd) zero = {0}, one = zero + 1.0;
    PT_(vd) ax = PT_(fabs)(x);
    PT_(vi) steep = y > ax;
    PT_(vd) big = PT_(sel)(steep, y, ax), small = PT_(sel)(steep, ax, y);
    PT_(vi) over = small > tan_pi8 * big;
    PT_(vd) u = PT_(sel)(over, small - big, small) /
              PT_(sel)(over, small + big, PT_(sel)(big > zero, big, one));
    PT_(vd) v = u / (1.0 + PT_(sqrt)(1.0 + u * u));
    PT_(vd) a = 2.0 * v * PT_(estrin)(v * v, c, 12);
    a = PT_(sel)(over, pi / 4 + a, a);
    a = PT_(sel)(steep, pi / 2 - a, a);
    return PT_(sel)(x < zero, pi - a, a);
}
