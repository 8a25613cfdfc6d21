"""The sweep's `reported` kind: the faults a hostile but ordinary user met (docs/faults.md,
"The fault sweep"), each replayed on the tiny scene and each with the class it must get.

A case here may carry, besides what every case has (sweep.Case):
  want   the class the case must get (clean, or fits where running whole is right);
  keys   words the error line must hold (the cause, the option that fixes it): a clean
         stop whose line lacks one is `unclear` (a misleading message); forbid: words
         it must not hold (a cause that is not the case's);
  judge  a check of the run's outcome (the processes left, a warning, the rows kept):
         a problem it returns makes the case `data loss`, `hang` or `unclear` as it says.
"""
import os
import re
import resource
import shutil
import signal
import subprocess
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
RUN_MPI = os.path.join(SOURCE, "run_mpi.sh")
TINY = os.path.join(SOURCE, "tests", "data", "scenes", "tiny.yaml")
BLOCK_3D = os.path.join(SOURCE, "tests", "data", "scenes", "block_3d.yaml")
CLOUD_SCENE = os.path.join(SOURCE, "tests", "data", "scenes", "cloud.yaml")
PLATE = os.path.join(SOURCE, "examples", "plate_hole.yaml")
# The tiny scene run long enough (about 10 s) for a signal or a second run to meet it.
ENVIRONMENT = None  # the sweep's environment(extra): BAPD_EXE set, so that no run builds bapd
LONG = [TINY, "-load_schedule", "0,1,100,1.05", "-output_interval", "10", "-checkpoint_interval", "200",
        "-progress_interval", "100"]


def run_quietly(args, env, timeout=120):
    """A run a case's set-up needs (the checkpoints it restarts from): it must succeed."""
    subprocess.run([RUN_MPI, "-n", "1"] + args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   timeout=timeout, check=True)


def wait_for(folder, pattern, process, seconds=40):
    """Until run.log matches pattern (the run reached its set-up or its steps)."""
    log = os.path.join(folder, "run.log")
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and process.poll() is None:
        if re.search(pattern, open(log, errors="replace").read(), re.M):
            return True
        time.sleep(0.05)
    return False


def run_processes(folder):
    """The bapd and mpiexec processes whose command line names this case's folder."""
    found = []
    for pid in os.listdir("/proc"):
        try:
            if pid.isdigit() and open(f"/proc/{pid}/comm").read().strip() in ("bapd", "mpiexec", "prterun", "orterun") \
                    and folder in open(f"/proc/{pid}/cmdline").read():
                found.append(int(pid))
        except OSError:
            pass
    return found


def rank_pid(folder):
    ranks = [p for p in run_processes(folder) if open(f"/proc/{p}/comm").read().strip() == "bapd"]
    return max(ranks) if ranks else None


def signal_rank(name, when=r"^step "):
    def action(process, folder):
        wait_for(folder, when, process)
        time.sleep(0.5)
        pid = rank_pid(folder)
        if pid:
            os.kill(pid, getattr(signal, "SIG" + name))
    return action


def signal_launcher(name, when=r"^step ", delay=0.5):
    def action(process, folder):
        if when:
            wait_for(folder, when, process)
        time.sleep(delay)
        os.kill(process.pid, getattr(signal, "SIG" + name))
    return action


def rows(path):
    if not os.path.isfile(path):
        return []
    return [line.split(",") for line in open(path).read().splitlines()[1:]]


def history_steps(out):
    return [int(r[0]) for r in rows(os.path.join(out, "history.csv"))]


def checkpointed_run(end_step, then_to=None, backup=False, kept=True):
    """setup: out holds a run of the tiny scene to end_step with a checkpoint every 10
    steps (backup_step<end_step>.h5, a copy of that checkpoint), continued in place to
    then_to; the files there before the case are returned to be kept (kept: a refused
    case; a continuation in place rewrites them)."""
    def setup(folder, out, env):
        base = ENVIRONMENT(env)
        run_quietly([TINY, "-checkpoint_interval", "10", "-end_step", str(end_step), "-output_dir", out], base)
        if backup:
            shutil.copy(os.path.join(out, "checkpoint.h5"), os.path.join(out, f"backup_step{end_step}.h5"))
        if then_to:
            run_quietly(["-restart", os.path.join(out, "checkpoint.h5"), "-end_step", str(then_to)], base)
        if not kept:
            return {}
        from sweep import digest  # (the sweep imports this module)
        return {os.path.join(out, n): digest(os.path.join(out, n)) for n in ("history.csv", "checkpoint.h5")}
    return setup


def write_file(name, text):
    def setup(folder, out, env):
        with open(os.path.join(folder, name), "w") as f:
            f.write(text)
    return setup


