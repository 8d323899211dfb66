#!/bin/sh
# Regenerate all LIGGGHTS reference data in this folder (serial runs, a few
# seconds in total) and re-run the verification scripts.
# Requires: liggghts (Debian package 3.8.0+repack1), python3, gzip.
set -e
cd "$(dirname "$0")"

echo "== case 1: hopper_walls"
cd hopper_walls
rm -f dump.hopper.* log.hopper
python3 make_hopper_stl.py                    # writes hopper.stl
liggghts -in in.hopper -log log.hopper > /dev/null
gzip -9 -n dump.hopper.atom dump.hopper.pgl   # dump.hopper.wgl stays plain text
python3 check_hopper.py > check_output.txt
cd ..

echo "== case 2: periodic_box"
cd periodic_box
rm -f dump.periodic.* log.periodic
liggghts -in in.periodic -log log.periodic > /dev/null
gzip -9 -n dump.periodic.atom dump.periodic.pgl
python3 check_periodic.py > check_output.txt
cd ..

echo "== case 3: triclinic (needs case 2)"
cd triclinic
rm -f dump.* log.triclinic log.images data.triclinic data.images
python3 make_triclinic.py > /dev/null          # writes data.triclinic
liggghts -in in.triclinic -log log.triclinic > /dev/null
python3 make_images.py > /dev/null             # writes data.images (not kept)
liggghts -in in.images -log log.images > /dev/null
python3 assemble_complete.py
gzip -9 -n dump.images.pgl
rm -f data.images
python3 check_triclinic.py > check_output.txt
cd ..
echo "== case 4: keyword_sets (needs hopper_walls/hopper.stl)"
keyword_sets/make.sh
echo "done"
