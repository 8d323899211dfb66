/* The edges of a kernel's azimuthal average along a branch and the rule split at them
 * (ring_edges.h).  Compiled once, for every build of the r-z deposits: their edge cells
 * get the same nodes to the bit. */
#include <config.h>

#include <math.h>

#include <gsl/gsl_poly.h>

#include "deposit_impl.h"
#include "gauss_legendre.h"
#include "ring_edges.h"

void mimas_ring_branch_init(mimas_ring_branch *br, const mimas_weight *wt, const double a[3],
                            const double ab[3])
{
    for (int m = 0; m < 3; m++) {
        br->a[m] = a[m];
        br->b[m] = ab[m] - a[m];
    }
    const double *b = br->b;
    br->len = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    br->q[0] = a[0] * a[0] + a[1] * a[1];
    br->q[1] = 2.0 * (a[0] * b[0] + a[1] * b[1]);
    br->q[2] = b[0] * b[0] + b[1] * b[1];
    br->star = br->q[2] > 0 ? -0.5 * br->q[1] / br->q[2] : 0.0;
    br->beta = br->q[2] > 0 ? sqrt(fmax(br->q[0] / br->q[2] - br->star * br->star, 0.0))
                            : INFINITY;
    double mx = a[0] + 0.5 * b[0], my = a[1] + 0.5 * b[1];
    br->qm[0] = mx * mx + my * my;
    br->qm[1] = 2.0 * (mx * b[0] + my * b[1]);
    br->rho_mid = sqrt(br->qm[0]);
    br->z_mid = a[2] + 0.5 * b[2];
    /* the plain rule (dep_ring_rule, 4 to 16 points) is accurate to 1e-9 of the kernel's
     * peak where no singular point is within a disc about the branch's middle, of radius
     * 4, 1.5 or 1 branch lengths for the rules of 4, 8 and 16 points */
    const double *xs, *ws;
    int rule = dep_ring_rule(wt, br->len, &xs, &ws);
    br->h = rule == 4 ? 4.0 : (rule == 8 ? 1.5 : 1.0);
    br->len8 = dep_ring_longest(wt, 8);
    double out = sqrt(wt->reach2) + 0.5 * br->len;
    br->out2 = out * out;
}

/* the quartic and its derivative at s (Horner) */
static double quartic(const double c[5], double s, double *d)
{
    double v = c[4], dv = 0.0;
    for (int k = 3; k >= 0; k--) {
        dv = dv * s + v;
        v = v * s + c[k];
    }
    *d = dv;
    return v;
}

/* The root in [a, b] where the quartic is monotone and changes sign (fa, fb its values at
 * the ends): Newton's steps from the secant's root, kept inside the bracket, which each
 * step narrows. */
static double bracketed_root(const double c[5], double a, double b, double fa, double fb)
{
    double x = a - fa * (b - a) / (fb - fa);
    if (!(x > a && x < b))
        x = 0.5 * (a + b);
    for (int it = 0; it < 100; it++) {
        double d, f = quartic(c, x, &d);
        if (f == 0.0)
            return x;
        if ((f < 0) == (fa < 0))
            a = x;
        else
            b = x;
        double next = d != 0.0 ? x - f / d : a;
        if (!(next > a && next < b))
            next = 0.5 * (a + b);
        /* to 1e-10 of the branch: a split that far from the edge changes the integral by
         * about (1e-10)^{3/2} = 1e-15 of the kernel's peak */
        if (fabs(next - x) < 1e-10 || b - a < 1e-10)
            return next;
        x = next;
    }
    return x;
}

/* Q's coefficients about the branch's middle, Q(1/2 + t) = sum e_k t^k, at the ring (r, z):
 * P = q + r^2 + dz^2 - R^2 with dz = dzm - bz t, Q = P^2 - 4 r^2 q, negative where the ring
 * is partly inside the support, zero on either edge; 0 for a branch of no length (Q
 * constant). */
