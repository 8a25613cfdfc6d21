#!/usr/bin/python3
"""Renders one field of a bapd run (-output_fields) at one output time to a PNG: the
points at their deformed positions, coloured by the field.

    scripts/plot_fields.py output                          # damage at the last time
    scripts/plot_fields.py output --field max_bond_stretch --time 0.1 --output s.png
    scripts/plot_fields.py output/fields.xdmf --field cauchy_stress --component yy --step 400

RUN is the run's -output_dir or its fields.xdmf. The time shown is the output time
nearest to --time (or the file of --step); without either, the last one. Fields:
the scalars damage, max_bond_stretch, thickness_stretch, strain_energy_density,
volume, rank, natural_id; the vectors displacement, velocity, force_density,
reference_position (their magnitude, or --component x / y / z); the tensors
nominal_stress, cauchy_stress, deformation_gradient (the in-plane Frobenius norm, or
--component xx / xy / yx / yy, and xz ... zz in 3D); any other dataset of the file by
its name. The component is in the title and the file name
(cauchy_stress_yy_step400.png); the colour bar's unit suits the values (kPa).

The grips placed outside the specimen (docs/options.md, "Loading": lattice rows
beyond the sheet's edges, held by the load sets, not part of the specimen) are drawn
apart, in grey, and left out of the colour scale: their stresses are the clamp's, not
the specimen's. They are the points the load sets hold (the dataset `load_set`,
non-zero), which bapd writes; in files without it, the points of a 2D lattice outside the specimen's frame
[0, width] x [0, height], which a bottom or left grip shows as y < 0 or x < 0, and
whose far edges are those of the other side mirrored (grips as deep at the top as at
the bottom, the default) unless --specimen WIDTH HEIGHT gives them. --grips show
draws them like the specimen. Needs h5py, numpy and matplotlib (Debian's
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
from matplotlib.lines import Line2D  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_labels import display_unit  # noqa: E402

# SI unit and the words of each field
FIELDS = {"damage": ("-", "damage"), "max_bond_stretch": ("-", "largest bond stretch"),
          "displacement": ("m", "displacement"), "velocity": ("m/s", "velocity"),
          "reference_position": ("m", "reference position"), "position": ("m", "position"),
          "thickness_stretch": ("-", "thickness stretch λ₃"), "strain_energy_density": ("J/m³", "strain energy density"),
          "volume": ("m^3", "volume"), "rank": (None, "rank"), "natural_id": (None, "natural id"),
          "force_density": ("N/m³", "force density"), "nominal_stress": ("Pa", "nominal stress P"),
          "cauchy_stress": ("Pa", "Cauchy stress σ"), "deformation_gradient": ("-", "deformation gradient F")}
TENSOR_COMPONENTS = {"xx": 0, "xy": 1, "xz": 2, "yx": 3, "yy": 4, "yz": 5, "zx": 6, "zy": 7, "zz": 8}  # row-major 3x3
GRIP_DATASETS = ("load_set",)
GRIP_GREY = "0.75"


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


def field_unit_and_words(name):
    """(SI unit or None, words) of a dataset; a name the table lacks by its words."""
    if name in FIELDS:
        return FIELDS[name]
    words = name.replace("_", " ")
    if "stress" in name:
        return "Pa", words
    if "stretch" in name or "strain" in name:
        return "-", words
    return None, words


def marker_size(fig, ax, position, width, height):
    """Marker area [points^2] for discs about as wide as the point spacing on screen
    (position, width and height in one unit).

    The spacing is estimated from the points' bounding box and count (a uniform
    lattice: sqrt(area / N)); with an equal aspect ratio the axes' scale is the
    smaller of the two directions' points per unit length."""
    spacing = np.sqrt(width * height / max(len(position), 1))
    ax.apply_aspect()  # the box the equal aspect ratio leaves, not the one asked for
    box = ax.get_position()
    fig_w, fig_h = fig.get_size_inches()
    points_per_unit = 72.0 * min(box.width * fig_w / width, box.height * fig_h / height)
    diameter = 0.95 * spacing * points_per_unit
    return float(np.clip(diameter * diameter, 0.05, 400.0))


