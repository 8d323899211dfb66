#!/bin/sh
# Builds the fuzz targets with clang's libFuzzer, AddressSanitizer and UBSan
# (apt-get install clang), and optionally runs each for a budget:
#   sh tests/fuzz/build-libfuzzer.sh OUTDIR [SECONDS]
# With SECONDS, every target runs that long on a copy of its saved corpus
# (tests/fuzz/corpus/TARGET) plus what it finds, and a line per target gives
# the executions and the coverage (libFuzzer's "cov", edges reached); a crash
# fails the script and leaves the input in OUTDIR.  CI runs a short budget
# (build-aux/setup); the longer run of the issue is SECONDS = 600:
#   sh tests/fuzz/build-libfuzzer.sh fuzz-build 600
# New inputs worth keeping (they reached new code) can be merged into the
# saved corpus with: OUTDIR/fuzz_T -merge=1 tests/fuzz/corpus/T OUTDIR/corpus-T
set -e
top=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-fuzz-build}
budget=${2:-}
mkdir -p "$out"
out=$(cd "$out" && pwd)
printf '#define _GNU_SOURCE 1\n#define PACKAGE_NAME "mimas"\n#define PACKAGE_VERSION "fuzz"\n' >"$out/config.h"
hdf5=$(pkg-config --cflags --libs hdf5 2>/dev/null || pkg-config --cflags --libs hdf5-serial)
lib="$top/src/error.c $top/src/frame.c $top/src/frame_check.c $top/src/tmpfiles.c \
     $top/src/id_index.c $top/src/h5util.c \
     $top/src/native_layout.c $top/src/native_write.c $top/readers/native_read.c \
     $top/readers/native_stream.c $top/readers/reader.c $top/readers/text_input.c \
     $top/readers/numparse.c $top/readers/lammps.c $top/readers/lammps_series.c \
     $top/readers/lammps_atoms.c $top/readers/lammps_local.c $top/readers/mercury.c \
     $top/src/parameters.c $top/readers/thermo_log.c"
sim="$top/src/sim/scenario.c $top/src/sim/dem.c $top/src/sim/contact_law.c \
     $top/src/sim/cohesion.c $top/src/sim/neighbour.c $top/src/sim/forces.c \
     $top/src/sim/integrate.c $top/src/sim/setup.c $top/src/sim/setup_ringshear.c \
     $top/src/sim/setup_box.c $top/src/sim/setup_pulloff.c $top/src/sim/blowup.c"
for f in "$top"/src/sim/setup_*.c; do
    case " $sim " in *" $f "*) ;; *) sim="$sim $f" ;; esac
done
cflags="-g -O1 -fsanitize=address,undefined -I$out -I$top/src -I$top/src/sim -I$top/readers"
incs="$hdf5 $(pkg-config --cflags gsl)"
# the library once (objects with the fuzzer's coverage hooks), then each target
mkdir -p "$out/obj"
objs=
for f in $lib $sim "$top/tests/fuzz/fuzz_input.c"; do
    o="$out/obj/$(basename "$f" .c).o"
    clang $cflags -fsanitize=fuzzer-no-link $incs -c "$f" -o "$o"
    objs="$objs $o"
done
targets="dump local mercury native scenario thermo"
libs="$hdf5 $(pkg-config --libs gsl) $(pkg-config --libs inih 2>/dev/null || echo -linih) -lz -lm"
for t in $targets; do
    clang $cflags -fsanitize=fuzzer $incs $objs "$top/tests/fuzz/fuzz_$t.c" $libs -o "$out/fuzz_$t"
done
[ -n "$budget" ] || exit 0
status=0
for t in $targets; do
    rm -rf "$out/corpus-$t"
    mkdir -p "$out/corpus-$t"
    cp "$top/tests/fuzz/corpus/$t"/* "$out/corpus-$t/" 2>/dev/null || true
    log="$out/fuzz-$t.log"
    if (cd "$out" && ASAN_OPTIONS=detect_leaks=1 ./fuzz_$t -max_total_time="$budget" \
            -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 "corpus-$t") >"$log" 2>&1; then
        verdict=ok
    else
        verdict=FAILED
        status=1
    fi
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n1 | sed 's/cov: //')
    ft=$(grep -o 'ft: [0-9]*' "$log" | tail -n1 | sed 's/ft: //')
    echo "fuzz_$t: $verdict, ${runs:-?} executions in ${budget} s, coverage ${cov:-?} edges (${ft:-?} features), corpus $(ls "$out/corpus-$t" | wc -l) inputs"
    [ "$verdict" = ok ] || tail -n 30 "$log"
done
exit $status
