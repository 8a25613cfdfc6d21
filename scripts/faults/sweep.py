"""The fault sweep of docs/faults.md: short runs of bapd, each given one fault, each
classified automatically.

Kinds of fault (--only):
  option   one option of the tiny scene given a wrong type, a negative, NaN, inf or a
           huge value (the options are those `bapd -help` lists for the scene)
  file     a scene, point cloud, Gmsh geometry or checkpoint that is missing, empty,
           truncated or has bytes changed
  signal   SIGTERM, SIGINT, SIGQUIT, SIGHUP, SIGUSR2, SIGSEGV or SIGBUS to run_mpi.sh or
           to one rank, during the set-up or at a random step
  disk     a small disk (tmpfs, root only) that fills at a random point of a run that
           writes field files, checkpoints, final_state.csv or a history row every step
  reported the faults a user met and reported (reported_cases.py), each on 1 and 2 ranks and
           each with the class it must get and the words its error line must hold
Classes: clean (exit != 0, exactly one `bapd: error:` line, no stack), fits (a full-disk
case whose files all fitted: exit 0, everything whole), crash (a signal, a segfault, a
PETSc or HDF5 stack, a Python trace), hang (no end within the timeout), silent (exit 0
where the run should have failed), unclear (exit != 0 without exactly one error line),
data loss (a file there before the run, or one the run wrote whole, is damaged);
killed (the reported kind's kill -9 of run_mpi.sh: nothing of the run left running).
Each run is short (-end_step, the 400-point scene) and the cases run one at a time.
"""
import argparse
import hashlib
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

import reported_cases
from reported_cases import CLOUD_SCENE, RUN_MPI, SOURCE, TINY  # (the paths, defined once)

GEOMETRY = os.path.join(SOURCE, "tests", "data", "geometry", "l_shape.geo")
TIMEOUT = 60  # s: a run of these scenes takes a few; more is a hang
STACK = re.compile(r"PETSC ERROR|HDF5-DIAG|Segmentation|core dumped|Caught signal|MPI_ABORT|Traceback|"
                   r"terminate called|stopped by SIG(SEGV|BUS|ILL|FPE) \(a crash|killed by SIG")
VALUES = ["abc", "-1", "nan", "inf", "1e30", "-1e30", "1,2,x"]


def environment(extra=None):
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    env.setdefault("BAPD_EXE", os.path.join(SOURCE, "build", "bapd"))
    env.update(extra or {})
    return env


def default_signals():
    """In each run's process (before exec): the stop signals back to their default. A
    sweep started in the background (`sweep.sh &`) ignores SIGINT and SIGQUIT, and under
    nohup SIGHUP; run_mpi.sh would inherit that and could not trap them."""
    for number in (signal.SIGINT, signal.SIGQUIT, signal.SIGHUP):
        signal.signal(number, signal.SIG_DFL)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def whole_csv(path):
    """'' if every row of the CSV file has the header's number of fields and a final newline."""
    text = open(path, errors="replace").read()
    if not text.endswith("\n"):
        return f"{os.path.basename(path)}: no final newline (a cut row)"
    rows = [r.split(",") for r in text.splitlines()]
    if rows and any(len(r) != len(rows[0]) for r in rows):
        return f"{os.path.basename(path)}: a row with another number of fields"
    return ""


def readable_h5(path, dataset=None):
    try:
        import h5py
    except ImportError:
        return ""
    try:
        with h5py.File(path, "r") as f:
            if dataset:
                f[dataset][...]
    except Exception as error:  # any failure to read it back is damage
        return f"{os.path.basename(path)} cannot be read back ({type(error).__name__})"
    return ""


