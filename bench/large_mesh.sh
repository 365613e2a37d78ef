#!/usr/bin/env bash
# The whole CLI on a large mesh as a user makes one: the corpus's 70k-face bunny subdivided twice
# in MeshLab (Subdivision Surfaces: Midpoint through meshlabserver: 1,114,656 faces, positions
# stored as floats, so the faces of one plane differ in their normals by 1e-7 to 1e-5), then
# `support-slim IN -o OUT --report R --quiet` at the defaults (read, slim, every figure, write).
# The speed target: a 1.2M-face input, the bunny refined twice, end to end in at most 5 s.
#
#   bench/large_mesh.sh [--runs N] [--build DIR] [--out DIR]
#
# Prints each run's wall seconds and peak memory (GNU time), then their medians. The mesh is made
# once into OUT (default out/large-mesh) and kept. Needs scripts/setup.sh's MeshLab and
# eval/run.sh corpus's corpus (made here when missing) and a build (default build/). For a paired
# comparison of two builds, run the printed command against each build's support-slim in turn.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs=5 build="$repo/build" out="$repo/out/large-mesh"
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n 2,13p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "large_mesh: unknown argument $1" >&2; exit 1 ;;
  esac
done
die() { echo "large_mesh: $*" >&2; exit 1; }
cli="$build/cli/support-slim"
[ -x "$cli" ] || die "no $cli: build first (scripts/build.sh)"
command -v meshlabserver >/dev/null 2>&1 || die "meshlabserver is missing: run scripts/setup.sh"
[ -x /usr/bin/time ] || die "GNU time is missing (apt-get install time)"
[ -f "$repo/data/corpus/bunny_70k.ply" ] || "$repo/eval/studies/corpus.sh" --build "$build" >/dev/null
mkdir -p "$out"
mesh="$out/bunny_meshlab_2x.ply"
if [ ! -f "$mesh" ]; then
  cat >"$out/midpoint2.mlx" <<'MLX'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Subdivision Surfaces: Midpoint">
  <Param type="RichInt" value="2" name="Iterations"/>
  <Param type="RichAbsPerc" value="0" min="0" max="1" name="Threshold"/>
  <Param type="RichBool" value="false" name="Selected"/>
 </filter>
</FilterScript>
MLX
  "$repo/scripts/with-xvfb.sh" meshlabserver -i "$repo/data/corpus/bunny_70k.ply" -o "$mesh.tmp.ply" \
    -s "$out/midpoint2.mlx" >"$out/meshlabserver.log" 2>&1 || die "meshlabserver failed; see $out/meshlabserver.log"
  mv "$mesh.tmp.ply" "$mesh"
fi
faces="$(grep -a -m1 '^element face' "$mesh" | awk '{print $3}')"
echo "mesh: $mesh ($faces faces)"
echo "command: $cli $mesh -o $out/slimmed.ply --report $out/report.json --quiet"
walls=() peaks=()
for ((k = 1; k <= runs; ++k)); do
  line="$( { /usr/bin/time -f '%e %M' "$cli" "$mesh" -o "$out/slimmed.ply" --report "$out/report.json" --quiet; } 2>&1 >/dev/null | tail -1)"
  read -r wall peak <<<"$line"
  echo "run $k: $wall s, peak $((peak / 1024)) MiB"
  walls+=("$wall") peaks+=("$peak")
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo "median of $runs runs: $(median "${walls[@]}") s, peak $(( $(median "${peaks[@]}" | cut -d. -f1) / 1024 )) MiB"
