#!/usr/bin/env bash
# The slicer frontier as a picture (gnuplot): one panel per model, support cut (the slicer's
# support, input -> result, mean of 4 turns; up is better) against the Hausdorff distance (% of
# the bbox diagonal), one line per method across the budgets; PrusaSlicer solid, Cura dashed.
#
#   eval/run.sh frontier-plot [FRONTIER.tsv [OUT.png]]      (FRONTIER.tsv: eval/run.sh frontier)
#
# Defaults: out/frontier/frontier.tsv, and OUT.png beside it (frontier.png). Needs gnuplot.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
case "${1:-}" in -h|--help) sed -n 2,8p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
tsv="${1:-$repo/out/frontier/frontier.tsv}"
png="${2:-$(dirname "$tsv")/frontier.png}"
[ -f "$tsv" ] || { echo "frontier-plot: no $tsv (eval/run.sh frontier writes it)" >&2; exit 1; }
command -v gnuplot >/dev/null 2>&1 || { echo "frontier-plot: gnuplot is not installed" >&2; exit 1; }
data="$(mktemp -d)"; trap 'rm -rf "$data"' EXIT
mapfile -t models < <(awk -F'\t' 'NR > 1 && !seen[$1]++ { print $1 }' "$tsv")
n=${#models[@]}
cols=5; rows=$(((n + cols - 1) / cols))
for m in "${models[@]}"; do
  for method in coherent paper; do
    # hausdorff, prusa cut, cura cut, budget; sorted by budget; the origin (no change) first.
    { echo "0 0 0 0"
      awk -F'\t' -v m="$m" -v me="$method" 'NR > 1 && $1 == m && $3 == me && $5 != "n/a" {
        print $7, -$5, ($6 == "n/a" ? "NaN" : -$6), $4 }' "$tsv" | sort -g -k4; } >"$data/${m}_$method.dat"
  done
done
{
  echo "set terminal pngcairo size $((cols * 300)),$((rows * 250 + 40)) font 'DejaVu Sans,9'"
  echo "set output '$png'"
  echo "set multiplot layout $rows,$cols title 'Support cut against shape change: PrusaSlicer (solid), Cura (dashed); coherent (blue) and the paper (red); budgets 1, 2, 3, 5, 10%' font ',11'"
  echo "set grid; set key top left font ',8'"
  echo "set xlabel 'Hausdorff, % of diagonal' offset 0,0.5; set ylabel 'support cut, %' offset 1.5,0"
  echo "set xrange [0:*]"
  first=1
  for m in "${models[@]}"; do
    echo "set title '${m//_/ }'"
    if [ -n "$first" ]; then key=""; first=""; else key="set key off;"; fi
    echo "$key plot '$data/${m}_coherent.dat' using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb '#1f5fbf' title 'coherent', \\"
    echo "  '$data/${m}_paper.dat' using 1:2 with linespoints lw 2 pt 5 ps 0.6 lc rgb '#c0392b' title 'paper', \\"
    echo "  '$data/${m}_coherent.dat' using 1:3 with linespoints dt 2 lw 1 pt 6 ps 0.5 lc rgb '#1f5fbf' notitle, \\"
    echo "  '$data/${m}_paper.dat' using 1:3 with linespoints dt 2 lw 1 pt 4 ps 0.5 lc rgb '#c0392b' notitle"
  done
  echo "unset multiplot"
} >"$data/plot.gp"
gnuplot "$data/plot.gp"
