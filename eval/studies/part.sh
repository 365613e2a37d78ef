#!/usr/bin/env bash
# The independent judge: does Support Slimming save support material in a real slicer?
#
#   eval/run.sh part MESH [options]
#
#  1. The part in the print frame (print direction turned onto +Z), scaled so its longest side
#     is --size mm (default 60), resting on the plate (slim-eval prepare).
#  2. Support Slimming on it (the support-slim CLI, the same core as the MeshLab filter).
#  3. Input and result sliced by PrusaSlicer and by CuraEngine under identical settings,
#     automatic supports at alpha_max (eval/studies/slice_support.sh), each at 4 quarter turns about the
#     print axis: the slicers' support grid follows the part's bounding box, so a single run
#     jitters by several percent with the grid's phase; every support figure is the mean.
#  4. The support filament summed from the G-code's support sections (slim-eval gcode), checked
#     against PrusaSlicer's own total.
#  5. Shape change: symmetric Hausdorff and mean distance from MeshLab's "Hausdorff Distance"
#     filter (meshlabserver, both directions), volume change and crease share (the share of edge
#     length whose dihedral angle changed by more than 10 degrees, and its 99th percentile),
#     largest vertex displacement.
#  6. Pictures (eval/studies/pictures.sh; f3d under Xvfb, ImageMagick): input and result with
#     the risky faces red; the displacement as a heat map with a colour bar in mm; the support
#     each slicer will print, drawn from the G-code's support extrusions beside the part's walls.
#  7. OUT/report.md (the tables, the pictures, the settings) and OUT/metrics.txt (key=value).
#
# With --orient the CLI first turns the part into the print pose its orientation search chooses
# and slims it there; the report then has three columns: input (as given), oriented, and oriented
# + slimmed, and the shape change (Hausdorff, displacement, volume) is that of the slimming alone,
# oriented -> slimmed, in the oriented frame.
#
# Needs: a build with support-slim, slim-eval and the private MeshLab prefix (--build, default
# build/), and prusa-slicer, CuraEngine with Cura's definitions, Xvfb, f3d, ImageMagick
# (scripts/setup.sh installs them).
# Exits non-zero with a one-line reason on bad input or when a step fails.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"

usage() {
  cat <<'EOF'
usage: eval/run.sh part MESH [options]

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
  --slicers LIST          prusa, or prusa,cura                                  [prusa,cura]
  --turns LIST            quarter turns about +Z each slicer figure is the mean of [0,90,180,270]
  --build DIR             build tree holding cli/support-slim, eval/slim-eval, prefix/  [build]
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
slicers="prusa,cura" turns="0,90,180,270"
slim_args=() orient_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --out|--size|--angle|--dir|--build|--name|--resolution|--domain|--method|--iterations|--max-deviation|--max-k|--orient-effort|--slicers|--turns)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --out) out="$2" ;;
        --size) size="$2" ;;
        --angle) angle="$2" ;;
        --dir) dir="$2" ;;
        --build) build="$2" ;;
        --name) name="$2" ;;
        --slicers) slicers="$2" ;;
        --turns) turns="$2" ;;
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
slim="$build/cli/support-slim"; eval_tool="$build/eval/slim-eval"; server="$build/prefix/bin/meshlabserver"
for f in "$slim" "$eval_tool" "$server"; do
  [ -x "$f" ] || die "$f is missing: build the targets support-slim, slim-eval and filter_support_slimming"
done
case "$slicers" in prusa|prusa,cura) ;; *) die "--slicers must be prusa or prusa,cura, got '$slicers'" ;; esac
[[ "$turns" =~ ^[0-9]+(,[0-9]+)*$ ]] || die "--turns expects degrees like 0,90,180,270, got '$turns'"
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
export OPENBLAS_NUM_THREADS=1  # the optimizer's statistics must repeat (core/platform/blas_threads.h)
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
  ref=(); [ "$part" = slimmed ] && ref=(--reference "$out/$base.ply" --displacement-vtk "$out/displacement.vtk")
  "$eval_tool" measure "$out/$part.ply" --angle "$angle" --plate-tolerance "$plate_tol" "${ref[@]}" \
    --stl "$out/$part.stl" --overhang-ply "$out/${part}_overhang.ply" >"$out/$part.txt" 2>"$out/$part.err" ||
    die "$(tail -1 "$out/$part.err" | sed 's/^slim-eval: //')"
done

