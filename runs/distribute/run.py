#!/usr/bin/env python3
"""--distribute data against replicate on the 9.6 M-triangle landscape
(builtin:landscape?objects=400000, generated twice under data, each rank keeping its share) at
640x480, 6 frames (the first dropped): peak memory per rank, load (with the cut), set-up, median
frame, and the hybrid's accuracy against raycast (lzb compare on the last frame), replicated on
1 rank x 2 threads and 2 x 1, data on 1 x 2, 2 x 1 and 4 x 1 (4 ranks oversubscribe the 2 cores:
their times are not speedups). Then the capacity run on ~5*10^7 triangles (objects=2097152):
raycast replicated on one rank, refused on one rank under an address-space limit, and rendered
by 4 ranks in data mode each under the same limit, the image byte-identical to the unlimited one.

Last, the composite's share of a 1920x1080 raycast frame (landscape of 1.0 M triangles, 6
frames) on 2 and 4 ranks, replicated and in data mode.

And the hybrid's stages on 2 ranks x 1 thread, replicated, in data mode, and in data mode drawn
by local z-buffering every frame (--frame-way local), alone and with a static plane (--plane 0.2):
where the data-mode frame goes.

Then the city (builtin:city, instanced) at 640x480 and 1920x1080 for raycast, the hybrid and
lzb: 1 x 2 and 2 x 1 replicated, 2 x 1 and 4 x 1 in data mode (12 frames, the first dropped).

With --scale, the data path at scale instead (scale.py: bytes read, peak and load a rank on
1 to 8 ranks, PLY files of 10^7 and 5*10^7 triangles; --before=PATH adds an earlier build's rows).

Usage: python3 runs/distribute/run.py [--quick]
       [--ranks | --capacity | --composite | --stages | --city | --scale [--before=LZB]
        [--plot-only]]
       (from the repository root, after scripts/build.sh; each flag: that part alone)
Writes runs/distribute/ranks.csv (one row per configuration and rank), capacity.csv,
composite.csv, stages.csv and city.csv; --scale writes scale.csv and scale.png.
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(flags=("--quick", "--ranks", "--capacity", "--composite", "--stages", "--city",
                          "--scale", "--plot-only"), valued=("before",))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
SCENE = "builtin:landscape?objects=4000" if QUICK else "builtin:landscape?objects=400000"
BIG = "builtin:landscape?objects=40000" if QUICK else "builtin:landscape?objects=2097152"
FRAMES = 3 if QUICK else 6
METHODS = ["raycast", "zbuffer", "hybrid"]
CONFIGS = [(1, 2, "replicate"), (2, 1, "replicate"), (1, 2, "data"), (2, 1, "data"),
           (4, 1, "data")]  # ranks, threads, mode


def accuracy(image_dir, reference_dir, scene):
    """Covered-correct rate of the last frame of image_dir against the reference's."""
    last = f"frame_{FRAMES - 1:04d}.exr"
    out = subprocess.run([common.LZB, "compare", os.path.join(image_dir, last),
                          os.path.join(reference_dir, last), "--scene", scene],
                         check=True, capture_output=True, text=True, env=common.ENV).stdout
    return json.loads(out)["correct_rate_covered"]


def ranks_study(work):
    reference = os.path.join(work, "reference")
    common.render(SCENE, ["--method", "raycast", "--subsamples", "--frames", str(FRAMES)],
                  threads=2, keep=reference)
    rows, commands = [], []
    for method in METHODS:
        for ranks, threads, mode in CONFIGS:
            kept = os.path.join(work, f"{method}_{ranks}_{mode}")
            shown, rep = common.render(
                SCENE, ["--method", method, "--frames", str(FRAMES), "--distribute", mode],
                ranks=ranks, threads=threads, keep=kept)
            commands.append(shown)
            correct = accuracy(kept, reference, SCENE) if method == "hybrid" else 1.0
            shutil.rmtree(kept, ignore_errors=True)
            frames = rep["frames"][1:]
            frame_s = common.median(f["seconds"] for f in frames)
            held = {r["rank"]: r["counts"].get("held_triangles", rep["scene"]["triangles_expanded"])
                    for r in rep["setup"]["ranks"]}
            for r in rep["frames"][-1]["ranks"]:
                work_done = r["counts"].get("rays", r["counts"].get("triangles_drawn", 0))
                rows.append({"method": method, "mode": mode, "ranks": ranks, "threads": threads,
                             "rank": r["rank"], "held_triangles": int(held[r["rank"]]),
                             "peak_mib": round(r["peak_memory_bytes"] / 2**20),
                             "load_s": round(rep["load_seconds"], 2),
                             "setup_s": round(rep["setup_seconds"], 2),
                             "frame_ms": round(1000 * frame_s, 1), "work": int(work_done),
                             "covered_correct": round(correct, 5)})
            print(f"{method} {ranks}x{threads} {mode}: frame {1000 * frame_s:.1f} ms, peak "
                  f"{[row['peak_mib'] for row in rows[-ranks:]]} MiB, covered-correct "
                  f"{correct:.5f}", flush=True)
    common.write_csv(os.path.join(HERE, "ranks.csv"), rows,
                     ["method", "mode", "ranks", "threads", "rank", "held_triangles", "peak_mib",
                      "load_s", "setup_s", "frame_ms", "work", "covered_correct"], commands)