def lattice_spacing(coordinates):
    """The smallest gap between the distinct values of one coordinate (0 if one value)."""
    values = np.unique(np.round(coordinates, 12))
    gaps = np.diff(values)
    gaps = gaps[gaps > 1e-12 * max(1.0, np.abs(values).max())]
    return float(gaps.min()) if len(gaps) else 0.0


def grip_points(f, reference, specimen):
    """(mask of the grip points outside the specimen, how they were found)."""
    for name in GRIP_DATASETS:
        if name in f:
            return f[name][()].reshape(len(reference), -1).any(axis=1), f"dataset '{name}'"
    none = np.zeros(len(reference), dtype=bool)
    if int(f.attrs.get("dimension", 2)) != 2:
        return none, "a 3D body's grips are its own points"
    x, y = reference[:, 0], reference[:, 1]
    dx = min(d for d in (lattice_spacing(x), lattice_spacing(y)) if d > 0) if len(x) > 1 else 0.0
    # a lattice has its points at ((i + 1/2) dx, (j + 1/2) dx) of the specimen's frame
    on_lattice = dx > 0 and all(np.abs(c / dx - 0.5 - np.round(c / dx - 0.5)).max() < 1e-6 for c in (x, y))
    if not on_lattice:
        return none, "the points are not a lattice (given points have their grips inside)"
    if specimen:
        width, height = specimen
    else:  # each far edge mirrors the near one: as many grip rows at the top as at the bottom
        width = x.max() + x.min() if x.min() < 0 else x.max() + dx / 2
        height = y.max() + y.min() if y.min() < 0 else y.max() + dx / 2
    outside = (x < 0) | (y < 0) | (x > width) | (y > height)
    how = f"outside the specimen [0, {width * 1e3:.4g}] x [0, {height * 1e3:.4g}] mm"
    return outside, how + ("" if specimen else " (far edges mirrored; --specimen gives them)")


def pick_values(name, values, component):
    """(values per point, component name or '') of a scalar, vector or tensor dataset."""
    if values.ndim == 2 and values.shape[1] == 9:  # a tensor
        if component == "magnitude":
            return np.linalg.norm(values[:, [0, 1, 3, 4]], axis=1), "norm"
        if component in TENSOR_COMPONENTS:
            return values[:, TENSOR_COMPONENTS[component]], component
        sys.exit(f"plot_fields.py: {name} is a tensor: give --component xx, xy, yx, yy (xz ... zz in 3D) or magnitude")
    if values.ndim == 2:
        if component in TENSOR_COMPONENTS:
            sys.exit(f"plot_fields.py: {name} is a vector: give --component x, y, z or magnitude")
        if component == "magnitude":
            return np.linalg.norm(values, axis=1), "magnitude"
        return values[:, "xyz".index(component)], component
    if component != "magnitude":
        sys.exit(f"plot_fields.py: {name} is a scalar: it has no component {component}")
    return values, ""


