#!/usr/bin/env bash
# Builds a private MeshLab prefix that loads our plugin without touching /usr:
#   PREFIX/bin/meshlabserver (a copy: a symlink would still read the system plugins folder)
#   PREFIX/lib/x86_64-linux-gnu/meshlab/{libmeshlab-common.so, plugins/*}  (system ones symlinked)
# MeshLab reads exactly <exe dir>/../lib/x86_64-linux-gnu/meshlab/plugins. Idempotent.
# Usage: make_prefix.sh PREFIX PLUGIN.so
set -euo pipefail
prefix="$1"; plugin="$2"
sys=/usr/lib/x86_64-linux-gnu/meshlab
lib="$prefix/lib/x86_64-linux-gnu/meshlab"
mkdir -p "$prefix/bin" "$lib/plugins"
for exe in meshlabserver meshlab; do
  [ -x "/usr/bin/$exe" ] && cp -u "/usr/bin/$exe" "$prefix/bin/$exe"
done
ln -sfn "$sys/libmeshlab-common.so" "$lib/libmeshlab-common.so"
for f in "$sys"/plugins/*.so; do
  name="$(basename "$f")"
  [ "$name" = "$(basename "$plugin")" ] || ln -sfn "$f" "$lib/plugins/$name"
done
cp -f "$plugin" "$lib/plugins/"
