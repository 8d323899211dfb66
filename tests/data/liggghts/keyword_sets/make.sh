#!/bin/sh
# Writes the dumps of this folder with LIGGGHTS (Debian package liggghts
# 3.8.0, serial, a few seconds): one run of in.keywords per keyword set of
# compute pair/gran/local and wall/gran/local that mimas infers from the
# column count (docs/readers.md): LIGGGHTS' default set (no keywords) and
# every keyword without history.  The logs are kept.
set -e
cd "$(dirname "$0")"
run() { # NAME PAIR_COLUMNS WALL_COLUMNS KEYWORDS...
    name=$1 np=$2 nw=$3
    shift 3
    pc=$(seq -f 'c_pgl[%g]' 1 "$np" | tr '\n' ' ')
    wc=$(seq -f 'c_wgl[%g]' 1 "$nw" | tr '\n' ' ')
    sed -e "s/KEYWORDS/$*/" -e "s/PCOLS/$pc/" -e "s/WCOLS/$wc/" -e "s/NAME/$name/g" \
        in.keywords >"in.$name"
    rm -f "dump.$name".*
    liggghts -in "in.$name" -log "log.$name" >/dev/null
    rm -f "in.$name"
    gzip -9 -n "dump.$name.atom" "dump.$name.pgl"   # the wall dump stays plain text
}
# default: pos 6, vel 6, id 3, force 3, torque 3, history 3, contactArea 1
run default 25 25
# all keywords but history (and ms_id, heatFlux): 38 columns
run nohist 38 38 pos vel id force force_normal force_tangential torque torque_normal \
    torque_tangential contactArea delta contactPoint
