#!/usr/bin/python3
"""Runs bapd once under mpiexec and records what the benchmarks need, as JSON.

    bapd_run.py --exe BAPD --ranks N --out DIR --label NAME [--sample 0.2] -- SCENE.yaml [bapd options]

Writes DIR/NAME.log (everything bapd printed) and DIR/NAME.json:
  wall_s            wall time of the whole run (mpiexec start to exit)
  cpu_s             user + system CPU time of every process of the run (rusage of
                    mpiexec and the ranks it waited for)
  cpu_utilisation   cpu_s / (wall_s x ranks): below 1 when the ranks had to share
                    cores with something else (this machine is shared)
  peak_rss_mb       sum over the ranks of their peak resident set size (VmHWM, read
                    from /proc/PID/status every --sample seconds)
  stepping_rss_mb   the largest sum over the ranks of VmRSS sampled after bapd printed
                    "Time stepping" (the memory of the time loop, setup transients gone)
  points, bonds, steps, sim_wall_s, schedule_steps   parsed from bapd's output
  stages            -log_view stage times in seconds (if -log_view was given)
  events            -log_view event times (max over ranks) and counts: TSStep, ...
  static_states     rows of OUTPUT_DIR/static_states.csv, if the scene wrote one
RSS is measured from outside, so bapd itself needs no change.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import threading
import time


def descendants(pid):
    """PIDs of every process below pid."""
    children = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        ppid = int(stat[stat.rfind(")") + 2:].split()[1])
        children.setdefault(ppid, []).append(int(entry))
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        for c in children.get(p, []):
            out.append(c)
            todo.append(c)
    return out


def status_kb(pid):
    """(comm, VmRSS kB, VmHWM kB) of a process, or None."""
    try:
        with open(f"/proc/{pid}/status") as f:
            text = f.read()
    except OSError:
        return None
    name = re.search(r"^Name:\s*(\S+)", text, re.M)
    rss = re.search(r"^VmRSS:\s*(\d+)", text, re.M)
    hwm = re.search(r"^VmHWM:\s*(\d+)", text, re.M)
    if not (name and rss and hwm):
        return None
    return name.group(1), int(rss.group(1)), int(hwm.group(1))


def cpu_seconds(pid):
    """User + system CPU time of a process so far (from /proc/PID/stat), or None."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            stat = f.read()
    except OSError:
        return None
    fields = stat[stat.rfind(")") + 2:].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def parse_output(text):
    r = {}
    m = re.search(r"^Body: (\d+) points, (\d+) bonds, (\d+) rank", text, re.M)
    if m:
        r["points"], r["bonds"], r["ranks_reported"] = int(m.group(1)), int(m.group(2)), int(m.group(3))
    m = re.search(r"edge cut (\d+), fewest owned (\d+), most ghosts (\d+)", text)
    if m:
        r["edge_cut"], r["fewest_owned"], r["most_ghosts"] = map(int, m.groups())
    m = re.search(r"about (\d+) steps", text)
    if m:
        r["schedule_steps"] = int(m.group(1))
    m = re.search(r"using dt = ([0-9.eE+-]+) s", text)
    if m:
        r["dt_s"] = float(m.group(1))
    m = re.search(r"^Finished: (\d+) steps, t = ([0-9.eE+-]+) s, stretch ([0-9.]+), wall ([0-9.]+) s", text, re.M)
    if m:
        r["steps"], r["end_time_s"], r["final_stretch"], r["sim_wall_s"] = (int(m.group(1)), float(m.group(2)),
                                                                           float(m.group(3)), float(m.group(4)))
    stages = {}
    for m in re.finditer(r"^\s*\d+:\s+([A-Za-z ]+?):\s+([0-9.eE+-]+)\s+([0-9.]+)%", text, re.M):
        stages[m.group(1).strip()] = float(m.group(2))
    if stages:
        r["stages"] = stages
    m = re.search(r"^Time \(sec\):\s+([0-9.eE+-]+)", text, re.M)
    if m:
        r["log_view_total_s"] = float(m.group(1))
    events = {}
    for m in re.finditer(r"^(TSStep|TSFunctionEval|VecScatterBegin|VecScatterEnd|SFBcastBegin|SFBcastEnd)\s+(\d+)\s+"
                         r"[0-9.]+\s+([0-9.eE+-]+)", text, re.M):
        events.setdefault(m.group(1), {"count": 0, "time_s": 0.0})
        events[m.group(1)]["count"] += int(m.group(2))
        events[m.group(1)]["time_s"] += float(m.group(3))
    if events:
        r["events"] = events
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--out", required=True)
    ap.add_argument("--label", required=True)
    ap.add_argument("--sample", type=float, default=0.2)
    ap.add_argument("--keep-best", action="store_true",
                    help="if DIR/NAME.json already holds a successful run with a smaller wall time, keep it "
                         "(repeat a run to get the minimum; the slower one goes to NAME.slower.json)")
    ap.add_argument("args", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    args = a.args[1:] if a.args and a.args[0] == "--" else a.args
    # The first bare .yaml is the scene; an overlay given as "-options_file_yaml FILE"
    # later stays where it is, after the scene (it is read after it).
    scene = [x for k, x in enumerate(args) if x.endswith((".yaml", ".yml")) and (k == 0 or args[k - 1] != "-options_file_yaml")]
    rest = [x for x in args if x not in scene[:1]]
    cmd = ["mpiexec", "-n", str(a.ranks), "--oversubscribe", "--bind-to", "none", a.exe]
    if scene:
        cmd += ["-options_file_yaml", scene[0]]
    cmd += rest
    os.makedirs(a.out, exist_ok=True)
    log_path = os.path.join(a.out, a.label + ".log.running")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

    hwm, stepping = {}, [0]
    stepping_started = [False]
    cpu_now, cpu_at_stepping = {}, {}  # per rank process: CPU seconds (last sample, at "Time stepping")
    done = threading.Event()

    t0 = time.time()
    with open(log_path, "w") as log:
        log.write("# " + " ".join(cmd) + "\n")
        log.flush()
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, text=True)

        def sampler():
            while not done.is_set():
                total = 0
                for pid in descendants(proc.pid):
                    s = status_kb(pid)
                    if s and s[0].startswith("bapd"):
                        hwm[pid] = max(hwm.get(pid, 0), s[2])
                        total += s[1]
                        c = cpu_seconds(pid)
                        if c is not None:
                            cpu_now[pid] = c
                if stepping_started[0]:
                    stepping[0] = max(stepping[0], total)
                done.wait(a.sample)

        th = threading.Thread(target=sampler, daemon=True)
        th.start()
        text = []
        for line in proc.stdout:
            log.write(line)
            text.append(line)
            if line.startswith("Time stepping"):
                stepping_started[0] = time.time()
                for pid in descendants(proc.pid):
                    s = status_kb(pid)
                    c = cpu_seconds(pid)
                    if s and s[0].startswith("bapd") and c is not None:
                        cpu_at_stepping[pid] = c
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.time() - t0
        done.set()
        th.join()
    rc = os.waitstatus_to_exitcode(status)
    out = "".join(text)
    result = {
        "label": a.label,
        "command": cmd,
        "ranks": a.ranks,
        "returncode": rc,
        "wall_s": wall,
        "cpu_s": usage.ru_utime + usage.ru_stime,
        "peak_rss_mb": sum(hwm.values()) / 1024.0,
        "stepping_rss_mb": stepping[0] / 1024.0,
        "stepping_wall_s": (time.time() - stepping_started[0]) if stepping_started[0] else None,
    }
    # Per rank: CPU seconds of the whole run and of the time loop (from "Time stepping"
    # to the last sample, at most --sample seconds before the end). On a shared machine
    # the largest per-rank time-loop CPU time is what the loop would take alone.
    result["rank_cpu_s"] = [cpu_now[p] for p in sorted(cpu_now)]
    result["rank_stepping_cpu_s"] = [cpu_now[p] - cpu_at_stepping[p] for p in sorted(cpu_now) if p in cpu_at_stepping]
    result["cpu_utilisation"] = result["cpu_s"] / (wall * a.ranks) if wall > 0 else 0
    result.update(parse_output(out))
    # The scene's output directory: static states of the plate-with-hole holds.
    outdir = None
    for k, x in enumerate(rest):
        if x == "-output_dir" and k + 1 < len(rest):
            outdir = rest[k + 1]
    if outdir and os.path.exists(os.path.join(outdir, "static_states.csv")):
        with open(os.path.join(outdir, "static_states.csv")) as f:
            result["static_states"] = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    path = os.path.join(a.out, a.label + ".json")
    if a.keep_best and os.path.exists(path):
        old = json.load(open(path))
        result["repeats"] = old.get("repeats", 1) + 1
        if old.get("returncode") == 0 and (rc != 0 or old["wall_s"] <= wall):
            old["repeats"] = result["repeats"]
            with open(os.path.join(a.out, a.label + ".slower.json"), "w") as f:
                json.dump(result, f, indent=1)
            os.replace(log_path, os.path.join(a.out, a.label + ".slower.log"))
            result = old
    if os.path.exists(log_path):
        os.replace(log_path, os.path.join(a.out, a.label + ".log"))
    with open(path + ".tmp", "w") as f:
        json.dump(result, f, indent=1)
    os.replace(path + ".tmp", path)
    print(f"{a.label}: rc {rc}, wall {wall:.1f} s, cpu {result['cpu_s']:.1f} s "
          f"(utilisation {100 * result['cpu_utilisation']:.0f} %), peak RSS {result['peak_rss_mb']:.0f} MB, "
          f"points {result.get('points')}, steps {result.get('steps')}")
    sys.exit(0 if rc == 0 else 1)


if __name__ == "__main__":
    main()
