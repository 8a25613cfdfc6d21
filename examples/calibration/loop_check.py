#!/usr/bin/python3
"""Closes the calibration loop: compares the static states of the
pure-shear run of a fitted material with the curve bapd-fit fitted (fit/curves.csv,
the incompressible homogeneous pure-shear response of that law at the fitted values).

    ./run_mpi.sh -n 2 examples/calibration/pure_shear_fitted.yaml \\
        -options_file_yaml examples/calibration/fit/material_gent.yaml -output_dir output/calibration_gent
    /usr/bin/python3 examples/calibration/loop_check.py output/calibration_gent \\
        --material examples/calibration/fit/material_gent.yaml [--tolerance 1]

The nominal stress of a static state is history.csv's top_nominal_stress_Pa (the top
grip's reaction over the specimen's width x thickness) at the static state's step. Prints the relative difference
at every static state and exits 1 if any exceeds the tolerance (percent; default 1).
"""
import argparse
import csv
import os
import sys


def read_yaml_values(path):
    """The scalar `key: value` lines of a flat YAML block (the material file)."""
    values = {}
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if ":" in line:
                key, value = (s.strip() for s in line.split(":", 1))
                if value:
                    values[key] = value
    return values


def fitted_curve(curves, law):
    """(stretch, nominal stress) of the law's pure-shear curve in bapd-fit's curves.csv."""
    points = [(float(r["stretch"]), float(r["nominal_stress_Pa"]))
              for r in csv.DictReader(open(curves)) if r["law"] == law and r["mode"] == "pure_shear"]
    if len(points) < 2:
        sys.exit(f"loop_check.py: error: {curves} has no pure_shear curve for {law}: fit that law first")
    return sorted(points)


def interpolate(points, x):
    """Cubic (Lagrange, four nearest samples) interpolation of the fitted curve: the
    samples are 0.02 apart, so the error is ~1e-8 relative, far below the check."""
    xs = [p[0] for p in points]
    if not xs[0] <= x <= xs[-1]:
        sys.exit(f"loop_check.py: error: stretch {x} is outside the fitted curve ({xs[0]} to {xs[-1]})")
    i = max(0, min(len(xs) - 4, next(k for k, v in enumerate(xs) if v >= x) - 2))
    total = 0.0
    for j in range(i, i + 4):
        w = 1.0
        for m in range(i, i + 4):
            if m != j:
                w *= (x - xs[m]) / (xs[j] - xs[m])
        total += w * points[j][1]
    return total


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="the run's -output_dir (holding static_states.csv and history.csv)")
    ap.add_argument("--material", default=os.path.join(here, "fit", "material_gent.yaml"))
    ap.add_argument("--curves", default=None, help="bapd-fit's curves.csv (default: next to --material)")
    ap.add_argument("--tolerance", type=float, default=1.0, help="percent")
    a = ap.parse_args()
    law = read_yaml_values(a.material).get("model")
    if not law:
        sys.exit(f"loop_check.py: error: {a.material}: no `model:` line (is it a material_<law>.yaml of bapd-fit?)")
    points = fitted_curve(a.curves or os.path.join(os.path.dirname(os.path.abspath(a.material)), "curves.csv"), law)
    try:
        rows = list(csv.DictReader(open(os.path.join(a.run, "static_states.csv"))))
        history = {r["step"]: r for r in csv.DictReader(open(os.path.join(a.run, "history.csv")))}
    except OSError as e:
        sys.exit(f"loop_check.py: error: {e.filename}: {e.strerror}; run the scene (with static holds) first")
    if not rows:
        sys.exit(f"loop_check.py: error: {a.run}/static_states.csv has no static state")
    worst = 0.0
    print(f"fitted {law} ({a.material}), run {a.run}")
    print("stretch  run_kPa  fit_kPa  difference")
    for r in rows:
        if r["step"] not in history:
            sys.exit(f"loop_check.py: error: {a.run}/history.csv has no row at step {r['step']} (a static state's)")
        lam, P = float(r["stretch"]), float(history[r["step"]]["top_nominal_stress_Pa"])
        fit = interpolate(points, lam)
        diff = 100 * (P / fit - 1)
        worst = max(worst, abs(diff))
        print(f"{lam:7.3f} {P / 1e3:8.3f} {fit / 1e3:8.3f} {diff:+9.2f} %")
    print(f"largest difference {worst:.2f} % (tolerance {a.tolerance:g} %)")
    sys.exit(0 if worst <= a.tolerance else 1)


if __name__ == "__main__":
    main()
