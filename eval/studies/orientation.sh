#!/usr/bin/env bash
# Print Orientation judged by PrusaSlicer on the corpus: the support as given, in the pose the
# search chooses, and in that pose slimmed.
#
#   eval/run.sh orientation [--corpus DIR] [--out DIR] [--models a,b,...] [--build DIR]
#                           [--budget PCT]
#
# Per model (data/corpus/<name>.ply, eval/run.sh corpus; default the organic ones): support-slim
# --orient --max-deviation PCT (default 5) --oriented-output, then PrusaSlicer on the part as
# given, oriented, and oriented + slimmed (eval/studies/slice_support.sh: the mean of 4 turns),
# next to the support model's own figures for the turn (the search's choice is the model's). Prints
# a table and writes OUT/orientation.tsv; each model is cached in OUT/<name>/ (delete it to redo).
# A study, not a test: about a minute a model on 2 cores.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
corpus="$repo/data/corpus" out="$repo/out/orientation" build="$repo/build" models="" budget=5
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus="$2" ;; --out) out="$2" ;; --models) models="$2" ;; --build) build="$2" ;; --budget) budget="$2" ;;
    -h|--help) sed -n 2,13p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "orientation: unknown argument $1" >&2; exit 1 ;;
  esac
  shift 2
done
die() { echo "orientation: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }
json_number() { sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([-+0-9.eE]*\).*/\1/p" "$1" | head -1; }
slim="$build/cli/support-slim" eval_tool="$build/eval/slim-eval"
[ -x "$slim" ] && [ -x "$eval_tool" ] || die "build support-slim and slim-eval first"
[ -f "$corpus/manifest.tsv" ] || die "no corpus in $corpus: run eval/run.sh corpus first"
[ -n "$models" ] || models="$(awk -F'\t' 'NR > 1 && $2 == "organic" { printf "%s%s", sep, $1; sep = "," }' "$corpus/manifest.tsv")"
export OPENBLAS_NUM_THREADS=1
mkdir -p "$out"

prusa() {  # PLY DIR: PrusaSlicer's support (mean of 4 quarter turns) into DIR/prusa.txt
  [ -s "$2/prusa.txt" ] && return 0
  mkdir -p "$2"
  "$eval_tool" measure "$1" --stl "$2/part.stl" >/dev/null || die "measure $1 failed"
  "$repo/eval/studies/slice_support.sh" "$2/part.stl" --slicer prusa --angle 45 --build "$build" --out "$2/slices" >"$2/prusa.txt.tmp" ||
    die "slicing $1 failed"
  mv "$2/prusa.txt.tmp" "$2/prusa.txt"
  rm -f "$2/slices/"*.gcode "$2/part.stl"
}

tsv="$out/orientation.tsv"
printf 'model\tgiven_mm3\toriented_mm3\tslimmed_mm3\toriented_pct\tslimmed_pct\tmodel_given_mm3\tmodel_oriented_mm3\tmodel_turn_pct\tdirection\n' >"$tsv"
for name in ${models//,/ }; do
  [ -f "$corpus/$name.ply" ] || die "no $corpus/$name.ply"
  dir="$out/$name"
  mkdir -p "$dir"
  if [ ! -s "$dir/report.json" ]; then
    "$slim" "$corpus/$name.ply" -o "$dir/slimmed.ply" --orient --oriented-output "$dir/oriented.ply" --angle 45 \
      --max-deviation "$budget" --report "$dir/report.json.tmp" >"$dir/slim.log" 2>&1 || die "support-slim failed on $name"
    mv "$dir/report.json.tmp" "$dir/report.json"
  fi
  prusa "$corpus/$name.ply" "$dir/given"
  prusa "$dir/oriented.ply" "$dir/oriented"
  prusa "$dir/slimmed.ply" "$dir/slimmed"
  given="$(kv "$dir/given/prusa.txt" support_mm3)" oriented="$(kv "$dir/oriented/prusa.txt" support_mm3)"
  slimmed="$(kv "$dir/slimmed/prusa.txt" support_mm3)"
  line="$(grep -m1 '^  support model ' "$dir/slim.log" || true)"
  model_given="$(echo "$line" | sed -n 's/.*model *\([0-9.e+]*\) (as given).*/\1/p')"
  model_oriented="$(echo "$line" | sed -n 's/.*-> \([0-9.e+]*\) (oriented).*/\1/p')"
  direction="$(sed -n 's/.*print direction (\([^)]*\)).*/\1/p' "$dir/slim.log" | head -1 | tr -d ' ')"
  awk -v n="$name" -v g="$given" -v o="$oriented" -v s="$slimmed" -v mg="$model_given" -v mo="$model_oriented" -v d="$direction" \
    'BEGIN { printf "%s\t%.0f\t%.0f\t%.0f\t%.1f\t%.1f\t%s\t%s\t%s\t%s\n", n, g, o, s, 100 * (o / g - 1), 100 * (s / g - 1), mg, mo,
             (mg > 0 ? sprintf("%.1f", 100 * (mo / mg - 1)) : "n/a"), d }' >>"$tsv"
done
echo "| model | PrusaSlicer: as given → oriented → oriented + slimmed (mm³) | the model's change of the turn | print direction chosen |"
echo "| --- | --- | ---: | --- |"
awk -F'\t' 'NR > 1 { printf "| %s | %s → %s (%+.1f%%) → %s (%+.1f%%) | %s%% | (%s) |\n", $1, $2, $3, $5, $4, $6, $9, $10 }' "$tsv"
