#!/usr/bin/env python3
"""Local z-buffering (--method lzb) against the z-buffer, measured side by side in one process.

Usage: python3 runs/lzb/run.py [paper] [occluders] [size] [reuse] [--quick] [--plot-only]
                                [--variants=naive,lazy,...]  (paper: run these, keep the rest)
(from the repository root, after building build-lzb/lzb; the real meshes come from
scripts/fetch-test-meshes.sh build-lzb/data). No argument runs all four studies. Time each
under the shared lock: flock /tmp/bench.lock python3 runs/lzb/run.py paper (then occluders,
size, reuse). Every run gets OMP_WAIT_POLICY=passive (see ENV below).

  paper      The paper's experiment: builtin:city?blocks=12 (1.8 M triangles), 512x512, 80 frames
             on the default circle, every stage with --reference zbuffer (each frame rendered by
             LZB, then by the z-buffer, in the same process): mean frame times, speedup, accuracy,
             per-stage seconds and counts, with the default (cost) plane; then final and naive
             with the paper's mean plane (final-auto, naive-auto). Each variant runs twice;
             each frame keeps its best LZB and best z-buffer time (PAPER_REPEATS).
             -> paper.csv, paper_frames.csv, paper_*.png
  occluders  Local occluder selection: static / dynamic / hybrid at K = 1, 3, 5, 10 in the
             final stage (selective + OOR + coherent walk, so the rays are the ones that matter),
             and lazy (every triangle tested) as the baseline: ray-triangle tests per ray, PVL
             size, times. -> occluders.csv, occluders.png
  size       Output sensitivity: frame time against scene size (city 12.6 K to 4 M triangles;
             an assembly of real scanned meshes 20 K to 4.8 M), image complexity (covered
             pixels) and depth complexity (surfaces along a 32x32 ray grid, a separate
             diagnostic run). -> size.csv, size_frames.csv, size_*.png

  reuse      Frame coherence of the dynamic plane: a slow circle (720 frames, 0.5 degrees and
             ~10 m per frame, 256x256, no reference) with --plane-reuse 8 and 0: frames that
             reused the plane, plane seconds, frame time. -> reuse.csv

Every CSV starts with a '# command:' line. Frame times are wall seconds per frame (the report's
'seconds' and 'reference_seconds'), averaged over the frames of a run. The machine is shared: each
run starts only once the machine is >= 85 % idle (other jobs can still start during a run).
"""
import csv, json, os, statistics, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402  (idle_fraction, gnuplot, datafile)

STUDIES = ["paper", "occluders", "size", "reuse"]
# A mistyped option or study is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--plot-only"), valued=("variants",), words=STUDIES)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(ROOT, "runs", "lzb")
LZB = os.environ.get("LZB_BIN", os.path.join(ROOT, "build-lzb", "lzb"))
DATA = os.environ.get("LZB_DATA", os.path.join(ROOT, "build-lzb", "data"))
THREADS = 2
QUICK = "--quick" in sys.argv
PLOT_ONLY = "--plot-only" in sys.argv
WANT = [a for a in sys.argv[1:] if not a.startswith("--")] or STUDIES
COMMAND = "python3 runs/lzb/run.py " + " ".join(sys.argv[1:])

STAGES = ["naive", "lazy", "selective", "oor", "final"]
# The paper's experiment: every stage with the defaults (our cost plane, native z-buffer for the
# near pass and the PVL), then the final and naive stages with the paper's mean-depth plane
# (--plane auto), and the final stage with OSMesa drawing the PVL (final-gl), the near pass
# (final-glnear) or both (final-allgl).
VARIANTS = [(st, ["--lzb-stage", st]) for st in STAGES] + [
    ("final-auto", ["--lzb-stage", "final", "--plane", "auto"]),
    ("naive-auto", ["--lzb-stage", "naive", "--plane", "auto"]),
    ("final-gl", ["--lzb-stage", "final", "--pvl-render", "gl"]),
    ("final-glnear", ["--lzb-stage", "final", "--near-render", "gl"]),
    ("final-allgl", ["--lzb-stage", "final", "--near-render", "gl", "--pvl-render", "gl"])]
