#!/usr/bin/env python3
"""Tile dealing for the far rays: interleaved (tile mod ranks) against by cost (contiguous runs of
equal ray count, --tile-deal cost), for lzb and the hybrid on the city at 640x480 and 1920x1080.
Per configuration: the median frame time (frames after the first), the slowest rank's and the
mean rank's pvl_find (the ray stage the deal splits), the rays each rank cast, and the idle time
of the others (wait). 1 x 1 is the base; 3 ranks oversubscribe this 2-core machine (marked).

Usage: python3 runs/speedup/tiles.py [--quick] [--plot-only]   (from the repository root, after
       scripts/build.sh; the plot needs gnuplot)
Writes runs/speedup/tiles.csv and tiles.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
FRAMES = 4 if QUICK else 11
SIZES = [(640, 480)] if QUICK else [(640, 480), (1920, 1080)]
METHODS = ["hybrid", "lzb"]
# (ranks, deal): the base, then both deals at 2 and 3 ranks.
CONFIGS = [(1, "interleaved"), (2, "interleaved"), (2, "cost"), (3, "interleaved"), (3, "cost")]
FIELDS = ["width", "height", "method", "ranks", "deal", "oversubscribed", "frame_s", "speedup",
          "pvl_find_max_s", "pvl_find_mean_s", "wait_s", "rays_min", "rays_max"]


def measure(frames):
    """Medians over frames: frame time, the ray stage's slowest and mean rank, the wait, the
    fewest and most rays a rank cast."""
    def per_rank(f, key, where="stages"):
        return [r[where].get(key, 0.0) for r in f["ranks"]]
    finds = [per_rank(f, "pvl_find") for f in frames]
    rays = [per_rank(f, "rays_cast", "counts") for f in frames]
    return {"frame_s": common.median(f["seconds"] for f in frames),
            "pvl_find_max_s": common.median(max(v) for v in finds),
            "pvl_find_mean_s": common.median(sum(v) / len(v) for v in finds),
            "wait_s": common.median(f["stages"].get("wait", 0.0) for f in frames),
            "rays_min": common.median(min(v) for v in rays),
            "rays_max": common.median(max(v) for v in rays)}


def run():
    rows, commands = [], []
    for (w, h) in SIZES:
        for method in METHODS:
            base = None
            for ranks, deal in CONFIGS:
                shown, rep = common.render(
                    "builtin:city", ["--method", method, "--tile-deal", deal, "--frames",
                                     str(FRAMES), "--width", str(w), "--height", str(h)],
                    ranks=ranks, threads=1)
                commands.append(shown)
                m = measure(rep["frames"][1:] or rep["frames"])
                base = base or m["frame_s"]
                rows.append({"width": w, "height": h, "method": method, "ranks": ranks,
                             "deal": deal, "oversubscribed": int(ranks > common.CORES), **m,
                             "speedup": base / m["frame_s"]})
                print(f"{w}x{h} {method:6s} {ranks} ranks {deal:11s}: {m['frame_s'] * 1e3:7.1f} ms "
                      f"(x{base / m['frame_s']:.2f}); pvl_find max {m['pvl_find_max_s'] * 1e3:.1f} "
                      f"mean {m['pvl_find_mean_s'] * 1e3:.1f} ms, wait {m['wait_s'] * 1e3:.1f} ms, "
                      f"rays {m['rays_min']:.0f}..{m['rays_max']:.0f}", flush=True)
                common.write_csv(os.path.join(HERE, "tiles.csv"), rows, FIELDS, commands)


def plot():
    rows = common.read_csv(os.path.join(HERE, "tiles.csv"))
    labels, blocks = [], []
    for r in rows:
        if int(r["ranks"]) == 1:
            continue
        labels.append(f"{r['method']} {r['width']}p {r['ranks']}r{'*' if int(r['oversubscribed']) else ''} "
                      f"{r['deal']}")
        blocks.append((len(labels) - 1, float(r["pvl_find_mean_s"]) * 1e3,
                       (float(r["pvl_find_max_s"]) - float(r["pvl_find_mean_s"])) * 1e3,
                       float(r["frame_s"]) * 1e3))
    common.stacked_bars(
        os.path.join(HERE, "tiles.png"),
        "far-ray tiles dealt interleaved or by cost: the ray stage (mean rank + excess of the "
        "slowest) and the frame (ms, medians; * oversubscribed)", labels, blocks,
        "'DATA' using 2 title 'pvl find, mean rank', '' using 3 title 'pvl find, slowest rank "
        "beyond the mean', '' using 0:4 with points pt 7 ps 1.5 title 'frame'", size="1400,600")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
