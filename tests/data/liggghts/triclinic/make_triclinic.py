#!/usr/bin/env python3
"""Map one snapshot of case 2 (../periodic_box, step 84000) affinely onto a
triclinic periodic box and write it as a LIGGGHTS/LAMMPS data file.

  s  = (x - lo) / L  (fractional coordinates in the orthogonal box,
                      wrapped into [0,1); image flags adjusted accordingly)
  x' = lo + H s,   H = [[Lx, xy, xz], [0, Ly, yz], [0, 0, Lz]]
  v' = F v,        F = H H0^-1 (the same linear map; omega unchanged)

with xy = 0.10 Lx, xz = -0.07 Lx, yz = 0.05 Ly (one negative tilt on
purpose, so that the bounding-box conversion of the dump header is exercised).
Lx, Ly, Lz and lo are the exact (%.17g) box values from ../periodic_box/log.periodic.
Plain Python 3, no numpy.  Usage: python3 make_triclinic.py
Writes data.triclinic (and prints the box)."""
import os, sys, gzip, math

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.join(HERE, "..", "periodic_box")
STEP = 84000
TILT = (0.10, -0.07, 0.05)      # xy/Lx, xz/Lx, yz/Ly
DENSITY = 2500.0                # as in ../periodic_box/in.periodic

def opn(name):
    p = os.path.join(SRC, name)
    if os.path.exists(p):
        return open(p)
    return gzip.open(p + ".gz", "rt")

# exact box at STEP from the thermo output of case 2
box = None
hdr = None
for line in opn("log.periodic"):
    w = line.split()
    if w and w[0] == "Step":
        hdr = w; continue
    if hdr and len(w) == len(hdr) and w[0] == str(STEP):
        t = dict(zip(hdr, w))
        box = [(float(t["Xlo"]), float(t["Xhi"])), (float(t["Ylo"]), float(t["Yhi"])),
               (float(t["Zlo"]), float(t["Zhi"]))]
if box is None:
    sys.exit("step %d not found in log.periodic" % STEP)
lo = [b[0] for b in box]
L = [b[1] - b[0] for b in box]
xy, xz, yz = TILT[0] * L[0], TILT[1] * L[0], TILT[2] * L[1]

# snapshot STEP of the per-atom dump
lines = opn("dump.periodic.atom").read().split("\n")
i = 0
rows = None
while i < len(lines):
    if lines[i].startswith("ITEM: TIMESTEP") and int(lines[i + 1]) == STEP:
        n = int(lines[i + 3])
        cols = lines[i + 8].split()[2:]
        rows = [lines[i + 9 + k].split() for k in range(n)]
        break
    i += 1
if rows is None:
    sys.exit("step %d not found in dump.periodic.atom" % STEP)
c = {name: k for k, name in enumerate(cols)}

atoms = []
for r in rows:
    x = [float(r[c["x"]]), float(r[c["y"]]), float(r[c["z"]])]
    img = [int(r[c["ix"]]), int(r[c["iy"]]), int(r[c["iz"]])]
    s = []
    for k in range(3):
        sk = (x[k] - lo[k]) / L[k]
        m = math.floor(sk)          # atoms not yet re-wrapped by LIGGGHTS
        sk -= m
        img[k] += m
        s.append(sk)
    xn = [lo[0] + L[0] * s[0] + xy * s[1] + xz * s[2],
          lo[1] + L[1] * s[1] + yz * s[2],
          lo[2] + L[2] * s[2]]
    v = [float(r[c["vx"]]), float(r[c["vy"]]), float(r[c["vz"]])]
    # F = H H0^-1 with H0 = diag(L)
    vn = [v[0] + xy / L[1] * v[1] + xz / L[2] * v[2],
          v[1] + yz / L[2] * v[2],
          v[2]]
    om = [float(r[c["omegax"]]), float(r[c["omegay"]]), float(r[c["omegaz"]])]
    atoms.append((int(r[c["id"]]), int(r[c["type"]]), 2.0 * float(r[c["radius"]]), xn, img, vn, om))
atoms.sort()

out = os.path.join(HERE, "data.triclinic")
with open(out, "w") as f:
    f.write("LIGGGHTS data file: case-2 snapshot step %d mapped to a triclinic box "
            "(xy=%.2f*Lx xz=%.2f*Lx yz=%.2f*Ly), written by make_triclinic.py\n\n"
            % (STEP, TILT[0], TILT[1], TILT[2]))
    f.write("%d atoms\n2 atom types\n\n" % len(atoms))
    f.write("%.17g %.17g xlo xhi\n" % box[0])
    f.write("%.17g %.17g ylo yhi\n" % box[1])
    f.write("%.17g %.17g zlo zhi\n" % box[2])
    f.write("%.17g %.17g %.17g xy xz yz\n\n" % (xy, xz, yz))
    # atom_style granular (sphere): atom-ID atom-type diameter density x y z ix iy iz
    f.write("Atoms\n\n")
    for a in atoms:
        f.write("%d %d %.17g %.17g %.17g %.17g %.17g %d %d %d\n"
                % (a[0], a[1], a[2], DENSITY, a[3][0], a[3][1], a[3][2], a[4][0], a[4][1], a[4][2]))
    # sphere velocities: atom-ID vx vy vz omegax omegay omegaz
    f.write("\nVelocities\n\n")
    for a in atoms:
        f.write("%d %.17g %.17g %.17g %.17g %.17g %.17g\n" % ((a[0],) + tuple(a[5]) + tuple(a[6])))
print("source: %s step %d, %d atoms" % (os.path.join("..", "periodic_box", "dump.periodic.atom"), STEP, len(atoms)))
print("box lo = %.17g %.17g %.17g" % tuple(lo))
print("L      = %.17g %.17g %.17g" % tuple(L))
print("xy xz yz = %.17g %.17g %.17g" % (xy, xz, yz))
print("volume = %.17g" % (L[0] * L[1] * L[2]))
print("wrote", out)
