#!/usr/bin/python3
"""Tables of docs/stability.md and docs/notes/stability-runs.md from the runs of run_all.sh.

Usage: report.py OUTPUT_DIR DOC

Rewrites, in DOC, the text between each `<!-- table:NAME -->` line and the next
`<!-- end -->` line with the table NAME built from OUTPUT_DIR (a table whose runs are
missing is left as it is). Every number of a table comes from a log, history.csv,
static_states.csv or spectrum.csv of OUTPUT_DIR.
"""
import csv
import math
import os
import re
import subprocess
import sys

import numpy as np
from scipy.optimize import brentq

HERE = os.path.dirname(os.path.abspath(__file__))
MU, JM = 4.55e3, 162.6
FEA_1_5 = 8.62  # mm, u_max of scene 1 at stretch 1.5 (docs/method.md section 7.1)


# ---------------------------------------------------------------- reading runs
def read_csv(path):
    with open(path) as f:
        return [{k: (float(v) if _number(v) else v) for k, v in r.items()} for r in csv.DictReader(f)]


def _number(v):
    try:
        float(v)
        return True
    except ValueError:
        return False


class Run:
    """What a run left in OUTPUT_DIR/NAME and OUTPUT_DIR/NAME.log."""

    def __init__(self, root, name):
        self.name = name
        self.dir = os.path.join(root, name)
        self.ok = os.path.exists(os.path.join(self.dir, "done"))
        if not self.ok:
            return
        with open(os.path.join(self.dir, "done")) as f:
            rc, wall = f.read().split()
        self.rc, self.wall = int(rc), float(wall)
        with open(os.path.join(root, name + ".log"), errors="replace") as f:
            self.log = f.read()
        self.stable = self._float(r"Stable time step (\S+) s")
        self.dt = self._float(r"using dt = (\S+) s")
        m = re.search(r"^(Finished|Stopped)[^:]*: (\d+) steps, t = (\S+) s, stretch (\S+), wall", self.log, re.M)
        self.steps = int(m.group(2)) if m else None
        self.final_stretch = float(m.group(4)) if m else None
        m = re.search(r"^bapd: error: (.*)$", self.log, re.M)
        self.error = m.group(1) if m else ""
        m = re.search(r" at step (\d+) ", self.error)
        self.stop_step = int(m.group(1)) if m else None
        m = re.search(r"Bonds with a singular shape tensor \(carry no force\): (\d+)", self.log)
        self.singular = int(m.group(1)) if m else 0
        m = re.search(r"^broken bonds: (\d+)", self.log, re.M)
        self.broken = int(m.group(1)) if m else None
        self.static = {}
        for lam, ux in re.findall(r"^Static at stretch (\S+):.*left_mid ux = (\S+) m", self.log, re.M):
            self.static[round(float(lam), 3)] = abs(float(ux)) * 1e3
        path = os.path.join(self.dir, "history.csv")
        self.history = read_csv(path) if os.path.exists(path) else []

    def u_max(self):
        """u_max at stretch 1.5 (mm): the static state, else the last history row at 1.5
        marked with a star (the hold ended before the static test passed)."""
        if 1.5 in self.static:
            return fmt(self.static[1.5], 4)
        if self.rc == 0 and self.history and abs(self.history[-1]["stretch"] - 1.5) < 1e-9:
            return fmt(abs(self.history[-1]["left_mid_ux_m"]) * 1e3, 4) + "*"
        return "-"

    def _float(self, pattern):
        m = re.search(pattern, self.log)
        return float(m.group(1)) if m else None

    def outcome(self):
        """One short phrase: how the run ended."""
        if self.rc == 0:
            return "ran to the end"
        e = self.error
        where = re.search(r"reference position \(([^)]*)\) m", e)
        at = f" at ({_mm(where.group(1))}) mm" if where else ""
        step = f" at step {self.stop_step}" if self.stop_step is not None else ""
        if "inverted" in e:
            n = re.match(r"(\d+) bond", e)
            return f"{n.group(1) if n else ''} bond(s) inverted{step}{at}".strip()
        if "diverged" in e:
            return f"runaway energy{step}" + (f", fastest point{at}" if at else "")
        if "NaN" in e:
            return f"NaN/Inf{step}"
        if "chain-extension" in e:
            return f"Gent chain limit{step}"
        return e[:80] or f"exit code {self.rc}"


