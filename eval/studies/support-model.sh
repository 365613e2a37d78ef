#!/usr/bin/env bash
# The support model (core/support_model/support_model.h) against the judge: PrusaSlicer and CuraEngine.
#
#   eval/run.sh support-model [options] [NAME=MESH ...]
#
# For every model (the corpus of eval/run.sh corpus, the T, mushroom and arch test shapes, and any
# NAME=MESH given; all in the print frame at a 60 mm longest side) the input and the results of
# support-slim (the paper's method at 5%, the coherent method at 5 and 10%) are
#   - sliced by both slicers through eval/studies/slice_support.sh (the judge's settings), each figure
#     the mean over the quarter turns 0 and 90 degrees (--turns): the judge's other two, 180 and
#     270, lay the support lines along the same axes as these two and give the same figures to
#     within 0.3% (the bunny: 5104, 4721, 5118, 4704 mm³ at 0, 90, 180, 270), at twice the cost;
#   - estimated by the model: its defaults (the grid phases averaged) and at the slicer's own
#     phase (grid_phases 1, the grid aligned to the bounding-box centre as PrusaSlicer aligns it).
# It prints a Markdown table: per mesh the absolute support (mm³); for results the change from
# the input (%) by each slicer and the model, and the model's error in points of that change;
# then the mean and largest absolute errors, per kind of model (organic, cad, creature, shape),
# meshes with open edges apart (each slicer closes their holes its own way before slicing; the
# model reads the faces as they are).
# "Phase luck" is the model's own change at the slicer's phase less its phase-averaged change:
# how much of a slicer's change the grid's phase alone may have made (the judge's quarter turns
# keep the grid's phase: the grid is centred on the bounding box, which a quarter turn maps onto
# itself).
# Files go to OUT (default out/support-model); finished slices are kept and not redone, so a
# second run only adds what is missing (--table-only: no slicing, the model estimated afresh on
# the meshes there and the table printed).
#
# Needs: a build with support_model_tool, slim-eval, support-slim and write_shape (--build); the
# corpus (eval/studies/corpus.sh, run when missing); prusa-slicer, cura-engine and Cura's printer
# definitions (scripts/setup.sh). Cost: 4 slices per mesh (2 slicers × 2 turns), 2-6 s each on an
# idle machine, two at a time: about 20 minutes cold for the 18 models × 4 meshes, seconds warm.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
die() { echo "support-model: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }

usage() {
  sed -n '2,23p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
  cat <<'EOF'
options:
  --build DIR     build tree                                          [build]
  --out DIR       where the meshes, slices and the table go           [out/support-model]
  --corpus DIR    the corpus (eval/run.sh corpus --out DIR)           [data/corpus]
  --jobs N        slicer runs at a time                               [2]
  --no-corpus     only the test shapes and the NAME=MESH given
  --table-only    no slicing or slimming: the table from the files in OUT
  --angle DEG     alpha_max                                           [45]
  --turns LIST    the quarter turns sliced (studies/slice_support.sh) [0,90]
EOF
}

build="$repo/build" out="$repo/out/support-model" corpus="$repo/data/corpus" jobs=2 angle=45 turns=0,90
use_corpus=1 table_only="" extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --build|--out|--corpus|--jobs|--angle|--turns)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --build) build="$2" ;; --out) out="$2" ;; --corpus) corpus="$2" ;; --jobs) jobs="$2" ;; --angle) angle="$2" ;;
        --turns) turns="$2" ;;
      esac
      shift 2 ;;
    --no-corpus) use_corpus=""; shift ;;
    --table-only) table_only=1; shift ;;
    *=*) extra+=("$1"); shift ;;
    *) die "unknown argument $1 (see --help)" ;;
  esac
done
build="$(cd "$build" 2>/dev/null && pwd)" || die "no build tree at the --build path"
for f in eval/support_model_tool eval/slim-eval cli/support-slim tests/eval/write_shape; do
  [ -x "$build/$f" ] || die "$build/$f is missing: build the project first"
done
mkdir -p "$out"
out="$(cd "$out" && pwd)"

# ---- the models: NAME KIND MESH per line ---------------------------------------------------------
models="$out/models.tsv"
if [ -z "$table_only" ]; then
  : >"$models"
  if [ -n "$use_corpus" ]; then
    [ -s "$corpus/manifest.tsv" ] || "$repo/eval/studies/corpus.sh" --out "$corpus" >/dev/null || die "eval/studies/corpus.sh failed"
    awk -F'\t' -v dir="$corpus" 'NR > 1 { print $1 "\t" $2 "\t" dir "/" $1 ".ply" }' "$corpus/manifest.tsv" >>"$models"
  fi
  for shape in t mushroom arch; do
    [ -s "$out/$shape.ply" ] || "$build/tests/eval/write_shape" "$shape" "$out/$shape.ply" 2
    printf '%s\tshape\t%s\n' "$shape" "$out/$shape.ply" >>"$models"
  done
  for e in "${extra[@]}"; do printf '%s\textra\t%s\n' "${e%%=*}" "${e#*=}" >>"$models"; done
fi
[ -s "$models" ] || die "no models (run without --table-only first)"

