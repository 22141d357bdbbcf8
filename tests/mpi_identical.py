#!/usr/bin/env python3
"""Same files on any thread and rank count, with the work really split (tests/mpi_identical.cases).

Every case renders its scenes 2 frames at 160x120 against an exact reference on 1 process with
2 threads (`one`) and 1 thread (`thread`), and on 2 and 3 MPI ranks of 1 thread (`two`, `three`):
each configuration is ONE `lzb batch` job that renders every case (one launch a rank count). The
check requires byte-identical images (with the sub-sample channels for the exact methods), the
same accuracy against the reference, and work that was really split: per frame, every rank's
share of the case's counts sums to the 1-rank count, and when there is sizeable work (>= 1000),
at least two ranks did some of it.

usage: mpi_identical.py stores LZB WORK [DATA]          sample tree stores for @store cases
       mpi_identical.py render CONFIG LZB WORK MPIEXEC [DATA]
       mpi_identical.py check WORK [DATA]
"""
import filecmp
import json
import os
import shlex
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIGS = {"one": (1, 2), "thread": (1, 1), "two": (2, 1), "three": (3, 1)}  # ranks, threads
DEFAULT_SCENES = ["builtin:city?blocks=3", "builtin:sphereflake?depth=2", "builtin:forest?levels=1"]
FILES = ["frame_0000.png", "frame_0000.exr", "frame_0001.png", "frame_0001.exr"]


def cases(data):
    """(name, method, counts, extra words, scenes) of every line of the cases file."""
    bunny = os.path.join(data, "bunny00.off") if data else ""
    meshes = {"@bunny": [bunny] if bunny and os.path.exists(bunny) and os.path.getsize(bunny) else []}
    out = []
    for line in open(os.path.join(HERE, "mpi_identical.cases")):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        name, method, counts, extra, scenes = (f.strip() for f in line.split("|"))
        scenes = [s for w in (scenes.split() or DEFAULT_SCENES + ["@bunny"])
                  for s in meshes.get(w, [w])]
        out.append((name, method, [c for c in counts.split(",") if c], extra.split(), scenes))
    return out


def store(work, name, i):
    return os.path.join(work, "stores", f"{name}_{i}.lzbtree")


def job_words(work, name, method, extra, scene, i):
    reference, words = "raycast", []
    for w in extra:
        words.append(store(work, name, i) if w == "@store" else w)
    if method == "zbuffer":
        words.append("--subsamples")
    elif method == "raycast":
        words.append("--subsamples")
        reference = "zbuffer"
    return [scene, "--method", method, "--reference", reference, *words, "--frames", "2",
            "--width", "160", "--height", "120", "--quiet"]


def build_stores(lzb, work, data):
    shutil.rmtree(work, ignore_errors=True)
    for name, _, _, extra, scenes in cases(data):
        if "@store" in extra:
            os.makedirs(os.path.join(work, "stores"), exist_ok=True)
            for i, scene in enumerate(scenes):
                subprocess.run([lzb, "build-tree", scene, "--out", store(work, name, i),
                                "--leaf-triangles", "8", "--quiet"], check=True,
                               stdout=subprocess.DEVNULL)


def render(config, lzb, work, mpiexec, data):
    ranks, threads = CONFIGS[config]
    shutil.rmtree(os.path.join(work, config), ignore_errors=True)
    lines = []
    for name, method, _, extra, scenes in cases(data):
        for i, scene in enumerate(scenes):
            out = os.path.join(work, config, f"{name}_{i}")
            words = job_words(work, name, method, extra, scene, i)
            lines.append(shlex.join(words + ["--threads", str(threads), "--out", out]))
    batch = os.path.join(work, f"{config}.batch")
    with open(batch, "w") as f:
        f.write("\n".join(lines) + "\n")
    launch = [mpiexec, "-n", str(ranks), "--oversubscribe"] if ranks > 1 else []
    subprocess.run(launch + [lzb, "batch", batch, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    print(f"{config}: {len(lines)} renders on {ranks} rank(s) x {threads} thread(s), one launch")


def check_split(counts, one, rep):
    """Per frame: the same accuracy, shares summing to the 1-rank counts, >= 2 ranks working."""
    ranks = rep["ranks"]
    for a, b in zip(one["frames"], rep["frames"]):
        assert a["accuracy"] == b["accuracy"], ("accuracy differs", a["accuracy"], b["accuracy"])
        assert len(b["ranks"]) == ranks, (ranks, len(b["ranks"]))
        working = set()
        for key in counts:
            total = a["counts"].get(key, 0)
            shares = [r["counts"].get(key, 0) for r in b["ranks"]]
            assert sum(shares) == total, (key, "shares", shares, "sum to", sum(shares), "not", total)
            working |= {r for r, s in enumerate(shares) if s > 0}
        if sum(a["counts"].get(k, 0) for k in counts) >= 1000:
            assert len(working) >= 2, ("one rank did all the work", counts)
    return ", ".join(f"{k} {[r['counts'].get(k, 0) for r in rep['frames'][0]['ranks']]}"
                     for k in counts)


def check(work, data):
    failures = 0
    for name, method, counts, extra, scenes in cases(data):
        for i, scene in enumerate(scenes):
            run = {c: os.path.join(work, c, f"{name}_{i}") for c in CONFIGS}
            try:
                for config in ("thread", "two", "three"):
                    for f in FILES:
                        assert filecmp.cmp(os.path.join(run["one"], f),
                                           os.path.join(run[config], f), shallow=False), \
                            (f, "differs", config)
                one = json.load(open(os.path.join(run["one"], "report.json")))
                split = [check_split(counts, one, json.load(open(os.path.join(run[c], "report.json"))))
                         for c in ("two", "three")]
                print(f"ok: {name} on {scene}: identical on 1 and 2 threads and 2 and 3 ranks, "
                      f"accuracy too, work split ({'; '.join(split)})")
            except (AssertionError, OSError, KeyError) as e:
                failures += 1
                print(f"FAIL: {name} on {scene} ({method} {' '.join(extra)}): {e}")
    print(f"{failures} failed" if failures else "every case identical")
    return 1 if failures else 0


def main(argv):
    if len(argv) >= 3 and argv[0] == "stores":
        return build_stores(argv[1], argv[2], argv[3] if len(argv) > 3 else "") or 0
    if len(argv) >= 5 and argv[0] == "render" and argv[1] in CONFIGS:
        return render(argv[1], argv[2], argv[3], argv[4], argv[5] if len(argv) > 5 else "") or 0
    if len(argv) >= 2 and argv[0] == "check":
        return check(argv[1], argv[2] if len(argv) > 2 else "")
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
