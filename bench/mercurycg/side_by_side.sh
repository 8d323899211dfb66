#!/bin/sh
# mimas average and MercuryCG side by side on the same frame (README.md):
#   side_by_side.sh [WORKDIR]
# Environment: MERCURYCG (the MercuryCG binary, required), MIMAS (default: mimas on
# PATH), PYTHON (with numpy, h5py: default /usr/bin/python3), ROUNDS (default 2: A B A B),
# CALLGRIND=1 to count instructions with valgrind as well (slow; load-independent; MIMAS
# must then be the program itself, e.g. an installed mimas or, in a build tree,
# LD_LIBRARY_PATH=_build/.libs with MIMAS=_build/.libs/mimas, not libtool's wrapper).
# The frame is made once in WORKDIR (default ./mercurycg-run): mimas simulate
# pack20k.ini, its last frame written as MercuryDPM files p20k.data / p20k.fstat and as a
# native file p20k.h5.  Both programs write Gauss XYZ fields, w = 1 mm (cutoff 3w), on
# the 26^3 grid over [0, 26 mm]^3, one thread; and mimas without a kernel (bins:center) on the
# native file, the floor of its time.
set -e
here=$(cd "$(dirname "$0")" && pwd)
: "${MERCURYCG:?set MERCURYCG to the MercuryCG binary}"
MIMAS=${MIMAS:-mimas}
PYTHON=${PYTHON:-/usr/bin/python3}
ROUNDS=${ROUNDS:-2}
work=${1:-mercurycg-run}
mkdir -p "$work"
cd "$work"
if [ ! -f p20k.fstat ]; then
    echo "making the frame (mimas simulate, a few minutes)..."
    "$MIMAS" simulate "$here/pack20k.ini" -o pack20k.h5 -q
    "$PYTHON" "$here/native_to_mercury.py" pack20k.h5 p20k
    "$MIMAS" convert p20k.data --contacts p20k.fstat --density 1 -o p20k.h5 -q
fi
grid="x=0:0.026:26,y=0:0.026:26,z=0:0.026:26"
mcg="'$MERCURYCG' p20k -coordinates XYZ -function Gauss -w 0.001 -n 26 -x 0 0.026 -y 0 0.026 -z 0 0.026 -o p20k.stat"
mim="'$MIMAS' average p20k.data --contacts p20k.fstat --density 1 --grid $grid --weight gauss:w=0.001 --threads 1 -q --tsv p20k_mimas.tsv"
nat="'$MIMAS' average p20k.h5 --grid $grid --weight gauss:w=0.001 --threads 1 -q --tsv p20k_native.tsv"
# the floor: the same command with each object put in one cell (bins:center), which reads the
# frame, adds its sums and writes the same table; no kernel can make mimas faster than this
flo="'$MIMAS' average p20k.h5 --grid $grid --weight bins:center --threads 1 -q --tsv p20k_floor.tsv"
timed() { # LABEL COMMAND: wall and user seconds
    /usr/bin/time -f "%e %U" -o time.txt sh -c "$2 >/dev/null 2>&1"
    set -- "$1" $(cat time.txt)
    printf '%-34s wall %6.2f s  user %6.2f s\n' "$1" "$2" "$3"
}
echo "load before: $(uptime)"
r=1
while [ "$r" -le "$ROUNDS" ]; do
    timed "MercuryCG ($r)" "$mcg"
    timed "mimas, MercuryDPM input ($r)" "$mim"
    timed "mimas, native input ($r)" "$nat"
    timed "mimas, native, no kernel ($r)" "$flo"
    r=$((r + 1))
done
echo "load after: $(uptime)"
if [ "${CALLGRIND:-0}" = 1 ]; then
    # mimas sets OMP_WAIT_POLICY=passive by running itself again, which valgrind's
    # tool cannot do: set it here
    export OMP_WAIT_POLICY=passive
    for prog in mcg mim nat flo; do
        eval "cmd=\$$prog"
        sh -c "valgrind --tool=callgrind --callgrind-out-file=cg.$prog.out $cmd" >/dev/null 2>&1
        printf '%-4s %s instructions\n' "$prog" "$(sed -n 's/^summary: //p' cg.$prog.out)"
    done
fi
echo "fields (MercuryCG prints 6 digits):"
"$PYTHON" "$here/compare.py" p20k.stat p20k_mimas.tsv
