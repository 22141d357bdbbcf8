#!/usr/bin/env python3
"""The randomized sample tree study (Klein et al., sections 4-6), in parts, each a list of rows of
one CSV:

- build: preprocessing throughput of `lzb build-tree` on builtin:landscape (every triangle stored,
  none instanced) in memory and out of core (--mem-mb 256), triangles per second, the build's peak
  resident memory (the process's, from wait4) and whether the two stores are byte-identical.
  --scale adds the 10^8-triangle landscape (4,194,304 objects) built with --mem-mb 2048, then
  rendered out of core (node caches of 512 and 256 MiB, the default 5-frame circle; and a walk
  of 16 frames 0.1 degree apart with caches of 512 and 1,400 MiB; the scene is not loaded), and
  raycast on the same scene, each with its peak memory.
- path: an 800-frame circle over a landscape store read out of core (--cache-mb 16): per frame,
  nodes visited, loaded (the paper: at most ~100 per frame) and prefetched, bytes read, the wait
  for loads and the frame time (path.csv, one row per frame).
- splat: far-off splatting sizes 1-5 against raycast in the same run, on the landscape and on a
  sub-pixel field of scanned meshes (the armadillo), frame time and accuracy.
- trade: at 10^7 triangles (builtin:landscape?objects=400000), trees built with c in {13.8, 4}
  and leaf sizes {8, 32, 128}, each rendered in core with splat sizes 1 and 2 against raycast:
  triangles drawn, frame time and accuracy, raycast's frame in the same run.
- server: the same out-of-core walk on 1 rank, 2 ranks each reading the store, and 2 and 3 ranks
  with --node-server (one rank serving nodes to the others), where the option exists.

Usage: python3 runs/sampletree/run.py [--quick] [--scale | --only PART,...] [--plot-only] [--no-wait]
       (--only build,scale reruns those parts alone, keeping the other parts' rows of the CSV)
       (from the repository root, after scripts/build.sh and scripts/fetch-test-meshes.sh build/data;
       plots need gnuplot)
Writes runs/sampletree/sampletree.csv, path.csv and sampletree.png; --quick (small scenes, few
frames, no waiting for a quiet machine: a check that the script works) writes quick*.csv/png.
"""
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

# A mistyped option is refused before anything runs (or a CSV is overwritten).
common.accept_args(flags=("--quick", "--scale", "--plot-only"), followed=("--only",))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
ONLY = sys.argv[sys.argv.index("--only") + 1].split(",") if "--only" in sys.argv else []
SCALE = "--scale" in sys.argv or "scale" in ONLY
NAME = "quick" if QUICK else "sampletree"
W, H = (160, 120) if QUICK else (640, 480)
FRAMES = 2 if QUICK else 10
PATH_FRAMES = 20 if QUICK else 800
BUILD_OBJECTS = [2000] if QUICK else [20000, 200000, 600000]
WALK = "builtin:landscape?objects=2000" if QUICK else "builtin:landscape?objects=20000"
SERVER = "builtin:landscape?objects=2000" if QUICK else "builtin:landscape?objects=200000"
FIELD = (f"builtin:replicated?mesh={common.DATA}/armadillo.off&k=2&levels=1" if QUICK else
         f"builtin:replicated?mesh={common.DATA}/armadillo.off&k=4&levels=2")
SCALE_OBJECTS = 4194304
TRADE = "builtin:landscape?objects=2000" if QUICK else "builtin:landscape?objects=400000"
TRADE_TREES = [(13.8, 32), (4.0, 32), (13.8, 8), (4.0, 8), (13.8, 128)]
SCRATCH = os.environ.get("LZB_SCRATCH", tempfile.gettempdir())
WAIT = not QUICK and "--no-wait" not in sys.argv

FIELDS = ["part", "scene", "config", "ranks", "triangles", "seconds", "triangles_per_s",
          "peak_rss_mb", "store_bytes", "identical", "median_frame_s", "median_nodes_visited",
          "median_nodes_loaded", "median_triangles_drawn", "median_splats_drawn",
          "median_load_wait_s", "median_correct_rate_covered", "min_correct_rate_covered",
          "psnr_aa", "peak_memory_mb"]
PATH_FIELDS = ["frame", "seconds", "nodes_visited", "nodes_stopped", "nodes_loaded",
               "nodes_prefetched", "cache_hits", "bytes_read", "load_wait_s", "triangles_drawn"]