# Idle OpenMP workers sleep instead of spinning: on 2 cores a spinning worker takes a core from
# llvmpipe's rasterizer threads (measured: lzb 44 -> 29 ms per frame, z-buffer 138 -> 133 ms).
# Both methods run in the same process, so both get it.
ENV = dict(os.environ, OMP_WAIT_POLICY="passive")
STAGE_TIMES = ["cull", "plane", "near", "unfinished", "oor_project", "raycast", "pvl_find",
               "pvl_render", "shade"]
COUNTS = ["plane_depth", "plane_reused", "near_triangles", "far_triangles", "unfinished_pixels",
          "rays_cast", "octree_nodes_visited", "ray_triangle_tests", "visibility_tests",
          "pvl_size", "oor_objects"]


def wait_quiet(limit_s=180):
    """The machine is shared (2 cores): start a measurement only when it is >= 85 % idle, so
    other jobs do not decide the result. Gives up after limit_s and says so."""
    import time
    start = time.time()
    while time.time() - start < limit_s:
        if common.idle_fraction(3.0) >= 0.85:
            return
        time.sleep(10)
    print("warning: the machine stayed busy; measuring anyway", flush=True)


def render(scene, args, frames, size=512, reference=True, timed=True, repeats=1):
    """Runs lzb render; returns (command line, report). Timed runs wait for a quiet machine.
    With repeats > 1 the run is repeated and each frame keeps its best time: the LZB fields
    (seconds, stages) of the repetition where LZB was fastest, and the smallest reference time
    (the images and counts are the same every time)."""
    reps = []
    for _ in range(repeats):
        if timed and not QUICK:
            wait_quiet()
        with tempfile.TemporaryDirectory() as out:
            cmd = [LZB, "render", scene, "--method", "lzb", *args, "--frames", str(frames),
                   "--width", str(size), "--height", str(size), "--threads", str(THREADS),
                   "--quiet", "--out", out]
            if reference:
                cmd += ["--reference", "zbuffer"]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=ENV)
            with open(os.path.join(out, "report.json")) as f:
                reps.append(json.load(f))
    rep = reps[0]
    for i, f in enumerate(rep["frames"]):
        best = min((r["frames"][i] for r in reps), key=lambda g: g["seconds"])
        f["seconds"], f["stages"] = best["seconds"], best["stages"]
        if "reference_seconds" in f:
            f["reference_seconds"] = min(r["frames"][i]["reference_seconds"] for r in reps)
    shown = " ".join(c if c != out else "OUT" for c in cmd).replace(ROOT + "/", "")
    if repeats > 1:
        shown += f" (x{repeats}, best per frame)"
    return shown, rep


def mean(xs):
    xs = list(xs)
    return sum(xs) / len(xs) if xs else float("nan")


def summary(rep):
    """Per-run means over frames."""
    fr = rep["frames"]
    row = {
        "frames": len(fr),
        "lzb_mean_s": mean(f["seconds"] for f in fr),
        "lzb_median_s": statistics.median(f["seconds"] for f in fr),
    }
    if "reference_seconds" in fr[0]:
        row["zbuffer_mean_s"] = mean(f["reference_seconds"] for f in fr)
        row["zbuffer_median_s"] = statistics.median(f["reference_seconds"] for f in fr)
        row["speedup_mean"] = row["zbuffer_mean_s"] / row["lzb_mean_s"]
        row["speedup_median"] = row["zbuffer_median_s"] / row["lzb_median_s"]
        row["correct_min"] = min(f["accuracy"]["correct_rate_covered"] for f in fr)
        row["correct_mean"] = mean(f["accuracy"]["correct_rate_covered"] for f in fr)
        row["exact_id_min"] = min(f["accuracy"]["exact_id_rate_covered"] for f in fr)
        row["exact_id_mean"] = mean(f["accuracy"]["exact_id_rate_covered"] for f in fr)
    for s in STAGE_TIMES:
        row["t_" + s] = mean(f["stages"].get(s, 0.0) for f in fr)
    # Medians resist the bursts of other jobs on the shared machine.
    row["pvl_find_median_s"] = statistics.median(f["stages"].get("pvl_find", 0.0) for f in fr)
    row["pvl_render_median_s"] = statistics.median(f["stages"].get("pvl_render", 0.0) for f in fr)
    for c in COUNTS:
        row[c] = mean(f["counts"].get(c, 0.0) for f in fr)
    rays = sum(f["counts"].get("rays_cast", 0.0) for f in fr)
    tests = sum(f["counts"].get("ray_triangle_tests", 0.0) for f in fr)
    row["tests_per_ray"] = tests / rays if rays else 0.0
    row["covered_pixels"] = mean(f["covered_pixels"] for f in fr)
    row["triangles"] = rep["scene"]["triangles_expanded"]
    return row


