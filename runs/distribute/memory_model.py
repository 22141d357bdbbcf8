#!/usr/bin/env python3
"""The memory model behind --distribute's estimates (src/regions/memory_estimate.cpp): each method's
peak memory on one rank (2 threads, 640x480, 2 frames, replicated) on the landscape at two sizes,
fitted as base + bytes per unique triangle. The estimate's constants are the fitted slopes,
rounded up, and the largest base.

Usage: python3 runs/distribute/memory_model.py   (from the repository root, after
       scripts/build.sh)
Writes runs/distribute/memory_model.csv (one row per method and size, with the fit).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args()

HERE = os.path.dirname(os.path.abspath(__file__))
SIZES = [40000, 160000]  # landscape objects: ~1.0 M and ~3.8 M unique triangles
METHODS = ["zbuffer", "raycast", "lzb", "hybrid", "rzb", "surfels", "sqrt5", "sampletree"]


def main():
    rows, commands = [], []
    for method in METHODS:
        points = []
        for objects in SIZES:
            shown, rep = common.render(f"builtin:landscape?objects={objects}",
                                       ["--method", method, "--frames", "2"], threads=2)
            commands.append(shown)
            tris = rep["scene"]["triangles_unique"]
            peak = max(f["peak_memory_bytes"] for f in rep["frames"])
            points.append((tris, peak))
            rows.append({"method": method, "objects": objects, "unique_triangles": tris,
                         "peak_mib": round(peak / 2**20)})
        (t0, p0), (t1, p1) = points
        slope = (p1 - p0) / (t1 - t0)
        for r in rows[-2:]:
            r["bytes_per_triangle"] = round(slope, 1)
            r["base_mib"] = round((p0 - slope * t0) / 2**20)
        print(f"{method}: {slope:.0f} bytes a triangle + {rows[-1]['base_mib']} MiB", flush=True)
    common.write_csv(os.path.join(HERE, "memory_model.csv"), rows,
                     ["method", "objects", "unique_triangles", "peak_mib", "bytes_per_triangle",
                      "base_mib"], commands)


if __name__ == "__main__":
    main()