static int quartic_mid(const mimas_ring_branch *br, double r, double z, double R2, double e[5])
{
    const double *qm = br->qm;
    double q2 = br->q[2], dzm = z - br->z_mid, bz = br->b[2], r2 = r * r;
    double p0 = qm[0] + r2 + dzm * dzm - R2, p1 = qm[1] - 2.0 * dzm * bz, p2 = q2 + bz * bz;
    e[0] = p0 * p0 - 4.0 * r2 * qm[0];
    e[1] = 2.0 * p0 * p1 - 4.0 * r2 * qm[1];
    e[2] = p1 * p1 + 2.0 * p0 * p2 - 4.0 * r2 * q2;
    e[3] = 2.0 * p1 * p2;
    e[4] = p2 * p2;
    return p2 > 0;
}

/* the m nodes from the n-th on at s: their distance from the axis, z offset, (r - rho)^2
 * and 1/(4 r rho) (infinite on the axis: r, rho >= 0); a loop without branches, which the
 * compiler vectorizes */
static void put_nodes(const mimas_ring_branch *br, double r, double z, const double *s, int m,
                      mimas_ring_nodes *nd, int n)
{
    double a0 = br->a[0], a1 = br->a[1], a2 = br->a[2];
    double b0 = br->b[0], b1 = br->b[1], b2 = br->b[2];
    double *restrict rhos = nd->rho + n, *restrict dz = nd->dz + n;
    double *restrict dr2 = nd->dr2 + n, *restrict irr = nd->irr + n;
    for (int k = 0; k < m; k++) {
        double p0 = a0 + s[k] * b0, p1 = a1 + s[k] * b1;
        double rho = sqrt(p0 * p0 + p1 * p1);
        rhos[k] = rho;
        dz[k] = z - (a2 + s[k] * b2);
        dr2[k] = (r - rho) * (r - rho);
        irr[k] = 1.0 / (4.0 * r * rho);
    }
}

/* A singular point of the average along the branch: an edge (g = 0) at s, or a pair
 * s +- i g off the real line (the branch nearly touching an edge, or passing near the
 * axis, where rho = sqrt(q) has its branch points). */
typedef struct sing_pt {
    double s, g;
} sing_pt;

/* The rule of m points (8 or 16; 16 where the map stretches the piece to more than 2 in
 * u) on [s0, s1] in u with the singular point p at one end made smooth: for an edge,
 * s = p + (s1 - p) u^2 (p <= s0) or s = p - (p - s0) u^2 (p >= s1), under which the
 * square root is smooth; for a pair, s = p.s + p.g sinh(u), under which
 * sqrt((s - p.s)^2 + p.g^2) is (Johnston and Elliott's sinh transformation); no p: plain. */
static int piece_nodes(const mimas_ring_branch *br, double r, double z, double s0, double s1,
                       const sing_pt *p, int m, mimas_ring_nodes *nd, int n)
{
    const double *xs = m == 16 ? gl16_x : gl8_x, *ws = m == 16 ? gl16_w : gl8_w;
    double u0 = 0.0, u1 = 1.0, c = 0.0, dir = 1.0; /* the edge's map: s = p + dir c u^2 */
    if (p && p->g > 0) {
        u0 = asinh((s0 - p->s) / p->g);
        u1 = asinh((s1 - p->s) / p->g);
    } else if (p) {
        dir = p->s <= s0 ? 1.0 : -1.0;
        c = dir > 0 ? s1 - p->s : p->s - s0;
        u0 = sqrt((dir > 0 ? s0 - p->s : p->s - s1) / c);
    }
    if (u1 - u0 > 2.0)
        xs = gl16_x, ws = gl16_w, m = 16;
    double sn[16], *wn = nd->w + n; /* u and its weight, then s and its */
    for (int i = 0; i < m; i++)
        gl_node(xs, ws, m, i, u0, u1, &sn[i], &wn[i]);
    if (p && p->g > 0) {
        for (int i = 0; i < m; i++) {
            double u = sn[i];
            sn[i] = p->s + p->g * sinh(u);
            wn[i] *= p->g * cosh(u);
        }
    } else if (p) {
        for (int i = 0; i < m; i++) {
            double u = sn[i];
            sn[i] = p->s + dir * c * u * u;
            wn[i] *= 2.0 * c * u;
        }
    } else {
        for (int i = 0; i < m; i++) {
            sn[i] = s0 + (s1 - s0) * sn[i];
            wn[i] *= s1 - s0;
        }
    }
    put_nodes(br, r, z, sn, m, nd, n);
    return n + m;
}

