#!/usr/bin/env python3
"""Embree's leaf layouts against raycast's bytes a triangle: the default (BVH8 with triangle4v
leaves, each triangle's three vertices copied into its leaf, robust Pluecker test) against
leaves that index the shared vertices (triangle4i): RTC_SCENE_FLAG_COMPACT (robust), and the
device configurations tri_accel=bvh8.triangle4i and bvh4.triangle4i (which Embree 3.13 pairs
with its fast Moeller test, not watertight), on the 10^7 landscape and its PLY export. Runs
RaycastBench.LeafLayouts (raycast/exact/raycast_bench_test.cpp): once with every layout built
side by side and their frames interleaved (Embree's own bytes from its memory monitor, the
median trace of 8 frames at 640x480 on 2 threads, the pixels whose ID or depth differ from the
default's), then once a process per layout for the peak resident bytes of the scene plus that
layout.

Usage: python3 runs/memory/leaves.py [--objects=400000] [--no-wait]
       (from the repository root, after scripts/build.sh)
Writes runs/memory/leaves.csv. Scratch files (the PLY export) go to $LZB_SCRATCH or /tmp.
"""
import csv
import io
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(valued=("objects",))

HERE = os.path.dirname(os.path.abspath(__file__))
OBJECTS = int(common.option("objects", ["400000"])[0])
BENCH = os.path.join(os.path.dirname(common.LZB), "raycast", "exact", "raycast_test")
LAYOUTS = ["default", "compact", "tri_accel=bvh8.triangle4i", "tri_accel=bvh4.triangle4i"]


def bench(scene, layouts, commands):
    """The bench's CSV rows for `layouts` built in one process."""
    env = dict(common.ENV, LZB_BENCH="1", LZB_BENCH_SCENE=scene, LZB_BENCH_LAYOUTS=";".join(layouts))
    cmd = [BENCH, "--gtest_filter=RaycastBench.LeafLayouts"]
    common.wait_quiet()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    commands.append(f"LZB_BENCH=1 LZB_BENCH_SCENE='{scene}' LZB_BENCH_LAYOUTS='{';'.join(layouts)}' "
                    + " ".join(cmd).replace(common.ROOT + "/", ""))
    lines = [line for line in out.splitlines() if line.count(",") >= 7]
    return list(csv.DictReader(io.StringIO("\n".join(lines))))


def main():
    rows, commands = [], []
    scenes = [(f"landscape {OBJECTS}", f"builtin:landscape?objects={OBJECTS}"),
              (f"ply {OBJECTS}", common.landscape_ply(OBJECTS))]
    for label, scene in scenes:
        together = bench(scene, LAYOUTS, commands)
        for row in together:
            alone = bench(scene, [row["layout"]], commands)[0]
            row["scene"] = label
            row["process_peak_bytes_per_triangle"] = alone["process_peak_bytes_per_triangle"]
            rows.append(row)
            print(f"{label:>18} {row['layout']:>26}: Embree {row['embree_bytes_per_triangle']} "
                  f"bytes a triangle, process peak {row['process_peak_bytes_per_triangle']}, trace "
                  f"{row['median_trace_ms']} ms, {row['pixels_other_id']} other IDs, "
                  f"{row['pixels_other_depth']} other depths", flush=True)
    common.write_csv(os.path.join(HERE, "leaves.csv"), rows,
                     ["scene", "layout", "unique_triangles", "embree_bytes_per_triangle",
                      "embree_peak_allocated_per_triangle", "process_peak_bytes_per_triangle",
                      "build_s", "median_trace_ms", "pixels_other_id", "pixels_other_depth"],
                     commands)


if __name__ == "__main__":
    main()
