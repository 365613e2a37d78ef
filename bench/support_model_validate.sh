#!/usr/bin/env bash
# The support model (core/support_model.h) against the slicers: PrusaSlicer and CuraEngine.
#
#   bench/support_model_validate.sh [options] [NAME=MESH ...]
#
# For every model (the T, mushroom and arch test shapes, the sample bunny, and any NAME=MESH
# given) in the print frame at a 60 mm longest side, the input and the results of support-slim
# (the paper's method at 5%, the coherent method at 2, 5 and 10%) are
#   - sliced by PrusaSlicer (the settings of tools/evaluate.sh) and by CuraEngine (the same print
#     settings, supports everywhere at support_angle = alpha_max), each at 4 turns about the print
#     axis (0, 22.5, 45, 67.5 degrees: a quarter turn maps the slicer's grid onto itself), and the
#     support filament of each G-code summed; a slicer's figure is the mean over the turns;
#   - estimated by the model (its defaults, one turn).
# It prints a Markdown table: per mesh the absolute support (mm³) and, for results, the change
# from the input (%), and the model's error against each slicer in points of that change; then
# the mean absolute errors. Files go to OUT (default out/support-model); finished slices are
# kept there and not redone, so a second run only adds what is missing.
#
# Needs: a build with support_model_tool, slim-eval, support-slim and write_shape (--build),
# prusa-slicer and cura-engine (installed when missing: apt-get), and CuraEngine's printer
# definitions from Debian's cura package (downloaded once into the cache folder).
# Cost: about 5-15 s per slice, two at a time (--jobs); some 20 minutes cold for the built-in set.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
self="$repo/bench/support_model_validate.sh"
die() { echo "support_model_validate: $*" >&2; exit 1; }

# ---- one slice (called back through xargs): MESH TURN SLICER OUTDIR BUILD CURA_DEFS ANGLE --------
if [ "${1:-}" = "--slice-one" ]; then
  mesh="$2" turn="$3" slicer="$4" dir="$5" build="$6" defs="$7" angle="$8"
  base="$dir/$(basename "${mesh%.*}").t$turn"
  [ -s "$base.$slicer.txt" ] && exit 0
  stl="$base.stl"
  [ -s "$stl" ] || "$build/bench/support_model_tool" turn "$mesh" "$turn" "$stl"
  gcode="$base.$slicer.gcode"
  if [ "$slicer" = prusa ]; then
    threshold="$("$build/tools/slim-eval" threshold "$angle")"
    prusa-slicer --export-gcode --layer-height 0.2 --first-layer-height 0.2 --nozzle-diameter 0.4 \
      --filament-diameter 1.75 --perimeters 2 --top-solid-layers 5 --bottom-solid-layers 4 --fill-density 15% \
      --fill-pattern rectilinear --support-material --support-material-auto --support-material-threshold "$threshold" \
      --skirts 0 --brim-width 0 --bed-shape 0x0,300x0,300x300,0x300 --center 150,150 --gcode-comments \
      --output "$gcode" "$stl" >"$base.$slicer.log" 2>&1 || { echo "prusa-slicer failed on $stl" >&2; exit 1; }
  else
    # CuraEngine evaluates no setting formulas: the values its front end would derive are given.
    CuraEngine slice -m1 -j "$defs/fdmprinter.def.json" \
      -s layer_height=0.2 -s layer_height_0=0.2 -s machine_nozzle_size=0.4 -s material_diameter=1.75 \
      -s wall_line_count=2 -s top_layers=5 -s bottom_layers=4 -s infill_sparse_density=15 -s infill_pattern=lines \
      -s infill_sparse_thickness=0.2 -s support_enable=true -s support_type=everywhere -s support_angle="$angle" \
      -s support_wall_count=0 -s support_infill_sparse_thickness=0.2 -s adhesion_type=none \
      -s machine_width=300 -s machine_depth=300 -s machine_height=300 -s center_object=true \
      -e0 -s machine_nozzle_size=0.4 -s material_diameter=1.75 \
      -l "$stl" -o "$gcode" >"$base.$slicer.log" 2>&1 || { echo "CuraEngine failed on $stl" >&2; exit 1; }
  fi
  "$build/bench/support_model_tool" gcode "$gcode" | sed 's/^support_mm3=//' >"$base.$slicer.txt.tmp"
  mv "$base.$slicer.txt.tmp" "$base.$slicer.txt"
  rm -f "$gcode"
  exit 0
fi

usage() {
  sed -n '2,22p' "$self" | sed 's/^# \{0,1\}//'
  cat <<'EOF'
options:
  --build DIR     build tree                                               [build]
  --out DIR       where the meshes, slices and the table go                [out/support-model]
  --jobs N        slices run at the same time                              [2]
  --no-cura       PrusaSlicer only
  --no-shapes     only the NAME=MESH models given (the bunny and shapes left out)
  --angle DEG     alpha_max                                                [45]
EOF
}

build="$repo/build" out="$repo/out/support-model" jobs=2 cura=1 shapes=1 angle=45 extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --angle) angle="$2"; shift 2 ;;
    --no-cura) cura=""; shift ;;
    --no-shapes) shapes=""; shift ;;
    *=*) extra+=("$1"); shift ;;
    *) die "unknown argument $1 (see --help)" ;;
  esac
done
for f in bench/support_model_tool tools/slim-eval cli/support-slim tests/eval/write_shape; do
  [ -x "$build/$f" ] || die "$build/$f is missing: build the project first"
