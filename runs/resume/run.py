#!/usr/bin/env python3
"""A batch job that loses a rank, then resumes (issue: batch jobs that survive a lost node).

usage: python3 runs/resume/run.py [--frames=N] [--kill-at=S]   # about 2 minutes here

In one run, each on 2 ranks x 1 thread, `builtin:city`, 640x480, the default method:
  1. the uninterrupted run of the whole path;
  2. the same command with rank 1 SIGKILLed after --kill-at seconds (default 6): how long the job
     took to end after the kill, its status, the frames recorded;
  3. `--resume` of the killed folder: the frames it rendered and its wall time;
  4. the path as two frame ranges (0:N/2, N/2:) into a third folder.
Every file of 3 and 4 is checked byte for byte against 1, and each record must hold one line per
frame. Writes runs/resume/resume.csv.
"""
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(valued=("frames", "kill-at"))
FRAMES = int(common.option("frames", ["200"])[0])
KILL_AT = float(common.option("kill-at", ["6"])[0])
HERE = os.path.dirname(os.path.abspath(__file__))
BASE = ["builtin:city", "--frames", str(FRAMES), "--threads", "1", "--quiet"]


def command(out, *extra):
    return [*common.MPIRUN, "-n", "2", common.LZB, "render", *BASE, "--out", out, *extra]


def timed(cmd):
    start = time.monotonic()
    p = subprocess.run(cmd, env=common.ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} exited {p.returncode}: {p.stdout}")
    return time.monotonic() - start


def rank_pid(out, rank):
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if out.encode() not in f.read().split(b"\0"):
                    continue
            with open(f"/proc/{pid}/environ", "rb") as f:
                if f"OMPI_COMM_WORLD_RANK={rank}".encode() in f.read().split(b"\0"):
                    return int(pid)
        except OSError:
            continue
    return None


def recorded(out):
    path = os.path.join(out, "frames.jsonl")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [json.loads(line)["frame"] for line in f.read().split("\n")[:-1]]


def check_same(ref, out, what):
    names = [f"frame_{f:04d}.{e}" for f in range(FRAMES) for e in ("png", "exr")]
    _, mismatch, errors = filecmp.cmpfiles(ref, out, names, shallow=False)
    if mismatch or errors:
        sys.exit(f"{what}: files differ from the uninterrupted run's: {(mismatch + errors)[:4]}")
    if sorted(recorded(out)) != list(range(FRAMES)):
        sys.exit(f"{what}: the record is not one line per frame")


def main():
    common.wait_quiet()
    work = tempfile.mkdtemp(prefix="lzb_resume_")
    rows, commands = [], []
    ref, killed, ranged = (os.path.join(work, n) for n in ("ref", "killed", "ranged"))

    cmd = command(ref)
    rows.append({"phase": "uninterrupted", "wall_s": round(timed(cmd), 2), "frames_rendered": FRAMES})
    commands.append(" ".join(cmd))

    cmd = command(killed)
    start = time.monotonic()
    p = subprocess.Popen(cmd, env=common.ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(KILL_AT)
    os.kill(rank_pid(killed, 1), signal.SIGKILL)
    killed_at = time.monotonic()
    status = p.wait()
    done = len(recorded(killed))
    rows.append({"phase": f"rank 1 SIGKILLed at {KILL_AT:g} s", "wall_s": round(killed_at - start, 2),
                 "frames_rendered": done, "ended_after_kill_s": round(time.monotonic() - killed_at, 2),
                 "status": status if status >= 0 else 128 - status})
    commands.append(" ".join(cmd) + f"  (rank 1 SIGKILLed after {KILL_AT:g} s)")

    cmd = command(killed, "--resume")
    rows.append({"phase": "--resume", "wall_s": round(timed(cmd), 2), "frames_rendered": FRAMES - done})
    commands.append(" ".join(cmd))
    check_same(ref, killed, "killed and resumed")

    half = FRAMES // 2
    for r in (f"0:{half}", f"{half}:"):
        cmd = command(ranged, "--frame-range", r)
        n = half if r.startswith("0:") else FRAMES - half
        rows.append({"phase": f"--frame-range {r}", "wall_s": round(timed(cmd), 2), "frames_rendered": n})
        commands.append(" ".join(cmd))
    check_same(ref, ranged, "two frame ranges")
    for r in rows:
        r["identical_to_uninterrupted"] = "" if r["phase"] == "uninterrupted" or "SIGKILL" in r["phase"] else "yes"

    common.write_csv(os.path.join(HERE, "resume.csv"), rows,
                     ["phase", "wall_s", "frames_rendered", "ended_after_kill_s", "status",
                      "identical_to_uninterrupted"], commands)
    for r in rows:
        print(r)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
