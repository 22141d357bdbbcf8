#!/usr/bin/env python3
"""The sqrt(5) sampling study (Stamminger & Drettakis, Interactive sampling and rendering for
complex and procedural geometry), in four parts, each a list of rows of one CSV:

- terrain: builtin:terrain from its own camera (one frame) along the ground to the horizon,
  --horizon on against off: initial
  samples, samples culled by the horizon (and by its first, largest-height test), samples
  generated and drawn, frame time; the images are the same (tested in sqrt5_test).
- generation: the displaced plane (runs/sqrt5/displaced_walk.toml: a camera moving a little per
  frame) at the A'min that makes about 3.3 M samples per frame (the paper's figure), samples
  generated per second of the sampling stage (--sqrt5-cache-mb 0: every sample evaluated each
  frame), and with the forest cache (frames after the first).
- amin: the displaced plane and sphere, frame time and accuracy against raycast for --amin from
  1/4 to 8 pixels.
- forest: builtin:halton-forest (mesh objects by Halton prefixes) against raycast and rzb.

Usage: python3 runs/sqrt5/run.py [--quick] [--plot-only] [--no-wait]
       (from the repository root, after scripts/build.sh; plots need gnuplot)
Writes runs/sqrt5/sqrt5.csv and sqrt5.png; --quick (2 frames at 128x96, no waiting for a quiet
machine: a check that the script works, not a measurement) writes quick.csv and quick.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
NAME = "quick" if QUICK else "sqrt5"
W, H = (128, 96) if QUICK else (640, 480)
FRAMES = 2 if QUICK else 6
TESS = "&tess=128" if QUICK else ""
# The moving camera of displaced_walk.toml at this A'min evaluates about 10.8 M samples a frame at
# 640x480 (measured; the amin part's plane at 0.25, about 3.1 M, is nearer the paper's 3.3 M).
GEN_AMIN = "0.25" if QUICK else "0.075"
AMINS = ["0.25", "1", "4"] if QUICK else ["0.25", "0.5", "1", "2", "4", "8"]

FIELDS = ["part", "scene", "config", "amin", "width", "height", "frames", "median_frame_s",
          "median_sample_s", "samples_initial", "samples_generated", "samples_refined",
          "samples_drawn", "samples_culled_horizon", "samples_culled_horizon_at_top",
          "halton_samples_drawn", "cache_hits", "cache_bytes", "samples_per_s",
          "median_correct_rate_covered", "min_correct_rate_covered", "psnr_aa"]


def measured(rep):
    """Frames after the first (the first builds caches), or all when there is one."""
    return rep["frames"][1:] or rep["frames"]


def row_of(part, scene, config, amin, rep):
    fr = measured(rep)
    c = lambda k: common.median(f["counts"].get(k, 0.0) for f in fr)  # noqa: E731
    acc = [f["accuracy"] for f in fr if "accuracy" in f]
    sample_s = common.median(f["stages"].get("sample", 0.0) for f in fr)
    row = {"part": part, "scene": scene, "config": config, "amin": amin, "width": W, "height": H,
           "frames": len(rep["frames"]),
           "median_frame_s": common.median(f["seconds"] for f in fr), "median_sample_s": sample_s}
    for k in ("samples_initial", "samples_generated", "samples_refined", "samples_drawn",
              "samples_culled_horizon", "samples_culled_horizon_at_top", "halton_samples_drawn",
              "cache_hits", "cache_bytes"):
        row[k] = c(k)
    row["samples_per_s"] = row["samples_generated"] / sample_s if sample_s > 0 else ""
    if acc:
        row["median_correct_rate_covered"] = common.median(a["correct_rate_covered"] for a in acc)
        row["min_correct_rate_covered"] = min(a["correct_rate_covered"] for a in acc)
        row["psnr_aa"] = common.median(a["psnr_aa"] or 99.0 for a in acc)
    return row


def jobs():
    """(part, scene, config, amin, arguments) of every run."""
    terrain = f"builtin:terrain?{TESS[1:]}" if TESS else "builtin:terrain"
    plane = f"builtin:displaced?{TESS[1:]}" if TESS else "builtin:displaced"
    sphere = f"builtin:displaced?shape=sphere{TESS}"
    forest = "builtin:halton-forest?trees=16" if QUICK else "builtin:halton-forest"
    for h in ("on", "off"):
        yield "terrain", terrain, f"horizon_{h}", "0.5", ["--method", "sqrt5", "--horizon", h]
    walk = os.path.join(HERE, "displaced_walk.toml")  # a camera moving a little per frame
    yield "generation", walk, "no_cache", GEN_AMIN, ["--method", "sqrt5", "--amin", GEN_AMIN,
                                                     "--sqrt5-cache-mb", "0"]
    yield "generation", walk, "cache", GEN_AMIN, ["--method", "sqrt5", "--amin", GEN_AMIN,
                                                  "--sqrt5-cache-mb", "4096"]
    for scene in (plane, sphere):
        for a in AMINS:
            yield "amin", scene, "sqrt5", a, ["--method", "sqrt5", "--amin", a, "--reference", "raycast"]
        # the exact peer on the tessellated surface, in the same run
        yield "amin", scene, "raycast", "", ["--method", "raycast", "--reference", "zbuffer"]
    for m, ref in (("sqrt5", "raycast"), ("raycast", "zbuffer"), ("rzb", "raycast")):
        yield "forest", forest, m, "0.5" if m == "sqrt5" else "", ["--method", m, "--reference", ref]


def run():
    rows, commands = [], []
    for part, scene, config, amin, args in jobs():
        # the terrain from its own camera along the ground (a path would circle above it)
        frames = 1 if part == "terrain" else FRAMES
        shown, rep = common.render(scene, [*args, "--frames", str(frames), "--width", str(W),
                                           "--height", str(H)],
                                   threads=common.CORES,
                                   quiet_wait=not QUICK and "--no-wait" not in sys.argv)
        commands.append(shown)
        row = row_of(part, scene, config, amin, rep)
        rows.append(row)
        print(f"{part:10s} {os.path.basename(scene):40s} {config:10s} amin {amin:5s}: "
              f"{row['median_frame_s'] * 1e3:8.1f} ms, generated {row['samples_generated']:.0f}, "
              f"drawn {row['samples_drawn'] + row['halton_samples_drawn']:.0f}, culled "
              f"{row['samples_culled_horizon']:.0f}, correct {row.get('median_correct_rate_covered', '')}",
              flush=True)
        common.write_csv(os.path.join(HERE, f"{NAME}.csv"), rows, FIELDS, commands)


def plot():
    rows = common.read_csv(os.path.join(HERE, f"{NAME}.csv"))
    amin = [r for r in rows if r["part"] == "amin" and r["config"] == "sqrt5"]
    scenes = sorted({r["scene"] for r in amin})
    blocks = [[(float(r["amin"]), float(r["median_frame_s"]) * 1e3,
                100 * float(r["median_correct_rate_covered"] or "nan"))
               for r in amin if r["scene"] == s] for s in scenes]
    # raycast on the same tessellated scene: a level line across the A'min axis
    peer = {r["scene"]: float(r["median_frame_s"]) * 1e3 for r in rows
            if r["part"] == "amin" and r["config"] == "raycast"}
    peers = [s for s in scenes if s in peer]
    xs = [float(r["amin"]) for r in amin]
    blocks += [[(x, peer[s], float("nan")) for x in (min(xs), max(xs))] for s in peers]
    data = common.datafile(blocks)
    titles = [s.replace("builtin:", "") for s in scenes]

    def lines(col):
        drawn = [f"'{data}' index {k} using 1:{col} with linespoints pt {4 + k} title '{t}'"
                 for k, t in enumerate(titles)]
        if col == 2:
            drawn += [f"'{data}' index {len(scenes) + k} using 1:2 with lines dt 2 lw 2 "
                      f"title 'raycast, {s.replace('builtin:', '')}'" for k, s in enumerate(peers)]
        return ", ".join(drawn)
    common.gnuplot(f"""
set terminal pngcairo size 1000,800 font ',10' noenhanced
set output '{os.path.join(HERE, f"{NAME}.png")}'
set multiplot layout 2,1 title "sqrt5 against A'min at {W}x{H} (median over frames; {common.CORES} cores)"
set logscale x 2
set grid
set key outside right
set xlabel "A'min (pixels)"
set logscale y
set ylabel 'frame time (ms, log)'
plot {lines(2)}
unset logscale y
set ylabel 'correct pixels, covered (%)'
plot {lines(3)}
unset multiplot
""")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
