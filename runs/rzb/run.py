#!/usr/bin/env python3
"""Randomized z-buffer (--method rzb) studies: CSV files (the command on the first line) and PNG plots.

Usage (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh):
  python3 runs/rzb/run.py [STUDY ...] [--quick] [--plot-only]
STUDY: sensitivity vs_zbuffer throughput table1 walkthrough eps dynamic (default: all)

  sensitivity  chessboard from 2^11 to ~1.4*10^14 triangles, point pass only (--fallback off), 640x480:
               frame time and its ratio largest / smallest (Wand et al. Fig. 6).        -> sensitivity.csv/.png
  vs_zbuffer   rzb (new sample set, and cache warm) against zbuffer on the largest scene the z-buffer
               still renders here (forest, 6.3*10^8 triangles), in one process, with accuracy. -> vs_zbuffer.csv
  throughput   point-pass samples per second against the atomic-min scatter limit measured in the
               same process.                                                            -> throughput.csv
  table1       Table 1 analogue: d = 1, 2, 5, new sample set vs cache, on city, forest and a real mesh,
               with the z-buffer's time and accuracy.                                   -> table1.csv
  walkthrough  80-frame walkthrough, cache against no cache, with stage times (Fig. 8): city and forest as
               rendered by default (z-buffer fallback on) and forest / chessboard point pass only.
                                                                       -> walkthrough.csv/.png, walkthrough_summary.csv
  eps          box selection / reconstruction time against eps, and --eps auto (Fig. 7). -> eps.csv/.png
  dynamic      insert a 5,558-triangle object into a 1.26 M triangle city one triangle at a time and
               remove it, against rebuilding (section 8.4).                             -> dynamic.csv
  fallback     the z-buffer fallback drawn by the native z-buffer against OSMesa (--fallback-render native |
               gl), 40-frame circles with --cache-mb 512 on the forest and the city, the two alternated
               run by run: median frame and fallback-stage seconds.                     -> fallback.csv
  forest_walk  builtin:forest, 40-frame circle, --cache-mb 512, d = 1 and 2: rzb against raycast, the two
               alternated run by run, with accuracy against --reference raycast.       -> forest_walk.csv
The machine these ran on has 2 cores shared with other work: compare figures from the same run.
Environment: LZB_BUILD=build folder (default build/); RZB_LOCK=/tmp/bench.lock runs every timed command
under flock, one measurement at a time.
"""
import csv, json, os, statistics, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (-h / --help prints this docstring instead of running)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(ROOT, "runs", "rzb")
BUILD = os.environ.get("LZB_BUILD", os.path.join(ROOT, "build"))
LZB = os.path.join(BUILD, "lzb")
TEST = os.path.join(BUILD, "src", "rzb", "rzb_test")
DATA = os.path.join(BUILD, "data") if os.path.isdir(os.path.join(BUILD, "data")) else os.path.join(ROOT, "build", "data")
THREADS = 2
quick = "--quick" in sys.argv
plot_only = "--plot-only" in sys.argv
STUDIES = ["sensitivity", "vs_zbuffer", "throughput", "table1", "walkthrough", "eps", "dynamic",
           "fallback", "forest_walk"]
studies = [a for a in sys.argv[1:] if not a.startswith("--")] or STUDIES[:7]
# A mistyped study or option is refused before anything runs (or any CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"), words=STUDIES)
CMD = "python3 runs/rzb/run.py " + " ".join(sys.argv[1:])


def write_csv(name, rows, fields, note=""):
    with open(os.path.join(HERE, name), "w", newline="") as f:
        f.write(f"# command: {CMD}; {THREADS} threads, 640x480{'; ' + note if note else ''}\n")
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"wrote runs/rzb/{name}", flush=True)


def read_csv(name):
    with open(os.path.join(HERE, name)) as f:
        return list(csv.DictReader(l for l in f if not l.startswith("#")))


# RZB_LOCK=/path: every timed command runs under `flock /path` (machines shared with other timing work:
# one lock per measurement, so no single hold is long).
LOCK = ["flock", os.environ["RZB_LOCK"]] if os.environ.get("RZB_LOCK") else []


