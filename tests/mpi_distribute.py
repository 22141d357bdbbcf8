#!/usr/bin/env python3
"""--distribute data: the scene cut into regions, each rank holding only its own.

The exact methods (zbuffer, raycast) render each scene 2 frames at 160x120 replicated on 1 rank,
then in data mode on 1, 2 and 3 ranks with 2 regions (fewer than 3 ranks: a rank holds nothing)
and 7 (more than the ranks), one `lzb batch` launch per rank count. Every data-mode file must
equal the replicated run's, byte for byte (no seam where a region plane cuts a mesh, no surface
of one rank showing through another's). The other methods render each region apart: their files
on 2 and 3 ranks must equal the 1-rank data-mode run's with the same regions. Every report must
prove the scene was split: the ranks' held triangles sum to the scene's, each region held once, a
rank with a share draws only from it (the zbuffer's triangles drawn per rank sum to the
replicated count) and, with 7 regions, every rank holds some. With 2 frame groups of 3 ranks,
each group holds the whole scene. The hybrid's probe (whether to cast every pixel) must give the
same choice and counts on every rank count.
The two binary PLY files (the city exported, and a terrain far from the origin that the loader
stores recentred) are read in slices, each rank reading only its slice of the file (its reported
bytes); the landscape and the bunny (a scan's OFF) are streamed, each rank keeping only its
triangles; the city generated is loaded whole and cut, and so is a TOML scene placing two mesh
files, each cut into its triangles (with 7 regions every rank must hold some). A procedural
terrain is cut into its triangles too (every rank holds some), except for sqrt5, which samples
the object's definition and so gets it whole on one rank.

usage: mpi_distribute.py LZB MPIEXEC WORK [DATA]
"""
import filecmp
import json
import math
import os
import shlex
import shutil
import struct
import subprocess
import sys

EXACT = ["zbuffer", "raycast"]
APPROXIMATE = ["lzb", "hybrid", "rzb", "surfels", "sqrt5", "sampletree"]
# Coarse surfel grids: surfelizing at the default resolution is most of a small run's time.
OWN = {"surfels": ["--surfel-grids", "1,2,4,8,16,32"]}
SCENES = ["builtin:city?blocks=3", "builtin:landscape", "builtin:sphereflake?depth=2"]
TERRAIN = "builtin:terrain?tess=48"  # procedural: 4,608 triangles
RANKS = [1, 2, 3]
REGIONS = [2, 7]
FILES = ["frame_0000.png", "frame_0000.exr", "frame_0001.png", "frame_0001.exr"]
COMMON = ["--frames", "2", "--width", "160", "--height", "120", "--threads", "1", "--quiet"]


def far_terrain(path, n=24, offset=1.0e6):
    """A binary PLY height field of 2 (n-1)^2 triangles around (offset, offset, 0)."""
    verts = [(offset + i, offset + j, 2.0 * math.sin(0.5 * i) * math.cos(0.4 * j))
             for j in range(n) for i in range(n)]
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            faces += [(a, b, c), (a, c, d)]
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(verts)}\n"
                 "property double x\nproperty double y\nproperty double z\n"
                 f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
                 "end_header\n").encode())
        for v in verts:
            f.write(struct.pack("<3d", *v))
        for t in faces:
            f.write(struct.pack("<B3i", 3, *t))


