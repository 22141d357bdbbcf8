#!/usr/bin/env bash
# The test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (g++) in
# build-sanitize/: any memory error, leak of ours or undefined behaviour fails the test that ran
# into it. Suppressions (tests/sanitize/, each justified there) cover only system libraries.
#   bash scripts/sanitize.sh [ctest args]        the whole suite
#   bash scripts/sanitize.sh --input [ctest args] what CI runs (.ci/run): the hostile-input tests
#     (scene readers and their checks, the fuzz regressions, the command line's refusals and
#     resource limits, the unprivileged error paths) and the core units, building only those
set -euo pipefail
cd "$(dirname "$0")/.."
targets=() filter=()
if [ "${1:-}" = "--input" ]; then
  shift
  targets=(--target lzb scene_test core_test image_test regions_test cli_test fuzz_replay_test)
  suites='Builtin|Chessboard|City|Forest|MeshFile|Replicated|Sphereflake|TomlScene|TomlSceneErrors'
  suites+='|TomlTextCheck|Triangulate|Camera|CameraFraming|CameraPath|DepthKey|Framebuffer|Frustum'
  suites+='|Mesh|Scene|ScenePart|PlySlices|StreamedShare|FrameIoTest|Metrics|Reference|Compare|Info'
  suites+='|Render|Batch'
  filter=(-R "^(($suites)\.|Targets/FuzzReplay\.|Cases/BadInput\.|unprivileged_error_paths$)")
fi
bash scripts/install-deps.sh --test
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DLZB_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)" "${targets[@]}"
bash scripts/fetch-test-meshes.sh build-sanitize/data
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
supp="$PWD/tests/sanitize"
# Leak detection is on by default; the lzb program turns it off for itself
# (tests/sanitize/lzb_asan_options.cpp), so ASAN_OPTIONS must not name it.
export ASAN_OPTIONS="abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$supp/ubsan.supp"
cd build-sanitize && ctest --output-on-failure -j 2 "${filter[@]}" "$@"
