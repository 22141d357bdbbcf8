#!/usr/bin/env python3
"""A TOML scene of two mesh files under --distribute data: builtin:landscape?objects=80000
(1.95 M triangles) exported as a binary PLY and placed twice side by side by a TOML scene (two
[[meshes]] entries, each placed once: 3.9 M triangles). raycast, 640x480, 3 frames: replicated on
1 rank x 2 threads, then in data mode on 4 ranks x 1 thread (oversubscribed) with this build
and, with --before=PATH, an earlier one (9a58c2f and before loaded the TOML scene whole on every
rank, then cut it; e1e78d4 and before kept each file whole, one unit). Per rank: the
triangles held and the peak memory; the load seconds, the median frame, and whether the frames
equal the replicated run's.

Usage: python3 runs/distribute/toml_split.py [--before=PATH/lzb]   (after scripts/build.sh)
Writes runs/distribute/toml_split.csv.
"""
import filecmp
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(valued=("before",))

HERE = os.path.dirname(os.path.abspath(__file__))
TOML = """root = "world"
[[meshes]]
name = "west"
file = "landscape.ply"
[[meshes]]
name = "east"
file = "landscape.ply"
[[nodes]]
name = "world"
instances = [{ node = "west" }, { node = "east", translate = [1300, 0, 0] }]
"""


def main():
    before = common.option("before", [None])[0]
    rows, commands = [], []
    with tempfile.TemporaryDirectory(prefix="lzb-toml-") as work:
        subprocess.run([common.LZB, "export", "builtin:landscape?objects=80000",
                        os.path.join(work, "landscape.ply"), "--quiet"], check=True)
        scene = os.path.join(work, "two.toml")
        with open(scene, "w") as f:
            f.write(TOML)
        runs = [("replicated", common.LZB, 1, 2, [])]
        runs.append(("data", common.LZB, 4, 1, ["--distribute", "data"]))
        if before:
            runs.append(("data, before", before, 4, 1, ["--distribute", "data"]))
        frames = {}
        for name, lzb, ranks, threads, extra in runs:
            keep = os.path.join(work, name.replace(", ", "_"))
            shown, r = common.render(scene, ["--method", "raycast", "--frames", "3", *extra],
                                     ranks=ranks, threads=threads, keep=keep, lzb=lzb)
            commands.append(shown.replace(work + "/", ""))
            frames[name] = os.path.join(keep, "frame_0002.png")
            ranks_ = r["setup"]["ranks"]
            rows.append({
                "run": name, "ranks": ranks, "threads": threads,
                "held_triangles": " ".join(str(int(x["counts"].get("held_triangles",
                                                                   r["scene"]["triangles_expanded"])))
                                           for x in ranks_),
                "peak_mib": " ".join(str(round(x["peak_memory_bytes"] / 2**20)) for x in ranks_),
                "load_s": round(r["load_seconds"], 2),
                "frame_ms": round(1000 * common.median(f["seconds"] for f in r["frames"]), 1),
                "identical": filecmp.cmp(frames["replicated"], frames[name], shallow=False)})
            print(rows[-1], flush=True)
    common.write_csv(os.path.join(HERE, "toml_split.csv"), rows,
                     ["run", "ranks", "threads", "held_triangles", "peak_mib", "load_s",
                      "frame_ms", "identical"], commands)


if __name__ == "__main__":
    main()
