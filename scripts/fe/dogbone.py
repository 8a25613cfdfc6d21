#!/usr/bin/python3
"""FE reference for examples/dogbone.yaml (a specimen from a Gmsh file).

The outline is read from examples/geometry/dogbone.geo itself (metres, gmsh's built-in
kernel): its boundary curves (lines and circular arcs) are rebuilt in mm in the OCC
kernel, which can cut them. 20 mm x 60 mm overall, a 10 mm gauge 24 mm long, 5 mm
fillets; thickness 2 mm. Grips: 4 point rows at each end (dx = 0.5 mm), x held, the
bottom fixed, the top moved by (lambda - 1) 60 mm (the body height); pulled to 1.5.
Gent, mu = 4.55 kPa, Jm = 162.6, plane stress, K = 1000 mu in the scene.

As for the waisted sheet (waisted_sheet.py): the free specimen is the outline between
y = 2 and 58 mm, clamped there. Outputs at each stretch: ux, uy (mm) of the scene's
probe gauge_edge, asked at (5.25, 30) mm: bapd records the nearest lattice point,
(5.25, 29.75) mm (the tie with 30.25 goes to the lower); s = top reaction /
(20 mm x 2 mm) (kPa). bapd keeps the lattice points inside the .geo's own mesh (1 mm
segments on the fillets, a sagitta of 0.025 mm); the FE uses the exact arcs.
Meshes: gmsh, size h, second-order geometry. Writes results/dogbone.csv.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS = 20.0, 60.0, 2.0          # mm
DX, GRIP_LAYERS = 0.5, 4                            # the scene's lattice and grips
PROBE = (5.25, 29.75)                               # mm
REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GEO = os.path.join(REPOSITORY, "examples", "geometry", "dogbone.geo")


def outline_curves(gmsh, path):
    """The .geo's boundary as [("Line", a, b) or ("Circle", a, centre, b)], in mm."""
    gmsh.merge(path)
    gmsh.model.geo.synchronize()
    surfaces = gmsh.model.getEntities(2)
    if len(surfaces) != 1:
        sys.exit(f"dogbone: {path} holds {len(surfaces)} surfaces, expected 1")
    curves = []
    for _, tag in gmsh.model.getBoundary(surfaces, oriented=True):
        lo, hi = gmsh.model.getParametrizationBounds(1, abs(tag))
        t = [lo[0], 0.5 * (lo[0] + hi[0]), hi[0]]
        p = 1000.0 * np.asarray(gmsh.model.getValue(1, abs(tag), t)).reshape(3, 3)[:, :2]
        if tag < 0:
            p = p[::-1]
        kind = gmsh.model.getType(1, abs(tag))
        if kind == "Line":
            curves.append(("Line", p[0], p[2]))
        elif kind == "Circle":
            curves.append(("Circle", p[0], circumcentre(*p), p[2]))
        else:
            sys.exit(f"dogbone: curve {tag} of {path} is a {kind}; only lines and arcs")
    gmsh.clear()
    return curves


def circumcentre(a, b, c):
    d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    ux = ((a @ a) * (b[1] - c[1]) + (b @ b) * (c[1] - a[1]) + (c @ c) * (a[1] - b[1])) / d
    uy = ((a @ a) * (c[0] - b[0]) + (b @ b) * (a[0] - c[0]) + (c @ c) * (b[0] - a[0])) / d
    return np.array([ux, uy])


def build_dogbone(gmsh, h, grip_depth):
    curves = outline_curves(gmsh, GEO)
    gmsh.model.add("dogbone")
    occ = gmsh.model.occ
    starts = [occ.addPoint(c[1][0], c[1][1], 0) for c in curves]
    edges = []
    for i, c in enumerate(curves):
        a, b = starts[i], starts[(i + 1) % len(curves)]
        if c[0] == "Line":
            edges.append(occ.addLine(a, b))
        else:
            centre = occ.addPoint(c[2][0], c[2][1], 0)
            edges.append(occ.addCircleArc(a, centre, b))
    outline = occ.addPlaneSurface([occ.addCurveLoop(edges)])
    free = occ.addRectangle(0, grip_depth, 0, WIDTH, HEIGHT - 2 * grip_depth)
    cut, _ = occ.intersect([(2, outline)], [(2, free)])
    occ.synchronize()
    return [tag for _, tag in cut]


def main():
    title = f"Dogbone (examples/dogbone.yaml, outline from {os.path.relpath(GEO, REPOSITORY)})"
    gent_fe.gripped_specimen_main(__doc__, title, "dogbone.csv", build_dogbone, [1.25, 1.5],
                                  height=HEIGHT, width=WIDTH, thickness=THICKNESS,
                                  grip_depth=GRIP_LAYERS * DX, probe=PROBE)


if __name__ == "__main__":
    main()
