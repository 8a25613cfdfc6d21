#!/usr/bin/python3
"""The table of bench/run_all.sh: reads a results directory, prints every figure.

    report.py RESULTS_DIR [--plot PNG]

Writes RESULTS_DIR/summary.md (the same tables in Markdown, pasted into
docs/performance.md) and RESULTS_DIR/accuracy.png (error against FEA vs wall time;
--plot writes it elsewhere too). Every section is optional: what was not run is left
out.
"""
import argparse
import glob
import json
import math
import os
import re

FEA_MM = {1.5: 8.62, 1.75: 11.10, 2.0: 13.01}  # plate with a hole, u_max (docs/method.md 7.1)
FLOPS_PER_CYCLE = 16  # 2 FMA pipes x 4 doubles (AVX2, 256 bit) x 2 flops: Zen 2/3/4, Haswell and later


def kv(line):
    return {k: v for k, v in re.findall(r"(\w+)=(\S+)", line)}


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return x


class Table:
    """Rows printed as aligned text and as Markdown."""

    def __init__(self, title, header, note=""):
        self.title, self.header, self.rows, self.note = title, header, [], note

    def add(self, *cells):
        self.rows.append([c if isinstance(c, str) else fmt(c) for c in cells])

    def text(self):
        w = [max(len(str(r[k])) for r in [self.header] + self.rows) for k in range(len(self.header))]
        out = [self.title]
        out.append("  " + "  ".join(str(h).rjust(w[k]) for k, h in enumerate(self.header)))
        for r in self.rows:
            out.append("  " + "  ".join(str(c).rjust(w[k]) for k, c in enumerate(r)))
        if self.note:
            out.append("  " + self.note)
        return "\n".join(out)

    def markdown(self):
        out = [f"**{self.title}**", "", "| " + " | ".join(self.header) + " |",
               "|" + "|".join("---:" for _ in self.header) + "|"]
        out += ["| " + " | ".join(r) + " |" for r in self.rows]
        if self.note:
            out += ["", self.note]
        return "\n".join(out)


def fmt(x):
    if x is None:
        return "-"
    if isinstance(x, int):
        return f"{x:,}".replace(",", " ")
    if isinstance(x, float):
        if math.isnan(x):
            return "-"
        a = abs(x)
        if a >= 1000:
            return f"{x:,.0f}".replace(",", " ")
        if a >= 100:
            return f"{x:.0f}"
        if a >= 10:
            return f"{x:.1f}"
        if a >= 1:
            return f"{x:.2f}"
        return f"{x:.3g}"
    return str(x)


def machine(d):
    m = {}
    path = os.path.join(d, "machine.txt")
    if os.path.exists(path):
        for line in open(path):
            if line.startswith("RESULT"):
                m.update(kv(line))
            elif "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                m[k] = v
    return m


def kernel_results(d):
    res = {}
    for path in sorted(glob.glob(os.path.join(d, "kernel", "*.txt"))):
        for line in open(path):
            if line.startswith("RESULT"):
                r = {k: num(v) for k, v in kv(line).items()}
                res[(int(r["side"]), round(r["factor"], 3))] = r
    return res


def lammps_results(d):
    res = {}
    for path in sorted(glob.glob(os.path.join(d, "lammps", "*.log"))):
        text = open(path).read()
        meta = None
        for line in text.splitlines():
            if line.startswith("RESULT"):
                meta = {k: num(v) for k, v in kv(line).items()}
        loops = re.findall(r"^Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", text, re.M)
        cpu = re.findall(r"^([0-9.]+)% CPU use", text, re.M)
        pair = re.findall(r"^Pair\s+\|\s*([0-9.eE+-]+)\s*\|\s*([0-9.eE+-]+)", text, re.M)
        if not (meta and loops and pair):
            continue
        steps, atoms = int(loops[-1][1]), int(loops[-1][2])
        pair_wall = float(pair[-1][1])
        use = float(cpu[-1]) / 100 if cpu else 1.0
        bonds = meta["bonds3"]
        res[(int(meta["side"]), round(meta["factor"], 3))] = {
            "atoms": atoms, "bonds": bonds, "steps": steps, "bonds_per_point": bonds / atoms,
            "ns_wall": 1e9 * pair_wall / (steps * bonds), "ns_cpu": 1e9 * pair_wall * use / (steps * bonds),
            "cpu_use": use}
    return res


