#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (g++) in
# build-sanitize/: any memory error, leak of ours or undefined behaviour fails the test that ran
# into it. Suppressions (tests/sanitize/, each justified there) cover only leaks inside system
# libraries. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DLZB_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)"
bash scripts/fetch-test-meshes.sh build-sanitize/data
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
supp="$PWD/tests/sanitize"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$supp/ubsan.supp"
cd build-sanitize && ctest --output-on-failure -j 2 "$@"