def timed(cmd):
    """Runs cmd; returns (wall seconds, peak resident MiB of the process, stdout)."""
    if WAIT:
        common.wait_quiet()
    t = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, env=common.ENV)
    out = p.stdout.read().decode()
    _, status, usage = os.wait4(p.pid, 0)
    seconds = time.perf_counter() - t
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}")
    return seconds, usage.ru_maxrss / 1024.0, out


def shown(cmd):
    return " ".join(cmd).replace(common.ROOT + "/", "").replace(SCRATCH + "/", "SCRATCH/")


def build(scene, store, mem_mb=0):
    cmd = [common.LZB, "build-tree", scene, "--out", store, "--threads", str(common.CORES)]
    if mem_mb:
        cmd += ["--mem-mb", str(mem_mb)]
    seconds, rss, out = timed(cmd)
    tris = int(re.search(r"sample tree of (\d+) triangles", out).group(1))
    return cmd, {"seconds": seconds, "triangles": tris, "triangles_per_s": tris / seconds,
                 "peak_rss_mb": rss, "store_bytes": os.path.getsize(store)}


def frame_row(part, scene, config, ranks, rep):
    fr = rep["frames"][1:] or rep["frames"]  # the first frame fills the cache
    c = lambda k: common.median(f["counts"].get(k, 0.0) for f in fr)  # noqa: E731
    acc = [f["accuracy"] for f in fr if "accuracy" in f]
    row = {"part": part, "scene": scene, "config": config, "ranks": ranks,
           "median_frame_s": common.median(f["seconds"] for f in fr),
           "median_nodes_visited": c("nodes_visited"), "median_nodes_loaded": c("nodes_loaded"),
           "median_triangles_drawn": c("triangles_drawn"), "median_splats_drawn": c("splats_drawn"),
           "median_load_wait_s": c("load_wait_seconds"),
           "peak_memory_mb": max(f["peak_memory_bytes"] for f in rep["frames"]) / 2**20}
    if acc:
        row["median_correct_rate_covered"] = common.median(a["correct_rate_covered"] for a in acc)
        row["min_correct_rate_covered"] = min(a["correct_rate_covered"] for a in acc)
        row["psnr_aa"] = common.median(a["psnr_aa"] or 99.0 for a in acc)
    return row