def _mm(pair):
    return ", ".join(f"{float(v) * 1e3:g}" for v in pair.split(","))


def runs(root, names):
    out = [Run(root, n) for n in names]
    return [r for r in out if r.ok]


def fmt(v, digits=3):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-" if v is None else ("inf" if v > 0 else "-inf")
    return f"{v:.{digits}g}"


def table(header, rows):
    """A markdown table, or None without rows (main() then leaves the doc's table as it
    is: run on the map alone, the other sections' tables must not be blanked)."""
    if not rows:
        return None
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


# ---------------------------------------------------------------- references
def gent_psi(l1, l2, l3, k_ratio):
    D = 2.0 / (k_ratio * MU)
    J = l1 * l2 * l3
    i1 = (l1 * l1 + l2 * l2 + l3 * l3) * J ** (-2.0 / 3.0)
    if i1 - 3 >= JM or J <= 0:
        return math.inf
    return -(MU * JM / 2) * math.log(1 - (i1 - 3) / JM) + (1 / D) * ((J * J - 1) / 2 - math.log(J))


def pure_shear_compressible(lam, k_ratio=1000.0):
    """Nominal stress of homogeneous compressible Gent pure shear (lambda_x = 1), plane
    stress (lambda_3 minimises the energy: S33 = 0)."""
    h = 1e-7
    grid = np.logspace(-3, 0.3, 800)
    vals = [gent_psi(1, lam, g, k_ratio) for g in grid]
    k = int(np.argmin(vals))
    ds = lambda l3: (gent_psi(1, lam, l3 * (1 + h), k_ratio) - gent_psi(1, lam, l3 * (1 - h), k_ratio)) / (2 * h * l3)
    l3 = brentq(ds, grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)], xtol=1e-15)
    return (gent_psi(1, lam * (1 + h), l3, k_ratio) - gent_psi(1, lam * (1 - h), l3, k_ratio)) / (2 * h * lam)


def eq36(lam):
    """Paper eq 36, incompressible pure shear."""
    g = JM - lam * lam - lam ** -2 + 2
    return MU * JM * (lam - lam ** -3) / g if g > 0 else math.inf


def stress_at(run, lam):
    """The top grip's nominal stress at stretch lam (linear between history rows)."""
    h = run.history
    for a, b in zip(h, h[1:]):
        if a["stretch"] <= lam <= b["stretch"] and b["stretch"] > a["stretch"]:
            w = (lam - a["stretch"]) / (b["stretch"] - a["stretch"])
            return (1 - w) * a["top_nominal_stress_Pa"] + w * b["top_nominal_stress_Pa"]
    return None


# ---------------------------------------------------------------- tables
def t_shear_reference():
    rows = []
    for lam in (2, 3, 5.125, 8, 9.5, 10, 12, 12.7, 13):
        s = pure_shear_compressible(lam)
        e = eq36(lam)
        rows.append([f"{lam:g}", f"{e / 1e3:.1f}" if math.isfinite(e) else "no energy", f"{s / 1e3:.1f}",
                     f"{s / e:.3f}" if math.isfinite(e) else "-"])
    return table(["stretch", "eq 36, incompressible (kPa)", "compressible K = 1000 mu, plane stress (kPa)", "ratio"], rows)


SHEAR_AT = (2, 3, 5.125, 8, 9.5, 12)


def t_shear(root):
    names = [f"shear_bond_only_c{c}" for c in (0, 50, 100, 150, 200, 300)]
    names += [f"shear_bond_only_c200_s{s}" for s in (0.4, 0.2, 0.1)]
    names += [f"shear_energy_consistent_c{c}" for c in (0, 50, 200)]
    names += [f"shear_energy_consistent_c200_s{s}" for s in (0.4, 0.2, 0.1)]
    refs = {lam: pure_shear_compressible(lam) for lam in SHEAR_AT}
    rows = []
    for r in runs(root, names):
        m = re.match(r"shear_(bond_only|energy_consistent)_c(\d+)(?:_s(\S+))?", r.name)
        form, c, safety = m.group(1), m.group(2), m.group(3) or "0.8"
        cells = []
        for lam in SHEAR_AT:
            s = stress_at(r, lam)
            cells.append(f"{s / refs[lam]:.3f}" if s is not None else "-")
        rows.append([form.replace("_", "-"), c, safety, fmt(r.dt), f"{r.final_stretch:.2f}" if r.final_stretch else "-",
                     r.steps, f"{r.wall:.0f}"] + cells + [r.outcome()])
    return table(["force form", "damping (1/s)", "safety", "dt (s)", "stretch reached", "steps", "wall (s)"] +
                 [f"s / s_ref at {lam:g}" for lam in SHEAR_AT] + ["outcome"], rows)


