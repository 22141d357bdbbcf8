#!/usr/bin/env python3
"""--reference and --subsamples under --distribute data: the accuracy the ranks judge together.

The hybrid renders the city (2 frames, 160x120, 7 regions) in data mode with --reference raycast
on 1, 2 and 3 ranks: every accuracy count must be the same on each (the reference is composited
from the ranks' parts like any exact frame; the ray witness's rays are made by the rank holding
the triangle asked about and traced by every rank), some pixel must be witnessed (else nothing
was asked of the ranks) and on 2 and 3 ranks more than one rank must have made witness rays
(the work was split). raycast --subsamples in data mode on 2 ranks must write the replicated
run's EXRs; `lzb compare` of the hybrid's frames against them with the whole scene loaded (the
one-rank witness) must give the ranks' accuracy exactly; and the replicated hybrid's
covered-correct rate must lie within 0.5 points of data mode's.

usage: mpi_distribute_accuracy.py LZB MPIEXEC WORK
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys

SCENE = "builtin:city?blocks=3"
COMMON = ["--frames", "2", "--width", "160", "--height", "120", "--threads", "1", "--quiet"]
DATA = ["--distribute", "data", "--regions", "7"]


def render(lzb, mpiexec, out, ranks, words):
    launch = [mpiexec, "-n", str(ranks), "--oversubscribe"] if ranks > 1 else []
    subprocess.run(launch + [lzb, "render", SCENE, *words, *COMMON, "--out", out], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    lzb, mpiexec, work = argv[:3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    hybrid = ["--method", "hybrid", "--reference", "raycast"]
    runs = {r: render(lzb, mpiexec, os.path.join(work, f"hybrid_{r}"), r, hybrid + DATA)
            for r in (1, 2, 3)}
    one = [f["accuracy"] for f in runs[1]["frames"]]
    assert sum(a["witnessed_pixels"] for a in one) > 0, "no pixel was witnessed"
    for r in (2, 3):
        accuracy = [f["accuracy"] for f in runs[r]["frames"]]
        assert accuracy == one, (r, "ranks judge otherwise", accuracy, one)
        made = [f["witness_rays_per_rank"] for f in runs[r]["frames"]]
        assert all(len(m) == r for m in made), made
        assert max(sum(1 for n in m if n > 0) for m in made) > 1, ("one rank made every ray", made)
        print(f"ok: {r} ranks judge as 1 (witness rays per rank and frame: {made})")

    exact = os.path.join(work, "raycast_replicated")
    render(lzb, mpiexec, exact, 1, ["--method", "raycast", "--subsamples"])
    parts = os.path.join(work, "raycast_data")
    render(lzb, mpiexec, parts, 2, ["--method", "raycast", "--subsamples"] + DATA)
    for f in ("frame_0000.exr", "frame_0001.exr"):
        assert filecmp.cmp(os.path.join(exact, f), os.path.join(parts, f), shallow=False), f
        test = os.path.join(work, "hybrid_1", f)
        whole = json.loads(subprocess.run([lzb, "compare", test, os.path.join(parts, f), "--scene",
                                           SCENE], check=True, capture_output=True, text=True).stdout)
        frame = one[int(f[6:10])]
        assert whole == frame, (f, "the whole scene's witness judges otherwise", whole, frame)
    print("ok: data-mode sub-samples are the replicated ones; the whole scene's witness agrees")

    replicated = render(lzb, mpiexec, os.path.join(work, "hybrid_replicated"), 1, hybrid)
    for a, b in zip(replicated["frames"], runs[1]["frames"]):
        ra, rb = a["accuracy"]["correct_rate_covered"], b["accuracy"]["correct_rate_covered"]
        assert abs(ra - rb) <= 0.005, ("covered-correct", ra, rb)
    print("ok: within 0.5 points of the replicated hybrid's covered-correct rate")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
