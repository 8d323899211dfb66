#!/usr/bin/env python3
"""Verify the case-3 (triclinic) data: the mapping, the triclinic dump header,
the raw LIGGGHTS run-0 dumps in the tilted box, and the assembled complete
data set (periodic contacts across tilted faces), including stress/atom vs.
contact virial.  Usage: python3 check_triclinic.py  (inside triclinic/)."""
import os, sys, math, gzip
HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True     # keep the data folder free of __pycache__
sys.path.insert(0, os.path.dirname(HERE))
from check_common import *

def find(name, d=HERE):
    for cand in (name, name + ".gz"):
        p = os.path.join(d, cand)
        if os.path.exists(p):
            return p
    raise SystemExit("missing " + name)

# ---- exact box from data.triclinic and log.triclinic
data = {}
datapos = {}
sec = None
for ln in open(find("data.triclinic")):
    w = ln.split()
    if not w: continue
    if w[-2:] == ["xlo", "xhi"]: data["x"] = [float(w[0]), float(w[1])]
    elif w[-2:] == ["ylo", "yhi"]: data["y"] = [float(w[0]), float(w[1])]
    elif w[-2:] == ["zlo", "zhi"]: data["z"] = [float(w[0]), float(w[1])]
    elif w[-3:] == ["xy", "xz", "yz"]: data["t"] = [float(v) for v in w[:3]]
    elif w[0] in ("Atoms", "Velocities"): sec = w[0]
    elif sec == "Atoms": datapos[int(w[0])] = [float(v) for v in w[4:7]]
th = read_log_thermo(find("log.triclinic"))[-1]
print("exact box (log.triclinic, %.17g):")
for k in ("Xlo", "Xhi", "Ylo", "Yhi", "Zlo", "Zhi", "Xy", "Xz", "Yz", "Volume"):
    print("  %-6s %.17g" % (k, th[k]))
ex = [th["Xlo"], th["Xhi"], th["Ylo"], th["Yhi"], th["Zlo"], th["Zhi"], th["Xy"], th["Xz"], th["Yz"]]
dd = data["x"] + data["y"] + data["z"] + data["t"]
print("  max |log - data.triclinic| = %s" % fmt(max(abs(a - b) for a, b in zip(ex, dd))))
V = (th["Xhi"] - th["Xlo"]) * (th["Yhi"] - th["Ylo"]) * (th["Zhi"] - th["Zlo"])
print("  |Volume - Lx*Ly*Lz|/V = %s" % fmt(abs(V - th["Volume"]) / V))
exact = {"boxhdr": "ITEM: BOX BOUNDS xy xz yz pp pp pp",
         "box": [[0, 0, th["Xy"]], [0, 0, th["Xz"]], [th["Zlo"], th["Zhi"], th["Yz"]]]}
xy, xz, yz = th["Xy"], th["Xz"], th["Yz"]
# bounding box as written in the dump header
bb = [[th["Xlo"] + min(0, xy, xz, xy + xz), th["Xhi"] + max(0, xy, xz, xy + xz), xy],
      [th["Ylo"] + min(0, yz), th["Yhi"] + max(0, yz), xz],
      [th["Zlo"], th["Zhi"], yz]]
exact["box"] = bb
box = Box(exact, (True, True, True))

