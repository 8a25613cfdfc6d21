#!/usr/bin/python3
"""The shaped specimens against their FE references, for docs/validation.md.

Reads the static states of run_all.sh's runs `waisted_static` and `dogbone_static`
(examples/waisted_sheet.yaml and examples/dogbone.yaml by the fast static route) and
the converged FE solutions of the same specimens (tests/data/fe/waisted_sheet.csv,
tests/data/fe/dogbone.csv: the finest P2 mesh, K = 1000 mu as bapd's default), and appends a
section to the report's lines: probe ux, uy and nominal stress s = top reaction /
(width x thickness), bapd against FE, at every stretch both have.
Also usable alone: shaped_report.py OUTPUT_ROOT [DOCS_DIR] prints the section.
"""
import csv
import os
import sys

# name of the run, scene, FE file, probe, width x thickness (m^2), what the FE mirrors
SPECIMENS = [
    ("waisted_static", "examples/waisted_sheet.yaml", "waisted_sheet.csv", "waist_edge", 0.020 * 0.002,
     "a sheet less two discs crossing its sides, an elliptical pore and a diamond window; 3-row grips inside"),
    ("dogbone_static", "examples/dogbone.yaml", "dogbone.csv", "gauge_edge", 0.020 * 0.002,
     "the outline of examples/geometry/dogbone.geo; grips: the points within 2 mm (4 rows) of its end lines"),
]


def fe_converged(path):
    """{stretch: (ux mm, uy mm, s kPa)} of the finest P2 K = 1000 mu mesh."""
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["formulation"] == "K=1000mu" and r["degree"] == "2"]
    best = min(rows, key=lambda r: float(r["h_mm"]))
    out = {}
    for key in best:
        if key.startswith("ux_"):
            lam = key[3:-3]
            out[float(lam)] = (float(best[f"ux_{lam}_mm"]), float(best[f"uy_{lam}_mm"]), float(best[f"s_{lam}_kPa"]))
    return out, best


def shaped(root, docs, lines):
    lines += ["## 4. Shaped specimens against FE", "",
              "Non-rectangular specimens at the uniform-lattice default (dx = 0.5 mm, delta = 3.015 dx, the "
              "bond-only force with the tensor stress correction, which the three shaped examples set with "
              "`force_form: bond_only`, Gent, K = 1000 mu), static states by the fast route "
              "(0.05 s ramps, `-relaxation adaptive`, holds end at kinetic energy < 1e-10 x internal), 1 rank, against "
              "the FE solutions of docs/fe_reference.md (finest P2 mesh; the FE clamps the specimen where the scene's "
              "rigid inside grip rows end). ux, uy: the probe's point; s: top reaction / (20 mm x 2 mm).", ""]
    for run, scene, fe_file, probe, area, what in SPECIMENS:
        path = os.path.join(root, run, "static_states.csv")
        if not os.path.exists(path):
            lines += [f"- `{scene}`: not run ({path} missing)", ""]
            continue
        fe, best = fe_converged(os.path.join(docs, "..", "tests", "data", "fe", fe_file))
        lines += [f"`{scene}` ({what}; FE h = {best['h_mm']} mm, {best['dofs']} dofs):", "",
                  "| stretch | ux bapd (mm) | ux FE | diff | uy bapd (mm) | uy FE | diff | s bapd (kPa) | s FE | diff |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        with open(path) as f:
            for r in csv.DictReader(f):
                lam = float(r["stretch"])
                if lam not in fe:
                    continue
                ux, uy = 1e3 * float(r[f"{probe}_ux_m"]), 1e3 * float(r[f"{probe}_uy_m"])
                s = 1e-3 * float(r["top_reaction_y_N"]) / area
                fx, fy, fs = fe[lam]
                lines.append(f"| {lam:g} | {ux:.4f} | {fx:.4f} | {100 * (ux / fx - 1):+.2f} % | {uy:.4f} | {fy:.4f} | "
                             f"{100 * (uy / fy - 1):+.2f} % | {s:.4f} | {fs:.4f} | {100 * (s / fs - 1):+.2f} % |")
        lines.append("")
    lines += MEASURED


# Measured once by hand (not rerun by run_all.sh): why the differences are what
# they are.
MEASURED = [
    "Every entry is within 2 % (the mark `validation.shaped_short` holds the dogbone to); the stress is the largest difference, -1.5 to -1.65 % on the "
    "waisted sheet and -0.9 to -1.1 % on the dogbone, bapd softer. It is the lattice's, first order in dx: halving "
    "the spacing (dx = 0.25 mm, the grips kept 1.5 and 2 mm deep: `-load_top_layers 6 -load_bottom_layers 6` for the "
    "waisted sheet; the dogbone's group grips are 2 mm deep at any dx; the probe read as the mean of the four lattice "
    "points around (4.25, 29.75) or (5.25, 29.75) mm, which are cell corners at that spacing) more than halves it:",
    "",
    "| specimen, stretch | s dx = 0.5 mm | s dx = 0.25 mm | uy 0.5 | uy 0.25 | ux 0.5 | ux 0.25 |",
    "|---|---|---|---|---|---|---|",
    "| waisted, 1.25 | -1.65 % | -0.74 % | -0.43 % | -0.17 % | +1.03 % | -1.14 % |",
    "| waisted, 1.5 | -1.59 % | -0.70 % | -0.47 % | -0.17 % | +0.67 % | -0.90 % |",
    "| dogbone, 1.25 | -1.07 % | -0.47 % | +0.01 % | +0.01 % | -1.07 % | -0.47 % |",
    "| dogbone, 1.5 | -0.94 % | -0.40 % | +0.01 % | +0.01 % | -0.86 % | -0.36 % |",
    "",
    "With the energy-consistent default form instead (measured once, the same "
    "runs without `force_form: bond_only`), the stress is -3.50 / -3.22 / -3.01 / -2.88 % on the waisted sheet "
    "(stretch 1.25 / 1.5 / 1.75 / 2; ux +2.48 ... -0.10 %, uy -0.53 ... -0.66 %) and -1.76 / -1.56 % on the dogbone: "
    "that form is not corrected at free edges, which the 12 mm waist's horizon-wide edge layers make a large share "
    "of the section, so the shaped examples keep the corrected bond-only form (its corner instability, "
    "docs/stress_consistency.md, needs grips outside and stretches beyond 4.5).",
    "",
    "The grip model is the FE's (a grip that is not shows at once: the dogbone held one row deep instead of "
    "four, `validation.shaped_short`, is -3.3 % at 1.25), and what is left is the lattice's picture of the curved "
    "edges, the pore and the window (points at cell centres; the cells whose centres lie in or on the diamond "
    "window cover up to 84 cells, 21 mm^2, against its 18 mm^2) and of the rigid grips' inner edge, each O(dx). "
    "The waist's probe ux changes sign between the two spacings: the probe sits 0.25 mm from a curved free edge, "
    "where ux falls by about 0.18 mm per mm inwards at stretch 1.25, so a boundary placed to within a fraction of "
    "dx moves it by about 1 %. Runs: 1 rank, the fast "
    "route, 20 s (dogbone) and 40 s (waisted sheet) at dx = 0.5 mm, 190 s and 280 s at 0.25 mm, on a loaded "
    "2-core machine.",
    "",
]


if __name__ == "__main__":
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    out = []
    shaped(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "docs"), out)
    print("\n".join(out))