# ---- 3./4. slice every part under identical settings, mean over the turns ----------------------
longest="$(kv "$out/prepare.txt" size | awk -F, '{ m = $1; if ($2 > m) m = $2; if ($3 > m) m = $3; print m }')"
bed="$(calc "($longest > 150 ? 2 * $longest : 300)")"  # square, with room around the part
IFS=, read -r -a slicer_list <<<"$slicers"
for part in "${parts[@]}"; do
  for slicer in "${slicer_list[@]}"; do
    say "slicing $part.stl ($slicer, turns $turns)"
    "$repo/eval/studies/slice_support.sh" "$out/$part.stl" --slicer "$slicer" --angle "$angle" --turns "$turns" --bed "$bed" \
      --build "$build" --out "$out/slices/$part" >"$out/${part}_$slicer.txt" 2>"$out/$part.err" ||
      die "$(tail -1 "$out/$part.err" | sed 's/^slice_support: //')"
  done
  first_turn="${turns%%,*}"
  cp "$out/slices/$part/prusa_turn$first_turn.gcode" "$out/$part.gcode"
  [ "$(kv "$out/slices/$part/prusa_turn$first_turn.txt" "setting[support_material_threshold]")" = "$threshold" ] ||
    die "$part.gcode was not sliced with support threshold $threshold"
done

# ---- 5. shape change through MeshLab's Hausdorff Distance filter, both directions ---------------
say "Hausdorff distance (meshlabserver)"
"$repo/eval/studies/hausdorff.sh" "$out/$base.ply" "$out/slimmed.ply" --diag "$diag" --out "$out" --build "$build" \
  >"$out/hausdorff.txt" 2>"$out/hausdorff.err" || die "$(tail -1 "$out/hausdorff.err" | sed 's/^hausdorff: //')"
hausdorff="$(kv "$out/hausdorff.txt" hausdorff_mm)"; mean_dist="$(kv "$out/hausdorff.txt" mean_distance_mm)"

# ---- 6. pictures: risky faces, displacement, the slicers' support; same cameras throughout ------
say "rendering"
# shellcheck source=pictures.sh
. "$repo/eval/studies/pictures.sh"
render_pictures

# ---- 7. report ----------------------------------------------------------------------------------
# sup PART SLICER [KEY]: a slicer figure of a part (default: the support, mean over the turns).
sup() { [ -f "$out/${1}_$2.txt" ] && calc "$(kv "$out/${1}_$2.txt" "${3:-support_mm3}")" || true; }
change() {  # BEFORE AFTER -> signed % change, or n/a when BEFORE is 0
  awk -v b="$1" -v a="$2" 'BEGIN { if (b == "" || a == "" || b == 0) print "n/a"; else printf "%+.1f%%", 100 * (a / b - 1) }'
}
change_num() { awk -v b="$1" -v a="$2" 'BEGIN { printf "%.6g", (b > 0 ? 100 * (a / b - 1) : 0) }'; }
support_before="$(sup input prusa)"; support_after="$(sup slimmed prusa)"
support_change="$(change "$support_before" "$support_after")"
cura_before="$(sup input cura)"; cura_after="$(sup slimmed cura)"
risky_before="$(kv "$out/input.txt" risky_area)"; risky_after="$(kv "$out/slimmed.txt" risky_area)"
area_before="$(kv "$out/input.txt" area)"; area_after="$(kv "$out/slimmed.txt" area)"
volume_before="$(kv "$out/$base.txt" volume)"; volume_after="$(kv "$out/slimmed.txt" volume)"
max_disp="$(kv "$out/slimmed.txt" max_displacement)"
crease_share="$(kv "$out/slimmed.txt" crease_share_pct)"; crease_p99="$(kv "$out/slimmed.txt" crease_p99_deg)"
mean_disp="$(kv "$out/slimmed.txt" mean_displacement)"; height_change="$(kv "$out/slimmed.txt" height_change_pct)"
affine="$(kv "$out/slimmed.txt" affine_departure_pct)"; folded="$(kv "$out/slimmed.txt" folded_faces)"
extents="$(for a in x y z; do kv "$out/slimmed.txt" "extent_change_${a}_pct"; done | tr '\n' ' ')"
proxy_before="$(kv "$out/input.txt" shadow_volume)"; proxy_after="$(kv "$out/slimmed.txt" shadow_volume)"
if [ -n "$orient" ]; then
  support_oriented="$(sup oriented prusa)"; cura_oriented="$(sup oriented cura)"
  total_oriented="$(sup oriented prusa total_mm3)"
  risky_oriented="$(kv "$out/oriented.txt" risky_area)"; area_oriented="$(kv "$out/oriented.txt" area)"
  proxy_oriented="$(kv "$out/oriented.txt" shadow_volume)"