def spectrum_rows(root, name):
    path = os.path.join(root, name, "spectrum.csv")
    return read_csv(path) if os.path.exists(path) else []


def t_spectrum_shear(root):
    bo = {round(r["stretch"], 1): r for r in spectrum_rows(root, "spectrum_shear_bond_only")}
    ec = {round(r["stretch"], 1): r for r in spectrum_rows(root, "spectrum_shear_energy_consistent")}
    if not bo and not ec:
        return None
    rows = []
    for lam in sorted(set(bo) | set(ec)):
        b, e = bo.get(lam), ec.get(lam)
        rows.append([f"{lam:g}",
                     fmt(b["abs_lambda_max_1_s2"]) if b else "-", fmt(b["stable_dt_s"] * 1e3) if b else "-",
                     fmt(b["growth_rate_1_s"]) if b else "-", fmt(b["critical_damping_1_s"]) if b else "-",
                     f"({b['mode_x_m'] * 1e3:g}, {b['mode_y_m'] * 1e3:g})" if b else "-",
                     fmt(e["abs_lambda_max_1_s2"]) if e else "-", fmt(e["stable_dt_s"] * 1e3) if e else "-",
                     fmt(e["asymmetry"], 2) if e else "-"])
    return table(["stretch", "bond-only lambda_max (1/s^2)", "bond-only stable step (ms)", "bond-only growth (1/s)",
                  "bond-only damping needed (1/s)", "mode at (mm)", "energy-consistent lambda_max (1/s^2)",
                  "energy-consistent stable step (ms)", "energy-consistent asymmetry"], rows)


def t_spectrum_broken(root):
    data = spectrum_rows(root, "spectrum_broken")
    if not data:
        return None
    by = {}
    for r in data:
        by.setdefault(round(r["broken_fraction"], 2), {})[r["force_form"]] = r
    base = {f: by[min(by)][f]["abs_lambda_max_1_s2"] for f in ("bond_only", "energy_consistent")}
    rows = []
    for frac in sorted(by):
        b, e = by[frac]["bond_only"], by[frac]["energy_consistent"]
        neg = b["min_re_lambda_1_s2"] < -1e-8 * b["abs_lambda_max_1_s2"]
        rows.append([f"{100 * frac:.0f} %", int(b["singular_bonds"]), f"{b['abs_lambda_max_1_s2'] / base['bond_only']:.2f}",
                     fmt(b["growth_rate_1_s"]), "none works (real negative eigenvalue)" if neg else fmt(b["critical_damping_1_s"]),
                     fmt(b["asymmetry"], 2), f"{e['abs_lambda_max_1_s2'] / base['energy_consistent']:.2f}",
                     fmt(e["stable_dt_s"] * 1e3), fmt(e["asymmetry"], 2)])
    return table(["bonds broken", "directed bonds with singular K", "bond-only lambda_max / intact",
                  "bond-only growth (1/s)", "bond-only damping needed (1/s)", "bond-only asymmetry",
                  "energy-consistent lambda_max / intact", "energy-consistent stable step (ms)",
                  "energy-consistent asymmetry"], rows)


