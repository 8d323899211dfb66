#!/bin/sh
# make_data.sh N RIN ROUT OUTFILE [GAP]
# Writes a *test* starting packing for ringshear.in: N spheres (d = 2 mm, rho = 2000 kg/m^3,
# type 1) on a simple-cubic lattice of spacing d (1 + GAP) inside the annulus
# RIN + d/2 < r < ROUT - d/2, layer by layer from the bottom (lowest centres at
# z = d/2 + GAP d/2) until N sites are used (the top layer is filled in lattice order,
# so it is partial). GAP defaults to 0: neighbours touch, so the contact law is exercised
# from the first step. The real benchmark uses a settled packing written by mimas in the
# same format (LAMMPS data file, atom_style granular: id type diameter density x y z).
set -eu
if [ $# -lt 4 ]; then
  echo "usage: $0 N RIN ROUT OUTFILE [GAP]" >&2
  exit 1
fi
n=$1 rin=$2 rout=$3 outfile=$4 gap=${5:-0}
tmp=$outfile.tmp.$$
trap 'rm -f "$tmp"' EXIT
awk -v n="$n" -v rin="$rin" -v rout="$rout" -v gap="$gap" -v file="$outfile" '
BEGIN {
  d = 0.002; rho = 2000
  if (!(n >= 1 && 0 < rin && rin + d < rout && gap >= 0)) {
    printf "make_data.sh: %s: need N >= 1, 0 < RIN, RIN + d < ROUT, GAP >= 0\n", file > "/dev/stderr"
    exit 2
  }
  s = d * (1 + gap)
  rmin = rin + d / 2 + 1e-9; rmax = rout - d / 2 - 1e-9
  m = int(rmax / s) + 1; ns = 0
  # lattice sites of one layer, in lattice order
  for (i = -m; i <= m; i++)
    for (j = -m; j <= m; j++) {
      x = i * s; y = j * s; r = sqrt(x * x + y * y)
      if (r >= rmin && r <= rmax) { sx[ns] = x; sy[ns] = y; ns++ }
    }
  if (ns == 0) { printf "make_data.sh: %s: annulus holds no lattice site\n", file > "/dev/stderr"; exit 2 }
  nl = int((n + ns - 1) / ns)
  z0 = d / 2 + gap * d / 2
  ztop = z0 + (nl - 1) * s + d / 2
  L = rout + d
  printf "LIGGGHTS data file: ring shear test packing, %d spheres on a cubic lattice (gap %g d), %d per layer\n\n", n, gap, ns
  printf "%d atoms\n1 atom types\n\n", n
  printf "%.9g %.9g xlo xhi\n%.9g %.9g ylo yhi\n%.9g %.9g zlo zhi\n\n", -L, L, -L, L, 0, ztop + d
  printf "Atoms\n\n"
  for (k = 0; k < n; k++) {
    l = int(k / ns); q = k - l * ns
    printf "%d 1 %g %g %.9e %.9e %.9e\n", k + 1, d, rho, sx[q], sy[q], z0 + l * s
  }
  printf "make_data.sh: %d sites per layer, %d layers, top of packing at z = %.4g m\n", ns, nl, ztop > "/dev/stderr"
}' > "$tmp"
mv "$tmp" "$outfile"
trap - EXIT