def callgrind_results(d):
    res = {}
    for path in glob.glob(os.path.join(d, "callgrind", "f*", "*.json")):
        f = round(float(os.path.basename(os.path.dirname(path))[1:]), 3)
        res.setdefault(f, {})[os.path.basename(path)[:-5]] = json.load(open(path))
    solver = os.path.join(d, "callgrind", "solver", "calls.json")
    solver0 = os.path.join(d, "callgrind", "solver0", "calls.json")
    calls = json.load(open(solver)) if os.path.exists(solver) else None
    if calls and os.path.exists(solver0):  # the time steps only: minus the setup's calls
        c0 = json.load(open(solver0))
        model, cbrt = calls["model_calls"] - c0["model_calls"], calls["cbrt_calls"] - c0["cbrt_calls"]
        kernel = calls["kernel_calls"] - c0["kernel_calls"]
        fallback = calls.get("lane_fallback_calls", 0) - c0.get("lane_fallback_calls", 0)
        if fallback > 0 or model < kernel:  # the four-bond lanes (since ea828f1): no cbrt per evaluation
            calls = {"kernel_calls": kernel, "lane_fallback_calls": fallback}
        else:
            calls = {"model_calls": model, "cbrt_calls": cbrt, "residual_evaluations_per_bond": cbrt / model}
    return res, calls


def runs(d, prefix):
    out = {}
    for path in glob.glob(os.path.join(d, "runs", prefix + "*.json")):
        r = json.load(open(path))
        out[r["label"]] = r
    return out


def step_time(r):
    """Seconds per time step inside TSStep (force, ghost exchange, TS updates)."""
    ev = r.get("events", {}).get("TSStep")
    if ev and ev["count"]:
        return ev["time_s"] / ev["count"]
    return None