def report_pairs(title, atom_file, pgl_file, sums=None, tag=""):
    sa = read_dump(find(atom_file))[0]
    sp = read_dump(find(pgl_file))[0]
    print()
    print("%s: %s + %s, step %d, %d atoms, %d contacts" % (title, atom_file, pgl_file, sa["step"], sa["n"], sp["n"]))
    print("  header: %s" % sa["boxhdr"])
    hb = Box(sa, (True, True, True))
    print("  header box -> lo %s, L %s, tilt %s" % (" ".join("%.6g" % v for v in hb.lo), " ".join("%.6g" % v for v in hb.L),
          " ".join("%.6g" % v for v in (hb.xy, hb.xz, hb.yz))))
    print("  max |header bound - exact bound| = %s m" % fmt(max(abs(sa["box"][i][j] - bb[i][j]) for i in range(3) for j in range(3))))
    res = check_pairs(sa, sp, box)
    st = res["stats"]
    A = res["atoms"]
    print("  max |x(dump) - x(data.triclinic)| = %s m" % fmt(max(norm(sub(A[i]["x"], datapos[i])) for i in A)))
    for key, what in (("delta_abs", "|r1+r2-|x1-x2|_minimg(tilted) - c38| [m]"),
                      ("delta_rel_big", "  same, relative, c38 > 1e-6 m"),
                      ("f_eq_fn_ft", "|F - (Fn+Ft)|/|F|"), ("fn_parallel", "|Fn x n12|/|Fn|"),
                      ("ft_perp", "|Ft . n12|/|F|"), ("t_eq_tn_tt", "|T - (Tn+Tt)|/|T|"),
                      ("torque_A", "|T - ((r1-delta/2) n12) x Ft|/|T|"),
                      ("cp_formula", "|c39-41 - (x1 r2 + x2' r1)/(r1+r2)| [m]"),
                      ("area_big", "|pi a^2 - c37|/c37, c38 > 1e-6 m")):
        print("  %-46s max %s" % (what, fmt(st[key].max)))
    print("  rows with periodic flag 1: %d; rows needing a (tilted) periodic image: %d; mismatches: %d"
          % (res["n_periodic_flag"], res["n_needs_image"], res["flag_mismatch"]))
    print("  contacts with F.n12 > 0: %d;  |Ft| > 0 in %d rows;  max |hist| = %s"
          % (res["n_attractive"], sum(1 for r in sp["rows"] if norm(r[P["ft"]]) > 0),
             fmt(max(norm(r[P["hist"]]) for r in sp["rows"]))))
    fscale = max([norm(r[P["f"]]) for r in sp["rows"]])
    fb = max(norm(sub(a["f"], res["pairforce"][i])) for i, a in A.items()) / fscale
    print("  force balance: max |f_atom - sum_pairs(+F if id1, -F if id2)| / max|F| = %s" % fmt(fb))
    worst, smax = stress_peratom_check(A, res["peratom_pair"])
    print("  per-atom: max |c_stress - (-m v v - 1/2 sum_c r12 (x) F1)| / max|c_stress| = %s" % fmt(worst))
    contact = [-v for v in res["virial"]]
    dumpsum = [sum(a["S"][k] for a in A.values()) for k in range(6)]
    if sums is not None:
        sumP = [sums["sumP[%d]" % k] for k in range(1, 7)]
        sumS = [sums["sumS[%d]" % k] for k in range(1, 7)]
        sumK = [sums["sumK[%d]" % k] for k in range(1, 7)]
        print("  rel |sumP(log) - (-sum_c r12 (x) F1)|      = %s" % fmt(rel6(sumP, contact)))
        print("  rel |sumS(log) - (sumP + sumK)(log)|       = %s" % fmt(rel6(sumS, [p + k for p, k in zip(sumP, sumK)])))
        print("  rel |sumS(log) - sum of dumped c_stress|   = %s" % fmt(rel6(sumS, dumpsum)))
    print("  sum c_stress / V (N/m^2; xx yy zz xy xz yz): " + " ".join("%.6e" % (v / th["Volume"]) for v in dumpsum))
    return res, sp

# ---- mapping check against the case-2 snapshot
src = read_dump(find("dump.periodic.atom", os.path.join(HERE, "..", "periodic_box")))
snap = [s for s in src if s["step"] == 84000][0]
t2 = {int(t["Step"]): t for t in read_log_thermo(find("log.periodic", os.path.join(HERE, "..", "periodic_box")))}[84000]
lo0 = [t2["Xlo"], t2["Ylo"], t2["Zlo"]]; L0 = [t2["Xhi"] - t2["Xlo"], t2["Yhi"] - t2["Ylo"], t2["Zhi"] - t2["Zlo"]]
A0 = atoms_by_id(snap)
worst = 0.0
for i, a in A0.items():
    s0 = [((a["x"][k] - lo0[k]) / L0[k]) % 1.0 for k in range(3)]
    x = datapos[i]
    s2 = (x[2] - th["Zlo"]) / L0[2]
    s1 = (x[1] - th["Ylo"] - s2 * yz) / L0[1]
    sx = (x[0] - th["Xlo"] - s1 * xy - s2 * xz) / L0[0]
    worst = max(worst, max(abs(p - q) for p, q in zip(s0, (sx, s1, s2))))
print()
print("mapping: max |fractional coords(data.triclinic) - fractional coords(case 2, step 84000)| = %s" % fmt(worst))

raw, sp_raw = report_pairs("RAW LIGGGHTS run 0 in the triclinic box", "dump.triclinic.atom", "dump.triclinic.pgl", th)
ti = read_log_thermo(find("log.images"))[-1]
comp, sp_comp = report_pairs("ASSEMBLED complete set (image work-around)", "dump.triclinic_complete.atom",
                             "dump.triclinic_complete.pgl", ti)
# raw contacts are a subset of the complete ones (atom order 1/2 may differ)
cm = {(int(r[12]), int(r[13])): r for r in sp_comp["rows"]}
same = swapped = missing = 0
dev = 0.0; dev2 = 0.0
for r in sp_raw["rows"]:
    k = (int(r[12]), int(r[13]))
    if k in cm:
        same += 1
        dev = max(dev, max(abs(a - b) for a, b in zip(r, cm[k])))
    elif k[::-1] in cm:
        swapped += 1
        dev2 = max(dev2, norm(add(r[P["f"]], cm[k[::-1]][P["f"]])))
    else:
        missing += 1
print()
print("raw contacts in the complete set: %d same atom order (max |difference| of all 41 values %s), "
      "%d with atoms 1/2 swapped (max |F_raw + F_complete| %s N), %d missing"
      % (same, fmt(dev), swapped, fmt(dev2), missing))
print("periodic contacts only in the complete set: %d" % sum(1 for r in sp_comp["rows"] if int(r[14]) == 1))
