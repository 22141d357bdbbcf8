#!/usr/bin/env bash
# Frame-parallel batches: 2 and 3 ranks in 2 frame groups write the files of the 1-rank run,
# every frame once, each rendered by the group it was dealt to (frame f by group f mod 2).
# usage: mpi_frame_groups.sh LZB_BINARY WORK_DIR MPIEXEC
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3"
rm -rf "$work" && mkdir -p "$work"
args=(render "builtin:city?blocks=3" --method hybrid --reference raycast --frames 5 --width 160
      --height 120 --quiet)
"$lzb" "${args[@]}" --threads 2 --out "$work/one" >/dev/null
for ranks in 2 3; do
  "$mpiexec" -n "$ranks" --oversubscribe "$lzb" "${args[@]}" --threads 1 --frame-groups 2 \
    --out "$work/groups_$ranks" >/dev/null
  for f in 0 1 2 3 4; do
    for ext in png exr; do
      cmp "$work/one/frame_000$f.$ext" "$work/groups_$ranks/frame_000$f.$ext" ||
        { echo "FAIL: frame $f.$ext differs on $ranks ranks in 2 groups"; exit 1; }
    done
  done
  python3 - "$work/one/report.json" "$work/groups_$ranks/report.json" "$ranks" <<'PY'
import json, sys
one, grouped, ranks = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), int(sys.argv[3])
assert grouped["parameters"]["frame_groups"] == 2
frames = grouped["frames"]
assert [f["frame"] for f in frames] == list(range(5)), [f["frame"] for f in frames]
assert [f["frame_group"] for f in frames] == [0, 1, 0, 1, 0], [f["frame_group"] for f in frames]
# Rank r is in group r * 2 // ranks; a group's frames were split among its ranks.
group_size = [sum(1 for r in range(ranks) if r * 2 // ranks == g) for g in (0, 1)]
sizes = [len(f["ranks"]) for f in frames]
assert sizes == [group_size[g] for g in [0, 1, 0, 1, 0]], (sizes, group_size)
assert [f["accuracy"] for f in frames] == [f["accuracy"] for f in one["frames"]]
assert grouped["summary"]["frames_per_second"] > 0
PY
  echo "ok: $ranks ranks in 2 frame groups write the 1-rank files"
done