def render(scene, args, ranks=1, frames=FRAMES):
    threads = max(1, common.CORES // ranks)
    return common.render(scene, [*args, "--frames", str(frames), "--width", str(W), "--height",
                                 str(H)], ranks=ranks, threads=threads, quiet_wait=WAIT)


class Study:
    def __init__(self):
        self.rows, self.commands = [], []

    def keep_all_but(self, parts):
        """The rows of the existing CSV (and their commands, in order) except those of `parts`."""
        path = os.path.join(HERE, f"{NAME}.csv")
        with open(path) as f:
            commands = [line[2:].rstrip("\n") for line in f if line.startswith("# ")][1:]
        for row, cmd in zip(common.read_csv(path), commands):
            if row["part"] not in parts:
                self.rows.append(row)
                self.commands.append(cmd)

    def add(self, row, command):
        self.rows.append(row)
        self.commands.append(command)
        print({k: (round(v, 4) if isinstance(v, float) else v) for k, v in row.items()
               if v not in ("", None)}, flush=True)
        common.write_csv(os.path.join(HERE, f"{NAME}.csv"), self.rows, FIELDS, self.commands)

    def build_part(self):
        for objects in BUILD_OBJECTS:
            scene = f"builtin:landscape?objects={objects}"
            stores = {}
            for config, mem in (("in_memory", 0), ("external_256mb", 256)):
                stores[config] = os.path.join(SCRATCH, f"lzb-st-{config}.lzbtree")
                cmd, r = build(scene, stores[config], mem)
                self.add({"part": "build", "scene": scene, "config": config, "ranks": 1, **r},
                         shown(cmd))
            same = subprocess.run(["cmp", "-s", *stores.values()]).returncode == 0
            self.rows[-1]["identical"] = self.rows[-2]["identical"] = int(same)
            for s in stores.values():
                os.remove(s)

    def path_part(self):
        store = os.path.join(SCRATCH, "lzb-st-walk.lzbtree")
        build(WALK, store)
        cmd, rep = common.render(WALK, ["--method", "sampletree", "--tree", store, "--cache-mb", "16",
                                        "--frames", str(PATH_FRAMES), "--width", str(W),
                                        "--height", str(H)], threads=common.CORES, quiet_wait=WAIT)
        rows = [{"frame": f["frame"], "seconds": f["seconds"], "load_wait_s":
                 f["counts"].get("load_wait_seconds", 0.0),
                 **{k: f["counts"].get(k, 0.0) for k in PATH_FIELDS if k in f["counts"]}}
                for f in rep["frames"]]
        common.write_csv(os.path.join(HERE, f"{NAME}_path.csv"), rows, PATH_FIELDS,
                         [shown(cmd.split())])
        self.add(frame_row("path", WALK, "cache_16mb", 1, rep), shown(cmd.split()))
        os.remove(store)

    def splat_part(self):
        for scene in (WALK, FIELD):
            store = os.path.join(SCRATCH, "lzb-st-splat.lzbtree")
            build(scene, store)
            for d in range(1, 6):
                cmd, rep = render(scene, ["--method", "sampletree", "--tree", store, "--splat",
                                          str(d), "--reference", "raycast"])
                self.add(frame_row("splat", scene, f"splat{d}", 1, rep), cmd)
            cmd, rep = render(scene, ["--method", "raycast", "--reference", "zbuffer"])
            self.add(frame_row("splat", scene, "raycast", 1, rep), cmd)
            os.remove(store)

    def trade_part(self):
        store = os.path.join(SCRATCH, "lzb-st-trade.lzbtree")
        for c, leaf in TRADE_TREES:
            cmd = [common.LZB, "build-tree", TRADE, "--out", store, "--c", str(c),
                   "--leaf-triangles", str(leaf), "--threads", str(common.CORES), "--quiet"]
            subprocess.run(cmd, check=True, env=common.ENV)
            built = shown(cmd)
            for d in (1, 2):
                cmd, rep = render(TRADE, ["--method", "sampletree", "--tree", store, "--splat",
                                          str(d), "--reference", "raycast"], frames=6)
                self.add(frame_row("trade", TRADE, f"c{c:g}_leaf{leaf}_splat{d}", 1, rep),
                         f"{built} && {cmd.replace(SCRATCH + '/', 'SCRATCH/')}")
        os.remove(store)
        cmd, rep = render(TRADE, ["--method", "raycast"], frames=6)
        self.add(frame_row("trade", TRADE, "raycast", 1, rep), cmd)

    def server_part(self):
        store = os.path.join(SCRATCH, "lzb-st-server.lzbtree")
        build(SERVER, store)
        ooc = ["--method", "sampletree", "--tree", store, "--cache-mb", "64"]
        has_server = "--node-server" in subprocess.run([common.LZB, "render", "--help"],
                                                       capture_output=True, text=True).stdout
        configs = [("local", 1, []), ("local", 2, [])]
        if has_server:
            configs += [("node_server", 2, ["--node-server"]), ("node_server", 3, ["--node-server"])]
        for config, ranks, extra in configs:
            cmd, rep = render(SERVER, [*ooc, *extra], ranks=ranks)
            self.add(frame_row("server", SERVER, config, ranks, rep), cmd)
        os.remove(store)

    def scale_part(self):
        scene = f"builtin:landscape?objects={SCALE_OBJECTS}"
        store = os.path.join(SCRATCH, "lzb-st-scale.lzbtree")
        cmd, r = build(scene, store, 2048)
        self.add({"part": "scale", "scene": scene, "config": "external_2048mb", "ranks": 1, **r},
                 shown(cmd))
        tree = ["--method", "sampletree", "--tree", store]
        # The default circle's 5 frames lie 72 degrees apart; the walk is 16 frames of a
        # 3600-frame circle (0.1 degree, ~11 units apart): a camera moving, the cache coherent.
        five, walk = ["--frames", "5"], ["--frames", "3600", "--frame-range", "0:16"]
        for config, args in (("sampletree_cache_512mb", [*tree, "--cache-mb", "512", *five]),
                             ("sampletree_cache_256mb", [*tree, "--cache-mb", "256", *five]),
                             ("walk_cache_512mb", [*tree, "--cache-mb", "512", *walk]),
                             ("walk_cache_1400mb", [*tree, "--cache-mb", "1400", *walk]),
                             ("raycast", ["--method", "raycast", *five])):
            cmd = [common.LZB, "render", scene, *args, "--width", str(W),
                   "--height", str(H), "--threads", str(common.CORES), "--quiet", "--out",
                   os.path.join(SCRATCH, "lzb-st-scale-out")]
            seconds, rss, _ = timed(cmd)
            import json
            with open(os.path.join(SCRATCH, "lzb-st-scale-out", "report.json")) as f:
                rep = json.load(f)
            row = frame_row("scale", scene, config, 1, rep)
            row.update({"seconds": seconds, "peak_rss_mb": rss})
            self.add(row, shown(cmd))
        os.remove(store)


def plot():
    rows = common.read_csv(os.path.join(HERE, f"{NAME}.csv"))
    path = common.read_csv(os.path.join(HERE, f"{NAME}_path.csv"))
    walk = [(int(float(r["frame"])), float(r["nodes_loaded"]), float(r["nodes_visited"]),
             float(r["seconds"]) * 1e3) for r in path]
    splat = [r for r in rows if r["part"] == "splat" and r["config"].startswith("splat")]
    scenes = sorted({r["scene"] for r in splat})
    blocks = [walk] + [[(int(r["config"][5:]), float(r["median_frame_s"]) * 1e3,
                         100 * float(r["median_correct_rate_covered"] or "nan"))
                        for r in splat if r["scene"] == s] for s in scenes]
    peer = {r["scene"]: float(r["median_frame_s"]) * 1e3 for r in rows
            if r["part"] == "splat" and r["config"] == "raycast"}
    blocks += [[(1, peer.get(s, float("nan")), 0), (5, peer.get(s, float("nan")), 0)] for s in scenes]
    trade = [r for r in rows if r["part"] == "trade" and "splat" in r["config"]]
    blocks += [[(float(r["median_frame_s"]) * 1e3, 100 * float(r["median_correct_rate_covered"]))
                for r in trade if r["config"].endswith(f"splat{d}")] for d in (1, 2)]
    trade_peer = [float(r["median_frame_s"]) * 1e3 for r in rows
                  if r["part"] == "trade" and r["config"] == "raycast"]
    data = common.datafile(blocks)
    first_trade = 1 + 2 * len(scenes)
    short = [s.replace("builtin:", "").split("&")[0].replace(common.DATA + "/", "") for s in scenes]
    splat_lines = lambda col: ", ".join(  # noqa: E731
        [f"'{data}' index {1 + k} using 1:{col} with linespoints pt {4 + k} title '{t}'"
         for k, t in enumerate(short)] +
        ([f"'{data}' index {1 + len(scenes) + k} using 1:2 with lines dt 2 lw 2 title 'raycast, {t}'"
          for k, t in enumerate(short)] if col == 2 else []))
    common.gnuplot(f"""
set terminal pngcairo size 1000,1450 font ',10' noenhanced
set output '{os.path.join(HERE, f"{NAME}.png")}'
set multiplot layout 4,1 title "randomized sample tree at {W}x{H} ({common.CORES} cores)"
set grid
set key outside right
set xlabel 'frame of the {len(walk)}-frame circle (out of core, 16 MiB cache)'
set ylabel 'nodes / frame (log)'
set logscale y
plot '{data}' index 0 using 1:2 with lines title 'nodes loaded', '' index 0 using 1:3 with lines title 'nodes visited'
set xlabel 'splat size d (far-off splatting)'
set ylabel 'frame time (ms, log)'
plot {splat_lines(2)}
unset logscale y
set ylabel 'correct pixels, covered (%)'
plot {splat_lines(3)}
set xlabel 'frame time (ms), 10^7 landscape in core; trees of c in (13.8, 4), leaf size in (8, 32, 128)'
set xrange [0:*]
{"set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lw 2" % (trade_peer[0], trade_peer[0]) if trade_peer else ""}
plot '{data}' index {first_trade} using 1:2 with points pt 7 title 'splat 1', '' index {first_trade + 1} using 1:2 with points pt 5 title 'splat 2 (dashed: raycast)'
unset multiplot
""")


if __name__ == "__main__":
    if ONLY:
        s = Study()
        s.keep_all_but(ONLY)
        for part in ONLY:
            getattr(s, f"{part}_part")()
    elif "--plot-only" not in sys.argv:
        s = Study()
        s.build_part()
        s.path_part()
        s.splat_part()
        s.server_part()
        s.trade_part()
        if SCALE:
            s.scale_part()
    plot()
