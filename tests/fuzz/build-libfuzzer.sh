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
# the library's sources as Makefile.am lists them (so this script cannot fall
# behind the library), compiled once with the fuzzer's coverage hooks into an
# archive: each target links only what it reaches
sources=$(awk '/^libmimas_la_SOURCES *[+]?=/ { on = 1 }
    on { for (i = 1; i <= NF; i++) if ($i ~ /[.](c|cc)$/) print $i; if ($0 !~ /[\\]$/) on = 0 }' \
    "$top/Makefile.am")
[ -n "$sources" ] || { echo "build-libfuzzer.sh: no library sources in Makefile.am" >&2; exit 1; }
incs="-I$out -I$top/src -I$top/src/sim -I$top/readers -I$top/averaging $hdf5 \
      $(pkg-config --cflags gsl fftw3) -isystem /usr/include/voro++"
cflags="-g -O1 -fsanitize=address,undefined -Wno-unknown-pragmas"
rm -rf "$out/obj"
mkdir -p "$out/obj"
rm -f "$out/libmimas-fuzz.a"
export top out incs cflags
printf '%s\n' $sources "tests/fuzz/fuzz_input.c" | xargs -P "$(nproc 2>/dev/null || echo 2)" -I{} sh -c '
    f={}; o="$out/obj/$(echo "$f" | tr / _).o"
    case $f in *.cc) cc="clang++ -std=c++17" ;; *) cc="clang -std=gnu17" ;; esac
    $cc $cflags -fsanitize=fuzzer-no-link $incs -c "$top/$f" -o "$o"' || exit 1
ar rcs "$out/libmimas-fuzz.a" "$out"/obj/*.o
targets="dump local mercury native scenario thermo"
libs="$hdf5 $(pkg-config --libs gsl fftw3) $(pkg-config --libs inih 2>/dev/null || echo -linih) \
      -lvoro++ -ldouble-conversion -lz -ldeflate -lm"
for t in $targets; do
    clang++ $cflags -fsanitize=fuzzer $incs -x c "$top/tests/fuzz/fuzz_$t.c" -x none \
        "$out/libmimas-fuzz.a" $libs -o "$out/fuzz_$t"
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
