"""The data path at scale (python3 runs/distribute/run.py --scale): what each rank reads, holds
and spends as ranks are added, 1 replicated rank against 1, 2, 4 and 8 data ranks (4 and 8
oversubscribe the 2 cores: their seconds are total CPU, not a cluster's wall time).

Scenes: builtin:landscape exported as a binary PLY of 10^7 triangles with shared vertices
(objects=416667) for raycast and the hybrid, and with --before=PATH (an earlier lzb) the same runs
of that build beside them; a 5*10^7-triangle PLY (objects=2083334) and the landscape generated
(10^7), raycast only. 3 frames at 640x480, 1 thread a rank. Each rank runs under rank_probe.py:
its bytes read (rchar), peak resident memory (VmHWM) and CPU seconds; the report gives the
reader's own count (bytes_read), the load and set-up seconds and the triangles each rank held.
Every data-mode image must equal the 1-rank data run's, and raycast's the replicated run's
(same_image); with --before, each run's images the earlier build's (same_as_before).

Writes runs/distribute/scale.csv (a row per rank) and scale.png (the largest rank's peak against
the rank count, per scene, method and build; --plot-only redraws it from the CSV).
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

HERE = os.path.dirname(os.path.abspath(__file__))
PROBE = os.path.join(HERE, "rank_probe.py")
QUICK = "--quick" in sys.argv
FRAMES = 3
RANKS = [1, 2, 4, 8]
FIELDS = ["scene", "build", "method", "mode", "ranks", "oversubscribed", "rank", "held_triangles",
          "peak_mib", "rchar_mib", "file_fraction_read", "bytes_read_mib", "load_s", "setup_s",
          "cpu_s", "same_image", "same_as_before"]


def before_binary():
    for a in sys.argv[1:]:
        if a.startswith("--before="):
            return a.split("=", 1)[1]
    return None


def probe_render(binary, scene, method, mode, ranks, out):
    """One render with every rank probed; returns (shown command, report, [rank probes])."""
    common.wait_quiet()
    probes = tempfile.mkdtemp(prefix="lzb-probe-")
    cmd = [binary, "render", scene, "--method", method, "--distribute", mode, "--frames",
           str(FRAMES), "--threads", "1", "--quiet", "--out", out]
    launch = [*common.MPIRUN, "-n", str(ranks)] if ranks > 1 else []
    subprocess.run([*launch, sys.executable, PROBE, probes, "--", *cmd], check=True,
                   stdout=subprocess.DEVNULL, env=common.ENV)
    with open(os.path.join(out, "report.json")) as f:
        rep = json.load(f)
    ranks_probed = []
    for r in range(ranks):
        with open(os.path.join(probes, f"rank_{r}.json")) as f:
            ranks_probed.append(json.load(f))
    shutil.rmtree(probes, ignore_errors=True)
    shown = " ".join([*launch, "python3 runs/distribute/rank_probe.py PROBES --", *cmd])
    return shown.replace(out, "OUT").replace(common.ROOT + "/", ""), rep, ranks_probed


def same_frames(a, b):
    return all(filecmp.cmp(os.path.join(a, f"frame_{i:04d}.exr"),
                           os.path.join(b, f"frame_{i:04d}.exr"), shallow=False)
               for i in range(FRAMES))


def study(label, scene, methods, builds, size, rows, commands, work):
    for method in methods:
        for build, binary in builds:
            runs = [("replicate", 1)] + [("data", n) for n in RANKS]
            first_data = None
            replicated = None
            for mode, ranks in runs:
                if QUICK and ranks > 2:
                    continue
                out = os.path.join(work, f"{label}_{method}_{build}_{mode}_{ranks}")
                shown, rep, probed = probe_render(binary, scene, method, mode, ranks, out)
                commands.append(shown)
                if mode == "replicate":
                    replicated = out
                    same = ""
                elif first_data is None:
                    first_data = out
                    same = same_frames(out, replicated) if method == "raycast" else ""
                else:
                    same = same_frames(out, first_data) and (
                        method != "raycast" or same_frames(out, replicated))
                held = {r["rank"]: r["counts"] for r in rep["setup"]["ranks"]}
                for r, p in enumerate(probed):
                    counts = held.get(r, {})
                    rows.append({
                        "scene": label, "build": build, "method": method, "mode": mode,
                        "ranks": ranks, "oversubscribed": int(ranks > 2), "rank": r,
                        "held_triangles": int(counts.get("held_triangles",
                                                         rep["scene"]["triangles_expanded"])),
                        "peak_mib": round(p["peak_kib"] / 1024, 1),
                        "rchar_mib": round(p["rchar"] / 2**20, 1),
                        "file_fraction_read": round(p["rchar"] / size, 3) if size else "",
                        "bytes_read_mib": round(counts["bytes_read"] / 2**20, 1)
                        if "bytes_read" in counts else "",
                        "load_s": round(rep["load_seconds"], 3),
                        "setup_s": round(rep["setup_seconds"], 3),
                        "cpu_s": round(p["cpu_s"], 2), "same_image": same,
                        "same_as_before": ""})
                mine = [x for x in rows if x["scene"] == label and x["method"] == method and
                        x["build"] == build and x["mode"] == mode and x["ranks"] == ranks]
                print(f"{label} {method} {build} {mode} x{ranks}: peak "
                      f"{max(x['peak_mib'] for x in mine)} MiB a rank, read "
                      f"{max(x['rchar_mib'] for x in mine)} MiB a rank, load "
                      f"{mine[0]['load_s']} s + set-up {mine[0]['setup_s']} s, same image: {same}",
                      flush=True)
        # This build's images against the earlier build's, run by run.
        for row in rows:
            if (row["scene"], row["method"], row["build"]) != (label, method, "this"):
                continue
            this = os.path.join(work, f"{label}_{method}_this_{row['mode']}_{row['ranks']}")
            before = this.replace("_this_", "_before_")
            if os.path.isdir(before):
                row["same_as_before"] = same_frames(this, before)
        for build, _ in builds:
            for mode, ranks in [("replicate", 1)] + [("data", n) for n in RANKS]:
                shutil.rmtree(os.path.join(work, f"{label}_{method}_{build}_{mode}_{ranks}"),
                              ignore_errors=True)


def ratios(rows):
    """The issue's figures, from rows of one run."""
    def peak(scene, method, build, mode, ranks):
        xs = [r["peak_mib"] for r in rows if (r["scene"], r["method"], r["build"], r["mode"],
                                              r["ranks"]) == (scene, method, build, mode, ranks)]
        return max(xs) if xs else None

    def field(scene, method, build, mode, ranks, name):
        xs = [r[name] for r in rows if (r["scene"], r["method"], r["build"], r["mode"],
                                        r["ranks"]) == (scene, method, build, mode, ranks)]
        return max(xs) if xs else None

    for scene, method, build in sorted({(r["scene"], r["method"], r["build"]) for r in rows}):
        one = peak(scene, method, build, "replicate", 1)
        p4, p8 = peak(scene, method, build, "data", 4), peak(scene, method, build, "data", 8)
        if one and p4 and p8:
            print(f"{scene} {method} {build}: 8-rank peak / replicated {p8 / one:.3f}, "
                  f"8 / 4 ranks {p8 / p4:.3f}, file read a rank at 8 "
                  f"{field(scene, method, build, 'data', 8, 'file_fraction_read')}")
        l1 = [field(scene, method, build, m, n, "load_s") + field(scene, method, build, m, n,
                                                                  "setup_s")
              for m, n in (("replicate", 1), ("data", 1), ("data", 2))
              if field(scene, method, build, m, n, "load_s") is not None]
        if len(l1) == 3:
            print(f"{scene} {method} {build}: load + set-up, 2 data ranks / 1 data rank "
                  f"{l1[2] / l1[1]:.3f}, / replicated {l1[2] / l1[0]:.3f}")


