#!/usr/bin/env bash
# The one entry point of the evaluation (eval/README.md):
#
#   eval/run.sh STUDY [args...]     sets the machine up (scripts/setup.sh) and builds what STUDY
#                                   runs into build/ (scripts/build.sh), both idempotent and quiet
#                                   (their log is shown when one fails), then runs
#                                   eval/studies/STUDY.sh with args, unchanged
#   eval/run.sh STUDY --help        that study's options, without setting up or building
#   eval/run.sh [--help]            the studies, one line each
#
# Exits with the study's status; non-zero with a one-line reason for an unknown study or when the
# setup or the build fails.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# STUDY | the build targets it runs | what it measures. A study with no targets needs no build.
studies=(
  "part|support-slim slim-eval filter_support_slimming|one mesh through support-slim and both slicers: support, shape cost, pictures (out/eval/)"
  "corpus|slim-eval write_shape|the evaluation corpus: real models and synthetic creatures in their print pose (data/corpus/)"
  "frontier|support-slim slim-eval support_model_tool filter_support_slimming|support cut against shape cost on the corpus, per method and budget (out/frontier/)"
  "frontier-plot||the frontier's table as a picture, with gnuplot (out/frontier/frontier.png)"
  "support-model|support-slim slim-eval support_model_tool write_shape|the support model's estimates against both slicers, file by file (out/support-model/)"
  "poses|slim-eval support_model_tool|the support model against PrusaSlicer over ten poses of each part (out/poses/)"
  "orientation|support-slim slim-eval|Print Orientation judged by PrusaSlicer on the corpus (out/orientation/)"
  "random-poses|support-slim slim-eval|Print Orientation from random starting poses against upright, by PrusaSlicer (out/random-poses/)"
  "hausdorff|filter_support_slimming|symmetric Hausdorff and mean distance between two meshes, MeshLab's filter"
)

list_studies() {
  echo "usage: eval/run.sh STUDY [args...]   (eval/run.sh STUDY --help: the study's own options)"
  echo
  local entry name what
  for entry in "${studies[@]}"; do
    name="${entry%%|*}" what="${entry##*|}"
    printf '  %-14s %s\n' "$name" "$what"
  done
}

case "${1:-}" in
  ""|-h|--help) list_studies; exit 0 ;;
esac
study="$1"; shift
targets="" found=""
for entry in "${studies[@]}"; do
  if [ "${entry%%|*}" = "$study" ]; then
    found=1; targets="${entry#*|}"; targets="${targets%%|*}"
  fi
done
[ -n "$found" ] || { echo "eval/run.sh: unknown study '$study' (eval/run.sh --help lists them)" >&2; exit 2; }
script="$here/eval/studies/$study.sh"

# A study's help needs neither the setup nor the build.
for arg in "$@"; do
  case "$arg" in -h|--help) exec "$script" "$@" ;; esac
done

if [ -n "$targets" ]; then
  log="$(mktemp)"; trap 'rm -f "$log"' EXIT
  "$here/scripts/setup.sh" >"$log" 2>&1 || { cat "$log" >&2; echo "eval/run.sh: the setup failed" >&2; exit 1; }
  # shellcheck disable=SC2086  # the targets are words
  "$here/scripts/build.sh" --target $targets >"$log" 2>&1 ||
    { cat "$log" >&2; echo "eval/run.sh: the build failed" >&2; exit 1; }
  rm -f "$log"; trap - EXIT
fi
exec "$script" "$@"
