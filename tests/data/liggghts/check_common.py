"""Shared verification code for the LIGGGHTS reference data in this folder.
Plain Python 3 (no numpy).  Column numbers below are 1-based, exactly as in
the dump headers (c_pgl[k], c_wgl[k]); see each case's README.md.

pair/gran/local column map being verified (41 columns, LIGGGHTS 3.8.0,
keywords: pos vel id force force_normal force_tangential torque
torque_normal torque_tangential history contactArea delta contactPoint):
  1-3 x of atom 1 (remapped into box)   4-6 x of atom 2 (remapped)
  7-9 v of atom 1                       10-12 v of atom 2
  13 id of atom 1   14 id of atom 2   15 periodic flag
  16-18 force on atom 1 from atom 2
  19-21 normal part of 16-18  22-24 tangential part of 16-18
  25-27 torque term   28-30 its normal part   31-33 its tangential part
  34-36 contact history (3 values)   37 contact area   38 overlap delta
  39-41 contact point
"""
import math
from ldump import (read_dump, read_log_thermo, sub, add, dot, cross, norm,
                   scale, outer6, VOIGT)

P = {  # 0-based indices into a pair/gran/local row
    "x1": slice(0, 3), "x2": slice(3, 6), "v1": slice(6, 9), "v2": slice(9, 12),
    "id1": 12, "id2": 13, "per": 14, "f": slice(15, 18), "fn": slice(18, 21),
    "ft": slice(21, 24), "t": slice(24, 27), "tn": slice(27, 30),
    "tt": slice(30, 33), "hist": slice(33, 36), "area": 36, "delta": 37,
    "cp": slice(38, 41)}
W = {  # 0-based indices into a wall/gran/local row
    "cpw": slice(0, 3), "x": slice(3, 6), "vw": slice(6, 9), "v": slice(9, 12),
    "mesh": 12, "tri": 13, "id": 14, "f": slice(15, 18), "fn": slice(18, 21),
    "ft": slice(21, 24), "t": slice(24, 27), "tn": slice(27, 30),
    "tt": slice(30, 33), "hist": slice(33, 36), "area": 36, "delta": 37,
    "cp": slice(38, 41)}


class Box:
    """Periodic box from a dump header (orthogonal or triclinic)."""
    def __init__(self, snap, periodic=(False, False, False)):
        b = snap["box"]
        if "xy" in snap["boxhdr"]:
            xy, xz, yz = b[0][2], b[1][2], b[2][2]
            xlo = b[0][0] - min(0.0, xy, xz, xy + xz)
            xhi = b[0][1] - max(0.0, xy, xz, xy + xz)
            ylo = b[1][0] - min(0.0, yz)
            yhi = b[1][1] - max(0.0, yz)
            zlo, zhi = b[2][0], b[2][1]
        else:
            xy = xz = yz = 0.0
            (xlo, xhi), (ylo, yhi), (zlo, zhi) = [r[:2] for r in b]
        self.lo = [xlo, ylo, zlo]
        self.L = [xhi - xlo, yhi - ylo, zhi - zlo]
        self.xy, self.xz, self.yz = xy, xz, yz
        self.per = periodic

    def minimg(self, d):
        """minimum-image version of separation d; returns (d', shifted?)"""
        d = list(d)
        shifted = False
        # z, then y, then x (LAMMPS convention for triclinic)
        if self.per[2]:
            n = round(d[2] / self.L[2])
            if n:
                shifted = True
                d[2] -= n * self.L[2]; d[1] -= n * self.yz; d[0] -= n * self.xz
        if self.per[1]:
            n = round(d[1] / self.L[1])
            if n:
                shifted = True
                d[1] -= n * self.L[1]; d[0] -= n * self.xy
        if self.per[0]:
            n = round(d[0] / self.L[0])
            if n:
                shifted = True
                d[0] -= n * self.L[0]
        return d, shifted


