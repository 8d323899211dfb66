#!/bin/sh
# Writes v1_0.h5: a native file of format version 1.0 (no tube, no gas
# fields), to check that newer readers still read it.  It was made with mimas
# 0.1.0 at commit 7143fb5 (the last one writing format 1.0):
#   git worktree add /tmp/mimas-1.0 7143fb5 && (cd /tmp/mimas-1.0 && autoreconf -fi &&
#       ./configure -q && make -j2 -s)
#   sh make_v1_0.sh /tmp/mimas-1.0/mimas
# Its content: 8 particles in a periodic box, 3 frames (steps 0, 100, 200).
set -e
MIMAS=${1:?usage: make_v1_0.sh PATH-TO-MIMAS-0.1.0-FORMAT-1.0}
dir=$(dirname "$0")
"$MIMAS" simulate "$dir/v1_0.ini" -o "$dir/v1_0.h5" -q --threads 1
