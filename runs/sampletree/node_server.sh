#!/usr/bin/env bash
# Local store against the node server (--node-server): the same out-of-core walk (5 frames of the
# landscape, 320x240, a 4 MiB node cache, 1 thread a rank) on 1, 2 and 3 ranks reading the store
# themselves and on 2 and 3 ranks with the last rank serving the nodes, REPEATS (3) times; every
# run must write the 1-rank files. Writes node_server.csv (first line: the commands; per run the
# median frame time and the render ranks' mean waits, medians over the frames) and prints it.
# usage (from the repository root, nothing else running): bash runs/sampletree/node_server.sh
set -euo pipefail
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
lzb="${LZB:-build/lzb}" here="runs/sampletree" scene='builtin:landscape?objects=20000'
work="${TMPDIR:-/tmp}/lzb_node_server"
mkdir -p "$work"
store="$work/landscape.lzbtree"
[ -s "$store" ] || "$lzb" build-tree "$scene" --out "$store" --quiet >/dev/null
common=(render "$scene" --method sampletree --tree "$store" --cache-mb 4 --frames 5 --width 320
        --height 240 --threads 1 --quiet)
repeats="${REPEATS:-3}"
for k in $(seq 1 "$repeats"); do
  "$lzb" "${common[@]}" --out "$work/r$k/local_1" >/dev/null
  for n in 2 3; do
    mpiexec -n "$n" --oversubscribe "$lzb" "${common[@]}" --out "$work/r$k/local_$n" >/dev/null
    mpiexec -n "$n" --oversubscribe "$lzb" "${common[@]}" --node-server --out "$work/r$k/server_$n" >/dev/null
  done
  for run in local_1 local_2 local_3 server_2 server_3; do
    for f in 0 1 2 3 4; do
      cmp "$work/r1/local_1/frame_000$f.exr" "$work/r$k/$run/frame_000$f.exr"
    done
  done
done
python3 - "$work" "$repeats" "$here/node_server.csv" "lzb ${common[*]} [mpiexec -n N --oversubscribe] [--node-server]" <<'PY'
import csv, json, statistics, sys
work, repeats, out, command = sys.argv[1:]
def med(xs): return statistics.median(xs) if xs else 0.0
rows = []
for repeat, run in ((k, r) for k in range(1, int(repeats) + 1)
                    for r in ("local_1", "local_2", "local_3", "server_2", "server_3")):
    rep = json.load(open(f"{work}/r{repeat}/{run}/report.json"))
    frames = rep["frames"]
    server = run.startswith("server")
    render = lambda f: f["ranks"][:-1] if server else f["ranks"]
    per = lambda key: [sum(r["counts"].get(key, 0) for r in render(f)) / len(render(f)) for f in frames]
    rows.append({
        "repeat": repeat, "run": run, "ranks": rep["ranks"], "render_ranks": len(render(frames[0])),
        "median_frame_s": med([f["seconds"] for f in frames]),
        "first_frame_s": frames[0]["seconds"],
        "median_load_wait_s": med(per("load_wait_seconds")),
        "median_remote_wait_s": med(per("remote_wait_seconds")),
        "nodes_loaded_per_frame": med([sum(r["counts"].get("nodes_loaded", 0) for r in render(f)) for f in frames]),
        "served_requests_per_frame": med([f["ranks"][-1]["counts"].get("served_requests", 0) for f in frames]) if server else "",
        "served_mb_per_frame": med([f["ranks"][-1]["counts"].get("served_bytes", 0) / 1e6 for f in frames]) if server else "",
    })
with open(out, "w", newline="") as fh:
    fh.write("# " + command + "\n")
    w = csv.DictWriter(fh, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
print(open(out).read())
PY