def render(scene, args, frames=3):
    """lzb render; returns the report's frames."""
    with tempfile.TemporaryDirectory() as out:
        cmd = LOCK + [LZB, "render", scene, "--threads", str(THREADS), "--frames", str(frames), "--quiet",
               "--out", out] + args
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "report.json")) as f:
            return json.load(f)


def bench(test, env):
    """Runs a benchmark test of rzb_test (RzbBench.*, enabled by LZB_BENCH=1); returns its BENCH lines."""
    e = dict(os.environ, LZB_BENCH="1", RZB_BENCH_THREADS=str(THREADS), LZB_SOURCE_DIR=ROOT, **env)
    p = subprocess.run(LOCK + [TEST, f"--gtest_filter=RzbBench.{test}"],
                       env=e, check=True, capture_output=True, text=True)
    return [json.loads(l[6:]) for l in p.stdout.splitlines() if l.startswith("BENCH ")]


def gnuplot(script):
    subprocess.run(["gnuplot"], input=script, text=True, check=True, cwd=HERE)


# ---------------------------------------------------------------------------------------------
def sensitivity():
    ks = list(range(5, 12 if quick else 24))  # n = 2^k squares per side: 2 n^2 triangles
    passes = 1 if quick else 2
    rows = []
    if not plot_only:
        # Passes over all sizes (interleaved, so machine drift hits every size alike); per size the
        # best frame of all passes (the least disturbed by other work on the shared machine).
        best = {}
        for p in range(passes):
            for k in ks:
                n = 2 ** k
                rep = render(f"builtin:chessboard?n={n}", ["--method", "rzb", "--fallback", "off"], frames=4)
                fr = rep["frames"]
                f = min(fr, key=lambda f: f["seconds"])
                if n not in best or f["seconds"] < best[n]["min_frame_s"]:
                    best[n] = {"n": n, "triangles": rep["scene"]["triangles_expanded"],
                               "min_frame_s": f["seconds"], "splat_s": f["stages"]["splat"],
                               "select_s": f["stages"]["select"], "samples": f["counts"]["samples_drawn"],
                               "boxes": f["counts"]["boxes_selected"], "setup_s": rep["setup_seconds"]}
                print(f"pass {p} chessboard n=2^{k:2d} {best[n]['triangles']:>22,} tris "
                      f"{f['seconds']:.3f} s (best {best[n]['min_frame_s']:.3f})", flush=True)
        rows = [best[2 ** k] for k in ks]
        base = rows[0]["min_frame_s"]
        for r in rows:
            r["ratio_to_smallest"] = r["min_frame_s"] / base
        write_csv("sensitivity.csv", rows, ["n", "triangles", "min_frame_s", "ratio_to_smallest", "splat_s",
                                            "select_s", "samples", "boxes", "setup_s"],
                  f"point pass only (--fallback off), best of 4 frames x {passes} passes")
    rows = read_csv("sensitivity.csv")
    ratio = float(rows[-1]["min_frame_s"]) / float(rows[0]["min_frame_s"])
    spread = max(float(r["min_frame_s"]) for r in rows) / min(float(r["min_frame_s"]) for r in rows)
    print(f"output sensitivity: largest / smallest scene frame time = {ratio:.2f} "
          f"(max / min over all sizes {spread:.2f})")
    gnuplot(f"""set terminal pngcairo size 800,500
set output 'sensitivity.png'
set datafile separator ','
set logscale x
set xlabel 'triangles (chessboard; nested 2x2 instancing above 8192)'
set ylabel 'frame time (s)'
set yrange [0:*]
set grid
set title 'rzb point pass (--fallback off), 640x480: largest/smallest scene = {ratio:.2f}'
plot 'sensitivity.csv' skip 2 using 2:3 with linespoints title 'frame (best)', '' skip 2 using 2:5 with linespoints title 'splat'
""")