def t_spectrum_plate(root):
    rows = []
    names = [f"spectrum_plate_h{h}_{f}" for h in (1.5, 2, 3.015) for f in ("bond_only", "energy_consistent")]
    names += ["spectrum_plate_plane_strain_k100", "spectrum_plate_plane_strain_k1000"]
    for name in names:
        for r in spectrum_rows(root, name):
            neg = r["min_re_lambda_1_s2"] < -1e-8 * r["abs_lambda_max_1_s2"]
            label = name.replace("spectrum_plate_", "").replace("_", " ").replace("bond only", "bond-only").replace(
                "energy consistent", "energy-consistent").replace("plane strain k1000", "plane strain, K = 1000 mu").replace(
                "plane strain k100", "plane strain, K = 100 mu")
            rows.append([label, f"{r['stretch']:.3g}", fmt(r["abs_lambda_max_1_s2"]), fmt(r["stable_dt_s"] * 1e3),
                         fmt(r["solver_rest_stable_dt_s"] * 1e3), fmt(r["growth_rate_1_s"]),
                         "none works (real negative eigenvalue)" if neg else fmt(r["critical_damping_1_s"]),
                         f"({r['mode_x_m'] * 1e3:g}, {r['mode_y_m'] * 1e3:g})"])
    if not rows:
        return None
    return table(["scene 1, dx = 4 mm", "stretch", "lambda_max (1/s^2)", "stable step (ms)", "estimate at rest (ms)",
                  "growth (1/s)", "damping needed (1/s)", "mode at (mm)"], rows)


def t_rows(root):
    sys.path.insert(0, HERE)
    import row_order  # noqa: E402
    rows = []
    for name in ("rows_dx0.001_bond_only", "rows_dx0.001_energy_consistent", "rows_dx0.0005_bond_only",
                 "rows_dx0.0005_energy_consistent", "rows_dx0.001_layers3"):
        r = Run(root, name)
        if not r.ok or not os.path.isdir(os.path.join(r.dir, "fields")):
            continue
        files = sorted(os.listdir(os.path.join(r.dir, "fields")))
        data = [row_order.ratios(os.path.join(r.dir, "fields", f)) for f in files if f.endswith(".h5")]
        crossed = next((s for s, lo, hi in data if lo < 0), None)
        cells = []
        for lam in (1.5, 2, 3, 4):
            near = min(data, key=lambda d: abs(d[0] - lam))
            cells.append(f"{near[1]:+.2f} / {near[2]:.2f}" if abs(near[0] - lam) < 0.15 else "-")
        rows.append([name.replace("rows_", ""), f"{crossed:.2f}" if crossed else "never (to stretch 4)"] + cells)
    if not rows:
        return None
    return table(["run", "rows cross at stretch"] + [f"min / max spacing ratio at {l:g}" for l in (1.5, 2, 3, 4)], rows)


def t_timestep(root):
    names = [f"timestep_s{s}" for s in (0.5, 0.8, 0.9, 1.0, 1.05, 1.1, 1.2, 1.5)]
    names += [f"timestep_failure_s{s}" for s in (1.1, 1.2, 1.5)]
    rows = []
    for r in runs(root, names):
        failure = "failure" in r.name
        safety = r.name.split("_s")[-1]
        rows.append([safety, "7.2" if failure else "none", fmt(r.dt), r.u_max(), r.steps, f"{r.wall:.1f}",
                     r.outcome(), _message(r)])
    return table(["safety", "critical stretch", "dt (s)", "u_max at 1.5 (mm)", "steps", "wall (s)", "outcome",
                  "message (start)"], rows)


def _message(r):
    if not r.error:
        return ""
    e = r.error
    cut = e.find(". Fastest point")
    if cut < 0:
        cut = e.find(": lower")
    return "`" + (e[:cut] if cut > 0 else e[:100]).replace("|", "/") + " ...`"


def t_bulk(root):
    rows = []
    for form in ("plane_stress", "plane_strain"):
        for k in (10, 100, 1000, 10000):
            for suffix in ("", "_s0.4", "_energy_consistent_s0.4"):
                r = Run(root, f"bulk_{form}_k{k}{suffix}")
                if not r.ok:
                    continue
                u = r.u_max()
                v = float(u.rstrip("*")) if u != "-" else None
                rows.append([form.replace("_", " ") + (", energy-consistent" if "energy" in suffix else ""), k,
                             "0.4" if suffix else "0.8", fmt(r.stable), r.steps, f"{r.wall:.1f}",
                             u, f"{100 * (v / FEA_1_5 - 1):+.1f} %" if v and form == "plane_stress" else "-", r.outcome()])
    if not rows:
        return None
    return table(["formulation", "K / mu", "safety", "stable step (s)", "steps", "wall (s)", "u_max at 1.5 (mm)",
                  "vs FEA 8.62 mm (plane stress)", "outcome"], rows)


