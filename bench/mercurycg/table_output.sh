#!/bin/sh
# What writing the fields costs in the side-by-side run (README.md):
#   table_output.sh [WORKDIR]
# Counts instructions with callgrind (load-independent) for the native-file command of
# side_by_side.sh (Gauss x-y-z, w = 1 mm, 26^3 cells, one thread), once with --tsv and
# once with -o (the HDF5 fields file), and prints the whole run, the part that writes the
# output (write_rows, resp. mimas_fields_finish, both with the derived fields they
# compute), the number conversion in it and the instructions per number written.
# Environment: MIMAS, the program itself (not libtool's wrapper: in a build tree
# LD_LIBRARY_PATH=$PWD/_build/.libs MIMAS=_build/.libs/mimas).  WORKDIR (default
# ./mercurycg-run) holds p20k.h5, made by side_by_side.sh.
set -e
MIMAS=${MIMAS:-mimas}
work=${1:-mercurycg-run}
if [ ! -f "$work/p20k.h5" ]; then
    echo "table_output.sh: no p20k.h5 in $work (side_by_side.sh makes it)" >&2
    exit 2
fi
export OMP_WAIT_POLICY=passive
grid="x=0:0.026:26,y=0:0.026:26,z=0:0.026:26"
echo "load: $(uptime)"
# OUT FUNCTION: inclusive instructions of the function (the largest of the lines naming
# it: callgrind_annotate lists a function's inlined parts apart, by source file)
incl() {
    callgrind_annotate --inclusive=yes --threshold=100 "$1" 2>/dev/null |
        awk -v f="$2" 'index($0, f) { gsub(",", "", $1); if ($1 + 0 > m) m = $1 + 0 }
                       END { print m + 0 }'
}
run() { # OUT OUTPUT-OPTIONS...
    out=$1
    shift
    valgrind --tool=callgrind --callgrind-out-file="$out" "$MIMAS" average "$work/p20k.h5" \
        --grid "$grid" --weight gauss:w=0.001 --threads 1 -q "$@" >/dev/null 2>&1
}
run "$work/cg.table.tsv.out" --tsv "$work/p20k_table.tsv"
run "$work/cg.table.h5.out" -o "$work/p20k_table_fields.h5"
numbers=$(awk -F'\t' 'NR > 1 { n += NF } END { print n }' "$work/p20k_table.tsv")
total=$(sed -n 's/^summary: //p' "$work/cg.table.tsv.out")
rows=$(incl "$work/cg.table.tsv.out" 'cmd_average.c:write_rows')
conv=$(incl "$work/cg.table.tsv.out" 'numfmt.cc:mimas_format_double')
fields=$(incl "$work/cg.table.tsv.out" 'average.c:mimas_average_fields')
h5total=$(sed -n 's/^summary: //p' "$work/cg.table.h5.out")
h5=$(incl "$work/cg.table.h5.out" 'output_h5.c:mimas_fields_finish')
h5fields=$(incl "$work/cg.table.h5.out" 'average.c:mimas_average_fields')
awk -v t="$total" -v r="$rows" -v c="$conv" -v f="$fields" -v n="$numbers" \
    -v ht="$h5total" -v h="$h5" -v hf="$h5fields" 'BEGIN {
    printf "--tsv: run %.3g, writing the table %.3g (%.1f %%), %d numbers: %.0f a number\n",
           t, r, 100 * r / t, n, r / n
    printf "       of which the conversion %.3g (%.0f a number), the derived fields %.3g\n",
           c, c / n, f
    printf "-o:    run %.3g, writing the fields file %.3g (%.1f %%), the derived fields %.3g\n",
           ht, h, 100 * h / ht, hf
}'
