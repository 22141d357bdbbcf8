#!/usr/bin/env python3
"""The speed-accuracy trade-off: every registered method with its accuracy parameters swept by
`lzb sweep`, one Pareto plot per scene.

Per scene (builtin:city, builtin:forest, builtin:sphereflake, a sub-pixel field of 1,600
instanced scanned armadillos, and the scanned armadillo itself) and per method (the list
`lzb render --help` gives): `lzb sweep` over the method's accuracy parameters, along the same
camera frames, every combination judged against the exact reference of each frame (raycast;
raycast itself against zbuffer). Swept: rzb the splat size d, eps, the oversampling and the
fallback threshold; the hybrid d, the oversampling and the fallback threshold; lzb the partition
plane (cost model, mean depth, fixed fractions of the frustum) and, with the paper's octree walk,
the local occluders per leaf; the sample tree c and d; surfels the finest grid and the largest
sprite; the exact methods are one point each. A method that refuses a scene (exit status 2, e.g.
the in-core sample tree above 2^24 triangles) is recorded as refused in the CSV's comment lines.

Usage: python3 runs/tradeoff/run.py [--quick] [--plot-only] [--scenes=a,b] [--methods=a,b] [--no-wait]
       [--keep]  (--keep: replace only the rerun methods' rows and commands of each scene's CSV)
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh;
       plots need gnuplot: bash scripts/install-deps.sh --bench)
Writes runs/tradeoff/<scene>.csv and <scene>.png: per combination the median frame time (frames
after the first), correct_rate_covered (minimum and median over frames), exact_id_rate_covered,
psnr_aa, error = 1 - median correct_rate_covered, and whether it is on the scene's Pareto front
(no other row is as fast and as accurate, one of them strictly). --quick (2 frames at 96x72, the
first and last value of each parameter, no waiting for a quiet machine: a check that the script
works, not a measurement) writes quick_<scene>.csv and quick_<scene>.png.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only", "--keep"), valued=("scenes", "methods"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
PREFIX = "quick_" if QUICK else ""
WIDTH, HEIGHT = (96, 72) if QUICK else (640, 480)
FRAMES = 2 if QUICK else 10
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
SCENES = {
    "city": "builtin:city",
    "forest": "builtin:forest",
    "sphereflake": "builtin:sphereflake",
    "field": f"builtin:replicated?mesh={ARMADILLO}&k=40&levels=1",
    "armadillo": ARMADILLO,
}


def grids_up_to(top):
    """The surfel levels 1, 2, 4, ... up to top (one --surfel-grids value)."""
    return ",".join(str(1 << k) for k in range(top.bit_length()))


# method: [(config label, fixed arguments, [--param NAME=V1,V2,...])]; exact methods sweep the
# thread count they run with (one value), which leaves their image alone.
SWEEPS = {
    "raycast": [("raycast", [], [f"threads={common.CORES}"])],
    "zbuffer": [("zbuffer", [], [f"threads={common.CORES}"])],
    "rzb": [("rzb", [], ["splat=1,2,4", "eps=1.2,1.5,3", "oversample=0.5,1,2", "fallback=auto,16"])],
    "hybrid": [("hybrid", [], ["splat=1,2,4", "oversample=0.5,1,2", "fallback=auto,0.001,0.1,16"])],
    "lzb": [("lzb", [], ["plane=cost,auto,0.05,0.2"]),
            # the local occluders act in the paper's octree walk only
            ("lzb_walk", ["--lzb-rays", "walk"], ["plane=cost,0.2", "occluders=0,1,5"])],
    "sampletree": [("sampletree", [], ["c=0,2,5", "splat=1,2,4"])],
    "surfels": [("surfels", ["--surfel-build", "setup"],
                 ["surfel-grids=" + ";".join(grids_up_to(g) for g in (64, 128, 256)),
                  "splat=1,2,4"])],
    "sqrt5": [("sqrt5", [], ["amin=0.25,0.5,1,2"])],
}
EXACT = {"raycast", "zbuffer"}
FIELDS = ["scene", "method", "config", "reference", "frames", "median_frame_s", "setup_s",
          "correct_rate_covered_min", "correct_rate_covered_median", "exact_id_rate_covered_median",
          "psnr_aa_median", "error", "pareto"]


def registered_methods():
    """The --method values, as `lzb render --help` lists them."""
    text = subprocess.run([common.LZB, "render", "--help"], capture_output=True, text=True,
                          env=common.ENV, check=True).stdout
    found = re.search(r"rendering method: ([\w| ]+)", text)
    return [m.strip() for m in found.group(1).split("|")]


def quick_param(param):
    """--quick keeps each parameter's first and last value."""
    name, values = param.split("=", 1)
    sep = ";" if ";" in values else ","
    vals = values.split(sep)
    return f"{name}={sep.join(dict.fromkeys([vals[0], vals[-1]]))}"


