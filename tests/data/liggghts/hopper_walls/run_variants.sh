#!/bin/sh
# Scratch experiment behind the "damping" section of README.md; NOT needed to
# regenerate the data set. Re-runs case 1 in a temporary directory with
# full-precision dumps (dump_modify format %.17g) for three combinations of
# coefficientRestitution e and coefficientFriction mu, then runs
# check_hopper.py and damping_check.py on each. Nothing is written here.
# (e = 1 together with mu = 0 is not used: without any dissipation particles
# bounce out of the open top of the box and the run stops with "Lost atoms".)
set -e
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d)
cp "$HERE/../ldump.py" "$HERE/../check_common.py" "$TMP/"
for v in "0.5 0.5" "1.0 0.5" "0.5 0.0"; do
  set -- $v
  d="$TMP/e$1_mu$2"; mkdir "$d"
  cp "$HERE/in.hopper" "$HERE/hopper.stl" "$HERE/check_hopper.py" "$HERE/damping_check.py" "$d/"
  python3 - "$d/in.hopper" "$1" "$2" <<'PY'
import sys
p, e, mu = sys.argv[1], sys.argv[2], sys.argv[3]
s = open(p).read()
s = s.replace("coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5",
              "coefficientRestitution peratomtypepair 2 %s %s %s %s" % ((e,) * 4))
s = s.replace("coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5",
              "coefficientFriction peratomtypepair 2 %s %s %s %s" % ((mu,) * 4))
fa = "%d %d" + " %.17g" * 3 + " %d %d %d" + " %.17g" * 17
fl = " ".join(["%.17g"] * 41)
s = s.replace("\nrun             47999",
              '\ndump_modify dmp format "%s"\ndump_modify dpgl format "%s"\ndump_modify dwgl format "%s"\nrun             47999' % (fa, fl, fl))
open(p, "w").write(s)
PY
  (cd "$d" && liggghts -in in.hopper -log log.hopper > /dev/null \
     && python3 check_hopper.py > check_output.txt \
     && python3 damping_check.py "$1" "$2")
  echo "  stress sums, rel|sumP(log) - (-sum_c r12(x)F1)| per step:"
  awk '/^ +[0-9]+ +/ && NF==7 {printf "    %s %s\n", $1, $2}' "$d/check_output.txt" | tr '\n' ' '; echo
done
echo "scratch results left in $TMP"
