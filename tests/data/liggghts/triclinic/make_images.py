#!/usr/bin/env python3
"""Work-around for the missing periodic ghost atoms of LIGGGHTS 3.8 (Debian)
in triclinic boxes (see README.md): write data.images, an ORTHOGONAL,
NON-periodic system that contains the 300 atoms of data.triclinic (ids 1-300)
plus explicit periodic images of them.  Image of atom `id` shifted by
n = (nx, ny, nz) in {-1,0,1}^3 \\ {0} gets the id  id + 1000*k,  with
k = 1 + index of n in the list SHIFTS below (k = 1..26).  Only images whose
centre is within SHELL of the triclinic cell are written (SHELL >= largest
contact distance r_i + r_j = 5 mm, plus margin), so every contact of an
original atom with a periodic image of another atom is present.
Plain Python 3.  Usage: python3 make_images.py  (needs data.triclinic)."""
import os, itertools

HERE = os.path.dirname(os.path.abspath(__file__))
SHELL = 0.0055
SHIFTS = [n for n in itertools.product((-1, 0, 1), repeat=3) if n != (0, 0, 0)]

lines = open(os.path.join(HERE, "data.triclinic")).read().split("\n")
box = {}
atoms, vels = [], {}
sec = None
for ln in lines:
    w = ln.split()
    if not w:
        continue
    if w[-2:] == ["xlo", "xhi"]: box["x"] = (float(w[0]), float(w[1])); continue
    if w[-2:] == ["ylo", "yhi"]: box["y"] = (float(w[0]), float(w[1])); continue
    if w[-2:] == ["zlo", "zhi"]: box["z"] = (float(w[0]), float(w[1])); continue
    if w[-3:] == ["xy", "xz", "yz"]: box["t"] = tuple(float(v) for v in w[:3]); continue
    if w[0] in ("Atoms", "Velocities"):
        sec = w[0]; continue
    if sec == "Atoms":
        atoms.append(w)
    elif sec == "Velocities":
        vels[w[0]] = w[1:]
lo = [box["x"][0], box["y"][0], box["z"][0]]
L = [box["x"][1] - lo[0], box["y"][1] - lo[1], box["z"][1] - lo[2]]
xy, xz, yz = box["t"]
A = (L[0], 0.0, 0.0); B = (xy, L[1], 0.0); C = (xz, yz, L[2])

def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def nrm(a): return sum(v*v for v in a) ** 0.5
V = L[0] * L[1] * L[2]
# shell thickness in fractional units along a, b, c (face-normal widths)
w = [SHELL * nrm(cross(B, C)) / V, SHELL * nrm(cross(C, A)) / V, SHELL * nrm(cross(A, B)) / V]

def frac(x):
    # inverse of x = lo + s0 A + s1 B + s2 C (upper-triangular)
    s2 = (x[2] - lo[2]) / L[2]
    s1 = (x[1] - lo[1] - s2 * yz) / L[1]
    s0 = (x[0] - lo[0] - s1 * xy - s2 * xz) / L[0]
    return (s0, s1, s2)

out_atoms = []
for a in atoms:
    aid = int(a[0])
    assert aid < 1000
    x = [float(v) for v in a[4:7]]
    out_atoms.append((aid, a[1], a[2], a[3], x, vels[a[0]]))
    for k, n in enumerate(SHIFTS, start=1):
        xi = [x[d] + n[0] * A[d] + n[1] * B[d] + n[2] * C[d] for d in range(3)]
        s = frac(xi)
        if all(-w[d] <= s[d] <= 1.0 + w[d] for d in range(3)):
            out_atoms.append((aid + 1000 * k, a[1], a[2], a[3], xi, vels[a[0]]))
mn = [min(a[4][d] for a in out_atoms) - 0.001 for d in range(3)]
mx = [max(a[4][d] for a in out_atoms) + 0.001 for d in range(3)]
with open(os.path.join(HERE, "data.images"), "w") as f:
    f.write("LIGGGHTS data file: data.triclinic + explicit periodic images (id + 1000*k), "
            "orthogonal non-periodic box, written by make_images.py\n\n")
    f.write("%d atoms\n2 atom types\n\n" % len(out_atoms))
    for d, nm in enumerate("xyz"):
        f.write("%.17g %.17g %slo %shi\n" % (mn[d], mx[d], nm, nm))
    f.write("\nAtoms\n\n")
    for a in out_atoms:
        f.write("%d %s %s %s %.17g %.17g %.17g 0 0 0\n" % (a[0], a[1], a[2], a[3], a[4][0], a[4][1], a[4][2]))
    f.write("\nVelocities\n\n")
    for a in out_atoms:
        f.write("%d %s\n" % (a[0], " ".join(a[5])))
print("SHIFTS (k = 1..26):", " ".join("%d:%s" % (k, "".join("%+d" % v for v in n)) for k, n in enumerate(SHIFTS, 1)))
print("originals %d, images %d, total %d" % (len(atoms), len(out_atoms) - len(atoms), len(out_atoms)))
