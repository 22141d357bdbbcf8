#!/usr/bin/env python3
"""Bytes per triangle per method: peak resident memory of a 3-frame render (640x480, 2 threads,
one rank) divided by the scene's unique triangles, with the median frame in the same run, on
builtin:landscape and on its export as a binary PLY (each placed mesh's vertices once, as a
scanned mesh or heightfield file holds them). With --before=BIN every row is also run with an
earlier build, alternating with this one, so the lean scene model's gain and its frame-time cost
are measured side by side (A/B).

Usage: python3 runs/memory/run.py [--before=PATH/lzb] [--sizes=40000,400000,2000000]
       [--methods=zbuffer,raycast,lzb,hybrid,rzb] [--big-methods=raycast,hybrid] [--no-wait]
       [--compact]  (each row also with --bvh compact, alternating; writes compact.csv instead)
       [--plot-only]  (redraws memory.png from memory.csv)
       (from the repository root, after scripts/build.sh; sizes are landscape objects: ~1.0 M,
       9.6 M and 48 M unique triangles; the largest size renders only --big-methods and no PLY)
Writes runs/memory/memory.csv and memory.png (bytes per triangle per method and build), or with
--compact runs/memory/compact.csv.
Scratch files (the PLY exports) go to $LZB_SCRATCH or /tmp.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(flags=("--plot-only", "--compact"),
                   valued=("before", "sizes", "methods", "big-methods"))

HERE = os.path.dirname(os.path.abspath(__file__))
BEFORE = (common.option("before", [None]) or [None])[0]
SIZES = [int(s) for s in common.option("sizes", ["40000", "400000", "2000000"])]
METHODS = common.option("methods", ["zbuffer", "raycast", "lzb", "hybrid", "rzb"])
BIG_METHODS = common.option("big-methods", ["raycast", "hybrid"])


COMPACT = "--compact" in sys.argv


def builds():
    """(label, binary, extra arguments) of every build compared: `this` is the tree's own,
    `this compact` it with --bvh compact, `before` --before's."""
    return ([("this", None, [])] + ([("this compact", None, ["--bvh", "compact"])] if COMPACT else [])
            + ([("before", BEFORE, [])] if BEFORE else []))


def measure(scene, label, method, binary, extra, rows, commands):
    shown, rep = common.render(scene, ["--method", method, "--frames", "3", *extra], threads=2,
                               lzb=binary)
    commands.append(shown)
    tris = rep["scene"]["triangles_unique"]
    peak = rep["summary"]["peak_memory_bytes_root"]
    row = {"scene": label, "build": "", "method": method, "unique_triangles": tris,
           "peak_mib": round(peak / 2**20), "bytes_per_triangle": round(peak / tris, 1),
           "median_frame_ms": round(1000 * rep["summary"]["median_frame_seconds"], 2),
           "load_s": round(rep["load_seconds"], 2)}
    rows.append(row)
    return row


def main():
    rows, commands = [], []
    for objects in SIZES:
        big = objects == max(SIZES) and len(SIZES) > 2
        scenes = [(f"landscape {objects}", f"builtin:landscape?objects={objects}")]
        if not big:
            scenes.append((f"ply {objects}", common.landscape_ply(objects)))
        for label, scene in scenes:
            for method in BIG_METHODS if big else METHODS:
                for name, binary, extra in builds():
                    row = measure(scene, label, method, binary, extra, rows, commands)
                    row["build"] = name
                    print(f"{label:>18} {method:>8} {name:>16}: {row['bytes_per_triangle']:7.1f} "
                          f"bytes a triangle, {row['peak_mib']} MiB, frame {row['median_frame_ms']} ms",
                          flush=True)
    common.write_csv(os.path.join(HERE, "compact.csv" if COMPACT else "memory.csv"), rows,
                     ["scene", "build", "method", "unique_triangles", "peak_mib",
                      "bytes_per_triangle", "median_frame_ms", "load_s"], commands)
    if not COMPACT:
        plot(rows)


def plot(rows):
    """Bytes per triangle at the 10^7 PLY (or the largest PLY measured), per method and build."""
    plys = sorted({r["scene"] for r in rows if r["scene"].startswith("ply")},
                  key=lambda s: int(s.split()[1]))
    if not plys:
        return
    scene = plys[-1]
    names = list(dict.fromkeys(r["build"] for r in rows))
    methods = [m for m in METHODS if any(r["method"] == m and r["scene"] == scene for r in rows)]
    data = []
    for i, m in enumerate(methods):
        vals = [next((float(r["bytes_per_triangle"]) for r in rows if r["scene"] == scene and
                      r["method"] == m and r["build"] == n), 0) for n in names]
        data.append([i, *vals])
    cols = ", ".join(f"DATA using {k + 2} title '{n}'" for k, n in enumerate(names))
    datafile = common.datafile([data])
    xtics = ", ".join(f"'{m}' {i}" for i, m in enumerate(methods))
    common.gnuplot(f"""
set terminal pngcairo size 900,500 font ',10'
set output '{os.path.join(HERE, "memory.png")}'
set title 'peak resident bytes per unique triangle: the {scene.split()[1]}-object landscape as a PLY (3 frames, 640x480, 2 threads)'
set yrange [0:*]
set key top left
set style data histograms
set style histogram clustered
set style fill solid 0.8 border -1
set xtics ({xtics})
set ylabel 'bytes per triangle'
set grid y
plot {cols.replace("DATA", f"'{datafile}'")}
""")


if __name__ == "__main__":
    if "--plot-only" in sys.argv:
        plot(common.read_csv(os.path.join(HERE, "memory.csv")))
    else:
        main()
