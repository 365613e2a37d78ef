#!/usr/bin/env bash
# The slicer frontier: for every corpus model and creature, at each deviation budget and for
# each method, what the slicers say the slimming saved and what the shape paid.
#
#   eval/run.sh frontier [--corpus DIR] [--out DIR] [--budgets 1,2,3,5,10]
#                        [--methods coherent,paper] [--models a,b,...] [--turns 0,90,180,270]
#                        [--build DIR] [--plot PNG] [--table-only]
#
# Per model (data/corpus/<name>.ply from eval/run.sh corpus: print pose, 60 mm), per method and
# budget: support-slim --method M --max-deviation B (defaults otherwise, alpha_max 45), then
#   prusa, cura   support change input -> result, % (eval/studies/slice_support.sh: mean of 4 turns)
#   hausdorff     symmetric Hausdorff distance, % of the bbox diagonal (eval/studies/hausdorff.sh;
#                 where MeshLab's filter fails, the CLI's own figure from --report)
#   volume        volume change, %;  crease  crease share, % (and its 99th percentile, degrees)
#   model         the support model's predicted change, %: the CLI's own figures (support-slim
#                 --report), or for a run that does not measure them (--method paper) the
#                 model's estimates of both files (eval/support_model_tool); the column is left
#                 out, never filled with a placeholder, when neither is there. Twice: the mean
#                 over grid phases (what the run minimises) and at the slicer's own phase (the
#                 part as placed: the prediction for these files). And a third time as the judge
#                 measures the slicers: at the slicer's own phase, the mean of the turns 0° and
#                 90° about the print axis (a quarter turn lays the support lines along the part's
#                 other axis; 180° and 270° repeat them), by eval/support_model_tool on both files.
# Writes OUT/frontier.tsv (every figure, one row per run, with the corpus half and the report's
# shape figures), OUT/frontier.md (the table, then the medians and worst per kind and half:
# eval/studies/frontier-summary.sh) and, with
# gnuplot, a plot of support cut against Hausdorff distance per model (--plot, default
# OUT/frontier.png). Every run is cached in OUT/<model>/<method>_<budget>/: a second call only
# does what is missing, so an interrupted study resumes; --table-only runs nothing and tables
# what is there (the runs not made yet are counted, not shown). It is a study, not a test: it takes
# about an hour for the whole corpus on 2 cores; the slicers run two at a time.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
corpus="$repo/data/corpus" out="$repo/out/frontier" budgets="1,2,3,5,10" methods="coherent,paper" models=""
turns="0,90,180,270" build="$repo/build" plot="" table_only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --table-only) table_only=1; shift; continue ;;
    --corpus) corpus="$2" ;; --out) out="$2" ;; --budgets) budgets="$2" ;; --methods) methods="$2" ;;
    --models) models="$2" ;; --turns) turns="$2" ;; --build) build="$2" ;; --plot) plot="$2" ;;
    -h|--help) sed -n 2,31p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "frontier: unknown argument $1" >&2; exit 1 ;;
  esac
  shift 2