def output_damage(out):
    """What the run left damaged in its output directory ('' if nothing)."""
    if not os.path.isdir(out):
        return ""
    problems = []
    for name in ("history.csv", "static_states.csv", "final_state.csv", "broken_bonds.csv"):
        path = os.path.join(out, name)
        if os.path.isfile(path) and os.path.getsize(path) > 0:
            problems.append(whole_csv(path))
    checkpoint = os.path.join(out, "checkpoint.h5")
    if os.path.isfile(checkpoint):
        problems.append(readable_h5(checkpoint))
    index = os.path.join(out, "fields.xdmf")
    if os.path.isfile(index):
        for name in sorted(set(re.findall(r">(fields/step_\d+\.h5):", open(index).read()))):
            path = os.path.join(out, name)
            problems.append(readable_h5(path, "displacement") if os.path.isfile(path) else f"fields.xdmf lists {name}, which is missing")
    return "; ".join(p for p in problems if p)


class Case:
    def __init__(self, kind, name, ranks, args, expect="fail", setup=None, check=None, env=None, action=None,
                 own_output=False, long_path=False, out_on=None, pipe=None):
        self.kind, self.name, self.ranks, self.args = kind, name, ranks, args
        self.expect = expect  # "fail": the run must fail; "either": failing cleanly or running whole are both right
        self.setup, self.check, self.env, self.action = setup, check, env or {}, action
        # The reported kind's (reported_cases.py): the class it must get, the words its error line
        # must hold, a check of its outcome, process limits; where its output goes (the
        # checkpoint's own directory, a 4200-character path, a small disk), a pipe for stdout.
        self.want, self.keys, self.judge, self.preexec = None, [], None, None
        self.own_output, self.long_path, self.out_on, self.pipe = own_output, long_path, out_on, pipe


def classify(case, status, seconds, log, out, before):
    errors = [line for line in log.splitlines() if "bapd: error:" in line]
    first = errors[0] if errors else ""
    if status is None:
        return "hang", f"no end after {TIMEOUT} s"
    if STACK.search(log) or status >= 128:
        match = STACK.search(log)
        return "crash", (match.group(0) if match else f"exit status {status}") + (f": {first}" if first else "")
    damage = output_damage(out)
    for path, value in before.items():
        if os.path.isfile(path) and digest(path) != value:
            damage = (damage + "; " if damage else "") + f"{os.path.basename(path)} (there before the run) was changed"
        elif not os.path.isfile(path) and status != 0:
            damage = (damage + "; " if damage else "") + f"{os.path.basename(path)} (there before the run) was removed"
    if status == 0:
        if case.expect == "fail":
            return "silent", "exit 0"
        return ("data loss", damage) if damage else ("fits", "exit 0, every file whole")
    if len(errors) != 1:
        return "unclear", f"exit {status}, {len(errors)} error lines"
    if damage:
        return "data loss", damage
    return "clean", first


def output_of(case, folder):
    """Where the case's run writes: its folder's out, on the disk its setup mounts, or
    under a path of 4200 characters (each name 200: past PATH_MAX, not NAME_MAX)."""
    if case.long_path:
        return os.path.join(folder, *(["d" * 200] * 21))
    return os.path.join(folder, case.out_on, "out") if case.out_on else os.path.join(folder, "out")


def command(case, folder, out):
    args = [RUN_MPI, "-n", str(case.ranks)] + [a.replace("{dir}", folder).replace("{out}", out) for a in case.args]
    if not case.own_output or case.long_path:
        args += ["-output_dir", out]
    if case.pipe:  # stdout through a pipe, stderr to the log; the exit status run_mpi.sh's
        quoted = " ".join("'" + a.replace("'", "'\\''") + "'" for a in args)
        args = ["bash", "-c", f"{quoted} 2>> run.log | {case.pipe} > /dev/null; exit ${{PIPESTATUS[0]}}"]
    return args