def make_files(lzb, work):
    """The PLY scenes and a TOML scene placing two of them, written into work."""
    city = os.path.join(work, "city.ply")
    subprocess.run([lzb, "export", "builtin:city?blocks=2", city, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    far_terrain(os.path.join(work, "far.ply"))
    far_terrain(os.path.join(work, "ground.ply"), offset=-12.0)
    with open(os.path.join(work, "two.toml"), "w") as f:
        f.write('root = "world"\n[[meshes]]\nname = "city"\nfile = "city.ply"\n'
                '[[meshes]]\nname = "ground"\nfile = "ground.ply"\n'
                '[[nodes]]\nname = "world"\ninstances = [{ node = "city" }, '
                '{ node = "ground", translate = [0, -3, 0], scale = 8 }]\n')


def scenes(work, data, method):
    """The exact methods' scenes; the others leave out the far terrain (the sample tree refuses
    it), the TOML scene (cut as the city is) and the bunny (streamed as the PLY files are), and
    all but sqrt5 the procedural terrain (cut as the city is). A scene's index is the same for
    every method (the approximate runs are checked against raycast's of the same index)."""
    files = [os.path.join(work, "city.ply")]
    if method not in EXACT:
        return SCENES + files + ([TERRAIN] if method == "sqrt5" else [])
    bunny = os.path.join(data, "bunny00.off") if data else ""
    return SCENES + files + [TERRAIN, os.path.join(work, "far.ply"),
                             os.path.join(work, "two.toml")] + (
        [bunny] if bunny and os.path.exists(bunny) and os.path.getsize(bunny) else [])


def runs(work, data):
    """(name, ranks, words) of every render: the ones compared against on 1 rank (replicated for
    an exact method, else data mode with the same regions)."""
    out = []
    for method in EXACT + APPROXIMATE:
        for i, scene in enumerate(scenes(work, data, method)):
            base = [scene, "--method", method, *COMMON, *OWN.get(method, [])]
            if method in EXACT:
                out.append((f"{method}_{i}_replicate", 1, base))
            else:
                out.append((f"{method}_{i}_regions_5", 1,
                            base + ["--distribute", "data", "--regions", "5"]))
            for ranks in RANKS:
                for regions in REGIONS:
                    out.append((f"{method}_{i}_data_{ranks}_{regions}_1", ranks,
                                base + ["--distribute", "data", "--regions", str(regions)]))
            # 2 frame groups of 3 ranks: each group holds the whole scene among its members.
            out.append((f"{method}_{i}_data_3_5_2", 3,
                        base + ["--distribute", "data", "--regions", "5", "--frame-groups", "2"]))
    return out


def render(lzb, mpiexec, work, data):
    for ranks in RANKS:
        lines = [shlex.join(words + ["--out", os.path.join(work, name)])
                 for name, r, words in runs(work, data) if r == ranks]
        batch = os.path.join(work, f"ranks{ranks}.batch")
        with open(batch, "w") as f:
            f.write("\n".join(lines) + "\n")
        launch = [mpiexec, "-n", str(ranks), "--oversubscribe"] if ranks > 1 else []
        subprocess.run(launch + [lzb, "batch", batch, "--quiet"], check=True,
                       stdout=subprocess.DEVNULL)


def held(rep):
    return [r["counts"]["held_triangles"] for r in rep["setup"]["ranks"]]


def prefix_of(name):
    """method_scene of a data-mode run's name."""
    return name.rsplit("_", 4)[0]


def same_as(name):
    """The 1-rank run whose files `name` must equal."""
    prefix, _, _, regions, groups = name.rsplit("_", 4)
    if prefix.split("_")[0] in EXACT:
        return prefix + "_replicate"
    return f"{prefix}_regions_{regions}" if groups != "1" else f"{prefix}_data_1_{regions}_1"


def check_run(lzb, work, name, replicated):
    for f in FILES:
        assert filecmp.cmp(os.path.join(work, replicated, f), os.path.join(work, name, f),
                           shallow=False), (f, "differs from", replicated)
    one = json.load(open(os.path.join(work, replicated, "report.json")))
    rep = json.load(open(os.path.join(work, name, "report.json")))
    regions, groups = (int(w) for w in name.rsplit("_", 2)[1:])
    shares = held(rep)
    assert sum(shares) == groups * one["scene"]["triangles_expanded"], ("held", shares)
    regions_held = [r["counts"]["held_regions"] for r in rep["setup"]["ranks"]]
    assert sum(regions_held) == groups * regions, ("regions held", regions_held)
    whole_object = prefix_of(name).startswith("sqrt5") and rep["scene"]["source"] == TERRAIN
    if whole_object:
        # sqrt5 samples the terrain's definition: the object stays one unit, on one rank a group.
        total = one["scene"]["triangles_expanded"]
        assert all(s in (0, total) for s in shares), ("the terrain cut for sqrt5", shares)
    elif regions >= rep["ranks"]:
        assert all(s > 0 for s in shares), ("a rank holds nothing", shares)
    if rep["scene"]["source"].endswith(".ply"):
        # A binary PLY of triangles is read in slices: each rank reads its group's share of the
        # file and the header, never the whole file (src/regions/sliced_share.hpp).
        size = os.path.getsize(rep["scene"]["source"])
        reads = [r["counts"]["bytes_read"] for r in rep["setup"]["ranks"]]
        limit = size / (rep["ranks"] // groups) + 65536 + 64
        assert all(b <= limit for b in reads), ("bytes read", reads, size)
    if prefix_of(name).split("_")[0] in APPROXIMATE:
        # Every region drawn: the covered pixels within 10 % of the exact image's (measured:
        # within 7 %), so equal files are no two empty frames.
        exact = json.load(open(os.path.join(work, prefix_of(name).replace(
            prefix_of(name).split("_")[0], "raycast", 1) + "_replicate", "report.json")))
        covered = sum(f["covered_pixels"] for f in rep["frames"])
        expected = sum(f["covered_pixels"] for f in exact["frames"])
        assert abs(covered - expected) <= 0.1 * expected, ("covered", covered, expected)
    if name.startswith("hybrid"):
        # The frame's way is chosen over every region of every rank: the same choice and the
        # same summed counts whichever rank holds which region.
        for a, b in zip(one["frames"], rep["frames"]):
            for k in ("every_pixel_cast", "probe_triangles", "probe_depth"):
                assert a["counts"].get(k) == b["counts"].get(k), (k, a["counts"].get(k),
                                                                 b["counts"].get(k))
    if name.endswith("_3_7_1") and prefix_of(name).split("_")[0] in ("zbuffer", "hybrid"):
        # lzb info estimates from the same cut: its shares are those the ranks held.
        info = json.loads(subprocess.run(
            [lzb, "info", rep["scene"]["source"], "--json", "--quiet", "--ranks", "3",
             "--distribute", "data", "--regions", "7", "--method", rep["method"]],
            check=True, capture_output=True, text=True).stdout)
        # A streamed scene (and a TOML scene's files) is estimated from its centres alone,
        # never held (no octrees).
        source = rep["scene"]["source"]
        streams = source.endswith((".ply", ".off", ".obj", ".toml")) or source.startswith(
            ("builtin:landscape", "builtin:terrain", "builtin:displaced"))
        assert bool(info.get("streamed")) == streams, ("info streamed", info.get("streamed"))
        # (An instanced share is estimated as at most the scene's unique triangles.)
        estimated = [r["triangles"] for r in info["estimate"]["ranks"]]
        held_unique = [min(int(s), info["triangles_unique"]) for s in shares]
        assert estimated == held_unique, ("info's shares", estimated, held_unique)
    if name.startswith("zbuffer") and groups == 1:
        for a, b in zip(one["frames"], rep["frames"]):
            drawn = [r["counts"].get("triangles_drawn", 0) for r in b["ranks"]]
            assert sum(drawn) == a["counts"]["triangles_drawn"], ("drawn", drawn)
            assert all(d <= s for d, s in zip(drawn, shares)), ("drew beyond its share", drawn)
    return f"held {shares}"


def check(lzb, work, data):
    failures = 0
    for name, ranks, words in runs(work, data):
        if "_data_" not in name or name == same_as(name):
            continue
        try:
            shares = check_run(lzb, work, name, same_as(name))
            print(f"ok: {name} ({words[0]}): the files of {same_as(name)}, {shares}")
        except (AssertionError, OSError, KeyError) as e:
            failures += 1
            print(f"FAIL: {name} ({words[0]}): {e}")
    print(f"{failures} failed" if failures else "every data-mode run equals its 1-rank run")
    return 1 if failures else 0


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    lzb, mpiexec, work = argv[:3]
    data = argv[3] if len(argv) > 3 else ""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    make_files(lzb, work)
    render(lzb, mpiexec, work, data)
    return check(lzb, work, data)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
