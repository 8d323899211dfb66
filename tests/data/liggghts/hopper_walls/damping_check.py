#!/usr/bin/env python3
"""Used by run_variants.sh (scratch experiment, not part of the data set).
For a case-1 variant with FULL-PRECISION dumps, compare each atom's dumped
force with (a) the sum of the pair/gran/local forces and (b) the sum of
normal-only Hertz forces whose damping term is evaluated with the half-step
velocities v(n-1/2) = v - dt/2 f/m (valid for coefficientFriction 0 only).
Usage: python3 damping_check.py <restitution> <friction>"""
import os, sys, math
sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from check_common import *

e, mu = float(sys.argv[1]), float(sys.argv[2])
Y, nu, dt, LX, LY = 5e6, 0.3, 1e-5, 0.06, 0.04
Ystar = Y / (2 * (1 - nu * nu))
beta = math.log(e) / math.sqrt(math.log(e) ** 2 + math.pi ** 2) if e < 1 else 0.0
atoms = read_dump("dump.hopper.atom"); pgl = read_dump("dump.hopper.pgl"); wgl = read_dump("dump.hopper.wgl")
w_raw = w_half = 0.0; n = 0; ftmax = 0.0
for sa, sp, sw in zip(atoms, pgl, wgl):
    A = atoms_by_id(sa)
    walled = {int(r[W["id"]]) for r in sw["rows"]}
    fr = {i: [0.0] * 3 for i in A}; fh = {i: [0.0] * 3 for i in A}
    for r in sp["rows"]:
        i1, i2 = int(r[P["id1"]]), int(r[P["id2"]]); a1, a2 = A[i1], A[i2]
        d = sub(r[P["x1"]], r[P["x2"]]); en = scale(1 / norm(d), d)      # 2 -> 1
        delta = r[P["delta"]]
        Rs = a1["r"] * a2["r"] / (a1["r"] + a2["r"]); ms = a1["m"] * a2["m"] / (a1["m"] + a2["m"])
        gn = -2 * math.sqrt(5 / 6) * beta * math.sqrt(2 * Ystar * math.sqrt(Rs * delta) * ms)
        vh1 = sub(a1["v"], scale(0.5 * dt / a1["m"], a1["f"]))
        vh2 = sub(a2["v"], scale(0.5 * dt / a2["m"], a2["f"]))
        Fh = scale(4 / 3 * Ystar * math.sqrt(Rs) * delta ** 1.5 - gn * dot(sub(vh1, vh2), en), en)
        if norm(r[P["f"]]) > 0:
            ftmax = max(ftmax, norm(r[P["ft"]]) / norm(r[P["f"]]))
        for k in range(3):
            fr[i1][k] += r[P["f"]][k]; fr[i2][k] -= r[P["f"]][k]
            fh[i1][k] += Fh[k]; fh[i2][k] -= Fh[k]
    for i, a in A.items():
        x, rr = a["x"], a["r"]
        if x[0] < rr or x[0] > LX - rr or x[1] < rr or x[1] > LY - rr or x[2] < rr or i in walled:
            continue
        g = [0.0, 0.0, -9.81 * a["m"]]; n += 1
        w_raw = max(w_raw, norm(sub(a["f"], add(fr[i], g))) / (9.81 * a["m"]))
        w_half = max(w_half, norm(sub(a["f"], add(fh[i], g))) / (9.81 * a["m"]))
print("e=%g mu=%g: %d atom-snapshots without wall contact" % (e, mu, n))
print("  max |f - (sum pair/gran/local F + m g)|/(m g)                    = %.3e" % w_raw)
print("  max |f - (sum normal-only Hertz F at v(n-1/2) + m g)|/(m g)     = %.3e%s"
      % (w_half, "" if mu == 0 else "   (not meaningful, mu > 0)"))
print("  max |Ft|/|F| in pair/gran/local                                  = %.3e" % ftmax)