done
die() { echo "frontier: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }
pct() { awk -v b="$1" -v a="$2" 'BEGIN { if (b == "" || a == "" || b == 0) print "n/a"; else printf "%.1f", 100 * (a / b - 1) }'; }
[ -f "$corpus/manifest.tsv" ] || die "no corpus in $corpus: run eval/run.sh corpus first"
build="$(cd "$build" && pwd)"; mkdir -p "$out"; out="$(cd "$out" && pwd)"
slim="$build/cli/support-slim" eval_tool="$build/eval/slim-eval" model_tool="$build/eval/support_model_tool"
[ -x "$slim" ] && [ -x "$eval_tool" ] || die "build support-slim and slim-eval first"
export OPENBLAS_NUM_THREADS=1
# The support model's figure, when the CLI has one (issue: support-slim --report FILE.json).
report_flag=""; "$slim" --help 2>&1 | grep -q -- '--report' && report_flag=1

slice_both() {  # PART.stl DIR: PrusaSlicer and Cura, mean of the turns, into DIR/{prusa,cura}.txt
  local slicer
  for slicer in prusa cura; do
    [ -s "$2/$slicer.txt" ] && continue
    "$repo/eval/studies/slice_support.sh" "$1" --slicer "$slicer" --angle 45 --turns "$turns" --build "$build" \
      --out "$2/slices" >"$2/$slicer.txt.tmp" || die "slicing $1 with $slicer failed"
    mv "$2/$slicer.txt.tmp" "$2/$slicer.txt"
    rm -f "$2/slices/${slicer}"_turn*.gcode  # large; the figures are kept
  done
}

# model_estimate REPORT.json KEY: a number from the CLI's JSON report (empty when absent).
json_number() { [ -f "$1" ] && sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([-+0-9.eE]*\).*/\1/p" "$1" | head -1 || true; }

run_one() {  # NAME METHOD BUDGET
  local name="$1" method="$2" budget="$3" dir="$out/$1/$2_$3" in_dir="$out/$1/input"
  [ -s "$dir/row.tsv" ] && return 0
  mkdir -p "$dir"
  local started=$SECONDS report=()
  [ -z "$report_flag" ] || report=(--report "$dir/report.json")
  "$slim" "$in_dir/input.ply" -o "$dir/result.ply" --dir 0,0,1 --angle 45 --plate-tolerance "$(kv "$in_dir/input.txt" plate_tol)" \
    --method "$method" --max-deviation "$budget" "${report[@]}" --quiet >"$dir/slim.log" 2>&1 ||
    die "support-slim failed on $name ($method, $budget%): $(tail -1 "$dir/slim.log")"
  local slim_s=$((SECONDS - started))
  "$eval_tool" measure "$dir/result.ply" --angle 45 --reference "$in_dir/input.ply" --stl "$dir/result.stl" >"$dir/measure.txt"
  slice_both "$dir/result.stl" "$dir"
  # MeshLab's Hausdorff filter, or where it fails (its uniform grid asserts on some inputs) the
  # core's exact point-to-triangle distance from the report (core/geometry/surface_distance.h).
  if ! "$repo/eval/studies/hausdorff.sh" "$in_dir/input.ply" "$dir/result.ply" --diag "$(kv "$in_dir/input.txt" diag)" --out "$dir" \
    --build "$build" >"$dir/hausdorff.txt" 2>"$dir/hausdorff.err"; then
    local core_h
    core_h="$(json_number "$dir/report.json" hausdorff_mm)"
    [ -n "$core_h" ] || die "eval/studies/hausdorff.sh failed on $name ($method, $budget%): $(tail -1 "$dir/hausdorff.err")"
    printf 'hausdorff_mm=%s\nsource=support-slim --report (MeshLab failed: %s)\n' "$core_h" "$(tail -1 "$dir/hausdorff.err")" >"$dir/hausdorff.txt"
  fi
  local diag model="" before after
  diag="$(kv "$in_dir/input.txt" diag)"
  before="$(json_number "$dir/report.json" support_estimate_before_mm3)"; after="$(json_number "$dir/report.json" support_estimate_after_mm3)"
  # A run that does not measure it (the paper's method reports 0): the model estimates both files.
  if { [ -z "$before" ] || awk -v b="$before" 'BEGIN { exit !(b == 0) }'; } && [ -x "$model_tool" ]; then
    [ -s "$in_dir/model.txt" ] || "$model_tool" estimate "$in_dir/input.ply" --angle 45 >"$in_dir/model.txt"
    "$model_tool" estimate "$dir/result.ply" --angle 45 >"$dir/model.txt"
    before="$(kv "$in_dir/model.txt" volume_mm3)"; after="$(kv "$dir/model.txt" volume_mm3)"
  fi
  [ -z "$before" ] || [ -z "$after" ] || model="$(pct "$before" "$after")"
  # The same at the slicer's own grid phase (support-slim --report), or the model's tool on both files.
  local phase="" pb pa
  pb="$(json_number "$dir/report.json" support_slicer_phase_before_mm3)"; pa="$(json_number "$dir/report.json" support_slicer_phase_after_mm3)"
  if { [ -z "$pb" ] || awk -v b="$pb" 'BEGIN { exit !(b == 0) }'; } && [ -x "$model_tool" ]; then
    [ -s "$in_dir/model_phase.txt" ] || "$model_tool" estimate "$in_dir/input.ply" --angle 45 --phases 1 --turns 1 >"$in_dir/model_phase.txt"
    "$model_tool" estimate "$dir/result.ply" --angle 45 --phases 1 --turns 1 >"$dir/model_phase.txt"
    pb="$(kv "$in_dir/model_phase.txt" volume_mm3)"; pa="$(kv "$dir/model_phase.txt" volume_mm3)"
  fi
  [ -z "$pb" ] || [ -z "$pa" ] || phase="$(pct "$pb" "$pa")"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$method" "$budget" \
    "$(pct "$(kv "$in_dir/prusa.txt" support_mm3)" "$(kv "$dir/prusa.txt" support_mm3)")" \
    "$(pct "$(kv "$in_dir/cura.txt" support_mm3)" "$(kv "$dir/cura.txt" support_mm3)")" \
    "$(awk -v h="$(kv "$dir/hausdorff.txt" hausdorff_mm)" -v d="$diag" 'BEGIN { printf "%.2f", 100 * h / d }')" \
    "$(awk -v v="$(kv "$dir/measure.txt" volume_change_pct)" 'BEGIN { printf "%.1f", v }')" \
    "$(awk -v v="$(kv "$dir/measure.txt" crease_share_pct)" 'BEGIN { printf "%.1f", v }')" \
    "$(awk -v v="$(kv "$dir/measure.txt" crease_p99_deg)" 'BEGIN { printf "%.1f", v }')" \
    "${model:-}" "$(kv "$in_dir/prusa.txt" support_mm3)" "$(kv "$dir/prusa.txt" support_mm3)" "$slim_s" \
    "$((SECONDS - started))" "${phase:-}" >"$dir/row.tsv"
}

prepare_input() {  # NAME
  local in_dir="$out/$1/input"
  # A model the corpus has remade since: every cached run of it is stale.
  if [ -f "$in_dir/input.ply" ] && [ "$corpus/$1.ply" -nt "$in_dir/input.ply" ]; then rm -rf "${out:?}/$1"; fi
  mkdir -p "$in_dir"
  if [ ! -s "$in_dir/input.txt" ]; then
    cp "$corpus/$1.ply" "$in_dir/input.ply"
    "$eval_tool" measure "$in_dir/input.ply" --angle 45 --stl "$in_dir/input.stl" >"$in_dir/input.txt.tmp"
    echo "plate_tol=$(awk -v d="$(kv "$in_dir/input.txt.tmp" diag)" 'BEGIN { print 1e-3 * d }')" >>"$in_dir/input.txt.tmp"
    mv "$in_dir/input.txt.tmp" "$in_dir/input.txt"
  fi
  slice_both "$in_dir/input.stl" "$in_dir"
}

bench_started=$SECONDS
IFS=, read -r -a budget_list <<<"$budgets"; IFS=, read -r -a method_list <<<"$methods"
mapfile -t names < <(awk -F'\t' 'NR > 1 { print $1 }' "$corpus/manifest.tsv")
if [ -n "$models" ]; then IFS=, read -r -a names <<<"$models"; fi
for name in "${names[@]}"; do
  [ -f "$corpus/$name.ply" ] || die "no $name.ply in $corpus"
  [ -z "$table_only" ] || continue
  t0=$SECONDS
  echo "[frontier] $name" >&2
  prepare_input "$name"
  for method in "${method_list[@]}"; do
    for budget in "${budget_list[@]}"; do run_one "$name" "$method" "$budget"; done
  done
  echo "[frontier] $name: $((SECONDS - t0)) s" >&2
done

# judged_change NAME METHOD BUDGET: the model's change input -> result at the slicer's own phase,
# mean of the quarter turns 0° and 90° (the judge's protocol); empty without the model's tool or
# the run's files. Each estimate is cached beside its mesh.
judged_change() {
  local in_dir="$out/$1/input" dir="$out/$1/$2_$3" mesh
  [ -x "$model_tool" ] && [ -f "$dir/result.ply" ] || return 0
  for mesh in "$in_dir/input.ply" "$dir/result.ply"; do
    [ -s "${mesh%/*}/model_judged.txt" ] ||
      "$model_tool" estimate "$mesh" --angle 45 --phases 1 --turns 2 >"${mesh%/*}/model_judged.txt" || return 0
  done
  pct "$(kv "$in_dir/model_judged.txt" volume_mm3)" "$(kv "$dir/model_judged.txt" volume_mm3)"
}

# ---- the table ----------------------------------------------------------------------------------
tsv="$out/frontier.tsv"
printf 'model\tkind\tmethod\tbudget_pct\tprusa_change_pct\tcura_change_pct\thausdorff_pct\tvolume_change_pct\tcrease_share_pct\tcrease_p99_deg\tmodel_change_pct\tprusa_before_mm3\tprusa_after_mm3\tslim_s\trun_s\tmodel_slicer_phase_change_pct\tmodel_judged_change_pct\thalf\taffine_departure_pct\theight_change_pct\tmean_displacement_pct\tfolded_faces\n' >"$tsv"
missing=0
for name in "${names[@]}"; do
  kind="$(awk -F'\t' -v n="$name" '$1 == n { print $2 }' "$corpus/manifest.tsv")"
  # The corpus half (tune or check; corpus.sh's manifest), empty for a corpus without halves.
  half="$(awk -F'\t' -v n="$name" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "half") h = i } $1 == n && h { print $h }' "$corpus/manifest.tsv")"
  for method in "${method_list[@]}"; do
    for budget in "${budget_list[@]}"; do
      row="$out/$name/${method}_$budget/row.tsv" report="$out/$name/${method}_$budget/report.json"
      if [ -s "$row" ]; then
        # The shape figures from the run's report (empty where the run has none).
        shape=""
        for key in affine_departure_pct height_change_pct mean_displacement_pct folded_faces; do
          shape="$shape	$(json_number "$report" "$key")"
        done
        awk -F'\t' -v OFS='\t' -v k="$kind" -v j="$(judged_change "$name" "$method" "$budget")" -v h="$half" -v s="$shape" \
          '{ $15 = $15 OFS j; $1 = $1 OFS k; print $0 OFS h s }' "$row" >>"$tsv"
      else missing=$((missing + 1)); fi
    done
  done
done
[ "$missing" -eq 0 ] || echo "[frontier] $missing runs not made yet (left out of the table)" >&2
with_model="$(awk -F'\t' 'NR > 1 && $11 != "" { print "yes"; exit }' "$tsv")"
{
  echo "| model | kind | method | budget | PrusaSlicer | Cura | Hausdorff (% diag) | volume | crease share (p99) |$( [ -z "$with_model" ] || echo " support model | at the slicer's phase | judged as the slicers (phase, quarter turns) |")"
  echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |$( [ -z "$with_model" ] || echo " ---: | ---: | ---: |")"
  awk -F'\t' -v m="$with_model" 'NR > 1 {
    line = sprintf("| %s | %s | %s | %s%% | %s%% | %s%% | %s | %s%% | %s%% (%s°) |", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10)
    if (m != "") line = line sprintf(" %s%% | %s | %s |", $11, $16 == "" ? "n/a" : $16 "%", $17 == "" ? "n/a" : $17 "%")
    print line }' "$tsv"
  echo
  echo "Judged by the median, per kind of model and corpus half (eval/studies/frontier-summary.sh):"
  echo
  "$repo/eval/studies/frontier-summary.sh" "$tsv"
} >"$out/frontier.md"
cat "$out/frontier.md"

# ---- the plot: support cut against Hausdorff distance, per model, both methods ------------------
[ -n "$plot" ] || plot="$out/frontier.png"
if command -v gnuplot >/dev/null 2>&1; then
  "$repo/eval/studies/frontier-plot.sh" "$tsv" "$plot" && echo "[frontier] plot: $plot" >&2
else
  echo "[frontier] gnuplot is not installed (apt-get install gnuplot-nox): no plot" >&2
fi
echo "[frontier] $((SECONDS - bench_started)) s" >&2
