#!/usr/bin/env python3
"""The peer study: every method beside the exact ray caster (Embree, the fastest exact peer), scene
by scene, in one run, with the machine's limits measured in the same run.

For every scene the methods run one after the other along the same camera path; each reports its
median frame time (frames after the first) and, judged against an exact reference with the ray
witness (src/image/README.md), its correct rate over covered pixels and PSNR. The reference is
raycast for every method but raycast itself (judged against zbuffer). The z-buffer, far slower
on the largest scenes, renders fewer frames there (the `frames` column says how many).

ParaView's pvbatch joins as a peer where it is installed (apt-get install paraview xvfb): the
scene exported by `lzb export` (up to 2*10^7 triangles) rendered along the first 8 cameras of the
same path on 1 and 2 ranks (IceT), frame time only (the median after the first frame). Install: apt-get install paraview python3-paraview xvfb.

Usage: python3 runs/peers/run.py [--quick] [--plot-only] [--scenes=a,b] [--methods=a,b] [--keep]
       (--keep: replace only the rerun scenes' and methods' rows of the existing CSV)
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh;
       plots need gnuplot: bash scripts/install-deps.sh --bench)
Writes runs/peers/peers.csv, limits.csv and peers.png.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only", "--keep"), valued=("scenes", "methods"))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
# name: (scene, width, height, frames, zbuffer frames)
SCENES = {
    "city_paper": ("builtin:city?blocks=12", 512, 512, 80, 80),
    "city_1080p": ("builtin:city?blocks=12", 1920, 1080, 20, 20),
    "forest": ("builtin:forest", 640, 480, 40, 3),
    "chessboard": ("builtin:chessboard?n=1048576", 640, 480, 10, 0),
    "field": (f"builtin:replicated?mesh={ARMADILLO}&k=40&levels=1", 640, 480, 10, 3),
    "sphereflake": ("builtin:sphereflake?depth=5", 512, 512, 20, 20),
    "armadillo": (ARMADILLO, 640, 480, 20, 20),
    "landscape": ("builtin:landscape?objects=400000", 640, 480, 10, 2),
}
METHODS = [("raycast", []), ("hybrid", []), ("lzb", []), ("rzb", []),
           ("rzb_d2", ["--splat", "2"]), ("zbuffer", [])]
# pvbatch renders at most this many frames of a path, on scenes up to this size (it spent over
# 10 minutes on the first frames of a 4.8*10^7-triangle forest here).
PVBATCH_FRAMES = 8
PVBATCH_MAX_TRIANGLES = 20_000_000
# Plotted after the methods when ParaView is installed (frame time only: pvbatch gives no IDs).
PEERS = ["pvbatch_1rank", "pvbatch_2ranks"]
# lzb culls per leaf and refuses 10^12-triangle instancing; no z-buffer draws it.
CANNOT = {("chessboard", "lzb"), ("chessboard", "zbuffer")}


def limits():
    out = subprocess.run([common.LZB, "limits", "--seconds", "1"], check=True,
                         capture_output=True, env=common.ENV).stdout
    return json.loads(out)


def pvbatch(scene, report, w, h, commands):
    """ParaView's pvbatch (llvmpipe, IceT across ranks) along the same cameras, where installed:
    rows of its median frame time on 1 and 2 ranks (the scene exported by `lzb export`)."""
    if shutil.which("pvbatch") is None or shutil.which("xvfb-run") is None:
        return []
    if report["scene"]["triangles_expanded"] > PVBATCH_MAX_TRIANGLES:
        return []
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        mesh, cams = os.path.join(tmp, "scene.ply"), os.path.join(tmp, "report.json")
        subprocess.run([common.LZB, "export", scene, mesh, "--quiet"], check=True, env=common.ENV)
        with open(cams, "w") as f:  # its first frames: pvbatch is slow, and steady after one
            json.dump(dict(report, frames=report["frames"][:PVBATCH_FRAMES]), f)
        for ranks in (1, 2):
            common.wait_quiet()
            cmd = ["xvfb-run", "-a", "mpirun", "-n", str(ranks), "--oversubscribe", "pvbatch",
                   os.path.join(HERE, "pvbatch_render.py"), mesh, cams, str(w), str(h)]
            out = subprocess.run(cmd, check=True, capture_output=True, env=common.ENV).stdout.decode()
            times = json.loads(out.strip().splitlines()[-1])["frame_seconds"]
            commands.append(" ".join(cmd).replace(tmp, "TMP").replace(common.ROOT + "/", ""))
            # The first frame reads (and with 2 ranks redistributes) the mesh.
            rows.append({"method": f"pvbatch_{ranks}rank" + ("s" if ranks > 1 else ""),
                         "frames": len(times), "median_frame_s": common.median(times[1:] or times)})
    return rows


def run():
    rows, commands = [], []
    kept_rows, kept_commands = (common.read_kept(os.path.join(HERE, "peers.csv"))
                                if "--keep" in sys.argv else ([], []))
    measured = [dict(limits(), when="start")]
    for name in common.option("scenes", list(SCENES)):
        scene, w, h, frames, zframes = SCENES[name]
        if QUICK:
            frames, zframes = min(frames, 3), min(zframes, 2)
        for label, extra in METHODS:
            if label not in common.option("methods", [m for m, _ in METHODS]):
                continue
            method = label.split("_")[0]
            n = zframes if method == "zbuffer" else frames
            if (name, method) in CANNOT or n == 0:
                print(f"{name}: {label} skipped (cannot render this scene)", flush=True)
                continue
            reference = "zbuffer" if method == "raycast" else "raycast"
            if name == "chessboard" and method == "raycast":
                reference = None  # no exact method but raycast draws 10^12 triangles
            args = ["--method", method, *extra, "--frames", str(n), "--width", str(w), "--height", str(h)]
            if reference:
                args += ["--reference", reference]
            shown, rep = common.render(scene, args, threads=common.CORES)
            commands.append(shown)
            fr = rep["frames"][1:] or rep["frames"]
            acc = [f["accuracy"] for f in fr if "accuracy" in f]
            counts = lambda k: common.median(f["counts"].get(k, 0.0) for f in fr)  # noqa: E731
            stages = lambda k: common.median(f["stages"].get(k, 0.0) for f in fr)  # noqa: E731
            row = {"scene": name, "triangles": rep["scene"]["triangles_expanded"], "width": w,
                   "height": h, "method": label, "frames": n,
                   "median_frame_s": common.median(f["seconds"] for f in fr),
                   "reference": reference or "",
                   "correct_rate_covered": min((a["correct_rate_covered"] for a in acc), default=""),
                   "median_correct_rate_covered": common.median(a["correct_rate_covered"] for a in acc) if acc else "",
                   "psnr_aa": common.median(a["psnr_aa"] or 99.0 for a in acc) if acc else "",
                   "setup_s": rep["setup_seconds"], "peak_memory_bytes": rep["summary"]["peak_memory_bytes_root"]}
            if method == "raycast" and stages("trace") > 0:
                row["rays_per_s"] = counts("rays") / stages("trace")
            if method == "zbuffer" and stages("draw") > 0:
                row["triangles_per_s"] = counts("triangles_drawn") / (stages("draw") + stages("readback"))
            if method == "hybrid":  # the frames whose probe cast every pixel (--frame-way)
                row["every_pixel_frames"] = sum(f["counts"].get("every_pixel_cast", 0.0) for f in fr) / len(fr)
            if method in ("rzb", "hybrid"):
                splat = stages("splat") or stages("points")
                if splat > 0:
                    row["samples_per_s"] = counts("samples_drawn") / splat
            rows.append(row)
            kept_rows = [r for r in kept_rows if (r["scene"], r["method"]) != (name, label)]
            if method == "raycast" and "pvbatch" in common.option("methods", ["pvbatch"]):
                for pv in pvbatch(scene, rep, w, h, commands):
                    rows.append({"scene": name, "triangles": row["triangles"], "width": w, "height": h, **pv})
                    print(f"{name} {pv['method']}: {pv['median_frame_s'] * 1e3:9.1f} ms", flush=True)
            print(f"{name} {label:8s}: {row['median_frame_s'] * 1e3:9.1f} ms, correct (covered, min) "
                  f"{row['correct_rate_covered']}, psnr_aa {row['psnr_aa']}", flush=True)
            save(ordered(kept_rows + rows), measured, kept_commands + commands)  # a long study keeps its part
    measured.append(dict(limits(), when="end"))
    save(ordered(kept_rows + rows), measured, kept_commands + commands)


def ordered(rows):
    """Rows by scene, then method, in the study's order."""
    scenes, methods = list(SCENES), [m for m, _ in METHODS] + PEERS
    return sorted(rows, key=lambda r: (scenes.index(r["scene"]), methods.index(r["method"])))


