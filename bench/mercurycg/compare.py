#!/usr/bin/env python3
"""Compares a MercuryCG .stat file (one time step, StandardFields) with the TSV of
mimas average on the same grid, field by field.

    compare.py OUT.stat MIMAS.tsv [--skip-faces K]

Prints, per field, the largest difference over the cells relative to the field's largest
magnitude, and the largest difference in units of MercuryCG's last printed digit.  With
--skip-faces K, cells within K cells of a face of the grid are left out (MercuryCG adds no
periodic images)."""
import sys

import numpy as np


def read_stat(path):
    with open(path) as f:
        lines = f.read().split("\n")
    head = lines[1].split()
    rows = [l.split() for l in lines[2:] if l.strip()]
    return head, rows


def main():
    args = sys.argv[1:]
    skip = 0
    if "--skip-faces" in args:
        k = args.index("--skip-faces")
        skip = int(args[k + 1])
        del args[k:k + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    head, rows = read_stat(args[0])
    text = [r for r in rows]
    m = np.array([[float(x) for x in r] for r in rows])
    with open(args[1]) as f:
        cols = f.readline().split()
    t = np.loadtxt(args[1], skiprows=1, ndmin=2)
    col = {c: i for i, c in enumerate(cols)}
    # the coordinate columns MercuryCG writes after time
    coords = [c for c in ("x", "y", "z") if c in col]
    key_m = lambda r: tuple(np.round(r[1:1 + len(coords)], 12))
    key_t = lambda r: tuple(np.round([r[col[c]] for c in coords], 12))
    index = {key_t(r): k for k, r in enumerate(t)}
    order = [index[key_m(r)] for r in m]
    t = t[order]
    base = 1 + len(coords)
    nu, rho = t[:, col["nu"]], t[:, col["rho"]]
    v = np.stack([t[:, col["v_" + a]] for a in "xyz"], axis=1)
    v = np.nan_to_num(v)
    j = rho[:, None] * v
    sym = ["xx", "xy", "xz", "yy", "yz", "zz"]
    ks = {s: t[:, col["kstress_" + (s if s in ("xx", "yy", "zz", "xy", "xz", "yz") else s)]]
          for s in sym}
    flux = np.stack([ks[s] + rho * v[:, "xyz".index(s[0])] * v[:, "xyz".index(s[1])]
                     for s in sym], axis=1)
    cs = np.stack([t[:, col["cstress_" + s]] for s in sym], axis=1)
    mc = m[:, base + 11:base + 20].reshape(-1, 3, 3)
    mcs = np.stack([0.5 * (mc[:, "xyz".index(s[0]), "xyz".index(s[1])] +
                           mc[:, "xyz".index(s[1]), "xyz".index(s[0])]) for s in sym], axis=1)
    pairs = [("nu", m[:, base], nu), ("rho", m[:, base + 1], rho),
             ("momentum", m[:, base + 2:base + 5], j),
             ("momentum flux", m[:, base + 5:base + 11], flux),
             ("cstress (sym)", mcs, cs)]
    keep = np.ones(len(m), bool)
    if skip:
        for c_i, c in enumerate(coords):
            vals = np.unique(m[:, 1 + c_i])
            lo, hi = vals[skip - 1] if skip <= len(vals) else vals[-1], vals[-skip]
            keep &= (m[:, 1 + c_i] > lo) & (m[:, 1 + c_i] < hi)
    print("cells compared: %d of %d" % (keep.sum(), len(m)))
    for name, a, b in pairs:
        a, b = np.asarray(a)[keep], np.asarray(b)[keep]
        scale = np.max(np.abs(a)) or 1.0
        diff = np.max(np.abs(a - b))
        # MercuryCG prints 6 significant digits: the unit of the last digit of each value
        ulp = 10.0 ** (np.floor(np.log10(np.maximum(np.abs(a), 1e-300))) - 5)
        digits = np.max(np.abs(a - b) / ulp)
        print("%-14s max |diff|/max|value| %.3g   max |diff| in last printed digits %.3g"
              % (name, diff / scale, digits))


if __name__ == "__main__":
    main()
