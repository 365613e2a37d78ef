#!/usr/bin/env bash
# Configures and builds into build/ (Release). Used by demo.sh and test.sh; idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$here/build/Makefile" ] && generator=(-G Ninja)
cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release "${generator[@]}" >/dev/null
cmake --build "$here/build" -j "$(nproc)" "$@"
