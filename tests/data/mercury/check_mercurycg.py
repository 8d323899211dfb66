#!/usr/bin/env python3
"""Explains MercuryCG's XYZ Gauss fields in box150_xyz.stat from box150.data/.fstat by an
independent computation (numpy/scipy), so that the differences mimas shows are understood:

1. the particle fields (VolumeFraction, Density, Momentum, MomentumFlux) are sums of the
   Gaussian exp(-r^2/2w^2) cut at 3w, normalised over the cut ball (density 1: MercuryCG
   assumes it without a .restart file);
2. the ContactStress is NOT the line integral of that kernel: MercuryCG takes
   erf(pN/sqrt2 w) - erf(iN/sqrt2 w) times exp(-t^2/2w^2) over the whole branch, zero
   outside a cylinder of radius 3w around the branch reaching 3w past both ends,
   renormalised over that cylinder, and evaluated only in the cells within 3w of the end
   points' bounding box (its cell loop) -- the model below reproduces it to the printed
   digits;
3. the exact line integral of the kernel (what mimas computes) differs from it by about
   1 % of the largest stress.

Run:  python3 check_mercurycg.py > check_mercurycg_output.txt"""
import numpy as np
from scipy.integrate import quad
from scipy.special import erf

W, C = 0.001, 3.0
CUT = C * W


def read(name):
    lines = open(name + ".data").read().split("\n")
    n = int(lines[0].split()[0])
    p = np.array([[float(x) for x in l.split()] for l in lines[1:1 + n]])
    contacts = []
    for l in open(name + ".fstat"):
        if l.startswith("#") or not l.strip():
            continue
        r = l.split()
        i, j = int(r[1]), int(r[2])
        v = [float(x) for x in r[3:]]
        ov, fn, ft = v[3], v[5], v[6]
        nn, tt = np.array(v[7:10]), np.array(v[10:13])
        if j >= 0:
            if j < i:
                continue  # the mirrored row of a pair
            contacts.append((i, j, fn * nn + ft * tt, nn, ov))
        else:  # a wall row carries -n and -t
            contacts.append((i, None, -(fn * nn + ft * tt), -nn, ov))
    return p[:, 0:3], p[:, 3:6], p[:, 6], contacts


def main():
    pos, vel, rad, contacts = read("box150")
    m = np.loadtxt("box150_xyz.stat", skiprows=2)
    pts = m[:, 1:4]
    coef = 1 / ((2 * np.pi * W * W) ** 1.5 *
                (erf(C / np.sqrt(2)) - np.sqrt(2 / np.pi) * C * np.exp(-C * C / 2)))
    mass = 4 / 3 * np.pi * rad ** 3  # density 1
    d2 = ((pts[:, None, :] - pos[None, :, :]) ** 2).sum(axis=2)
    phi = np.where(d2 < CUT * CUT, coef * np.exp(-d2 / (2 * W * W)), 0.0)
    nu = phi @ mass
    mom = phi @ (mass[:, None] * vel)
    sym = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]
    flux = np.stack([phi @ (mass * vel[:, a] * vel[:, b]) for a, b in sym], axis=1)

    def cylinder(r, I, P, n):
        i_n, p_n = np.dot(I - r, n), np.dot(P - r, n)
        if i_n > CUT or p_n < -CUT:
            return 0.0
        t2 = np.dot(P - r, P - r) - p_n * p_n
        if t2 > CUT * CUT:
            return 0.0
        s2 = W * np.sqrt(2)
        a, b = -CUT, CUT + (p_n - i_n)
        g = lambda x: erf(x / s2) * x + s2 / np.sqrt(np.pi) * np.exp(-(x / s2) ** 2)
        pre = 1 / (2 * np.pi * W * W * (1 - np.exp(-C * C / 2))) * 0.5 / (g(b) - g(a))
        return pre * (erf(p_n / s2) - erf(i_n / s2)) * np.exp(-0.5 * t2 / (W * W))

    def exact(r, a, b):
        """int_0^1 of the cut kernel along the segment from a to b, by quadrature"""
        f = lambda s: (lambda q: coef * np.exp(-q / (2 * W * W)) if q < CUT * CUT else 0.0)(
            float(((r - a - s * (b - a)) ** 2).sum()))
        # break points where the segment crosses the cut sphere about r
        bb = b - a
        A, B, Cq = bb @ bb, (r - a) @ bb, (r - a) @ (r - a) - CUT * CUT
        pts_ = [0.0, 1.0]
        disc = B * B - A * Cq
        if disc > 0:
            pts_ += [s for s in ((B - np.sqrt(disc)) / A, (B + np.sqrt(disc)) / A) if 0 < s < 1]
        pts_ = sorted(pts_)
        return sum(quad(f, lo, hi, epsabs=0, epsrel=1e-12)[0] for lo, hi in zip(pts_, pts_[1:]))

    s_cyl = np.zeros((len(pts), 3, 3))
    s_exact = np.zeros((len(pts), 3, 3))
    for i, j, f, n, ov in contacts:
        P = pos[i]
        if j is not None:  # I = the other particle; branch n (R_P + R_I - delta)
            I = pos[j]
            branch = n * (rad[i] + rad[j] - ov)
        else:  # the contact point, where MercuryCG's reader puts it
            I = P - (rad[i] - 0.5 * ov) * n
            branch = P - I
        fb = np.outer(f, branch)
        lo, hi = np.minimum(I, P) - CUT, np.maximum(I, P) + CUT
        for k, r in enumerate(pts):
            if np.all(r >= lo) and np.all(r <= hi):
                psi = cylinder(r, I, P, n)
                if psi:
                    s_cyl[k] += fb * psi
            # the exact line integral: over the branch from I to P, along r_P - r_I
            s_exact[k] += fb * exact(r, P - branch, P)
    print("MercuryCG's printed digits (6 significant) against the computation here:")
    base = 4
    for name, mine, col in [("VolumeFraction", nu[:, None], slice(base, base + 1)),
                            ("Density", nu[:, None], slice(base + 1, base + 2)),
                            ("Momentum", mom, slice(base + 2, base + 5)),
                            ("MomentumFlux", flux, slice(base + 5, base + 11)),
                            ("ContactStress (cylinder model)", s_cyl.reshape(-1, 9),
                             slice(base + 11, base + 20))]:
        mc = m[:, col]
        unit = 10.0 ** (np.floor(np.log10(np.maximum(np.abs(mc), 1e-300))) - 5)
        worst = np.max(np.abs(mine - mc) / unit)
        print("  %-32s largest difference %.2f units of the last printed digit" % (name, worst))
    mc = m[:, base + 11:base + 20]
    rel = np.max(np.abs(s_exact.reshape(-1, 9) - mc)) / np.max(np.abs(mc))
    print("ContactStress with the exact line integral of the kernel (mimas): differs from "
          "MercuryCG's by up to %.2f %% of the largest component" % (100 * rel))


if __name__ == "__main__":
    main()
