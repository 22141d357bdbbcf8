#!/usr/bin/env python3
"""Batch jobs that survive a lost rank: frame ranges, --resume, the record (frames.jsonl).

An uninterrupted 2-rank run of a short path is the reference. Then:
- frame ranges 0:3 and 3:N written into one folder (the second by 2 frame groups) give the
  reference's files byte for byte, and a record of every frame;
- 10 tries, on 2, 3 and 4 ranks and with 2 frame groups: one rank, chosen at random, is killed
  with SIGKILL at a random instant (during the set-up, or a random time after a random frame was
  recorded: while rendering, compositing or writing, at least 2 frames before the end). The job
  must end within 10 s with a non-zero status, every frame its record holds must be intact (the
  reference's bytes), and a --resume must leave the reference's files and one record per frame;
- a --resume with another method, size or seed is refused with exit status 2 naming the field,
  and writes nothing;
- a torn last line (written here) is left out by `lzb report` and cut off by --resume;
- under a launcher that keeps the other ranks when one dies (mpirun --enable-recovery), the
  watchdog (--stall-timeout 3) ends the rank left waiting within 10 s.

usage: mpi_resume.py LZB MPIEXEC WORK
"""
import filecmp
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time

# Frames long enough (about 80 ms each, written) that random instants fall in every step.
FRAMES = 16
SCENE = "builtin:city?blocks=6"
COMMON = ["--method", "zbuffer", "--frames", str(FRAMES), "--width", "640", "--height", "480",
          "--threads", "1", "--quiet"]
TRIES = [(2, 1), (3, 1), (4, 1), (4, 2), (2, 1), (3, 1), (4, 1), (4, 2), (2, 1), (3, 1)]


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def frame_files(frames=range(FRAMES)):
    return [f"frame_{f:04d}.{ext}" for f in frames for ext in ("png", "exr")]


def records(folder):
    with open(os.path.join(folder, "frames.jsonl"), "rb") as f:
        text = f.read().decode()
    return [json.loads(line) for line in text.split("\n")[:-1]]


def stable(record):
    """What a frame's record holds that no rank count or timing changes."""
    return {k: record[k] for k in ("frame", "covered_pixels", "camera", "files")}


def same_files(a, b, names):
    _, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    return mismatch + errors


