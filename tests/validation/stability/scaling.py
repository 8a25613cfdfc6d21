#!/usr/bin/env python3
"""Scaling: the same scene with every length times s_L and every modulus
times s_mu gives the same dimensionless answer. Time scales with L sqrt(rho / mu), so
the schedule times are multiplied by s_L / sqrt(s_mu) and the damping divided by it.
Compares, row by row, every column of history.csv made dimensionless (u / L,
stress / mu, force / (mu L^2), energy / (mu L^3), t / T), and the stable time step
and step count of the log. No absolute tolerance in the solver may show: the
results agree to round-off.

    scaling.py            (BAPD_EXE: the program; ctest sets it)
"""
import csv
import math
import os
import re
import shutil
import subprocess
import sys

EXE = os.environ["BAPD_EXE"]
WORK = "stability_scaling"
# A plate with a hole (scene 1 in miniature): 8 x 16 points, dx = 1 mm, pulled to
# stretch 1.5 and held until static (the hold ends on a relative energy test).
LENGTHS = {"body_width": [0.008], "body_height": [0.016], "body_thickness": [0.001], "body_dx": [0.001],
           "body_holes": [0.004, 0.008, 0.002], "probe_left_mid_at": [0.0, 0.008]}
TIMES = {"load_schedule": [0, 1.0, 0.05, 1.5, 0.3, 1.5]}  # (t, lambda): the times scale
FIXED = ["-horizon_factor", "3.015", "-material_Jm", "162.6", "-material_bulk_ratio", "1000", "-material_density", "1000",
         "-load_sets", "top,bottom", "-load_top_region", "top", "-load_top_x", "fixed", "-load_top_y", "stretch",
         "-load_top_y_scale", "0.5", "-load_bottom_region", "bottom", "-load_bottom_x", "fixed", "-load_bottom_y",
         "stretch", "-load_bottom_y_scale", "-0.5", "-probes", "left_mid", "-static_tolerance", "1e-6",
         "-output_interval", "10", "-progress_interval", "1000000"]
MU, DAMPING = 4.55e3, 100.0
# (name, length factor, modulus factor)
CASES = [("length_x1000", 1e3, 1.0), ("modulus_x1000", 1.0, 1e3), ("both_x0.001", 1e-3, 1e-3)]
# The stable step is estimated by power iteration on K v = -(f(eps v) - f(0)) / eps with
# eps = 1e-7 dx: a forward difference whose round-off is ~1e-16 / 1e-7 = 1e-9 of the
# result, in bits that differ from one scale to another. The chosen step (and so every
# time and displacement of the history, energies twice as much) can differ by that
# much, no more: steps and static holds must still be identical.
TOLERANCE_STEP = 2e-8
TOLERANCE_COMPUTED_STEP = 1e-7
# With the scaled time step given (-time_step), only round-off remains: ~1e-16 a
# step, grown over ~320 damped steps (measured 1e-14).
TOLERANCE_GIVEN_STEP = 1e-12


def fmt(values):
    return ",".join(repr(float(v)) for v in values)


