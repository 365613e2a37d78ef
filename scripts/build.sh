#!/usr/bin/env bash
# Configures and builds into build/ (Release), through ccache (scripts/lib/ccache.sh). Used by
# demo.sh and test.sh; idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$here/scripts/lib/ccache.sh"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$here/build/Makefile" ] && generator=(-G Ninja)
cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release "${ccache_launcher[@]}" "${generator[@]}" >/dev/null
cmake --build "$here/build" -j "$(nproc)" "$@"