def write_csv(name, rows, fields, commands):
    path = os.path.join(HERE, name)
    with open(path, "w", newline="") as f:
        f.write(f"# command: {COMMAND}; {THREADS} threads; OMP_WAIT_POLICY=passive; runs: "
                f"{' | '.join(commands)}\n")
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    print("wrote", path)


def read_csv(name):
    with open(os.path.join(HERE, name)) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith("#")))
    for r in rows:
        for k, v in r.items():
            try:
                r[k] = float(v)
            except (TypeError, ValueError):
                pass
    return rows


# ---------------------------------------------------------------------------------------------
# The paper's experiment.

PAPER_SCENE = "builtin:city?blocks=12"
# Each paper run twice, best time per frame: the machine is shared, and a burst of another job
# during one run otherwise moves a variant's mean by 30 % (z-buffer means of 100-140 ms seen on
# the same frames).
PAPER_REPEATS = 1 if QUICK else 2


def paper_subset():
    """--variants=a,b,...: the paper variants to run now (default: all). The others keep their
    rows from the existing CSVs, so the study can be timed in several shorter locked runs."""
    for a in sys.argv[1:]:
        if a.startswith("--variants="):
            want = a.split("=", 1)[1].split(",")
            unknown = [v for v in want if v not in dict(VARIANTS)]
            if unknown:
                sys.exit(f"unknown paper variants {unknown}; known: {[n for n, _ in VARIANTS]}")
            return want
    return [n for n, _ in VARIANTS]


def merge_rows(name, new_rows, ran):
    """new_rows for the variants in `ran`, the existing CSV's rows for the others, in VARIANTS
    order."""
    old = []
    if len(ran) < len(VARIANTS) and os.path.exists(os.path.join(HERE, name)):
        with open(os.path.join(HERE, name)) as f:
            old = [r for r in csv.DictReader(l for l in f if not l.startswith("#"))
                   if r["stage"] not in ran]
    rows = old + new_rows
    order = {n: i for i, (n, _) in enumerate(VARIANTS)}
    return sorted(rows, key=lambda r: (order.get(r["stage"], len(order)), int(r.get("frame", 0))))


def paper():
    frames = 8 if QUICK else 80
    ran = paper_subset()
    rows, frame_rows, commands = [], [], []
    for stage, args in VARIANTS:
        if stage not in ran:
            continue
        cmd, rep = render(PAPER_SCENE, args, frames, repeats=PAPER_REPEATS)
        commands.append(cmd)
        row = summary(rep)
        row["stage"] = stage
        row["command"] = cmd
        rows.append(row)
        for f in rep["frames"]:
            c = f["counts"]
            frame_rows.append({
                "stage": stage, "frame": f["frame"], "lzb_s": f["seconds"],
                "zbuffer_s": f["reference_seconds"], "covered_pixels": f["covered_pixels"],
                "correct": f["accuracy"]["correct_rate_covered"],
                "exact_id": f["accuracy"]["exact_id_rate_covered"],
                **{k: c.get(k, 0.0) for k in COUNTS}})
        print(f"paper {stage:10s} lzb {row['lzb_mean_s']*1e3:7.1f} ms  zbuffer "
              f"{row['zbuffer_mean_s']*1e3:7.1f} ms  speedup {row['speedup_mean']:5.2f}x  "
              f"correct >= {row['correct_min']:.5f}", flush=True)
    fields = (["stage", "triangles", "frames", "lzb_mean_s", "zbuffer_mean_s", "speedup_mean",
               "lzb_median_s", "zbuffer_median_s", "speedup_median", "correct_min",
               "correct_mean", "exact_id_min", "exact_id_mean", "tests_per_ray"] +
              ["t_" + s for s in STAGE_TIMES] + COUNTS + ["command"])
    if len(ran) < len(VARIANTS):
        commands.append("other variants: rows of earlier runs (see each row's command)")
    write_csv("paper.csv", merge_rows("paper.csv", rows, ran), fields, commands)
    write_csv("paper_frames.csv", merge_rows("paper_frames.csv", frame_rows, ran),
              ["stage", "frame", "lzb_s", "zbuffer_s", "covered_pixels", "correct", "exact_id"] +
              COUNTS, commands)


