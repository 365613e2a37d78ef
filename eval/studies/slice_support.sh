#!/usr/bin/env bash
# The support a slicer builds under a part, as the mean over turns about the print axis.
#
#   eval/studies/slice_support.sh PART.stl --slicer prusa|cura --angle DEG --out DIR [options]
#
# The part is in the print frame (+Z up, resting on z = 0; slim-eval prepare). Both slicers build
# support under a footprint on a grid aligned to the part's bounding box, so their figure jitters
# with the grid's phase: a speck that moves the box by half a cell moves it by several percent.
# Turning the part about the print axis changes no overhang angle, only that phase; the mean over
# a few turns is the figure to judge a change by. Turns are whole quarter turns (the coordinates
# are swapped, not rounded), so a part and its result are sliced at exactly the same four poses.
#
# Settings (both slicers alike): 0.2 mm layers (first layer too), 0.4 mm nozzle, 1.75 mm
# filament, 2 walls, 15% infill, no skirt/brim, automatic support everywhere (on the part too),
# at the self-supporting angle DEG from the vertical: PrusaSlicer's threshold is 90 - DEG (it
# measures from the horizontal), Cura's support_angle is DEG itself. Everything else is each
# slicer's default (PrusaSlicer: grid support with interface layers; Cura 4.13: zigzag support,
# no interface).
#
# Prints key=value lines: support_mm3 (mean over the turns), support_mm3_turn<DEG> for each
# turn, support_mm3_min, support_mm3_max, spread_pct (max - min against the mean),
# support_interface_mm3, total_mm3 (all filament, mean) and, for PrusaSlicer, the largest
# |total_vs_slicer_pct| (our sum of all extrusion against the slicer's own total). The G-codes
# stay in DIR as <slicer>_turn<DEG>.gcode. Exits non-zero with a one-line reason on failure.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"

usage() {
  cat <<'USAGE'
usage: eval/studies/slice_support.sh PART.stl --slicer prusa|cura --angle DEG --out DIR [options]
  --turns LIST   quarter turns about +Z, in degrees (multiples of 90)      [0,90,180,270]
  --jobs N       slicer runs at a time                                              [2]
  --bed MM       square bed side (the part is centred on it)                      [300]
  --build DIR    build tree holding eval/slim-eval                              [build]
  --cura-definitions DIR  folder with fdmprinter.def.json and fdmextruder.def.json
                 [$SLIM_CURA_DEFINITIONS, else /var/cache/support-slimming/cura/definitions]
USAGE
}
die() { echo "slice_support: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }

part="" slicer="" angle="" out="" turns="0,90,180,270" jobs=2 bed=300 build="$repo/build"
cura_defs="${SLIM_CURA_DEFINITIONS:-/var/cache/support-slimming/cura/definitions}"
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --slicer|--angle|--out|--turns|--jobs|--bed|--build|--cura-definitions)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --slicer) slicer="$2" ;; --angle) angle="$2" ;; --out) out="$2" ;; --turns) turns="$2" ;;
        --jobs) jobs="$2" ;; --bed) bed="$2" ;; --build) build="$2" ;; --cura-definitions) cura_defs="$2" ;;
      esac
      shift 2 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$part" ] || die "more than one part given"; part="$1"; shift ;;
  esac
done
[ -n "$part" ] && [ -r "$part" ] || die "cannot read the part '${part}'"
[ -n "$out" ] || die "--out DIR is required"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs expects a positive whole number, got '$jobs'"
[[ "$bed" =~ ^[0-9]+(\.[0-9]+)?$ ]] || die "--bed expects mm, got '$bed'"
eval_tool="$build/eval/slim-eval"
[ -x "$eval_tool" ] || die "$eval_tool is missing: build the target slim-eval"
awk -v a="$angle" 'BEGIN { exit !(a ~ /^[0-9]+(\.[0-9]+)?$/ && a > 0 && a < 90) }' ||
  die "--angle must lie strictly between 0 and 90 degrees, got '$angle'"
[[ "$turns" =~ ^[0-9]+(,[0-9]+)*$ ]] || die "--turns expects degrees like 0,90,180,270, got '$turns'"
IFS=, read -r -a turn_list <<<"$turns"
for t in "${turn_list[@]}"; do
  [[ "$t" =~ ^[0-9]+$ ]] && [ $((t % 90)) -eq 0 ] || die "--turns takes multiples of 90 degrees, got '$t'"