/* The rule on [s0, s1] made smooth at the one singular point within its length of it;
 * where there are more, halved, until the halves have one or none (or the room for nodes
 * runs out: then the nearest).  8 points, 16 where the piece is longer than 2 w or its map
 * stretches it.  Room: a piece is entered with room for its 16
 * and 16 for each of the pending pieces after it, and halved only if there is room for one
 * more: so it never takes theirs. */
static int piece_split(const mimas_ring_branch *br, double r, double z, double s0, double s1,
                       const sing_pt *pt, int np, int pending, mimas_ring_nodes *nd, int n)
{
    double ds = s1 - s0, best = ds * ds;
    const sing_pt *p = NULL;
    int near = 0;
    for (int i = 0; i < np; i++) {
        double off = pt[i].s < s0 ? s0 - pt[i].s : (pt[i].s > s1 ? pt[i].s - s1 : 0.0);
        double d = off * off + pt[i].g * pt[i].g;
        if (d < ds * ds) {
            near++;
            if (d <= best)
                p = &pt[i], best = d;
        }
    }
    if (near > 1 && n + 16 * (pending + 2) <= MIMAS_RING_NODES_MAX) {
        n = piece_split(br, r, z, s0, s0 + 0.5 * ds, pt, np, pending + 1, nd, n);
        return piece_split(br, r, z, s0 + 0.5 * ds, s1, pt, np, pending, nd, n);
    }
    int m = ds * br->len <= br->len8 ? 8 : 16; /* dep_ring_rule's, 4 points taking 8 */
    return piece_nodes(br, r, z, s0, s1, p, m, nd, n);
}

/* v[0..n-1] in ascending order (insertion: a few values) */
static void sort_few(double *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
            double tmp = v[j];
            v[j] = v[j - 1];
            v[j - 1] = tmp;
        }
}

/* The singular points within reach of the branch (real parts in [lo, hi]): Q's real roots,
 * bracketed by its turning points (the roots of the cubic Q', GSL's solver, unless turns is
 * 0: Q monotone on [lo, hi]), the complex pairs where it turns without reaching zero (g from
 * Q's parabola there), and the nearest approach to the axis. */
static int singular_points(const mimas_ring_branch *br, const double c[5], double q_mid,
                           double lo, double hi, int turns, sing_pt *pt)
{
    /* Q' = 4 c4 s^3 + 3 c3 s^2 + 2 c2 s + c1: its real roots, ascending, are where Q turns */
    double t[3], x[6], f[6], d;
    int nt = turns ? gsl_poly_solve_cubic(0.75 * c[3] / c[4], 0.5 * c[2] / c[4],
                                          0.25 * c[1] / c[4], &t[0], &t[1], &t[2])
                   : 0;
    /* the points between which Q is monotone, ascending, with Q there: the ends of
     * [lo, hi], the turning points, and the middle, where Q is known (q_mid), which
     * narrows the brackets of the roots */
    int nx = 0, n = 0, mid = 0;
    x[nx] = lo;
    f[nx++] = quartic(c, lo, &d);
    for (int i = 0; i < nt; i++) {
        double v = quartic(c, t[i], &d);
        double curv = 2.0 * c[2] + t[i] * (6.0 * c[3] + 12.0 * c[4] * t[i]); /* Q'' */
        if (!(t[i] > lo && t[i] < hi))
            continue;
        if (!mid && t[i] >= 0.5)
            x[nx] = 0.5, f[nx++] = q_mid, mid = 1;
        x[nx] = t[i];
        f[nx++] = v;
        if (v * curv > 0) /* a minimum above zero or a maximum below: a pair */
            pt[n++] = (sing_pt){t[i], sqrt(2.0 * v / curv)};
    }
    if (!mid)
        x[nx] = 0.5, f[nx++] = q_mid;
    x[nx] = hi;
    f[nx++] = quartic(c, hi, &d);
    /* a root where Q changes sign */
    for (int i = 0; i + 1 < nx; i++)
        if ((f[i] < 0) != (f[i + 1] < 0))
            pt[n++] = (sing_pt){bracketed_root(c, x[i], x[i + 1], f[i], f[i + 1]), 0.0};
    if (br->q[2] > 0 && br->star >= lo && br->star <= hi)
        pt[n++] = (sing_pt){br->star, br->beta};
    return n;
}