def limited_render(work, name, ranks, limit_kib, extra):
    """lzb render of BIG under `ulimit -v limit_kib` (0: none): (exit status, report or None)."""
    out = os.path.join(work, name)
    cmd = [common.LZB, "render", BIG, "--method", "raycast", "--frames", "2", "--quiet",
           "--threads", "2" if ranks == 1 else "1", "--out", out, *extra]
    if limit_kib:
        cmd = ["sh", "-c", f'ulimit -v {limit_kib}; exec "$0" "$@"', *cmd]
    if ranks > 1:
        cmd = [*common.MPIRUN, "-n", str(ranks), *cmd]
    common.wait_quiet()
    status = subprocess.run(cmd, env=common.ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    shown = " ".join(c if c != out else "OUT" for c in cmd).replace(common.ROOT + "/", "")
    rep = None
    if status.returncode == 0:
        with open(os.path.join(out, "report.json")) as f:
            rep = json.load(f)
    return shown, status.returncode, status.stderr.strip().splitlines()[-1:] , rep, out


def capacity_study(work):
    """One rank refuses what 4 ranks under the same limit render, byte for byte."""
    rows, commands = [], []
    shown, status, _, whole, whole_dir = limited_render(work, "whole", 1, 0, [])
    commands.append(shown)
    peak = max(r["peak_memory_bytes"] for r in whole["setup"]["ranks"])
    peak = max(peak, max(f["peak_memory_bytes"] for f in whole["frames"]))
    # 40 % of the one rank's peak and 1 GiB for the address space a process maps beside its
    # data: the replicated scene cannot fit, a quarter of it can.
    limit_kib = int((0.4 * peak + 2**30) / 1024)
    rows.append({"run": "1 rank, no limit", "limit_mib": 0, "status": status,
                 "peak_mib_per_rank": round(peak / 2**20), "same_image": True, "message": ""})
    for name, ranks, extra in [("one", 1, []), ("four", 4, ["--distribute", "data"])]:
        shown, status, message, rep, out = limited_render(work, name, ranks, limit_kib, extra)
        commands.append(shown)
        same = status == 0 and all(
            filecmp.cmp(os.path.join(whole_dir, f), os.path.join(out, f), shallow=False)
            for f in ("frame_0000.exr", "frame_0001.exr"))
        peaks = [] if rep is None else [r["peak_memory_bytes"] for r in rep["setup"]["ranks"]] + [
            r["peak_memory_bytes"] for f in rep["frames"] for r in f["ranks"]]
        rows.append({"run": f"{ranks} rank(s) {' '.join(extra) or 'replicated'}",
                     "limit_mib": round(limit_kib / 1024), "status": status,
                     "peak_mib_per_rank": round(max(peaks) / 2**20) if peaks else "",
                     "same_image": same, "message": " ".join(message)})
        print(rows[-1], flush=True)
    common.write_csv(os.path.join(HERE, "capacity.csv"), rows,
                     ["run", "limit_mib", "status", "peak_mib_per_rank", "same_image", "message"],
                     commands)


def composite_study():
    """The composite's share of a 1080p frame: whole frames with their colour under data."""
    rows, commands = [], []
    for ranks in (2, 4):
        for mode in ("replicate", "data"):
            shown, rep = common.render(
                "builtin:landscape?objects=40000",
                ["--method", "raycast", "--distribute", mode, "--width", "1920", "--height",
                 "1080", "--frames", "6"], ranks=ranks)
            commands.append(shown)
            frames = rep["frames"][1:]
            frame_s = common.median(f["seconds"] for f in frames)
            composite_s = common.median(f["stages"].get("composite", 0.0) for f in frames)
            rows.append({"ranks": ranks, "mode": mode, "frame_ms": round(1000 * frame_s, 1),
                         "composite_ms": round(1000 * composite_s, 1),
                         "composite_share": round(composite_s / frame_s, 3)})
            print(rows[-1], flush=True)
    common.write_csv(os.path.join(HERE, "composite.csv"), rows,
                     ["ranks", "mode", "frame_ms", "composite_ms", "composite_share"], commands)


# The hybrid on 2 ranks x 1 thread: replicated, data (each region its own probe), and, drawn by
# local z-buffering every frame, data (each region its own partition plane) and data with a
# static plane (every region's plane at the same depth).
LOCAL = ["--frame-way", "local"]
STAGE_CONFIGS = [("replicate", []), ("data", []), ("data, --frame-way local", LOCAL),
                 ("data, --frame-way local --plane 0.2", [*LOCAL, "--plane", "0.2"])]


def stages_study():
    """Where the hybrid's data-mode frame goes: median stage times and the work counts."""
    rows, commands, stages = [], [], set()
    for name, extra in STAGE_CONFIGS:
        shown, rep = common.render(
            SCENE, ["--method", "hybrid", "--frames", str(FRAMES), "--distribute",
                    name.split(",")[0], *extra], ranks=2)
        commands.append(shown)
        frames = rep["frames"][1:]
        row = {"config": name, "frame_ms": round(1000 * common.median(f["seconds"] for f in frames), 1)}
        for count in ("near_triangles_drawn", "rays_cast", "pvl_size", "every_pixel_cast"):
            row[count] = common.median(f["counts"].get(count, 0) for f in frames)
        for stage in {k for f in frames for k in f["stages"]}:
            row[stage + "_ms"] = round(1000 * common.median(f["stages"].get(stage, 0.0)
                                                            for f in frames), 1)
            stages.add(stage + "_ms")
        rows.append(row)
        print(row, flush=True)
    common.write_csv(os.path.join(HERE, "stages.csv"), rows,
                     ["config", "frame_ms", "near_triangles_drawn", "rays_cast", "pvl_size",
                      "every_pixel_cast", *sorted(stages)], commands)


# The city (instanced: every rank holds the buildings its regions place) at both sizes.
CITY_SIZES = [(640, 480), (1920, 1080)]
CITY_CONFIGS = [(1, 2, "replicate"), (2, 1, "replicate"), (2, 1, "data"), (4, 1, "data")]
CITY_METHODS = ["raycast", "hybrid", "lzb"]


def city_study():
    """The city at 640x480 and 1920x1080, replicated and in data mode: median frame, its shade
    and composite stages, peak memory a rank."""
    rows, commands = [], []
    frames = 4 if QUICK else 12
    for width, height in CITY_SIZES:
        for method in CITY_METHODS:
            for ranks, threads, mode in CITY_CONFIGS:
                shown, rep = common.render(
                    "builtin:city", ["--method", method, "--frames", str(frames), "--distribute",
                                     mode, "--width", str(width), "--height", str(height)],
                    ranks=ranks, threads=threads)
                commands.append(shown)
                kept = rep["frames"][1:]
                stage = lambda name: round(1000 * common.median(  # noqa: E731
                    f["stages"].get(name, 0.0) for f in kept), 2)
                rows.append({"size": f"{width}x{height}", "method": method, "mode": mode,
                             "ranks": ranks, "threads": threads,
                             "frame_ms": round(1000 * common.median(f["seconds"] for f in kept), 1),
                             "shade_ms": stage("shade"), "composite_ms": stage("composite"),
                             "regions_ms": stage("composite regions"),
                             "peak_mib": round(max(r["peak_memory_bytes"] for f in rep["frames"]
                                                   for r in f["ranks"]) / 2**20),
                             "load_s": round(rep["load_seconds"], 2)})
                print(rows[-1], flush=True)
    common.write_csv(os.path.join(HERE, "city.csv"), rows,
                     ["size", "method", "mode", "ranks", "threads", "frame_ms", "shade_ms",
                      "composite_ms", "regions_ms", "peak_mib", "load_s"], commands)


def main():
    if "--scale" in sys.argv:
        import scale  # noqa: E402 (the study of its own file)
        scale.main()
        return
    if "--city" in sys.argv:
        city_study()
        return
    if "--composite" in sys.argv:
        composite_study()
        return
    if "--stages" in sys.argv:
        stages_study()
        return
    work = tempfile.mkdtemp(prefix="lzb-distribute-")
    try:
        if "--capacity" in sys.argv:
            capacity_study(work)
            return
        ranks_study(work)
        if "--ranks" in sys.argv:
            return
        capacity_study(work)
        composite_study()
        stages_study()
        city_study()
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
