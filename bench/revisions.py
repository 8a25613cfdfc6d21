#!/usr/bin/python3
"""The table of bench/compare_revisions.sh: time to solution, old revision against new.

    revisions.py RUNS_DIR --scenes plate,pure_shear,notched --repeats N --old A --new B [--threshold 1.10]

Reads RUNS_DIR/SCENE_{old,new}_R.json (bench/bapd_run.py) and prints, per scene and
revision: the best and the spread of the CPU time over the repeats ((max - min) / min),
the wall time of the best run, steps, ghost exchanges of the displacement (-log_view's
VecScatterBegin count: one per evaluation of the force operator, dynamics, output and
stable-step estimates, plus one a step with failure on, where the breaking pass
updates the positions), and CPU time per step per point. The
ratio is new / old of the best CPU times; above --threshold the scene is flagged
SLOWER and the exit status is 1. "identical" says whether history.csv of the first
repeats are the same byte for byte (different steps or bonds broken: "differs").
"""
import argparse
import filecmp
import json
import os
import sys


def load(runs, scene, side, repeats):
    out = []
    for r in range(1, repeats + 1):
        path = os.path.join(runs, f"{scene}_{side}_{r}.json")
        if os.path.exists(path):
            out.append(json.load(open(path)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs")
    ap.add_argument("--scenes", default="plate,pure_shear,notched")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--threshold", type=float, default=1.10)
    ap.add_argument("--old", default="old")
    ap.add_argument("--new", default="new")
    a = ap.parse_args()
    print(f"old = {a.old}, new = {a.new}; CPU time = user + system of the run, best of {a.repeats} "
          f"(spread = (max - min) / min)\n")
    print("| scene | rev | points | steps | ghost exchanges | CPU s (best) | spread | wall s | CPU us/step/point | "
          "new/old CPU | history.csv |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    slower = []
    for scene in a.scenes.split(","):
        best = {}
        for side in ("old", "new"):
            rs = [r for r in load(a.runs, scene, side, a.repeats) if r.get("returncode") == 0]
            if not rs:
                print(f"| {scene} | {side} | failed or missing | | | | | | | | |")
                continue
            cpus = [r["cpu_s"] for r in rs]
            b = min(rs, key=lambda r: r["cpu_s"])
            best[side] = b
            steps, points = b.get("steps", 0), b.get("points", 0)
            evals = b.get("events", {}).get("VecScatterBegin", {}).get("count", 0)
            per = 1e6 * b["cpu_s"] / (steps * points) if steps and points else float("nan")
            spread = (max(cpus) - min(cpus)) / min(cpus) if len(cpus) > 1 else 0.0
            ratio, same = "", ""
            if side == "new" and "old" in best:
                q = b["cpu_s"] / best["old"]["cpu_s"]
                flag = " **SLOWER**" if q > a.threshold else ""
                if flag:
                    slower.append(scene)
                ratio = f"{q:.3f}{flag}"
                h_old = os.path.join(a.runs, f"o_{scene}_old_1", "history.csv")
                h_new = os.path.join(a.runs, f"o_{scene}_new_1", "history.csv")
                if os.path.exists(h_old) and os.path.exists(h_new):
                    same = "identical" if filecmp.cmp(h_old, h_new, shallow=False) else "differs"
            print(f"| {scene} | {side} | {points} | {steps} | {evals} | {b['cpu_s']:.2f} | {100 * spread:.1f} % | "
                  f"{b['wall_s']:.2f} | {per:.3f} | {ratio} | {same} |")
    if slower:
        print(f"\nSLOWER by more than {100 * (a.threshold - 1):.0f} %: {', '.join(slower)}")
        sys.exit(1)
    print(f"\nno scene more than {100 * (a.threshold - 1):.0f} % slower")


if __name__ == "__main__":
    main()