def run_case(case, work, index):
    folder = os.path.join(work, f"{index:03d}")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    out = output_of(case, folder)
    before = {}
    extra_env = dict(case.env)
    try:
        if case.setup:
            before = case.setup(folder, out, extra_env) or {}

        def preexec():
            default_signals()
            if case.preexec:
                case.preexec()
        start = time.monotonic()
        with open(os.path.join(folder, "run.log"), "w") as log:
            process = subprocess.Popen(command(case, folder, out), cwd=folder, stdout=log, stderr=subprocess.STDOUT,
                                       env=environment(extra_env), start_new_session=True, preexec_fn=preexec)
            status = None
            try:
                if case.action:
                    case.action(process, folder)
                status = process.wait(timeout=max(1.0, TIMEOUT - (time.monotonic() - start)))
            except subprocess.TimeoutExpired:
                status = None
            finally:
                if process.poll() is None:
                    os.killpg(process.pid, signal.SIGKILL)  # this case's own session: run_mpi.sh, mpiexec, ranks
                    process.wait()
        seconds = time.monotonic() - start
        text = open(os.path.join(folder, "run.log"), errors="replace").read()
        if case.want == "killed":  # run_mpi.sh killed on purpose: what counts is what is left
            verdict, note = ("killed", "nothing of the run left running") if status is not None else ("hang", "")
        else:
            verdict, note = classify(case, status, seconds, text, out, before)
        if case.check and verdict in ("clean", "fits"):
            problem = case.check(folder, out)
            if problem:
                verdict, note = "data loss", problem
        if getattr(case, "full_disk", False) and verdict == "clean" and "No space left on device" not in note \
                and "File too large" not in note:
            verdict, note = "unclear", "the error line does not name the full disk: " + note
        missing = [k for k in case.keys if k not in note]
        wrong = [k for k in getattr(case, "forbid", []) if k in note]
        if verdict == "clean" and (missing or wrong):
            verdict, note = "unclear", (f"the error line lacks '{missing[0]}': " if missing else
                                        f"the error line says '{wrong[0]}': ") + note
        if case.judge and verdict in ("clean", "fits", "killed"):
            problem = case.judge(folder, out, text, extra_env.get("TMPDIR"))
            if problem:
                verdict, note = problem[0], problem[1] + (f" ({note})" if note else "")
    finally:
        if case.out_on:
            subprocess.run(["umount", os.path.join(folder, case.out_on)], stderr=subprocess.DEVNULL)
        if "TMPDIR" in extra_env and extra_env["TMPDIR"].startswith(folder):
            subprocess.run(["umount", extra_env["TMPDIR"]], stderr=subprocess.DEVNULL)
    return verdict, note, seconds


# --- the cases -------------------------------------------------------------------------

def tiny_options(env):
    """The options `bapd -help` lists for the tiny scene: [(name, shown value)]."""
    text = subprocess.run([env["BAPD_EXE"], "-options_file_yaml", TINY, "-help"], capture_output=True, text=True,
                          env=env, timeout=60).stdout
    options = []
    for name, value in re.findall(r"^\s+(-[a-z][a-z0-9_]*) <([^>]*)>", text, re.M):
        if name in ("-output_dir", "-options_file_yaml", "-help", "-version", "-end_step") or name in dict(options):
            continue
        options.append((name, value))
    return options


def reference_output(work, env):
    """An undisturbed run's output (history.csv, checkpoint.h5 at step 10): the files a
    case finds in its output directory before it starts, and the checkpoint the
    checkpoint cases damage."""
    ref = os.path.join(work, "reference")
    if not os.path.isfile(os.path.join(ref, "checkpoint.h5")):
        shutil.rmtree(ref, ignore_errors=True)
        subprocess.run([RUN_MPI, "-n", "2", TINY, "-checkpoint_interval", "10", "-end_step", "10", "-output_dir", ref],
                       env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=120, check=True)
    return ref


def with_previous_results(ref):
    """setup: the output directory holds a previous run's results, which a failing run must keep."""
    def setup(folder, out, env):
        os.makedirs(out)
        kept = {}
        for name in ("history.csv", "checkpoint.h5"):
            shutil.copy(os.path.join(ref, name), os.path.join(out, name))
            kept[os.path.join(out, name)] = digest(os.path.join(out, name))
        return kept
    return setup


