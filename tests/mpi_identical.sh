#!/usr/bin/env bash
# Renders the same frames on 1 process (1 and 2 threads) and on 2 and 3 MPI ranks, and requires
# byte-identical images (with the sub-sample channels for the exact methods), the same accuracy
# against a reference, and work that was really split: per frame, every rank's share of COUNTS
# sums to the 1-rank count, and when there is sizeable work, at least two ranks did some of it.
# usage: mpi_identical.sh LZB_BINARY WORK_DIR MPIEXEC METHOD COUNTS [DATA_DIR] [EXTRA ARGS...]
#   COUNTS: comma-separated report counts that measure the split work (e.g. rays_cast)
#   EXTRA ARGS: an argument @store becomes a sample tree store of the scene, built first
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3" method="$4" counts="$5" data="${6:-}"
shift 6 || shift $#
rm -rf "$work" && mkdir -p "$work"
scenes=("builtin:city?blocks=3" "builtin:sphereflake?depth=2" "builtin:forest?levels=1")
[ -n "$data" ] && [ -s "$data/bunny00.off" ] && scenes+=("$data/bunny00.off")
# LZB_IDENTICAL_SCENES (space-separated) replaces the list: a method's own scenes (sqrt5's procedural ones)
[ -n "${LZB_IDENTICAL_SCENES:-}" ] && read -r -a scenes <<< "$LZB_IDENTICAL_SCENES"
reference=raycast extra=("$@")
case "$method" in
  zbuffer) extra+=(--subsamples) ;;
  raycast) extra+=(--subsamples) reference=zbuffer ;;
esac
i=0
for scene in "${scenes[@]}"; do
  run_extra=()
  for a in "${extra[@]}"; do
    if [ "$a" = "@store" ]; then
      a="$work/store_$i.lzbtree"
      "$lzb" build-tree "$scene" --out "$a" --leaf-triangles 8 --quiet >/dev/null
    fi
    run_extra+=("$a")
  done
  args=(render "$scene" --method "$method" --reference "$reference" "${run_extra[@]}" --frames 2
        --width 160 --height 120 --quiet)
  "$lzb" "${args[@]}" --threads 2 --out "$work/one_$i" >/dev/null
  "$lzb" "${args[@]}" --threads 1 --out "$work/thread_$i" >/dev/null
  "$mpiexec" -n 2 --oversubscribe "$lzb" "${args[@]}" --threads 1 --out "$work/two_$i" >/dev/null
  "$mpiexec" -n 3 --oversubscribe "$lzb" "${args[@]}" --threads 1 --out "$work/three_$i" >/dev/null
  for run in thread two three; do
    for f in frame_0000.png frame_0000.exr frame_0001.png frame_0001.exr; do
      cmp "$work/one_$i/$f" "$work/${run}_$i/$f" || { echo "FAIL: $scene $method $f differs ($run)"; exit 1; }
    done
  done
  python3 - "$counts" "$work/one_$i/report.json" "$work/two_$i/report.json" "$work/three_$i/report.json" <<'PY' || { echo "FAIL: $scene $method"; exit 1; }
import json, sys
keys = [k for k in sys.argv[1].split(",") if k]
one, *many = (json.load(open(p)) for p in sys.argv[2:])
for rep in many:
    ranks = rep["ranks"]
    for a, b in zip(one["frames"], rep["frames"]):
        assert a["accuracy"] == b["accuracy"], ("accuracy differs", a["accuracy"], b["accuracy"])
        assert len(b["ranks"]) == ranks, (ranks, len(b["ranks"]))
        working = set()
        for key in keys:
            total = a["counts"].get(key, 0)
            shares = [r["counts"].get(key, 0) for r in b["ranks"]]
            assert sum(shares) == total, (key, "shares", shares, "sum to", sum(shares), "not", total)
            working |= {r for r, s in enumerate(shares) if s > 0}
        if sum(a["counts"].get(k, 0) for k in keys) >= 1000:
            assert len(working) >= 2, ("one rank did all the work", keys)
    print(f"  {ranks} ranks: " + ", ".join(
        f"{k} {[r['counts'].get(k, 0) for r in rep['frames'][0]['ranks']]}" for k in keys))
PY
  echo "ok: $scene ($method ${extra[*]}) identical on 1 and 2 threads and 2 and 3 ranks, accuracy against $reference too, work split"
  i=$((i + 1))
done