def atoms_by_id(snap):
    c = snap["cols"]
    ix = {name: k for k, name in enumerate(c)}
    out = {}
    for r in snap["rows"]:
        out[int(r[ix["id"]])] = {
            "x": [r[ix["x"]], r[ix["y"]], r[ix["z"]]],
            "v": [r[ix["vx"]], r[ix["vy"]], r[ix["vz"]]],
            "f": [r[ix["fx"]], r[ix["fy"]], r[ix["fz"]]],
            "r": r[ix["radius"]], "m": r[ix["mass"]],
            "S": [r[ix["c_stress[%d]" % k]] for k in range(1, 7)],
            "type": int(r[ix["type"]])}
    return out


class Stat:
    """running max of a (relative) deviation"""
    def __init__(self): self.max = 0.0; self.n = 0
    def add(self, v):
        self.n += 1
        if v > self.max: self.max = v


def relvec(a, b, scale_=None):
    d = norm(sub(a, b))
    s = scale_ if scale_ is not None else max(norm(a), norm(b))
    return d / s if s > 0 else d


def check_pairs(snap_a, snap_p, box, verbose_torque=True):
    """Verify one pair/gran/local snapshot against the per-atom snapshot.
    Returns dict of statistics (max deviations) and the contact virial sum."""
    A = atoms_by_id(snap_a)
    st = {k: Stat() for k in (
        "pos1", "pos2", "vel1", "vel2", "delta_abs", "delta_rel", "f_eq_fn_ft",
        "fn_parallel", "ft_perp", "t_eq_tn_tt", "tn_over_t", "t_perp",
        "cp_formula", "cp_between", "area", "torque_A", "torque_B", "torque_C",
        "hist_perp", "delta_rel_big", "area_big", "ft_antipar_hist")}
    n_attractive = 0
    n_periodic_flag = 0
    n_needs_image = 0
    flag_mismatch = 0
    id1_gt_id2 = 0
    virial = [0.0] * 6          # sum_c (x1 - x2) (x) F1   (LAMMPS virial)
    peratom_pair = {i: [0.0] * 6 for i in A}  # -1/2 sum (x1-x2)(x)F1 per atom
    pairforce = {i: [0.0, 0.0, 0.0] for i in A}
    for r in snap_p["rows"]:
        i1, i2 = int(r[P["id1"]]), int(r[P["id2"]])
        a1, a2 = A[i1], A[i2]
        x1, x2 = r[P["x1"]], r[P["x2"]]
        st["pos1"].add(norm(sub(x1, a1["x"])))
        st["pos2"].add(norm(sub(x2, a2["x"])))
        st["vel1"].add(norm(sub(r[P["v1"]], a1["v"])))
        st["vel2"].add(norm(sub(r[P["v2"]], a2["v"])))
        if i1 > i2: id1_gt_id2 += 1
        d12, shifted = box.minimg(sub(x1, x2))      # x1 - x2
        per = int(r[P["per"]])
        n_periodic_flag += per
        n_needs_image += shifted
        if per != int(shifted): flag_mismatch += 1
        dist = norm(d12)
        n12 = scale(-1.0 / dist, d12)               # unit vector 1 -> 2
        delta = r[P["delta"]]
        dgeo = a1["r"] + a2["r"] - dist
        st["delta_abs"].add(abs(dgeo - delta))
        st["delta_rel"].add(abs(dgeo - delta) / delta)
        if delta > 1e-6:
            st["delta_rel_big"].add(abs(dgeo - delta) / delta)
        F, Fn, Ft = r[P["f"]], r[P["fn"]], r[P["ft"]]
        st["f_eq_fn_ft"].add(relvec(F, add(Fn, Ft)))
        st["fn_parallel"].add(norm(cross(Fn, n12)) / norm(Fn))
        st["ft_perp"].add(abs(dot(Ft, n12)) / max(norm(F), 1e-300))
        if dot(F, n12) > 0: n_attractive += 1
        T, Tn, Tt = r[P["t"]], r[P["tn"]], r[P["tt"]]
        if norm(T) > 0:
            st["t_eq_tn_tt"].add(relvec(T, add(Tn, Tt)))
            st["tn_over_t"].add(norm(Tn) / norm(T))
            st["t_perp"].add(abs(dot(T, n12)) / norm(T))
            # candidate lever arms for the torque column
            armA = scale(a1["r"] - 0.5 * delta, n12)   # centre 1 -> mid of overlap
            armB = scale(a1["r"], n12)                  # full radius
            armC = scale(dist * a1["r"] / (a1["r"] + a2["r"]), n12)  # -> contactPoint
            for key, arm in (("torque_A", armA), ("torque_B", armB), ("torque_C", armC)):
                st[key].add(relvec(T, cross(arm, Ft)))
        # contact point
        cpf = [(a1["x"][k] * a2["r"] + (a1["x"][k] - d12[k]) * a1["r"]) /
               (a1["r"] + a2["r"]) for k in range(3)]
        cp = r[P["cp"]]
        st["cp_formula"].add(norm(sub(cp, cpf)))
        # position of cp along the branch 1->2 (0 = centre 1, 1 = centre 2)
        t = dot(sub(cp, x1), scale(-1.0, d12)) / dist**2
        off = norm(sub(sub(cp, x1), scale(-t, d12)))
        st["cp_between"].add(0.0 if (0.0 <= t <= 1.0 and off < 1e-4 * dist + 1e-12) else 1.0)
        # contact area = pi a^2 of the lens circle
        R1, R2 = a1["r"], a2["r"]
        a2_ = -0.25 * ((dist-R1-R2)*(dist+R1-R2)*(dist-R1+R2)*(dist+R1+R2)) / dist**2
        st["area"].add(abs(math.pi * a2_ - r[P["area"]]) / r[P["area"]])
        if delta > 1e-6:
            st["area_big"].add(abs(math.pi * a2_ - r[P["area"]]) / r[P["area"]])
        h = r[P["hist"]]
        if norm(h) > 0:
            st["hist_perp"].add(abs(dot(h, n12)) / norm(h))
            if norm(Ft) > 0:
                # 1 + cos(angle(Ft, hist)): 0 if Ft is exactly anti-parallel to hist
                st["ft_antipar_hist"].add(1.0 + dot(Ft, h) / (norm(Ft) * norm(h)))
        w = outer6(d12, F)
        for k in range(6):
            virial[k] += w[k]
            peratom_pair[i1][k] += -0.5 * w[k]
            peratom_pair[i2][k] += -0.5 * w[k]
        for k in range(3):
            pairforce[i1][k] += F[k]
            pairforce[i2][k] -= F[k]
    return {"stats": st, "n": len(snap_p["rows"]), "n_attractive": n_attractive,
            "n_periodic_flag": n_periodic_flag, "n_needs_image": n_needs_image,
            "flag_mismatch": flag_mismatch, "id1_gt_id2": id1_gt_id2,
            "virial": virial, "peratom_pair": peratom_pair,
            "pairforce": pairforce, "atoms": A}


def stress_peratom_check(A, peratom_pair, fix_part=None):
    """max over atoms/components of |S_dump - (ke + pair)| / max|S_dump|"""
    smax = max(abs(s) for a in A.values() for s in a["S"]) or 1.0
    worst = 0.0
    for i, a in A.items():
        ke = [-a["m"] * a["v"][p] * a["v"][q] for (p, q) in VOIGT]
        for k in range(6):
            pred = ke[k] + peratom_pair[i][k]
            worst = max(worst, abs(a["S"][k] - pred) / smax)
    return worst, smax


def rel6(a, b):
    """|a-b| / |a| over the 6 Voigt components (Frobenius-like)"""
    num = math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))
    den = math.sqrt(sum(x * x for x in a))
    return num / den if den > 0 else num


def fmt(x):
    return "%.3e" % x