def t_horizon(root):
    rows = []
    for h in ("1.5", "2", "2.515", "3.015", "3.515", "4", "5"):
        p, n, e = Run(root, f"horizon_plate_h{h}"), Run(root, f"horizon_notched_h{h}"), \
            Run(root, f"horizon_plate_energy_consistent_h{h}")
        if not p.ok:
            continue
        rows.append([h, p.singular, n.singular if n.ok else "-", fmt(p.stable), p.steps, f"{p.wall:.1f}",
                     p.u_max(), p.outcome(), e.u_max() if e.ok else "-", e.outcome() if e.ok else "-"])
    if not rows:
        return None
    return table(["delta / dx", "singular K, scene 1", "singular K, scene 3 (1 mm)", "stable step (s)", "steps", "wall (s)",
                  "u_max at 1.5 (mm)", "outcome (bond-only)", "u_max, energy-consistent (mm)",
                  "outcome (energy-consistent)"], rows)


ISLAND = "0.0009,0.002,0.0016,0.002,0.0016,0.002,0.0016,0.0027,0.0016,0.0027,0.0009,0.0027,0.0009,0.0027,0.0009,0.002"
DIAGONAL = "0.001,0.002,0.0015,0.002,0.0015,0.002,0.0015,0.0025,0.0015,0.0025,0.001,0.0025,0.001,0.0025,0.001,0.002"
# case: (label, extra notches, critical stretch)
TORN = {"torn": ("notch", "", 2), "torn_island": ("notch + isolated point", ISLAND, 2),
        "torn_energy_consistent": ("notch, energy-consistent", "", 2),
        "torn_diagonal": ("notch + box with corners on the diagonals", DIAGONAL, 2),
        "torn_brittle": ("notch, critical stretch 1.5", "", 1.5),
        "torn_k100": ("notch, critical stretch 1.5, K = 100 mu", "", 1.5)}


def t_fracture(root):
    rows = []
    for case, (label, extra, sc) in TORN.items():
        for s in ("0.8", "0.6", "0.5", "0.4", "0.3", "0.2"):
            r = Run(root, f"{case}_s{s}")
            if not r.ok:
                continue
            notches = "0,0.005,0.003,0.005" + ("," + extra if extra else "")
            check = subprocess.run([sys.executable, os.path.join(HERE, "..", "..", "tests", "stability", "check_torn.py"),
                                    r.dir, "--dx", "0.0005", "--horizon-factor", "3.015", "--critical-stretch", str(sc),
                                    "--notches", notches, "--opening", "0.01"], capture_output=True, text=True)
            iso = re.search(r"(\d+) isolated", check.stdout)
            broken = r.broken if r.broken is not None else "-"
            if r.rc != 0:
                verdict = "-"
            elif check.returncode == 0:
                verdict = "torn in two, halves apart"
            elif "not torn" in check.stdout:
                verdict = "not torn in two"
            else:  # torn, but the probes did not end apart: the sheet broke up around them
                verdict = "fragmented (the probes' points broke loose)"
            rows.append([label, s, fmt(r.dt), r.steps, broken, iso.group(1) if iso and r.rc == 0 else "-", verdict,
                         r.outcome()])
    for s in ("0.25", "0.4"):
        r = Run(root, f"notched_paper_s{s}")
        if r.ok:
            rows.append(["scene 3, dx = 1/3 mm (the paper's grid)", s, fmt(r.dt), r.steps,
                         r.broken if r.broken is not None else "-", "-",
                         f"reached stretch {r.final_stretch:.2f}" if r.final_stretch else "-", r.outcome()])
    for form in ("bond_only", "energy_consistent"):
        for s in ("0.8", "0.4"):
            r = Run(root, f"notched_dx0.001_{form}_s{s}")
            if r.ok:
                rows.append([f"scene 3, dx = 1 mm, {form.replace('_', '-')}", s, fmt(r.dt), r.steps,
                             r.broken if r.broken is not None else "-", "-",
                             f"reached stretch {r.final_stretch:.2f}" if r.final_stretch else "-", r.outcome()])
    if not rows:
        return None
    return table(["case", "safety", "dt (s)", "steps", "broken bonds", "isolated points", "result", "outcome"], rows)


