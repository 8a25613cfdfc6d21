#!/usr/bin/python3
"""FE reference for examples/waisted_sheet.yaml (a non-rectangular specimen).

The scene (mm): the sheet [0, 20] x [0, 60], thickness 2, less two discs of radius 12
centred at (-8, 30) and (28, 30) (a 12 mm waist), an elliptical pore centred at (10, 30)
with radii 1.5 x 0.8 tilted 30 degrees, and the diamond window (10, 46), (13, 49),
(10, 52), (7, 49). Grips: 3 point rows at each end (dx = 0.5 mm), x held, the bottom
fixed, the top moved by (lambda - 1) 60 mm (the default reference length: the body
height). Gent, mu = 4.55 kPa, Jm = 162.6, plane stress, K = 1000 mu.

Mirror in the continuum: the grips are rigid, so the free specimen is the shape
between y = 1.5 and y = 58.5 mm (the grip rows' cells end there), clamped on those two
edges (ux = 0; uy = 0 below, (lambda - 1) 60 mm above). Outputs at each stretch:
  ux, uy of the probe (mm): the scene's probe waist_edge at (4.25, 30) records the
  lattice point nearest to it, (4.25, 29.75) (the tie with (4.25, 30.25) goes to the
  lower by round-off and by natural id; bapd prints "Probe waist_edge: point ... at");
  s = top reaction / (20 mm x 2 mm) (kPa), as bapd's history (width x thickness).
Meshes: gmsh, size h, h/4 within 1 mm of the pore and the window (their corners and
tight curvature), second-order geometry. Writes results/waisted_sheet.csv.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS = 20.0, 60.0, 2.0          # mm
DX, GRIP_LAYERS = 0.5, 3                            # the scene's lattice and grips
PROBE = (4.25, 29.75)                               # mm


def build_waisted(gmsh, h, grip_depth):
    occ = gmsh.model.occ
    sheet = occ.addRectangle(0, grip_depth, 0, WIDTH, HEIGHT - 2 * grip_depth)
    left = occ.addDisk(-8, 30, 0, 12, 12)
    right = occ.addDisk(28, 30, 0, 12, 12)
    pore = occ.addDisk(10, 30, 0, 1.5, 0.8)
    occ.rotate([(2, pore)], 10, 30, 0, 0, 0, 1, np.radians(30))
    corners = [occ.addPoint(x, y, 0) for x, y in [(10, 46), (13, 49), (10, 52), (7, 49)]]
    lines = [occ.addLine(corners[i], corners[(i + 1) % 4]) for i in range(4)]
    window = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    cut, _ = occ.cut([(2, sheet)], [(2, left), (2, right), (2, pore), (2, window)])
    occ.synchronize()
    # Curves of the pore and the window: those whose bounding box lies in their boxes.
    near = []
    for box in [(8, 28.5, 12, 31.5), (6.9, 45.9, 13.1, 52.1)]:
        near += [tag for _, tag in gmsh.model.getEntitiesInBoundingBox(
            box[0], box[1], -1, box[2], box[3], 1, dim=1)]
    gent_fe.refine_near(gmsh, "CurvesList", near, h / 4, h, 1.0, 1.0 + 3 * h, 200)
    return [tag for _, tag in cut]


def main():
    gent_fe.gripped_specimen_main(__doc__, "Waisted sheet (examples/waisted_sheet.yaml)",
                                  "waisted_sheet.csv", build_waisted, [1.25, 1.5, 1.75, 2.0],
                                  height=HEIGHT, width=WIDTH, thickness=THICKNESS,
                                  grip_depth=GRIP_LAYERS * DX, probe=PROBE)


if __name__ == "__main__":
    main()
