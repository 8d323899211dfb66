#!/usr/bin/env python3
"""Verify the column meaning of the case-1 dumps against each other.
Usage: python3 check_hopper.py   (run inside hopper_walls/; reads .gz or plain)
Output is what check_output.txt contains."""
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

atoms = read_dump(find("dump.hopper.atom"))
pgl = read_dump(find("dump.hopper.pgl"))
wgl = read_dump(find("dump.hopper.wgl"))
thermo = {int(t["Step"]): t for t in read_log_thermo(find("log.hopper"))}
assert [s["step"] for s in atoms] == [s["step"] for s in pgl] == [s["step"] for s in wgl]
LX, LY = 0.06, 0.04
g = [0.0, 0.0, -9.81]
box = Box(atoms[0], (False, False, False))

print("steps:", " ".join(str(s["step"]) for s in atoms))
print("atoms per snapshot:", " ".join(str(s["n"]) for s in atoms))
print("pair contacts per snapshot:", " ".join(str(s["n"]) for s in pgl))
print("mesh-wall contacts per snapshot:", " ".join(str(s["n"]) for s in wgl))
print("pair/gran/local columns:", len(pgl[-1]["cols"]), " wall/gran/local columns:", len(wgl[-1]["cols"]))
agg = {}
tot = {"n": 0, "attr": 0, "per": 0, "id1gt": 0}
wst = {k: Stat() for k in ("pos", "vel", "vwall0", "delta", "f_eq", "fn_par",
                            "ft_perp", "area", "t_eq", "tn", "torqueA", "cp39_zero",
                            "cpw_on_plane")}
w_sign_bad = 0
w_tri = {}
prim_contacts = 0
fb = Stat(); fb_n = 0
stress_rows = []
for sa, sp, sw in zip(atoms, pgl, wgl):
    res = check_pairs(sa, sp, box)
    for k, s in res["stats"].items():
        agg.setdefault(k, Stat()).add(s.max)
    tot["n"] += res["n"]; tot["attr"] += res["n_attractive"]
    tot["per"] += res["n_periodic_flag"]; tot["id1gt"] += res["id1_gt_id2"]
    A = res["atoms"]
    # ---- wall contacts
    wallforce = {i: [0.0, 0.0, 0.0] for i in A}
    wall_peratom = {i: [0.0] * 6 for i in A}
    for r in sw["rows"]:
        i = int(r[W["id"]]); a = A[i]
        x, cpw = r[W["x"]], r[W["cpw"]]
        wst["pos"].add(norm(sub(x, a["x"])))
        wst["vel"].add(norm(sub(r[W["v"]], a["v"])))
        wst["vwall0"].add(norm(r[W["vw"]]))
        d = sub(x, cpw); dist = norm(d); nw = scale(1.0 / dist, d)  # wall -> particle
        wst["delta"].add(abs((a["r"] - dist) - r[W["delta"]]) / r[W["delta"]])
        F, Fn, Ft = r[W["f"]], r[W["fn"]], r[W["ft"]]
        wst["f_eq"].add(relvec(F, add(Fn, Ft)))
        wst["fn_par"].add(norm(cross(Fn, nw)) / norm(Fn))
        wst["ft_perp"].add(abs(dot(Ft, nw)) / norm(F))
        if dot(F, nw) <= 0: w_sign_bad += 1
        dl = r[W["delta"]]
        wst["area"].add(abs(math.pi * (a["r"]**2 - (a["r"] - dl)**2) - r[W["area"]]) / r[W["area"]])
        T = r[W["t"]]
        if norm(T) > 0:
            wst["t_eq"].add(relvec(T, add(r[W["tn"]], r[W["tt"]])))
            wst["tn"].add(norm(r[W["tn"]]) / norm(T))
            wst["torqueA"].add(relvec(T, cross(scale(-(a["r"] - 0.5 * dl), nw), Ft)))
        wst["cp39_zero"].add(norm(r[W["cp"]]))
        tri = int(r[W["tri"]]); side = "left" if cpw[0] < 0.03 else "right"
        w_tri.setdefault((int(r[W["mesh"]]), tri), set()).add(side)
        # contact point on the plate plane: z = 0.04 - (28/22) x  or  z = 0.012 + (28/22)(x-0.038)
        s_ = 28.0 / 22.0
        zpl = 0.04 - s_ * cpw[0] if side == "left" else 0.012 + s_ * (cpw[0] - 0.038)
        wst["cpw_on_plane"].add(abs(cpw[2] - zpl))
        for k in range(3): wallforce[i][k] += F[k]
    # atoms touching primitive walls (not reported by wall/gran/local)
    touching = set()
    for i, a in A.items():
        x, rr = a["x"], a["r"]
        if x[0] < rr or x[0] > LX - rr or x[1] < rr or x[1] > LY - rr or x[2] < rr:
            touching.add(i)
    prim_contacts += len(touching)
    # force balance f_atom = pair + mesh wall + m g for atoms not touching primitive walls
    fscale = max(norm(a["f"]) for a in A.values())
    for i, a in A.items():
        if i in touching: continue
        pred = [res["pairforce"][i][k] + wallforce[i][k] + a["m"] * g[k] for k in range(3)]
        fb.add(norm(sub(a["f"], pred)) / max(a["m"] * 9.81, 1e-300)); fb_n += 1
    # stress: per atom (atoms not touching any wall), and sums
    smax = max(abs(s) for a in A.values() for s in a["S"]) or 1.0
    worst = 0.0
    for i, a in A.items():
        if i in touching or norm(wallforce[i]) > 0: continue
        ke = [-a["m"] * a["v"][p] * a["v"][q] for (p, q) in VOIGT]
        for k in range(6):
            worst = max(worst, abs(a["S"][k] - ke[k] - res["peratom_pair"][i][k]) / smax)
    th = thermo[sa["step"]]
    sumP = [th["sumP[%d]" % k] for k in range(1, 7)]
    sumS = [th["sumS[%d]" % k] for k in range(1, 7)]
    sumK = [th["sumK[%d]" % k] for k in range(1, 7)]
    sumF = [th["sumF[%d]" % k] for k in range(1, 7)]
    contact = [-v for v in res["virial"]]
    dumpsum = [sum(a["S"][k] for a in A.values()) for k in range(6)]
    kesum = [sum(-a["m"] * a["v"][p] * a["v"][q] for a in A.values()) for (p, q) in VOIGT]
    stress_rows.append((sa["step"], rel6(sumP, contact) if res["n"] else float("nan"),
                        rel6(sumS, [p + k + f for p, k, f in zip(sumP, sumK, sumF)]),
                        max(abs(v) for v in sumF), rel6(sumS, dumpsum), rel6(sumK, kesum), worst))