# ---------------------------------------------------------------------------------------------
def vs_zbuffer():
    """The Table 1 run of the largest scene the z-buffer still renders here (both in one process)."""
    scene = "builtin:forest?levels=2" if quick else "builtin:forest?levels=3"
    if not plot_only:
        rows = [j for j in bench("Table1", {"RZB_BENCH_SCENE": scene}) if j["d"] == 1]
        for j in rows:
            j["speedup"] = j["zbuffer_s"] / j["frame_s"]
            print(f"{scene} cache={j['cache']!s:5s}: rzb {j['frame_s']:.3f} s, zbuffer {j['zbuffer_s']:.3f} s "
                  f"(x{j['speedup']:.1f}), correct {j['correct_rate_covered']:.4f}", flush=True)
        write_csv("vs_zbuffer.csv", rows, ["scene", "triangles", "d", "cache", "frame_s", "first_frame_s",
                                           "zbuffer_s", "speedup", "correct_rate_covered", "psnr_aa", "samples",
                                           "fallback_triangles", "setup_s"],
                  "rzb and zbuffer render the same view in one process; cache: best warm frame")


# ---------------------------------------------------------------------------------------------
def throughput():
    # The forest and the field of 1600 armadillos are runs/peers' scenes (sub-pixel triangles).
    scenes = ["builtin:chessboard?n=64", os.path.join(DATA, "bunny00.off"), "builtin:forest?levels=3",
              "builtin:chessboard?n=1048576", "builtin:forest",
              f"builtin:replicated?mesh={os.path.join(DATA, 'armadillo.off')}&k=40&levels=1"]
    if quick:
        scenes = scenes[:2]
    if not plot_only:
        rows = []
        for s in scenes:
            # Point pass only, except the forest and the field, whose large triangles near the
            # camera go to the fallback as by default (the point pass alone would cap those boxes).
            fallback = "auto" if "forest" in s or "replicated" in s else "off"
            for j in bench("PointPassParts", {"RZB_BENCH_SCENE": s, "RZB_BENCH_FALLBACK": fallback}):
                rows.append(j)
                print(f"{s}: {j['splat_per_s'] / 1e6:.1f} M samples/s, scatter limit "
                      f"{j['scatter_limit_per_s'] / 1e6:.1f} M/s = {100 * j['fraction_of_limit']:.1f} %", flush=True)
        write_csv("throughput.csv", rows, ["scene", "fallback", "threads", "samples", "splat_per_s", "scatter_limit_per_s",
                                           "fraction_of_limit", "draw_per_s", "draw_pick_per_s",
                                           "cpu_ns_per_sample_draw", "cpu_ns_per_sample_draw_pick",
                                           "cpu_ns_per_sample_splat", "wide_keys", "boxes"],
                  "the point pass of the default view, best of 3; limit: random 64-bit atomic min into 640x480")


# ---------------------------------------------------------------------------------------------
def table1():
    scenes = [("city", "builtin:city?blocks=8" if quick else "builtin:city?blocks=32"),
              ("forest", "builtin:forest?levels=2"),
              ("bunny (scanned)", os.path.join(DATA, "bunny00.off")),
              ("forest 2.6e12", "builtin:forest?levels=6")]
    if not plot_only:
        rows = []
        for name, s in scenes:
            env = {"RZB_BENCH_SCENE": s}
            if "levels=6" in s:
                env["RZB_BENCH_NO_ZBUFFER"] = "1"
            for j in bench("Table1", env):
                j["name"] = name
                rows.append(j)
                print(f"{name:16s} d={j['d']} cache={j['cache']!s:5s} {j['frame_s']:.3f} s "
                      f"(zbuffer {j['zbuffer_s']:.3f} s) correct {j.get('correct_rate_covered', float('nan')):.4f}", flush=True)
        write_csv("table1.csv", rows, ["name", "scene", "triangles", "d", "cache", "frame_s", "first_frame_s",
                                       "zbuffer_s", "correct_rate_covered", "psnr_aa", "samples", "fallback_triangles",
                                       "setup_s", "tree_bytes"],
                  "frame_s: new sample set (cache off) or best warm frame of the same view (cache on)")


