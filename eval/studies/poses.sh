#!/usr/bin/env bash
# The support model against PrusaSlicer over many poses of one part: does the model rank the
# print directions as the slicer does? (Print Orientation's final choice is the model's.)
#
#   eval/run.sh poses [--corpus DIR] [--out DIR] [--models a,b,...] [--dirs LIST]
#                     [--build DIR] [--model-options "..."]
#
# For each model (data/corpus/<name>.ply, eval/run.sh corpus) and each print direction (X,Y,Z in
# the model's corpus frame; LIST separated by spaces, default the six axes and four 45° tilts),
# the part is turned onto that direction (slim-eval prepare --size 0, the scale kept), then:
#   model   the support model's estimate, mm³ (eval/support_model_tool estimate, its defaults:
#           the mean over 4 grid phases; --model-options adds options, e.g. "--open-slices 0")
#   prusa   PrusaSlicer's support, mm³, the mean of 4 quarter turns (eval/studies/slice_support.sh)
# Prints one row per pose, then per model the mean |model / prusa - 1| and whether the model's
# least-support pose is PrusaSlicer's (and, when not, what PrusaSlicer says the model's pick
# costs against its own best). Writes OUT/poses.tsv. Each pose is cached in OUT/<model>/<dir>/;
# delete it to redo. A study, not a test: about 3 s a pose on 2 cores.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
corpus="$repo/data/corpus" out="$repo/out/poses" build="$repo/build" models="knight,suzanne,wuson,spider,bunny,horse"
dirs="0,0,1 0,0,-1 1,0,0 -1,0,0 0,1,0 0,-1,0 1,0,1 0,1,1 -1,0,1 0,-1,1" model_options=""
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus="$2" ;; --out) out="$2" ;; --models) models="$2" ;; --dirs) dirs="$2" ;;
    --build) build="$2" ;; --model-options) model_options="$2" ;;
    -h|--help) sed -n 2,17p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "poses: unknown argument $1" >&2; exit 1 ;;
  esac
  shift 2
done
die() { echo "poses: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }
eval_tool="$build/eval/slim-eval" model_tool="$build/eval/support_model_tool"
[ -x "$eval_tool" ] && [ -x "$model_tool" ] || die "build slim-eval and support_model_tool first"
mkdir -p "$out"
tsv="$out/poses.tsv"
printf 'model\tdirection\tmodel_mm3\tprusa_mm3\terror_pct\n' >"$tsv"
for name in ${models//,/ }; do
  [ -f "$corpus/$name.ply" ] || die "no $corpus/$name.ply: run eval/run.sh corpus first"
  for d in $dirs; do
    cell="$out/$name/${d//,/_}"
    mkdir -p "$cell"
    if [ ! -s "$cell/prusa.txt" ] || [ ! -s "$cell/model.txt" ]; then
      "$eval_tool" prepare "$corpus/$name.ply" "$cell/part" --size 0 --dir "$d" >/dev/null || die "prepare $name $d failed"
      "$eval_tool" measure "$cell/part.ply" --stl "$cell/part.stl" >/dev/null || die "measure $name $d failed"
      # shellcheck disable=SC2086
      "$model_tool" estimate "$cell/part.ply" $model_options >"$cell/model.txt" || die "model $name $d failed"
      "$repo/eval/studies/slice_support.sh" "$cell/part.stl" --slicer prusa --angle 45 --build "$build" --out "$cell/slices" \
        >"$cell/prusa.txt.tmp" || die "slicing $name $d failed"
      mv "$cell/prusa.txt.tmp" "$cell/prusa.txt"
      rm -f "$cell/slices/"*.gcode
    fi
    m="$(kv "$cell/model.txt" volume_mm3)" p="$(kv "$cell/prusa.txt" support_mm3)"
    printf '%s\t%s\t%s\t%s\t%s\n' "$name" "$d" "$m" "$p" \
      "$(awk -v m="$m" -v p="$p" 'BEGIN { if (p > 0) printf "%.1f", 100 * (m / p - 1); else print "n/a" }')" >>"$tsv"
  done
done
awk -F'\t' 'NR > 1 {
  printf "%-16s %-8s model %8.0f  PrusaSlicer %8.0f  %s%%\n", $1, $2, $3, $4, $5
  n[$1]++; if ($4 > 0) { e = $3 / $4 - 1; err[$1] += (e < 0 ? -e : e) }
  if (!($1 in bm) || $3 < bm[$1]) { bm[$1] = $3; bmp[$1] = $4; bmd[$1] = $2 }
  if (!($1 in bp) || $4 < bp[$1]) { bp[$1] = $4; bpd[$1] = $2 }
  order[$1] = order[$1] ? order[$1] : ++count; name[count] = $1
} END {
  for (i = 1; i <= count; i++) {
    k = name[i]
    printf "%s: mean |model/prusa - 1| %.1f%% over %d poses; the model picks %s (PrusaSlicer %.0f), the slicer prefers %s (%.0f)%s\n",
      k, 100 * err[k] / n[k], n[k], bmd[k], bmp[k], bpd[k], bp[k],
      bmd[k] == bpd[k] ? "" : sprintf(": the pick costs %+.1f%%", 100 * (bmp[k] / bp[k] - 1))
  }
}' "$tsv"
