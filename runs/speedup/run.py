#!/usr/bin/env python3
"""Speedup study: ranks 1, 2 (3 and 4 oversubscribe this 2-core machine: marked) x threads 1, 2,
for the hybrid method and each method alone, on scenes of ~2 M (city), ~2*10^7 (a field of 400
instanced armadillos) and 2.2*10^12 (instanced chessboard) triangles, at 640x480 and 1920x1080.
Per configuration: the median frame time (frames after the first), its speedup and parallel
efficiency against 1 rank x 1 thread, and the per-stage breakdown: render (the slowest rank's
stages), composite, shade (at the root), and imbalance (the slowest rank's render time minus the
mean over ranks).

Usage: python3 runs/speedup/run.py [--quick] [--plot-only] [--methods=a,b] [--scenes=a,b]
                                   [--configs=1x1,2x1,...]   (ranks x threads; the first is the base)
                                   [--keep]   (replace only the rerun scenes' and methods' rows)
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh;
       plots need gnuplot). The same command on a cluster: see runs/speedup/README.md.
Writes runs/speedup/speedup.csv, stages.csv, speedup.png and stages.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only", "--keep"),
                   valued=("scenes", "methods", "configs"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
# Frames a run renders (the first is dropped): the city's frames are short, and its medians
# over 5 frames moved by up to 40 % between runs on this VM.
FRAMES = {"city": 21, "field": 6, "chessboard": 6}
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
SCENES = {
    "city": "builtin:city",
    "field": f"builtin:replicated?mesh={ARMADILLO}&k=20&levels=1",
    "chessboard": "builtin:chessboard?n=1048576",
}
# The per-leaf cull of lzb and the hybrid refuses 10^12-triangle instancing (too many visible
# instance paths), and no z-buffer draws it: those combinations are skipped and said so.
# The hybrid draws the chessboard since its frame-level way casts every pixel there (runs/peers).
CANNOT = {("chessboard", "zbuffer"), ("chessboard", "lzb")}
METHODS = ["hybrid", "lzb", "rzb", "raycast", "zbuffer"]
SIZES = [(640, 480)] if QUICK else [(640, 480), (1920, 1080)]
# The hybrid's stages whose work is split across ranks (every other render stage is repeated on
# every rank: cull, plane, near pass, unfinished mask, OOR projection, combine).
SPLIT_STAGES = ("pvl_find", "pvl_render", "points")
CONFIGS = [(1, 1), (1, 2), (2, 1)] if QUICK else [(1, 1), (1, 2), (2, 1), (3, 1), (4, 1)]


def breakdown(frames):
    """Medians over frames of the frame time and its parts."""
    parts = {"frame_s": [], "render_s": [], "composite_s": [], "shade_s": [], "imbalance_s": []}
    for f in frames:
        per_rank = [sum(v for k, v in r["stages"].items() if k not in common.AFTER_RENDER)
                    for r in f["ranks"]]
        parts["frame_s"].append(f["seconds"])
        parts["render_s"].append(max(per_rank))
        parts["composite_s"].append(f["stages"].get("composite", 0.0))
        parts["shade_s"].append(f["stages"].get("shade", 0.0))
        parts["imbalance_s"].append(max(per_rank) - sum(per_rank) / len(per_rank))
    return {k: common.median(v) for k, v in parts.items()}


def save(rows, stage_rows, commands):
    # Kept rows (--keep) and new ones in the study's order: scene, size, method (stable: configs).
    key = lambda r: (list(SCENES).index(r["scene"]), int(r["width"]), METHODS.index(r["method"]))  # noqa: E731
    rows, stage_rows = sorted(rows, key=key), sorted(stage_rows, key=key)
    common.write_csv(os.path.join(HERE, "speedup.csv"), rows,
                     ["scene", "triangles", "width", "height", "method", "ranks", "threads",
                      "oversubscribed", "frame_s", "render_s", "composite_s", "shade_s",
                      "imbalance_s", "speedup", "efficiency"], commands)
    common.write_csv(os.path.join(HERE, "stages.csv"), stage_rows,
                     ["scene", "width", "height", "method", "ranks", "threads", "stage", "seconds"],
                     commands)


def run():
    methods = common.option("methods", METHODS)
    scenes = common.option("scenes", list(SCENES))
    configs = [tuple(int(v) for v in c.split("x")) for c in common.option("configs", [])] or CONFIGS
    rows, stage_rows, commands = [], [], []
    if "--keep" in sys.argv:
        rows, commands = common.read_kept(os.path.join(HERE, "speedup.csv"))
        stage_rows = common.read_csv(os.path.join(HERE, "stages.csv"))
        rerun = lambda r: r["scene"] in scenes and r["method"] in methods  # noqa: E731
        rows = [r for r in rows if not rerun(r)]
        stage_rows = [r for r in stage_rows if not rerun(r)]
    for scene in scenes:
        for (w, h) in SIZES:
            for method in methods:
                if (scene, method) in CANNOT:
                    print(f"{scene} {method}: skipped (cannot render this scene)", flush=True)
                    continue
                base = None
                for ranks, threads in configs:
                    shown, rep = common.render(
                        SCENES[scene], ["--method", method, "--frames", str(3 if QUICK else FRAMES[scene]), "--width",
                                        str(w), "--height", str(h)], ranks=ranks, threads=threads)
                    commands.append(shown)
                    frames = rep["frames"][1:] or rep["frames"]
                    b = breakdown(frames)
                    base = base or b["frame_s"]
                    workers = ranks * threads
                    row = {"scene": scene, "triangles": rep["scene"]["triangles_expanded"],
                           "width": w, "height": h, "method": method, "ranks": ranks,
                           "threads": threads, "oversubscribed": int(workers > common.CORES),
                           **b, "speedup": base / b["frame_s"],
                           "efficiency": base / b["frame_s"] / workers}
                    rows.append(row)
                    for name in {k for f in frames for k in f["stages"]}:
                        stage_rows.append({"scene": scene, "width": w, "height": h, "method": method,
                                           "ranks": ranks, "threads": threads, "stage": name,
                                           "seconds": common.median(f["stages"].get(name, 0.0) for f in frames)})
                    print(f"{scene} {w}x{h} {method:8s} {ranks}x{threads}: {b['frame_s'] * 1e3:8.1f} ms "
                          f"(x{row['speedup']:.2f}; render {b['render_s'] * 1e3:.1f}, composite "
                          f"{b['composite_s'] * 1e3:.1f}, shade {b['shade_s'] * 1e3:.1f}, imbalance "
                          f"{b['imbalance_s'] * 1e3:.1f} ms)", flush=True)
                    save(rows, stage_rows, commands)  # after every run: a long study keeps its part


def plot():
    rows = common.read_csv(os.path.join(HERE, "speedup.csv"))
    combos = sorted({(r["scene"], int(r["width"]), int(r["height"])) for r in rows})
    methods = [m for m in METHODS if any(r["method"] == m for r in rows)]
    panels = []
    for scene, w, h in combos:
        blocks = []
        for m in methods:
            pts = [(int(r["ranks"]) * int(r["threads"]) + (0.1 if int(r["threads"]) > 1 else 0.0),
                    float(r["speedup"])) for r in rows
                   if r["scene"] == scene and int(r["width"]) == w and r["method"] == m]
            blocks.append(sorted(pts) or [(1, 1)])
        data = common.datafile(blocks)
        lines = ", ".join(f"'{data}' index {i} with linespoints title '{m}'" for i, m in enumerate(methods))
        panels.append(f"set title '{scene} {w}x{h}'\nplot {lines}, x with lines dt 2 lc 'gray' title 'ideal'\n")
    common.gnuplot(f"""