# ---------------------------------------------------------------------------------------------
def walkthrough():
    # (name, scene, extra bench env). The first two are the default renderer (z-buffer fallback on),
    # where OSMesa draws most of the frame and the cache can only speed up the rest; the last two
    # are point pass only (--fallback off), which shows the cache's own effect.
    runs = [("city", "builtin:city", {}),
            ("forest", "builtin:forest?levels=3", {}),
            ("forest, fallback off", "builtin:forest?levels=3", {"RZB_BENCH_FALLBACK": "off"}),
            ("chessboard 2.2e12, fallback off", "builtin:chessboard?n=1048576", {"RZB_BENCH_FALLBACK": "off"})]
    if quick:
        runs = runs[:1]
    if not plot_only:
        rows, summary = [], []
        for name, s, env in runs:
            js = bench("CacheWalkthrough", dict(env, RZB_BENCH_SCENE=s, RZB_BENCH_STEP="0.5"))
            tot = {"name": name, "scene": s, "fallback": js[0]["fallback"], "frames": len(js)}
            for j in js:
                j["name"] = name
                for side in ("plain", "cached"):
                    st = j[side + "_stages"]
                    j[side + "_fallback_s"] = st.get("fallback", 0.0)
                    j[side + "_splat_s"] = st.get("splat", 0.0)
                j["cached_build_s"] = j["cached_stages"].get("cache_build", 0.0)
                for k in ("plain_s", "cached_s", "plain_fallback_s", "cached_fallback_s", "plain_splat_s",
                          "cached_splat_s", "cached_build_s", "cache_hits", "cache_misses", "fallback_triangles"):
                    tot[k] = tot.get(k, 0.0) + j[k]
            rows += js
            tot["speedup"] = tot["plain_s"] / tot["cached_s"]
            # The part the cache replaces: drawing samples (plain) against splatting cached sets + building them.
            tot["point_pass_speedup"] = tot["plain_splat_s"] / (tot["cached_splat_s"] + tot["cached_build_s"])
            tot["splat_speedup"] = tot["plain_splat_s"] / tot["cached_splat_s"]
            tot["fallback_share"] = tot["plain_fallback_s"] / tot["plain_s"]
            tot["fallback_triangles"] /= len(js)
            summary.append(tot)
            print(f"{name}: {len(js)} frames {tot['plain_s']:.2f} s without cache, {tot['cached_s']:.2f} s with: "
                  f"x{tot['speedup']:.2f} (fallback {100 * tot['fallback_share']:.0f} % of the plain time; "
                  f"point pass x{tot['point_pass_speedup']:.2f} incl. building sets, splat alone x{tot['splat_speedup']:.1f})",
                  flush=True)
        write_csv("walkthrough.csv", rows, ["name", "scene", "fallback", "frame", "plain_s", "cached_s",
                                            "plain_fallback_s", "cached_fallback_s", "plain_splat_s", "cached_splat_s",
                                            "cached_build_s", "cache_hits", "cache_misses", "cache_bytes",
                                            "fallback_triangles", "plain_samples", "cached_samples"],
                  "camera walks forward 0.5 m per frame; the cache starts empty; stage seconds per frame")
        write_csv("walkthrough_summary.csv", summary,
                  ["name", "scene", "fallback", "frames", "plain_s", "cached_s", "speedup", "fallback_share",
                   "fallback_triangles", "plain_fallback_s", "cached_fallback_s", "plain_splat_s", "cached_splat_s",
                   "cached_build_s", "point_pass_speedup", "splat_speedup", "cache_hits", "cache_misses"],
                  "sums over the walkthrough (fallback_triangles: per frame); point_pass_speedup = "
                  "plain splat / (cached splat + cache build)")
    rows = read_csv("walkthrough.csv")
    names = list(dict.fromkeys(r["name"] for r in rows))
    files = {n: f"walkthrough_{k}.dat" for k, n in enumerate(names)}
    for n in names:
        with open(os.path.join(HERE, files[n]), "w") as f:
            for r in rows:
                if r["name"] == n:
                    f.write(f"{r['frame']} {r['plain_s']} {r['cached_s']}\n")
    plots = ", ".join(f"'{files[n]}' using 1:2 with lines lc {k + 1} dt 2 title '{n}, no cache', "
                      f"'{files[n]}' using 1:3 with lines lc {k + 1} lw 2 title '{n}, cache'"
                      for k, n in enumerate(names))
    gnuplot(f"""set terminal pngcairo size 900,560
set output 'walkthrough.png'
set xlabel 'frame'
set ylabel 'frame time (s)'
set logscale y
set grid
set key outside below
set title 'rzb 80-frame walkthrough, 640x480, d = 1 (dashed: new samples every frame; solid: sample cache)'
plot {plots}
""")
    for n in names:
        os.remove(os.path.join(HERE, files[n]))


