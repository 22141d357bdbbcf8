#!/usr/bin/env python3
"""--distribute data against replicate: peak memory per rank, load (with the cut), set-up and
median frame of the exact methods on the 9.6 M-triangle landscape
(builtin:landscape?objects=400000, generated twice under data, each rank keeping its share) at
640x480, 6 frames (the first dropped): replicated on 1 rank x 2 threads and 2 x 1, data on 1 x 2,
2 x 1 and 3 x 1 (3 ranks oversubscribe the 2 cores: their times are not speedups).

Usage: python3 runs/distribute/run.py [--quick]   (from the repository root, after
       scripts/build.sh)
Writes runs/distribute/ranks.csv (one row per configuration and rank).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(flags=("--quick",))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
SCENE = "builtin:landscape?objects=4000" if QUICK else "builtin:landscape?objects=400000"
FRAMES = 3 if QUICK else 6
METHODS = ["raycast", "zbuffer"]
CONFIGS = [(1, 2, "replicate"), (2, 1, "replicate"), (1, 2, "data"), (2, 1, "data"),
           (3, 1, "data")]  # ranks, threads, mode


def main():
    rows, commands = [], []
    for method in METHODS:
        for ranks, threads, mode in CONFIGS:
            shown, rep = common.render(
                SCENE, ["--method", method, "--frames", str(FRAMES), "--distribute", mode],
                ranks=ranks, threads=threads)
            commands.append(shown)
            frames = rep["frames"][1:]
            frame_s = common.median(f["seconds"] for f in frames)
            held = {r["rank"]: r["counts"].get("held_triangles", rep["scene"]["triangles_expanded"])
                    for r in rep["setup"]["ranks"]}
            for r in rep["frames"][-1]["ranks"]:
                work = r["counts"].get("rays", r["counts"].get("triangles_drawn", 0))
                rows.append({"method": method, "mode": mode, "ranks": ranks, "threads": threads,
                             "rank": r["rank"], "held_triangles": int(held[r["rank"]]),
                             "peak_mib": round(r["peak_memory_bytes"] / 2**20),
                             "load_s": round(rep["load_seconds"], 2),
                             "setup_s": round(rep["setup_seconds"], 2),
                             "frame_ms": round(1000 * frame_s, 1), "work": int(work)})
            print(f"{method} {ranks}x{threads} {mode}: frame {1000 * frame_s:.1f} ms, peak "
                  f"{[row['peak_mib'] for row in rows[-ranks:]]} MiB", flush=True)
    common.write_csv(os.path.join(HERE, "ranks.csv"), rows,
                     ["method", "mode", "ranks", "threads", "rank", "held_triangles", "peak_mib",
                      "load_s", "setup_s", "frame_ms", "work"], commands)


if __name__ == "__main__":
    main()