def plot(rows):
    series = sorted({(r["scene"], r["method"], r["build"]) for r in rows})
    blocks, titles = [], []
    for s in series:
        block = []
        for n in RANKS:
            xs = [float(r["peak_mib"]) for r in rows
                  if (r["scene"], r["method"], r["build"]) == s and r["mode"] == "data" and
                  int(r["ranks"]) == n]
            if xs:
                block.append([n, max(xs)])
        if block:
            blocks.append(block)
            titles.append(" ".join(s))
    data = common.datafile(blocks)
    plots = ", ".join(f"'{data}' index {i} using 1:2 with linespoints title '{t}'"
                      for i, t in enumerate(titles))
    common.gnuplot(f"""
set terminal pngcairo size 900,520 font ',10'
set output '{os.path.join(HERE, "scale.png")}'
set title 'largest rank peak under --distribute data (3 frames, 640x480, 1 thread a rank; 4, 8 oversubscribed)'
set logscale x 2
set logscale y 2
set xtics (1, 2, 4, 8)
set xlabel 'ranks'
set ylabel 'MiB'
set ytics (128, 256, 512, 1024, 2048, 4096, 8192)
set key top right
set grid
plot {plots}
""")


def main():
    if "--plot-only" in sys.argv:  # redraws scale.png from scale.csv
        plot(common.read_csv(os.path.join(HERE, "scale.csv")))
        return
    before = before_binary()
    builds = [("this", common.LZB)] + ([("before", before)] if before else [])
    work = tempfile.mkdtemp(prefix="lzb-scale-")
    rows, commands = [], []
    objects = 4000 if QUICK else 416667
    ply = common.landscape_ply(objects)
    study(f"ply {objects}", ply, ["raycast", "hybrid"], builds, os.path.getsize(ply), rows,
          commands, work)
    if not QUICK:
        big = common.landscape_ply(2083334)
        study("ply 2083334", big, ["raycast"], builds[:1], os.path.getsize(big), rows, commands,
              work)
        study(f"landscape {objects}", f"builtin:landscape?objects={objects}", ["raycast"],
              builds[:1], 0, rows, commands, work)
    shutil.rmtree(work, ignore_errors=True)
    common.write_csv(os.path.join(HERE, "scale.csv"), rows, FIELDS, commands)
    ratios(rows)
    plot(rows)


if __name__ == "__main__":
    main()
