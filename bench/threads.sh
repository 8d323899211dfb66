#!/bin/sh
# mimas simulate with 1 and 2 OpenMP threads, on a quiet and on a loaded
# machine (two busy processes compete for the cores), with the default passive
# waiting and, for comparison, with OMP_WAIT_POLICY=active (spinning threads).
# Prints wall and CPU seconds of each run and the machine load; re-run it on
# a quiet machine for figures of the code alone.
#   sh bench/threads.sh [MIMAS] [PARTICLES] [STEPS]
mimas=${1:-./mimas}
n=${2:-3000}
steps=${3:-2000}
dir=$(mktemp -d "${TMPDIR:-/tmp}/mimas-threads-XXXXXX")
trap 'rm -rf "$dir"' EXIT
# a granular gas in a periodic box, one frame at the end
"$mimas" simulate --print-defaults box |
    sed "s/^count = .*/count = $n/; s/^size_[xyz] = .*/&/; s/^output_every = .*/output_every = $steps/; s/^time = .*/time = $(awk -v s="$steps" 'BEGIN { print s * 5e-6 }')/" |
    sed "s/^size_x = .*/size_x = 0.06/; s/^size_y = .*/size_y = 0.06/; s/^size_z = .*/size_z = 0.06/" >"$dir/box.ini"
run() { # LABEL THREADS [ENV...]: wall and CPU seconds of one run
    label=$1 threads=$2
    shift 2
    perl -MTime::HiRes=time -e '
        my $t = time; system(@ARGV) == 0 or exit 1; my $w = time - $t;
        my (undef, undef, $cu, $cs) = times;
        printf "%.2f %.2f\n", $w, $cu + $cs;' -- env "$@" "$mimas" simulate "$dir/box.ini" \
        -o "$dir/run.h5" --force -q --threads "$threads" >"$dir/t" || { echo "$label: failed"; return; }
    read wall cpu <"$dir/t"
    printf '%-34s %8s s wall %8s s CPU\n' "$label" "$wall" "$cpu"
}
echo "mimas simulate, $n particles, $steps steps (load before: $(cut -d' ' -f1-3 /proc/loadavg))"
for load in quiet loaded; do
    pids=
    if [ $load = loaded ]; then
        for k in 1 2; do sh -c 'while :; do :; done' & pids="$pids $!"; done
    fi
    run "$load, 1 thread" 1
    run "$load, 2 threads" 2
    run "$load, 2 threads, OMP_WAIT_POLICY=active" 2 OMP_WAIT_POLICY=active
    for p in $pids; do kill "$p"; done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