# ---------------------------------------------------------------------------------------------
def eps():
    scenes = [("city", "builtin:city"), ("forest", "builtin:forest?levels=3")]
    if quick:
        scenes = scenes[:1]
    if not plot_only:
        rows = []
        for name, s in scenes:
            for j in bench("EpsCurve", {"RZB_BENCH_SCENE": s}):
                j["name"] = name
                rows.append(j)
                print(f"{name} eps {j['eps']:.3f}{' (auto)' if j['auto'] else ''}: {j['frame_s']:.3f} s "
                      f"select {j['select_s']:.4f} reconstruct {j['reconstruct_s']:.3f}", flush=True)
        write_csv("eps.csv", rows, ["name", "scene", "eps", "auto", "frame_s", "select_s", "reconstruct_s",
                                    "nodes_visited", "boxes", "samples"], "best of 3 frames of the default view")
    rows = read_csv("eps.csv")
    names = list(dict.fromkeys(r["name"] for r in rows))
    for n in names:
        with open(os.path.join(HERE, f"eps_{n}.dat"), "w") as f:
            for r in rows:
                if r["name"] == n and r["auto"] == "False":
                    f.write(f"{r['eps']} {r['frame_s']} {r['select_s']} {r['reconstruct_s']}\n")
        with open(os.path.join(HERE, f"eps_{n}_auto.dat"), "w") as f:
            for r in rows:
                if r["name"] == n and r["auto"] == "True":
                    f.write(f"{r['eps']} {r['frame_s']}\n")
    plots = ", ".join(f"'eps_{n}.dat' using 1:2 with linespoints title '{n} total', "
                      f"'eps_{n}.dat' using 1:3 with linespoints title '{n} box selection', "
                      f"'eps_{n}.dat' using 1:4 with linespoints title '{n} reconstruction', "
                      f"'eps_{n}_auto.dat' using 1:2 with points pt 7 ps 2 title '{n} --eps auto'" for n in names)
    gnuplot(f"""set terminal pngcairo size 900,550
set output 'eps.png'
set logscale xy
set xrange [1:20]
set xlabel 'depth accuracy eps'
set ylabel 'seconds'
set grid
set key outside
set title 'rzb: box selection vs reconstruction time (Fig. 7), 640x480'
plot {plots}
""")
    for n in names:
        os.remove(os.path.join(HERE, f"eps_{n}.dat"))
        os.remove(os.path.join(HERE, f"eps_{n}_auto.dat"))


# ---------------------------------------------------------------------------------------------
def dynamic():
    if not plot_only:
        rows = bench("DynamicUpdates", {})
        print(rows[0], flush=True)
        write_csv("dynamic.csv", rows, ["city_triangles", "object_triangles", "rebuild_s", "insert_s", "remove_s",
                                        "insert_remove_s", "us_per_triangle", "compact_s", "area_error",
                                        "dirty_samples_per_s", "static_samples_per_s"],
                  "library level (SampleTree), one thread; object: CGAL elephant.off")


# ---------------------------------------------------------------------------------------------
def median_stage(frames, stage):
    return statistics.median(f["stages"].get(stage, 0.0) for f in frames)


