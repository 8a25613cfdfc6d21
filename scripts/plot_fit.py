#!/usr/bin/python3
"""Draws bapd-fit's data against its fitted curves, one PNG per test mode.

    scripts/plot_fit.py OUTPUT_DIR        # reads data.csv and curves.csv, writes fit_<mode>.png

bapd-fit calls it after a fit (unless -no_plot). The axes are the stretch and the
nominal stress in the unit that suits its values (Pa, kPa or MPa); the legend names
each data file and each law with its fitted parameters (parameters_<law>.csv); the
title names the test. A notched pure-shear curve (bapd-fit's toughness) is drawn on the
pure-shear figure with its crack onset lambda_c +- its uncertainty and the first law's
Gamma (toughness.csv). Needs numpy and matplotlib (Debian's python3-numpy,
python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_labels import display_unit  # noqa: E402

TESTS = {"uniaxial": "uniaxial tension", "pure_shear": "pure shear", "equibiaxial": "equibiaxial tension"}


def fail(message):
    print(f"plot_fit.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: {e.strerror}; run bapd-fit first (it writes data.csv and curves.csv)")


def law_label(out, law):
    """'gent: mu = 4.55 kPa, Jm = 162.6' from parameters_<law>.csv (the law's name alone without it)."""
    path = os.path.join(out, f"parameters_{law}.csv")
    if not os.path.exists(path):
        return law
    parts = []
    for r in rows(path):
        value = float(r["value"])
        if r["unit"] == "Pa":
            shown, factor = display_unit("Pa", [value])
            parts.append(f"{r['parameter']} = {value * factor:.4g} {shown}")
        else:
            parts.append(f"{r['parameter']} = {value:.4g}" + (f" {r['unit']}" if r["unit"] not in ("", "-") else ""))
    return f"{law}: " + ", ".join(parts)


def toughness_marks(ax, out, mode_data, factor):
    """The notched curve and lambda_c +- u with the first law's Gamma (toughness.csv) on the pure-shear axes."""
    for file in sorted({r["file"] for r in mode_data}):
        pts = [r for r in mode_data if r["file"] == file]
        ax.plot([float(r["stretch"]) for r in pts], [float(r["nominal_stress_Pa"]) * factor for r in pts],
                "s", ms=4, mfc="none", color="0.5", label=f"notched: {os.path.basename(file)}")
    path = os.path.join(out, "toughness.csv")
    if not os.path.exists(path):
        return
    laws = rows(path)
    if not laws:
        return
    lc, u = float(laws[0]["onset_stretch"]), float(laws[0]["onset_stretch_uncertainty"])
    ax.axvspan(lc - u, lc + u, color="0.85", zorder=0)
    first = laws[0]  # the first law of -law (every law's Gamma: toughness.csv)
    ax.axvline(lc, color="0.3", ls=":", label=f"λc = {lc:.4g} ± {u:.2g}: Γ = {float(first['fracture_energy_J_m2']):.4g} ± "
               f"{float(first['fracture_energy_uncertainty_J_m2']):.2g} J/m² ({first['law']})")


def main():
    if len(sys.argv) != 2:
        fail("usage: plot_fit.py OUTPUT_DIR (bapd-fit's -output_dir)")
    out = sys.argv[1]
    data, curves = rows(os.path.join(out, "data.csv")), rows(os.path.join(out, "curves.csv"))
    notched = [r for r in data if r["mode"] == "notched_pure_shear"]
    modes = sorted({r["mode"] for r in data} - {"notched_pure_shear"})
    for mode in modes:
        mode_data = [r for r in data if r["mode"] == mode]
        mode_curves = [r for r in curves if r["mode"] == mode]
        notched_here = notched if mode == "pure_shear" else []
        shown, factor = display_unit("Pa", [float(r["nominal_stress_Pa"]) for r in mode_data + mode_curves + notched_here])
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for file in sorted({r["file"] for r in mode_data}):
            pts = [r for r in mode_data if r["file"] == file]
            ax.plot([float(r["stretch"]) for r in pts], [float(r["nominal_stress_Pa"]) * factor for r in pts],
                    "o", mfc="none", color="k", label=f"data: {os.path.basename(file)}")
        for law in dict.fromkeys(r["law"] for r in curves):
            pts = [r for r in mode_curves if r["law"] == law]
            if pts:
                ax.plot([float(r["stretch"]) for r in pts], [float(r["nominal_stress_Pa"]) * factor for r in pts],
                        "-", label=law_label(out, law))
        if notched_here:
            toughness_marks(ax, out, notched_here, factor)
        ax.set_xlabel("stretch λ (-)")
        ax.set_ylabel(f"nominal stress ({shown})")
        ax.set_title(f"bapd-fit: {TESTS.get(mode, mode.replace('_', ' '))}, data and fitted laws", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
        fig.tight_layout()
        path = os.path.join(out, f"fit_{mode}.png")
        fig.savefig(path, dpi=120)
        plt.close(fig)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
