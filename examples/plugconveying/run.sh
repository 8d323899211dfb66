#!/bin/sh
# The plug conveying example, end to end:
#   simulate -> plugs (space-time porosity diagram, plug list, tracks,
#   statistics along the tube) -> radial (profiles across the tube, in the
#   plugs and everywhere) -> disperse (a cohort of grains: sigma^2(t), D)
# Usage: run.sh [OUTDIR]   (mimas from $MIMAS, else from PATH)
# Leaves the tables and PNG plots in OUTDIR (default ./plugconveying-example).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-plugconveying-example}
MIMAS=${MIMAS:-mimas}
mkdir -p "$out"
out=$(cd "$out" && pwd)
# the tube has filled by about 1.5 s (keep in step with plugconveying.ini);
# the feed column (type 2, below the inlet) is left out of every analysis
from=1.5

echo "== 1/4 simulate: $here/plugconveying.ini (vertical tube of 0.15 m, up to about 1300 grains, 3 s)"
# --force: a second run of the example replaces the first one's output;
# THREADS=N picks the thread count (default: OpenMP's, all cores)
"$MIMAS" simulate "$here/plugconveying.ini" -o "$out/run.h5" --force ${THREADS:+--threads "$THREADS"}
echo "== 2/4 plugs: slices of d/2, plugs of porosity < 0.6 and at least d long, tracked"
# the space-time diagram over the whole run (filling included), the tables from t >= $from s
"$MIMAS" plugs "$out/run.h5" --exclude-types 2 --from 0.05 --spacetime "$out/spacetime.png" -q \
    --plugs "$out/plugs-all.tsv"
"$MIMAS" plugs "$out/run.h5" --exclude-types 2 --from $from --plugs "$out/plugs.tsv" \
    --tracks "$out/tracks.tsv" --stats "$out/stats.tsv" --summary "$out/summary.tsv" -q
cat "$out/summary.tsv"
echo "== 3/4 radial: porosity and velocity across the tube, in the plugs and over the whole tube"
"$MIMAS" radial "$out/run.h5" --exclude-types 2 --from $from --in-plugs -o "$out/radial-plugs.tsv" -q
"$MIMAS" radial "$out/run.h5" --exclude-types 2 --from $from -o "$out/radial.tsv" -q
echo "== 4/4 disperse: the grains released between 1.0 and 1.1 s, followed through the tube"
"$MIMAS" disperse "$out/run.h5" --exclude-types 2 --from 0.5 --cohort inserted:1.0:1.1 \
    --fit-from 0.01 --cohorts "$out/cohort.tsv" --diffusion "$out/diffusion.tsv" \
    --tsv "$out/msd.tsv" --plot "$out/disperse.png" -q
cat "$out/diffusion.tsv"
echo
echo "plug conveying example done; in $out/:"
echo "  run.h5          particles, contacts, wall contacts and the gas fields of every frame (mimas info $out/run.h5)"
echo "  spacetime.png   porosity along the tube against time (dark = dense: the plugs) with the plug centres"
echo "  plugs.tsv       every plug of every frame from t = $from s (centre, ends, length, grains, velocity; plugs-all.tsv: from the start)"
echo "  tracks.tsv      plug tracks (velocities, lifetimes)"
echo "  stats.tsv       plug statistics along the tube;  summary.tsv  whole-run figures (grains in the tube, pressure drop, ...)"
echo "  radial-plugs.tsv, radial.tsv  radial profiles in the plugs and over the tube"
echo "  cohort.tsv, diffusion.tsv, msd.tsv, disperse.png  the cohort's spreading sigma^2(t) and D"