fi
total_before="$(sup input prusa total_mm3)"; total_after="$(sup slimmed prusa total_mm3)"
check_before="$(sup input prusa total_vs_slicer_pct)"; check_after="$(sup slimmed prusa total_vs_slicer_pct)"
share() { awk -v v="$1" -v t="$2" 'BEGIN { printf "%.1f%%", 100 * v / t }'; }
pct_of_diag() { awk -v v="$1" -v d="$diag" 'BEGIN { printf "%.2f", 100 * v / d }'; }
n_turns="$(awk -F, '{ print NF }' <<<"$turns")"
elapsed=$((SECONDS - started))

{
  echo "support_mm3_before=$support_before"
  echo "support_mm3_after=$support_after"
  echo "support_change_pct=$(change_num "$support_before" "$support_after")"
  echo "support_spread_pct_before=$(sup input prusa spread_pct)"
  echo "support_spread_pct_after=$(sup slimmed prusa spread_pct)"
  echo "support_interface_mm3_before=$(sup input prusa support_interface_mm3)"
  echo "support_interface_mm3_after=$(sup slimmed prusa support_interface_mm3)"
  if [ -n "$cura_before" ]; then
    echo "cura_support_mm3_before=$cura_before"
    echo "cura_support_mm3_after=$cura_after"
    echo "cura_support_change_pct=$(change_num "$cura_before" "$cura_after")"
    echo "cura_support_spread_pct_before=$(sup input cura spread_pct)"
    echo "cura_support_spread_pct_after=$(sup slimmed cura spread_pct)"
  fi
  echo "turns=$n_turns"
  echo "filament_mm3_before=$total_before"
  echo "filament_mm3_after=$total_after"
  echo "total_vs_slicer_pct_before=$check_before"
  echo "total_vs_slicer_pct_after=$check_after"
  echo "shadow_volume_before=$proxy_before"
  echo "shadow_volume_after=$proxy_after"
  if [ -n "$orient" ]; then
    echo "support_mm3_oriented=$support_oriented"
    [ -z "$cura_oriented" ] || echo "cura_support_mm3_oriented=$cura_oriented"
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
  echo "volume_change_pct=$(change_num "$volume_before" "$volume_after")"
  echo "crease_share_pct=$crease_share"
  echo "crease_p99_deg=$crease_p99"
  echo "hausdorff_mm=$hausdorff"
  echo "hausdorff_pct=$(pct_of_diag "$hausdorff")"
  echo "mean_distance_mm=$mean_dist"
  echo "mean_distance_pct=$(pct_of_diag "$mean_dist")"
  echo "max_displacement_mm=$max_disp"
  echo "mean_displacement_mm=$mean_disp"
  echo "mean_displacement_pct=$(pct_of_diag "$mean_disp")"
  read -r extent_x extent_y extent_z <<<"$extents"
  echo "extent_change_x_pct=$extent_x"
  echo "extent_change_y_pct=$extent_y"
  echo "extent_change_z_pct=$extent_z"
  echo "height_change_pct=$height_change"
  echo "affine_departure_pct=$affine"
  echo "folded_faces=$folded"
  echo "iterations=$iterations"
  echo "slim_seconds=$slim_seconds"
  echo "angle=$angle"
  echo "slicer_threshold=$threshold"
  echo "size_mm=$size"
  echo "scale=$(kv "$out/prepare.txt" scale)"
  echo "bbox_diagonal_mm=$diag"
  echo "evaluation_seconds=$elapsed"
} >"$out/metrics.txt"

