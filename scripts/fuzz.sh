#!/usr/bin/env bash
# Fuzzes the scene input: builds the libFuzzer targets of tests/fuzz with clang (ASan + UBSan,
# coverage, the TOML parser compiled in) into build-fuzz/ and runs each for SECONDS (default 60),
# one after the other.
#   bash scripts/fuzz.sh SECONDS [TARGET...]     targets: toml off ply obj stl gltf glb (default all)
# Each run starts from the kept inputs (tests/fuzz/corpus/TARGET, tests/fuzz/regressions/TARGET)
# and adds what gains coverage to build-fuzz/corpus/TARGET (not committed). An input that crashes,
# trips a sanitizer, escapes as anything but an InputError, runs over 10 s or 2 GiB goes to
# build-fuzz/findings/TARGET/; fix it and keep it in tests/fuzz/regressions/TARGET, which ctest
# replays (fuzz_replay_test). Exit status 1 when any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
((${#targets[@]})) || targets=(toml off ply obj stl gltf glb)
bash scripts/install-deps.sh --fuzz
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DLZB_FUZZ=ON >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
# Leaks inside assimp on malformed input are its own (tests/sanitize/lsan.supp says which).
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitize/lsan.supp:print_suppressions=0"
found=0
for t in "${targets[@]}"; do
  corpus="build-fuzz/corpus/$t" findings="build-fuzz/findings/$t"
  mkdir -p "$corpus" "$findings"
  kept=(tests/fuzz/corpus/"$t")
  [ -d "tests/fuzz/regressions/$t" ] && kept+=(tests/fuzz/regressions/"$t")
  dict=()
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  echo "fuzz: $t for $seconds s"
  # The first folder receives new inputs; the kept ones are read only.
  if ! build-fuzz/tests/fuzz_"$t" "$corpus" "${kept[@]}" "${dict[@]}" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -max_len=8192 -artifact_prefix="$findings/" \
      -print_final_stats=1 2>"build-fuzz/fuzz_$t.log"; then
    found=1
    echo "fuzz: $t found something: $(ls "$findings")" >&2
    tail -40 "build-fuzz/fuzz_$t.log" >&2
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb|cov:" "build-fuzz/fuzz_$t.log" | tail -3
done
exit "$found"
