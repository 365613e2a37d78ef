#!/usr/bin/env bash
# Fuzzes the core: builds the libFuzzer target (clang, AddressSanitizer, UndefinedBehaviorSanitizer)
# into build-fuzz and runs it from the seed corpus (tests/fuzz/corpus, the bad-input catalogue)
# and the regressions (tests/fuzz/regressions) for FUZZ_SECONDS (default 60). New inputs go to
# build-fuzz/corpus, crashes, timeouts and leaks to build-fuzz/artifacts; the exit status is
# libFuzzer's (0: nothing found). For long runs: FUZZ_SECONDS=14400 FUZZ_JOBS=2 scripts/fuzz.sh
# (docs/robustness.md: Fuzzing). FUZZ_SEED fixes libFuzzer's random seed: CI passes one, so that its bounded
# run replays the same mutations every time and a red CI always means a reproducible finding,
# not a lucky draw; exploratory runs leave it unset (a fresh seed each run). Idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
build="$here/build-fuzz"
seconds="${FUZZ_SECONDS:-60}"
jobs="${FUZZ_JOBS:-1}"
seed="${FUZZ_SEED:-}"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ] && generator=(-G Ninja)
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSLIM_FUZZ=ON -DSLIM_BUILD_PLUGIN=OFF -DSLIM_BUILD_BENCH=OFF "${generator[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" --target slim_fuzz
mkdir -p "$build/corpus" "$build/artifacts"
export OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -timeout: one input may take at most 30 s (they take milliseconds); -rss_limit_mb: 2 GB.
args=(-max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1
      -artifact_prefix="$build/artifacts/" "$build/corpus" "$here/tests/fuzz/corpus" "$here/tests/fuzz/regressions")
if [ -n "$seed" ]; then args=(-seed="$seed" "${args[@]}"); fi
if [ "$jobs" -gt 1 ]; then args=(-jobs="$jobs" -workers="$jobs" "${args[@]}"); fi
cd "$build"
"$build/tests/fuzz/slim_fuzz" "${args[@]}"
