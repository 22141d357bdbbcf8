#!/usr/bin/env python3
"""The benchmark studies (runs/*/*.py) answer -h / --help with their usage and leave their CSVs and
plots alone, and refuse an unknown argument with status 2 before running anything.

Every study runs as its own __main__ inside this one process (a Python start costs 0.5 s here, and
there are 46 runs); a study that would start its measurement instead is stopped after 20 s.

usage: studies_cli.py REPOSITORY_ROOT
"""
import contextlib
import glob
import io
import os
import runpy
import signal
import sys


class Overran(Exception):
    pass


def run(study, args):
    """(exit status, stdout, stderr) of `python3 study args`, run here."""
    out, err = io.StringIO(), io.StringIO()
    sys.modules.pop("common", None)  # it reads the arguments when imported
    sys.argv = [study, *args]
    saved_path = list(sys.path)
    sys.path.insert(0, os.path.dirname(os.path.abspath(study)))
    signal.alarm(20)
    status = 0
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            runpy.run_path(study, run_name="__main__")
    except SystemExit as e:
        status = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except Overran:
        status = "still running after 20 s"
    finally:
        signal.alarm(0)
        sys.path[:] = saved_path
    return status, out.getvalue(), err.getvalue()


def stamp():
    files = sorted(glob.glob("runs/**/*.csv", recursive=True) +
                   glob.glob("runs/**/*.png", recursive=True))
    return [(f, os.stat(f).st_mtime_ns, os.stat(f).st_size) for f in files]


def main(root):
    os.chdir(root)
    signal.signal(signal.SIGALRM, lambda *_: (_ for _ in ()).throw(Overran()))
    before = stamp()
    studies = sorted(glob.glob("runs/*/run.py")) + ["runs/lzb/far_rays.py", "runs/speedup/tiles.py"]
    failures = []
    for study in studies:
        for flag in ("-h", "--help"):
            status, out, _ = run(study, [flag])
            if status != 0 or "usage" not in out.lower():
                failures.append(f"{study} {flag}: status {status}, no usage in: {out[:200]}")
    bad_args = [["runs/rzb/run.py", "bogus_study"], ["runs/lzb/run.py", "bogus_study"],
                ["runs/peers/run.py", "--scene=city"], ["runs/sampletree/run.py", "--only"]]
    bad_args += [[study, "--qiuck"] for study in studies]
    for study, *args in bad_args:
        status, _, err = run(study, args)
        if status != 2 or "unknown" not in err:
            failures.append(f"{study} {' '.join(args)}: status {status}, '{err.strip()}'")
    if stamp() != before:
        failures.append("a study wrote its results")
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print(f"studies: {len(studies)} print their usage, {len(bad_args)} unknown arguments refused, "
          "nothing written")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