def sweep(scene, method, extra, params):
    """Runs lzb sweep; returns (shown command, rows of its sweep.csv, refusal message or None)."""
    reference = "zbuffer" if method == "raycast" else "raycast"
    out = tempfile.mkdtemp(prefix="lzb-tradeoff-")
    cmd = [common.LZB, "sweep", scene, "--method", method, *extra, "--reference", reference,
           "--width", str(WIDTH), "--height", str(HEIGHT), "--frames", str(FRAMES), "--quiet",
           "--out", os.path.join(out, "sweep")]
    if method not in EXACT:
        cmd += ["--threads", str(common.CORES)]
    for p in params:
        cmd += ["--param", quick_param(p) if QUICK else p]
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, env=common.ENV)
        shown = " ".join(c if out not in c else c.replace(out, "OUT") for c in cmd).replace(common.ROOT + "/", "")
        if run.returncode == 2:
            return shown, [], run.stderr.strip().splitlines()[-1] if run.stderr.strip() else "exit 2"
        if run.returncode != 0:
            raise RuntimeError(f"{shown}: exit {run.returncode}\n{run.stdout}\n{run.stderr}")
        rows = common.read_csv(os.path.join(out, "sweep", "sweep.csv"))
    finally:
        shutil.rmtree(out, ignore_errors=True)
    return shown, [dict(r, reference=reference) for r in rows], None


def config_label(label, params, row):
    names = [p.split("=", 1)[0] for p in params]
    # a --surfel-grids list is named by its finest grid
    swept = " ".join(f"{n}=..{row[n].split(',')[-1]}" if "," in row[n] else f"{n}={row[n]}"
                     for n in names if n != "threads")
    return f"{label} {swept}".strip()


def mark_pareto(rows):
    """pareto = 1 when no other row is at least as fast and as accurate, one of them strictly."""
    for r in rows:
        t, e = float(r["median_frame_s"]), r["error"]
        r["pareto"] = int(not any(
            float(o["median_frame_s"]) <= t and o["error"] <= e and
            (float(o["median_frame_s"]) < t or o["error"] < e) for o in rows if o is not r))


def run_scene(name, methods):
    scene = SCENES[name]
    rows, commands = [], []
    path = os.path.join(HERE, f"{PREFIX}{name}.csv")
    kept_rows, kept_commands = (common.read_kept(path) if "--keep" in sys.argv and
                                os.path.exists(path) else ([], []))
    kept_rows = [dict(r, error=float(r["error"])) for r in kept_rows if r["method"] not in methods]
    kept_commands = [c for c in kept_commands
                     if not any(f" --method {m} " in c for m in methods)]
    for method in methods:
        for label, extra, params in SWEEPS.get(method, []):
            if not QUICK and "--no-wait" not in sys.argv:
                common.wait_quiet()
            shown, got, refused = sweep(scene, method, extra, params)
            commands.append(shown if refused is None else f"refused (exit 2): {shown}: {refused}")
            if refused:
                print(f"{name} {label}: refused: {refused}", flush=True)
                continue
            for r in got:
                r.update(scene=name, method=method, config=config_label(label, params, r),
                         error=1.0 - float(r["correct_rate_covered_median"]))
                rows.append(r)
                print(f"{name} {r['config']:40s}: {float(r['median_frame_s']) * 1e3:9.2f} ms, "
                      f"error {r['error']:.2e}", flush=True)
    rows = kept_rows + rows
    mark_pareto(rows)
    common.write_csv(path, rows, FIELDS, kept_commands + commands)


def plot_scene(name):
    path = os.path.join(HERE, f"{PREFIX}{name}.csv")
    if not os.path.exists(path):
        return
    rows = common.read_csv(path)
    if not rows:
        return
    errors = [float(r["error"]) for r in rows]
    floor = min([e for e in errors if e > 0] or [1e-5]) / 10
    methods = list(dict.fromkeys(r["method"] for r in rows))
    point = lambda r: (float(r["median_frame_s"]), max(float(r["error"]), floor))  # noqa: E731
    blocks = [[point(r) for r in rows if r["method"] == m] for m in methods]
    front = sorted((r for r in rows if r["pareto"] == "1"), key=lambda r: float(r["median_frame_s"]))
    blocks.append([point(r) for r in front])
    data = common.datafile(blocks)
    labels = "\n".join(f"set label {i + 1} '{r['config']}' at {point(r)[0]},{point(r)[1]} "
                       f"offset 0.8,0.6 font ',8'" for i, r in enumerate(front))
    plots = [f"'{data}' index {k} using 1:2 with points pt {5 if m == 'raycast' else 4 + k} "
             f"ps {2.2 if m == 'raycast' else 1.2} title '{m}'" for k, m in enumerate(methods)]
    plots.append(f"'{data}' index {len(methods)} using 1:2 with lines lw 2 dt 2 lc rgb 'black' "
                 f"title 'Pareto front'")
    what = "quick check, not a measurement" if QUICK else f"{common.CORES} cores"
    common.gnuplot(f"""
set terminal pngcairo size 1300,900 font ',10' noenhanced
set output '{os.path.join(HERE, f"{PREFIX}{name}.png")}'
set title '{name} ({SCENES[name].replace(common.ROOT + "/", "")}), {WIDTH}x{HEIGHT}, {FRAMES} frames; {what}'
set logscale xy
set grid
set key outside right
set xlabel 'median frame time (s, frames after the first; log)'
set ylabel 'error = 1 - correct_rate_covered (median over frames; log; 0 drawn at {floor:.1e})'
{labels}
plot {", ".join(plots)}
""")


def main():
    scenes = common.option("scenes", list(SCENES))
    if "--plot-only" not in sys.argv:
        methods = common.option("methods", registered_methods())
        for m in methods:
            if m not in SWEEPS:
                print(f"warning: no sweep defined for method {m}; add it to SWEEPS", flush=True)
        for name in scenes:
            run_scene(name, methods)
    for name in scenes:
        plot_scene(name)


if __name__ == "__main__":
    main()
