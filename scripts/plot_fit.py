#!/usr/bin/python3
"""Draws bapd-fit's data against its fitted curves, one PNG per test mode.

    scripts/plot_fit.py OUTPUT_DIR        # reads data.csv and curves.csv, writes fit_<mode>.png

bapd-fit calls it after a fit (unless -no_plot). Needs numpy and matplotlib
(Debian's python3-numpy, python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(message):
    print(f"plot_fit.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: {e.strerror}; run bapd-fit first (it writes data.csv and curves.csv)")


def main():
    if len(sys.argv) != 2:
        fail("usage: plot_fit.py OUTPUT_DIR (bapd-fit's -output_dir)")
    out = sys.argv[1]
    data, curves = rows(os.path.join(out, "data.csv")), rows(os.path.join(out, "curves.csv"))
    modes = sorted({r["mode"] for r in data})
    for mode in modes:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for file in sorted({r["file"] for r in data if r["mode"] == mode}):
            pts = [r for r in data if r["mode"] == mode and r["file"] == file]
            ax.plot([float(r["stretch"]) for r in pts], [float(r["nominal_stress_Pa"]) / 1e3 for r in pts],
                    "o", mfc="none", color="k", label=f"data: {os.path.basename(file)}")
        for law in dict.fromkeys(r["law"] for r in curves):
            pts = [r for r in curves if r["mode"] == mode and r["law"] == law]
            if pts:
                ax.plot([float(r["stretch"]) for r in pts], [float(r["nominal_stress_Pa"]) / 1e3 for r in pts],
                        "-", label=law)
        ax.set_xlabel("stretch [-]")
        ax.set_ylabel("nominal stress [kPa]")
        ax.set_title(f"bapd-fit: {mode.replace('_', ' ')}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = os.path.join(out, f"fit_{mode}.png")
        fig.savefig(path, dpi=120)
        plt.close(fig)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
