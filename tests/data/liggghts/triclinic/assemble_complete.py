#!/usr/bin/env python3
"""Assemble the complete triclinic data set from the image work-around run.

Inputs : dump.triclinic.atom      (LIGGGHTS run 0 in the triclinic box: box
                                   header and image flags are taken from it)
         dump.images.atom(.gz)     (LIGGGHTS run 0, originals of the image system)
         dump.images.pgl(.gz)      (LIGGGHTS run 0, all contacts of the image system)
Outputs: dump.triclinic_complete.atom, dump.triclinic_complete.pgl
         in exactly the LIGGGHTS text format, with the triclinic box header.

Rules (all numbers are copied as the strings LIGGGHTS printed, except where
stated):
 * per-atom: rows of dump.images.atom (forces and stress/atom of the
   originals are complete, they interacted with the explicit images);
   ix iy iz replaced by the flags of the same id in dump.triclinic.atom.
 * contacts between two originals: copied unchanged (periodic flag 0).
 * contacts between two images: dropped.
 * contact original-image: every periodic contact appears twice, once for
   each side (A-B' and A'-B). One row is kept, preferring a row whose atom 1
   is an original (as in LIGGGHTS' own periodic rows, where atom 1 is a local
   atom and atom 2 a ghost), and among those the one with the larger id of
   atom 1. The image id is replaced by the original id (id % 1000), the
   image's position columns by the original's position (= what LIGGGHTS'
   domain->remap() returns), and the periodic flag c15 is set to 1. If no row
   with an original as atom 1 exists, the contact point c39-41 (which
   LIGGGHTS computes from the unwrapped positions) is translated by the
   lattice vector of atom 1's image and reformatted with %g.
Plain Python 3.  Usage: python3 assemble_complete.py"""
import os, gzip, itertools

HERE = os.path.dirname(os.path.abspath(__file__))
SHIFTS = [n for n in itertools.product((-1, 0, 1), repeat=3) if n != (0, 0, 0)]

def opn(name):
    p = os.path.join(HERE, name)
    return open(p) if os.path.exists(p) else gzip.open(p + ".gz", "rt")

def read_raw(name):
    L = opn(name).read().split("\n")
    n = int(L[3])
    return L[:9], [L[9 + k].split() for k in range(n)]

hdr_t, rows_t = read_raw("dump.triclinic.atom")
hdr_ia, rows_ia = read_raw("dump.images.atom")
hdr_ip, rows_ip = read_raw("dump.images.pgl")
cols = hdr_ia[8].split()[2:]
c = {nm: k for k, nm in enumerate(cols)}
flags = {r[0]: (r[c["ix"]], r[c["iy"]], r[c["iz"]]) for r in rows_t}
pos = {}
out_atoms = []
for r in rows_ia:
    r = list(r)
    r[c["ix"]], r[c["iy"]], r[c["iz"]] = flags[r[0]]
    pos[int(r[0])] = r[c["x"]:c["x"] + 3]
    out_atoms.append(r)

# lattice vectors of the triclinic cell (exact, from data.triclinic)
box = {}
for ln in open(os.path.join(HERE, "data.triclinic")):
    w = ln.split()
    if w[-2:] == ["xlo", "xhi"]: box["x"] = (float(w[0]), float(w[1]))
    if w[-2:] == ["ylo", "yhi"]: box["y"] = (float(w[0]), float(w[1]))
    if w[-2:] == ["zlo", "zhi"]: box["z"] = (float(w[0]), float(w[1]))
    if w[-3:] == ["xy", "xz", "yz"]: box["t"] = [float(v) for v in w[:3]]
Lx, Ly, Lz = (box[k][1] - box[k][0] for k in "xyz")
xy, xz, yz = box["t"]
def shift(k):
    n = SHIFTS[k - 1]
    return (n[0] * Lx + n[1] * xy + n[2] * xz, n[1] * Ly + n[2] * yz, n[2] * Lz)

plain, periodic = [], {}
for r in rows_ip:
    i1, i2 = int(float(r[12])), int(float(r[13]))
    im1, im2 = i1 > 1000, i2 > 1000
    if not im1 and not im2:
        plain.append(r)
    elif im1 and im2:
        continue
    else:
        key = tuple(sorted((i1 % 1000, i2 % 1000)))
        periodic.setdefault(key, []).append(r)

n_translated = 0
out_pgl = list(plain)
for key in sorted(periodic):
    cand = periodic[key]
    assert len(cand) == 2, (key, len(cand))
    cand.sort(key=lambda r: (int(float(r[12])) < 1000, int(float(r[12])) % 1000), reverse=True)
    r = list(cand[0])
    i1, i2 = int(float(r[12])), int(float(r[13]))
    if i1 > 1000:       # atom 1 is an image: translate the contact point back
        n_translated += 1
        s = shift(i1 // 1000)
        for d in range(3):
            r[38 + d] = "%g" % (float(r[38 + d]) - s[d])
    o1, o2 = i1 % 1000, i2 % 1000
    r[0:3] = pos[o1]
    r[3:6] = pos[o2]
    r[12], r[13], r[14] = str(o1), str(o2), "1"
    out_pgl.append(r)

with open(os.path.join(HERE, "dump.triclinic_complete.atom"), "w") as f:
    f.write("\n".join(hdr_t[:8]) + "\n" + hdr_ia[8] + "\n")
    for r in out_atoms:
        f.write(" ".join(r) + " \n")
with open(os.path.join(HERE, "dump.triclinic_complete.pgl"), "w") as f:
    f.write("ITEM: TIMESTEP\n%s\nITEM: NUMBER OF ENTRIES\n%d\n" % (hdr_t[1], len(out_pgl)))
    f.write("\n".join(hdr_t[4:8]) + "\n" + hdr_ip[8] + "\n")
    for r in out_pgl:
        f.write(" ".join(r) + " \n")
print("atoms %d; contacts: %d between originals + %d periodic = %d; "
      "periodic rows with translated contact point: %d"
      % (len(out_atoms), len(plain), len(periodic), len(out_pgl), n_translated))
