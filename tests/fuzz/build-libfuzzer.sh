#!/bin/sh
# Builds the fuzz targets with clang's libFuzzer, AddressSanitizer and UBSan
# (development only; CI replays the corpus with tests/fuzz/corpus.test).
#   sh tests/fuzz/build-libfuzzer.sh OUTDIR      (needs: apt-get install clang)
# then e.g.  OUTDIR/fuzz_dump -max_total_time=600 NEWCORPUS tests/fuzz/corpus/dump
set -e
top=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-fuzz-build}
mkdir -p "$out"
printf '#define _GNU_SOURCE 1\n#define PACKAGE_NAME "mimas"\n#define PACKAGE_VERSION "fuzz"\n' >"$out/config.h"
hdf5=$(pkg-config --cflags --libs hdf5 2>/dev/null || pkg-config --cflags --libs hdf5-serial)
lib="$top/src/error.c $top/src/frame.c $top/src/id_index.c $top/src/h5util.c \
     $top/src/native_layout.c $top/src/native_write.c $top/readers/native_read.c \
     $top/readers/native_stream.c $top/readers/reader.c $top/readers/text_input.c \
     $top/readers/numparse.c $top/readers/lammps.c $top/readers/lammps_series.c \
     $top/readers/lammps_atoms.c $top/readers/lammps_local.c $top/src/parameters.c \
     $top/readers/thermo_log.c"
[ -f "$top/readers/mercury.c" ] && lib="$lib $top/readers/mercury.c"
for t in dump local mercury thermo; do
    [ -f "$top/tests/fuzz/fuzz_$t.c" ] || continue
    clang -g -O1 -fsanitize=fuzzer,address,undefined -I"$out" -I"$top/src" -I"$top/readers" \
        $lib "$top/tests/fuzz/fuzz_input.c" "$top/tests/fuzz/fuzz_$t.c" $hdf5 -lz -lm \
        -o "$out/fuzz_$t"
done