def plot_paper():
    rows = read_csv("paper.csv")
    frames = read_csv("paper_frames.csv")
    # Frame time along the path: z-buffer and every stage.
    names = [n for n, _ in VARIANTS]
    blocks = [[(f["frame"], f["zbuffer_s"] * 1e3) for f in frames if f["stage"] == "final"]]
    for st in names:
        blocks.append([(f["frame"], f["lzb_s"] * 1e3) for f in frames if f["stage"] == st])
    data = common.datafile(blocks)
    plots = [f"'{data}' index 0 with lines lw 2 lc rgb 'black' title 'zbuffer'"]
    plots += [f"'{data}' index {i + 1} with lines title 'lzb {st}'" for i, st in enumerate(names)]
    common.gnuplot(f"""
set terminal pngcairo size 900,500
set output '{os.path.join(HERE, "paper_frame_time.png")}'
set title 'City 1.8 M triangles, 512x512, {THREADS} threads: frame time along the circle'
set xlabel 'frame'
set ylabel 'frame time [ms]'
set logscale y
set grid
set key outside right
plot {', '.join(plots)}
""")
    os.unlink(data)
    # Mean frame time per stage, split into stage seconds, beside the z-buffer.
    parts = ["cull", "plane", "near", "unfinished", "oor_project", "raycast", "pvl_find",
             "pvl_render", "shade"]
    lines = []
    for r in rows:
        vals = [r["t_" + p] * 1e3 for p in parts]
        other = max(r["lzb_mean_s"] * 1e3 - sum(vals), 0.0)
        lines.append([f"{r['stage']}"] + vals + [other])
    zb = mean(r["zbuffer_mean_s"] for r in rows) * 1e3  # the z-buffer of every run, averaged
    lines.append(["zbuffer"] + [0.0] * len(parts) + [zb])
    data = common.datafile([lines])
    cols = " ".join(f"'{data}' using {i + 2}{':xtic(1)' if i == 0 else ''} title '{n}',"
                    for i, n in enumerate([p.replace("_", " ") for p in parts] +
                                          ["other / z-buffer"]))
    common.gnuplot(f"""
set terminal pngcairo size 1000,500
set output '{os.path.join(HERE, "paper_stages.png")}'
set title 'Mean frame time per stage (80 frames, city 1.8 M triangles, 512x512)'
set ylabel 'mean frame time [ms]'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set key outside right
set grid y
plot {cols.rstrip(',')}
""")
    os.unlink(data)


# ---------------------------------------------------------------------------------------------
# Local occluder selection.

