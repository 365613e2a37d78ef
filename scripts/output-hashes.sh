#!/usr/bin/env bash
# Hashes what support-slim writes for every corpus model, so that a change meant to keep the
# behaviour (a restructuring, a rename) can be shown to keep it bit for bit.
#
#   scripts/output-hashes.sh [--build DIR] [--corpus DIR] [--out FILE] [--compare FILE]
#
# For each model of the corpus (eval/run.sh corpus; data/corpus/manifest.tsv) and each of four
# runs (the defaults; --orient with --oriented-output; --method paper; --one-resolution at 30
# degrees with a 3% budget), one line: model, run, and the SHA-256 of the mesh written, of the
# oriented mesh (--orient), of the --report JSON without its "seconds" figure and of the summary
# with its timings masked. --out writes the lines to FILE (default: stdout); --compare FILE
# compares them with an earlier list and exits 1 naming every line that differs.
# The corpus must be the same files for both lists: it is made by this build's tools, so make it
# once (eval/run.sh corpus) and keep it.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$repo/build" corpus="$repo/data/corpus" out="" compare=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --corpus) corpus="$(cd "$2" && pwd)"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --compare) compare="$2"; shift 2 ;;
    -h|--help) sed -n 2,15p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "output-hashes: unknown argument $1" >&2; exit 2 ;;
  esac
done
die() { echo "output-hashes: $*" >&2; exit 2; }
cli="$build/cli/support-slim"
[ -x "$cli" ] || die "no $cli: build first (scripts/build.sh)"
[ -f "$corpus/manifest.tsv" ] || die "no corpus in $corpus: run eval/run.sh corpus"
[ -z "$compare" ] || [ -f "$compare" ] || die "no list to compare with: $compare"

work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
hash() { if [ -f "$1" ]; then sha256sum <"$1" | cut -c1-16; else echo "-"; fi; }
run() {  # run NAME VARIANT ARGS...: one line of hashes
  local name="$1" variant="$2"; shift 2
  rm -f "$work"/*
  "$cli" "$corpus/$name.ply" -o "$work/out.ply" --report "$work/report.json" --quiet "$@" >"$work/summary.txt" 2>"$work/err.txt" ||
    { echo "$name $variant failed: $(cat "$work/err.txt")" >&2; echo "$name $variant failed"; return 0; }
  # The run's folder is a new one each time: it is masked with the timings.
  grep -v '"seconds"' "$work/report.json" | sed "s|$work|WORK|g" >"$work/report.txt"
  sed -E "s|$work|WORK|g; s/[0-9]+\.[0-9]+ s\b/T s/g" "$work/summary.txt" >"$work/summary.masked"
  echo "$name $variant mesh=$(hash "$work/out.ply") oriented=$(hash "$work/oriented.ply") report=$(hash "$work/report.txt") summary=$(hash "$work/summary.masked")"
}
lines="$work.lines"; : >"$lines"; trap 'rm -rf "$work" "$lines"' EXIT
while IFS=$'\t' read -r name _; do
  [ "$name" = name ] && continue
  {
    run "$name" default
    run "$name" orient --orient --oriented-output "$work/oriented.ply"
    run "$name" paper --method paper
    run "$name" one30 --one-resolution --angle 30 --max-deviation 3
  } >>"$lines"
  echo "[output-hashes] $name" >&2
done <"$corpus/manifest.tsv"

if [ -n "$out" ]; then cp "$lines" "$out"; else cat "$lines"; fi
if [ -n "$compare" ]; then
  if diff <(sort "$compare") <(sort "$lines") >"$work.diff"; then
    echo "output-hashes: all $(wc -l <"$lines") runs are the same bit for bit as in $compare"
  else
    echo "output-hashes: runs that differ from $compare (< before, > now):" >&2
    cat "$work.diff" >&2; rm -f "$work.diff"
    exit 1
  fi
  rm -f "$work.diff"
fi