def run(name, s_l, s_mu, time_step=None):
    s_t = s_l / math.sqrt(s_mu)
    args = [EXE] + FIXED + (["-time_step", repr(time_step * s_t)] if time_step else []) + ["-material_mu", repr(MU * s_mu), "-damping", repr(DAMPING / s_t), "-output_dir", f"{WORK}/{name}"]
    for key, values in LENGTHS.items():
        args += [f"-{key}", fmt(v * s_l for v in values)]
    for key, values in TIMES.items():
        args += [f"-{key}", fmt(v * s_t if k % 2 == 0 else v for k, v in enumerate(values))]
    mpiexec = os.environ.get("MPIEXEC", "mpiexec")
    result = subprocess.run([mpiexec, "-n", "1", "--oversubscribe", "--bind-to", "none"] + args, capture_output=True, text=True)
    log = result.stdout + result.stderr
    with open(f"{WORK}/{name}.log", "w") as f:
        f.write(log)
    if result.returncode != 0:
        print(log)
        sys.exit(f"FAIL {name}: exit code {result.returncode}")
    steps = int(re.search(r"Finished: (\d+) steps", log).group(1))
    static = re.findall(r"Static at stretch \S+: t = \S+ s, step (\d+)", log)
    with open(f"{WORK}/{name}/history.csv") as f:
        rows = list(csv.reader(f))
    history = [[float(v) for v in r] for r in rows[1:]]
    dt = history[1][1] / history[1][0]  # time_s / step of the first row after step 0 (the log prints 5 digits)
    return {"stable": dt / s_t, "steps": steps, "static": static, "header": rows[0],
            "rows": history, "s_l": s_l, "s_mu": s_mu, "s_t": s_t}


UNITS = ("_s", "_m", "_Pa", "_N", "_J")


def unit(column):
    return next((u for u in UNITS if column.endswith(u)), "")


def dimensionless(column, value, r):
    s_l, s_mu, s_t = r["s_l"], r["s_mu"], r["s_t"]
    scale = {"_s": s_t, "_m": s_l, "_Pa": s_mu, "_N": s_mu * s_l**2, "_J": s_mu * s_l**3, "": 1.0}[unit(column)]
    return value / scale  # step, stretch and broken_bonds are dimensionless already


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    ref = run("base", 1.0, 1.0)
    runs = [(name, run(name, s_l, s_mu), TOLERANCE_COMPUTED_STEP) for name, s_l, s_mu in CASES]
    runs += [(name + "_given_step", run(name + "_given_step", s_l, s_mu, ref["stable"]), TOLERANCE_GIVEN_STEP)
             for name, s_l, s_mu in CASES]
    failed = False
    for name, r, tolerance in runs:
        problems = []
        if r["steps"] != ref["steps"]:
            problems.append(f"{r['steps']} steps, base {ref['steps']}")
        if r["static"] != ref["static"]:
            problems.append(f"static holds ended at steps {r['static']}, base {ref['static']}")
        d_stable = abs(r["stable"] - ref["stable"]) / ref["stable"]
        if d_stable > TOLERANCE_STEP:
            problems.append(f"time step / T differs by {d_stable:.2e}")
        worst = (0.0, "", 0)
        if r["header"] != ref["header"] or len(r["rows"]) != len(ref["rows"]):
            problems.append(f"history.csv has another shape ({len(r['rows'])} rows, base {len(ref['rows'])})")
        else:
            # Differences relative to the largest value of the same kind (a reaction x that
            # is zero by symmetry is compared with the reactions, not with its own noise).
            largest = {}
            for c, column in enumerate(ref["header"]):
                top = max(abs(dimensionless(column, row[c], ref)) for row in ref["rows"])
                largest[unit(column) or column] = max(largest.get(unit(column) or column, 1e-300), top)
            for c, column in enumerate(ref["header"]):
                a = [dimensionless(column, row[c], ref) for row in ref["rows"]]
                b = [dimensionless(column, row[c], r) for row in r["rows"]]
                scale = largest[unit(column) or column]
                for k, (x, y) in enumerate(zip(a, b)):
                    if abs(x - y) / scale > worst[0]:
                        worst = (abs(x - y) / scale, column, k)
            if worst[0] > tolerance:
                problems.append(f"history differs by {worst[0]:.2e} of the largest value of its kind ({worst[1]}, row {worst[2]})")
        status = "FAIL" if problems else "ok  "
        print(f"{status} {name}: {r['steps']} steps, time step / T equal to {d_stable:.1e}, history equal to "
              f"{worst[0]:.1e} ({worst[1] or '-'}), static holds at steps {r['static']}" + ("; " + "; ".join(problems) if problems else ""))
        failed |= bool(problems)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
