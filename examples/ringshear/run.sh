#!/bin/sh
# The ring shear cell example, end to end (README's main job):
#   simulate -> average (r-z bins, time average over the steady part)
#   -> shearband (erf fit per layer) -> rheology (yield line, mu(I), viscosity)
# Usage: run.sh [OUTDIR]   (mimas from $MIMAS, else from PATH)
# Leaves the tables and PNG plots in OUTDIR (default ./ringshear-example).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-ringshear-example}
MIMAS=${MIMAS:-mimas}
mkdir -p "$out"
out=$(cd "$out" && pwd)
# the cell (keep in step with ringshear.ini)
r_in=0.005 r_split=0.025 r_out=0.035 height=0.012 omega=0.5
# steady state: the bottom turns from t = 0.25 s; average over t >= 0.75 s
from=0.75

echo "== 1/4 simulate: $here/ringshear.ini (about 6,500 particles, 1.75 s)"
# --force: a second run of the example replaces the first one's output;
# THREADS=N picks the thread count (default: OpenMP's, all cores)
"$MIMAS" simulate "$here/ringshear.ini" -o "$out/run.h5" --force ${THREADS:+--threads "$THREADS"}
echo "== 2/4 average: r-z bins of 2 mm, t >= $from s, glued bottom particles (type 2) left out"
"$MIMAS" average "$out/run.h5" --grid r=$r_in:$r_out:15,z=0.002:$height:5 --weight bins \
    --from $from --exclude-types 2 --errors -q -o "$out/fields.h5" --tsv "$out/fields.tsv"
echo "== 3/4 shearband: erf fit of omega(r)/Omega per layer"
"$MIMAS" shearband "$out/fields.h5" --omega $omega --fenistein $r_split,$height \
    --plot "$out/shearband.png" -o "$out/shearband.tsv"
cat "$out/shearband.tsv"
echo "== 4/4 rheology: yield line, mu(I), viscosity"
"$MIMAS" rheology "$out/fields.h5" --definition luding --min-shear-rate 0.02 \
    --shear-rate-windows 0.1:0.5,0.5:1,1:2,2:4,4:8 --I-windows 0.001:0.003,0.003:0.01,0.01:0.03,0.03:0.1 \
    --plot "$out/rheology" -o "$out/rheology.tsv"
grep -E '^(table|yield|mu_I)' "$out/rheology.tsv" || true
echo
echo "ring shear example done; in $out/:"
echo "  run.h5           particles, contacts and wall contacts of every frame (mimas info $out/run.h5)"
echo "  fields.h5 (.xdmf) averaged fields on the r-z grid (ParaView opens fields.xdmf); fields.tsv"
echo "  shearband.tsv    band centre Rc and width W per layer;  shearband.png  the profiles and fits"
echo "  rheology.tsv     yield line, mu(I), viscosity laws;  rheology.{yield,mu_I,eta}.png  tau(p), mu(I), eta"