def limit(kind, soft, hard=None):
    """preexec: a process limit (ulimit) on the case's run_mpi.sh and all it starts."""
    def apply():
        resource.setrlimit(kind, (soft, soft if hard is None else hard))
    return apply


def mounted_tmpfs(name, kb, fill=False):
    """setup: a tmpfs of kb KB at <folder>/<name> (root), filled to the last byte if asked."""
    def setup(folder, out, env):
        disk = os.path.join(folder, name)
        os.makedirs(disk)
        subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kb}k", "tmpfs", disk], check=True)
        if fill:
            subprocess.run(["dd", "if=/dev/zero", f"of={disk}/filler", "bs=4k"], stderr=subprocess.DEVNULL)
        if name == "tmp":
            env["TMPDIR"] = disk
    return setup


def own_tmpdir(folder, out, env):
    """setup: a TMPDIR of the case's own (short: Open MPI's sockets live there), so that
    what run_mpi.sh leaves there is this run's."""
    env["TMPDIR"] = tempfile.mkdtemp(prefix="bapd_sweep.")


def fill_disk(process, folder):
    """action: once the run steps, another process fills its disk (<folder>/disk)."""
    wait_for(folder, r"^step ", process)
    subprocess.run(["dd", "if=/dev/zero", f"of={folder}/disk/filler", "bs=4k"], stderr=subprocess.DEVNULL)


def judge_no_process_left(seconds=10):
    """judge: no mpiexec or rank of the run left `seconds` after run_mpi.sh ended, and
    no signal file of run_mpi.sh's left in its TMPDIR (own_tmpdir)."""
    def judge(folder, out, log, tmpdir):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline and run_processes(folder):
            time.sleep(0.1)
        left = run_processes(folder)
        if left:
            for pid in left:  # the sweep's own clean-up: these are processes it started
                os.kill(pid, signal.SIGKILL)
            return "hang", f"processes of the run left {seconds} s after run_mpi.sh ended: {left}"
        for _ in range(50):  # (its watcher polls once a second)
            stray = [n for n in os.listdir(tmpdir) if n.startswith("bapd_signal.")]
            if not stray:
                break
            time.sleep(0.1)
        shutil.rmtree(tmpdir, ignore_errors=True)
        if stray:
            return "data loss", f"run_mpi.sh left {stray} behind in TMPDIR"
        return None
    return judge


def judge_warning(text):
    def judge(folder, out, log, _):
        if not any("bapd: warning:" in line and text in line for line in log.splitlines()):
            return "unclear", f"no warning saying '{text}'"
        return None
    return judge


def judge_rows_kept(first, last):
    """judge: history.csv holds every step from first to last (the restart dropped none)."""
    def judge(folder, out, log, _):
        steps = history_steps(out)
        missing = [s for s in range(first, last + 1, 10) if s not in steps]
        if missing:
            return "data loss", f"history.csv lacks the rows of step(s) {missing} (it has {steps})"
        return None
    return judge


def two_runs():
    """setup: a first run (the long tiny scene) writing into out; the case is the second."""
    first = {}

    def setup(folder, out, env):
        log = open(os.path.join(folder, "first.log"), "w")
        first[folder] = subprocess.Popen([RUN_MPI, "-n", "1"] + LONG + ["-end_time", "3", "-output_dir", out],
                                         stdout=log, stderr=subprocess.STDOUT, env=ENVIRONMENT(env),
                                         start_new_session=True)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not os.path.isfile(os.path.join(out, "history.csv")):
            time.sleep(0.05)
        time.sleep(0.5)

    def judge(folder, out, log, _):
        process = first.pop(folder)
        try:
            status = process.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            return "hang", "the first run did not end"
        if status != 0:
            return "data loss", f"the first run failed (exit {status}) once the second had started"
        return None
    return setup, judge


def deep_scene(folder, out, env):
    with open(os.path.join(folder, "deep.yaml"), "w") as f:
        f.write("body:\n  dx: 0.001\nx: " + "[" * 100000 + "]" * 100000 + "\n")