def fallback():
    """Native z-buffer against OSMesa for the fallback: whole cached frames, runs alternated."""
    scenes = ["builtin:forest", "builtin:city"]
    reps = 1 if quick else 3
    frames = 10 if quick else 40
    if not plot_only:
        rows = []
        for s in scenes:
            for rep in range(reps):
                for render_kind in ("native", "gl"):
                    r = render(s, ["--method", "rzb", "--cache-mb", "512", "--fallback-render", render_kind],
                               frames=frames)
                    fr = r["frames"]
                    row = {"scene": s, "fallback_render": render_kind, "run": rep, "frames": len(fr),
                           "median_frame_s": statistics.median(f["seconds"] for f in fr),
                           "median_fallback_s": median_stage(fr, "fallback"),
                           "median_splat_s": median_stage(fr, "splat"),
                           "median_cache_build_s": median_stage(fr, "cache_build"),
                           "fallback_triangles": statistics.median(f["counts"]["fallback_triangles"] for f in fr)}
                    row["fallback_share"] = row["median_fallback_s"] / row["median_frame_s"]
                    rows.append(row)
                    print(f"{s} {render_kind:6s} run {rep}: frame {row['median_frame_s']:.4f} s, fallback "
                          f"{row['median_fallback_s']:.4f} s ({100 * row['fallback_share']:.0f} %)", flush=True)
        write_csv("fallback.csv", rows, ["scene", "fallback_render", "run", "frames", "median_frame_s",
                                         "median_fallback_s", "fallback_share", "median_splat_s",
                                         "median_cache_build_s", "fallback_triangles"],
                  f"--cache-mb 512, {frames} frames; native and gl alternated run by run; medians over each run's frames")
    rows = read_csv("fallback.csv")
    for s in dict.fromkeys(r["scene"] for r in rows):
        for k in ("native", "gl"):
            sel = [r for r in rows if r["scene"] == s and r["fallback_render"] == k]
            print(f"{s} {k}: median over runs: frame {statistics.median(float(r['median_frame_s']) for r in sel):.4f} s, "
                  f"fallback {statistics.median(float(r['median_fallback_s']) for r in sel):.4f} s")


def forest_walk():
    """rzb (cache) against raycast on the forest circle, alternated in one run; accuracy of each d from a
    run with --reference raycast (the image does not depend on it; its frames are timed too)."""
    scene = "builtin:forest"
    reps = 1 if quick else 3
    frames = 10 if quick else 40

    def run(method, d, rep, reference):
        args = ["--method", method]
        if method == "rzb":
            args += ["--cache-mb", "512", "--splat", str(d)]
        if reference:
            args += ["--reference", "raycast"]
        fr = render(scene, args, frames=frames)["frames"]
        row = {"method": method, "d": d if method == "rzb" else "", "run": rep, "reference": reference,
               "frames": len(fr), "median_frame_s": statistics.median(f["seconds"] for f in fr)}
        if reference:
            acc = [f["accuracy"] for f in fr]
            row["correct_rate_covered"] = statistics.median(a["correct_rate_covered"] for a in acc)
            row["min_correct_rate_covered"] = min(a["correct_rate_covered"] for a in acc)
            row["psnr_aa"] = statistics.median(a["psnr_aa"] for a in acc)
        if method == "rzb":
            for st in ("select", "fallback", "cache_build", "splat", "resolve", "shade"):
                row[st + "_s"] = median_stage(fr, st)
            row["samples"] = statistics.median(f["counts"]["samples_drawn"] for f in fr)
            row["fallback_triangles"] = statistics.median(f["counts"]["fallback_triangles"] for f in fr)
        print(f"run {rep} {method} d={row['d']} reference={reference}: {row['median_frame_s']:.4f} s "
              f"{row.get('correct_rate_covered', '')}", flush=True)
        return row

    if not plot_only:
        rows = []
        for rep in range(reps):
            for d in (1, 2):
                rows.append(run("rzb", d, rep, False))
                rows.append(run("raycast", d, rep, False))
        for d in (1, 2):
            rows.append(run("rzb", d, 0, True))
        write_csv("forest_walk.csv", rows, ["method", "d", "run", "reference", "frames", "median_frame_s",
                                            "correct_rate_covered", "min_correct_rate_covered", "psnr_aa",
                                            "select_s", "fallback_s", "cache_build_s", "splat_s", "resolve_s",
                                            "shade_s", "samples", "fallback_triangles"],
                  f"builtin:forest, {frames}-frame circle; rzb --cache-mb 512; rzb and raycast alternated run by "
                  "run; accuracy (median over frames) from the runs with --reference raycast")
    rows = read_csv("forest_walk.csv")
    ray = statistics.median(float(r["median_frame_s"]) for r in rows if r["method"] == "raycast")
    for d in ("1", "2"):
        rz = statistics.median(float(r["median_frame_s"]) for r in rows
                               if r["method"] == "rzb" and r["d"] == d and r["reference"] == "False")
        print(f"forest d={d}: rzb {rz:.4f} s, raycast {ray:.4f} s: rzb / raycast = {rz / ray:.2f}")


for s in studies:
    globals()[s]()
