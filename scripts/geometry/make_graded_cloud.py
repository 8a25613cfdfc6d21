#!/usr/bin/python3
"""Writes the point cloud of examples/point_cloud.yaml: a 20 mm x 40 mm sheet on a
graded grid, finest (0.4 mm) on the centre lines where the scene's hole is, coarsest
(1 mm) at the edges. The points sit at the images of the cell centres of a uniform
grid in (u, v) in [-1, 1]^2 under x = W/2 (1 + (u + b u^3) / (1 + b)) (y alike), and
each point's volume is the image of its cell: X'(u) Y'(v) du dv x thickness, so the
volumes add up to the sheet's. The hole is cut by the scene (body: holes), not here.

Columns x, y, volume [m, m, m^3] and block_id (1): the Peridigm/PeriLab convention
that -body_cloud reads (docs/options.md "Body").
  /usr/bin/python3 scripts/geometry/make_graded_cloud.py examples/geometry/graded_sheet.csv
"""
import sys

WIDTH, HEIGHT, THICKNESS = 0.020, 0.040, 0.002
NX, NY = 28, 56   # points along x and y
B = 0.5           # grading: spacing ratio edge / centre = 1 + 3 b = 2.5


def axis(length, n):
    """Positions and spacings of n points along [0, length], finest at the middle."""
    du = 2.0 / n
    out = []
    for k in range(n):
        u = -1.0 + (k + 0.5) * du
        x = 0.5 * length * (1.0 + (u + B * u ** 3) / (1.0 + B))
        dx = 0.5 * length * (1.0 + 3.0 * B * u * u) / (1.0 + B) * du
        out.append((x, dx))
    return out


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "graded_sheet.csv"
    xs, ys = axis(WIDTH, NX), axis(HEIGHT, NY)
    with open(path, "w") as f:
        f.write("x,y,volume,block_id\n")
        for y, hy in ys:
            for x, hx in xs:
                f.write(f"{x:.17g},{y:.17g},{hx * hy * THICKNESS:.17g},1\n")
    total = sum(hx for _, hx in xs) * sum(hy for _, hy in ys) * THICKNESS
    print(f"{path}: {NX * NY} points, volume {total:.6g} m^3 (sheet {WIDTH * HEIGHT * THICKNESS:.6g}), "
          f"spacing {min(h for _, h in xs) * 1e3:.3g} to {max(h for _, h in xs) * 1e3:.3g} mm")


if __name__ == "__main__":
    main()
