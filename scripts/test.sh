#!/usr/bin/env bash
# Install what is missing, build, fetch the real test meshes, and run every test with ctest; prints
# how long the build and the suite took.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/install-deps.sh --test
bash scripts/build.sh
bash scripts/fetch-test-meshes.sh build/data
built=$SECONDS
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# lzb re-executes itself to set this (src/cli/omp_wait_policy.hpp): set here, each of the suite's
# hundreds of lzb starts loads its ~280 libraries once instead of twice.
export OMP_WAIT_POLICY=passive
status=0
(cd build && ctest --output-on-failure -j 2 "$@") || status=$?
echo "test.sh: install and build $((built - start)) s, ctest $((SECONDS - built)) s (exit $status)"
exit $status
