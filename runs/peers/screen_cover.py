#!/usr/bin/env python3
"""What the hybrid's screen cover (src/hybrid/screen_cover.hpp) saves on a frame cast every
pixel: ScreenCoverBench (src/hybrid/screen_cover_bench_test.cpp) casts each frame of the city's
circle at 1920x1080 without a cover and with one (the walk plus the cast), alternating, on 1 and
2 threads, median of --rounds (default 5), in one process; the two images must match.

Usage: python3 runs/peers/screen_cover.py [--scene=SPEC] [--rounds=N]   (about a minute)
Writes runs/peers/screen_cover.csv: per frame and thread count the castable rays (raycast's, the
tiles under the scene's box), the cover's rays (-1: the walk gave way, a leaf under every pixel),
the walk's ms, the cast without and with the cover (walk included) and their ratio.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (-h / --help prints this docstring instead of running)

common.accept_args(valued=("scene", "rounds"))
HERE = os.path.dirname(os.path.abspath(__file__))
BIN = os.path.join(os.path.dirname(common.LZB), "src", "hybrid", "hybrid_test")
env = dict(common.ENV, LZB_BENCH="1", LZB_BENCH_ROUNDS=common.option("rounds", ["5"])[0],
           LZB_BENCH_SCENE=common.option("scene", ["builtin:city"])[0])
common.wait_quiet()
cmd = [BIN, "--gtest_filter=ScreenCoverBench.*"]
out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
lines = [line for line in out.splitlines() if line.count(",") == 10]
header, rows = lines[0].split(","), [dict(zip(lines[0].split(","), line.split(","))) for line in lines[1:]]
shown = (f"LZB_BENCH=1 LZB_BENCH_ROUNDS={env['LZB_BENCH_ROUNDS']} LZB_BENCH_SCENE={env['LZB_BENCH_SCENE']} "
         + " ".join(cmd).replace(common.ROOT + "/", ""))
common.write_csv(os.path.join(HERE, "screen_cover.csv"), rows, header, [shown])
for r in rows:
    print(f"frame {r['frame']:>2} threads {r['threads']}: {r['castable_rays']:>8} -> {r['cover_rays']:>7} rays, "
          f"walk {r['walk_ms']} ms, cast {r['cast_ms']} -> {r['cover_cast_ms']} ms ({r['speedup']}x)")
