#!/bin/sh
# Frame-parallel scaling of the MPI build (docs/parallel.md): wall time,
# speed-up and parallel efficiency of `mimas average --weight gauss` and
# `mimas voronoi` over FRAMES frames of PARTICLES particles, for 1 and 2 ranks
# and threads x ranks, plus the time to only read the frames.  Run from the
# MPI build directory (configure --with-mpi):
#   sh ../bench/bench_mpi.sh [FRAMES] [PARTICLES]      (default 20 100000)
# Prints one line per configuration: what, ranks, threads, wall s, CPU s,
# speed-up against 1 rank x 1 thread, efficiency = speed-up / cores used.
set -u
frames=${1:-20}
particles=${2:-100000}
here=$(pwd)
mimas=$here/mimas
[ -x "$mimas" ] || { echo "bench_mpi.sh: run it in a build directory (no ./mimas here)" >&2; exit 1; }
"$mimas" --version | grep -q "without MPI" && { echo "bench_mpi.sh: this mimas is built without MPI" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
data=$here/bench-mpi-$frames-$particles.h5
if [ ! -f "$data" ]; then
    echo "writing $frames frames of $particles particles to $data"
    ./tests/tools/make_frames -o "$data" --frames "$frames" --particles "$particles" \
        --contacts $((3 * particles)) --walls 0 --seed 11 || exit 1
fi
echo "machine: $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"

# t LABEL RANKS THREADS ARGS...: one timed run
base=
t() {
    label=$1 ranks=$2 threads=$3
    shift 3
    start=$(date +%s.%N)
    if [ "$ranks" -eq 1 ]; then
        /usr/bin/time -f "%S %U" -o "$here/.bench-time" env OMP_NUM_THREADS="$threads" \
            "$mimas" "$@" --threads "$threads" >/dev/null 2>&1
    else
        /usr/bin/time -f "%S %U" -o "$here/.bench-time" mpirun -q --oversubscribe \
            --bind-to none -n "$ranks" -x OMP_NUM_THREADS="$threads" \
            "$mimas" "$@" --threads "$threads" >/dev/null 2>&1
    fi
    end=$(date +%s.%N)
    cpu=$(awk '{print $1 + $2}' "$here/.bench-time")
    wall=$(awk -v a="$start" -v b="$end" "BEGIN { print b - a }")
    [ -z "$base" ] && base=$wall
    awk -v l="$label" -v r="$ranks" -v th="$threads" -v w="$wall" -v c="$cpu" -v b="$base" \
        'BEGIN { s = b / w; printf "%-28s ranks %d threads %d  wall %7.2f s  cpu %7.2f s  speed-up %5.2f  efficiency %4.2f\n", l, r, th, w, c, s, s / (r * th) }'
}

grid="--grid x=-0.5:1.5:26,y=-0.5:1.5:26,z=-0.5:1.5:26"
for what in gauss voronoi read; do
    base=
    case $what in
    gauss) set -- average "$data" $grid --weight gauss:w=0.03 ;;
    voronoi) set -- voronoi "$data" --tsv /dev/null ;;
    read) set -- average "$data" --grid none --weight bins --fields n ;;
    esac
    t "$what" 1 1 "$@"
    t "$what" 2 1 "$@"
    t "$what" 1 2 "$@"
    t "$what" 2 2 "$@"
done
rm -f "$here/.bench-time"
