#!/usr/bin/env bash
# The frontier judged by the median: per method, budget, kind of model and corpus half (tune,
# check and both), the median, worst and best support change by each slicer and the largest shape
# figures, from a frontier table.
#
#   eval/studies/frontier-summary.sh FRONTIER.tsv     # a markdown table on stdout
#
# FRONTIER.tsv is eval/studies/frontier.sh's table (one row per run, a header naming its
# columns; the columns are found by name). Changes are % (negative: less support); the worst is the
# largest change (the least cut), the best the smallest; "all" is a corpus without halves. "Cura agrees" counts the runs where Cura's
# change has the sign of PrusaSlicer's and at least half its size. A figure a run lacks ("n/a" or
# empty) is left out of that column's median and extremes; a column no run has shows "n/a".
set -euo pipefail
[ $# -eq 1 ] && [ -f "$1" ] || { echo "usage: frontier-summary.sh FRONTIER.tsv" >&2; exit 1; }
awk -F'\t' '
function num(s) { return s != "" && s != "n/a" && s ~ /^[-+0-9.eE]+$/ }
function sorted(list, out,    n, i, j, v) {  # list: values joined by spaces; out[1..n] ascending
  n = split(list, out, " ")
  for (i = 2; i <= n; ++i) { v = out[i] + 0; for (j = i - 1; j >= 1 && out[j] + 0 > v; --j) out[j + 1] = out[j]; out[j + 1] = v }
  return n
}
function median(list,    a, n) { n = sorted(list, a); if (n == 0) return "n/a"; return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
function worst(list,    a, n) { n = sorted(list, a); return n ? a[n] : "n/a" }
function best(list,    a, n) { n = sorted(list, a); return n ? a[1] : "n/a" }
function fmt(x, d) { return x == "n/a" ? x : sprintf("%." d "f", x) }
function add(key, col, v) { if (num(v)) values[key, col] = values[key, col] " " v }
NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
{
  half = ("half" in c) && $c["half"] != "" ? $c["half"] : "all"
  groups[1] = $c["method"] SUBSEP $c["budget_pct"] SUBSEP $c["kind"] SUBSEP half
  groups[2] = $c["method"] SUBSEP $c["budget_pct"] SUBSEP $c["kind"] SUBSEP "both"
  for (g = 1; g <= (half == "all" ? 1 : 2); ++g) {
    key = groups[g]
    base = $c["method"] SUBSEP $c["budget_pct"] SUBSEP $c["kind"]
    if (!(base in seen)) { seen[base] = 1; bases[++bases_seen] = base }
    count[key]++
    p = $c["prusa_change_pct"]; q = $c["cura_change_pct"]
    add(key, "prusa", p); add(key, "cura", q)
    if (num(p) && num(q) && p * q > 0 && (q < 0 ? -q : q) >= 0.5 * (p < 0 ? -p : p)) agree[key]++
    if (num(p) && num(q)) judged[key]++
    n = split("hausdorff_pct volume_change_pct crease_share_pct affine_departure_pct height_change_pct mean_displacement_pct folded_faces", shape, " ")
    for (s = 1; s <= n; ++s) if (shape[s] in c) add(key, shape[s], shape[s] == "volume_change_pct" && $c[shape[s]] < 0 ? -$c[shape[s]] : $c[shape[s]])
  }
}
END {
  print "| method | budget | kind | half | runs | PrusaSlicer median | worst | best | Cura median | worst | Cura agrees | Hausdorff max | volume change max (either way) | crease max | affine max | height max | mean displacement max | folds max |"
  print "| --- | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  split("all tune check both", halves, " ")
  for (b = 1; b <= bases_seen; ++b) for (h = 1; h <= 4; ++h) {
    key = bases[b] SUBSEP halves[h]
    if (!(key in count)) continue
    split(key, k, SUBSEP)
    printf "| %s | %s%% | %s | %s | %d | %s | %s | %s | %s | %s | %d of %d | %s | %s | %s | %s | %s | %s | %s |\n", k[1], k[2], k[3], k[4], count[key],
      fmt(median(values[key, "prusa"]), 1), fmt(worst(values[key, "prusa"]), 1), fmt(best(values[key, "prusa"]), 1),
      fmt(median(values[key, "cura"]), 1), fmt(worst(values[key, "cura"]), 1), agree[key], judged[key],
      fmt(worst(values[key, "hausdorff_pct"]), 2), fmt(worst(values[key, "volume_change_pct"]), 2), fmt(worst(values[key, "crease_share_pct"]), 2),
      fmt(worst(values[key, "affine_departure_pct"]), 2), fmt(worst(values[key, "height_change_pct"]), 2),
      fmt(worst(values[key, "mean_displacement_pct"]), 2), fmt(worst(values[key, "folded_faces"]), 0)
  }
}' "$1"
