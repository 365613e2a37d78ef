#!/usr/bin/env bash
# The independent judge: does Support Slimming save support material in a real slicer?
#
#   tools/evaluate.sh MESH [options]
#
#  1. The part in the print frame (print direction turned onto +Z), scaled so its longest side
#     is --size mm (default 60), resting on the plate (slim-eval prepare).
#  2. Support Slimming on it (the support-slim CLI, the same core as the MeshLab filter).
#  3. Input and result sliced by PrusaSlicer under identical settings, automatic supports with
#     the threshold matching alpha_max (90 - alpha_max: the slicer measures from the horizontal).
#  4. The support filament summed from the G-code's "Support material (interface)" sections,
#     checked against the slicer's own total (slim-eval gcode).
#  5. Shape change: symmetric Hausdorff and mean distance from MeshLab's "Hausdorff Distance"
#     filter (meshlabserver, both directions), volume change, largest vertex displacement.
#  6. Pictures: input and result, risky faces red, same cameras (f3d under Xvfb, ImageMagick).
#  7. OUT/report.md (the table, the picture, the settings) and OUT/metrics.txt (key=value).
#
# With --orient the CLI first turns the part into the print pose its orientation search chooses
# and slims it there; the report then has three columns: input (as given), oriented, and oriented
# + slimmed, and the shape change (Hausdorff, displacement, volume) is that of the slimming alone,
# oriented -> slimmed, in the oriented frame.
#
# Needs: a build with support-slim, slim-eval and the private MeshLab prefix (--build, default
# build/), and prusa-slicer, Xvfb, f3d, ImageMagick (scripts/setup.sh installs them).
# Exits non-zero with a one-line reason on bad input or when a step fails.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

usage() {
  cat <<'EOF'
usage: tools/evaluate.sh MESH [options]

  --out DIR               where the report and its files go        [out/eval/<mesh name>]
  --size MM               longest side of the part on the plate (0: keep the mesh's scale) [60]
  --angle DEG             self-supporting angle from the vertical, (0, 90)               [45]
  --dir X,Y,Z             print direction of MESH                                     [0,0,1]
  --resolution N, --domain voxel|tetgen, --method coherent|paper, --iterations N,
  --max-deviation PCT, --max-k K
                          passed to support-slim (its defaults otherwise)
  --orient                orient first (support-slim --orient): three columns, input,
                          oriented, oriented + slimmed
  --orient-effort E       fast, normal or thorough (with --orient)                   [normal]
  --build DIR             build tree holding cli/support-slim, tools/slim-eval, prefix/ [build]
  --name TEXT             the part's name in the report                  [the mesh file name]
  --quiet                 print only the table at the end
  -h, --help              this text
EOF
}

die() { echo "evaluate: $*" >&2; exit 1; }
say() { [ -n "$quiet" ] || echo "[evaluate] $*" >&2; }
# kv FILE KEY: the value of KEY in a key=value file (empty when absent).
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }
# calc EXPR: floating-point arithmetic (awk), e.g. calc "100 * ($a / $b - 1)".
calc() { awk "BEGIN { printf \"%.6g\", $1 }"; }
# fmt DIGITS VALUE: fixed decimals for the report.
fmt() { awk -v d="$1" -v v="$2" 'BEGIN { printf "%." d "f", v }'; }
# xrun CMD...: on a fresh private Xvfb, whose display number parallel runs (ctest -j) cannot share.
xrun() { "$repo/scripts/with-xvfb.sh" "$@"; }
is_number() { [[ "$1" =~ ^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)$ ]]; }

mesh="" out="" size=60 angle=45 dir="0,0,1" build="$repo/build" name="" quiet="" orient=""
slim_args=() orient_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --out|--size|--angle|--dir|--build|--name|--resolution|--domain|--method|--iterations|--max-deviation|--max-k|--orient-effort)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --out) out="$2" ;;
        --size) size="$2" ;;
        --angle) angle="$2" ;;
        --dir) dir="$2" ;;
        --build) build="$2" ;;
        --name) name="$2" ;;
        --orient-effort) orient_args+=("$1" "$2") ;;
        *) slim_args+=("$1" "$2") ;;
      esac
      shift 2 ;;
    --quiet) quiet=1; shift ;;
    --orient) orient=1; shift ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$mesh" ] || die "more than one mesh given: $mesh and $1"; mesh="$1"; shift ;;
  esac
done

