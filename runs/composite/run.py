#!/usr/bin/env python3
"""Compositing benchmark in the style of IceT's SimpleTiming: per rank and frame, render,
composite, bytes sent and frame time, for every compositing strategy, at 640x480, 1920x1080 and
4096x2160, on 1-4 ranks (3 and 4 oversubscribe this 2-core machine: marked), with the hybrid
method on the city (2.1 M triangles), 12 frames along the default path, the first two dropped
(warm-up). The memory-copy rate is measured in the same run.

Usage: python3 runs/composite/run.py [--quick] [--plot-only]   (from the repository root, after
       scripts/build.sh; plots need gnuplot: bash scripts/install-deps.sh --bench)
Writes runs/composite/ranks.csv (one row per rank and frame), summary.csv (medians per
configuration) and composite.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
SCENE = "builtin:city"
METHOD = "hybrid"
FRAMES = 4 if QUICK else 12
# Frames measured from this one on: the first ones fault the heap's pages in as it grows to its
# steady size (frame 1 of a 2-rank 1080p run: ~3000 page faults, a 25-46 ms composite).
WARMUP = 2
SIZES = [(640, 480), (1920, 1080)] if QUICK else [(640, 480), (1920, 1080), (4096, 2160)]
RANKS = [1, 2] if QUICK else [1, 2, 3, 4]
STRATEGIES = ["reduce", "bswap", "direct", "tiles"]


def run():
    rank_rows, summary, commands = [], [], []
    copy_rate = common.memcpy_rate()
    print(f"memory copy: {copy_rate / 1e9:.1f} GB/s", flush=True)
    for (w, h) in SIZES:
        for ranks in RANKS:
            for strategy in STRATEGIES if ranks > 1 else ["reduce"]:
                shown, rep = common.render(
                    SCENE, ["--method", METHOD, "--composite", strategy, "--frames", str(FRAMES),
                            "--width", str(w), "--height", str(h)],
                    ranks=ranks, threads=max(1, common.CORES // ranks))
                commands.append(shown)
                frames = rep["frames"][WARMUP:]
                for f in frames:
                    for r in f["ranks"]:
                        stages = r["stages"]
                        rank_rows.append({
                            "width": w, "height": h, "ranks": ranks, "strategy": strategy,
                            "frame": f["frame"], "rank": r["rank"],
                            "render_s": sum(v for k, v in stages.items() if k not in common.AFTER_RENDER),
                            "wait_s": stages.get("wait", 0.0),
                            "composite_s": stages.get("composite", 0.0),
                            "bytes_sent": r.get("bytes_sent", 0.0),
                            "frame_s": f["seconds"],
                            "oversubscribed": int(ranks > common.CORES)})
                frame_s = common.median(f["seconds"] for f in frames)
                composite_s = common.median(f["stages"].get("composite", 0.0) for f in frames)
                wait_s = common.median(f["stages"].get("wait", 0.0) for f in frames)
                sent = common.median(f["bytes_sent"] for f in frames)
                row = {"width": w, "height": h, "ranks": ranks, "strategy": strategy,
                       "threads_per_rank": max(1, common.CORES // ranks),
                       "oversubscribed": int(ranks > common.CORES),
                       "frame_s": frame_s, "wait_s": wait_s, "composite_s": composite_s,
                       "composite_share": composite_s / frame_s if frame_s > 0 else 0.0,
                       "bytes_sent_per_frame": sent,
                       "composite_gb_per_s": sent / composite_s / 1e9 if composite_s > 0 else 0.0,
                       "memcpy_gb_per_s": copy_rate / 1e9}
                summary.append(row)
                print(f"{w}x{h} {ranks} ranks {strategy:7s}: frame {frame_s * 1e3:7.1f} ms, "
                      f"wait {wait_s * 1e3:6.2f} ms, composite {composite_s * 1e3:6.2f} ms ({row['composite_share'] * 100:4.1f} %), "
                      f"{sent / 1e6:6.2f} MB sent", flush=True)
    common.write_csv(os.path.join(HERE, "ranks.csv"), rank_rows,
                     ["width", "height", "ranks", "strategy", "frame", "rank", "render_s",
                      "wait_s", "composite_s", "bytes_sent", "frame_s", "oversubscribed"], commands)
    common.write_csv(os.path.join(HERE, "summary.csv"), summary,
                     ["width", "height", "ranks", "strategy", "threads_per_rank", "oversubscribed",
                      "frame_s", "wait_s", "composite_s", "composite_share", "bytes_sent_per_frame",
                      "composite_gb_per_s", "memcpy_gb_per_s"], commands)


def plot():
    rows = common.read_csv(os.path.join(HERE, "summary.csv"))
    sizes = sorted({(int(r["width"]), int(r["height"])) for r in rows})
    panels = []
    for (w, h) in sizes:
        blocks = []
        for s in STRATEGIES:
            blocks.append([(int(r["ranks"]), float(r["composite_share"]) * 100) for r in rows
                           if int(r["width"]) == w and r["strategy"] == s and int(r["ranks"]) > 1])
        data = common.datafile(blocks)
        lines = ", ".join(f"'{data}' index {i} with linespoints title '{s}'" for i, s in enumerate(STRATEGIES))
        panels.append(f"set title '{w}x{h}'\nplot {lines}\n")
    common.gnuplot(f"""
set terminal pngcairo size 1500,450 font ',10'
set output '{os.path.join(HERE, "composite.png")}'
set multiplot layout 1,{len(sizes)} title 'Compositing share of a hybrid frame (city 2.1 M triangles; 3-4 ranks oversubscribe 2 cores)'
set xlabel 'ranks'
set ylabel 'composite / frame time (%)'
set xtics 1
set key top left
set grid
{''.join(panels)}
unset multiplot
""")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