set terminal pngcairo size 1600,{400 * ((len(combos) + 2) // 3)} font ',10'
set output '{os.path.join(HERE, "speedup.png")}'
set multiplot layout {(len(combos) + 2) // 3},3 title 'Speedup over 1 rank x 1 thread (workers = ranks x threads; x.1 = 2 threads per rank; > 2 workers oversubscribe 2 cores)'
set xlabel 'workers'
set ylabel 'speedup'
set xrange [0.5:4.5]
set yrange [0:4.5]
set key top left
set grid
{''.join(panels)}
unset multiplot
""")
    # Where the time goes: the hybrid's parts per configuration (city, both sizes).
    stages = common.read_csv(os.path.join(HERE, "stages.csv"))
    blocks, labels = [], []
    for r in rows:
        # Stage figures are maxima over ranks: their sum means little when ranks share a core.
        if r["method"] != "hybrid" or r["scene"] != "city" or int(r["oversubscribed"]):
            continue
        mine = {x["stage"]: float(x["seconds"]) * 1e3 for x in stages
                if (x["method"], x["scene"], x["width"], x["ranks"], x["threads"]) ==
                (r["method"], r["scene"], r["width"], r["ranks"], r["threads"])}
        split = sum(mine.get(k, 0.0) for k in SPLIT_STAGES)
        replicated = sum(v for k, v in mine.items() if k not in SPLIT_STAGES + common.AFTER_RENDER)
        parts = [replicated, split, mine.get("wait", 0.0), mine.get("composite", 0.0),
                 mine.get("shade", 0.0)]
        labels.append(f"{r['width']}p {r['ranks']}x{r['threads']}")
        blocks.append((len(labels) - 1, *parts, max(0.0, float(r["frame_s"]) * 1e3 - sum(parts))))
    if not blocks:
        return
    common.stacked_bars(
        os.path.join(HERE, "stages.png"),
        "hybrid on the city: where a frame goes (ms, medians; ranks x threads)", labels, blocks,
        "'DATA' using 2 title 'replicated stages', '' using 3 title 'split stages (pvl find + "
        "render, points)', '' using 4 title 'wait (imbalance)', '' using 5 title 'composite', '' "
        "using 6 title 'shade (root)', '' using 7 title 'untimed'")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
