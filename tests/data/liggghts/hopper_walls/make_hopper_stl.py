#!/usr/bin/env python3
"""Write hopper.stl: two inclined plates (2 triangles each) forming a hopper
with a slot outlet 0.022 < x < 0.038 (m), spanning 0 <= y <= 0.04.
Left plate:  (0, y, 0.040) -> (0.022, y, 0.012)
Right plate: (0.038, y, 0.012) -> (0.060, y, 0.040)
Units: metres (LIGGGHTS 'units si'). Plain Python, deterministic output."""

def facet(f, a, b, c):
    # normal from right-hand rule (LIGGGHTS recomputes it anyway)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1]*v[2]-u[2]*v[1], u[2]*v[0]-u[0]*v[2], u[0]*v[1]-u[1]*v[0]]
    ln = sum(x*x for x in n) ** 0.5
    n = [x/ln for x in n]
    f.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(n))
    for p in (a, b, c):
        f.write("      vertex %.9g %.9g %.9g\n" % tuple(p))
    f.write("    endloop\n  endfacet\n")

Y0, Y1 = 0.0, 0.04
with open("hopper.stl", "w") as f:
    f.write("solid hopper\n")
    # left plate, upper edge at x=0,z=0.04, lower edge at x=0.022,z=0.012
    A, B = (0.0, Y0, 0.040), (0.022, Y0, 0.012)
    C, D = (0.022, Y1, 0.012), (0.0, Y1, 0.040)
    facet(f, A, B, C); facet(f, A, C, D)
    # right plate, lower edge x=0.038,z=0.012, upper edge x=0.06,z=0.04
    A, B = (0.038, Y0, 0.012), (0.060, Y0, 0.040)
    C, D = (0.060, Y1, 0.040), (0.038, Y1, 0.012)
    facet(f, A, B, C); facet(f, A, C, D)
    f.write("endsolid hopper\n")
