# Writes averaging/ring_tables.h (run from the source tree: python3 averaging/gen_ring_tables.py)
from fractions import Fraction
from math import comb
import mpmath as mp
mp.mp.dps = 50
N = 64; H = 192
STEP = 16         # intervals per unit of X
XMAX = 18         # the table covers 0 <= X <= XMAX (cutoffs up to 6)
DEG = 7           # Taylor degree about each interval's midpoint

def M_half_taylor(x0, deg):
    # M_{1/2}(X) = sum_k X^k / ((1/2)(3/2)...(k+1/2)); coefficient j of (X - x0)^j
    x0 = mp.mpf(x0)
    inv_poch = [mp.mpf(1) / mp.rf(mp.mpf(1) / 2, k + 1) for k in range(400)]
    return [mp.fsum(mp.binomial(k, j) * x0 ** (k - j) * inv_poch[k] for k in range(j, 400))
            for j in range(deg + 1)]

def fmt(vals, indent="    "):
    s = []; line = indent
    for v in vals:
        t = " %r," % v
        if len(line) + len(t) > 95:
            s.append(line); line = indent
        line += t
    s.append(line)
    return "\n".join(s)

out = []
out.append("""/* Tables of the Gaussian's ring series (internal to weight.c, deposit_ring.c), written
 * by averaging/gen_ring_tables.py: the binomial coefficients c_n = (2n choose n) / 4^n of
 * (1 - u^2)^{-1/2} = sum c_n u^{2n}; 1 / (j + 1/2); and M_{1/2}(X) = e^X sqrt(pi)
 * erf(sqrt X) / sqrt X = sum_k X^k / ((1/2)(3/2)..(k + 1/2)) on 0 <= X <= RING_XMAX as
 * Taylor polynomials of degree RING_DEG about the midpoints of intervals 1/RING_STEP long
 * (50-digit arithmetic, mpmath; the remainder is about 1e-16 relative). */
#ifndef MIMAS_RING_TABLES_H
#define MIMAS_RING_TABLES_H
""")
out.append("#define RING_NC %d\n#define RING_NH %d\n#define RING_STEP %d\n#define RING_XMAX %d\n#define RING_DEG %d\n" % (N, H, STEP, XMAX, DEG))
out.append("static const double ring_binom[RING_NC] = {\n" + fmt([float(Fraction(comb(2*n, n), 4**n)) for n in range(N)]) + "\n};")
out.append("static const double ring_inv_half[RING_NH] = {\n" + fmt([float(Fraction(2, 2*j+1)) for j in range(H)]) + "\n};")
rows = []
for m in range(STEP * XMAX):
    x0 = mp.mpf(2 * m + 1) / (2 * STEP)
    c = M_half_taylor(x0, DEG)
    rows.append("    {" + fmt([float(v) for v in c], "     ").strip() + "},")
out.append("static const double ring_m_half[RING_STEP * RING_XMAX][RING_DEG + 1] = {\n" + "\n".join(rows) + "\n};\n")
out.append("""/* M_{1/2}(X) for 0 <= X <= RING_XMAX: the Taylor polynomial about the midpoint of X's
 * interval, by Estrin's scheme (shorter chains of dependent operations than Horner's). */
static inline double ring_m_half_at(double X)
{
    int m = (int)(X * RING_STEP);
    if (m >= RING_STEP * RING_XMAX)
        m = RING_STEP * RING_XMAX - 1;
    const double *c = ring_m_half[m];
    double t = X - (m + 0.5) / RING_STEP, t2 = t * t;
#if RING_DEG != 7
#error "ring_m_half_at evaluates degree 7"
#endif
    double lo = (c[0] + c[1] * t) + t2 * (c[2] + c[3] * t);
    double hi = (c[4] + c[5] * t) + t2 * (c[6] + c[7] * t);
    return lo + t2 * t2 * hi;
}
""")
out.append("#endif")
open("averaging/ring_tables.h", "w").write("\n".join(out) + "\n")
