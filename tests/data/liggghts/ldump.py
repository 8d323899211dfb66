"""Minimal plain-Python reader for LAMMPS/LIGGGHTS text dumps (.gz or plain).
Used only by the check_*.py scripts in tests/data/liggghts/*/.
read_dump(path) -> list of snapshots, each a dict:
  step, n, box (list of 'ITEM: BOX BOUNDS' lines as float lists), boxhdr,
  cols (column names), rows (list of lists of floats)."""
import gzip, math

def _open(path):
    return gzip.open(path, "rt") if path.endswith(".gz") else open(path)

def read_dump(path):
    snaps = []
    with _open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            s = {"step": int(lines[i + 1])}
            i += 2
            assert lines[i].startswith("ITEM: NUMBER OF")
            s["n"] = int(lines[i + 1]); i += 2
            assert lines[i].startswith("ITEM: BOX BOUNDS")
            s["boxhdr"] = lines[i]
            s["box"] = [[float(v) for v in lines[i + k].split()] for k in (1, 2, 3)]
            i += 4
            assert lines[i].startswith("ITEM: ATOMS") or lines[i].startswith("ITEM: ENTRIES")
            s["cols"] = lines[i].split()[2:]
            i += 1
            s["rows"] = [[float(v) for v in lines[i + k].split()] for k in range(s["n"])]
            i += s["n"]
            snaps.append(s)
        else:
            i += 1
    return snaps

def read_log_thermo(path):
    """Return list of dicts for every thermo block row in a LIGGGHTS log."""
    out = []
    hdr = None
    for line in open(path):
        w = line.split()
        if w and w[0] == "Step":
            hdr = w
            continue
        if hdr is not None:
            if len(w) == len(hdr):
                try:
                    out.append(dict(zip(hdr, [float(x) for x in w])))
                    continue
                except ValueError:
                    pass
            hdr = None
    return out

# small vector helpers
def sub(a, b): return [a[0]-b[0], a[1]-b[1], a[2]-b[2]]
def add(a, b): return [a[0]+b[0], a[1]+b[1], a[2]+b[2]]
def dot(a, b): return a[0]*b[0] + a[1]*b[1] + a[2]*b[2]
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
def norm(a): return math.sqrt(dot(a, a))
def scale(s, a): return [s*a[0], s*a[1], s*a[2]]
# Voigt order used by LAMMPS stress/atom: xx yy zz xy xz yz
VOIGT = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
def outer6(a, b): return [a[i]*b[j] for (i, j) in VOIGT]
