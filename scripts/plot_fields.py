#!/usr/bin/python3
"""Renders one field of a bapd run (-output_fields) at one output time to a PNG: the
points at their deformed positions, coloured by the field.

    scripts/plot_fields.py output                          # damage at the last time
    scripts/plot_fields.py output --field max_bond_stretch --time 0.1 --output s.png
    scripts/plot_fields.py output/fields.xdmf --field displacement --component y --step 400

RUN is the run's -output_dir or its fields.xdmf. The time shown is the output time
nearest to --time (or the file of --step); without either, the last one. Fields:
the scalars damage, max_bond_stretch, thickness_stretch, strain_energy_density,
volume, rank, natural_id; the vectors displacement, velocity, force_density,
reference_position (their magnitude, or --component x / y); the tensors
nominal_stress, cauchy_stress, deformation_gradient (the in-plane Frobenius norm, or
--component xx / xy / yx / yy). Needs h5py, numpy and matplotlib (Debian's
python3-h5py, python3-numpy, python3-matplotlib; scripts/install-deps.sh).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

UNITS = {"damage": "-", "max_bond_stretch": "-", "displacement": "m", "velocity": "m/s", "reference_position": "m",
         "thickness_stretch": "-", "strain_energy_density": "J/m^3", "volume": "m^3", "rank": "-", "natural_id": "-",
         "force_density": "N/m^3", "nominal_stress": "Pa", "cauchy_stress": "Pa", "deformation_gradient": "-"}
TENSOR_COMPONENTS = {"xx": 0, "xy": 1, "yx": 3, "yy": 4}  # of the row-major 3x3 in the file


def frames_of(xdmf):
    """(step, time, file) of every output time the XDMF index lists, in order."""
    base = os.path.dirname(os.path.abspath(xdmf))
    frames = []
    for grid in ET.parse(xdmf).getroot().find("Domain/Grid").findall("Grid"):
        step = int(grid.get("Name").split()[-1])
        time = float(grid.find("Time").get("Value"))
        path = grid.find("Geometry/DataItem").text.strip().split(":")[0]
        frames.append((step, time, os.path.join(base, path)))
    return frames


def marker_size(fig, ax, position, width, height):
    """Marker area [points^2] for discs about as wide as the point spacing on screen.

    The spacing is estimated from the points' bounding box and count (a uniform
    lattice: sqrt(area / N)); with an equal aspect ratio the axes' scale is the
    smaller of the two directions' points per metre."""
    spacing = np.sqrt(width * height / max(len(position), 1))
    ax.apply_aspect()  # the box the equal aspect ratio leaves, not the one asked for
    box = ax.get_position()
    fig_w, fig_h = fig.get_size_inches()
    points_per_metre = 72.0 * min(box.width * fig_w / width, box.height * fig_h / height)
    diameter = 0.95 * spacing * points_per_metre
    return float(np.clip(diameter * diameter, 0.05, 400.0))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", help="the run's -output_dir, or its fields.xdmf")
    p.add_argument("--field", default="damage", choices=sorted(UNITS))
    p.add_argument("--component", choices=["magnitude", "x", "y", *TENSOR_COMPONENTS], default="magnitude",
                   help="of a vector (x, y) or tensor (xx, xy, yx, yy) field")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--time", type=float, help="output time nearest to this [s]")
    which.add_argument("--step", type=int, help="the output of this step")
    p.add_argument("--output", help="PNG to write (default: <field>_step<N>.png beside fields.xdmf)")
    p.add_argument("--size", type=float, default=0, help="marker size [points^2] (default: the point spacing on screen)")
    p.add_argument("--dpi", type=int, default=150)
    args = p.parse_args()

    xdmf = args.run if args.run.endswith(".xdmf") else os.path.join(args.run, "fields.xdmf")
    if not os.path.exists(xdmf):
        sys.exit(f"plot_fields.py: {xdmf} not found: run bapd with -output_fields")
    frames = frames_of(xdmf)
    if not frames:
        sys.exit(f"plot_fields.py: {xdmf} lists no output time")
    if args.step is not None:
        matches = [f for f in frames if f[0] == args.step]
        if not matches:
            sys.exit(f"plot_fields.py: no output at step {args.step}; steps: {[f[0] for f in frames]}")
        step, time, path = matches[0]
    elif args.time is not None:
        step, time, path = min(frames, key=lambda f: abs(f[1] - args.time))
    else:
        step, time, path = frames[-1]

    with h5py.File(path, "r") as f:
        position = f["position"][()]
        values = f[args.field][()]
        stretch = float(f.attrs.get("stretch", np.nan))
    label = f"{args.field} [{UNITS[args.field]}]"
    if values.ndim == 2 and values.shape[1] == 9:  # a tensor
        if args.component == "magnitude":
            values = np.linalg.norm(values[:, [0, 1, 3, 4]], axis=1)
            label = f"|{args.field}| [{UNITS[args.field]}]"
        elif args.component in TENSOR_COMPONENTS:
            values = values[:, TENSOR_COMPONENTS[args.component]]
            label = f"{args.field} {args.component} [{UNITS[args.field]}]"
        else:
            sys.exit(f"plot_fields.py: {args.field} is a tensor: give --component xx, xy, yx or yy (or magnitude)")
    elif values.ndim == 2:
        if args.component in TENSOR_COMPONENTS:
            sys.exit(f"plot_fields.py: {args.field} is a vector: give --component x or y (or magnitude)")
        if args.component == "magnitude":
            values = np.linalg.norm(values[:, :2], axis=1)
            label = f"|{args.field}| [{UNITS[args.field]}]"
        else:
            values = values[:, "xy".index(args.component)]
            label = f"{args.field} {args.component} [{UNITS[args.field]}]"

    width = np.ptp(position[:, 0]) or 1.0
    height = np.ptp(position[:, 1]) or 1.0
    fig_width = 7.0
    fig, ax = plt.subplots(figsize=(fig_width, max(2.5, min(12.0, fig_width * height / width))))
    order = np.argsort(values, kind="stable")  # the largest values drawn last, on top
    vmin, vmax = (0.0, 1.0) if args.field == "damage" else (None, None)
    art = ax.scatter(position[order, 0], position[order, 1], c=values[order], s=1.0, cmap="viridis",
                     vmin=vmin, vmax=vmax, linewidths=0)
    fig.colorbar(art, ax=ax, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{args.field} at the deformed positions\nstep {step}, t = {time:.4g} s, stretch {stretch:.4f}", fontsize=10)
    fig.tight_layout()
    art.set_sizes([args.size or marker_size(fig, ax, position, width, height)])  # once the layout is final
    output = args.output or os.path.join(os.path.dirname(os.path.abspath(xdmf)), f"{args.field}_step{step}.png")
    fig.savefig(output, dpi=args.dpi)
    print(f"{output}: {args.field} at step {step}, t = {time:.6g} s")


if __name__ == "__main__":
    main()
