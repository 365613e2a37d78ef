#!/usr/bin/env bash
# Sets up the machine if needed, builds everything and runs the whole suite with ctest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
cd "$here/build"
# One BLAS thread: the optimizer's statistics must repeat exactly (core/platform/blas_threads.h says why).
export OPENBLAS_NUM_THREADS=1
ctest --output-on-failure -j "$(nproc)" "$@"
