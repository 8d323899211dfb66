#!/usr/bin/env python3
"""Writes one frame of a mimas native file as MercuryDPM output files NAME.data and
NAME.fstat (3-D xballs format and the .fstat layout with contact points, marker 1), so
that MercuryCG and mimas can read the same frame.

    native_to_mercury.py RUN.h5 NAME [FRAME]     (FRAME: index, default the last)

The .data file is written with 17 significant digits, so both programs see the same
positions; the .fstat file with 10, as MercuryDPM writes it (MercuryDPM's reader skips the
mirrored row of a pair with ignore(256, '\n'): longer rows break it).  The .fstat rows follow MercuryDPM's
BaseInteraction::writeToFStat (see docs/readers-mercury.md): a pair is written twice,
row `P I` with the normal from I to P and the force on P, then the mirrored row; a wall
row carries -n and -t (the wall flip) and the id -(wall)-1.  The contact point is the one
MercuryDPM's reader rebuilds, r_P - (R_P - delta/2) n, so both programs use the same.
Requires h5py and numpy."""
import sys

import h5py
import numpy as np


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    path, name = sys.argv[1], sys.argv[2]
    with h5py.File(path, "r") as h:
        part = h["particles/all"]
        nframes = part["position/value"].shape[0]
        k = int(sys.argv[3]) if len(sys.argv) > 3 else nframes - 1
        if k < 0:
            k += nframes
        n = int(h["observables/all/particle_count/value"][k])
        ids = part["id/value"][k, :n]
        pos = part["position/value"][k, :n]
        vel = part["velocity/value"][k, :n]
        rad = part["radius/value"][k, :n]
        omega = part["angular_velocity/value"][k, :n] if "angular_velocity" in part \
            else np.zeros((n, 3))
        t = float(part["position/time"][k])
        lo = part["box/lower/value"][k]
        hi = part["box/upper/value"][k]
        index = {int(i): m for m, i in enumerate(ids)}
        pairs = walls = None
        if "contacts/all" in h:
            c = h["contacts/all"]
            a, b = c["offset"][k], c["offset"][k + 1]
            pairs = (c["i"][a:b], c["j"][a:b], c["force"][a:b])
        if "contacts/walls" in h:
            c = h["contacts/walls"]
            a, b = c["offset"][k], c["offset"][k + 1]
            walls = (c["particle"][a:b], c["wall"][a:b], c["force"][a:b])
    g = lambda x: "%.17g" % x
    # .fstat: 10 digits, as MercuryDPM writes them: MercuryDPM's reader skips the row it
    # does not use with ignore(256, '\n'), so a longer row breaks it
    g10 = lambda x: "%.10g" % x
    with open(name + ".data", "w") as out:
        out.write(" ".join([str(n), g(t)] + [g(x) for x in lo] + [g(x) for x in hi]) + "\n")
        for m in range(n):
            row = list(pos[m]) + list(vel[m]) + [rad[m], 0, 0, 0] + list(omega[m])
            out.write(" ".join(g(x) for x in row) + " 0\n")
    with open(name + ".fstat", "w") as out:
        out.write("# %s 1\n# %s\n# %s %s 0 0 0 0\n" % (
            g10(t), " ".join(g10(x) for x in list(lo) + list(hi)), g10(rad.min()), g10(rad.max())))

        def row(p, q, n_, f, overlap, cp):
            fn = float(np.dot(f, n_))
            ft_vec = f - fn * n_
            ft = float(np.linalg.norm(ft_vec))
            tv = ft_vec / ft if ft > 0 else np.zeros(3)
            return " ".join([g10(t), str(p), str(q)] + [g10(x) for x in cp] +
                            [g10(overlap), "0", g10(fn), g10(ft)] + [g10(x) for x in n_] +
                            [g10(x) for x in tv]) + "\n"

        if pairs is not None:
            for i, j, f in zip(*pairs):
                p, q = index[int(i)], index[int(j)]
                if p > q:
                    p, q, f = q, p, -f
                d = pos[p] - pos[q]
                dist = float(np.linalg.norm(d))
                n_ = d / dist
                overlap = rad[p] + rad[q] - dist
                cp = pos[p] - (rad[p] - 0.5 * overlap) * n_
                out.write(row(p, q, n_, f, overlap, cp))
                out.write(row(q, p, -n_, -f, overlap, cp))
        if walls is not None:
            for i, w, f in zip(*walls):
                p = index[int(i)]
                # the wall's normal towards the particle: along the force's normal part is
                # not known here; use the direction of the force (frictionless walls) or, in
                # general, the nearest box face of the wall id (1..6: -x +x -y +y -z +z)
                axis, side = (int(w) - 1) // 2, (int(w) - 1) % 2
                n_wp = np.zeros(3)
                n_wp[axis] = 1.0 if side == 0 else -1.0
                dist = pos[p][axis] - lo[axis] if side == 0 else hi[axis] - pos[p][axis]
                overlap = rad[p] - dist
                fn = float(np.dot(f, n_wp))
                ft_vec = f - fn * n_wp
                ft = float(np.linalg.norm(ft_vec))
                tv = ft_vec / ft if ft > 0 else np.zeros(3)
                cp = pos[p] - (rad[p] - 0.5 * overlap) * n_wp
                # the wall flip: -n and -t, so that force = -(fn n + ft t) with n = -n_wp
                out.write(" ".join([g10(t), str(p), str(-int(w) - 1)] + [g10(x) for x in cp] +
                                   [g10(overlap), "0", g10(fn), g10(ft)] +
                                   [g10(x) for x in -n_wp] + [g10(x) for x in -tv]) + "\n")


if __name__ == "__main__":
    main()
