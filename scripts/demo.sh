#!/usr/bin/env bash
# The main job on the sample bunny: builds the plugin into a private MeshLab prefix (build/prefix)
# and runs it through the real meshlabserver. Writes out/bunny_overhang.ply (risky faces coloured
# and selected, face quality = n·d + sin(alpha_max)). Idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh" --target filter_support_slimming
mkdir -p "$here/out"
home="$(mktemp -d)"; trap 'rm -rf "$home"' EXIT
log="$here/out/bunny_overhang.log"
HOME="$home" xvfb-run -a "$here/build/prefix/bin/meshlabserver" \
  -i "$here/data/bunny.ply" -o "$here/out/bunny_overhang.ply" -m fq fc sa \
  -s "$here/examples/overhang_analysis.mlx" >"$log" 2>&1 || { cat "$log"; exit 1; }
echo
echo "Overhang Analysis of the sample bunny (print direction +Z, self-supporting angle 45 deg):"
grep -m1 -o "Overhang Analysis: .*" "$log" | sed 's/^Overhang Analysis: /  /; s/; /\n  /g'
echo
echo "Coloured mesh: $here/out/bunny_overhang.ply (open it in MeshLab; red = risky, blue = safe)"