def occluders():
    frames = 4 if QUICK else 16
    rows, commands = [], []
    for mode in ["static", "dynamic", "hybrid"]:
        for k in [1, 3, 5, 10]:
            cmd, rep = render(PAPER_SCENE, ["--lzb-stage", "final", "--occluder-mode", mode,
                                            "--occluders", str(k)], frames)
            commands.append(cmd)
            row = summary(rep)
            row.update(mode=mode, K=k)
            rows.append(row)
            print(f"occluders {mode:7s} K={k:2d}: {row['tests_per_ray']:6.2f} tests/ray  PVL "
                  f"{row['pvl_size']:9.0f}  find {row['pvl_find_median_s']*1e3:6.1f} ms  render "
                  f"{row['pvl_render_median_s']*1e3:6.1f} ms  frame "
                  f"{row['lzb_median_s']*1e3:6.1f} ms (medians)", flush=True)
    # Every triangle tested (lazy's test) with the same OOR rays and walk, as the baseline:
    # K = 0 static occluders would test nothing, so "lazy" is the final stage with K = all.
    cmd, rep = render(PAPER_SCENE, ["--lzb-stage", "final", "--occluder-mode", "static",
                                    "--occluders", "1000"], frames)
    commands.append(cmd)
    row = summary(rep)
    row.update(mode="lazy", K=0)
    rows.append(row)
    write_csv("occluders.csv", rows,
              ["mode", "K", "frames", "tests_per_ray", "pvl_size", "t_pvl_find", "t_pvl_render",
               "pvl_find_median_s", "pvl_render_median_s", "lzb_median_s", "zbuffer_median_s",
               "speedup_median", "lzb_mean_s", "zbuffer_mean_s", "speedup_mean", "correct_min",
               "exact_id_min",
               "rays_cast", "ray_triangle_tests", "visibility_tests", "octree_nodes_visited"],
              commands)


def plot_occluders():
    rows = read_csv("occluders.csv")
    modes = ["static", "dynamic", "hybrid"]
    blocks = [[(r["K"], r["tests_per_ray"], r["pvl_size"], r["pvl_find_median_s"] * 1e3,
                r["lzb_median_s"] * 1e3) for r in rows if r["mode"] == m] for m in modes]
    lazy = [r for r in rows if r["mode"] == "lazy"][0]
    data = common.datafile(blocks)

    def panel(col, label, lazyval):
        p = ", ".join(f"'{data}' index {i} using 1:{col} with linespoints title '{m}'"
                      for i, m in enumerate(modes))
        return f"set ylabel '{label}'\nplot {p}, {lazyval} with lines dt 2 lc rgb 'black' title 'all'\n"

    common.gnuplot(f"""
set terminal pngcairo size 1200,400
set output '{os.path.join(HERE, "occluders.png")}'
set multiplot layout 1,4 title 'Local occluders in the final stage (city 1.8 M, 512x512; dashed: every triangle tested)'
set xlabel 'K occluders per leaf'
set xtics (1, 3, 5, 10)
set grid
set key top right
{panel(2, 'ray-triangle tests per ray', lazy['tests_per_ray'])}
{panel(3, 'PVL size [triangles]', lazy['pvl_size'])}
{panel(4, 'PVL finding, median [ms]', lazy['pvl_find_median_s'] * 1e3)}
{panel(5, 'frame time, median [ms]', lazy['lzb_median_s'] * 1e3)}
unset multiplot
""")
    os.unlink(data)


# ---------------------------------------------------------------------------------------------
# Output sensitivity.

MESHES = ["bunny00.off", "armadillo.off", "ChineseDragon-10kv.off", "mannequin-devil.off",
          "elephant.off", "fandisk.off"]


def off_bounds(path):
    with open(path) as f:
        toks = f.read().split()
    n = int(toks[1])
    vals = [float(v) for v in toks[4:4 + 3 * n]]
    lo = [min(vals[k::3]) for k in range(3)]
    hi = [max(vals[k::3]) for k in range(3)]
    return lo, hi