# Rows every table shares: the shape change of the slimming, next to each other.
shape_rows() {  # WITH_VOLUME(yes/no) LEADING_EMPTY_CELLS
  [ "$1" = no ] || echo "| volume change | $2$(change "$volume_before" "$volume_after") |"
  echo "| crease share (dihedral change > 10°) | $2$(fmt 2 "$crease_share")% of edge length, 99th percentile $(fmt 1 "$crease_p99")° |"
  echo "| Hausdorff distance (symmetric) | $2$(fmt 3 "$hausdorff") mm ($(pct_of_diag "$hausdorff")% of diag) |"
  echo "| mean distance (both ways) | $2$(fmt 3 "$mean_dist") mm ($(pct_of_diag "$mean_dist")% of diag) |"
  echo "| largest vertex displacement | $2$(fmt 3 "$max_disp") mm ($(pct_of_diag "$max_disp")% of diag) |"
  echo "| mean vertex displacement | $2$(fmt 3 "$mean_disp") mm ($(pct_of_diag "$mean_disp")% of diag) |"
  echo "| proportions | $2height $(fmt 2 "$height_change")%, best-fit affine map $(fmt 2 "$affine")% from rigid, $folded folded faces |"
}
mm3() { [ -n "$1" ] && echo "$(fmt 0 "$1") mm³" || echo "n/a"; }

table_oriented() {
  echo "| | input (as given) | oriented | oriented + slimmed |"
  echo "| --- | ---: | ---: | ---: |"
  echo "| support, PrusaSlicer (mean of $n_turns turns) | $(mm3 "$support_before") | $(mm3 "$support_oriented") ($(change "$support_before" "$support_oriented")) | **$(mm3 "$support_after") ($support_change)** |"
  [ -z "$cura_before" ] || echo "| support, Cura (mean of $n_turns turns) | $(mm3 "$cura_before") | $(mm3 "$cura_oriented") ($(change "$cura_before" "$cura_oriented")) | **$(mm3 "$cura_after") ($(change "$cura_before" "$cura_after"))** |"
  echo "| support proxy (shadow volume) | $(mm3 "$proxy_before") | $(mm3 "$proxy_oriented") ($(change "$proxy_before" "$proxy_oriented")) | $(mm3 "$proxy_after") ($(change "$proxy_before" "$proxy_after")) |"
  echo "| risky area (alpha_max $angle°) | $(fmt 1 "$risky_before") mm² ($(share "$risky_before" "$area_before")) | $(fmt 1 "$risky_oriented") mm² ($(share "$risky_oriented" "$area_oriented")) | $(fmt 1 "$risky_after") mm² ($(share "$risky_after" "$area_after")) |"
  echo "| all filament (PrusaSlicer) | $(mm3 "$total_before") | $(mm3 "$total_oriented") | $(mm3 "$total_after") |"
  echo "| print direction (input frame) | 0,0,1 | $orient_direction (turned $orient_turn°) | same |"
  echo "| *slimming only (oriented → slimmed):* | | | |"
  shape_rows yes "| | "
  echo "| iterations, optimizer time | | | $iterations, $slim_seconds s ($stop_reason) |"
}

table() {
  if [ -n "$orient" ]; then table_oriented; return; fi
  echo "| | input | slimmed | change |"
  echo "| --- | ---: | ---: | ---: |"
  echo "| support, PrusaSlicer (mean of $n_turns turns) | $(mm3 "$support_before") | $(mm3 "$support_after") | **$support_change** |"
  [ -z "$cura_before" ] || echo "| support, Cura (mean of $n_turns turns) | $(mm3 "$cura_before") | $(mm3 "$cura_after") | **$(change "$cura_before" "$cura_after")** |"
  echo "| all filament (PrusaSlicer) | $(mm3 "$total_before") | $(mm3 "$total_after") | $(change "$total_before" "$total_after") |"
  echo "| risky area (alpha_max $angle°) | $(fmt 1 "$risky_before") mm² ($(share "$risky_before" "$area_before")) | $(fmt 1 "$risky_after") mm² ($(share "$risky_after" "$area_after")) | $(change "$risky_before" "$risky_after") |"
  echo "| volume | $(mm3 "$volume_before") | $(mm3 "$volume_after") | $(change "$volume_before" "$volume_after") |"
  shape_rows no "| | "
  echo "| iterations, optimizer time | | $iterations, $slim_seconds s | $stop_reason |"
}

turn_table() {  # the figure of each turn: how far a single run can be off
  echo "| support per turn (mm³) | $(tr ',' '\n' <<<"$turns" | sed 's/$/°/' | paste -sd'|' | sed 's/|/ | /g') | spread |"
  echo "| --- |$(tr ',' '\n' <<<"$turns" | sed 's/.*/ ---: |/' | paste -sd'\0')  ---: |"
  for part in "${parts[@]}"; do
    for slicer in "${slicer_list[@]}"; do
      echo "| $part, $slicer | $(for t in ${turns//,/ }; do printf '%s | ' "$(fmt 0 "$(kv "$out/${part}_$slicer.txt" "support_mm3_turn$t")")"; done)$(fmt 1 "$(kv "$out/${part}_$slicer.txt" spread_pct)")% |"
    done
  done
}

