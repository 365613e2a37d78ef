#!/usr/bin/env bash
# The sanitizer stage: builds the core, the CLI, the plugin and their tests with AddressSanitizer
# and UndefinedBehaviorSanitizer (SLIM_SANITIZE=ON) into build-asan and runs them; any report
# fails. The plugin is loaded into the ASan-linked plugin tests, so the ASan runtime comes first
# without LD_PRELOAD. Not run here: the meshlabserver end-to-end tests (meshlabserver is not
# ASan-linked and cannot load an ASan plugin) and other tools' tests, and the core's and the CLI's
# comparisons of whole runs on the refined bunny, T, arch and mushroom, and the whole bunny runs
# of the dialog's, the report's and the position tests, which repeat the plugin's and the CLI's
# own whole run under other settings (LEFT_TO_THE_MAIN_SUITE below): they repeat, many times
# over and at 40-250 s each here (each run slims at three voxel resolutions), the slimming that
# the smaller tests run here too, and they judge the results, not the memory use. Extra ctest arguments pass through.
# Idempotent.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
source "$here/scripts/lib/ccache.sh"
build="$here/build-asan"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ] && generator=(-G Ninja)
# The same settings for the build (gtest discovery runs the tests) and for ctest:
#  - detect_odr_violation=0: the plugin and the test host both link VCG's PLY library (static),
#    so its globals exist twice by design; each copy is only used by its own module.
#  - LSan suppressions for Qt and MeshLab's own allocations (tests/sanitizers/lsan.supp).
export ASAN_OPTIONS="detect_leaks=1:detect_odr_violation=0:halt_on_error=1:strict_init_order=1"
export LSAN_OPTIONS="suppressions=$here/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export OPENBLAS_NUM_THREADS=1 QT_QPA_PLATFORM=offscreen
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DSLIM_SANITIZE=ON -DSLIM_BUILD_BENCH=OFF "${ccache_launcher[@]}" "${generator[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" --target slim_sanitized_tests
cd "$build"
LEFT_TO_THE_MAIN_SUITE='^(Slimming\.(CoherentSavesMoreSupportThanThePaperOnThe(T|Bunny|Arch)|ASavingWithinTheModelsErrorLeavesTheInputAsItWas|NeverReturnsAPartThatNeedsMoreSupport|ArchOpeningIsSlimmedWithinTheCreaseLimit|TheDefaultsKeepTheBunnysSizeAndProportions|NoFaceFoldsOverEvenWithoutTheLimits)|CostlyOverhangs\.TheSlimmingLeavesTheCheapOverhangsAlone|Cli\.ASmallSavingReturnsThePartAsGiven|PluginDialog\.(TheBudgetIsAnAbsoluteOrPercentageValue|TheSlimmedLayersVertexColoursShowTheDisplacement|ALeastSavingOf99PercentReturnsTheInputUnchangedWithTheReason|TheCreaseLimitReachesTheChoiceOfResult)|CliReport\.(TheResolutionLadderIsSaidAndOneResolutionTurnsItOff|FiguresAreThoseOfTheFilesWritten)|Slimming\.PaperMethodAlsoHelpsAndCoherentHelpsMore|Robustness\.ResultDoesNotDependOnPosition|CliReport\.TheSummaryLeadsWithTheVerdict|CliBatch\.FiveFilesOneBadGoOnAndAgreeWithSingleRuns|CliColour\.TheDefaultColoursEachVertexByHowFarItMoved|CliReport\.(TheCreaseLimitHoldsInTheFileWritten|AllowStretchLetsThePartStretch))$'
ctest --output-on-failure -j "$(nproc)" -L '^(core|cli|plugin|fuzz)$' -E "$LEFT_TO_THE_MAIN_SUITE" "$@"
