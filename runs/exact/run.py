#!/usr/bin/env python3
"""zbuffer vs raycast frame time on the city and on the chessboard series n = 2^k.

Usage: python3 runs/exact/run.py [--quick] [--plot-only]   (from the repository root, after scripts/build.sh)
Writes runs/exact/results.csv, runs/exact/frame_time.png and prints the llvmpipe triangle rate.
Each configuration renders FRAMES frames along the default camera path in one process; the
median frame time is reported. Methods alternate per scene so machine drift hits both alike.
"""
import csv, json, os, statistics, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (-h / --help prints this docstring instead of running)

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"))

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LZB = os.path.join(ROOT, "build", "lzb")
HERE = os.path.join(ROOT, "runs", "exact")
quick = "--quick" in sys.argv
FRAMES = 3 if quick else 5
THREADS = 2

scenes = [("city", "builtin:city")]
for k in range(4, 10 if quick else 12):
    scenes.append((f"chessboard_2^{k}", f"builtin:chessboard?n={2**k}"))
# Past what a z-buffer can draw, the ray caster still renders the instanced board.
raycast_only = [] if quick else [(f"chessboard_2^{k}", f"builtin:chessboard?n={2**k}") for k in (14, 17, 20)]

def render(scene, method):
    with tempfile.TemporaryDirectory() as out:
        cmd = [LZB, "render", scene, "--method", method, "--frames", str(FRAMES), "--threads",
               str(THREADS), "--quiet", "--out", out]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "report.json")) as f:
            rep = json.load(f)
    frames = rep["frames"]
    row = {
        "scene": scene,
        "method": method,
        "triangles": rep["scene"]["triangles_expanded"],
        "median_frame_s": statistics.median(f["seconds"] for f in frames),
        "setup_s": rep["setup_seconds"],
    }
    if method == "zbuffer":
        drawn = statistics.median(f["counts"].get("triangles_drawn", 0) for f in frames)
        draw_s = statistics.median(f["stages"].get("draw", 0) + f["stages"].get("readback", 0) for f in frames)
        row["triangles_per_s"] = drawn / draw_s if draw_s > 0 else ""
    else:
        rays = statistics.median(f["counts"].get("rays", 0) for f in frames)
        trace_s = statistics.median(f["stages"].get("trace", 0) for f in frames)
        row["rays_per_s"] = rays / trace_s if trace_s > 0 else ""
    return row

def read_rows():
    with open(os.path.join(HERE, "results.csv")) as f:
        lines = [l for l in f if not l.startswith("#")]
    out = []
    for r in csv.DictReader(lines):
        r["triangles"] = int(r["triangles"])
        r["median_frame_s"] = float(r["median_frame_s"])
        for k in ("triangles_per_s", "rays_per_s"):
            r[k] = float(r[k]) if r[k] else ""
        out.append(r)
    return out

rows = read_rows() if "--plot-only" in sys.argv else []
for name, scene in ([] if rows else scenes):
    for method in ("zbuffer", "raycast"):
        r = render(scene, method)
        r["name"] = name
        rows.append(r)
        print(f"{name:18s} {method:8s} {r['triangles']:>16,} tris  {r['median_frame_s']*1000:9.1f} ms", flush=True)
for name, scene in ([] if "--plot-only" in sys.argv else raycast_only):
    r = render(scene, "raycast")
    r["name"] = name
    rows.append(r)
    print(f"{name:18s} raycast  {r['triangles']:>16,} tris  {r['median_frame_s']*1000:9.1f} ms", flush=True)

if "--plot-only" not in sys.argv:
  fields = ["name", "scene", "method", "triangles", "median_frame_s", "setup_s", "triangles_per_s", "rays_per_s"]
  with open(os.path.join(HERE, "results.csv"), "w", newline="") as f:
    f.write(f"# command: python3 runs/exact/run.py{' --quick' if quick else ''}; {FRAMES} frames, {THREADS} threads, 640x480\n")
    w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
    w.writeheader()
    w.writerows(rows)

rates = [r["triangles_per_s"] for r in rows if r.get("triangles_per_s")]
big = [r for r in rows if r["method"] == "zbuffer" and r["triangles"] >= 1e6]
print(f"llvmpipe triangle rate (scenes >= 1M triangles): median "
      f"{statistics.median(r['triangles_per_s'] for r in big)/1e6:.2f} M tris/s" if big else "")
rays = [r["rays_per_s"] for r in rows if r.get("rays_per_s")]
if rays:
    print(f"Embree primary rays: median {statistics.median(rays)/1e6:.2f} M rays/s")

# Plot: frame time against expanded triangle count, chessboard series, both methods.
with tempfile.NamedTemporaryFile("w", suffix=".dat", delete=False) as d:
    for method in ("zbuffer", "raycast"):
        d.write(f"# {method}\n")
        for r in rows:
            if r["method"] == method and r["name"].startswith("chessboard"):
                d.write(f"{r['triangles']} {r['median_frame_s']}\n")
        d.write("\n\n")
    data = d.name
gp = f"""
set terminal pngcairo size 800,500
set output '{os.path.join(HERE, "frame_time.png")}'
set logscale xy
set xlabel 'triangles (chessboard, expanded)'
set ylabel 'median frame time [s]'
set title 'Exact references at 640x480, {THREADS} threads'
set key left top
set grid
plot '{data}' index 0 with linespoints title 'zbuffer (OSMesa llvmpipe)', \
     '{data}' index 1 with linespoints title 'raycast (Embree)'
"""
subprocess.run(["gnuplot"], input=gp, text=True, check=True)
os.unlink(data)
print("wrote", os.path.join(HERE, "results.csv"), "and frame_time.png")
