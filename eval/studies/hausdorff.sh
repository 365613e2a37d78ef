#!/usr/bin/env bash
# Symmetric Hausdorff and mean distance between two meshes, through MeshLab's "Hausdorff
# Distance" filter run by meshlabserver both ways (A sampled against B, and B against A), 100000
# samples on faces, edges and vertices.
#
#   eval/run.sh hausdorff A.ply B.ply --diag MM --out DIR [--build DIR]
#
# MM bounds the search (use the bounding-box diagonal). Prints hausdorff_mm (the larger of the
# two maxima) and mean_distance_mm (the mean of the two means). Needs the private MeshLab prefix
# of a build (BUILD/prefix/bin/meshlabserver) and Xvfb. Exits non-zero with a one-line reason.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
die() { echo "hausdorff: $*" >&2; exit 1; }
a="" b="" diag="" out="" build="$repo/build"
while [ $# -gt 0 ]; do
  case "$1" in
    --diag|--out|--build) [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in --diag) diag="$2" ;; --out) out="$2" ;; --build) build="$2" ;; esac; shift 2 ;;
    -h|--help) sed -n 2,10p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1" ;;
    *) if [ -z "$a" ]; then a="$1"; elif [ -z "$b" ]; then b="$1"; else die "more than two meshes given"; fi; shift ;;
  esac
done
[ -r "$a" ] && [ -r "$b" ] || die "need two readable meshes"
[[ "$diag" =~ ^[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$ ]] || die "--diag expects mm, got '$diag'"
[ -n "$out" ] || die "--out DIR is required"
server="$build/prefix/bin/meshlabserver"
[ -x "$server" ] || die "$server is missing: build the target filter_support_slimming"
mkdir -p "$out"

hausdorff_filter() {  # SAMPLED TARGET
  cat <<XML
 <filter name="Hausdorff Distance">
  <Param type="RichMesh" name="SampledMesh" value="$1"/>
  <Param type="RichMesh" name="TargetMesh" value="$2"/>
  <Param type="RichBool" name="SaveSample" value="false"/>
  <Param type="RichBool" name="SampleVert" value="true"/>
  <Param type="RichBool" name="SampleEdge" value="true"/>
  <Param type="RichBool" name="SampleFauxEdge" value="false"/>
  <Param type="RichBool" name="SampleFace" value="true"/>
  <Param type="RichInt" name="SampleNum" value="100000"/>
  <Param type="RichAbsPerc" name="MaxDist" value="$diag" min="0" max="$diag"/>
 </filter>
XML
}
{ echo '<!DOCTYPE FilterScript>'; echo '<FilterScript>'; hausdorff_filter 0 1; hausdorff_filter 1 0; echo '</FilterScript>'; } \
  >"$out/hausdorff.mlx"
home="$(mktemp -d)"; trap 'rm -rf "$home"' EXIT  # MeshLab's settings: never the user's
HOME="$home" XDG_CONFIG_HOME="$home/.config" "$repo/scripts/with-xvfb.sh" "$server" -i "$a" -i "$b" -s "$out/hausdorff.mlx" \
  >"$out/hausdorff.log" 2>&1 || die "meshlabserver failed on the Hausdorff Distance script (see $out/hausdorff.log)"
# Each run logs "LOG: 2 Sampled N pts ..." then "LOG: 2 min : a   max b   mean : c   RMS : d" in mm
# (meshlabserver then echoes the whole log again without the "LOG:" prefix).
mapfile -t hd < <(awk '/^LOG: .*Sampled [0-9]+ pts/ { want = 1; next }
                       want && /^LOG: .*min :/ { for (i = 1; i <= NF; i++) { if ($i == "max") mx = $(i+1); if ($i == "mean") mn = $(i+2) }
                                         print mx, mn; want = 0 }' "$out/hausdorff.log")
[ "${#hd[@]}" -eq 2 ] || die "meshlabserver logged ${#hd[@]} Hausdorff results instead of 2 (see $out/hausdorff.log)"
read -r max_ab mean_ab <<<"${hd[0]}"
read -r max_ba mean_ba <<<"${hd[1]}"
awk -v m1="$max_ab" -v m2="$max_ba" -v a1="$mean_ab" -v a2="$mean_ba" \
  'BEGIN { printf "hausdorff_mm=%.6g\nmean_distance_mm=%.6g\n", (m1 > m2 ? m1 : m2), (a1 + a2) / 2 }'
