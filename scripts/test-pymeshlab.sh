#!/usr/bin/env bash
# The PyMeshLab check, in a virtual environment of its own (the only step of the project that
# needs PyPI; scripts/test.sh and scripts/demo.sh never do):
#   1. a venv with pymeshlab==$SLIM_PYMESHLAB_VERSION (default 2025.7.post1), cached in
#      $SLIM_PYMESHLAB_VENV and made again only when that version is not in it;
#   2. scripts/pymeshlab-plugin.sh with that venv first on PATH: the double-precision plugin,
#      checked against and linked to what the wheel bundles, in build-pymeshlab/;
#   3. ctest -L pymeshlab there: the plugin loaded by pymeshlab.load_plugin, its three filters on
#      the bunny through apply_filter (tests/pymeshlab/), and examples/support_slimming.py.
# Every stage prints how long it took; any failure exits non-zero.
#
# Usage: scripts/test-pymeshlab.sh [BUILD_DIR]     (default: build-pymeshlab/ in this checkout)
#        scripts/test-pymeshlab.sh --prepare-only   make the venv (step 1), then stop
# Environment:
#   SLIM_PYMESHLAB_VENV     default /var/cache/support-slimming/pymeshlab-<version> when writable,
#                           else ~/.cache/support-slimming/pymeshlab-<version>
#   SLIM_PYMESHLAB_VERSION  default 2025.7.post1 (the release the plugin is tested with)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prepare_only=0
[ "${1:-}" = "--prepare-only" ] && { prepare_only=1; shift; }
build="${1:-$here/build-pymeshlab}"
version="${SLIM_PYMESHLAB_VERSION:-2025.7.post1}"
cache=/var/cache/support-slimming
if ! mkdir -p "$cache" 2>/dev/null || [ ! -w "$cache" ]; then cache="$HOME/.cache/support-slimming"; fi
venv="${SLIM_PYMESHLAB_VENV:-$cache/pymeshlab-$version}"

stage_start=0
stage() { stage_start=$SECONDS; echo "=== [pymeshlab] $*"; }
stage_done() { echo "=== [pymeshlab] done in $((SECONDS - stage_start)) s"; }

stage "a venv with pymeshlab==$version in $venv"
if ! "$venv/bin/python" -c "import importlib.metadata as m, sys; sys.exit(m.version('pymeshlab') != '$version')" 2>/dev/null; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  # Debian's own python3 and its venv module (python3-venv), whatever else is first on PATH.
  if ! /usr/bin/python3 -c 'import ensurepip' 2>/dev/null; then
    $SUDO apt-get update -qq && $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv >/dev/null
  fi
  rm -rf "$venv"
  /usr/bin/python3 -m venv "$venv"
  # numpy comes with pymeshlab (its meshes are numpy arrays); pip keeps its own download cache.
  "$venv/bin/pip" install -q --disable-pip-version-check "pymeshlab==$version"
fi
"$venv/bin/python" -c "import importlib.metadata as m; print('[pymeshlab] pymeshlab', m.version('pymeshlab'), 'numpy', m.version('numpy'))"
stage_done
[ "$prepare_only" = 0 ] || exit 0

stage "the double-precision plugin for it (scripts/pymeshlab-plugin.sh)"
plugin="$(PATH="$venv/bin:$PATH" "$here/scripts/pymeshlab-plugin.sh" "$build" | tail -n 1)"
echo "[pymeshlab] plugin: $plugin"
stage_done

stage "ctest -L pymeshlab"
cd "$build"
OPENBLAS_NUM_THREADS=1 ctest -L pymeshlab --output-on-failure
stage_done
