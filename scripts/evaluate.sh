#!/usr/bin/env bash
# Judges Support Slimming on MESH with a real slicer (tools/evaluate.sh): sets the machine up if
# needed, builds what the judge runs into build/, then prints the before/after table and where the
# report and picture are. Every option of tools/evaluate.sh works (see --help).
#   scripts/evaluate.sh data/bunny.ply
#   scripts/evaluate.sh part.stl --angle 30 --size 80 --out out/eval/part30
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case "${1:-}" in -h|--help) exec "$here/tools/evaluate.sh" --help ;; esac
log="$(mktemp)"; trap 'rm -f "$log"' EXIT
"$here/scripts/setup.sh" >"$log" 2>&1 || { cat "$log" >&2; echo "evaluate: setup failed" >&2; exit 1; }
"$here/scripts/build.sh" --target support-slim slim-eval filter_support_slimming >"$log" 2>&1 ||
  { cat "$log" >&2; echo "evaluate: the build failed" >&2; exit 1; }
rm -f "$log"
"$here/tools/evaluate.sh" --build "$here/build" "$@"
