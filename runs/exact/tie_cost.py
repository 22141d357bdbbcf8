#!/usr/bin/env python3
"""What the least-(t, ID) tie order of every Embree query costs: this build against an earlier
one (--before=PATH/lzb, e.g. 80925d6's, which kept whichever equal-t hit Embree met last),
interleaved run by run, one rank, 2 threads, median frame (and `trace` stage: the rays, where the
change lies; the hybrid's frames that cast every pixel) after the first of each run, then the
median over --reps runs (default 5). Scenes: the city at 1920x1080 (raycast and the hybrid), the
forest, the sphereflake, the 10^7 landscape (raycast).

Usage: python3 runs/exact/tie_cost.py --before=PATH/lzb [--reps=N]   (about 4 minutes; 6 at 7 reps)
Writes runs/exact/tie_cost.csv (a row per scene, method and build, every run's frame).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (-h / --help prints this docstring instead of running)

common.accept_args(valued=("before", "reps"))
before = common.option("before", [None])[0]
if not before:
    print("tie_cost.py: --before=PATH/lzb is required (see --help)", file=sys.stderr)
    sys.exit(2)
REPS = int(common.option("reps", ["5"])[0])
HERE = os.path.dirname(os.path.abspath(__file__))
CASES = [
    ("city 1080p", "builtin:city", ["--width", "1920", "--height", "1080", "--frames", "11"],
     "raycast"),
    ("city 1080p", "builtin:city", ["--width", "1920", "--height", "1080", "--frames", "11"],
     "hybrid"),
    ("forest", "builtin:forest", ["--frames", "11"], "raycast"),
    ("sphereflake", "builtin:sphereflake?depth=5", ["--width", "512", "--height", "512",
                                                    "--frames", "6"], "raycast"),
    ("landscape 10^7", "builtin:landscape?objects=400000", ["--frames", "4"], "raycast"),
]

rows, commands = [], []
for name, scene, args, method in CASES:
    runs = {"before": [], "this": []}
    trace = {"before": [], "this": []}
    for _ in range(REPS):
        for build, lzb in (("before", before), ("this", None)):
            shown, rep = common.render(scene, [*args, "--method", method], threads=2, lzb=lzb)
            commands.append(shown)
            later = rep["frames"][1:]
            runs[build].append(1e3 * common.median(f["seconds"] for f in later))
            trace[build].append(1e3 * common.median(f["stages"].get("trace", 0.0) for f in later))
    med = {b: common.median(v) for b, v in runs.items()}
    tr = {b: common.median(v) for b, v in trace.items()}
    for b in ("before", "this"):
        rows.append({"scene": name, "method": method, "build": b, "median_frame_ms": f"{med[b]:.2f}",
                     "median_trace_ms": f"{tr[b]:.2f}",
                     "runs_ms": " ".join(f"{v:.2f}" for v in runs[b]),
                     "trace_runs_ms": " ".join(f"{v:.2f}" for v in trace[b])})
    print(f"{name} {method}: frame before {med['before']:.2f} ms, this {med['this']:.2f} "
          f"({med['this'] / med['before']:.3f}); trace {tr['before']:.2f}, {tr['this']:.2f} "
          f"({tr['this'] / max(tr['before'], 1e-9):.3f})", flush=True)
common.write_csv(os.path.join(HERE, "tie_cost.csv"), rows,
                 ["scene", "method", "build", "median_frame_ms", "median_trace_ms", "runs_ms",
                  "trace_runs_ms"], commands)
