#!/usr/bin/env python3
"""Text mesh files under --distribute data: builtin:landscape?objects=80000 (1.95 M triangles)
exported as binary PLY, then written as ASCII PLY, OFF and OBJ (this script converts it, keeping
the shared vertices and face colours where the format holds them), each rendered by raycast
loaded whole on 1 rank x 2 threads and streamed on 2 ranks x 1 thread (data mode), alternating,
3 times each: load seconds, peak memory per rank, and whether the frames are identical.

Usage: python3 runs/distribute/text_load.py   (from the repository root, after scripts/build.sh)
Writes runs/distribute/text_load.csv.
"""
import filecmp
import multiprocessing
import os
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args()

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = "builtin:landscape?objects=80000"
REPEATS = 3


def read_binary(path):
    """Vertices and (indices, rgb) faces of `lzb export`'s binary PLY."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len("end_header\n")
    head = data[:end].decode().split("\n")
    count = {l.split()[1]: int(l.split()[2]) for l in head if l.startswith("element")}
    nv, nf = count["vertex"], count["face"]
    v = struct.unpack_from("<%df" % (3 * nv), data, end)
    verts = ["%.9g %.9g %.9g" % v[3 * i:3 * i + 3] for i in range(nv)]
    faces = [struct.unpack_from("<B3i3B", data, end + 12 * nv + 16 * f)[1:] for f in range(nf)]
    return verts, faces


def write_text(verts, faces, folder):
    """The scene as ASCII PLY (face colours), OFF and OBJ (no colours: neither format has face
    colours the loader reads)."""
    ply, off, obj = (os.path.join(folder, "landscape." + e) for e in ("ply", "off", "obj"))
    with open(ply, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                "property float z\nelement face %d\nproperty list uchar int vertex_indices\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
                % (len(verts), len(faces)))
        f.writelines(v + "\n" for v in verts)
        f.writelines("3 %d %d %d %d %d %d\n" % t for t in faces)
    with open(off, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        f.writelines(v + "\n" for v in verts)
        f.writelines("3 %d %d %d\n" % t[:3] for t in faces)
    with open(obj, "w") as f:
        f.write("o landscape\n")
        f.writelines("v " + v + "\n" for v in verts)
        f.writelines("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1) for t in faces)


def convert(binary, work):
    write_text(*read_binary(binary), work)


def main():
    rows, commands = [], []
    with tempfile.TemporaryDirectory(prefix="lzb-text-") as work:
        binary = os.path.join(work, "landscape_binary.ply")
        subprocess.run([common.LZB, "export", SCENE, binary, "--quiet"], check=True)
        # In a child process: a render forked from a large Python would report its size as the
        # render's peak (Linux keeps the larger maximum RSS across fork and exec).
        child = multiprocessing.Process(target=convert, args=(binary, work))
        child.start()
        child.join()
        files = {k: os.path.join(work, "landscape." + e)
                 for k, e in (("ascii_ply", "ply"), ("off", "off"), ("obj", "obj"))}
        for fmt, path in files.items():
            for rep in range(REPEATS):
                frames = {}
                for mode, ranks, threads, extra in (("whole", 1, 2, []),
                                                    ("data", 2, 1, ["--distribute", "data"])):
                    keep = os.path.join(work, mode)
                    shown, r = common.render(path, ["--method", "raycast", *extra], ranks=ranks,
                                             threads=threads, keep=keep)
                    commands.append(shown.replace(work + "/", ""))
                    frames[mode] = os.path.join(keep, "frame_0000.png")
                    peaks = [x["peak_memory_bytes"] for x in r["setup"]["ranks"]]
                    rows.append({"format": fmt, "repeat": rep, "mode": mode, "ranks": ranks,
                                 "threads": threads, "load_s": round(r["load_seconds"], 3),
                                 "peak_mib_per_rank": round(max(peaks) / 2**20),
                                 "file_mb": round(os.path.getsize(path) / 1e6)})
                same = filecmp.cmp(frames["whole"], frames["data"], shallow=False)
                rows[-1]["identical_to_whole"] = rows[-2]["identical_to_whole"] = same
                print(fmt, rep, [(x["mode"], x["load_s"], x["peak_mib_per_rank"]) for x in rows[-2:]],
                      "identical" if same else "DIFFERENT", flush=True)
    common.write_csv(os.path.join(HERE, "text_load.csv"), rows,
                     ["format", "repeat", "mode", "ranks", "threads", "load_s",
                      "peak_mib_per_rank", "file_mb", "identical_to_whole"], commands)


if __name__ == "__main__":
    main()