def assembly(k):
    """A TOML scene: k x k 'zoos' of the six scanned meshes (k = 0: the dragon alone), each mesh
    scaled to unit size and standing on y = 0, seen from the grid's edge at eye height."""
    os.makedirs(os.path.join(HERE, "scenes"), exist_ok=True)
    path = os.path.join(HERE, "scenes", f"assembly_{k}.toml")
    meshes = MESHES if k > 0 else ["ChineseDragon-10kv.off"]
    rel = os.path.relpath(DATA, os.path.dirname(path))
    lines = ['root = "world"', ""]
    places = []
    for i, m in enumerate(meshes):
        lo, hi = off_bounds(os.path.join(DATA, m))
        s = 1.0 / max(h - l for h, l in zip(hi, lo))
        c = [(h + l) / 2 for h, l in zip(hi, lo)]
        x, z = 1.5 * (i % 3), 1.5 * (i // 3)
        places.append((f"m{i}", s, [x - s * c[0], -s * lo[1], z - s * c[2]]))
        lines += ["[[meshes]]", f'name = "m{i}"', f'file = "{rel}/{m}"', ""]
    lines += ["[[nodes]]", 'name = "zoo"', "instances = ["]
    lines += [f'  {{ node = "{n}", translate = [{t[0]:.6g}, {t[1]:.6g}, {t[2]:.6g}], scale = {s:.6g} }},'
              for n, s, t in places]
    lines += ["]", ""]
    side = max(k, 1)
    pitch = 5.0
    lines += ["[[nodes]]", 'name = "world"', "instances = ["]
    lines += [f'  {{ node = "zoo", translate = [{pitch * i:.6g}, 0, {pitch * j:.6g}] }},'
              for i in range(side) for j in range(side)]
    lines += ["]", ""]
    extent = pitch * (side - 1) + 3.0
    cx, cz = extent / 2 - 0.25, extent / 2 - 0.75
    lines += ["[camera]", f"position = [{cx:.6g}, 0.8, {-0.3 * extent - 2:.6g}]",
              f"look_at = [{cx:.6g}, 0.4, {cz:.6g}]", "fov = 50", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return path


def size():
    frames = 4 if QUICK else 16
    scenes = [("city", f"builtin:city?blocks={b}") for b in ([1, 2, 4, 8] if QUICK else [1, 2, 4, 8, 12, 18])]
    scenes += [("assembly", assembly(k)) for k in ([0, 1, 2] if QUICK else [0, 1, 2, 3, 5])]
    rows, frame_rows, commands = [], [], []
    for family, scene in scenes:
        cmd, rep = render(scene, [], frames)
        commands.append(cmd)
        cmd2, diag = render(scene, ["--lzb-depth-complexity", "32"], frames, reference=False,
                            timed=False)
        commands.append(cmd2)
        row = summary(rep)
        row.update(family=family, scene=os.path.relpath(scene, ROOT) if os.path.exists(scene) else scene)
        row["depth_complexity"] = mean(f["counts"]["depth_complexity"] for f in diag["frames"])
        row["depth_complexity_covered"] = mean(
            f["counts"]["depth_complexity_covered"] for f in diag["frames"])
        rows.append(row)
        for f, d in zip(rep["frames"], diag["frames"]):
            frame_rows.append({
                "family": family, "triangles": row["triangles"], "frame": f["frame"],
                "lzb_s": f["seconds"], "zbuffer_s": f["reference_seconds"],
                "covered_pixels": f["covered_pixels"],
                "depth_complexity": d["counts"]["depth_complexity"],
                "depth_complexity_covered": d["counts"]["depth_complexity_covered"],
                "correct": f["accuracy"]["correct_rate_covered"]})
        print(f"size {family:8s} {row['triangles']:>10,} tris  lzb {row['lzb_mean_s']*1e3:7.1f} ms  "
              f"zbuffer {row['zbuffer_mean_s']*1e3:7.1f} ms  speedup {row['speedup_mean']:5.2f}x  "
              f"depth complexity {row['depth_complexity_covered']:5.1f}  correct >= "
              f"{row['correct_min']:.5f}", flush=True)
    write_csv("size.csv", rows,
              ["family", "scene", "triangles", "frames", "lzb_mean_s", "zbuffer_mean_s",
               "speedup_mean", "correct_min", "exact_id_mean", "covered_pixels",
               "depth_complexity", "depth_complexity_covered", "near_triangles", "pvl_size",
               "rays_cast", "plane_depth"], commands)
    write_csv("size_frames.csv", frame_rows,
              ["family", "triangles", "frame", "lzb_s", "zbuffer_s", "covered_pixels",
               "depth_complexity", "depth_complexity_covered", "correct"], commands)


def plot_size():
    rows = read_csv("size.csv")
    frames = read_csv("size_frames.csv")
    fams = ["city", "assembly"]
    blocks = []
    for fam in fams:
        blocks.append([(r["triangles"], r["lzb_mean_s"] * 1e3, r["zbuffer_mean_s"] * 1e3)
                       for r in rows if r["family"] == fam])
    data = common.datafile(blocks)
    p = []
    for i, fam in enumerate(fams):
        p.append(f"'{data}' index {i} using 1:2 with linespoints pt 7 title 'lzb {fam}'")
        p.append(f"'{data}' index {i} using 1:3 with linespoints pt 5 dt 2 title 'zbuffer {fam}'")
    common.gnuplot(f"""
set terminal pngcairo size 800,500
set output '{os.path.join(HERE, "size_scene.png")}'
set title 'Frame time against scene size (512x512, {THREADS} threads, mean over the path)'
set logscale xy
set xlabel 'triangles'
set ylabel 'mean frame time [ms]'
set grid
set key left top
plot {', '.join(p)}
""")
    os.unlink(data)
    # Image and depth complexity vary with the view: every frame of the scene of each family
    # closest to 1.8 M triangles (so scene size does not mix in).
    chosen = {fam: min((r["triangles"] for r in rows if r["family"] == fam),
                       key=lambda t: abs(t - 1.8e6)) for fam in fams}
    for measure, label, name in [("covered_pixels", "image complexity: covered pixels", "size_image.png"),
                                 ("depth_complexity_covered", "depth complexity: surfaces per covered ray", "size_depth.png")]:
        blocks = []
        for fam in fams:
            blocks.append([(f[measure], f["lzb_s"] * 1e3, f["zbuffer_s"] * 1e3)
                           for f in frames if f["family"] == fam and f["triangles"] == chosen[fam]])
        data = common.datafile(blocks)
        p = []
        for i, fam in enumerate(fams):
            p.append(f"'{data}' index {i} using 1:2 with points pt 7 title 'lzb {fam} {chosen[fam] / 1e6:.1f} M'")
            p.append(f"'{data}' index {i} using 1:3 with points pt 6 title 'zbuffer {fam} {chosen[fam] / 1e6:.1f} M'")
        common.gnuplot(f"""
set terminal pngcairo size 900,500
set output '{os.path.join(HERE, name)}'
set key outside right
set title 'Frame time against {label.split(":")[0]} (every frame along the path)'
set logscale y
set xlabel '{label}'
set ylabel 'frame time [ms]'
set grid
plot {', '.join(p)}
""")
        os.unlink(data)


# ---------------------------------------------------------------------------------------------
# Frame coherence of the partition plane.

def reuse():
    frames = 72 if QUICK else 720
    rows, commands = [], []
    for n in [8, 0]:
        cmd, rep = render(PAPER_SCENE, ["--plane-reuse", str(n)], frames, size=256,
                          reference=False)
        commands.append(cmd)
        row = summary(rep)
        fr = rep["frames"]
        row.update(plane_reuse=n, reused_frames=sum(f["counts"]["plane_reused"] for f in fr),
                   coarse_rays=mean(f["counts"]["coarse_rays"] for f in fr))
        rows.append(row)
        print(f"reuse {n}: {row['reused_frames']:.0f} of {frames} frames reused the plane; plane "
              f"{row['t_plane'] * 1e3:.3f} ms, frame {row['lzb_mean_s'] * 1e3:.1f} ms", flush=True)
    write_csv("reuse.csv", rows, ["plane_reuse", "frames", "reused_frames", "coarse_rays",
                                  "t_plane", "lzb_mean_s", "unfinished_pixels", "rays_cast",
                                  "near_triangles", "pvl_size"], commands)


def plot_reuse():
    pass  # two rows: the CSV says it all


if __name__ == "__main__":
    os.makedirs(HERE, exist_ok=True)
    for study, run, plot in [("paper", paper, plot_paper), ("occluders", occluders, plot_occluders),
                             ("size", size, plot_size), ("reuse", reuse, plot_reuse)]:
        if study not in WANT:
            continue
        if not PLOT_ONLY:
            run()
        plot()
        print("plotted", study)
