#!/usr/bin/env python3
"""What the hybrid's screen cover (src/hybrid/screen_cover.hpp) saves on a frame cast every
pixel: ScreenCoverBench (src/hybrid/screen_cover_bench_test.cpp) casts each frame of the city's
circle at 1920x1080 without a cover and with one (the walk plus the cast), alternating, on 1 and
2 threads, median of --rounds (default 5), in one process; the two images must match.

Usage: python3 runs/peers/screen_cover.py [--scene=SPEC] [--width=W --height=H --frames=N]
       [--rounds=N]   (about a minute)
Writes runs/peers/screen_cover.csv (rows of other scenes or sizes kept, with their commands):
per frame and thread count the castable rays (raycast's, the
tiles under the scene's box), the cover's rays (-1: the walk gave way, a leaf under every pixel),
the walk's ms, the cast without and with the cover (walk included) and their ratio.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (-h / --help prints this docstring instead of running)

common.accept_args(valued=("scene", "rounds", "width", "height", "frames"))
HERE = os.path.dirname(os.path.abspath(__file__))
BIN = os.path.join(os.path.dirname(common.LZB), "src", "hybrid", "hybrid_test")
SETTINGS = {"LZB_BENCH_SCENE": common.option("scene", ["builtin:city"])[0],
            "LZB_BENCH_WIDTH": common.option("width", ["1920"])[0],
            "LZB_BENCH_HEIGHT": common.option("height", ["1080"])[0],
            "LZB_BENCH_FRAMES": common.option("frames", ["11"])[0],
            "LZB_BENCH_ROUNDS": common.option("rounds", ["5"])[0]}
env = dict(common.ENV, LZB_BENCH="1", **SETTINGS)
common.wait_quiet()
cmd = [BIN, "--gtest_filter=ScreenCoverBench.*"]
out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
lines = [line for line in out.splitlines() if line.count(",") == 10]
header = lines[0].split(",")
rows = [dict(zip(header, line.split(","))) for line in lines[1:]]
settings = " ".join(f"{k}={v}" for k, v in SETTINGS.items())
shown = f"LZB_BENCH=1 {settings} " + " ".join(cmd).replace(common.ROOT + "/", "")
# Rows and commands of other scenes or sizes stay.
VIEW = ("LZB_BENCH_SCENE", "LZB_BENCH_WIDTH", "LZB_BENCH_HEIGHT")
view = " ".join(f"{k}={SETTINGS[k]}" for k in VIEW) + " "
path = os.path.join(HERE, "screen_cover.csv")
kept, commands = common.read_kept(path) if os.path.exists(path) else ([], [])
kept = [r for r in kept
        if (r["scene"], r["width"], r["height"]) != tuple(SETTINGS[k] for k in VIEW)]
commands = [c for c in commands if view not in c]
common.write_csv(path, kept + rows, header, commands + [shown])
for r in rows:
    print(f"frame {r['frame']:>2} threads {r['threads']}: {r['castable_rays']:>8} -> "
          f"{r['cover_rays']:>7} rays, walk {r['walk_ms']} ms, cast {r['cast_ms']} -> "
          f"{r['cover_cast_ms']} ms ({r['speedup']}x)")