def alias_bomb(folder, out, env):
    lines = ["a: &a {x: 1, y: 1, z: 1, u: 1, v: 1, w: 1, p: 1, q: 1, r: 1}"]
    for i in range(1, 9):
        lines.append(f"a{i}: &a{i} {{" + ", ".join(f"k{k}: *a" + (str(i - 1) if i > 1 else "") for k in range(9)) + "}")
    with open(os.path.join(folder, "bomb.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def flipped_attribute(ref, name):
    """setup: the reference checkpoint with one bit of one attribute flipped (the low
    bit of its mantissa, or of its first byte)."""
    def setup(folder, out, env):
        import h5py
        import numpy
        path = os.path.join(folder, "flipped.h5")
        shutil.copy(os.path.join(ref, "checkpoint.h5"), path)
        group, _, attribute = name.rpartition("/")
        with h5py.File(path, "r+") as f:
            attrs = f[group or "/"].attrs
            value = attrs[attribute]
            if isinstance(value, bytes):
                attrs[attribute] = bytes([value[0] ^ 1]) + value[1:]
            else:
                array = numpy.array([value])
                array.view(numpy.uint8)[0] ^= 1
                attrs.create(attribute, array[0], dtype=array.dtype)
    return setup


def reported_cases(Case, ref, environment):
    """Every reported case the sweep can script, each with the class it must get
    (Case, environment: the sweep's; ref: the sweep's reference run, its checkpoint)."""
    global ENVIRONMENT
    ENVIRONMENT = environment
    cases = []

    def case(name, args, want="clean", keys=(), **more):
        judge, forbid = more.pop("judge", None), more.pop("forbid", [])
        preexec = more.pop("preexec", None)
        c = Case("reported", name, 0, args, expect="fail" if want == "clean" else "either", **more)
        c.want, c.keys, c.judge, c.preexec, c.forbid = want, list(keys), judge, preexec, forbid
        cases.append(c)

    short = ["-end_step", "5"]
    # Silent wrong results.
    case("-time_step 1", [TINY, "-time_step", "1"], keys=["-time_step 1", "stable time step"])
    case("-ts_dt 1", [TINY, "-ts_dt", "1"], keys=["-ts_dt", "stable time step"])
    case("-time_step 1 with failure", [TINY, "-time_step", "1", "-failure_critical_stretch", "1.5"],
         keys=["-time_step 1", "stable time step"])
    case("a load past the chain limit (Jm 10, stretch 5)", [TINY, "-material_Jm", "10", "-load_schedule", "0,1,0.02,5"],
         keys=["-material_Jm", "chain limit"])
    case("-ts_max_steps 10", [TINY, "-ts_max_steps", "10"], keys=["-ts_max_steps", "short of its end time"])
    case("-ts_max_time 0.005", [TINY, "-ts_max_time", "0.005"], keys=["-ts_max_time", "-end_time"])
    case("one-row grips", [TINY, "-load_top_layers", "1", "-load_bottom_layers", "1"] + short, want="fits",
         judge=judge_warning("less than the horizon"))
    # Data lost.
    setup, judge = two_runs()
    case("two runs into one directory 0.5 s apart", [TINY] + short, keys=["in use by another run"], setup=setup,
         judge=judge)
    case("an older checkpoint copy restarted in place", ["-restart", "{out}/backup_step20.h5", "-end_step", "30"],
         keys=["newer results", "-restart_discard_newer"], setup=checkpointed_run(20, then_to=40, backup=True),
         own_output=True)
    case("a restart in place that adds a probe", ["-restart", "{out}/checkpoint.h5", "-probes", "p",
                                                  "-probe_p_at", "0.005,0.005", "-end_step", "30"],
         want="fits", setup=checkpointed_run(20, kept=False), judge=judge_rows_kept(0, 30), own_output=True)
    # Crashes.
    case("ulimit -v 1000000, 1 million points", [TINY, "-body_dx", "0.00001"] + short,
         keys=["process limit", "-body_dx"], preexec=limit(resource.RLIMIT_AS, 1000000 * 1024))
    case("SIGQUIT to a rank", LONG, keys=["SIGQUIT"], action=signal_rank("QUIT"))
    case("SIGSEGV to a rank", LONG, keys=["SIGSEGV", "sent by process"], action=signal_rank("SEGV"))
    case("TMPDIR on a full disk", [TINY] + short, keys=["TMPDIR"], setup=mounted_tmpfs("tmp", 64, fill=True))
    case("TMPDIR missing", [TINY] + short, keys=["TMPDIR"], env={"TMPDIR": "/nonexistent/tmp"})
    case("ulimit -n 20 (hard)", [TINY] + short, keys=["ulimit -n"], preexec=limit(resource.RLIMIT_NOFILE, 20))
    case("ulimit -n 20 (soft)", [TINY] + short, want="fits", preexec=limit(resource.RLIMIT_NOFILE, 20, 4096))
    # Hangs.
    case("-ts_type beuler", [TINY, "-ts_type", "beuler"], keys=["-ts_type beuler", "explicit"])
    case("-ts_type cn", [TINY, "-ts_type", "cn"], keys=["-ts_type cn", "explicit"])
    case("kill -9 of run_mpi.sh", LONG, want="killed", action=signal_launcher("KILL"), judge=judge_no_process_left(),
         setup=own_tmpdir)
    case(".geo with MeshSizeMax 1e-7", [TINY, "-body_shapes", "cut", "-body_cut_type", "mesh", "-body_cut_file",
                                        "{dir}/fine.geo"] + short, want="fits",
         setup=write_file("fine.geo", "Mesh.MeshSizeMax = 1e-7;\nPoint(1) = {0.002, 0.002, 0};\n"
                                      "Point(2) = {0.004, 0.002, 0};\nPoint(3) = {0.004, 0.004, 0};\n"
                                      "Point(4) = {0.002, 0.004, 0};\nLine(1) = {1, 2};\nLine(2) = {2, 3};\n"
                                      "Line(3) = {3, 4};\nLine(4) = {4, 1};\nCurve Loop(1) = {1, 2, 3, 4};\n"
                                      "Plane Surface(1) = {1};\n"))
    case("-body_cloud /dev/zero", [CLOUD_SCENE, "-body_cloud", "/dev/zero"] + short, keys=["-body_cloud", "device"])
    case("a YAML alias bomb", ["{dir}/bomb.yaml"] + short, keys=["aliases"], setup=alias_bomb)
    case("a scene nested 100000 deep", ["{dir}/deep.yaml"] + short, keys=["nested"], setup=deep_scene)
    # Misleading messages.
    case("compression to stretch 0.1", [TINY, "-load_schedule", "0,1,0.01,0.1"], keys=["Cause: the compression"])
    case("-body_width 1e308", [TINY, "-body_width", "1e308"] + short, keys=["-body_width"])
    case("-body_dx 1e-300", [TINY, "-body_dx", "1e-300"] + short, keys=["-body_dx"])
    case("-material_mu 1e-300", [TINY, "-material_mu", "1e-300"] + short, keys=["-material_mu"])
    case("another scene's checkpoint", [PLATE, "-restart", os.path.join(ref, "checkpoint.h5"), "-end_step", "15"],
         keys=["another"])
    case("a 2D checkpoint on a 3D scene", [BLOCK_3D, "-restart", os.path.join(ref, "checkpoint.h5"), "-end_step", "15"],
         keys=["2D", "3D"])
    for name in ("step", "time_s", "time_step_s", "format", "geometry/dx_m", "geometry/points", "time_step/lambda_per_s2"):
        case(f"a bit of checkpoint attribute {name} flipped", ["-restart", "{dir}/flipped.h5", "-end_step", "15"],
             keys=["flipped.h5"], forbid=["another body"], setup=flipped_attribute(ref, name))
    # (the stretch at the checkpoint is written for the reader and never read back: the run goes on)
    case("a bit of checkpoint attribute stretch flipped", ["-restart", "{dir}/flipped.h5", "-end_step", "15"], want="fits",
         setup=flipped_attribute(ref, "stretch"))
    case("Ctrl-C in the first second", LONG, keys=["SIGINT"], action=signal_launcher("INT", when=None, delay=0.5))
    case("SIGINT to run_mpi.sh", LONG, keys=["interrupted by SIGINT"], action=signal_launcher("INT"))
    case("SIGHUP to run_mpi.sh", LONG, keys=["SIGHUP"], action=signal_launcher("HUP"))
    case("SIGHUP to a rank", LONG, keys=["SIGHUP"], action=signal_rank("HUP"))
    case("a pipe into head", LONG + ["-end_time", "1"], keys=["interrupted by SIGPIPE", "-restart"], pipe="head -n 3")
    case("final_state.csv on a full disk", [TINY, "-output_final_state", "-output_interval", "1000"],
         keys=["final_state.csv", "No space left on device"], setup=mounted_tmpfs("disk", 24), out_on="disk",
         env={"BAPD_TEST_NO_SPACE_RESERVATION": "1"})
    for reserved in (True, False):  # (without the reservation the fill meets HDF5's writes)
        case(f"another process fills the disk while fields are written{'' if reserved else ' (no reservation)'}",
             LONG + ["-output_fields", "-output_fields_interval", "1", "-progress_interval", "1"],
             keys=["No space left on device"], setup=mounted_tmpfs("disk", 2048), out_on="disk", action=fill_disk,
             env={} if reserved else {"BAPD_TEST_NO_SPACE_RESERVATION": "1"})
    case("SIGTERM during the set-up of 40000 points", [TINY, "-body_dx", "0.00005", "-end_step", "3"],
         keys=["interrupted by SIGTERM"], action=signal_launcher("TERM", when=r"^Scene", delay=0.3))
    case("a 4200-character output path", [TINY] + short, keys=["-output_dir", "File name too long"],
         own_output=True, long_path=True)
    return cases