def main():
    lzb, mpiexec, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rng = random.Random(34)

    def launch(ranks, out, *extra, groups=1, common=COMMON):
        launcher = [mpiexec, "--oversubscribe", "-n", str(ranks)] if ranks > 1 else []
        cmd = [*launcher, lzb, "render", SCENE, *common, "--frame-groups", str(groups),
               "--out", out, *extra]
        return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def run(ranks, out, *extra, groups=1, status=0, common=COMMON):
        p = launch(ranks, out, *extra, groups=groups, common=common)
        text = p.communicate(timeout=300)[0]
        if p.returncode != status:
            fail(f"{' '.join(p.args)} exited {p.returncode} (want {status}): {text}")
        return text

    ref = os.path.join(work, "ref")
    start = time.monotonic()
    run(2, ref)
    took = time.monotonic() - start
    ref_records = [stable(r) for r in records(ref)]
    if [r["frame"] for r in ref_records] != list(range(FRAMES)):
        fail(f"the reference's record is not one line per frame: {ref_records}")
    print(f"ok: reference of {FRAMES} frames on 2 ranks in {took:.1f} s")

    # Frame ranges: two tasks into one folder make the one run.
    ranged = os.path.join(work, "ranged")
    run(1, ranged, "--frame-range", "0:3")
    if os.path.exists(os.path.join(ranged, frame_files([3])[0])):
        fail("--frame-range 0:3 wrote frame 3")
    run(4, ranged, "--frame-range", "3:", groups=2)
    bad = same_files(ref, ranged, frame_files())
    if bad:
        fail(f"frame ranges 0:3 + 3:{FRAMES} differ from one run: {bad}")
    with open(os.path.join(ranged, "report.json")) as f:
        if len(json.load(f)["frames"]) != FRAMES:
            fail("the second range's report does not hold every frame of the record")
    print(f"ok: frame ranges 0:3 + 3:{FRAMES} (1 rank, then 2 frame groups) equal one run")

    # Kills at random instants, then resumes.
    for i, (ranks, groups) in enumerate(TRIES):
        out = os.path.join(work, f"killed{i}")
        p = launch(ranks, out, groups=groups)
        wait_for_instant(p, out, rng.randrange(-1, FRAMES - 2), rng)
        victim = kill_one_rank(p, out, rng)
        killed_at = time.monotonic()
        try:
            p.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            p.kill()
            fail(f"try {i}: the job still ran 30 s after rank {victim} was killed")
        ended = time.monotonic() - killed_at
        if victim is None:
            fail(f"try {i}: the run ended before the kill")
        if p.returncode == 0 or ended > 10:
            fail(f"try {i}: rank {victim} killed, job ended {ended:.1f} s later with {p.returncode}")
        done = [r["frame"] for r in records(out)] if os.path.exists(
            os.path.join(out, "frames.jsonl")) else []
        bad = same_files(ref, out, frame_files(done))
        if bad:
            fail(f"try {i}: frames recorded finished are not intact: {bad}")
        run(2, out, "--resume")
        bad = same_files(ref, out, frame_files())
        if bad:
            fail(f"try {i}: the resumed files differ from the uninterrupted run's: {bad}")
        if [stable(r) for r in records(out)] != ref_records:
            fail(f"try {i}: the resumed record is not one record per frame, as the reference's")
        leftovers = [n for n in os.listdir(out) if n.startswith(".")]
        if leftovers:
            fail(f"try {i}: temporaries left: {leftovers}")
        print(f"ok: try {i}: {ranks} ranks, {groups} group(s), rank {victim} killed with "
              f"{len(done)} frame(s) recorded; ended in {ended:.1f} s (status {p.returncode}); "
              "resumed to the reference")

    # A launcher that keeps the job going when a rank dies (mpirun --enable-recovery): the
    # watchdog ends the ranks left waiting for it.
    out = os.path.join(work, "recovery")
    p = subprocess.Popen([mpiexec, "--enable-recovery", "-n", "2", lzb, "render", SCENE, *COMMON,
                          "--stall-timeout", "3", "--out", out],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wait_for_instant(p, out, 1, rng)
    victim = kill_one_rank(p, out, rng, rank=1)
    killed_at = time.monotonic()
    try:
        text = p.communicate(timeout=30)[0]
    except subprocess.TimeoutExpired:
        p.kill()
        fail("under mpirun --enable-recovery a rank still waited 30 s after its peer was killed")
    ended = time.monotonic() - killed_at
    if victim is None or ended > 10 or "finished no frame" not in text:
        fail(f"--stall-timeout 3: rank {victim} killed, job ended {ended:.1f} s later: {text}")
    print(f"ok: mpirun --enable-recovery, rank 1 killed: the watchdog ended rank 0 {ended:.1f} s "
          "later (--stall-timeout 3)")

    # Refused resumes write nothing.
    before = snapshot(ref)
    for option, value, field in (("--method", "raycast", "method"), ("--width", "201", "width"),
                                 ("--seed", "7", "seed")):
        changed = COMMON.copy()
        if option in changed:
            changed[changed.index(option) + 1] = value
        else:
            changed += [option, value]
        text = run(1, ref, "--resume", status=2, common=changed)
        if f"{field}: was" not in text:
            fail(f"the refused resume ({option} {value}) does not name {field}: {text}")
        if snapshot(ref) != before:
            fail(f"the refused resume ({option} {value}) wrote into the folder")
    print("ok: resumes with another method, width or seed exit 2 naming it, writing nothing")

    # A torn last line.
    with open(os.path.join(ref, "frames.jsonl"), "a") as f:
        f.write('{"frame": 3, "covered_pi')
    run(1, ref, "--resume")  # renders nothing, and cuts the line off
    if [stable(r) for r in records(ref)] != ref_records:
        fail("--resume did not cut the torn line off")
    with open(os.path.join(ref, "frames.jsonl"), "a") as f:
        f.write('{"frame": 3, "cov')
    subprocess.run([lzb, "report", ref], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(ref, "report.json")) as f:
        frames = json.load(f)["frames"]
    if [fr["frame"] for fr in frames] != list(range(FRAMES)):
        fail(f"`lzb report` did not leave the torn line out: {[fr['frame'] for fr in frames]}")
    print("ok: a torn last line is left out by `lzb report` and cut off by --resume")


def recorded_lines(out):
    try:
        with open(os.path.join(out, "frames.jsonl"), "rb") as f:
            return f.read().count(b"\n")
    except OSError:
        return 0


def wait_for_instant(p, out, frames_done, rng):
    """Waits until `out`'s record holds frames_done + 1 frames, then a random part of a frame
    (frames_done < 0: a random instant of the set-up), so the kill falls in a frame, a
    composite, a write or the set-up of a job with at least 2 frames left, however loaded the
    machine is."""
    deadline = time.monotonic() + 120
    if frames_done < 0:
        while not rank_pids(out) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.005)
        time.sleep(rng.uniform(0.0, 0.3))
        return
    while recorded_lines(out) <= frames_done and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.002)
    time.sleep(rng.uniform(0.0, 0.06))


def snapshot(folder):
    return sorted((n, os.stat(os.path.join(folder, n)).st_mtime_ns) for n in os.listdir(folder))


def rank_pids(out):
    """{rank: pid} of the lzb processes rendering into `out`."""
    ranks = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                argv = f.read().split(b"\0")
            if out.encode() not in argv or b"render" not in argv:
                continue
            with open(f"/proc/{pid}/environ", "rb") as f:
                env = dict(e.split(b"=", 1) for e in f.read().split(b"\0") if b"=" in e)
        except OSError:
            continue
        if b"OMPI_COMM_WORLD_RANK" in env:
            ranks[int(env[b"OMPI_COMM_WORLD_RANK"])] = int(pid)
    return ranks


def kill_one_rank(p, out, rng, rank=None):
    """SIGKILLs a rank (else a random one) of the job writing `out`; its rank, or None when none
    is left."""
    ranks = rank_pids(out)
    if not ranks or p.poll() is not None:
        return None
    victim = rng.choice(sorted(ranks)) if rank is None else rank
    if victim not in ranks:
        return None
    try:
        os.kill(ranks[victim], signal.SIGKILL)
    except ProcessLookupError:
        return None
    return victim


if __name__ == "__main__":
    main()
