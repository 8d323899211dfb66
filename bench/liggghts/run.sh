#!/bin/sh
# run.sh DATAFILE STEPS
# Runs the ring shear benchmark (ringshear.in) in LIGGGHTS, serially (one process: Debian's
# LIGGGHTS deadlocks under mpirun -np 2), and prints particle-steps per second from the log's
# "Loop time of T on 1 procs for S steps with N atoms" line, plus the process CPU time.
#
# The cell follows from N (the "atoms" line of DATAFILE) unless RIN, RSPLIT, ROUT are set:
#   N < 31623 (10^4.5): rin 0.0059, rsplit 0.034, rout 0.044 m   (the 10^4 benchmark)
#   otherwise:          rin 0.0147, rsplit 0.085, rout 0.11 m    (the 10^5 benchmark)
# The cylinder walls reach 4 mm above the highest particle top.
# Environment: OMEGA (rad/s, default 2 pi 0.01), DUMPEVERY (K > 0: per-atom and per-contact
# dumps every K steps), SURFROT (1: rotating walls via surface_ang_vel instead of move/mesh),
# WORKDIR (default run_<data>_<steps>), LIGGGHTS (executable, default liggghts).
# (-screen none is not used: LIGGGHTS 3.8 crashes in the STL reader, which prints to screen.)
# CPU time: a second run with 0 steps (same setup) is subtracted, so "loop CPU" excludes
# reading the data and meshes and the first neighbour build.
set -eu
if [ $# -ne 2 ]; then
  echo "usage: $0 DATAFILE STEPS" >&2
  exit 1
fi
data=$1 steps=$2
here=$(cd "$(dirname "$0")" && pwd)
[ -r "$data" ] || { echo "run.sh: $data: cannot read" >&2; exit 2; }
n=$(awk '$2 == "atoms" && NF == 2 { print $1; exit }' "$data")
[ -n "$n" ] || { echo "run.sh: $data: no 'N atoms' line" >&2; exit 2; }
if [ "$n" -lt 31623 ]; then
  rin=${RIN:-0.0059} rsplit=${RSPLIT:-0.034} rout=${ROUT:-0.044}
else
  rin=${RIN:-0.0147} rsplit=${RSPLIT:-0.085} rout=${ROUT:-0.11}
fi
omega=${OMEGA:-0.0628318530717959}
# highest particle top (z + d/2) in the Atoms section, + 4 mm
height=$(awk '/^Atoms/ { a = 1; next } a && /^[A-Z]/ { a = 0 }
              a && NF >= 7 { t = $7 + $3 / 2; if (t > m) m = t }
              END { printf "%.6g", m + 0.004 }' "$data")
work=${WORKDIR:-run_$(basename "$data" .data)_$steps}
mkdir -p "$work"
data_abs=$(cd "$(dirname "$data")" && pwd)/$(basename "$data")
cd "$work"
"$here/make_mesh.sh" "$rin" "$rsplit" "$rout" "$height" mesh 2>/dev/null

run() { # run STEPS LOG TIMEFILE
  /usr/bin/time -f '%e %U %S' -o "$3" "${LIGGGHTS:-liggghts}" -in "$here/ringshear.in" \
    -log "$2" -screen "$2.screen" -var data "$data_abs" -var steps "$1" -var rin "$rin" \
    -var rsplit "$rsplit" -var rout "$rout" -var height "$height" -var meshdir mesh \
    -var omega "$omega" -var dumpevery "${DUMPEVERY:-0}" -var surfrot "${SURFROT:-0}" \
    -var thermoevery 1000 ||
    { echo "run.sh: liggghts failed, see $work/$2" >&2; exit 3; }
}
run 0 log.setup time.setup
run "$steps" log.liggghts time.run

awk -v n="$n" -v steps="$steps" -v rin="$rin" -v rsplit="$rsplit" -v rout="$rout" \
    -v h="$height" -v work="$work" '
FILENAME == "time.setup" { cpu0 = $2 + $3; next }
FILENAME == "time.run"   { wall = $1; cpu = $2 + $3; next }
/^Loop time of/          { t = $4; procs = $6; s = $9; na = $12 }
/^Neighbor list builds/  { nb = $5 }
/^Dangerous builds/      { db = $4 }
/^Ave neighs\/atom/      { an = $4 }
END {
  if (t == "" || s != steps) { print "run.sh: no Loop time line for the run in " work "/log.liggghts" > "/dev/stderr"; exit 3 }
  if (na != n) { printf "run.sh: %d atoms at the end, %d in the data file\n", na, n > "/dev/stderr"; exit 3 }
  printf "liggghts: %d particles, %d steps, %g s loop time, %.4g particle-steps/s\n", na, s, t, na * s / t
  printf "cell: rin %g rsplit %g rout %g m, walls %g m high, %d proc(s)\n", rin, rsplit, rout, h, procs
  printf "neighbour list builds: %d (dangerous %d), ave neighs/atom: %s (half list, each pair once)\n", nb, db, an
  lc = cpu - cpu0
  printf "process: %.2f s wall, %.2f s CPU (setup-only run: %.2f s CPU); loop CPU %.2f s, %.4g particle-steps per CPU-second\n", wall, cpu, cpu0, lc, (lc > 0 ? na * s / lc : 0)
}' time.setup time.run log.liggghts