def t_spectrum_narrow(root):
    rows = []
    for dx in ("0.001", "0.0005"):
        for r in spectrum_rows(root, f"spectrum_narrow_dx{dx}"):
            rows.append([f"{float(dx) * 1e3:g}", f"{r['stretch']:.3g}", fmt(r["abs_lambda_max_1_s2"]),
                         fmt(r["stable_dt_s"] * 1e3), fmt(r["growth_rate_1_s"]), fmt(r["critical_damping_1_s"]),
                         fmt(r["asymmetry"], 2), f"({r['mode_x_m'] * 1e3:g}, {r['mode_y_m'] * 1e3:g})"])
    if not rows:
        return None
    return table(["dx (mm)", "stretch", "lambda_max (1/s^2)", "stable step (ms)", "growth (1/s)", "damping needed (1/s)",
                  "asymmetry", "mode at (mm)"], rows)


def _cause(r):
    m = re.search(r"Cause: (.*?)\.(?:\s|$)", r.error)  # up to the first full stop (not the one of a number)
    return m.group(1) if m else ("" if r.rc == 0 else "(no cause named)")


def t_map(root):
    """The stability map (section 8): runs named map__VARIABLE__VALUE__FORM__RATE__STEP."""
    names = sorted(n for n in os.listdir(root) if n.startswith("map__") and os.path.isdir(os.path.join(root, n)))
    order = {"Jm": 0, "bulk_ratio": 1, "horizon": 2, "safety": 3}
    cells = {}
    for r in runs(root, names):
        parts = r.name.split("__")
        if len(parts) != 6:  # an older map's run (no force form in the name)
            continue
        _, var, value, form, rate, step = parts
        dt = [row["dt_s"] for row in r.history if "dt_s" in row]
        shortest = f"{min(dt) / dt[0]:.2f}" if dt and dt[0] > 0 else "-"
        cell = f"{r.outcome()}" + (f": {_cause(r)}" if r.rc else "") + (f" (dt down to {shortest} x)" if step == "adaptive" and shortest not in ("-", "1.00") else "")
        cells.setdefault((order.get(var, 9), var, value, form, rate), {})[step] = (cell, r.final_stretch)
    if not cells:
        return None
    def key(k):
        try:
            return (k[0], float(k[2].split("_")[0]), k[2], k[3], k[4])
        except ValueError:
            return (k[0], 0.0, k[2], k[3], k[4])
    rows = []
    for k in sorted(cells, key=key):
        _, var, value, form, rate = k
        c = cells[k]
        def show(step):
            if step not in c:
                return "-"
            cell, lam = c[step]
            return cell if cell.startswith("ran") else f"stretch {fmt(lam, 4)}: {cell}"
        rows.append([var.replace("_", " "), value.replace("_", " "), form.replace("_", "-"), rate, show("fixed"), show("adaptive")])
    return table(["varied", "value", "force form", "loading", "step fixed at rest (-time_step_reestimate 0)", "step re-estimated (default)"], rows)


TABLES = {"shear_reference": lambda root: t_shear_reference(), "shear": t_shear, "spectrum_shear": t_spectrum_shear,
          "spectrum_broken": t_spectrum_broken, "spectrum_narrow": t_spectrum_narrow, "spectrum_plate": t_spectrum_plate, "rows": t_rows,
          "timestep": t_timestep, "bulk": t_bulk, "horizon": t_horizon, "fracture": t_fracture,
          "map": t_map}


def main():
    root, doc = sys.argv[1], sys.argv[2]
    with open(doc) as f:
        text = f.read()
    for name, build in TABLES.items():
        pattern = re.compile(r"(<!-- table:%s -->\n)(.*?)(<!-- end -->)" % re.escape(name), re.S)
        if not pattern.search(text):
            continue
        body = build(root)
        if body is None:
            print(f"{name}: no runs, left as it is")
            continue
        text = pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(3), text)
        print(f"{name}: updated")
    with open(doc, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
