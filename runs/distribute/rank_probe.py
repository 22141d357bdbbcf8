#!/usr/bin/env python3
"""Runs one rank's command and writes what the rank cost to OUT/rank_R.json (R: the rank Open MPI
gives it): bytes read through read() and its kin (rchar of /proc/PID/io, sampled every 5 ms until
the process ends, so the last sample before the end), peak resident memory (VmHWM, sampled alike),
and user + system CPU seconds (wait4).

usage (one rank a process, under mpirun): rank_probe.py OUT -- COMMAND...
"""
import json
import os
import sys
import time


def sample(pid, last):
    try:
        with open(f"/proc/{pid}/io") as f:
            io = dict(line.split(": ") for line in f.read().splitlines())
        with open(f"/proc/{pid}/status") as f:
            hwm = next(int(line.split()[1]) for line in f if line.startswith("VmHWM"))
        return {"rchar": int(io["rchar"]), "peak_kib": hwm}
    except (OSError, StopIteration, ValueError):
        return last


def main(argv):
    out, command = argv[0], argv[2:]
    rank = os.environ.get("OMPI_COMM_WORLD_RANK", "0")
    pid = os.fork()
    if pid == 0:
        os.execvp(command[0], command)
    last = {"rchar": 0, "peak_kib": 0}
    while True:
        done, status, usage = os.wait4(pid, os.WNOHANG)
        if done:
            break
        last = sample(pid, last)
        time.sleep(0.005)
    last["cpu_s"] = usage.ru_utime + usage.ru_stime
    last["peak_kib"] = max(last["peak_kib"], usage.ru_maxrss)
    with open(os.path.join(out, f"rank_{rank}.json"), "w") as f:
        json.dump(last, f)
    return os.waitstatus_to_exitcode(status)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