variants=(input paper5 coherent5 coherent10)
if [ -z "$table_only" ]; then
  while IFS=$'\t' read -r name kind mesh; do
    dir="$out/$name"
    mkdir -p "$dir"
    [ -s "$dir/input.ply" ] || "$build/eval/slim-eval" prepare "$mesh" "$dir/input" --size 60 >/dev/null ||
      die "cannot prepare $mesh"
    for v in "${variants[@]:1}"; do
      [ -s "$dir/$v.ply" ] && continue
      method="${v%%[0-9]*}" budget="${v##*[a-z]}"
      OPENBLAS_NUM_THREADS=1 "$build/cli/support-slim" "$dir/input.ply" -o "$dir/$v.ply" --method "$method" \
        --max-deviation "$budget" --angle "$angle" --quiet >"$dir/$v.log" 2>&1 || die "support-slim failed on $name ($v)"
    done
    for v in "${variants[@]}"; do
      [ -s "$dir/$v.stl" ] || "$build/eval/slim-eval" measure "$dir/$v.ply" --stl "$dir/$v.stl" >/dev/null
      for slicer in prusa cura; do
        [ -s "$dir/$v.$slicer/${slicer}_turns.txt" ] && continue
        "$repo/eval/studies/slice_support.sh" "$dir/$v.stl" --slicer "$slicer" --angle "$angle" --out "$dir/$v.$slicer" \
          --turns "$turns" --jobs "$jobs" --build "$build" >"$dir/$v.$slicer.log" 2>&1 || die "slicing $name ($v) with $slicer failed"
        rm -f "$dir/$v.$slicer"/*.gcode  # the figures are kept, the G-code (megabytes) is not
      done
    done
  done <"$models"
fi

# ---- the model (always estimated afresh: milliseconds), and the table ------------------------------
rows="$out/results.tsv"
: >"$rows"
while IFS=$'\t' read -r name kind mesh; do
  for v in "${variants[@]}"; do
    d="$out/$name"
    [ -s "$d/$v.ply" ] || continue
    for phases in 4 1; do
      "$build/eval/support_model_tool" estimate "$d/$v.ply" --angle "$angle" --phases "$phases" >"$d/$v.model$phases.txt"
    done
    [ -s "$d/$v.prusa/prusa_turns.txt" ] && [ -s "$d/$v.cura/cura_turns.txt" ] && [ -s "$d/$v.model1.txt" ] || continue
    open="$(kv "$d/input.model1.txt" open_edges)"
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$kind$([ "${open:-0}" -gt 0 ] && echo ' (open)')" "$v" "$(kv "$d/$v.prusa/prusa_turns.txt" support_mm3)" \
      "$(kv "$d/$v.cura/cura_turns.txt" support_mm3)" "$(kv "$d/$v.model4.txt" volume_mm3)" "$(kv "$d/$v.model1.txt" volume_mm3)" >>"$rows"
  done
done <"$models"
awk -F'\t' '
  function pct(a, b) { return b > 0 ? 100 * (a / b - 1) : 0 }
  function abs(x) { return x < 0 ? -x : x }
  function add(key, e) { n[key]++; s[key] += abs(e); if (abs(e) > w[key]) w[key] = abs(e) }
  BEGIN {
    print "| model | kind | mesh | PrusaSlicer mm³ | Cura mm³ | model mm³ (slicer phase) | PrusaSlicer | Cura | model | model, slicer phase | error vs PrusaSlicer | vs Cura | slicer phase vs PrusaSlicer | phase luck |"
    print "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  }
  $3 == "input" {
    p0 = $4; c0 = $5; m0 = $6; q0 = $7
    printf "| %s | %s | input | %.0f | %.0f | %.0f (%.0f) | | | | | | | | |\n", $1, $2, $4, $5, $6, $7
    closed = $2 !~ /open/
    ap[$2] += abs(pct($6, $4)); aq[$2] += abs(pct($7, $4)); ac[$2] += abs(pct($6, $5)); ni[$2]++
    ap["all"] += abs(pct($6, $4)); aq["all"] += abs(pct($7, $4)); ac["all"] += abs(pct($6, $5)); ni["all"]++
    if (closed) { ap["closed"] += abs(pct($6, $4)); aq["closed"] += abs(pct($7, $4)); ac["closed"] += abs(pct($6, $5)); ni["closed"]++ }
    next
  }
  {
    dp = pct($4, p0); dc = pct($5, c0); dm = pct($6, m0); dq = pct($7, q0)
    printf "| %s | %s | %s | %.0f | %.0f | %.0f (%.0f) | %+.1f%% | %+.1f%% | %+.1f%% | %+.1f%% | %+.1f | %+.1f | %+.1f | %+.1f |\n",
      $1, $2, $3, $4, $5, $6, $7, dp, dc, dm, dq, dm - dp, dm - dc, dq - dp, dq - dm
    add("P " $2, dm - dp); add("C " $2, dm - dc); add("Q " $2, dq - dp); add("P all", dm - dp); add("C all", dm - dc); add("Q all", dq - dp)
    if ($2 !~ /open/) { add("P closed", dm - dp); add("C closed", dm - dc); add("Q closed", dq - dp) }
  }
  END {
    print ""
    print "| kind | results | change error vs PrusaSlicer: mean (worst) | vs Cura | slicer phase vs PrusaSlicer | inputs: model vs PrusaSlicer, mean abs % | vs Cura | slicer phase vs PrusaSlicer |"
    print "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    split("organic,cad,creature,shape,extra,organic (open),cad (open),closed,all", kinds, ",")
    for (i = 1; i <= 9; i++) {
      k = kinds[i]
      if (!n["P " k]) continue
      printf "| %s | %d | %.1f (%.1f) | %.1f (%.1f) | %.1f (%.1f) | %.1f | %.1f | %.1f |\n", k, n["P " k],
        s["P " k] / n["P " k], w["P " k], s["C " k] / n["C " k], w["C " k], s["Q " k] / n["Q " k], w["Q " k],
        ap[k] / ni[k], ac[k] / ni[k], aq[k] / ni[k]
    }
  }' "$rows" | tee "$out/table.md"