done
need=()
command -v prusa-slicer >/dev/null || need+=(prusa-slicer)
[ -z "$cura" ] || command -v CuraEngine >/dev/null || need+=(cura-engine)
[ ${#need[@]} -eq 0 ] || DEBIAN_FRONTEND=noninteractive apt-get install -y "${need[@]}" >/dev/null || die "cannot install ${need[*]}"

# CuraEngine's printer definitions come with Debian's cura package (not with cura-engine).
cache="${SLIM_CACHE:-/var/cache/support-slimming}/cura-definitions"
if [ -n "$cura" ] && [ ! -s "$cache/fdmprinter.def.json" ]; then
  tmp="$(mktemp -d)"
  (cd "$tmp" && apt-get download cura >/dev/null 2>&1 && dpkg -x cura_*.deb x) || die "cannot download Debian's cura package"
  mkdir -p "$cache" && cp "$tmp"/x/usr/share/cura/resources/definitions/fdm{printer,extruder}.def.json "$cache/"
  rm -rf "$tmp"
fi

# ---- the models and their slimmed results ----------------------------------------------------
mkdir -p "$out"
out="$(cd "$out" && pwd)"
models=()
add_model() {  # NAME MESH
  mkdir -p "$out/$1"
  [ -s "$out/$1/input.ply" ] || "$build/tools/slim-eval" prepare "$2" "$out/$1/input" --size 60 >/dev/null
  models+=("$1")
}
if [ -n "$shapes" ]; then
  for shape in t mushroom arch; do
    [ -s "$out/$shape.ply" ] || "$build/tests/eval/write_shape" "$shape" "$out/$shape.ply" 2
    add_model "$shape" "$out/$shape.ply"
  done
  add_model bunny "$repo/data/bunny.ply"
fi
for e in "${extra[@]}"; do add_model "${e%%=*}" "${e#*=}"; done
variants=(input paper5 coherent2 coherent5 coherent10)
for m in "${models[@]}"; do
  for v in "${variants[@]:1}"; do
    [ -s "$out/$m/$v.ply" ] && continue
    method="${v%%[0-9]*}" budget="${v##*[a-z]}"
    OPENBLAS_NUM_THREADS=1 "$build/cli/support-slim" "$out/$m/input.ply" -o "$out/$m/$v.ply" --method "$method" \
      --max-deviation "$budget" --angle "$angle" --quiet >"$out/$m/$v.log" 2>&1 || die "support-slim failed on $m ($v)"
  done
done

# ---- slices, two at a time --------------------------------------------------------------------
turns=(0 22.5 45 67.5)
slicers=(prusa); [ -z "$cura" ] || slicers+=(cura)
for m in "${models[@]}"; do
  for v in "${variants[@]}"; do
    for t in "${turns[@]}"; do
      for s in "${slicers[@]}"; do echo "$out/$m/$v.ply $t $s $out/$m"; done
    done
  done
done | xargs -P "$jobs" -L 1 bash -c '"$0" --slice-one "$1" "$2" "$3" "$4" "'"$build"'" "'"$cache"'" "'"$angle"'"' "$self"

# ---- the model, and the table -----------------------------------------------------------------
mean_of() { awk '{ s += $1; n++ } END { if (n) printf "%.3f", s / n }' "$@"; }
rows="$out/results.tsv"
: >"$rows"
for m in "${models[@]}"; do
  for v in "${variants[@]}"; do
    model="$("$build/bench/support_model_tool" estimate "$out/$m/$v.ply" --angle "$angle" | awk -F= '$1 == "volume_mm3" { print $2 }')"
    prusa="$(mean_of "$out/$m/$v".t*.prusa.txt)"
    curav=""; [ -z "$cura" ] || curav="$(mean_of "$out/$m/$v".t*.cura.txt)"
    printf '%s\t%s\t%s\t%s\t%s\n' "$m" "$v" "$prusa" "${curav:-nan}" "$model" >>"$rows"
  done
done
awk -F'\t' -v cura="$cura" '
  function pct(a, b) { return b > 0 ? 100 * (a / b - 1) : 0 }
  BEGIN {
    print "| model | mesh | PrusaSlicer mm³ | Cura mm³ | model mm³ | PrusaSlicer change | Cura change | model change | error vs PrusaSlicer (points) | error vs Cura (points) |"
    print "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  }
  $2 == "input" { p0 = $3; c0 = $4; m0 = $5 }
  {
    line = sprintf("| %s | %s | %.0f | %s | %.0f |", $1, $2, $3, cura ? sprintf("%.0f", $4) : "", $5)
    if ($2 == "input") { print line " | | | | | |"; next }
    dp = pct($3, p0); dc = pct($4, c0); dm = pct($5, m0)
    ep = dm - dp; ec = dm - dc; ap += (ep < 0 ? -ep : ep); ac += (ec < 0 ? -ec : ec); n++
    if ((ep < 0 ? -ep : ep) > wp) wp = (ep < 0 ? -ep : ep)
    if ((ec < 0 ? -ec : ec) > wc) wc = (ec < 0 ? -ec : ec)
    printf "%s %+.1f%% | %s | %+.1f%% | %+.1f | %s |\n", line, dp, cura ? sprintf("%+.1f%%", dc) : "", dm, ep, cura ? sprintf("%+.1f", ec) : ""
  }
  END {
    if (n) printf "\nMean absolute error of the predicted change: %.1f points against PrusaSlicer (worst %.1f)%s, over %d results.\n",
      ap / n, wp, cura ? sprintf(", %.1f against Cura (worst %.1f)", ac / n, wc) : "", n
  }' "$rows" | tee "$out/table.md"