def mutate_bytes(data, rng, how):
    data = bytearray(data)
    if how == "empty":
        return b""
    if how == "truncate":
        return bytes(data[:rng.randrange(1, max(2, len(data)))])
    if how == "flip":
        for _ in range(rng.randint(1, 8)):
            k = rng.randrange(len(data))
            data[k] ^= 1 << rng.randrange(8)
        return bytes(data)
    if how == "zero_block":
        k = rng.randrange(len(data))
        data[k:k + 4096] = bytes(len(data[k:k + 4096]))
        return bytes(data)
    if how == "junk":
        return bytes(rng.randrange(256) for _ in range(rng.randint(16, 4096)))
    if how == "garbage_line":
        lines = bytes(data).split(b"\n")
        lines.insert(rng.randrange(len(lines) + 1), b"{[: ]] \x00 - -: 'x")
        return b"\n".join(lines)
    raise ValueError(how)


def good_cloud():
    rows = ["x,y,volume,block_id"]
    for j in range(20):
        for i in range(20):
            rows.append(f"{(i + 0.5) * 0.0005!r},{(j + 0.5) * 0.0005!r},2.5e-10,1")
    return ("\n".join(rows) + "\n").encode()


def make_cases(count, rng, env, work, only):
    ref = reference_output(work, env)
    previous = with_previous_results(ref)
    cases = []
    ranks = lambda: rng.choice([1, 2, 3])  # noqa: E731
    short = ["-end_step", "5"]

    # Options: each listed option with each wrong value, in a random order; as many as the
    # share of the option cases allows.
    option_cases = []
    for name, shown in tiny_options(env):
        for value in VALUES:
            option_cases.append(Case("option", f"{name} {value}", 0, [TINY, name, value] + short, setup=previous))
    rng.shuffle(option_cases)

    # Files.
    file_cases = []
    scene_text = open(TINY, "rb").read()
    for how in ["empty", "truncate", "truncate", "truncate", "flip", "flip", "flip", "garbage_line", "garbage_line", "junk"]:
        def setup(folder, out, env, how=how, seed=rng.random()):
            data = mutate_bytes(scene_text, random.Random(seed), how)
            open(os.path.join(folder, "scene.yaml"), "wb").write(data)
            return previous(folder, out, env)
        file_cases.append(Case("file", f"scene {how}", 0, ["{dir}/scene.yaml"] + short, setup=setup))
    file_cases.append(Case("file", "scene missing", 0, ["{dir}/no_such.yaml"] + short, setup=previous))
    file_cases.append(Case("file", "scene is a directory", 0, ["-options_file_yaml", "{dir}"] + short, setup=previous))
    cloud = good_cloud()
    for how in ["empty", "truncate", "truncate", "flip", "flip", "flip", "garbage_line", "junk", "nan", "inf", "negative"]:
        def setup(folder, out, env, how=how, seed=rng.random()):
            r = random.Random(seed)
            if how in ("nan", "inf", "negative"):
                lines = cloud.decode().splitlines()
                k = r.randrange(1, len(lines))
                field = r.randrange(3)
                parts = lines[k].split(",")
                parts[field] = {"nan": "nan", "inf": "inf", "negative": "-" + parts[field]}[how]
                lines[k] = ",".join(parts)
                data = ("\n".join(lines) + "\n").encode()
            else:
                data = mutate_bytes(cloud, r, how)
            open(os.path.join(folder, "cloud.csv"), "wb").write(data)
            return previous(folder, out, env)
        file_cases.append(Case("file", f"cloud {how}", 0, [CLOUD_SCENE, "-body_cloud", "{dir}/cloud.csv"] + short, setup=setup))
    geometry = open(GEOMETRY, "rb").read()
    mesh = ["-body_shapes", "cut", "-body_cut_type", "mesh", "-body_cut_operation", "subtract", "-body_cut_file", "{dir}/cut.geo"]
    for how in ["empty", "truncate", "truncate", "flip", "flip", "garbage_line", "junk"]:
        def setup(folder, out, env, how=how, seed=rng.random()):
            open(os.path.join(folder, "cut.geo"), "wb").write(mutate_bytes(geometry, random.Random(seed), how))
            return previous(folder, out, env)
        file_cases.append(Case("file", f"gmsh geometry {how}", 0, [TINY] + mesh + short, setup=setup))
    checkpoint = open(os.path.join(ref, "checkpoint.h5"), "rb").read()
    for how in ["empty", "truncate", "truncate", "truncate", "flip", "flip", "flip", "flip", "zero_block", "zero_block", "junk"]:
        def setup(folder, out, env, how=how, seed=rng.random()):
            open(os.path.join(folder, "damaged.h5"), "wb").write(mutate_bytes(checkpoint, random.Random(seed), how))
            return previous(folder, out, env)
        file_cases.append(Case("file", f"checkpoint {how}", 0, ["-restart", "{dir}/damaged.h5", "-end_step", "15"], setup=setup))
    file_cases.append(Case("file", "checkpoint missing", 0, ["-restart", "{dir}/no_such.h5", "-end_step", "15"], setup=previous))

    # Signals at a random moment: during the set-up, or at a random step of a long run.
    signal_cases = []
    long_run = [TINY, "-load_schedule", "0,1,100,1.05", "-output_interval", "10", "-checkpoint_interval", "200",
                "-progress_interval", "100"]
    choices = [("launcher", "TERM"), ("launcher", "INT"), ("rank", "TERM"), ("rank", "INT"), ("rank", "QUIT"),
               ("rank", "HUP"), ("rank", "USR2"), ("rank", "SEGV"), ("rank", "BUS")]
    for k in range(40):
        target, name = choices[k % len(choices)]
        when = "setup" if k % 4 == 3 else "step"
        delay = rng.uniform(0.0, 3.0)

        def action(process, folder, target=target, name=name, when=when, delay=delay, pick=rng.random()):
            log = os.path.join(folder, "run.log")
            deadline = time.monotonic() + 40
            while time.monotonic() < deadline and process.poll() is None:
                text = open(log, errors="replace").read()
                if (when == "setup" and "Scene" in text) or (when == "step" and re.search(r"^step ", text, re.M)):
                    break
                time.sleep(0.05)
            time.sleep(delay if when == "step" else delay / 10)
            sig = getattr(signal, "SIG" + name)
            if target == "launcher":
                os.kill(process.pid, sig)
                return
            ranks = []
            for pid in os.listdir("/proc"):
                try:
                    if pid.isdigit() and open(f"/proc/{pid}/comm").read().strip() == "bapd" and \
                            folder in open(f"/proc/{pid}/cmdline").read():
                        ranks.append(int(pid))
                except OSError:
                    pass
            if ranks:
                os.kill(sorted(ranks)[int(pick * len(ranks))], sig)
        signal_cases.append(Case("signal", f"SIG{name} to {target} during {when}", 0, long_run, action=action,
                                 expect="fail"))

    # Full disks of random sizes, written at random points.
    disk_cases = []
    if os.geteuid() == 0:
        writes = {"fields": ["-output_fields", "-output_fields_interval", "2"],
                  "checkpoint": ["-checkpoint_interval", "5"],
                  "final_state": ["-output_final_state"],
                  "history": ["-output_interval", "1"]}
        # Sizes (KB) from a disk too small for the first write to one that holds the run.
        sizes = {"fields": (120, 700), "checkpoint": (60, 500), "final_state": (16, 96), "history": (12, 48)}
        for k in range(40):
            what = rng.choice(sorted(writes))
            kb = rng.randrange(*sizes[what])
            late = rng.random() < 0.5

            def setup(folder, out, env, kb=kb, late=late):
                disk = os.path.join(folder, "disk")
                os.makedirs(disk)
                subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kb}k", "tmpfs", disk], check=True)
                if late:
                    env["BAPD_TEST_NO_SPACE_RESERVATION"] = "1"
                return {}
            case = Case("disk", f"{what} on {kb} KB{' (no reservation)' if late else ''}", 0,
                        [TINY, "-load_grip_placement", "inside", "-end_step", "30"] + writes[what], expect="either",
                        setup=setup)
            case.out_on, case.full_disk = "disk", True
            disk_cases.append(case)

    # The reported cases, each on 1 and on 2 ranks.
    reported = []
    for n in (1, 2):
        for case in reported_cases.reported_cases(Case, ref, environment):
            case.fixed_ranks = n
            reported.append(case)
    # The share of each kind: every file, signal and disk case, the rest options (the
    # reported cases on top).
    chosen = {"file": file_cases, "signal": signal_cases, "disk": disk_cases, "reported": reported}
    fixed = sum(len(v) for k, v in chosen.items() if k in only and k != "reported")
    chosen["option"] = option_cases[:max(0, count - fixed)] if "option" in only else []
    for kind in ("option", "file", "signal", "disk", "reported"):
        if kind in only:
            cases += chosen[kind]
    for case in cases:
        drawn = ranks()  # (for every case, the reported ones last: the other kinds' draws are those of a sweep without them)
        case.ranks = getattr(case, "fixed_ranks", drawn)
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cases", type=int, default=240, help="cases of the random kinds (the options fill what the file, signal and disk cases leave); the reported "
                        "cases come on top")
    parser.add_argument("--seed", type=int, default=1, help="the random choices' seed (a sweep is repeatable)")
    parser.add_argument("--only", default="option,file,signal,disk,reported", help="kinds of fault, comma-separated")
    parser.add_argument("--work", default="faults_sweep", help="the directory of the runs (one folder a case)")
    parser.add_argument("--match", default="", help="only the cases whose name holds this text")
    parser.add_argument("--smoke", action="store_true", help="a short subset: one case of each kind (about 30 s)")
    args = parser.parse_args()
    env = environment()
    if not os.access(env["BAPD_EXE"], os.X_OK):
        sys.exit(f"sweep.sh: error: no bapd at {env['BAPD_EXE']}: build it (scripts/build.sh) or set BAPD_EXE")
    only = set(args.only.split(","))
    unknown = only - {"option", "file", "signal", "disk", "reported"}
    if unknown:
        sys.exit(f"sweep.sh: error: --only {','.join(sorted(unknown))}: give option, file, signal, disk or reported")
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)
    rng = random.Random(args.seed)
    cases = make_cases(args.cases, rng, env, work, only)
    cases = [case for case in cases if args.match in case.name]
    if args.smoke:
        picked = {}
        for case in cases:
            picked.setdefault(case.kind, case)
        cases = list(picked.values())
    counts = {}
    bad = []
    print(f"{'#':>3}  {'kind':6}  {'np':>2}  {'class':9}  {'s':>5}  case: note")
    for index, case in enumerate(cases):
        verdict, note, seconds = run_case(case, work, index)
        counts[verdict] = counts.get(verdict, 0) + 1
        if verdict not in ("clean", "fits") if case.want is None else verdict != case.want:
            bad.append((index, case, verdict, note))
        print(f"{index:3d}  {case.kind:6}  {case.ranks:2d}  {verdict:9}  {seconds:5.1f}  {case.name}: {note[:150]}", flush=True)
    print()
    print(f"{len(cases)} cases: " + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())))
    for index, case, verdict, note in bad:
        print(f"  not clean: #{index} {case.kind} '{case.name}' on {case.ranks} rank(s): {verdict}: {note[:300]} "
              f"({os.path.join(work, f'{index:03d}', 'run.log')})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