/* c: the coefficients of Q(s) = Q(1/2 + t) from e, those in t */
static void about_start(const double e[5], double c[5])
{
    for (int k = 0; k < 5; k++)
        c[k] = e[k];
    for (int i = 0; i < 4; i++)
        for (int j = 3; j >= i; j--)
            c[j] -= 0.5 * c[j + 1];
}

/* Whether Q may have a root within h of the branch's middle: not where |Q(1/2)| exceeds
 * sum_k |e_k| h^k, which bounds |Q(1/2 + t) - Q(1/2)| on the complex disc |t| <= h. */
static int root_near(const double e[5], double h)
{
    double bound = h * (fabs(e[1]) + h * (fabs(e[2]) + h * (fabs(e[3]) + h * fabs(e[4]))));
    return !(fabs(e[0]) > (1.0 + 1e-12) * bound);
}

/* Whether Q may turn within h of the branch's middle: not where |Q'(1/2)| exceeds
 * sum_k k |e_k| h^(k-1), which bounds |Q'(1/2 + t) - Q'(1/2)| for |t| <= h. */
static int turn_near(const double e[5], double h)
{
    double bound = h * (2.0 * fabs(e[2]) + h * (3.0 * fabs(e[3]) + h * 4.0 * fabs(e[4])));
    return !(fabs(e[1]) > (1.0 + 1e-12) * bound);
}

int mimas_ring_edge_nodes(const mimas_ring_branch *br, const mimas_weight *wt, double r,
                          double z, mimas_ring_nodes *nd)
{
    double h = br->h, lo = 0.5 - h, hi = 0.5 + h, c[5], e[5];
    /* the distance from the ring, sqrt((rho - r)^2 + dz^2), changes by at most the distance
     * along the branch: beyond the reach plus half the branch's length at its middle, all of
     * the branch is outside the support */
    double dzm = z - br->z_mid, drm = br->rho_mid - r, dm2 = drm * drm + dzm * dzm;
    if (dm2 >= br->out2)
        return 0;
    if (!quartic_mid(br, r, z, wt->reach2, e))
        return -1;
    double mid_off = br->star - 0.5, axis2 = br->beta * br->beta + mid_off * mid_off;
    if (!root_near(e, h) && !(axis2 < h * h))
        return -1; /* no singular point near: the axis's too */
    /* no edge on the branch (Q keeps its sign on it) and the middle outside the support:
     * all of it is, and the ring has no weight */
    if (!root_near(e, 0.5) && dm2 >= wt->reach2)
        return 0;
    about_start(e, c);
    sing_pt pt[8];
    int np = singular_points(br, c, e[0], lo, hi, turn_near(e, h), pt), n = 0;
    /* the pieces: between the edges and the real parts of the pairs within the branch */
    double cut[10] = {0.0};
    int nc = 1;
    for (int i = 0; i < np; i++)
        if (pt[i].s > 0.0 && pt[i].s < 1.0)
            cut[nc++] = pt[i].s;
    cut[nc++] = 1.0;
    sort_few(cut + 1, nc - 2);
    for (int p = 0; p + 1 < nc; p++) {
        double s0 = cut[p], s1 = cut[p + 1], ds = s1 - s0, mid = s0 + 0.5 * ds;
        if (!(ds > 0))
            continue;
        double x = br->a[0] + mid * br->b[0], y = br->a[1] + mid * br->b[1];
        double rho = sqrt(x * x + y * y), dz = z - (br->a[2] + mid * br->b[2]);
        if (!((r - rho) * (r - rho) + dz * dz < wt->reach2))
            continue; /* a piece outside the support (between edges: all of it) */
        n = piece_split(br, r, z, s0, s1, pt, np, nc - 2 - p, nd, n);
    }
    for (; n % 8; n++) { /* out of reach, no weight */
        nd->w[n] = nd->rho[n] = nd->dz[n] = 0.0;
        nd->dr2[n] = nd->irr[n] = INFINITY;
    }
    return n;
}