def save(rows, measured, commands):
    fields = ["scene", "triangles", "width", "height", "method", "frames", "median_frame_s",
              "reference", "correct_rate_covered", "median_correct_rate_covered", "psnr_aa",
              "rays_per_s", "triangles_per_s", "samples_per_s", "every_pixel_frames", "setup_s",
              "peak_memory_bytes"]
    common.write_csv(os.path.join(HERE, "peers.csv"), rows, fields, commands)
    common.write_csv(os.path.join(HERE, "limits.csv"), measured,
                     ["when", "threads", "width", "height", "memcpy_bytes_per_s",
                      "atomic_min_scatter_per_s", "key_writes_per_s"],
                     [f"{common.LZB} limits --seconds 1".replace(common.ROOT + "/", "")])


def plot():
    rows = common.read_csv(os.path.join(HERE, "peers.csv"))
    scenes = [s for s in SCENES if any(r["scene"] == s for r in rows)]
    methods = [m for m in [m for m, _ in METHODS] + PEERS if any(r["method"] == m for r in rows)]
    def value(s, m, key, scale=1.0):
        for r in rows:
            if r["scene"] == s and r["method"] == m and r[key] not in ("", None):
                return float(r[key]) * scale
        return "NaN"
    blocks = [[(i, value(s, m, "median_frame_s", 1e3), value(s, m, "median_correct_rate_covered", 100))
               for i, s in enumerate(scenes)] for m in methods]
    data = common.datafile(blocks)
    xtics = ", ".join(f"'{s}' {i}" for i, s in enumerate(scenes))
    lines_t = ", ".join(f"'{data}' index {k} using ($1+{(k - len(methods) / 2) * 0.12}):2 with points pt {5 + k} ps 1.5 title '{m}'"
                        for k, m in enumerate(methods))
    lines_a = ", ".join(f"'{data}' index {k} using ($1+{(k - len(methods) / 2) * 0.12}):3 with points pt {5 + k} ps 1.5 title '{m}'"
                        for k, m in enumerate(methods))
    common.gnuplot(f"""
set terminal pngcairo size 1400,900 font ',10' noenhanced
set output '{os.path.join(HERE, "peers.png")}'
set multiplot layout 2,1 title 'Every method beside the exact ray caster (median over frames; 2 cores)'
set xtics ({xtics})
set xrange [-0.5:{len(scenes) - 0.5}]
set grid
set logscale y
set ylabel 'frame time (ms, log)'
set key outside right
plot {lines_t}
unset logscale y
set ylabel 'correct pixels, covered (%)'
set yrange [80:100.5]
plot {lines_a}
unset multiplot
""")


if __name__ == "__main__":
    if "--plot-only" not in sys.argv:
        run()
    plot()
