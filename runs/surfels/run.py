#!/usr/bin/env python3
"""The surfel study (Tobor et al., Rendering by surfels): polygons against surfels on the paper's
sphereflake (depth 3-5) and on a field of scanned-mesh instances, at 512x512.

Along the same camera path, one scene at a time and in one run: the exact ray caster (raycast,
judged against zbuffer), the z-buffer (zbuffer, judged against raycast) and --method surfels with
levels of detail up to 128^3 and up to 256^3 cells, sprites of at most 1, 2 and 4 pixels (the
paper's figures 7-10), every level built before the first frame (--surfel-build setup) so that the
set-up time is the preprocessing. Each row: the median frame time (frames after the first), the
correct rate over covered pixels against the exact reference (minimum and median over frames),
the surfels drawn, the placements drawn as polygons and as surfels (the per-object switch keeps
objects whose cells would open holes as polygons) and the surfel placements per grid and sprite, the set-up (surfelization) time, the surfels
cached and their bytes.

Usage: python3 runs/surfels/run.py [--quick] [--plot-only] [--scenes=a,b] [--configs=a,b] [--no-wait]
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh;
       plots need gnuplot: bash scripts/install-deps.sh --bench)
Writes runs/surfels/surfels.csv and surfels.png; --quick (2 frames at 128x128, no waiting for a
quiet machine: a check that the script works, not a measurement) writes quick.csv and quick.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"), valued=("scenes", "configs"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
NAME = "quick" if QUICK else "surfels"
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
SIZE = 128 if QUICK else 512
# name: (scene, frames, zbuffer frames)
SCENES = {
    "sphereflake3": ("builtin:sphereflake?depth=3", 20, 20),
    "sphereflake4": ("builtin:sphereflake?depth=4", 20, 20),
    "sphereflake5": ("builtin:sphereflake?depth=5", 20, 10),
    "field": (f"builtin:replicated?mesh={ARMADILLO}&k=40&levels=1", 10, 3),
}
GRIDS = (128, 256)
SPRITES = (1, 2, 4)


def levels_up_to(grid):
    """The levels of detail 1, 2, 4, ... up to grid (the paper keeps several per object)."""
    return ",".join(str(1 << k) for k in range(grid.bit_length()))


# label: (method arguments, reference)
CONFIGS = {"raycast": (["--method", "raycast"], "zbuffer"),
           "zbuffer": (["--method", "zbuffer"], "raycast")}
for g in GRIDS:
    for d in SPRITES:
        CONFIGS[f"surfels_g{g}_d{d}"] = (["--method", "surfels", "--surfel-grids", levels_up_to(g),
                                          "--splat", str(d), "--surfel-build", "setup"], "raycast")

FIELDS = ["scene", "triangles", "width", "height", "config", "frames", "median_frame_s",
          "reference", "correct_rate_covered", "median_correct_rate_covered",
          "median_exact_id_rate_covered", "psnr_aa", "surfels_drawn", "placements_polygons",
          "placements_surfels", "grid_placements", "sprite_placements", "setup_s", "surfelize_s", "surfels_cached", "bytes_per_surfel",
          "collector_bytes_per_surfel", "peak_memory_bytes"]


def histogram(counts):
    """{"128": 5, "256": 6} as '128:5 256:6' (one CSV field)."""
    return " ".join(f"{k}:{int(v)}" for k, v in sorted(counts.items(), key=lambda kv: int(kv[0])))


def row_of(name, scene, label, n, reference, rep):
    fr = rep["frames"][1:] or rep["frames"]
    acc = [f["accuracy"] for f in fr if "accuracy" in f]
    counts = lambda k: common.median(f["counts"].get(k, 0.0) for f in fr)  # noqa: E731
    setup = rep.get("setup", {})
    row = {"scene": name, "triangles": rep["scene"]["triangles_expanded"], "width": SIZE,
           "height": SIZE, "config": label, "frames": n, "reference": reference,
           "median_frame_s": common.median(f["seconds"] for f in fr),
           "correct_rate_covered": min((a["correct_rate_covered"] for a in acc), default=""),
           "median_correct_rate_covered": common.median(a["correct_rate_covered"] for a in acc) if acc else "",
           "median_exact_id_rate_covered": common.median(a["exact_id_rate_covered"] for a in acc) if acc else "",
           "psnr_aa": common.median(a["psnr_aa"] or 99.0 for a in acc) if acc else "",
           "setup_s": rep["setup_seconds"], "peak_memory_bytes": rep["summary"]["peak_memory_bytes_root"]}
    if label.startswith("surfels"):
        row.update({"surfels_drawn": counts("surfels_drawn"),
                    "placements_polygons": counts("placements_polygons"),
                    "placements_surfels": counts("placements_surfels"),
                    # placements per grid and per sprite size on the first measured frame
                    "grid_placements": histogram(fr[0]["counts"].get("grid_placements", {})),
                    "sprite_placements": histogram(fr[0]["counts"].get("sprite_placements", {})),
                    "surfelize_s": setup.get("stages", {}).get("surfelize", ""),
                    "surfels_cached": setup.get("counts", {}).get("surfels_cached", ""),
                    "bytes_per_surfel": setup.get("counts", {}).get("bytes_per_surfel", ""),
                    "collector_bytes_per_surfel": setup.get("counts", {}).get("collector_bytes_per_surfel", "")})
    return row


def run():
    rows, commands = [], []
    for name in common.option("scenes", list(SCENES)):
        scene, frames, zframes = SCENES[name]
        if QUICK:
            frames, zframes = 2, 2
        for label in common.option("configs", list(CONFIGS)):
            method_args, reference = CONFIGS[label]
            n = zframes if label == "zbuffer" else frames
            args = [*method_args, "--frames", str(n), "--width", str(SIZE), "--height", str(SIZE),
                    "--reference", reference]
            shown, rep = common.render(scene, args, threads=common.CORES,
                                       quiet_wait=not QUICK and "--no-wait" not in sys.argv)
            commands.append(shown)
            row = row_of(name, scene, label, n, reference, rep)
            rows.append(row)
            print(f"{name} {label:16s}: {row['median_frame_s'] * 1e3:9.1f} ms, correct (covered, min) "
                  f"{row['correct_rate_covered']}, set-up {row['setup_s']:.2f} s", flush=True)
            common.write_csv(os.path.join(HERE, f"{NAME}.csv"), rows, FIELDS, commands)


def plot():
    rows = common.read_csv(os.path.join(HERE, f"{NAME}.csv"))
    scenes = [s for s in SCENES if any(r["scene"] == s for r in rows)]
    configs = [c for c in CONFIGS if any(r["config"] == c for r in rows)]

    def value(s, c, key, scale=1.0):
        for r in rows:
            if r["scene"] == s and r["config"] == c and r[key] not in ("", None):
                return float(r[key]) * scale
        return "NaN"
    blocks = [[(i, value(s, c, "median_frame_s", 1e3), value(s, c, "median_correct_rate_covered", 100),
                value(s, c, "setup_s")) for i, s in enumerate(scenes)] for c in configs]
    data = common.datafile(blocks)
    xtics = ", ".join(f"'{s}' {i}" for i, s in enumerate(scenes))

    def lines(col):
        return ", ".join(f"'{data}' index {k} using ($1+{(k - len(configs) / 2) * 0.08}):{col} "
                         f"with points pt {4 + k} ps 1.5 title '{c}'" for k, c in enumerate(configs))
    common.gnuplot(f"""
set terminal pngcairo size 1400,1200 font ',10' noenhanced
set output '{os.path.join(HERE, f"{NAME}.png")}'
set multiplot layout 3,1 title 'Polygons vs surfels at {SIZE}x{SIZE} (median over frames; {common.CORES} cores)'
set xtics ({xtics})
set xrange [-0.5:{len(scenes) - 0.5}]
set grid
set key outside right
set logscale y
set ylabel 'frame time (ms, log)'
plot {lines(2)}
unset logscale y
set ylabel 'correct pixels, covered (%)'
plot {lines(3)}
set logscale y
set ylabel 'set-up (s, log; surfels: surfelization)'
plot {lines(4)}
unset multiplot
""")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
