#!/bin/sh
# The wet ring shear study (make example-wet; docs/rheology.md, docs/study.md):
# the small cell of examples/ringshear at three liquid contents D = 0 (dry),
# 0.01 and 0.05, each run simulate -> average, then the runs compared:
#   shearband --study liquid_content   band centre Rc and width W against D
#   rheology  --study liquid_content   yield line (tau0, zeta, psi) and the
#                                      windowed viscosities against D
#   energy    --study liquid_content   mean energies and their coefficient of
#                                      variation against D
# Usage: run.sh [OUTDIR]   (mimas from $MIMAS, else from PATH; THREADS=N)
# Leaves the tables and PNG plots in OUTDIR (default ./ringshear-wet-example).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-ringshear-wet-example}
MIMAS=${MIMAS:-mimas}
mkdir -p "$out"
out=$(cd "$out" && pwd)
# the cell of examples/ringshear (keep in step with its ringshear.ini)
cell="$here/../ringshear/ringshear.ini"
r_in=0.005 r_out=0.035 height=0.012 omega=0.5
from=0.75
start=$(date +%s)

runs=
for D in 0 0.01 0.05; do
    # the cell's scenario with the liquid content set (a later [particles]
    # section overrides the key)
    { cat "$cell"; printf '\n[particles]\nliquid_content = %s\n' "$D"; } >"$out/wet-$D.ini"
    echo "== D = $D: simulate (about 6,500 particles, 1.75 s), average t >= $from s"
    "$MIMAS" simulate "$out/wet-$D.ini" -o "$out/run-$D.h5" --threads "${THREADS:-2}"
    "$MIMAS" average "$out/run-$D.h5" --grid r=$r_in:$r_out:15,z=0.002:$height:5 --weight bins \
        --from $from --exclude-types 2 -q -o "$out/fields-$D.h5"
    runs="$runs $D"
done
fields=$(for D in $runs; do printf '%s ' "$out/fields-$D.h5"; done)
sims=$(for D in $runs; do printf '%s ' "$out/run-$D.h5"; done)

echo "== shearband: Rc and W of the surface layer against D"
# shellcheck disable=SC2086
"$MIMAS" shearband $fields --study liquid_content --omega $omega \
    -o "$out/shearband.tsv" --trends "$out/shearband-trends.tsv" --plot "$out/shearband.png"
cat "$out/shearband-trends.tsv"
echo "== rheology: yield line and windowed viscosities against D"
# shellcheck disable=SC2086
"$MIMAS" rheology $fields --study liquid_content --definition luding --min-shear-rate 0.02 \
    --shear-rate-windows 0.02:0.1,0.1:0.5,0.5:1 --I-windows 0.0001:0.001,0.001:0.003,0.003:0.01 \
    -o "$out/rheology.tsv" --trends "$out/rheology-trends.tsv" --plot "$out/rheology"
grep -E '^(table|yield|eta_window)' "$out/rheology-trends.tsv" || true
echo "== energy: mean energies over t >= $from s and their coefficient of variation"
# shellcheck disable=SC2086
"$MIMAS" energy $sims --study liquid_content --from $from \
    -o "$out/energy.tsv" --trends "$out/energy-trends.tsv" --plot "$out/energy.png"
cat "$out/energy.tsv"
end=$(date +%s)
echo
echo "wet ring shear study done in $((end - start)) s of wall time; the processor time of the"
echo "shell and of the commands it ran (user, system):"
times
echo "in $out/:"
echo "  run-D.h5, fields-D.h5   each run and its fields (D = 0, 0.01, 0.05)"
echo "  shearband.tsv           the layers of every run; shearband-trends.tsv  Rc, W against D"
echo "  rheology.tsv            every run's rheology; rheology-trends.tsv  the lines against D"
echo "  energy.tsv              every run's energies; energy-trends.tsv"
echo "  shearband.png  rheology.study.png  energy.png   the trends with the runs' error bars"