# ---- checks: one line and a non-zero exit for anything missing or malformed ----------------------
[ -n "$mesh" ] || die "no mesh given (see --help)"
[ -n "$orient" ] || [ ${#orient_args[@]} -eq 0 ] || die "--orient-effort needs --orient"
[ -f "$mesh" ] && [ -r "$mesh" ] || die "cannot read $mesh"
is_number "$size" || die "--size expects a number of mm, got '$size'"
is_number "$angle" || die "--angle expects degrees, got '$angle'"
awk -v a="$angle" 'BEGIN { exit !(a > 0 && a < 90) }' || die "--angle must lie strictly between 0 and 90 degrees, got $angle"
build="$(cd "$build" 2>/dev/null && pwd)" || die "no build tree at the --build path"
slim="$build/cli/support-slim"; eval_tool="$build/tools/slim-eval"; server="$build/prefix/bin/meshlabserver"
for f in "$slim" "$eval_tool" "$server"; do
  [ -x "$f" ] || die "$f is missing: build the targets support-slim, slim-eval and filter_support_slimming"
done
for tool in prusa-slicer Xvfb f3d; do
  command -v "$tool" >/dev/null 2>&1 || die "$tool is not installed (scripts/setup.sh installs it)"
done
convert -version 2>/dev/null | grep -q ImageMagick || die "ImageMagick's convert is not installed (apt-get install imagemagick)"
threshold="$("$eval_tool" threshold "$angle" 2>&1)" || die "${threshold#slim-eval: }"

[ -n "$name" ] || name="$(basename "${mesh%.*}")"
[ -n "$out" ] || out="$repo/out/eval/$name"
mkdir -p "$out" || die "cannot create $out"
out="$(cd "$out" && pwd)"
home="$(mktemp -d)"; trap 'rm -rf "$home"' EXIT  # MeshLab's and f3d's settings: never the user's
export HOME="$home" XDG_CONFIG_HOME="$home/.config"
export OPENBLAS_NUM_THREADS=1  # the optimizer's statistics must repeat (core/blas_threads.h)
started=$SECONDS

# ---- 1. the part in the print frame ------------------------------------------------------------
say "preparing $mesh (longest side $size mm, print direction $dir)"
"$eval_tool" prepare "$mesh" "$out/input" --size "$size" --dir "$dir" >"$out/prepare.txt" 2>"$out/prepare.err" ||
  die "$(tail -1 "$out/prepare.err" | sed 's/^slim-eval: //')"
diag="$(kv "$out/prepare.txt" diag)"
plate_tol="$(calc "1e-3 * $diag")"  # the CLI's default, fixed here so every step uses the same

# ---- 2. Support Slimming (after orientation with --orient) ----------------------------------------
# parts: what is measured and sliced; base: what the slimming started from (the shape change is
# measured from it: with --orient the oriented part, so the turn does not count).
if [ -n "$orient" ]; then
  parts=(input oriented slimmed) base=oriented
  pose_args=(--orient --oriented-output "$out/oriented.ply" "${orient_args[@]}")
else
  parts=(input slimmed) base=input
  pose_args=(--dir 0,0,1)
fi
say "support-slim ${pose_args[*]} ${slim_args[*]:-(defaults)} --angle $angle"
"$slim" "$out/input.ply" -o "$out/slimmed.ply" "${pose_args[@]}" --angle "$angle" --plate-tolerance "$plate_tol" \
  "${slim_args[@]}" --quiet >"$out/slim.log" 2>&1 || die "support-slim failed: $(tail -1 "$out/slim.log")"
orient_direction="" orient_turn=""
if [ -n "$orient" ]; then
  orient_line="$(grep -E '^ +orientation +print direction' "$out/slim.log" || true)"
  [ -n "$orient_line" ] || die "support-slim printed no 'orientation' line (see $out/slim.log)"
  orient_direction="$(sed -E 's/.*direction \(([^)]*)\).*/\1/; s/ //g' <<<"$orient_line")"
  orient_turn="$(sed -E 's/.*turned ([0-9.]+) deg.*/\1/' <<<"$orient_line")"
fi
iter_line="$(grep -E '^ +iterations ' "$out/slim.log" || true)"
[ -n "$iter_line" ] || die "support-slim printed no 'iterations' line (see $out/slim.log)"
iterations="$(awk '{ print $2 }' <<<"$iter_line")"
slim_seconds="$(awk '{ print $4 }' <<<"$iter_line")"
stop_reason="$(sed -E 's/^[^(]*\((.*)\)$/\1/' <<<"$iter_line")"  # the outer parentheses

for part in "${parts[@]}"; do
  ref=(); [ "$part" = slimmed ] && ref=(--reference "$out/$base.ply")
  "$eval_tool" measure "$out/$part.ply" --angle "$angle" --plate-tolerance "$plate_tol" "${ref[@]}" \
    --stl "$out/$part.stl" --overhang-ply "$out/${part}_overhang.ply" >"$out/$part.txt" 2>"$out/$part.err" ||
    die "$(tail -1 "$out/$part.err" | sed 's/^slim-eval: //')"
done

# ---- 3./4. slice both under identical settings, measure the support -----------------------------
longest="$(kv "$out/prepare.txt" size | awk -F, '{ m = $1; if ($2 > m) m = $2; if ($3 > m) m = $3; print m }')"
bed="$(calc "($longest > 150 ? 2 * $longest : 300)")"  # square, with room around the part
center="$(calc "$bed / 2")"
slicer_settings=(
  --layer-height 0.2 --first-layer-height 0.2
  --nozzle-diameter 0.4 --filament-diameter 1.75
  --perimeters 2 --top-solid-layers 5 --bottom-solid-layers 4
  --fill-density 15% --fill-pattern rectilinear
  --support-material --support-material-auto --support-material-threshold "$threshold"
  --skirts 0 --brim-width 0
  --bed-shape "0x0,${bed}x0,${bed}x${bed},0x${bed}" --center "$center,$center"
  --gcode-comments
)
for part in "${parts[@]}"; do
  say "slicing $part.stl (PrusaSlicer, support threshold $threshold deg from the horizontal)"
  prusa-slicer --export-gcode "${slicer_settings[@]}" --output "$out/$part.gcode" "$out/$part.stl" \
    >"$out/slice_$part.log" 2>&1 || die "prusa-slicer failed on $part.stl: $(grep -iE 'error|exception' "$out/slice_$part.log" | tail -1)"
  "$eval_tool" gcode "$out/$part.gcode" >"$out/${part}_gcode.txt" 2>"$out/$part.err" ||
    die "$(tail -1 "$out/$part.err" | sed 's/^slim-eval: //')"
  [ "$(kv "$out/${part}_gcode.txt" "setting[support_material_threshold]")" = "$threshold" ] ||
    die "$part.gcode was not sliced with support threshold $threshold"
done

# ---- 5. shape change through MeshLab's Hausdorff Distance filter, both directions ---------------
say "Hausdorff distance (meshlabserver)"
hausdorff_filter() {  # SAMPLED TARGET
  cat <<EOF
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
EOF
}
{ echo '<!DOCTYPE FilterScript>'; echo '<FilterScript>'; hausdorff_filter 0 1; hausdorff_filter 1 0; echo '</FilterScript>'; } \
  >"$out/hausdorff.mlx"
xrun "$server" -i "$out/$base.ply" -i "$out/slimmed.ply" -s "$out/hausdorff.mlx" >"$out/hausdorff.log" 2>&1 ||
  die "meshlabserver failed on the Hausdorff Distance script (see $out/hausdorff.log)"
# Each run logs "LOG: 2 Sampled N pts ..." then "LOG: 2 min : a   max b   mean : c   RMS : d" in mm
# (meshlabserver then echoes the whole log again without the "LOG:" prefix).
mapfile -t hd < <(awk '/^LOG: .*Sampled [0-9]+ pts/ { want = 1; next }
                       want && /^LOG: .*min :/ { for (i = 1; i <= NF; i++) { if ($i == "max") mx = $(i+1); if ($i == "mean") mn = $(i+2) }
                                         print mx, mn; want = 0 }' "$out/hausdorff.log")
[ "${#hd[@]}" -eq 2 ] || die "meshlabserver logged ${#hd[@]} Hausdorff results instead of 2 (see $out/hausdorff.log)"
read -r max_in_out mean_in_out <<<"${hd[0]}"
read -r max_out_in mean_out_in <<<"${hd[1]}"
hausdorff="$(calc "($max_in_out > $max_out_in ? $max_in_out : $max_out_in)")"
mean_dist="$(calc "($mean_in_out + $mean_out_in) / 2")"

# ---- 6. pictures: same cameras for both, from above and from below -----------------------------
say "rendering"
read -r cx cy cz reach < <(awk -F'[=,]' '/^bbox_min=/ { x0 = $2; y0 = $3; z0 = $4 } /^bbox_max=/ { x1 = $2; y1 = $3; z1 = $4 }
  END { dx = x1 - x0; dy = y1 - y0; dz = z1 - z0; print (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2, 1.8 * sqrt(dx*dx + dy*dy + dz*dz) }' \
  "$out/input.txt")
camera() {  # ELEVATION_Z: the camera direction is (0.55, -0.8, ELEVATION_Z), normalised
  awk -v cx="$cx" -v cy="$cy" -v cz="$cz" -v r="$reach" -v ez="$1" 'BEGIN {
    n = sqrt(0.55 * 0.55 + 0.64 + ez * ez)
    printf "--camera-position=%g,%g,%g --camera-focal-point=%g,%g,%g --camera-view-up=0,0,1",
      cx + r * 0.55 / n, cy - r * 0.8 / n, cz + r * ez / n, cx, cy, cz }'
}
for part in "${parts[@]}"; do
  views=()
  for view in above:0.35 below:-0.6; do
    png="$out/${part}_${view%%:*}.png"
    # shellcheck disable=SC2046  # the camera flags are meant to split
    xrun f3d "$out/${part}_overhang.ply" --output="$png" --scalars=RGBA --comp=-2 --cells \
      --resolution=480,420 --bg-color=1,1,1 $(camera "${view#*:}") >"$out/render.log" 2>&1 && [ -s "$png" ] ||
      die "f3d could not render ${part}_overhang.ply (see $out/render.log)"
    views+=("$png")
  done
  # A caption on the top view; it needs a font, and the picture is fine without one.
  convert "${views[0]}" -background white -gravity north -splice 0x36 -font DejaVu-Sans -pointsize 22 -annotate +0+8 "$part" "${views[0]}" 2>/dev/null || true
  convert "${views[@]}" -append "$out/$part.png" || die "ImageMagick could not stack the views of $part"
done
picture="$out/before_after.png"
pictures=(); for part in "${parts[@]}"; do pictures+=("$out/$part.png"); done
convert "${pictures[@]}" +append "$picture" || die "ImageMagick could not join the pictures"

# ---- 7. report ----------------------------------------------------------------------------------
support_before="$(calc "$(kv "$out/input_gcode.txt" support_mm3)")"
support_after="$(calc "$(kv "$out/slimmed_gcode.txt" support_mm3)")"
change() {  # BEFORE AFTER -> signed % change, or n/a when BEFORE is 0
  awk -v b="$1" -v a="$2" 'BEGIN { if (b == 0) print "n/a"; else printf "%+.1f%%", 100 * (a / b - 1) }'
}
support_change="$(change "$support_before" "$support_after")"
risky_before="$(kv "$out/input.txt" risky_area)"; risky_after="$(kv "$out/slimmed.txt" risky_area)"
area_before="$(kv "$out/input.txt" area)"; area_after="$(kv "$out/slimmed.txt" area)"
volume_before="$(kv "$out/input.txt" volume)"; volume_after="$(kv "$out/slimmed.txt" volume)"
max_disp="$(kv "$out/slimmed.txt" max_displacement)"
proxy_before="$(kv "$out/input.txt" shadow_volume)"; proxy_after="$(kv "$out/slimmed.txt" shadow_volume)"
if [ -n "$orient" ]; then
  support_oriented="$(calc "$(kv "$out/oriented_gcode.txt" support_mm3)")"
  total_oriented="$(kv "$out/oriented_gcode.txt" total_mm3)"
  check_oriented="$(kv "$out/oriented_gcode.txt" total_vs_slicer_pct)"
  risky_oriented="$(kv "$out/oriented.txt" risky_area)"; area_oriented="$(kv "$out/oriented.txt" area)"
  proxy_oriented="$(kv "$out/oriented.txt" shadow_volume)"
fi
total_before="$(kv "$out/input_gcode.txt" total_mm3)"; total_after="$(kv "$out/slimmed_gcode.txt" total_mm3)"
check_before="$(kv "$out/input_gcode.txt" total_vs_slicer_pct)"; check_after="$(kv "$out/slimmed_gcode.txt" total_vs_slicer_pct)"
share() { awk -v v="$1" -v t="$2" 'BEGIN { printf "%.1f%%", 100 * v / t }'; }
pct_of_diag() { awk -v v="$1" -v d="$diag" 'BEGIN { printf "%.2f", 100 * v / d }'; }
elapsed=$((SECONDS - started))

{
  echo "support_mm3_before=$support_before"
  echo "support_mm3_after=$support_after"
  echo "support_change_pct=$(calc "($support_before > 0 ? 100 * ($support_after / $support_before - 1) : 0)")"
  echo "support_interface_mm_before=$(kv "$out/input_gcode.txt" support_interface_mm)"
  echo "support_interface_mm_after=$(kv "$out/slimmed_gcode.txt" support_interface_mm)"
  echo "filament_mm3_before=$total_before"
  echo "filament_mm3_after=$total_after"
  echo "total_vs_slicer_pct_before=$check_before"
  echo "total_vs_slicer_pct_after=$check_after"
  echo "shadow_volume_before=$proxy_before"
  echo "shadow_volume_after=$proxy_after"
  if [ -n "$orient" ]; then
    echo "support_mm3_oriented=$support_oriented"
    echo "filament_mm3_oriented=$total_oriented"
    echo "risky_area_oriented=$risky_oriented"
    echo "shadow_volume_oriented=$proxy_oriented"
    echo "orient_direction=$orient_direction"
    echo "orient_turn_deg=$orient_turn"
  fi
  echo "risky_area_before=$risky_before"
  echo "risky_area_after=$risky_after"
  echo "volume_before=$volume_before"
  echo "volume_after=$volume_after"
  echo "volume_change_pct=$(calc "100 * ($volume_after / $volume_before - 1)")"
  echo "hausdorff_mm=$hausdorff"
  echo "hausdorff_pct=$(pct_of_diag "$hausdorff")"
  echo "mean_distance_mm=$mean_dist"
  echo "mean_distance_pct=$(pct_of_diag "$mean_dist")"
  echo "max_displacement_mm=$max_disp"
  echo "iterations=$iterations"
  echo "slim_seconds=$slim_seconds"
  echo "angle=$angle"
  echo "slicer_threshold=$threshold"
  echo "size_mm=$size"
  echo "scale=$(kv "$out/prepare.txt" scale)"
  echo "bbox_diagonal_mm=$diag"
  echo "evaluation_seconds=$elapsed"
} >"$out/metrics.txt"

table_oriented() {
  echo "| | input (as given) | oriented | oriented + slimmed |"
  echo "| --- | ---: | ---: | ---: |"
  echo "| support material (PrusaSlicer) | $(fmt 0 "$support_before") mm³ | $(fmt 0 "$support_oriented") mm³ ($(change "$support_before" "$support_oriented")) | **$(fmt 0 "$support_after") mm³ ($support_change)** |"
  echo "| support proxy (shadow volume) | $(fmt 0 "$proxy_before") mm³ | $(fmt 0 "$proxy_oriented") mm³ ($(change "$proxy_before" "$proxy_oriented")) | $(fmt 0 "$proxy_after") mm³ ($(change "$proxy_before" "$proxy_after")) |"
  echo "| risky area (alpha_max $angle°) | $(fmt 1 "$risky_before") mm² ($(share "$risky_before" "$area_before")) | $(fmt 1 "$risky_oriented") mm² ($(share "$risky_oriented" "$area_oriented")) | $(fmt 1 "$risky_after") mm² ($(share "$risky_after" "$area_after")) |"
  echo "| all filament | $(fmt 0 "$total_before") mm³ | $(fmt 0 "$total_oriented") mm³ | $(fmt 0 "$total_after") mm³ |"
  echo "| print direction (input frame) | 0,0,1 | $orient_direction (turned $orient_turn°) | same |"
  echo "| Hausdorff distance, slimming only (oriented → slimmed) | | | $(fmt 3 "$hausdorff") mm ($(pct_of_diag "$hausdorff")% of diag) |"
  echo "| mean distance, slimming only | | | $(fmt 3 "$mean_dist") mm ($(pct_of_diag "$mean_dist")% of diag) |"
  echo "| largest vertex displacement, slimming only | | | $(fmt 3 "$max_disp") mm ($(pct_of_diag "$max_disp")% of diag) |"
  echo "| volume | $(fmt 0 "$volume_before") mm³ | | $(fmt 0 "$volume_after") mm³ ($(change "$volume_before" "$volume_after")) |"
  echo "| iterations, optimizer time | | | $iterations, $slim_seconds s ($stop_reason) |"
}

table() {
  if [ -n "$orient" ]; then table_oriented; return; fi
  echo "| | input | slimmed | change |"
  echo "| --- | ---: | ---: | ---: |"
  echo "| support material (PrusaSlicer) | $(fmt 0 "$support_before") mm³ | $(fmt 0 "$support_after") mm³ | **$support_change** |"
  echo "| all filament | $(fmt 0 "$total_before") mm³ | $(fmt 0 "$total_after") mm³ | $(change "$total_before" "$total_after") |"
  echo "| risky area (alpha_max $angle°) | $(fmt 1 "$risky_before") mm² ($(share "$risky_before" "$area_before")) | $(fmt 1 "$risky_after") mm² ($(share "$risky_after" "$area_after")) | $(change "$risky_before" "$risky_after") |"
  echo "| volume | $(fmt 0 "$volume_before") mm³ | $(fmt 0 "$volume_after") mm³ | $(change "$volume_before" "$volume_after") |"
  echo "| Hausdorff distance (symmetric) | | $(fmt 3 "$hausdorff") mm | $(pct_of_diag "$hausdorff")% of diag |"
  echo "| mean distance (both ways) | | $(fmt 3 "$mean_dist") mm | $(pct_of_diag "$mean_dist")% of diag |"
  echo "| largest vertex displacement | | $(fmt 3 "$max_disp") mm | $(pct_of_diag "$max_disp")% of diag |"
  echo "| iterations, optimizer time | | $iterations, $slim_seconds s | $stop_reason |"
}

{
  echo "# Support Slimming, judged by PrusaSlicer: $name"
  echo
  if [ -n "$orient" ]; then
    echo "Input \`$mesh\` as given along $dir, then turned by the orientation search (print direction"
    echo "$orient_direction of the input, $orient_turn° from it) and slimmed in that pose; scaled"
  else
    echo "Input \`$mesh\`, printed along $dir, scaled"
  fi
  echo " to a longest side of $size mm (×$(kv "$out/prepare.txt" scale)),"
  echo "bounding-box diagonal $(fmt 2 "$diag") mm. Self-supporting angle $angle° from the vertical, so"
  echo "PrusaSlicer's support threshold is $threshold° (it measures from the horizontal)."
  echo
  table
  echo
  echo "Differences in support volume under about 2% are slicer noise: a 0.1% change of scale moves"
  echo "the support by about 1.2%, a 1° turn about Z by about 0.75%. Both parts are sliced at one fixed"
  echo "scale, in the same place, with the same settings."
  echo
  echo "![${parts[*]}, left to right](before_after.png)"
  echo
  echo "Left to right: ${parts[*]}; top seen from above, bottom from below, same cameras."
  echo "Red faces need support by our rule (n·d + sin(alpha_max) < 0), blue ones do not."
  echo
  echo "## How it was measured"
  echo
  echo "- Support Slimming: \`support-slim ${pose_args[*]/#$out\//} --angle $angle --plate-tolerance $plate_tol${slim_args[*]:+ ${slim_args[*]}}\`"
  echo "  on the part in the print frame; it stopped after $iterations iterations ($stop_reason)."
  echo "- Slicer: $(prusa-slicer --help 2>/dev/null | grep -m1 -o 'PrusaSlicer-[^ ]*'), \`${slicer_settings[*]}\`."
  echo "- Support: the filament extruded (E rising while X/Y move, wipes and retractions left out) in the"
  echo "  G-code's \`;TYPE:Support material\` and \`;TYPE:Support material interface\` sections, times the"
  echo "  cross-section of $(kv "$out/input_gcode.txt" filament_diameter) mm filament. All extrusion summed the same way differs from"
  echo "  the slicer's own \"filament used\" by $(fmt 4 "$check_before")% (input) and $(fmt 4 "$check_after")% (slimmed)."
  echo "- Shape: MeshLab's Hausdorff Distance filter (meshlabserver), input → slimmed and slimmed → input,"
  echo "  100000 samples on faces, edges and vertices; max of the two maxima, mean of the two means."
  echo "  Volume and displacement from the meshes (same vertices before and after)."
  echo "- Files: \`input.gcode\`, \`slimmed.gcode\`, \`slimmed.ply\` (deformed part), \`metrics.txt\` beside this report."
} >"$out/report.md"

if [ -z "$quiet" ]; then echo; fi
echo "$name: support $(fmt 0 "$support_before") -> $(fmt 0 "$support_after") mm³ ($support_change) at alpha_max $angle°, $size mm"
table
echo "report:  $out/report.md"
echo "picture: $picture"