done
case "$slicer" in
  prusa) command -v prusa-slicer >/dev/null 2>&1 || die "prusa-slicer is not installed (scripts/setup.sh installs it)"
         threshold="$("$eval_tool" threshold "$angle" 2>&1)" || die "${threshold#slim-eval: }" ;;
  cura)  command -v CuraEngine >/dev/null 2>&1 || die "CuraEngine is not installed (scripts/setup.sh installs cura-engine)"
         [ -f "$cura_defs/fdmprinter.def.json" ] && [ -f "$cura_defs/fdmextruder.def.json" ] ||
           die "no Cura definitions in $cura_defs (scripts/setup.sh fetches them)" ;;
  *) die "--slicer must be prusa or cura, got '${slicer}'" ;;
esac
mkdir -p "$out" || die "cannot create $out"
centre="$(awk -v b="$bed" 'BEGIN { print b / 2 }')"

slice_prusa() {  # STL GCODE
  prusa-slicer --export-gcode --layer-height 0.2 --first-layer-height 0.2 --nozzle-diameter 0.4 \
    --filament-diameter 1.75 --perimeters 2 --top-solid-layers 5 --bottom-solid-layers 4 \
    --fill-density 15% --fill-pattern rectilinear \
    --support-material --support-material-auto --support-material-threshold "$threshold" \
    --skirts 0 --brim-width 0 --bed-shape "0x0,${bed}x0,${bed}x${bed},0x${bed}" --center "$centre,$centre" \
    --gcode-comments --output "$2" "$1"
}
slice_cura() {  # STL GCODE
  CuraEngine slice -m1 -j "$cura_defs/fdmprinter.def.json" \
    -s machine_width="$bed" -s machine_depth="$bed" -s machine_height="$bed" \
    -s machine_center_is_zero=false -s center_object=true \
    -s layer_height=0.2 -s layer_height_0=0.2 -s machine_nozzle_size=0.4 -s material_diameter=1.75 \
    -s wall_line_count=2 -s top_layers=5 -s bottom_layers=4 -s infill_sparse_density=15 \
    -s support_enable=true -s support_type=everywhere -s support_angle="$angle" -s adhesion_type=none \
    -e0 -s material_diameter=1.75 -s machine_nozzle_size=0.4 -l "$1" -o "$2"
}

# One turn: the turned part, sliced, measured into $out/<slicer>_turn<T>.txt.
one_turn() {  # DEG
  local t="$1" base="$out/${slicer}_turn$1"
  "$eval_tool" turn "$part" "$base.stl" --quarter-turns $(($1 / 90)) 2>"$base.err" ||
    { echo "$(tail -1 "$base.err")" >"$base.fail"; return 1; }
  "slice_$slicer" "$base.stl" "$base.gcode" >"$base.log" 2>&1 ||
    { echo "$slicer failed on the part turned by $t deg (see $base.log)" >"$base.fail"; return 1; }
  "$eval_tool" gcode "$base.gcode" --filament-diameter 1.75 >"$base.txt" 2>"$base.err" ||
    { echo "$(tail -1 "$base.err")" >"$base.fail"; return 1; }
  rm -f "$base.stl" "$base.err"
}

rm -f "$out/${slicer}"_turn*.fail
running=0
for t in "${turn_list[@]}"; do
  one_turn "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
done
wait || true
for t in "${turn_list[@]}"; do
  f="$out/${slicer}_turn$t.fail"
  [ ! -f "$f" ] || die "$(sed 's/^slim-eval: //' "$f")"
done

{
  echo "slicer=$slicer"
  echo "turns=$turns"
  for t in "${turn_list[@]}"; do echo "support_mm3_turn$t=$(kv "$out/${slicer}_turn$t.txt" support_mm3)"; done
} >"$out/${slicer}_turns.txt"
for t in "${turn_list[@]}"; do cat "$out/${slicer}_turn$t.txt"; echo "--"; done | awk -v slicer="$slicer" '
  function abs(x) { return x < 0 ? -x : x }
  /^support_mm3=/ { s = substr($0, 13) + 0; sum += s; n++; if (n == 1 || s < lo) lo = s; if (n == 1 || s > hi) hi = s }
  /^support_interface_mm3=/ { si += substr($0, 23) }
  /^total_mm3=/ { tot += substr($0, 11) }
  /^total_vs_slicer_pct=/ { c = abs(substr($0, 21)); if (c > check) check = c; seen = 1 }
  END {
    mean = sum / n
    printf "support_mm3=%.6g\nsupport_mm3_min=%.6g\nsupport_mm3_max=%.6g\n", mean, lo, hi
    printf "spread_pct=%.4g\n", (mean > 0 ? 100 * (hi - lo) / mean : 0)
    printf "support_interface_mm3=%.6g\ntotal_mm3=%.6g\n", si / n, tot / n
    if (seen) printf "total_vs_slicer_pct=%.6g\n", check
  }' >>"$out/${slicer}_turns.txt"
cat "$out/${slicer}_turns.txt"
