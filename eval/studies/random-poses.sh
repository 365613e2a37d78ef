#!/usr/bin/env bash
# Print Orientation from random starting poses, judged by PrusaSlicer: does the search find a
# pose at least as good as the one the part was modelled in, wherever it starts?
#
#   eval/run.sh random-poses [--corpus DIR] [--out DIR] [--models a,b,...] [--seeds K]
#                            [--build DIR] [--baseline-build DIR] [--budget PCT]
#
# Per model (data/corpus/<name>.ply, in its print pose: "upright") and seed 1..K (default 3), the
# part is turned onto a random print direction drawn from the seed (slim-eval prepare --dir,
# scale kept), then support-slim --orient --max-deviation PCT (default 5) --oriented-output.
# PrusaSlicer (the mean of quarter turns 0 and 90, eval/studies/slice_support.sh) judges the
# random pose, the upright one, the chosen one and the chosen one slimmed; with --baseline-build,
# also the pose another build's support-slim --orient chooses (a before/after of the search).
# Prints one row per model and seed and then, over every row, the median and worst of the chosen
# pose against the least of upright and the baseline's choice, and the median cut of oriented +
# slimmed against upright. Writes OUT/random-poses.tsv; each pose is cached in OUT/<name>/<seed>/
# (delete it to redo). A study, not a test: about half a minute a pose on 2 cores.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
corpus="$repo/data/corpus" out="$repo/out/random-poses" build="$repo/build" baseline="" models="" seeds=3 budget=5
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus="$2" ;; --out) out="$2" ;; --models) models="$2" ;; --seeds) seeds="$2" ;; --build) build="$2" ;;
    --baseline-build) baseline="$2" ;; --budget) budget="$2" ;;
    -h|--help) sed -n 2,17p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "random-poses: unknown argument $1" >&2; exit 1 ;;
  esac
  shift 2
done
die() { echo "random-poses: $*" >&2; exit 1; }
kv() { awk -v k="$2" 'index($0, k "=") == 1 { print substr($0, length(k) + 2); exit }' "$1"; }
slim="$build/cli/support-slim" eval_tool="$build/eval/slim-eval"
[ -x "$slim" ] && [ -x "$eval_tool" ] || die "build support-slim and slim-eval first"
[ -z "$baseline" ] || [ -x "$baseline/cli/support-slim" ] || die "no $baseline/cli/support-slim"
[ -f "$corpus/manifest.tsv" ] || die "no corpus in $corpus: run eval/run.sh corpus first"
[ -n "$models" ] || models="$(awk -F'\t' 'NR > 1 && $2 == "organic" { printf "%s%s", sep, $1; sep = "," }' "$corpus/manifest.tsv")"
export OPENBLAS_NUM_THREADS=1
mkdir -p "$out"

prusa() {  # MESH DIR: PrusaSlicer's support (mean of quarter turns 0 and 90), printed
  if [ ! -s "$2/prusa.txt" ]; then
    mkdir -p "$2"
    "$eval_tool" measure "$1" --stl "$2/part.stl" >/dev/null || die "measure $1 failed"
    "$repo/eval/studies/slice_support.sh" "$2/part.stl" --slicer prusa --angle 45 --turns 0,90 --build "$build" \
      --out "$2/slices" >"$2/prusa.txt.tmp" || die "slicing $1 failed"
    mv "$2/prusa.txt.tmp" "$2/prusa.txt"
    rm -f "$2/slices/"*.gcode "$2/part.stl"
  fi
  kv "$2/prusa.txt" support_mm3
}

random_direction() {  # SEED NAME: a unit vector from the seed and the model's name (Box-Muller)
  awk -v seed="$1" -v name="$2" 'BEGIN {
    h = seed; for (i = 1; i <= length(name); ++i) h = (h * 31 + index("abcdefghijklmnopqrstuvwxyz_0123456789", substr(name, i, 1))) % 2147483647
    srand(h); for (k = 1; k <= 3; ++k) v[k] = sqrt(-2 * log(1 - rand())) * cos(2 * 3.141592653589793 * rand())
    n = sqrt(v[1]^2 + v[2]^2 + v[3]^2); printf "%.6f,%.6f,%.6f", v[1] / n, v[2] / n, v[3] / n }'
}

tsv="$out/random-poses.tsv"
printf 'model\tseed\trandom_mm3\tupright_mm3\tbaseline_mm3\tchosen_mm3\tslimmed_mm3\tchosen_vs_best_pct\tslimmed_vs_upright_pct\n' >"$tsv"
for name in ${models//,/ }; do
  [ -f "$corpus/$name.ply" ] || die "no $corpus/$name.ply"
  upright="$(prusa "$corpus/$name.ply" "$out/$name/upright")"
  for seed in $(seq 1 "$seeds"); do
    dir="$out/$name/$seed"
    mkdir -p "$dir"
    [ -s "$dir/random.ply" ] || "$eval_tool" prepare "$corpus/$name.ply" "$dir/random" --size 0 --dir "$(random_direction "$seed" "$name")" >/dev/null ||
      die "turning $name failed"
    [ -s "$dir/slimmed.ply" ] || "$slim" "$dir/random.ply" -o "$dir/slimmed.ply" --orient --oriented-output "$dir/oriented.ply" \
      --angle 45 --max-deviation "$budget" --quiet >"$dir/slim.log" 2>&1 || die "support-slim failed on $name ($seed)"
    base="n/a"
    if [ -n "$baseline" ]; then
      [ -s "$dir/baseline.ply" ] || "$baseline/cli/support-slim" "$dir/random.ply" -o "$dir/baseline.ply" --orient --iterations 0 \
        --angle 45 --quiet >/dev/null 2>&1 || die "the baseline failed on $name ($seed)"
      base="$(prusa "$dir/baseline.ply" "$dir/sliced_baseline")"
    fi
    row="$(printf '%s\t%s\t%s\t%s\t%s\t%s\t%s' "$name" "$seed" "$(prusa "$dir/random.ply" "$dir/sliced_random")" "$upright" "$base" \
      "$(prusa "$dir/oriented.ply" "$dir/sliced_oriented")" "$(prusa "$dir/slimmed.ply" "$dir/sliced_slimmed")")"
    echo "$row" | awk -F'\t' -v OFS='\t' '{ best = $4; if ($5 != "n/a" && $5 < best) best = $5
      print $0, sprintf("%.1f", 100 * ($6 / best - 1)), sprintf("%.1f", 100 * ($7 / $4 - 1)) }' >>"$tsv"
    tail -1 "$tsv"
  done
done
awk -F'\t' 'NR > 1 { c[++n] = $8; s[n] = $9; if (n == 1 || $8 > worst) worst = $8; within += ($8 <= 5) }
  function median(a, n,   i, j, t) { for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
                                      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
  END { if (!n) exit; printf "chosen against the least of upright and the baseline: median %+.1f%%, worst %+.1f%%, within 5%%: %d of %d\n", median(c, n), worst, within, n
        printf "oriented + slimmed against upright: median %+.1f%%\n", median(s, n) }' "$tsv"