{
  echo "# Support Slimming, judged by PrusaSlicer and Cura: $name"
  echo
  if [ -n "$orient" ]; then
    echo "Input \`$mesh\` as given along $dir, then turned by the orientation search (print direction"
    echo "$orient_direction of the input, $orient_turn° from it) and slimmed in that pose; scaled"
  else
    echo "Input \`$mesh\`, printed along $dir, scaled"
  fi
  echo " to a longest side of $size mm (×$(kv "$out/prepare.txt" scale)),"
  echo "bounding-box diagonal $(fmt 2 "$diag") mm. Self-supporting angle $angle° from the vertical, so"
  echo "PrusaSlicer's support threshold is $threshold° (it measures from the horizontal) and Cura's support angle $angle°."
  echo
  table
  echo
  echo "Each support figure is the mean over $n_turns quarter turns about the print axis. The slicers"
  echo "stretch support to a grid aligned with the part's bounding box, so one run moves by several"
  echo "percent with the grid's phase alone (below); differences within that spread are slicer noise."
  echo
  turn_table
  echo
  echo "![${parts[*]}, left to right](before_after.png)"
  echo
  echo "Left to right: ${parts[*]}; top seen from above, bottom from below, same cameras."
  echo "Red faces need support by our rule (n·d + sin(alpha_max) < 0), blue ones do not."
  echo
  echo "![how far each vertex moved](displacement.png)"
  echo
  echo "How far each vertex moved from the $base part, in mm (colour bar), from above and below."
  echo
  echo "![the support the slicers print](support.png)"
  echo
  echo "The support each slicer will print (orange: its support extrusions in the G-code, turn ${turns%%,*}),"
  echo "beside the part's outer walls of every second layer (grey); ${parts[*]} left to right, same camera."
  echo
  echo "## How it was measured"
  echo
  echo "- Support Slimming: \`support-slim ${pose_args[*]/#$out\//} --angle $angle --plate-tolerance $plate_tol${slim_args[*]:+ ${slim_args[*]}}\`"
  echo "  on the part in the print frame; it stopped after $iterations iterations ($stop_reason)."
  echo "- Slicers: $(prusa-slicer --help 2>/dev/null | grep -m1 -o 'PrusaSlicer-[^ ]*')$( [ -z "$cura_before" ] || echo ", CuraEngine $(CuraEngine help 2>&1 | grep -m1 -o 'version [0-9.]*' | cut -d' ' -f2)"),"
  echo "  with the settings of \`eval/studies/slice_support.sh\` (0.2 mm layers, 2 walls, 15% infill, automatic support everywhere),"
  echo "  each part at turns $turns about +Z."
  echo "- Support: the filament extruded (E rising while X/Y move, wipes and retractions left out) in the"
  echo "  G-code's support sections (PrusaSlicer: \`Support material\`, \`Support material interface\`; Cura:"
  echo "  \`SUPPORT\`, \`SUPPORT-INTERFACE\`), times the filament's cross-section (1.75 mm). All extrusion summed the"
  echo "  same way differs from PrusaSlicer's own \"filament used\" by at most $(fmt 4 "$check_before")% (input) and $(fmt 4 "$check_after")% (slimmed)."
  echo "- Shape: MeshLab's Hausdorff Distance filter (meshlabserver), $base → slimmed and slimmed → $base,"
  echo "  100000 samples on faces, edges and vertices; max of the two maxima, mean of the two means."
  echo "  Volume (signed enclosed volume), crease share (over interior manifold edges, the length share whose"
  echo "  dihedral angle changed by more than 10°) and displacement from the meshes (same vertices before and after)."
  echo "- Files: \`slices/<part>/<slicer>_turn<deg>.gcode\`, \`slimmed.ply\` (deformed part), \`metrics.txt\` beside this report."
} >"$out/report.md"

if [ -z "$quiet" ]; then echo; fi
echo "$name: support $(fmt 0 "$support_before") -> $(fmt 0 "$support_after") mm³ ($support_change, PrusaSlicer, mean of $n_turns turns) at alpha_max $angle°, $size mm"
table
echo "report:  $out/report.md"
echo "picture: $out/before_after.png"