def describe(name, component):
    """Title words of a field and component: 'Cauchy stress σ_yy', '|displacement|', 'displacement y'."""
    words = field_unit_and_words(name)[1]
    if not component:
        return words
    if component == "magnitude":
        return f"|{words}|"
    if component == "norm":
        return f"|{words}| (in-plane norm)"
    if words.endswith(("σ", "P", "F")):
        return f"{words}$_{{{component}}}$"
    return f"{words} {component}"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", help="the run's -output_dir, or its fields.xdmf")
    p.add_argument("--field", default="damage", help="a dataset of the field files (default damage)")
    p.add_argument("--component", choices=["magnitude", "x", "y", "z", *TENSOR_COMPONENTS], default="magnitude",
                   help="of a vector (x, y, z) or tensor (xx, xy, yx, yy, ...) field")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--time", type=float, help="output time nearest to this [s]")
    which.add_argument("--step", type=int, help="the output of this step")
    p.add_argument("--output", help="PNG to write (default: <field>[_<component>]_step<N>.png beside fields.xdmf)")
    p.add_argument("--size", type=float, default=0, help="marker size [points^2] (default: the point spacing on screen)")
    p.add_argument("--specimen", nargs=2, type=float, metavar=("WIDTH", "HEIGHT"),
                   help="the specimen's width and height [m] (the scene's -body_width, -body_height): the far edges "
                        "beyond which grip points lie (default: mirrored from the near ones)")
    p.add_argument("--grips", choices=["apart", "show"], default="apart",
                   help="apart (default): grip points outside the specimen in grey, out of the colour scale; "
                        "show: coloured like the specimen")
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
        if args.field not in f:
            sys.exit(f"plot_fields.py: {path} has no field '{args.field}'; it has {', '.join(sorted(f.keys()))}")
        position = f["position"][()]
        reference = f["reference_position"][()]
        raw = f[args.field][()]
        stretch = float(f.attrs.get("stretch", np.nan))
        grips, grips_how = grip_points(f, reference, args.specimen)
    if args.grips == "show":
        grips = np.zeros(len(position), dtype=bool)
    values, component = pick_values(args.field, raw, args.component)
    specimen = ~grips
    si, _ = field_unit_and_words(args.field)
    shown, factor = display_unit(si, values[specimen]) if si not in (None, "-") else (si, 1.0)
    values = values * factor
    what = describe(args.field, component)
    label = what + (f" ({shown})" if shown else "")

    position = position * 1e3  # drawn in mm
    width = np.ptp(position[:, 0]) or 1.0
    height = np.ptp(position[:, 1]) or 1.0
    fig_width = 7.0
    fig, ax = plt.subplots(figsize=(fig_width, max(2.5, min(12.0, fig_width * height / width))))
    arts = []
    if grips.any():
        arts.append(ax.scatter(position[grips, 0], position[grips, 1], s=1.0, color=GRIP_GREY, linewidths=0))
    order = np.flatnonzero(specimen)[np.argsort(values[specimen], kind="stable")]  # the largest values drawn last, on top
    vmin, vmax = (0.0, 1.0) if args.field == "damage" else (None, None)
    art = ax.scatter(position[order, 0], position[order, 1], c=values[order], s=1.0, cmap="viridis",
                     vmin=vmin, vmax=vmax, linewidths=0)
    arts.append(art)
    fig.colorbar(art, ax=ax, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"{what[:1].upper() + what[1:]} at the deformed positions\n"
                 f"step {step}, t = {time:.4g} s, stretch {stretch:.4f}", fontsize=10)
    if grips.any():
        proxy = Line2D([], [], marker="o", linestyle="", color=GRIP_GREY, markersize=6)
        ax.legend([proxy], [f"grips outside the specimen ({int(grips.sum())} points)"],
                  loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=8, frameon=False)
    fig.tight_layout()
    size = args.size or marker_size(fig, ax, position, width, height)
    for a in arts:
        a.set_sizes([size])  # once the layout is final
    suffix = f"_{component}" if component else ""
    output = args.output or os.path.join(os.path.dirname(os.path.abspath(xdmf)), f"{args.field}{suffix}_step{step}.png")
    fig.savefig(output, dpi=args.dpi)
    low, high = art.get_clim()
    print(f"{output}: {what.replace('$_{', '_').replace('}$', '')} at step {step}, t = {time:.6g} s, colour scale {low:.6g} to {high:.6g} {shown if shown not in (None, '-') else ''}".rstrip()
          + (f"; {int(grips.sum())} grip points apart ({grips_how})" if grips.any() else ""))


if __name__ == "__main__":
    main()
