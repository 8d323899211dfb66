#!/usr/bin/env python3
"""Verify the case-2 (periodic box) dumps: pair/gran/local column meaning,
periodic flag, force balance, and stress/atom vs. contact virial.
Usage: python3 check_periodic.py   (inside periodic_box/; .gz or plain)."""
import os, sys, math
HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True     # keep the data folder free of __pycache__
sys.path.insert(0, os.path.dirname(HERE))
from check_common import *

def find(name):
    for cand in (name, name + ".gz"):
        p = os.path.join(HERE, cand)
        if os.path.exists(p):
            return p
    raise SystemExit("missing " + name)

GAMMA_VISCOUS = 0.002          # fix visc all viscous 0.002
DT = 1.0e-5
atoms = read_dump(find("dump.periodic.atom"))
pgl = read_dump(find("dump.periodic.pgl"))
thermo = {}
for t in read_log_thermo(find("log.periodic")):
    thermo[int(t["Step"])] = t      # later rows (next run's step-0 line) are identical
assert [s["step"] for s in atoms] == [s["step"] for s in pgl]
print("steps:", " ".join(str(s["step"]) for s in atoms))
print("atoms per snapshot:", " ".join(str(s["n"]) for s in atoms))
print("pair contacts per snapshot:", " ".join(str(s["n"]) for s in pgl))
agg = {}
tot = {"n": 0, "attr": 0, "per": 0, "img": 0, "mis": 0, "id1gt": 0}
fb = Stat(); per_atom = Stat(); rows = []
hdr_box = Stat()
dl = []; small_d = [0]
posmod = Stat(); ghost_v_half = Stat(); ghost_v_full = Stat(); local_v = Stat(); n_wrapped = [0]
for sa, sp in zip(atoms, pgl):
    th = thermo[sa["step"]]
    # exact box from the log (dump header has only 6 significant digits)
    exact = {"box": [[th["Xlo"], th["Xhi"]], [th["Ylo"], th["Yhi"]], [th["Zlo"], th["Zhi"]]],
             "boxhdr": "ITEM: BOX BOUNDS pp pp pp"}
    for k in range(3):
        for m in range(2):
            hdr_box.add(abs(sa["box"][k][m] - exact["box"][k][m]))
    box = Box(exact, (True, True, True))
    V = th["Volume"]
    assert abs(V - box.L[0] * box.L[1] * box.L[2]) <= 1e-15 * V
    res = check_pairs(sa, sp, box)
    for r in sp["rows"]:
        dl.append(r[P["delta"]]); small_d[0] += r[P["delta"]] <= 1e-6
    for k, s in res["stats"].items():
        agg.setdefault(k, Stat()).add(s.max)
    tot["n"] += res["n"]; tot["attr"] += res["n_attractive"]; tot["per"] += res["n_periodic_flag"]
    tot["img"] += res["n_needs_image"]; tot["mis"] += res["flag_mismatch"]; tot["id1gt"] += res["id1_gt_id2"]
    A = res["atoms"]
    fscale = max([norm(r[P["f"]]) for r in sp["rows"]] + [norm(b["f"]) for b in A.values()])
    for i, a in A.items():
        # fix viscous acts on the half-step velocity v(n-1/2) = v - dt/2 f/m
        vh = sub(a["v"], scale(0.5 * DT / a["m"], a["f"]))
        pred = [res["pairforce"][i][k] - GAMMA_VISCOUS * vh[k] for k in range(3)]
        fb.add(norm(sub(a["f"], pred)) / fscale)
    # positions modulo the box, ghost velocities of periodic rows
    for r in sp["rows"]:
        for col, idc in (("x1", "id1"), ("x2", "id2")):
            d, _ = box.minimg(sub(r[P[col]], A[int(r[P[idc]])]["x"]))
            posmod.add(norm(d))
            if norm(sub(r[P[col]], A[int(r[P[idc]])]["x"])) > 0.5 * min(box.L):
                n_wrapped[0] += 1
        a2 = A[int(r[P["id2"]])]
        if int(r[P["per"]]) == 1:
            vh = sub(a2["v"], scale(0.5 * DT / a2["m"], a2["f"]))
            ghost_v_half.add(norm(sub(r[P["v2"]], vh)) / max(norm(a2["v"]), 1e-300))
            ghost_v_full.add(norm(sub(r[P["v2"]], a2["v"])) / max(norm(a2["v"]), 1e-300))
        else:
            local_v.add(norm(sub(r[P["v2"]], a2["v"])))
    worst, smax = stress_peratom_check(A, res["peratom_pair"])
    per_atom.add(worst)
    sumP = [th["sumP[%d]" % k] for k in range(1, 7)]
    sumS = [th["sumS[%d]" % k] for k in range(1, 7)]
    sumK = [th["sumK[%d]" % k] for k in range(1, 7)]
    sumF = [th["sumF[%d]" % k] for k in range(1, 7)]
    contact = [-v for v in res["virial"]]
    dumpsum = [sum(a["S"][k] for a in A.values()) for k in range(6)]
    rows.append((sa["step"], res["n"], res["n_periodic_flag"], V,
                 rel6(sumP, contact), rel6(sumS, [p + k + f for p, k, f in zip(sumP, sumK, sumF)]),
                 max(abs(v) for v in sumF), rel6(sumS, dumpsum), worst,
                 [s / V for s in sumS]))