def cpu_step_time(r):
    """CPU seconds per step of the slowest rank: its time-loop CPU time, scaled by the
    share of the time loop's wall time spent inside TSStep."""
    ev = r.get("events", {}).get("TSStep") if r else None
    cpu, wall = (r or {}).get("rank_stepping_cpu_s"), (r or {}).get("stepping_wall_s")
    if not (ev and ev["count"] and cpu and wall):
        return None
    return max(cpu) * min(1.0, ev["time_s"] / wall) / ev["count"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("--plot")
    a = ap.parse_args()
    d = a.results
    m = machine(d)
    tables = []
    ghz = float(m.get("clock_ghz", "nan"))
    peak = FLOPS_PER_CYCLE * ghz  # GFLOP/s per core
    head = (f"Machine: {m.get('cpu', '?')} (family {m.get('cpu_family', '?')} model {m.get('cpu_model', '?')}), "
            f"{m.get('cores', '?')} cores, {m.get('memory_gb', '?')} GB, {m.get('hypervisor', 'bare metal')} guest; "
            f"measured clock {ghz:.2f} GHz; peak {peak:.1f} GFLOP/s/core "
            f"({FLOPS_PER_CYCLE} flops/cycle = 2 FMA x 4 doubles x 2); load at start {m.get('load_at_start', '?')}; "
            f"{m.get('date', '?')}, git {m.get('git', '?')}, {m.get('compiler', '?')}")

    # 1. kernel
    ker, lmp = kernel_results(d), lammps_results(d)
    cg, solver_calls = callgrind_results(d)
    if ker:
        t = Table("1. Force kernel: bond evaluations per second per core (M/s; thread CPU time, min of reps)",
                  ["points", "delta/dx", "bonds/pt", "BA warm", "BA dynamics", "BA cold", "BA P=F", "BA force eval",
                   "EC force eval", "LAMMPS peri/lps", "LAMMPS bonds/pt", "BA/LAMMPS", "EC/LAMMPS", "flops/bond",
                   "GFLOP/s", "% peak"],
                  "BA warm/dynamics/cold: the kernel with c33 warm-started after a 1e-5 dx / 5e-4 dx move (1.0 / 1.75 "
                  "residual evaluations per bond; the solver does 1.71) or not at all (2.0). BA force eval = dynamics "
                  "kernel + assemble_force_density: what a time step costs per bond. LAMMPS = Pair time (all three "
                  "peri/lps loops) per directed bond on a simple cubic lattice with the same number of bonds, CPU-use "
                  "corrected. EC force eval = the energy-consistent kernel (warm) + assemble_force_density. BA/LAMMPS, "
                  "EC/LAMMPS = force eval / LAMMPS (per bond speed, > 1: faster than LAMMPS). flops/bond (callgrind, 100 x 100 points), GFLOP/s "
                  "and % peak: BA warm.")
        for (side, f), r in sorted(ker.items(), key=lambda kv: (kv[0][1], kv[0][0])):
            warm = 1e3 / r["gent_warm_ns"]
            dyn = 1e3 / r["gent_dynamics_ns"] if "gent_dynamics_ns" in r else None
            full = 1e3 / (r.get("gent_dynamics_ns", r["gent_warm_ns"]) + r["assemble_ns"] * r["bonds"] / r["evaluated"])
            assemble = r["assemble_ns"] * r["bonds"] / r["evaluated"]
            ec = 1e3 / (r["energy_warm_ns"] + assemble) if "energy_warm_ns" in r else None
            L = lmp.get((side, f))
            lm = 1e3 / L["ns_cpu"] if L else None
            flops = cg.get(f, {}).get("gent_warm", {}).get("flops_per_unit")
            gf = flops * warm / 1e3 if flops else None
            t.add(int(r["points"]), f"{f:.3f}", r["bonds_per_point"], warm, dyn, 1e3 / r["gent_cold_ns"],
                  1e3 / r["identity_ns"], full, ec, lm, L["bonds_per_point"] if L else None,
                  full / lm if lm else None, ec / lm if lm and ec else None, flops, gf, 100 * gf / peak if gf else None)
        tables.append(t)

    if cg:
        t = Table("1b. Where a bond's instructions go (callgrind, Gent warm kernel, per bond evaluation)",
                  ["delta/dx", "part", "instructions", "% instr", "flops", "div+sqrt"])
        for f in sorted(cg):
            g = cg[f].get("gent_warm")
            if not g:
                continue
            for part, v in g["parts"].items():
                if v["instructions"] < 0.5:
                    continue
                t.add(f"{f:.3f}", part, v["instructions"], 100 * v["instructions"] / g["instructions_per_unit"],
                      v["flops"], v["div_sqrt"])
            t.add(f"{f:.3f}", "TOTAL", g["instructions_per_unit"], 100.0, g["flops_per_unit"],
                  g["div_sqrt_per_unit"])
        tables.append(t)
        t = Table("1c. Per-bond cost by variant (callgrind counts; time = thread CPU, 1e5 points)",
                  ["delta/dx", "variant", "instructions", "flops", "div+sqrt", "cbrt", "ns (CPU)", "IPC"])
        for f in sorted(cg):
            r = ker.get((316, f)) or ker.get((100, f))
            times = {"gent_warm": "gent_warm_ns", "gent_cold": "gent_cold_ns", "identity": "identity_ns",
                     "model_warm": "model_ns", "assemble": "assemble_ns", "gent_dynamics": "gent_dynamics_ns"}
            for v in ("gent_warm", "gent_dynamics", "gent_cold", "identity", "model_warm", "assemble"):
                g = cg[f].get(v)
                if not g:
                    continue
                ns = r.get(times[v]) if r else None
                if v == "assemble" and ns and r:  # per bond evaluation, like the others
                    ns = ns * r["bonds"] / r["evaluated"]
                ipc = g["instructions_per_unit"] / (ns * ghz) if ns else None
                t.add(f"{f:.3f}", v, g["instructions_per_unit"], g["flops_per_unit"], g["div_sqrt_per_unit"],
                      g["cbrt_calls_per_unit"], ns, ipc)
        if solver_calls and "residual_evaluations_per_bond" in solver_calls:
            t.note = (f"Inside the solver (callgrind on bapd, default scene, 100 time steps minus a 0-step run, "
                      f"i.e. the power iteration of the setup removed): "
                      f"{solver_calls['residual_evaluations_per_bond']:.3f} residual evaluations (cbrt) per bond "
                      f"evaluation.")
        elif solver_calls:
            t.note = (f"Inside the solver (callgrind on bapd, default scene, 100 time steps minus a 0-step run): "
                      f"{solver_calls['lane_fallback_calls']} bonds left the four-bond lanes for the scalar solve "
                      f"in {solver_calls['kernel_calls']} force evaluations (docs/notes/performance-kernel-1.md 1a).")
        tables.append(t)

    # 2 + 4a: scaling and memory
    sc = runs(d, "scaling_")
    if sc:
        t = Table("2. Memory per point (bapd, plate with a hole, delta = 3.015 dx; RSS from /proc/PID/status)",
                  ["points", "ranks", "peak RSS MB", "stepping RSS MB", "peak B/point", "stepping B/point"])
        by = {}
        for label, r in sorted(sc.items(), key=lambda kv: (kv[1].get("points", 0), kv[1]["ranks"])):
            if r.get("points") is None:
                continue
            by[(r["points"], r["ranks"])] = r
            t.add(r["points"], r["ranks"], r["peak_rss_mb"], r["stepping_rss_mb"],
                  r["peak_rss_mb"] * 2**20 / r["points"], r["stepping_rss_mb"] * 2**20 / r["points"])
        for label, r in sorted(runs(d, "memory_").items()):  # variants (e.g. -checkpoint_on_error false)
            if r.get("points"):
                t.add(r["points"], f"{r['ranks']} ({label.split('_np')[-1].split('_', 1)[-1]})", r["peak_rss_mb"],
                      r["stepping_rss_mb"], r["peak_rss_mb"] * 2**20 / r["points"],
                      r["stepping_rss_mb"] * 2**20 / r["points"])
        ones = sorted((p, r) for (p, n), r in by.items() if n == 1)
        if len(ones) >= 2:
            (p0, r0), (p1, r1) = ones[0], ones[-1]
            marg_peak = (r1["peak_rss_mb"] - r0["peak_rss_mb"]) * 2**20 / (p1 - p0)
            marg_step = (r1["stepping_rss_mb"] - r0["stepping_rss_mb"]) * 2**20 / (p1 - p0)
            t.note = (f"Marginal cost per point between {p0} and {p1} points (1 rank): {marg_peak:.0f} B peak, "
                      f"{marg_step:.0f} B while stepping (the fixed ~{r0['stepping_rss_mb'] - marg_step * p0 / 2**20:.0f} "
                      f"MB of MPI/PETSc libraries removed).")
        tables.append(t)
        t = Table("4a. Strong scaling (time per step inside TSStep; speedup = 1 rank / N ranks)",
                  ["points", "ranks", "wall s/step", "speedup", "CPU s/step", "CPU speedup", "util.",
                   "M bond evals/s/core"])
        for (p, n), r in sorted(by.items()):
            s = step_time(r)
            base = step_time(by[(p, 1)]) if (p, 1) in by else None
            sp = base / s if (s and base) else None
            c, cb = cpu_step_time(r), cpu_step_time(by.get((p, 1), {}))
            rate = r["bonds"] / (c or s) / n / 1e6 if (c or s) else None
            t.add(p, n, s, sp, c, cb / c if (c and cb) else None, r["cpu_utilisation"], rate)
        t.note = ("wall s/step: TSStep event of -log_view. CPU s/step: the slowest rank's CPU time in the time loop "
                  "times the TSStep share of the loop's wall time (what a step costs on an idle core; for N ranks it "
                  "includes MPI's busy waiting while the partner rank is descheduled). util. = CPU / (wall x ranks) "
                  "of the whole run: below 1 means the ranks shared the cores with other work.")
        tables.append(t)

    # 3. scenes
    sn = runs(d, "scene_")
    acc = runs(d, "accuracy_")
    if sn:
        t = Table("3. Time to solution of the paper scenes (extrapolated from runs of 0 and N steps)",
                  ["scene", "ranks", "points", "steps", "setup s", "s/step", "total s", "wall total s", "util.",
                   "Setup%", "Partition%", "Force%", "Ghost%", "Time step%", "Output%"],
                  "total = T(0 steps) + steps x (T(N) - T(0)) / N with T = CPU time of the busiest rank: for 1 rank "
                  "what the run takes on an idle core, for N ranks an upper bound of it (MPI's busy waiting while "
                  "the partner is descheduled counts). wall total: the same from wall times, whatever the machine's "
                  "load allowed (util. = CPU / (wall x ranks) of the N-step run). Stage shares: -log_view stages "
                  "(wall) extrapolated the same way. plate_hole steps: the measured full run (static holds end "
                  "early) if present, else the schedule's upper bound.")
        scenes = sorted({re.match(r"scene_(.+)_np\d+_s\d+", k).group(1) for k in sn})
        for scene in scenes:
            for n in sorted({v["ranks"] for k, v in sn.items() if k.startswith(f"scene_{scene}_np")}):
                zero = sn.get(f"scene_{scene}_np{n}_s0")
                long = [v for k, v in sn.items() if k.startswith(f"scene_{scene}_np{n}_s") and not k.endswith("_s0")]
                if not zero or not long or "steps" not in long[0]:
                    continue
                L = long[0]
                N = L["steps"]
                full = zero.get("schedule_steps")
                if scene == "plate_hole":
                    ref = [v for k, v in acc.items() if k == "accuracy_dx0.001_f3.015" and v.get("steps")]
                    if ref:
                        full = ref[0]["steps"]
                per_w = (L["wall_s"] - zero["wall_s"]) / N
                total_w = zero["wall_s"] + per_w * full
                if zero.get("rank_cpu_s") and L.get("rank_cpu_s"):
                    # the busiest rank's CPU time: for 1 rank what the run takes on an idle
                    # core; for N ranks an upper bound of it (MPI's busy waiting counts)
                    t0, per = max(zero["rank_cpu_s"]), (max(L["rank_cpu_s"]) - max(zero["rank_cpu_s"])) / N
                else:
                    t0, per = zero["wall_s"], per_w
                total = t0 + per * full
                st0, stN = zero.get("stages", {}), L.get("stages", {})
                names = ["Setup", "Partition", "Force", "Ghost exchange", "Time step", "Output"]
                # Setup and Partition happen once: taken from the N-step run; the others
                # grow with the steps (Force also holds the setup's power iteration).
                ext = {k: (stN.get(k, 0) if k in ("Setup", "Partition")
                           else st0.get(k, 0) + max(0.0, stN.get(k, 0) - st0.get(k, 0)) * full / N) for k in names}
                ssum = sum(ext.values()) or 1
                t.add(scene, n, zero.get("points"), full, t0, per, total, total_w, L.get("cpu_utilisation"),
                      *[100 * ext[k] / ssum for k in names])
        tables.append(t)

    # 4b. partition
    parts = []
    for path in sorted(glob.glob(os.path.join(d, "partition", "*.txt"))):
        graph = None
        for line in open(path):
            if line.startswith("RESULT kind=graph"):
                graph = {k: num(v) for k, v in kv(line).items()}
            elif line.startswith("RESULT kind=parts"):
                parts.append(({k: num(v) for k, v in kv(line).items()}, graph))
    if parts:
        t = Table("4b. Partition only: METIS k-way on the bond graph, two rings of ghosts (as the solver)",
                  ["points", "parts", "edge cut", "cut/edges %", "ghosts/owned", "max ghosts/owned", "imbalance",
                   "redundant %", "speedup bound", "halo MB/step", "METIS s", "peak RSS MB"])
        for r, g in sorted(parts, key=lambda x: (x[0]["points"], x[0]["parts"])):
            t.add(int(r["points"]), int(r["parts"]), int(r["edge_cut"]), 100 * r["cut_fraction"], r["ghost_ratio"],
                  r["max_ghost_ratio"], r["imbalance"], 100 * r.get("redundant_bonds", float("nan")),
                  r.get("speedup_bound"), r["halo_mb"], r["metis_s"], r["hwm_mb"])
        graphs = {int(g["points"]): g for _, g in parts if g}
        t.note = "; ".join(f"{p} points: graph built in {g['build_s']:.1f} s, {g['families_bytes_per_point']:.0f} B/point "
                           f"in Families, peak {g['families_hwm_mb']:.0f} MB after build_families"
                           for p, g in sorted(graphs.items()))
        tables.append(t)

    # 5. accuracy
    if acc:
        t = Table("5. Plate with a hole: u_max error against FEA vs cost",
                  ["dx mm", "delta/dx", "points", "ranks", "wall s", "CPU s", "err 1.5 %", "err 1.75 %", "err 2.0 %",
                   "max |err| %"],
                  "FEA u_max: 8.62, 11.10, 13.01 mm at stretch 1.5, 1.75, 2.0; u_max = ux of the left_mid probe at "
                  "the static state of each hold (static_states.csv).")
        pts = []
        for label, r in acc.items():
            mm = re.match(r"accuracy_dx([0-9.]+)_f([0-9.]+)", label)
            dx, f = float(mm.group(1)) * 1e3, float(mm.group(2))
            errs = {}
            for row in r.get("static_states", []):
                lam = round(row["stretch"], 2)
                if lam in FEA_MM:
                    errs[lam] = 100 * (abs(row["left_mid_ux_m"]) * 1e3 - FEA_MM[lam]) / FEA_MM[lam]
            worst = max((abs(e) for e in errs.values()), default=None) if len(errs) == 3 else None
            pts.append((dx, f, r, errs, worst))
        for dx, f, r, errs, worst in sorted(pts, key=lambda p: (-p[0], p[1])):
            t.add(dx, f"{f:.3f}", r.get("points"), r["ranks"], r["wall_s"], r["cpu_s"], errs.get(1.5), errs.get(1.75),
                  errs.get(2.0), worst)
        def cost(p):  # one rank: the CPU time of the run (an idle core); more ranks: wall
            return p[2]["cpu_s"] if p[2]["ranks"] == 1 else p[2]["wall_s"]

        lines = []
        for target in (1, 3, 10):
            ok = [p for p in pts if p[4] is not None and p[4] <= target]
            if ok:
                best = min(ok, key=cost)
                lines.append(f"{target} %: dx = {best[0]:g} mm, delta = {best[1]:.3f} dx, {cost(best):.0f} s "
                             f"({'CPU, 1 core' if best[2]['ranks'] == 1 else 'wall, %d ranks' % best[2]['ranks']})")
                continue
            # Extrapolate: error = C dx^p from the two finest dx of each delta; cost ~ dx^-3
            # (points ~ dx^-2, steps ~ dx^-1).
            guesses = []
            for f in sorted({p[1] for p in pts}):
                runs_f = sorted([p for p in pts if p[1] == f and p[4]], key=lambda p: p[0])
                if len(runs_f) < 2:
                    continue
                (d1, _, _, _, e1), (d2, _, _, _, e2) = runs_f[0], runs_f[1]
                order = math.log(e2 / e1) / math.log(d2 / d1)
                if order <= 0:
                    continue
                dx = d1 * (target / e1) ** (1 / order)
                guesses.append((cost(runs_f[0]) * (d1 / dx) ** 3, dx, f, order))
            if guesses:
                c, dx, f, order = min(guesses)
                lines.append(f"{target} %: not reached; extrapolated (error ~ dx^{order:.1f}) dx = {dx:.2g} mm at "
                             f"delta = {f:.3f} dx, ~{c:.0f} s")
            else:
                lines.append(f"{target} %: not reached by any run here")
        t.note += " Cheapest run within: " + "; ".join(lines) + "."
        tables.append(t)
        plot_accuracy(pts, [os.path.join(d, "accuracy.png")] + ([a.plot] if a.plot else []))

    text = [head, ""] + [tb.text() + "\n" for tb in tables]
    print("\n".join(text))
    with open(os.path.join(d, "summary.md"), "w") as f:
        f.write(head + "\n\n" + "\n\n".join(tb.markdown() for tb in tables) + "\n")


def run_cost(r):
    return r["cpu_s"] if r["ranks"] == 1 else r["wall_s"]


def plot_accuracy(pts, paths):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    markers = {2.515: "v", 3.015: "o", 3.515: "s"}
    colors = {1.5: "C0", 1.75: "C1", 2.0: "C2"}
    for dx, f, r, errs, worst in pts:
        for lam, e in errs.items():
            ax.scatter(run_cost(r), abs(e), marker=markers.get(f, "x"), color=colors[lam], s=40)
        ax.annotate(f"{dx:g} mm", (run_cost(r), max(abs(e) for e in errs.values()) if errs else 1),
                    textcoords="offset points", xytext=(4, 4), fontsize=8)
    for lam, c in colors.items():
        ax.scatter([], [], color=c, label=f"stretch {lam}")
    for f, mk in markers.items():
        ax.scatter([], [], color="gray", marker=mk, label=f"delta = {f} dx")
    for target in (1, 3, 10):
        ax.axhline(target, color="gray", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost of the whole run (s; CPU time on one core for 1-rank runs)")
    ax.set_ylabel("|u_max error| against FEA (%)")
    ax.set_title("Plate with a hole: accuracy vs cost")
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    for p in paths:
        fig.savefig(p, dpi=120)


if __name__ == "__main__":
    main()
