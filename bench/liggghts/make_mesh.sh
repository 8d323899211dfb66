#!/bin/sh
# make_mesh.sh RIN RSPLIT ROUT HEIGHT OUTDIR [EDGE]
# Writes the four ASCII STL walls of the split-bottom ring shear cell (axis = z through
# x = y = 0, bottom at z = 0) into OUTDIR:
#   inner.stl         cylinder r = RIN,            0 <= z <= HEIGHT   (static)
#   bottom_static.stl annulus  RIN  < r < RSPLIT,  z = 0              (static)
#   bottom_rot.stl    annulus  RSPLIT < r < ROUT,  z = 0              (rotates)
#   outer.stl         cylinder r = ROUT,           0 <= z <= HEIGHT   (rotates)
# All four use the same number of sectors, chosen so the chord at ROUT is at most EDGE
# (default 0.002 m = one particle diameter; the sagitta is then EDGE^2/(8 ROUT), < 0.6 %
# of d for both benchmark cells). Cylinders are split into rings of height <= 4 EDGE, the
# annuli into rings of width <= 4 EDGE, so no triangle angle falls below LIGGGHTS' 0.5 deg
# quality warning.
set -eu
if [ $# -lt 5 ]; then
  echo "usage: $0 RIN RSPLIT ROUT HEIGHT OUTDIR [EDGE]" >&2
  exit 1
fi
rin=$1 rsplit=$2 rout=$3 height=$4 out=$5 edge=${6:-0.002}
mkdir -p "$out"
awk -v rin="$rin" -v rsplit="$rsplit" -v rout="$rout" -v h="$height" -v out="$out" \
    -v edge="$edge" '
function tri(f, ax, ay, az, bx, by, bz, cx, cy, cz,    ux, uy, uz, vx, vy, vz, nx, ny, nz, l) {
  ux = bx - ax; uy = by - ay; uz = bz - az
  vx = cx - ax; vy = cy - ay; vz = cz - az
  nx = uy * vz - uz * vy; ny = uz * vx - ux * vz; nz = ux * vy - uy * vx
  l = sqrt(nx * nx + ny * ny + nz * nz)
  printf "facet normal %.9e %.9e %.9e\n outer loop\n", nx / l, ny / l, nz / l > f
  printf "  vertex %.9e %.9e %.9e\n", ax, ay, az > f
  printf "  vertex %.9e %.9e %.9e\n", bx, by, bz > f
  printf "  vertex %.9e %.9e %.9e\n", cx, cy, cz > f
  printf " endloop\nendfacet\n" > f
}
# cylinder of radius r, normals pointing to the side given by sgn (+1 outwards, -1 inwards)
function cylinder(f, name, r, sgn,    i, k, nz, a0, a1, z0, z1) {
  printf "solid %s\n", name > f
  nz = int(h / (4 * edge)) + 1
  for (i = 0; i < ns; i++) {
    a0 = 2 * pi * i / ns; a1 = 2 * pi * (i + 1) / ns
    for (k = 0; k < nz; k++) {
      z0 = h * k / nz; z1 = h * (k + 1) / nz
      if (sgn > 0) {
        tri(f, r*cos(a0), r*sin(a0), z0, r*cos(a1), r*sin(a1), z0, r*cos(a1), r*sin(a1), z1)
        tri(f, r*cos(a0), r*sin(a0), z0, r*cos(a1), r*sin(a1), z1, r*cos(a0), r*sin(a0), z1)
      } else {
        tri(f, r*cos(a0), r*sin(a0), z0, r*cos(a1), r*sin(a1), z1, r*cos(a1), r*sin(a1), z0)
        tri(f, r*cos(a0), r*sin(a0), z0, r*cos(a0), r*sin(a0), z1, r*cos(a1), r*sin(a1), z1)
      }
    }
  }
  printf "endsolid %s\n", name > f
  close(f)
}
# flat annulus r0 < r < r1 at z = 0, normals +z
function annulus(f, name, r0, r1,    i, k, nr, a0, a1, ra, rb) {
  printf "solid %s\n", name > f
  nr = int((r1 - r0) / (4 * edge)) + 1
  for (i = 0; i < ns; i++) {
    a0 = 2 * pi * i / ns; a1 = 2 * pi * (i + 1) / ns
    for (k = 0; k < nr; k++) {
      ra = r0 + (r1 - r0) * k / nr; rb = r0 + (r1 - r0) * (k + 1) / nr
      tri(f, ra*cos(a0), ra*sin(a0), 0, rb*cos(a0), rb*sin(a0), 0, rb*cos(a1), rb*sin(a1), 0)
      tri(f, ra*cos(a0), ra*sin(a0), 0, rb*cos(a1), rb*sin(a1), 0, ra*cos(a1), ra*sin(a1), 0)
    }
  }
  printf "endsolid %s\n", name > f
  close(f)
}
BEGIN {
  pi = atan2(0, -1)
  if (!(0 < rin && rin < rsplit && rsplit < rout && h > 0 && edge > 0)) {
    print "make_mesh.sh: need 0 < RIN < RSPLIT < ROUT, HEIGHT > 0, EDGE > 0" > "/dev/stderr"
    exit 2
  }
  ns = int(2 * pi * rout / edge) + 1
  cylinder(out "/inner.stl", "inner", rin, 1)
  annulus(out "/bottom_static.stl", "bottom_static", rin, rsplit)
  annulus(out "/bottom_rot.stl", "bottom_rot", rsplit, rout)
  cylinder(out "/outer.stl", "outer", rout, -1)
  printf "make_mesh.sh: %d sectors, STL files in %s\n", ns, out > "/dev/stderr"
}'