print()
print("pair/gran/local checks over %d contact rows (all snapshots):" % tot["n"])
print("  |c1-3 or c4-6 - x(id)| modulo box            max %s  (rows where they differ by a box vector: %d)" % (fmt(posmod.max), n_wrapped[0]))
print("  |c10-12 - v(id c14)|, rows with c15=0           max %s" % fmt(local_v.max))
print("  |c10-12 - v(id c14)|/|v|, rows with c15=1       max %s" % fmt(ghost_v_full.max))
print("  |c10-12 - (v - dt/2 f/m)(id c14)|/|v|, c15=1   max %s" % fmt(ghost_v_half.max))
for key, what in (("vel1", "|c7-9  - v(id c13)|"),
                  ("delta_abs", "|r1+r2-|x1-x2|_minimg - c38|  [m]"), ("delta_rel", "  same, relative to c38"),
                  ("delta_rel_big", "  same, relative, only c38 > 1e-6 m"),
                  ("f_eq_fn_ft", "|F - (Fn+Ft)|/|F|"), ("fn_parallel", "|Fn x n12|/|Fn|"),
                  ("ft_perp", "|Ft . n12|/|F|"), ("t_eq_tn_tt", "|T - (Tn+Tt)|/|T|"),
                  ("tn_over_t", "|Tn|/|T|"), ("torque_A", "|T - ((r1-delta/2) n12) x Ft|/|T|"),
                  ("cp_formula", "|c39-41 - (x1 r2 + x2' r1)/(r1+r2)| [m] (x2' = image of 2 nearest 1)"),
                  ("area", "|pi a^2 - c37|/c37"), ("area_big", "  same, only c38 > 1e-6 m"),
                  ("hist_perp", "|hist . n12|/|hist|"),
                  ("ft_antipar_hist", "1 + cos(angle(Ft, hist))  (0 = anti-parallel)")):
    print("  %-46s max %s" % (what, fmt(agg[key].max)))
print("  contacts with F.n12 > 0: %d of %d" % (tot["attr"], tot["n"]))
print("  contacts with c38 <= 1e-6 m: %d;  min c38 = %.3e m,  max c38 = %.3e m" % (small_d[0], min(dl), max(dl)))
print("  rows with periodic flag c15 = 1: %d; rows whose x1-x2 needs a periodic image: %d; mismatches: %d"
      % (tot["per"], tot["img"], tot["mis"]))
print("  rows with id1 > id2: %d of %d" % (tot["id1gt"], tot["n"]))
print("  dump-header box vs exact (log) box: max abs diff %s m" % fmt(hdr_box.max))
print()
print("force balance f_atom = sum_pairs(+F if id1, -F if id2) - %g v(n-1/2),  v(n-1/2) = v - dt/2 f/m:" % GAMMA_VISCOUS)
print("  max over snapshots of max|resid| / max(|F_contact|,|f_atom|) = %s" % fmt(fb.max))
print()
print("stress/atom (xx yy zz xy xz yz), per step:")
print("  step  contacts  periodic  volume(log)            rel|sumP(log)+sum_c r12(x)F1|  rel|sumS-(P+K+F)|  max|sumF|  rel|sumS(log)-sum dump|  per-atom max|S-(-mvv+pair)|/max|S|")
for r in rows:
    print("  %6d  %4d  %4d  %.17g  %s  %s  %s  %s  %s" % (r[0], r[1], r[2], r[3], fmt(r[4]), fmt(r[5]), fmt(r[6]), fmt(r[7]), fmt(r[8])))
print()
print("sum_atoms c_stress / V  (N/m^2, LAMMPS sign: compression negative), last step %d:" % rows[-1][0])
print("  " + " ".join("%.6e" % v for v in rows[-1][9]))
