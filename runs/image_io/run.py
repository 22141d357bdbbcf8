#!/usr/bin/env python3
"""Image I/O and process starts: what a start of a program costs with and without OpenImageIO's
shared libraries (empty programs linked with each set, and `lzb --help`), and, given an lzb built
with the former OpenImageIO writer (--baseline=PATH, e.g. a build of commit 12fe001), the whole
`lzb render` of 12 frames at 1920x1080 on a small scene, where writing the frames is most of the
time: this build (A) and the baseline (B) in turn, medians of RUNS each.

Usage: python3 runs/image_io/run.py [--quick] [--baseline=PATH]   (from the repository root,
       after scripts/build.sh; needs g++ and libopenimageio-dev)
Writes runs/image_io/startup.csv (one row per program) and, with --baseline, render_ab.csv.
"""
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(flags=("--quick",), valued=("baseline",))

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
RUNS = 3 if QUICK else 11
BASELINE = common.option("baseline", [None])[0]
# The libraries lzb links besides the image writer.
LZB_LIBS = ["-lembree3", "-lOSMesa", "-lassimp", "-lmpi", "-lgomp"]
PROGRAMS = {"empty": [], "empty + OpenImageIO": ["-lOpenImageIO", "-lOpenImageIO_Util"],
            "empty + lzb's other libraries": LZB_LIBS,
            "empty + both": LZB_LIBS + ["-lOpenImageIO", "-lOpenImageIO_Util"]}
RENDER = ["render", "builtin:sphereflake?depth=1", "--width", "1920", "--height", "1080",
          "--frames", "12", "--method", "zbuffer", "--threads", "2", "--quiet"]


def seconds_of(cmd):
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=common.ENV)
    return time.perf_counter() - t


def libraries(path):
    out = subprocess.run(["ldd", path], check=True, capture_output=True, text=True).stdout
    return len(out.splitlines())


def build_empty_programs(folder):
    source = os.path.join(folder, "empty.cpp")
    with open(source, "w") as f:
        f.write("int main() { return 0; }\n")
    paths = {}
    for i, (name, libs) in enumerate(PROGRAMS.items()):
        paths[name] = os.path.join(folder, f"empty{i}")
        # --no-as-needed: keep the libraries an empty program does not call.
        subprocess.run(["g++", source, "-o", paths[name], "-Wl,--no-as-needed", *libs], check=True)
    return paths


def startup_rows(folder):
    rows, commands = [], []
    programs = {name: [path] for name, path in build_empty_programs(folder).items()}
    programs["lzb --help"] = [common.LZB, "--help"]
    if BASELINE:
        programs["baseline lzb --help"] = [BASELINE, "--help"]
    common.wait_quiet()
    for name, cmd in programs.items():
        times = [seconds_of(cmd) for _ in range(RUNS)]
        rows.append({"program": name, "libraries": libraries(cmd[0]),
                     "start_s": round(common.median(times), 4), "runs": RUNS})
        commands.append(" ".join(cmd).replace(folder, "TMP").replace(common.ROOT + "/", ""))
        print(f"{name}: {rows[-1]['start_s']} s, {rows[-1]['libraries']} libraries", flush=True)
    return rows, commands


def render_ab_rows(folder):
    a = [common.LZB, *RENDER, "--out", os.path.join(folder, "a")]
    b = [BASELINE, *RENDER, "--out", os.path.join(folder, "b")]
    common.wait_quiet()
    times = {"A": [], "B": []}
    for _ in range(RUNS):  # in turn, so a drift of the machine's speed falls on both
        times["A"].append(seconds_of(a))
        times["B"].append(seconds_of(b))
    ma, mb = common.median(times["A"]), common.median(times["B"])
    print(f"12 frames at 1080p: this build {ma:.3f} s, baseline {mb:.3f} s, A/B {ma / mb:.3f}")
    rows = [{"build": "A (this)", "wall_s": round(ma, 3), "runs": RUNS},
            {"build": "B (baseline)", "wall_s": round(mb, 3), "runs": RUNS},
            {"build": "A/B", "wall_s": round(ma / mb, 3), "runs": RUNS}]
    shown = [" ".join(c).replace(folder, "TMP").replace(common.ROOT + "/", "") for c in (a, b)]
    return rows, shown


def main():
    with tempfile.TemporaryDirectory(prefix="lzb-image-io-") as folder:
        rows, commands = startup_rows(folder)
        common.write_csv(os.path.join(HERE, "startup.csv"), rows,
                         ["program", "libraries", "start_s", "runs"], commands)
        if BASELINE:
            rows, commands = render_ab_rows(folder)
            common.write_csv(os.path.join(HERE, "render_ab.csv"), rows, ["build", "wall_s", "runs"],
                             commands)


if __name__ == "__main__":
    main()
