"""Helpers the run scripts share: rendering through `lzb render` (under mpirun for several ranks),
waiting for a quiet machine, CSV files with their command line, gnuplot, and the machine's
memory-copy rate measured in the same run."""
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# -h / --help prints the running study's docstring (its usage) instead of starting the study,
# which would overwrite its CSVs.
if {"-h", "--help"} & set(sys.argv[1:]):
    import __main__
    print((__main__.__doc__ or "see the study's README.md").strip())
    sys.exit(0)


def accept_args(flags=(), valued=(), words=(), followed=()):
    """Refuses, with status 2 before anything runs (or a CSV is overwritten), every argument that
    is not one of `flags`, --NAME=VALUE for NAME in `valued`, one of `words`, or the value after
    one of `followed`. --no-wait (wait_quiet) is always accepted."""
    args, unknown = sys.argv[1:], []
    for i, a in enumerate(args):
        name = a[2:].split("=", 1)[0] if a.startswith("--") and "=" in a else None
        if (a in flags or a == "--no-wait" or a in words or name in valued or
                (a in followed and i + 1 < len(args)) or (i > 0 and args[i - 1] in followed)):
            continue
        unknown.append(a)
    if unknown:
        print(f"{os.path.relpath(sys.argv[0])}: unknown argument(s) {' '.join(unknown)} (see --help)",
              file=sys.stderr)
        sys.exit(2)


def option(name, default):
    """The comma-separated values of --NAME=a,b (default when absent)."""
    for a in sys.argv[1:]:
        if a.startswith(f"--{name}="):
            return a.split("=", 1)[1].split(",")
    return default


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LZB = os.path.join(os.environ.get("LZB_BUILD", os.path.join(ROOT, "build")), "lzb")
DATA = os.path.join(ROOT, "build", "data")
# Idle OpenMP threads must not spin on the cores the other ranks and llvmpipe need.
ENV = dict(os.environ, OMP_WAIT_POLICY="passive", OMPI_ALLOW_RUN_AS_ROOT="1",
           OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
CORES = os.cpu_count() or 1
# Frame stages after rendering (mpi/frame_driver.hpp): idle until the slowest rank, the exchange,
# the root's shading.
AFTER_RENDER = ("wait", "composite", "shade")
# How several ranks are started: on a cluster, e.g. LZB_MPIRUN="mpirun --hostfile hosts".
MPIRUN = os.environ.get("LZB_MPIRUN", "mpirun --oversubscribe").split()


def idle_fraction(seconds=2.0):
    """Share of CPU time the machine spent idle over the next `seconds` (/proc/stat)."""
    def sample():
        with open("/proc/stat") as f:
            vals = [int(v) for v in f.readline().split()[1:]]
        return vals[3] + vals[4], sum(vals)
    i0, t0 = sample()
    time.sleep(seconds)
    i1, t1 = sample()
    return (i1 - i0) / max(t1 - t0, 1)


def wait_quiet(limit_s=600):
    """Starts a measurement only on a machine >= 85 % idle (it is shared), for at most limit_s.
    --no-wait skips it (a functional check, not a measurement)."""
    if "--no-wait" in sys.argv:
        return False
    start = time.time()
    while time.time() - start < limit_s:
        if idle_fraction() >= 0.85:
            return True
        time.sleep(5)
    print("warning: the machine stayed busy; measuring anyway", flush=True)
    return False


def render(scene, args, ranks=1, threads=1, quiet_wait=True, keep=None, lzb=None):
    """Runs lzb render (under mpirun for ranks > 1); returns (shown command, report). keep: a
    folder for the frames, left in place (else a temporary one, removed). lzb: another binary
    (an earlier build, for before/after rows in one run)."""
    if quiet_wait:
        wait_quiet()
    out = keep or tempfile.mkdtemp(prefix="lzb-run-")
    try:
        cmd = [lzb or LZB, "render", scene, *args, "--threads", str(threads), "--quiet", "--out", out]
        if ranks > 1:
            cmd = [*MPIRUN, "-n", str(ranks), *cmd]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=ENV)
        with open(os.path.join(out, "report.json")) as f:
            rep = json.load(f)
    finally:
        if not keep:
            shutil.rmtree(out, ignore_errors=True)
    shown = " ".join(c if c != out else "OUT" for c in cmd).replace(ROOT + "/", "")
    return shown, rep


def landscape_ply(objects):
    """builtin:landscape?objects=N exported as a binary PLY (each placed mesh's vertices once, as
    a scanned mesh or heightfield file holds them) into $LZB_SCRATCH or /tmp, once."""
    path = os.path.join(os.environ.get("LZB_SCRATCH", "/tmp"), f"lzb-memory-landscape-{objects}.ply")
    if not os.path.exists(path):
        subprocess.run([LZB, "export", f"builtin:landscape?objects={objects}", path, "--quiet",
                        "--max-triangles", "1000000000"], check=True, env=ENV)
    return path


def median(xs):
    xs = list(xs)
    return statistics.median(xs) if xs else 0.0


def memcpy_rate(megabytes=256, repeats=5):
    """Bytes per second of one large copy (the best of `repeats`), measured now."""
    src = bytearray(os.urandom(1 << 20)) * megabytes
    dst = bytearray(len(src))
    view_src, view_dst = memoryview(src), memoryview(dst)
    best = float("inf")
    for _ in range(repeats):
        t = time.perf_counter()
        view_dst[:] = view_src
        best = min(best, time.perf_counter() - t)
    return len(src) / best


def write_csv(path, rows, fields, commands):
    """CSV with the command lines that made it as leading # lines."""
    with open(path, "w", newline="") as f:
        f.write(f"# made by: python3 {' '.join(sys.argv).replace(ROOT + '/', '')}\n")
        for c in dict.fromkeys(commands):  # once each (a --keep rerun repeats its commands)
            f.write(f"# {c}\n")
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def read_kept(path):
    """--keep: an existing study CSV's rows and the commands that made them, for a run of some
    scenes or methods to replace only its own rows."""
    with open(path) as f:
        commands = [line[2:].rstrip("\n") for line in f if line.startswith("# ")][1:]
    return read_csv(path), commands


def gnuplot(script):
    if shutil.which("gnuplot") is None:
        print("gnuplot missing (bash scripts/install-deps.sh --bench): no plot", flush=True)
        return
    subprocess.run(["gnuplot"], input=script.encode(), check=True)


def datafile(blocks):
    """A gnuplot data file of blocks (lists of rows of numbers), blocks separated by 2 blank lines."""
    f = tempfile.NamedTemporaryFile("w", suffix=".dat", delete=False)
    for block in blocks:
        for row in block:
            f.write(" ".join(str(v) for v in row) + "\n")
        f.write("\n\n")
    f.close()
    return f.name


def stacked_bars(path, title, labels, rows, columns, size="1200,550"):
    """A PNG of stacked bars (gnuplot rowstacked histogram), one bar per label: rows are (index,
    values...), `columns` the plot command's column list with DATA standing for the data file."""
    data = datafile([rows])
    xtics = ", ".join(f"'{l}' {i}" for i, l in enumerate(labels))
    gnuplot(f"""
set terminal pngcairo size {size} font ',10'
set output '{path}'
set title '{title}'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set xtics ({xtics}) rotate by -30
set ylabel 'ms'
set key outside right
set grid y
plot {columns.replace("DATA", data)}
""")
