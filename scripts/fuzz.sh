#!/usr/bin/env bash
# Fuzzes the core and the CLI's mesh readers: builds the two libFuzzer targets (clang,
# AddressSanitizer, UndefinedBehaviorSanitizer) into build-fuzz and runs them one after the other
# for FUZZ_SECONDS in all (default 60: two thirds for the core, a third for the readers).
#   slim_fuzz    the core, from tests/fuzz/corpus (the bad-input catalogue) and tests/fuzz/regressions;
#                new inputs go to build-fuzz/corpus, findings to build-fuzz/artifacts.
#   reader_fuzz  the PLY, STL, OBJ and OFF readers, from tests/fuzz/reader_corpus (the bad-file
#                catalogue and well-formed files) and tests/fuzz/reader_regressions; new inputs go
#                to build-fuzz/reader-corpus, findings to build-fuzz/reader-artifacts.
# The exit status is 0 when neither found anything. FUZZ_TARGETS="reader_fuzz" runs one target
# alone (with all of FUZZ_SECONDS). For long runs: FUZZ_SECONDS=14400 FUZZ_JOBS=2 scripts/fuzz.sh
# (docs/robustness.md). FUZZ_SEED fixes libFuzzer's random seed: CI passes one, so that its bounded
# run replays the same mutations every time and a red CI always means a reproducible finding,
# not a lucky draw; exploratory runs leave it unset (a fresh seed each run). Idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
source "$here/scripts/lib/ccache.sh"
build="$here/build-fuzz"
seconds="${FUZZ_SECONDS:-60}"
jobs="${FUZZ_JOBS:-1}"
seed="${FUZZ_SEED:-}"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ] && generator=(-G Ninja)
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSLIM_FUZZ=ON -DSLIM_BUILD_PLUGIN=OFF -DSLIM_BUILD_BENCH=OFF "${ccache_launcher[@]}" "${generator[@]}" >/dev/null
targets=(${FUZZ_TARGETS:-slim_fuzz reader_fuzz})
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"
export OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# run TARGET SECONDS CORPUS ARTIFACTS SEEDS...: one bounded libFuzzer run. -timeout: one input may
# take at most 120 s: most take milliseconds, but a slimming of a few hundred faces with a large
# rigid feature takes tens of seconds under AddressSanitizer and coverage (several times a release
# build's time), and only a hang should fail the run; -rss_limit_mb: 2 GB (also the largest single
# malloc).
run() {
  local target="$1" time="$2" corpus="$3" artifacts="$4"
  shift 4
  mkdir -p "$corpus" "$artifacts"
  local args=(-max_total_time="$time" -timeout=120 -rss_limit_mb=2048 -print_final_stats=1
              -artifact_prefix="$artifacts/" "$corpus" "$@")
  if [ -n "$seed" ]; then args=(-seed="$seed" "${args[@]}"); fi
  if [ "$jobs" -gt 1 ]; then args=(-jobs="$jobs" -workers="$jobs" "${args[@]}"); fi
  echo "fuzz: $target for $time s"
  (cd "$build" && "$build/tests/fuzz/$target" "${args[@]}")
}
status=0
for target in "${targets[@]}"; do
  # Two targets share the time: the core two thirds, the readers the rest.
  time="$seconds"
  if [ "${#targets[@]}" -gt 1 ]; then
    if [ "$target" = slim_fuzz ]; then time=$((seconds * 2 / 3)); else time=$((seconds - seconds * 2 / 3)); fi
  fi
  case "$target" in
    slim_fuzz) run slim_fuzz "$time" "$build/corpus" "$build/artifacts" "$here/tests/fuzz/corpus" \
                 "$here/tests/fuzz/regressions" || status=1 ;;
    reader_fuzz) run reader_fuzz "$time" "$build/reader-corpus" "$build/reader-artifacts" \
                   "$here/tests/fuzz/reader_corpus" "$here/tests/fuzz/reader_regressions" || status=1 ;;
    *) echo "fuzz.sh: unknown target $target" >&2; exit 2 ;;
  esac
done
exit "$status"
