#!/usr/bin/python3
"""Plots columns of a bapd history.csv against each other to a PNG: by default the
stress-stretch curve (nominal stress of the first load set against the applied stretch).

    scripts/plot_history.py output/pure_shear                       # stress-stretch curve
    scripts/plot_history.py output/pure_shear --reference eq36      # with the paper's eq 36
    scripts/plot_history.py output/plate --x time_s --y kinetic_energy_J internal_energy_J --logy
    scripts/plot_history.py output/a output/b --label coarse fine   # two runs on one plot
    scripts/plot_history.py output/ps --reference-csv data.csv:stretch,stress_Pa

RUN is a run's -output_dir or its history.csv; several runs are drawn on one plot.
--reference eq36 draws the incompressible Gent pure-shear response (paper eq 36),
P = mu Jm (l - l^-3) / (Jm - l^2 - l^-2 + 2), with --mu and --Jm (defaults: the
paper's 4.55 kPa and 162.6); --reference neo_hookean_pure_shear the Jm -> inf limit.
--reference-csv FILE:XCOL,YCOL draws measured or computed data from another CSV.
The axes are labelled with the quantities and their units, read from the column names
(top_nominal_stress_Pa: "top nominal stress (kPa)", the values scaled to the unit
that suits them; scripts/plot_labels.py); the title says what is drawn against what.
Needs numpy and matplotlib (Debian's python3-numpy, python3-matplotlib).
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_labels import axis_label, common_label, split_name  # noqa: E402


def fail(message):
    sys.exit(f"plot_history.py: error: {message}")


def read_columns(path):
    """The CSV at path as {column name: numpy array}."""
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(f) if r and not r[0].lstrip().startswith("#")]  # '# mode: ...' lines of bapd-fit's CSVs
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    if len(rows) < 2:
        fail(f"{path} holds no data row (is the run still at its first output?)")
    header, data = rows[0], rows[1:]
    width = len(header)
    complete = [r for r in data if len(r) == width]  # a row cut by a killed run is left out
    try:
        values = np.array(complete, dtype=float)
    except ValueError:
        fail(f"{path}: a value is not a number")
    return {name: values[:, k] for k, name in enumerate(header)}


def history_path(run):
    path = run if run.endswith(".csv") else os.path.join(run, "history.csv")
    if not os.path.exists(path):
        fail(f"{path} not found: give a run's -output_dir or its history.csv")
    return path


def column(columns, name, path):
    if name not in columns:
        fail(f"{path} has no column '{name}'; its columns: {', '.join(columns)}")
    return columns[name]


def default_y(columns, path):
    stresses = [c for c in columns if c.endswith("_nominal_stress_Pa")]
    if not stresses:
        fail(f"{path} has no nominal-stress column: name one with --y")
    return [stresses[0]]


def reference_curve(kind, x, mu, Jm):
    l = np.linspace(max(1.0, np.nanmin(x)), np.nanmax(x), 400)
    if kind == "eq36":
        return l, mu * Jm * (l - l**-3) / (Jm - l**2 - l**-2 + 2), f"Gent pure shear, eq 36 (mu = {mu:g} Pa, Jm = {Jm:g})"
    return l, mu * (l - l**-3), f"neo-Hookean pure shear (mu = {mu:g} Pa)"


def si_to(unit, axis_unit, name, axis_name):
    """The factor from a reference column's unit to the axis column's (kPa to Pa: 1000)."""
    if unit == axis_unit:
        return 1.0
    if (unit, axis_unit) == ("kPa", "Pa"):
        return 1e3
    if (unit, axis_unit) == ("Pa", "kPa"):
        return 1e-3
    fail(f"--reference-csv: column {name} is in {unit or 'no unit'}, the axis's {axis_name} in {axis_unit or 'no unit'}; "
         "name the reference columns with their units (stretch, ..._Pa, ..._kPa)")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="a run's -output_dir or its history.csv (several: one curve each)")
    p.add_argument("--x", default="stretch", help="column on the x axis (default: stretch)")
    p.add_argument("--y", nargs="+", help="column(s) on the y axis (default: the first *_nominal_stress_Pa)")
    p.add_argument("--label", nargs="+", help="one legend label per run (default: the run's folder)")
    p.add_argument("--reference", choices=["eq36", "neo_hookean_pure_shear"], help="analytic reference curve")
    p.add_argument("--mu", type=float, default=4.55e3, help="shear modulus of the reference curve [Pa]")
    p.add_argument("--Jm", type=float, default=162.6, help="Gent limit of the reference curve [-]")
    p.add_argument("--reference-csv", help="FILE:XCOL,YCOL, reference data from another CSV")
    p.add_argument("--logy", action="store_true", help="logarithmic y axis")
    p.add_argument("--output", help="PNG to write (default: <y>_vs_<x>.png beside the first history.csv)")
    p.add_argument("--dpi", type=int, default=150)
    args = p.parse_args()
    if args.label and len(args.label) != len(args.runs):
        fail(f"--label gives {len(args.label)} labels for {len(args.runs)} runs")

    # every series first, so that one unit and one scale serve the whole axis
    series, all_x, y_names, names = [], [], None, []
    for k, run in enumerate(args.runs):
        path = history_path(run)
        columns = read_columns(path)
        x = column(columns, args.x, path)
        y_names = args.y or default_y(columns, path)
        name = args.label[k] if args.label else os.path.basename(os.path.dirname(os.path.abspath(path)))
        names.append(name)
        for y_name in y_names:
            series.append((name, y_name, x, column(columns, y_name, path)))
        all_x.append(x)
    x_all = np.concatenate(all_x)
    # the references, in the axes' SI units: (x, y, style, label)
    references = []
    if args.reference:
        if args.x != "stretch":
            fail("--reference is a curve against the stretch: use it with --x stretch")
        if split_name(y_names[0])[1] != "Pa":
            fail(f"--reference is a nominal stress in Pa; the y axis is {y_names[0]}")
        lx, ly, label = reference_curve(args.reference, x_all, args.mu, args.Jm)
        references.append((lx, ly, dict(color="k", linestyle="--", linewidth=1), label))
    if args.reference_csv:
        try:
            file, cols = args.reference_csv.rsplit(":", 1)
            xcol, ycol = cols.split(",")
        except ValueError:
            fail(f"--reference-csv {args.reference_csv}: expected FILE:XCOL,YCOL")
        ref = read_columns(file)
        rx = column(ref, xcol, file) * si_to(split_name(xcol)[1], split_name(args.x)[1], xcol, args.x)
        ry = column(ref, ycol, file) * si_to(split_name(ycol)[1], split_name(y_names[0])[1], ycol, y_names[0])
        references.append((rx, ry, dict(color="k", marker="s", linestyle="", markersize=4, fillstyle="none"),
                           os.path.basename(file)))
    # one unit and one scale for everything on an axis
    x_label, x_factor = axis_label(args.x, np.concatenate([x_all] + [r[0] for r in references]))
    shared = common_label(y_names, [s[3] for s in series] + [r[1] for r in references])
    if shared is None:  # several units on one axis: each series in its own SI unit, named in the legend
        y_label, y_factor = ", ".join(axis_label(n)[0] for n in y_names), 1.0
    else:
        y_label, y_factor = shared

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, y_name, x, y in series:
        if len(y_names) == 1:
            label = name
        else:
            words, unit = split_name(y_name)
            label = f"{name}: {words}" + (f" ({unit})" if shared is None and unit else "")
        ax.plot(x * x_factor, y * y_factor, marker="o" if len(x) < 40 else None, markersize=3, label=label)
    for rx, ry, style, label in references:
        ax.plot(rx * x_factor, ry * y_factor, label=label, **style)
    if args.logy:
        ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    y_words = shared[0].rsplit(" (", 1)[0] if shared else ", ".join(split_name(n)[0] for n in y_names)
    x_words = x_label.rsplit(" (", 1)[0]
    ax.set_title(f"{y_words[:1].upper() + y_words[1:]} against {x_words}" + (f": {names[0]}" if len(names) == 1 else ""),
                 fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    first = history_path(args.runs[0])
    output = args.output or os.path.join(os.path.dirname(os.path.abspath(first)), f"{y_names[0]}_vs_{args.x}.png")
    fig.savefig(output, dpi=args.dpi)
    print(f"{output}: {y_label} against {x_label}, {len(args.runs)} run(s)")


if __name__ == "__main__":
    main()
