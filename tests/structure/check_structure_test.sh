#!/usr/bin/env bash
# scripts/check-structure.sh against trees made to break each rule once, and one that keeps them
# all: every breach is named with its file and line, and a clean tree passes.
#
#   tests/structure/check_structure_test.sh SOURCE_DIR
set -euo pipefail
source_dir="$1"
check="$source_dir/scripts/check-structure.sh"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# A minimal tree: two ranked core folders, the adapters, and a function of `lines` lines.
make_tree() {
  local root="$1"
  mkdir -p "$root/filter_support_slimming/core/geometry" "$root/filter_support_slimming/core/optimizer" \
           "$root/vcg_adapters" "$root/mesh_io" "$root/cli"
  printf '#pragma once\nnamespace slim {\nint area();\n}\n' >"$root/filter_support_slimming/core/geometry/surface.h"
  printf '#pragma once\n#include "core/geometry/surface.h"\nnamespace slim {\nint run();\n}\n' \
    >"$root/filter_support_slimming/core/optimizer/slimming.h"
  printf '#include "core/optimizer/slimming.h"\n#include "mesh_io/mesh_io.h"\nint main() { return 0; }\n' >"$root/cli/main.cpp"
}
# function FILE LINES: a function whose signature and braces span LINES lines.
function_of() {
  { echo "int f(int x) {"; for ((k = 0; k < $2 - 2; ++k)); do echo "  x += $k;  // {"; done; echo "}"; } >"$1"
}
# expect NAME STATUS PATTERN ROOT: the checker's status, and its output naming PATTERN.
expect() {
  local name="$1" status="$2" pattern="$3" root="$4" out got=0
  out="$("$check" "$root" 2>&1)" || got=$?
  [ "$got" = "$status" ] || fail "$name: exit $got, expected $status; output: $out"
  grep -q -- "$pattern" <<<"$out" || fail "$name: the output does not name '$pattern': $out"
}

make_tree "$work/clean"
function_of "$work/clean/filter_support_slimming/core/geometry/long.cpp" 80
expect "a clean tree with an 80-line function" 0 "includes run downwards" "$work/clean"

make_tree "$work/up"
printf '#pragma once\n#include "core/optimizer/slimming.h"\n' >"$work/up/filter_support_slimming/core/geometry/bad.h"
expect "an include from a lower folder to a higher one" 1 "core/geometry/bad.h:2: geometry/ includes core/optimizer/slimming.h" "$work/up"

make_tree "$work/qt"
printf '#include <QString>\n' >"$work/qt/filter_support_slimming/core/geometry/qt.cpp"
expect "Qt in the core" 1 "core/geometry/qt.cpp:1: the core includes Qt, VCG or MeshLab" "$work/qt"

make_tree "$work/out"
printf '#include "vcg_adapters/surface_adapter.h"\n' >"$work/out/filter_support_slimming/core/geometry/adapter.cpp"
expect "an adapter in the core" 1 "adapter.cpp:1: the core includes vcg_adapters/surface_adapter.h, outside the core" "$work/out"

make_tree "$work/unranked"
mkdir -p "$work/unranked/filter_support_slimming/core/misc"
printf 'int g();\n' >"$work/unranked/filter_support_slimming/core/misc/g.h"
expect "a core folder with no rank" 1 "core/misc/g.h:1: a core file outside the ranked folders" "$work/unranked"

make_tree "$work/side"
printf '#include "cli/main.cpp"\n' >"$work/side/vcg_adapters/bad.h"
expect "an adapter including the CLI" 1 "vcg_adapters/bad.h:1: vcg_adapters/ includes cli/main.cpp" "$work/side"

make_tree "$work/eval"
mkdir -p "$work/eval/eval"
printf '#include "core/optimizer/slimming.h"\n#include "cli/main.cpp"\n' >"$work/eval/eval/bad.cpp"
expect "eval/ including the CLI" 1 "eval/bad.cpp:2: eval/ includes cli/main.cpp" "$work/eval"

make_tree "$work/long"
function_of "$work/long/filter_support_slimming/core/geometry/long.cpp" 81
expect "an 81-line function" 1 "long.cpp:1: a function of 81 lines, over 80" "$work/long"

make_tree "$work/big"
for ((k = 0; k < 401; ++k)); do echo "int v$k = $k;"; done >"$work/big/mesh_io/big.cpp"
expect "a 401-line file" 1 "mesh_io/big.cpp:1: 401 lines, over 400" "$work/big"

expect "this checkout" 0 "includes run downwards" "$source_dir"

[ "$failures" = 0 ] && echo "check_structure_test: all cases pass"
exit $((failures > 0))
