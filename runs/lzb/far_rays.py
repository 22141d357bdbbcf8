#!/usr/bin/env python3
"""Who casts lzb's far rays: Embree (--lzb-rays embree, the default) or the paper's octree walk
(--lzb-rays walk), beside the exact ray caster (raycast) and the hybrid, on the peer study's
scenes, in one run.

Timed runs have no reference (it would share the process's caches); every method runs ROUNDS
times along the same path, the methods alternating within a round, and each frame keeps its
median over the rounds; the table gives the median over frames after the first. Accuracy
(correct_rate_covered against raycast with the ray witness, src/image/README.md) comes from one
extra, untimed run per method with --reference raycast.

Usage: python3 runs/lzb/far_rays.py [--quick] [--plot-only] [--no-wait]
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh)
Writes runs/lzb/far_rays.csv and far_rays.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
ROUNDS = 1 if QUICK else 3
THREADS = 2
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
# name: (scene, width, height, frames)
SCENES = {
    "city_paper": ("builtin:city?blocks=12", 512, 512, 80),
    "city_1080p": ("builtin:city?blocks=12", 1920, 1080, 20),
    "sphereflake": ("builtin:sphereflake?depth=5", 512, 512, 20),
    "armadillo": (ARMADILLO, 640, 480, 20),
    "field": (f"builtin:replicated?mesh={ARMADILLO}&k=40&levels=1", 640, 480, 10),
    "forest": ("builtin:forest", 640, 480, 10),
}
METHODS = [("raycast", ["--method", "raycast"]),
           ("lzb_embree", ["--method", "lzb", "--lzb-rays", "embree"]),
           ("lzb_walk", ["--method", "lzb", "--lzb-rays", "walk"]),
           ("hybrid", ["--method", "hybrid"])]
FIELDS = ["scene", "method", "frames", "median_ms", "raycast_over_method", "correct_rate_covered",
          "min_correct_rate_covered", "rays_cast", "pvl_size", "pvl_find_ms"]
CSV = os.path.join(HERE, "far_rays.csv")


def frame_args(name):
    scene, w, h, frames = SCENES[name]
    if QUICK:
        frames = min(frames, 3)
    return scene, ["--width", str(w), "--height", str(h), "--frames", str(frames)]


def per_frame_medians(reports):
    """Each frame's median seconds over the rounds, frames after the first."""
    frames = zip(*(r["frames"] for r in reports))
    return [common.median(f["seconds"] for f in same) for same in list(frames)[1:]]


def stage_median(report, stage):
    return common.median(f["stages"].get(stage, 0.0) for f in report["frames"][1:])


def count_median(report, key):
    return common.median(f["counts"].get(key, 0.0) for f in report["frames"][1:])


def measure(name):
    scene, args = frame_args(name)
    timed = {m: [] for m, _ in METHODS}
    commands = []
    for _ in range(ROUNDS):
        for m, margs in METHODS:
            shown, rep = common.render(scene, [*args, *margs], threads=THREADS)
            timed[m].append(rep)
            commands.append(shown)
    rows = []
    for m, margs in METHODS:
        acc = []  # raycast is the reference itself
        if m != "raycast":
            shown, rep = common.render(scene, [*args, *margs, "--reference", "raycast"],
                                       threads=THREADS, quiet_wait=False)
            commands.append(shown)
            acc = [f["accuracy"]["correct_rate_covered"] for f in rep["frames"] if "accuracy" in f]
        rows.append({"scene": name, "method": m, "frames": len(timed[m][0]["frames"]),
                     "median_ms": round(1000 * common.median(per_frame_medians(timed[m])), 2),
                     "correct_rate_covered": round(common.median(acc), 6) if acc else "",
                     "min_correct_rate_covered": round(min(acc), 6) if acc else "",
                     "rays_cast": count_median(timed[m][0], "rays_cast"),
                     "pvl_size": count_median(timed[m][0], "pvl_size"),
                     "pvl_find_ms": round(1000 * stage_median(timed[m][0], "pvl_find"), 2)})
    ray = next(r["median_ms"] for r in rows if r["method"] == "raycast")
    for r in rows:
        r["raycast_over_method"] = round(ray / r["median_ms"], 3) if r["median_ms"] else ""
    return rows, commands


def plot():
    rows = common.read_csv(CSV)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    blocks = []
    for m, _ in METHODS:
        blocks.append([(i, next((r["median_ms"] for r in rows
                                 if r["scene"] == s and r["method"] == m), "NaN"))
                       for i, s in enumerate(scenes)])
    data = common.datafile(blocks)
    xtics = ", ".join(f'"{s}" {i}' for i, s in enumerate(scenes))
    series = ", ".join(f"'{data}' index {k} using ($1+{(k - 1.5) * 0.2}):2 with boxes "
                       f"title '{m}'" for k, (m, _) in enumerate(METHODS))
    common.gnuplot(f"""set terminal pngcairo size 1000,520 noenhanced
set output '{os.path.join(HERE, "far_rays.png")}'
set title 'lzb far rays: Embree vs the octree walk, beside raycast and the hybrid (median frame, 2 threads)'
set ylabel 'ms per frame (log)'
set logscale y
set style fill solid 0.8
set boxwidth 0.18
set xtics ({xtics})
set key top left
plot {series}
""")


def main():
    if "--plot-only" not in sys.argv:
        rows, commands = [], []
        for name in SCENES:
            r, c = measure(name)
            rows += r
            commands += c
            common.write_csv(CSV, rows, FIELDS, commands)  # kept after every scene
            print(name, [(x["method"], x["median_ms"], x["correct_rate_covered"]) for x in r],
                  flush=True)
    plot()


if __name__ == "__main__":
    main()