def line(name, key, what):
    print("  %-44s max %s" % (what, fmt(agg[key].max)))
print()
print("pair/gran/local checks over %d contact rows (all snapshots):" % tot["n"])
line("", "pos1", "|c1-3  - x(id c13)|  [m]")
line("", "pos2", "|c4-6  - x(id c14)|  [m]")
line("", "vel1", "|c7-9  - v(id c13)|  [m/s]")
line("", "vel2", "|c10-12 - v(id c14)| [m/s]")
line("", "delta_abs", "|r1+r2-|x1-x2| - c38|  [m]")
line("", "delta_rel", "  same, relative to c38")
line("", "delta_rel_big", "  same, relative, only c38 > 1e-6 m")
line("", "f_eq_fn_ft", "|c16-18 - (c19-21 + c22-24)|/|F|")
line("", "fn_parallel", "|c19-21 x n12|/|Fn|")
line("", "ft_perp", "|c22-24 . n12|/|F|")
line("", "t_eq_tn_tt", "|c25-27 - (c28-30 + c31-33)|/|T|")
line("", "tn_over_t", "|c28-30|/|T|")
line("", "t_perp", "|T . n12|/|T|")
line("", "torque_A", "|T - ((r1-delta/2) n12) x Ft|/|T|")
line("", "torque_B", "|T - (r1 n12) x Ft|/|T|")
line("", "torque_C", "|T - (x_cp - x1) x Ft|/|T|")
line("", "cp_formula", "|c39-41 - (x1 r2 + x2 r1)/(r1+r2)|  [m]")
line("", "cp_between", "contact point off segment 1-2 (1=yes)")
line("", "area", "|pi a^2 - c37|/c37 (lens radius a)")
line("", "area_big", "  same, only c38 > 1e-6 m")
line("", "hist_perp", "|c34-36 . n12|/|hist|")
line("", "ft_antipar_hist", "1 + cos(angle(Ft, hist)) (0 = anti-parallel)")
print("  contacts with F(c16-18).n12 > 0 (n12 = unit 1->2): %d of %d" % (tot["attr"], tot["n"]))
print("  periodic flag c15 = 1: %d;  rows with id1 > id2: %d" % (tot["per"], tot["id1gt"]))
print()
print("force balance f_atom = sum_pairs(+F if id1, -F if id2) + sum_meshwall F + m g,")
print("  for %d atom-snapshots not touching a primitive wall: max |resid|/(m g) = %s"
      % (fb_n, fmt(fb.max)))
print()
print("wall/gran/local checks (mesh hopper only):")
for k, what in (("pos", "|c4-6 - x(id c15)|"), ("vel", "|c10-12 - v(id c15)|"),
                ("vwall0", "|c7-9| (wall velocity)"), ("delta", "|(r - |x - c1-3|) - c38|/c38"),
                ("f_eq", "|F - (Fn+Ft)|/|F|"), ("fn_par", "|Fn x n_wall->particle|/|Fn|"),
                ("ft_perp", "|Ft . n|/|F|"), ("area", "|pi(r^2-(r-delta)^2) - c37|/c37"),
                ("t_eq", "|T - (Tn+Tt)|/|T|"), ("tn", "|Tn|/|T|"),
                ("torqueA", "|T - (-(r-delta/2) n) x Ft|/|T|"),
                ("cp39_zero", "|c39-41| (contactPoint, walls)"),
                ("cpw_on_plane", "distance of c1-3 from the plate plane [m]")):
    print("  %-44s max %s" % (what, fmt(wst[k].max)))
print("  rows with F.(x - c1-3) <= 0: %d" % w_sign_bad)
print("  (c13 mesh index, c14 triangle id) -> plate:", {k: sorted(v) for k, v in sorted(w_tri.items())})
print("  atom-snapshots touching a primitive wall (absent from wall/gran/local): %d" % prim_contacts)
print()
print("stress/atom (c_stress[1..6] = xx yy zz xy xz yz), per step:")
print("  step   rel|sumP(log) - (-sum_c r12(x)F1)|  rel|sumS-(P+K+F)|  max|sumF|  rel|sumS(log)-sum dump|  rel|sumK(log)-sum(-m v v)|  per-atom max|S-(ke+pair)|/max|S| (atoms w/o wall contact)")
for row in stress_rows:
    print("  %6d  %s  %s  %s  %s  %s  %s" % (row[0],) + tuple(fmt(v) for v in row[1:]) if False else
          "  %6d  %-10s  %-10s  %-10s  %-10s  %-10s  %-10s" % ((row[0],) + tuple(fmt(v) for v in row[1:])))
